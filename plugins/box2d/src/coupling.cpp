// fluid::box2d — the coupling's frame: fluid step, forces to bodies, Box2D step, reports.
#include <fluid/box2d/coupling.h>
#include <fluid/box2d/shapes.h>

#include "body_boundary.h"
#include "box2d_math.h"
#include "solver_state.h"

#include <fluid/error.h>
#include <fluid/internal/binary.h>
#include <fluid/internal/checks.h>
#include <fluid/registry.h>

#include <box2d/box2d.h>

#include <algorithm>
#include <cstring>
#include <istream>
#include <ostream>
#include <cmath>
#include <numbers>
#include <sstream>
#include <unordered_map>
#include <unordered_set>

namespace fluid::box2d {

namespace {

// The coupling's own World::step: the plugin lets it through (BodyBoundary::steppedBy) until the
// step returns or throws.
struct HostStep {
    BodyBoundary& boundary;
    explicit HostStep(BodyBoundary& b) : boundary(b) { boundary.setHostStepping(true); }
    ~HostStep() { boundary.setHostStepping(false); }
    HostStep(const HostStep&) = delete;
    HostStep& operator=(const HostStep&) = delete;
};

void checkRange(const char* field, double value, double lo, double hi, const char* unit) {
    internal::checkRange("fluid::box2d::CouplingDef: ", field, value, lo, hi, unit);
}

void validate(const CouplingDef& def) {
    checkRange("friction", def.friction, 0.0, 10.0, "1");
    checkRange("splashSpeed", def.splashSpeed, 0.0, 1e3, "m/s");
    checkRange("velocityIterations", def.velocityIterations, 1.0, 1000.0, "count");
    checkRange("positionIterations", def.positionIterations, 1.0, 1000.0, "count");
}

// Rounds of a 1/60 s frame with the explicit solver (more for a longer frame, fluid::
// frameSubsteps), each a quarter frame in its own CFL sub-steps: with one round per frame a
// body answered the fluid a frame late and was thrown out of it (docs/box2d.md, "One frame").
constexpr uint32_t kExplicitRounds = 4;

// Dry gaps of at most this many probes between wet ones count as wet: a particle may rest a
// little farther from the surface here and there.
constexpr std::size_t kBridge = 2;

// How far below the fluid's surface the chord across a run of wet points lies (unit: spacings;
// see submergedArea).
constexpr double kChordDepth = 1.0;

// The area of a convex fixture's outline loop cut off by the chord across its longest run of
// wet probes (see the Coupling class comment), scaled from the probe polygon to the shape.
double submergedArea(const FixtureEntry& entry, std::span<const uint8_t> wet, double spacing,
                     double& chordLength) {
    chordLength = 0.0;
    const std::size_t n = entry.probes.size();
    std::size_t wetCount = 0;
    for (const uint8_t w : wet) {
        wetCount += w;
    }
    if (wetCount == 0 || entry.probeArea <= 0.0) {
        return 0.0;
    }
    std::vector<uint8_t> run(wet.begin(), wet.end());
    if (wetCount < n) {
        // Bridge short dry gaps, walking once round the loop from a wet probe.
        std::size_t start = 0;
        while (wet[start] == 0) {
            ++start;
        }
        std::size_t gap = 0;
        for (std::size_t step = 1; step <= n; ++step) {
            const std::size_t k = (start + step) % n;
            if (wet[k] == 0) {
                ++gap;
                continue;
            }
            if (gap > 0 && gap <= kBridge) {
                for (std::size_t g = 1; g <= gap; ++g) {
                    run[(k + n - g) % n] = 1;
                }
            }
            gap = 0;
        }
    }
    std::size_t dry = n;
    for (std::size_t k = 0; k < n; ++k) {
        if (run[k] == 0) {
            dry = k;
            break;
        }
    }
    if (dry == n) {
        return entry.area; // wet all round
    }
    // The longest run, walking once round from a dry probe (the first of equal runs wins).
    std::size_t bestStart = 0, bestLength = 0, length = 0;
    for (std::size_t step = 1; step <= n; ++step) {
        const std::size_t k = (dry + step) % n;
        if (run[k] != 0) {
            ++length;
            if (length > bestLength) {
                bestLength = length;
                bestStart = (k + n + 1 - length) % n;
            }
        } else {
            length = 0;
        }
    }
    if (bestLength < 3) {
        return 0.0;
    }
    std::vector<glm::dvec2> polygon(bestLength);
    for (std::size_t k = 0; k < bestLength; ++k) {
        polygon[k] = entry.probes[(bestStart + k) % n];
    }
    // The chord between the run's ends lies below the fluid's surface: the top particles'
    // centres sit half a spacing under it, and those against a body a little lower still
    // (measured: floating discs and squares at 0.25 to 0.75 of water's density, the chord 0.9
    // to 1.5 spacings under the far-field surface). The band of one spacing above the chord
    // belongs to the submerged part.
    const glm::dvec2 chord = polygon.back() - polygon.front();
    chordLength = std::sqrt(chord.x * chord.x + chord.y * chord.y);
    const double band = chordLength * kChordDepth * spacing;
    return std::min(entry.area,
                    entry.area * (std::fabs(shoelace(polygon)) + band) / entry.probeArea);
}

} // namespace

float arealDensity(const World& world, MaterialId material) {
    return world.material(material).restDensity * world.def().depth;
}

Coupling::Coupling(World& world, b2World& physics, const CouplingDef& def)
    : m_physics(&physics), m_boundary(nullptr), m_def(def) {
    detail::linkMath(); // Box2D's sinf, cosf and atan2f: box2d_math.cpp
    validate(def);
    // A loaded snapshot brings the plugin back detached, in its place among the boundaries.
    for (const auto& plugin : world.boundaries()) {
        auto* bodies = dynamic_cast<BodyBoundary*>(plugin.get());
        if (bodies != nullptr && !bodies->attached()) {
            m_boundary = bodies;
            break;
        }
    }
    if (m_boundary == nullptr) {
        m_boundary = &static_cast<BodyBoundary&>(
            world.addBoundary(std::make_unique<BodyBoundary>()));
    }
    m_boundary->attach(&physics, &m_def);
    m_boundary->setContactBodies(&m_contactBodies);
}

void registerCouplingPlugin(Registry& registry) {
    registry.add(PluginInfo{std::string(BodyBoundary::kType), PluginKind::Boundary,
                            "Box2D bodies of a fluid::box2d::Coupling (snapshots only: detached "
                            "until a Coupling takes it over)",
                            {},
                            [] { return std::unique_ptr<Plugin>(new BodyBoundary()); }});
}

Coupling::~Coupling() {
    m_boundary->setContactBodies(nullptr);
    m_boundary->attach(nullptr, nullptr);
}

const CouplingDef& Coupling::def() const {
    return m_def;
}

void Coupling::setDef(const CouplingDef& def) {
    validate(def);
    m_def = def;
}

b2World& Coupling::physics() const {
    return *m_physics;
}

std::span<const BodyReport> Coupling::bodies() const {
    return m_reports;
}

const BodyReport* Coupling::report(const b2Body* body) const {
    for (const BodyReport& r : m_reports) {
        if (r.body == body) {
            return &r;
        }
    }
    return nullptr;
}

std::span<const SplashEvent> Coupling::splashes() const {
    return m_splashes;
}

std::span<const ContactEvent> Coupling::contacts() const {
    return m_contacts;
}

void Coupling::checkWorld(const World& world, const char* function) const {
    if (world.stepping()) {
        // A plugin's hook (or a Box2D callback it runs) stepping the coupling again: the nested
        // round would move the bodies and the fluid twice in one frame.
        throw Error(std::string("fluid::box2d::Coupling::") + function +
                        ": called during the world's own step (from a plugin's hook); the "
                        "coupling steps only between the world's steps",
                    ErrorCode::WrongState);
    }
    for (const auto& plugin : world.boundaries()) {
        if (plugin.get() == m_boundary) {
            return;
        }
    }
    throw Error(std::string("fluid::box2d::Coupling::") + function +
                    ": the world is not the one this coupling was made with",
                ErrorCode::BadArgument);
}

// Box2D divides by a dynamic body's mass and by its rotational inertia about its centre of mass
// (b2Body::m_I, which GetInertia reports about the body's origin); see kMinBodyMass.
void Coupling::checkBodies(const World& world, const char* function) const {
    const float spacing = coarsestSpacing(world), density = densestArealDensity(world);
    uint32_t index = 0;
    for (const b2Body* b = m_physics->GetBodyList(); b != nullptr; b = b->GetNext(), ++index) {
        if (b->GetType() != b2_dynamicBody) {
            continue;
        }
        const float mass = b->GetMass();
        const b2Vec2 c = b->GetLocalCenter();
        const float centred = b->GetInertia() - mass * b2Dot(c, c);
        const bool light = !(mass >= kMinBodyMass);
        if (light || (!b->IsFixedRotation() && centred > 0.0f && centred < kMinBodyInertia)) {
            std::ostringstream s;
            s << "fluid::box2d::Coupling::" << function << ": dynamic body " << index
              << " (in GetBodyList() order) has ";
            if (light) {
                s << "a mass of " << mass << " kg, less than kMinBodyMass (" << kMinBodyMass
                  << " kg)";
            } else {
                s << "a rotational inertia of " << centred
                  << " kg m^2 about its centre of mass, less than kMinBodyInertia ("
                  << kMinBodyInertia << " kg m^2)";
            }
            throw Error(s.str(), ErrorCode::OutOfRange);
        }
        // What the fluid throws (shapes.h): pointed polygons thinner than a spacing, bodies
        // lighter than kMinDensityRatio of the densest material, over their coupled fixtures.
        float area = 0.0f;
        ShapeProblem problem;
        for (const b2Fixture* f = b->GetFixtureList(); f != nullptr; f = f->GetNext()) {
            if ((f->GetFilterData().categoryBits & m_def.categoryMask) == 0) {
                continue;
            }
            const b2Shape* shape = f->GetShape();
            if (shape->GetType() == b2Shape::e_polygon && !problem) {
                const auto* polygon = static_cast<const b2PolygonShape*>(shape);
                std::vector<glm::vec2> v;
                for (int32 k = 0; k < polygon->m_count; ++k) {
                    v.emplace_back(polygon->m_vertices[k].x, polygon->m_vertices[k].y);
                }
                problem = checkPointedPolygon(v, spacing);
            }
            if (shape->GetType() == b2Shape::e_polygon || shape->GetType() == b2Shape::e_circle) {
                b2MassData unit;
                shape->ComputeMass(&unit, 1.0f);
                area += unit.mass;
            }
        }
        if (!problem && area > 0.0f) {
            problem = checkDynamicMass(mass, area, kMinBodyInertia, true, density);
        }
        if (problem) {
            std::ostringstream s;
            s << "fluid::box2d::Coupling::" << function << ": dynamic body " << index
              << " (in GetBodyList() order): " << problem.message;
            throw Error(s.str(), ErrorCode::OutOfRange);
        }
    }
}

void Coupling::startFrame(const World& world) {
    m_splashes.clear();
    m_contacts.clear();
    m_removed.clear();
    m_profile = Profile{};
    m_contactSums.clear();
    finishContacts(world);
    forgetDestroyedContactBodies();
}

void Coupling::step(World& world, float dt) {
    checkWorld(world, "step");
    checkBodies(world, "step");
    if (!(dt > 0.0f && dt <= 1.0f)) {
        const HostStep host(*m_boundary);
        world.step(dt); // throws World::step's own message, before Box2D moves anything
    }
    startFrame(world);
    if (world.def().solver != Solver::PositionBased) {
        // The explicit solver: kExplicitRounds rounds a 1/60 s frame, more for a longer one by
        // the long-frame rule (see the class comment), each in its own CFL sub-steps.
        const uint32_t rounds = frameSubsteps(kExplicitRounds, dt);
        const float h = dt / float(rounds);
        for (uint32_t round = 0; round < rounds; ++round) {
            m_physics->Step(h, m_def.velocityIterations, m_def.positionIterations);
            fluidRound(world, h, h);
        }
        return;
    }
    // The position-based solver: one round per sub-step the frame is due (World::substepsFor,
    // the world's carried time included), each a Box2D step and a world step of exactly one
    // sub-step of the fixed length; what is left of the frame, positive or negative, is
    // carried by the world, and Box2D's time with it. The first round's world step is the
    // sub-step less the time the world carried already, the last one's the sub-step plus what
    // the frame leaves (under half a sub-step either way: World::step rounds it to one).
    const uint32_t rounds = world.substepsFor(dt);
    if (rounds == 0) {
        const HostStep host(*m_boundary);
        world.step(dt); // under half a sub-step due: only carried
        return;
    }
    const double h = world.substepLength();
    const double rest = world.carriedTime() + double(dt) - double(rounds) * h;
    for (uint32_t round = 0; round < rounds; ++round) {
        m_physics->Step(float(h), m_def.velocityIterations, m_def.positionIterations);
        const double given = h - world.carriedTime() + (round + 1 == rounds ? rest : 0.0);
        // As a float, nudged by an ulp where its rounding would tip the world's rounding to
        // none or two sub-steps (a frame's rest of exactly half a sub-step).
        float step = float(std::max(given, 1e-9));
        while (world.substepsFor(step) == 0) {
            step = std::nextafter(step, 1.0f);
        }
        while (world.substepsFor(step) > 1) {
            step = std::nextafter(step, 0.0f);
        }
        fluidRound(world, step, float(h));
    }
}

void Coupling::stepFluid(World& world, float dt) {
    checkWorld(world, "stepFluid");
    checkBodies(world, "stepFluid");
    startFrame(world);
    // The time the world simulates: dt, or for the position-based solver the whole sub-steps
    // due (its carried time included).
    const bool positionBased = world.def().solver == Solver::PositionBased;
    const double simulated = positionBased ? double(world.substepsFor(dt)) * world.substepLength()
                                           : double(dt);
    fluidRound(world, dt, float(simulated));
}

std::span<const RemovedEvent> Coupling::removedEvents() const {
    return m_removed;
}

const Profile& Coupling::profile() const {
    return m_profile;
}

void Coupling::addProfile(const Profile& round) {
    Profile& p = m_profile;
    p.step += round.step;
    // Every round runs the same solver, so the same stages; a stage new to the frame (the
    // explicit solver's probe) is added after the others.
    for (const StageTime& t : round.stageTimes()) {
        uint32_t k = 0;
        while (k < p.stageCount && std::string_view(p.stages[k].name) != t.name) {
            ++k;
        }
        if (k == p.stageCount) {
            if (k == kMaxProfileStages) {
                continue;
            }
            p.stages[k].name = t.name;
            ++p.stageCount;
        }
        p.stages[k].ms += t.ms;
    }
    p.substeps += round.substeps;
    p.speedClamped += round.speedClamped;
    p.nonFiniteRepaired += round.nonFiniteRepaired;
    p.forceDropped += round.forceDropped;
    if (p.forceDroppedPlugin < 0) {
        p.forceDroppedPlugin = round.forceDroppedPlugin;
    }
    p.separated += round.separated;
    p.emitted += round.emitted;
    p.emitBlocked += round.emitBlocked;
    p.emitSkipped += round.emitSkipped;
    p.removed += round.removed;
    p.iterations = round.iterations;
    p.cflDt = round.cflDt;
    p.soundSpeed = round.soundSpeed;
    p.densityErrorMax = round.densityErrorMax;
    p.densityErrorAvg = round.densityErrorAvg;
    p.particles = round.particles;
}

void Coupling::fluidRound(World& world, float given, float simulated) {
    std::vector<double> masses(world.materialCount());
    for (std::size_t k = 0; k < masses.size(); ++k) {
        masses[k] = world.material(MaterialId{uint16_t(k)}).mass;
    }
    m_boundary->setMaterialMasses(std::move(masses));
    {
        const HostStep host(*m_boundary);
        world.step(given);
    }
    if (world.lastSubsteps() == 0) {
        return; // the frame only added to the world's carried time: nothing moved
    }
    const float dt = simulated;
    applyCorrections();
    addProfile(world.profile());
    const std::span<const RemovedEvent> removed = world.removedEvents();
    m_removed.insert(m_removed.end(), removed.begin(), removed.end());
    makeReports(world);
    if (!m_contactBodies.empty()) {
        collectContacts(world, dt);
        finishContacts(world);
    }
    applyForces(dt);
    remember();
}

// The coarse pressure solve moved each dynamic body with the fluid during the step (see
// RigidBodyImpulse): the body takes the velocity change and the displacement, so that Box2D goes
// on from where the fluid left it. The seen pose already moved (BodyBoundary::
// receiveBodyImpulses), so the next step does not sweep the body over the correction again.
void Coupling::applyCorrections() {
    for (const BodyEntry& entry : m_boundary->bodies()) {
        const RigidBodyImpulse& c = entry.coarse;
        b2Body* body = entry.body;
        const float mass = body->GetMass();
        if (entry.type != b2_dynamicBody || !(mass > 0.0f) ||
            (c.impulse.x == 0.0f && c.impulse.y == 0.0f && c.displacement.x == 0.0f &&
             c.displacement.y == 0.0f)) {
            continue;
        }
        body->SetLinearVelocity(body->GetLinearVelocity() +
                                b2Vec2(c.impulse.x / mass, c.impulse.y / mass));
        body->SetTransform(body->GetPosition() + b2Vec2(c.displacement.x, c.displacement.y),
                           body->GetAngle());
    }
}

void Coupling::applyForces(float dt) {
    const std::span<const BodyEntry> bodies = m_boundary->bodies();
    std::unordered_map<const b2Body*, const Previous*> previous; // lookup only
    for (const Previous& p : m_previous) {
        previous.emplace(p.body, &p);
    }
    m_debt.assign(bodies.size(), glm::dvec2(0.0, 0.0));
    m_torqueDebt.assign(bodies.size(), 0.0);
    m_applied.assign(bodies.size(), glm::vec2(0.0f, 0.0f));
    m_appliedTorque.assign(bodies.size(), 0.0f);
    const double h = dt;
    for (std::size_t b = 0; b < bodies.size(); ++b) {
        const BodyEntry& entry = bodies[b];
        if (entry.type != b2_dynamicBody) {
            continue;
        }
        if (!std::isfinite(entry.force.x) || !std::isfinite(entry.force.y) ||
            !std::isfinite(entry.torque)) {
            continue; // never hand Box2D a NaN: it would spread through every contact
        }
        // The relaxation for added mass and drag (see the class comment).
        const auto found = previous.find(entry.body);
        const double mass = entry.body->GetMass();
        const glm::dvec2 center{entry.body->GetLocalCenter().x, entry.body->GetLocalCenter().y};
        const double inertia =
            entry.body->GetInertia() - mass * (center.x * center.x + center.y * center.y);
        const double added = m_addedMass[b];
        const double w = mass / (mass + added + h * entry.drag);
        const double wr = inertia > 0.0
                              ? inertia / (inertia * (1.0 + added / mass) + h * entry.angularDrag)
                              : 1.0;
        // Hydrostatic part, from this step's submerged area: it follows the body's position
        // at once (relaxing it too would delay the buoyancy spring and pump energy into a
        // floating body's bobbing).
        const b2Vec2 g2 = m_physics->GetGravity();
        const glm::dvec2 buoyancy =
            -m_displaced[b] * double(entry.body->GetGravityScale()) * glm::dvec2(g2.x, g2.y);
        // The rest (added mass, drag, waves) joins what is owed from earlier steps, and a share
        // w of the debt is paid now: what the fluid took, the body gives, however w changes
        // from step to step.
        glm::dvec2 owed = (found != previous.end() ? found->second->debt : glm::dvec2(0.0)) +
                          h * (entry.force - buoyancy);
        const double torqueOwed =
            (found != previous.end() ? found->second->torqueDebt : 0.0) + h * entry.torque;
        // But never more against the body's motion than its momentum: the fluid held the
        // body's sweep velocity for the whole step (the body is as heavy as the world there),
        // so a light body slammed into it has pushed more fluid than it could have; that
        // excess would throw the body back out (a crate dropped onto water bounced off). It
        // is dropped, in full from twice the speed one round of gravity gives and not at all
        // below once it: a body at rest is owed a steady force against its buoyancy's count
        // (the coarse solve carries most of its weight), and cut whenever its speed of a few
        // tenths of a millimetre a second pointed the other way, that force kicked it
        // (docs/notes/bodies_coarse_solve.md, "What else shook a body at rest").
        const b2Vec2 v2 = entry.body->GetLinearVelocity();
        const glm::dvec2 v(v2.x, v2.y);
        const double speed = std::sqrt(v.x * v.x + v.y * v.y);
        const double fall = h * std::sqrt(double(g2.x) * g2.x + double(g2.y) * g2.y);
        const double share = fall > 0.0 ? std::clamp(speed / fall - 1.0, 0.0, 1.0) : 1.0;
        if (speed > 0.0 && share > 0.0) {
            const glm::dvec2 u = v / speed;
            const double against = -(owed.x * u.x + owed.y * u.y);
            if (against > mass * speed) {
                owed += share * (against - mass * speed) * u;
            }
        }
        const glm::dvec2 dynamic = w * owed / h;
        const double torque = wr * torqueOwed / h;
        m_debt[b] = owed - h * dynamic;
        m_torqueDebt[b] = torqueOwed - h * torque;
        const glm::dvec2 f = buoyancy + dynamic;
        m_applied[b] = glm::vec2(float(f.x), float(f.y));
        m_appliedTorque[b] = float(torque);
        if (f.x != 0.0 || f.y != 0.0) {
            entry.body->ApplyForce(b2Vec2(m_applied[b].x, m_applied[b].y),
                                   entry.body->GetWorldCenter(), true);
        }
        if (torque != 0.0) {
            entry.body->ApplyTorque(m_appliedTorque[b], true);
        }
    }
}

void Coupling::remember() {
    m_previous.clear();
    for (std::size_t b = 0; b < m_reports.size(); ++b) {
        const BodyReport& r = m_reports[b];
        m_previous.push_back({r.body, r.wetPoints > 0, r.material, m_debt[b], m_torqueDebt[b],
                              m_applied[b], m_appliedTorque[b]});
    }
}

void Coupling::makeReports(const World& world) {
    const std::span<const BodyEntry> bodies = m_boundary->bodies();
    const std::span<const Collider> colliders = m_boundary->colliders();
    const double spacing = m_boundary->spacing();
    const double wetRadius = 0.75 * spacing;

    // Each collider's probes in the world, at the bodies' poses now.
    std::vector<uint32_t> probeBegin(colliders.size() + 1, 0);
    for (std::size_t k = 0; k < colliders.size(); ++k) {
        probeBegin[k + 1] =
            probeBegin[k] + uint32_t(m_boundary->entry(colliders[k].entry).probes.size());
    }
    std::vector<uint8_t> wet(probeBegin.back(), 0);
    std::vector<uint16_t> wetMaterial(probeBegin.back(), 0);
    struct Frame {
        glm::dvec2 com{0.0, 0.0};
        double c = 1.0, s = 0.0;
    };
    // Where the fluid's step left each body: its start pose moved on by its velocities.
    const double frameDt = m_boundary->frameDt();
    std::vector<Frame> frames(bodies.size());
    for (std::size_t b = 0; b < bodies.size(); ++b) {
        const BodyEntry& e = bodies[b];
        const double angle = e.angle + e.omega * frameDt;
        frames[b] = {e.com + frameDt * e.velocity + glm::dvec2(e.coarse.displacement),
                     detail::cos(angle), detail::sin(angle)};
    }
    std::vector<Box> boxes(colliders.size());
    for (std::size_t k = 0; k < colliders.size(); ++k) {
        const Frame& f = frames[colliders[k].body];
        glm::dvec2 lo(1e300), hi(-1e300);
        for (const glm::dvec2 p : m_boundary->entry(colliders[k].entry).probes) {
            const glm::dvec2 w = f.com + glm::dvec2(f.c * p.x - f.s * p.y, f.s * p.x + f.c * p.y);
            lo = glm::min(lo, w);
            hi = glm::max(hi, w);
        }
        boxes[k] = {float(lo.x - wetRadius), float(lo.y - wetRadius), float(hi.x + wetRadius),
                    float(hi.y + wetRadius)};
    }
    BoxGrid grid;
    grid.build(boxes, float(std::max(8.0 * spacing, 0.1)));

    // Every particle marks the probes within wetRadius of it (the first, in slot order, names
    // the material).
    const std::span<const float> px = world.positionX(), py = world.positionY();
    const std::span<const uint16_t> material = world.materialIndex();
    const double r2 = wetRadius * wetRadius;
    for (uint32_t i = 0; i < px.size(); ++i) {
        const Box point{px[i], py[i], px[i], py[i]};
        grid.forEach(point, boxes, [&](uint32_t k) {
            const FixtureEntry& entry = m_boundary->entry(colliders[k].entry);
            const Frame& f = frames[colliders[k].body];
            const glm::dvec2 d = glm::dvec2(px[i], py[i]) - f.com;
            const glm::dvec2 local(f.c * d.x + f.s * d.y, -f.s * d.x + f.c * d.y);
            const glm::i64vec2 cell = probeCellOf(local, entry.probeCell);
            const int64_t ix = cell.x, iy = cell.y;
            const auto mark = [&](uint32_t probe) {
                const glm::dvec2 e = entry.probes[probe] - local;
                const uint32_t slot = probeBegin[k] + probe;
                if (e.x * e.x + e.y * e.y <= r2 && wet[slot] == 0) {
                    wet[slot] = 1;
                    wetMaterial[slot] = material[i];
                }
            };
            if (entry.probeColumns > 0) {
                // The table: per column, its three cells' probes are one range.
                const int64_t y0 = std::max(iy - 1, entry.probeY0) - entry.probeY0;
                const int64_t y1 = std::min(iy + 1, entry.probeY0 + entry.probeRows - 1) -
                                   entry.probeY0;
                const int64_t x0 = std::max(ix - 1, entry.probeX0) - entry.probeX0;
                const int64_t x1 = std::min(ix + 1, entry.probeX0 + entry.probeColumns - 1) -
                                   entry.probeX0;
                for (int64_t cx = x0; y0 <= y1 && cx <= x1; ++cx) {
                    const size_t c = size_t(cx * entry.probeRows);
                    for (uint32_t n = entry.probeStart[c + size_t(y0)];
                         n < entry.probeStart[c + size_t(y1) + 1]; ++n) {
                        mark(entry.probeCells[n].second);
                    }
                }
                return;
            }
            for (int64_t cx = ix - 1; cx <= ix + 1; ++cx) {
                for (int64_t cy = iy - 1; cy <= iy + 1; ++cy) {
                    const int64_t key = cellKey({cx, cy});
                    auto it =
                        std::lower_bound(entry.probeCells.begin(), entry.probeCells.end(), key,
                                         [](const std::pair<int64_t, uint32_t>& a, int64_t b) {
                                             return a.first < b;
                                         });
                    for (; it != entry.probeCells.end() && it->first == key; ++it) {
                        mark(it->second);
                    }
                }
            }
        });
    }

    // Reports, in body order.
    m_reports.assign(bodies.size(), BodyReport{});
    m_addedMass.assign(bodies.size(), 0.0);
    m_displaced.assign(bodies.size(), 0.0);
    std::vector<uint32_t> counts;
    for (std::size_t b = 0; b < bodies.size(); ++b) {
        const BodyEntry& entry = bodies[b];
        BodyReport& r = m_reports[b];
        r.body = entry.body;
        // The sweeps' forces and the coarse solve's impulse over the step.
        const double invDt = frameDt > 0.0 ? 1.0 / frameDt : 0.0;
        r.force = glm::vec2(entry.force + invDt * glm::dvec2(entry.coarse.impulse));
        r.torque = float(entry.torque);
        double area = 0.0, submerged = 0.0, chords = 0.0;
        counts.clear();
        for (uint32_t k = entry.colliderBegin; k < entry.colliderEnd; ++k) {
            const FixtureEntry& fixture = m_boundary->entry(colliders[k].entry);
            const std::span<const uint8_t> flags(wet.data() + probeBegin[k],
                                                 probeBegin[k + 1] - probeBegin[k]);
            for (uint32_t p = probeBegin[k]; p < probeBegin[k + 1]; ++p) {
                if (wet[p] != 0) {
                    ++r.wetPoints;
                    if (counts.size() <= wetMaterial[p]) {
                        counts.resize(std::size_t(wetMaterial[p]) + 1, 0);
                    }
                    ++counts[wetMaterial[p]];
                }
            }
            if (fixture.area > 0.0) {
                double chord = 0.0;
                area += fixture.area;
                submerged += submergedArea(fixture, flags, spacing, chord);
                chords += chord * chord;
            }
        }
        r.submergedArea = float(submerged);
        r.submergedFraction = area > 0.0 ? float(std::clamp(submerged / area, 0.0, 1.0)) : 0.0f;
        if (!counts.empty()) {
            r.material = world.adopt(MaterialId{
                uint16_t(std::max_element(counts.begin(), counts.end()) - counts.begin())});
        }
        // The added mass the relaxation assumes (see the class comment): the submerged area's,
        // or, entering the fluid, a plate's as wide as the wet chord at a free surface. None in
        // a paste (a material with a yield stress): it does not flow around the body, it holds
        // it on its elastic strain, a spring that relaxing would delay and so pump (a crate
        // resting on yoghurt shook at 14 Hz, docs/box2d.md "Why the force is relaxed").
        if (r.wetPoints > 0 && r.material.index < world.materialCount()) {
            const double rho = arealDensity(world, r.material);
            const bool paste = world.material(r.material).yieldStress > 0.0f;
            m_addedMass[b] =
                paste ? 0.0 : rho * std::max(submerged, std::numbers::pi / 8.0 * chords);
            m_displaced[b] = rho * submerged;
        }
    }

    // Events: bodies that changed state since the previous step, in body order; then bodies
    // that were wet and are no longer coupled (still in the b2World: destroyed ones say
    // nothing, their address may already be another body's).
    std::unordered_map<const b2Body*, const Previous*> previous; // lookup only
    for (const Previous& p : m_previous) {
        previous.emplace(p.body, &p);
    }
    std::unordered_set<const b2Body*> current; // lookup only
    for (std::size_t b = 0; b < bodies.size(); ++b) {
        const BodyReport& r = m_reports[b];
        current.insert(r.body);
        const auto found = previous.find(r.body);
        const bool wasWet = found != previous.end() && found->second->wet;
        const bool isWet = r.wetPoints > 0;
        if (!wasWet && isWet) {
            m_contacts.push_back({r.body, ContactPhase::Begin, r.material});
            const double speed = std::sqrt(bodies[b].velocity.x * bodies[b].velocity.x +
                                           bodies[b].velocity.y * bodies[b].velocity.y);
            if (speed > m_def.splashSpeed) {
                glm::dvec2 sum{0.0, 0.0};
                const Frame& f = frames[b];
                for (uint32_t k = bodies[b].colliderBegin; k < bodies[b].colliderEnd; ++k) {
                    const FixtureEntry& fixture = m_boundary->entry(colliders[k].entry);
                    for (uint32_t p = 0; p < fixture.probes.size(); ++p) {
                        if (wet[probeBegin[k] + p] != 0) {
                            const glm::dvec2 q = fixture.probes[p];
                            sum += f.com + glm::dvec2(f.c * q.x - f.s * q.y, f.s * q.x + f.c * q.y);
                        }
                    }
                }
                const glm::dvec2 at = sum / double(r.wetPoints);
                m_splashes.push_back({r.body, glm::vec2(at), float(speed), r.material});
            }
        } else if (wasWet && !isWet) {
            m_contacts.push_back({r.body, ContactPhase::End, found->second->material});
        }
    }
    bool anyGone = false;
    for (const Previous& p : m_previous) {
        anyGone = anyGone || (p.wet && current.count(p.body) == 0);
    }
    if (anyGone) {
        std::unordered_set<const b2Body*> alive; // lookup only
        for (const b2Body* body = m_physics->GetBodyList(); body != nullptr;
             body = body->GetNext()) {
            alive.insert(body);
        }
        for (const Previous& p : m_previous) {
            if (p.wet && current.count(p.body) == 0 && alive.count(p.body) != 0) {
                m_contacts.push_back({p.body, ContactPhase::End, p.material});
            }
        }
    }
}

namespace {
constexpr char kStateMagic[8] = {'F', 'L', 'C', 'O', 'U', 'P', 'L', 'E'};
// 2: the bodies that ask for contact events follow the poses (a version-1 save has none).
constexpr uint32_t kStateVersion = 2;
// Bounds of a saved body state, from the live limits: a coupled body is at most 1e5 m from the
// origin and at most 1e3 m/s fast (BodyBoundary: faster or farther bodies are skipped), and of
// at most 1e9 kg (the fluid's RigidBody::mass). The momentum such a body can hold bounds what
// the relaxation owes it (unit: N s), with the lever arm its angular impulse (unit: N m s);
// paid over the shortest frame, 1 ms (a level's frame rate is at most 1000 Hz), they bound the
// force and torque handed to Box2D (unit: N, N m). Past these a body turns NaN at its first
// step. The seen angle is a Box2D body angle (a float; unit: rad).
constexpr double kMaxPosition = 1e5;
constexpr double kMaxImpulse = 1e9 * 1e3;
constexpr double kMaxAngularImpulse = kMaxImpulse * kMaxPosition;
constexpr double kMaxForce = kMaxImpulse / 1e-3;
constexpr double kMaxTorque = kMaxAngularImpulse / 1e-3;
constexpr double kMaxAngle = 3.4e38;
} // namespace

void Coupling::save(std::ostream& out) const {
    std::unordered_map<const b2Body*, uint32_t> index; // lookup only
    for (const b2Body* b = m_physics->GetBodyList(); b != nullptr; b = b->GetNext()) {
        index.emplace(b, uint32_t(index.size()));
    }
    internal::StreamWriter w(out);
    out.write(kStateMagic, sizeof(kStateMagic));
    w.put(kStateVersion);
    // Bodies destroyed since the last frame are left out.
    uint32_t kept = 0;
    for (const Previous& p : m_previous) {
        kept += index.count(p.body) != 0 ? 1 : 0;
    }
    w.put(kept);
    for (const Previous& p : m_previous) {
        const auto found = index.find(p.body);
        if (found == index.end()) {
            continue;
        }
        w.put(found->second);
        w.put(uint8_t(p.wet ? 1 : 0));
        w.put(p.material.index);
        w.put(p.debt.x);
        w.put(p.debt.y);
        w.put(p.torqueDebt);
        w.put(p.applied.x);
        w.put(p.applied.y);
        w.put(p.appliedTorque);
    }
    const std::vector<BodyBoundary::SeenPose> poses = m_boundary->seenPoses();
    w.put(uint32_t(poses.size()));
    for (const BodyBoundary::SeenPose& p : poses) {
        w.put(index.at(p.body));
        w.put(p.com.x);
        w.put(p.com.y);
        w.put(p.angle);
    }
    std::vector<uint32_t> asking;
    for (const b2Body* b = m_physics->GetBodyList(); b != nullptr; b = b->GetNext()) {
        if (m_contactBodies.count(b) != 0) {
            asking.push_back(index.at(b));
        }
    }
    w.put(uint32_t(asking.size()));
    for (const uint32_t k : asking) {
        w.put(k);
    }
    if (!out) {
        throw Error("fluid::box2d::Coupling::save: the stream failed while writing", ErrorCode::Io);
    }
}

void Coupling::load(std::istream& in) {
    std::vector<b2Body*> bodies;
    for (b2Body* b = m_physics->GetBodyList(); b != nullptr; b = b->GetNext()) {
        bodies.push_back(b);
    }
    internal::StreamReader r(in, "coupling save");
    char magic[sizeof(kStateMagic)];
    if (!in.read(magic, sizeof(magic)) || std::memcmp(magic, kStateMagic, sizeof(magic)) != 0) {
        r.fail("not a coupling save (bad magic)");
    }
    const auto version = r.get<uint32_t>("version");
    if (version != 1 && version != kStateVersion) {
        r.fail("version " + std::to_string(version) + " is not supported (this build reads 1 and " +
               std::to_string(kStateVersion) + ")");
    }
    const auto bodyIndex = [&](const char* field) {
        const auto k = r.get<uint32_t>(field);
        if (k >= bodies.size()) {
            r.fail(std::string(field) + " " + std::to_string(k) + " is beyond the Box2D world's " +
                   std::to_string(bodies.size()) + " bodies");
        }
        return k;
    };
    std::vector<Previous> previous(r.count("body state count", uint32_t(bodies.size())));
    for (Previous& p : previous) {
        const uint32_t k = bodyIndex("body index");
        p.body = bodies[k];
        const std::string of = "body " + std::to_string(k) + " ";
        const auto wet = r.get<uint8_t>("wet flag");
        if (wet > 1) {
            r.fail(of + "wet flag = " + std::to_string(wet) + " is not 0 or 1");
        }
        p.wet = wet != 0;
        p.material = MaterialId{r.get<uint16_t>("material")};
        p.debt.x = r.number(of + "debt x", -kMaxImpulse, kMaxImpulse, "N s");
        p.debt.y = r.number(of + "debt y", -kMaxImpulse, kMaxImpulse, "N s");
        p.torqueDebt = r.number(of + "torque debt", -kMaxAngularImpulse, kMaxAngularImpulse,
                                "N m s");
        const auto force = float(kMaxForce), torque = float(kMaxTorque);
        p.applied.x = r.number(of + "applied force x", -force, force, "N");
        p.applied.y = r.number(of + "applied force y", -force, force, "N");
        p.appliedTorque = r.number(of + "applied torque", -torque, torque, "N m");
    }
    std::vector<BodyBoundary::SeenPose> poses(r.count("pose count", uint32_t(bodies.size())));
    for (BodyBoundary::SeenPose& p : poses) {
        const uint32_t k = bodyIndex("posed body index");
        p.body = bodies[k];
        const std::string of = "body " + std::to_string(k) + " seen ";
        p.com.x = r.number(of + "x", -kMaxPosition, kMaxPosition, "m");
        p.com.y = r.number(of + "y", -kMaxPosition, kMaxPosition, "m");
        p.angle = r.number(of + "angle", -kMaxAngle, kMaxAngle, "rad");
    }
    std::unordered_set<const b2Body*> asking;
    if (version >= 2) {
        const uint32_t count = r.count("contact body count", uint32_t(bodies.size()));
        for (uint32_t k = 0; k < count; ++k) {
            asking.insert(bodies[bodyIndex("contact body index")]);
        }
    }
    // Everything read: now the coupling changes.
    m_contactBodies = std::move(asking);
    m_previous = std::move(previous);
    m_boundary->setSeenPoses(poses);
    m_reports.clear();
    m_splashes.clear();
    m_contacts.clear();
    m_removed.clear();
    m_profile = Profile{};
    m_contactSums.clear();
    m_particleContacts.clear();
    m_contactHandles.clear();
    m_contactBegin.assign(1, 0);
    // A Box2D world restored by loadPhysics from a version-2 save carries the forces Box2D has
    // accumulated (these among them): adding them again would double them. A world without any
    // (a version-1 save, a world rebuilt by hand) gets them here.
    for (const Previous& p : m_previous) {
        if (p.body->GetType() != b2_dynamicBody) {
            continue;
        }
        if (detail::carriesForce(*p.body)) {
            continue;
        }
        if (p.applied.x != 0.0f || p.applied.y != 0.0f) {
            p.body->ApplyForce(b2Vec2(p.applied.x, p.applied.y), p.body->GetWorldCenter(), true);
        }
        if (p.appliedTorque != 0.0f) {
            p.body->ApplyTorque(p.appliedTorque, true);
        }
    }
}

} // namespace fluid::box2d
