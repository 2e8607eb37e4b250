// fluid::c — region queries (fluid/c.h, fluid/query.h).
#include "c_internal.h"

#include <fluid/query.h>

#include <vector>

using namespace fluid;
using namespace fluid::c;

namespace {

// The region of a query, or Failure(NULL_ARGUMENT).
Shape regionOf(const fluid_shape* region, const char* function) {
    need(region, function, "region");
    return toCpp(*region, function);
}

} // namespace

fluid_status fluid_world_query(const fluid_world* world, const fluid_shape* region,
                               fluid_query_visitor visit, void* user, uint32_t* visited) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        const char* const function = "fluid_world_query";
        const World& w = worldOf(world, function);
        need(reinterpret_cast<const void*>(visit), function, "visit");
        const Shape shape = regionOf(region, function);
        const uint32_t n = queryParticles(w, shape, [&](const QueryHit& hit) {
            const fluid_query_hit c{toC(hit.handle), hit.index, toC(hit.material)};
            return visit(user, &c);
        });
        if (visited != nullptr) {
            *visited = n;
        }
    });
}

fluid_status fluid_world_query_ids(const fluid_world* world, const fluid_shape* region,
                                   fluid_particle_id* ids, uint32_t capacity, uint32_t* found) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        const char* const function = "fluid_world_query_ids";
        const World& w = worldOf(world, function);
        if (capacity > 0) {
            need(ids, function, "ids");
        }
        std::vector<ParticleHandle> handles(capacity);
        const uint32_t n = queryParticles(w, regionOf(region, function), handles);
        for (uint32_t k = 0; k < n && k < capacity; ++k) {
            ids[k] = toC(handles[k]);
        }
        if (found != nullptr) {
            *found = n;
        }
    });
}

fluid_status fluid_world_count_in(const fluid_world* world, const fluid_shape* region,
                                  uint32_t* per_material, uint32_t material_count,
                                  uint32_t* total) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        const char* const function = "fluid_world_count_in";
        const World& w = worldOf(world, function);
        if (material_count > 0) {
            need(per_material, function, "per_material");
        }
        const uint32_t n = countParticles(w, regionOf(region, function),
                                          std::span<uint32_t>(per_material, material_count));
        if (total != nullptr) {
            *total = n;
        }
    });
}
