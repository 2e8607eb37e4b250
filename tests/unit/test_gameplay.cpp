// Emitters, drains, lifetimes, sensors and the removal events read after World::step.
#include "test_support.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <sstream>
#include <string>

using namespace fluid;
using fluid::test::kFrame;

namespace {

// A zero-gravity world with water (and yoghurt) and no walls.
World openWorld(uint32_t workers = 1) {
    WorldDef def;
    def.workerCount = workers;
    World world(def);
    world.addMaterial(water());
    world.addMaterial(yoghurt());
    return world;
}

EmitterDef faucet(glm::vec2 at) {
    EmitterDef e;
    e.position = at;
    e.direction = {1.0f, 0.0f};
    e.speed = 1.5f;
    e.width = 0.04f; // 5 lanes at water's 0.01 m spacing
    e.rate = 600.0f; // 120 rows per second: two rows a frame at 60 Hz
    return e;
}

} // namespace

TEST_CASE("emitter: a faucet emits its rate in evenly spaced rows at its speed", "[gameplay]") {
    World world = openWorld();
    const EmitterId id = world.addEmitter(faucet({0.0f, 0.0f}));
    world.step(kFrame);
    // Two rows of five lanes in the first frame, moving along +x at 1.5 m/s.
    REQUIRE(world.emittedCount(id) == 10);
    REQUIRE(world.profile().emitted == 10);
    REQUIRE(world.particleCount() == 10);
    for (uint32_t i = 0; i < 10; ++i) {
        CHECK(world.velocityX()[i] == Approx(1.5f).margin(0.05f));
        CHECK(std::fabs(world.positionY()[i]) <= 0.021f);
    }
    for (int f = 1; f < 60; ++f) {
        world.step(kFrame);
    }
    // One second at 600 particles per second (the last row may still be owed to rounding).
    CHECK(world.emittedCount(id) >= 595);
    CHECK(world.emittedCount(id) <= 600);
    CHECK(world.particleCount() == world.emittedCount(id));
}

TEST_CASE("emitter: maxCount stops it, rate 0 closes it, setEmitter moves it", "[gameplay]") {
    World world = openWorld();
    EmitterDef def = faucet({0.0f, 0.0f});
    def.maxCount = 37;
    const EmitterId id = world.addEmitter(def);
    for (int f = 0; f < 10; ++f) {
        world.step(kFrame);
    }
    CHECK(world.emittedCount(id) == 37);
    CHECK(world.particleCount() == 37);

    EmitterDef second = faucet({1.0f, 1.0f});
    second.rate = 0.0f;
    const EmitterId closed = world.addEmitter(second);
    world.step(kFrame);
    CHECK(world.emittedCount(closed) == 0);
    second.rate = 300.0f;
    second.position = {2.0f, 2.0f};
    world.setEmitter(closed, second);
    world.step(kFrame);
    CHECK(world.emittedCount(closed) == 5);
    CHECK(world.emitter(closed).position == glm::vec2(2.0f, 2.0f));
    CHECK(world.emitterCount() == 2);
}

TEST_CASE("emitter: a full world blocks emission and says so", "[gameplay]") {
    WorldDef def;
    def.maxParticles = 25;
    World world(def);
    world.addMaterial(water());
    const EmitterId id = world.addEmitter(faucet({0.0f, 0.0f}));
    uint32_t blocked = 0;
    for (int f = 0; f < 4; ++f) {
        world.step(kFrame);
        blocked += world.profile().emitBlocked;
    }
    CHECK(world.particleCount() == 25);
    CHECK(world.emittedCount(id) == 25);
    CHECK(blocked == 40 - 25);
}

TEST_CASE("emitter: jitter is deterministic per seed", "[gameplay]") {
    auto run = [](uint64_t seed) {
        World world = openWorld();
        EmitterDef def = faucet({0.0f, 0.0f});
        def.jitter = 0.3f;
        def.seed = seed;
        world.addEmitter(def);
        for (int f = 0; f < 5; ++f) {
            world.step(kFrame);
        }
        return fluid::test::stateHash(world);
    };
    CHECK(run(7) == run(7));
    CHECK(run(7) != run(8));
}

TEST_CASE("emitter: bad definitions name the field", "[gameplay]") {
    World world = openWorld();
    EmitterDef def = faucet({0.0f, 0.0f});
    def.rate = 1000.0f;
    CHECK_THROWS_WITH(world.addEmitter(def),
                      "World::addEmitter: rate = 1000 particles/s overlaps: a nozzle 0.04 m wide "
                      "(5 lanes at 0.0100265 m spacing) at speed 1.5 m/s emits at most 748.017 "
                      "particles/s; lower the rate, or widen or speed up the jet");
    def = faucet({0.0f, 0.0f});
    def.direction = {0.0f, 0.0f};
    CHECK_THROWS_WITH(world.addEmitter(def),
                      "World::addEmitter: direction = (0, 0) has no direction; expected a "
                      "non-zero vector");
    def = faucet({0.0f, 0.0f});
    def.speed = std::numeric_limits<float>::quiet_NaN();
    CHECK_THROWS_WITH(world.addEmitter(def),
                      "World::addEmitter: speed = nan is out of range [0.01, 100] (unit: m/s)");
    def = faucet({0.0f, 0.0f});
    def.material = MaterialId{9};
    CHECK_THROWS_WITH(world.addEmitter(def), "unknown material id 9; the world has 2 materials");
    CHECK_THROWS_WITH(world.emittedCount(EmitterId{3}),
                      "World::emittedCount: unknown emitter id 3; the world has 0 emitters");
    CHECK(world.emitterCount() == 0);
}

TEST_CASE("lifetimes: particles expire and are reported, the rest live on", "[gameplay]") {
    World world = openWorld();
    EmitterDef def = faucet({0.0f, 0.0f});
    def.lifetime = 0.25f;
    const EmitterId id = world.addEmitter(def);
    const ParticleHandle forever = world.addParticle({5.0f, 5.0f}, {0.0f, 0.0f}, MaterialId{0});
    const ParticleHandle brief = world.addParticle({-5.0f, 5.0f}, {0.0f, 0.0f}, MaterialId{0});
    world.setLifetime(brief, 0.11f);
    CHECK(world.lifetime(forever) == std::numeric_limits<float>::infinity());
    CHECK(world.lifetime(brief) == 0.11f);
    uint32_t expired = 0;
    bool briefGone = false;
    for (int f = 0; f < 60; ++f) {
        world.step(kFrame);
        for (const RemovedEvent& e : world.removedEvents()) {
            REQUIRE(e.cause == RemovalCause::Lifetime);
            briefGone = briefGone || e.particle == brief;
            ++expired;
        }
        if (f == 6) {
            // 7 frames = 0.117 s > 0.11 s > 6 frames: gone in the 7th step, not before.
            CHECK(!world.isValid(brief));
        } else if (f == 5) {
            CHECK(world.isValid(brief));
        }
    }
    CHECK(briefGone);
    CHECK(world.isValid(forever));
    // Every emitted particle is alive or reported, and none outlived 0.25 s (15 frames).
    CHECK(world.particleCount() + expired == world.emittedCount(id) + 2);
    CHECK(world.particleCount() - 1 <= 15 * 10);
    CHECK_THROWS_WITH(world.setLifetime(forever, -1.0f),
                      "World::setLifetime: lifetime = -1 is out of range [0, 1e+06] (unit: s)");
}

TEST_CASE("drains remove what falls in, report it in order, and keep mass accounted",
          "[gameplay]") {
    World world = openWorld();
    world.addForce(std::make_unique<GravityForce>(0.0f, -9.81f));
    BlobDef blob = fluid::test::latticeBlock(world, MaterialId{0}, -0.05f, 0.2f, 10, 10);
    const uint32_t water = world.spawnBlob(blob);
    blob = fluid::test::latticeBlock(world, MaterialId{1}, 0.5f, 0.2f, 10, 10);
    const uint32_t yoghurt = world.spawnBlob(blob);
    DrainDef onlyYoghurt;
    onlyYoghurt.shape = Shape::box({0.3f, -1.0f}, {0.8f, 0.0f});
    onlyYoghurt.onlyMaterial = true;
    onlyYoghurt.material = MaterialId{1};
    const DrainId d0 = world.addDrain(onlyYoghurt);
    DrainDef sink;
    sink.shape = Shape::box({-0.5f, -1.0f}, {1.0f, -0.2f});
    const DrainId d1 = world.addDrain(sink);
    uint32_t fromD0 = 0, fromD1 = 0;
    for (int f = 0; f < 40; ++f) {
        world.step(kFrame);
        uint32_t lastDrain = 0;
        for (const RemovedEvent& e : world.removedEvents()) {
            REQUIRE(e.cause == RemovalCause::Drain);
            REQUIRE(e.drain.index >= lastDrain); // grouped by drain, in the order added
            lastDrain = e.drain.index;
            REQUIRE(!world.isValid(e.particle));
            REQUIRE(e.position.y <= 0.0f);
            if (e.drain == d0) {
                CHECK(e.material.index == 1);
                ++fromD0;
            } else {
                CHECK(e.drain == d1);
                ++fromD1;
            }
        }
        CHECK(world.profile().removed == world.removedEvents().size());
    }
    // Both blobs fell 0.2 m into their drains within 40 frames (free fall takes 0.2 s).
    CHECK(fromD0 == yoghurt);
    CHECK(fromD1 == water);
    CHECK(world.particleCount() == 0);
    CHECK(world.drainCount() == 2);
    DrainDef bad;
    bad.shape = Shape::circle({0.0f, 0.0f}, -1.0f);
    CHECK_THROWS_WITH(world.addDrain(bad),
                      "World::addDrain: radius = -1 must be finite and > 0 (unit: m)");
}

TEST_CASE("sensors count, weigh and measure each material inside", "[gameplay]") {
    World world = openWorld();
    const BlobDef w = fluid::test::latticeBlock(world, MaterialId{0}, 0.0f, 0.0f, 10, 10);
    const uint32_t waterCount = world.spawnBlob(w);
    const BlobDef y = fluid::test::latticeBlock(world, MaterialId{1}, 0.2f, 0.0f, 8, 8);
    const uint32_t yoghurtCount = world.spawnBlob(y);
    SensorDef all;
    all.shape = Shape::box({-0.1f, -0.1f}, {0.5f, 0.3f});
    const SensorId sAll = world.addSensor(all);
    SensorDef left;
    left.shape = Shape::circle({0.05f, 0.05f}, 0.12f);
    const SensorId sLeft = world.addSensor(left);
    CHECK(world.sensorReading(sAll)[0].count == 0); // nothing measured before a step
    world.step(kFrame);
    const auto r = world.sensorReading(sAll);
    REQUIRE(r.size() == 2);
    CHECK(r[0].count == waterCount);
    CHECK(r[1].count == yoghurtCount);
    CHECK(r[0].mass == Approx(waterCount * 0.013f));
    const float waterArea = particleArea(water(), world.def().depth);
    CHECK(r[0].area == Approx(waterCount * waterArea));
    CHECK(r[0].volume == Approx(r[0].area * world.def().depth));
    // A 10 x 10 lattice block covers 0.1 x 0.1 m.
    CHECK(r[0].area == Approx(0.01f).epsilon(0.01));
    const auto l = world.sensorReading(sLeft);
    CHECK(l[0].count == waterCount); // the circle holds the whole water block
    CHECK(l[1].count == 0);
    CHECK(world.sensorCount() == 2);
    CHECK(area(left.shape) == Approx(3.14159265f * 0.12f * 0.12f));
    CHECK_THROWS_WITH(world.sensorReading(SensorId{5}),
                      "World::sensorReading: unknown sensor id 5; the world has 2 sensors");
}

TEST_CASE("removal events are the same for 1, 2 and 4 workers", "[gameplay]") {
    auto run = [](uint32_t workers) {
        World world = openWorld(workers);
        world.addForce(std::make_unique<GravityForce>(0.0f, -9.81f));
        EmitterDef def = faucet({0.0f, 0.0f});
        def.jitter = 0.2f;
        def.lifetime = 0.3f;
        world.addEmitter(def);
        DrainDef sink;
        sink.shape = Shape::box({0.1f, -1.0f}, {0.3f, -0.05f});
        world.addDrain(sink);
        uint64_t hash = 0;
        for (int f = 0; f < 40; ++f) {
            world.step(kFrame);
            for (const RemovedEvent& e : world.removedEvents()) {
                // Each run's world has a tag of its own (tags are never reused): the slot,
                // generation and indices are what the workers must agree on.
                REQUIRE(e.particle.world != 0);
                REQUIRE(e.material.world == e.particle.world);
                const std::string record = fluid::test::removalRecord(e);
                hash = fluid::test::fnv1a(record.data(), record.size(), hash);
            }
        }
        return hash ^ fluid::test::stateHash(world);
    };
    const uint64_t one = run(1);
    CHECK(run(2) == one);
    CHECK(run(4) == one);
}

TEST_CASE("emitters and blobs refuse absurd sizes without undefined behaviour", "[gameplay]") {
    World world = openWorld();
    Material dust = water();
    dust.name = "dust";
    // The finest spacing a world takes, 1 mm.
    dust.mass = kMinSpacing * kMinSpacing * dust.restDensity * world.def().depth;
    dust.smoothingDistance = 4.0f * kMinSpacing;
    const MaterialId id = world.addMaterial(dust);
    EmitterDef def = faucet({0.0f, 0.0f});
    def.material = id;
    def.width = 100.0f;
    CHECK_THROWS_WITH(world.addEmitter(def),
                      "World::addEmitter: width = 100 m is 100001 lanes at 0.001 m "
                      "spacing; at most 10000");
    // A blob thinner than one spacing holds no lattice point, however long it is.
    BlobDef sliver;
    sliver.material = id;
    sliver.shape.halfExtents = {200.0f, 0.0004f};
    CHECK(world.spawnBlob(sliver) == 0);
    // Larger than the position range: refused with the range and the material that sets it.
    sliver.shape.halfExtents = {1e30f, 0.0004f};
    CHECK_THROWS_WITH(world.spawnBlob(sliver),
                      "spawnBlob: the shape's lower corner = (-1e+30, -0.0004) is outside the "
                      "position range [-262.144, 262.144] (unit: m; 2^18 spacings of the finest "
                      "material, 'dust' at 0.001 m; docs/gameplay.md, Far from the origin)");
    BlobDef huge;
    huge.material = id;
    huge.shape.halfExtents = {200.0f, 200.0f};
    CHECK_THROWS_WITH(world.spawnBlob(huge),
                      "spawnBlob: particle cap exceeded: the blob needs about 1.59999e+11 "
                      "particles; maxParticles = 1048576");
}

namespace {

// A force whose prepare hook throws while `fail` is set: a plugin finding bad state.
class FailingForce final : public ForcePlugin {
public:
    static constexpr std::array<ParamDecl, 1> kParams{
        {{"fail", "1", 1.0, 0.0, 1.0, "1 makes prepare throw."}}};
    FailingForce() : ForcePlugin("force.test_failing", kParams) {}
    void prepare(const StepContext&) override {
        if (value(0) >= 0.5) {
            throw Error("plugin 'force.test_failing': asked to fail");
        }
    }
    void apply(const ForceContext&, uint32_t, uint32_t) override {}
};

} // namespace

TEST_CASE("a plugin that throws from prepare leaves the world as it was, emitters included",
          "[gameplay]") {
    auto build = [](bool failing) {
        World world = openWorld();
        EmitterDef def = faucet({0.0f, 0.0f});
        def.jitter = 0.3f;
        def.lifetime = 0.05f;
        world.addEmitter(def);
        world.addForce(std::make_unique<GravityForce>(0.0f, -9.81f));
        ForcePlugin& plugin = world.addForce(std::make_unique<FailingForce>());
        plugin.setParam("fail", 0.0);
        for (int f = 0; f < 5; ++f) {
            world.step(kFrame); // some particles, some expired: free slots in the table
        }
        if (failing) {
            plugin.setParam("fail", 1.0);
            const uint32_t count = world.particleCount();
            const uint32_t emitted = world.emittedCount(EmitterId{0});
            const double time = world.time();
            for (int k = 0; k < 3; ++k) {
                CHECK_THROWS_WITH(world.step(kFrame), "plugin 'force.test_failing': asked to fail");
            }
            CHECK(world.particleCount() == count);
            CHECK(world.emittedCount(EmitterId{0}) == emitted);
            CHECK(world.time() == time);
            plugin.setParam("fail", 0.0);
        }
        for (int f = 0; f < 5; ++f) {
            world.step(kFrame);
        }
        return fluid::test::stateHash(world) ^ world.emittedCount(EmitterId{0});
    };
    CHECK(build(true) == build(false));
}

TEST_CASE("long lifetimes run down exactly, tiny and huge jet directions are fine", "[gameplay]") {
    World world = openWorld();
    const ParticleHandle h = world.addParticle({0.0f, 0.0f}, {0.0f, 0.0f}, MaterialId{0});
    world.setLifetime(h, 1e6f);
    for (int f = 0; f < 600; ++f) {
        world.step(kFrame);
    }
    // Ten seconds off a million: a float countdown would not have moved at all.
    CHECK(world.lifetime(h) == Approx(1e6 - 10.0).margin(0.1));
    for (const glm::vec2 dir : {glm::vec2(1e-25f, 0.0f), glm::vec2(1e20f, 1e20f)}) {
        World jet = openWorld();
        EmitterDef def = faucet({0.0f, 0.0f});
        def.direction = dir;
        jet.addEmitter(def);
        jet.step(kFrame);
        REQUIRE(jet.particleCount() == 10);
        CHECK(fluid::test::allFinite(jet));
        const float speed = std::hypot(jet.velocityX()[0], jet.velocityY()[0]);
        CHECK(speed == Approx(1.5f).margin(0.05f));
    }
}

TEST_CASE("shapes far from the origin keep their area and validity", "[gameplay]") {
    const glm::vec2 o{10000.0f, 10000.0f};
    const Shape cup = Shape::polygon(
        {o, o + glm::vec2(0.3f, 0.0f), o + glm::vec2(0.3f, 0.2f), o + glm::vec2(0.0f, 0.2f)});
    CHECK_NOTHROW(validate(cup, "test"));
    // 0.3 x 0.2 m up to the float rounding of the corners (1 mm at 1e4 m).
    CHECK(area(cup) == Approx(0.06f).epsilon(0.01));
}

TEST_CASE("setMaterial keeps emitters valid, the registry refuses duplicate parameters",
          "[gameplay]") {
    World world = openWorld();
    world.addEmitter(faucet({0.0f, 0.0f})); // 600/s of 748 allowed at water's spacing
    Material heavy = water();
    heavy.mass = 0.03f; // a wider spacing: fewer lanes and a lower limit than 600/s
    heavy.smoothingDistance = 0.05f; // 3.3 of its spacings
    CHECK_THROWS_WITH(world.setMaterial(MaterialId{0}, heavy),
                      Catch::Matchers::StartsWith("World::setMaterial: rate = 600 particles/s "
                                                  "overlaps"));
    CHECK(world.material(MaterialId{0}).mass == 0.013f); // unchanged
    static constexpr std::array<ParamDecl, 2> twice{
        {{"a", "1", 0.0, 0.0, 1.0, "first"}, {"a", "1", 0.0, 0.0, 1.0, "again"}}};
    Registry registry;
    CHECK_THROWS_WITH(
        registry.add(PluginInfo{"force.twice", PluginKind::Force, "x", twice,
                                [] { return std::unique_ptr<Plugin>(new GravityForce()); }}),
        "Registry::add: plugin type 'force.twice' declares parameter 'a' twice");
    CHECK(registry.types().empty());
}

TEST_CASE("a value the plugin refuses in onParamChanged reverts, numbers and points alike",
          "[gameplay]") {
    Registry registry;
    registerBuiltinPlugins(registry);
    std::unique_ptr<Plugin> polygon = registry.create("boundary.polygon");
    // A bow tie: its edges cross, which the declaration's count range cannot see.
    const std::vector<glm::vec2> bowTie{{0, 0}, {1, 1}, {1, 0}, {0, 1}};
    CHECK_THROWS_AS(polygon->setPoints("vertices", bowTie), Error);
    CHECK(polygon->points("vertices").empty()); // never had points: still none
    const std::vector<glm::vec2> square{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    polygon->setPoints("vertices", square);
    CHECK_THROWS_AS(polygon->setPoints("vertices", bowTie), Error);
    const auto kept = polygon->points("vertices");
    CHECK(std::vector<glm::vec2>(kept.begin(), kept.end()) == square);
}

TEST_CASE("ids carry their world: another world refuses them, adopt carries them over",
          "[gameplay][bad-input]") {
    World a = openWorld();
    World b = openWorld();
    const MaterialId water = a.addMaterial(fluid::water());
    const EmitterId faucetId = a.addEmitter(faucet({0.0f, 0.0f}));
    DrainDef sinkDef;
    sinkDef.shape = Shape::box({0.1f, -1.0f}, {0.3f, -0.05f});
    const DrainId sink = a.addDrain(sinkDef);
    SensorDef cupDef;
    cupDef.shape = Shape::circle({0.0f, 0.0f}, 0.2f);
    const SensorId cup = a.addSensor(cupDef);
    b.addEmitter(faucet({0.0f, 0.0f}));
    b.addDrain(sinkDef);
    b.addSensor(cupDef);
    // Every id names the world that made it, as the world's particle handles do.
    const uint32_t tagA = a.addParticle({0.5f, 0.5f}, {0.0f, 0.0f}, water).world;
    const uint32_t tagB = b.adopt(ParticleHandle{0, 1, tagA}).world;
    REQUIRE(tagA != 0);
    REQUIRE(tagB != tagA);
    CHECK(water.world == tagA);
    CHECK(faucetId.world == tagA);
    CHECK(sink.world == tagA);
    CHECK(cup.world == tagA);
    // Another world refuses them, naming both worlds, even where the index exists there.
    const std::string worlds = " was made by another world (world " + std::to_string(tagA) +
                               "; this is world " + std::to_string(tagB) +
                               "; an id kept from the world a snapshot was saved from needs "
                               "World::adopt)";
    CHECK_THROWS_WITH(b.material(water), "material id 2" + worlds);
    CHECK_THROWS_WITH(b.addParticle({0.0f, 0.0f}, {0.0f, 0.0f}, water), "material id 2" + worlds);
    CHECK_THROWS_WITH(b.emitter(faucetId), "World::emitter: emitter id 0" + worlds);
    CHECK_THROWS_WITH(b.setEmitter(faucetId, faucet({0.0f, 0.0f})),
                      "World::setEmitter: emitter id 0" + worlds);
    CHECK_THROWS_WITH(b.drain(sink), "World::drain: drain id 0" + worlds);
    CHECK_THROWS_WITH(b.sensorReading(cup), "World::sensorReading: sensor id 0" + worlds);
    // An id made by hand from an index is taken as that index by any world.
    CHECK(b.material(MaterialId{1}).name == a.material(MaterialId{1}).name);
    CHECK(b.emitter(EmitterId{0}).position == glm::vec2(0.0f, 0.0f));
    // Equal when the indices are: the tag says which world made an id, not what it names.
    CHECK(water == MaterialId{2});
    CHECK(b.adopt(water) == water);
    // A world loaded from a snapshot is another world; adopt carries the ids over.
    std::stringstream bytes;
    a.save(bytes);
    Registry registry;
    registerBuiltinPlugins(registry);
    const World loaded = World::load(bytes, registry);
    CHECK_THROWS_AS(loaded.material(water), Error);
    CHECK(loaded.material(loaded.adopt(water)).name == a.material(water).name);
    CHECK(loaded.emitter(loaded.adopt(faucetId)).direction == glm::vec2(1.0f, 0.0f));
    CHECK(loaded.drain(loaded.adopt(sink)).shape.center == sinkDef.shape.center);
    CHECK(loaded.sensor(loaded.adopt(cup)).shape.radius == cupDef.shape.radius);
    CHECK(loaded.adopt(water).world != tagA);
}
