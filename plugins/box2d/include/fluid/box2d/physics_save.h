// fluid — saving and restoring a Box2D 2.4 world: bodies, fixtures, revolute joints.
#pragma once

#include <iosfwd>
#include <memory>

class b2World;

namespace fluid::box2d {

/// Writes `physics` to `out` in a binary form `loadPhysics` reads back: the world's gravity and
/// settings; every body in `GetBodyList()` order with its type, pose, velocities, damping,
/// gravity scale, flags (awake, enabled, bullet, fixed rotation, sleep allowed) and mass data;
/// every fixture in order (circle, polygon, edge, chain; density, friction, restitution and its
/// threshold, sensor flag, filter); every revolute joint with its anchors, limits and motor;
/// then the solver state Box2D 2.4.1 keeps private (format version 2): every contact in the
/// world's list order with its fixtures, flags, friction and restitution mixing, tangent speed,
/// TOI state and manifold (points, feature ids, normal and tangent impulses); the broad phase's
/// dynamic tree node for node and its move buffer; each body's sweep, inertia about its centre of
/// mass, accumulated force and torque, sleep timer and its fixtures' proxies; revolute joints'
/// impulses; the world's last inverse time step and flags. A world `loadPhysics` restores steps
/// on bit-identically with this one. Not saved: user data (pointers), contact listeners and
/// filters, the destruction listener and debug draw. Throws `fluid::Error` for a joint of
/// another type (naming it). Thread rule: the thread that steps `physics`, between steps.
void savePhysics(const b2World& physics, std::ostream& out);

/// Reads what `savePhysics` wrote and builds a new `b2World` whose bodies, fixtures and joints
/// keep their saved order in `GetBodyList()`, `GetFixtureList()` and `GetJointList()`, and,
/// from a version-2 save, Box2D's solver state, so that it steps on bit-identically (a
/// version-1 save, without it, still loads: its contacts are made anew at the first step).
/// Throws `fluid::Error` ("box2d save: ...") for a truncated or malformed save: a count out of
/// range or larger than the bytes left could hold (checked before anything is sized by it), a
/// non-finite or out-of-range value, naming the field (|coordinate| above 1e5 m, speeds above
/// 1e6 m/s or rad/s, mass above 1e9 kg, density above 1e9 kg/m^2, gravity scale, friction or
/// restitution above 1e3, motor torque above 1e15 N m, a dynamic body lighter than
/// `kMinBodyMass` or `kMinBodyInertia` of coupling.h), an unknown shape or joint type; a
/// fixture a level file could not declare, named by body and fixture ("box2d save: body 0
/// fixture 6 circle radius = 2.3e-38 is not finite or out of [0.005, 10000] (unit: m)"):
/// body-local coordinates above 1e4 m, a circle's radius outside [0.005, 1e4] m (Box2D's
/// linear slop), a polygon not of 3 to 8 vertices at least 0.005 m apart, not convex
/// counter-clockwise or of less than 2.5e-5 m^2, an edge or chain link no longer than 0.005 m,
/// a chain of more than 4096 points; a solver state that does not fit the world (a broad-phase
/// tree that is not a tree, a proxy that is not its own leaf, a contact between fixtures of
/// one body or with a touching flag its points deny, impulses above 1e15 N s, naming the node,
/// proxy or contact). Any thread (the new world is the caller's).
std::unique_ptr<b2World> loadPhysics(std::istream& in);

} // namespace fluid::box2d
