// Contact events (fluid/contacts.h) between particles and boundary plugins' rigid bodies: a disc
// held in a resting tank reports the particles around it (a brute-force scan's) and the
// buoyancy as its impulse; a dry disc and a disc that does not ask report nothing, and asking
// changes nothing of the step; a disc moving through water reads its speed as the approach
// speed; the same events for 1, 2 and 4 workers and after a save and load; bad calls refused.
#include "test_support.h"

#include <fluid/contacts.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <numbers>
#include <set>
#include <sstream>

using namespace fluid;
using namespace fluid::test;

namespace {

constexpr float kRadius = 0.05f;

struct Tank {
    World world;
    MaterialId water;
    CircleBoundary* disc = nullptr;
};

// A 0.6 m wide tank of water 0.4 m deep (60 x 40 lattice points) with a disc of radius 5 cm at
// `centre` (plugin 1), asking for contact events or not.
Tank discTank(glm::vec2 centre, bool contacts, WorldDef def) {
    Tank t{World(def), {}, nullptr};
    t.water = t.world.addMaterial(forSolver(water(), def.solver));
    t.world.addForce(std::make_unique<GravityForce>());
    t.world.addBoundary(std::make_unique<BoxContainer>(-0.3f, 0.0f, 0.3f, 1.0f));
    auto disc = std::make_unique<CircleBoundary>(centre, kRadius);
    disc->setContactEvents(contacts);
    t.disc = disc.get();
    t.world.addBoundary(std::move(disc));
    t.world.spawnBlob(latticeBlock(t.world, t.water, -0.3f, 0.0f, 60, 40));
    return t;
}

WorldDef def(uint32_t workers = 1, Solver solver = Solver::PositionBased) {
    WorldDef d;
    d.workerCount = workers;
    d.solver = solver;
    return d;
}

// The precise preset: a body of mass 0 (the host moves it) takes no part in the game preset's
// coarse pressure solve, so its samples miss the large-scale pressure that solve carries (the
// disc below read -6 N, pushed down, for a buoyancy of +10 N; docs/box2d.md, "Which preset").
WorldDef precise(uint32_t workers = 1) {
    WorldDef d = def(workers);
    d.positionBased = positionBasedPreset(Quality::Precise);
    return d;
}

// Everything an event holds, as bytes (floats compared bit for bit).
std::vector<uint8_t> eventBytes(const World& world) {
    std::vector<uint8_t> out;
    const auto add = [&](const void* data, size_t size) {
        const auto* b = static_cast<const uint8_t*>(data);
        out.insert(out.end(), b, b + size);
    };
    const std::span<const BodyContact> events = bodyContacts(world);
    for (uint32_t k = 0; k < events.size(); ++k) {
        const BodyContact& e = events[k];
        add(&e.plugin, sizeof e.plugin);
        add(&e.body, sizeof e.body);
        add(&e.material.index, sizeof e.material.index);
        add(&e.group.index, sizeof e.group.index); // not its world tag: each world has its own
        add(&e.group.generation, sizeof e.group.generation);
        add(&e.particles, sizeof e.particles);
        add(&e.impulse, sizeof e.impulse);
        add(&e.point, sizeof e.point);
        add(&e.approachSpeed, sizeof e.approachSpeed);
        for (const ParticleHandle h : contactParticles(world, k)) {
            add(&h.slot, sizeof h.slot);
            add(&h.generation, sizeof h.generation);
        }
    }
    return out;
}

// The slots of the particles within kContactReach sample spacings of one of the disc's
// samples now: a scan of every particle against every sample.
std::set<uint32_t> touchingNow(const Tank& t) {
    const float reach = kContactReach * t.world.spacing(t.water);
    const KinematicShape::Pose pose = t.disc->pose();
    std::set<uint32_t> out;
    for (uint32_t i = 0; i < t.world.particleCount(); ++i) {
        const glm::dvec2 p(t.world.positionX()[i], t.world.positionY()[i]);
        for (const glm::dvec2 local : t.disc->localSamples()) {
            const glm::dvec2 d = p - pose.toWorld(local);
            if (d.x * d.x + d.y * d.y <= double(reach) * double(reach)) {
                out.insert(t.world.handleAt(i).slot);
                break;
            }
        }
    }
    return out;
}

} // namespace

TEST_CASE("contacts: a disc held in a resting tank reports the particles around it and the "
          "buoyancy",
          "[unit][contacts]") {
    const glm::vec2 centre{0.0f, 0.2f};
    Tank t = discTank(centre, true, precise());
    const float s = t.world.spacing(t.water);
    // Two groups: the particles left of the disc's centre (less than half of those around it)
    // move into a second one, so the event must name the group most of its particles are in.
    const GroupHandle left = createGroup(t.world);
    for (uint32_t i = 0; i < t.world.particleCount(); ++i) {
        if (t.world.positionX()[i] < centre.x - 0.02f) {
            setGroup(t.world, t.world.handleAt(i), left);
        }
    }
    double lift = 0.0, side = 0.0;
    int frames = 0;
    for (int f = 0; f < 120; ++f) {
        t.world.step(kFrame);
        const std::span<const BodyContact> events = bodyContacts(t.world);
        REQUIRE(events.size() == 1);
        const BodyContact& e = events[0];
        CHECK(e.plugin == 1);
        CHECK(e.body == 0);
        CHECK(e.material == t.water);
        REQUIRE(contactParticles(t.world, 0).size() == e.particles);
        CHECK(e.group == majorityGroup(t.world, contactParticles(t.world, 0)));
        CHECK(isValid(t.world, e.group));
        CHECK(e.group != left);
        if (f >= 60) {
            lift += double(e.impulse.y);
            side += double(e.impulse.x);
            ++frames;
        }
    }
    // Archimedes: the fluid's mean force on the disc over the last second is the weight of the
    // water it displaces, rho g pi R^2 depth, within 5% (the samples stand for the disc's outline
    // at the lattice's resolution; docs/plugins.md, "Contact events"), and nothing sideways.
    const double buoyancy =
        1000.0 * double(kG) * std::numbers::pi * kRadius * kRadius * double(t.world.def().depth);
    const double seconds = double(frames) * double(kFrame);
    std::printf("[measure] disc of 5 cm in a resting tank: lift %.3f N (buoyancy %.3f N), "
                "side %.4f N, %u particles touching\n",
                lift / seconds, buoyancy, side / seconds, bodyContacts(t.world)[0].particles);
    CHECK(lift / seconds == Approx(buoyancy).epsilon(0.05));
    CHECK(std::fabs(side / seconds) < 0.02 * buoyancy);

    // The particles: every one a scan finds touching the disc now, and each one reported within
    // a tenth of a spacing more of the disc (the tank is at rest: no particle moves that far in
    // a frame).
    const BodyContact& e = bodyContacts(t.world)[0];
    const std::set<uint32_t> now = touchingNow(t);
    std::set<uint32_t> reported;
    for (const ParticleHandle h : contactParticles(t.world, 0)) {
        REQUIRE(t.world.isValid(h));
        reported.insert(h.slot);
        const glm::vec2 p = t.world.position(h);
        CHECK(std::hypot(p.x - centre.x, p.y - centre.y) <
              kRadius - 0.5f * s + kContactReach * s + 0.1f * s);
    }
    CHECK(std::includes(reported.begin(), reported.end(), now.begin(), now.end()));
    // The first row round the disc: one particle per spacing of its circumference, less the
    // gaps of a square lattice bent round a circle.
    const double ring = 2.0 * std::numbers::pi * kRadius / double(s);
    CHECK(double(e.particles) > 0.75 * ring);
    CHECK(double(e.particles) < 1.1 * ring);
    // The ring's mean point is the disc's centre; at rest nothing approaches.
    CHECK(std::hypot(e.point.x - centre.x, e.point.y - centre.y) < 0.2f * s);
    CHECK(e.approachSpeed < 0.05f);
}

TEST_CASE("contacts: a dry disc and a disc that does not ask report nothing, and asking changes "
          "nothing of the step",
          "[unit][contacts]") {
    for (const Solver solver : {Solver::PositionBased, Solver::Explicit}) {
        INFO(solverLabel(solver));
        // A few frames each: the explicit solver's take a hundred sub-steps (CI time under ASan).
        const int frames = solver == Solver::Explicit ? 2 : 8;
        Tank dry = discTank({0.0f, 0.7f}, true, def(1, solver));    // 0.25 m above the water
        Tank quiet = discTank({0.0f, 0.2f}, false, def(1, solver)); // in it, not asking
        Tank asking = discTank({0.0f, 0.2f}, true, def(1, solver)); // in it, asking
        for (int f = 0; f < frames; ++f) {
            dry.world.step(kFrame);
            quiet.world.step(kFrame);
            asking.world.step(kFrame);
            CHECK(bodyContacts(dry.world).empty());
            CHECK(bodyContacts(quiet.world).empty());
            CHECK(bodyContacts(asking.world).size() == 1);
        }
        // The events only read the step: the particles move as without them, bit for bit.
        CHECK(stateHash(asking.world) == stateHash(quiet.world));
        // Stopped between steps: the next step reports nothing.
        asking.disc->setContactEvents(false);
        asking.world.step(kFrame);
        CHECK(bodyContacts(asking.world).empty());
        CHECK_THROWS_WITH(contactParticles(asking.world, 0),
                          "fluid::contactParticles: contact = 0 is out of range: the last step "
                          "reported 0 contacts");
    }
}

TEST_CASE("contacts: a disc moving through the water reads its speed as the approach speed",
          "[unit][contacts]") {
    // The disc crosses the resting tank at 1 m/s: the water ahead of it stands still, so it
    // approaches the disc's front at the disc's speed until the solver moves it away.
    Tank t = discTank({-0.2f, 0.2f}, true, def());
    for (int f = 0; f < 30; ++f) {
        t.world.step(kFrame);
    }
    t.disc->setVelocity({1.0f, 0.0f}, 0.0f);
    float fastest = 0.0f;
    for (int f = 0; f < 12; ++f) {
        t.world.step(kFrame);
        REQUIRE(bodyContacts(t.world).size() == 1);
        const BodyContact& e = bodyContacts(t.world)[0];
        fastest = std::max(fastest, e.approachSpeed);
        // Pushing the water ahead: the liquid pushes back, against the motion.
        CHECK(e.impulse.x < 0.0f);
        // The mean of points within reach of the disc lies within that reach of its centre
        // (the disc moved 1/60 m during the step: its sub-steps' places lie behind it).
        const glm::dvec2 c = t.disc->pose().origin;
        const double reach = kRadius + kContactReach * t.world.spacing(t.water) + kFrame;
        CHECK(std::hypot(e.point.x - c.x, e.point.y - c.y) < reach);
    }
    std::printf("[measure] disc at 1 m/s through water: approach speed up to %.3f m/s\n", fastest);
    CHECK(fastest > 0.8f);
    CHECK(fastest < 1.5f);
}

// [slow]: the worker matrix is too slow for the asan preset (docs/building.md), where the events'
// other tests still run on one worker; the release and tsan presets run it.
TEST_CASE("contacts: the same events for 1, 2 and 4 workers and after a save and load",
          "[unit][contacts][slow]") {
    for (const Solver solver : {Solver::PositionBased, Solver::Explicit}) {
        INFO(solverLabel(solver));
        // Saved after half of them; few, as above (CI time under ASan).
        const int frames = solver == Solver::Explicit ? 2 : 10;
        std::vector<std::vector<uint8_t>> runs;
        for (const uint32_t workers : {1u, 2u, 4u}) {
            Tank t = discTank({0.0f, 0.35f}, true, def(workers, solver)); // at the surface
            t.disc->setVelocity({0.0f, -0.5f}, 0.0f);
            std::vector<uint8_t> all;
            for (int f = 0; f < frames; ++f) {
                t.world.step(kFrame);
                const std::vector<uint8_t> bytes = eventBytes(t.world);
                all.insert(all.end(), bytes.begin(), bytes.end());
            }
            REQUIRE(!bodyContacts(t.world).empty());
            runs.push_back(all);
        }
        CHECK(runs[1] == runs[0]);
        CHECK(runs[2] == runs[0]);

        // Saved mid-way, loaded, both stepped on: the same events, and the shape still asks.
        Tank t = discTank({0.0f, 0.35f}, true, def(1, solver));
        t.disc->setVelocity({0.0f, -0.5f}, 0.0f);
        for (int f = 0; f < frames / 2; ++f) {
            t.world.step(kFrame);
        }
        World loaded = reloaded(t.world);
        CHECK(bodyContacts(loaded).empty()); // events are not state
        auto* shape = dynamic_cast<const KinematicShape*>(loaded.boundaries()[1].get());
        REQUIRE(shape != nullptr);
        CHECK(shape->contactEvents());
        for (int f = frames / 2; f < frames; ++f) {
            t.world.step(kFrame);
            loaded.step(kFrame);
            CHECK(eventBytes(loaded) == eventBytes(t.world));
        }
        CHECK(!bodyContacts(loaded).empty());
    }
}

TEST_CASE("contacts: a snapshot of shapes that do not ask is unchanged, and a bad flag is refused",
          "[unit][contacts]") {
    Tank quiet = discTank({0.0f, 0.2f}, false, def());
    Tank asking = discTank({0.0f, 0.2f}, true, def());
    asking.disc->setContactEvents(false);
    std::stringstream a, b;
    quiet.world.save(a);
    asking.world.save(b);
    CHECK(a.str() == b.str());
    // A shape's state holds one byte, 1, when it asks; anything else is refused by name.
    CircleBoundary circle({0.0f, 0.0f}, 0.1f);
    StateWriter out;
    out.write(uint8_t(2));
    StateReader in(out.bytes());
    CHECK_THROWS_WITH(circle.restoreState(in),
                      "snapshot: plugin 'boundary.circle': contact events flag = 2 is not 0 or 1");
    circle.setContactEvents(true);
    StateWriter on;
    circle.saveState(on);
    CHECK(on.bytes().size() == 1);
    CircleBoundary other({0.0f, 0.0f}, 0.1f);
    StateReader back(on.bytes());
    other.restoreState(back);
    CHECK(other.contactEvents());
}

TEST_CASE("contacts: reading the events during the world's own step is refused",
          "[unit][contacts]") {
    Tank t = discTank({0.0f, 0.2f}, true, def());
    std::string message;
    ErrorCode code = ErrorCode::BadArgument;
    t.world.addForce(std::make_unique<HookForce>([&] {
        try {
            (void)bodyContacts(t.world);
        } catch (const Error& e) {
            message = e.what();
            code = e.code();
        }
    }));
    t.world.step(kFrame);
    CHECK(code == ErrorCode::WrongState);
    CHECK(message == "fluid::bodyContacts: called during the world's own step (from a plugin's "
                     "hook or a task); read the contacts between steps");
    CHECK(bodyContacts(t.world).size() == 1); // and between steps it answers
}
