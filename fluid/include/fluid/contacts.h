// fluid — contact events: which bodies the liquid touched during the last step, how many
// particles, how hard (docs/plugins.md and docs/box2d.md, "Contact events").
#pragma once

#include <fluid/handle.h>

#include <glm/vec2.hpp>

#include <cstdint>
#include <span>

namespace fluid {

class World;

/// How close a particle's centre must come to one of a body's boundary samples to touch the body
/// (unit: sample spacings, `StepContext::sampleSpacing`). A body's outermost samples lie half a
/// spacing inside its surface and the liquid's first row half a spacing outside it, so a
/// particle resting on the body stands one spacing from them and the second row two: 1.5 counts
/// the first row only. Thread rule: a constant.
inline constexpr float kContactReach = 1.5f;

/// What the liquid did to one body over a step (a world's step, or a Box2D coupling's frame of
/// rounds): the part of a contact event `BodyContact` and `box2d::ParticleContact` share. Plain
/// data.
struct ContactSummary {
    /// The material most of the touching particles have (ties: the lower index).
    MaterialId material{};
    /// The particle group most of the touching particles belong to (fluid/groups.h; ties: the
    /// lower index; particles in no group are not counted); null when none of them is in one.
    GroupHandle group{};
    /// Distinct particles that touched the body during the step, over all its sub-steps (unit:
    /// count; >= 1); `contactParticles` (`Coupling::contactParticles`) lists them.
    uint32_t particles = 0;
    /// The liquid's impulse on the body over the step (unit: N s). A world's contact: its
    /// pressure and viscous forces on the body's samples summed over the sub-steps (the force
    /// `receiveForces` gets, times the step's time), plus the position-based coarse solve's push
    /// on a body with a mass; divide by the step's time (`World::step`'s simulated time) for the
    /// mean force. A Box2D body's: each round's `BodyReport::force` (pressure, viscosity,
    /// projection and coarse solve; before the relaxation hands it to Box2D) times the round's
    /// time, summed; floating at rest, it balances the body's weight times the frame's time.
    glm::vec2 impulse{0.0f, 0.0f};
    /// Mean position of the touching particles, each counted once per sub-step it touched (unit:
    /// m): where a splash sound or effect goes.
    glm::vec2 point{0.0f, 0.0f};
    /// Largest speed at which a touching particle moved towards one of the body's samples,
    /// relative to the sample's own velocity, at the end of a sub-step (unit: m/s; >= 0; 0 when
    /// every touching particle moved away or along). The solver stops an incoming particle over
    /// a few sub-steps, so a fast hit reads a good part of its speed: a splash's loudness.
    float approachSpeed = 0.0f;
};

/// What the liquid did to one body during the last step. Reported, after the step, for every
/// rigid body (`BoundaryPlugin::rigidBodies`) that asked for it (`RigidBody::contacts`) and that
/// some particle touched (came within `kContactReach` sample spacings of one of its samples at
/// the end of one of the step's sub-steps); a body that asked but stayed dry reports nothing.
/// Plain data; valid until the next step.
struct BodyContact : ContactSummary {
    /// The boundary plugin, by its index in `World::boundaries()` (unit: index).
    uint32_t plugin = 0;
    /// The body, by its index in that plugin's `rigidBodies()` (unit: index).
    uint32_t body = 0;
};

/// The contacts of the last `World::step`, ordered by plugin (in `World::boundaries()` order),
/// then by body index: the same for any number of workers and after a save and load. Empty
/// after a step that simulated nothing (a frame shorter than half a sub-step) and in a world
/// loaded from a snapshot until it steps (events are not state). Cost: nothing in a world where
/// no body asks; otherwise a pass over the asking bodies' samples per sub-step (and the
/// position-based solver then measures the forces on their samples). Throws `fluid::Error` with
/// `ErrorCode::WrongState` during the world's own step. Thread rule: between steps, from any
/// thread (the world must not change meanwhile).
std::span<const BodyContact> bodyContacts(const World& world);

/// The particles that touched the body of `bodyContacts(world)[contact]` during the last step,
/// by handle, in increasing slot order (`ParticleHandle::slot`); a particle a drain or its
/// lifetime removed at the end of the step has a stale handle by now. Throws `fluid::Error`
/// naming the index and the count for `contact` >= `bodyContacts(world).size()`, and with
/// `ErrorCode::WrongState` during the world's own step. Thread rule: as `bodyContacts`.
std::span<const ParticleHandle> contactParticles(const World& world, uint32_t contact);

} // namespace fluid
