# Checks that fluid can be consumed by a game in both supported ways:
#   (a) installed: `cmake --install` into a fresh prefix, then find_package(fluid CONFIG REQUIRED);
#   (b) vendored:  add_subdirectory(<fluid source> fluid-build), with no tests/bench/examples.
# In both modes the consumer in consumer/ is configured, built and run.
#
# Usage:
#   cmake -DSOURCE_DIR=<fluid source> -DBINARY_DIR=<built fluid tree> -DWORK_DIR=<scratch dir>
#         [-DGENERATOR=<gen>] [-DBUILD_TYPE=<type>] -P check_install.cmake
# GENERATOR, BUILD_TYPE, the compiler and its flags default to those of BINARY_DIR's cache, so the
# consumer is built like the parent build.
cmake_minimum_required(VERSION 3.25)

function(fail)
    string(JOIN "" _msg ${ARGN})
    message(FATAL_ERROR "check_install: ${_msg}")
endfunction()

foreach(_var IN ITEMS SOURCE_DIR BINARY_DIR WORK_DIR)
    if(NOT DEFINED ${_var} OR "${${_var}}" STREQUAL "")
        fail("${_var} is not set; run with -DSOURCE_DIR=.. -DBINARY_DIR=.. -DWORK_DIR=.. -P")
    endif()
    get_filename_component(${_var} "${${_var}}" ABSOLUTE)
endforeach()
if(NOT EXISTS "${BINARY_DIR}/CMakeCache.txt")
    fail("BINARY_DIR '${BINARY_DIR}' is not a configured build tree (no CMakeCache.txt)")
endif()
if(NOT EXISTS "${SOURCE_DIR}/CMakeLists.txt")
    fail("SOURCE_DIR '${SOURCE_DIR}' has no CMakeLists.txt")
endif()

# Build the consumer the way the parent tree was built.
load_cache("${BINARY_DIR}" READ_WITH_PREFIX PARENT_
    CMAKE_GENERATOR CMAKE_MAKE_PROGRAM CMAKE_BUILD_TYPE CMAKE_CXX_COMPILER CMAKE_CXX_FLAGS
    CMAKE_EXE_LINKER_FLAGS FLUID_INSTALL FLUID_CCACHE FLUID_CCACHE_PROGRAM)
if(NOT DEFINED GENERATOR OR GENERATOR STREQUAL "")
    set(GENERATOR "${PARENT_CMAKE_GENERATOR}")
endif()
if(NOT DEFINED BUILD_TYPE OR BUILD_TYPE STREQUAL "")
    set(BUILD_TYPE "${PARENT_CMAKE_BUILD_TYPE}")
endif()
if(DEFINED PARENT_FLUID_INSTALL AND NOT PARENT_FLUID_INSTALL)
    fail("FLUID_INSTALL is OFF in '${BINARY_DIR}': there is nothing to install")
endif()

set(_common_args -G "${GENERATOR}")
if(BUILD_TYPE)
    list(APPEND _common_args "-DCMAKE_BUILD_TYPE=${BUILD_TYPE}")
endif()
foreach(_var IN ITEMS CMAKE_MAKE_PROGRAM CMAKE_CXX_COMPILER CMAKE_CXX_FLAGS CMAKE_EXE_LINKER_FLAGS)
    if(NOT "${PARENT_${_var}}" STREQUAL "")
        list(APPEND _common_args "-D${_var}=${PARENT_${_var}}")
    endif()
endforeach()

# Through the parent's compiler cache, when it has one: the subdirectory mode compiles the core
# with the parent's flags, so it costs cache lookups rather than a second build.
if(PARENT_FLUID_CCACHE AND PARENT_FLUID_CCACHE_PROGRAM)
    list(APPEND _common_args "-DCMAKE_CXX_COMPILER_LAUNCHER=${PARENT_FLUID_CCACHE_PROGRAM}")
endif()

set(_config_args)
if(BUILD_TYPE)
    set(_config_args --config "${BUILD_TYPE}")
endif()

# run(<description> <command>...): run a command, fail with its output if it fails.
function(run description)
    message(STATUS "check_install: ${description}")
    execute_process(COMMAND ${ARGN}
        RESULT_VARIABLE _rc
        OUTPUT_VARIABLE _out
        ERROR_VARIABLE _out)
    if(NOT _rc STREQUAL "0")
        string(JOIN " " _cmd ${ARGN})
        fail("${description} failed (exit ${_rc})\n  command: ${_cmd}\n--- output ---\n${_out}"
             "--- end of output ---")
    endif()
endfunction()

# Finds the consumer executable inside a build tree (single- or multi-config generators).
function(find_consumer_exe build_dir out_var)
    foreach(_candidate IN ITEMS
            "${build_dir}/fluid_consumer" "${build_dir}/fluid_consumer.exe"
            "${build_dir}/${BUILD_TYPE}/fluid_consumer" "${build_dir}/${BUILD_TYPE}/fluid_consumer.exe")
        if(EXISTS "${_candidate}" AND NOT IS_DIRECTORY "${_candidate}")
            set(${out_var} "${_candidate}" PARENT_SCOPE)
            return()
        endif()
    endforeach()
    fail("built the consumer in '${build_dir}' but found no fluid_consumer executable there")
endfunction()

set(_consumer_src "${CMAKE_CURRENT_LIST_DIR}/consumer")
set(_prefix "${WORK_DIR}/prefix")
set(_package_build "${WORK_DIR}/consumer-package")
set(_subdir_build "${WORK_DIR}/consumer-subdirectory")
file(REMOVE_RECURSE "${_prefix}" "${_package_build}" "${_subdir_build}")
file(MAKE_DIRECTORY "${WORK_DIR}")

# ---- (a) installed package ---------------------------------------------------------------------
run("install ${BINARY_DIR} into ${_prefix}"
    "${CMAKE_COMMAND}" --install "${BINARY_DIR}" --prefix "${_prefix}" ${_config_args})

if(NOT EXISTS "${_prefix}/include/fluid/fluid.h")
    fail("the install has no include/fluid/fluid.h (under ${_prefix})")
endif()
file(GLOB_RECURSE _configs "${_prefix}/*/fluidConfig.cmake")
file(GLOB_RECURSE _versions "${_prefix}/*/fluidConfigVersion.cmake")
file(GLOB_RECURSE _targets "${_prefix}/*/fluidTargets.cmake")
if(NOT _configs OR NOT _versions OR NOT _targets)
    fail("the install lacks fluidConfig.cmake, fluidConfigVersion.cmake or fluidTargets.cmake "
         "(under ${_prefix})")
endif()
# Build-only helpers must not leak into the exported package.
foreach(_file IN LISTS _targets)
    file(READ "${_file}" _text)
    if(_text MATCHES "fluid_warnings")
        fail("${_file} refers to fluid_warnings; link it as $<BUILD_INTERFACE:fluid_warnings>")
    endif()
endforeach()

run("configure the consumer (package mode)"
    "${CMAKE_COMMAND}" -S "${_consumer_src}" -B "${_package_build}" ${_common_args}
    -DFLUID_CONSUMER_MODE=package
    "-DCMAKE_PREFIX_PATH=${_prefix}"
    -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF)

# Make sure the package came from our fresh prefix, not from somewhere else on the machine.
load_cache("${_package_build}" READ_WITH_PREFIX CONSUMER_ fluid_DIR)
file(REAL_PATH "${_prefix}" _real_prefix)
file(REAL_PATH "${CONSUMER_fluid_DIR}" _real_fluid_dir)
string(FIND "${_real_fluid_dir}" "${_real_prefix}/" _pos)
if(NOT _pos EQUAL 0)
    fail("package mode found fluid at '${CONSUMER_fluid_DIR}', not under '${_prefix}'")
endif()

run("build the consumer (package mode)"
    "${CMAKE_COMMAND}" --build "${_package_build}" ${_config_args})
find_consumer_exe("${_package_build}" _exe)
run("run the consumer (package mode)" "${_exe}")

# ---- (b) add_subdirectory -----------------------------------------------------------------------
run("configure the consumer (subdirectory mode)"
    "${CMAKE_COMMAND}" -S "${_consumer_src}" -B "${_subdir_build}" ${_common_args}
    -DFLUID_CONSUMER_MODE=subdirectory
    "-DFLUID_SOURCE_DIR=${SOURCE_DIR}")
# Only the consumer and what it links (the core library), as a game's build would: the rest of
# fluid's libraries (level files, Box2D coupling) are built and tested in the parent tree.
run("build the consumer (subdirectory mode)"
    "${CMAKE_COMMAND}" --build "${_subdir_build}" --target fluid_consumer ${_config_args})
find_consumer_exe("${_subdir_build}" _exe)
run("run the consumer (subdirectory mode)" "${_exe}")

message(STATUS "check_install: package and subdirectory consumers built and ran")
