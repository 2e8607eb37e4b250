// fluid::box2d internals — what the coupling reads of Box2D's private solver state
// (physics_save.cpp, which reaches it through box2d_internals.h).
#pragma once

class b2Body;

namespace fluid::box2d::detail {

/// Whether `body` holds a force or torque for Box2D's next step (applied since the last step;
/// b2Body 2.4.1 keeps them private). Thread rule: the thread that steps its world.
bool carriesForce(const b2Body& body);

} // namespace fluid::box2d::detail
