// Box2D coupling, fast tests of the API: CouplingDef errors, arealDensity, reports of bodies that
// are not coupled, another world, bodies created and destroyed between steps, the category mask,
// the filter and sensors.
#include "box2d_support.h"

#include <fluid/box2d/shapes.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

using namespace fluid;
using namespace fluid::test;
using fluid::box2d::Coupling;
using fluid::box2d::CouplingDef;

namespace {

// A pool: water 0.15 m deep (60 x 15 particles) in a 0.6 x 0.5 m box, gravity on both sides.
struct Pool {
    World world;
    MaterialId water = world.addMaterial(fluid::water());
    b2World physics{b2Vec2(0.0f, -kG)};
    float s = world.spacing(water);
    float width = 60.0f * s;
    float top = 0.5f;

    explicit Pool(const WorldDef& def = physicsDef()) : world(def) {
        fillTank(world, water, 60, 15, top);
    }
};

bool listed(const Coupling& coupling, uintptr_t body) {
    for (const box2d::BodyReport& r : coupling.bodies()) {
        if (reinterpret_cast<uintptr_t>(r.body) == body) {
            return true;
        }
    }
    return false;
}

} // namespace

TEST_CASE("CouplingDef out of range: the constructor and setDef name the field", "[box2d]") {
    World world;
    b2World physics(b2Vec2(0.0f, -kG));
    struct Bad {
        CouplingDef def;
        std::string message;
    };
    auto with = [](auto change) {
        CouplingDef d;
        change(d);
        return d;
    };
    const std::vector<Bad> bad{
        {with([](CouplingDef& d) { d.friction = -1.0f; }),
         "fluid::box2d::CouplingDef: friction = -1 is out of range [0, 10] (unit: 1)"},
        {with([](CouplingDef& d) { d.friction = 11.0f; }),
         "fluid::box2d::CouplingDef: friction = 11 is out of range [0, 10] (unit: 1)"},
        {with([](CouplingDef& d) { d.friction = kNaN; }),
         "fluid::box2d::CouplingDef: friction = nan is out of range [0, 10] (unit: 1)"},
        {with([](CouplingDef& d) { d.splashSpeed = -0.5f; }),
         "fluid::box2d::CouplingDef: splashSpeed = -0.5 is out of range [0, 1000] "
         "(unit: m/s)"},
        {with([](CouplingDef& d) { d.splashSpeed = 2000.0f; }),
         "fluid::box2d::CouplingDef: splashSpeed = 2000 is out of range [0, 1000] "
         "(unit: m/s)"},
        {with([](CouplingDef& d) { d.velocityIterations = 0; }),
         "fluid::box2d::CouplingDef: velocityIterations = 0 is out of range [1, 1000] "
         "(unit: count)"},
        {with([](CouplingDef& d) { d.positionIterations = 1001; }),
         "fluid::box2d::CouplingDef: positionIterations = 1001 is out of range "
         "[1, 1000] (unit: count)"},
    };
    for (const Bad& b : bad) {
        CAPTURE(b.message);
        CHECK_THROWS_MATCHES(Coupling(world, physics, b.def), Error,
                             Catch::Matchers::Message(b.message));
    }
    // A refused constructor adds nothing to the world.
    CHECK(world.boundaries().empty());

    Coupling coupling(world, physics);
    REQUIRE(world.boundaries().size() == 1);
    CHECK(world.boundaries()[0]->type() == "box2d.bodies");
    CouplingDef good;
    good.friction = 0.25f;
    good.splashSpeed = 3.0f;
    coupling.setDef(good);
    for (const Bad& b : bad) {
        CAPTURE(b.message);
        CHECK_THROWS_MATCHES(coupling.setDef(b.def), Error, Catch::Matchers::Message(b.message));
        // The old settings stay.
        CHECK(coupling.def().friction == 0.25f);
        CHECK(coupling.def().splashSpeed == 3.0f);
        CHECK(coupling.def().velocityIterations == 8);
    }
    CHECK(&coupling.physics() == &physics);
}

TEST_CASE("arealDensity is rest density times slab depth", "[box2d]") {
    World world;
    const MaterialId w = world.addMaterial(fluid::water());
    const MaterialId y = world.addMaterial(fluid::yoghurt());
    CHECK(box2d::arealDensity(world, w) ==
          Approx(double(world.material(w).restDensity) * kDefaultDepth).epsilon(1e-6));
    CHECK(box2d::arealDensity(world, y) ==
          Approx(double(world.material(y).restDensity) * kDefaultDepth).epsilon(1e-6));
    // The seed's water: 1000 kg/m^3 x 0.12931 m.
    CHECK(box2d::arealDensity(world, w) == Approx(129.31339).epsilon(1e-5));
    WorldDef deep;
    deep.depth = 0.5f;
    World other(deep);
    const MaterialId w2 = other.addMaterial(fluid::water());
    CHECK(box2d::arealDensity(other, w2) == Approx(500.0).epsilon(1e-6));
    // It is mass per area of the plane: particle mass / particle area (spacing^2).
    const float s = world.spacing(w);
    CHECK(box2d::arealDensity(world, w) ==
          Approx(world.material(w).mass / (double(s) * s)).epsilon(1e-4));
}

TEST_CASE("report is nullptr for bodies that are not coupled, another world throws", "[box2d]") {
    Pool pool;
    b2Body* masked =
        addBox(pool.physics, b2_staticBody, {0.1f, 0.4f}, 0.02f, 0.02f, 0.0f, 0.0f, kWallCategory);
    b2Body* sensor = nullptr;
    {
        b2BodyDef bd;
        bd.position.Set(0.3f, 0.4f);
        sensor = pool.physics.CreateBody(&bd);
        b2CircleShape c;
        c.m_radius = 0.03f;
        b2FixtureDef fd;
        fd.shape = &c;
        fd.isSensor = true;
        sensor->CreateFixture(&fd);
    }
    b2BodyDef bare;
    b2Body* noFixtures = pool.physics.CreateBody(&bare);
    b2Body* coupled = addBox(pool.physics, b2_staticBody, {0.5f, 0.4f}, 0.02f, 0.02f, 0.0f);
    b2World elsewhere(b2Vec2(0.0f, 0.0f));
    b2Body* foreign = addCircle(elsewhere, b2_dynamicBody, {0.3f, 0.3f}, 0.05f, 1.0f);

    CouplingDef def;
    def.categoryMask = kFluidMask;
    // Declared before the coupling, which must not outlive the world it talks to.
    World moved;
    Coupling coupling(pool.world, pool.physics, def);
    // Before the first step nothing is coupled yet.
    CHECK(coupling.bodies().empty());
    CHECK(coupling.report(coupled) == nullptr);
    CHECK(coupling.splashes().empty());
    CHECK(coupling.contacts().empty());

    coupling.step(pool.world, kFrame);
    REQUIRE(coupling.report(coupled) != nullptr);
    CHECK(coupling.report(coupled)->body == coupled);
    CHECK(coupling.report(masked) == nullptr);
    CHECK(coupling.report(sensor) == nullptr);
    CHECK(coupling.report(noFixtures) == nullptr);
    CHECK(coupling.report(foreign) == nullptr);
    CHECK(coupling.report(nullptr) == nullptr);
    REQUIRE(coupling.bodies().size() == 1);
    CHECK(coupling.bodies()[0].body == coupled);
    // A dry body in the air: no force, nothing submerged.
    CHECK(coupling.report(coupled)->wetPoints == 0);
    CHECK(coupling.report(coupled)->submergedFraction == 0.0f);
    CHECK(coupling.report(coupled)->force.x == 0.0f);
    CHECK(coupling.report(coupled)->force.y == 0.0f);

    // Another world: refused by step and stepFluid, and nothing moves.
    World otherWorld;
    const uint64_t before = stateHash(pool.world);
    const uint64_t bodiesBefore = bodiesHash(pool.physics);
    CHECK_THROWS_MATCHES(coupling.step(otherWorld, kFrame), Error,
                         Catch::Matchers::Message("fluid::box2d::Coupling::step: the world is not "
                                                  "the one this coupling was made with"));
    CHECK_THROWS_MATCHES(
        coupling.stepFluid(otherWorld, kFrame), Error,
        Catch::Matchers::Message("fluid::box2d::Coupling::stepFluid: the world is not the one "
                                 "this coupling was made with"));
    CHECK(stateHash(pool.world) == before);
    CHECK(bodiesHash(pool.physics) == bodiesBefore);
    CHECK(otherWorld.time() == 0.0);
    // A bad dt is World::step's error, and leaves the bodies alone too.
    CHECK_THROWS_AS(coupling.step(pool.world, 0.0f), Error);
    CHECK(bodiesHash(pool.physics) == bodiesBefore);

    // The world may be moved after the coupling was made.
    moved = std::move(pool.world);
    coupling.step(moved, kFrame);
    CHECK(coupling.report(coupled) != nullptr);
    CHECK(moved.time() == Approx(2.0 * kFrame));
}

TEST_CASE("a coupled frame keeps the world's clock: one round per sub-step, the time within "
          "half a sub-step of the frames' sum",
          "[box2d][clock]") {
    World world(physicsDef());
    const MaterialId water = world.addMaterial(fluid::water());
    fillTank(world, water, 10, 4, 0.3f);
    b2World physics(b2Vec2(0.0f, -kG));
    addCircle(physics, b2_dynamicBody, {0.05f, 0.2f}, 0.02f, 50.0f);
    Coupling coupling(world, physics);
    const double h = world.substepLength();
    double given = 0.0;
    uint32_t rounds = 0;
    // Frames shorter than a sub-step (carried, a round every fourth or fifth), a little short
    // of one (a round each, the shortfall owed), then of any length from 1/240 to 1/30 s.
    std::vector<float> frames(30, 0.001f);
    frames.insert(frames.end(), 100, float(1.0 / 240.0 - 1e-7));
    uint64_t state = 7;
    for (int k = 0; k < 60; ++k) {
        state = state * 6364136223846793005ull + 1442695040888963407ull; // LCG, fixed seed
        const double u = double(state >> 11) / double(uint64_t(1) << 53);
        frames.push_back(float(1.0 / 240.0 + u * (1.0 / 30.0 - 1.0 / 240.0)));
    }
    for (size_t f = 0; f < frames.size(); ++f) {
        INFO("frame " << f << " of " << frames[f] << " s");
        const uint32_t due = world.substepsFor(frames[f]);
        coupling.step(world, frames[f]);
        given += double(frames[f]);
        rounds += coupling.profile().substeps;
        REQUIRE(coupling.profile().substeps == due);
        REQUIRE(std::fabs(world.time() + world.carriedTime() - given) < 1e-9);
        REQUIRE(std::fabs(world.time() - double(rounds) * h) < 1e-9);
        REQUIRE(std::fabs(world.carriedTime()) <= 0.5 * h);
    }
    CHECK(rounds == uint32_t(std::lround(given / h)));
}

TEST_CASE("stepFluid leaves the Box2D step to the game", "[box2d]") {
    Pool pool;
    b2Body* ball = addCircle(pool.physics, b2_dynamicBody, {0.3f, 0.4f}, 0.03f, 50.0f);
    ball->SetLinearVelocity({1.0f, 0.0f});
    Coupling coupling(pool.world, pool.physics);
    coupling.stepFluid(pool.world, kFrame);
    // The fluid stepped, Box2D did not: the ball has not moved.
    CHECK(pool.world.time() == Approx(kFrame));
    CHECK(ball->GetPosition().x == 0.3f);
    CHECK(ball->GetPosition().y == 0.4f);
    REQUIRE(coupling.report(ball) != nullptr);
    pool.physics.Step(kFrame, 8, 3);
    coupling.step(pool.world, kFrame);
    CHECK(ball->GetPosition().x > 0.3f);
}

TEST_CASE("a dynamic body lighter than kMinBodyMass or kMinBodyInertia is refused, nothing moves",
          "[box2d][bad-input]") {
    Pool pool;
    b2Body* ball = addCircle(pool.physics, b2_dynamicBody, {0.3f, 0.4f}, 0.03f, 50.0f);
    Coupling coupling(pool.world, pool.physics);
    coupling.step(pool.world, kFrame);
    const uint64_t before = stateHash(pool.world);
    const uint64_t bodiesBefore = bodiesHash(pool.physics);
    const double time = pool.world.time();
    b2MassData data;
    ball->GetMassData(&data);
    const b2MassData kept = data;
    // Box2D's inverse of 4.7e-40 kg overflows a float: the body would turn NaN at its first step.
    data.mass = 4.7e-40f;
    ball->SetMassData(&data);
    CHECK_THROWS_MATCHES(coupling.step(pool.world, kFrame), Error,
                         Catch::Matchers::Message(
                             "fluid::box2d::Coupling::step: dynamic body 0 (in GetBodyList() "
                             "order) has a mass of 4.7e-40 kg, less than kMinBodyMass (1e-06 kg)"));
    data = kept;
    data.I = kept.mass * b2Dot(kept.center, kept.center) + 1e-20f;
    ball->SetMassData(&data);
    CHECK_THROWS_MATCHES(
        coupling.stepFluid(pool.world, kFrame), Error,
        Catch::Matchers::Message("fluid::box2d::Coupling::stepFluid: dynamic body 0 (in "
                                 "GetBodyList() order) has a rotational inertia of 1e-20 kg m^2 "
                                 "about its centre of mass, less than kMinBodyInertia (1e-12 kg "
                                 "m^2)"));
    CHECK(stateHash(pool.world) == before);
    CHECK(bodiesHash(pool.physics) == bodiesBefore);
    CHECK(pool.world.time() == time);
    // A milligram 3 cm ball is heavy enough for Box2D but 3e-3 of the water's areal density:
    // the fluid would throw it (kMinDensityRatio). (SetFixedRotation recomputes the mass from
    // the fixtures, so it comes first.)
    ball->SetFixedRotation(true);
    data = kept;
    data.mass = box2d::kMinBodyMass;
    ball->SetMassData(&data);
    CHECK_THROWS_WITH(coupling.step(pool.world, kFrame),
                      Catch::StartsWith("fluid::box2d::Coupling::step: dynamic body 0 (in "
                                        "GetBodyList() order): the fixtures weigh 1e-06 kg over ") &&
                          Catch::Contains("a dynamic body needs at least 0.05 of it"));
    CHECK(stateHash(pool.world) == before);
    // At the floor it steps; a body that does not turn needs no inertia.
    const float floor = box2d::kMinDensityRatio * box2d::densestArealDensity(pool.world) *
                        float(std::numbers::pi) * 0.03f * 0.03f;
    data.mass = floor * 1.001f;
    ball->SetMassData(&data);
    for (int frame = 0; frame < 30; ++frame) {
        coupling.step(pool.world, kFrame);
    }
    CHECK(std::isfinite(ball->GetPosition().x));
    CHECK(std::isfinite(ball->GetPosition().y));
    CHECK(std::isfinite(ball->GetLinearVelocity().y));
    CHECK(allFinite(pool.world));
    CHECK(pool.world.time() == Approx(time + 30.0 * kFrame));
}

TEST_CASE("a pointed body made in Box2D directly is refused by the coupling's step",
          "[box2d][bad-input]") {
    // The level loader and the C API refuse it as they read it; a game that builds its bodies
    // with Box2D's own calls meets the same rule at the step, before anything moves.
    Pool pool;
    b2BodyDef def;
    def.type = b2_dynamicBody;
    def.position = {0.3f, 0.4f};
    b2Body* wedge = pool.physics.CreateBody(&def);
    b2PolygonShape shape;
    const b2Vec2 v[] = {{-0.05f, 0.0f}, {0.05f, 0.0f}, {0.0f, 0.005f}};
    shape.Set(v, 3);
    wedge->CreateFixture(&shape, 0.5f * box2d::arealDensity(pool.world, pool.water));
    Coupling coupling(pool.world, pool.physics);
    const uint64_t before = stateHash(pool.world);
    CHECK_THROWS_WITH(coupling.step(pool.world, kFrame),
                      Catch::StartsWith("fluid::box2d::Coupling::step: dynamic body 0 (in "
                                        "GetBodyList() order): the corner at vertex ") &&
                          Catch::Contains("must hold one of the fluid's spacing"));
    CHECK(stateHash(pool.world) == before);
    wedge->SetType(b2_staticBody); // a static wedge is fine
    CHECK_NOTHROW(coupling.step(pool.world, kFrame));
}

TEST_CASE("a body created mid-run pushes fluid, a destroyed one disappears", "[box2d]") {
    // The precise preset: the game preset's coarse solve pushes only dynamic bodies, so a
    // kinematic plate's report misses its share of the buoyancy (docs/box2d.md, "Which preset").
    Pool pool(preciseDef());
    b2Body* anchor = addBox(pool.physics, b2_staticBody, {0.05f, 0.45f}, 0.02f, 0.02f, 0.0f);
    Coupling coupling(pool.world, pool.physics);
    for (int f = 0; f < 20; ++f) {
        coupling.step(pool.world, kFrame);
    }
    const float restSpeed = maxSpeed(pool.world);
    CHECK(coupling.bodies().size() == 1);

    // A kinematic plate 0.2 x 0.06 m coming down at 1 m/s; its bottom starts 0.02 m above the
    // water and ends 0.1 s later 0.08 m below the surface.
    const float surface = 15.0f * pool.s;
    b2Body* plate =
        addBox(pool.physics, b2_kinematicBody, {0.3f, surface + 0.05f}, 0.1f, 0.03f, 0.0f);
    plate->SetLinearVelocity({0.0f, -1.0f});
    uint32_t intrudedMax = 0;
    for (int f = 0; f < 6; ++f) {
        coupling.step(pool.world, kFrame);
        intrudedMax = std::max(intrudedMax, intrusion(pool.world, pool.physics).count);
    }
    const box2d::BodyReport* r = coupling.report(plate);
    REQUIRE(r != nullptr);
    CHECK(r->body == plate);
    CHECK(listed(coupling, reinterpret_cast<uintptr_t>(plate)));
    CHECK(coupling.bodies().size() == 2);
    // Body-list order: Box2D lists the newest body first.
    CHECK(coupling.bodies()[0].body == plate);
    CHECK(coupling.bodies()[1].body == anchor);
    CHECK(r->wetPoints > 0);
    CHECK(r->submergedFraction > 0.0f);
    // The fluid pushes back against the plate's motion, and was pushed: it moves now.
    CHECK(r->force.y > 0.0f);
    const float pushedSpeed = maxSpeed(pool.world);
    std::printf("[measure] plate created mid-run: rest max speed %.4f m/s, after 0.1 s of "
                "pushing %.3f m/s, force (%.2f, %.2f) N, submerged %.2f, %u particles inside\n",
                restSpeed, pushedSpeed, r->force.x, r->force.y, r->submergedFraction, intrudedMax);
    CHECK(restSpeed < 0.1f);
    CHECK(pushedSpeed > 0.3f);
    CHECK(intrudedMax == 0);
    // Stopped 0.02 m under the surface, the water closes over it and settles in 3 s: the plate
    // is then fully submerged and buoyed up by the weight of the water it displaces.
    plate->SetLinearVelocity({0.0f, 0.0f});
    double lift = 0.0;
    for (int f = 0; f < 180; ++f) {
        coupling.step(pool.world, kFrame);
        intrudedMax = std::max(intrudedMax, intrusion(pool.world, pool.physics).count);
        if (f >= 150) {
            lift += coupling.report(plate)->force.y / 30.0;
        }
    }
    r = coupling.report(plate);
    REQUIRE(r != nullptr);
    const double buoyancy = box2d::arealDensity(pool.world, pool.water) * 0.2 * 0.06 * kG;
    std::printf("[measure] plate 3 s after stopping under water: submerged %.3f, %u wet points, "
                "lift %.3f N vs displaced weight %.3f N (%+.2f%%), %u particles inside\n",
                r->submergedFraction, r->wetPoints, lift, buoyancy, 100.0 * (lift / buoyancy - 1.0),
                intrudedMax);
    CHECK(r->submergedFraction > 0.95f);
    CHECK(intrudedMax == 0);
    // 5%: the settled water is compressed by up to 2-3% at depth (the solver's density error),
    // and the pressure difference across the plate with it.
    CHECK(lift == Approx(buoyancy).epsilon(0.05));

    // Destroyed between steps: gone from the reports at the next step, no event, no crash; its
    // hole fills.
    const auto gone = reinterpret_cast<uintptr_t>(plate);
    const b2Vec2 where = plate->GetPosition();
    pool.physics.DestroyBody(plate);
    plate = nullptr;
    coupling.step(pool.world, kFrame);
    CHECK_FALSE(listed(coupling, gone));
    CHECK(coupling.bodies().size() == 1);
    CHECK(coupling.bodies()[0].body == anchor);
    for (const box2d::ContactEvent& e : coupling.contacts()) {
        CHECK(reinterpret_cast<uintptr_t>(e.body) != gone);
    }
    for (int f = 0; f < 30; ++f) {
        coupling.step(pool.world, kFrame);
    }
    uint32_t inHole = 0;
    const auto px = pool.world.positionX(), py = pool.world.positionY();
    for (uint32_t i = 0; i < pool.world.particleCount(); ++i) {
        if (std::fabs(px[i] - where.x) < 0.1f && std::fabs(py[i] - where.y) < 0.03f) {
            ++inHole;
        }
    }
    std::printf("[measure] 0.5 s after the plate was destroyed: %u particles where it was\n",
                inHole);
    CHECK(inHole > 20);
    CHECK(allFinite(pool.world));
}

TEST_CASE("the category mask, the filter and sensors keep fixtures out of the fluid", "[box2d]") {
    // Zero gravity: a 10 x 10 block at 2 m/s flies at a static plate 0.04 m thick. When the
    // plate is coupled the block splashes on it; when not, the block flies through it.
    enum class Variant { Coupled, Masked, Filtered, Sensor };
    const Variant variant =
        GENERATE(Variant::Coupled, Variant::Masked, Variant::Filtered, Variant::Sensor);
    const char* names[] = {"coupled", "masked", "filtered", "sensor"};
    CAPTURE(names[int(variant)]);

    World world(physicsDef());
    const MaterialId water = world.addMaterial(fluid::water());
    world.addForce(std::make_unique<GravityForce>(0.0f, 0.0f));
    world.spawnBlob(latticeBlock(world, water, 0.0f, 0.0f, 10, 10, {2.0f, 0.0f}));
    b2World physics(b2Vec2(0.0f, 0.0f));
    b2BodyDef bd;
    bd.position.Set(0.25f, 0.05f);
    b2Body* plate = physics.CreateBody(&bd);
    b2PolygonShape shape;
    shape.SetAsBox(0.02f, 0.4f);
    b2FixtureDef fd;
    fd.shape = &shape;
    fd.filter.categoryBits = variant == Variant::Masked ? uint16_t(0x0004) : uint16_t(0x0001);
    fd.isSensor = variant == Variant::Sensor;
    b2Fixture* fixture = plate->CreateFixture(&fd);
    CouplingDef def;
    def.categoryMask = 0xFFFB;
    if (variant == Variant::Filtered) {
        def.filter = [fixture](const b2Fixture& f) { return &f != fixture; };
    }
    Coupling coupling(world, physics, def);
    uint32_t insideMax = 0;
    for (int f = 0; f < 18; ++f) {
        coupling.step(world, kFrame);
        insideMax = std::max(insideMax, intrusion(world, physics, 0xFFFF, true).count);
    }
    const uint32_t beyond = world.particleCount() - countOutside(world, 0.27f, -1.0f, 10.0f, 1.0f);
    std::printf("[measure] block at 2 m/s against a %s plate: %u of %u particles beyond it after "
                "0.3 s, at most %u inside it\n",
                names[int(variant)], beyond, world.particleCount(), insideMax);
    if (variant == Variant::Coupled) {
        CHECK(coupling.report(plate) != nullptr);
        CHECK(insideMax == 0);
        CHECK(beyond == 0);
    } else {
        CHECK(coupling.report(plate) == nullptr);
        CHECK(coupling.bodies().empty());
        CHECK(insideMax > 0);
        CHECK(beyond == world.particleCount());
    }
}

TEST_CASE("the game preset carries a body in its coarse solve: a box at half water's density "
          "floats",
          "[box2d]") {
    // Before the bodies were unknowns of the coarse solve, the correction moved the water out
    // of the body's way without a reaction: a box at half water's density sank to the floor.
    Pool pool;
    pool.world.setPositionBased(positionBasedPreset(Quality::Game));
    const float rho = box2d::arealDensity(pool.world, pool.water);
    const float surface = 15.0f * pool.s, half = 0.04f;
    b2Body* box =
        addBox(pool.physics, b2_dynamicBody, {0.3f, surface + half}, 0.1f, half, 0.5f * rho);
    Coupling coupling(pool.world, pool.physics, CouplingDef{});
    double lift = 0.0;
    const int frames = 150, window = 30;
    for (int f = 0; f < frames; ++f) {
        coupling.step(pool.world, kFrame);
        if (f >= frames - window) {
            lift += double(coupling.report(box)->force.y) / window;
        }
    }
    const double weight = double(box->GetMass()) * kG;
    const double bottom = box->GetPosition().y - half;
    std::printf("[measure] game preset, box at 0.5 on 0.15 m of water: bottom %.4f m (surface "
                "%.4f m), lift %.2f N vs weight %.2f N over the last 0.5 s\n",
                bottom, surface, lift, weight);
    CHECK(allFinite(pool.world));
    // Floating: its bottom in the water, well above the floor, the fluid carrying it.
    CHECK(bottom > 0.5 * surface);
    CHECK(bottom < surface);
    CHECK(lift == Approx(weight).epsilon(0.1));
}

TEST_CASE("the game preset: small light crates are never thrown out of the water or spun up",
          "[box2d]") {
    // 4.5 cm crates (two coarse cells) at a quarter of water's density. Two ways the coarse
    // solve once threw them: samples of a crate above the liquid, clamped into the grid's top
    // row, read as a solid row over full nodes (the crates left the water at 1 m/s); and a
    // rotation through the grid's staircase faces, which spun one to 15 rad/s until it sank
    // through the floor of the water.
    Pool pool;
    pool.world.setPositionBased(positionBasedPreset(Quality::Game));
    const float rho = box2d::arealDensity(pool.world, pool.water);
    const float surface = 15.0f * pool.s, half = 0.0225f;
    std::vector<b2Body*> crates;
    for (int k = 0; k < 4; ++k) {
        crates.push_back(addBox(pool.physics, b2_dynamicBody,
                                {0.1f + 0.13f * float(k), surface + half + 0.002f}, half, half,
                                0.25f * rho));
    }
    Coupling coupling(pool.world, pool.physics, CouplingDef{});
    float highest = 0.0f, lowest = 1.0f, spin = 0.0f;
    for (int f = 0; f < 300; ++f) {
        coupling.step(pool.world, kFrame);
        for (const b2Body* crate : crates) {
            highest = std::max(highest, crate->GetPosition().y - half);
            lowest = std::min(lowest, crate->GetPosition().y - half);
            spin = std::max(spin, std::fabs(crate->GetAngularVelocity()));
        }
    }
    std::printf("[measure] game preset, 4.5 cm crates at 0.25 on %.3f m of water, 5 s: bottoms "
                "between %.4f and %.4f m, largest spin %.2f rad/s\n",
                surface, lowest, highest, spin);
    CHECK(allFinite(pool.world));
    // Floating a quarter submerged (the bottom 1.1 cm under the surface), bobbing by at most a
    // few spacings (the game preset's bodies move at several cm/s: docs/position_based.md).
    CHECK(highest < surface + 3.0f * pool.s);
    CHECK(lowest > surface - 4.0f * pool.s);
    CHECK(spin < 5.0f);
}

TEST_CASE("a boundary plugin's rigid body with bad data is refused with the plugin's name",
          "[box2d]") {
    struct BadBodies final : BoundaryPlugin {
        RigidBody body;
        BadBodies() : BoundaryPlugin("test.bad_bodies", {}) {}
        void prepare(const StepContext&) override {
            m_samples.clear();
            m_samples.add(0.3f, 0.3f);
        }
        void project(const ProjectContext&, uint32_t, uint32_t) override {}
        std::span<const RigidBody> rigidBodies() const override { return {&body, 1}; }
    };
    Pool pool;
    pool.world.setPositionBased(positionBasedPreset(Quality::Game));
    auto& bad = static_cast<BadBodies&>(pool.world.addBoundary(std::make_unique<BadBodies>()));
    bad.body.mass = kNaN;
    bad.body.sampleEnd = 1;
    CHECK_THROWS_WITH(pool.world.step(kFrame),
                      "test.bad_bodies: rigid body 0: mass = nan is out of range [0, 1e9] "
                      "(unit: kg)");
    bad.body.mass = 1.0f;
    bad.body.sampleEnd = 2;
    CHECK_THROWS_WITH(pool.world.step(kFrame), "test.bad_bodies: rigid body 0: samples [0, 2) "
                                               "are not within the plugin's 1 samples");
    bad.body.sampleEnd = 1;
    bad.body.mass = -1.0f;
    CHECK_THROWS_WITH(pool.world.step(kFrame),
                      "test.bad_bodies: rigid body 0: mass = -1 is out of range [0, 1e9] "
                      "(unit: kg)");
    bad.body.mass = 1.0f;
    pool.world.step(kFrame);
    CHECK(allFinite(pool.world));
}

TEST_CASE("a plugin's hook cannot step the coupling that is stepping its world",
          "[box2d][bad-input][reentry]") {
    Pool pool;
    b2Body* ball = addCircle(pool.physics, b2_dynamicBody, {0.3f, 0.4f}, 0.03f, 50.0f);
    Coupling coupling(pool.world, pool.physics);
    std::vector<std::string> messages;
    pool.world.addForce(std::make_unique<HookForce>([&] {
        for (int k = 0; k < 2; ++k) {
            try {
                if (k == 0) {
                    coupling.step(pool.world, kFrame);
                } else {
                    coupling.stepFluid(pool.world, kFrame);
                }
                messages.emplace_back("no error");
            } catch (const Error& e) {
                CHECK(e.code() == ErrorCode::WrongState);
                messages.emplace_back(e.what());
            }
        }
    }));
    const float y = ball->GetPosition().y;
    for (int frame = 0; frame < 30; ++frame) {
        coupling.step(pool.world, kFrame);
    }
    // 30 frames of 4 rounds: each round's world step ran the hook once.
    REQUIRE(messages.size() == 2 * 30 * 4);
    CHECK(messages[0] == "fluid::box2d::Coupling::step: called during the world's own step (from "
                         "a plugin's hook); the coupling steps only between the world's steps");
    CHECK(messages[1] == "fluid::box2d::Coupling::stepFluid: called during the world's own step "
                         "(from a plugin's hook); the coupling steps only between the world's "
                         "steps");
    CHECK(pool.world.time() == Approx(30.0 * kFrame).margin(1e-9)); // no nested frame
    CHECK(ball->GetPosition().y < y); // the outer steps went on: the ball fell
}
