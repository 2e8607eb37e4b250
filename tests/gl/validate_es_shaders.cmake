# validate_es_shaders.cmake — run with `cmake -P` by the test gl.shaders_compile_as_glsl_es_300:
# embeds SHADERS ('|'-separated) as the web build does (cmake/embed_shaders.cmake with ES=ON,
# each shader's text written into WORK) and compiles each with VALIDATOR (glslangValidator).
# Prints "N shaders compile as GLSL ES 3.00", or fails naming the shader and the compiler's
# message.
cmake_minimum_required(VERSION 3.25)
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}/text")
execute_process(
    COMMAND ${CMAKE_COMMAND} "-DSHADERS=${SHADERS}" "-DOUTPUT=${WORK}/embedded_es.cpp" -DES=ON
            "-DWRITE_DIR=${WORK}/text" -P "${EMBED}"
    RESULT_VARIABLE _embedded)
if(NOT _embedded EQUAL 0)
    message(FATAL_ERROR "validate_es_shaders: embedding the shaders as GLSL ES failed")
endif()
file(GLOB _shaders "${WORK}/text/*")
list(LENGTH _shaders _count)
if(_count EQUAL 0)
    message(FATAL_ERROR "validate_es_shaders: no shader was written")
endif()
foreach(_shader IN LISTS _shaders)
    file(READ "${_shader}" _text LIMIT 16)
    if(NOT _text MATCHES "^#version 300 es")
        message(FATAL_ERROR "validate_es_shaders: ${_shader} does not start with #version 300 es")
    endif()
    # glslangValidator picks the stage from the extension (.vert, .frag).
    execute_process(COMMAND "${VALIDATOR}" "${_shader}"
                    RESULT_VARIABLE _result OUTPUT_VARIABLE _out ERROR_VARIABLE _err)
    if(NOT _result EQUAL 0)
        message(FATAL_ERROR "validate_es_shaders: ${_shader} does not compile as GLSL ES 3.00:\n"
                            "${_out}${_err}")
    endif()
endforeach()
message("${_count} shaders compile as GLSL ES 3.00")
