// fluid-demo — the HUD: frame rate, particles, simulation cost, modes and probes, top left.
#pragma once

#include <cstdint>
#include <string_view>

namespace fluid::demo {

/// What the HUD shows; the main loop fills it every frame.
struct HudInfo {
    /// Rendered frames per second (unit: Hz).
    float fps = 0.0f;
    /// Particles in the world (unit: count).
    uint32_t particles = 0;
    /// Wall time the simulation took this frame, all its steps (unit: ms).
    float simMsPerFrame = 0.0f;
    /// Solver sub-steps of the last step (unit: count; `Profile::substeps`).
    uint32_t substeps = 0;
    /// Name of the current view ("metaballs", "pressure", "particles").
    std::string_view view;
    /// Name of the material Space drops.
    std::string_view material;
    /// True while gravity is off (G).
    bool zeroG = false;
    /// True while paused (P).
    bool paused = false;
    /// `FramePacer::behind()`: shows the amber "simulation behind" line.
    bool behind = false;
    /// `FramePacer::speed()` (unit: 1; 1 = real time).
    double speed = 1.0;
    /// `FramePacer::droppedSteps()` (unit: count).
    uint64_t droppedSteps = 0;
    /// The liquid under the cursor (`LiquidProbe::cursorText`; empty: no line).
    std::string_view cursor;
    /// The laser's hit (`LiquidProbe::laserText`; empty while it is off: no line).
    std::string_view laser;
};

/// Draws the HUD top-left: fps, particles, sim ms/frame, sub-steps, view, material, gravity or
/// zero-g, the liquid under the cursor and the laser's hit, PAUSED, and "simulation behind: 71% speed" in amber while `behind`. Labels and hints
/// are a light grey on an 82% opaque backing, readable over the grey walls. No decoration,
/// takes no input; `drawLevelBanner` keeps clear of its right edge (as measured when last
/// drawn). Thread rule (every function here): between `ImGuiBridge::newFrame` and `render`,
/// on the GL thread.
void drawHud(const HudInfo& info);

/// Right edge of the HUD as last drawn, margin included (unit: px; 260 before the first
/// draw): the banner keeps clear of it. Same thread rule as `drawHud`.
float hudRight();

} // namespace fluid::demo
