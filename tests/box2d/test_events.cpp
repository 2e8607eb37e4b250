// Box2D coupling, fast tests of what the coupling reports: contact begin and end events and
// splashes of balls entering a pool, and the hydrostatic force on a static floor under a tank.
#include "box2d_support.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <set>
#include <utility>
#include <vector>

using namespace fluid;
using namespace fluid::test;
using fluid::box2d::ContactEvent;
using fluid::box2d::ContactPhase;
using fluid::box2d::Coupling;
using fluid::box2d::SplashEvent;

TEST_CASE("a ball dropped into a pool makes one Begin and one splash, lifted out one End",
          "[box2d][events]") {
    // Water is material 0 and unused; the pool is yoghurt (material 1), so a material left at
    // its default 0 shows. Yoghurt 0.15 m deep in a 0.6 x 1.2 m box.
    World world(physicsDef());
    world.addMaterial(fluid::water());
    const MaterialId yog = world.addMaterial(fluid::yoghurt());
    REQUIRE(yog.index == 1);
    const float s = world.spacing(yog);
    const uint32_t cols = 60, rows = 15;
    const float width = float(cols) * s, surface = float(rows) * s;
    world.addForce(std::make_unique<GravityForce>(0.0f, -kG));
    world.addBoundary(std::make_unique<BoxContainer>(0.0f, 0.0f, width, 1.2f));
    world.spawnBlob(latticeBlock(world, yog, 0.0f, 0.0f, cols, rows));
    b2World physics(b2Vec2(0.0f, -kG));
    addTankWalls(physics, 0.0f, 0.0f, width, 1.2f, true);
    const float rho = box2d::arealDensity(world, yog);

    // The fast ball (twice the yoghurt's density: it sinks and stays wet) falls 0.4 m onto the
    // surface (about 2.8 m/s); the slow box is lowered into it at 0.3 m/s, below the splash
    // speed: it begins a contact without a splash.
    const float r = 0.05f;
    b2Body* fast = addCircle(physics, b2_dynamicBody, {0.2f, surface + 0.4f + r}, r, 2.0f * rho);
    b2Body* slow =
        addBox(physics, b2_kinematicBody, {0.45f, surface + 0.01f + 0.06f}, 0.04f, 0.06f, 0.0f);
    slow->SetLinearVelocity({0.0f, -0.3f});
    box2d::CouplingDef def;
    def.categoryMask = kFluidMask;
    def.splashSpeed = 1.0f;
    Coupling coupling(world, physics, def);

    std::vector<ContactEvent> contacts;
    std::vector<SplashEvent> splashes;
    int beginFrame = -1;
    float lastSpeed = 0.0f; // the fast ball's speed during the frame's fluid step
    float speedAtBegin = 0.0f;
    for (int f = 0; f < 90; ++f) {
        if (f == 20) {
            slow->SetLinearVelocity({0.0f, 0.0f}); // 0.1 m down: mostly in, stays there
        }
        coupling.step(world, kFrame);
        // Box2D steps first, then the fluid sweeps each body at the velocity Box2D left it
        // with; the fluid's force waits for the next frame's Box2D step.
        lastSpeed = fast->GetLinearVelocity().Length();
        for (const ContactEvent& e : coupling.contacts()) {
            contacts.push_back(e);
            if (e.body == fast && beginFrame < 0) {
                beginFrame = f;
                speedAtBegin = lastSpeed;
            }
        }
        splashes.insert(splashes.end(), coupling.splashes().begin(), coupling.splashes().end());
    }
    const box2d::BodyReport* rep = coupling.report(fast);
    REQUIRE(rep != nullptr);
    std::printf("[measure] ball dropped 0.4 m into yoghurt: Begin at frame %d at %.2f m/s; %zu "
                "contact events, %zu splashes",
                beginFrame, speedAtBegin, contacts.size(), splashes.size());
    for (const SplashEvent& e : splashes) {
        std::printf("; splash at (%.3f, %.3f) speed %.2f m/s material %u", e.position.x,
                    e.position.y, e.speed, unsigned(e.material.index));
    }
    std::printf("; at the end %.2f submerged\n", rep->submergedFraction);

    // Exactly one Begin per ball, with the pool's material; no End while they are in.
    REQUIRE(contacts.size() == 2);
    uint32_t fastBegins = 0, slowBegins = 0;
    for (const ContactEvent& e : contacts) {
        CHECK(e.phase == ContactPhase::Begin);
        CHECK(e.material == yog);
        fastBegins += e.body == fast ? 1 : 0;
        slowBegins += e.body == slow ? 1 : 0;
    }
    CHECK(fastBegins == 1);
    CHECK(slowBegins == 1);
    // One splash: the fast ball's, at its speed when it hit, where it hit.
    REQUIRE(splashes.size() == 1);
    const SplashEvent& splash = splashes[0];
    CHECK(splash.body == fast);
    CHECK(splash.material == yog);
    CHECK(splash.speed > def.splashSpeed);
    CHECK(splash.speed == Approx(speedAtBegin).epsilon(0.01));
    CHECK(splash.speed == Approx(std::sqrt(2.0f * kG * 0.4f)).epsilon(0.1));
    CHECK(std::fabs(splash.position.x - 0.2f) < r);
    CHECK(std::fabs(splash.position.y - surface) < r + s);
    CHECK(rep->wetPoints > 0);
    CHECK(rep->material == yog);

    // Lifted out (teleported 0.5 m above the pool, at rest): one End, with the material it was
    // in, at the next step; nothing for the other ball.
    fast->SetTransform({0.2f, surface + 0.5f}, 0.0f);
    fast->SetLinearVelocity({0.0f, 0.0f});
    fast->SetAngularVelocity(0.0f);
    coupling.step(world, kFrame);
    REQUIRE(coupling.contacts().size() == 1);
    CHECK(coupling.contacts()[0].body == fast);
    CHECK(coupling.contacts()[0].phase == ContactPhase::End);
    CHECK(coupling.contacts()[0].material == yog);
    CHECK(coupling.splashes().empty());
    REQUIRE(coupling.report(fast) != nullptr);
    CHECK(coupling.report(fast)->wetPoints == 0);
    CHECK(coupling.report(fast)->submergedFraction == 0.0f);
    // And nothing more while it stays dry.
    coupling.step(world, kFrame);
    CHECK(coupling.contacts().empty());
}

TEST_CASE("the force on a static floor under a resting tank is the fluid's weight",
          "[box2d][events]") {
    // A 0.4 m wide tank of water 0.2 m deep whose floor is a static Box2D body; the box
    // container's own floor lies 0.1 m lower, out of the fluid's reach, so the Box2D floor
    // carries the fluid alone. The side walls (the container's) can only carry weight through
    // viscous shear, which vanishes at rest. The precise preset: the game preset's coarse solve
    // pushes only dynamic bodies, so a static floor's report misses its share of the weight
    // (docs/box2d.md, "Which preset").
    World world(preciseDef());
    const MaterialId water = world.addMaterial(fluid::water());
    const float s = world.spacing(water);
    const uint32_t cols = 40, rows = 20;
    const float width = float(cols) * s;
    world.addForce(std::make_unique<GravityForce>(0.0f, -kG));
    world.addBoundary(std::make_unique<BoxContainer>(0.0f, -0.1f, width, 0.5f));
    world.spawnBlob(latticeBlock(world, water, 0.0f, 0.0f, cols, rows));
    b2World physics(b2Vec2(0.0f, -kG));
    b2Body* floor =
        addBox(physics, b2_staticBody, {0.5f * width, -0.05f}, 0.5f * width + 0.2f, 0.05f, 0.0f);
    Coupling coupling(world, physics);
    const double weight = totalMass(world) * kG;

    // 1.5 s to settle, then the force averaged over 0.5 s.
    glm::dvec2 force{0.0, 0.0};
    double torque = 0.0;
    const glm::dvec2 p0 = momentum(world);
    for (int f = 0; f < 120; ++f) {
        coupling.step(world, kFrame);
        REQUIRE(coupling.report(floor) != nullptr);
        if (f >= 90) {
            force += glm::dvec2(coupling.report(floor)->force) / 30.0;
            torque += coupling.report(floor)->torque / 30.0;
        }
    }
    // How far the fluid still is from equilibrium: its momentum change per second over the
    // whole run, against its weight (the floor must carry weight minus that).
    const double imbalance = length(momentum(world) - p0) / (120.0 * kFrame) / weight;
    const Bounds b = bounds(world);
    std::printf("[measure] tank on a Box2D floor: weight %.2f N, floor force (%.3f, %.2f) N = "
                "%.4f of the weight, torque %.3f N m about the floor's centre, fluid floor gap "
                "%.4f m, momentum imbalance %.2g of the weight\n",
                weight, force.x, force.y, -force.y / weight, torque, b.y0, imbalance);
    // The fluid pushes the floor down with its weight. Tolerance 2%: at rest the fluid's
    // momentum hardly changes (the imbalance above, about 1e-6 of the weight), so the floor must
    // carry all of it but what the side walls take through shear, which vanishes at rest; 2% is
    // what an error in the force path (a missed sample, a wrong sub-step average, the viscous
    // part or the pressure of the surface layer) would show as, and 20 times what was measured.
    CHECK(-force.y == Approx(weight).epsilon(0.02));
    CHECK(std::fabs(force.x) < 0.01 * weight);
    // The tank is centred on the floor: the weight acts through its centre.
    CHECK(std::fabs(torque) < 0.01 * weight * 0.5 * width);
    CHECK(b.y0 > 0.0f);
    CHECK(b.y0 < s);
}

TEST_CASE("a coupled frame reports every drained particle once, whatever its rounds",
          "[box2d][events]") {
    // A pool drained through its floor while a box floats in it: the coupling steps the fluid
    // in four rounds per frame, and a drain removes particles in each of them.
    World world(physicsDef());
    const MaterialId water = world.addMaterial(fluid::water());
    const float s = world.spacing(water);
    const uint32_t cols = 40, rows = 20;
    const float width = float(cols) * s;
    world.addForce(std::make_unique<GravityForce>(0.0f, -kG));
    world.addBoundary(std::make_unique<BoxContainer>(0.0f, 0.0f, width, 0.6f));
    world.spawnBlob(latticeBlock(world, water, 0.0f, 0.0f, cols, rows));
    DrainDef drain;
    drain.shape = Shape::box({0.3f * width, -0.01f}, {0.7f * width, 0.03f});
    world.addDrain(drain);
    b2World physics(b2Vec2(0.0f, -kG));
    addTankWalls(physics, 0.0f, 0.0f, width, 0.6f, true);
    addBox(physics, b2_dynamicBody, {0.5f * width, float(rows) * s + 0.05f}, 0.04f, 0.03f,
           0.5f * box2d::arealDensity(world, water));
    box2d::CouplingDef def;
    def.categoryMask = kFluidMask;
    Coupling coupling(world, physics, def);
    REQUIRE(world.def().positionBased.substeps == 4);

    std::set<std::pair<uint32_t, uint32_t>> removed; // every removed handle, once
    uint32_t total = 0, lastRoundOnly = 0;
    for (int f = 0; f < 60; ++f) {
        const uint32_t before = world.particleCount();
        coupling.step(world, kFrame);
        const uint32_t lost = before - world.particleCount();
        INFO("frame " << f);
        REQUIRE(coupling.removedEvents().size() == lost);
        CHECK(coupling.profile().removed == lost);
        for (const RemovedEvent& e : coupling.removedEvents()) {
            CHECK(e.cause == RemovalCause::Drain);
            CHECK(removed.insert({e.particle.slot, e.particle.generation}).second);
        }
        total += lost;
        lastRoundOnly += uint32_t(world.removedEvents().size());
    }
    // Drained in every round, not only the frame's last: the world alone reports fewer.
    CHECK(total > 100);
    CHECK(lastRoundOnly < total);
}
