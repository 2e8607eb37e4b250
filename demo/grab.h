// fluid-demo — grabbing a Box2D body with the mouse (shift + drag, Q / E to turn a plank).
#pragma once

#include <box2d/box2d.h>
#include <glm/vec2.hpp>

namespace fluid::demo {

/// The body under `p` (unit: m): a dynamic or kinematic one; static ground is never grabbed.
/// Null when there is none.
b2Body* bodyAt(b2World& world, glm::vec2 p);

/// A body held by the mouse: dynamic bodies follow a mouse joint, kinematic ones (the planks
/// of "Fill the cup") get the velocity that brings the grabbed point to the cursor in one
/// frame, capped at 3 m/s, so the fluid sees them move instead of teleport. Main thread.
struct Grab {
    /// The body held; null when nothing is.
    b2Body* body = nullptr;
    /// The joint's static anchor (dynamic bodies only).
    b2Body* ground = nullptr;
    /// The joint pulling a dynamic body.
    b2MouseJoint* joint = nullptr;
    /// The grabbed point in the body's frame (unit: m).
    b2Vec2 localPoint{0.0f, 0.0f};
    /// Q / E: the turn rate given to a kinematic body (unit: rad/s).
    float spin = 0.0f;

    /// Takes hold of `target` at `p` (unit: m).
    void begin(b2World& world, b2Body* target, glm::vec2 p);
    /// Pulls the held body towards `p` (unit: m) for a frame of `dt` (unit: s).
    void update(glm::vec2 p, float dt);
    /// Lets go: a kinematic body stops, the joint goes with its anchor (when `world` is not
    /// null: pass null when the world is already gone).
    void end(b2World* world);
};

} // namespace fluid::demo
