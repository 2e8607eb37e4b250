// Box2D coupling, contact events (Coupling::setContactEvents, particleContacts): a crate dropped
// into a tank reports the particles touching it and the impulse the liquid gave it.
#include "box2d_support.h"

#include <fluid/contacts.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <sstream>
#include <vector>

using namespace fluid;
using namespace fluid::test;
using fluid::box2d::Coupling;
using fluid::box2d::ParticleContact;

TEST_CASE("explore box2d contacts", "[.explore]") {
    WorldDef def = physicsDef();
    if (std::getenv("PRECISE")) def.positionBased = positionBasedPreset(Quality::Precise);
    World world(def);
    const MaterialId w = world.addMaterial(fluid::water());
    const float s = world.spacing(w);
    const uint32_t cols = 60, rows = 20;
    const float width = fillTank(world, w, cols, rows, 1.0f);
    const float surface = float(rows) * s;
    b2World physics(b2Vec2(0.0f, -kG));
    addTankWalls(physics, 0.0f, 0.0f, width, 1.0f);
    const float rho = box2d::arealDensity(world, w);
    b2Body* crate = addBox(physics, b2_dynamicBody, {0.3f, surface + 0.2f}, 0.05f, 0.05f, 0.5f * rho);
    b2Body* dry = addBox(physics, b2_staticBody, {0.1f, surface + 0.3f}, 0.03f, 0.03f, 0.0f);
    box2d::CouplingDef cd;
    cd.categoryMask = kFluidMask;
    Coupling coupling(world, physics, cd);
    coupling.setContactEvents(crate, true);
    coupling.setContactEvents(dry, true);
    const double weight = crate->GetMass() * kG;
    for (int f = 0; f < 240; ++f) {
        coupling.step(world, kFrame);
        for (const ParticleContact& c : coupling.particleContacts()) {
            if (f % 10 == 0 || (f > 5 && f < 30))
            std::printf("f %d %s n %u imp %g %g F %g %g (weight %g) pt %g %g appr %g v %g\n", f,
                        c.body == crate ? "crate" : "dry", c.particles, c.impulse.x, c.impulse.y,
                        c.impulse.x / kFrame, c.impulse.y / kFrame, weight, c.point.x, c.point.y,
                        c.approachSpeed, crate->GetLinearVelocity().y);
        }
    }
}
