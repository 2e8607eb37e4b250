// Calls back into a world from inside its own step (a plugin's hook): every call that would
// change, save or step the world is refused with ErrorCode::WrongState and names the rule, the
// outer step goes on, and reads stay allowed. docs/plugins.md, "Calling back into the world".
#include "test_support.h"

#include <catch2/catch.hpp>

#include <functional>
#include <sstream>

using namespace fluid;
using namespace fluid::test;

TEST_CASE("a plugin's hook cannot change, save or step the world that runs it",
          "[unit][bad-input][reentry]") {
    World world;
    const MaterialId w = world.addMaterial(water());
    world.addForce(std::make_unique<GravityForce>());
    world.addBoundary(std::make_unique<BoxContainer>(-0.2f, 0.0f, 0.2f, 0.4f));
    world.spawnBlob(latticeBlock(world, w, -0.2f, 0.0f, 20, 8));
    const ParticleHandle first = world.handleAt(0);
    const EmitterId emitter = world.addEmitter([&] {
        EmitterDef e;
        e.material = w;
        e.position = {0.0f, 0.3f};
        e.rate = 0.0f;
        return e;
    }());
    const uint32_t particles = world.particleCount();

    struct Call {
        const char* name;
        std::function<void()> run;
    };
    const std::vector<Call> calls{
        {"World::step", [&] { world.step(kFrame); }},
        {"World::addMaterial", [&] { world.addMaterial(water()); }},
        {"World::setMaterial", [&] { world.setMaterial(w, water()); }},
        {"World::addParticle",
         [&] {
             world.addParticle({0.0f, 0.3f}, {0.0f, 0.0f}, w);
         }},
        {"World::spawnBlob", [&] { world.spawnBlob(latticeBlock(world, w, -0.1f, 0.3f, 2, 2)); }},
        {"World::removeParticle", [&] { world.removeParticle(first); }},
        {"World::setVelocity",
         [&] {
             world.setVelocity(first, {1.0f, 0.0f});
         }},
        {"World::setLifetime", [&] { world.setLifetime(first, 1.0f); }},
        {"World::addEmitter", [&] { world.addEmitter(world.emitter(emitter)); }},
        {"World::setEmitter", [&] { world.setEmitter(emitter, world.emitter(emitter)); }},
        {"World::addDrain",
         [&] {
             DrainDef d;
             d.shape = Shape::box({-0.1f, 0.0f}, {0.1f, 0.1f});
             world.addDrain(d);
         }},
        {"World::addSensor",
         [&] {
             SensorDef d;
             d.shape = Shape::box({-0.1f, 0.0f}, {0.1f, 0.1f});
             world.addSensor(d);
         }},
        {"World::addForce", [&] { world.addForce(std::make_unique<GravityForce>()); }},
        {"World::addBoundary", [&] { world.addBoundary(std::make_unique<BoxContainer>()); }},
        {"World::setPositionBased", [&] { world.setPositionBased(world.def().positionBased); }},
        {"World::save",
         [&] {
             std::ostringstream out;
             world.save(out);
         }},
    };
    size_t which = 0;
    std::vector<std::string> messages;
    uint32_t readCount = 0;
    world.addForce(std::make_unique<HookForce>([&] {
        REQUIRE(world.stepping());
        readCount = world.particleCount(); // reads are fine
        try {
            calls[which].run();
            messages.emplace_back("no error");
        } catch (const Error& e) {
            CHECK(e.code() == ErrorCode::WrongState);
            messages.emplace_back(e.what());
        }
    }));
    CHECK_FALSE(world.stepping());
    for (which = 0; which < calls.size(); ++which) {
        CAPTURE(calls[which].name);
        world.step(kFrame);
        CHECK_FALSE(world.stepping());
        REQUIRE(messages.size() == which + 1);
        CHECK(messages.back() ==
              std::string(calls[which].name) +
                  ": called during the world's own step (from a plugin's hook or a task); a "
                  "world is changed, saved or stepped only between its steps");
    }
    CHECK(readCount == particles);
    // Each outer step simulated its own frame and nothing more; nothing was added or removed.
    CHECK(world.time() == Approx(double(calls.size()) * kFrame).margin(1e-6));
    CHECK(world.particleCount() == particles);
    CHECK(world.materialCount() == 1);
    CHECK(world.forces().size() == 2); // gravity and the hook
    CHECK(world.boundaries().size() == 1);
    CHECK(world.drainCount() == 0);
    CHECK(world.sensorCount() == 0);
    CHECK(world.velocity(first).x != 1.0f);
    // Between steps the same calls work.
    CHECK_NOTHROW(world.addMaterial(water()));
    CHECK_NOTHROW(world.setVelocity(first, {1.0f, 0.0f}));
}

TEST_CASE("a step that throws from a hook leaves the world steppable",
          "[unit][bad-input][reentry]") {
    World world;
    const MaterialId w = world.addMaterial(water());
    world.spawnBlob(latticeBlock(world, w, -0.2f, 0.0f, 10, 10));
    bool fail = true;
    world.addForce(std::make_unique<HookForce>([&] {
        if (fail) {
            throw Error("the hook's own check");
        }
    }));
    CHECK_THROWS_WITH(world.step(kFrame), "the hook's own check");
    CHECK_FALSE(world.stepping()); // cleared on the way out
    fail = false;
    CHECK_NOTHROW(world.step(kFrame));
    CHECK_NOTHROW(world.addParticle({0.5f, 0.5f}, {0.0f, 0.0f}, w));
}
