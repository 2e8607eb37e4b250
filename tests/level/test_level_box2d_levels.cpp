// fluid tests — the shipped levels with Box2D bodies: levels/paddle_wheel.json (the faucet's
// stream turns the wheel, in the direction of the side it falls on) and levels/crates.json
// (bodies as the file says; light crates float as deep as their density says, heavy ones sink).
// Short runs: fluid-tests-level is a fast executable.
#include <catch2/catch.hpp>

#include "level_support.h"
#include "test_support.h"

#include <fluid/level.h>

#include <box2d/box2d.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

using namespace fluid;
using namespace fluid::test;

namespace {

// The level's body named `name`; fails the test when there is none.
b2Body* requireBody(const Level& level, std::string_view name) {
    b2Body* body = bodyNamed(level, name);
    if (body == nullptr) {
        FAIL("no body " << name);
    }
    return body;
}

bool finite(const b2Body* body) {
    const b2Vec2 p = body->GetPosition(), v = body->GetLinearVelocity();
    return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(body->GetAngle()) &&
           std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(body->GetAngularVelocity());
}

} // namespace

TEST_CASE("paddle_wheel.json: the stream turns the wheel the way of the side it falls on",
          "[level][bodies]") {
    const std::string text = readLevel("paddle_wheel.json");
    // The shipped faucet pours right of the axle (x = 0.62 > 0.5): clockwise. Its mirror image
    // pours left of it (x = 0.38): counter-clockwise.
    const std::string faucet = "\"position\": [0.62, 0.95]";
    REQUIRE(text.find(faucet) != std::string::npos);
    std::string mirrored = text;
    mirrored.replace(mirrored.find(faucet), faucet.size(), "\"position\": [0.38, 0.95]");

    for (const double side : {1.0, -1.0}) {
        Level level = parseLevel(side > 0 ? text : mirrored, "paddle_wheel.json", builtins());
        REQUIRE(level.bodies.size() == 2);
        REQUIRE(level.joints.size() == 1);
        const b2Body* wheel = requireBody(level, "wheel");
        CHECK(wheel->GetType() == b2_dynamicBody);
        CHECK(requireBody(level, "axle")->GetType() == b2_staticBody);
        // A balanced wheel: it stays put until the water arrives (about 10 frames).
        playFrames(level, 6);
        CHECK(std::abs(wheel->GetAngle()) < 1e-3f);
        // 3 s of simulated time in all.
        const double ms = playFrames(level, 174);
        const float angle = wheel->GetAngle(), omega = wheel->GetAngularVelocity();
        INFO("side " << side << ": angle " << angle << " rad, omega " << omega << " rad/s");
        // More than one full turn, clockwise (negative) when the stream falls on the right.
        CHECK(-side * angle > 2.0 * M_PI);
        CHECK(-side * omega > 2.0);
        // The revolute joint holds the wheel on its axle.
        CHECK(std::abs(wheel->GetPosition().x - 0.5f) < 2e-3f);
        CHECK(std::abs(wheel->GetPosition().y - 0.5f) < 2e-3f);
        CHECK(test::allFinite(level.world));
        CHECK(level.world.particleCount() < 3000);
        std::printf("[measure] paddle_wheel.json (faucet %s of the axle): after 3 s angle %.2f "
                    "rad, omega %.2f rad/s, %u particles, %.2f ms per frame\n",
                    side > 0 ? "right" : "left", angle, omega, level.world.particleCount(), ms);
    }
}

TEST_CASE("crates.json: bodies as written, light crates float, heavy ones sink",
          "[level][bodies]") {
    Level level = parseLevel(readLevel("crates.json"), "crates.json", builtins());
    REQUIRE(level.bodies.size() == 9);
    const double areal = box2d::arealDensity(level.world, level.materials[0].second);
    // The tank walls are Box2D's only (the fluid has its boundary.box): static and dry.
    const b2Body* tank = requireBody(level, "tank");
    CHECK(tank->GetType() == b2_staticBody);
    CHECK(tank->GetFixtureList()->GetFilterData().categoryBits == kDryFixtureCategory);
    // Masses from densityRatio: ratio x areal density x area.
    CHECK(requireBody(level, "cork")->GetMass() == Approx(0.25 * areal * 0.1 * 0.08).epsilon(1e-5));
    CHECK(requireBody(level, "brick")->GetMass() == Approx(2.0 * areal * 0.1 * 0.05).epsilon(1e-5));
    CHECK(requireBody(level, "stone")->GetMass() ==
          Approx(1.5 * areal * M_PI * 0.035 * 0.035).epsilon(1e-5));
    CHECK(requireBody(level, "hull")->GetMass() ==
          Approx(0.4 * areal * 0.5 * 0.14 * 0.08).epsilon(1e-5));
    CHECK(level.world.particleCount() < 3000);

    const double ms = playFrames(level, 120);
    CHECK(test::allFinite(level.world));
    for (const auto& [name, body] : level.bodies) {
        INFO(name);
        CHECK(finite(body));
        if (body->GetType() != b2_dynamicBody) {
            continue;
        }
        // Nothing left the tank.
        CHECK(body->GetPosition().x > 0.0f);
        CHECK(body->GetPosition().x < 2.0f);
        CHECK(body->GetPosition().y > 0.0f);
        CHECK(body->GetPosition().y < 1.0f);
    }
    // After 2 s: the brick (2x the water's density) and the stone (1.5x) lie on the floor under
    // water; the wooden crates float, deeper the denser they are (Archimedes: the submerged
    // fraction of a floating box is its density ratio, 0.25, 0.5, 0.75).
    const auto submerged = [&](std::string_view name) {
        const box2d::BodyReport* report = level.coupling->report(requireBody(level, name));
        REQUIRE(report != nullptr);
        return report->submergedFraction;
    };
    const float brick = requireBody(level, "brick")->GetPosition().y;
    const float stone = requireBody(level, "stone")->GetPosition().y;
    CHECK(brick < 0.05f);
    CHECK(stone < 0.05f);
    CHECK(submerged("brick") > 0.9f);
    CHECK(submerged("stone") > 0.9f);
    const float cork = submerged("cork"), pine = submerged("pine"), oak = submerged("oak");
    CHECK(cork > 0.05f);
    CHECK(cork < pine);
    CHECK(pine < oak);
    CHECK(oak < 0.95f);
    CHECK(requireBody(level, "cork")->GetPosition().y > requireBody(level, "oak")->GetPosition().y);
    std::printf("[measure] crates.json after 2 s: brick y %.3f m, stone y %.3f m; submerged "
                "fraction cork %.2f (ratio 0.25), pine %.2f (0.5), oak %.2f (0.75); %u "
                "particles, %.2f ms per frame\n",
                brick, stone, cork, pine, oak, level.world.particleCount(), ms);
}

// The README's level loop: `level.step()` moves a level's Box2D bodies with the liquid; the bare
// `level.world.step`, which would leave them frozen, is refused with a message naming the call
// to make, before anything moves. Once the coupling is gone the world steps on its own again.
TEST_CASE("a level with bodies steps as the README shows, and refuses a bare World::step",
          "[level][bodies]") {
    Level level = loadLevel(std::string(FLUID_LEVELS_DIR) + "/crates.json", builtins());
    REQUIRE(level.coupling != nullptr);
    std::vector<b2Vec2> start;
    for (const auto& [name, body] : level.bodies) {
        start.push_back(body->GetPosition());
    }
    const uint64_t before = stateHash(level.world);
    CHECK_THROWS_WITH(level.world.step(1.0f / level.frameRate),
                      "World::step: boundary plugin 1 ('box2d.bodies') carries another engine's "
                      "bodies: step the world with fluid::box2d::Coupling::step (a level: "
                      "fluid::Level::step), which moves them with it; a bare World::step would "
                      "leave them behind");
    CHECK(stateHash(level.world) == before);
    CHECK(level.world.time() == 0.0);
    for (int frame = 0; frame < 60; ++frame) {
        level.step();
    }
    // The eight dynamic bodies fall onto the water or through it; the static tank stays.
    uint32_t moving = 0;
    for (std::size_t b = 0; b < level.bodies.size(); ++b) {
        const b2Body* body = level.bodies[b].second;
        const b2Vec2 d = body->GetPosition() - start[b];
        if (body->GetType() == b2_dynamicBody && d.Length() > 0.01f) {
            ++moving;
        }
    }
    CHECK(moving == 8);
    CHECK(level.world.time() == Approx(1.0).epsilon(1e-5));
    // The coupling's own stepping (Coupling::step through Level::step) still works after a
    // refused call, and without the coupling the world is an ordinary one.
    level.coupling.reset();
    level.world.step(1.0f / level.frameRate);
    CHECK(allFinite(level.world));
}
