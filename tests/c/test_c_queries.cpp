// Region queries through the C API (fluid_world_query, _query_ids, _count_in): the C++
// queries' results, statuses for bad regions and for a query from inside the step.
#include "c_test_support.h"

#include <fluid/c.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace {

fluid_world* dam() {
    fluid_world_def def = fluid_default_world_def();
    fluid_world* world = nullptr;
    C_OK(fluid_world_create(&def, &world));
    fluid::test::waterTank(world, {0.0f, 0.0f}, {1.0f, 1.0f}, {0.0f, 0.0f}, {0.3f, 0.4f});
    for (int frame = 0; frame < 10; ++frame) {
        C_OK(fluid_world_step(world, 1.0f / 60.0f));
    }
    return world;
}

struct Visits {
    std::vector<fluid_query_hit> hits;
    uint32_t stopAfter = ~0u;
};

bool record(void* user, const fluid_query_hit* hit) {
    auto& v = *static_cast<Visits*>(user);
    v.hits.push_back(*hit);
    return v.hits.size() < v.stopAfter;
}

} // namespace

TEST_CASE("C: region queries find what a scan of the positions finds", "[c][queries]") {
    fluid_world* world = dam();
    const float *x = nullptr, *y = nullptr;
    uint32_t n = 0;
    C_OK(fluid_world_positions(world, &x, &y, &n));
    const fluid_shape circle = fluid_circle_shape({0.15f, 0.1f}, 0.08f);
    std::vector<uint32_t> expected;
    for (uint32_t i = 0; i < n; ++i) {
        if (std::hypot(x[i] - 0.15f, y[i] - 0.1f) <= 0.08f) {
            expected.push_back(i);
        }
    }
    REQUIRE(expected.size() > 50);
    Visits visits;
    uint32_t visited = 0;
    C_OK(fluid_world_query(world, &circle, record, &visits, &visited));
    REQUIRE(visited == expected.size());
    for (std::size_t k = 0; k < expected.size(); ++k) {
        CHECK(visits.hits[k].index == expected[k]);
        fluid_particle_id at{};
        C_OK(fluid_world_particle_at(world, expected[k], &at));
        CHECK(visits.hits[k].id.slot == at.slot);
        CHECK(visits.hits[k].id.generation == at.generation);
        CHECK(visits.hits[k].material.index == 0);
    }
    // Stopped after five.
    Visits five;
    five.stopAfter = 5;
    C_OK(fluid_world_query(world, &circle, record, &five, &visited));
    CHECK(visited == 5);
    // Into a buffer too short: the first ones, the whole count.
    std::vector<fluid_particle_id> ids(10);
    uint32_t found = 0;
    C_OK(fluid_world_query_ids(world, &circle, ids.data(), 10, &found));
    CHECK(found == expected.size());
    CHECK(ids[9].slot == visits.hits[9].id.slot);
    C_OK(fluid_world_query_ids(world, &circle, nullptr, 0, &found)); // just the count
    CHECK(found == expected.size());
    uint32_t perMaterial[2] = {7, 7}, total = 0;
    C_OK(fluid_world_count_in(world, &circle, perMaterial, 2, &total));
    CHECK(total == expected.size());
    CHECK(perMaterial[0] == expected.size());
    CHECK(perMaterial[1] == 0);
    // Bad regions and arguments.
    const fluid_shape bad =
        fluid_circle_shape({std::numeric_limits<float>::quiet_NaN(), 0.0f}, 0.1f);
    CHECK(fluid_world_query(world, &bad, record, &visits, nullptr) == FLUID_ERROR_INVALID_ARGUMENT);
    CHECK_THAT(std::string(fluid_last_error()), Catch::StartsWith("queryParticles: "));
    CHECK(fluid_world_query(world, nullptr, record, &visits, nullptr) == FLUID_ERROR_NULL_ARGUMENT);
    CHECK(std::string(fluid_last_error()) == "fluid_world_query: region is NULL");
    CHECK(fluid_world_query_ids(world, &circle, nullptr, 3, &found) == FLUID_ERROR_NULL_ARGUMENT);
    CHECK(fluid_world_destroy(world) == FLUID_OK);
}

namespace {

void queryFromPrepare(void* user, const fluid_step_context*) {
    auto& in = *static_cast<fluid::test::CallFromStep*>(user);
    const fluid_shape circle = fluid_circle_shape({0.15f, 0.1f}, 0.08f);
    uint32_t total = 0;
    in.status = fluid_world_count_in(in.world, &circle, nullptr, 0, &total);
    in.message = fluid_last_error();
}

} // namespace

TEST_CASE("C: a query from inside the world's step is refused", "[c][queries]") {
    fluid_world* world = dam();
    fluid::test::CallFromStep inside;
    inside.world = world;
    fluid_force_plugin_def def = fluid_default_force_plugin_def();
    def.type = "force.test-query";
    def.user = &inside;
    def.prepare = queryFromPrepare;
    def.apply = fluid::test::noForce;
    fluid_plugin_id id{};
    C_OK(fluid_world_add_force(world, &def, &id));
    C_OK(fluid_world_step(world, 1.0f / 60.0f));
    CHECK(inside.status == FLUID_ERROR_REFUSED);
    CHECK(inside.message == "countParticles: called during the world's own step (from a plugin's "
                            "hook or a task); query the world between its steps");
    CHECK(fluid_world_destroy(world) == FLUID_OK);
}
