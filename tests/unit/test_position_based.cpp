// The position-based solver's settings, its pressure reading and its vorticity confinement.
#include "test_support.h"

#include <catch2/catch.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

using namespace fluid;
using namespace fluid::test;

namespace {

// A resting water block in a box under gravity: 20 columns, `rows` rows.
World tank(uint32_t rows, WorldDef def = {}) {
    World world(def);
    const MaterialId w = world.addMaterial(water());
    const float s = world.spacing(w);
    world.addForce(std::make_unique<GravityForce>(0.0f, -kG));
    world.addBoundary(std::make_unique<BoxContainer>(0.0f, 0.0f, 20.0f * s, 1.0f));
    world.spawnBlob(latticeBlock(world, w, 0.0f, 0.0f, 20, rows));
    return world;
}

} // namespace

TEST_CASE("position-based settings change between steps and show in the profile",
          "[unit][position-based]") {
    World world = tank(10);
    REQUIRE(world.def().solver == Solver::PositionBased);
    world.step(kFrame);
    CHECK(world.lastSubsteps() == world.def().positionBased.substeps);
    CHECK(world.profile().iterations == world.def().positionBased.iterations);
    CHECK(world.profile().densityErrorMax >= world.profile().densityErrorAvg);

    PositionBasedDef settings;
    settings.substeps = 2;
    settings.iterations = 3;
    world.setPositionBased(settings);
    CHECK(world.def().positionBased.substeps == 2);
    world.step(kFrame);
    CHECK(world.lastSubsteps() == 2);
    CHECK(world.profile().iterations == 3);

    PositionBasedDef bad = settings;
    bad.iterations = 0;
    CHECK_THROWS_MATCHES(world.setPositionBased(bad), Error,
                         Catch::Message("World::setPositionBased: iterations = 0 is out of range "
                                        "[1, 32] (unit: count)"));
    bad = settings;
    bad.vorticity = -1.0f;
    CHECK_THROWS_MATCHES(world.setPositionBased(bad), Error,
                         Catch::Message("World::setPositionBased: vorticity = -1 is out of range "
                                        "[0, 1] (unit: 1)"));
    bad.vorticity = std::numeric_limits<float>::infinity();
    CHECK_THROWS_AS(world.setPositionBased(bad), Error);
    // Unchanged by the rejected calls.
    CHECK(world.def().positionBased.iterations == 3);
    CHECK(world.def().positionBased.vorticity == 0.0f);
    world.step(kFrame);
    CHECK(world.lastSubsteps() == 2);
    CHECK(allFinite(world));
}

TEST_CASE("the long-frame rule: substepsFor(dt) is the sub-steps step(dt) takes, at any rate",
          "[unit][position-based]") {
    // The rule itself: the setting up to a tenth over 1/60 s, then per 1/60 s, rounded up.
    CHECK(frameSubsteps(4, 1.0f / 60.0f) == 4);
    CHECK(frameSubsteps(4, 1.0f / 59.94f) == 4);
    CHECK(frameSubsteps(4, 1.0f / 240.0f) == 4);
    CHECK(frameSubsteps(4, 1.0f / 50.0f) == 5);
    CHECK(frameSubsteps(4, 0.1f) == 24);
    CHECK(frameSubsteps(4, 0.5f) == 120);
    CHECK(frameSubsteps(4, 1.0f) == 240);
    CHECK(frameSubsteps(1, 1.0f) == 60);
    CHECK(frameSubsteps(64, 1.0f) == 3834); // ceil(3840 - 6.4): the slack stays
    const std::string tail =
        " s is out of range; expected a finite value in (0, 1] (typically 1/60)";
    CHECK_THROWS_MATCHES(frameSubsteps(4, 0.0f), Error,
                         Catch::Message("fluid::frameSubsteps: frameDt = 0" + tail));
    CHECK_THROWS_MATCHES(frameSubsteps(4, 2.0f), Error,
                         Catch::Message("fluid::frameSubsteps: frameDt = 2" + tail));
    CHECK_THROWS_MATCHES(frameSubsteps(0, kFrame), Error,
                         Catch::Message("fluid::frameSubsteps: perFrame = 0 is out of range "
                                        "[1, 64] (unit: count)"));
    CHECK_THROWS_MATCHES(frameSubsteps(65, kFrame), Error,
                         Catch::Message("fluid::frameSubsteps: perFrame = 65 is out of range "
                                        "[1, 64] (unit: count)"));

    // The world's count is the one its step takes.
    World world = tank(6);
    PositionBasedDef settings;
    settings.substeps = 3;
    world.setPositionBased(settings);
    for (const float dt : {kFrame, 1.0f / 30.0f, 0.1f, 0.5f, 1.0f}) {
        CAPTURE(dt);
        const uint32_t planned = world.substepsFor(dt);
        CHECK(planned == frameSubsteps(3, dt));
        world.step(dt);
        CHECK(world.lastSubsteps() == planned);
    }
    CHECK(world.substepsFor(1.0f) == 180);
    CHECK_THROWS_MATCHES(world.substepsFor(std::numeric_limits<float>::quiet_NaN()), Error,
                         Catch::Message("World::substepsFor: frameDt = nan" + tail));
    CHECK_THROWS_MATCHES(world.substepsFor(-1.0f), Error,
                         Catch::Message("World::substepsFor: frameDt = -1" + tail));
    CHECK(allFinite(world));
}

namespace {

// One water particle in a box: the cheapest world that keeps the clock.
World oneParticle() {
    World world;
    const MaterialId w = world.addMaterial(water());
    world.addBoundary(std::make_unique<BoxContainer>(0.0f, 0.0f, 1.0f, 1.0f));
    world.spawnBlob(latticeBlock(world, w, 0.5f, 0.5f, 1, 1));
    return world;
}

// Steps `world` with the frames `next` gives; per frame the sub-steps taken are counted in
// `taken` (index: sub-steps), the most |time() - sum of frames| is kept, and the frames after
// which time() + carriedTime() is not the sum of the frames given (s, summed in double).
struct ClockRun {
    double given = 0.0;       // sum of the frames (s)
    double farthest = 0.0;    // most |time() - given| after a frame (s)
    uint32_t taken[4] = {};   // frames that took 0, 1, 2, 3+ sub-steps
    uint32_t zeroThenTwo = 0; // frames of two sub-steps right after one of none
    uint32_t unbalanced = 0;  // frames after which time() + carriedTime() != given
};
template <class Next> ClockRun runClock(World& world, uint32_t frames, Next next) {
    ClockRun run;
    uint32_t previous = 1;
    for (uint32_t f = 0; f < frames; ++f) {
        const float dt = next();
        world.step(dt);
        run.given += double(dt);
        const uint32_t n = world.lastSubsteps();
        ++run.taken[std::min(n, 3u)];
        run.zeroThenTwo += previous == 0 && n == 2 ? 1 : 0;
        previous = n;
        run.farthest = std::max(run.farthest, std::fabs(world.time() - run.given));
        if (std::fabs(world.time() + world.carriedTime() - run.given) > 1e-9) {
            if (run.unbalanced == 0) {
                UNSCOPED_INFO("first at frame " << f << ": time " << world.time()
                                                << " s + carried " << world.carriedTime()
                                                << " s, frames " << run.given << " s");
            }
            ++run.unbalanced;
        }
    }
    CHECK(run.unbalanced == 0);
    return run;
}

} // namespace

TEST_CASE("the world's clock tracks the sum of the frames: a frame a little short of a "
          "sub-step takes it and the next ones pay it back",
          "[unit][position-based][clock]") {
    World world = oneParticle();
    const double h = world.substepLength();
    REQUIRE(float(h) == 1.0f / 240.0f);

    SECTION("2,400 frames of 1/240 s - 1e-7 s: one sub-step each, the time within a sub-step "
            "of their sum") {
        const float shortFrame = float(1.0 / 240.0 - 1e-7);
        const ClockRun run = runClock(world, 2400, [&] { return shortFrame; });
        CHECK(run.taken[1] == 2400);
        CHECK(std::fabs(world.time() - 2400.0 * double(shortFrame)) < h);
        CHECK(run.given == Approx(9.99976).epsilon(1e-6));
        CHECK(world.carriedTime() == Approx(-2400.0 * (h - double(shortFrame))));
    }
    SECTION("12,000 frames of 1/240 s - 4e-7 s: the time stays within half a sub-step of their "
            "sum, one sub-step skipped, none doubled") {
        // 4e-7 s is just under what a frame could fall short before and still take its whole
        // sub-step, forgetting the shortfall: over these frames the clock ran 1.15 sub-steps
        // ahead, and on without bound.
        const float shortFrame = float(1.0 / 240.0 - 4e-7);
        const ClockRun run = runClock(world, 12000, [&] { return shortFrame; });
        CHECK(run.farthest <= 0.5 * h);
        CHECK(run.taken[0] == 1); // the frames' sum is 11,998.85 sub-steps
        CHECK(run.taken[2] + run.taken[3] == 0);
        CHECK(run.taken[1] == 11999);
    }
    SECTION("frames of exactly 1/240 s step exactly once each and carry nothing") {
        const ClockRun run = runClock(world, 2400, [] { return 1.0f / 240.0f; });
        CHECK(run.taken[1] == 2400);
        CHECK(world.carriedTime() == 0.0);
        CHECK(world.time() == 2400.0 * h);
    }
    SECTION("frames of 1/240 s with a jitter of +-1e-7 s step once each, never none then two") {
        uint64_t state = 2024;
        const ClockRun run = runClock(world, 10000, [&] {
            state = state * 6364136223846793005ull + 1442695040888963407ull; // LCG, fixed seed
            const double u = double(state >> 11) / double(uint64_t(1) << 53);
            return float(1.0 / 240.0 + (2.0 * u - 1.0) * 1e-7);
        });
        CHECK(run.taken[1] == 10000);
        CHECK(run.zeroThenTwo == 0);
        CHECK(run.farthest <= 0.5 * h);
    }
    SECTION("1/1000 s frames: a sub-step every fourth or fifth frame, the time within half a "
            "sub-step of the frames'") {
        const ClockRun run = runClock(world, 1200, [] { return 0.001f; });
        CHECK(run.taken[1] == 288); // 1.2 s of 1/240 s
        CHECK(run.taken[0] == 1200 - 288);
        CHECK(run.farthest <= 0.5 * h);
    }
}

TEST_CASE("a resting tank's pressure grows with depth as rho0 g d", "[unit][position-based]") {
    const uint32_t rows = 20;
    World world = tank(rows);
    for (int frame = 0; frame < 90; ++frame) {
        world.step(kFrame);
    }
    REQUIRE(allFinite(world));
    const Material& m = world.material(MaterialId{0});
    const float s = world.spacing(MaterialId{0});
    const float surface = float(rows) * s; // the block's top edge
    // Mean pressure of the particles in horizontal bands, away from the side walls' corners.
    const auto px = world.positionX(), py = world.positionY(), p = world.pressure();
    double bandSum[4] = {}, bandDepth[4] = {};
    uint32_t bandCount[4] = {};
    for (uint32_t i = 0; i < world.particleCount(); ++i) {
        const float depth = surface - py[i];
        const auto band = static_cast<int>(depth / (0.25f * surface));
        if (band < 0 || band > 3 || px[i] < 3.0f * s || px[i] > 17.0f * s) {
            continue;
        }
        bandSum[band] += p[i];
        bandDepth[band] += depth;
        ++bandCount[band];
    }
    // The top band is the free surface's (pressure near 0); the three below read hydrostatics.
    for (int band = 1; band < 4; ++band) {
        REQUIRE(bandCount[band] > 20);
        const double mean = bandSum[band] / bandCount[band];
        const double expected = m.restDensity * kG * bandDepth[band] / bandCount[band];
        CAPTURE(band, mean, expected);
        CHECK(mean == Approx(expected).epsilon(0.25));
    }
}

TEST_CASE("vorticity confinement keeps a spinning zero-g blob spinning longer",
          "[unit][position-based]") {
    auto spin = [](float vorticity) {
        WorldDef def;
        def.positionBased.vorticity = vorticity;
        World world(def);
        const MaterialId w = world.addMaterial(water());
        BlobDef blob;
        blob.shape.type = ShapeType::Circle;
        blob.shape.radius = 0.1f;
        blob.material = w;
        world.spawnBlob(blob);
        // Rigid rotation at 10 rad/s about the centre.
        for (uint32_t i = 0; i < world.particleCount(); ++i) {
            const ParticleHandle h = world.handleAt(i);
            const glm::vec2 x = world.position(h);
            world.setVelocity(h, {-10.0f * x.y, 10.0f * x.x});
        }
        const double e0 = kineticPerMass(world);
        for (int frame = 0; frame < 30; ++frame) {
            world.step(kFrame);
        }
        REQUIRE(allFinite(world));
        return kineticPerMass(world) / e0;
    };
    const double plain = spin(0.0f);
    const double confined = spin(0.5f);
    CAPTURE(plain, confined);
    CHECK(plain < 1.0);      // viscosity spins it down
    CHECK(confined > plain); // confinement gives some rotation back
}

TEST_CASE("particles stacked on one point are parted, by either solver, the same for any workers",
          "[unit][position-based]") {
    // Three particles on one point and a pair on another, in zero gravity, at rest. The pair
    // terms have no direction between particles at one point: without separateStacked they
    // stay stacked for good (the 16k dam's front stacked 52 particles in a wall corner).
    const Solver solver = GENERATE(Solver::PositionBased, Solver::Explicit);
    CAPTURE(solverLabel(solver));
    std::vector<glm::vec2> last;
    for (const uint32_t workers : {1u, 3u}) {
        WorldDef def;
        def.solver = solver;
        def.workerCount = workers;
        World world(def);
        const MaterialId w = world.addMaterial(water());
        const float s = world.spacing(w);
        world.addBoundary(std::make_unique<BoxContainer>(-1.0f, -1.0f, 1.0f, 1.0f));
        std::vector<ParticleHandle> handles;
        for (int k = 0; k < 3; ++k) {
            handles.push_back(world.addParticle({0.1f, 0.2f}, {0.0f, 0.0f}, w));
        }
        for (int k = 0; k < 2; ++k) {
            handles.push_back(world.addParticle({-0.3f, 0.0f}, {0.0f, 0.0f}, w));
        }
        world.step(kFrame);
        // Two of the three and one of the pair are moved in the first sub-step.
        CHECK(world.profile().separated == 3);
        for (int f = 0; f < 30; ++f) {
            world.step(kFrame);
        }
        CHECK(world.profile().separated == 0);
        std::vector<glm::vec2> at;
        for (const ParticleHandle h : handles) {
            at.push_back(world.position(h));
        }
        for (size_t i = 0; i < at.size(); ++i) {
            CAPTURE(i, at[i].x, at[i].y);
            CHECK(std::isfinite(at[i].x));
            CHECK(std::isfinite(at[i].y));
            for (size_t j = 0; j < i; ++j) {
                // Parted to at least half a spacing (the pressure pushes them apart once they
                // have a direction).
                CHECK(glm::length(at[i] - at[j]) > 0.5f * s);
            }
        }
        // Momentum: the cluster's centre stays where it was (no net push).
        glm::vec2 centre3{0.0f, 0.0f}, centre2{0.0f, 0.0f};
        for (int k = 0; k < 3; ++k) {
            centre3 += at[size_t(k)] / 3.0f;
        }
        for (int k = 3; k < 5; ++k) {
            centre2 += at[size_t(k)] / 2.0f;
        }
        CHECK(centre3.x == Approx(0.1f).margin(1e-3));
        CHECK(centre3.y == Approx(0.2f).margin(1e-3));
        CHECK(centre2.x == Approx(-0.3f).margin(1e-3));
        CHECK(centre2.y == Approx(0.0f).margin(1e-3));
        if (!last.empty()) {
            CHECK(at == last); // bit-identical for 1 and 3 workers
        }
        last = at;
        // Emptied, stepped, then one particle again: nothing to part, nothing read out of range.
        for (const ParticleHandle h : handles) {
            world.removeParticle(h);
        }
        world.step(kFrame);
        CHECK(world.profile().separated == 0);
        const ParticleHandle alone = world.addParticle({0.1f, 0.2f}, {0.0f, 0.0f}, w);
        world.step(kFrame);
        CHECK(world.profile().separated == 0);
        CHECK(world.position(alone) == glm::vec2(0.1f, 0.2f));
    }
}

TEST_CASE("the profile names each solver's stages in the order a step runs them",
          "[unit][profile]") {
    const std::vector<std::string> positionBased = {
        "prepare",  "external",  "predict", "sort",       "coarse", "density sweeps",
        "velocity", "viscosity", "surface", "boundaries", "finish"};
    const std::vector<std::string> explicitSph = {"prepare",  "sort",      "external",
                                                  "probe",    "density",   "pressure",
                                                  "forces",   "integrate", "boundaries",
                                                  "finish"};
    for (const Solver solver : {Solver::PositionBased, Solver::Explicit}) {
        INFO(solverLabel(solver));
        WorldDef def;
        def.solver = solver;
        World world = tank(10, def);
        CHECK(world.profile().stageTimes().empty());
        world.step(kFrame);
        const Profile& profile = world.profile();
        std::vector<std::string> names;
        double sum = 0.0;
        for (const StageTime& t : profile.stageTimes()) {
            names.emplace_back(t.name);
            CHECK(t.ms >= 0.0f);
            sum += t.ms;
        }
        CHECK(names == (solver == Solver::PositionBased ? positionBased : explicitSph));
        // The stages are parts of the step: together no longer than it.
        CHECK(sum <= double(profile.step) + 1e-3);
        CHECK(profile.stage("sort") == profile.stages[names[1] == "sort" ? 1 : 3].ms);
        CHECK(profile.stage("no such stage") == 0.0f);
    }
}
