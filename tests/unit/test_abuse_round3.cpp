// fluid tests — abuse, round 3: range bounds that are not floats, many sensors, control
// characters in names and error texts, boxes that hold nothing.
#include "test_support.h"

#include <catch2/catch.hpp>

#include <fluid/error.h>
#include <fluid/gameplay.h>
#include <fluid/material.h>
#include <fluid/plugins/box_container.h>
#include <fluid/plugins/builtin.h>
#include <fluid/registry.h>
#include <fluid/shape.h>
#include <fluid/task.h>
#include <fluid/world.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

using namespace fluid;

namespace {

// The smallest float a field accepts: its bound rounded to float, or the next float above it
// when the bound itself is refused.
float smallestAccepted(const MaterialField& f) {
    const auto lo = float(f.lo);
    return f.openLow ? std::nextafter(lo, std::numeric_limits<float>::infinity()) : lo;
}

} // namespace

TEST_CASE("every float field of Material validates at its documented minimum and maximum",
          "[abuse3][materials]") {
    for (const MaterialField& f : materialFields()) {
        REQUIRE(f.real != nullptr);
        INFO(f.name);
        Material m = water();
        m.*f.real = smallestAccepted(f);
        CHECK_NOTHROW(validate(m));
        m.*f.real = float(f.hi);
        CHECK_NOTHROW(validate(m));
        // One float beyond either end is refused.
        m.*f.real = std::nextafter(float(f.hi), std::numeric_limits<float>::infinity());
        CHECK_THROWS_AS(validate(m), Error);
        m.*f.real = f.openLow
                        ? float(f.lo)
                        : std::nextafter(float(f.lo), -std::numeric_limits<float>::infinity());
        CHECK_THROWS_AS(validate(m), Error);
    }
    // The report's case: 0.003 is not a float, and the float nearest to it is the minimum.
    Material m = water();
    m.smoothingDistance = 3e-3f;
    CHECK_NOTHROW(validate(m));
    m.smoothingDistance = std::nextafter(3e-3f, 0.0f);
    CHECK_THROWS_WITH(validate(m), "material 'water': smoothingDistance = 0.0029999998 is out of "
                                   "range [0.003, 0.4] (unit: m)");
    m = water();
    m.flowIndex = 0.1f;
    CHECK_NOTHROW(validate(m));
}

TEST_CASE("a world takes every spacing and support its documented ranges give, and refuses "
          "the settings that do not fit together, naming them",
          "[abuse3][materials]") {
    World world;
    const float depth = world.def().depth;
    Material m = water();
    // The mass that gives water's rest density a particle spacing of `spacing` (unit: kg).
    const auto massAt = [rho = m.restDensity, depth](float spacing) {
        return spacing * spacing * rho * depth;
    };
    // The four corners of the spacing and support ranges.
    for (const float spacing : {kMinSpacing, kMaxSpacing}) {
        for (const float support : {kMinSupportSpacings, kMaxSupportSpacings}) {
            INFO(spacing << " m, " << support << " spacings");
            m.mass = massAt(spacing);
            m.smoothingDistance = support * spacing;
            CHECK_NOTHROW(world.addMaterial(m));
            CHECK(world.spacing(MaterialId{uint16_t(world.materialCount() - 1)}) ==
                  Approx(spacing).epsilon(1e-5));
        }
    }
    // The smallest smoothing distance, at the finest spacing.
    m.mass = massAt(kMinSpacing);
    m.smoothingDistance = 3e-3f;
    CHECK_NOTHROW(world.addMaterial(m));
    // Just outside: a spacing one percent off either end, a support one percent off either end.
    m = water();
    m.mass = 1000.0f;
    CHECK_THROWS_WITH(world.addMaterial(m),
                      "World::addMaterial: material 'water': mass = 1000 kg, restDensity = 1000 "
                      "kg/m^3 and depth = 0.129313 m give a particle spacing of sqrt(mass / "
                      "(restDensity depth)) = 2.78085 m; expected [0.001, 0.05] m");
    m = water();
    m.mass = massAt(0.99f * kMinSpacing);
    m.smoothingDistance = 3e-3f;
    CHECK_THROWS_WITH(world.addMaterial(m), Catch::Contains("give a particle spacing of"));
    m.mass = massAt(1.01f * kMaxSpacing);
    m.smoothingDistance = 0.2f;
    CHECK_THROWS_WITH(world.addMaterial(m), Catch::Contains("give a particle spacing of"));
    m = water();
    m.smoothingDistance = 0.1f;
    CHECK_THROWS_WITH(world.addMaterial(m),
                      "World::addMaterial: material 'water': smoothingDistance = 0.1 m is "
                      "9.97356 particle spacings (0.0100265 m, from mass, restDensity and "
                      "depth); expected 3 to 8 spacings");
    m.smoothingDistance = 0.99f * 3.0f * particleSpacing(m, depth);
    CHECK_THROWS_WITH(world.addMaterial(m), Catch::Contains("expected 3 to 8 spacings"));
    // setMaterial checks the same, and keeps the old material.
    m = water();
    const MaterialId w = world.addMaterial(m);
    m.smoothingDistance = 0.01f;
    CHECK_THROWS_WITH(world.setMaterial(w, m),
                      Catch::StartsWith("World::setMaterial: material 'water': smoothingDistance "
                                        "= 0.01 m is 0.997356 particle spacings"));
    CHECK(world.material(w).smoothingDistance == 0.032f);
    // The depth is the world's: the water preset in a 1000 m deep slab has a 0.4 mm spacing.
    WorldDef deep;
    deep.depth = 1000.0f;
    World thick(deep);
    CHECK_THROWS_WITH(thick.addMaterial(water()), Catch::Contains("depth = 1000 m give a particle "
                                                                  "spacing of"));
}

TEST_CASE("every float field of WorldDef validates at its documented minimum and maximum",
          "[abuse3][world]") {
    for (const Field<WorldDef>& f : worldFields()) {
        if (f.real == nullptr) {
            continue;
        }
        INFO(f.name);
        for (const double bound : {f.lo, f.hi}) {
            WorldDef def;
            def.*f.real = float(bound);
            if (f.openLow && bound == f.lo) {
                def.*f.real = std::nextafter(float(bound), std::numeric_limits<float>::infinity());
            }
            CHECK_NOTHROW(World(def));
        }
    }
}

TEST_CASE("adding sensors costs the same per sensor however many there are", "[abuse3][gameplay]") {
    // 100k sensors in 20 chunks of 5k, timed against a reference that does what adding a
    // sensor has to do at least: append the sensor and its readings (one per material) to two
    // growing vectors. Memory effects (fresh pages, caches) hit both alike. A cost linear in
    // the sensors already there (the old whole-table reset: 4 x 16 bytes per sensor for every
    // add) makes the last quarter's chunks thousands of times the reference's; a constant cost
    // keeps them within a few times. Medians of 5 chunks keep one slow chunk (another process
    // on the core) from deciding.
    using Clock = std::chrono::steady_clock;
    constexpr int kChunks = 20;
    constexpr int kPerChunk = 5000;
    constexpr std::size_t kMaterials = 4;
    const auto median = [](std::vector<double> v) {
        std::sort(v.begin(), v.end());
        return v[v.size() / 2];
    };
    const auto lastQuarter = [&](const std::array<double, kChunks>& seconds) {
        return median({seconds.end() - kChunks / 4, seconds.end()});
    };
    SensorDef def;
    def.shape = Shape::circle({0.0f, 0.0f}, 0.1f);

    std::array<double, kChunks> reference{};
    {
        std::vector<SensorDef> sensors;
        std::vector<SensorReading> readings;
        for (int c = 0; c < kChunks; ++c) {
            const auto start = Clock::now();
            for (int k = 0; k < kPerChunk; ++k) {
                sensors.push_back(def);
                readings.resize(sensors.size() * kMaterials);
            }
            reference[c] = std::chrono::duration<double>(Clock::now() - start).count();
        }
        REQUIRE(readings.size() == kChunks * kPerChunk * kMaterials);
    }

    World world;
    // Names from a table: GCC 12 at -O3 misreads a name built in the loop (a false
    // -Wstringop-overflow on the string's copy).
    const std::array<std::string, kMaterials> names{"m0", "m1", "m2", "m3"};
    for (const std::string& name : names) {
        Material m = water();
        m.name = name;
        world.addMaterial(m);
    }
    std::array<double, kChunks> seconds{};
    for (int c = 0; c < kChunks; ++c) {
        const auto start = Clock::now();
        for (int k = 0; k < kPerChunk; ++k) {
            world.addSensor(def);
        }
        seconds[c] = std::chrono::duration<double>(Clock::now() - start).count();
    }
    REQUIRE(world.sensorCount() == uint32_t(kChunks * kPerChunk));
    const double ours = lastQuarter(seconds);
    const double floor = std::max(lastQuarter(reference), 1e-5);
    INFO("last quarter: " << ours * 1e6 << " us per chunk of " << kPerChunk
                          << " sensors; reference " << floor * 1e6 << " us");
    CHECK(ours < 50.0 * floor);

    // The new sensor reads zeros until a step; the table has one entry per material.
    const SensorId last100k{uint32_t(kChunks * kPerChunk - 1)};
    REQUIRE(world.sensorReading(last100k).size() == kMaterials);
    CHECK(world.sensorReading(last100k)[3].count == 0);
}

TEST_CASE("a sensor added after a step reads zeros, the others keep their readings",
          "[abuse3][gameplay]") {
    World world;
    const MaterialId w = world.addMaterial(water());
    BlobDef blob;
    blob.material = w;
    blob.shape = Shape::box({0.0f, 0.0f}, {0.1f, 0.1f});
    const uint32_t spawned = world.spawnBlob(blob);
    REQUIRE(spawned > 0);
    SensorDef def;
    def.shape = Shape::box({-1.0f, -1.0f}, {1.0f, 1.0f});
    const SensorId a = world.addSensor(def);
    world.step(1.0f / 60.0f);
    CHECK(world.sensorReading(a)[0].count == spawned);
    const SensorId b = world.addSensor(def);
    CHECK(world.sensorReading(a)[0].count == spawned);
    CHECK(world.sensorReading(b)[0].count == 0);
    world.step(1.0f / 60.0f);
    CHECK(world.sensorReading(b)[0].count == spawned);
}

TEST_CASE("a material name must be printable text", "[abuse3][materials]") {
    Material m = water();
    m.name = std::string("wa\0ter", 6);
    CHECK_THROWS_WITH(validate(m), "material 'wa\\x00ter': the name holds a control character "
                                   "(byte 0x00 at offset 2); names are printable text");
    m.name = "\x1b[31mred";
    CHECK_THROWS_WITH(validate(m), "material '\\x1b[31mred': the name holds a control character "
                                   "(byte 0x1b at offset 0); names are printable text");
    m.name = "tab\there";
    CHECK_THROWS_WITH(validate(m), "material 'tab\\x09here': the name holds a control character "
                                   "(byte 0x09 at offset 3); names are printable text");
    m.name = "del\x7f";
    CHECK_THROWS_WITH(validate(m), "material 'del\\x7f': the name holds a control character "
                                   "(byte 0x7f at offset 3); names are printable text");
    World world;
    CHECK_THROWS_WITH(world.addMaterial(m), "material 'del\\x7f': the name holds a control "
                                            "character (byte 0x7f at offset 3); names are "
                                            "printable text");
    // UTF-8 multibyte characters are printable text.
    m.name = "Wasser \xc3\xa4\xe2\x82\xac";
    CHECK_NOTHROW(validate(m));
    CHECK_NOTHROW(world.addMaterial(m));
}

TEST_CASE("error texts are one line and are not cut at a NUL", "[abuse3][errors]") {
    constexpr char kQuoted[] = "unknown material 'wa\0ter'; known: wa";
    const Error e(std::string(kQuoted, sizeof kQuoted - 1));
    CHECK(std::string(e.what()) == "unknown material 'wa\\x00ter'; known: wa");
    CHECK(std::string(Error("a\nb\x1b[0m\x7f").what()) == "a\\x0ab\\x1b[0m\\x7f");
    CHECK(Error::printable("caf\xc3\xa9 100%") == "caf\xc3\xa9 100%");
    // A value a user gave, quoted by the library.
    Registry registry;
    registerBuiltinPlugins(registry);
    try {
        (void)registry.create(std::string("boundary.b\0x", 12));
        FAIL("no error");
    } catch (const Error& error) {
        CHECK(
            std::string(error.what()).rfind("unknown plugin type 'boundary.b\\x00x'; known:", 0) ==
            0);
    }
}

TEST_CASE("a box plugin with an empty inner rectangle is refused when it is made",
          "[abuse3][plugins]") {
    Registry registry;
    registerBuiltinPlugins(registry);
    const std::array<ParamValue, 2> inverted{{{"minX", 1.0}, {"maxX", 0.0}}};
    CHECK_THROWS_WITH(registry.create("boundary.box", inverted),
                      "plugin 'boundary.box': the inner rectangle [1, 0] x [0, 2] is empty; "
                      "expected minX < maxX and minY < maxY");
    const std::array<ParamValue, 1> flat{{{"maxY", -0.0}}};
    CHECK_THROWS_WITH(registry.createBoundary("boundary.box", flat),
                      "plugin 'boundary.box': the inner rectangle [-1, 1] x [0, -0] is empty; "
                      "expected minX < maxX and minY < maxY");
    CHECK_THROWS_WITH(BoxContainer(0.0f, 0.0f, 1.0f, 0.0f),
                      "plugin 'boundary.box': the inner rectangle [0, 1] x [0, 0] is empty; "
                      "expected minX < maxX and minY < maxY");
    // Values set one by one may pass through an empty box; made whole, it is fine.
    const std::array<ParamValue, 2> moved{{{"minX", 5.0}, {"maxX", 6.0}}};
    const auto box = registry.create("boundary.box", moved);
    CHECK_NOTHROW(box->checkParams());
    CHECK_NOTHROW(BoxContainer(5.0f, 0.0f, 6.0f, 1.0f));
}

TEST_CASE("more workers than cores run on as many threads as the cores, with the same results",
          "[abuse3][threads]") {
    const auto run = [](uint32_t workers, uint32_t& threads) {
        WorldDef def;
        def.positionBased = positionBasedPreset(Quality::Game);
        def.workerCount = workers;
        World world(def);
        const MaterialId w = world.addMaterial(water());
        world.addForce(std::make_unique<GravityForce>(0.0f, -9.81f));
        world.addBoundary(std::make_unique<BoxContainer>(0.0f, 0.0f, 0.8f, 0.6f));
        world.spawnBlob(test::latticeBlock(world, w, 0.0f, 0.0f, 20, 30));
        CHECK(world.profile().threads == 1); // before the first step
        for (int frame = 0; frame < 20; ++frame) {
            world.step(1.0f / 60.0f);
        }
        threads = world.profile().threads;
        return test::stateHash(world);
    };
    const uint32_t cores = usableCores();
    REQUIRE(cores >= 1);
    uint32_t threads = 0;
    const uint64_t serial = run(1, threads);
    CHECK(threads == 1);
    for (const uint32_t workers : {2u, cores + 1, 256u}) {
        INFO(workers << " workers on " << cores << " cores");
        CHECK(run(workers, threads) == serial);
        CHECK(threads == std::min(workers, cores));
    }
    ThreadPool pool(256);
    CHECK(pool.workerCount() == 256);
    CHECK(pool.threadCount() == cores);
    CHECK(pool.hook().workerCount == cores);
}

TEST_CASE("positions outside the world's range are refused, and a particle that leaves it is "
          "removed with an event",
          "[abuse3][positions]") {
    World world;
    CHECK(world.positionLimit() == 0.0f); // no material yet
    const MaterialId w = world.addMaterial(water());
    const float limit = world.positionLimit();
    CHECK(limit == Approx(kPositionSpacings * world.spacing(w)).epsilon(1e-6)); // 2,628 m
    CHECK(limit > 2600.0f);
    // The report's cases: refused with the value and the range, never a crash or NaN.
    CHECK_THROWS_WITH(world.addParticle({1e20f, 0.0f}, {}, w),
                      "World::addParticle: position = (1e+20, 0) is outside the position range "
                      "[-2628.39, 2628.39] (unit: m; 2^18 spacings of the finest material, "
                      "'water' at 0.0100265 m; docs/gameplay.md, Far from the origin)");
    CHECK_THROWS_AS(world.addParticle({3e38f, 0.0f}, {}, w), Error);
    CHECK_THROWS_AS(world.addParticle({-3e38f, -3e38f}, {}, w), Error);
    EmitterDef emitter;
    emitter.material = w;
    emitter.position = {0.0f, -1e4f};
    CHECK_THROWS_WITH(world.addEmitter(emitter),
                      Catch::StartsWith("World::addEmitter: position = (0, -10000) is outside "
                                        "the position range [-2628.39, 2628.39]"));
    CHECK(world.particleCount() == 0);
    // At the edge: accepted. Moving out at 10 m/s in zero g, it leaves within a frame and is
    // removed at the end of that step, with its cause; the one beside it stays.
    const ParticleHandle leaving = world.addParticle({limit - 0.05f, 0.0f}, {10.0f, 0.0f}, w);
    const ParticleHandle staying = world.addParticle({limit - 0.05f, 1.0f}, {-10.0f, 0.0f}, w);
    world.step(1.0f / 60.0f);
    REQUIRE(world.removedEvents().size() == 1);
    const RemovedEvent& event = world.removedEvents()[0];
    CHECK(event.cause == RemovalCause::OutOfRange);
    CHECK(event.particle == leaving);
    CHECK(event.position.x > limit);
    CHECK(event.velocity.x == Approx(10.0f));
    CHECK_FALSE(world.isValid(leaving));
    CHECK(world.isValid(staying));
    CHECK(world.particleCount() == 1);
    // A material with a finer spacing narrows the range; particles beyond it leave at the next
    // step the same way.
    Material fine = water();
    fine.name = "fine";
    fine.mass = 4.0f * kMinSpacing * kMinSpacing * fine.restDensity * world.def().depth; // 2 mm
    fine.smoothingDistance = 4.0f * 2.0f * kMinSpacing;
    world.addMaterial(fine);
    CHECK(world.positionLimit() == Approx(kPositionSpacings * 2e-3f).epsilon(1e-5)); // 524 m
    world.step(1.0f / 60.0f);
    REQUIRE(world.removedEvents().size() == 1);
    CHECK(world.removedEvents()[0].particle == staying);
    CHECK(world.removedEvents()[0].cause == RemovalCause::OutOfRange);
    CHECK(world.particleCount() == 0);
}

TEST_CASE("a resting tank at the edge of the position range rests as it does at the origin",
          "[abuse3][positions][physics]") {
    // Float keeps positions to 1/32 spacing out to the limit; beyond it the same tank stirs
    // more (docs/gameplay.md, Far from the origin).
    const auto settle = [](float offset, uint32_t& separated) {
        WorldDef def;
        def.positionBased = positionBasedPreset(Quality::Game);
        World world(def);
        const MaterialId w = world.addMaterial(water());
        const float s = world.spacing(w);
        REQUIRE(offset + 1.3f <= world.positionLimit());
        world.addForce(std::make_unique<GravityForce>(0.0f, -9.81f));
        world.addBoundary(
            std::make_unique<BoxContainer>(offset, offset, offset + 1.2f, offset + 0.8f));
        BlobDef blob;
        blob.material = w;
        blob.shape =
            Shape::box({offset + 0.5f * s, offset + 0.5f * s}, {offset + 1.2f, offset + 0.15f});
        world.spawnBlob(blob);
        separated = 0;
        for (int frame = 0; frame < 240; ++frame) {
            world.step(1.0f / 60.0f);
            separated += world.profile().separated;
        }
        REQUIRE(test::allFinite(world));
        return test::energy(world, 0.0).kinetic;
    };
    uint32_t separatedOrigin = 0, separatedEdge = 0;
    const double origin = settle(0.0f, separatedOrigin);
    const double edge = settle(2600.0f - 1.3f, separatedEdge);
    std::printf("[measure] resting tank after 4 s: kinetic energy %.4f J at the origin, %.4f J "
                "at 2,600 m; separated %u / %u\n",
                origin, edge, separatedOrigin, separatedEdge);
    CHECK(edge < 2.0 * origin);
    CHECK(separatedEdge == 0);
}

TEST_CASE("one sweep per sub-step needs the coarse correction", "[abuse3][world]") {
    WorldDef def; // the game preset: 1 iteration, with the coarse correction
    def.positionBased.coarseCorrection = 0.0f;
    CHECK_THROWS_WITH(World(def),
                      "WorldDef: positionBased.iterations = 1 needs the coarse correction, but "
                      "coarseCorrection = 0; use 2 or more iterations, or a coarseCorrection "
                      "above 0 (the game preset: 1 iteration, 0.4)");
    def.positionBased = positionBasedPreset(Quality::Game);
    CHECK_NOTHROW(World(def));
    World world(def);
    PositionBasedDef pb = positionBasedPreset(Quality::Game);
    pb.coarseCorrection = 0.0f;
    CHECK_THROWS_WITH(world.setPositionBased(pb),
                      Catch::StartsWith("World::setPositionBased: iterations = 1 needs the "
                                        "coarse correction"));
    CHECK(world.def().positionBased.coarseCorrection == 0.4f); // kept
    pb.iterations = 2;
    CHECK_NOTHROW(world.setPositionBased(pb));
}
