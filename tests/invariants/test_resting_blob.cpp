// A block of each preset resting 1 s in zero gravity (surface tension pulls it round) still
// reads its rest density inside, with each solver.
#include "test_support.h"

#include <catch2/catch.hpp>

#include <cmath>

using namespace fluid;
using namespace fluid::test;

TEST_CASE("a block resting 1 s in zero gravity still reads its rest density",
          "[slow][invariants][density]") {
    const Solver solver = GENERATE(Solver::PositionBased, Solver::Explicit);
    CAPTURE(solverLabel(solver));
    for (const Material& preset : {water(), yoghurt()}) {
        CAPTURE(preset.name);
        Stopwatch sw("rest density 1 s " + preset.name + ", " + solverLabel(solver));
        World world(physicsDef(solver));
        const MaterialId id = world.addMaterial(forSolver(preset, solver));
        world.spawnBlob(latticeBlock(world, id, -0.12f, -0.12f, 24, 24));
        for (int frame = 0; frame < 60; ++frame) {
            world.step(kFrame);
        }
        REQUIRE(allFinite(world));
        const Reading r = readInterior(world, id);
        CAPTURE(r.interior, r.worst, r.mean, r.compression, world.lastSubsteps());
        CHECK(r.interior >= 100);
        if (solver == Solver::Explicit) {
            CHECK(r.worst <= 0.01);
        } else {
            // The position-based constraint is one-sided: it keeps every particle from being
            // compressed, while surface tension pulling the square round may leave a particle
            // a little under-dense for a while (the yoghurt's worst reads about -2%).
            CHECK(r.compression <= 0.01);
            CHECK(std::fabs(r.mean) <= 0.005);
        }
    }
}
