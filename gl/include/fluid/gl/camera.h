// fluid::gl — a 2D camera: metres to pixels and back. Pure math, no GL.
#pragma once
#include <glm/vec2.hpp>

namespace fluid::gl {

/// Maps world coordinates (m, y up) to pixels of a target (origin top-left, y down) and back.
/// A plain value; thread rule: none (no shared state).
struct Camera {
    /// World point at the target's centre (unit: m).
    glm::vec2 center{0.0f, 0.0f};
    /// Zoom (unit: px/m; > 0).
    float pixelsPerMetre = 100.0f;
    /// Target size (unit: px; each >= 1).
    glm::ivec2 viewport{1, 1};

    /// The camera that shows the rectangle [lo, hi] (unit: m) whole, centred, in a target of
    /// `viewport` pixels, with `margin` (unit: 1, fraction of the rectangle; >= 0) around it.
    /// A degenerate rectangle is widened to 1 mm.
    static Camera fit(glm::vec2 lo, glm::vec2 hi, glm::ivec2 viewport, float margin = 0.05f);
    /// The pixel of a world point (unit: px, origin top-left, y down; not rounded).
    glm::vec2 worldToPixel(glm::vec2 world) const;
    /// The world point of a pixel (unit: m).
    glm::vec2 pixelToWorld(glm::vec2 pixel) const;
    /// The world rectangle the target shows: lower-left and upper-right corners (unit: m).
    glm::vec2 worldMin() const;
    /// See `worldMin`.
    glm::vec2 worldMax() const;
};

} // namespace fluid::gl
