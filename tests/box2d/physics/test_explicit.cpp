// The coupling with the explicit solver (Solver::Explicit): the issue asks for both solvers;
// every other Box2D test runs the default, position-based one.
#include "box2d_support.h"

#include <catch2/catch.hpp>

#include <cmath>

using namespace fluid;
using namespace fluid::test;

TEST_CASE("explicit solver: a disc at half the water's density floats about half submerged, "
          "its weight carried by the fluid",
          "[slow][box2d][explicit]") {
    Stopwatch sw("explicit solver, floating disc");
    World world(physicsDef(Solver::Explicit));
    const MaterialId water = world.addMaterial(fluid::water());
    // A pool 0.3 m wide and 0.12 m deep (360 particles: the explicit solver takes about 50
    // sub-steps a frame), a disc 0.06 m across laid on its surface.
    const uint32_t rows = 12;
    const float top = 0.5f, radius = 0.03f;
    const float width = fillTank(world, water, 30, rows, top);
    const float s = world.spacing(water);
    b2World physics(b2Vec2(0.0f, -kG));
    addTankWalls(physics, 0.0f, 0.0f, width, top);
    const float rho = box2d::arealDensity(world, water);
    b2Body* disc = addCircle(physics, b2_dynamicBody, {0.5f * width, float(rows) * s + radius},
                             radius, 0.5f * rho);
    box2d::CouplingDef def;
    def.categoryMask = kFluidMask;
    box2d::Coupling coupling(world, physics, def);

    // 3 s; the last second averaged (the disc still bobs by a few cm/s).
    const int frames = 180, window = 60;
    double lift = 0.0, fraction = 0.0;
    uint32_t inside = 0;
    for (int f = 0; f < frames; ++f) {
        coupling.step(world, kFrame);
        inside = std::max(inside, intrusion(world, physics, kFluidMask).count);
        if (f >= frames - window) {
            const box2d::BodyReport* r = coupling.report(disc);
            REQUIRE(r != nullptr);
            lift += r->force.y / double(window);
            fraction += r->submergedFraction / double(window);
        }
    }
    const double weight = double(disc->GetMass()) * kG;
    std::printf("[measure] explicit solver, disc at 0.5: lift %.4f N vs weight %.4f N (%+.1f%%), "
                "submerged %.3f, %u sub-steps in the last frame, %u particles inside at worst\n",
                lift, weight, 100.0 * (lift / weight - 1.0), fraction, coupling.profile().substeps,
                inside);
    CHECK(coupling.profile().substeps > 4); // 4 rounds, each in the explicit solver's sub-steps
    CHECK(lift == Approx(weight).epsilon(0.1));
    CHECK(fraction == Approx(0.5).margin(0.15));
    CHECK(inside == 0);
    CHECK(allFinite(world));
}
