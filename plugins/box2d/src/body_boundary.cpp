// fluid::box2d — Box2D fixtures as fluid boundaries: sampling, projection, forces.
#include "body_boundary.h"

#include "box2d_math.h"

#include <fluid/error.h>
#include <fluid/plugins/chain.h>
#include <fluid/plugins/circle.h>
#include <fluid/plugins/polygon.h>

#include <box2d/box2d.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

namespace fluid::box2d {

namespace {

enum Kind : int { kCircle = 0, kPolygon = 1, kEdge = 2, kChain = 3 };

// Largest |position| (unit: m) and |velocity| (unit: m/s, rad/s) of a coupled body: the range of
// the shapes' pose parameters (see KinematicShape::kPoseParams).
constexpr double kMaxPosition = 1e5;
constexpr double kMaxSpeed = 1e3;
// A body whose pose moved this much further than its velocity says since the fluid last saw it
// (unit: sample spacings; rad) was moved by hand: Box2D's own position correction of contacts
// stays well under it.
constexpr double kJump = 2.0;
constexpr double kJumpAngle = 0.2;

glm::dvec2 toVec(b2Vec2 v) {
    return {double(v.x), double(v.y)};
}

glm::dvec2 rotate(glm::dvec2 v, double c, double s) {
    return {c * v.x - s * v.y, s * v.x + c * v.y};
}

// Points along a -> b at most `spacing` apart, a included, b not.
void addEdgeProbes(glm::dvec2 a, glm::dvec2 b, double spacing, std::vector<glm::dvec2>& out) {
    const double length = std::sqrt((b.x - a.x) * (b.x - a.x) + (b.y - a.y) * (b.y - a.y));
    const int n = std::max(1, static_cast<int>(std::ceil(length / spacing)));
    for (int k = 0; k < n; ++k) {
        const double t = double(k) / double(n);
        out.push_back(a + t * (b - a));
    }
}

std::string where(uint32_t bodyIndex, uint32_t fixtureIndex) {
    return "box2d.bodies: body " + std::to_string(bodyIndex) +
           " (in b2World::GetBodyList order) fixture " + std::to_string(fixtureIndex) + ": ";
}

} // namespace

double shoelace(std::span<const glm::dvec2> points) {
    double twice = 0.0;
    for (std::size_t k = 0; k < points.size(); ++k) {
        const glm::dvec2 a = points[k], b = points[(k + 1) % points.size()];
        twice += a.x * b.y - a.y * b.x;
    }
    return 0.5 * twice;
}

// ---- BoxGrid ------------------------------------------------------------------------------

void BoxGrid::build(std::span<const Box> boxes, float cellSize) {
    m_cellsX = m_cellsY = 0;
    m_start.clear();
    m_entries.clear();
    if (boxes.empty()) {
        return;
    }
    m_bounds = boxes[0];
    for (const Box& b : boxes) {
        m_bounds.loX = std::min(m_bounds.loX, b.loX);
        m_bounds.loY = std::min(m_bounds.loY, b.loY);
        m_bounds.hiX = std::max(m_bounds.hiX, b.hiX);
        m_bounds.hiY = std::max(m_bounds.hiY, b.hiY);
    }
    constexpr float kMaxCells = 256.0f;
    const float extent = std::max(m_bounds.hiX - m_bounds.loX, m_bounds.hiY - m_bounds.loY);
    const float cell = std::max(cellSize, extent / kMaxCells);
    m_invCell = 1.0f / cell;
    m_cellsX = static_cast<uint32_t>(
        std::clamp(std::ceil((m_bounds.hiX - m_bounds.loX) * m_invCell), 1.0f, kMaxCells));
    m_cellsY = static_cast<uint32_t>(
        std::clamp(std::ceil((m_bounds.hiY - m_bounds.loY) * m_invCell), 1.0f, kMaxCells));
    m_start.assign(std::size_t(m_cellsX) * m_cellsY + 1, 0);
    // Count, prefix-sum, fill: each cell's list in box order.
    for (int pass = 0; pass < 2; ++pass) {
        std::vector<uint32_t> fill;
        if (pass == 1) {
            for (std::size_t c = 1; c < m_start.size(); ++c) {
                m_start[c] += m_start[c - 1];
            }
            m_entries.resize(m_start.back());
            fill.assign(m_start.begin(), m_start.end() - 1);
        }
        for (uint32_t index = 0; index < boxes.size(); ++index) {
            const Box& b = boxes[index];
            for (int y = cellY(b.loY); y <= cellY(b.hiY); ++y) {
                for (int x = cellX(b.loX); x <= cellX(b.hiX); ++x) {
                    const uint32_t cellIndex = uint32_t(y) * m_cellsX + uint32_t(x);
                    if (pass == 0) {
                        ++m_start[cellIndex + 1];
                    } else {
                        m_entries[fill[cellIndex]++] = index;
                    }
                }
            }
        }
    }
}

// ---- BodyBoundary -------------------------------------------------------------------------

BodyBoundary::BodyBoundary() : BoundaryPlugin(kType, {}) {}

BodyBoundary::~BodyBoundary() = default;

void BodyBoundary::attach(b2World* physics, const CouplingDef* def) {
    m_physics = physics;
    m_def = def;
    if (physics == nullptr) {
        m_samples.clear();
        m_bodies.clear();
        m_colliders.clear();
        m_boxes.clear();
        m_sweepPose = SweepPose{};
        m_grid.build({}, 1.0f);
    }
}

float BodyBoundary::friction() const {
    return m_def != nullptr ? m_def->friction : 0.0f;
}

const char* BodyBoundary::steppedBy() const {
    return m_physics != nullptr && !m_hostStepping
               ? "fluid::box2d::Coupling::step (a level: fluid::Level::step)"
               : nullptr;
}

bool BodyBoundary::contains(glm::vec2 point) const {
    if (m_physics == nullptr) {
        return false;
    }
    const b2Vec2 p(point.x, point.y);
    for (const b2Body* body = m_physics->GetBodyList(); body != nullptr; body = body->GetNext()) {
        for (const b2Fixture* f = body->GetFixtureList(); f != nullptr; f = f->GetNext()) {
            if (couples(*f) && f->TestPoint(p)) {
                return true;
            }
        }
    }
    return false;
}

bool BodyBoundary::couples(const b2Fixture& fixture) const {
    if (fixture.IsSensor()) {
        return false;
    }
    if ((fixture.GetFilterData().categoryBits & m_def->categoryMask) == 0) {
        return false;
    }
    return !m_def->filter || m_def->filter(fixture);
}

uint32_t BodyBoundary::findOrBuild(b2Fixture& fixture, const glm::dvec2& localCenter,
                                   uint32_t bodyIndex, uint32_t fixtureIndex) {
    // The geometry in the centre-of-mass frame, as numbers.
    std::vector<float> signature;
    std::vector<glm::dvec2> points; // outline in the centre-of-mass frame
    glm::dvec2 offset{0.0, 0.0};
    double radius = 0.0;
    bool closed = false;
    const b2Shape* shape = fixture.GetShape();
    switch (shape->GetType()) {
    case b2Shape::e_circle: {
        const auto* circle = static_cast<const b2CircleShape*>(shape);
        radius = circle->m_radius;
        offset = toVec(circle->m_p) - localCenter;
        signature = {float(kCircle), float(radius), float(offset.x), float(offset.y)};
        closed = true;
        break;
    }
    case b2Shape::e_polygon: {
        const auto* polygon = static_cast<const b2PolygonShape*>(shape);
        signature = {float(kPolygon)};
        for (int32 k = 0; k < polygon->m_count; ++k) {
            points.push_back(toVec(polygon->m_vertices[k]) - localCenter);
        }
        closed = true;
        break;
    }
    case b2Shape::e_edge: {
        const auto* edge = static_cast<const b2EdgeShape*>(shape);
        signature = {float(kEdge)};
        points = {toVec(edge->m_vertex1) - localCenter, toVec(edge->m_vertex2) - localCenter};
        break;
    }
    case b2Shape::e_chain: {
        const auto* chain = static_cast<const b2ChainShape*>(shape);
        signature = {float(kChain)};
        int32 count = chain->m_count;
        // b2ChainShape::CreateLoop repeats the first vertex at the end.
        if (count >= 4 && chain->m_vertices[0] == chain->m_vertices[count - 1]) {
            closed = true;
            --count;
        }
        for (int32 k = 0; k < count; ++k) {
            points.push_back(toVec(chain->m_vertices[k]) - localCenter);
        }
        signature.push_back(closed ? 1.0f : 0.0f);
        break;
    }
    default:
        throw Error(where(bodyIndex, fixtureIndex) + "unknown Box2D shape type " +
                        std::to_string(int(shape->GetType())),
                    ErrorCode::BadArgument);
    }
    for (const glm::dvec2 p : points) {
        signature.push_back(float(p.x));
        signature.push_back(float(p.y));
    }

    const auto found = m_index.find(&fixture);
    if (found != m_index.end() && m_entries[found->second].signature == signature) {
        m_entries[found->second].seen = true;
        return found->second;
    }

    FixtureEntry entry;
    entry.fixture = &fixture;
    entry.signature = std::move(signature);
    entry.offset = offset;
    entry.closed = closed;
    std::vector<glm::vec2> vertices(points.size());
    std::transform(points.begin(), points.end(), vertices.begin(),
                   [](glm::dvec2 p) { return glm::vec2(p); });
    try {
        if (shape->GetType() == b2Shape::e_circle) {
            auto circle = std::make_unique<CircleBoundary>();
            circle->setParam("radius", radius);
            entry.shape = std::move(circle);
            entry.area = std::numbers::pi * radius * radius;
        } else if (shape->GetType() == b2Shape::e_polygon) {
            auto polygon = std::make_unique<PolygonBoundary>();
            polygon->setPoints("vertices", vertices);
            entry.shape = std::move(polygon);
            entry.area = std::fabs(shoelace(points));
        } else {
            auto chain = std::make_unique<ChainBoundary>();
            chain->setParam("closed", closed ? 1.0 : 0.0);
            chain->setPoints("points", vertices);
            entry.shape = std::move(chain);
        }
    } catch (const Error& e) {
        throw Error(where(bodyIndex, fixtureIndex) + e.what(), e.code());
    }
    entry.outline = std::move(points);
    entry.radius = radius;
    entry.seen = true;
    if (found != m_index.end()) {
        m_entries[found->second] = std::move(entry);
        return found->second;
    }
    m_entries.push_back(std::move(entry));
    m_index.emplace(&fixture, uint32_t(m_entries.size() - 1));
    return uint32_t(m_entries.size() - 1);
}

namespace {

// Lays the outline probes of `entry` at `spacing` and sorts them into cells of `cell`.
void layProbes(FixtureEntry& entry, double spacing, double cell) {
    entry.probes.clear();
    if (entry.radius > 0.0) {
        const int n = std::max(
            8, static_cast<int>(std::ceil(2.0 * std::numbers::pi * entry.radius / spacing)));
        for (int k = 0; k < n; ++k) {
            const double a = 2.0 * std::numbers::pi * double(k) / double(n);
            entry.probes.push_back(entry.offset +
                                   entry.radius * glm::dvec2(detail::cos(a), detail::sin(a)));
        }
    } else {
        const std::vector<glm::dvec2>& outline = entry.outline;
        const std::size_t edges = entry.closed ? outline.size() : outline.size() - 1;
        for (std::size_t k = 0; k < edges; ++k) {
            addEdgeProbes(outline[k], outline[(k + 1) % outline.size()], spacing, entry.probes);
        }
        if (!entry.closed) {
            entry.probes.push_back(outline.back());
        }
    }
    entry.probeArea = entry.closed ? std::fabs(shoelace(entry.probes)) : 0.0;
    entry.probeCells.clear();
    entry.probeStart.clear();
    entry.probeColumns = entry.probeRows = 0;
    const int64_t most = std::numeric_limits<int64_t>::max();
    glm::i64vec2 lo(most), hi(-most);
    std::vector<glm::i64vec2> cells(entry.probes.size());
    for (uint32_t k = 0; k < entry.probes.size(); ++k) {
        cells[k] = probeCellOf(entry.probes[k], cell);
        lo = glm::min(lo, cells[k]);
        hi = glm::max(hi, cells[k]);
        entry.probeCells.emplace_back(cellKey(cells[k]), k);
    }
    std::sort(entry.probeCells.begin(), entry.probeCells.end());
    // The table over the probes' box of cells, when it stays within a few cells per probe.
    if (!entry.probes.empty()) {
        const int64_t columns = hi.x - lo.x + 1, rows = hi.y - lo.y + 1;
        // (In double: a chain thousands of kilometres long must not wrap the product.)
        if (double(columns) * double(rows) <= 16.0 * double(entry.probes.size()) + 1024.0) {
            entry.probeX0 = lo.x;
            entry.probeY0 = lo.y;
            entry.probeColumns = columns;
            entry.probeRows = rows;
            entry.probeStart.assign(size_t(columns * rows) + 1, 0);
            for (const glm::i64vec2 c : cells) {
                ++entry.probeStart[size_t((c.x - lo.x) * rows + (c.y - lo.y)) + 1];
            }
            for (size_t c = 1; c < entry.probeStart.size(); ++c) {
                entry.probeStart[c] += entry.probeStart[c - 1];
            }
        }
    }
    entry.probeSpacing = spacing;
    entry.probeCell = cell;
}

} // namespace

void BodyBoundary::prepare(const StepContext& context) {
    m_kicks.clear();
    m_samples.clear();
    m_bodies.clear();
    m_rigid.clear();
    m_colliders.clear();
    m_boxes.clear();
    m_sweepPose = SweepPose{}; // the colliders are listed anew: their boxes too
    m_spacing = context.sampleSpacing;
    m_frameDt = context.frameDt;
    if (m_physics == nullptr) {
        m_grid.build({}, 1.0f);
        return;
    }
    for (FixtureEntry& e : m_entries) {
        e.seen = false;
    }
    const double spacing = context.sampleSpacing;
    const double wetCell = 0.75 * spacing;
    const double frameDt = context.frameDt;
    m_nextPose.clear();
    uint32_t bodyIndex = 0;
    for (b2Body* body = m_physics->GetBodyList(); body != nullptr;
         body = body->GetNext(), ++bodyIndex) {
        if (!body->IsEnabled()) {
            continue;
        }
        // The sweep: from where the fluid last saw the body (the end of its previous step) to
        // where Box2D has put it now, at constant speed. A body seen for the first time, or one
        // that jumped (b2Body::SetTransform, or a new body at a destroyed one's address), comes
        // in along its velocity instead: sweeping a teleport would shove the fluid along the way.
        const glm::dvec2 endCom = toVec(body->GetWorldCenter());
        const double endAngle = body->GetAngle();
        const glm::dvec2 vNow = toVec(body->GetLinearVelocity());
        const double wNow = body->GetAngularVelocity();
        glm::dvec2 startCom = endCom - frameDt * vNow;
        double startAngle = endAngle - frameDt * wNow;
        const auto last = m_lastPose.find(body);
        if (last != m_lastPose.end()) {
            const glm::dvec2 d = (endCom - last->second.com) - frameDt * vNow;
            const double turn = (endAngle - last->second.angle) - frameDt * wNow;
            if (std::sqrt(d.x * d.x + d.y * d.y) <= kJump * spacing &&
                std::fabs(turn) <= kJumpAngle) {
                startCom = last->second.com;
                startAngle = last->second.angle;
            }
        }
        m_nextPose.emplace(body, LastPose{endCom, endAngle});
        const glm::dvec2 com = startCom;
        const glm::dvec2 velocity = (endCom - startCom) / frameDt;
        const double omega = (endAngle - startAngle) / frameDt;
        const double angle = std::remainder(startAngle, 2.0 * std::numbers::pi);
        if (!std::isfinite(com.x) || !std::isfinite(com.y) || !std::isfinite(angle) ||
            std::fabs(com.x) > kMaxPosition || std::fabs(com.y) > kMaxPosition ||
            !(std::fabs(velocity.x) <= kMaxSpeed) || !(std::fabs(velocity.y) <= kMaxSpeed) ||
            !(std::fabs(omega) <= kMaxSpeed)) {
            continue; // out of the shapes' range this step: neither a boundary nor pushed
        }
        BodyEntry be;
        be.body = body;
        be.type = int(body->GetType());
        be.com = com;
        be.velocity = velocity;
        be.angle = angle;
        be.omega = omega;
        be.colliderBegin = uint32_t(m_colliders.size());
        const glm::dvec2 localCenter = toVec(body->GetLocalCenter());
        const double c = detail::cos(angle), s = detail::sin(angle);
        uint32_t fixtureIndex = 0;
        for (b2Fixture* fixture = body->GetFixtureList(); fixture != nullptr;
             fixture = fixture->GetNext(), ++fixtureIndex) {
            if (!couples(*fixture)) {
                continue;
            }
            const uint32_t index = findOrBuild(*fixture, localCenter, bodyIndex, fixtureIndex);
            FixtureEntry& entry = m_entries[index];
            if (entry.probeCells.empty() || entry.probeSpacing != spacing) {
                layProbes(entry, spacing, wetCell); // new, rebuilt, or another spacing
            }
            // Pose: the shape's local origin is the body's centre of mass (a circle's own
            // centre), moving with the body's velocity there during the step.
            const glm::dvec2 origin = com + rotate(entry.offset, c, s);
            const glm::dvec2 r = origin - com;
            const glm::dvec2 v = velocity + omega * glm::dvec2(-r.y, r.x);
            const auto clampSpeed = [](double x) { return std::clamp(x, -kMaxSpeed, kMaxSpeed); };
            try {
                entry.shape->setPose(glm::vec2(std::clamp(origin.x, -kMaxPosition, kMaxPosition),
                                               std::clamp(origin.y, -kMaxPosition, kMaxPosition)),
                                     float(angle));
                entry.shape->setVelocity(glm::vec2(clampSpeed(v.x), clampSpeed(v.y)), float(omega));
                entry.shape->prepare(context);
            } catch (const Error& e) {
                throw Error(where(bodyIndex, fixtureIndex) + e.what(), e.code());
            }
            Collider collider;
            collider.entry = index;
            collider.body = uint32_t(m_bodies.size());
            collider.sampleBegin = uint32_t(m_samples.size());
            const BoundarySamples& samples = entry.shape->samples();
            for (std::size_t k = 0; k < samples.size(); ++k) {
                m_samples.add(samples.px[k], samples.py[k], samples.vx[k], samples.vy[k]);
            }
            collider.sampleEnd = uint32_t(m_samples.size());
            m_colliders.push_back(collider);

            // Where the shape sweeps during the step: its local box turned by the angle at
            // rest, or the circle about its origin that holds it at any angle, at both ends of
            // the straight path of the origin; plus the reach of a projection.
            const glm::dvec2 lo = entry.shape->localMin(), hi = entry.shape->localMax();
            const glm::dvec2 end = origin + frameDt * v;
            Box box;
            glm::dvec2 extentLo, extentHi;
            if (omega == 0.0) {
                extentLo = glm::dvec2(1e300);
                extentHi = glm::dvec2(-1e300);
                for (const glm::dvec2 corner :
                     {lo, hi, glm::dvec2(lo.x, hi.y), glm::dvec2(hi.x, lo.y)}) {
                    const glm::dvec2 w = rotate(corner, c, s);
                    extentLo = glm::min(extentLo, w);
                    extentHi = glm::max(extentHi, w);
                }
            } else {
                double reach = 0.0;
                for (const glm::dvec2 corner :
                     {lo, hi, glm::dvec2(lo.x, hi.y), glm::dvec2(hi.x, lo.y)}) {
                    reach = std::max(reach, std::sqrt(corner.x * corner.x + corner.y * corner.y));
                }
                extentLo = glm::dvec2(-reach);
                extentHi = glm::dvec2(reach);
            }
            const double margin = spacing;
            box.loX = float(std::min(origin.x, end.x) + extentLo.x - margin);
            box.loY = float(std::min(origin.y, end.y) + extentLo.y - margin);
            box.hiX = float(std::max(origin.x, end.x) + extentHi.x + margin);
            box.hiY = float(std::max(origin.y, end.y) + extentHi.y + margin);
            m_boxes.push_back(box);
        }
        be.colliderEnd = uint32_t(m_colliders.size());
        if (be.colliderEnd > be.colliderBegin) {
            // A dynamic body is an unknown of the coarse pressure solve (its mass as Box2D
            // weighs it: kg/m^2 x area, the fluid's areal density times the same area).
            RigidBody rigid;
            if (body->GetType() == b2_dynamicBody) {
                rigid.mass = body->GetMass();
            }
            rigid.sampleBegin = m_colliders[be.colliderBegin].sampleBegin;
            rigid.sampleEnd = m_colliders[be.colliderEnd - 1].sampleEnd;
            rigid.contacts = m_contactBodies != nullptr && m_contactBodies->count(body) != 0;
            m_rigid.push_back(rigid);
            m_bodies.push_back(be);
        }
    }

    // Entries of fixtures not seen (destroyed, filtered out) go; colliders follow the moves.
    std::vector<uint32_t> remap(m_entries.size(), 0);
    uint32_t kept = 0;
    for (uint32_t k = 0; k < m_entries.size(); ++k) {
        if (m_entries[k].seen) {
            remap[k] = kept;
            if (kept != k) {
                m_entries[kept] = std::move(m_entries[k]);
            }
            ++kept;
        }
    }
    m_entries.resize(kept);
    m_index.clear();
    for (uint32_t k = 0; k < kept; ++k) {
        m_index.emplace(m_entries[k].fixture, k);
    }
    for (Collider& collider : m_colliders) {
        collider.entry = remap[collider.entry];
    }
    // Cells of one support: a particle's path per sub-step stays well inside one, and a cell
    // meets few sweep boxes, so each particle tests few that it misses (with cells of four
    // supports, crates resting side by side shared cells and every particle near them tested
    // them all). The visits are in collider order whatever the cells: the same bits.
    m_grid.build(m_boxes, context.supportRadius);
    m_lastPose.swap(m_nextPose);
}

std::vector<BodyBoundary::SeenPose> BodyBoundary::seenPoses() const {
    std::vector<SeenPose> out;
    if (m_physics == nullptr) {
        return out;
    }
    for (const b2Body* body = m_physics->GetBodyList(); body != nullptr; body = body->GetNext()) {
        const auto found = m_lastPose.find(body);
        if (found != m_lastPose.end()) {
            out.push_back({body, found->second.com, found->second.angle});
        }
    }
    return out;
}

void BodyBoundary::setSeenPoses(std::span<const SeenPose> poses) {
    m_lastPose.clear();
    for (const SeenPose& p : poses) {
        m_lastPose[p.body] = LastPose{p.com, p.angle};
    }
}

void BodyBoundary::project(const ProjectContext& context, uint32_t begin, uint32_t end) {
    if (m_colliders.empty()) {
        return;
    }
    // Each collider's sweep, worked out the first time a particle of this range comes near it.
    std::vector<KinematicShape::Sweep> sweeps(m_colliders.size());
    std::vector<uint8_t> ready(m_colliders.size(), 0);
    std::vector<Kick> kicks;
    std::vector<uint32_t> near; // the colliders near particle i, in collider (= body) order
    const uint32_t second = context.prevTimeInStep == context.timeInStep ? 1 : 0;
    // Runs one collider's projection on particle i and records the velocity it gave.
    auto run = [&](uint32_t i, uint32_t k, bool pushOutOnly) {
        const KinematicShape& shape = *m_entries[m_colliders[k].entry].shape;
        if (ready[k] == 0) {
            sweeps[k] = shape.sweep(context);
            // Where the coarse solve has moved the body so far (its samples stand there): the
            // shape moves with it, so no particle is left where the body will stand once the
            // coupling takes the correction.
            const uint32_t body = m_colliders[k].body;
            if (body < context.bodyShifts.size()) {
                const BodyShift& shift = context.bodyShifts[body];
                const glm::dvec2 v(shift.velocity), o(shift.offset);
                sweeps[k].before.origin += o + v * double(context.prevTimeInStep);
                sweeps[k].now.origin += o + v * double(context.timeInStep);
                sweeps[k].before.velocity += v;
                sweeps[k].now.velocity += v;
            }
            ready[k] = 1;
        }
        const float x = context.px[i], y = context.py[i];
        const float vx = context.vx[i], vy = context.vy[i];
        if (pushOutOnly) {
            shape.pushOutParticle(sweeps[k], context, i);
        } else {
            shape.projectParticle(sweeps[k], context, i);
        }
        if (context.vx[i] != vx || context.vy[i] != vy) {
            kicks.push_back({context.timeInStep, second, i, k, context.material[i],
                             context.vx[i] - vx, context.vy[i] - vy, context.px[i],
                             context.py[i]});
        }
        return context.px[i] != x || context.py[i] != y;
    };
    for (uint32_t i = begin; i < end; ++i) {
        const Box path{
            std::min(context.prevX[i], context.px[i]), std::min(context.prevY[i], context.py[i]),
            std::max(context.prevX[i], context.px[i]), std::max(context.prevY[i], context.py[i])};
        near.clear();
        bool moved = false;
        m_grid.forEach(path, m_boxes, [&](uint32_t k) {
            near.push_back(k);
            moved = run(i, k, false) || moved;
        });
        if (!moved || near.size() < 2) {
            continue;
        }
        // A body's fixtures may overlap (a paddle wheel's blades meet at its hub): pushed out of
        // one, a particle can stand inside another. It leaves the union of the body's fixtures:
        // each one it stands inside pushes it to its nearest surface, until none does (a few
        // rounds reach the union's surface for the convex overlaps bodies are made of).
        constexpr int kUnionRounds = 8;
        for (std::size_t first = 0; first < near.size();) {
            const uint32_t body = m_colliders[near[first]].body;
            std::size_t last = first + 1;
            while (last < near.size() && m_colliders[near[last]].body == body) {
                ++last;
            }
            for (int round = 0; round < kUnionRounds && last - first > 1; ++round) {
                bool pushed = false;
                for (std::size_t n = first; n < last; ++n) {
                    pushed = run(i, near[n], true) || pushed;
                }
                if (!pushed) {
                    break;
                }
            }
            first = last;
        }
    }
    if (!kicks.empty()) {
        const std::lock_guard<std::mutex> lock(m_kickMutex);
        m_kicks.insert(m_kicks.end(), kicks.begin(), kicks.end());
    }
}

bool BodyBoundary::bodyContains(uint32_t body, glm::vec2 point, float timeInStep) const {
    if (body >= m_bodies.size()) {
        return false;
    }
    const BodyEntry& e = m_bodies[body];
    // Into the body's centre-of-mass frame at timeInStep, then out at its pose now (the end
    // of the sweep), where Box2D's fixtures stand.
    const double t = timeInStep;
    SweepPose& pose = m_sweepPose;
    const b2Transform& xf = e.body->GetTransform();
    if (pose.body != body || pose.t != t || pose.com != e.com || pose.velocity != e.velocity ||
        pose.angle != e.angle || pose.omega != e.omega || pose.px != xf.p.x ||
        pose.py != xf.p.y || pose.qs != xf.q.s || pose.qc != xf.q.c) {
        const double angle = e.angle + t * e.omega;
        pose = {t,
                e.com,
                e.velocity,
                e.angle,
                e.omega,
                e.com + t * e.velocity,
                detail::cos(angle),
                detail::sin(angle),
                body,
                xf.p.x,
                xf.p.y,
                xf.q.s,
                xf.q.c};
        m_sweepBoxes.resize(m_colliders.size());
        for (uint32_t k = e.colliderBegin; k < e.colliderEnd; ++k) {
            const b2Shape* shape = m_entries[m_colliders[k].entry].fixture->GetShape();
            Box& box = m_sweepBoxes[k];
            if (shape->GetType() == b2Shape::e_chain || shape->GetType() == b2Shape::e_edge) {
                box = {1.0f, 1.0f, -1.0f, -1.0f}; // empty: a line holds no point inside
                continue;
            }
            b2AABB aabb;
            shape->ComputeAABB(&aabb, xf, 0);
            const b2Vec2 size = aabb.upperBound - aabb.lowerBound;
            const float margin = 1e-5f * (1.0f + std::abs(aabb.lowerBound.x) +
                                          std::abs(aabb.lowerBound.y) + size.x + size.y);
            box = {aabb.lowerBound.x - margin, aabb.lowerBound.y - margin,
                   aabb.upperBound.x + margin, aabb.upperBound.y + margin};
        }
    }
    const glm::dvec2 d = glm::dvec2(point) - pose.at;
    const glm::dvec2 local = rotate(d, pose.c, -pose.s);
    const glm::dvec2 center = toVec(e.body->GetWorldCenter());
    const glm::dvec2 now = center + rotate(local, double(xf.q.c), double(xf.q.s));
    const b2Vec2 p(float(now.x), float(now.y));
    for (uint32_t k = e.colliderBegin; k < e.colliderEnd; ++k) {
        const Box& box = m_sweepBoxes[k];
        if (p.x < box.loX || p.x > box.hiX || p.y < box.loY || p.y > box.hiY) {
            continue;
        }
        if (m_entries[m_colliders[k].entry].fixture->TestPoint(p)) {
            return true;
        }
    }
    return false;
}

void BodyBoundary::receiveBodyImpulses(std::span<const RigidBodyImpulse> impulses) {
    for (std::size_t b = 0; b < m_bodies.size() && b < impulses.size(); ++b) {
        BodyEntry& body = m_bodies[b];
        body.coarse = impulses[b];
        const auto last = m_lastPose.find(body.body);
        if (last != m_lastPose.end()) {
            last->second.com += glm::dvec2(impulses[b].displacement);
        }
    }
}

void BodyBoundary::receiveForces(std::span<const float> fx, std::span<const float> fy,
                                 std::span<const float> drag) {
    // Summed in sample order, in double: the same bits for any number of workers.
    for (BodyEntry& body : m_bodies) {
        glm::dvec2 force{0.0, 0.0};
        double torque = 0.0, linear = 0.0, angular = 0.0;
        for (uint32_t k = body.colliderBegin; k < body.colliderEnd; ++k) {
            const Collider& collider = m_colliders[k];
            for (uint32_t j = collider.sampleBegin; j < collider.sampleEnd; ++j) {
                const glm::dvec2 f{fx[j], fy[j]};
                const glm::dvec2 r = glm::dvec2(m_samples.px[j], m_samples.py[j]) - body.com;
                force += f;
                torque += r.x * f.y - r.y * f.x;
                linear += drag[j];
                angular += drag[j] * (r.x * r.x + r.y * r.y);
            }
        }
        body.force = force;
        body.torque = torque;
        body.drag = linear;
        body.angularDrag = angular;
    }
    // What the projections gave the particles, the bodies lose: a body that pushes into the
    // fluid faster than its pressure can clear the way sets the particles in its path to its
    // own velocity (KinematicShape::projectParticle), and pays for that momentum here, as a
    // force averaged over the step. In (call, particle, collider) order: the same sums for
    // any number of workers.
    std::sort(m_kicks.begin(), m_kicks.end(), [](const Kick& a, const Kick& b) {
        if (a.timeInStep != b.timeInStep) {
            return a.timeInStep < b.timeInStep;
        }
        if (a.second != b.second) {
            return a.second < b.second;
        }
        if (a.particle != b.particle) {
            return a.particle < b.particle;
        }
        return a.collider < b.collider;
    });
    const double invDt = m_frameDt > 0.0 ? 1.0 / m_frameDt : 0.0;
    for (const Kick& kick : m_kicks) {
        BodyEntry& body = m_bodies[m_colliders[kick.collider].body];
        const double mass = kick.material < m_masses.size() ? m_masses[kick.material] : 0.0;
        const glm::dvec2 f = -mass * invDt * glm::dvec2(kick.dvx, kick.dvy);
        // The lever arm from where the body's centre of mass was at that time.
        const glm::dvec2 com = body.com + double(kick.timeInStep) * body.velocity;
        const glm::dvec2 r = glm::dvec2(kick.x, kick.y) - com;
        body.force += f;
        body.torque += r.x * f.y - r.y * f.x;
    }
    m_kicks.clear();
}

} // namespace fluid::box2d
