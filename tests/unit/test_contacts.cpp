// Contact events (fluid/contacts.h) between particles and boundary plugins' rigid bodies.
#include "test_support.h"

#include <fluid/contacts.h>

#include <catch2/catch.hpp>

#include <cstdio>
#include <sstream>

using namespace fluid;
using namespace fluid::test;

namespace {

struct Tank {
    World world;
    MaterialId water;
    CircleBoundary* disc = nullptr;
};

// A 0.6 m wide tank of water 0.4 m deep with a fixed disc of radius 0.05 m at `centre`.
Tank discTank(glm::vec2 centre, bool contacts, uint32_t workers = 1,
              Solver solver = Solver::PositionBased) {
    WorldDef def;
    def.workerCount = workers;
    def.solver = solver;
    if (std::getenv("PRECISE")) def.positionBased = positionBasedPreset(Quality::Precise);
    Tank t{World(def), {}, nullptr};
    t.water = t.world.addMaterial(forSolver(water(), solver));
    t.world.addForce(std::make_unique<GravityForce>());
    t.world.addBoundary(std::make_unique<BoxContainer>(-0.3f, 0.0f, 0.3f, 1.0f));
    auto disc = std::make_unique<CircleBoundary>(centre, 0.05f);
    disc->setContactEvents(contacts);
    t.disc = disc.get();
    t.world.addBoundary(std::move(disc));
    t.world.spawnBlob(latticeBlock(t.world, t.water, -0.3f, 0.0f, 60, 40));
    return t;
}

} // namespace

TEST_CASE("explore contacts", "[contacts][.explore]") {
    Tank t = discTank({0.0f, 0.2f}, true);
    for (int f = 0; f < 120; ++f) {
        t.world.step(kFrame);
        const auto c = bodyContacts(t.world);
        if (f % 10 == 9) {
            for (const BodyContact& e : c) {
                std::printf("f %d plugin %u body %u n %u imp %g %g F %g %g pt %g %g appr %g\n", f,
                            e.plugin, e.body, e.particles, e.impulse.x, e.impulse.y,
                            e.impulse.x / kFrame, e.impulse.y / kFrame, e.point.x, e.point.y,
                            e.approachSpeed);
            }
        }
    }
    {
        const float r = t.world.spacing(t.water);
        std::vector<int> hist(8);
        for (uint32_t i = 0; i < t.world.particleCount(); ++i) {
            const float d = std::hypot(t.world.positionX()[i], t.world.positionY()[i] - 0.2f) - 0.05f;
            if (d < 4 * r) { hist[std::min(7, int(d / (0.25f * r) + 2))]++; if (d < 1.0f * r) std::printf("%.3f,%.3f ", t.world.positionX()[i], t.world.positionY()[i]-0.2f);}
        }
        std::printf("\n");
        for (int h : hist) std::printf("%d ", h);
        std::printf("\n");
    }
    const double buoy = 1000.0 * 9.81 * 3.14159265 * 0.05 * 0.05 * t.world.def().depth;
    std::printf("buoyancy %g N particles on ring %g\n", buoy,
                2 * 3.14159265 * (0.05 + 0.5 * t.world.spacing(t.water)) / t.world.spacing(t.water));
}
