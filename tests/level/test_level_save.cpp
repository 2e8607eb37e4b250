// fluid tests — level saves (Level::save, readLevelSave): a level continues bit-identically,
// without bodies and with Box2D bodies (levels/crates.json; every level with bodies:
// test_level_save_exact.cpp); names, goal, bodies the game added and joints come back; bad or
// truncated saves get clear errors.
#include <catch2/catch.hpp>

#include "level_support.h"
#include "virtual_file.h"

#include <fluid/box2d/physics_save.h>
#include <fluid/level.h>

#include <box2d/box2d.h>

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
    for (const auto span :
         {world.positionX(), world.positionY(), world.velocityX(), world.velocityY()}) {
        out.insert(out.end(), span.begin(), span.end());
    }
    return out;
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

// Where the save's length-prefixed parts lie: the level file name, its text, the world and,
// with bodies, the Box2D world and the coupling (unit: bytes from the start).
struct Part {
    std::size_t at = 0, size = 0;
};

std::vector<Part> partsOf(const std::string& bytes) {
    std::vector<Part> parts;
    std::size_t at = 12; // magic, version
    const auto next = [&] {
        uint64_t n = 0;
        std::memcpy(&n, bytes.data() + at, sizeof(n));
        parts.push_back({at + 8, std::size_t(n)});
        at += 8 + std::size_t(n);
    };
    next();
    next();
    at += 4; // the goal state
    next();
    uint32_t physics = 0;
    std::memcpy(&physics, bytes.data() + at, sizeof(physics));
    at += 4;
    if (physics == 1) {
        next();
        next();
    }
    return parts;
}

// The save with part `k` (see partsOf) replaced by `content`, resealed.
std::string withPart(const std::string& bytes, std::size_t k, const std::string& content) {
    const Part part = partsOf(bytes)[k];
    const uint64_t n = content.size();
    std::string out = bytes.substr(0, part.at - 8);
    out.append(reinterpret_cast<const char*>(&n), sizeof(n));
    out += content;
    out += bytes.substr(part.at + part.size);
    return resealed(out);
}

// A small tank: water (and oil, a yoghurt, when `oil`), a box, and a sensor with a goal on it
// when `sensor`.
std::string tank(bool sensor, bool oil, bool waterFirst = true) {
    std::string materials = waterFirst ? R"({ "name": "water" })" : R"({ "name": "oil" })";
    if (oil) {
        materials += R"(, { "name": "oil", "preset": "yoghurt" })";
    }
    std::string text = R"({ "version": 1, "name": "tank", "world": { "gravity": [0, -9.81] },
        "materials": [ )" +
                       materials + R"( ],
        "plugins": [ { "type": "boundary.box", "name": "room",
                       "params": { "minX": 0, "minY": 0, "maxX": 1, "maxY": 1 } } ],
        "emitters": [ { "name": "tap", "material": ")" +
                       std::string(waterFirst ? "water" : "oil") + R"(", "position": [0.5, 0.8],
                        "direction": [0, -1], "speed": 1, "width": 0.03, "rate": 50 } ])";
    if (sensor) {
        text += R"(, "sensors": [ { "name": "cup", "shape": "box", "min": [0.4, 0.0],
                                   "max": [0.6, 0.2] } ],
                    "goal": { "sensor": "cup", "material": "water", "fraction": 0.8 })";
    }
    return text + "}";
}

// Whether every Box2D body of the level has a finite pose and velocity.
bool finiteBodies(const Level& level) {
    for (const b2Body* b = level.physics->GetBodyList(); b != nullptr; b = b->GetNext()) {
        const b2Vec2 p = b->GetPosition(), v = b->GetLinearVelocity();
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(b->GetAngle()) ||
            !std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(b->GetAngularVelocity())) {
            return false;
        }
    }
    return true;
}

// What loadPhysics says about `bytes`: its error, or "no error".
std::string physicsError(const std::string& bytes) {
    std::istringstream s(bytes);
    try {
        box2d::loadPhysics(s);
    } catch (const Error& e) {
        return std::string(e.what());
    }
    return std::string("no error");
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

TEST_CASE("crates.json saved at 10 s continues bit-identically", "[save][slow]") {
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
    CHECK(restored.physics->GetContactCount() == level.physics->GetContactCount());

    // A restored b2World holds its contacts with their warm-starting impulses, its broad phase
    // and its bodies' sweeps: 1 s on, nothing differs (before Box2D's solver state was saved,
    // the hull ended 1.01 mm off: docs/box2d.md, "Saving").
    for (int f = 0; f < 60; ++f) {
        level.step();
        restored.step();
    }
    for (std::size_t b = 0; b < level.bodies.size(); ++b) {
        const b2Body* x = level.bodies[b].second;
        const b2Body* y = restored.bodies[b].second;
        CHECK(y->GetPosition() == x->GetPosition());
        CHECK(y->GetAngle() == x->GetAngle());
        CHECK(y->GetLinearVelocity() == x->GetLinearVelocity());
        CHECK(y->GetAngularVelocity() == x->GetAngularVelocity());
    }
    CHECK(state(restored.world) == state(level.world));
    CHECK(saveOf(restored) == saveOf(level));
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
    // And it steps as the original does, the crate's contacts with the wheel and the hinge's
    // impulses included.
    for (int f = 0; f < 30; ++f) {
        level.step();
        restored.step();
    }
    CHECK(restored.world.particleCount() > 0);
    CHECK(again->GetPosition() == crate->GetPosition());
    CHECK(again->GetAngle() == crate->GetAngle());
    CHECK(saveOf(restored) == saveOf(level));
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
    b2PolygonShape slab;
    slab.SetAsBox(0.5f, 0.1f, b2Vec2(0.5f, -0.5f), 0.0f);
    ground->CreateFixture(&slab, 0.0f);
    def.type = b2_dynamicBody;
    // A crate that lands on the slab: contacts with warm-starting impulses.
    def.position.Set(0.5f, -0.2f);
    b2Body* crate = physics.CreateBody(&def);
    b2PolygonShape crateBox;
    crateBox.SetAsBox(0.05f, 0.05f, b2Vec2(0.0f, 0.0f), 0.2f);
    crate->CreateFixture(&crateBox, 1.0f);
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
    for (int k = 0; k < 20; ++k) {
        physics.Step(1.0f / 60.0f, 8, 3);
    }
    bool touching = false;
    for (const b2ContactEdge* e = crate->GetContactList(); e != nullptr; e = e->next) {
        touching = touching || e->contact->IsTouching();
    }
    REQUIRE(touching);
    std::ostringstream out;
    box2d::savePhysics(physics, out);
    std::istringstream in(out.str());
    const std::unique_ptr<b2World> copy = box2d::loadPhysics(in);
    std::ostringstream again;
    box2d::savePhysics(*copy, again);
    CHECK(again.str() == out.str());
    CHECK(copy->GetContactCount() == physics.GetContactCount());
    // Stepped alike, both worlds stay the same, bit for bit (contacts, joint impulses and the
    // broad phase are saved).
    for (int k = 0; k < 30; ++k) {
        physics.Step(1.0f / 60.0f, 8, 3);
        copy->Step(1.0f / 60.0f, 8, 3);
    }
    const b2Body* w2 = copy->GetBodyList();
    CHECK(w2->GetPosition() == wheel->GetPosition());
    CHECK(w2->GetAngle() == wheel->GetAngle());
    CHECK(w2->GetAngularVelocity() == wheel->GetAngularVelocity());
    const b2Body* c2 = w2->GetNext();
    CHECK(c2->GetPosition() == crate->GetPosition());
    CHECK(c2->GetAngle() == crate->GetAngle());
    std::ostringstream both[2];
    box2d::savePhysics(physics, both[0]);
    box2d::savePhysics(*copy, both[1]);
    CHECK(both[0].str() == both[1].str());

    std::string bytes = out.str();
    CHECK(physicsError(bytes.substr(0, 20)) ==
          "box2d save: truncated (ended while reading world setting)");
    CHECK(physicsError("not a save at all") == "box2d save: not a Box2D world save (bad magic)");
    std::string nan = bytes;
    const float bad = std::nanf("");
    std::memcpy(nan.data() + 12, &bad, sizeof(bad)); // gravity x
    CHECK(physicsError(nan) == "box2d save: gravity = nan is not finite or out of [-1e+06, 1e+06]");

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

TEST_CASE("a Box2D save continues bit-identically after the game destroyed and made bodies",
          "[save]") {
    // Box2D hands a destroyed body's broad-phase nodes to the next one made: proxy ids no
    // longer follow the body list, and the smaller id of a new pair is its contact's fixture A
    // (b2BroadPhase::UpdatePairs). The save keeps the tree node for node, so the crate that
    // lands on the other after the save makes the same contact, A and B as in the original.
    b2World physics(b2Vec2(0.0f, -9.81f));
    b2BodyDef def;
    b2PolygonShape slab;
    slab.SetAsBox(2.0f, 0.1f);
    physics.CreateBody(&def)->CreateFixture(&slab, 0.0f);
    b2PolygonShape box;
    box.SetAsBox(0.1f, 0.1f);
    def.type = b2_dynamicBody;
    def.position.Set(-0.5f, 0.5f);
    b2Body* gone = physics.CreateBody(&def);
    gone->CreateFixture(&box, 1.0f);
    def.position.Set(0.5f, 0.25f);
    physics.CreateBody(&def)->CreateFixture(&box, 1.0f);
    for (int k = 0; k < 5; ++k) {
        physics.Step(1.0f / 60.0f, 8, 3);
    }
    physics.DestroyBody(gone);
    def.position.Set(0.55f, 1.2f);
    def.angle = 0.3f;
    b2Body* falling = physics.CreateBody(&def);
    falling->CreateFixture(&box, 1.0f);
    for (int k = 0; k < 5; ++k) {
        physics.Step(1.0f / 60.0f, 8, 3);
    }
    REQUIRE(falling->GetContactList() == nullptr); // not near the other crate yet
    std::ostringstream out;
    box2d::savePhysics(physics, out);
    std::istringstream in(out.str());
    const std::unique_ptr<b2World> copy = box2d::loadPhysics(in);
    for (int k = 0; k < 90; ++k) {
        physics.Step(1.0f / 60.0f, 8, 3);
        copy->Step(1.0f / 60.0f, 8, 3);
    }
    REQUIRE(falling->GetContactList() != nullptr);
    const b2Body* again = copy->GetBodyList();
    CHECK(again->GetPosition() == falling->GetPosition());
    CHECK(again->GetAngle() == falling->GetAngle());
    std::ostringstream both[2];
    box2d::savePhysics(physics, both[0]);
    box2d::savePhysics(*copy, both[1]);
    CHECK(both[0].str() == both[1].str());
}

TEST_CASE("a coupling save with a huge finite impulse is refused, naming the body and field",
          "[save][bad-input]") {
    Level level = parseLevel(readLevel("paddle_wheel.json"), "paddle_wheel.json", builtins());
    for (int f = 0; f < 5; ++f) {
        level.step();
    }
    const std::string bytes = saveOf(level);
    const Part coupling = partsOf(bytes)[4];
    // The coupling's first body state: magic, version, count, then body index, wet flag,
    // material and the unpaid impulse (debt x, y: doubles).
    uint32_t states = 0, body = 0;
    std::memcpy(&states, bytes.data() + coupling.at + 12, sizeof(states));
    REQUIRE(states > 0);
    std::memcpy(&body, bytes.data() + coupling.at + 16, sizeof(body));
    std::string altered = bytes;
    const double huge = 5.28e237;
    std::memcpy(altered.data() + coupling.at + 23, &huge, sizeof(huge));
    CHECK_THROWS_MATCHES(restore(resealed(altered)), Error,
                         Catch::Message("level save 's.sav': the coupling: coupling save: body " +
                                        std::to_string(body) +
                                        " debt x = 5.28e+237 is not finite or out of [-1e+12, "
                                        "1e+12] (unit: N s)"));
}

TEST_CASE("mutated coupling sections are refused or step without NaN", "[save][bad-input]") {
    Level level = parseLevel(readLevel("paddle_wheel.json"), "paddle_wheel.json", builtins());
    for (int f = 0; f < 5; ++f) {
        level.step();
    }
    const std::string bytes = saveOf(level);
    const Part coupling = partsOf(bytes)[4];
    uint32_t states = 0;
    std::memcpy(&states, bytes.data() + coupling.at + 12, sizeof(states));
    REQUIRE(states > 0);
    // Each body state: u32 index, u8 wet, u16 material, 3 doubles (debt, torque debt), 3 floats
    // (applied force, torque). One value of one state set to a huge or tiny finite number.
    std::mt19937 random(31);
    int refused = 0, nonFinite = 0;
    for (int trial = 0; trial < 150; ++trial) {
        std::string altered = bytes;
        const std::size_t state = coupling.at + 16 + (random() % states) * 43;
        const std::size_t field = random() % 6;
        const double sign = random() % 2 == 0 ? 1.0 : -1.0;
        if (field < 3) {
            const double v = sign * std::pow(10.0, double(random() % 300));
            std::memcpy(altered.data() + state + 7 + field * 8, &v, sizeof(v));
        } else {
            const float v = float(sign * std::pow(10.0, double(random() % 38)));
            std::memcpy(altered.data() + state + 31 + (field - 3) * 4, &v, sizeof(v));
        }
        try {
            Level l = restore(resealed(altered));
            for (int f = 0; f < 5; ++f) {
                l.step();
            }
            nonFinite += finiteBodies(l) ? 0 : 1;
        } catch (const Error&) {
            ++refused;
        }
    }
    INFO(refused << " of 150 refused");
    CHECK(nonFinite == 0);
    CHECK(refused > 0);
}

TEST_CASE("a save whose world lacks a sensor its level file declares is refused",
          "[save][bad-input]") {
    Level plain = parseLevel(tank(false, false), "tank.json", builtins());
    plain.step();
    const std::string bytes = withPart(saveOf(plain), 1, tank(true, false));
    // Before, it loaded and failed at the first step: World::sensorReading: unknown sensor id 0.
    CHECK_THROWS_MATCHES(restore(bytes), Error,
                         Catch::Message("level save 's.sav': its level file declares sensor "
                                        "'cup' (0), but the world holds 0 sensors"));
}

TEST_CASE("a save's world must hold its level file's materials and plugins by name and type",
          "[save][bad-input]") {
    Level oil = parseLevel(tank(false, false, false), "tank.json", builtins());
    CHECK_THROWS_MATCHES(restore(withPart(saveOf(oil), 1, tank(false, false))), Error,
                         Catch::Message("level save 's.sav': its level file declares material "
                                        "'water' (0), but the world's material 0 is 'oil'"));
    std::string circle = tank(false, false);
    const std::string box = R"("type": "boundary.box", "name": "room",
                       "params": { "minX": 0, "minY": 0, "maxX": 1, "maxY": 1 })";
    REQUIRE(circle.find(box) != std::string::npos);
    circle.replace(circle.find(box), box.size(),
                   R"("type": "boundary.circle", "name": "room", "params": { "radius": 1 })");
    Level round = parseLevel(circle, "tank.json", builtins());
    CHECK_THROWS_MATCHES(
        restore(withPart(saveOf(round), 1, tank(false, false))), Error,
        Catch::Message("level save 's.sav': its level file declares boundary 'room' (0) of type "
                       "'boundary.box', but the world's boundary 0 is of type 'boundary.circle'"));
}

TEST_CASE("a material the game added to the world comes back named, with the file's", "[save]") {
    // The world holds water and oil; the level file declares water only (the game added oil,
    // as the demo adds its materials): oil is listed too, so tools (fluid-run's CSV) see it.
    Level both = parseLevel(tank(false, true), "tank.json", builtins());
    both.step();
    const Level restored = restore(withPart(saveOf(both), 1, tank(false, false)));
    REQUIRE(restored.materials.size() == 2);
    CHECK(restored.materials[0].first == "water");
    CHECK(restored.materials[0].second.index == 0);
    CHECK(restored.materials[1].first == "oil");
    CHECK(restored.materials[1].second.index == 1);
}

TEST_CASE("a huge level save of another version is refused from its header", "[save][bad-input]") {
    std::string head("FLUIDLVL", 8);
    const uint32_t version = 2;
    head.append(reinterpret_cast<const char*>(&version), sizeof(version));
    VirtualFile file(head, uint64_t(256) << 20); // 256 MiB of body that is never needed
    std::istream in(&file);
    CHECK_THROWS_MATCHES(
        readLevelSave(in, "big.level", builtins()), Error,
        Catch::Message("level save 'big.level': format version 2 is not supported; this fluid "
                       "reads version 1"));
    CHECK(file.served() <= 65536); // the first window only
}

TEST_CASE("errors of a save's level text name the save", "[save][bad-input]") {
    Level level = parseLevel(readLevel("fill_the_cup.json"), "fill_the_cup.json", builtins());
    const std::string bytes = saveOf(level);
    // A registry without boundary.box, which the level file uses.
    Registry lacking;
    for (const PluginInfo& info : builtins().types()) {
        if (info.type != "boundary.box") {
            lacking.add(info);
        }
    }
    std::string text;
    try {
        parseLevel(readLevel("fill_the_cup.json"), "fill_the_cup.json", lacking);
    } catch (const LevelError& e) {
        text = e.what();
    }
    REQUIRE(text.rfind("fill_the_cup.json:", 0) == 0);
    std::istringstream in(bytes);
    CHECK_THROWS_MATCHES(readLevelSave(in, "cup.level", lacking), Error,
                         Catch::Message("level save 'cup.level': the level file: " + text));
}

TEST_CASE("Box2D world saves refuse values that would turn a body NaN, and counts past the end",
          "[save][bad-input]") {
    b2World physics(b2Vec2(0.0f, -9.81f));
    b2BodyDef def;
    def.type = b2_dynamicBody;
    b2Body* body = physics.CreateBody(&def);
    b2CircleShape disc;
    disc.m_radius = 0.1f;
    body->CreateFixture(&disc, 2.0f);
    std::ostringstream out;
    box2d::savePhysics(physics, out);
    const std::string bytes = out.str();
    // Magic, version, gravity, 5 settings, the body count; then the body's type, position,
    // angle, velocity, angular velocity, damping (2), gravity scale.
    const std::size_t bodyAt = 8 + 4 + 8 + 5 + 4;
    std::string scaled = bytes;
    const float huge = 1e30f;
    std::memcpy(scaled.data() + bodyAt + 33, &huge, sizeof(huge));
    CHECK(physicsError(scaled) ==
          "box2d save: gravity scale = 1e+30 is not finite or out of [-1000, 1000]");
    std::string fast = bytes;
    std::memcpy(fast.data() + bodyAt + 13, &huge, sizeof(huge)); // velocity x
    CHECK(physicsError(fast) ==
          "box2d save: body velocity = 1e+30 is not finite or out of [-1e+06, "
          "1e+06]");
    // A mass or rotational inertia so small that Box2D's inverse overflows a float (a fuzzed
    // save's 4.7e-40 kg turned a body NaN at its first step): refused below kMinBodyMass and
    // kMinBodyInertia.
    std::string light = bytes;
    const float denormal = 4.7e-40f;
    std::memcpy(light.data() + bodyAt + 42, &denormal, sizeof(denormal)); // mass
    CHECK(physicsError(light) ==
          "box2d save: a dynamic body's mass = 4.7e-40 kg is less than kMinBodyMass (1e-06 kg)");
    std::string spinning = bytes;
    std::memcpy(spinning.data() + bodyAt + 54, &denormal, sizeof(denormal)); // inertia
    CHECK(physicsError(spinning) ==
          "box2d save: a dynamic body's rotational inertia about its centre of mass = 4.7e-40 kg "
          "m^2 is less than kMinBodyInertia (1e-12 kg m^2)");
    // The disc moved far from the body's origin: Box2D's CreateFixture would assert (the
    // inertia about the centre of mass cancels to 0 in float); the body's fixture follows its
    // mass data, count and the fixture kind and radius.
    std::string far = bytes;
    const b2Vec2 centre(1e4f, 1e4f);
    std::memcpy(far.data() + bodyAt + 62 + 5, &centre, sizeof(centre));
    CHECK(physicsError(far) ==
          "box2d save: a body's fixtures give it no positive rotational inertia "
          "about its centre of mass");
    std::string many = bytes;
    const uint32_t count = 1u << 20;
    std::memcpy(many.data() + bodyAt - 4, &count, sizeof(count));
    CHECK(physicsError(many) == "box2d save: body count = 1048576 needs at least 65011712 bytes; " +
                                    std::to_string(bytes.size() - bodyAt) + " remain");
}

TEST_CASE("Box2D saves check the solver state: impulses, contacts, the broad-phase tree",
          "[save][bad-input]") {
    // A box resting on a static slab: one contact of two points, a tree of two leaves under
    // one root.
    b2World physics(b2Vec2(0.0f, -9.81f));
    b2BodyDef def;
    b2Body* ground = physics.CreateBody(&def);
    b2PolygonShape slab;
    slab.SetAsBox(1.0f, 0.1f);
    ground->CreateFixture(&slab, 0.0f);
    def.type = b2_dynamicBody;
    def.position.Set(0.0f, 0.2f);
    b2Body* box = physics.CreateBody(&def);
    b2PolygonShape square;
    square.SetAsBox(0.1f, 0.1f);
    box->CreateFixture(&square, 1.0f);
    for (int k = 0; k < 30; ++k) {
        physics.Step(1.0f / 60.0f, 8, 3);
    }
    REQUIRE(physics.GetContactCount() == 1);
    REQUIRE(physics.GetContactList()->GetManifold()->pointCount == 2);
    std::ostringstream out;
    box2d::savePhysics(physics, out);
    const std::string bytes = out.str();
    REQUIRE(physicsError(bytes) == "no error");
    const auto at = [&](std::size_t offset, auto value) {
        std::string altered = bytes;
        std::memcpy(altered.data() + offset, &value, sizeof(value));
        return physicsError(altered);
    };
    const auto read = [&](std::size_t offset) {
        int32_t v = 0;
        std::memcpy(&v, bytes.data() + offset, sizeof(v));
        return v;
    };
    // The layout (physics_save.cpp): version 1's fields (header 25 bytes, 2 bodies of 62 bytes
    // with a 104-byte polygon each, the joint count), then the solver state: the inverse time
    // step and two flags, per body 44 bytes and per fixture a proxy count, id and box; the tree
    // (capacity, root, free list, insertions, then per node its height and 4 or 29 bytes); the
    // buffered moves; the contacts (indices, flags, mixing, TOI, manifold: 110 bytes with two
    // points).
    const std::size_t solver = 25 + 4 + 2 * (62 + 104) + 4;
    const std::size_t firstProxy = solver + 6 + 44 + 4;
    const std::size_t contact = bytes.size() - 110;
    const std::size_t tree = contact - 4 - 4 - (16 + 3 * 33 + 13 * 8);
    REQUIRE(read(tree) == 16);       // capacity
    REQUIRE(read(tree + 4) == 2);    // root: the leaves are nodes 0 and 1
    REQUIRE(read(tree + 8) == 3);    // the free list's head
    REQUIRE(read(contact - 8) == 0); // no buffered moves
    REQUIRE(read(contact - 4) == 1); // one contact
    REQUIRE(read(firstProxy) >= 0);
    REQUIRE(read(firstProxy) <= 1);

    const float nan = std::nanf("");
    CHECK(at(solver, nan) ==
          "box2d save: inverse time step = nan is not finite or out of [0, 1e+09]");
    const int32_t inner = 2;
    CHECK(at(firstProxy, inner) ==
          "box2d save: body 0 fixture 0 proxy 0 names tree node 2, not a leaf");
    // Body 0's centre of mass, a metre off.
    const b2Vec2 centre = box->GetWorldCenter() + b2Vec2(1.0f, 0.0f);
    std::ostringstream off;
    off << "box2d save: body 0 centre of mass (" << centre.x << ", " << centre.y
        << ") m is 1 m from where its position, angle and mass centre put it";
    CHECK(at(solver + 6, centre) == off.str());
    // The tree: a leaf that names another parent, a free list that loops.
    const int32_t other = 1;
    CHECK(at(tree + 16 + 4, other) ==
          "box2d save: tree node 0 is a child of node 2 but names another parent");
    const int32_t loop = 3;
    CHECK(at(tree + 16 + 3 * 33 + 4, loop) ==
          "box2d save: the broad-phase tree's free list reaches 3, not a free node, or twice");
    // The contact: both sides on one body, NaN and negative impulses, a touching flag without
    // points, a count past the end.
    const uint32_t bodyA = uint32_t(read(contact));
    CHECK(at(contact + 12, bodyA) ==
          "box2d save: contact 0 joins two fixtures of body " + std::to_string(bodyA));
    CHECK(at(contact + 70 + 8, nan) ==
          "box2d save: contact 0 normal impulse = nan is not finite or out of [0, 1e+15]");
    CHECK(at(contact + 70 + 8, -1.0f) ==
          "box2d save: contact 0 normal impulse = -1 is not finite or out of [0, 1e+15]");
    const uint32_t untouched = uint32_t(read(contact + 24)) & ~uint32_t(0x2);
    CHECK(at(contact + 24, untouched) ==
          "box2d save: contact 0 touching flag disagrees with its 2 manifold points");
    const uint32_t many = 1000;
    CHECK(at(contact - 4, many) == "box2d save: contact count = 1000 needs at least 53000 bytes; "
                                   "110 remain");
    const uint32_t future = 3;
    CHECK(at(8, future) == "box2d save: version 3 is not supported (this build reads 1 and 2)");

    // A version-1 save (no solver state) still loads: its world makes its contacts anew.
    std::string old = bytes.substr(0, solver);
    const uint32_t one = 1;
    std::memcpy(old.data() + 8, &one, sizeof(one));
    std::istringstream in(old);
    const std::unique_ptr<b2World> copy = box2d::loadPhysics(in);
    CHECK(copy->GetContactCount() == 0);
    copy->Step(1.0f / 60.0f, 8, 3);
    CHECK(copy->GetContactCount() == 1);
}

TEST_CASE("a level save whose fixture a level file could not declare is refused on load",
          "[save][bad-input]") {
    // The wheel's hub (radius 0.03 m) set to 2.3e-38 m in the Box2D part, the checksum made
    // right again. Before, the save loaded and every step failed in the coupling (the disc is
    // below boundary.circle's 1e-4 m); a level file's circle needs Box2D's linear slop.
    Level level = parseLevel(readLevel("paddle_wheel.json"), "paddle_wheel.json", builtins());
    level.step();
    const std::string bytes = saveOf(level);
    const Part physics = partsOf(bytes)[3];
    const float hub = 0.03f, tiny = 2.3e-38f;
    std::vector<std::size_t> found;
    for (std::size_t k = physics.at; k + sizeof(hub) <= physics.at + physics.size; ++k) {
        if (std::memcmp(bytes.data() + k, &hub, sizeof(hub)) == 0) {
            found.push_back(k);
        }
    }
    REQUIRE(found.size() == 1);
    std::string altered = bytes;
    std::memcpy(altered.data() + found[0], &tiny, sizeof(tiny));
    CHECK(errorOfSave(resealed(altered)) ==
          "level save 's.sav': the Box2D world: box2d save: body 0 fixture 6 circle radius = "
          "2.3e-38 is not finite or out of [0.005, 10000] (unit: m)");
}

TEST_CASE("Box2D saves hold fixtures to a level file's rules: sizes, local coordinates, chains",
          "[save][bad-input]") {
    const auto saveWith = [](const b2Shape& shape) {
        b2World physics(b2Vec2(0.0f, -9.81f));
        b2BodyDef def;
        physics.CreateBody(&def)->CreateFixture(&shape, 0.0f);
        std::ostringstream out;
        box2d::savePhysics(physics, out);
        return out.str();
    };
    b2EdgeShape stub;
    stub.SetTwoSided(b2Vec2(0.0f, 0.0f), b2Vec2(0.0f, 0.00390625f)); // 2^-8 m
    CHECK(physicsError(saveWith(stub)) == "box2d save: body 0 fixture 0 edge is 0.00390625 m "
                                          "long; expected more than 0.005 m (Box2D's linear slop)");
    // A sliver Box2D makes (its corners far apart) of 1.5e-5 m^2.
    const b2Vec2 sliver[3] = {{0.0f, 0.0f}, {0.125f, 0.0f}, {0.0625f, 0.000244140625f}};
    b2PolygonShape thin;
    thin.Set(sliver, 3);
    CHECK(physicsError(saveWith(thin)) ==
          "box2d save: body 0 fixture 0 polygon: the polygon's area is 1.5258789e-05 m^2; "
          "expected at least 2.5e-05 m^2 (Box2D's linear slop squared)");
    b2CircleShape far;
    far.m_radius = 0.5f;
    far.m_p.Set(2e4f, 0.0f);
    CHECK(physicsError(saveWith(far)) ==
          "box2d save: body 0 fixture 0 circle centre = 20000 is not finite or out of [-10000, "
          "10000]");
    // 4097 points: the coupling refuses more than 4096 at every step.
    std::vector<b2Vec2> points;
    for (int k = 0; k < 4097; ++k) {
        points.emplace_back(0.01f * float(k), 0.0f);
    }
    b2ChainShape longChain;
    longChain.CreateChain(points.data(), int32(points.size()), b2Vec2(-0.01f, 0.0f),
                          b2Vec2(41.0f, 0.0f));
    CHECK(
        physicsError(saveWith(longChain)) ==
        "box2d save: body 0 fixture 0 chain has 4097 points; at most 4096 (the coupling's limit)");
    points.pop_back();
    b2ChainShape loop; // 4096 points and the repeated first
    loop.CreateLoop(points.data(), int32(points.size()));
    CHECK(physicsError(saveWith(loop)) == "no error");
}
