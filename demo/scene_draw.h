// fluid-demo — what the renderer draws besides the liquid: walls and shapes of the boundary
// plugins, sensors, drains and emitters of the level, and its Box2D bodies.
#pragma once
#include <fluid/gl/shapes.h>
#include <fluid/level.h>

#include <glm/vec2.hpp>

#include <span>

class b2Body;

namespace fluid::demo {

/// The world rectangle a level is framed in (unit: m).
struct ViewBounds {
    /// Lower-left and upper-right corners (unit: m).
    glm::vec2 lo{0.0f, 0.0f}, hi{1.0f, 1.0f};
};

/// The rectangle to frame `level` in (unit: m): its first `boundary.box` tank with the walls
/// drawn round it when it has one, grown to hold the emitters, sensors, bodies and the static
/// Box2D fixtures within a tenth of the tank's size of it; otherwise the extent of everything
/// in the level (particles, shapes, bodies) with room around it for blobs to drift. Call once
/// after loading, so the camera does not follow the liquid. Stepping thread.
ViewBounds levelBounds(const Level& level);

/// Walls, static shapes, drains and sensors (with their fill shown by `goalFill`, unit: 1 in
/// [0, 1], for the goal's sensor), drawn under the liquid with outlines `lineWidth` wide
/// (unit: m). Stepping thread (reads plugins and Box2D).
void drawUnder(const Level& level, double goalFill, float lineWidth, gl::ShapeBatch& batch);

/// A Box2D body's pose at the start of the last level frame (`drawOver`).
struct BodyPose {
    const b2Body* body = nullptr;
    glm::vec2 position{0.0f, 0.0f}; // m
    float angle = 0.0f;             // rad
};

/// Box2D bodies (filled, outlined, shaded by density: light floats, dark sinks), kinematic
/// plugin shapes and emitter nozzles, drawn over the liquid. `lineWidth` (unit: m) is the
/// outline width, about 1.5 px. Stepping thread.
/// A body listed in `previous` is drawn `factor` (unit: 1; [0, 1]) of the way from that pose to
/// its current one, as the liquid is drawn between frames (fluid::Interpolation::Step); others
/// at their current pose.
void drawOver(const Level& level, float lineWidth, gl::ShapeBatch& batch,
              std::span<const BodyPose> previous = {}, float factor = 1.0f);

} // namespace fluid::demo
