// fluid::c internals: the wrapped objects, the conversions and the exception guard the C API's
// source files share. Nothing here has logic of its own beyond turning C into C++ and back.
#pragma once
#include <fluid/c.h>

#include "c_status.h"

#include <fluid/error.h>
#include <fluid/fluid.h>
#include <fluid/level.h>

#include <exception>
#include <memory>
#include <new>
#include <string>
#include <string_view>
#include <vector>

namespace fluid::c {

/// A failure the C layer itself names (a NULL argument, an unknown preset), or a C++ error
/// given the status that fits it.
struct Failure {
    fluid_status status;
    std::string message;
};

/// Records `message` as this thread's last error and returns `status`.
fluid_status fail(fluid_status status, std::string_view message);

/// Runs `body`, turning every exception into a status and this thread's message: Failure as it
/// says; fluid::Error (fluid::LevelError among them) as its code says (`statusOf`), with its
/// message; std::bad_alloc as out of memory; anything else as `status` with its message.
template <class Body> fluid_status guard(fluid_status status, Body&& body) noexcept;

/// Throws Failure(FLUID_ERROR_NULL_ARGUMENT) naming `what` in `function` when `pointer` is NULL.
inline void need(const void* pointer, const char* function, const char* what) {
    if (pointer == nullptr) {
        throw Failure{FLUID_ERROR_NULL_ARGUMENT,
                      std::string(function) + ": " + what + " is NULL"};
    }
}

} // namespace fluid::c

/// The C API's world: the C++ world (its own, or a level's) and the arrays the C API hands out
/// that the C++ world keeps in other shapes.
struct fluid_world {
    /// The world itself.
    fluid::World* world = nullptr;
    /// Set when this handle owns it (fluid_world_create, fluid_world_load).
    std::unique_ptr<fluid::World> owned;
    /// fluid_world_removed_events' copy, refreshed on each call.
    mutable std::vector<fluid_removed_event> removed;
    /// fluid_world_sensor_readings' copies, one per sensor, refreshed on each call.
    mutable std::vector<std::vector<fluid_sensor_reading>> readings;
    /// fluid_world_get_material's copies of the names, one per material, each on the heap so
    /// that adding materials never moves one: replaced only when the material's name changed.
    mutable std::vector<std::unique_ptr<std::string>> materialNames;
};

namespace fluid::c {

/// The C++ world of a C handle, or Failure(FLUID_ERROR_NULL_ARGUMENT).
inline World& worldOf(fluid_world* world, const char* function) {
    need(world, function, "world");
    return *world->world;
}
inline const World& worldOf(const fluid_world* world, const char* function) {
    need(world, function, "world");
    return *world->world;
}

/// Throws Failure(FLUID_ERROR_REFUSED) when `world` is inside its own step (a C plugin's
/// callback destroying the world that runs it).
inline void refuseWhileStepping(const World& world, const char* function) {
    if (world.stepping()) {
        throw Failure{FLUID_ERROR_REFUSED,
                      std::string(function) +
                          ": called during the world's own step (from a plugin's callback); a "
                          "world is destroyed only between its steps"};
    }
}

/// Runs a step: a fluid::Error from inside it is the world refusing the step (a plugin that
/// threw, a boundary that lays bad samples, a host that must step the world), whatever its
/// code: Failure(FLUID_ERROR_REFUSED) with its message. Memory that ran out stays
/// FLUID_ERROR_OUT_OF_MEMORY (`guard`).
template <class Body> void refusedStep(Body&& body) {
    try {
        body();
    } catch (const Error& e) {
        if (e.code() == ErrorCode::OutOfMemory) {
            throw;
        }
        throw Failure{FLUID_ERROR_REFUSED, e.what()};
    }
}

/// Conversions between the C structs and the C++ ones.
inline glm::vec2 toVec(fluid_vec2 v) { return {v.x, v.y}; }
inline fluid_vec2 toC(glm::vec2 v) { return {v.x, v.y}; }
MaterialId toCpp(fluid_material_id id);
inline fluid_material_id toC(MaterialId id) { return {id.index, id.world}; }
inline ParticleHandle toCpp(fluid_particle_id id) { return {id.slot, id.generation, id.world}; }
inline fluid_particle_id toC(ParticleHandle h) { return {h.slot, h.generation, h.world}; }
inline EmitterId toCpp(fluid_emitter_id id) { return {id.index, id.world}; }
inline DrainId toCpp(fluid_drain_id id) { return {id.index, id.world}; }
inline SensorId toCpp(fluid_sensor_id id) { return {id.index, id.world}; }
Shape toCpp(const fluid_shape& shape, const char* function);

/// `text` in bytes the library allocated (malloc: fluid_bytes_free frees them); throws
/// std::bad_alloc when memory runs out.
fluid_bytes toBytes(const std::string& text);

/// The plugin types: the built-ins and those registered in C, a copy made under the
/// registrations' lock (any thread).
Registry registry();

/// A plugin of `world` by C id: checks the kind, index and world tag (FLUID_ERROR_STALE_ID).
Plugin& pluginOf(World& world, fluid_plugin_id id, const char* function);

/// The world's tag, as its ids carry it.
inline uint32_t tagOf(const World& world) { return world.adopt(MaterialId{}).world; }

template <class Body> fluid_status guard(fluid_status status, Body&& body) noexcept {
    try {
        body();
        return FLUID_OK;
    } catch (const Failure& f) {
        return fail(f.status, f.message);
    } catch (const Error& e) {
        return fail(statusOf(e.code()), e.what());
    } catch (const std::bad_alloc&) {
        return fail(FLUID_ERROR_OUT_OF_MEMORY, "out of memory");
    } catch (const std::exception& e) {
        return fail(status, e.what());
    } catch (...) {
        return fail(status, "an unknown exception");
    }
}

/// A call that reads one value of a world: checks `world` and `out` (NULL:
/// FLUID_ERROR_NULL_ARGUMENT naming `what` in `function`), then writes `read(world)` to `*out`;
/// failures as `guard` turns them into statuses (FLUID_ERROR_INVALID_ARGUMENT for the rest).
template <class Out, class Read>
fluid_status readWorld(const fluid_world* world, const char* function, Out* out, const char* what,
                       Read&& read) noexcept {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        const World& w = worldOf(world, function);
        need(out, function, what);
        *out = read(w);
    });
}

/// A call that changes a world: checks `world`, then runs `change(world)`; failures as `guard`
/// turns them into statuses (FLUID_ERROR_INVALID_ARGUMENT for the rest).
template <class Change>
fluid_status changeWorld(fluid_world* world, const char* function, Change&& change) noexcept {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] { change(worldOf(world, function)); });
}

} // namespace fluid::c
