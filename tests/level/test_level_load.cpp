// fluid tests — the shipped levels (levels/*.json): each loads, builds what the file says and
// runs 120 frames without NaN; level-specific physics and goal checks.
#include <catch2/catch.hpp>

#include <fluid/level.h>
#include <fluid/plugins/builtin.h>

#include "test_support.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using namespace fluid;
using fluid::test::builtins;
using fluid::test::countOf;

namespace {

std::string levelPath(const char* name) {
    return std::string(FLUID_LEVELS_DIR) + "/" + name;
}

std::string readText(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// Runs `frames` frames through Level::step; returns the wall time per frame (unit: ms).
double run(Level& level, int frames) {
    const auto t0 = std::chrono::steady_clock::now();
    for (int f = 0; f < frames; ++f) {
        level.step();
    }
    const auto t1 = std::chrono::steady_clock::now();
    return std::chrono::duration<double, std::milli>(t1 - t0).count() / frames;
}

const Level::PluginEntry* plugin(const Level& level, std::string_view name) {
    for (const Level::PluginEntry& p : level.plugins) {
        if (p.name == name) {
            return &p;
        }
    }
    return nullptr;
}

} // namespace

// Levels with a test case of their own below (each runs 120 frames or more and checks for
// NaN); any other level in levels/ is run here, so a new level is never left untested.
// paddle_wheel.json and crates.json are played in test_level_box2d_levels.cpp; the demo's
// levels in test_level_demo_levels.cpp (big_tank.json for 150 frames).
constexpr std::string_view kLevelsWithOwnTest[] = {
    "dam_break.json",       "zero_g_blobs.json", "fill_the_cup.json",     "planetoid.json",
    "paddle_wheel.json",    "crates.json",       "yoghurt_vs_water.json", "zero_g_arena.json",
    "cup_and_planks.json",  "big_tank.json",     "yoghurt_dollop.json",   "sticky_plank.json",
    "yoghurt_or_water.json"};

TEST_CASE("every shipped level loads, and levels without a test of their own run 120 frames",
          "[level]") {
    const Registry& registry = builtins();
    std::vector<std::filesystem::path> files;
    for (const auto& entry : std::filesystem::directory_iterator(FLUID_LEVELS_DIR)) {
        if (entry.path().extension() == ".json") {
            files.push_back(entry.path());
        }
    }
    std::sort(files.begin(), files.end());
    REQUIRE(files.size() >= 3);
    for (const std::string_view name : kLevelsWithOwnTest) {
        CHECK(std::find(files.begin(), files.end(),
                        std::filesystem::path(FLUID_LEVELS_DIR) / std::string(name)) !=
              files.end());
    }
    for (const std::filesystem::path& file : files) {
        INFO(file.string());
        Level level = loadLevel(file.string(), registry);
        CHECK(level.file == file.string());
        CHECK(level.warnings.empty()); // no blob overlaps another
        CHECK_FALSE(level.name.empty());
        CHECK(level.world.particleCount() + level.world.emitterCount() > 0);
        const std::string name = file.filename().string();
        if (std::find(std::begin(kLevelsWithOwnTest), std::end(kLevelsWithOwnTest), name) !=
            std::end(kLevelsWithOwnTest)) {
            continue;
        }
        const double ms = run(level, 120);
        CHECK(test::allFinite(level.world));
        CHECK(level.world.time() == Approx(2.0).epsilon(1e-4));
        std::printf("[measure] level %s: %u particles after 120 frames, %.2f ms per frame\n",
                    name.c_str(), level.world.particleCount(), ms);
    }
}

TEST_CASE("dam_break.json: the column collapses along the floor, no particle lost or escaped",
          "[level]") {
    Level level = loadLevel(levelPath("dam_break.json"), builtins());
    CHECK(level.name == "Dam break");
    CHECK(level.frameRate == 60.0f);
    REQUIRE(level.materials.size() == 1);
    CHECK(level.materials[0].first == "water");
    // world.gravity adds force.gravity first, then the file's plugins follow.
    REQUIRE(level.world.forces().size() == 1);
    CHECK(level.world.forces()[0]->type() == "force.gravity");
    CHECK(level.world.forces()[0]->param("gy") == -9.81);
    REQUIRE(plugin(level, "gravity") != nullptr);
    const Level::PluginEntry* tank = plugin(level, "tank");
    REQUIRE(tank != nullptr);
    CHECK(tank->kind == PluginKind::Boundary);
    CHECK(level.world.boundaries()[tank->index]->param("maxX") == 0.6);
    CHECK(level.goalState() == GoalState::None);

    // A 0.15 m x 0.3 m block on water's lattice (spacing 0.0100265 m): 14 x 29 particles.
    const uint32_t count = level.world.particleCount();
    const float spacing = level.world.spacing(level.materials[0].second);
    CHECK(count == uint32_t(std::floor(0.15f / spacing) * std::floor(0.3f / spacing)));
    CHECK(count == 406);
    const double mass = test::totalMass(level.world);
    const test::Bounds before = test::bounds(level.world);
    const double ms = run(level, 120);
    std::printf("[measure] level dam_break.json: %u particles, %.2f ms per frame\n",
                level.world.particleCount(), ms);
    CHECK(test::allFinite(level.world));
    const test::Bounds after = test::bounds(level.world);
    std::printf("[measure] dam_break: front x %.3f -> %.3f m, top y %.3f -> %.3f m\n", before.x1,
                after.x1, before.y1, after.y1);
    CHECK(level.world.particleCount() == count);
    CHECK(test::totalMass(level.world) == Approx(mass).epsilon(1e-12));
    // After 2 s the surge has crossed the 0.6 m floor (a 0.3 m column runs at ~3 m/s) and the
    // column has fallen; every centre stays inside the tank.
    CHECK(after.x1 > 0.5f);
    CHECK(after.y1 < before.y1 - 0.1f);
    CHECK(test::countOutside(level.world, -1e-3f, -1e-3f, 0.601f, 0.501f) == 0);
}

TEST_CASE("zero_g_blobs.json: two materials in free fall keep their momentum", "[level]") {
    Level level = loadLevel(levelPath("zero_g_blobs.json"), builtins());
    REQUIRE(level.materials.size() == 2);
    CHECK(level.materials[1].first == "yoghurt");
    CHECK(level.world.material(level.materials[1].second).viscosity == yoghurt().viscosity);
    CHECK(level.world.forces().empty()); // no world.gravity: zero-g
    CHECK(level.world.boundaries().empty());
    const MaterialId water = level.materials[0].second;
    const MaterialId yog = level.materials[1].second;
    const uint32_t waterCount = countOf(level.world, water);
    const uint32_t yogCount = countOf(level.world, yog);
    CHECK(waterCount > 80);
    CHECK(yogCount > 80);
    const glm::dvec2 p0 = test::momentum(level.world);
    const double scale = test::totalMass(level.world) * 0.15;
    const double ms = run(level, 120);
    std::printf("[measure] level zero_g_blobs.json: %u particles, %.2f ms per frame\n",
                level.world.particleCount(), ms);
    CHECK(test::allFinite(level.world));
    const glm::dvec2 p1 = test::momentum(level.world);
    std::printf("[measure] zero_g_blobs: %u water + %u yoghurt, momentum (%.3e, %.3e) -> "
                "(%.3e, %.3e) kg m/s\n",
                waterCount, yogCount, p0.x, p0.y, p1.x, p1.y);
    CHECK(countOf(level.world, water) == waterCount);
    CHECK(countOf(level.world, yog) == yogCount);
    // No external force, no wall: only internal (pairwise) forces act.
    CHECK(std::abs(p1.x - p0.x) < 1e-3 * scale);
    CHECK(std::abs(p1.y - p0.y) < 1e-3 * scale);
    // The blobs met: the gap between them (0.06 m at the start) has closed.
    const test::Bounds w = test::bounds(level.world, water.index);
    const test::Bounds y = test::bounds(level.world, yog.index);
    CHECK(w.x1 + 0.011f >= y.x0);
}

TEST_CASE("fill_the_cup.json: the faucet fills the cup, the goal is won and stays won", "[level]") {
    const Registry& registry = builtins();
    Level level = loadLevel(levelPath("fill_the_cup.json"), registry);
    REQUIRE(level.emitters.size() == 1);
    CHECK(level.emitters[0].first == "faucet");
    REQUIRE(level.sensors.size() == 1);
    REQUIRE(level.drains.size() == 1);
    CHECK(level.goal.present);
    CHECK(level.goal.sensorName == "cup");
    CHECK(level.goal.measure == GoalMeasure::Fraction);
    CHECK(level.goal.amount == 0.8);
    CHECK(level.goal.timeLimit == 30.0);
    CHECK(level.goal.description == "Fill the cup to 80%");
    CHECK(level.world.particleCount() == 0);
    CHECK(level.goalState() == GoalState::Pending);
    CHECK(level.goalValue() == 0.0);

    // Steps frame by frame to count what the drain removes.
    const EmitterId faucet = level.emitters[0].second;
    uint32_t removed = 0;
    const auto stepCounting = [&] {
        level.step();
        removed += uint32_t(level.world.removedEvents().size());
    };
    for (int f = 0; f < 120; ++f) {
        stepCounting();
    }
    CHECK(test::allFinite(level.world));
    const double value2s = level.goalValue();
    std::printf("[measure] fill_the_cup: after 2 s %u emitted, %u in the world, cup %.1f%% full\n",
                level.world.emittedCount(faucet), level.world.particleCount(), 100.0 * value2s);
    CHECK(level.world.emittedCount(faucet) == 100); // 50 per second
    CHECK(value2s > 0.05);
    CHECK(level.goalState() == GoalState::Pending);

    int frames = 120;
    while (level.goalState() == GoalState::Pending && frames < 60 * 30) {
        stepCounting();
        ++frames;
    }
    std::printf("[measure] fill_the_cup: goal won after %.2f s (%d frames), cup %.1f%% full, "
                "%u drained\n",
                level.world.time(), frames, 100.0 * level.goalValue(), removed);
    REQUIRE(level.goalState() == GoalState::Won);
    CHECK(level.goalValue() >= 0.8);
    // Won is final, whatever the sensor reads later.
    for (int f = 0; f < 30; ++f) {
        stepCounting();
        CHECK(level.goalState() == GoalState::Won);
    }
    // Every emitted particle is in the world or was removed by the drain.
    CHECK(level.world.particleCount() + removed == level.world.emittedCount(faucet));
    CHECK(test::allFinite(level.world));
}

TEST_CASE("fill_the_cup.json with a short time limit is lost, and stays lost", "[level]") {
    std::string text = readText(levelPath("fill_the_cup.json"));
    const std::size_t at = text.find("\"timeLimit\": 30");
    REQUIRE(at != std::string::npos);
    text.replace(at, 15, "\"timeLimit\": 0.5");
    Level level = parseLevel(text, "short.json", builtins());
    CHECK(level.goal.timeLimit == 0.5);
    run(level, 29);
    CHECK(level.goalState() == GoalState::Pending);
    run(level, 1); // t = 0.5 s
    CHECK(level.goalState() == GoalState::Lost);
    // The cup fills later (the won level above needs about 4.7 s); the level stays lost.
    run(level, 60 * 5);
    CHECK(level.goalValue() >= 0.8);
    std::printf("[measure] fill_the_cup, 0.5 s limit: cup %.1f%% full at %.1f s, still lost\n",
                100.0 * level.goalValue(), level.world.time());
    CHECK(level.goalState() == GoalState::Lost);
}

TEST_CASE("planetoid.json: fluid falls onto the planet and stays outside it", "[level]") {
    const Registry& registry = builtins();
    if (registry.find("force.point_gravity") == nullptr ||
        registry.find("boundary.circle") == nullptr) {
        FAIL("planetoid.json needs force.point_gravity and boundary.circle");
    }
    Level level = loadLevel(levelPath("planetoid.json"), registry);
    CHECK(level.world.material(level.materials[1].second).viscosity == 15.0f);
    REQUIRE(plugin(level, "planet") != nullptr);
    REQUIRE(plugin(level, "pull") != nullptr);
    CHECK(level.world.forces().size() == 1);
    const auto meanRadius = [&] {
        double sum = 0.0;
        const auto px = level.world.positionX(), py = level.world.positionY();
        for (uint32_t i = 0; i < level.world.particleCount(); ++i) {
            sum += std::hypot(double(px[i]), double(py[i]));
        }
        return sum / level.world.particleCount();
    };
    const uint32_t count = level.world.particleCount();
    const double r0 = meanRadius();
    const double ms = run(level, 120);
    std::printf("[measure] level planetoid.json: %u particles, %.2f ms per frame\n",
                level.world.particleCount(), ms);
    CHECK(test::allFinite(level.world));
    const double r1 = meanRadius();
    double rMin = 1e9;
    const auto px = level.world.positionX(), py = level.world.positionY();
    for (uint32_t i = 0; i < level.world.particleCount(); ++i) {
        rMin = std::min(rMin, std::hypot(double(px[i]), double(py[i])));
    }
    std::printf("[measure] planetoid: mean radius %.3f -> %.3f m, closest %.4f m (planet 0.15)\n",
                r0, r1, rMin);
    CHECK(level.world.particleCount() == count);
    CHECK(r1 < r0 - 0.02);
    CHECK(rMin > 0.15 - 0.005);
}

TEST_CASE("the fuzz seed with every key of the format loads as written", "[level]") {
    const std::string path = std::string(FLUID_TEST_DATA_DIR) + "/../../fuzz/seeds/everything.json";
    Level level = loadLevel(path, builtins());
    const WorldDef& def = level.world.def();
    CHECK(def.solver == Solver::Explicit);
    CHECK(def.positionBased.vorticity == 0.1f);
    CHECK(def.positionBased.substeps == 4);
    CHECK(def.positionBased.iterations == 8);
    CHECK(def.positionBased.viscosityInterval == 2);
    CHECK(def.positionBased.coarseCorrection == 0.4f);
    CHECK(def.maxParticles == 5000);
    CHECK(def.depth == 0.1293f);
    REQUIRE(level.materials.size() == 2);
    CHECK(level.world.material(level.materials[0].second).name == "water");
    // gravity first, then the six forces in file order; four boundaries.
    REQUIRE(level.world.forces().size() == 7);
    CHECK(level.world.forces()[1]->type() == "force.point_gravity");
    CHECK(level.world.forces()[6]->type() == "force.damping");
    // Four boundaries of the file, then the Box2D coupling's.
    REQUIRE(level.world.boundaries().size() == 5);
    CHECK(level.world.boundaries()[4]->type() == "box2d.bodies");
    CHECK(level.world.boundaries()[1]->points("vertices").size() == 3);
    CHECK(level.world.boundaries()[2]->points("points")[1] == glm::vec2(0.3f, 0.4f));
    // Unnamed plugins are listed under their type.
    REQUIRE(level.plugins.size() == 11);
    CHECK(level.plugins[3].name == "boundary.chain");
    CHECK(level.plugins[3].kind == PluginKind::Boundary);
    CHECK(level.plugins[3].index == 2);
    const EmitterDef& faucet = level.world.emitter(level.emitters[0].second);
    CHECK(faucet.maxCount == 1000);
    CHECK(faucet.seed == 1);
    CHECK(faucet.jitter == 0.1f);
    REQUIRE(level.drains.size() == 2);
    CHECK(level.world.drain(level.drains[0].second).onlyMaterial);
    CHECK_FALSE(level.world.drain(level.drains[1].second).onlyMaterial);
    CHECK(level.goal.measure == GoalMeasure::Volume);
    CHECK(level.goal.amount == 0.001);
    CHECK(level.world.particleCount() > 100);
    // Three bodies (the third unnamed), one joint, the coupling's settings.
    REQUIRE(level.bodies.size() == 3);
    CHECK(level.bodies[2].first == "body2");
    CHECK(level.bodies[2].second->GetType() == b2_kinematicBody);
    REQUIRE(level.joints.size() == 1);
    CHECK(level.joints[0].first == "hinge");
    REQUIRE(level.coupling != nullptr);
    CHECK(level.coupling->def().velocityIterations == 8);
}

TEST_CASE("LevelOptions override the file's workers and cap its particles", "[level]") {
    const Registry& registry = builtins();
    LevelOptions options;
    options.workerCount = 2;
    options.maxParticles = 50000; // more than the file's 20000: the file's value stays
    Level level = loadLevel(levelPath("dam_break.json"), registry, options);
    CHECK(level.world.def().workerCount == 2);
    CHECK(level.world.def().maxParticles == 20000);

    options.maxParticles = 300; // the dam's 406 particles no longer fit
    try {
        loadLevel(levelPath("dam_break.json"), registry, options);
        FAIL("no error");
    } catch (const LevelError& e) {
        CHECK(e.path() == "/blobs/0");
        CHECK(e.message() == "the blob spans about 406 lattice points (spacing 0.010026513 m); "
                             "the world holds at most 300 particles (world.maxParticles)");
    }
}

TEST_CASE("a level names its quality preset, and explicit settings override its fields",
          "[level]") {
    const auto worldOf = [](const std::string& world) {
        return parseLevel(R"({"version": 1, "materials": [{"name": "w", "preset": "water"}], )"
                          R"("world": )" +
                              world + "}",
                          "t.json", builtins())
            .world.def()
            .positionBased;
    };
    const PositionBasedDef game = positionBasedPreset(Quality::Game);
    const PositionBasedDef precise = positionBasedPreset(Quality::Precise);
    const PositionBasedDef none = worldOf("{}");
    CHECK(none.substeps == WorldDef{}.positionBased.substeps);
    CHECK(none.iterations == WorldDef{}.positionBased.iterations);
    const PositionBasedDef g = worldOf(R"({"quality": "game"})");
    CHECK(g.substeps == game.substeps);
    CHECK(g.iterations == game.iterations);
    CHECK(g.viscosityInterval == game.viscosityInterval);
    CHECK(g.coarseCorrection == game.coarseCorrection);
    const PositionBasedDef p = worldOf(R"({"quality": "precise"})");
    CHECK(p.substeps == precise.substeps);
    CHECK(p.iterations == precise.iterations);
    CHECK(p.viscosityInterval == precise.viscosityInterval);
    const PositionBasedDef o = worldOf(R"({"quality": "game", "iterations": 5})");
    CHECK(o.substeps == game.substeps);
    CHECK(o.iterations == 5);
    CHECK(o.viscosityInterval == game.viscosityInterval);
}

TEST_CASE("an emitter whose nozzle lies outside the container or inside a solid is named in a "
          "warning, and what it cannot place is counted as skipped",
          "[level]") {
    const std::string text = R"({
  "version": 1,
  "world": { "gravity": [0, -9.81] },
  "materials": [ { "name": "water", "preset": "water" } ],
  "plugins": [ { "type": "boundary.box", "name": "tank", "params": { "minX": 0, "maxX": 0.3, "maxY": 0.3 } },
               { "type": "boundary.circle", "name": "pipe", "params": { "x": 0.15, "y": 0.1, "radius": 0.05 } } ],
  "emitters": [
    { "name": "out", "material": "water", "position": [0.5, 0.5], "speed": 1.5, "rate": 500 },
    { "name": "in", "material": "water", "position": [0.15, 0.1], "direction": [0, 1], "speed": 0.5, "rate": 200 },
    { "name": "fine", "material": "water", "position": [0.15, 0.25], "speed": 1.5, "rate": 500 }
  ]
})";
    Level level = parseLevel(text, "t.json", builtins());
    REQUIRE(level.warnings.size() == 2);
    CHECK(level.warnings[0] ==
          "t.json:8:5: at /emitters/0: the emitter's nozzle [0.5, 0.5] lies inside a solid or "
          "outside the container of plugin \"tank\": it places no particle there (counted as "
          "skipped)");
    CHECK(level.warnings[1] ==
          "t.json:9:5: at /emitters/1: the emitter's nozzle [0.15, 0.1] lies inside a solid or "
          "outside the container of plugin \"pipe\": it places no particle there (counted as "
          "skipped)");
    uint32_t skipped = 0;
    for (int f = 0; f < 60; ++f) {
        level.step();
        skipped += level.world.profile().emitSkipped;
    }
    // Only "fine" places particles: all of them in the tank and out of the pipe.
    CHECK(skipped >= 690); // one second of "out" (500) and "in" (200), less a row
    CHECK(level.world.particleCount() > 400);
    CHECK(level.world.particleCount() <= 510);
    CHECK(test::countOutside(level.world, 0.0f, 0.0f, 0.3f, 0.3f) == 0);
}

TEST_CASE("blobs leave out what lies inside bodies and solid plugins, with a warning",
          "[level]") {
    const std::string text = R"({
  "version": 1,
  "world": { "gravity": [0, -9.81] },
  "materials": [ { "name": "water", "preset": "water" } ],
  "plugins": [ { "type": "boundary.box", "params": { "minX": 0, "maxX": 1, "maxY": 1 } },
               { "type": "boundary.circle", "params": { "x": 0.7, "y": 0.1, "radius": 0.05 } } ],
  "bodies": [ { "name": "crate", "position": [0.2, 0.1],
                "fixtures": [ { "shape": "box", "width": 0.1, "height": 0.1, "densityRatio": 0.5 } ] } ],
  "blobs": [
    { "material": "water", "shape": "box", "min": [0, 0], "max": [0.9, 0.2] }
  ]
})";
    Level level = parseLevel(text, "t.json", builtins());
    // The crate stands in a boundary.box tank with nothing in Box2D to hold it: warned too.
    REQUIRE(level.warnings.size() == 2);
    CHECK(level.warnings[0] ==
          "t.json:7:15: at /bodies/0: body 'crate' is dynamic, but no static or kinematic body "
          "stands in Box2D: the boundary plugins (boundary.box 'boundary.box', boundary.circle "
          "'boundary.circle') hold the fluid only, and the body passes through them; add a "
          "static body with \"fluid\": false along the walls (docs/levels.md, \"Bodies\")");
    CHECK_THAT(level.warnings[1],
               Catch::StartsWith("t.json:10:5: at /blobs/0: ") &&
                   Catch::EndsWith(" lattice points lie inside solids (plugins or bodies) or "
                                   "outside the container and were left out"));
    // No particle inside the crate or the disc.
    for (uint32_t i = 0; i < level.world.particleCount(); ++i) {
        const float x = level.world.positionX()[i], y = level.world.positionY()[i];
        CHECK_FALSE((std::fabs(x - 0.2f) < 0.05f && std::fabs(y - 0.1f) < 0.05f));
        CHECK((x - 0.7f) * (x - 0.7f) + (y - 0.1f) * (y - 0.1f) >= 0.05f * 0.05f);
    }
    // Nothing is thrown out at the first frames (free fall alone reaches 0.8 m/s).
    float fastest = 0.0f;
    for (int f = 0; f < 5; ++f) {
        level.step();
        for (uint32_t i = 0; i < level.world.particleCount(); ++i) {
            fastest = std::max(fastest, std::hypot(level.world.velocityX()[i],
                                                   level.world.velocityY()[i]));
        }
    }
    CHECK(fastest < 1.5f);

    // A blob wholly inside the crate is an error.
    const std::string buried = R"({
  "version": 1,
  "materials": [ { "name": "water", "preset": "water" } ],
  "bodies": [ { "name": "crate", "position": [0.2, 0.1],
                "fixtures": [ { "shape": "box", "width": 0.2, "height": 0.2, "densityRatio": 0.5 } ] } ],
  "blobs": [ { "material": "water", "shape": "box", "min": [0.15, 0.05], "max": [0.25, 0.15] } ]
})";
    std::string buriedError = "no error";
    try {
        parseLevel(buried, "t.json", builtins());
    } catch (const LevelError& e) {
        buriedError = e.what();
    }
    CHECK_THAT(buriedError,
               Catch::StartsWith("t.json:6:14: at /blobs/0: the blob holds no particle: all of "
                                 "its ") &&
                   Catch::EndsWith(" lattice points lie inside solids (plugins or bodies) or "
                                   "outside the container"));
}

TEST_CASE("blobs that overlap load with a warning naming the blob, the file, line and column",
          "[level]") {
    const std::string text = R"({
  "version": 1,
  "materials": [ { "name": "water", "preset": "water" } ],
  "blobs": [
    { "material": "water", "shape": "box", "min": [0, 0], "max": [0.1, 0.1] },
    { "material": "water", "shape": "box", "min": [0.2, 0], "max": [0.3, 0.1] },
    { "material": "water", "shape": "box", "min": [0.05, 0], "max": [0.25, 0.1] }
  ]
})";
    const Level level = parseLevel(text, "t.json", builtins());
    const float s = level.world.spacing(MaterialId{0});
    INFO("spacing " << s);
    // The third blob covers half of each of the others.
    REQUIRE(level.warnings.size() == 2);
    CHECK_THAT(level.warnings[0],
               Catch::StartsWith("t.json:7:5: at /blobs/2: ") &&
                   Catch::Contains("particles lie inside blob 0 (closer than 0.8 lattice spacings "
                                   "to its particles): the liquid there starts at about twice its "
                                   "rest density and bursts apart; move or shrink one of them"));
    CHECK_THAT(level.warnings[1], Catch::StartsWith("t.json:7:5: at /blobs/2: ") &&
                                      Catch::Contains("inside blob 1 ("));
    // A circle over a box's edge, on a lattice offset from the box's: its particles inside
    // the box are counted, those outside are not.
    const std::string circle = R"({
  "version": 1,
  "materials": [ { "name": "water", "preset": "water" } ],
  "blobs": [
    { "material": "water", "shape": "box", "min": [0, 0], "max": [0.1, 0.1] },
    { "material": "water", "shape": "circle", "center": [0.1, 0.05], "radius": 0.04 }
  ]
})";
    const Level overlapping = parseLevel(circle, "t.json", builtins());
    REQUIRE(overlapping.warnings.size() == 1);
    CHECK_THAT(overlapping.warnings[0], Catch::StartsWith("t.json:6:5: at /blobs/1: ") &&
                                            Catch::Contains(" of the blob's 45 particles"));
    // Blobs side by side, touching or a spacing apart, warn of nothing.
    for (const char* second : {"[0.1, 0]", "[0.11, 0]"}) {
        INFO(second);
        const std::string apart = std::string(R"({
  "version": 1,
  "materials": [ { "name": "water", "preset": "water" } ],
  "blobs": [
    { "material": "water", "shape": "box", "min": [0, 0], "max": [0.1, 0.1] },
    { "material": "water", "shape": "box", "min": )") + second + R"(, "max": [0.2, 0.1] }
  ]
})";
        CHECK(parseLevel(apart, "t.json", builtins()).warnings.empty());
    }
}

TEST_CASE("the seed_yoghurt preset is Table 4.1's yoghurt, which the explicit solver pours",
          "[level]") {
    Level level = parseLevel(
        R"({"version": 1, "world": {"solver": "explicit", "maxParticles": 2000},
            "materials": [{"name": "y", "preset": "seed_yoghurt"}],
            "plugins": [{"type": "boundary.box", "name": "tank",
                         "params": {"minX": 0, "minY": 0, "maxX": 0.6, "maxY": 0.5}}],
            "blobs": [{"material": "y", "shape": "box", "min": [0, 0], "max": [0.1, 0.2]}]})",
        "t.json", builtins());
    const Material& m = level.world.material(level.materials[0].second);
    CHECK(m.name == "y");
    CHECK(m.viscosity == seedYoghurt().viscosity);
    CHECK_FALSE(hasYield(m));
    const uint32_t count = level.world.particleCount();
    REQUIRE(count > 100);
    const auto top = [&] {
        const auto y = level.world.positionY();
        return *std::max_element(y.begin(), y.begin() + level.world.particleCount());
    };
    const float before = top();
    for (int f = 0; f < 180; ++f) {
        level.step();
    }
    std::printf("[measure] seed_yoghurt column top: %.4f m -> %.4f m in 3 s\n", before, top());
    // Three seconds: the 20 Pa s column slumps, and every particle stays in the tank.
    CHECK(level.world.particleCount() == count);
    CHECK(top() < before - 0.015f);
    const auto x = level.world.positionX(), y = level.world.positionY();
    for (uint32_t i = 0; i < count; ++i) {
        CHECK((x[i] >= 0.0f && x[i] <= 0.6f && y[i] >= 0.0f && y[i] <= 0.5f));
    }
}
