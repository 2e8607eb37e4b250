// The 2D reading of 3D mass and density (material.h): the interior of a fresh resting body of
// each preset reads its rest density within 1% (after 1 s: tests/invariants/test_resting_blob.cpp).
#include "test_support.h"

#include <catch2/catch.hpp>

#include <cmath>

using namespace fluid;
using namespace fluid::test;

TEST_CASE("a fresh resting block of each preset reads its rest density", "[unit][density]") {
    const Solver solver = GENERATE(Solver::PositionBased, Solver::Explicit);
    CAPTURE(solverName(solver));
    for (const Material& preset : {water(), yoghurt()}) {
        CAPTURE(preset.name);
        WorldDef def;
        def.solver = solver;
        World world(def); // zero gravity: no force plugin, no boundary
        const MaterialId id = world.addMaterial(forSolver(preset, solver));
        world.spawnBlob(latticeBlock(world, id, -0.12f, -0.12f, 24, 24));
        REQUIRE(world.particleCount() == 24u * 24u);
        world.step(1e-4f); // one tiny step: density is computed, nothing moves measurably
        const Reading r = readInterior(world, id);
        CAPTURE(r.interior, r.worst, r.mean);
        CHECK(r.interior >= 100);
        CHECK(r.worst <= 0.01);
        if (solver == Solver::PositionBased) {
            // The material's lattice is the density constraint's rest state: no correction
            // kicks it (a 0.4% one in 25 us would be 4 m/s); only surface tension pulls.
            CHECK(maxSpeed(world) < 0.01f);
        }
    }
}
