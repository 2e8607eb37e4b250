# fluid_add_level_fuzzer(): the level loader's libFuzzer target, fluid-fuzz-level
# (tests/fuzz/level_fuzz.cpp against fluid::level). Needs clang, with every library compiled with
# -fsanitize=...,fuzzer-no-link so that libFuzzer sees their coverage. Used by tests/fuzz (the
# project scripts/fuzz.sh builds on its own) and by the top-level FLUID_BUILD_FUZZ option (the
# asan preset, so that CI builds the sanitized code once for its tests and the fuzzer).
function(fluid_add_level_fuzzer)
    if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
        message(FATAL_ERROR "fluid-fuzz-level needs clang (libFuzzer): configure with -DCMAKE_CXX_COMPILER=clang++-14, or run scripts/fuzz.sh")
    endif()
    if(NOT TARGET fluid::level)
        message(FATAL_ERROR "fluid-fuzz-level needs fluid::level (FLUID_BUILD_LEVEL)")
    endif()
    add_executable(fluid-fuzz-level ${CMAKE_CURRENT_FUNCTION_LIST_DIR}/../tests/fuzz/level_fuzz.cpp)
    target_link_libraries(fluid-fuzz-level PRIVATE fluid::level)
    target_compile_options(fluid-fuzz-level PRIVATE -fsanitize=fuzzer)
    target_link_options(fluid-fuzz-level PRIVATE -fsanitize=fuzzer)
endfunction()
