// Box2D coupling, contact events (Coupling::setContactEvents, particleContacts): a crate dropped
// into a tank reports its impact speed, then, floating at rest, its weight as the liquid's
// impulse and the particles along its wet outline; a dry body and a crate that does not ask
// report nothing; the same events for 1, 2 and 4 workers and after the coupling's save and load.
#include "box2d_support.h"

#include <fluid/box2d/physics_save.h>
#include <fluid/contacts.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <optional>
#include <sstream>
#include <vector>

using namespace fluid;
using namespace fluid::test;
using fluid::box2d::Coupling;
using fluid::box2d::ParticleContact;

namespace {

// Water 0.2 m deep in a 0.6 m tank; a 10 cm crate at half the water's density 0.2 m above the
// surface (asking for contact events; it does not turn), another beside it (not asking), and a
// static box above the water that never touches it (asking).
struct Scene {
    World world;
    MaterialId water;
    float surface = 0.0f;
    std::unique_ptr<b2World> physics;
    std::unique_ptr<Coupling> coupling;
    b2Body* crate = nullptr;
    b2Body* quiet = nullptr;
    b2Body* dry = nullptr;
};

constexpr float kHalf = 0.05f; // the crates' half size (m)
constexpr float kDrop = 0.2f;  // from the crate's centre to the surface (m)

std::unique_ptr<Scene> crateScene(uint32_t workers, Quality quality = Quality::Game) {
    WorldDef def = physicsDef();
    def.workerCount = workers;
    def.positionBased = positionBasedPreset(quality);
    auto s = std::make_unique<Scene>(Scene{World(def), {}, 0.0f, nullptr, nullptr});
    s->water = s->world.addMaterial(fluid::water());
    const float spacing = s->world.spacing(s->water);
    const uint32_t cols = 60, rows = 20;
    const float width = fillTank(s->world, s->water, cols, rows, 1.0f);
    s->surface = float(rows) * spacing;
    s->physics = std::make_unique<b2World>(b2Vec2(0.0f, -kG));
    addTankWalls(*s->physics, 0.0f, 0.0f, width, 1.0f);
    const float rho = box2d::arealDensity(s->world, s->water);
    s->crate =
        addBox(*s->physics, b2_dynamicBody, {0.2f, s->surface + kDrop}, kHalf, kHalf, 0.5f * rho);
    // Upright: a half-dense square floats corner down (its stable pose), and the game preset's
    // coarse solve leaves a gap under a corner (docs/box2d.md, "Which preset").
    s->crate->SetFixedRotation(true);
    s->quiet =
        addBox(*s->physics, b2_dynamicBody, {0.45f, s->surface + kDrop}, kHalf, kHalf, 0.5f * rho);
    s->dry = addBox(*s->physics, b2_staticBody, {0.05f, s->surface + 0.3f}, 0.03f, 0.03f, 0.0f);
    box2d::CouplingDef cd;
    cd.categoryMask = kFluidMask;
    s->coupling = std::make_unique<Coupling>(s->world, *s->physics, cd);
    s->coupling->setContactEvents(s->crate, true);
    s->coupling->setContactEvents(s->dry, true);
    return s;
}

// A frame's events as bytes (floats bit for bit; bodies by their index in the body list).
std::vector<uint8_t> eventBytes(const Scene& s) {
    std::vector<uint8_t> out;
    const auto add = [&](const void* data, size_t size) {
        const auto* b = static_cast<const uint8_t*>(data);
        out.insert(out.end(), b, b + size);
    };
    const std::span<const ParticleContact> events = s.coupling->particleContacts();
    for (uint32_t k = 0; k < events.size(); ++k) {
        const ParticleContact& e = events[k];
        uint32_t body = 0;
        for (const b2Body* b = s.physics->GetBodyList(); b != e.body; b = b->GetNext()) {
            ++body;
        }
        add(&body, sizeof body);
        add(&e.material.index, sizeof e.material.index);
        add(&e.group.index, sizeof e.group.index); // not its world tag: each world has its own
        add(&e.group.generation, sizeof e.group.generation);
        add(&e.particles, sizeof e.particles);
        add(&e.impulse, sizeof e.impulse);
        add(&e.point, sizeof e.point);
        add(&e.approachSpeed, sizeof e.approachSpeed);
        for (const ParticleHandle h : s.coupling->contactParticles(k)) {
            add(&h.slot, sizeof h.slot);
            add(&h.generation, sizeof h.generation);
        }
    }
    return out;
}

} // namespace

TEST_CASE("contacts: a crate dropped into a tank reports its impact, then its weight and its wet "
          "outline",
          "[box2d][contacts]") {
    // The precise preset, as the levels with floating bodies name it: on the game preset the
    // coupling hands Box2D the hydrostatic force and drops part of the rest (docs/box2d.md,
    // "Which preset"), and the liquid's own impulse on the floating crate read 2.1% under its
    // weight.
    std::unique_ptr<Scene> s = crateScene(physicsWorkers(), Quality::Precise);
    const float spacing = s->world.spacing(s->water);
    const double weight = double(s->crate->GetMass()) * kG;
    float impact = -1.0f, speedBefore = 0.0f;
    double lift = 0.0, particles = 0.0;
    int resting = 0;
    for (int f = 0; f < 240; ++f) {
        const float fall = -s->crate->GetLinearVelocity().y;
        s->coupling->step(s->world, kFrame);
        for (const ParticleContact& e : s->coupling->particleContacts()) {
            // Neither the crate that does not ask nor the body above the water reports.
            REQUIRE(e.body == s->crate);
            CHECK(e.material == s->water);
            CHECK(e.particles == s->coupling->contactParticles(0).size());
            CHECK(e.group == majorityGroup(s->world, s->coupling->contactParticles(0)));
            CHECK(isValid(s->world, e.group));
            if (impact < 0.0f) {
                impact = e.approachSpeed;
                speedBefore = fall;
            }
        }
        if (f >= 150) {
            // Floating at rest (its speed under 0.1 m/s): every frame reports it.
            REQUIRE(s->coupling->particleContacts().size() == 1);
            const ParticleContact& e = s->coupling->particleContacts()[0];
            lift += double(e.impulse.y);
            particles += double(e.particles);
            ++resting;
            CHECK(std::fabs(e.point.x - s->crate->GetPosition().x) < kHalf);
            CHECK(e.point.y < s->crate->GetPosition().y); // its wet half is below
        }
    }
    const double seconds = double(resting) * double(kFrame);
    const double force = lift / seconds, mean = particles / double(resting);
    // Half its density: half submerged, wet along its bottom and half of each side.
    const double wet = (2.0 * kHalf + 2.0 * kHalf) / double(spacing);
    std::printf("[measure] crate dropped %.2f m into water: first contact at %.2f m/s approach "
                "(falling at %.2f m/s); floating: liquid force %.3f N for a weight of %.3f N, "
                "%.1f particles touching (wet outline %.1f spacings)\n",
                kDrop - kHalf, impact, speedBefore, force, weight, mean, wet);
    // The first contact reads the fall: the water stands still, the crate comes down at
    // sqrt(2 g h) (within 20%: Box2D's step and the first sub-steps' slowing).
    CHECK(impact == Approx(std::sqrt(2.0 * kG * (kDrop - kHalf))).epsilon(0.2));
    // At rest the liquid holds the crate up: its impulse over the last 1.5 s is the weight's
    // (docs/box2d.md, "Contact events"). The crate still bobs at under 1 cm/s: a momentum change of at most
    // 0.01 m/s x its mass over 1.5 s, 0.07% of the weight; 1% allows for that and the rounds'
    // one-round lag.
    CHECK(force == Approx(weight).epsilon(0.01));
    // One row of particles along the wet outline, within 30% (corners, the surface's row).
    CHECK(mean == Approx(wet).epsilon(0.3));
}

TEST_CASE("contacts: a crate's events are the same for 1, 2 and 4 workers and after the "
          "coupling's save and load",
          "[box2d][contacts]") {
    const int frames = 30; // through the impact (frame 10)
    std::vector<std::vector<uint8_t>> runs;
    for (const uint32_t workers : {1u, 2u, 4u}) {
        std::unique_ptr<Scene> s = crateScene(workers);
        std::vector<uint8_t> all;
        for (int f = 0; f < frames; ++f) {
            s->coupling->step(s->world, kFrame);
            const std::vector<uint8_t> bytes = eventBytes(*s);
            all.insert(all.end(), bytes.begin(), bytes.end());
        }
        REQUIRE(!s->coupling->particleContacts().empty());
        runs.push_back(all);
    }
    CHECK(runs[1] == runs[0]);
    CHECK(runs[2] == runs[0]);

    // Saved just before the impact: world, Box2D world and coupling; loaded into new ones. The
    // setting comes back with the coupling, by body index.
    std::unique_ptr<Scene> s = crateScene(1);
    for (int f = 0; f < 8; ++f) {
        s->coupling->step(s->world, kFrame);
    }
    std::stringstream world, physics, coupling;
    s->world.save(world);
    box2d::savePhysics(*s->physics, physics);
    s->coupling->save(coupling);
    Registry registry;
    registerBuiltinPlugins(registry);
    box2d::registerCouplingPlugin(registry);
    auto loaded = std::make_unique<Scene>(
        Scene{World::load(world, registry), s->water, s->surface, nullptr, nullptr});
    loaded->physics = box2d::loadPhysics(physics);
    loaded->coupling =
        std::make_unique<Coupling>(loaded->world, *loaded->physics, s->coupling->def());
    loaded->coupling->load(coupling);
    std::vector<b2Body*> bodies;
    for (b2Body* b = loaded->physics->GetBodyList(); b != nullptr; b = b->GetNext()) {
        bodies.push_back(b);
    }
    uint32_t asking = 0;
    for (b2Body* b : bodies) {
        asking += loaded->coupling->contactEvents(b) ? 1 : 0;
    }
    CHECK(asking == 2);
    CHECK(loaded->coupling->particleContacts().empty()); // events are not state
    for (int f = 8; f < frames; ++f) {
        s->coupling->step(s->world, kFrame);
        loaded->coupling->step(loaded->world, kFrame);
        CHECK(eventBytes(*loaded) == eventBytes(*s));
    }
    CHECK(!loaded->coupling->particleContacts().empty());
}

TEST_CASE("contacts: the coupling refuses a body of another world, forgets destroyed ones, and "
          "asking changes nothing of the step",
          "[box2d][contacts]") {
    std::unique_ptr<Scene> s = crateScene(1);
    b2World other(b2Vec2(0.0f, -kG));
    b2Body* stranger = addCircle(other, b2_dynamicBody, {0.0f, 0.0f}, 0.05f, 10.0f);
    const char* message = "fluid::box2d::Coupling::setContactEvents: the body is not one of the "
                          "coupling's b2World (a null, destroyed or another world's body)";
    CHECK_THROWS_WITH(s->coupling->setContactEvents(stranger, true), message);
    CHECK_THROWS_WITH(s->coupling->setContactEvents(nullptr, true), message);
    CHECK_THROWS_WITH(s->coupling->contactParticles(0),
                      "fluid::box2d::Coupling::contactParticles: contact = 0 is out of range: the "
                      "last step reported 0 contacts");
    // With their codes (docs/errors.md): a body not in the coupling's world is a stale id.
    const auto codeOf = [](const auto& call) {
        try {
            call();
        } catch (const Error& e) {
            return std::optional<ErrorCode>(e.code());
        }
        return std::optional<ErrorCode>();
    };
    CHECK(codeOf([&] { s->coupling->setContactEvents(stranger, true); }) == ErrorCode::StaleId);
    CHECK(codeOf([&] { (void)s->coupling->contactParticles(0); }) == ErrorCode::OutOfRange);

    // The same scene without asking: bodies and particles bit for bit the same.
    std::unique_ptr<Scene> plain = crateScene(1);
    plain->coupling->setContactEvents(plain->crate, false);
    plain->coupling->setContactEvents(plain->dry, false);
    for (int f = 0; f < 20; ++f) {
        s->coupling->step(s->world, kFrame);
        plain->coupling->step(plain->world, kFrame);
        CHECK(plain->coupling->particleContacts().empty());
    }
    CHECK(!s->coupling->particleContacts().empty());
    CHECK(stateHash(s->world) == stateHash(plain->world));
    CHECK(bodiesHash(*s->physics) == bodiesHash(*plain->physics));

    // Destroyed: forgotten at the next step (a new body at its address does not inherit it).
    s->physics->DestroyBody(s->crate);
    s->coupling->step(s->world, kFrame);
    CHECK(s->coupling->particleContacts().empty());
    CHECK(!s->coupling->contactEvents(s->crate));
    CHECK(s->coupling->contactEvents(s->dry));
}
