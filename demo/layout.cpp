// fluid-demo — the window's layout (see layout.h).
#include "demo/layout.h"

#include <glm/common.hpp>

#include <algorithm>
#include <cmath>

namespace fluid::demo {
namespace {
// At scale 1 (unit: px): the band's height, which holds the banner's title, one line of text
// and a goal's progress bar, or five lines of the HUD; the gap between the overlays and the
// band's bottom edge; the margin to the window's edges; the widest HUD.
constexpr float kBand = 124.0f;
constexpr float kGap = 6.0f;
constexpr float kEdge = 10.0f;
constexpr float kHudWidth = 420.0f;
// The window the overlays are drawn at full size in, and below which they shrink (unit: px).
constexpr glm::vec2 kFullSize{960.0f, 540.0f};
constexpr float kMinScale = 0.5f;
// The margin round the framed level, a share of its size on every side (unit: 1).
constexpr float kMargin = 0.05f;
} // namespace

OverlayLayout overlayLayout(glm::ivec2 window) {
    const glm::vec2 size(glm::max(window, glm::ivec2(1)));
    OverlayLayout layout;
    layout.scale = std::clamp(std::min(size.x / kFullSize.x, size.y / kFullSize.y), kMinScale,
                              1.0f);
    layout.band = std::round(kBand * layout.scale);
    layout.edge = std::round(kEdge * layout.scale);
    const float bottom = layout.band - std::round(kGap * layout.scale);
    layout.hud.min = {layout.edge, layout.edge};
    layout.hud.max = {layout.edge + std::min(kHudWidth * layout.scale, 0.45f * size.x), bottom};
    layout.banner.min = {layout.edge, layout.edge};
    layout.banner.max = {size.x - layout.edge, bottom};
    return layout;
}

gl::Camera frameLevel(glm::vec2 lo, glm::vec2 hi, glm::ivec2 window) {
    const OverlayLayout layout = overlayLayout(window);
    const glm::ivec2 full = glm::max(window, glm::ivec2(1));
    // The room below the band, at least a pixel high.
    const glm::ivec2 room{full.x, std::max(full.y - int(layout.band), 1)};
    gl::Camera camera = gl::Camera::fit(lo, hi, room, kMargin);
    // The same zoom in the whole window, the level's centre at the room's centre: half the
    // band below the window's.
    camera.viewport = full;
    camera.center.y += 0.5f * (float(full.y) - float(room.y)) / camera.pixelsPerMetre;
    return camera;
}

} // namespace fluid::demo
