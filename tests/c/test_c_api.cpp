// The C API (fluid/c.h) against the C++ API it wraps: the same bits for the same scene, plugins
// written in C (tests/c/c_plugins.c, compiled as C99) that act and float a body, snapshots and
// levels through C, every error path with its status and the C++ API's own message, and a
// short fuzz of the entry points.
#include "c_plugins.h"
#include "c_test_support.h"

#include <fluid/c.h>
#include <fluid/fluid.h>
#include <fluid/box2d/coupling.h>
#include <fluid/level.h>

#include <box2d/box2d.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

using namespace fluid;
using fluid::test::CWorld;

namespace {

using fluid::test::kFrame; // unit: s

// The C++ API's message for `body`, which must throw fluid::Error.
template <class Body> std::string cppMessage(Body&& body) {
    try {
        body();
    } catch (const Error& e) {
        return e.what();
    }
    FAIL("the C++ call did not throw");
    return {};
}

// The dam: a 1 x 2 m tank, gravity, a block of water 0.4 x 0.6 m in its left corner.
void cppDam(World& world) {
    const MaterialId water = world.addMaterial(fluid::water());
    world.addBoundary(std::make_unique<BoxContainer>(0.0f, 0.0f, 1.0f, 2.0f));
    world.addForce(std::make_unique<GravityForce>(0.0f, -9.81f));
    BlobDef blob;
    blob.shape = Shape::box({0.0f, 0.0f}, {0.4f, 0.6f});
    blob.material = water;
    world.spawnBlob(blob);
}

fluid_material_id cDam(fluid_world* world) {
    const fluid_material_id id =
        fluid::test::waterTank(world, {0.0f, 0.0f}, {1.0f, 2.0f}, {0.0f, 0.0f}, {0.4f, 0.6f});
    uint32_t spawned = 0;
    C_OK(fluid_world_particle_count(world, &spawned));
    REQUIRE(spawned > 1000);
    return id;
}

// Every particle's position and velocity, in slot order, as the C API hands them out.
std::vector<float> cState(const fluid_world* world) {
    const float *x = nullptr, *y = nullptr, *vx = nullptr, *vy = nullptr;
    uint32_t n = 0, m = 0;
    C_OK(fluid_world_positions(world, &x, &y, &n));
    C_OK(fluid_world_velocities(world, &vx, &vy, &m));
    REQUIRE(n == m);
    std::vector<float> state;
    for (const float* a : {x, y, vx, vy}) {
        state.insert(state.end(), a, a + n);
    }
    return state;
}

std::vector<float> cppState(const World& world) {
    std::vector<float> state;
    for (const auto& a : {world.positionX(), world.positionY(), world.velocityX(),
                          world.velocityY()}) {
        state.insert(state.end(), a.begin(), a.end());
    }
    return state;
}

bool sameBits(const std::vector<float>& a, const std::vector<float>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

} // namespace

TEST_CASE("C API: the version in the header is the library's", "[c]") {
    CHECK(fluid_version() == FLUID_C_VERSION);
    CHECK(FLUID_C_VERSION == FLUID_C_VERSION_MAJOR * 100 + FLUID_C_VERSION_MINOR);
    CHECK(std::string(fluid_status_name(FLUID_ERROR_STALE_ID)) == "FLUID_ERROR_STALE_ID");
    CHECK(std::string(c_test_status_name(99)) == "unknown status");
}

TEST_CASE("C API: the dam stepped through C and through C++ gives the same bits, on 1 and 2 "
          "workers",
          "[c]") {
    std::vector<float> first;
    for (const uint32_t workers : {1u, 2u}) {
        CAPTURE(workers);
        WorldDef def;
        def.positionBased = positionBasedPreset(Quality::Game);
        def.workerCount = workers;
        World cpp(def);
        cppDam(cpp);

        fluid_world_def cdef = fluid_default_world_def();
        C_OK(fluid_world_def_set_quality(&cdef, "game"));
        cdef.worker_count = workers;
        CWorld c(cdef);
        cDam(c.world);
        for (int f = 0; f < 90; ++f) {
            cpp.step(kFrame);
            C_OK(fluid_world_step(c.world, kFrame));
        }
        double time = 0.0;
        C_OK(fluid_world_time(c.world, &time));
        CHECK(time == cpp.time());
        const std::vector<float> state = cState(c.world);
        CHECK(sameBits(state, cppState(cpp)));
        if (first.empty()) {
            first = state;
        } else {
            CHECK(sameBits(state, first)); // and the same on 1 and 2 workers
        }
    }
}

TEST_CASE("C API: an emitter, a drain, a sensor and the removal events as through C++", "[c]") {
    // C++: a tank, gravity, a nozzle pouring down into a drain in the right corner, a sensor
    // over the left half.
    World cpp(WorldDef{});
    const MaterialId water = cpp.addMaterial(fluid::water());
    cpp.addBoundary(std::make_unique<BoxContainer>(0.0f, 0.0f, 1.0f, 1.0f));
    cpp.addForce(std::make_unique<GravityForce>(0.0f, -9.81f));
    EmitterDef nozzle;
    nozzle.position = {0.7f, 0.6f};
    nozzle.direction = {0.0f, -1.0f};
    nozzle.rate = 400.0f;
    nozzle.material = water;
    nozzle.lifetime = 1.5f;
    const EmitterId emitter = cpp.addEmitter(nozzle);
    DrainDef drain;
    drain.shape = Shape::box({0.8f, 0.0f}, {1.0f, 0.3f});
    const DrainId cppDrain = cpp.addDrain(drain);
    SensorDef sensor;
    sensor.shape = Shape::box({0.0f, 0.0f}, {0.75f, 0.5f});
    const SensorId cppSensor = cpp.addSensor(sensor);

    CWorld c(fluid_default_world_def());
    fluid_material_def waterDef{};
    C_OK(fluid_material_preset("water", &waterDef));
    fluid_material_id cwater{};
    C_OK(fluid_world_add_material(c.world, &waterDef, &cwater));
    const fluid_param box[] = {{"minX", 0.0}, {"minY", 0.0}, {"maxX", 1.0}, {"maxY", 1.0}};
    const fluid_param gravity[] = {{"gy", -9.81}};
    fluid_plugin_id plugin{};
    C_OK(fluid_world_add_plugin(c.world, "boundary.box", box, 4, &plugin));
    C_OK(fluid_world_add_plugin(c.world, "force.gravity", gravity, 1, &plugin));
    fluid_emitter_def cnozzle = fluid_default_emitter_def();
    cnozzle.position = {0.7f, 0.6f};
    cnozzle.direction = {0.0f, -1.0f};
    cnozzle.rate = 400.0f;
    cnozzle.material = cwater;
    cnozzle.lifetime = 1.5f;
    fluid_emitter_id cemitter{};
    C_OK(fluid_world_add_emitter(c.world, &cnozzle, &cemitter));
    fluid_drain_def cdrain{};
    cdrain.shape = fluid_box_shape({0.8f, 0.0f}, {1.0f, 0.3f});
    fluid_drain_id cdrainId{};
    C_OK(fluid_world_add_drain(c.world, &cdrain, &cdrainId));
    fluid_sensor_id csensor{};
    C_OK(fluid_world_add_sensor(c.world, fluid_box_shape({0.0f, 0.0f}, {0.75f, 0.5f}), &csensor));

    uint32_t drained = 0, expired = 0;
    for (int f = 0; f < 150; ++f) {
        cpp.step(kFrame);
        C_OK(fluid_world_step(c.world, kFrame));
        const fluid_removed_event* events = nullptr;
        uint32_t count = 0;
        C_OK(fluid_world_removed_events(c.world, &events, &count));
        const auto cppEvents = cpp.removedEvents();
        REQUIRE(count == cppEvents.size());
        for (uint32_t k = 0; k < count; ++k) {
            CHECK(events[k].position.x == cppEvents[k].position.x);
            CHECK(events[k].velocity.y == cppEvents[k].velocity.y);
            CHECK(events[k].particle.slot == cppEvents[k].particle.slot);
            CHECK(events[k].cause == int(cppEvents[k].cause));
            if (events[k].cause == FLUID_REMOVED_BY_DRAIN) {
                CHECK(events[k].drain.index == cppDrain.index);
                ++drained;
            } else {
                CHECK(events[k].cause == FLUID_REMOVED_BY_LIFETIME);
                ++expired;
            }
        }
    }
    std::printf("[measure] C API gameplay: %u drained, %u expired over 2.5 s\n", drained, expired);
    CHECK(drained > 50);
    CHECK(expired > 0);
    uint32_t emitted = 0;
    C_OK(fluid_world_emitted_count(c.world, cemitter, &emitted));
    CHECK(emitted == cpp.emittedCount(emitter));
    CHECK(emitted > 500);
    CHECK(sameBits(cState(c.world), cppState(cpp)));
    const fluid_sensor_reading* readings = nullptr;
    uint32_t materials = 0;
    C_OK(fluid_world_sensor_readings(c.world, csensor, &readings, &materials));
    const auto cppReadings = cpp.sensorReading(cppSensor);
    REQUIRE(materials == cppReadings.size());
    CHECK(readings[0].count == cppReadings[0].count);
    CHECK(readings[0].count > 0);
    CHECK(readings[0].mass == cppReadings[0].mass);
    CHECK(readings[0].volume == cppReadings[0].volume);
    // An emitter changed between steps: off.
    cnozzle.rate = 0.0f;
    C_OK(fluid_world_set_emitter(c.world, cemitter, &cnozzle));
    C_OK(fluid_world_step(c.world, kFrame));
    uint32_t after = 0;
    C_OK(fluid_world_emitted_count(c.world, cemitter, &after));
    CHECK(after == emitted);
}

TEST_CASE("C API: a force plugin written in C acts as the built-in gravity, bit for bit, with "
          "its parameters, prepare and destroy",
          "[c]") {
    c_test_counters counters{};
    fluid_world_def def = fluid_default_world_def();
    C_OK(fluid_world_def_set_quality(&def, "game"));
    auto build = [&](bool ownForce) {
        fluid_world* world = nullptr;
        C_OK(fluid_world_create(&def, &world));
        fluid_material_def water{};
        C_OK(fluid_material_preset("water", &water));
        fluid_material_id id{};
        C_OK(fluid_world_add_material(world, &water, &id));
        const fluid_param box[] = {{"maxX", 1.0}, {"maxY", 2.0}, {"minX", 0.0}};
        fluid_plugin_id plugin{};
        C_OK(fluid_world_add_plugin(world, "boundary.box", box, 3, &plugin));
        fluid_plugin_id force{};
        if (ownForce) {
            const fluid_force_plugin_def acceleration = c_test_acceleration(&counters);
            C_OK(fluid_world_add_force(world, &acceleration, &force));
        } else {
            const fluid_param gravity[] = {{"gy", -9.81}};
            C_OK(fluid_world_add_plugin(world, "force.gravity", gravity, 1, &force));
        }
        CHECK(force.kind == FLUID_PLUGIN_FORCE);
        fluid_blob_def blob = fluid_default_blob_def();
        blob.shape = fluid_box_shape({0.3f, 0.5f}, {0.7f, 0.9f});
        blob.material = id;
        C_OK(fluid_world_spawn_blob(world, &blob, nullptr));
        return std::make_pair(world, force);
    };
    auto [own, ownForce] = build(true);
    auto [builtin, builtinForce] = build(false);
    double gy = 0.0;
    C_OK(fluid_plugin_get_param(own, ownForce, "gy", &gy));
    CHECK(gy == -9.81); // the declaration's default
    for (int f = 0; f < 60; ++f) {
        C_OK(fluid_world_step(own, kFrame));
        C_OK(fluid_world_step(builtin, kFrame));
    }
    CHECK(counters.prepared == 60);
    const std::vector<float> fallen = cState(own);
    CHECK(sameBits(fallen, cState(builtin)));
    // It acts: the blob fell.
    const size_t n = fallen.size() / 4;
    double meanY = 0.0;
    for (size_t i = 0; i < n; ++i) {
        meanY += fallen[n + i] / double(n);
    }
    CHECK(meanY < 0.5);
    // A parameter set through the C API reaches the callbacks: sideways now, on both.
    C_OK(fluid_plugin_set_param(own, ownForce, "gx", 4.0));
    C_OK(fluid_plugin_set_param(builtin, builtinForce, "gx", 4.0));
    for (int f = 0; f < 30; ++f) {
        C_OK(fluid_world_step(own, kFrame));
        C_OK(fluid_world_step(builtin, kFrame));
    }
    CHECK(sameBits(cState(own), cState(builtin)));
    CHECK(counters.prepared == 90);
    CHECK(counters.destroyed == 0);
    fluid_world_destroy(own);
    CHECK(counters.destroyed == 1);
    fluid_world_destroy(builtin);
    CHECK(counters.destroyed == 1);

    // A def the world refuses leaves the plugin's user data to its owner: no destroy.
    c_test_counters refused{};
    fluid_force_plugin_def bad = c_test_acceleration(&refused);
    bad.apply = nullptr;
    CWorld world(def);
    fluid_plugin_id id{};
    CHECK(fluid_world_add_force(world.world, &bad, &id) == FLUID_ERROR_NULL_ARGUMENT);
    CHECK(std::string(fluid_last_error()) ==
          "fluid_world_add_force: plugin type 'c_test.acceleration': def->apply is NULL");
    CHECK(refused.destroyed == 0);
}

namespace {

// Water about 0.2 m deep (a whole number of spacings) in a `boundary.box` tank `width` wide and
// 1 m tall, under gravity `g` (m/s^2): what the C box floats in. WaterTank holds the water's
// preset and id, its lattice spacing and its depth (m).
struct WaterTank {
    fluid_material_def water{};
    fluid_material_id id{};
    float spacing = 0.0f, depth = 0.0f;
};
WaterTank fillWaterTank(fluid_world* world, float width, float g) {
    WaterTank t;
    C_OK(fluid_material_preset("water", &t.water));
    C_OK(fluid_world_add_material(world, &t.water, &t.id));
    C_OK(fluid_world_spacing(world, t.id, &t.spacing));
    t.depth = std::round(0.2f / t.spacing) * t.spacing;
    const fluid_param tank[] = {{"minX", 0.0}, {"minY", 0.0}, {"maxX", width}, {"maxY", 1.0}};
    fluid_plugin_id plugin{};
    C_OK(fluid_world_add_plugin(world, "boundary.box", tank, 4, &plugin));
    const fluid_param gravity[] = {{"gy", double(g)}};
    C_OK(fluid_world_add_plugin(world, "force.gravity", gravity, 1, &plugin));
    fluid_blob_def blob = fluid_default_blob_def();
    blob.shape = fluid_box_shape({0.0f, 0.0f}, {width, t.depth});
    blob.material = t.id;
    C_OK(fluid_world_spawn_blob(world, &blob, nullptr));
    return t;
}

} // namespace

TEST_CASE("C API: a boundary plugin written in C carries its own rigid body, which floats at "
          "Archimedes' draft",
          "[c][slow]") {
    // Water 0.2 m deep in a tank 0.64 m wide; a box 0.3 m wide and 0.2 m tall at half water's
    // density, starting with its bottom on the surface; 7 s to settle (as the Box2D coupling's
    // Archimedes test, precise preset, 10%).
    fluid_world_def def = fluid_default_world_def();
    C_OK(fluid_world_def_set_quality(&def, "precise"));
    CWorld world(def);
    const float width = 0.64f, g = -9.81f;
    const WaterTank tank = fillWaterTank(world.world, width, g);
    const fluid_material_def& water = tank.water;
    const float s = tank.spacing, depth = tank.depth;
    fluid_plugin_id plugin{};

    const float halfWidth = 0.15f, halfHeight = 0.1f, ratio = 0.5f;
    const float slab = def.depth;
    const float mass = ratio * water.rest_density * slab * (2 * halfWidth) * (2 * halfHeight);
    const float added = water.rest_density * slab * 3.14159265f * halfWidth * halfWidth;
    c_test_box box;
    REQUIRE(c_test_box_init(&box, 0.5f * width, depth + halfHeight, halfWidth, halfHeight, mass,
                            added, g));
    const fluid_boundary_plugin_def boxDef = c_test_box_plugin(&box);
    C_OK(fluid_world_add_boundary(world.world, &boxDef, &plugin));
    CHECK(plugin.kind == FLUID_PLUGIN_BOUNDARY);

    const int frames = 420, window = 30;
    double submerged = 0.0, lift = 0.0, speed = 0.0;
    for (int f = 0; f < frames; ++f) {
        C_OK(fluid_world_step(world.world, kFrame));
        if (f < frames - window) {
            continue;
        }
        // The waterline either side of the box, out of its kernel's reach: the top particle of
        // each column of one spacing, plus half a spacing.
        const float *x = nullptr, *y = nullptr;
        uint32_t n = 0;
        C_OK(fluid_world_positions(world.world, &x, &y, &n));
        const float reach = 2.0f * water.smoothing_distance;
        std::vector<float> top(size_t(width / s) + 1, -1.0f);
        for (uint32_t i = 0; i < n; ++i) {
            const float gap = std::fabs(x[i] - box.x) - halfWidth;
            if (gap > reach && x[i] > reach && x[i] < width - reach) {
                float& t = top[size_t(x[i] / s)];
                t = std::max(t, y[i]);
            }
        }
        double level = 0.0;
        int columns = 0;
        for (const float t : top) {
            if (t > 0.0f) {
                level += t + 0.5 * s;
                ++columns;
            }
        }
        REQUIRE(columns >= 5);
        level /= columns;
        const double bottom = box.y - halfHeight;
        submerged += std::clamp((level - bottom) / (2.0 * halfHeight), 0.0, 1.0) / window;
        lift += box.lift / double(window);
        speed = std::max(speed, double(std::fabs(box.vy)));
    }
    std::printf("[measure] C API floating box at %.2f of water's density: submerged %.4f "
                "(%+.1f%%), lift %.3f N vs weight %.3f N, speed %.4f m/s over the last 0.5 s\n",
                double(ratio), submerged, 100.0 * (submerged / ratio - 1.0), lift,
                double(mass * -g), speed);
    CHECK(std::fabs(submerged / ratio - 1.0) <= 0.10);
    CHECK(lift == Approx(double(mass * -g)).epsilon(0.05));
    CHECK(speed < 0.01);
    CHECK(box.destroyed == 0);
    fluid_world_destroy(world.world);
    world.world = nullptr;
    CHECK(box.destroyed == 1);
    c_test_box_free(&box);
}

namespace {

// What the C box's project and receive_body_impulses saw (project runs on worker threads: the
// same values from each, so plain atomics do).
struct ShiftSeen {
    std::atomic<uint32_t> count{0xFFFFFFFFu}; // body_shift_count of the step's last call
    std::atomic<float> endShift{0.0f};        // its vertical shift at its time_in_step
    std::atomic<float> endTime{-1.0f};        // that time_in_step
    float displacement = 0.0f;                // receive_body_impulses' vertical displacement
    fluid_boundary_plugin_def inner{};
};
ShiftSeen g_shiftSeen;

void seenProject(void* user, const fluid_project_context* c, uint32_t begin, uint32_t end) {
    if (c->time_in_step >= g_shiftSeen.endTime.load()) {
        g_shiftSeen.endTime = c->time_in_step;
        g_shiftSeen.count = c->body_shift_count;
        g_shiftSeen.endShift =
            c->body_shift_count == 1
                ? c->body_shifts[0].offset.y + c->body_shifts[0].velocity.y * c->time_in_step
                : 0.0f;
    }
    g_shiftSeen.inner.project(user, c, begin, end);
}

void seenImpulses(void* user, const fluid_rigid_body_impulse* j, uint32_t count) {
    g_shiftSeen.displacement = count == 1 ? j[0].displacement.y : 0.0f;
    g_shiftSeen.inner.receive_body_impulses(user, j, count);
}

} // namespace

// The game preset's coarse solve moves a C plugin's rigid body within the step; its project gets
// where (fluid_project_context::body_shifts, C API 1.1), and at the step's end that shift is the
// displacement receive_body_impulses then hands the host: the particles were put outside the
// box where it ends up.
TEST_CASE("C API: a C boundary's project sees the coarse solve's shift of its rigid body, which "
          "ends the step at the displacement the host gets",
          "[c]") {
    fluid_world_def def = fluid_default_world_def(); // the game preset
    CWorld world(def);
    const float width = 0.64f, g = -9.81f;
    const WaterTank tank = fillWaterTank(world.world, width, g);
    const fluid_material_def& water = tank.water;
    const float depth = tank.depth;
    fluid_plugin_id plugin{};
    const float halfWidth = 0.15f, halfHeight = 0.1f, ratio = 0.5f;
    const float mass = ratio * water.rest_density * def.depth * (2 * halfWidth) * (2 * halfHeight);
    const float added = water.rest_density * def.depth * 3.14159265f * halfWidth * halfWidth;
    c_test_box box;
    REQUIRE(c_test_box_init(&box, 0.5f * width, depth + halfHeight - ratio * 2 * halfHeight,
                            halfWidth, halfHeight, mass, added, g));
    g_shiftSeen.inner = c_test_box_plugin(&box);
    fluid_boundary_plugin_def boxDef = g_shiftSeen.inner;
    boxDef.project = seenProject;
    boxDef.receive_body_impulses = seenImpulses;
    C_OK(fluid_world_add_boundary(world.world, &boxDef, &plugin));

    int moved = 0;
    float largest = 0.0f, worst = 0.0f;
    for (int f = 0; f < 120; ++f) {
        g_shiftSeen.endTime = -1.0f;
        C_OK(fluid_world_step(world.world, kFrame));
        CAPTURE(f, g_shiftSeen.count.load(), g_shiftSeen.endShift.load(), g_shiftSeen.displacement);
        if (g_shiftSeen.displacement != 0.0f) {
            ++moved;
            CHECK(g_shiftSeen.count == 1u);
            largest = std::max(largest, std::fabs(g_shiftSeen.displacement));
        }
        worst = std::max(worst, std::fabs(g_shiftSeen.endShift - g_shiftSeen.displacement));
    }
    std::printf("[measure] C API box in the game preset: the coarse solve moved it in %d of 120 "
                "steps, by up to %.3g m; the shift its project saw at the step's end against "
                "the displacement it got: at most %.3g m apart\n",
                moved, double(largest), double(worst));
    CHECK(moved >= 10);     // the solve moved the box (50 of the 120 steps when written)
    CHECK(largest > 1e-4f); // by more than float noise
    CHECK(worst <= 1e-7f);  // and the project saw where it put it
    fluid_world_destroy(world.world);
    world.world = nullptr;
    c_test_box_free(&box);
}

TEST_CASE("C API: a snapshot in memory loads into a world that steps on bit for bit, and a C "
          "plugin's type cannot be made again",
          "[c]") {
    c_test_counters counters{}; // outlives the world, whose plugin's destroy counts in it
    fluid_world_def def = fluid_default_world_def();
    C_OK(fluid_world_def_set_quality(&def, "game"));
    CWorld world(def);
    cDam(world.world);
    for (int f = 0; f < 20; ++f) {
        C_OK(fluid_world_step(world.world, kFrame));
    }
    fluid_bytes bytes{};
    C_OK(fluid_world_save(world.world, &bytes));
    REQUIRE(bytes.size > 0);
    CWorld loaded;
    C_OK(fluid_world_load(bytes.data, bytes.size, 0, &loaded.world));
    fluid_bytes_free(&bytes);
    CHECK(bytes.data == nullptr);
    for (int f = 0; f < 20; ++f) {
        C_OK(fluid_world_step(world.world, kFrame));
        C_OK(fluid_world_step(loaded.world, kFrame));
    }
    CHECK(sameBits(cState(world.world), cState(loaded.world)));

    const fluid_force_plugin_def acceleration = c_test_acceleration(&counters);
    fluid_plugin_id id{};
    C_OK(fluid_world_add_force(world.world, &acceleration, &id));
    C_OK(fluid_world_save(world.world, &bytes));
    fluid_world* again = nullptr;
    CHECK(fluid_world_load(bytes.data, bytes.size, 0, &again) == FLUID_ERROR_UNKNOWN_NAME);
    CHECK(again == nullptr);
    CHECK(std::string(fluid_last_error()).find("c_test.acceleration") != std::string::npos);
    std::istringstream in(std::string(reinterpret_cast<const char*>(bytes.data), bytes.size));
    Registry registry;
    registerBuiltinPlugins(registry);
    CHECK(std::string(fluid_last_error()) == cppMessage([&] { World::load(in, registry); }));
    fluid_bytes_free(&bytes);
}

TEST_CASE("C API: a plugin type written in C, registered by name, is added by name, named in "
          "a level file and made again by a snapshot",
          "[c]") {
    c_test_counters counters{};
    const fluid_plugin_type_def type = c_test_acceleration_type("c_test.fall", &counters, false);
    C_OK(fluid_register_plugin_type(&type));
    CHECK(fluid_register_plugin_type(&type) == FLUID_ERROR_INVALID_ARGUMENT);
    CHECK(std::string(fluid_last_error()) ==
          "Registry::add: plugin type 'c_test.fall' is already registered");
    fluid_plugin_type_def builtin = type;
    builtin.type = "force.gravity";
    CHECK(fluid_register_plugin_type(&builtin) == FLUID_ERROR_INVALID_ARGUMENT);
    fluid_plugin_type_def noFactory = type;
    noFactory.type = "c_test.no_factory";
    noFactory.create_force = nullptr;
    CHECK(fluid_register_plugin_type(&noFactory) == FLUID_ERROR_NULL_ARGUMENT);
    CHECK(std::string(fluid_last_error()) ==
          "fluid_register_plugin_type: plugin type 'c_test.no_factory': def->create_force is NULL");
    const fluid_plugin_type_def refusing =
        c_test_acceleration_type("c_test.refusing", &counters, true);
    C_OK(fluid_register_plugin_type(&refusing));
    {
        // By name, as a built-in: the same bits as force.gravity, saved and made again.
        fluid_world_def def = fluid_default_world_def();
        C_OK(fluid_world_def_set_quality(&def, "game"));
        CWorld own(def), reference(def);
        cDam(reference.world); // force.gravity, gy -9.81
        fluid_material_def water{};
        C_OK(fluid_material_preset("water", &water));
        fluid_material_id id{};
        C_OK(fluid_world_add_material(own.world, &water, &id));
        const fluid_param box[] = {{"minX", 0.0}, {"minY", 0.0}, {"maxX", 1.0}, {"maxY", 2.0}};
        fluid_plugin_id plugin{};
        C_OK(fluid_world_add_plugin(own.world, "boundary.box", box, 4, &plugin));
        const fluid_param fall[] = {{"gx", 0.0}, {"gy", -9.81}};
        C_OK(fluid_world_add_plugin(own.world, "c_test.fall", fall, 2, &plugin));
        const char* name = nullptr;
        C_OK(fluid_plugin_type(own.world, plugin, &name));
        CHECK(std::string(name) == "c_test.fall");
        fluid_blob_def blob = fluid_default_blob_def();
        blob.shape = fluid_box_shape({0.0f, 0.0f}, {0.4f, 0.6f});
        blob.material = id;
        C_OK(fluid_world_spawn_blob(own.world, &blob, nullptr));
        for (int f = 0; f < 30; ++f) {
            C_OK(fluid_world_step(own.world, kFrame));
            C_OK(fluid_world_step(reference.world, kFrame));
        }
        CHECK(sameBits(cState(own.world), cState(reference.world)));
        CHECK(counters.prepared == 30);
        fluid_bytes bytes{};
        C_OK(fluid_world_save(own.world, &bytes));
        CWorld loaded;
        C_OK(fluid_world_load(bytes.data, bytes.size, 0, &loaded.world));
        fluid_bytes_free(&bytes);
        for (int f = 0; f < 30; ++f) {
            C_OK(fluid_world_step(own.world, kFrame));
            C_OK(fluid_world_step(loaded.world, kFrame));
        }
        CHECK(sameBits(cState(own.world), cState(loaded.world)));
        CHECK(counters.prepared == 90); // both instances count in the type's counters
        CHECK(fluid_world_add_plugin(own.world, "c_test.refusing", nullptr, 0, &plugin) ==
              FLUID_ERROR_INVALID_ARGUMENT);
        CHECK(std::string(fluid_last_error()) ==
              "plugin type 'c_test.refusing' (written in C): create_force refused");
    }
    CHECK(counters.destroyed == 2);
    // Named in a level file.
    const std::string text =
        R"({"version": 1, "materials": [{"name": "water"}],
  "plugins": [{"type": "boundary.box", "params": {"minX": 0, "minY": 0, "maxX": 0.5, "maxY": 1}},
              {"type": "c_test.fall", "params": {"gy": -5}}],
  "blobs": [{"material": "water", "shape": "box", "min": [0, 0.2], "max": [0.2, 0.4]}]})";
    fluid_level* level = nullptr;
    C_OK(fluid_level_parse(text.data(), text.size(), "fall.json", nullptr, &level));
    for (int f = 0; f < 6; ++f) {
        C_OK(fluid_level_step(level));
    }
    fluid_world* world = nullptr;
    C_OK(fluid_level_world(level, &world));
    const std::vector<float> state = cState(world);
    const size_t n = state.size() / 4;
    double vy = 0.0;
    for (size_t i = 0; i < n; ++i) {
        vy += state[3 * n + i] / double(n);
    }
    CHECK(vy == Approx(-0.5).margin(0.03)); // 0.1 s of falling at the file's 5 m/s^2
    fluid_level_destroy(level);
    CHECK(counters.destroyed == 3);
}

TEST_CASE("C API: a level loads, steps, saves and loads back as through C++", "[c]") {
    std::string path = FLUID_LEVELS_DIR;
    path.append("/dam_break.json");
    fluid_level_options options = fluid_default_level_options();
    options.worker_count = 1;
    fluid_level* level = nullptr;
    C_OK(fluid_level_load(path.c_str(), &options, &level));
    Registry registry;
    registerBuiltinPlugins(registry);
    LevelOptions cppOptions;
    cppOptions.workerCount = 1;
    Level cpp = loadLevel(path, registry, cppOptions);
    float rate = 0.0f;
    C_OK(fluid_level_frame_rate(level, &rate));
    CHECK(rate == cpp.frameRate);
    for (int f = 0; f < 30; ++f) {
        C_OK(fluid_level_step(level));
        cpp.step();
    }
    fluid_world* world = nullptr;
    C_OK(fluid_level_world(level, &world));
    CHECK(sameBits(cState(world), cppState(cpp.world)));
    // A level's world is the level's: fluid_world_destroy leaves it alone.
    fluid_world_destroy(world);
    uint32_t count = 0;
    C_OK(fluid_world_particle_count(world, &count));
    CHECK(count == cpp.world.particleCount());
    fluid_material_id water{};
    C_OK(fluid_level_find_material(level, cpp.materials.front().first.c_str(), &water));
    CHECK(fluid_level_find_material(level, "no such", &water) == FLUID_ERROR_UNKNOWN_NAME);
    CHECK(std::string(fluid_last_error()) ==
          "fluid_level_find_material: the level has no material named 'no such'");

    fluid_bytes save{};
    C_OK(fluid_level_save_bytes(level, &save));
    fluid_level* restored = nullptr;
    C_OK(fluid_level_read_save(save.data, save.size, "dam.save", &options, &restored));
    fluid_bytes_free(&save);
    for (int f = 0; f < 30; ++f) {
        C_OK(fluid_level_step(level));
        C_OK(fluid_level_step(restored));
    }
    fluid_world* restoredWorld = nullptr;
    C_OK(fluid_level_world(restored, &restoredWorld));
    CHECK(sameBits(cState(world), cState(restoredWorld)));
    fluid_goal_state state = FLUID_GOAL_PENDING;
    double value = -1.0;
    C_OK(fluid_level_goal(level, &state, &value));
    CHECK(state == (cpp.goal.present ? FLUID_GOAL_PENDING : FLUID_GOAL_NONE));
    fluid_level_destroy(restored);
    fluid_level_destroy(level);
}

TEST_CASE("C API: a crate dropped into a level, a body thrown and gravity changed, through C as "
          "through C++",
          "[c]") {
    // What the demo does to a level's bodies (ctrl + click drops a crate, a drag moves a body),
    // through both APIs: the same bits after a second.
    std::string path = FLUID_LEVELS_DIR;
    path.append("/crates.json");
    fluid_level_options options = fluid_default_level_options();
    options.worker_count = 1;
    fluid_level* level = nullptr;
    C_OK(fluid_level_load(path.c_str(), &options, &level));
    Registry registry;
    registerBuiltinPlugins(registry);
    LevelOptions cppOptions;
    cppOptions.workerCount = 1;
    Level cpp = loadLevel(path, registry, cppOptions);

    fluid_material_id water{};
    C_OK(fluid_level_find_material(level, cpp.materials.front().first.c_str(), &water));
    float areal = 0.0f;
    C_OK(fluid_level_areal_density(level, water, &areal));
    CHECK(areal == box2d::arealDensity(cpp.world, cpp.materials.front().second));
    fluid_body_def crate = fluid_default_body_def();
    crate.shape.center = {0.9f, 0.5f}; // (fluid_box_shape's corners would round the centre)
    crate.shape.half_extents = {0.05f, 0.05f};
    crate.angle = -0.3f;
    crate.density = 0.5f * areal;
    uint32_t index = 0, count = 0;
    C_OK(fluid_level_add_body(level, &crate, &index));
    C_OK(fluid_level_body_count(level, &count));
    CHECK(index == cpp.bodies.size());
    CHECK(count == cpp.bodies.size() + 1);
    {
        b2BodyDef def;
        def.type = b2_dynamicBody;
        def.position = {0.9f, 0.5f};
        def.angle = -0.3f;
        b2Body* body = cpp.physics->CreateBody(&def);
        b2PolygonShape box;
        box.SetAsBox(0.05f, 0.05f);
        b2FixtureDef fixture;
        fixture.shape = &box;
        fixture.density = 0.5f * areal;
        fixture.friction = 0.4f;
        body->CreateFixture(&fixture);
    }
    // Weaker gravity, on the fluid and on Box2D (the demo's G key sets zero).
    C_OK(fluid_level_set_gravity(level, {0.0f, -4.0f}));
    for (const auto& force : cpp.world.forces()) {
        if (force->type() == "force.gravity") {
            force->setParam("gx", 0.0);
            force->setParam("gy", -4.0);
        }
    }
    cpp.physics->SetGravity({0.0f, -4.0f});
    for (b2Body* b = cpp.physics->GetBodyList(); b != nullptr; b = b->GetNext()) {
        b->SetAwake(true);
    }
    fluid_world* cworld = nullptr;
    C_OK(fluid_level_world(level, &cworld));
    uint32_t forces = 0;
    C_OK(fluid_world_plugin_count(cworld, FLUID_PLUGIN_FORCE, &forces));
    REQUIRE(forces == cpp.world.forces().size());
    for (uint32_t k = 0; k < forces; ++k) {
        const char* type = nullptr;
        C_OK(fluid_plugin_type(cworld, {k, FLUID_PLUGIN_FORCE, 0}, &type));
        CHECK(std::string(type) == cpp.world.forces()[k]->type());
    }
    C_OK(fluid_level_set_body_velocity(level, 1, {0.5f, 1.0f}, 2.0f));
    b2Body* thrown = cpp.bodies[1].second;
    thrown->SetLinearVelocity({0.5f, 1.0f});
    thrown->SetAngularVelocity(2.0f);
    thrown->SetAwake(true);
    for (int f = 0; f < 60; ++f) {
        C_OK(fluid_level_step(level));
        cpp.step();
    }
    fluid_world* world = nullptr;
    C_OK(fluid_level_world(level, &world));
    CHECK(sameBits(cState(world), cppState(cpp.world)));
    const char* name = nullptr;
    fluid_vec2 at{};
    float angle = 0.0f;
    C_OK(fluid_level_body(level, 1, &name, &at, &angle));
    CHECK(std::string(name) == cpp.bodies[1].first);
    CHECK(at.x == thrown->GetPosition().x);
    CHECK(at.y == thrown->GetPosition().y);
    CHECK(angle == thrown->GetAngle());
    C_OK(fluid_level_body(level, index, &name, &at, nullptr));
    CHECK(std::string(name).empty());
    CHECK(at.y < 0.5f); // the crate fell into the water
    // Bad bodies are refused with their reason.
    fluid_body_def bad = crate;
    bad.density = 0.0f;
    CHECK(fluid_level_add_body(level, &bad, nullptr) == FLUID_ERROR_INVALID_ARGUMENT);
    CHECK(std::string(fluid_last_error()) ==
          "fluid_level_add_body: density must be finite and > 0 for a dynamic body (>= 0 "
          "otherwise), kg/m^2");
    const fluid_vec2 star[] = {{0, 0}, {0.1f, 0}, {0.05f, 0.02f}, {0.1f, 0.1f}, {0, 0.1f}};
    bad = crate;
    bad.shape = fluid_polygon_shape(star, 5);
    CHECK(fluid_level_add_body(level, &bad, nullptr) == FLUID_ERROR_INVALID_ARGUMENT);
    CHECK(std::string(fluid_last_error()) ==
          "fluid_level_add_body: the polygon is not convex at vertex 2; a Box2D polygon is convex (split "
              "a concave shape into several fixtures)");
    CHECK(fluid_level_set_body_velocity(level, 99, {0, 0}, 0) == FLUID_ERROR_STALE_ID);
    fluid_level_destroy(level);

    fluid_level* noBodies = nullptr;
    std::string dam = FLUID_LEVELS_DIR;
    dam.append("/dam_break.json");
    C_OK(fluid_level_load(dam.c_str(), &options, &noBodies));
    CHECK(fluid_level_add_body(noBodies, &crate, nullptr) == FLUID_ERROR_REFUSED);
    fluid_level_destroy(noBodies);
}

TEST_CASE("C API: every error path returns its status and the C++ API's own message", "[c]") {
    fluid_world_def def = fluid_default_world_def();
    CWorld c(def);
    World cpp(WorldDef{});
    fluid_material_def waterDef{};
    C_OK(fluid_material_preset("water", &waterDef));
    fluid_material_id water{};
    C_OK(fluid_world_add_material(c.world, &waterDef, &water));
    const MaterialId cppWater = cpp.addMaterial(fluid::water());

    SECTION("a NULL argument") {
        CHECK(fluid_world_step(nullptr, kFrame) == FLUID_ERROR_NULL_ARGUMENT);
        CHECK(std::string(fluid_last_error()) == "fluid_world_step: world is NULL");
        CHECK(fluid_world_add_material(c.world, nullptr, &water) == FLUID_ERROR_NULL_ARGUMENT);
        CHECK(std::string(fluid_last_error()) == "fluid_world_add_material: def is NULL");
    }
    SECTION("a stale particle handle") {
        fluid_particle_id p{};
        C_OK(fluid_world_add_particle(c.world, {0.1f, 0.1f}, {0.0f, 0.0f}, water, &p));
        const ParticleHandle h = cpp.addParticle({0.1f, 0.1f}, {0.0f, 0.0f}, cppWater);
        C_OK(fluid_world_remove_particle(c.world, p));
        cpp.removeParticle(h);
        bool valid = true;
        C_OK(fluid_world_particle_valid(c.world, p, &valid));
        CHECK_FALSE(valid);
        fluid_vec2 at{7.0f, 7.0f};
        CHECK(fluid_world_particle_position(c.world, p, &at) == FLUID_ERROR_STALE_ID);
        CHECK(at.x == 7.0f); // outputs untouched
        // The same text as the C++ API's, bar the world tag each message names.
        const std::string cMessage = fluid_last_error();
        const std::string cppText = cppMessage([&] { (void)cpp.position(h); });
        CHECK(cMessage.substr(0, cMessage.find("world")) ==
              cppText.substr(0, cppText.find("world")));
        CHECK(fluid_world_remove_particle(c.world, p) == FLUID_ERROR_STALE_ID);
        CHECK(fluid_world_set_particle_velocity(c.world, p, {1.0f, 0.0f}) ==
              FLUID_ERROR_STALE_ID);
    }
    SECTION("a turned blob: the C++ lattice, and its angle's range") {
        fluid_blob_def blob = fluid_default_blob_def();
        const fluid_vec2 layer[4] = {{0.1f, 0.6f}, {0.55f, 0.41f}, {0.566f, 0.45f}, {0.116f, 0.64f}};
        blob.shape = fluid_polygon_shape(layer, 4);
        blob.material = water;
        uint32_t made = 0;
        C_OK(fluid_world_spawn_blob_turned(c.world, &blob, -0.4f, &made));
        BlobDef cppBlob;
        cppBlob.shape = Shape::polygon({{0.1f, 0.6f}, {0.55f, 0.41f}, {0.566f, 0.45f}, {0.116f, 0.64f}});
        cppBlob.material = cppWater;
        cppBlob.latticeAngle = -0.4f;
        REQUIRE(made == cpp.spawnBlob(cppBlob));
        REQUIRE(made > 0);
        const float *x = nullptr, *y = nullptr;
        uint32_t n = 0;
        C_OK(fluid_world_positions(c.world, &x, &y, &n));
        CHECK(std::vector<float>(x, x + n) ==
              std::vector<float>(cpp.positionX().begin(), cpp.positionX().end()));
        CHECK(std::vector<float>(y, y + n) ==
              std::vector<float>(cpp.positionY().begin(), cpp.positionY().end()));
        CHECK(fluid_world_spawn_blob_turned(c.world, &blob, 7.0f, nullptr) ==
              FLUID_ERROR_INVALID_ARGUMENT);
        cppBlob.latticeAngle = 7.0f;
        CHECK(std::string(fluid_last_error()) == cppMessage([&] { cpp.spawnBlob(cppBlob); }));
        CHECK(std::string(fluid_last_error()) ==
              "spawnBlob: latticeAngle = 7 is out of range [-6.2832, 6.2832] (unit: rad)");
    }
    SECTION("NaN arguments") {
        fluid_particle_id p{};
        const float nan = std::numeric_limits<float>::quiet_NaN();
        CHECK(fluid_world_add_particle(c.world, {nan, 0.0f}, {0.0f, 0.0f}, water, &p) ==
              FLUID_ERROR_INVALID_ARGUMENT);
        CHECK(std::string(fluid_last_error()) ==
              cppMessage([&] { cpp.addParticle({nan, 0.0f}, {0.0f, 0.0f}, cppWater); }));
        CHECK(fluid_world_step(c.world, nan) == FLUID_ERROR_INVALID_ARGUMENT);
        CHECK(std::string(fluid_last_error()) == cppMessage([&] { cpp.step(nan); }));
        fluid_material_def bad = waterDef;
        C_OK(fluid_material_def_set(&bad, "viscosity", -1.0));
        CHECK(fluid_world_add_material(c.world, &bad, &water) == FLUID_ERROR_INVALID_ARGUMENT);
        Material cppBad = fluid::water();
        cppBad.viscosity = -1.0f;
        CHECK(std::string(fluid_last_error()) == cppMessage([&] { cpp.addMaterial(cppBad); }));
        fluid_world_def nanDef = fluid_default_world_def();
        CHECK(fluid_world_def_set(&nanDef, "substeps", std::nan("")) ==
              FLUID_ERROR_INVALID_ARGUMENT);
        CHECK(std::string(fluid_last_error()) ==
              "fluid_world_def_set: 'substeps' = nan is not a whole number in [1, 12] (unit: "
              "count)");
        CHECK(fluid_world_def_set(&nanDef, "depth", std::nan("")) ==
              FLUID_ERROR_INVALID_ARGUMENT);
        CHECK(std::string(fluid_last_error()) ==
              "fluid_world_def_set: 'depth' = nan is not a number in [0.0001, 1000] (unit: m)");
        nanDef.depth = std::nanf("");
        fluid_world* never = nullptr;
        CHECK(fluid_world_create(&nanDef, &never) == FLUID_ERROR_INVALID_ARGUMENT);
        CHECK(never == nullptr);
        WorldDef cppNan;
        cppNan.depth = std::nanf("");
        CHECK(std::string(fluid_last_error()) == cppMessage([&] { World w(cppNan); }));
    }
    SECTION("unknown names") {
        Registry registry;
        registerBuiltinPlugins(registry);
        fluid_plugin_id id{};
        CHECK(fluid_world_add_plugin(c.world, "force.nope", nullptr, 0, &id) ==
              FLUID_ERROR_UNKNOWN_NAME);
        // The C++ message, whose list of known types the C API's registry may extend (types
        // registered in C by other tests of this process come after the built-ins).
        CHECK(std::string(fluid_last_error())
                  .rfind(cppMessage([&] { registry.create("force.nope"); }), 0) == 0);
        const fluid_param gz[] = {{"gz", 1.0}};
        CHECK(fluid_world_add_plugin(c.world, "force.gravity", gz, 1, &id) ==
              FLUID_ERROR_UNKNOWN_NAME);
        const std::vector<ParamValue> cppGz{{"gz", 1.0}};
        CHECK(std::string(fluid_last_error()) ==
              cppMessage([&] { registry.create("force.gravity", cppGz); }));
        const fluid_param far[] = {{"gy", 1e9}};
        CHECK(fluid_world_add_plugin(c.world, "force.gravity", far, 1, &id) ==
              FLUID_ERROR_INVALID_ARGUMENT);
        C_OK(fluid_world_add_plugin(c.world, "force.gravity", nullptr, 0, &id));
        CHECK(fluid_plugin_set_param(c.world, id, "strength", 1.0) == FLUID_ERROR_UNKNOWN_NAME);
        GravityForce gravity;
        CHECK(std::string(fluid_last_error()) ==
              cppMessage([&] { gravity.setParam("strength", 1.0); }));
        fluid_material_def m{};
        CHECK(fluid_material_preset("honey", &m) == FLUID_ERROR_UNKNOWN_NAME);
        CHECK(std::string(fluid_last_error()) ==
              "fluid_material_preset: unknown preset 'honey' (expected water, yoghurt or "
              "seed_yoghurt)");
        CHECK(fluid_world_def_set_quality(&def, "ultra") == FLUID_ERROR_UNKNOWN_NAME);
        CHECK(fluid_material_def_set(&m, "colour", 1.0) == FLUID_ERROR_UNKNOWN_NAME);
        CHECK(std::string(fluid_last_error()).rfind("fluid_material_def_set: unknown field "
                                                    "'colour' (fields: mass, restDensity",
                                                    0) == 0);
    }
    SECTION("stale and foreign ids") {
        CWorld other(def);
        fluid_material_def w2{};
        C_OK(fluid_material_preset("water", &w2));
        fluid_material_id foreign{};
        C_OK(fluid_world_add_material(other.world, &w2, &foreign));
        fluid_particle_id p{};
        CHECK(fluid_world_add_particle(c.world, {0.1f, 0.1f}, {0.0f, 0.0f}, foreign, &p) ==
              FLUID_ERROR_STALE_ID);
        const fluid_material_id past{7, water.world};
        fluid_material_def out{};
        CHECK(fluid_world_get_material(c.world, past, &out) == FLUID_ERROR_STALE_ID);
        CHECK(std::string(fluid_last_error()) ==
              cppMessage([&] { (void)cpp.material(MaterialId{7, 0}); }));
        fluid_plugin_id plugin{3, FLUID_PLUGIN_FORCE, 0};
        CHECK(fluid_plugin_set_param(c.world, plugin, "gy", 1.0) == FLUID_ERROR_STALE_ID);
        CHECK(std::string(fluid_last_error()) ==
              "fluid_plugin_set_param: no force plugin 3 in this world (it has 0)");
        fluid_emitter_id emitter{0, 0};
        uint32_t count = 0;
        CHECK(fluid_world_emitted_count(c.world, emitter, &count) == FLUID_ERROR_STALE_ID);
    }
    SECTION("too many particles") {
        fluid_world_def small = fluid_default_world_def();
        C_OK(fluid_world_def_set(&small, "maxParticles", 10));
        CWorld tiny(small);
        fluid_material_id id{};
        C_OK(fluid_world_add_material(tiny.world, &waterDef, &id));
        fluid_blob_def blob = fluid_default_blob_def();
        blob.material = id;
        CHECK(fluid_world_spawn_blob(tiny.world, &blob, nullptr) == FLUID_ERROR_LIMIT);
        CHECK(std::string(fluid_last_error()).find("maxParticles = 10") != std::string::npos);
    }
    SECTION("bad level files and snapshots") {
        Registry registry;
        registerBuiltinPlugins(registry);
        const std::string text = "{\"version\": 1, \"materials\": [}";
        fluid_level* level = nullptr;
        CHECK(fluid_level_parse(text.data(), text.size(), "broken.json", nullptr, &level) ==
              FLUID_ERROR_BAD_FILE);
        CHECK(level == nullptr);
        CHECK(std::string(fluid_last_error()) ==
              cppMessage([&] { parseLevel(text, "broken.json", registry); }));
        CHECK(fluid_level_load("/nonexistent/level.json", nullptr, &level) == FLUID_ERROR_IO);
        CHECK(std::string(fluid_last_error()) ==
              cppMessage([&] { loadLevel("/nonexistent/level.json", registry); }));
        const char garbage[] = "not a snapshot";
        fluid_world* world = nullptr;
        CHECK(fluid_world_load(garbage, sizeof garbage, 0, &world) == FLUID_ERROR_BAD_FILE);
        std::istringstream in(std::string(garbage, sizeof garbage));
        CHECK(std::string(fluid_last_error()) ==
              cppMessage([&] { World::load(in, registry); }));
    }
    SECTION("the message is per thread") {
        CHECK(fluid_world_step(nullptr, kFrame) == FLUID_ERROR_NULL_ARGUMENT);
        std::string other;
        std::thread([&] {
            other = fluid_last_error(); // nothing failed on this thread yet
            fluid_material_def m{};
            (void)fluid_material_preset("honey", &m);
        }).join();
        CHECK(other.empty());
        CHECK(std::string(fluid_last_error()) == "fluid_world_step: world is NULL");
    }
}

TEST_CASE("C API: fuzzed calls never crash, hang or leave NaN, and each failure has a status and a "
          "message",
          "[c]") {
    // A short run (CI): random calls with random, often bad, arguments on two worlds.
    std::mt19937 random(20261128);
    auto pick = [&](int n) { return int(random() % uint32_t(n)); };
    auto number = [&]() -> float {
        switch (pick(6)) {
        case 0: return std::numeric_limits<float>::quiet_NaN();
        case 1: return std::numeric_limits<float>::infinity();
        case 2: return -1e30f;
        default: return std::uniform_real_distribution<float>(-1.0f, 2.0f)(random);
        }
    };
    const char* names[] = {"force.gravity", "boundary.box", "force.vortex", "force.wind",
                           "boundary.circle", "nope", "", "force.pointer"};
    const char* params[] = {"gx", "gy", "minX", "maxX", "radius", "x", "y", "strength", "?"};
    fluid_world_def def = fluid_default_world_def();
    C_OK(fluid_world_def_set_quality(&def, "game"));
    C_OK(fluid_world_def_set(&def, "maxParticles", 4000));
    CWorld a(def), b(def);
    fluid_material_def water{};
    C_OK(fluid_material_preset("water", &water));
    fluid_material_id materials[2]{};
    C_OK(fluid_world_add_material(a.world, &water, &materials[0]));
    C_OK(fluid_world_add_material(b.world, &water, &materials[1]));
    std::vector<fluid_particle_id> particles;
    int failures = 0;
    for (int call = 0; call < 3000; ++call) {
        fluid_world* w = pick(2) == 0 ? a.world : b.world;
        const fluid_material_id m = materials[pick(2)];
        fluid_status status = FLUID_OK;
        switch (pick(10)) {
        case 0: {
            fluid_particle_id p{};
            status = fluid_world_add_particle(w, {number(), number()}, {number(), number()}, m, &p);
            if (status == FLUID_OK) {
                particles.push_back(p);
            }
            break;
        }
        case 1:
            if (!particles.empty()) {
                status = fluid_world_remove_particle(w, particles[size_t(pick(int(particles.size())))]);
            }
            break;
        case 2: {
            fluid_blob_def blob = fluid_default_blob_def();
            blob.shape = pick(2) == 0 ? fluid_box_shape({number(), number()}, {number(), number()})
                                      : fluid_circle_shape({number(), number()}, number() * 0.2f);
            blob.material = m;
            blob.velocity = {number(), number()};
            status = fluid_world_spawn_blob(w, &blob, nullptr);
            break;
        }
        case 3: {
            fluid_param values[2] = {{params[pick(9)], double(number())},
                                     {params[pick(9)], double(number())}};
            fluid_plugin_id id{};
            status = fluid_world_add_plugin(w, names[pick(8)], values, uint32_t(pick(3)), &id);
            break;
        }
        case 4: {
            const fluid_plugin_id id{uint32_t(pick(4)), uint32_t(pick(3)), uint32_t(pick(2))};
            status = fluid_plugin_set_param(w, id, params[pick(9)], double(number()));
            break;
        }
        case 5:
            status = fluid_world_step(w, pick(4) == 0 ? number() : kFrame);
            break;
        case 6: {
            fluid_emitter_def e = fluid_default_emitter_def();
            e.position = {number(), number()};
            e.direction = {number(), number()};
            e.rate = number() * 100.0f;
            e.material = m;
            fluid_emitter_id id{};
            status = fluid_world_add_emitter(w, &e, &id);
            break;
        }
        case 7: {
            std::string bytes(size_t(pick(64)), '\0');
            for (char& ch : bytes) {
                ch = char(pick(256));
            }
            fluid_world* loaded = nullptr;
            status = fluid_world_load(bytes.data(), bytes.size(), 0, &loaded);
            fluid_world_destroy(loaded);
            break;
        }
        case 8: {
            std::string text = "{\"version\": 1, \"materials\": {\"w\": {\"preset\": \"water\"}}}";
            text[size_t(pick(int(text.size())))] = char(32 + pick(90));
            fluid_level* level = nullptr;
            status = fluid_level_parse(text.data(), text.size(), "fuzz.json", nullptr, &level);
            fluid_level_destroy(level);
            break;
        }
        default: {
            fluid_material_def d = water;
            const char* fields[] = {"mass", "viscosity", "restDensity", "flowIndex", "?"};
            status = fluid_material_def_set(&d, fields[pick(5)], double(number()));
            if (status == FLUID_OK) {
                status = fluid_world_set_material(w, m, &d);
            }
            break;
        }
        }
        if (status != FLUID_OK) {
            ++failures;
            INFO("call " << call << ": " << fluid_status_name(status));
            REQUIRE(std::string(fluid_status_name(status)) != "unknown status");
            REQUIRE(std::strlen(fluid_last_error()) > 0);
        }
        for (fluid_world* world : {a.world, b.world}) {
            const float *x = nullptr, *y = nullptr;
            uint32_t n = 0;
            C_OK(fluid_world_positions(world, &x, &y, &n));
            REQUIRE(std::all_of(x, x + n, [](float v) { return std::isfinite(v); }));
            REQUIRE(std::all_of(y, y + n, [](float v) { return std::isfinite(v); }));
        }
    }
    std::printf("[measure] C API fuzz: 3000 calls, %d refused with a status and a message\n",
                failures);
    CHECK(failures > 300);
}

namespace {

// docs/c_api_reference.md's row for `field`: "| `name` | `member` | unit | range | ... | description |".
template <class Def> void checkDocRow(const std::string& doc, const Field<Def>& field) {
    CAPTURE(field.name);
    const std::string head = "| `" + std::string(field.name) + "` | `";
    const size_t at = doc.find(head);
    REQUIRE(at != std::string::npos);
    const size_t end = doc.find('\n', at);
    REQUIRE(end != std::string::npos);
    const std::string row(doc.begin() + std::ptrdiff_t(at), doc.begin() + std::ptrdiff_t(end));
    std::vector<std::string> cells;
    size_t b = 1;
    for (size_t e = row.find(" |", b); e != std::string::npos; e = row.find(" |", b)) {
        size_t first = b;
        while (first < e && row[first] == ' ') {
            ++first;
        }
        cells.emplace_back(row.begin() + std::ptrdiff_t(first), row.begin() + std::ptrdiff_t(e));
        b = e + 2;
    }
    REQUIRE(cells.size() >= 5);
    // The C member: the name in snake case.
    std::string member;
    for (const char ch : field.name) {
        if (std::isupper(static_cast<unsigned char>(ch))) {
            member.push_back('_');
            member.push_back(char(std::tolower(static_cast<unsigned char>(ch))));
        } else {
            member.push_back(ch);
        }
    }
    CHECK(cells[1] == "`" + member + "`");
    CHECK(cells[2] == std::string(field.unit));
    const std::string& range = cells[3];
    REQUIRE(range.size() > 4);
    CHECK(range.front() == (field.openLow ? '(' : '['));
    CHECK(range.back() == ']');
    const size_t comma = range.find(", ");
    REQUIRE(comma != std::string::npos);
    CHECK(std::strtod(range.c_str() + 1, nullptr) == field.lo);
    CHECK(std::strtod(range.c_str() + comma + 2, nullptr) == field.hi);
    CHECK(cells.back() == std::string(field.description));
}

} // namespace

TEST_CASE("C API: docs/c_api_reference.md's field tables are the C++ field tables", "[c]") {
    std::ifstream in(std::string(FLUID_SOURCE_DIR) + "/docs/c_api_reference.md");
    REQUIRE(in);
    std::ostringstream text;
    text << in.rdbuf();
    const std::string doc = text.str();
    for (const auto& f : positionBasedFields()) {
        checkDocRow(doc, f);
    }
    for (const auto& f : worldFields()) {
        checkDocRow(doc, f);
    }
    for (const auto& f : materialFields()) {
        checkDocRow(doc, f);
    }
}
