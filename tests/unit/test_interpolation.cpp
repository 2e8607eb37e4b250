// Positions between steps (fluid/groups.h): drawn at the display's rate (144 Hz, and 480 Hz
// where some frames simulate no sub-step), the interpolated positions of a moving liquid change
// every frame and advance evenly with the frames' time (half a sub-step behind), where the
// current positions repeat; new, moved and loaded particles do not streak; the result is the
// same on 1, 2 and 4 workers; off, the world keeps nothing.
#include "test_support.h"

#include <fluid/groups.h>

#include <catch2/catch.hpp>

#include <sstream>

using namespace fluid;
using namespace fluid::test;

namespace {

// A blob drifting at 0.6 m/s through empty space (no gravity, no walls): its centre of mass
// moves exactly with the frames' time, whatever its particles do inside it.
constexpr float kDrift = 0.6f;

World driftingBlob(uint32_t workers) {
    WorldDef def;
    def.workerCount = workers;
    World world(def);
    const MaterialId w = world.addMaterial(water());
    world.spawnBlob(latticeBlock(world, w, 0.0f, 0.0f, 16, 16, {kDrift, 0.0f}));
    setInterpolation(world, true);
    return world;
}

double meanX(std::span<const float> x) {
    double sum = 0.0;
    for (const float v : x) {
        sum += v;
    }
    return sum / double(x.size());
}

} // namespace

TEST_CASE("interpolation: at 144 Hz and 480 Hz the drawn liquid moves every frame, evenly with "
          "the frames' time",
          "[interpolation]") {
    const float hz = GENERATE(144.0f, 480.0f);
    World world = driftingBlob(1);
    const float dt = 1.0f / hz;
    const double h = world.substepLength();
    const double x0 = meanX(world.positionX());
    std::vector<float> x(world.particleCount()), y(world.particleCount());
    double lastDrawn = x0 - kDrift * h / 2.0;
    double lastCurrent = x0;
    uint32_t repeatedCurrent = 0, idleFrames = 0;
    const int frames = int(hz); // one second
    for (int frame = 1; frame <= frames; ++frame) {
        world.step(dt);
        idleFrames += world.lastSubsteps() == 0 ? 1 : 0;
        REQUIRE(interpolatedPositions(world, x, y) == world.particleCount());
        const double drawn = meanX(x);
        // Half a sub-step behind the frames given: the drawn centre is where the blob was then.
        const double expected = x0 + double(kDrift) * (double(frame) * double(dt) - h / 2.0);
        CHECK(std::fabs(drawn - expected) < 2e-5);
        // Every frame moves the picture forward by one frame's drift (no repeat, no jump back).
        CHECK(drawn - lastDrawn > 0.9 * kDrift * dt);
        CHECK(drawn - lastDrawn < 1.1 * kDrift * dt);
        lastDrawn = drawn;
        const double current = meanX(world.positionX());
        repeatedCurrent += current == lastCurrent ? 1 : 0;
        lastCurrent = current;
    }
    if (hz > 240.0f) {
        // Without interpolation these frames would repeat the picture.
        CHECK(idleFrames > uint32_t(frames / 3));
        CHECK(repeatedCurrent == idleFrames);
    } else {
        CHECK(idleFrames == 0);
    }
}

TEST_CASE("interpolation over whole steps: fixed 60 Hz ticks drawn at 144 Hz and 480 Hz move the "
          "picture every frame, one tick behind",
          "[interpolation]") {
    const float hz = GENERATE(144.0f, 480.0f);
    const Solver solver = GENERATE(Solver::PositionBased, Solver::Explicit);
    CAPTURE(hz, solverLabel(solver));
    WorldDef def;
    def.solver = solver;
    World world(def);
    const MaterialId w = world.addMaterial(water());
    world.spawnBlob(latticeBlock(world, w, 0.0f, 0.0f, 16, 16, {kDrift, 0.0f}));
    setInterpolation(world, Interpolation::Step);
    REQUIRE(interpolation(world) == Interpolation::Step);
    REQUIRE(interpolating(world));
    const double tick = 1.0 / 60.0, frameDt = 1.0 / double(hz);
    const double x0 = meanX(world.positionX());
    std::vector<float> x(world.particleCount()), y(world.particleCount());
    double accumulator = 0.0, lastDrawn = x0, ticks = 0.0;
    uint32_t idleFrames = 0;
    for (int frame = 1; frame <= int(hz); ++frame) { // one second of display frames
        accumulator += frameDt;
        bool ticked = false;
        while (accumulator >= tick) { // the game's fixed-step loop
            world.step(float(tick));
            accumulator -= tick;
            ticks += 1.0;
            ticked = true;
        }
        idleFrames += ticked ? 0 : 1;
        CHECK(interpolationFactor(world) == 1.0f); // the game's own factor counts here
        const float factor = float(accumulator / tick);
        interpolatedPositions(world, x, y, factor);
        const double drawn = meanX(x);
        if (ticks < 1.0) {
            CHECK(drawn == Approx(x0).margin(1e-6)); // nothing simulated yet: previous = current
            continue;
        }
        // One tick behind the display's time: the blob drifts exactly with the ticks simulated.
        const double expected = x0 + double(kDrift) * ((ticks - 1.0) * tick + double(factor) * tick);
        CHECK(std::fabs(drawn - expected) < 2e-5);
        if (ticks >= 2.0 || !ticked) { // the first tick's picture starts at x0
            CHECK(drawn - lastDrawn > 0.9 * kDrift * frameDt);
            CHECK(drawn - lastDrawn < 1.1 * kDrift * frameDt);
        }
        lastDrawn = drawn;
    }
    CHECK(idleFrames > uint32_t(hz / 3.0f)); // frames that step no tick, where positions repeat
    // The mode is saved; a loaded world's previous positions are its current ones.
    World loaded = reloaded(world);
    CHECK(interpolation(loaded) == Interpolation::Step);
    CHECK(std::equal(previousPositionX(loaded).begin(), previousPositionX(loaded).end(),
                     loaded.positionX().begin(), loaded.positionX().end()));
    CHECK_THROWS_WITH(setInterpolation(world, Interpolation(7)),
                      "setInterpolation: mode = 7 is not an Interpolation (Off 0, Substep 1, "
                      "Step 2)");
}

TEST_CASE("interpolation: the factor is the carried time over the sub-step plus a half",
          "[interpolation]") {
    World world = driftingBlob(1);
    const double h = world.substepLength();
    for (const float dt : {1.0f / 144.0f, 1.0f / 480.0f, 1.0f / 60.0f, 0.013f}) {
        world.step(dt);
        const float expected = float(world.carriedTime() / h + 0.5);
        CHECK(interpolationFactor(world) == expected);
        CHECK(interpolationFactor(world) >= 0.0f);
        CHECK(interpolationFactor(world) < 1.0f);
        // At the factor's ends the positions are the previous and the current ones exactly.
        std::vector<float> x(world.particleCount()), y(x.size());
        interpolatedPositions(world, x, y, 0.0f);
        CHECK(std::equal(x.begin(), x.end(), previousPositionX(world).begin()));
        interpolatedPositions(world, x, y, 1.0f);
        CHECK(std::equal(x.begin(), x.end(), world.positionX().begin()));
        CHECK(std::equal(y.begin(), y.end(), world.positionY().begin()));
    }
    CHECK_THROWS_WITH(interpolatedPositions(world, {}, {}, 1.5f),
                      "interpolatedPositions: factor = 1.5 is out of range; expected [0, 1], or "
                      "a negative value for interpolationFactor(world)");
    CHECK_THROWS_WITH(interpolatedPositions(world, {}, {}, NAN),
                      Catch::Matchers::StartsWith("interpolatedPositions: factor = nan is out"));
    WorldDef explicitDef;
    explicitDef.solver = Solver::Explicit;
    World explicitWorld(explicitDef);
    CHECK(interpolationFactor(explicitWorld) == 1.0f);
}

TEST_CASE("interpolation: new, moved and loaded particles do not streak", "[interpolation]") {
    World world = driftingBlob(1);
    for (int frame = 0; frame < 5; ++frame) {
        world.step(1.0f / 144.0f);
    }
    const uint32_t before = world.particleCount();
    const GroupHandle g = spawnGroup(world, latticeBlock(world, MaterialId{0}, 1.0f, 1.0f, 4, 4));
    const auto same = [&](uint32_t i) {
        return previousPositionX(world)[i] == world.positionX()[i] &&
               previousPositionY(world)[i] == world.positionY()[i];
    };
    for (uint32_t i = before; i < world.particleCount(); ++i) {
        CHECK(same(i));
    }
    world.step(1.0f / 144.0f);
    moveGroup(world, g, {0.5f, 0.0f});
    for (uint32_t i = 0; i < world.particleCount(); ++i) {
        if (groupOf(world, world.handleAt(i)) == g) {
            CHECK(same(i));
        } else {
            CHECK_FALSE(same(i)); // the drifting blob moved during the sub-step
        }
    }
    // Emitted particles start where they are emitted.
    EmitterDef e;
    e.position = {-1.0f, 0.0f};
    e.rate = 100.0f;
    e.material = MaterialId{0};
    world.addEmitter(e);
    for (int frame = 0; frame < 4; ++frame) {
        world.step(1.0f / 144.0f);
    }
    REQUIRE(previousPositionX(world).size() == world.particleCount());
    World loaded = reloaded(world);
    CHECK(interpolating(loaded));
    CHECK(std::equal(previousPositionX(loaded).begin(), previousPositionX(loaded).end(),
                     loaded.positionX().begin(), loaded.positionX().end()));
    // Off: nothing kept, the current positions drawn.
    setInterpolation(world, false);
    CHECK(previousPositionX(world).empty());
    std::vector<float> x(world.particleCount()), y(x.size());
    interpolatedPositions(world, x, y);
    CHECK(std::equal(x.begin(), x.end(), world.positionX().begin()));
}

TEST_CASE("interpolation: the same interpolated positions on 1, 2 and 4 workers",
          "[interpolation][determinism]") {
    std::vector<float> reference;
    for (const uint32_t workers : {1u, 2u, 4u}) {
        WorldDef def;
        def.workerCount = workers;
        World world(def);
        const MaterialId w = world.addMaterial(water());
        world.addForce(std::make_unique<GravityForce>());
        world.addBoundary(std::make_unique<BoxContainer>(-0.3f, 0.0f, 0.3f, 0.6f));
        world.spawnBlob(latticeBlock(world, w, -0.3f, 0.0f, 20, 30));
        setInterpolation(world, true);
        for (int frame = 0; frame < 50; ++frame) {
            world.step(1.0f / 144.0f);
        }
        std::vector<float> x(world.particleCount()), y(x.size());
        interpolatedPositions(world, x, y);
        x.insert(x.end(), y.begin(), y.end());
        if (reference.empty()) {
            reference = x;
        } else {
            CHECK(x == reference);
        }
    }
}
