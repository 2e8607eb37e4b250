// fluid::level — the Box2D part of the level format (docs/levels.md): bodies with their
// fixtures, revolute joints and the coupling settings. Box2D 2.4 checks its input with assertions
// (compiled into Debian's libbox2d, so a bad value aborts the program), and silently repairs
// some shapes (a polygon becomes its convex hull): every value is checked here first, as written,
// and a bad file is a LevelError.
#include "bodies.h"

#include "names.h"

#include <fluid/box2d/coupling.h>
#include <fluid/box2d/shapes.h>

#include <box2d/box2d.h>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace fluid::detail {

namespace {

// The Box2D body types' names, as a body's "type" writes them: the one table of them.
constexpr EnumName<b2BodyType> kBodyTypeNames[] = {
    {b2_staticBody, "static"},
    {b2_kinematicBody, "kinematic"},
    {b2_dynamicBody, "dynamic"},
};

// Ranges of the format (docs/levels.md lists them). Body-local coordinates are bounded tighter
// than world positions: Box2D stores them in float, and a shape far from its body's origin
// loses its size to rounding.
constexpr Range kPosition{-1e5, 1e5, "m"};
constexpr Range kLocal{-1e4, 1e4, "m"};
// Box2D's linear slop: shapes thinner than it do not collide reliably, and a polygon of
// (nearly) zero area fails Box2D's mass assertion.
constexpr double kSlop = 0.005;
static_assert(float(kSlop) == b2_linearSlop, "the format's smallest size is Box2D's linear slop");
constexpr Range kShapeSize{kSlop, 1e4, "m"};
constexpr Range kAngle{-1e3, 1e3, "rad"};
constexpr Range kVelocity{-1e3, 1e3, "m/s"};
constexpr Range kAngularVelocity{-1e3, 1e3, "rad/s"};
constexpr Range kDamping{0.0, 1e3, "1/s"};
constexpr Range kDensity{0.0, 1e6, "kg/m^2"};
constexpr Range kDensityRatio{0.0, 1e3, "1"};
constexpr Range kFriction{0.0, 1e3, "1"};
constexpr Range kRestitution{0.0, 1.0, "1"};
constexpr Range kMotorSpeed{-1e3, 1e3, "rad/s"};
constexpr Range kMotorTorque{0.0, 1e9, "N m"};
// The coupling refuses longer chains at every step (box2d::Coupling, "Limits").
constexpr std::size_t kMaxChainPoints = 4096;
// Box2D's default fixture category: fixtures that touch fluid keep it.
constexpr uint16_t kWetCategory = 0x0001;

b2Vec2 toB2(glm::vec2 v) {
    return {v.x, v.y};
}

double cross(glm::dvec2 a, glm::dvec2 b) {
    return a.x * b.y - a.y * b.x;
}

std::string str(std::size_t k) {
    return std::to_string(k);
}

// A Box2D polygon is convex, counter-clockwise, has 3 to 8 vertices no two closer than the slop
// (Box2D welds closer ones) and an area above zero. The file's vertices are checked as written
// (either winding) and returned counter-clockwise; `at` points at the vertex list.
std::vector<b2Vec2> convexPolygon(const JsonDocument& doc, const std::string& at,
                                  const std::vector<glm::vec2>& vertices, float spacing) {
    const std::size_t n = vertices.size();
    // The checks every coupled body's polygon passes (level files, the C API, Box2D saves).
    const box2d::ShapeProblem problem = box2d::checkPolygon(vertices, spacing);
    if (problem) {
        doc.fail(problem.vertex >= 0 ? childPointer(at, std::size_t(problem.vertex)) : at,
                 problem.message);
    }
    double twiceArea = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        twiceArea += cross(glm::dvec2(vertices[i]), glm::dvec2(vertices[(i + 1) % n]));
    }
    const double sign = twiceArea > 0.0 ? 1.0 : -1.0;
    std::vector<b2Vec2> out;
    for (std::size_t k = 0; k < n; ++k) {
        out.push_back(toB2(vertices[sign > 0.0 ? k : n - 1 - k]));
    }
    return out;
}

// Box2D's own test for chain links (b2ChainShape asserts it), in float as Box2D computes it.
bool linkTooShort(glm::vec2 a, glm::vec2 b) {
    return !(b2DistanceSquared(toB2(a), toB2(b)) > b2_linearSlop * b2_linearSlop);
}

// One fixture as the file gives it, checked, ready for b2Body::CreateFixture.
struct FixtureSpec {
    b2Shape::Type type = b2Shape::e_polygon;
    b2PolygonShape polygon;
    b2CircleShape circle;
    b2EdgeShape edge;
    // A chain's points; b2ChainShape owns heap memory and is not safely copyable, so the shape
    // is made when the fixture is created.
    std::vector<b2Vec2> chain;
    bool loop = false;
    float density = 0.0f;
    float friction = 0.2f;
    float restitution = 0.0f;

    const b2Shape* massShape() const {
        return type == b2Shape::e_polygon  ? static_cast<const b2Shape*>(&polygon)
               : type == b2Shape::e_circle ? &circle
                                           : nullptr;
    }
};

class BodiesReader {
public:
    BodiesReader(const JsonDocument& doc, Level& level) : m_doc(doc), m_level(level) {}

    void read(const ObjectReader& root) {
        const Json* bodies = root.array("bodies", "bodies");
        const Json* joints = root.array("joints", "joints");
        box2d::CouplingDef def;
        // Fixtures of bodies declared with "fluid": false carry kDryFixtureCategory.
        def.categoryMask = uint16_t(~kDryFixtureCategory);
        if (const Json* value = root.find("coupling")) {
            readCoupling(
                ObjectReader(m_doc, *value, root.pointer("coupling"), "the coupling settings"),
                def);
        }
        if (bodies == nullptr || bodies->empty()) {
            if (root.has("coupling")) {
                root.failAt("coupling", "coupling settings need bodies; the level declares none");
            }
            if (joints != nullptr && !joints->empty()) {
                root.failAt("joints", "joints need bodies; the level declares none");
            }
            return;
        }

        m_level.physics = std::make_unique<b2World>(gravity());
        if (!m_level.materials.empty()) {
            m_arealDensity = box2d::arealDensity(m_level.world, m_level.materials[0].second);
        }
        for (std::size_t i = 0; i < bodies->size(); ++i) {
            readBody(root, i, (*bodies)[i]);
        }
        for (std::size_t i = 0; joints != nullptr && i < joints->size(); ++i) {
            readJoint(root, i, (*joints)[i]);
        }
        warnUnheldBodies(root);
        located(m_doc, root.pointer("bodies"), [&] {
            m_level.coupling =
                std::make_unique<box2d::Coupling>(m_level.world, *m_level.physics, def);
            for (const b2Body* body : m_contactBodies) {
                m_level.coupling->setContactEvents(body, true);
            }
        });
    }

private:
    // Box2D's gravity is the fluid's uniform gravity: the sum of the world's force.gravity
    // plugins (world.gravity adds one). Other forces (point gravity, wind...) act on the fluid
    // only; bodies feel them through the fluid.
    b2Vec2 gravity() const {
        double gx = 0.0, gy = 0.0;
        for (const auto& force : m_level.world.forces()) {
            if (force->type() == "force.gravity") {
                gx += force->param("gx");
                gy += force->param("gy");
            }
        }
        return {float(gx), float(gy)};
    }

    void readCoupling(const ObjectReader& c, box2d::CouplingDef& def) const {
        c.allowOnly({"friction", "splashSpeed", "velocityIterations", "positionIterations"});
        def.friction = float(c.number("friction", {0.0, 10.0, "1"}, def.friction));
        def.splashSpeed = float(c.number("splashSpeed", {0.0, 1e3, "m/s"}, def.splashSpeed));
        def.velocityIterations = int32_t(
            c.integer("velocityIterations", {1.0, 1000.0, "count"}, def.velocityIterations));
        def.positionIterations = int32_t(
            c.integer("positionIterations", {1.0, 1000.0, "count"}, def.positionIterations));
    }

    // The fluid's boundary plugins hold the fluid only: Box2D never sees them. A dynamic body in
    // a level whose Box2D world holds nothing static or kinematic falls through the tank: warn,
    // naming the body and the plugins it passes through (docs/box2d.md, "Shapes and masses").
    void warnUnheldBodies(const ObjectReader& root) {
        std::string walls;
        for (const Level::PluginEntry& plugin : m_level.plugins) {
            if (plugin.kind != PluginKind::Boundary) {
                continue;
            }
            const auto& boundary = m_level.world.boundaries()[plugin.index];
            walls += (walls.empty() ? "" : ", ") + std::string(boundary->type()) + " '" +
                     plugin.name + "'";
        }
        if (walls.empty()) {
            return;
        }
        for (const b2Body* b = m_level.physics->GetBodyList(); b != nullptr; b = b->GetNext()) {
            if (b->GetType() != b2_dynamicBody && b->GetFixtureList() != nullptr) {
                return; // something stands in Box2D: the author built the walls there
            }
        }
        for (std::size_t k = 0; k < m_level.bodies.size(); ++k) {
            if (m_level.bodies[k].second->GetType() != b2_dynamicBody) {
                continue;
            }
            m_level.warnings.push_back(m_doc.locatedText(
                childPointer(root.pointer("bodies"), k),
                "body '" + m_level.bodies[k].first +
                    "' is dynamic, but no static or kinematic body stands in Box2D: the "
                    "boundary plugins (" +
                    walls +
                    ") hold the fluid only, and the body passes through them; add a static "
                    "body with \"fluid\": false along the walls (docs/levels.md, \"Bodies\")"));
        }
    }

    // ---- bodies ----------------------------------------------------------------------------
    void readBody(const ObjectReader& root, std::size_t index, const Json& value) {
        const std::string at = childPointer(root.pointer("bodies"), index);
        const ObjectReader b(m_doc, value, at, "a body");
        b.allowOnly({"name", "type", "position", "angle", "velocity", "angularVelocity",
                     "linearDamping", "angularDamping", "fixedRotation", "bullet", "fluid",
                     "contacts", "fixtures"});
        // An unnamed body is "body<k>": the name it has in Level::bodies, joints and fluid-run.
        const bool named = b.has("name");
        const std::string name = named ? requiredName(b, "body") : "body" + str(index);
        m_bodyNames.add(m_doc, name, named ? b.pointer("name") : at, m_level.bodies.size());

        const std::string typeName =
            b.string("type", std::string(nameIn(kBodyTypeNames, b2_dynamicBody)));
        const std::optional<b2BodyType> typeNamed = valueIn(kBodyTypeNames, typeName);
        if (!typeNamed) {
            b.failAt("type",
                     "unknown body type " + internal::quoted(typeName) +
                         "; known: " + namesIn(kBodyTypeNames, ", "),
                     ErrorCode::UnknownName);
        }
        const b2BodyType type = *typeNamed;
        b2BodyDef def;
        def.position = toB2(b.point("position", kPosition, {0.0f, 0.0f}));
        def.angle = float(b.number("angle", kAngle, 0.0));
        const b2Vec2 velocity = toB2(b.point("velocity", kVelocity, {0.0f, 0.0f}));
        const float omega = float(b.number("angularVelocity", kAngularVelocity, 0.0));
        if (type == b2_staticBody && (velocity.x != 0.0f || velocity.y != 0.0f || omega != 0.0f)) {
            b.failAt(velocity.x != 0.0f || velocity.y != 0.0f ? "velocity" : "angularVelocity",
                     "a static body does not move; give it type 'kinematic' (moved by its "
                     "velocity) or 'dynamic'");
        }
        def.linearDamping = float(b.number("linearDamping", kDamping, 0.0));
        def.angularDamping = float(b.number("angularDamping", kDamping, 0.0));
        def.fixedRotation = b.boolean("fixedRotation", false);
        def.bullet = b.boolean("bullet", false);
        const bool wet = b.boolean("fluid", true);
        const bool contacts = b.boolean("contacts", false);
        if (contacts && !wet) {
            b.failAt("contacts", "a body with \"fluid\": false never touches the liquid: it has "
                                 "no contact events");
        }

        const Json& list = b.required("fixtures", "an array of at least one fixture");
        b.array("fixtures", "fixtures");
        if (list.empty()) {
            b.failAt("fixtures", "expected at least one fixture, got an empty array");
        }
        std::vector<FixtureSpec> fixtures;
        for (std::size_t k = 0; k < list.size(); ++k) {
            fixtures.push_back(readFixture(
                ObjectReader(m_doc, list[k], childPointer(b.pointer("fixtures"), k), "a fixture"),
                type, type == b2_dynamicBody && wet));
        }
        if (type == b2_dynamicBody) {
            checkMass(b, fixtures, def.fixedRotation, wet);
        }

        // Built static, typed last: Box2D recomputes a dynamic body's mass after every fixture
        // and asserts on the inertia of a partial set; checkMass vetted the whole set.
        def.type = b2_staticBody;
        b2Body* body = m_level.physics->CreateBody(&def);
        for (const FixtureSpec& f : fixtures) {
            b2FixtureDef fd;
            fd.density = f.density;
            fd.friction = f.friction;
            fd.restitution = f.restitution;
            fd.filter.categoryBits = wet ? kWetCategory : kDryFixtureCategory;
            b2ChainShape chain;
            if (f.type == b2Shape::e_chain) {
                const int32 n = int32(f.chain.size());
                if (f.loop) {
                    chain.CreateLoop(f.chain.data(), n);
                } else {
                    // Ghost vertices continue the end links straight on.
                    chain.CreateChain(f.chain.data(), n, 2.0f * f.chain[0] - f.chain[1],
                                      2.0f * f.chain[n - 1] - f.chain[n - 2]);
                }
                fd.shape = &chain;
            } else if (f.type == b2Shape::e_edge) {
                fd.shape = &f.edge;
            } else {
                fd.shape = f.massShape();
            }
            body->CreateFixture(&fd);
        }
        if (type != b2_staticBody) {
            body->SetType(type);
            body->SetLinearVelocity(velocity);
            body->SetAngularVelocity(omega);
        }
        m_level.bodies.emplace_back(name, body);
        if (contacts) {
            m_contactBodies.push_back(body);
        }
    }

    // Box2D gives a dynamic body without mass 1 kg, and asserts when its rotational inertia
    // about the centre of mass comes out <= 0 in float (b2Body::ResetMassData subtracts
    // m |c|^2 from the inertia about the body's origin: fixtures far from the origin cancel).
    // The same sums, in the same order (Box2D's fixture list is newest first), with a margin.
    void checkMass(const ObjectReader& b, const std::vector<FixtureSpec>& fixtures,
                   bool fixedRotation, bool wet) const {
        float mass = 0.0f, inertia = 0.0f, area = 0.0f;
        b2Vec2 center(0.0f, 0.0f);
        for (std::size_t k = fixtures.size(); k-- > 0;) {
            const b2Shape* shape = fixtures[k].massShape();
            if (shape == nullptr || fixtures[k].density == 0.0f) {
                continue;
            }
            b2MassData data;
            shape->ComputeMass(&data, fixtures[k].density);
            b2MassData unit;
            shape->ComputeMass(&unit, 1.0f);
            area += unit.mass;
            mass += data.mass;
            center += data.mass * data.center;
            inertia += data.I;
        }
        if (!(mass > 0.0f)) {
            b.failAt("fixtures", "a dynamic body needs mass: expected a box, circle or polygon "
                                 "fixture with a density above 0");
        }
        center *= 1.0f / mass;
        const float centred = inertia - mass * b2Dot(center, center);
        // The floors every coupled body meets (box2d::checkDynamicMass); a dry body ("fluid":
        // false) floats in nothing, so the fluid's density does not bound it.
        const box2d::ShapeProblem problem = box2d::checkDynamicMass(
            mass, area, inertia > 0.0f ? centred : box2d::kMinBodyInertia, true,
            wet ? box2d::densestArealDensity(m_level.world) : 0.0f);
        if (problem) {
            b.failAt("fixtures", problem.message);
        }
        if (!fixedRotation && inertia > 0.0f) {
            if (!(centred > 1e-5f * inertia)) {
                b.failAt("fixtures", "the fixtures' centre of mass lies " +
                                         formatNumber(center.Length()) +
                                         " m from the body's position, too far for Box2D's "
                                         "single-precision inertia; move the body's position to "
                                         "its fixtures");
            }
            if (centred < box2d::kMinBodyInertia) {
                b.failAt("fixtures",
                         "the fixtures' rotational inertia about their centre of "
                         "mass is " +
                             formatNumber(centred) + " kg m^2, less than the " +
                             formatNumber(box2d::kMinBodyInertia) +
                             " kg m^2 a dynamic body that turns needs (Box2D divides by "
                             "it); make them wider or set 'fixedRotation'");
            }
        }
    }

    // `coupledDynamic`: a dynamic body the fluid pushes (not "fluid": false), whose polygons
    // must hold a circle of the fluid's spacing when pointed (box2d::checkPolygon).
    FixtureSpec readFixture(const ObjectReader& f, b2BodyType bodyType,
                            bool coupledDynamic) const {
        const std::string shape =
            f.requiredString("shape", "a shape: box, circle, polygon, edge or chain");
        std::vector<std::string_view> allowed{"shape", "friction", "restitution"};
        FixtureSpec spec;
        if (shape == "box") {
            allowed.insert(allowed.end(), {"width", "height", "center", "angle"});
        } else if (shape == "circle") {
            allowed.insert(allowed.end(), {"radius", "center"});
        } else if (shape == "polygon") {
            allowed.push_back("vertices");
        } else if (shape == "edge") {
            allowed.insert(allowed.end(), {"from", "to"});
        } else if (shape == "chain") {
            allowed.insert(allowed.end(), {"points", "loop"});
        } else {
            f.failAt("shape",
                     "unknown shape " + internal::quoted(shape) +
                         "; known: box, circle, polygon, edge, chain",
                     ErrorCode::UnknownName);
        }
        const bool hasArea = shape == "box" || shape == "circle" || shape == "polygon";
        if (!hasArea) {
            for (const std::string_view key : {"density", "densityRatio"}) {
                if (f.has(key)) {
                    m_doc.failAtKey(f.pointer(key),
                                    "an " + shape + " has no area, hence no mass: '" +
                                        std::string(key) + "' applies to box, circle and polygon");
                }
            }
        } else {
            allowed.insert(allowed.end(), {"density", "densityRatio"});
        }
        f.allowOnly(allowed);

        if (shape == "box") {
            const double width = f.requiredNumber("width", kShapeSize);
            const double height = f.requiredNumber("height", kShapeSize);
            const glm::vec2 center = f.point("center", kLocal, {0.0f, 0.0f});
            const double angle = f.number("angle", kAngle, 0.0);
            spec.type = b2Shape::e_polygon;
            spec.polygon.SetAsBox(float(0.5 * width), float(0.5 * height), toB2(center),
                                  float(angle));
        } else if (shape == "circle") {
            spec.type = b2Shape::e_circle;
            spec.circle.m_radius = float(f.requiredNumber("radius", kShapeSize));
            spec.circle.m_p = toB2(f.point("center", kLocal, {0.0f, 0.0f}));
        } else if (shape == "polygon") {
            const std::vector<b2Vec2> v = convexPolygon(
                m_doc, f.pointer("vertices"),
                f.requiredPoints("vertices", kLocal, 3, std::size_t(b2_maxPolygonVertices)),
                coupledDynamic ? box2d::coarsestSpacing(m_level.world) : 0.0f);
            spec.type = b2Shape::e_polygon;
            spec.polygon.Set(v.data(), int32(v.size()));
        } else if (shape == "edge") {
            const glm::vec2 from = f.requiredPoint("from", kLocal);
            const glm::vec2 to = f.requiredPoint("to", kLocal);
            if (linkTooShort(from, to)) {
                f.failAt("to", "the edge is " + formatNumber(glm::distance(from, to)) +
                                   " m long; expected more than 0.005 m (Box2D's linear slop)");
            }
            spec.type = b2Shape::e_edge;
            spec.edge.SetTwoSided(toB2(from), toB2(to));
        } else {
            readChain(f, spec);
        }

        if (hasArea) {
            readDensity(f, bodyType, spec);
        }
        spec.friction = float(f.number("friction", kFriction, spec.friction));
        spec.restitution = float(f.number("restitution", kRestitution, spec.restitution));
        return spec;
    }

    void readChain(const ObjectReader& f, FixtureSpec& spec) const {
        const std::vector<glm::vec2> points =
            f.requiredPoints("points", kLocal, 2, kMaxChainPoints);
        spec.loop = f.boolean("loop", false);
        if (spec.loop && points.size() < 3) {
            f.failAt("points", "a loop needs at least 3 points, got " + str(points.size()));
        }
        const std::size_t n = points.size();
        for (std::size_t k = 1; k <= n; ++k) {
            if (k == n && !spec.loop) {
                break;
            }
            const glm::vec2 a = points[k - 1], b = points[k % n];
            if (linkTooShort(a, b)) {
                m_doc.fail(childPointer(f.pointer("points"), k % n),
                           "point " + str(k % n) + " is " + formatNumber(glm::distance(a, b)) +
                               " m from point " + str(k - 1) +
                               "; consecutive points must be more than 0.005 m apart "
                               "(Box2D's linear slop)");
            }
        }
        spec.type = b2Shape::e_chain;
        for (const glm::vec2 p : points) {
            spec.chain.push_back(toB2(p));
        }
    }

    // Exactly one of density and densityRatio; a dynamic body's fixtures need one.
    void readDensity(const ObjectReader& f, b2BodyType bodyType, FixtureSpec& spec) const {
        const bool absolute = f.has("density"), ratio = f.has("densityRatio");
        if (absolute && ratio) {
            const bool ratioSecond =
                m_doc.keyOffset(f.pointer("densityRatio")) > m_doc.keyOffset(f.pointer("density"));
            m_doc.failAtKey(f.pointer(ratioSecond ? "densityRatio" : "density"),
                            std::string("expected only one of 'density', 'densityRatio'; '") +
                                (ratioSecond ? "density" : "densityRatio") + "' is given too");
        }
        if (absolute) {
            spec.density = float(f.number("density", kDensity, 0.0));
        } else if (ratio) {
            spec.density = float(f.number("densityRatio", kDensityRatio, 0.0) * m_arealDensity);
        } else if (bodyType == b2_dynamicBody) {
            f.fail("missing the density of a dynamic body's fixture; expected 'density' (kg/m^2) "
                   "or 'densityRatio' (1, a multiple of the first material's areal density)");
        }
    }

    // ---- joints ----------------------------------------------------------------------------
    void readJoint(const ObjectReader& root, std::size_t index, const Json& value) {
        const std::string at = childPointer(root.pointer("joints"), index);
        const ObjectReader j(m_doc, value, at, "a joint");
        const std::string type = j.requiredString("type", "a joint type: revolute");
        if (type != "revolute") {
            j.failAt("type", "unknown joint type " + internal::quoted(type) + "; known: revolute",
                     ErrorCode::UnknownName);
        }
        j.allowOnly({"type", "name", "bodyA", "bodyB", "anchor", "collideConnected", "enableMotor",
                     "motorSpeed", "maxMotorTorque", "enableLimit", "lowerAngle", "upperAngle"});
        const bool named = j.has("name");
        const std::string name = named ? requiredName(j, "joint") : "joint" + str(index);
        m_jointNames.add(m_doc, name, named ? j.pointer("name") : at, m_level.joints.size());

        const std::string nameA = j.requiredString("bodyA", "the name of a body");
        b2Body* a = m_level.bodies[m_bodyNames.find(m_doc, nameA, j.pointer("bodyA"))].second;
        const std::string nameB = j.requiredString("bodyB", "the name of a body");
        b2Body* b = m_level.bodies[m_bodyNames.find(m_doc, nameB, j.pointer("bodyB"))].second;
        if (a == b) {
            j.failAt("bodyB", "expected a body other than bodyA ('" + nameA +
                                  "'); a joint connects two bodies");
        }
        b2RevoluteJointDef def;
        def.Initialize(a, b, toB2(j.requiredPoint("anchor", kPosition)));
        def.collideConnected = j.boolean("collideConnected", false);
        def.enableMotor = j.boolean("enableMotor", false);
        def.motorSpeed = float(j.number("motorSpeed", kMotorSpeed, 0.0));
        def.maxMotorTorque = float(j.number("maxMotorTorque", kMotorTorque, 0.0));
        def.enableLimit = j.boolean("enableLimit", false);
        def.lowerAngle = float(j.number("lowerAngle", kAngle, 0.0));
        def.upperAngle = float(j.number("upperAngle", kAngle, 0.0));
        if (def.upperAngle < def.lowerAngle) {
            j.failAt("upperAngle", "expected upperAngle >= lowerAngle (" +
                                       formatNumber(def.lowerAngle) + " rad), got " +
                                       formatNumber(def.upperAngle));
        }
        m_level.joints.emplace_back(name, m_level.physics->CreateJoint(&def));
    }

    std::vector<const b2Body*> m_contactBodies; // bodies with "contacts": true
    const JsonDocument& m_doc;
    Level& m_level;
    // Indices in Level::bodies and Level::joints.
    NameTable<std::size_t> m_bodyNames{"body"};
    NameTable<std::size_t> m_jointNames{"joint"};
    // Areal density of the first material (unit: kg/m^2): what densityRatio multiplies.
    float m_arealDensity = 0.0f;
};

} // namespace

void readBodies(const JsonDocument& doc, const ObjectReader& root, Level& level) {
    BodiesReader(doc, level).read(root);
}

} // namespace fluid::detail
