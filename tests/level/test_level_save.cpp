// fluid tests — level saves (Level::save, readLevelSave): a level without bodies continues
// bit-identically; with Box2D bodies (levels/crates.json) closely, within 1 mm; names, goal,
// bodies the game added and joints come back; bad or truncated saves get clear errors.
#include <catch2/catch.hpp>

#include "level_support.h"

#include <fluid/box2d/physics_save.h>
#include <fluid/level.h>

#include <box2d/box2d.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

using namespace fluid;
using namespace fluid::test;

namespace {

std::string saveOf(const Level& level) {
    std::ostringstream out;
    level.save(out);
    return out.str();
}

Level restore(const std::string& bytes, const LevelOptions& options = {}) {
    std::istringstream in(bytes);
    return readLevelSave(in, "s.sav", builtins(), options);
}

std::string errorOfSave(const std::string& bytes) {
    try {
        restore(bytes);
    } catch (const Error& e) {
        return e.what();
    }
    return "no error";
}

// Every particle's position and velocity, in slot order.
std::vector<float> state(const World& world) {
    std::vector<float> out;
    for (const auto span : {world.positionX(), world.positionY(), world.velocityX(),
                            world.velocityY()}) {
        out.insert(out.end(), span.begin(), span.end());
    }
    return out;
}

// Each material's centre of mass (unit: m).
std::vector<glm::dvec2> centres(const World& world) {
    std::vector<glm::dvec2> sum(world.materialCount(), glm::dvec2(0.0));
    std::vector<double> count(world.materialCount(), 0.0);
    const auto px = world.positionX(), py = world.positionY();
    const auto material = world.materialIndex();
    for (std::size_t i = 0; i < px.size(); ++i) {
        sum[material[i]] += glm::dvec2(px[i], py[i]);
        count[material[i]] += 1.0;
    }
    for (std::size_t m = 0; m < sum.size(); ++m) {
        sum[m] /= std::max(count[m], 1.0);
    }
    return sum;
}

// The bytes with their trailing checksum made right again (a well-formed but altered save).
std::string resealed(std::string bytes) {
    uint64_t h = 0xcbf29ce484222325ull;
    for (std::size_t k = 0; k + 8 < bytes.size(); ++k) {
        h ^= uint8_t(bytes[k]);
        h *= 0x100000001b3ull;
    }
    std::memcpy(bytes.data() + bytes.size() - 8, &h, 8);
    return bytes;
}

} // namespace

TEST_CASE("a level without bodies continues bit-identically from its save", "[save]") {
    Level level = parseLevel(readLevel("dam_break.json"), "dam_break.json", builtins());
    REQUIRE(level.physics == nullptr);
    for (int f = 0; f < 30; ++f) {
        level.step();
    }
    const std::string bytes = saveOf(level);
    CHECK(saveOf(level) == bytes); // the same state, the same bytes

    Level restored = restore(bytes);
    CHECK(restored.file == "dam_break.json");
    CHECK(restored.name == level.name);
    CHECK(restored.world.time() == level.world.time());
    CHECK(restored.materials == level.materials);
    CHECK(restored.emitters == level.emitters);
    CHECK(restored.sensors == level.sensors);
    CHECK(saveOf(restored) == bytes);
    for (int f = 0; f < 60; ++f) {
        level.step();
        restored.step();
    }
    REQUIRE(state(restored.world).size() == state(level.world).size());
    CHECK(state(restored.world) == state(level.world));
}

TEST_CASE("the goal's state comes back with the level", "[save]") {
    Level level = parseLevel(readLevel("fill_the_cup.json"), "fill_the_cup.json", builtins());
    REQUIRE(level.goal.present);
    level.goal.timeLimit = 0.2; // lost after 0.2 s: a final state the save must keep
    for (int f = 0; f < 15; ++f) {
        level.step();
    }
    REQUIRE(level.goalState() == GoalState::Lost);
    Level restored = restore(saveOf(level));
    // The time limit comes from the file again (longer); the latched state is the save's.
    CHECK(restored.goal.timeLimit != 0.2);
    CHECK(restored.goalState() == GoalState::Lost);
}

TEST_CASE("crates.json saved at 10 s continues within 1 mm of the uninterrupted run",
          "[save][slow]") {
    Level level = parseLevel(readLevel("crates.json"), "crates.json", builtins());
    REQUIRE(level.physics != nullptr);
    const int framesTo10s = int(std::lround(10.0 * level.frameRate));
    for (int f = 0; f < framesTo10s; ++f) {
        level.step();
    }
    const std::string bytes = saveOf(level);
    Level restored = restore(bytes);
    REQUIRE(restored.bodies.size() == level.bodies.size());
    REQUIRE(restored.joints.size() == level.joints.size());
    for (std::size_t b = 0; b < level.bodies.size(); ++b) {
        CHECK(restored.bodies[b].first == level.bodies[b].first);
        const b2Body* x = level.bodies[b].second;
        const b2Body* y = restored.bodies[b].second;
        CHECK(y->GetPosition() == x->GetPosition());
        CHECK(y->GetAngle() == x->GetAngle());
        CHECK(y->GetLinearVelocity() == x->GetLinearVelocity());
        CHECK(y->GetAngularVelocity() == x->GetAngularVelocity());
        CHECK(y->IsAwake() == x->IsAwake());
        CHECK(y->GetMass() == x->GetMass());
    }
    CHECK(state(restored.world) == state(level.world));

    for (int f = 0; f < 60; ++f) {
        level.step();
        restored.step();
    }
    double worstBody = 0.0, worstCentre = 0.0;
    for (std::size_t b = 0; b < level.bodies.size(); ++b) {
        const b2Vec2 d =
            restored.bodies[b].second->GetPosition() - level.bodies[b].second->GetPosition();
        worstBody = std::max(worstBody, double(d.Length()));
    }
    const std::vector<glm::dvec2> a = centres(level.world), b = centres(restored.world);
    for (std::size_t m = 0; m < a.size(); ++m) {
        worstCentre = std::max(worstCentre, glm::length(a[m] - b[m]));
    }
    INFO("worst body " << worstBody << " m, worst centre of mass " << worstCentre << " m");
    CHECK(worstBody < 1e-3);
    CHECK(worstCentre < 1e-3);
    CHECK(restored.world.particleCount() == level.world.particleCount());
}

TEST_CASE("a level save keeps bodies the game added, and the coupling takes over its plugin",
          "[save]") {
    Level level = parseLevel(readLevel("paddle_wheel.json"), "paddle_wheel.json", builtins());
    REQUIRE(level.physics != nullptr);
    b2BodyDef def;
    def.type = b2_dynamicBody;
    def.position.Set(0.5f, 0.8f);
    def.angularVelocity = 2.0f;
    b2Body* crate = level.physics->CreateBody(&def);
    b2PolygonShape box;
    box.SetAsBox(0.04f, 0.03f);
    crate->CreateFixture(&box, 300.0f);
    for (int f = 0; f < 20; ++f) {
        level.step();
    }
    const std::size_t boundaries = level.world.boundaries().size();
    Level restored = restore(saveOf(level));
    CHECK(restored.physics->GetBodyCount() == level.physics->GetBodyCount());
    CHECK(restored.physics->GetJointCount() == level.physics->GetJointCount());
    // The snapshot's plugin is taken over, not doubled.
    CHECK(restored.world.boundaries().size() == boundaries);
    const b2Body* again = restored.physics->GetBodyList(); // the newest body is first
    CHECK(again->GetPosition() == crate->GetPosition());
    CHECK(again->GetAngularVelocity() == crate->GetAngularVelocity());
    CHECK(saveOf(restored) == saveOf(level));
    restored.step(); // and it steps
    CHECK(restored.world.particleCount() > 0);
}

TEST_CASE("bad level saves: clear errors, never a crash", "[save][bad-input]") {
    Level level = parseLevel(readLevel("paddle_wheel.json"), "paddle_wheel.json", builtins());
    for (int f = 0; f < 5; ++f) {
        level.step();
    }
    const std::string bytes = saveOf(level);
    CHECK(errorOfSave("") == "level save 's.sav': not a level save (no FLUIDLVL header)");
    CHECK(errorOfSave("FLUIDSNP and more") ==
          "level save 's.sav': not a level save (no FLUIDLVL header)");
    CHECK(errorOfSave(bytes.substr(0, 10)) == "level save 's.sav': truncated (10 bytes)");
    for (const std::size_t keep : {bytes.size() / 3, bytes.size() / 2, bytes.size() - 1}) {
        CHECK(errorOfSave(bytes.substr(0, keep)) ==
              "level save 's.sav': corrupt or truncated (checksum mismatch)");
    }
    std::string flipped = bytes;
    flipped[bytes.size() / 2] = char(flipped[bytes.size() / 2] ^ 0x10);
    CHECK(errorOfSave(flipped) == "level save 's.sav': corrupt or truncated (checksum mismatch)");
    std::string future = bytes;
    future[8] = 2;
    CHECK(errorOfSave(future) ==
          "level save 's.sav': format version 2 is not supported; this fluid reads version 1");

    // Altered and resealed: every part checks its own fields. Random single-byte changes must
    // load or throw fluid::Error, never crash (ASan runs this too).
    std::mt19937 random(7);
    int refused = 0;
    for (int trial = 0; trial < 300; ++trial) {
        std::string altered = bytes;
        const std::size_t at = 12 + random() % (altered.size() - 20);
        altered[at] = char(random());
        try {
            Level l = restore(resealed(altered));
            l.step();
        } catch (const Error&) {
            ++refused;
        }
    }
    CHECK(refused > 0);

    CHECK_THROWS_WITH(loadLevelSave("/nonexistent/x.sav", builtins()),
                      "loadLevelSave: cannot open '/nonexistent/x.sav'");
}

TEST_CASE("Box2D world saves keep order, fixtures and joints, and refuse bad ones",
          "[save][bad-input]") {
    b2World physics(b2Vec2(0.0f, -9.81f));
    b2BodyDef def;
    b2Body* ground = physics.CreateBody(&def);
    b2Vec2 chain[3] = {{0.0f, 0.0f}, {1.0f, 0.0f}, {1.0f, 1.0f}};
    b2ChainShape shape;
    shape.CreateChain(chain, 3, {-1.0f, 0.0f}, {1.0f, 2.0f});
    ground->CreateFixture(&shape, 0.0f);
    def.type = b2_dynamicBody;
    def.position.Set(0.3f, 0.5f);
    def.linearVelocity.Set(1.0f, -2.0f);
    b2Body* wheel = physics.CreateBody(&def);
    b2CircleShape disc;
    disc.m_radius = 0.1f;
    disc.m_p.Set(0.02f, 0.0f);
    wheel->CreateFixture(&disc, 2.0f);
    b2PolygonShape blade;
    blade.SetAsBox(0.2f, 0.01f, b2Vec2(0.1f, 0.0f), 0.3f);
    b2FixtureDef bladeDef;
    bladeDef.shape = &blade;
    bladeDef.density = 1.0f;
    bladeDef.isSensor = true;
    bladeDef.filter.categoryBits = 0x0004;
    wheel->CreateFixture(&bladeDef);
    b2RevoluteJointDef hinge;
    hinge.Initialize(ground, wheel, wheel->GetWorldCenter());
    hinge.enableMotor = true;
    hinge.motorSpeed = 3.0f;
    hinge.maxMotorTorque = 4.0f;
    physics.CreateJoint(&hinge);
    for (int k = 0; k < 10; ++k) {
        physics.Step(1.0f / 60.0f, 8, 3);
    }
    std::ostringstream out;
    box2d::savePhysics(physics, out);
    std::istringstream in(out.str());
    const std::unique_ptr<b2World> copy = box2d::loadPhysics(in);
    std::ostringstream again;
    box2d::savePhysics(*copy, again);
    CHECK(again.str() == out.str());
    // Stepped alike, both worlds stay close (Box2D's contacts and joint impulses restart).
    for (int k = 0; k < 30; ++k) {
        physics.Step(1.0f / 60.0f, 8, 3);
        copy->Step(1.0f / 60.0f, 8, 3);
    }
    const b2Body* w2 = copy->GetBodyList();
    CHECK((w2->GetPosition() - wheel->GetPosition()).Length() < 1e-3f);

    std::string bytes = out.str();
    const auto refuse = [](const std::string& b) {
        std::istringstream s(b);
        try {
            box2d::loadPhysics(s);
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    CHECK(refuse(bytes.substr(0, 20)) ==
          "box2d save: truncated (ended while reading world setting)");
    CHECK(refuse("not a save at all") == "box2d save: not a Box2D world save (bad magic)");
    std::string nan = bytes;
    const float bad = std::nanf("");
    std::memcpy(nan.data() + 12, &bad, sizeof(bad)); // gravity x
    CHECK(refuse(nan) == "box2d save: gravity = nan is not finite or out of [-1e+06, 1e+06]");

    // Single bytes changed at random: refused with an error, or a world that steps without
    // crashing (ASan runs this too).
    std::mt19937 random(11);
    int loaded = 0, refusedCount = 0;
    for (int trial = 0; trial < 400; ++trial) {
        std::string altered = bytes;
        altered[12 + random() % (altered.size() - 12)] = char(random());
        std::istringstream s(altered);
        try {
            const std::unique_ptr<b2World> w = box2d::loadPhysics(s);
            for (int k = 0; k < 5; ++k) {
                w->Step(1.0f / 60.0f, 8, 3);
            }
            ++loaded;
        } catch (const Error&) {
            ++refusedCount;
        }
    }
    CHECK(refusedCount > 0);
    CHECK(loaded > 0);

    b2World mouse(b2Vec2(0.0f, 0.0f));
    b2Body* a = mouse.CreateBody(&def);
    b2Body* b = mouse.CreateBody(&def);
    b2DistanceJointDef rope;
    rope.Initialize(a, b, a->GetPosition(), b->GetPosition() + b2Vec2(0.0f, 1.0f));
    mouse.CreateJoint(&rope);
    std::ostringstream refused;
    CHECK_THROWS_WITH(box2d::savePhysics(mouse, refused),
                      "fluid::box2d::savePhysics: joint type 3 (b2JointType) cannot be saved; "
                      "only revolute joints can");
}
