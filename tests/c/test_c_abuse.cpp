// The C API under abuse from plugins written against it: callbacks that call back into the world
// that runs them (refused with FLUID_ERROR_REFUSED, the world stepping once per frame), and a C
// boundary whose output is not finite (the same rule as a C++ plugin's).
#include "c_test_support.h"

#include <fluid/c.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

namespace {

using fluid::test::kFrame; // unit: s

// A 0.6 m tank of water with gravity.
fluid_world* tank() {
    fluid_world_def def = fluid_default_world_def();
    fluid_world* world = nullptr;
    C_OK(fluid_world_create(&def, &world));
    fluid::test::waterTank(world, {-0.3f, 0.0f}, {0.3f, 0.6f}, {-0.3f, 0.0f}, {0.3f, 0.15f});
    uint32_t spawned = 0;
    C_OK(fluid_world_particle_count(world, &spawned));
    REQUIRE(spawned > 100);
    return world;
}

// What a force plugin's prepare tries on the world that runs it, and what came back.
struct Caller {
    fluid_world* world = nullptr;
    int action = 0;
    std::vector<fluid_status> statuses;
    std::vector<std::string> messages;
};

void callBack(void* user, const fluid_step_context* /*context*/) {
    auto& c = *static_cast<Caller*>(user);
    fluid_status status = FLUID_OK;
    switch (c.action) {
    case 0:
        status = fluid_world_step(c.world, kFrame);
        break;
    case 1: {
        const fluid_param gravity[] = {{"gy", -1.0}};
        fluid_plugin_id id{};
        status = fluid_world_add_plugin(c.world, "force.gravity", gravity, 1, &id);
        break;
    }
    case 2:
        status = fluid_world_destroy(c.world);
        break;
    case 3: {
        fluid_material_def water{};
        fluid_material_preset("water", &water);
        fluid_material_id id{};
        status = fluid_world_add_material(c.world, &water, &id);
        break;
    }
    case 4: {
        fluid_material_id material{};
        fluid_particle_id handle{};
        status = fluid_world_add_particle(c.world, {0.0f, 0.5f}, {0.0f, 0.0f}, material, &handle);
        break;
    }
    default: {
        uint32_t count = 0; // a read: allowed
        status = fluid_world_particle_count(c.world, &count);
        break;
    }
    }
    c.statuses.push_back(status);
    c.messages.emplace_back(fluid_last_error());
}

void applyNothing(void*, const fluid_force_context*, uint32_t, uint32_t) {}

} // namespace

TEST_CASE("C: a plugin's callback that calls back into its world is refused",
          "[c][bad-input][reentry]") {
    const int action = GENERATE(0, 1, 2, 3, 4, 5);
    CAPTURE(action);
    fluid_world* world = tank();
    Caller caller;
    caller.world = world;
    caller.action = action;
    fluid_force_plugin_def def = fluid_default_force_plugin_def();
    def.type = "force.test-caller";
    def.user = &caller;
    def.prepare = callBack;
    def.apply = applyNothing;
    fluid_plugin_id id{};
    C_OK(fluid_world_add_force(world, &def, &id));
    uint32_t before = 0;
    C_OK(fluid_world_particle_count(world, &before));
    for (int frame = 0; frame < 120; ++frame) {
        C_OK(fluid_world_step(world, kFrame));
    }
    double time = 0.0;
    C_OK(fluid_world_time(world, &time));
    CHECK(time == Approx(2.0).margin(1e-6)); // 120 frames: no nested step added any
    uint32_t after = 0;
    C_OK(fluid_world_particle_count(world, &after));
    CHECK(after == before);
    REQUIRE(caller.statuses.size() == 120);
    const char* const names[] = {"World::step", "World::addForce", "fluid_world_destroy",
                                 "World::addMaterial", "World::addParticle"};
    for (size_t k = 0; k < caller.statuses.size(); ++k) {
        if (action == 5) {
            CHECK(caller.statuses[k] == FLUID_OK);
            continue;
        }
        CHECK(caller.statuses[k] == FLUID_ERROR_REFUSED);
        CHECK_THAT(caller.messages[k], Catch::StartsWith(names[action]) &&
                                           Catch::Contains("during the world's own step"));
    }
    if (action == 0) {
        CHECK(caller.messages[0] ==
              "World::step: called during the world's own step (from a plugin's hook or a "
              "task); a world is changed, saved or stepped only between its steps");
    }
    if (action == 2) {
        CHECK(caller.messages[0] ==
              "fluid_world_destroy: called during the world's own step (from a plugin's "
              "callback); a world is destroyed only between its steps");
    }
    CHECK(fluid_world_destroy(world) == FLUID_OK); // between steps: fine
    CHECK(fluid_world_destroy(nullptr) == FLUID_OK);
}

namespace {

// A C boundary that lays one sample at x = NaN, or whose project writes NaN into a particle.
struct Faulty {
    bool badSample = false;
    std::vector<float> px{0.0f, 0.01f, 0.02f}, py{0.3f, 0.3f, 0.3f}, v{0.0f, 0.0f, 0.0f};
};

void faultyPrepare(void* user, const fluid_step_context*, fluid_boundary_samples* samples) {
    auto& f = *static_cast<Faulty*>(user);
    if (f.badSample) {
        f.px[1] = std::numeric_limits<float>::quiet_NaN();
    }
    samples->px = f.px.data();
    samples->py = f.py.data();
    samples->vx = f.v.data();
    samples->vy = f.v.data();
    samples->count = 3;
}

void faultyProject(void* user, const fluid_project_context* ctx, uint32_t begin, uint32_t end) {
    const auto& f = *static_cast<const Faulty*>(user);
    for (uint32_t i = begin; i < end; ++i) {
        if (!f.badSample && i % 10 == 3) {
            ctx->px[i] = std::numeric_limits<float>::quiet_NaN(); // 0 / 0 in a normal
        }
    }
}

} // namespace

TEST_CASE("C: a C boundary's non-finite output follows the C++ plugins' rule",
          "[c][bad-input][plugins]") {
    fluid_world* world = tank();
    C_OK(fluid_world_step(world, kFrame));
    Faulty faulty;
    fluid_boundary_plugin_def def = fluid_default_boundary_plugin_def();
    def.type = "boundary.test-faulty";
    def.user = &faulty;
    def.prepare = faultyPrepare;
    def.project = faultyProject;
    fluid_plugin_id id{};
    C_OK(fluid_world_add_boundary(world, &def, &id));
    SECTION("a sample at NaN refuses the step, naming the plugin") {
        faulty.badSample = true;
        double before = 0.0;
        C_OK(fluid_world_time(world, &before));
        CHECK(fluid_world_step(world, kFrame) == FLUID_ERROR_REFUSED);
        CHECK(std::string(fluid_last_error()) ==
              "World::step: boundary plugin 1 ('boundary.test-faulty'): sample 1 at (nan, 0.3) "
              "with velocity (0, 0) is not finite; a boundary plugin's prepare must lay finite "
              "samples");
        double after = 0.0;
        C_OK(fluid_world_time(world, &after));
        CHECK(after == before);
    }
    SECTION("NaN written by project is undone for that particle") {
        for (int frame = 0; frame < 30; ++frame) {
            C_OK(fluid_world_step(world, kFrame));
            const float *x = nullptr, *y = nullptr, *vx = nullptr, *vy = nullptr;
            uint32_t n = 0;
            C_OK(fluid_world_positions(world, &x, &y, &n));
            C_OK(fluid_world_velocities(world, &vx, &vy, &n));
            for (uint32_t i = 0; i < n; ++i) {
                REQUIRE(std::isfinite(x[i]));
                REQUIRE(std::isfinite(y[i]));
                REQUIRE(std::isfinite(vx[i]));
                REQUIRE(std::isfinite(vy[i]));
                REQUIRE(x[i] >= -0.3f);
                REQUIRE(x[i] <= 0.3f);
                REQUIRE(y[i] >= 0.0f);
            }
        }
    }
    CHECK(fluid_world_destroy(world) == FLUID_OK);
}

TEST_CASE("C: fluid_level_add_body runs a level file's checks before Box2D sees the body",
          "[c][bad-input][bodies]") {
    std::string path = FLUID_LEVELS_DIR;
    path.append("/crates.json");
    fluid_level* level = nullptr;
    C_OK(fluid_level_load(path.c_str(), nullptr, &level));
    uint32_t count = 0;
    C_OK(fluid_level_body_count(level, &count));
    fluid_body_def crate = fluid_default_body_def();
    crate.shape.center = {0.9f, 0.5f};
    crate.shape.half_extents = {0.05f, 0.05f};
    crate.density = 50.0f;
    const auto refused = [&](const fluid_body_def& def, const std::string& message) {
        CHECK(fluid_level_add_body(level, &def, nullptr) == FLUID_ERROR_INVALID_ARGUMENT);
        CHECK(std::string(fluid_last_error()) == "fluid_level_add_body: " + message);
    };
    // These aborted the process in Box2D's asserts.
    fluid_body_def tiny = crate;
    tiny.shape.half_extents = {0.0001f, 0.0001f};
    refused(tiny, "a box's width is 0.0002 m; expected at least 0.005 m (Box2D's linear slop)");
    const fluid_vec2 sliver[] = {{0.0f, 0.0f}, {0.1f, 0.0f}, {0.05f, 1e-6f}};
    fluid_body_def sliverBody = crate;
    sliverBody.position = {0.9f, 0.5f};
    sliverBody.shape = fluid_polygon_shape(sliver, 3);
    refused(sliverBody, "the polygon's area is 5e-08 m^2; expected at least 2.5e-05 m^2 (Box2D's "
                        "linear slop squared)");
    // Under the mass floors: refused at the add, not at every later step.
    fluid_body_def dust = crate;
    dust.shape = fluid_circle_shape({0.9f, 0.5f}, 1e-5f);
    refused(dust, "a circle's radius is 1e-05 m; expected at least 0.005 m (Box2D's linear slop)");
    fluid_body_def feather = crate;
    feather.density = 1e-5f;
    refused(feather, "the fixtures weigh 1e-07 kg, less than the 1e-06 kg a dynamic body needs "
                     "(Box2D divides by its mass); raise their density or size");
    feather.density = 1.0f;
    CHECK(fluid_level_add_body(level, &feather, nullptr) == FLUID_ERROR_INVALID_ARGUMENT);
    CHECK_THAT(std::string(fluid_last_error()),
               Catch::Contains("a dynamic body needs at least 0.05 of it (kMinDensityRatio)"));
    // A pointed dynamic polygon thinner than a spacing (it spun up to Box2D's limits).
    const fluid_vec2 wedge[] = {{-0.05f, 0.0f}, {0.05f, 0.0f}, {0.0f, 0.005f}};
    fluid_body_def wedgeBody = crate;
    wedgeBody.position = {0.9f, 0.5f};
    wedgeBody.shape = fluid_polygon_shape(wedge, 3);
    CHECK(fluid_level_add_body(level, &wedgeBody, nullptr) == FLUID_ERROR_INVALID_ARGUMENT);
    CHECK_THAT(std::string(fluid_last_error()),
               Catch::Contains("must hold one of the fluid's spacing, 0.01 m"));
    wedgeBody.type = FLUID_BODY_STATIC; // a static wedge moves nothing
    wedgeBody.density = 0.0f;
    uint32_t wedgeIndex = 0;
    C_OK(fluid_level_add_body(level, &wedgeBody, &wedgeIndex));
    uint32_t after = 0;
    C_OK(fluid_level_body_count(level, &after));
    CHECK(after == count + 1); // nothing refused was added
    for (int frame = 0; frame < 3; ++frame) {
        C_OK(fluid_level_step(level)); // and the level steps on
    }
    // A body added can be removed again; so can the file's.
    uint32_t crateIndex = 0;
    C_OK(fluid_level_add_body(level, &crate, &crateIndex));
    CHECK(crateIndex == count + 1);
    C_OK(fluid_level_remove_body(level, wedgeIndex));
    C_OK(fluid_level_body_count(level, &after));
    CHECK(after == count + 1);
    fluid_vec2 position{};
    C_OK(fluid_level_body(level, count, nullptr, &position, nullptr)); // the crate moved down
    CHECK(position.x == Approx(0.9f));
    C_OK(fluid_level_remove_body(level, 0)); // the file's first body
    C_OK(fluid_level_body_count(level, &after));
    CHECK(after == count);
    CHECK(fluid_level_remove_body(level, after) == FLUID_ERROR_STALE_ID);
    for (int frame = 0; frame < 3; ++frame) {
        C_OK(fluid_level_step(level));
    }
    CHECK(fluid_level_destroy(level) == FLUID_OK);
}
