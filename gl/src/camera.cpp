// fluid::gl — the 2D camera (pure math).
#include <fluid/gl/camera.h>

#include <glm/common.hpp>

#include <algorithm>
#include <cmath>

namespace fluid::gl {

namespace {
// A degenerate rectangle is widened to this (unit: m) so the zoom stays finite.
constexpr float kMinExtent = 1e-3f;
} // namespace

Camera Camera::fit(glm::vec2 lo, glm::vec2 hi, glm::ivec2 viewport, float margin) {
    Camera camera;
    camera.viewport = glm::max(viewport, glm::ivec2(1));
    if (!std::isfinite(margin) || margin < 0.0f) {
        margin = 0.0f;
    }
    const glm::vec2 a = glm::min(lo, hi);
    const glm::vec2 b = glm::max(lo, hi);
    camera.center = 0.5f * (a + b);
    const glm::vec2 extent = glm::max(b - a, glm::vec2(kMinExtent)) * (1.0f + 2.0f * margin);
    const glm::vec2 pixels(camera.viewport);
    // The tighter axis decides: the whole rectangle shows, the other axis gets extra room.
    camera.pixelsPerMetre = std::min(pixels.x / extent.x, pixels.y / extent.y);
    return camera;
}

glm::vec2 Camera::worldToPixel(glm::vec2 world) const {
    const glm::vec2 half = 0.5f * glm::vec2(viewport);
    return {half.x + (world.x - center.x) * pixelsPerMetre,
            half.y - (world.y - center.y) * pixelsPerMetre};
}

glm::vec2 Camera::pixelToWorld(glm::vec2 pixel) const {
    const glm::vec2 half = 0.5f * glm::vec2(viewport);
    return {center.x + (pixel.x - half.x) / pixelsPerMetre,
            center.y - (pixel.y - half.y) / pixelsPerMetre};
}

glm::vec2 Camera::worldMin() const {
    return center - 0.5f * glm::vec2(viewport) / pixelsPerMetre;
}

glm::vec2 Camera::worldMax() const {
    return center + 0.5f * glm::vec2(viewport) / pixelsPerMetre;
}

} // namespace fluid::gl
