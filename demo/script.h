// fluid-demo — scripted input: a timed list of key presses and mouse actions that the game
// plays as if a player made them. Tests drive the interactive game with it; the game records a
// player's input in the same format (`fluid-demo --record`), for a bug report or a replay.
#pragma once
#include "demo/platform.h"

#include <glm/vec2.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace fluid::demo {

/// One scripted input.
struct ScriptAction {
    /// What it does.
    enum class Kind : uint8_t {
        /// Press and release a key (`key`).
        Key,
        /// Move the mouse to `position`.
        Move,
        /// Move the mouse to `position` and press `button` (with `shift` or `ctrl` held).
        Press,
        /// Release `button` (and the modifiers `Press` held).
        Release,
    };
    /// Frame at whose start it happens (unit: frame number, from 1).
    uint32_t frame = 1;
    /// See `Kind`.
    Kind kind = Kind::Key;
    /// The key of `Key`.
    demo::Key key = demo::Key::Unknown;
    /// 0 left, 1 right, for `Press` and `Release`.
    int button = 0;
    /// Modifiers held during a `Press` until its `Release`.
    bool shift = false, ctrl = false;
    /// Mouse position in the level (unit: m) for `Move` and `Press`: finite here; the game
    /// refuses one off its window when it plays the action.
    glm::vec2 position{0.0f, 0.0f};
    /// The script's line it was read from, for messages (unit: line number, from 1; 0 when
    /// not read from a file).
    uint32_t line = 0;
};

/// Reads a script: one action per line, `#` starts a comment, frames in non-decreasing order.
///
///     FRAME key NAME                      (S, G, M, Space, R, P, Period, N, B, Tab, F1,
///                                          Escape, Q, E, Num1 ... Num9)
///     FRAME move X Y                      (metres, in the level's coordinates)
///     FRAME press left|right X Y [shift|ctrl]
///     FRAME release left|right
///
/// Throws `fluid::Error` "FILE:LINE: MESSAGE" for anything else, and "FILE: MESSAGE" for a
/// path that is a directory or cannot be read. A position is checked against the window when
/// it is played (`GameOptions::scriptPath`). Any thread.
std::vector<ScriptAction> readScript(const std::string& path);

/// The name `readScript` reads for `key`, or nullptr for the keys a script cannot press (the
/// modifiers, which `press` carries, and keys the game does not use). Any thread.
const char* scriptKeyName(Key key);

/// One line of a script for `action`, `readScript`'s format, no newline. Positions are written
/// with 9 significant digits, so they read back to the same floats. `pixel`, when given, is
/// appended as a comment (`# pixel X Y`): where the pointer was on the window. Any thread.
std::string scriptLine(const ScriptAction& action, const glm::ivec2* pixel = nullptr);

} // namespace fluid::demo
