// fluid — 2D SPH liquid for games.
#pragma once

#include <fluid/fields.h>
#include <fluid/handle.h>
#include <fluid/shape.h>

#include <glm/vec2.hpp>

#include <cstdint>
#include <span>
#include <string>

namespace fluid {

/// An emitter of a world (from `World::addEmitter`). A world's emitters are never removed: an id
/// stays valid for the life of the world that made it (see `MaterialId` for the rule on other
/// worlds). Thread rule: a plain value.
struct EmitterId {
    /// Index in the world's emitter list (unit: index).
    uint32_t index = 0;
    /// Tag of the `World` that made the id (as `ParticleHandle::world`; 0 in an id made by hand
    /// from an index, which every world takes as an index).
    uint32_t world = 0;
    /// Ids are equal when their indices are (the tag says which world made one, not what it
    /// names).
    friend constexpr bool operator==(EmitterId a, EmitterId b) { return a.index == b.index; }
};

/// A drain of a world (from `World::addDrain`). A world's drains are never removed: an id stays
/// valid for the life of the world that made it (see `MaterialId` for the rule on other worlds).
/// Thread rule: a plain value.
struct DrainId {
    /// Index in the world's drain list (unit: index).
    uint32_t index = 0;
    /// Tag of the `World` that made the id (as `ParticleHandle::world`; 0 in an id made by hand
    /// from an index, which every world takes as an index).
    uint32_t world = 0;
    /// Ids are equal when their indices are (the tag says which world made one, not what it
    /// names).
    friend constexpr bool operator==(DrainId a, DrainId b) { return a.index == b.index; }
};

/// A sensor of a world (from `World::addSensor`). A world's sensors are never removed: an id stays
/// valid for the life of the world that made it (see `MaterialId` for the rule on other worlds).
/// Thread rule: a plain value.
struct SensorId {
    /// Index in the world's sensor list (unit: index).
    uint32_t index = 0;
    /// Tag of the `World` that made the id (as `ParticleHandle::world`; 0 in an id made by hand
    /// from an index, which every world takes as an index).
    uint32_t world = 0;
    /// Ids are equal when their indices are (the tag says which world made one, not what it
    /// names).
    friend constexpr bool operator==(SensorId a, SensorId b) { return a.index == b.index; }
};

/// A faucet: emits rows of particles across a nozzle, moving along `direction` at `speed`.
/// Particles are emitted at the start of each `World::step` for the time that passed since the
/// last one, each placed where it would be had it left the nozzle at its own emission time, so
/// a jet is evenly spaced whatever the frame rate. A row holds `lanes = 1 + round(width /
/// spacing)` particles, one spacing apart across the nozzle. No particle is placed where the
/// liquid already stands at its rest density, inside a solid or outside a container (a boundary
/// plugin's `contains`): those count in `Profile::emitSkipped`.
struct EmitterDef {
    /// Centre of the nozzle (unit: m; finite).
    glm::vec2 position{0.0f, 0.0f};
    /// Direction of the jet (unit: 1; finite, not zero; normalised by the world).
    glm::vec2 direction{0.0f, -1.0f};
    /// Exit speed (unit: m/s; range [0.01, 100]). Typical: 1.5.
    float speed = 1.5f;
    /// Nozzle width across the jet (unit: m; range [0, 100]; 0 = one particle per row).
    /// Typical: 0.05.
    float width = 0.05f;
    /// Particles per second (unit: 1/s; range [0, 1e6]). At most lanes * speed / spacing: rows
    /// closer than one spacing would overlap (`World::addEmitter` says the limit). 0 = closed.
    float rate = 500.0f;
    /// Material of the emitted particles.
    MaterialId material{};
    /// Most particles this emitter emits over its life (unit: count; 0 = no limit).
    uint32_t maxCount = 0;
    /// Lifetime of each emitted particle (unit: s; range [0, 1e6]; 0 = lives forever).
    float lifetime = 0.0f;
    /// Random offset across the jet, as a share of the spacing (unit: 1; range [0, 0.5]);
    /// breaks the lattice look of a jet. Drawn from the emitter's own generator (seeded with
    /// `seed`), so results stay deterministic and survive a snapshot.
    float jitter = 0.0f;
    /// Seed of the emitter's random generator (unit: 1; any value).
    uint64_t seed = 1;
};

/// The numbers of `EmitterDef` (see `Field`): speed, width, rate, maxCount, lifetime and jitter.
/// `position`, `direction`, `material` and `seed` are checked on their own. Static storage. Any
/// thread.
std::span<const Field<EmitterDef>> emitterFields();

/// A drain (kill zone): particles inside its shape at the end of a step are removed and
/// reported in `World::removedEvents`.
struct DrainDef {
    /// The region (see `Shape`).
    Shape shape;
    /// Removes only particles of `material` when true; every material when false.
    bool onlyMaterial = false;
    /// The material removed when `onlyMaterial` is set.
    MaterialId material{};
};

/// A sensor: measures how much of each material lies inside its shape at the end of every step
/// (`World::sensorReading`). The basis of goals such as "fill the cup".
struct SensorDef {
    /// The region (see `Shape`).
    Shape shape;
};

/// How much of one material a sensor holds, measured at the end of the last step.
struct SensorReading {
    /// Particles inside (unit: count).
    uint32_t count = 0;
    /// Their mass (unit: kg).
    float mass = 0.0f;
    /// Their rest area: count * m / (rho0 * depth) (unit: m^2); compare with `area(shape)`.
    float area = 0.0f;
    /// Their rest volume in the slab: area * depth (unit: m^3; 1e-3 m^3 is one litre).
    float volume = 0.0f;
};

/// Why a particle left the world during a step.
enum class RemovalCause : uint8_t {
    /// It was inside a drain (`RemovedEvent::drain` says which).
    Drain,
    /// Its lifetime ran out.
    Lifetime,
    /// It left the world's position range (`World::positionLimit`).
    OutOfRange,
};

/// One particle removed by the world during the last step (not by `World::removeParticle`).
struct RemovedEvent {
    /// The particle's handle (stale by now: compare it with handles you kept).
    ParticleHandle particle;
    /// Where it was and how it moved when removed (unit: m, m/s).
    glm::vec2 position{0.0f, 0.0f};
    /// See `position`.
    glm::vec2 velocity{0.0f, 0.0f};
    /// Its material.
    MaterialId material{};
    /// Drain, lifetime or out of range.
    RemovalCause cause = RemovalCause::Drain;
    /// The drain, when `cause` is `RemovalCause::Drain`.
    DrainId drain{};
};

} // namespace fluid
