// fluid — the command-line rule shared by fluid-bench, fluid-run, fluid-soak, fluid-float and
// fluid-demo: a bad command line exits with status 2, as their documentation says.
#pragma once

#include <fluid/error.h>
#include <fluid/world.h>

#include <CLI/CLI.hpp>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace fluid::tools {

/// Parses `argv` into `app`. Returns -1 when the program should go on; otherwise the status to
/// exit with: 0 after `--help` (the help printed on standard output), 2 for a bad command line
/// (an unknown option, a value of the wrong type or out of range, a missing required option:
/// CLI11's message and its usage hint printed on standard error). Main thread.
inline int parseCommandLine(CLI::App& app, int argc, char** argv) {
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        const int status = app.exit(e); // prints the help, or the message and the hint
        return status == 0 ? 0 : 2;
    }
    return -1;
}

/// The names of an enum's name table (`fluid::kQualityNames`...), for CLI::IsMember: an option
/// takes exactly the names the library parses. Any thread.
template <class Enum, std::size_t N>
std::vector<std::string> namesOf(const EnumName<Enum> (&table)[N]) {
    std::vector<std::string> names;
    for (const EnumName<Enum>& row : table) {
        names.emplace_back(row.name);
    }
    return names;
}

/// The --quality option of the tools that step a world of their own: `quality` is set to
/// "game" and takes one of the presets' names (`fluid::kQualityNames`). Main thread.
inline CLI::Option* addQualityOption(CLI::App& app, std::string& quality,
                                     const std::string& description) {
    quality = std::string(qualityName(Quality::Game));
    return app.add_option("--quality", quality, description)
        ->check(CLI::IsMember(namesOf(kQualityNames)));
}

/// A world definition with the position-based preset named `quality` (as --quality checked it)
/// and `threads` workers (unit: count; [1, 256]). Any thread.
inline WorldDef presetWorldDef(const std::string& quality, uint32_t threads) {
    WorldDef def;
    def.positionBased = positionBasedPreset(qualityFromName(quality).value_or(Quality::Game));
    def.workerCount = threads;
    return def;
}

} // namespace fluid::tools
