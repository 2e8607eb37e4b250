// Bad input: clear errors that name the value, the world left unchanged, no NaN spreading.
#include "test_support.h"

#include <catch2/catch.hpp>

#include <limits>

using namespace fluid;
using namespace fluid::test;

namespace {

struct Snapshot {
    std::vector<float> px, py, vx, vy, rho;
    double time = 0.0;
    uint32_t substeps = 0;
    explicit Snapshot(const World& w)
        : px(w.positionX().begin(), w.positionX().end()),
          py(w.positionY().begin(), w.positionY().end()),
          vx(w.velocityX().begin(), w.velocityX().end()),
          vy(w.velocityY().begin(), w.velocityY().end()),
          rho(w.density().begin(), w.density().end()), time(w.time()), substeps(w.lastSubsteps()) {}
    bool operator==(const Snapshot&) const = default;
};

// A force plugin that writes a non-finite value into some particles' acceleration (a broken
// user plugin).
class BrokenForce final : public ForcePlugin {
public:
    static constexpr std::array<ParamDecl, 0> kParams{};
    explicit BrokenForce(float bad) : ForcePlugin("force.test-broken", kParams), m_bad(bad) {}
    void apply(const ForceContext& ctx, uint32_t begin, uint32_t end) override {
        for (uint32_t i = begin; i < end; ++i) {
            if (i % 97 == 5) {
                ctx.ax[i] = m_bad;
            }
            if (i % 101 == 7) {
                ctx.ay[i] += m_bad;
            }
        }
    }

private:
    float m_bad;
};

} // namespace

TEST_CASE("World::step rejects a bad frameDt and leaves the world unchanged", "[unit][bad-input]") {
    World world;
    const MaterialId w = world.addMaterial(water());
    world.addForce(std::make_unique<GravityForce>());
    world.addBoundary(std::make_unique<BoxContainer>(-0.2f, 0.0f, 0.2f, 0.4f));
    world.spawnBlob(latticeBlock(world, w, -0.1f, 0.0f, 10, 10));
    world.step(kFrame);
    const Snapshot before(world);
    REQUIRE(before.time > 0.0);

    const std::string tail =
        " s is out of range; expected a finite value in (0, 1] (typically 1/60)";
    CHECK_THROWS_MATCHES(world.step(0.0f), Error,
                         Catch::Message("World::step: frameDt = 0" + tail));
    CHECK_THROWS_MATCHES(world.step(-1.0f), Error,
                         Catch::Message("World::step: frameDt = -1" + tail));
    CHECK_THROWS_MATCHES(world.step(kNaN), Error,
                         Catch::Message("World::step: frameDt = nan" + tail));
    CHECK_THROWS_MATCHES(world.step(kInf), Error,
                         Catch::Message("World::step: frameDt = inf" + tail));
    CHECK_THROWS_MATCHES(world.step(-kInf), Error,
                         Catch::Message("World::step: frameDt = -inf" + tail));
    CHECK_THROWS_MATCHES(world.step(2.0f), Error,
                         Catch::Message("World::step: frameDt = 2" + tail));
    CHECK(Snapshot(world) == before);
    // The world still steps normally afterwards.
    world.step(kFrame);
    CHECK(world.time() == Approx(2.0 * kFrame));
    CHECK(allFinite(world));
}

TEST_CASE("World::step without a material throws", "[unit][bad-input]") {
    World world;
    CHECK_THROWS_MATCHES(
        world.step(kFrame), Error,
        Catch::Message("World::step: the world has no material; call addMaterial first"));
}

TEST_CASE("WorldDef with NaN or out-of-range fields throws", "[unit][bad-input]") {
    WorldDef def;
    SECTION("NaN depth") {
        def.depth = kNaN;
        CHECK_THROWS_MATCHES(World(def), Error,
                             Catch::Message("WorldDef: depth = nan is out of range [0.0001, 1000] "
                                            "(unit: m)"));
    }
    SECTION("negative depth") {
        def.depth = -1.0f;
        CHECK_THROWS_MATCHES(World(def), Error,
                             Catch::Message("WorldDef: depth = -1 is out of range [0.0001, 1000] "
                                            "(unit: m)"));
    }
    SECTION("negative courant") {
        def.courant = -0.4f;
        CHECK_THROWS_MATCHES(World(def), Error,
                             Catch::Message("WorldDef: courant = -0.4 is out of range [0.01, 1] "
                                            "(unit: 1)"));
    }
    SECTION("NaN sound speed") {
        def.soundSpeed = kNaN;
        CHECK_THROWS_MATCHES(World(def), Error,
                             Catch::Message("WorldDef: soundSpeed = nan is out of range: 0 (derive "
                                            "from the scene) or [0.1, 10000] (unit: m/s)"));
    }
    SECTION("negative sound speed") {
        def.soundSpeed = -5.0f;
        CHECK_THROWS_MATCHES(World(def), Error,
                             Catch::Message("WorldDef: soundSpeed = -5 is out of range: 0 (derive "
                                            "from the scene) or [0.1, 10000] (unit: m/s)"));
    }
    SECTION("zero workers") {
        def.workerCount = 0;
        CHECK_THROWS_MATCHES(World(def), Error,
                             Catch::Message("WorldDef: workerCount = 0 is out of range [1, 256] "
                                            "(unit: count)"));
    }
    SECTION("zero particle cap") {
        def.maxParticles = 0;
        CHECK_THROWS_AS(World(def), Error);
    }
    SECTION("zero sub-step cap") {
        def.maxSubsteps = 0;
        CHECK_THROWS_AS(World(def), Error);
    }
    SECTION("a sub-step cap that would let one frame take seconds") {
        def.maxSubsteps = 1001;
        CHECK_THROWS_MATCHES(World(def), Error,
                             Catch::Message("WorldDef: maxSubsteps = 1001 is out of range "
                                            "[1, 1000] (unit: count)"));
    }
    SECTION("zero position-based sub-steps") {
        def.positionBased.substeps = 0;
        CHECK_THROWS_MATCHES(World(def), Error,
                             Catch::Message("WorldDef: positionBased.substeps = 0 is out of range "
                                            "[1, 12] (unit: count)"));
    }
    SECTION("too many position-based iterations") {
        def.positionBased.iterations = 101;
        CHECK_THROWS_MATCHES(World(def), Error,
                             Catch::Message("WorldDef: positionBased.iterations = 101 is out of "
                                            "range [1, 32] (unit: count)"));
    }
    SECTION("NaN vorticity confinement") {
        def.positionBased.vorticity = kNaN;
        CHECK_THROWS_MATCHES(World(def), Error,
                             Catch::Message("WorldDef: positionBased.vorticity = nan is out of "
                                            "range [0, 1] (unit: 1)"));
    }
    SECTION("enqueue without finish") {
        def.tasks.enqueue = [](TaskCallback*, uint32_t, uint32_t, void*, void*) -> void* {
            return nullptr;
        };
        CHECK_THROWS_MATCHES(
            World(def), Error,
            Catch::Message("WorldDef: tasks.enqueue is set but tasks.finish is null"));
    }
}

TEST_CASE("the particle cap throws and adds nothing", "[unit][bad-input]") {
    WorldDef def;
    def.maxParticles = 100;
    World world(def);
    const MaterialId w = world.addMaterial(water());

    // A blob larger than the cap: rejected as a whole.
    CHECK_THROWS_AS(world.spawnBlob(latticeBlock(world, w, 0.0f, 0.0f, 20, 20)), Error);
    CHECK(world.particleCount() == 0);
    // 90 fit; 50 more would pass the cap: all or nothing.
    REQUIRE(world.spawnBlob(latticeBlock(world, w, 0.0f, 0.0f, 9, 10)) == 90);
    CHECK_THROWS_MATCHES(world.spawnBlob(latticeBlock(world, w, 0.5f, 0.0f, 10, 5)), Error,
                         Catch::Message("spawnBlob: particle cap exceeded: 50 more particles would "
                                        "pass maxParticles = 100"));
    CHECK(world.particleCount() == 90);
    for (int i = 0; i < 10; ++i) {
        world.addParticle({1.0f + 0.02f * float(i), 1.0f}, {0.0f, 0.0f}, w);
    }
    CHECK(world.particleCount() == 100);
    CHECK_THROWS_MATCHES(world.addParticle({2.0f, 2.0f}, {0.0f, 0.0f}, w), Error,
                         Catch::Message("World::addParticle: particle cap exceeded: the world "
                                        "holds maxParticles = 100 particles"));
    CHECK(world.particleCount() == 100);
    world.step(kFrame); // a full world still steps
    CHECK(allFinite(world));
}

TEST_CASE("addParticle rejects non-finite input and unknown materials", "[unit][bad-input]") {
    World world;
    const MaterialId w = world.addMaterial(water());
    CHECK_THROWS_MATCHES(world.addParticle({kNaN, 0.0f}, {0.0f, 0.0f}, w), Error,
                         Catch::Message("World::addParticle: position = (nan, 0) is not finite"));
    CHECK_THROWS_MATCHES(world.addParticle({0.0f, 0.0f}, {0.0f, kInf}, w), Error,
                         Catch::Message("World::addParticle: velocity = (0, inf) is not finite"));
    CHECK_THROWS_MATCHES(world.addParticle({0.0f, 0.0f}, {0.0f, 0.0f}, MaterialId{7}), Error,
                         Catch::Message("unknown material id 7; the world has 1 materials"));
    CHECK(world.particleCount() == 0);
    const ParticleHandle h = world.addParticle({0.0f, 0.0f}, {0.0f, 0.0f}, w);
    CHECK_THROWS_MATCHES(world.setVelocity(h, {kNaN, kNaN}), Error,
                         Catch::Message("World::setVelocity: velocity = (nan, nan) is not finite"));
    CHECK(world.velocity(h) == glm::vec2(0.0f, 0.0f));
    CHECK_THROWS_AS(world.addForce(nullptr), Error);
    CHECK_THROWS_AS(world.addBoundary(nullptr), Error);
}

TEST_CASE("registry and parameters reject unknown names and bad values", "[unit][bad-input]") {
    Registry registry;
    CHECK_THROWS_MATCHES(registry.create("force.gravity"), Error,
                         Catch::Message("unknown plugin type 'force.gravity'; known: (none: call "
                                        "registerBuiltinPlugins first)"));
    registry.add<GravityForce>("Uniform gravity.");
    registry.add<BoxContainer>("A tank.");
    CHECK_THROWS_MATCHES(registry.create("force.nope"), Error,
                         Catch::Message("unknown plugin type 'force.nope'; known: force.gravity "
                                        "boundary.box"));
    CHECK_THROWS_MATCHES(registerBuiltinPlugins(registry), Error,
                         Catch::Message("Registry::add: plugin type 'force.gravity' is already "
                                        "registered"));

    std::unique_ptr<Plugin> g = registry.create("force.gravity");
    CHECK_THROWS_MATCHES(g->setParam("gy", 2000.0), Error,
                         Catch::Message("plugin 'force.gravity': parameter 'gy' = 2000 is out of "
                                        "range [-1000, 1000] (unit: m/s^2)"));
    CHECK_THROWS_MATCHES(g->setParam("gy", std::numeric_limits<double>::quiet_NaN()), Error,
                         Catch::Message("plugin 'force.gravity': parameter 'gy' = nan is not "
                                        "finite; expected [-1000, 1000] (unit: m/s^2)"));
    CHECK_THROWS_MATCHES(g->setParam("gz", 1.0), Error,
                         Catch::Message("plugin 'force.gravity': unknown parameter 'gz'; known: "
                                        "gx gy"));
    CHECK_THROWS_MATCHES(g->param("g"), Error,
                         Catch::Message("plugin 'force.gravity': unknown parameter 'g'; known: "
                                        "gx gy"));
    CHECK(g->param("gy") == Approx(-9.81)); // unchanged by the failed calls

    const std::vector<ParamValue> bad{{"friction", -1.0}};
    CHECK_THROWS_MATCHES(registry.create("boundary.box", bad), Error,
                         Catch::Message("plugin 'boundary.box': parameter 'friction' = -1 is out "
                                        "of range [0, 10] (unit: 1)"));
    CHECK_THROWS_MATCHES(registry.createForce("boundary.box"), Error,
                         Catch::Message("plugin 'boundary.box' is not a force plugin"));
    CHECK_THROWS_MATCHES(registry.createBoundary("force.gravity"), Error,
                         Catch::Message("plugin 'force.gravity' is not a boundary plugin"));
}

TEST_CASE("an empty box container is reported when the world steps", "[unit][bad-input]") {
    World world;
    const MaterialId w = world.addMaterial(water());
    world.addParticle({0.0f, 0.5f}, {0.0f, 0.0f}, w);
    auto& box = world.addBoundary(std::make_unique<BoxContainer>());
    box.setParam("minX", 2.0); // minX > maxX
    CHECK_THROWS_AS(world.step(kFrame), Error);
}

TEST_CASE("a force plugin writing NaN or infinity does not spread it", "[unit][bad-input]") {
    const Solver solver = GENERATE(Solver::PositionBased, Solver::Explicit);
    CAPTURE(solverLabel(solver));
    float bad = kNaN;
    SECTION("NaN") {
        bad = kNaN;
    }
    SECTION("infinity") {
        bad = kInf;
    }
    CAPTURE(bad);
    WorldDef def;
    def.solver = solver;
    World world(def);
    const MaterialId w = world.addMaterial(water());
    world.addForce(std::make_unique<GravityForce>());
    world.addForce(std::make_unique<BrokenForce>(bad));
    world.addBoundary(std::make_unique<BoxContainer>(-0.15f, 0.0f, 0.15f, 0.4f));
    world.spawnBlob(latticeBlock(world, w, -0.15f, 0.0f, 30, 12));
    uint32_t repaired = 0;
    for (int frame = 0; frame < 10; ++frame) {
        CAPTURE(frame);
        world.step(kFrame);
        repaired += world.profile().nonFiniteRepaired;
        CAPTURE(world.profile().soundSpeed, world.profile().substeps);
        REQUIRE(allFinite(world));
        const auto p = world.pressure();
        for (uint32_t i = 0; i < world.particleCount(); ++i) {
            REQUIRE(std::isfinite(p[i]));
        }
        REQUIRE(countOutside(world, -0.15f, 0.0f, 0.15f, 0.4f) == 0);
        REQUIRE(std::isfinite(world.profile().soundSpeed));
        REQUIRE(std::isfinite(world.profile().densityErrorMax));
    }
    CHECK(repaired == 0); // dropped per plugin before the integration had to repair anything
    CHECK(world.profile().forceDropped > 0);
    CHECK(world.profile().forceDroppedPlugin == 1); // the broken one, not gravity (0)
}

TEST_CASE("a force plugin's non-finite value drops only that plugin's contribution",
          "[unit][bad-input]") {
    // Zero-g blob: gravity pulls every particle, the broken plugin poisons some of them. Those
    // keep gravity's pull; before, their whole acceleration was zeroed.
    World world;
    const MaterialId w = world.addMaterial(water());
    world.addForce(std::make_unique<GravityForce>(0.0f, -9.81f));
    world.addForce(std::make_unique<BrokenForce>(kNaN));
    world.addParticle({0.0f, 0.0f}, {0.0f, 0.0f}, w);
    for (uint32_t k = 1; k < 200; ++k) {
        world.addParticle({float(k), 0.0f}, {0.0f, 0.0f}, w); // 1 m apart: no pair forces
    }
    world.step(kFrame);
    // Every isolated particle fell alike, the poisoned ones (array index 5, 102, 199; 7, 108)
    // included.
    const auto vy = world.velocityY();
    for (uint32_t i = 0; i < world.particleCount(); ++i) {
        INFO("particle " << i);
        CHECK(vy[i] == Approx(-9.81f * kFrame).epsilon(1e-4));
    }
    CHECK(world.profile().forceDropped > 0);
    CHECK(world.profile().forceDroppedPlugin == 1);
    CHECK(world.profile().nonFiniteRepaired == 0);
}
