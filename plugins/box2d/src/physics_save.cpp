// fluid::box2d — saving and restoring a Box2D world (see physics_save.h).
#include <fluid/box2d/physics_save.h>

#include <fluid/box2d/coupling.h>

#include <fluid/internal/binary.h>

#include <box2d/box2d.h>

#include <cmath>
#include <cstring>
#include <sstream>
#include <unordered_map>
#include <vector>

namespace fluid::box2d {

namespace {

constexpr char kMagic[8] = {'F', 'L', 'B', '2', 'D', 'W', 'L', 'D'};
constexpr uint32_t kVersion = 1;
// Sanity limits for a save's counts (a corrupt count must not allocate gigabytes).
constexpr uint32_t kMaxBodies = 1u << 20;
constexpr uint32_t kMaxFixtures = 1u << 16;
constexpr uint32_t kMaxChain = 1u << 16;
constexpr uint32_t kMaxJoints = 1u << 20;
// The fewest bytes one saved body, fixture, chain vertex and joint take (unit: bytes): a count
// is checked against the bytes left before anything is sized by it.
constexpr uint32_t kBodyBytes = 62;
constexpr uint32_t kFixtureBytes = 36;
constexpr uint32_t kVertexBytes = 8;
constexpr uint32_t kJointBytes = 47;
// The largest coordinate a saved position or vertex may have (unit: m): fluid's own bound.
constexpr float kMaxCoordinate = 1e5f;
// Bounds that keep every product Box2D's step forms finite (a value past them turns a body NaN
// at its first step, silently). Box2D moves a body at most b2_maxTranslation per step whatever
// its velocity, so the speeds are far above anything a game sets (unit: m/s and rad/s).
constexpr float kMaxSpeed = 1e6f;
// The fluid's own bound on a body's mass (unit: kg; RigidBody::mass), and on a fixture's
// density (unit: kg/m^2).
constexpr float kMaxMass = 1e9f;
constexpr float kMaxDensity = 1e9f;
// The largest mass at the largest coordinate (unit: kg m^2).
constexpr float kMaxInertia = kMaxMass * kMaxCoordinate * kMaxCoordinate;
// Gravity scale (unit: 1), friction and restitution (unit: 1): the level format's bound on
// friction; gravity (at most 1e6 m/s^2) times the scale stays finite times any mass.
constexpr float kMaxFactor = 1e3f;
// A revolute joint's motor torque (unit: N m).
constexpr float kMaxTorque = 1e15f;

enum ShapeKind : uint8_t { kCircle, kEdge, kPolygon, kChain };

void putVec(internal::StreamWriter& w, b2Vec2 v) {
    w.put(v.x);
    w.put(v.y);
}

void putFixture(internal::StreamWriter& w, const b2Fixture& f) {
    const b2Shape* shape = f.GetShape();
    switch (shape->GetType()) {
    case b2Shape::e_circle: {
        const auto& c = static_cast<const b2CircleShape&>(*shape);
        w.put(uint8_t(kCircle));
        w.put(c.m_radius);
        putVec(w, c.m_p);
        break;
    }
    case b2Shape::e_edge: {
        const auto& e = static_cast<const b2EdgeShape&>(*shape);
        w.put(uint8_t(kEdge));
        w.put(e.m_radius);
        for (const b2Vec2& v : {e.m_vertex0, e.m_vertex1, e.m_vertex2, e.m_vertex3}) {
            putVec(w, v);
        }
        w.put(uint8_t(e.m_oneSided ? 1 : 0));
        break;
    }
    case b2Shape::e_polygon: {
        const auto& p = static_cast<const b2PolygonShape&>(*shape);
        w.put(uint8_t(kPolygon));
        w.put(p.m_radius);
        putVec(w, p.m_centroid);
        w.put(uint32_t(p.m_count));
        for (int32 k = 0; k < p.m_count; ++k) {
            putVec(w, p.m_vertices[k]);
            putVec(w, p.m_normals[k]);
        }
        break;
    }
    case b2Shape::e_chain: {
        const auto& c = static_cast<const b2ChainShape&>(*shape);
        w.put(uint8_t(kChain));
        w.put(uint32_t(c.m_count));
        for (int32 k = 0; k < c.m_count; ++k) {
            putVec(w, c.m_vertices[k]);
        }
        putVec(w, c.m_prevVertex);
        putVec(w, c.m_nextVertex);
        break;
    }
    default:
        throw Error("fluid::box2d::savePhysics: a fixture has an unknown shape type " +
                    std::to_string(int(shape->GetType())));
    }
    w.put(f.GetDensity());
    w.put(f.GetFriction());
    w.put(f.GetRestitution());
    w.put(f.GetRestitutionThreshold());
    w.put(uint8_t(f.IsSensor() ? 1 : 0));
    const b2Filter& filter = f.GetFilterData();
    w.put(filter.categoryBits);
    w.put(filter.maskBits);
    w.put(filter.groupIndex);
}

// Reads checked values: finite, in range.
struct In {
    internal::StreamReader r;
    float number(const char* field, float lo = -3e38f, float hi = 3e38f) {
        return r.number<float>(field, lo, hi);
    }
    b2Vec2 vec(const char* field, float bound = 3e38f) {
        const float x = number(field, -bound, bound);
        const float y = number(field, -bound, bound);
        return {x, y};
    }
    bool flag(const char* field) {
        const auto v = r.get<uint8_t>(field);
        if (v > 1) {
            r.fail(std::string(field) + " = " + std::to_string(v) + " is not 0 or 1");
        }
        return v != 0;
    }
};

// A fixture read back, before its body exists (`def.shape` is set when it is created: the
// struct moves).
struct FixtureRead {
    ShapeKind kind = kCircle;
    b2CircleShape circle;
    b2EdgeShape edge;
    b2PolygonShape polygon;
    std::vector<b2Vec2> chain;
    b2Vec2 prev{0.0f, 0.0f}, next{0.0f, 0.0f};
    b2FixtureDef def;
};

FixtureRead getFixture(In& in) {
    FixtureRead f;
    const auto kind = in.r.get<uint8_t>("shape type");
    switch (kind) {
    case kCircle:
        f.circle.m_radius = in.number("circle radius", 0.0f, kMaxCoordinate);
        f.circle.m_p = in.vec("circle centre", kMaxCoordinate);
        break;
    case kEdge:
        f.edge.m_radius = in.number("edge radius", 0.0f, kMaxCoordinate);
        f.edge.m_vertex0 = in.vec("edge vertex", kMaxCoordinate);
        f.edge.m_vertex1 = in.vec("edge vertex", kMaxCoordinate);
        f.edge.m_vertex2 = in.vec("edge vertex", kMaxCoordinate);
        f.edge.m_vertex3 = in.vec("edge vertex", kMaxCoordinate);
        f.edge.m_oneSided = in.flag("edge one-sided");
        break;
    case kPolygon: {
        f.polygon.m_radius = in.number("polygon radius", 0.0f, kMaxCoordinate);
        f.polygon.m_centroid = in.vec("polygon centroid", kMaxCoordinate);
        const auto count = in.r.get<uint32_t>("polygon vertex count");
        if (count < 3 || count > uint32_t(b2_maxPolygonVertices)) {
            in.r.fail("a polygon has " + std::to_string(count) + " vertices (3 to " +
                      std::to_string(b2_maxPolygonVertices) + ")");
        }
        f.polygon.m_count = int32(count);
        for (uint32_t k = 0; k < count; ++k) {
            f.polygon.m_vertices[k] = in.vec("polygon vertex", kMaxCoordinate);
            f.polygon.m_normals[k] = in.vec("polygon normal", 1.001f);
        }
        // Box2D needs a convex counter-clockwise polygon with some area whose normals face out
        // of its edges (b2PolygonShape::Set makes one); libbox2d asserts on the area, and a
        // polygon breaking the rest would give NaN contacts.
        float twiceArea = 0.0f;
        for (uint32_t k = 0; k < count; ++k) {
            twiceArea += b2Cross(f.polygon.m_vertices[k], f.polygon.m_vertices[(k + 1) % count]);
        }
        if (!(twiceArea > 2e-6f)) {
            in.r.fail("a polygon encloses no area");
        }
        for (uint32_t k = 0; k < count; ++k) {
            const b2Vec2 a = f.polygon.m_vertices[k];
            const b2Vec2 b = f.polygon.m_vertices[(k + 1) % count];
            const b2Vec2 c = f.polygon.m_vertices[(k + 2) % count];
            b2Vec2 normal = b2Cross(b - a, 1.0f);
            const bool edge = normal.Normalize() > b2_linearSlop;
            if (!edge || b2Cross(b - a, c - b) <= 0.0f ||
                (normal - f.polygon.m_normals[k]).Length() > 1e-3f) {
                in.r.fail("polygon edge " + std::to_string(k) +
                          " is degenerate, not convex counter-clockwise, or its normal does not "
                          "face out of it");
            }
        }
        break;
    }
    case kChain: {
        const uint32_t count = in.r.count("chain vertex count", kMaxChain, kVertexBytes);
        if (count < 2) {
            in.r.fail("a chain has " + std::to_string(count) + " vertices (at least 2)");
        }
        f.chain.resize(count);
        for (std::size_t k = 0; k < count; ++k) {
            f.chain[k] = in.vec("chain vertex", kMaxCoordinate);
            // Box2D's own rule for chains (b2ChainShape::CreateChain asserts it).
            if (k > 0 && b2DistanceSquared(f.chain[k - 1], f.chain[k]) <=
                             b2_linearSlop * b2_linearSlop) {
                in.r.fail("chain vertices " + std::to_string(k - 1) + " and " +
                          std::to_string(k) + " are closer than b2_linearSlop");
            }
        }
        f.prev = in.vec("chain previous vertex", kMaxCoordinate);
        f.next = in.vec("chain next vertex", kMaxCoordinate);
        break;
    }
    default:
        in.r.fail("unknown shape type " + std::to_string(kind));
    }
    f.kind = ShapeKind(kind);
    f.def.density = in.number("density", 0.0f, kMaxDensity);
    f.def.friction = in.number("friction", 0.0f, kMaxFactor);
    f.def.restitution = in.number("restitution", 0.0f, kMaxFactor);
    f.def.restitutionThreshold = in.number("restitution threshold", 0.0f);
    f.def.isSensor = in.flag("sensor");
    f.def.filter.categoryBits = in.r.get<uint16_t>("category bits");
    f.def.filter.maskBits = in.r.get<uint16_t>("mask bits");
    f.def.filter.groupIndex = in.r.get<int16_t>("group index");
    return f;
}

struct BodyRead {
    b2BodyDef def;
    bool enabled = true;
    b2MassData mass{};
    std::vector<FixtureRead> fixtures;
};

// Box2D recomputes a dynamic body's mass from its fixtures at each CreateFixture of a fixture
// with density (b2Body::ResetMassData, over the fixtures made so far: the loader makes them
// from the last to the first) and asserts that the rotational inertia about the centre of mass
// is positive. The same sums, in the same order and float arithmetic, refuse a body that would
// fail it (a small disc far from the body's origin, say) before anything is built.
void checkFixtureMass(In& in, const BodyRead& b) {
    if (b.def.type != b2_dynamicBody || b.def.fixedRotation) {
        return;
    }
    for (std::size_t made = b.fixtures.size(); made-- > 0;) {
        if (!(b.fixtures[made].def.density > 0.0f)) {
            continue; // CreateFixture resets the mass only for a fixture with density
        }
        float mass = 0.0f, inertia = 0.0f;
        b2Vec2 center(0.0f, 0.0f);
        for (std::size_t k = made; k < b.fixtures.size(); ++k) {
            const FixtureRead& f = b.fixtures[k];
            if (f.def.density == 0.0f || f.kind == kChain) {
                continue; // a chain has no mass
            }
            const b2Shape& shape = f.kind == kCircle ? static_cast<const b2Shape&>(f.circle)
                                   : f.kind == kEdge ? static_cast<const b2Shape&>(f.edge)
                                                     : static_cast<const b2Shape&>(f.polygon);
            b2MassData data;
            shape.ComputeMass(&data, f.def.density);
            mass += data.mass;
            center += data.mass * data.center;
            inertia += data.I;
        }
        if (mass > 0.0f) {
            center *= 1.0f / mass;
        }
        if (inertia > 0.0f && !(inertia - mass * b2Dot(center, center) > 0.0f)) {
            in.r.fail("a body's fixtures give it no positive rotational inertia about its "
                      "centre of mass");
        }
    }
}

struct JointRead {
    uint32_t bodyA = 0, bodyB = 0;
    b2RevoluteJointDef def;
};

} // namespace

void savePhysics(const b2World& physics, std::ostream& out) {
    internal::StreamWriter w(out);
    out.write(kMagic, sizeof(kMagic));
    w.put(kVersion);
    putVec(w, physics.GetGravity());
    w.put(uint8_t(physics.GetAllowSleeping() ? 1 : 0));
    w.put(uint8_t(physics.GetWarmStarting() ? 1 : 0));
    w.put(uint8_t(physics.GetContinuousPhysics() ? 1 : 0));
    w.put(uint8_t(physics.GetSubStepping() ? 1 : 0));
    w.put(uint8_t(physics.GetAutoClearForces() ? 1 : 0));

    std::unordered_map<const b2Body*, uint32_t> index; // lookup only
    w.put(uint32_t(physics.GetBodyCount()));
    for (const b2Body* b = physics.GetBodyList(); b != nullptr; b = b->GetNext()) {
        index.emplace(b, uint32_t(index.size()));
        w.put(uint8_t(b->GetType()));
        putVec(w, b->GetPosition());
        w.put(b->GetAngle());
        putVec(w, b->GetLinearVelocity());
        w.put(b->GetAngularVelocity());
        w.put(b->GetLinearDamping());
        w.put(b->GetAngularDamping());
        w.put(b->GetGravityScale());
        for (const bool flag : {b->IsAwake(), b->IsEnabled(), b->IsBullet(), b->IsFixedRotation(),
                                b->IsSleepingAllowed()}) {
            w.put(uint8_t(flag ? 1 : 0));
        }
        b2MassData mass;
        b->GetMassData(&mass);
        w.put(mass.mass);
        putVec(w, mass.center);
        w.put(mass.I);
        uint32_t fixtures = 0;
        for (const b2Fixture* f = b->GetFixtureList(); f != nullptr; f = f->GetNext()) {
            ++fixtures;
        }
        w.put(fixtures);
        for (const b2Fixture* f = b->GetFixtureList(); f != nullptr; f = f->GetNext()) {
            putFixture(w, *f);
        }
    }
    w.put(uint32_t(physics.GetJointCount()));
    for (const b2Joint* j = physics.GetJointList(); j != nullptr; j = j->GetNext()) {
        if (j->GetType() != e_revoluteJoint) {
            throw Error("fluid::box2d::savePhysics: joint type " + std::to_string(j->GetType()) +
                        " (b2JointType) cannot be saved; only revolute joints can");
        }
        const auto& r = static_cast<const b2RevoluteJoint&>(*j);
        // GetBodyA and GetBodyB are not const in Box2D 2.4; they only read.
        auto* joint = const_cast<b2Joint*>(j);
        w.put(index.at(joint->GetBodyA()));
        w.put(index.at(joint->GetBodyB()));
        putVec(w, r.GetLocalAnchorA());
        putVec(w, r.GetLocalAnchorB());
        w.put(r.GetReferenceAngle());
        for (const bool flag : {j->GetCollideConnected(), r.IsLimitEnabled(), r.IsMotorEnabled()}) {
            w.put(uint8_t(flag ? 1 : 0));
        }
        w.put(r.GetLowerLimit());
        w.put(r.GetUpperLimit());
        w.put(r.GetMotorSpeed());
        w.put(r.GetMaxMotorTorque());
    }
    if (!out) {
        throw Error("fluid::box2d::savePhysics: the stream failed while writing");
    }
}

std::unique_ptr<b2World> loadPhysics(std::istream& stream) {
    In in{internal::StreamReader(stream, "box2d save")};
    char magic[sizeof(kMagic)];
    if (!stream.read(magic, sizeof(magic)) || std::memcmp(magic, kMagic, sizeof(kMagic)) != 0) {
        in.r.fail("not a Box2D world save (bad magic)");
    }
    const auto version = in.r.get<uint32_t>("version");
    if (version != kVersion) {
        in.r.fail("version " + std::to_string(version) + " is not supported (this build reads " +
                  std::to_string(kVersion) + ")");
    }
    const b2Vec2 gravity = in.vec("gravity", 1e6f);
    bool settings[5];
    for (bool& s : settings) {
        s = in.flag("world setting");
    }

    std::vector<BodyRead> bodies(in.r.count("body count", kMaxBodies, kBodyBytes));
    for (BodyRead& b : bodies) {
        const auto type = in.r.get<uint8_t>("body type");
        if (type > uint8_t(b2_dynamicBody)) {
            in.r.fail("unknown body type " + std::to_string(type));
        }
        b.def.type = b2BodyType(type);
        b.def.position = in.vec("body position", kMaxCoordinate);
        b.def.angle = in.number("body angle");
        b.def.linearVelocity = in.vec("body velocity", kMaxSpeed);
        b.def.angularVelocity = in.number("body angular velocity", -kMaxSpeed, kMaxSpeed);
        b.def.linearDamping = in.number("linear damping", 0.0f);
        b.def.angularDamping = in.number("angular damping", 0.0f);
        b.def.gravityScale = in.number("gravity scale", -kMaxFactor, kMaxFactor);
        b.def.awake = in.flag("awake");
        b.enabled = in.flag("enabled");
        b.def.bullet = in.flag("bullet");
        b.def.fixedRotation = in.flag("fixed rotation");
        b.def.allowSleep = in.flag("sleep allowed");
        b.mass.mass = in.number("mass", 0.0f, kMaxMass);
        b.mass.center = in.vec("mass centre", kMaxCoordinate);
        b.mass.I = in.number("rotational inertia", 0.0f, kMaxInertia);
        // SetMassData keeps the mass and I - m |c|^2, the inertia about the centre of mass, and
        // Box2D divides by both: each at least its kMinBody... bound (the inertia positive and
        // bounded for a body that turns; a mass of 0 counts as 1 there).
        const float m = b.mass.mass > 0.0f ? b.mass.mass : 1.0f;
        const float centred = b.mass.I - m * b2Dot(b.mass.center, b.mass.center);
        const bool turns = b.mass.I > 0.0f && !b.def.fixedRotation;
        if (b.def.type == b2_dynamicBody && turns && !(centred > 0.0f)) {
            in.r.fail("a body's rotational inertia about its centre of mass is not positive");
        }
        const bool light = m < kMinBodyMass || (turns && centred < kMinBodyInertia);
        if (b.def.type == b2_dynamicBody && light) {
            std::ostringstream s;
            if (m < kMinBodyMass) {
                s << "a dynamic body's mass = " << m << " kg is less than kMinBodyMass ("
                  << kMinBodyMass << " kg)";
            } else {
                s << "a dynamic body's rotational inertia about its centre of mass = " << centred
                  << " kg m^2 is less than kMinBodyInertia (" << kMinBodyInertia << " kg m^2)";
            }
            in.r.fail(s.str());
        }
        b.fixtures.resize(in.r.count("fixture count", kMaxFixtures, kFixtureBytes));
        for (FixtureRead& f : b.fixtures) {
            f = getFixture(in);
        }
        checkFixtureMass(in, b);
    }
    std::vector<JointRead> joints(in.r.count("joint count", kMaxJoints, kJointBytes));
    for (JointRead& j : joints) {
        j.bodyA = in.r.get<uint32_t>("joint body A");
        j.bodyB = in.r.get<uint32_t>("joint body B");
        if (j.bodyA >= bodies.size() || j.bodyB >= bodies.size() || j.bodyA == j.bodyB) {
            in.r.fail("a joint connects bodies " + std::to_string(j.bodyA) + " and " +
                      std::to_string(j.bodyB) + " of " + std::to_string(bodies.size()));
        }
        j.def.localAnchorA = in.vec("joint anchor A", kMaxCoordinate);
        j.def.localAnchorB = in.vec("joint anchor B", kMaxCoordinate);
        j.def.referenceAngle = in.number("joint reference angle");
        j.def.collideConnected = in.flag("joint collide connected");
        j.def.enableLimit = in.flag("joint limit enabled");
        j.def.enableMotor = in.flag("joint motor enabled");
        j.def.lowerAngle = in.number("joint lower limit");
        j.def.upperAngle = in.number("joint upper limit");
        if (j.def.lowerAngle > j.def.upperAngle) {
            in.r.fail("a joint's lower limit is above its upper limit");
        }
        j.def.motorSpeed = in.number("joint motor speed", -kMaxSpeed, kMaxSpeed);
        j.def.maxMotorTorque = in.number("joint motor torque", 0.0f, kMaxTorque);
    }

    // Box2D puts each new body, fixture and joint at the head of its list: created from the last
    // to the first, they keep their saved order.
    auto physics = std::make_unique<b2World>(gravity);
    physics->SetAllowSleeping(settings[0]);
    physics->SetWarmStarting(settings[1]);
    physics->SetContinuousPhysics(settings[2]);
    physics->SetSubStepping(settings[3]);
    physics->SetAutoClearForces(settings[4]);
    std::vector<b2Body*> made(bodies.size(), nullptr);
    for (std::size_t k = bodies.size(); k-- > 0;) {
        BodyRead& b = bodies[k];
        b2BodyDef def = b.def;
        // Velocities and sleep go on last: adding fixtures moves the centre of mass (and a
        // spinning body's velocity with it), and setting a velocity wakes a body.
        def.linearVelocity.SetZero();
        def.angularVelocity = 0.0f;
        def.awake = true;
        b2Body* body = physics->CreateBody(&def);
        for (std::size_t f = b.fixtures.size(); f-- > 0;) {
            FixtureRead& fixture = b.fixtures[f];
            b2ChainShape chain;
            switch (fixture.kind) {
            case kCircle:
                fixture.def.shape = &fixture.circle;
                break;
            case kEdge:
                fixture.def.shape = &fixture.edge;
                break;
            case kPolygon:
                fixture.def.shape = &fixture.polygon;
                break;
            case kChain:
                chain.CreateChain(fixture.chain.data(), int32(fixture.chain.size()), fixture.prev,
                                  fixture.next);
                fixture.def.shape = &chain;
                break;
            }
            body->CreateFixture(&fixture.def);
        }
        if (b.def.type == b2_dynamicBody) {
            body->SetMassData(&b.mass);
        }
        body->SetLinearVelocity(b.def.linearVelocity);
        body->SetAngularVelocity(b.def.angularVelocity);
        body->SetAwake(b.def.awake);
        body->SetEnabled(b.enabled);
        made[k] = body;
    }
    for (std::size_t k = joints.size(); k-- > 0;) {
        JointRead& j = joints[k];
        j.def.bodyA = made[j.bodyA];
        j.def.bodyB = made[j.bodyB];
        physics->CreateJoint(&j.def);
    }
    return physics;
}

} // namespace fluid::box2d
