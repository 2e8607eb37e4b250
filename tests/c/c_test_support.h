// fluid tests — what the C API's tests share: a status check that fails with the message, a
// world that destroys itself, a tank of water made through C, and a plugin's view of a call
// made from inside the step.
#pragma once

#include "test_support.h"

#include <fluid/c.h>

#include <catch2/catch.hpp>

#include <string>

// Fails the test with the call's message unless it returned FLUID_OK.
#define C_OK(call)                                                                                 \
    do {                                                                                           \
        const fluid_status c_ok_status = (call);                                                   \
        INFO(#call << ": " << fluid_status_name(c_ok_status) << ": " << fluid_last_error());       \
        REQUIRE(c_ok_status == FLUID_OK);                                                          \
    } while (false)

namespace fluid::test {

/// A C world destroyed with the test's scope.
struct CWorld {
    fluid_world* world = nullptr;
    CWorld() = default;
    explicit CWorld(const fluid_world_def& def) { C_OK(fluid_world_create(&def, &world)); }
    ~CWorld() { fluid_world_destroy(world); }
    CWorld(const CWorld&) = delete;
    CWorld& operator=(const CWorld&) = delete;
};

/// Adds water (the preset), a boundary.box tank with inner corners `lo`, `hi` (unit: m),
/// gravity (0, -9.81) m/s^2 and a blob of water filling [blobLo, blobHi], in that order;
/// returns the water's id.
inline fluid_material_id waterTank(fluid_world* world, fluid_vec2 lo, fluid_vec2 hi,
                                   fluid_vec2 blobLo, fluid_vec2 blobHi) {
    fluid_material_def water{};
    C_OK(fluid_material_preset("water", &water));
    fluid_material_id id{};
    C_OK(fluid_world_add_material(world, &water, &id));
    const fluid_param box[] = {{"minX", lo.x}, {"minY", lo.y}, {"maxX", hi.x}, {"maxY", hi.y}};
    fluid_plugin_id plugin{};
    C_OK(fluid_world_add_plugin(world, "boundary.box", box, 4, &plugin));
    const fluid_param gravity[] = {{"gx", 0.0}, {"gy", -9.81}};
    C_OK(fluid_world_add_plugin(world, "force.gravity", gravity, 2, &plugin));
    fluid_blob_def blob = fluid_default_blob_def();
    blob.shape = fluid_box_shape(blobLo, blobHi);
    blob.material = id;
    C_OK(fluid_world_spawn_blob(world, &blob, nullptr));
    return id;
}

/// What a call made from inside a world's step (a plugin's prepare callback) returned; the
/// callback's user pointer.
struct CallFromStep {
    fluid_world* world = nullptr;
    fluid_status status = FLUID_OK;
    std::string message; // fluid_last_error() right after the call
};

/// A force plugin's apply that does nothing (for plugins that only watch the step).
inline void noForce(void*, const fluid_force_context*, uint32_t, uint32_t) {}

} // namespace fluid::test
