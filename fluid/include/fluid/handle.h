// fluid — 2D SPH liquid for games.
#pragma once

#include <cstdint>

namespace fluid {

/// A particle's stable name. Slots in the particle arrays move every sub-step (they are sorted
/// by grid cell); a handle keeps naming the same particle until it is removed, after which it is
/// stale: `World::isValid` says false and calls that need the particle throw `fluid::Error`.
/// The all-zero handle is null. Thread rule: a plain value, copy it anywhere.
struct ParticleHandle {
    /// Slot in the world's handle table (unit: index; 0 .. maxParticles-1).
    uint32_t slot = 0;
    /// Generation of the slot when the handle was made (unit: count; 0 means null).
    uint32_t generation = 0;
    /// Tag of the `World` object that made the handle (unit: id; 0 in the null handle): 1 for
    /// the process's first world, counting up and never reused, so a program making its worlds
    /// in the same order gets the same tags in every run, and a handle kept from a destroyed
    /// world (a restarted level) names nothing in a later one. Another world refuses the handle
    /// (`World::isValid` is false, other calls throw naming it). Not saved in snapshots: a
    /// loaded world has its own tag, and `World::adopt` carries a handle over to it.
    uint32_t world = 0;

    /// True for the null handle.
    constexpr bool isNull() const { return generation == 0; }
    /// Handles are equal when slot, generation and world are.
    friend constexpr bool operator==(ParticleHandle, ParticleHandle) = default;
};

/// A material of a world (from `World::addMaterial`). Materials, emitters, drains and sensors
/// are added, never removed: an id stays valid for the life of the world that made it. An id
/// carries that world's tag, and another world refuses it with `fluid::Error` naming both (a
/// world loaded from a snapshot is another world: `World::adopt` carries an id over to it). An
/// id made by hand from an index (`MaterialId{2}`, tag 0) is taken by any world as that index.
/// Thread rule: a plain value.
struct MaterialId {
    /// Index into the world's material table (unit: index, 0 .. materialCount()-1).
    uint16_t index = 0;
    /// Tag of the `World` that made the id (as `ParticleHandle::world`; 0 in an id made by hand).
    uint32_t world = 0;
    /// Ids are equal when their indices are (the tag says which world made one, not what it
    /// names).
    friend constexpr bool operator==(MaterialId a, MaterialId b) { return a.index == b.index; }
};

// ---- Groups (groups.h) ----

/// A group of particles: a blob, an emitter's output, or one the game made (`createGroup`).
/// Groups are destroyed (`destroyGroup`) or merged away (`mergeGroups`), after which the handle
/// is stale: calls that take it throw `fluid::Error` naming it. The all-zero handle is null.
/// Thread rule: a plain value, copy it anywhere.
struct GroupHandle {
    /// Index in the world's group table (unit: index).
    uint32_t index = 0;
    /// Generation of the entry when the handle was made (unit: count; 0 means null).
    uint32_t generation = 0;
    /// Tag of the `World` that made it (as `ParticleHandle::world`; 0 in the null handle).
    uint32_t world = 0;
    /// True for the null handle.
    constexpr bool isNull() const { return generation == 0; }
    /// Handles are equal when index, generation and world are.
    friend constexpr bool operator==(GroupHandle, GroupHandle) = default;
};

} // namespace fluid
