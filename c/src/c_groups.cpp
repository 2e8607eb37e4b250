// fluid::c — groups, per-particle user data and colours, positions between steps (fluid/c.h,
// fluid/groups.h).
#include "c_internal.h"

#include <fluid/groups.h>

#include <string>
#include <string_view>
#include <vector>

using namespace fluid;
using namespace fluid::c;

static_assert(sizeof(fluid_colour) == 4, "fluid_colour is four bytes, as Colour");

namespace {

GroupHandle toCpp(fluid_group_id id) {
    return {id.index, id.generation, id.world};
}
fluid_group_id toC(GroupHandle h) {
    return {h.index, h.generation, h.world};
}
Colour toCpp(fluid_colour c) {
    return {c.r, c.g, c.b, c.a};
}
fluid_colour toC(Colour c) {
    return {c.r, c.g, c.b, c.a};
}
GroupDef toCpp(const fluid_group_def* def) {
    return def == nullptr ? GroupDef{} : GroupDef{def->user_data, toCpp(def->colour)};
}

bool live(const World& w, fluid_group_id g) {
    return isValid(w, toCpp(g));
}

} // namespace

fluid_status fluid_world_create_group(fluid_world* world, const fluid_group_def* def,
                                      fluid_group_id* group) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        World& w = worldOf(world, "fluid_world_create_group");
        need(group, "fluid_world_create_group", "group");
        *group = toC(createGroup(w, toCpp(def)));
    });
}

fluid_status fluid_world_spawn_group(fluid_world* world, const fluid_blob_def* blob,
                                     fluid_group_id into, const fluid_group_def* def,
                                     fluid_group_id* group, uint32_t* spawned) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        const char* const function = "fluid_world_spawn_group";
        World& w = worldOf(world, function);
        need(blob, function, "blob");
        need(group, function, "group");
        BlobDef b;
        b.shape = fluid::c::toCpp(blob->shape, function);
        b.velocity = toVec(blob->velocity);
        b.material = fluid::c::toCpp(blob->material);
        b.lifetime = blob->lifetime;
        b.structure = blob->structure;
        b.group = toCpp(into);
        (void)w.material(b.material); // a stale material id first, as the C API's calls do
        const uint32_t before = w.particleCount();
        const GroupHandle made = spawnGroup(w, b, toCpp(def));
        *group = toC(made);
        if (spawned != nullptr) {
            *spawned = w.particleCount() - before;
        }
    });
}

fluid_status fluid_world_group_valid(const fluid_world* world, fluid_group_id group, bool* valid) {
    return readWorld(world, "fluid_world_group_valid", valid, "valid",
                     [&](const World& w) { return live(w, group); });
}

fluid_status fluid_world_particle_group(const fluid_world* world, fluid_particle_id particle,
                                        fluid_group_id* group) {
    return readWorld(world, "fluid_world_particle_group", group, "group",
                     [&](const World& w) { return toC(groupOf(w, fluid::c::toCpp(particle))); });
}

fluid_status fluid_world_set_particle_group(fluid_world* world, fluid_particle_id particle,
                                            fluid_group_id group) {
    return changeWorld(world, "fluid_world_set_particle_group",
                       [&](World& w) { setGroup(w, fluid::c::toCpp(particle), toCpp(group)); });
}

fluid_status fluid_world_emitter_group(const fluid_world* world, fluid_emitter_id emitter,
                                       fluid_group_id* group) {
    return readWorld(world, "fluid_world_emitter_group", group, "group", [&](const World& w) {
        return toC(emitterGroup(w, fluid::c::toCpp(emitter)));
    });
}

fluid_status fluid_world_set_emitter_group(fluid_world* world, fluid_emitter_id emitter,
                                           fluid_group_id group) {
    return changeWorld(world, "fluid_world_set_emitter_group", [&](World& w) {
        setEmitterGroup(w, fluid::c::toCpp(emitter), toCpp(group));
    });
}

fluid_status fluid_world_set_group_def(fluid_world* world, fluid_group_id group,
                                       const fluid_group_def* def) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        World& w = worldOf(world, "fluid_world_set_group_def");
        need(def, "fluid_world_set_group_def", "def");
        setGroupDef(w, toCpp(group), toCpp(def));
    });
}

fluid_status fluid_world_group_count(const fluid_world* world, fluid_group_id group,
                                     uint32_t* count) {
    return readWorld(world, "fluid_world_group_count", count, "count",
                     [&](const World& w) { return groupCount(w, toCpp(group)); });
}

fluid_status fluid_world_group_particles(const fluid_world* world, fluid_group_id group,
                                         fluid_particle_id* ids, uint32_t capacity,
                                         uint32_t* count) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        const char* const function = "fluid_world_group_particles";
        const World& w = worldOf(world, function);
        if (capacity > 0) {
            need(ids, function, "ids");
        }
        std::vector<ParticleHandle> handles(capacity);
        uint32_t n = 0;
        n = groupParticles(w, toCpp(group), handles);
        for (uint32_t k = 0; k < n && k < capacity; ++k) {
            ids[k] = fluid::c::toC(handles[k]);
        }
        if (count != nullptr) {
            *count = n;
        }
    });
}

fluid_status fluid_world_group_centre(const fluid_world* world, fluid_group_id group,
                                      fluid_vec2* centre) {
    return readWorld(world, "fluid_world_group_centre", centre, "centre",
                     [&](const World& w) { return fluid::c::toC(groupCentre(w, toCpp(group))); });
}

fluid_status fluid_world_group_velocity(const fluid_world* world, fluid_group_id group,
                                        fluid_vec2* velocity) {
    return readWorld(world, "fluid_world_group_velocity", velocity, "velocity",
                     [&](const World& w) { return fluid::c::toC(groupVelocity(w, toCpp(group))); });
}

fluid_status fluid_world_move_group(fluid_world* world, fluid_group_id group, fluid_vec2 offset) {
    return changeWorld(world, "fluid_world_move_group",
                       [&](World& w) { moveGroup(w, toCpp(group), toVec(offset)); });
}

fluid_status fluid_world_set_group_velocity(fluid_world* world, fluid_group_id group,
                                            fluid_vec2 velocity) {
    return changeWorld(world, "fluid_world_set_group_velocity",
                       [&](World& w) { setGroupVelocity(w, toCpp(group), toVec(velocity)); });
}

fluid_status fluid_world_destroy_group(fluid_world* world, fluid_group_id group,
                                       bool with_particles) {
    return changeWorld(world, "fluid_world_destroy_group",
                       [&](World& w) { destroyGroup(w, toCpp(group), with_particles); });
}

fluid_status fluid_world_merge_groups(fluid_world* world, fluid_group_id into,
                                      fluid_group_id from) {
    return changeWorld(world, "fluid_world_merge_groups",
                       [&](World& w) { mergeGroups(w, toCpp(into), toCpp(from)); });
}

fluid_status fluid_world_particle_user_data(const fluid_world* world, fluid_particle_id particle,
                                            uint32_t* value) {
    return readWorld(world, "fluid_world_particle_user_data", value, "value",
                     [&](const World& w) { return userData(w, fluid::c::toCpp(particle)); });
}

fluid_status fluid_world_set_particle_user_data(fluid_world* world, fluid_particle_id particle,
                                                uint32_t value) {
    return changeWorld(world, "fluid_world_set_particle_user_data",
                       [&](World& w) { setUserData(w, fluid::c::toCpp(particle), value); });
}

fluid_status fluid_world_set_group_user_data(fluid_world* world, fluid_group_id group,
                                             uint32_t value) {
    return changeWorld(world, "fluid_world_set_group_user_data",
                       [&](World& w) { setGroupUserData(w, toCpp(group), value); });
}

fluid_status fluid_world_user_data(const fluid_world* world, uint32_t* values, uint32_t capacity,
                                   uint32_t* count) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        const World& w = worldOf(world, "fluid_world_user_data");
        if (capacity > 0) {
            need(values, "fluid_world_user_data", "values");
        }
        const uint32_t n = fillUserData(w, std::span<uint32_t>(values, capacity));
        if (count != nullptr) {
            *count = n;
        }
    });
}

fluid_status fluid_world_particle_colour(const fluid_world* world, fluid_particle_id particle,
                                         fluid_colour* colour) {
    return readWorld(world, "fluid_world_particle_colour", colour, "colour", [&](const World& w) {
        return toC(fluid::colour(w, fluid::c::toCpp(particle)));
    });
}

fluid_status fluid_world_set_particle_colour(fluid_world* world, fluid_particle_id particle,
                                             fluid_colour colour) {
    return changeWorld(world, "fluid_world_set_particle_colour",
                       [&](World& w) { setColour(w, fluid::c::toCpp(particle), toCpp(colour)); });
}

fluid_status fluid_world_set_group_colour(fluid_world* world, fluid_group_id group,
                                          fluid_colour colour) {
    return changeWorld(world, "fluid_world_set_group_colour",
                       [&](World& w) { setGroupColour(w, toCpp(group), toCpp(colour)); });
}

fluid_status fluid_world_colours(const fluid_world* world, const fluid_colour** colours,
                                 uint32_t* count) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        const World& w = worldOf(world, "fluid_world_colours");
        need(colours, "fluid_world_colours", "colours");
        need(count, "fluid_world_colours", "count");
        const std::span<const uint32_t> packed = fluid::colours(w);
        // Colour::pack puts r in the low byte: on the little-endian machines fluid runs on the
        // packed words are r, g, b, a bytes, as fluid_colour.
        *colours = packed.empty() ? nullptr : reinterpret_cast<const fluid_colour*>(packed.data());
        *count = uint32_t(packed.size());
    });
}

fluid_status fluid_world_set_colour_mixing(fluid_world* world, float rate) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT,
                 [&] { setColourMixing(worldOf(world, "fluid_world_set_colour_mixing"), rate); });
}

fluid_status fluid_world_set_interpolation(fluid_world* world, bool on) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT,
                 [&] { setInterpolation(worldOf(world, "fluid_world_set_interpolation"), on); });
}

fluid_status fluid_world_set_interpolation_mode(fluid_world* world, uint32_t mode) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        World& w = worldOf(world, "fluid_world_set_interpolation_mode");
        if (mode > FLUID_INTERPOLATION_STEP) {
            throw Error("fluid_world_set_interpolation_mode: mode = " + std::to_string(mode) +
                            " is not a fluid_interpolation (FLUID_INTERPOLATION_OFF 0, "
                            "FLUID_INTERPOLATION_SUBSTEP 1, FLUID_INTERPOLATION_STEP 2)",
                        ErrorCode::OutOfRange);
        }
        setInterpolation(w, Interpolation(uint8_t(mode)));
    });
}

fluid_status fluid_world_interpolation_factor(const fluid_world* world, float* factor) {
    return readWorld(world, "fluid_world_interpolation_factor", factor, "factor",
                     [&](const World& w) { return interpolationFactor(w); });
}

fluid_status fluid_world_interpolated_positions(const fluid_world* world, float* x, float* y,
                                                uint32_t capacity, float factor, uint32_t* count) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        const char* const function = "fluid_world_interpolated_positions";
        const World& w = worldOf(world, function);
        if (capacity > 0) {
            need(x, function, "x");
            need(y, function, "y");
        }
        const uint32_t n = interpolatedPositions(w, std::span<float>(x, capacity),
                                                 std::span<float>(y, capacity), factor);
        if (count != nullptr) {
            *count = n;
        }
    });
}
