// Yoghurt is more viscous than water: in the same dam break its front lags and it reaches the
// far wall later.
//
// Scene size: the prototype's 0.5 x 1 m block would be ~5,000 particles at ~130 sub-steps per
// frame (c = 10 sqrt(g H) = 31 m/s): minutes per run. A 0.25 x 0.5 m block (about 1,250
// particles, 1:2 like the dam break, box four widths wide) shows the same contrast at a quarter
// of the particles and ~70% of the sub-steps; the fronts travel half as far, so t = 0.3 s is
// still mid-run (the water front needs about 0.35 s to cross 0.75 m).
#include "test_support.h"

#include <catch2/catch.hpp>

#include <cmath>

using namespace fluid;
using namespace fluid::test;

namespace {

struct DamRun {
    float frontAt03 = 0.0f; // max x at t = 0.3 s (m)
    int wallFrame = -1;     // first frame with max x >= far wall - one spacing (-1: never)
    uint32_t particles = 0;
    float spacing = 0.0f;
};

DamRun runDam(Solver solver, const Material& preset, float boxW, int maxFrames) {
    World world(physicsDef(solver));
    const MaterialId id = world.addMaterial(preset);
    const float s = world.spacing(id);
    const auto cols = static_cast<uint32_t>(std::lround(0.25f / s));
    const auto rows = static_cast<uint32_t>(std::lround(0.5f / s));
    world.addForce(std::make_unique<GravityForce>(0.0f, -kG));
    world.addBoundary(std::make_unique<BoxContainer>(0.0f, 0.0f, boxW, 1.0f));
    world.spawnBlob(latticeBlock(world, id, 0.0f, 0.0f, cols, rows));
    DamRun r;
    r.particles = world.particleCount();
    r.spacing = s;
    for (int frame = 1; frame <= maxFrames; ++frame) {
        world.step(kFrame);
        REQUIRE(allFinite(world));
        REQUIRE(countOutside(world, 0.0f, 0.0f, boxW, 1.0f) == 0);
        const float front = bounds(world).x1;
        if (frame == 18) {
            r.frontAt03 = front;
        }
        if (r.wallFrame < 0 && front >= boxW - s) {
            r.wallFrame = frame;
        }
        if (frame >= 18 && r.wallFrame >= 0) {
            break;
        }
    }
    return r;
}

} // namespace

TEST_CASE("yoghurt's dam-break front lags water's and reaches the far wall later",
          "[slow][invariants][viscosity]") {
    const Solver solver = GENERATE(Solver::PositionBased, Solver::Explicit);
    CAPTURE(solverLabel(solver));
    Stopwatch sw(std::string("yoghurt vs water dam break, ") + solverLabel(solver));
    const float boxW = 1.0f; // four block widths
    const DamRun w = runDam(solver, water(), boxW, 90);
    // Yoghurt gets up to 1.5 s; if it has not arrived by then it is later anyway.
    const DamRun y = runDam(solver, forSolver(yoghurt(), solver), boxW, 90);
    CAPTURE(w.particles, y.particles, w.frontAt03, y.frontAt03, w.wallFrame, y.wallFrame);
    std::printf(
        "[measure] %s dam break fronts at 0.3 s: water %.3f m (%u particles), yoghurt %.3f m "
        "(%u); far wall reached at frame: water %d, yoghurt %d\n",
        solverLabel(solver), w.frontAt03, w.particles, y.frontAt03, y.particles, w.wallFrame,
        y.wallFrame);
    CHECK(y.frontAt03 < w.frontAt03);
    REQUIRE(w.wallFrame > 0); // water arrives within 1.5 s
    CHECK((y.wallFrame < 0 || y.wallFrame > w.wallFrame));
}
