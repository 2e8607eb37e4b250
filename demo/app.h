// fluid-demo — the interactive game: window, fixed-step loop, controls, HUD and panels.
#pragma once
#include "demo/level_list.h"

#include <glm/vec2.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace fluid::demo {

/// How the game starts.
struct GameOptions {
    /// The playlist (N / B / 1-9 / Esc move through it).
    std::vector<LevelFile> levels;
    /// Index of the first level in `levels`.
    int first = 0;
    /// Window size (unit: px).
    glm::ivec2 size{1280, 720};
    /// Worker threads of each world (unit: count; >= 1).
    uint32_t workers = 2;
    /// Start in fullscreen.
    bool fullscreen = false;
    /// Where F12 saves screenshots.
    std::string screenshotDir = ".";
};

/// Opens the window and plays until it is closed or Quit is chosen. Returns the exit status:
/// 0, or 1 when the window or OpenGL cannot be set up (message on stderr). Main thread.
int runGame(const GameOptions& options);

} // namespace fluid::demo
