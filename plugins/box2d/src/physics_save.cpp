// fluid::box2d — saving and restoring a Box2D world (see physics_save.h).
#include <fluid/box2d/physics_save.h>
#include <fluid/box2d/shapes.h>

#include <fluid/box2d/coupling.h>

#include <fluid/internal/binary.h>

#include "box2d_internals.h"
#include "solver_state.h"

#include <box2d/box2d.h>

#include <cmath>
#include <cstring>
#include <set>
#include <sstream>
#include <tuple>
#include <unordered_map>
#include <vector>

namespace fluid::box2d {

namespace {

constexpr char kMagic[8] = {'F', 'L', 'B', '2', 'D', 'W', 'L', 'D'};
// Version 2 adds the solver state (solver state below); version 1 saves still load.
constexpr uint32_t kVersion = 2;
// Sanity limits for a save's counts (a corrupt count must not allocate gigabytes).
constexpr uint32_t kMaxBodies = 1u << 20;
constexpr uint32_t kMaxFixtures = 1u << 16;
// A chain's vertices: 4096 points, and the repeated first one of a loop.
constexpr uint32_t kMaxChain = 4097;
constexpr uint32_t kMaxJoints = 1u << 20;
// The fewest bytes one saved body, fixture, chain vertex and joint take (unit: bytes): a count
// is checked against the bytes left before anything is sized by it.
constexpr uint32_t kBodyBytes = 62;
constexpr uint32_t kFixtureBytes = 36;
constexpr uint32_t kVertexBytes = 8;
constexpr uint32_t kJointBytes = 47;
// The largest coordinate a saved position may have (unit: m): fluid's own bound.
constexpr float kMaxCoordinate = 1e5f;
// A level file's bounds on fixtures (level/src/bodies.cpp): body-local coordinates (unit: m;
// Box2D stores them in float, and a shape far from its body's origin loses its size to
// rounding), the smallest size, Box2D's linear slop, and the largest (unit: m), a chain's points
// (the coupling refuses longer chains at every step).
constexpr float kMaxLocal = 1e4f;
constexpr float kMinSize = b2_linearSlop;
constexpr float kMaxSize = 1e4f;
constexpr uint32_t kMaxChainPoints = 4096;
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
// The solver state's bounds: an impulse is at most the largest mass at the largest speed (unit:
// N s), an angular impulse that at the largest lever (unit: N m s); a force accumulated between
// steps the largest mass at the largest gravity (unit: N), its torque at the largest lever
// (unit: N m). A broad-phase box reaches a little past the largest coordinate (fat margins,
// swept motion; unit: m).
constexpr float kMaxImpulse = kMaxMass * kMaxSpeed;
constexpr float kMaxAngularImpulse = kMaxImpulse * kMaxCoordinate;
constexpr float kMaxForce = kMaxMass * 1e6f;
constexpr float kMaxAppliedTorque = kMaxForce * kMaxCoordinate;
constexpr float kMaxBox = 4.0f * kMaxCoordinate;
// Counts of the solver state: tree nodes, buffered moves, contacts.
constexpr uint32_t kMaxTreeNodes = 1u << 20;
constexpr uint32_t kMaxMoves = 1u << 20;
constexpr uint32_t kMaxContacts = 1u << 20;
// The fewest bytes one tree node, move and contact take (unit: bytes).
constexpr uint32_t kNodeBytes = 8;
constexpr uint32_t kMoveBytes = 4;
constexpr uint32_t kContactBytes = 53;

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
                        std::to_string(int(shape->GetType())),
                    ErrorCode::BadArgument);
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
    float number(const std::string& field, float lo = -3e38f, float hi = 3e38f,
                 const char* unit = nullptr) {
        return r.number<float>(field, lo, hi, unit);
    }
    b2Vec2 vec(const std::string& field, float bound = 3e38f) {
        const float x = number(field, -bound, bound);
        const float y = number(field, -bound, bound);
        return {x, y};
    }
    bool flag(const std::string& field) {
        const auto v = r.get<uint8_t>(field.c_str());
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

// A fixture as the save holds it, through the checks a level file's fixture passes
// (level/src/bodies.cpp, docs/levels.md "Bodies"): body-local coordinates within 1e4 m; a
// circle's radius from Box2D's linear slop (0.005 m) to 1e4 m; a polygon as box2d::checkPolygon
// takes it (shapes.h: vertices at least the slop apart, its area at least the slop squared,
// strictly convex and simple); an edge longer than the slop; a chain of at
// most 4096 points whose links are longer than the slop. Box2D asserts on some of these and
// collides thinner shapes unreliably; the coupling refuses a disc under 1e-4 m, a chain over 4096
// points or a repeated point at every step, so a save holding one loaded and then failed every
// step. `of` names the fixture ("body 0 fixture 6 ").
FixtureRead getFixture(In& in, const std::string& of) {
    FixtureRead f;
    const auto kind = in.r.get<uint8_t>("shape type");
    switch (kind) {
    case kCircle:
        f.circle.m_radius = in.number(of + "circle radius", kMinSize, kMaxSize, "m");
        f.circle.m_p = in.vec(of + "circle centre", kMaxLocal);
        break;
    case kEdge: {
        f.edge.m_radius = in.number(of + "edge radius", 0.0f, kMaxSize);
        f.edge.m_vertex0 = in.vec(of + "edge vertex", kMaxLocal);
        f.edge.m_vertex1 = in.vec(of + "edge vertex", kMaxLocal);
        f.edge.m_vertex2 = in.vec(of + "edge vertex", kMaxLocal);
        f.edge.m_vertex3 = in.vec(of + "edge vertex", kMaxLocal);
        f.edge.m_oneSided = in.flag(of + "edge one-sided");
        // The level loader's test, in float as Box2D computes it.
        if (!(b2DistanceSquared(f.edge.m_vertex1, f.edge.m_vertex2) > kMinSize * kMinSize)) {
            std::ostringstream m;
            m << of << "edge is " << b2Distance(f.edge.m_vertex1, f.edge.m_vertex2)
              << " m long; expected more than 0.005 m (Box2D's linear slop)";
            in.r.fail(m.str());
        }
        break;
    }
    case kPolygon: {
        f.polygon.m_radius = in.number(of + "polygon radius", 0.0f, kMaxSize);
        f.polygon.m_centroid = in.vec(of + "polygon centroid", kMaxLocal);
        const auto count = in.r.get<uint32_t>("polygon vertex count");
        if (count < 3 || count > uint32_t(b2_maxPolygonVertices)) {
            in.r.fail(of + "polygon has " + std::to_string(count) + " vertices (3 to " +
                      std::to_string(b2_maxPolygonVertices) + ")");
        }
        f.polygon.m_count = int32(count);
        for (uint32_t k = 0; k < count; ++k) {
            f.polygon.m_vertices[k] = in.vec(of + "polygon vertex", kMaxLocal);
            f.polygon.m_normals[k] = in.vec(of + "polygon normal", 1.001f);
        }
        // The checks a level file's polygon passes (shapes.h: vertices at least the slop
        // apart, an area of at least its square, strictly convex and simple), then Box2D's own
        // form: counter-clockwise, with its edges' outward normals.
        std::vector<glm::vec2> outline;
        for (uint32_t k = 0; k < count; ++k) {
            outline.emplace_back(f.polygon.m_vertices[k].x, f.polygon.m_vertices[k].y);
        }
        if (const ShapeProblem problem = checkPolygon(outline, 0.0f)) {
            in.r.fail(of + "polygon: " + problem.message);
        }
        for (uint32_t k = 0; k < count; ++k) {
            const b2Vec2 a = f.polygon.m_vertices[k];
            const b2Vec2 b = f.polygon.m_vertices[(k + 1) % count];
            const b2Vec2 c = f.polygon.m_vertices[(k + 2) % count];
            b2Vec2 normal = b2Cross(b - a, 1.0f);
            const bool edge = normal.Normalize() > b2_linearSlop;
            if (!edge || b2Cross(b - a, c - b) <= 0.0f ||
                (normal - f.polygon.m_normals[k]).Length() > 1e-3f) {
                in.r.fail(of + "polygon edge " + std::to_string(k) +
                          " is degenerate, not convex counter-clockwise, or its normal does not "
                          "face out of it");
            }
        }
        break;
    }
    case kChain: {
        const uint32_t count = in.r.count("chain vertex count", kMaxChain, kVertexBytes);
        if (count < 2) {
            in.r.fail(of + "chain has " + std::to_string(count) + " vertices (at least 2)");
        }
        f.chain.resize(count);
        for (std::size_t k = 0; k < count; ++k) {
            f.chain[k] = in.vec(of + "chain vertex", kMaxLocal);
            // Box2D's own rule for chains (b2ChainShape::CreateChain asserts it).
            if (k > 0 &&
                b2DistanceSquared(f.chain[k - 1], f.chain[k]) <= b2_linearSlop * b2_linearSlop) {
                in.r.fail(of + "chain vertices " + std::to_string(k - 1) + " and " +
                          std::to_string(k) + " are closer than b2_linearSlop");
            }
        }
        // A loop (b2ChainShape::CreateLoop) repeats its first point at the end.
        const bool loop = count >= 4 && f.chain.front() == f.chain.back();
        const uint32_t points = loop ? count - 1 : count;
        if (points > kMaxChainPoints) {
            in.r.fail(of + "chain has " + std::to_string(points) + " points; at most " +
                      std::to_string(kMaxChainPoints) + " (the coupling's limit)");
        }
        f.prev = in.vec(of + "chain previous vertex", kMaxLocal);
        f.next = in.vec(of + "chain next vertex", kMaxLocal);
        break;
    }
    default:
        in.r.fail(of + "unknown shape type " + std::to_string(kind));
    }
    f.kind = ShapeKind(kind);
    f.def.density = in.number(of + "density", 0.0f, kMaxDensity);
    f.def.friction = in.number(of + "friction", 0.0f, kMaxFactor);
    f.def.restitution = in.number(of + "restitution", 0.0f, kMaxFactor);
    f.def.restitutionThreshold = in.number(of + "restitution threshold", 0.0f);
    f.def.isSensor = in.flag(of + "sensor");
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

// ---- the solver state (version 2) ---------------------------------------------------------
// What Box2D 2.4.1's next Step reads besides the bodies, fixtures and joints above, kept in
// private members (box2d_internals.h): the world's last inverse time step (warm starting scales
// every stored impulse by dt / dt0, 0 in a new world) and its flags; each body's sweep (centre
// of mass now and at the step's start: a body's position and angle do not round-trip its centre
// exactly), inertia about the centre of mass (GetMassData / SetMassData do not round-trip it),
// accumulated force and sleep timer; each fixture's broad-phase proxies; revolute joints'
// impulses; the broad phase's dynamic tree node for node (its fat boxes decide when contacts
// begin and end, its node ids which fixture of a new contact is A, its shape the order pairs
// are found in) and move buffer; every contact in the world's list order (which fixes the
// order of each body's contact edges, hence the island and constraint order) with its flags,
// friction and restitution mixing, tangent speed, TOI state and manifold (points, feature ids,
// normal and tangent impulses).

void putBox(internal::StreamWriter& w, const b2AABB& box) {
    putVec(w, box.lowerBound);
    putVec(w, box.upperBound);
}

void putSolverState(internal::StreamWriter& w, const b2World& physics) {
    using namespace detail;
    w.put(field<WorldInvDt0>(physics));
    w.put(uint8_t(field<WorldNewContacts>(physics) ? 1 : 0));
    w.put(uint8_t(field<WorldStepComplete>(physics) ? 1 : 0));
    struct Where {
        uint32_t body = 0, fixture = 0;
    };
    std::unordered_map<const b2Fixture*, Where> where; // lookup only
    uint32_t bodyIndex = 0;
    for (const b2Body* b = physics.GetBodyList(); b != nullptr; b = b->GetNext(), ++bodyIndex) {
        const b2Sweep& sweep = field<BodySweep>(*b);
        putVec(w, sweep.c);
        putVec(w, sweep.c0);
        w.put(sweep.a0);
        w.put(sweep.alpha0);
        w.put(field<BodyInertia>(*b));
        putVec(w, field<BodyForce>(*b));
        w.put(field<BodyTorque>(*b));
        w.put(field<BodySleepTime>(*b));
        uint32_t fixtureIndex = 0;
        for (const b2Fixture* f = b->GetFixtureList(); f != nullptr;
             f = f->GetNext(), ++fixtureIndex) {
            where.emplace(f, Where{bodyIndex, fixtureIndex});
            const int32 proxies = field<FixtureProxyCount>(*f);
            w.put(uint32_t(proxies));
            for (int32 k = 0; k < proxies; ++k) {
                const b2FixtureProxy& proxy = field<FixtureProxies>(*f)[k];
                w.put(proxy.proxyId);
                putBox(w, proxy.aabb);
            }
        }
    }
    for (const b2Joint* j = physics.GetJointList(); j != nullptr; j = j->GetNext()) {
        const auto& r = static_cast<const b2RevoluteJoint&>(*j); // savePhysics checked the type
        putVec(w, field<RevoluteImpulse>(r));
        w.put(field<RevoluteMotorImpulse>(r));
        w.put(field<RevoluteLowerImpulse>(r));
        w.put(field<RevoluteUpperImpulse>(r));
    }
    const b2ContactManager& manager = field<WorldContacts>(physics);
    const b2BroadPhase& phase = manager.m_broadPhase;
    const b2DynamicTree& tree = field<PhaseTree>(phase);
    const int32 capacity = field<TreeNodeCapacity>(tree);
    w.put(uint32_t(capacity));
    w.put(field<TreeRoot>(tree));
    w.put(field<TreeFreeList>(tree));
    w.put(field<TreeInsertions>(tree));
    const b2TreeNode* nodes = field<TreeNodes>(tree);
    for (int32 k = 0; k < capacity; ++k) {
        const b2TreeNode& n = nodes[k];
        w.put(n.height);
        if (n.height < 0) {
            w.put(n.next);
        } else {
            w.put(n.parent);
            w.put(n.child1);
            w.put(n.child2);
            w.put(uint8_t(n.moved ? 1 : 0));
            putBox(w, n.aabb);
        }
    }
    const int32 moves = field<PhaseMoveCount>(phase);
    w.put(uint32_t(moves));
    for (int32 k = 0; k < moves; ++k) {
        w.put(field<PhaseMoveBuffer>(phase)[k]);
    }
    w.put(uint32_t(manager.m_contactCount));
    for (const b2Contact* c = physics.GetContactList(); c != nullptr; c = c->GetNext()) {
        for (const auto& [f, child] : {std::pair(c->GetFixtureA(), c->GetChildIndexA()),
                                       std::pair(c->GetFixtureB(), c->GetChildIndexB())}) {
            const Where at = where.at(f);
            w.put(at.body);
            w.put(at.fixture);
            w.put(uint32_t(child));
        }
        w.put(field<ContactFlags>(*c));
        w.put(c->GetFriction());
        w.put(c->GetRestitution());
        w.put(c->GetRestitutionThreshold());
        w.put(c->GetTangentSpeed());
        w.put(field<ContactToiCount>(*c));
        w.put(field<ContactToi>(*c));
        // A manifold without points holds nothing else: Box2D leaves its type, normal and point
        // as they were (uninitialised in a contact that never touched) and reads none of them.
        const b2Manifold& m = *c->GetManifold();
        w.put(uint8_t(m.pointCount));
        if (m.pointCount == 0) {
            continue;
        }
        w.put(uint8_t(m.type));
        putVec(w, m.localNormal);
        putVec(w, m.localPoint);
        for (int32 k = 0; k < m.pointCount; ++k) {
            const b2ManifoldPoint& p = m.points[k];
            putVec(w, p.localPoint);
            w.put(p.normalImpulse);
            w.put(p.tangentImpulse);
            w.put(p.id.key);
        }
    }
}

struct ProxyRead {
    int32 id = 0;
    b2AABB box{};
};

struct BodyState {
    b2Vec2 c{0.0f, 0.0f}, c0{0.0f, 0.0f};
    float a0 = 0.0f, alpha0 = 0.0f, inertia = 0.0f;
    b2Vec2 force{0.0f, 0.0f};
    float torque = 0.0f, sleep = 0.0f;
    std::vector<std::vector<ProxyRead>> proxies; // per fixture, per child
};

struct JointState {
    b2Vec2 impulse{0.0f, 0.0f};
    float motor = 0.0f, lower = 0.0f, upper = 0.0f;
};

struct NodeRead {
    int32 height = -1;
    int32 link = -1; // the parent of a node in the tree, the next free node of a free one
    int32 child1 = -1, child2 = -1;
    bool moved = false;
    b2AABB box{};
};

struct ContactRead {
    uint32_t body[2] = {0, 0}, fixture[2] = {0, 0}, child[2] = {0, 0};
    uint32_t flags = 0;
    float friction = 0.0f, restitution = 0.0f, threshold = 0.0f, tangentSpeed = 0.0f;
    int32 toiCount = 0;
    float toi = 0.0f;
    b2Manifold manifold{};
};

struct SolverState {
    float invDt0 = 0.0f;
    bool newContacts = false, stepComplete = true;
    std::vector<BodyState> bodies;
    std::vector<JointState> joints;
    int32 root = -1, freeList = -1, insertions = 0;
    std::vector<NodeRead> nodes;
    std::vector<int32> moves;
    std::vector<ContactRead> contacts;
};

// A fixture's children (a chain's links; one for every other shape).
uint32_t childCount(const FixtureRead& f) {
    return f.kind == kChain ? uint32_t(f.chain.size() - 1) : 1u;
}

b2AABB getBox(In& in, const std::string& field) {
    b2AABB box;
    box.lowerBound = in.vec(field + " lower corner", kMaxBox);
    box.upperBound = in.vec(field + " upper corner", kMaxBox);
    if (!(box.lowerBound.x <= box.upperBound.x && box.lowerBound.y <= box.upperBound.y)) {
        in.r.fail(field + " has its lower corner above its upper one");
    }
    return box;
}

std::string str(uint64_t k) {
    return std::to_string(k);
}

// Reads the solver state, each value checked on its own; checkSolverState checks how they fit
// together once the world is built.
SolverState getSolverState(In& in, const std::vector<BodyRead>& bodies, std::size_t joints) {
    SolverState s;
    s.invDt0 = in.number("inverse time step", 0.0f, 1e9f);
    s.newContacts = in.flag("new contacts flag");
    s.stepComplete = in.flag("step complete flag");
    s.bodies.resize(bodies.size());
    for (std::size_t k = 0; k < bodies.size(); ++k) {
        const BodyRead& b = bodies[k];
        BodyState& st = s.bodies[k];
        const std::string of = "body " + str(k) + " ";
        st.c = in.vec(of + "centre of mass", 2.0f * kMaxCoordinate);
        st.c0 = in.vec(of + "centre of mass at the step's start", 2.0f * kMaxCoordinate);
        st.a0 = in.number(of + "angle at the step's start");
        st.alpha0 = in.number(of + "sweep fraction", 0.0f, 1.0f);
        if (!(st.alpha0 < 1.0f)) {
            in.r.fail(of + "sweep fraction = 1 is not below 1");
        }
        st.inertia =
            in.number(of + "rotational inertia about its centre of mass", 0.0f, kMaxInertia);
        // GetMassData gave the inertia about the body's origin as Box2D computes it.
        if (st.inertia + b.mass.mass * b2Dot(b.mass.center, b.mass.center) != b.mass.I) {
            std::ostringstream m;
            m << of << "rotational inertia about its centre of mass = " << st.inertia
              << " kg m^2 does not give its inertia about its origin (" << b.mass.I << " kg m^2)";
            in.r.fail(m.str());
        }
        const bool turns = b.def.type == b2_dynamicBody && !b.def.fixedRotation;
        if (st.inertia > 0.0f && !turns) {
            in.r.fail(of + "does not turn (static, kinematic or fixed rotation) but has a "
                           "rotational inertia about its centre of mass");
        }
        if (st.inertia > 0.0f && st.inertia < kMinBodyInertia) {
            std::ostringstream m;
            m << of << "rotational inertia about its centre of mass = " << st.inertia
              << " kg m^2 is less than kMinBodyInertia (" << kMinBodyInertia << " kg m^2)";
            in.r.fail(m.str());
        }
        st.force = in.vec(of + "force", kMaxForce);
        st.torque = in.number(of + "torque", -kMaxAppliedTorque, kMaxAppliedTorque);
        st.sleep = in.number(of + "sleep time", 0.0f, 1e9f);
        st.proxies.resize(b.fixtures.size());
        for (std::size_t f = 0; f < b.fixtures.size(); ++f) {
            const auto count = in.r.get<uint32_t>("proxy count");
            const uint32_t expected = b.enabled ? childCount(b.fixtures[f]) : 0u;
            if (count != expected) {
                in.r.fail(of + "fixture " + str(f) + " has " + str(count) +
                          " broad-phase proxies; its shape and its body's enabled flag give " +
                          str(expected));
            }
            st.proxies[f].resize(count);
            for (ProxyRead& p : st.proxies[f]) {
                p.id = in.r.get<int32>("proxy id");
                p.box = getBox(in, of + "fixture " + str(f) + " proxy box");
            }
        }
    }
    s.joints.resize(joints);
    for (std::size_t k = 0; k < joints; ++k) {
        const std::string of = "joint " + str(k) + " ";
        JointState& j = s.joints[k];
        j.impulse = in.vec(of + "impulse", kMaxImpulse);
        j.motor = in.number(of + "motor impulse", -kMaxAngularImpulse, kMaxAngularImpulse);
        j.lower = in.number(of + "lower limit impulse", 0.0f, kMaxAngularImpulse);
        j.upper = in.number(of + "upper limit impulse", 0.0f, kMaxAngularImpulse);
    }

    const uint32_t capacity = in.r.count("tree node capacity", kMaxTreeNodes, kNodeBytes);
    // Box2D's pool starts at 16 nodes and doubles when full.
    if (capacity < 16 || (capacity & (capacity - 1)) != 0) {
        in.r.fail("the broad-phase tree's node capacity " + str(capacity) +
                  " is not 16 times a power of 2");
    }
    s.root = in.r.get<int32>("tree root");
    s.freeList = in.r.get<int32>("tree free list");
    s.insertions = in.r.get<int32>("tree insertion count");
    s.nodes.resize(capacity);
    for (uint32_t k = 0; k < capacity; ++k) {
        NodeRead& n = s.nodes[k];
        n.height = in.r.get<int32>("tree node height");
        if (n.height < -1 || n.height >= int32(capacity)) {
            in.r.fail("tree node " + str(k) + " height " + std::to_string(n.height) +
                      " is out of [-1, " + str(capacity - 1) + "]");
        }
        if (n.height == -1) {
            n.link = in.r.get<int32>("tree node link");
            continue;
        }
        n.link = in.r.get<int32>("tree node parent");
        n.child1 = in.r.get<int32>("tree node child");
        n.child2 = in.r.get<int32>("tree node child");
        n.moved = in.flag("tree node moved flag");
        n.box = getBox(in, "tree node " + str(k) + " box");
    }
    s.moves.resize(in.r.count("buffered move count", kMaxMoves, kMoveBytes));
    for (int32& m : s.moves) {
        m = in.r.get<int32>("buffered move");
    }
    s.contacts.resize(in.r.count("contact count", kMaxContacts, kContactBytes));
    for (std::size_t k = 0; k < s.contacts.size(); ++k) {
        ContactRead& c = s.contacts[k];
        const std::string of = "contact " + str(k) + " ";
        for (int side = 0; side < 2; ++side) {
            c.body[side] = in.r.get<uint32_t>("contact body");
            c.fixture[side] = in.r.get<uint32_t>("contact fixture");
            c.child[side] = in.r.get<uint32_t>("contact child");
        }
        c.flags = in.r.get<uint32_t>("contact flags");
        c.friction = in.number(of + "friction", 0.0f, kMaxFactor);
        c.restitution = in.number(of + "restitution", 0.0f, kMaxFactor);
        c.threshold = in.number(of + "restitution threshold", 0.0f);
        c.tangentSpeed = in.number(of + "tangent speed", -kMaxSpeed, kMaxSpeed);
        c.toiCount = in.r.get<int32>("contact TOI count");
        if (c.toiCount < 0 || c.toiCount > b2_maxSubSteps + 1) {
            in.r.fail(of + "TOI count " + std::to_string(c.toiCount) + " is out of [0, " +
                      std::to_string(b2_maxSubSteps + 1) + "]");
        }
        c.toi = in.number(of + "time of impact", 0.0f, 1.0f);
        b2Manifold& m = c.manifold;
        m.type = b2Manifold::e_circles;
        m.localNormal.SetZero();
        m.localPoint.SetZero();
        const auto points = in.r.get<uint8_t>("manifold point count");
        if (points > b2_maxManifoldPoints) {
            in.r.fail(of + "manifold has " + str(points) + " points (at most " +
                      str(b2_maxManifoldPoints) + ")");
        }
        m.pointCount = points;
        if (points == 0) {
            continue;
        }
        const auto type = in.r.get<uint8_t>("manifold type");
        if (type > uint8_t(b2Manifold::e_faceB)) {
            in.r.fail(of + "manifold type " + str(type) + " is not one");
        }
        m.type = b2Manifold::Type(type);
        m.localNormal = in.vec(of + "manifold normal", 1.001f);
        if (m.type != b2Manifold::e_circles && std::abs(m.localNormal.Length() - 1.0f) > 1e-3f) {
            in.r.fail(of + "manifold normal is not of unit length");
        }
        m.localPoint = in.vec(of + "manifold point", kMaxBox);
        for (int32 p = 0; p < m.pointCount; ++p) {
            b2ManifoldPoint& point = m.points[p];
            point.localPoint = in.vec(of + "manifold point", kMaxBox);
            point.normalImpulse = in.number(of + "normal impulse", 0.0f, kMaxImpulse);
            point.tangentImpulse = in.number(of + "tangent impulse", -kMaxImpulse, kMaxImpulse);
            point.id.key = in.r.get<uint32>("contact feature id");
        }
    }
    return s;
}

// Whether Box2D makes a contact with fixtures of these shapes in this order (b2Contact's
// registers: the second shape is a circle, or a polygon the first is no circle for).
bool contactOrder(b2Shape::Type a, b2Shape::Type b) {
    return b == b2Shape::e_circle || (b == b2Shape::e_polygon && a != b2Shape::e_circle);
}

// How the solver state fits the world loadPhysics built from the rest of the save: the tree is
// a tree (every node reached once from the root, each parent its children's, heights and boxes
// their children's), its free list holds the other nodes, every fixture proxy names its own
// leaf and every leaf a proxy, boxes hold what they must, contacts join fixtures that exist, of
// two bodies, in Box2D's order, once each. Nothing of the world changes here.
void checkSolverState(In& in, const SolverState& s, const std::vector<b2Body*>& bodies,
                      const std::vector<std::vector<b2Fixture*>>& fixtures) {
    const int32 capacity = int32(s.nodes.size());
    for (std::size_t k = 0; k < bodies.size(); ++k) {
        const b2Transform& xf = bodies[k]->GetTransform();
        const b2Vec2 lc = bodies[k]->GetLocalCenter();
        const b2Vec2 centre = b2Mul(xf, lc);
        const float off = (s.bodies[k].c - centre).Length();
        if (!(off <= 1e-4f * (1.0f + xf.p.Length() + lc.Length()))) {
            std::ostringstream m;
            m << "body " << k << " centre of mass (" << s.bodies[k].c.x << ", " << s.bodies[k].c.y
              << ") m is " << off << " m from where its position, angle and mass centre put it";
            in.r.fail(m.str());
        }
    }

    // The tree, from its root.
    int32 used = 0;
    for (const NodeRead& n : s.nodes) {
        used += n.height >= 0 ? 1 : 0;
    }
    const auto node = [&](int32 id) { return id >= 0 && id < capacity && s.nodes[id].height >= 0; };
    std::vector<uint8_t> seen(s.nodes.size(), 0);
    int32 reached = 0, leaves = 0;
    if (s.root != b2_nullNode) {
        if (!node(s.root)) {
            in.r.fail("the broad-phase tree's root " + std::to_string(s.root) +
                      " is not a node of the tree");
        }
        if (s.nodes[s.root].link != b2_nullNode) {
            in.r.fail("the broad-phase tree's root " + std::to_string(s.root) + " has a parent");
        }
        std::vector<int32> stack{s.root};
        while (!stack.empty()) {
            const int32 id = stack.back();
            stack.pop_back();
            const std::string of = "tree node " + std::to_string(id) + " ";
            if (seen[id] != 0) {
                in.r.fail(of + "is reached twice from the tree's root");
            }
            seen[id] = 1;
            ++reached;
            const NodeRead& n = s.nodes[id];
            if (n.child1 == b2_nullNode) {
                if (n.child2 != b2_nullNode || n.height != 0) {
                    in.r.fail(of + "has no first child but a second one or a height");
                }
                ++leaves;
                continue;
            }
            for (const int32 child : {n.child1, n.child2}) {
                if (!node(child)) {
                    in.r.fail(of + "has child " + std::to_string(child) +
                              ", not a node of the tree");
                }
                if (s.nodes[child].link != id) {
                    in.r.fail("tree node " + std::to_string(child) + " is a child of node " +
                              std::to_string(id) + " but names another parent");
                }
            }
            const NodeRead &a = s.nodes[n.child1], &b = s.nodes[n.child2];
            if (n.height != 1 + std::max(a.height, b.height)) {
                in.r.fail(of + "height is not one more than its children's");
            }
            b2AABB both;
            both.Combine(a.box, b.box);
            if (both.lowerBound != n.box.lowerBound || both.upperBound != n.box.upperBound) {
                in.r.fail(of + "box is not its children's union");
            }
            stack.push_back(n.child1);
            stack.push_back(n.child2);
        }
    }
    if (reached != used) {
        in.r.fail("the broad-phase tree holds " + std::to_string(used) + " nodes, but " +
                  std::to_string(reached) + " are reached from its root");
    }
    int32 free = 0;
    for (int32 id = s.freeList; id != b2_nullNode; id = s.nodes[id].link) {
        if (id < 0 || id >= capacity || s.nodes[id].height != -1 || seen[id] != 0) {
            in.r.fail("the broad-phase tree's free list reaches " + std::to_string(id) +
                      ", not a free node, or twice");
        }
        seen[id] = 1;
        ++free;
    }
    if (free != capacity - used) {
        in.r.fail("the broad-phase tree's free list holds " + std::to_string(free) + " of its " +
                  std::to_string(capacity - used) + " free nodes");
    }

    // Every proxy its own leaf, every leaf a proxy; the boxes hold what they must.
    std::vector<uint8_t> claimed(s.nodes.size(), 0);
    int32 proxies = 0;
    for (std::size_t k = 0; k < bodies.size(); ++k) {
        for (std::size_t f = 0; f < fixtures[k].size(); ++f) {
            const b2Fixture& fixture = *fixtures[k][f];
            for (std::size_t c = 0; c < s.bodies[k].proxies[f].size(); ++c) {
                const ProxyRead& p = s.bodies[k].proxies[f][c];
                const std::string of =
                    "body " + str(k) + " fixture " + str(f) + " proxy " + str(c) + " ";
                if (!node(p.id) || s.nodes[p.id].child1 != b2_nullNode) {
                    in.r.fail(of + "names tree node " + std::to_string(p.id) + ", not a leaf");
                }
                if (claimed[p.id] != 0) {
                    in.r.fail(of + "names tree node " + std::to_string(p.id) + ", another proxy's");
                }
                claimed[p.id] = 1;
                ++proxies;
                if (!s.nodes[p.id].box.Contains(p.box)) {
                    in.r.fail(of + "box is not inside its tree node's");
                }
                b2AABB shape;
                fixture.GetShape()->ComputeAABB(&shape, bodies[k]->GetTransform(), int32(c));
                if (!p.box.Contains(shape)) {
                    in.r.fail(of + "box does not hold the fixture where its body lies");
                }
            }
        }
    }
    if (proxies != leaves) {
        in.r.fail("the broad-phase tree holds " + std::to_string(leaves) + " leaves for " +
                  std::to_string(proxies) + " fixture proxies");
    }
    for (std::size_t k = 0; k < s.moves.size(); ++k) {
        const int32 id = s.moves[k];
        if (id != b2BroadPhase::e_nullProxy && (id < 0 || id >= capacity || claimed[id] == 0)) {
            in.r.fail("buffered move " + str(k) + " names tree node " + std::to_string(id) +
                      ", not a proxy");
        }
    }

    // Contacts.
    std::set<std::tuple<const b2Fixture*, uint32_t, const b2Fixture*, uint32_t>> pairs;
    for (std::size_t k = 0; k < s.contacts.size(); ++k) {
        const ContactRead& c = s.contacts[k];
        const std::string of = "contact " + str(k) + " ";
        const b2Fixture* f[2] = {nullptr, nullptr};
        for (int side = 0; side < 2; ++side) {
            const uint32_t b = c.body[side], i = c.fixture[side];
            if (b >= bodies.size() || i >= fixtures[b].size() ||
                c.child[side] >= uint32_t(fixtures[b][i]->GetShape()->GetChildCount())) {
                in.r.fail(of + "names body " + str(b) + " fixture " + str(i) + " child " +
                          str(c.child[side]) + ", which the save does not hold");
            }
            f[side] = fixtures[b][i];
            if (!bodies[b]->IsEnabled()) {
                in.r.fail(of + "touches body " + str(b) + ", which is disabled");
            }
        }
        if (c.body[0] == c.body[1]) {
            in.r.fail(of + "joins two fixtures of body " + str(c.body[0]));
        }
        if (bodies[c.body[0]]->GetType() != b2_dynamicBody &&
            bodies[c.body[1]]->GetType() != b2_dynamicBody) {
            in.r.fail(of + "joins bodies " + str(c.body[0]) + " and " + str(c.body[1]) +
                      ", neither of them dynamic");
        }
        if (!contactOrder(f[0]->GetType(), f[1]->GetType())) {
            in.r.fail(of + "pairs shape types " + str(f[0]->GetType()) + " and " +
                      str(f[1]->GetType()) + " (b2Shape::Type) in an order Box2D does not make");
        }
        const auto key = f[0] < f[1] ? std::tuple(f[0], c.child[0], f[1], c.child[1])
                                     : std::tuple(f[1], c.child[1], f[0], c.child[0]);
        if (!pairs.insert(key).second) {
            in.r.fail(of + "joins the same fixtures as an earlier contact");
        }
        if ((c.flags & ~uint32_t(0x3F)) != 0) {
            std::ostringstream m;
            m << of << "flags 0x" << std::hex << c.flags << " hold bits Box2D does not use";
            in.r.fail(m.str());
        }
        const bool touching = (c.flags & detail::kContactTouching) != 0;
        if (f[0]->IsSensor() || f[1]->IsSensor()) {
            if (c.manifold.pointCount != 0) {
                in.r.fail(of + "involves a sensor but holds manifold points");
            }
        } else if (touching != (c.manifold.pointCount > 0)) {
            in.r.fail(of + "touching flag disagrees with its " + str(c.manifold.pointCount) +
                      " manifold points");
        }
    }
}

// Puts the checked solver state into the world loadPhysics built: the tree replaces the one
// the fixtures' creation made (the proxies keep their saved ids), contacts are made in Box2D's
// way (b2Contact::Create, linked as b2ContactManager::AddPair links them) from the last to the
// first, so that the world's list and every body's edge list keep their saved order.
void applySolverState(b2World& physics, const SolverState& s, const std::vector<b2Body*>& bodies,
                      const std::vector<std::vector<b2Fixture*>>& fixtures,
                      const std::vector<b2Joint*>& joints) {
    using namespace detail;
    b2ContactManager& manager = field<WorldContacts>(physics);
    b2BroadPhase& phase = manager.m_broadPhase;
    b2DynamicTree& tree = field<PhaseTree>(phase);
    b2TreeNode*& nodes = field<TreeNodes>(tree);
    const int32 capacity = int32(s.nodes.size());
    b2Free(nodes);
    nodes = static_cast<b2TreeNode*>(b2Alloc(capacity * int32(sizeof(b2TreeNode))));
    std::memset(static_cast<void*>(nodes), 0, std::size_t(capacity) * sizeof(b2TreeNode));
    int32 used = 0;
    for (int32 k = 0; k < capacity; ++k) {
        const NodeRead& n = s.nodes[k];
        b2TreeNode& to = nodes[k];
        to.height = n.height;
        if (n.height < 0) {
            to.next = n.link;
            continue;
        }
        ++used;
        to.parent = n.link;
        to.child1 = n.child1;
        to.child2 = n.child2;
        to.moved = n.moved;
        to.aabb = n.box;
    }
    field<TreeRoot>(tree) = s.root;
    field<TreeNodeCount>(tree) = used;
    field<TreeNodeCapacity>(tree) = capacity;
    field<TreeFreeList>(tree) = s.freeList;
    field<TreeInsertions>(tree) = s.insertions;
    for (std::size_t k = 0; k < bodies.size(); ++k) {
        for (std::size_t f = 0; f < fixtures[k].size(); ++f) {
            b2FixtureProxy* proxies = field<FixtureProxies>(*fixtures[k][f]);
            for (std::size_t c = 0; c < s.bodies[k].proxies[f].size(); ++c) {
                const ProxyRead& p = s.bodies[k].proxies[f][c];
                proxies[c].proxyId = p.id;
                proxies[c].aabb = p.box;
                nodes[p.id].userData = &proxies[c];
            }
        }
    }
    int32*& moves = field<PhaseMoveBuffer>(phase);
    int32& moveCapacity = field<PhaseMoveCapacity>(phase);
    const int32 moveCount = int32(s.moves.size());
    if (moveCount > moveCapacity) {
        while (moveCapacity < moveCount) {
            moveCapacity *= 2;
        }
        b2Free(moves);
        moves = static_cast<int32*>(b2Alloc(moveCapacity * int32(sizeof(int32))));
    }
    if (moveCount > 0) {
        std::memcpy(moves, s.moves.data(), s.moves.size() * sizeof(int32));
    }
    field<PhaseMoveCount>(phase) = moveCount;

    for (std::size_t k = s.contacts.size(); k-- > 0;) {
        const ContactRead& c = s.contacts[k];
        b2Fixture* a = fixtures[c.body[0]][c.fixture[0]];
        b2Fixture* b = fixtures[c.body[1]][c.fixture[1]];
        b2Contact* contact = member(ContactCreate{})(a, int32(c.child[0]), b, int32(c.child[1]),
                                                     manager.m_allocator);
        // checkSolverState kept the order Box2D makes: nothing is swapped.
        b2Body* bodyA = a->GetBody();
        b2Body* bodyB = b->GetBody();
        field<ContactPrev>(*contact) = nullptr;
        field<ContactNext>(*contact) = manager.m_contactList;
        if (manager.m_contactList != nullptr) {
            field<ContactPrev>(*manager.m_contactList) = contact;
        }
        manager.m_contactList = contact;
        for (const auto& [edge, body, other] :
             {std::tuple(&field<ContactNodeA>(*contact), bodyA, bodyB),
              std::tuple(&field<ContactNodeB>(*contact), bodyB, bodyA)}) {
            b2ContactEdge*& list = field<BodyContacts>(*body);
            edge->contact = contact;
            edge->other = other;
            edge->prev = nullptr;
            edge->next = list;
            if (list != nullptr) {
                list->prev = edge;
            }
            list = edge;
        }
        ++manager.m_contactCount;
        field<ContactFlags>(*contact) = c.flags;
        contact->SetFriction(c.friction);
        contact->SetRestitution(c.restitution);
        contact->SetRestitutionThreshold(c.threshold);
        contact->SetTangentSpeed(c.tangentSpeed);
        field<ContactToiCount>(*contact) = c.toiCount;
        field<ContactToi>(*contact) = c.toi;
        *contact->GetManifold() = c.manifold;
    }

    for (std::size_t k = 0; k < bodies.size(); ++k) {
        b2Body& body = *bodies[k];
        const BodyState& st = s.bodies[k];
        // The local centre and the angle are the saved ones already (SetMassData, the body's
        // definition).
        b2Sweep& sweep = field<BodySweep>(body);
        sweep.c = st.c;
        sweep.c0 = st.c0;
        sweep.a0 = st.a0;
        sweep.alpha0 = st.alpha0;
        field<BodyInertia>(body) = st.inertia;
        field<BodyInvInertia>(body) = st.inertia > 0.0f ? 1.0f / st.inertia : 0.0f;
        field<BodyForce>(body) = st.force;
        field<BodyTorque>(body) = st.torque;
        field<BodySleepTime>(body) = st.sleep;
    }
    for (std::size_t k = 0; k < joints.size(); ++k) {
        auto& r = static_cast<b2RevoluteJoint&>(*joints[k]);
        field<RevoluteImpulse>(r) = s.joints[k].impulse;
        field<RevoluteMotorImpulse>(r) = s.joints[k].motor;
        field<RevoluteLowerImpulse>(r) = s.joints[k].lower;
        field<RevoluteUpperImpulse>(r) = s.joints[k].upper;
    }
    field<WorldInvDt0>(physics) = s.invDt0;
    field<WorldNewContacts>(physics) = s.newContacts;
    field<WorldStepComplete>(physics) = s.stepComplete;
}

} // namespace

bool detail::carriesForce(const b2Body& body) {
    const b2Vec2 force = detail::field<detail::BodyForce>(body);
    return force.x != 0.0f || force.y != 0.0f || detail::field<detail::BodyTorque>(body) != 0.0f;
}

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
                            " (b2JointType) cannot be saved; only revolute joints can",
                        ErrorCode::BadArgument);
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
    putSolverState(w, physics);
    if (!out) {
        throw Error("fluid::box2d::savePhysics: the stream failed while writing", ErrorCode::Io);
    }
}

std::unique_ptr<b2World> loadPhysics(std::istream& stream) {
    In in{internal::StreamReader(stream, "box2d save")};
    char magic[sizeof(kMagic)];
    if (!stream.read(magic, sizeof(magic)) || std::memcmp(magic, kMagic, sizeof(kMagic)) != 0) {
        in.r.fail("not a Box2D world save (bad magic)");
    }
    const auto version = in.r.get<uint32_t>("version");
    if (version != 1 && version != kVersion) {
        in.r.fail("version " + std::to_string(version) +
                  " is not supported (this build reads 1 and " + std::to_string(kVersion) + ")");
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
        for (std::size_t f = 0; f < b.fixtures.size(); ++f) {
            b.fixtures[f] = getFixture(in, "body " + std::to_string(&b - bodies.data()) +
                                               " fixture " + std::to_string(f) + " ");
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
    // Version 1 saves end here: their world rebuilds its contacts at the next step.
    const bool solver = version >= 2;
    const SolverState state = solver ? getSolverState(in, bodies, joints.size()) : SolverState{};

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
    if (solver) {
        std::vector<std::vector<b2Fixture*>> fixtures(made.size());
        for (std::size_t k = 0; k < made.size(); ++k) {
            for (b2Fixture* f = made[k]->GetFixtureList(); f != nullptr; f = f->GetNext()) {
                fixtures[k].push_back(f);
            }
        }
        std::vector<b2Joint*> jointList;
        for (b2Joint* j = physics->GetJointList(); j != nullptr; j = j->GetNext()) {
            jointList.push_back(j);
        }
        checkSolverState(in, state, made, fixtures);
        applySolverState(*physics, state, made, fixtures, jointList);
    }
    return physics;
}

} // namespace fluid::box2d
