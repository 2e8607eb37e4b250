// fluid-demo — the HUD: frame rate, particles, simulation cost, modes and probes, top left.
#pragma once

#include "demo/layout.h"

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

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

/// One piece of a HUD line and how it is coloured.
struct HudSpan {
    /// How a span is drawn.
    enum class Style : uint8_t {
        /// A value: ImGui's text colour.
        Value,
        /// A label or a hint: the light grey `ui::kHint`.
        Label,
        /// A warning: amber (PAUSED, "simulation behind").
        Warning,
        /// Zero-g: cyan.
        ZeroG,
    };
    /// The text.
    std::string text;
    /// Its colour.
    Style style = Style::Value;
};

/// The HUD's lines, top to bottom, each a row of spans drawn with ImGui's item spacing between
/// them: "60 fps | 406 particles", "sim 0.8 ms/frame | 4 sub-steps", "view metaballs  material
/// water  gravity on" (or "zero-g"), then "PAUSED P resume, . step" while paused, "simulation
/// behind: 71% speed (3 dropped)" while behind, "cursor ..." and "laser ..." when set, and
/// the hints "F1 help   Esc levels   Tab tuning". Pure: any thread.
std::vector<std::vector<HudSpan>> hudLines(const HudInfo& info);

/// Draws the HUD (`hudLines`) at the top left of `box` (unit: px; `OverlayLayout::hud`) at
/// `scale` (`OverlayLayout::scale`: text, padding and spacing) or smaller, as large as lets
/// every line fit inside the box; at half size, lines that still do not fit are left out (the
/// hints, then the simulation's cost, then lines from the bottom). Labels and hints are a light grey on an 82% opaque backing,
/// readable over the grey walls. No decoration, takes no input. Returns the HUD's right edge
/// (unit: px): the banner starts a margin right of it. Thread rule (every function drawing
/// here): between `ImGuiBridge::newFrame` and `render`, on the GL thread.
float drawHud(const HudInfo& info, const PixelRect& box, float scale = 1.0f);

} // namespace fluid::demo
