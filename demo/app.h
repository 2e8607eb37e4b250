// fluid-demo — the interactive game: window, fixed-step loop, controls, HUD and panels.
#pragma once
#include "demo/level_list.h"
#include "demo/script.h"

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
    /// Where F5 saves the level and F9 loads it back (one file per level, `<stem>.level`;
    /// created when needed).
    std::string saveDir = ".";
    /// Scripted input (`readScript`), played at the frames it names.
    std::vector<ScriptAction> script;
    /// 0: play until the window closes. Otherwise run exactly this many frames of one step
    /// each (no real-time pacing, so a script gives the same result on any machine), print a
    /// summary line (level, time, particles per material, centre of mass, view, gravity, body
    /// positions) and exit (unit: count).
    uint32_t frames = 0;
    /// With `frames`: save the last frame, HUD included, to this PNG.
    std::string screenshot;
};

/// Opens the window and plays until it is closed or Quit is chosen (or `frames` ran). Returns
/// the exit status: 0, or 1 when the window or OpenGL cannot be set up or the screenshot
/// cannot be written (message on stderr). Main thread.
int runGame(const GameOptions& options);

} // namespace fluid::demo
