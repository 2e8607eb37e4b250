// The 2D reading of 3D mass and density (material.h): the interior of a fresh resting body of
// each preset reads its rest density within 1% (after 1 s: tests/invariants/test_resting_blob.cpp).
#include "test_support.h"

#include <catch2/catch.hpp>

#include <cmath>

using namespace fluid;
using namespace fluid::test;

TEST_CASE("a fresh resting block of each preset reads its rest density", "[unit][density]") {
    const Solver solver = GENERATE(Solver::PositionBased, Solver::Explicit);
    CAPTURE(solverLabel(solver));
    for (const Material& preset : {water(), yoghurt()}) {
        CAPTURE(preset.name);
        // The precise preset: the density constraint alone. The game preset's coarse grid reads
        // a lattice's bilinear fill past its dead band and moves the block
        // (docs/position_based.md, "Which preset").
        WorldDef def;
        def.positionBased = positionBasedPreset(Quality::Precise);
        def.solver = solver;
        World world(def); // zero gravity: no force plugin, no boundary
        Material material = forSolver(preset, solver);
        if (solver == Solver::PositionBased) {
            // No surface tension, so that only a density correction could move the lattice in
            // the sub-step.
            material.surfaceTension = 0.0f;
        }
        const MaterialId id = world.addMaterial(material);
        world.spawnBlob(latticeBlock(world, id, -0.12f, -0.12f, 24, 24));
        REQUIRE(world.particleCount() == 24u * 24u);
        // One short step: density is computed, nothing moves measurably (the position-based
        // solver's shortest is one sub-step, 1/240 s; a frame under half of one is carried, not
        // stepped).
        world.step(solver == Solver::PositionBased ? float(world.substepLength()) : 1e-4f);
        const Reading r = readInterior(world, id);
        CAPTURE(r.interior, r.worst, r.mean);
        CHECK(r.interior >= 100);
        CHECK(r.worst <= 0.01);
        if (solver == Solver::PositionBased) {
            // The material's lattice is the density constraint's rest state: no correction
            // kicks it.
            CHECK(maxSpeed(world) < 1e-3f);
        }
    }
}
