// Particle handles: add/remove, stale detection (also after slot reuse), survival across steps
// while the grid sort moves slots.
#include "test_support.h"

#include <catch2/catch.hpp>

#include <sstream>

using namespace fluid;
using namespace fluid::test;

TEST_CASE("add and remove particles, handles go stale", "[unit][handles]") {
    World world;
    const MaterialId w = world.addMaterial(water());
    const ParticleHandle a = world.addParticle({0.0f, 0.0f}, {0.0f, 0.0f}, w);
    const ParticleHandle b = world.addParticle({1.0f, 0.0f}, {0.5f, 0.0f}, w);
    const ParticleHandle c = world.addParticle({2.0f, 0.0f}, {0.0f, 0.0f}, w);
    REQUIRE(world.particleCount() == 3);
    CHECK_FALSE(a.isNull());
    CHECK(a != b);
    CHECK(world.isValid(a));
    CHECK(world.isValid(b));
    CHECK(world.position(b) == glm::vec2(1.0f, 0.0f));
    CHECK(world.velocity(b) == glm::vec2(0.5f, 0.0f));
    CHECK(world.handleAt(*world.indexOf(c)) == c);

    world.removeParticle(a);
    CHECK(world.particleCount() == 2);
    CHECK_FALSE(world.isValid(a));
    CHECK_FALSE(world.indexOf(a).has_value());
    // The others still name their particles (removal moved the last one into the hole).
    CHECK(world.position(b) == glm::vec2(1.0f, 0.0f));
    CHECK(world.position(c) == glm::vec2(2.0f, 0.0f));

    CHECK_THROWS_MATCHES(world.removeParticle(a), Error,
                         Catch::Message("World::removeParticle: stale particle handle {slot " +
                                        std::to_string(a.slot) + ", generation " +
                                        std::to_string(a.generation) +
                                        "}: that particle was removed"));
    CHECK_THROWS_MATCHES(world.position(a), Error,
                         Catch::Message("World::position: stale particle handle {slot " +
                                        std::to_string(a.slot) + ", generation " +
                                        std::to_string(a.generation) +
                                        "}: that particle was removed"));
    CHECK_THROWS_AS(world.velocity(a), Error);
    CHECK_THROWS_AS(world.setVelocity(a, {1.0f, 0.0f}), Error);
    CHECK_THROWS_MATCHES(world.removeParticle(ParticleHandle{}), Error,
                         Catch::Message("World::removeParticle: null particle handle"));
    CHECK_FALSE(world.isValid(ParticleHandle{}));
    // A handle that was never issued.
    CHECK_FALSE(world.isValid(ParticleHandle{1000, 1, a.world}));
    CHECK_THROWS_AS(world.position(ParticleHandle{1000, 1, a.world}), Error);
    CHECK(world.particleCount() == 2);

    SECTION("slot reuse bumps the generation") {
        const ParticleHandle d = world.addParticle({3.0f, 0.0f}, {0.0f, 0.0f}, w);
        CHECK(d.slot == a.slot);             // the freed slot is reused...
        CHECK(d.generation != a.generation); // ...under a new generation
        CHECK(world.isValid(d));
        CHECK_FALSE(world.isValid(a)); // the old handle does not name the new particle
        CHECK_THROWS_AS(world.position(a), Error);
        CHECK(world.position(d) == glm::vec2(3.0f, 0.0f));
        world.removeParticle(d);
        CHECK_FALSE(world.isValid(d));
        CHECK(world.isValid(b));
        CHECK(world.isValid(c));
    }
}

TEST_CASE("handles follow their particles through steps", "[unit][handles]") {
    const Solver solver = GENERATE(Solver::PositionBased, Solver::Explicit);
    CAPTURE(solverLabel(solver));
    // The precise preset: with no wall in reach the game preset's coarse correction keeps the
    // momentum by taking its moves' mean off every particle, the lone one too
    // (docs/position_based.md, "Which preset").
    WorldDef def;
    def.positionBased = positionBasedPreset(Quality::Precise);
    def.solver = solver;
    World world(def); // zero gravity
    const MaterialId w = world.addMaterial(water());
    // A lone particle added first but lying far up-right, where the grid sort puts it last.
    const ParticleHandle lone = world.addParticle({0.5f, 0.5f}, {1.0f, -0.5f}, w);
    world.spawnBlob(latticeBlock(world, w, -0.1f, -0.1f, 20, 20));
    const uint32_t n = world.particleCount();
    REQUIRE(n == 401);
    REQUIRE(*world.indexOf(lone) == 0);

    // One blob particle gets a distinct velocity; remember every particle by handle.
    const ParticleHandle marked = world.handleAt(210);
    world.setVelocity(marked, {0.3f, 0.2f});
    const glm::vec2 markedStart = world.position(marked);
    std::vector<ParticleHandle> handles;
    std::vector<glm::vec2> start;
    for (uint32_t i = 0; i < n; ++i) {
        handles.push_back(world.handleAt(i));
        start.push_back(world.position(handles.back()));
    }

    // Short enough that viscosity barely slows the marked particle: 0.2 ms, or for the
    // position-based solver one sub-step (1/240 s; a frame under half of one is carried, not
    // stepped).
    const float dt = solver == Solver::PositionBased ? float(world.substepLength()) : 2e-4f;
    world.step(dt);
    REQUIRE(world.particleCount() == n);
    // Sorting moved slots: the lone particle is no longer in slot 0.
    CHECK(*world.indexOf(lone) != 0);
    uint32_t moved = 0;
    for (uint32_t i = 0; i < n; ++i) {
        moved += *world.indexOf(handles[i]) != i ? 1 : 0;
    }
    CHECK(moved > 0);
    // The lone particle has no neighbours: it moved exactly ballistically.
    CHECK(world.position(lone).x == Approx(0.5f + dt * 1.0f).epsilon(1e-6));
    CHECK(world.position(lone).y == Approx(0.5f - dt * 0.5f).epsilon(1e-6));
    CHECK(world.velocity(lone).x == Approx(1.0f).epsilon(1e-6));
    const glm::vec2 v = world.velocity(marked);
    const glm::vec2 d = world.position(marked) - markedStart;
    if (solver == Solver::Explicit) {
        // The marked particle keeps (about) its distinct velocity and moved along it.
        CHECK(v.x == Approx(0.3f).epsilon(0.05));
        CHECK(v.y == Approx(0.2f).epsilon(0.05));
        CHECK(d.x == Approx(0.3f * dt).epsilon(0.05));
        CHECK(d.y == Approx(0.2f * dt).epsilon(0.05));
    } else {
        // Incompressible: pushing into a packed lattice, the marked particle shares its motion
        // with its neighbours at once; it still moves along its velocity, the fastest of all.
        const float speed = std::sqrt(v.x * v.x + v.y * v.y);
        CHECK(speed > 0.5f * std::sqrt(0.13f));
        CHECK((v.x * 0.3f + v.y * 0.2f) / (speed * std::sqrt(0.13f)) > 0.95f);
        CHECK(d.x > 0.0f);
        CHECK(d.y > 0.0f);
        for (uint32_t i = 1; i < n; ++i) {
            if (handles[i] != marked) {
                const glm::vec2 u = world.velocity(handles[i]);
                CHECK(std::sqrt(u.x * u.x + u.y * u.y) < speed);
            }
        }
    }
    // Every handle still names the same particle: each blob particle moved far less than the
    // spacing (the lone one, handles[0], moved 0.2 mm; 4.7 mm in the position-based sub-step).
    REQUIRE(handles[0] == lone);
    float worst = 0.0f;
    for (uint32_t i = 0; i < n; ++i) {
        REQUIRE(world.isValid(handles[i]));
        REQUIRE(world.handleAt(*world.indexOf(handles[i])) == handles[i]);
        const glm::vec2 e = world.position(handles[i]) - start[i];
        if (i > 0) {
            worst = std::max(worst, std::sqrt(e.x * e.x + e.y * e.y));
        }
    }
    // The position-based step is a 1/240 s sub-step, in which the marked particle pushes its
    // neighbours farther, still a small share of the spacing.
    CHECK(worst < (solver == Solver::PositionBased ? 2e-3f : 1e-4f));

    // Removal after steps: the rest keep their identity.
    world.removeParticle(marked);
    CHECK_FALSE(world.isValid(marked));
    for (int k = 0; k < 5; ++k) {
        world.step(dt);
    }
    CHECK(world.particleCount() == n - 1);
    CHECK(world.position(lone).x == Approx(0.5f + 6 * dt).epsilon(1e-5));
}

TEST_CASE("handles know their world: another world refuses them", "[unit][handles]") {
    World first;
    World second;
    const MaterialId w1 = first.addMaterial(water());
    const MaterialId w2 = second.addMaterial(water());
    const ParticleHandle a = first.addParticle({0.0f, 0.0f}, {0.0f, 0.0f}, w1);
    const ParticleHandle b = second.addParticle({1.0f, 0.0f}, {0.0f, 0.0f}, w2);
    // Same slot and generation, different worlds.
    REQUIRE(a.slot == b.slot);
    REQUIRE(a.generation == b.generation);
    CHECK(a.world != b.world);
    CHECK(a != b);
    CHECK_FALSE(second.isValid(a));
    CHECK_FALSE(second.indexOf(a).has_value());
    CHECK_THROWS_MATCHES(
        second.removeParticle(a), Error,
        Catch::Message("World::removeParticle: particle handle {slot 0, generation 1} belongs to "
                       "another world (world " +
                       std::to_string(a.world) + "; this is world " + std::to_string(b.world) +
                       "; a handle saved with a snapshot needs World::adopt)"));
    CHECK(second.particleCount() == 1); // nothing removed
    CHECK(second.isValid(b));
    CHECK(first.isValid(a));
}

TEST_CASE("a handle from a destroyed world is refused by every later world, and a loaded world "
          "adopts saved handles",
          "[unit][handles][snapshot]") {
    // A level restart: the old world goes, a new one is made the same way. The old handle
    // names slot 0, generation 1, which the new world also holds: the tag alone tells them apart.
    ParticleHandle old;
    {
        World once;
        old = once.addParticle({0.0f, 0.0f}, {0.0f, 0.0f}, once.addMaterial(water()));
    }
    World again;
    const MaterialId w = again.addMaterial(water());
    const ParticleHandle h = again.addParticle({0.5f, 0.25f}, {0.0f, 0.0f}, w);
    REQUIRE(h.slot == old.slot);
    REQUIRE(h.generation == old.generation);
    CHECK(h.world > old.world); // tags count up, never reused
    CHECK_FALSE(again.isValid(old));
    CHECK_THROWS_MATCHES(again.position(old), Error,
                         Catch::Message("World::position: particle handle {slot 0, generation 1} "
                                        "belongs to another world (world " +
                                        std::to_string(old.world) + "; this is world " +
                                        std::to_string(h.world) +
                                        "; a handle saved with a snapshot needs World::adopt)"));
    for (int k = 0; k < 3; ++k) { // restarted again and again: still refused
        World later;
        later.addParticle({0.0f, 0.0f}, {0.0f, 0.0f}, later.addMaterial(water()));
        CHECK_FALSE(later.isValid(old));
    }

    std::stringstream bytes;
    again.save(bytes);
    Registry registry;
    const World loaded = World::load(bytes, registry);
    CHECK_FALSE(loaded.isValid(h)); // another World object
    const ParticleHandle adopted = loaded.adopt(h);
    CHECK(adopted.slot == h.slot);
    CHECK(adopted.generation == h.generation);
    CHECK(loaded.isValid(adopted));
    CHECK(loaded.position(adopted) == glm::vec2(0.5f, 0.25f));
    CHECK(loaded.adopt(ParticleHandle{}).isNull());
    CHECK(loaded.adopt(ParticleHandle{}) == ParticleHandle{});
}
