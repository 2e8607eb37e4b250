// Shared by the demo tests: run fluid-demo and capture what it prints.
#pragma once
#include <catch2/catch.hpp>

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace demo_test {

/// What a fluid-demo run printed (stdout and stderr together) and its exit status (-1 when it
/// did not exit normally).
struct Run {
    int status = -1;
    std::string output;
};

/// Runs fluid-demo with `args` (shell words), after the shell prefix `env` (e.g. "env -u
/// DISPLAY").
inline Run runDemo(const std::string& args, const std::string& env = "") {
    const std::string command = env + " '" FLUID_DEMO_PATH "' " + args + " 2>&1";
    Run run;
    FILE* pipe = ::popen(command.c_str(), "r");
    REQUIRE(pipe != nullptr);
    std::array<char, 4096> buffer{};
    size_t n = 0;
    while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) {
        run.output.append(buffer.data(), n);
    }
    const int raw = ::pclose(pipe);
    run.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    return run;
}

} // namespace demo_test
