// Determinism of the Box2D coupling: the bodies (position, angle, velocities, as bytes), the
// reports and the particles are bit-identical after 300 frames for 1, 2 and 4 workers.
#include "box2d_support.h"

#include <catch2/catch.hpp>

#include <cinttypes>

using namespace fluid;
using namespace fluid::test;

namespace {

struct Hashes {
    uint64_t particles = 0;
    uint64_t bodies = 0;
    uint64_t reports = 0; // every report of every frame
    uint64_t events = 0;  // every contact and splash of every frame
    uint32_t contacts = 0;
    uint32_t splashes = 0;

    bool operator==(const Hashes&) const = default;
};

// A 0.8 m tank of water 0.2 m deep; a box, a disc and a triangle of different densities
// dropped in, a kinematic paddle turning in the water and a static edge ramp along the left.
Hashes run(uint32_t workers, Quality quality) {
    WorldDef wd;
    wd.workerCount = workers;
    wd.positionBased = positionBasedPreset(quality);
    World world(wd);
    const MaterialId water = world.addMaterial(fluid::water());
    const float top = 1.0f;
    const float width = fillTank(world, water, 80, 20, top);

    b2World physics(b2Vec2(0.0f, -kG));
    addTankWalls(physics, 0.0f, 0.0f, width, top, true);
    const float rho = box2d::arealDensity(world, water);
    addBox(physics, b2_dynamicBody, {0.2f, 0.5f}, 0.06f, 0.04f, 0.6f * rho, 0.2f);
    addCircle(physics, b2_dynamicBody, {0.45f, 0.6f}, 0.05f, 1.5f * rho);
    {
        b2BodyDef bd;
        bd.type = b2_dynamicBody;
        bd.position.Set(0.65f, 0.45f);
        bd.angularVelocity = 2.0f;
        b2Body* b = physics.CreateBody(&bd);
        const b2Vec2 v[3] = {{-0.06f, -0.04f}, {0.07f, -0.03f}, {0.0f, 0.06f}};
        b2PolygonShape tri;
        tri.Set(v, 3);
        b2FixtureDef fd;
        fd.shape = &tri;
        fd.density = 0.8f * rho;
        b->CreateFixture(&fd);
    }
    {
        b2BodyDef bd;
        bd.type = b2_kinematicBody;
        bd.position.Set(0.4f, 0.12f);
        bd.angularVelocity = -3.0f;
        b2Body* b = physics.CreateBody(&bd);
        b2PolygonShape bar;
        bar.SetAsBox(0.08f, 0.015f);
        b2FixtureDef fd;
        fd.shape = &bar;
        b->CreateFixture(&fd);
    }
    {
        b2BodyDef bd;
        b2Body* b = physics.CreateBody(&bd);
        b2EdgeShape ramp;
        ramp.SetTwoSided({0.0f, 0.3f}, {0.15f, 0.1f});
        b2FixtureDef fd;
        fd.shape = &ramp;
        b->CreateFixture(&fd);
    }
    box2d::CouplingDef def;
    def.categoryMask = kFluidMask;
    box2d::Coupling coupling(world, physics, def);

    Hashes h;
    h.reports = h.events = 1469598103934665603ull;
    for (int f = 0; f < 300; ++f) {
        coupling.step(world, kFrame);
        for (const box2d::BodyReport& r : coupling.bodies()) {
            const float v[5] = {r.force.x, r.force.y, r.torque, r.submergedArea,
                                r.submergedFraction};
            h.reports = fnv1a(v, sizeof v, h.reports);
            h.reports = fnv1a(&r.wetPoints, sizeof r.wetPoints, h.reports);
            h.reports = fnv1a(&r.material.index, sizeof r.material.index, h.reports);
        }
        for (const box2d::ContactEvent& e : coupling.contacts()) {
            const uint8_t phase = uint8_t(e.phase);
            h.events = fnv1a(&phase, 1, h.events);
            ++h.contacts;
        }
        for (const box2d::SplashEvent& e : coupling.splashes()) {
            const float v[3] = {e.position.x, e.position.y, e.speed};
            h.events = fnv1a(v, sizeof v, h.events);
            ++h.splashes;
        }
    }
    REQUIRE(allFinite(world));
    h.particles = stateHash(world);
    h.bodies = bodiesHash(physics);
    return h;
}

} // namespace

TEST_CASE("determinism: bodies, reports and particles bit-identical for 1, 2 and 4 workers",
          "[slow][box2d][determinism]") {
    // The game preset moves the bodies in its coarse solve too.
    const Quality quality = GENERATE(Quality::Precise, Quality::Game);
    CAPTURE(int(quality));
    Stopwatch sw("Box2D determinism, 3 runs of 300 frames");
    const Hashes one = run(1, quality);
    const Hashes two = run(2, quality);
    const Hashes four = run(4, quality);
    std::printf("[measure] Box2D determinism (300 frames): particles %016" PRIx64 " / %016" PRIx64
                " / %016" PRIx64 ", bodies %016" PRIx64 " / %016" PRIx64 " / %016" PRIx64
                ", reports %016" PRIx64 " / %016" PRIx64 " / %016" PRIx64
                "; %u contact events, %u splashes (1 / 2 / 4 workers)\n",
                one.particles, two.particles, four.particles, one.bodies, two.bodies, four.bodies,
                one.reports, two.reports, four.reports, one.contacts, one.splashes);
    CHECK(one.particles == two.particles);
    CHECK(one.particles == four.particles);
    CHECK(one.bodies == two.bodies);
    CHECK(one.bodies == four.bodies);
    CHECK(one.reports == two.reports);
    CHECK(one.reports == four.reports);
    CHECK(one.events == two.events);
    CHECK(one.events == four.events);
    // Something happened to compare: bodies fell in (contacts, a splash).
    CHECK(one.contacts >= 3);
    CHECK(one.splashes >= 1);
}
