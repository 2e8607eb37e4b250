// fluid tests — the levels written for fluid-demo and its playlist: levels/playlist.txt names
// existing levels in the demo's order; yoghurt_vs_water.json shows the viscosity contrast;
// zero_g_arena.json has no net force but its walls, and its blobs meet; cup_and_planks.json is
// lost with the planks where the file puts them and won with them moved into a slide;
// big_tank.json (the stress level) stays in its tank with a sane compression; the yield-stress
// levels: yoghurt_dollop.json heaps yoghurt on a table water runs off, sticky_plank.json's
// yoghurt clings to its tilted plank until shaken off, yoghurt_or_water.json's water runs down a
// chute the yoghurt sticks to until pushed. Short runs:
// fluid-tests-level is a fast executable (each case takes well under 5 s in Release).
#include <catch2/catch.hpp>

#include "compression.h"
#include "level_support.h"
#include "test_support.h"

#include <fluid/level.h>
#include <fluid/plugins/pointer.h>

#include <box2d/box2d.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

using namespace fluid;
using namespace fluid::test;

namespace {

std::string shippedLevel(const std::string& stem) {
    return std::string(FLUID_LEVELS_DIR) + "/" + stem + ".json";
}

// The level's material named `name`; fails the test when there is none.
MaterialId requireMaterial(const Level& level, std::string_view name) {
    for (const auto& [n, id] : level.materials) {
        if (n == name) {
            return id;
        }
    }
    FAIL("no material " << name);
    return {};
}

// The level's plugin named `name`; fails the test when there is none.
const Level::PluginEntry& requirePlugin(const Level& level, std::string_view name) {
    for (const Level::PluginEntry& p : level.plugins) {
        if (p.name == name) {
            return p;
        }
    }
    FAIL("no plugin " << name);
    return level.plugins.front();
}

// Mass-weighted centre of the particles (unit: m), in double.
glm::dvec2 centreOfMass(const World& world) {
    const auto px = world.positionX(), py = world.positionY();
    const auto mat = world.materialIndex();
    glm::dvec2 sum{0.0, 0.0};
    double mass = 0.0;
    for (uint32_t i = 0; i < world.particleCount(); ++i) {
        const double m = world.material(MaterialId{mat[i]}).mass;
        sum += m * glm::dvec2(px[i], py[i]);
        mass += m;
    }
    return sum / mass;
}

// Smallest distance between a particle of material `a` and one of material `b` (unit: m).
double closestPair(const World& world, MaterialId a, MaterialId b) {
    const auto px = world.positionX(), py = world.positionY();
    const auto mat = world.materialIndex();
    std::vector<glm::dvec2> pa, pb;
    for (uint32_t i = 0; i < world.particleCount(); ++i) {
        if (mat[i] == a.index) {
            pa.emplace_back(px[i], py[i]);
        } else if (mat[i] == b.index) {
            pb.emplace_back(px[i], py[i]);
        }
    }
    double best = INFINITY;
    for (const glm::dvec2& p : pa) {
        for (const glm::dvec2& q : pb) {
            best = std::min(best, std::hypot(p.x - q.x, p.y - q.y));
        }
    }
    return best;
}

// The stems of levels/playlist.txt in order: '#' starts a comment, blank lines are skipped.
std::vector<std::string> readPlaylist() {
    std::ifstream in(std::string(FLUID_LEVELS_DIR) + "/playlist.txt");
    REQUIRE(in);
    std::vector<std::string> stems;
    std::string line;
    while (std::getline(in, line)) {
        line = line.substr(0, line.find('#'));
        const auto first = line.find_first_not_of(" \t\r");
        if (first == std::string::npos) {
            continue;
        }
        const auto last = line.find_last_not_of(" \t\r");
        stems.push_back(line.substr(first, last - first + 1));
    }
    return stems;
}

} // namespace

TEST_CASE("playlist.txt: the demo's levels exist, none twice, the first seven in order",
          "[level][demo]") {
    const std::vector<std::string> stems = readPlaylist();
    const std::vector<std::string> first = {"dam_break", "yoghurt_vs_water", "zero_g_arena",
                                            "crates",    "planetoid",        "cup_and_planks",
                                            "big_tank"};
    REQUIRE(stems.size() >= first.size());
    CHECK(std::equal(first.begin(), first.end(), stems.begin()));
    std::vector<std::string> sorted = stems;
    std::sort(sorted.begin(), sorted.end());
    CHECK(std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end());
    for (const std::string& stem : stems) {
        INFO(stem);
        CHECK(stem.find_first_of(" \t/.") == std::string::npos);
        REQUIRE(std::filesystem::is_regular_file(shippedLevel(stem)));
        // The demo shows the title and the text: each level has both.
        const Level level = loadLevel(shippedLevel(stem), builtins());
        CHECK_FALSE(level.name.empty());
        CHECK_FALSE(level.description.empty());
    }
    std::printf("[measure] playlist.txt: %zu levels\n", stems.size());
}

TEST_CASE("yoghurt_vs_water.json: the water front runs ahead of the yoghurt's, each in its tank",
          "[level][demo][slow]") {
    Level level = loadLevel(shippedLevel("yoghurt_vs_water"), builtins());
    const MaterialId water = requireMaterial(level, "water");
    const MaterialId yog = requireMaterial(level, "yoghurt");
    CHECK(level.world.material(yog).viscosity > 5.0f * level.world.material(water).viscosity);
    requirePlugin(level, "divider");
    // Two equal columns, 0.15 m x 0.3 m, at the left wall of each half: water in [0, 0.75],
    // yoghurt in [0.77, 1.52] (the divider fills [0.75, 0.77]).
    const uint32_t nWater = countOf(level.world, water), nYog = countOf(level.world, yog);
    CHECK(nWater > 300);
    CHECK(nYog > 300);
    const float waterWall = 0.75f, yogStart = 0.77f, yogWall = 1.52f;
    const Bounds w0 = bounds(level.world, water.index);
    const Bounds y0 = bounds(level.world, yog.index);
    // The same column: the fronts start one column width from their wall.
    CHECK(std::abs(w0.x1 - (y0.x1 - yogStart)) < 0.005f);

    // Every frame for 2 s: nothing crosses the divider or leaves the tank. At 0.5 s the water
    // front has crossed its 0.75 m floor; the yoghurt's is about two thirds of the way
    // (measured 0.61 m vs 0.38 m of run with both presets).
    const auto contained = [&] {
        const Bounds w = bounds(level.world, water.index), y = bounds(level.world, yog.index);
        return countOutside(level.world, -1e-3f, -1e-3f, 1.521f, 0.501f) == 0 &&
               w.x1 <= waterWall + 1e-3f && y.x0 >= yogStart - 1e-3f;
    };
    double ms = 0.0;
    for (int f = 0; f < 30; ++f) {
        ms += playFrames(level, 1);
        REQUIRE(contained());
    }
    const Bounds w = bounds(level.world, water.index), y = bounds(level.world, yog.index);
    const float waterRun = w.x1 - w0.x1, yogRun = y.x1 - y0.x1;
    std::printf("[measure] yoghurt_vs_water after 0.5 s: water front %.3f m (ran %.3f m), "
                "yoghurt front %.3f m from its wall (ran %.3f m); %u + %u particles, %.2f ms "
                "per frame\n",
                w.x1, waterRun, y.x1 - yogStart, yogRun, nWater, nYog, ms / 30);
    CHECK(waterRun > yogRun + 0.1f);
    CHECK(w.x1 > waterWall - 0.05f); // water reached its far wall
    CHECK(y.x1 < yogWall - 0.1f);    // yoghurt is still on its way
    for (int f = 30; f < 120; ++f) {
        playFrames(level, 1);
        REQUIRE(contained());
    }
    CHECK(test::allFinite(level.world));
    CHECK(countOf(level.world, water) == nWater);
    CHECK(countOf(level.world, yog) == nYog);
}

TEST_CASE("zero_g_arena.json: blobs meet without gravity, none leaves, gravity pulls them down",
          "[level][demo][slow]") {
    Level level = loadLevel(shippedLevel("zero_g_arena"), builtins());
    const MaterialId water = requireMaterial(level, "water");
    const MaterialId yog = requireMaterial(level, "yoghurt");
    // world.gravity [0, 0]: the force.gravity plugin is there for the demo to turn on.
    const Level::PluginEntry& gravity = requirePlugin(level, "gravity");
    REQUIRE(gravity.kind == PluginKind::Force);
    ForcePlugin& g = *level.world.forces()[gravity.index];
    CHECK(g.type() == "force.gravity");
    CHECK(g.param("gx") == 0.0);
    CHECK(g.param("gy") == 0.0);
    CHECK(level.physics == nullptr);
    const float x0 = -0.5f, y0 = -0.35f, x1 = 0.5f, y1 = 0.35f; // the arena's walls
    const float s = level.world.spacing(water);

    const double mass = totalMass(level.world);
    const glm::dvec2 p0 = momentum(level.world);
    const glm::dvec2 c0 = centreOfMass(level.world);
    const double gap0 = closestPair(level.world, water, yog);
    CHECK(gap0 > 0.1);
    int contactFrame = -1;
    glm::dvec2 drift1{0.0, 0.0};
    double ms = 0.0;
    const int frames = 150; // 2 s
    for (int f = 1; f <= frames; ++f) {
        ms += playFrames(level, 1);
        REQUIRE(countOutside(level.world, x0, y0, x1, y1) == 0);
        if (contactFrame < 0 && closestPair(level.world, water, yog) < 1.5 * s) {
            contactFrame = f;
        }
        if (f == 90) {
            // 1.5 s: no blob has reached a wall yet, so only internal forces have acted: the
            // centre of mass has moved by the initial momentum alone (gravity would have
            // dropped it by 11 m, i.e. onto the floor).
            const glm::dvec2 expected = c0 + p0 / mass * level.world.time();
            drift1 = centreOfMass(level.world) - expected;
            const Bounds b = bounds(level.world);
            CHECK(b.x0 > x0 + 0.1f);
            CHECK(b.x1 < x1 - 0.1f);
            CHECK(b.y0 > y0 + 0.05f);
            CHECK(b.y1 < y1 - 0.05f);
        }
    }
    CHECK(test::allFinite(level.world));
    std::printf("[measure] zero_g_arena: %u particles, water-yoghurt gap %.3f m at 0 s; contact "
                "(< 1.5 spacings) at frame %d (%.2f s); centre of mass off the momentum's line "
                "by (%.1e, %.1e) m at 1.5 s; %.2f ms per frame\n",
                level.world.particleCount(), gap0, contactFrame, contactFrame / 60.0, drift1.x,
                drift1.y, ms / frames);
    REQUIRE(contactFrame > 0);
    CHECK(contactFrame <= 75); // within 1.25 s (measured about 0.9 s)
    CHECK(std::abs(drift1.x) < 2e-3);
    CHECK(std::abs(drift1.y) < 2e-3);

    // The demo's G key: gravity on pulls the centre of mass down, the walls still hold.
    const double cy = centreOfMass(level.world).y;
    g.setParam("gy", -9.81);
    playFrames(level, 30);
    const double fall = cy - centreOfMass(level.world).y;
    std::printf("[measure] zero_g_arena with gravity on: centre of mass fell %.3f m in 0.5 s\n",
                fall);
    CHECK(fall > 0.1);
    CHECK(countOutside(level.world, x0, y0, x1, y1) == 0);
}

namespace {

// Plays a cup_and_planks level until the goal is decided (or `maxFrames`); counts what the
// drain removed and the most particles the world held.
struct CupRun {
    int frames = 0;
    uint32_t removed = 0;
    uint32_t peak = 0;
    double ms = 0.0;
};

CupRun playCup(Level& level, int maxFrames) {
    CupRun r;
    const auto t0 = std::chrono::steady_clock::now();
    while (level.goalState() == GoalState::Pending && r.frames < maxFrames) {
        level.step();
        ++r.frames;
        // With bodies a frame is several world steps (one per sub-step, see Coupling::step)
        // and World::removedEvents holds the last one's only: the coupling's profile sums them.
        r.removed +=
            level.coupling ? level.coupling->profile().removed : level.world.profile().removed;
        r.peak = std::max(r.peak, level.world.particleCount());
    }
    r.ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count() /
        std::max(r.frames, 1);
    return r;
}

} // namespace

TEST_CASE("cup_and_planks.json: lost with the planks where they hang, won with a slide",
          "[level][demo][bodies][slow]") {
    const Registry& registry = builtins();
    const char* planks[] = {"plank1", "plank2", "plank3"};

    SECTION("as loaded: the stream misses the cup, the minute runs out, the level is lost") {
        Level level = loadLevel(shippedLevel("cup_and_planks"), registry);
        REQUIRE(level.goal.present);
        CHECK(level.goal.amount == 0.8);
        CHECK(level.goal.timeLimit == 60.0);
        CHECK(level.goal.description.find("shift") != std::string::npos);
        REQUIRE(level.emitters.size() == 1);
        REQUIRE(level.bodies.size() == 3);
        for (const char* name : planks) {
            INFO(name);
            b2Body* body = bodyNamed(level, name);
            REQUIRE(body != nullptr);
            CHECK(body->GetType() == b2_kinematicBody);
            // One 0.28 m x 0.02 m box (a kinematic body has no mass).
            const b2Fixture* fixture = body->GetFixtureList();
            REQUIRE(fixture != nullptr);
            CHECK(fixture->GetNext() == nullptr);
            REQUIRE(fixture->GetType() == b2Shape::e_polygon);
            const auto* box = static_cast<const b2PolygonShape*>(fixture->GetShape());
            float w = 0.0f, h = 0.0f;
            for (int i = 0; i < box->m_count; ++i) {
                w = std::max(w, 2.0f * std::abs(box->m_vertices[i].x));
                h = std::max(h, 2.0f * std::abs(box->m_vertices[i].y));
            }
            CHECK(w == Approx(0.28f).margin(1e-5));
            CHECK(h == Approx(0.02f).margin(1e-5));
        }
        const b2Vec2 plank1 = bodyNamed(level, "plank1")->GetPosition();
        const CupRun r = playCup(level, 60 * 61);
        const EmitterId faucet = level.emitters[0].second;
        std::printf("[measure] cup_and_planks as loaded: goal %s at %.2f s (%d frames), cup "
                    "%.1f%% full, %u emitted, %u drained, at most %u particles, %.2f ms per "
                    "frame\n",
                    level.goalState() == GoalState::Lost ? "lost" : "not lost", level.world.time(),
                    r.frames, 100.0 * level.goalValue(), level.world.emittedCount(faucet),
                    r.removed, r.peak, r.ms);
        REQUIRE(level.goalState() == GoalState::Lost);
        CHECK(level.world.time() == Approx(60.0).margin(1.0 / 60.0));
        CHECK(level.goalValue() < 0.8);
        // The drain keeps the count bounded: the stream in flight only.
        CHECK(r.peak < 200);
        CHECK(level.world.particleCount() + r.removed == level.world.emittedCount(faucet));
        CHECK(level.world.emittedCount(faucet) > 4000); // 80 per second for a minute
        // Kinematic planks nobody drags stay put.
        CHECK(bodyNamed(level, "plank1")->GetPosition() == plank1);
        CHECK(test::allFinite(level.world));
    }

    SECTION("the planks moved into a staircase slide: the cup fills before the time limit") {
        Level level = loadLevel(shippedLevel("cup_and_planks"), registry);
        // The slide a player would build: plank1 under the faucet (x = 0.1), each plank's low
        // end over the next one's high end, plank3's low end over the cup (inner x in
        // [0.77, 0.93]). The planks keep the file's tilt (-0.35 rad): the demo drags, it does
        // not turn.
        const float slide[3][2] = {{0.2f, 0.6f}, {0.44f, 0.5f}, {0.68f, 0.4f}};
        for (int i = 0; i < 3; ++i) {
            b2Body* body = bodyNamed(level, planks[i]);
            REQUIRE(body != nullptr);
            CHECK(body->GetAngle() == Approx(-0.35f));
            body->SetTransform(b2Vec2(slide[i][0], slide[i][1]), body->GetAngle());
        }
        const CupRun r = playCup(level, 60 * 61);
        std::printf("[measure] cup_and_planks with a slide: goal %s at %.2f s (%d frames), cup "
                    "%.1f%% full, %u particles, %.2f ms per frame\n",
                    level.goalState() == GoalState::Won ? "won" : "not won", level.world.time(),
                    r.frames, 100.0 * level.goalValue(), level.world.particleCount(), r.ms);
        REQUIRE(level.goalState() == GoalState::Won);
        CHECK(level.goalValue() >= 0.8);
        CHECK(level.world.time() < 15.0); // measured about 5.6 s: time to spare for the player
        CHECK(test::allFinite(level.world));
    }
}

namespace {

// What 150 frames of big_tank.json do (its column moved right by `dx`, unit: m).
struct BigTankRun {
    uint32_t count = 0;     // particles
    uint32_t workers = 0;   // the world's worker threads
    uint32_t outside = 0;   // particles outside the tank, most in any frame
    double worst = 0.0;     // largest compression (1), from the positions
    double ms = 0.0;        // per frame
    float reach = 0.0f;     // farthest x (m) any particle reached
    Bounds before, after;
    bool finite = false;
};

// big_tank.json with its column moved right by `dx` (m), played 150 frames. The largest
// compression is one particle's where the column's surge meets a wall, and it moves with the
// column's place as much as with any change of the solver's bits: the test reads it at eight
// places 0.5 mm apart (docs/levels.md, "Which preset each level runs").
BigTankRun playBigTank(double dx) {
    const std::string text = readLevel("big_tank.json");
    const std::string column = R"("min": [0.5, 0], "max": [0.86, 0.70])";
    const size_t at = text.find(column);
    REQUIRE(at != std::string::npos);
    char moved[96];
    std::snprintf(moved, sizeof moved, R"("min": [%.4f, 0], "max": [%.4f, 0.70])", 0.5 + dx,
                  0.86 + dx);
    LevelOptions options;
    options.workerCount = physicsWorkers(); // results do not depend on it
    Level level = parseLevel(text.substr(0, at) + moved + text.substr(at + column.size()),
                             "big_tank.json", builtins(), options);
    BigTankRun r;
    r.count = level.world.particleCount();
    r.workers = level.world.def().workerCount;
    r.before = bounds(level.world);
    // Compression from the positions alone (bench/compression.h, as the preset tests read it):
    // the solver's own reading (Profile::densityErrorMax) is taken before the game preset's
    // coarse correction and single sweep are done with a sub-step, so it reads about twice
    // the positions' figure at rest (docs/position_based.md, "Which preset").
    bench::CompressionMeter meter(level.world.spacing(MaterialId{0}));
    const int frames = 150;
    for (int f = 0; f < frames; ++f) {
        r.ms += playFrames(level, 1);
        r.outside =
            std::max(r.outside, countOutside(level.world, -1e-3f, -1e-3f, 2.401f, 1.201f));
        r.worst =
            std::max(r.worst, meter.measure(level.world.positionX(), level.world.positionY()).max);
        r.reach = std::max(r.reach, bounds(level.world).x1);
    }
    r.ms /= frames;
    r.after = bounds(level.world);
    r.finite = test::allFinite(level.world);
    CHECK(level.world.particleCount() == r.count);
    return r;
}

} // namespace

TEST_CASE("big_tank.json: the stress level's particles stay in the tank, sanely compressed",
          "[level][demo][slow]") {
    // The shipped column, then moved right by 0.5 to 3.5 mm: at every place the particles stay
    // in the tank and the largest compression stays under 15%, which the level's 6 sub-steps a
    // frame hold (figures: docs/levels.md, "Which preset each level runs").
    for (int k = 0; k < 8; ++k) {
        const double dx = 0.0005 * k;
        const BigTankRun r = playBigTank(dx);
        std::printf("[measure] big_tank, column moved %.1f mm: %u particles, 150 frames with %u "
                    "workers, %.2f ms per frame, largest compression %.1f%%, extent x [%.2f, "
                    "%.2f] -> [%.2f, %.2f] m, reach %.2f m\n",
                    1000.0 * dx, r.count, r.workers, r.ms, 100.0 * r.worst, r.before.x0,
                    r.before.x1, r.after.x0, r.after.x1, r.reach);
        CAPTURE(dx);
        CHECK(r.outside == 0);
        CHECK(r.finite);
        CHECK(r.worst < 0.15);
        // The column broke both ways: the surge reached both walls within 2.5 s.
        CHECK(r.after.x0 < 0.05f);
        CHECK(r.reach > 2.2f); // within 0.2 m of the far wall (the surge of 960 particles is low)
        if (k == 0) {
            // The count is what keeps 60 fps in the demo (docs/demo.md), measured, not a
            // target here: at least the seed's 900, at most the fuzz target's cap.
            CHECK(r.count >= 900);
            CHECK(r.count <= 20000);
        }
    }
}

// Not run by ctest (hidden): the largest compression at the test's eight places, for
// scripts/readings.sh (the same runs as the test above).
TEST_CASE("readings: big_tank.json's largest compression at eight placements of its column",
          "[.readings]") {
    for (int k = 0; k < 8; ++k) {
        const double dx = 0.0005 * k;
        std::printf("[reading] big-tank/shift=%.1fmm/largest-compression %.2f%%\n", 1000.0 * dx,
                    100.0 * playBigTank(dx).worst);
    }
}

namespace {

// Particles of `material` inside the box [x0, x1] x [y0, y1] (unit: m).
uint32_t countIn(const World& world, MaterialId material, float x0, float y0, float x1, float y1) {
    const auto px = world.positionX(), py = world.positionY();
    const auto mat = world.materialIndex();
    uint32_t n = 0;
    for (uint32_t i = 0; i < world.particleCount(); ++i) {
        n += mat[i] == material.index && px[i] >= x0 && px[i] <= x1 && py[i] >= y0 && py[i] <= y1
                 ? 1
                 : 0;
    }
    return n;
}

// The demo's pointer as its left drag makes it (demo/session.cpp): a force.pointer of 40 m/s^2
// pushing away from the cursor, of radius 0.12 x the view's size, which is the level's box
// `size` (m) and the walls drawn 4% of it thick on each side.
PointerForce& addDemoPointer(Level& level, const Registry& registry, double size) {
    const std::array<ParamValue, 2> params{{{"radius", 0.12 * 1.08 * size}, {"strength", 40.0}}};
    return static_cast<PointerForce&>(
        level.world.addForce(registry.createForce(PointerForce::kType, params)));
}

} // namespace

TEST_CASE("yoghurt_dollop.json: poured beside their tables, water and yoghurt miss them, and "
          "pushed onto its table the yoghurt heaps there",
          "[level][demo][yield][slow]") {
    const Registry& registry = builtins();
    Level level = loadLevel(shippedLevel("yoghurt_dollop"), registry);
    const MaterialId water = requireMaterial(level, "water");
    const MaterialId yog = requireMaterial(level, "yoghurt");
    CHECK(level.world.material(yog).yieldStress == 400.0f); // the preset
    CHECK(level.world.material(water).yieldStress == 0.0f);
    REQUIRE(level.emitters.size() == 2);
    REQUIRE(level.goal.present);
    // Two spouts pour 160 particles each beside equal tables (tops 0.3 m wide at y = 0.12 m,
    // from x = 0.225 and 0.995 m, on stems at 0.355-0.395 and 1.125-1.165 m), 6.5 cm left of
    // their left edges; the goal wants 60% of the 5 cm over the yoghurt's table.
    const auto waterOn = [&] { return countIn(level.world, water, 0.225f, 0.12f, 0.525f, 0.17f); };
    const auto yogOn = [&] { return countIn(level.world, yog, 0.995f, 0.12f, 1.295f, 0.17f); };

    SECTION("left alone, both land on the floor: the water spreads flat, the yoghurt heaps") {
        playFrames(level, 60 * 21);
        const Bounds w = bounds(level.world, water.index), y = bounds(level.world, yog.index);
        std::printf("[measure] yoghurt_dollop left alone, 21 s: %u water and %u yoghurt "
                    "particles on the tables; tops %.3f m (water) and %.3f m (yoghurt); spread "
                    "%.3f m and %.3f m; goal %s\n",
                    waterOn(), yogOn(), w.y1, y.y1, w.x1 - w.x0, y.x1 - y.x0,
                    level.goalState() == GoalState::Lost ? "lost" : "not lost");
        CHECK(countOf(level.world, water) == 160);
        CHECK(countOf(level.world, yog) == 160);
        CHECK(level.goalState() == GoalState::Lost);
        // The water flat from the wall to the stem, the yoghurt heaped beside its table (the
        // figures: docs/levels.md, after the level table).
        CHECK(yogOn() <= 10);
        CHECK(w.x0 < 0.01f);
        CHECK(w.x1 > 0.34f); // from the wall to the stem
        CHECK(w.y1 < 0.06f);
        CHECK(y.x1 - y.x0 < 0.35f); // a heap between the divider and the stem
        CHECK(y.y1 > w.y1 + 0.05f);
        CHECK(test::allFinite(level.world));
    }

    SECTION("the yoghurt's stream pushed onto its table (left drag) heaps there") {
        // The demo's left drag held at (0.86, 0.14), 7 cm left of the stream and 2 cm over the
        // table, for the 3 s the spout pours; the aim matters to about 2 cm (docs/levels.md).
        PointerForce& pointer = addDemoPointer(level, registry, 1.52);
        double wonAt = -1.0;
        for (int f = 1; f <= 60 * 6; ++f) {
            pointer.setPointer({0.86f, 0.14f}, f <= 180 ? 1.0f : 0.0f);
            level.step();
            if (wonAt < 0.0 && level.goalState() == GoalState::Won) {
                wonAt = level.world.time();
            }
        }
        const Bounds w = bounds(level.world, water.index), y = bounds(level.world, yog.index);
        std::printf("[measure] yoghurt_dollop pushed, 6 s: %u water and %u yoghurt particles on "
                    "the tables; tops %.3f m (water) and %.3f m (yoghurt); goal won at %.2f s\n",
                    waterOn(), yogOn(), w.y1, y.y1, wonAt);
        CHECK(level.goalState() == GoalState::Won);
        CHECK(wonAt < 4.0);
        CHECK(yogOn() >= 100);
        CHECK(y.y1 > 0.17f); // a mound over the goal's band
        CHECK(test::allFinite(level.world));
    }

    SECTION("the water's stream pushed the same way does not stay on its table") {
        // The cursor as far left of the water's stream and as high (0.11, 0.14) for 3 s.
        PointerForce& pointer = addDemoPointer(level, registry, 1.52);
        uint32_t most = 0;
        for (int f = 1; f <= 60 * 6; ++f) {
            pointer.setPointer({0.11f, 0.14f}, f <= 180 ? 1.0f : 0.0f);
            level.step();
            most = std::max(most, waterOn());
        }
        std::printf("[measure] yoghurt_dollop, the water pushed: at most %u on its table, %u "
                    "after 6 s\n",
                    most, waterOn());
        CHECK(most < 20);
        CHECK(waterOn() < 10);
        CHECK(test::allFinite(level.world));
    }
}

TEST_CASE("sticky_plank.json: the yoghurt clings to the tilted plank, carried and shaken it "
          "falls into the bowl",
          "[level][demo][bodies][yield][slow]") {
    const Registry& registry = builtins();
    Level level = loadLevel(shippedLevel("sticky_plank"), registry);
    const MaterialId yog = requireMaterial(level, "yoghurt");
    CHECK(level.world.material(yog).yieldStress == 400.0f); // the preset
    b2Body* plank = bodyNamed(level, "plank");
    REQUIRE(plank != nullptr);
    CHECK(plank->GetType() == b2_kinematicBody);
    REQUIRE(level.goal.present);
    const uint32_t count = countOf(level.world, yog);
    CHECK(count >= 50);
    CHECK(level.goal.amount <= 0.8 * count);
    // The bowl's inside, as the goal's sensor.
    const auto inBowl = [&] { return countIn(level.world, yog, 0.86f, 0.02f, 1.38f, 0.16f); };
    // The demo's shift + drag of a kinematic plank (demo/app.cpp, Grab): the grabbed point (the
    // plank's centre here) gets the velocity that brings it to the cursor in one frame, at most
    // 3 m/s, and Q / E held turn it at 2 rad/s (E clockwise). Plays `frames` frames with the
    // cursor at cursor(f) and E held while turning(f), frame f counted from 1.
    const auto grab = [&](int frames, const auto& cursor, const auto& turning, const auto& after) {
        const float dt = 1.0f / level.frameRate;
        for (int f = 1; f <= frames; ++f) {
            const glm::vec2 to = cursor(f);
            const b2Vec2 at = plank->GetPosition();
            b2Vec2 v{(to.x - at.x) / dt, (to.y - at.y) / dt};
            if (v.Length() > 3.0f) {
                v *= 3.0f / v.Length();
            }
            plank->SetLinearVelocity(v);
            plank->SetAngularVelocity(turning(f) ? -2.0f : 0.0f);
            level.step();
            after(f);
        }
        plank->SetLinearVelocity({0.0f, 0.0f});
        plank->SetAngularVelocity(0.0f);
    };
    // 1.5 s of an eased move of the cursor from the plank's centre (0.36, 0.5) to `to`.
    const auto carry = [](int f, glm::vec2 to) -> glm::vec2 {
        const float t = 0.5f - 0.5f * std::cos(3.14159265f * float(std::min(f, 90)) / 90.0f);
        return glm::vec2(0.36f, 0.5f) + t * (to - glm::vec2(0.36f, 0.5f));
    };

    SECTION("left alone, the layer settles and stays on the plank") {
        playFrames(level, 60 * 61);
        const Bounds b = bounds(level.world, yog.index);
        std::printf("[measure] sticky_plank left alone: lowest yoghurt at %.3f m after 61 s (the "
                    "plank's low end at 0.39 m), %u in the bowl, goal %s\n",
                    b.y0, inBowl(), level.goalState() == GoalState::Lost ? "lost" : "not lost");
        CHECK(level.goalState() == GoalState::Lost);
        CHECK(inBowl() == 0);
        // The front settles 3 cm in the first 5 s, then stays short of the plank's end (the
        // figures: docs/levels.md, after the level table).
        CHECK(b.y0 > 0.41f);
        CHECK(test::allFinite(level.world));
    }

    // Where the cursor holds the plank's centre to shake it (S) and to turn it (T).
    const float SX = 1.0f, SY = 0.34f, TX = 1.1f, TY = 0.35f;
    SECTION("carried low over the bowl and shaken hard as the demo's grab does, it falls in") {
        // The cursor: 1.5 s to (1.0, 0.34), the plank's low end 11 cm over the bowl's rim, then
        // twelve shakes of +-6 cm, 10 frames each (2 s), then still (how far this may move and
        // still win: docs/levels.md).
        const auto cursor = [&](int f) -> glm::vec2 {
            if (f > 100 && f <= 220) {
                return {((f - 101) / 5) % 2 == 0 ? SX + 0.06f : SX - 0.06f, SY};
            }
            return carry(f, {SX, SY});
        };
        const auto carried = [&](int f) {
            if (f == 90) {
                // Carried across without losing any: all of it still on the plank.
                CHECK(inBowl() == 0);
                CHECK(bounds(level.world, yog.index).y0 > 0.25f);
            }
        };
        const auto noTurn = [](int) { return false; };
        grab(300, cursor, noTurn, carried);
        std::printf("[measure] sticky_plank shaken over the bowl: %u of %u in the bowl after "
                    "%.1f s, goal %s\n",
                    inBowl(), count, level.world.time(),
                    level.goalState() == GoalState::Won ? "won" : "not won");
        CHECK(level.goalState() == GoalState::Won);
        CHECK(test::allFinite(level.world));
    }

    SECTION("carried over the bowl and turned upside down with E, most of it hangs on; shaken, "
            "it falls in") {
        // The cursor: 1.5 s to (1.1, 0.35), then E held for 1.5 s turns the plank by 3 rad; then
        // twelve shakes of +-6 cm as above. Upside down the layer's weight, rho g t = 440 Pa per
        // unit of plank, is under what the walls' hold carries once the paste has rested (up to
        // twice the yield stress), so it hangs until shaken (docs/levels.md).
        const auto cursor = [&](int f) -> glm::vec2 {
            if (f > 200 && f <= 320) {
                return {((f - 201) / 5) % 2 == 0 ? TX + 0.06f : TX - 0.06f, TY};
            }
            return carry(f, {TX, TY});
        };
        const auto holdE = [](int f) { return f > 100 && f <= 190; };
        uint32_t turned = 0;
        grab(400, cursor, holdE, [&](int f) {
            if (f == 200) {
                turned = inBowl();
            }
        });
        std::printf("[measure] sticky_plank turned over the bowl: %u of %u in the bowl after "
                    "turning (3.3 s), %u after shaking (%.1f s), plank at %.2f rad, goal %s\n",
                    turned, count, inBowl(), level.world.time(), plank->GetAngle(),
                    level.goalState() == GoalState::Won ? "won" : "not won");
        CHECK(plank->GetAngle() == Approx(-3.4).margin(0.05));
        CHECK(turned < level.goal.amount);
        CHECK(level.goalState() == GoalState::Won);
        CHECK(test::allFinite(level.world));
    }
}

TEST_CASE("yoghurt_or_water.json: the water runs down its chute into its cup, the yoghurt "
          "stays on its own until pushed",
          "[level][demo][yield][slow]") {
    const Registry& registry = builtins();
    Level level = loadLevel(shippedLevel("yoghurt_or_water"), registry);
    const MaterialId water = requireMaterial(level, "water");
    const MaterialId yog = requireMaterial(level, "yoghurt");
    CHECK(level.world.material(yog).yieldStress == 400.0f); // the preset
    const uint32_t nWater = countOf(level.world, water), nYog = countOf(level.world, yog);
    // The same polygon on each chute; the materials' spacings differ (1.14 and 1.15 cm), so the
    // counts differ by a few: 121 water and 118 yoghurt particles.
    CHECK(nYog >= 100);
    CHECK(std::abs(int(nWater) - int(nYog)) <= int(nYog) / 20);
    REQUIRE(level.goal.present);
    // The cups' insides: water x in [0.42, 0.58], yoghurt x in [1.08, 1.24], y up to 0.16.
    const auto waterCup = [&] { return countIn(level.world, water, 0.42f, 0.02f, 0.58f, 0.16f); };
    const auto yogCup = [&] { return countIn(level.world, yog, 1.08f, 0.02f, 1.24f, 0.16f); };

    SECTION("left alone: the water fills its cup, the yoghurt never leaves its chute") {
        playFrames(level, 300);
        CHECK(waterCup() == nWater);
        const Bounds y5 = bounds(level.world, yog.index);
        playFrames(level, 60 * 61 - 300);
        const Bounds y = bounds(level.world, yog.index);
        std::printf("[measure] yoghurt_or_water left alone: %u of %u water particles in its cup "
                    "after 5 s; the yoghurt's lowest point %.4f m at 5 s, %.4f m at 61 s; goal "
                    "%s\n",
                    nWater, nWater, y5.y0, y.y0,
                    level.goalState() == GoalState::Lost ? "lost" : "not lost");
        // The chutes fall 19 degrees, from 0.45 m to 0.30 m; the rested dollop is 4 cm thick and
        // 30 cm long, its lowest point 0.346 m at load (the figures: docs/levels.md).
        CHECK(yogCup() == 0);
        CHECK(y.y0 > 0.33f);                   // 3 cm above the chute's end
        CHECK(std::abs(y.y0 - y5.y0) < 0.01f); // and not creeping
        CHECK(level.goalState() == GoalState::Lost);
        CHECK(test::allFinite(level.world));
    }

    SECTION("pushed down the chute with the demo's pointer (left drag), it fills its cup") {
        // The demo's left drag, dragged in 1 s from behind the dollop, 3 cm over the chute, to
        // beyond the chute's end, 6 cm over it there; the chute keeps a film (docs/levels.md).
        PointerForce& pointer = addDemoPointer(level, registry, 1.3);
        for (int f = 1; f <= 300; ++f) {
            const float t = std::clamp(float(f - 10) / 60.0f, 0.0f, 1.0f);
            pointer.setPointer({0.66f + 0.54f * t, 0.48f - 0.15f * t},
                               f >= 10 && f < 80 ? 1.0f : 0.0f);
            level.step();
        }
        std::printf("[measure] yoghurt_or_water pushed: %u of %u yoghurt particles in its cup "
                    "after 5 s, goal %s\n",
                    yogCup(), nYog, level.goalState() == GoalState::Won ? "won" : "not won");
        CHECK(level.goalState() == GoalState::Won);
        CHECK(waterCup() == nWater);
        CHECK(test::allFinite(level.world));
    }
}
