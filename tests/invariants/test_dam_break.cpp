// Dam break: 2,000 water particles, a 1:2 block in the left of a box four times its width,
// 3 s of 60 Hz frames. No NaN, no particle outside the box, no explosion, at any frame.
#include "test_support.h"

#include <catch2/catch.hpp>

using namespace fluid;
using namespace fluid::test;

TEST_CASE("dam break: 2,000 particles, 3 s, no NaN, no leak, no explosion",
          "[slow][sweep][invariants][dam]") {
    const Solver solver = GENERATE(Solver::PositionBased, Solver::Explicit);
    CAPTURE(solverLabel(solver));
    Stopwatch sw(std::string("dam break 3 s, ") + solverLabel(solver));
    World world(physicsDef(solver));
    const MaterialId w = world.addMaterial(water());
    const float s = world.spacing(w);
    const uint32_t cols = 32, rows = 63; // 2,016 particles, width:height 1:2 (to a row)
    const float blockW = float(cols) * s;
    const float h0 = float(rows) * s;
    const float boxW = 4.0f * blockW;
    const float boxH = 2.0f * h0;
    world.addForce(std::make_unique<GravityForce>(0.0f, -kG));
    world.addBoundary(std::make_unique<BoxContainer>(0.0f, 0.0f, boxW, boxH));
    REQUIRE(world.spawnBlob(latticeBlock(world, w, 0.0f, 0.0f, cols, rows)) == cols * rows);
    const uint32_t n = world.particleCount();
    const float speedLimit = 2.5f * std::sqrt(2.0f * kG * h0);

    uint32_t nanFrames = 0, leakFrames = 0, fastFrames = 0, firstBad = 0;
    float worstSpeed = 0.0f;
    uint32_t maxSubsteps = 0, clamped = 0;
    float reach = 0.0f;
    for (uint32_t frame = 1; frame <= 180; ++frame) {
        world.step(kFrame);
        maxSubsteps = std::max(maxSubsteps, world.lastSubsteps());
        clamped += world.profile().speedClamped;
        const bool finite = allFinite(world);
        const uint32_t outside = countOutside(world, 0.0f, 0.0f, boxW, boxH);
        const float v = maxSpeed(world);
        worstSpeed = std::max(worstSpeed, v);
        reach = std::max(reach, bounds(world).x1);
        nanFrames += finite ? 0 : 1;
        leakFrames += outside > 0 ? 1 : 0;
        fastFrames += v > speedLimit ? 1 : 0;
        if ((!finite || outside > 0 || v > speedLimit) && firstBad == 0) {
            firstBad = frame;
            UNSCOPED_INFO("first bad frame " << frame << ": finite " << finite << ", outside "
                                             << outside << ", max speed " << v);
        }
    }
    CAPTURE(n, h0, speedLimit, worstSpeed, maxSubsteps, clamped, reach, boxW);
    std::printf("[measure] %s dam break: n %u, H0 %.3f m, max speed %.3f m/s (limit %.3f), "
                "substeps/frame max %u, speed-capped %u, NaN frames %u, leak frames %u, reach "
                "%.3f of %.3f m\n",
                solverLabel(solver), n, h0, worstSpeed, speedLimit, maxSubsteps, clamped, nanFrames,
                leakFrames, reach, boxW);
    CHECK(nanFrames == 0);
    CHECK(leakFrames == 0);
    CHECK(fastFrames == 0);
    CHECK(world.particleCount() == n);
    // The dam did break: the front reached the far wall.
    CHECK(reach >= boxW - s);
}

namespace {

// The dam break: a 0.5 x 1 m water block (50 x 100 particles) in the left of a 2 x 2 m
// box. Returns the first frame at which the front (the largest x) reaches the far wall (within
// a spacing), or -1; runs `frames` frames, or stops at the arrival when `untilArrival`.
struct BigDam {
    int arrival = -1;
    uint32_t nanFrames = 0, leakFrames = 0, fastFrames = 0, frames = 0;
    float worstSpeed = 0.0f, limit = 0.0f;
    uint32_t maxSubsteps = 0;
};

BigDam runBigDam(Solver solver, int frames, bool untilArrival) {
    World world(physicsDef(solver));
    const MaterialId w = world.addMaterial(water());
    const float s = world.spacing(w);
    const uint32_t cols = 50, rows = 100;
    const float h0 = float(rows) * s;
    const float boxW = 2.0f, boxH = 2.0f;
    world.addForce(std::make_unique<GravityForce>(0.0f, -kG));
    world.addBoundary(std::make_unique<BoxContainer>(0.0f, 0.0f, boxW, boxH));
    REQUIRE(world.spawnBlob(latticeBlock(world, w, 0.0f, 0.0f, cols, rows)) == cols * rows);
    BigDam r;
    r.limit = 2.5f * std::sqrt(2.0f * kG * h0);
    for (int frame = 1; frame <= frames; ++frame) {
        world.step(kFrame);
        ++r.frames;
        r.maxSubsteps = std::max(r.maxSubsteps, world.lastSubsteps());
        const float v = maxSpeed(world);
        r.worstSpeed = std::max(r.worstSpeed, v);
        r.nanFrames += allFinite(world) ? 0 : 1;
        r.leakFrames += countOutside(world, 0.0f, 0.0f, boxW, boxH) > 0 ? 1 : 0;
        r.fastFrames += v > r.limit ? 1 : 0;
        if (r.arrival < 0 && bounds(world).x1 >= boxW - s) {
            r.arrival = frame;
            if (untilArrival) {
                break;
            }
        }
    }
    return r;
}

} // namespace

TEST_CASE("dam break 0.5 x 1 m for 10 s with the default solver: no leak, front on time",
          "[slow][long][invariants][dam]") {
    Stopwatch sw("dam break 0.5 x 1 m: explicit to arrival, default 10 s");
    REQUIRE(WorldDef{}.solver == Solver::PositionBased);
    const BigDam reference = runBigDam(Solver::Explicit, 120, true);
    const BigDam pbf = runBigDam(Solver::PositionBased, 600, false);
    CAPTURE(reference.arrival, pbf.arrival, pbf.worstSpeed, pbf.limit, pbf.maxSubsteps);
    std::printf("[measure] dam 0.5 x 1 m: front at the far wall at frame %d (explicit, %u "
                "sub-steps/frame max) and %d (position-based, %u); position-based over 10 s: max "
                "speed %.3f m/s (limit %.3f), NaN frames %u, leak frames %u\n",
                reference.arrival, reference.maxSubsteps, pbf.arrival, pbf.maxSubsteps,
                pbf.worstSpeed, pbf.limit, pbf.nanFrames, pbf.leakFrames);
    REQUIRE(reference.arrival > 0);
    REQUIRE(pbf.frames == 600);
    CHECK(pbf.nanFrames == 0);
    CHECK(pbf.leakFrames == 0);
    CHECK(pbf.fastFrames == 0);
    REQUIRE(pbf.arrival > 0);
    CHECK(double(pbf.arrival) <= 1.2 * double(reference.arrival));
}
