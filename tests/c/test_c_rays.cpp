// Ray casts and the liquid at a point through the C API (fluid_world_ray_cast,
// _ray_cast_particles, _sample): a tank's surface and pressure, the particle cast against a scan
// of the positions and steered by its visitor, statuses and messages for bad input and for a
// cast from inside the step.
#include "c_test_support.h"

#include <fluid/c.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

using fluid::test::CWorld;

namespace {

// 0.3 m of water, 0.4 m deep, settled for a second; returns the water's id.
fluid_material_id settledTank(CWorld& w) {
    const fluid_material_id id =
        fluid::test::waterTank(w.world, {0.0f, 0.0f}, {0.3f, 1.0f}, {0.0f, 0.0f}, {0.3f, 0.4f});
    for (int frame = 0; frame < 60; ++frame) {
        C_OK(fluid_world_step(w.world, 1.0f / 60.0f));
    }
    return id;
}

struct Seen {
    std::vector<fluid_ray_particle_hit> hits;
    float answer = 1.0f;
};

float recordHit(void* user, const fluid_ray_particle_hit* hit) {
    auto& seen = *static_cast<Seen*>(user);
    seen.hits.push_back(*hit);
    return seen.answer;
}

} // namespace

TEST_CASE("C: a ray cast down reads a tank's surface, sample reads its pressure and depth",
          "[c][rays]") {
    CWorld w(fluid_default_world_def());
    const fluid_material_id id = settledTank(w);
    const float *x = nullptr, *y = nullptr;
    uint32_t n = 0;
    C_OK(fluid_world_positions(w.world, &x, &y, &n));
    const float top = *std::max_element(y, y + n);
    fluid_material_def water{};
    C_OK(fluid_material_preset("water", &water));
    float spacing = 0.0f;
    C_OK(fluid_world_spacing(w.world, id, &spacing));

    fluid_ray_hit hit{};
    C_OK(fluid_world_ray_cast(w.world, {0.15f, 0.9f}, {0.15f, 0.0f}, nullptr, &hit));
    REQUIRE(hit.hit);
    CHECK_FALSE(hit.starts_inside);
    CHECK(std::fabs(hit.point.y - (top + 0.5f * spacing)) <= 0.5f * spacing);
    CHECK(hit.normal.y > 0.95f);
    CHECK(hit.fraction == Approx((0.9f - hit.point.y) / 0.9f).margin(1e-5f));
    CHECK(hit.material.index == 0);
    CHECK(hit.index < n);
    bool valid = false;
    C_OK(fluid_world_particle_valid(w.world, hit.particle, &valid));
    CHECK(valid);
    // From inside: starts inside, fraction 0. A fatter field reaches higher.
    fluid_ray_hit inside{};
    C_OK(fluid_world_ray_cast(w.world, {0.15f, 0.1f}, {0.15f, 0.9f}, nullptr, &inside));
    CHECK((inside.hit && inside.starts_inside && inside.fraction == 0.0f));
    fluid_surface_field fat = fluid_default_surface_field();
    CHECK(fat.field_radius == 2.0f);
    CHECK(fat.threshold == 0.6f);
    fat.threshold = 0.3f;
    fluid_ray_hit higher{};
    C_OK(fluid_world_ray_cast(w.world, {0.15f, 0.9f}, {0.15f, 0.0f}, &fat, &higher));
    CHECK(higher.point.y > hit.point.y);

    // Half way down: hydrostatic pressure (within 25%: the position-based solver's own
    // pressure, docs/queries.md), the depth within half a spacing, all water.
    const float surface = hit.point.y;
    fluid_liquid_sample s{};
    float shares[2] = {7.0f, 7.0f};
    C_OK(fluid_world_sample(w.world, {0.15f, 0.5f * surface}, nullptr, shares, 2, &s));
    CHECK(s.in_liquid);
    CHECK(s.field > 0.6f);
    CHECK(s.depth == Approx(0.5f * surface).margin(0.5f * spacing));
    CHECK(s.pressure == Approx(water.rest_density * 9.81f * 0.5f * surface).epsilon(0.25));
    CHECK(s.density_ratio == Approx(1.0f).margin(0.05f));
    CHECK(s.neighbours > 20);
    CHECK(shares[0] == Approx(1.0f));
    CHECK(shares[1] == 0.0f);
    CHECK(s.material.index == 0);
    C_OK(fluid_world_sample(w.world, {0.15f, 0.9f}, nullptr, nullptr, 0, &s));
    CHECK_FALSE(s.in_liquid);
    CHECK(s.depth == 0.0f);
    CHECK(s.neighbours == 0);
}

TEST_CASE("C: a particle cast reports what a scan finds, in order, as its visitor steers",
          "[c][rays]") {
    CWorld w(fluid_default_world_def());
    settledTank(w);
    const float *x = nullptr, *y = nullptr;
    uint32_t n = 0;
    C_OK(fluid_world_positions(w.world, &x, &y, &n));
    const fluid_vec2 p1{-0.1f, 0.05f}, p2{0.4f, 0.3f};
    const float radius = 0.01f;
    // The scan: the circles the segment meets, by entry fraction then index.
    const double dx = p2.x - p1.x, dy = p2.y - p1.y, length = std::hypot(dx, dy);
    std::vector<std::pair<double, uint32_t>> expected;
    for (uint32_t i = 0; i < n; ++i) {
        const double qx = x[i] - p1.x, qy = y[i] - p1.y;
        const double tc = (qx * dx + qy * dy) / length;
        const double across2 = qx * qx + qy * qy - tc * tc;
        if (across2 <= double(radius) * radius) {
            const double t = tc - std::sqrt(double(radius) * radius - across2);
            if (t >= 0.0 && t <= length) {
                expected.push_back({t / length, i});
            }
        }
    }
    std::sort(expected.begin(), expected.end());
    REQUIRE(expected.size() > 10);
    Seen all;
    uint32_t visited = 0;
    C_OK(fluid_world_ray_cast_particles(w.world, p1, p2, radius, recordHit, &all, &visited));
    REQUIRE(visited == expected.size());
    REQUIRE(all.hits.size() == expected.size());
    for (std::size_t k = 0; k < expected.size(); ++k) {
        CHECK(all.hits[k].index == expected[k].second);
        CHECK(all.hits[k].fraction == Approx(expected[k].first).margin(1e-6));
        fluid_particle_id at{};
        C_OK(fluid_world_particle_at(w.world, expected[k].second, &at));
        CHECK(all.hits[k].id.slot == at.slot);
    }
    // 0 stops; the hit's own fraction clips to the closest.
    Seen stop;
    stop.answer = 0.0f;
    C_OK(fluid_world_ray_cast_particles(w.world, p1, p2, radius, recordHit, &stop, &visited));
    CHECK(visited == 1);
    Seen half;
    half.answer = 0.5f;
    C_OK(fluid_world_ray_cast_particles(w.world, p1, p2, radius, recordHit, &half, &visited));
    const auto upToHalf = std::count_if(expected.begin(), expected.end(),
                                        [](const auto& e) { return float(e.first) <= 0.5f; });
    CHECK(visited == uint32_t(upToHalf));
}

namespace {

void castFromPrepare(void* user, const fluid_step_context*) {
    auto& in = *static_cast<fluid::test::CallFromStep*>(user);
    fluid_ray_hit hit{};
    in.status = fluid_world_ray_cast(in.world, {0.1f, 0.9f}, {0.1f, 0.0f}, nullptr, &hit);
    in.message = fluid_last_error();
}

float nanVisitor(void*, const fluid_ray_particle_hit*) {
    return std::numeric_limits<float>::quiet_NaN();
}

} // namespace

TEST_CASE("C: bad rays, points, fields and visitors, and casts from inside the step", "[c][rays]") {
    CWorld w(fluid_default_world_def());
    settledTank(w);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    fluid_ray_hit hit{};
    CHECK(fluid_world_ray_cast(w.world, {nan, 0.0f}, {1.0f, 1.0f}, nullptr, &hit) ==
          FLUID_ERROR_INVALID_ARGUMENT);
    CHECK(std::string(fluid_last_error()) ==
          "fluid_world_ray_cast: p1 = (nan, 0) is not finite (unit: m)");
    CHECK(fluid_world_ray_cast(w.world, {0.0f, 0.0f}, {1.0f, INFINITY}, nullptr, &hit) ==
          FLUID_ERROR_INVALID_ARGUMENT);
    CHECK(std::string(fluid_last_error()) ==
          "fluid_world_ray_cast: p2 = (1, inf) is not finite (unit: m)");
    fluid_surface_field field = fluid_default_surface_field();
    field.field_radius = 0.5f;
    CHECK(fluid_world_ray_cast(w.world, {0.0f, 0.0f}, {1.0f, 1.0f}, &field, &hit) ==
          FLUID_ERROR_INVALID_ARGUMENT);
    CHECK(std::string(fluid_last_error()) ==
          "fluid_world_ray_cast: field->field_radius = 0.5 is out of range [1, 4] (unit: 1)");
    CHECK(fluid_world_ray_cast(w.world, {0.0f, 0.0f}, {1.0f, 1.0f}, nullptr, nullptr) ==
          FLUID_ERROR_NULL_ARGUMENT);
    CHECK(std::string(fluid_last_error()) == "fluid_world_ray_cast: hit is NULL");
    CHECK(fluid_world_ray_cast(nullptr, {0.0f, 0.0f}, {1.0f, 1.0f}, nullptr, &hit) ==
          FLUID_ERROR_NULL_ARGUMENT);
    fluid_liquid_sample s{};
    field = fluid_default_surface_field();
    field.threshold = -1.0f;
    CHECK(fluid_world_sample(w.world, {0.1f, 0.1f}, &field, nullptr, 0, &s) ==
          FLUID_ERROR_INVALID_ARGUMENT);
    CHECK(std::string(fluid_last_error()) ==
          "fluid_world_sample: field->threshold = -1 is out of range [0.05, 4] (unit: 1)");
    CHECK(fluid_world_sample(w.world, {0.1f, -INFINITY}, nullptr, nullptr, 0, &s) ==
          FLUID_ERROR_INVALID_ARGUMENT);
    CHECK(std::string(fluid_last_error()) ==
          "fluid_world_sample: point = (0.1, -inf) is not finite (unit: m)");
    CHECK(fluid_world_sample(w.world, {0.1f, 0.1f}, nullptr, nullptr, 2, &s) ==
          FLUID_ERROR_NULL_ARGUMENT);
    CHECK(std::string(fluid_last_error()) == "fluid_world_sample: material_fractions is NULL");
    uint32_t visited = 0;
    CHECK(fluid_world_ray_cast_particles(w.world, {0.0f, 0.0f}, {1.0f, 1.0f}, -0.01f, nanVisitor,
                                         nullptr, &visited) == FLUID_ERROR_INVALID_ARGUMENT);
    CHECK(std::string(fluid_last_error()) ==
          "fluid_world_ray_cast_particles: radius = -0.01 is out of range (0, inf) (unit: m)");
    CHECK(fluid_world_ray_cast_particles(w.world, {-0.1f, 0.1f}, {0.4f, 0.1f}, 0.01f, nanVisitor,
                                         nullptr, &visited) == FLUID_ERROR_INVALID_ARGUMENT);
    CHECK(std::string(fluid_last_error()) ==
          "fluid_world_ray_cast_particles: the visitor returned nan; expected -1 (ignore the "
          "particle), 0 (stop), a fraction in (0, 1) (clip the ray) or 1 (go on)");
    CHECK(fluid_world_ray_cast_particles(w.world, {0.0f, 0.0f}, {1.0f, 1.0f}, 0.01f, nullptr,
                                         nullptr, &visited) == FLUID_ERROR_NULL_ARGUMENT);
    CHECK(std::string(fluid_last_error()) == "fluid_world_ray_cast_particles: visit is NULL");
    // From a plugin's prepare callback: refused.
    fluid::test::CallFromStep inside;
    inside.world = w.world;
    fluid_force_plugin_def def = fluid_default_force_plugin_def();
    def.type = "force.test-ray";
    def.user = &inside;
    def.prepare = castFromPrepare;
    def.apply = fluid::test::noForce;
    fluid_plugin_id id{};
    C_OK(fluid_world_add_force(w.world, &def, &id));
    C_OK(fluid_world_step(w.world, 1.0f / 60.0f));
    CHECK(inside.status == FLUID_ERROR_REFUSED);
    CHECK(inside.message == "rayCast: called during the world's own step (from a plugin's hook "
                            "or a task); query the world between its steps");
}
