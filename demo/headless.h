// fluid-demo — headless runs: step levels a fixed number of frames, render, save PNGs. For
// tests, screenshots for the docs, and machines without a display (under Xvfb).
#pragma once
#include "demo/level_list.h"

#include <fluid/gl/renderer.h>

#include <glm/vec2.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace fluid::demo {

/// What a headless run does.
struct HeadlessOptions {
    /// Levels to play, each from its start.
    std::vector<LevelFile> levels;
    /// Views to save for each level (one PNG each).
    std::vector<gl::View> views{gl::View::Metaballs};
    /// Frames to step each level before its screenshots (unit: count; >= 1).
    uint32_t frames = 120;
    /// Also render every this many frames while stepping (unit: count; 0 = only at the end),
    /// so a test sees GL errors of mid-run states.
    uint32_t renderEvery = 0;
    /// Display rate (unit: Hz; 0 = off): each frame feeds 1 / displayHz s to a frame pacer that
    /// runs whole level frames, as the game does, and the liquid is drawn between the last two
    /// at the fraction of a frame the pacer holds (fluid/groups.h, Interpolation::Step).
    float displayHz = 0.0f;
    /// Image size (unit: px).
    glm::ivec2 size{960, 540};
    /// Worker threads of each world (unit: count; >= 1).
    uint32_t workers = 2;
    /// Draws the HUD and the level banner into the screenshots.
    bool hud = true;
    /// One file (a single level and view) ...
    std::string screenshot;
    /// ... or a directory receiving LEVEL-VIEW.png per level and view, and summary.txt.
    std::string screenshotDir;
};

/// Runs `options`; prints one summary line per image on stdout (level, view, frames, particles,
/// size, camera, GL errors, file). Returns the process exit status: 0 done, 1 a level or GL
/// set-up error (message on stderr), 3 GL errors while rendering. Needs a display (Xvfb).
int runHeadless(const HeadlessOptions& options);

} // namespace fluid::demo
