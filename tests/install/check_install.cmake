# Checks that fluid can be consumed by a game in both supported ways:
#   (a) installed: `cmake --install` into a fresh prefix, then find_package(fluid CONFIG ...):
#       - consumer_core/: a bare find_package(fluid) loads the core alone, configured as on a
#         machine without Box2D, nlohmann_json, OpenGL and GLEW (CMAKE_DISABLE_FIND_PACKAGE_*),
#         and optional components whose dependencies are missing only come back not found;
#       - consumer/ with COMPONENTS naming every installed component, calling into each;
#       - requests that must fail, naming the component and what is missing: gl without GLEW,
#         level without nlohmann_json, an unknown component, a component not installed;
#       - with the C API installed, consumer_c/, a game written in C:
#         - a C-only CMake project (no C++ enabled), linking fluid::c and fluid::c_shared;
#         - pkg-config: the installed .pc files and what they list, consumer_c/Makefile with
#           make and CC=gcc (fluid-c-static and fluid-c), gcc with pkg-config on its command
#           line, again with the install tree moved; and consumer/ compiled by the C++
#           compiler with fluid-level and fluid-gl;
#         each program run, and consumer_c/main.c checks its results;
#   (b) vendored:  add_subdirectory(<fluid source> fluid-build), with no tests/bench/examples,
#       and none of the optional libraries unless the game turns them on; the C consumer with
#       FLUID_BUILD_LEVEL and FLUID_BUILD_C, configured and its link line checked.
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
    CMAKE_C_COMPILER CMAKE_C_FLAGS CMAKE_EXE_LINKER_FLAGS FLUID_INSTALL FLUID_CCACHE
    FLUID_CCACHE_PROGRAM
    FLUID_BUILD_BOX2D FLUID_BUILD_LEVEL FLUID_BUILD_GL FLUID_BUILD_C)
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
# The C consumer's compiler (a C-only project: the C++ compiler above is for fluid itself, in
# subdirectory mode).
set(_c_args)
foreach(_var IN ITEMS CMAKE_C_COMPILER CMAKE_C_FLAGS)
    if(NOT "${PARENT_${_var}}" STREQUAL "")
        list(APPEND _c_args "-D${_var}=${PARENT_${_var}}")
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

# run(<description> <command>...): run a command, fail with its output if it fails; the output
# is left in RUN_OUTPUT.
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
    set(RUN_OUTPUT "${_out}" PARENT_SCOPE)
endfunction()


# run_failing(<description> PATTERNS <regex>... COMMAND <command>...): run a command that must
# fail, and whose output must match every regex (case-sensitive). CMake wraps long messages, so
# a space in a regex matches any run of blanks and line breaks.
function(run_failing description)
    cmake_parse_arguments(PARSE_ARGV 1 _arg "" "" "PATTERNS;COMMAND")
    message(STATUS "check_install: ${description}")
    execute_process(COMMAND ${_arg_COMMAND}
        RESULT_VARIABLE _rc
        OUTPUT_VARIABLE _out
        ERROR_VARIABLE _out)
    string(JOIN " " _cmd ${_arg_COMMAND})
    if(_rc STREQUAL "0")
        fail("${description}: the command succeeded but must fail\n  command: ${_cmd}\n"
             "--- output ---\n${_out}--- end of output ---")
    endif()
    foreach(_pattern IN LISTS _arg_PATTERNS)
        string(REPLACE " " "[ \t\r\n]+" _regex "${_pattern}")
        if(NOT _out MATCHES "${_regex}")
            fail("${description}: the output does not match '${_pattern}'\n  command: ${_cmd}\n"
                 "--- output ---\n${_out}--- end of output ---")
        endif()
    endforeach()
endfunction()

# find_exe(<build dir> <name> <out var>): the executable <name> inside a build tree (single- or
# multi-config generators).
function(find_exe build_dir name out_var)
    foreach(_candidate IN ITEMS
            "${build_dir}/${name}" "${build_dir}/${name}.exe"
            "${build_dir}/${BUILD_TYPE}/${name}" "${build_dir}/${BUILD_TYPE}/${name}.exe")
        if(EXISTS "${_candidate}" AND NOT IS_DIRECTORY "${_candidate}")
            set(${out_var} "${_candidate}" PARENT_SCOPE)
            return()
        endif()
    endforeach()
    fail("built '${name}' in '${build_dir}' but found no such executable there")
endfunction()

# check_found_in_prefix(<build dir>): the package came from our fresh prefix, not from
# somewhere else on the machine.
function(check_found_in_prefix build_dir)
    load_cache("${build_dir}" READ_WITH_PREFIX CONSUMER_ fluid_DIR)
    file(REAL_PATH "${_prefix}" _real_prefix)
    file(REAL_PATH "${CONSUMER_fluid_DIR}" _real_fluid_dir)
    string(FIND "${_real_fluid_dir}" "${_real_prefix}/" _pos)
    if(NOT _pos EQUAL 0)
        fail("'${build_dir}' found fluid at '${CONSUMER_fluid_DIR}', not under '${_prefix}'")
    endif()
endfunction()

set(_consumer_src "${CMAKE_CURRENT_LIST_DIR}/consumer")
set(_consumer_c_src "${CMAKE_CURRENT_LIST_DIR}/consumer_c")
set(_consumer_core_src "${CMAKE_CURRENT_LIST_DIR}/consumer_core")
set(_prefix "${WORK_DIR}/prefix")
set(_core_build "${WORK_DIR}/consumer-core")
set(_package_build "${WORK_DIR}/consumer-package")
set(_failing_build "${WORK_DIR}/consumer-failing")
set(_subdir_build "${WORK_DIR}/consumer-subdirectory")
set(_subdir_level_build "${WORK_DIR}/consumer-subdirectory-level")
set(_c_build "${WORK_DIR}/consumer-c")
set(_c_pkgconfig_build "${WORK_DIR}/consumer-c-pkgconfig")
set(_subdir_c_build "${WORK_DIR}/consumer-subdirectory-c")
set(_moved_prefix "${WORK_DIR}/prefix-moved")
file(REMOVE_RECURSE "${_prefix}" "${_core_build}" "${_package_build}" "${_failing_build}"
    "${_subdir_build}" "${_subdir_level_build}" "${_c_build}" "${_c_pkgconfig_build}"
    "${_subdir_c_build}" "${_moved_prefix}")
file(MAKE_DIRECTORY "${WORK_DIR}")

# The components the parent tree installs, and the targets file of each.
set(_components core)
set(_targets_file_core fluidCoreTargets.cmake)
set(_targets_file_box2d fluidBox2dTargets.cmake)
set(_targets_file_level fluidLevelTargets.cmake)
set(_targets_file_gl fluidGlTargets.cmake)
set(_targets_file_c fluidCTargets.cmake)
foreach(_comp IN ITEMS box2d level gl c)
    string(TOUPPER "${_comp}" _upper)
    if(PARENT_FLUID_BUILD_${_upper})
        list(APPEND _components ${_comp})
    endif()
endforeach()
message(STATUS "check_install: installed components: ${_components}")

# A machine view without fluid's optional dependencies.
set(_without_optional_deps
    -DCMAKE_DISABLE_FIND_PACKAGE_box2d=ON
    -DCMAKE_DISABLE_FIND_PACKAGE_nlohmann_json=ON
    -DCMAKE_DISABLE_FIND_PACKAGE_OpenGL=ON
    -DCMAKE_DISABLE_FIND_PACKAGE_GLEW=ON)
set(_package_args "-DCMAKE_PREFIX_PATH=${_prefix}" -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF)

# ---- (a) installed package ---------------------------------------------------------------------
run("install ${BINARY_DIR} into ${_prefix}"
    "${CMAKE_COMMAND}" --install "${BINARY_DIR}" --prefix "${_prefix}" ${_config_args})

if(NOT EXISTS "${_prefix}/include/fluid/fluid.h")
    fail("the install has no include/fluid/fluid.h (under ${_prefix})")
endif()
file(GLOB_RECURSE _configs "${_prefix}/*/fluidConfig.cmake")
file(GLOB_RECURSE _versions "${_prefix}/*/fluidConfigVersion.cmake")
if(NOT _configs OR NOT _versions)
    fail("the install lacks fluidConfig.cmake or fluidConfigVersion.cmake (under ${_prefix})")
endif()
list(GET _configs 0 _config)
get_filename_component(_package_dir "${_config}" DIRECTORY)
foreach(_comp IN ITEMS core box2d level gl c)
    set(_file "${_package_dir}/${_targets_file_${_comp}}")
    if(_comp IN_LIST _components AND NOT EXISTS "${_file}")
        fail("component '${_comp}' was built but the install lacks ${_file}")
    elseif(NOT _comp IN_LIST _components AND EXISTS "${_file}")
        fail("component '${_comp}' was not built but the install has ${_file}")
    endif()
endforeach()
# Build-only helpers must not leak into the exported package, and the core's targets file must
# not refer to any optional dependency.
file(GLOB _targets "${_package_dir}/fluid*Targets*.cmake")
foreach(_file IN LISTS _targets)
    file(READ "${_file}" _text)
    if(_text MATCHES "fluid_warnings")
        fail("${_file} refers to fluid_warnings; link it as $<BUILD_INTERFACE:fluid_warnings>")
    endif()
endforeach()
file(READ "${_package_dir}/${_targets_file_core}" _text)
if(_text MATCHES "box2d::|nlohmann_json|OpenGL::|GLEW::|fluid::(box2d|level|gl)")
    fail("${_package_dir}/${_targets_file_core} refers to an optional library "
         "('${CMAKE_MATCH_0}'); the core must need glm and threads only")
endif()

# (a1) The core alone, on a machine view without the optional dependencies. find_package(fluid)
# must not even look for them: CMake then reports each CMAKE_DISABLE_FIND_PACKAGE_<Pkg> given on
# the command line as unused.
run("configure the core consumer without Box2D, nlohmann_json, OpenGL and GLEW"
    "${CMAKE_COMMAND}" -S "${_consumer_core_src}" -B "${_core_build}" ${_common_args}
    ${_package_args} ${_without_optional_deps})
check_found_in_prefix("${_core_build}")
foreach(_pkg IN ITEMS box2d nlohmann_json OpenGL GLEW)
    if(NOT RUN_OUTPUT MATCHES "not used by the project:[^-]*CMAKE_DISABLE_FIND_PACKAGE_${_pkg}[\r\n]")
        fail("find_package(fluid) without components looked for ${_pkg} (CMake does not report "
             "CMAKE_DISABLE_FIND_PACKAGE_${_pkg} as unused)\n--- output ---\n${RUN_OUTPUT}"
             "--- end of output ---")
    endif()
endforeach()
run("build the core consumer" "${CMAKE_COMMAND}" --build "${_core_build}" ${_config_args})
find_exe("${_core_build}" fluid_consumer_core _exe)
run("run the core consumer" "${_exe}")
# The optional components asked for with OPTIONAL_COMPONENTS come back not found, without failing.
run("configure the core consumer with OPTIONAL_COMPONENTS box2d level gl"
    "${CMAKE_COMMAND}" -S "${_consumer_core_src}" -B "${_core_build}"
    "-DFLUID_CONSUMER_OPTIONAL=box2d,level,gl")

# (a2) Every installed component, by name.
string(JOIN "," _all_components ${_components})
run("configure the consumer (package mode, COMPONENTS ${_all_components})"
    "${CMAKE_COMMAND}" -S "${_consumer_src}" -B "${_package_build}" ${_common_args}
    ${_package_args}
    -DFLUID_CONSUMER_MODE=package
    "-DFLUID_CONSUMER_COMPONENTS=${_all_components}")
check_found_in_prefix("${_package_build}")
run("build the consumer (package mode)"
    "${CMAKE_COMMAND}" --build "${_package_build}" ${_config_args})
find_exe("${_package_build}" fluid_consumer _exe)
run("run the consumer (package mode)" "${_exe}")

# (a3) Requests that must fail, with a message naming the component and what it lacks.
# failing_request(<description> <components> <configure args> PATTERNS <regex>...)
function(failing_request description components)
    cmake_parse_arguments(PARSE_ARGV 2 _arg "" "" "ARGS;PATTERNS")
    file(REMOVE_RECURSE "${_failing_build}")
    run_failing("${description}"
        PATTERNS ${_arg_PATTERNS}
        COMMAND "${CMAKE_COMMAND}" -S "${_consumer_src}" -B "${_failing_build}" ${_common_args}
            ${_package_args} ${_arg_ARGS}
            -DFLUID_CONSUMER_MODE=package
            "-DFLUID_CONSUMER_COMPONENTS=${components}")
endfunction()

if("gl" IN_LIST _components)
    failing_request("COMPONENTS gl without GLEW must fail naming gl and GLEW" gl
        ARGS -DCMAKE_DISABLE_FIND_PACKAGE_GLEW=ON
        PATTERNS "component 'gl' needs GLEW" "fluid_FOUND to FALSE")
else()
    failing_request("COMPONENTS gl, not installed, must fail naming gl" gl
        PATTERNS "component 'gl' was not installed" "FLUID_BUILD_GL=OFF")
endif()
if("level" IN_LIST _components)
    failing_request("COMPONENTS level without nlohmann_json must fail naming level and nlohmann_json"
        level
        ARGS -DCMAKE_DISABLE_FIND_PACKAGE_nlohmann_json=ON
        PATTERNS "component 'level' needs nlohmann_json")
    failing_request("COMPONENTS level without Box2D must fail naming level and box2d" level
        ARGS -DCMAKE_DISABLE_FIND_PACKAGE_box2d=ON
        PATTERNS "component 'box2d' needs box2d" "component 'level' needs component 'box2d'")
endif()
failing_request("an unknown component must fail naming it" core,physics
    PATTERNS "component 'physics' is unknown")
file(REMOVE_RECURSE "${_failing_build}")

# run_c_consumer(<description> <executable>): run a build of consumer_c/main.c, which must
# succeed and say it checked its results.
function(run_c_consumer description exe)
    run("${description}" ${ARGN} "${exe}")
    if(NOT RUN_OUTPUT MATCHES "consumer_c: ok: [0-9]+ particles")
        fail("${description}: the program exited 0 without its 'consumer_c: ok' line\n"
             "--- output ---\n${RUN_OUTPUT}--- end of output ---")
    endif()
endfunction()

# check_needed(<executable> <regex> <TRUE|FALSE>): whether the executable's dynamic section
# names a needed library matching <regex> is <TRUE|FALSE> (the static build must not need
# libfluid_c.so, the shared one must).
function(check_needed exe regex expected)
    run("read the dynamic section of ${exe}" "${_readelf}" -d "${exe}")
    if(RUN_OUTPUT MATCHES "\\(NEEDED\\)[^\n]*${regex}")
        set(_has TRUE)
    else()
        set(_has FALSE)
    endif()
    if(NOT _has STREQUAL expected)
        if(expected)
            fail("${exe} does not need a library matching '${regex}' but must\n${RUN_OUTPUT}")
        else()
            fail("${exe} needs a library matching '${regex}' but must not\n${RUN_OUTPUT}")
        endif()
    endif()
endfunction()

# match_in_order(<description> <text> <regex>...): <text>'s words include, in this order, one
# matching each regex whole (each after the previous one's).
function(match_in_order description text)
    separate_arguments(_words UNIX_COMMAND "${text}")
    set(_word_list ${_words})
    foreach(_regex IN LISTS ARGN)
        set(_found FALSE)
        while(_word_list)
            list(POP_FRONT _word_list _word)
            if(_word MATCHES "^${_regex}$")
                set(_found TRUE)
                break()
            endif()
        endwhile()
        if(NOT _found)
            string(JOIN "  " _items ${ARGN})
            fail("${description}: '${text}' does not list, in this order: ${_items}")
        endif()
    endforeach()
endfunction()

if("c" IN_LIST _components)
    find_program(_readelf NAMES readelf)
    find_program(_pkg_config NAMES pkg-config pkgconf)
    find_program(_make NAMES make gmake)
    find_program(_gcc NAMES gcc)
    foreach(_tool IN ITEMS readelf pkg_config make gcc)
        if(NOT _${_tool})
            fail("the C consumers need ${_tool} (scripts/deps.sh installs it), not found")
        endif()
    endforeach()

    # (a4) A game written in C, in a C-only CMake project.
    run("configure the C consumer (a C-only CMake project, find_package(fluid COMPONENTS c))"
        "${CMAKE_COMMAND}" -S "${_consumer_c_src}" -B "${_c_build}" ${_common_args} ${_c_args}
        ${_package_args})
    check_found_in_prefix("${_c_build}")
    run("build the C consumer (fluid::c and fluid::c_shared)"
        "${CMAKE_COMMAND}" --build "${_c_build}" ${_config_args})
    find_exe("${_c_build}" fluid_consumer_c_static _exe)
    check_needed("${_exe}" "libfluid_c" FALSE)
    run_c_consumer("run the C consumer linked with fluid::c" "${_exe}")
    find_exe("${_c_build}" fluid_consumer_c_shared _exe)
    check_needed("${_exe}" "libfluid_c\\.so\\.1" TRUE)
    run_c_consumer("run the C consumer linked with fluid::c_shared" "${_exe}")

    # (a5) pkg-config, in front of the machine's own directories (Box2D's and glm's files).
    file(GLOB_RECURSE _pc_files "${_prefix}/*/pkgconfig/fluid.pc")
    if(NOT _pc_files)
        fail("the install has no pkgconfig/fluid.pc (under ${_prefix})")
    endif()
    list(GET _pc_files 0 _pc_file)
    get_filename_component(_pc_dir "${_pc_file}" DIRECTORY)
    foreach(_pc IN ITEMS fluid-box2d fluid-level fluid-c fluid-c-static)
        if(NOT EXISTS "${_pc_dir}/${_pc}.pc")
            fail("the install has no ${_pc_dir}/${_pc}.pc")
        endif()
    endforeach()
    if("gl" IN_LIST _components AND NOT EXISTS "${_pc_dir}/fluid-gl.pc")
        fail("component 'gl' was built but the install has no ${_pc_dir}/fluid-gl.pc")
    endif()
    set(_pc_env "${CMAKE_COMMAND}" -E env "PKG_CONFIG_PATH=${_pc_dir}:$ENV{PKG_CONFIG_PATH}")

    # Where the files say the library is: the prefix it was installed into.
    run("pkg-config --variable=libdir fluid-c"
        ${_pc_env} "${_pkg_config}" --variable=libdir fluid-c)
    string(STRIP "${RUN_OUTPUT}" _libdir)
    file(REAL_PATH "${_libdir}" _real_libdir)
    file(REAL_PATH "${_pc_dir}/.." _real_expected_libdir)
    if(NOT _real_libdir STREQUAL _real_expected_libdir)
        fail("fluid-c.pc's libdir is '${_libdir}', not the install's '${_real_expected_libdir}'")
    endif()
    # What each lists, in link order.
    run("pkg-config --libs fluid-c" ${_pc_env} "${_pkg_config}" --libs fluid-c)
    string(STRIP "${RUN_OUTPUT}" _libs)
    if(NOT _libs MATCHES "^-L[^ ]+ -lfluid_c$")
        fail("pkg-config --libs fluid-c gives '${_libs}', not '-L<libdir> -lfluid_c'")
    endif()
    run("pkg-config --static --libs fluid-c"
        ${_pc_env} "${_pkg_config}" --static --libs fluid-c)
    string(STRIP "${RUN_OUTPUT}" _libs)
    match_in_order("pkg-config --static --libs fluid-c" "${_libs}"
        -lfluid_c -lfluid_level -lfluid_box2d -lfluid "-lstdc\\+\\+" -lm)
    match_in_order("pkg-config --static --libs fluid-c" "${_libs}" -lfluid_box2d -lbox2d)
    run("pkg-config --libs fluid-c-static"
        ${_pc_env} "${_pkg_config}" --libs fluid-c-static)
    string(STRIP "${RUN_OUTPUT}" _libs)
    match_in_order("pkg-config --libs fluid-c-static" "${_libs}" ".*/libfluid_c\\.a"
        ".*/libfluid_level\\.a" ".*/libfluid_box2d\\.a" ".*/libfluid\\.a" "-lstdc\\+\\+" -lm)
    match_in_order("pkg-config --libs fluid-c-static" "${_libs}" ".*/libfluid_box2d\\.a" -lbox2d)

    # make with CC=gcc, then gcc with pkg-config on its command line, as docs/c_api.md shows.
    file(MAKE_DIRECTORY "${_c_pkgconfig_build}")
    run("make consumer_c/Makefile with CC=gcc (pkg-config fluid-c-static and fluid-c)"
        ${_pc_env} "${_make}" -C "${_c_pkgconfig_build}" -f "${_consumer_c_src}/Makefile"
        "SRC=${_consumer_c_src}" "CC=${_gcc}")
    check_needed("${_c_pkgconfig_build}/consumer_c_static" "libfluid_c" FALSE)
    run_c_consumer("run the C consumer made with pkg-config fluid-c-static"
        "${_c_pkgconfig_build}/consumer_c_static")
    check_needed("${_c_pkgconfig_build}/consumer_c_shared" "libfluid_c\\.so\\.1" TRUE)
    run_c_consumer("run the C consumer made with pkg-config fluid-c"
        "${_c_pkgconfig_build}/consumer_c_shared")
    run("gcc -std=c99 main.c $(pkg-config --cflags --libs fluid-c-static)"
        ${_pc_env} sh -c "cd '${_c_pkgconfig_build}' && '${_gcc}' -std=c99 \
'${_consumer_c_src}/main.c' $('${_pkg_config}' --cflags --libs fluid-c-static) -o consumer_c_cc")
    run_c_consumer("run the C consumer built by gcc with pkg-config fluid-c-static"
        "${_c_pkgconfig_build}/consumer_c_cc")
    # The same with the install tree moved: the .pc files find their prefix from their own
    # directory. (Moved back after: the consumers above have run paths into it.)
    file(RENAME "${_prefix}" "${_moved_prefix}")
    string(REPLACE "${_prefix}/" "${_moved_prefix}/" _moved_pc_dir "${_pc_dir}/")
    run("gcc with pkg-config fluid-c-static, the install tree moved to ${_moved_prefix}"
        "${CMAKE_COMMAND}" -E env "PKG_CONFIG_PATH=${_moved_pc_dir}:$ENV{PKG_CONFIG_PATH}"
        sh -c "cd '${_c_pkgconfig_build}' && '${_gcc}' -std=c99 '${_consumer_c_src}/main.c' \
$('${_pkg_config}' --cflags --libs fluid-c-static) -o consumer_c_moved \
&& '${_pkg_config}' --variable=prefix fluid-c-static")
    string(STRIP "${RUN_OUTPUT}" _moved_pc_prefix)
    file(REAL_PATH "${_moved_pc_prefix}" _real_moved_pc_prefix)
    file(REAL_PATH "${_moved_prefix}" _real_moved_prefix)
    if(NOT _real_moved_pc_prefix STREQUAL _real_moved_prefix)
        fail("moved to '${_moved_prefix}', fluid-c-static.pc's prefix is '${_moved_pc_prefix}'")
    endif()
    run_c_consumer("run the C consumer built against the moved install tree"
        "${_c_pkgconfig_build}/consumer_c_moved")
    file(RENAME "${_moved_prefix}" "${_prefix}")
    # The C++ libraries' files: consumer/ calling into the core, box2d, level (and gl).
    set(_cxx_pcs fluid-level)
    set(_cxx_defs -DFLUID_CONSUMER_WITH_BOX2D -DFLUID_CONSUMER_WITH_LEVEL)
    if("gl" IN_LIST _components)
        list(APPEND _cxx_pcs fluid-gl)
        list(APPEND _cxx_defs -DFLUID_CONSUMER_WITH_GL)
    endif()
    set(_cxx "${PARENT_CMAKE_CXX_COMPILER}")
    if(PARENT_FLUID_CCACHE AND PARENT_FLUID_CCACHE_PROGRAM)
        set(_cxx "${PARENT_FLUID_CCACHE_PROGRAM} ${_cxx}")
    endif()
    string(JOIN " " _cxx_defs_text ${_cxx_defs})
    string(JOIN " " _cxx_pcs_text ${_cxx_pcs})
    run("c++ -std=c++20 consumer/main.cpp $(pkg-config --cflags --libs ${_cxx_pcs_text})"
        ${_pc_env} sh -c "cd '${_c_pkgconfig_build}' && ${_cxx} -std=c++20 ${_cxx_defs_text} \
'${_consumer_src}/main.cpp' $('${_pkg_config}' --cflags --libs ${_cxx_pcs_text}) \
-o consumer_cxx")
    run("run the C++ consumer built with pkg-config ${_cxx_pcs_text}"
        "${_c_pkgconfig_build}/consumer_cxx")
endif()

# ---- (b) add_subdirectory -----------------------------------------------------------------------
run("configure the consumer (subdirectory mode)"
    "${CMAKE_COMMAND}" -S "${_consumer_src}" -B "${_subdir_build}" ${_common_args}
    -DFLUID_CONSUMER_MODE=subdirectory
    "-DFLUID_SOURCE_DIR=${SOURCE_DIR}")
# Only the consumer and what it links (the core library), as a game's build would: the rest of
# fluid's libraries (level files, Box2D coupling) are built and tested in the parent tree.
run("build the consumer (subdirectory mode)"
    "${CMAKE_COMMAND}" --build "${_subdir_build}" --target fluid_consumer ${_config_args})
find_exe("${_subdir_build}" fluid_consumer _exe)
run("run the consumer (subdirectory mode)" "${_exe}")

# A game that turns on FLUID_BUILD_LEVEL gets fluid::level and fluid::box2d, not fluid::gl
# (the consumer's CMakeLists.txt checks the targets; configuring is enough).
if("level" IN_LIST _components)
    run("configure the consumer (subdirectory mode, FLUID_BUILD_LEVEL)"
        "${CMAKE_COMMAND}" -S "${_consumer_src}" -B "${_subdir_level_build}" ${_common_args}
        -DFLUID_CONSUMER_MODE=subdirectory
        -DFLUID_CONSUMER_COMPONENTS=level
        "-DFLUID_SOURCE_DIR=${SOURCE_DIR}")
endif()

# A game written in C that adds fluid's source tree, with the C API turned on. Configured, not
# built: building would compile fluid::level, fluid::box2d and the C API a second time (a
# minute and a half on 2 cores with a cold compiler cache), and the package mode above links
# and runs the same targets. What this mode adds is the link line, read from the generated
# build files: the C compiler's driver, the C++ runtime after the last of fluid's archives.
# check_c_link(<build dir> <target>): that check, for Ninja and Makefile generators.
function(check_c_link build_dir target)
    if(EXISTS "${build_dir}/CMakeFiles/${target}.dir/link.txt")
        file(READ "${build_dir}/CMakeFiles/${target}.dir/link.txt" _link)
        separate_arguments(_words UNIX_COMMAND "${_link}")
        list(GET _words 0 _driver)
        set(_libraries "${_link}")
    elseif(EXISTS "${build_dir}/build.ninja")
        file(READ "${build_dir}/build.ninja" _ninja)
        # The statement and its indented variables; its rule names the linker's language.
        set(_statement "\nbuild ${target}: ([A-Za-z]+)_EXECUTABLE_LINKER[^\n]*\n(  [^\n]*\n)*")
        if(NOT _ninja MATCHES "${_statement}")
            fail("${build_dir}/build.ninja has no link statement for ${target}")
        endif()
        set(_driver "${CMAKE_MATCH_1}")
        string(REGEX MATCH "LINK_LIBRARIES = [^\n]*" _libraries "${CMAKE_MATCH_0}")
    else()
        fail("no link.txt or build.ninja for ${target} in ${build_dir} (generator '${GENERATOR}')")
    endif()
    if(_driver MATCHES "\\+\\+|CXX")
        fail("${target} links with the C++ compiler's driver ('${_driver}'), not the C one")
    endif()
    match_in_order("the link of ${target} in ${build_dir}" "${_libraries}"
        "(.*/)?libfluid_c\\.a" "(.*/)?libfluid\\.a" "-lstdc\\+\\+" -lm)
endfunction()

if("c" IN_LIST _components)
    run("configure the C consumer (subdirectory mode, FLUID_BUILD_C)"
        "${CMAKE_COMMAND}" -S "${_consumer_c_src}" -B "${_subdir_c_build}" ${_common_args}
        ${_c_args}
        -DFLUID_CONSUMER_MODE=subdirectory
        "-DFLUID_SOURCE_DIR=${SOURCE_DIR}")
    check_c_link("${_subdir_c_build}" fluid_consumer_c_static)
endif()

message(STATUS "check_install: core-only, all-component, failing-request, C (CMake and "
               "pkg-config) and subdirectory consumers passed")
