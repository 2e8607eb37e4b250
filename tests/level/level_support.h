// fluid tests — helpers the level tests share: the built-in registry, the message a level text
// fails with, a body by its level name.
#pragma once

#include <fluid/level.h>
#include <fluid/plugins/builtin.h>

#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>

class b2Body;

namespace fluid::test {

/// The registry with every built-in plugin, made once.
inline const Registry& builtins() {
    static const Registry registry = [] {
        Registry r;
        registerBuiltinPlugins(r);
        return r;
    }();
    return registry;
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
