// fluid tests — helpers the level tests share: the message a level text
// fails with, a body by its level name.
#pragma once

#include "test_support.h"

#include <fluid/level.h>
#include <fluid/plugins/builtin.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>

class b2Body;

namespace fluid::test {

/// A valid level with one material, `extra` spliced in after it (starting with ", ").
inline std::string levelWith(const std::string& extra) {
    return R"({"version": 1, "materials": [{"name": "water"}])" + extra + "}";
}

/// Plays `frames` frames of `level`; returns the wall time per frame (unit: ms).
inline double playFrames(Level& level, int frames) {
    const auto t0 = std::chrono::steady_clock::now();
    for (int f = 0; f < frames; ++f) {
        level.step();
    }
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
               .count() /
           std::max(frames, 1);
}

/// The text of the shipped level `name` (a file in levels/); empty if it cannot be read.
inline std::string readLevel(const char* name) {
    std::ifstream in(std::string(FLUID_LEVELS_DIR) + "/" + name, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

/// The message of the LevelError that parsing `text` as "t.json" throws ("no error" when none).
inline std::string errorOf(std::string_view text, const LevelOptions& options = {}) {
    try {
        parseLevel(text, "t.json", builtins(), options);
    } catch (const LevelError& e) {
        return e.what();
    }
    return "no error";
}

/// The code of the LevelError loading `text` throws (nothing when it loads).
inline std::optional<ErrorCode> codeOf(std::string_view text, const LevelOptions& options = {}) {
    try {
        parseLevel(text, "t.json", builtins(), options);
    } catch (const LevelError& e) {
        return e.code();
    }
    return std::nullopt;
}

/// The level's body named `name`, nullptr when there is none.
inline b2Body* bodyNamed(const Level& level, std::string_view name) {
    for (const auto& [n, body] : level.bodies) {
        if (n == name) {
            return body;
        }
    }
    return nullptr;
}

/// `level.save` as bytes.
inline std::string saveOf(const Level& level) {
    std::ostringstream out;
    level.save(out);
    return out.str();
}

/// The level a save's bytes hold, named "s.sav" in errors.
inline Level restore(const std::string& bytes, const LevelOptions& options = {}) {
    std::istringstream in(bytes);
    return readLevelSave(in, "s.sav", builtins(), options);
}

} // namespace fluid::test
