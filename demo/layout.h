// fluid-demo — where things go in the window: a band across the top for the HUD and the level
// banner, the level framed below it, so neither overlay ever covers the level.
#pragma once

#include <fluid/gl/camera.h>

#include <glm/vec2.hpp>

namespace fluid::demo {

/// A rectangle of window pixels (origin top left, y down; unit: px).
struct PixelRect {
    /// Top-left corner.
    glm::vec2 min{0.0f};
    /// Bottom-right corner.
    glm::vec2 max{0.0f};
    /// max.x - min.x (unit: px).
    float width() const { return max.x - min.x; }
    /// max.y - min.y (unit: px).
    float height() const { return max.y - min.y; }
};

/// Where the overlays go in a window of a given size. Pure: any thread.
struct OverlayLayout {
    /// Text scale of the HUD and the banner (unit: 1): 1 in windows of 960 x 540 and more,
    /// smaller in smaller ones (the window's shorter side against 960 x 540, at least 0.5).
    float scale = 1.0f;
    /// Height of the band across the top (unit: px; 124 at scale 1): the HUD and the banner
    /// stay in it; the level is framed below it (`frameLevel`).
    float band = 0.0f;
    /// Margin between the overlays and the window's edges (unit: px; 10 at scale 1).
    float edge = 10.0f;
    /// The box the HUD fits in, top left (it scales its text down when its lines do not fit).
    PixelRect hud;
    /// The box the banner fits in: its top and bottom, and its right edge (the window's); it
    /// starts right of the HUD as drawn.
    PixelRect banner;
};

/// The layout of a window of `window` pixels (each at least 1).
OverlayLayout overlayLayout(glm::ivec2 window);

/// The camera that shows the rectangle [lo, hi] (unit: m) whole in a window of `window`
/// pixels below the overlays' band, with a 5% margin, centred in the room below the band.
gl::Camera frameLevel(glm::vec2 lo, glm::vec2 hi, glm::ivec2 window);

} // namespace fluid::demo
