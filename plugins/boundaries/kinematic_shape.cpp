// fluid — base of the built-in shape boundaries: pose, velocities, samples, projection loop.
#include <fluid/plugins/kinematic_shape.h>

#include <fluid/error.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <numbers>
#include <sstream>
#include <utility>

namespace fluid {

KinematicShape::KinematicShape(std::string_view type, std::span<const ParamDecl> params)
    : BoundaryPlugin(type, params) {}

KinematicShape::Pose KinematicShape::pose(double t) const {
    Pose p;
    p.origin = {value(kX) + value(kVx) * t, value(kY) + value(kVy) * t};
    const double angle = value(kAngle) + value(kOmega) * t;
    p.cosA = std::cos(angle);
    p.sinA = std::sin(angle);
    p.velocity = {value(kVx), value(kVy)};
    p.omega = value(kOmega);
    return p;
}

void KinematicShape::setPose(glm::vec2 position, float angle) {
    setParam("x", position.x);
    setParam("y", position.y);
    setParam("angle", angle);
}

void KinematicShape::setVelocity(glm::vec2 velocity, float omega) {
    setParam("vx", velocity.x);
    setParam("vy", velocity.y);
    setParam("omega", omega);
}

void KinematicShape::onParamChanged(std::size_t index) {
    if (index < kPoseParamCount) {
        return;
    }
    m_built = false; // the shape itself changed: lay the samples again at the next prepare
    // A refused shape throws; Plugin::setParam and setPoints then put the old value back.
    validate();
}

void KinematicShape::checkCoordinates(std::size_t index) const {
    const std::span<const glm::vec2> points = pointsAt(index);
    for (std::size_t k = 0; k < points.size(); ++k) {
        const glm::vec2 p = points[k];
        if (std::fabs(p.x) <= kMaxCoordinate && std::fabs(p.y) <= kMaxCoordinate) {
            continue;
        }
        const ParamDecl& decl = params()[index];
        std::ostringstream s;
        s << "plugin '" << type() << "': parameter '" << decl.name << "' point " << k << " = ("
          << p.x << ", " << p.y << ") is outside [" << -kMaxCoordinate << ", " << kMaxCoordinate
          << "] (unit: " << decl.unit << ")";
        throw Error(s.str(), ErrorCode::OutOfRange);
    }
}

void KinematicShape::checkSampleCount(double estimate, std::string_view what,
                                      double spacing) const {
    if (estimate <= double(kMaxSamples)) {
        return;
    }
    // Two significant digits: the estimate is rough, and a message should read at a glance.
    const double unit = std::pow(10.0, std::floor(std::log10(estimate)) - 1.0);
    const double rounded = std::isfinite(unit) ? std::round(estimate / unit) * unit : estimate;
    std::ostringstream s;
    s << "plugin '" << type() << "': " << what << " needs about " << std::fixed
      << std::setprecision(0) << rounded << std::defaultfloat << std::setprecision(6)
      << " boundary samples at spacing " << spacing << " m; at most " << kMaxSamples;
    throw Error(s.str(), ErrorCode::OutOfRange);
}

double KinematicShape::layerCount(double spacing, double support) {
    return std::max(1.0, std::ceil(support / spacing - 1e-9));
}

void KinematicShape::prepare(const StepContext& context) {
    if (!m_built || m_builtSpacing != context.sampleSpacing ||
        m_builtSupport != context.supportRadius) {
        // Not built until build returns: a shape it rejects keeps no stale geometry for project.
        m_built = false;
        m_local.clear();
        build(context.sampleSpacing, context.supportRadius, m_local, m_bounds);
        m_built = true;
        m_builtSpacing = context.sampleSpacing;
        m_builtSupport = context.supportRadius;
    }
    // Local -> world at the start of the step; the world moves each sample on with its velocity
    // during the sub-steps.
    const Pose p = pose(0.0);
    m_samples.clear();
    for (const glm::dvec2 local : m_local) {
        const glm::dvec2 w = p.toWorld(local);
        const glm::dvec2 v = p.velocityAt(w);
        m_samples.add(static_cast<float>(w.x), static_cast<float>(w.y), static_cast<float>(v.x),
                      static_cast<float>(v.y));
    }
    m_body = RigidBody{0.0f, 0, static_cast<uint32_t>(m_samples.size()), true};
}

void KinematicShape::setContactEvents(bool on) {
    m_contacts = on;
}

std::span<const RigidBody> KinematicShape::rigidBodies() const {
    if (!m_contacts || m_body.sampleEnd != m_samples.size()) {
        return {};
    }
    return {&m_body, 1};
}

void KinematicShape::saveState(StateWriter& out) const {
    if (m_contacts) {
        out.write(uint8_t(1));
    }
}

void KinematicShape::restoreState(StateReader& in) {
    if (in.remaining() == 0) {
        m_contacts = false;
        return;
    }
    const auto flag = in.read<uint8_t>();
    if (flag > 1) {
        throw Error("snapshot: plugin '" + std::string(type()) +
                        "': contact events flag = " + std::to_string(flag) + " is not 0 or 1",
                    ErrorCode::BadFile);
    }
    m_contacts = flag == 1;
}

KinematicShape::Sweep KinematicShape::sweep(const ProjectContext& context) const {
    Sweep w;
    w.before = pose(double(context.prevTimeInStep));
    w.now = pose(double(context.timeInStep));
    w.spacing = context.spacing;
    // How far outside a surface a particle is put: small against the spacing, large against the
    // rounding of a float position (a few ulps at the shape's distance from the world origin),
    // so that the stored position is still outside.
    const double extent = std::max({std::fabs(m_bounds.lo.x), std::fabs(m_bounds.lo.y),
                                    std::fabs(m_bounds.hi.x), std::fabs(m_bounds.hi.y)});
    const double magnitude = std::fabs(w.now.origin.x) + std::fabs(w.now.origin.y) + extent;
    w.eps = std::max(1e-3 * w.spacing, 4e-7 * magnitude);
    const double margin = reach(w.spacing) + w.eps;
    w.lo = m_bounds.lo - margin;
    w.hi = m_bounds.hi + margin;
    return w;
}

void KinematicShape::place(const Sweep& w, const ProjectContext& context, uint32_t i,
                           const Contact& contact) const {
    const glm::dvec2 x = w.now.toWorld(contact.point);
    context.px[i] = static_cast<float>(x.x);
    context.py[i] = static_cast<float>(x.y);
    // No velocity into the wall relative to the wall's own velocity there: v_n >= wall v_n.
    const glm::dvec2 n = w.now.rotate(contact.normal);
    const glm::dvec2 wall = w.now.velocityAt(x);
    const double vn = context.vx[i] * n.x + context.vy[i] * n.y;
    const double wallN = wall.x * n.x + wall.y * n.y;
    if (vn < wallN) {
        context.vx[i] = static_cast<float>(context.vx[i] + (wallN - vn) * n.x);
        context.vy[i] = static_cast<float>(context.vy[i] + (wallN - vn) * n.y);
    }
}

void KinematicShape::projectParticle(const Sweep& w, const ProjectContext& context,
                                     uint32_t i) const {
    const glm::dvec2 p = w.before.toLocal({context.prevX[i], context.prevY[i]});
    const glm::dvec2 c = w.now.toLocal({context.px[i], context.py[i]});
    // Early out: the path's box misses the shape's.
    if (std::max(p.x, c.x) < w.lo.x || std::min(p.x, c.x) > w.hi.x || std::max(p.y, c.y) < w.lo.y ||
        std::min(p.y, c.y) > w.hi.y) {
        return;
    }
    Contact contact;
    if (collide(p, c, w.spacing, w.eps, contact)) {
        place(w, context, i, contact);
    }
}

bool KinematicShape::pushOutParticle(const Sweep& w, const ProjectContext& context,
                                     uint32_t i) const {
    const glm::dvec2 c = w.now.toLocal({context.px[i], context.py[i]});
    if (c.x < w.lo.x || c.x > w.hi.x || c.y < w.lo.y || c.y > w.hi.y) {
        return false;
    }
    // A path that starts where it ends: a particle inside goes to the nearest surface point.
    Contact contact;
    if (!collide(c, c, w.spacing, w.eps, contact)) {
        return false;
    }
    place(w, context, i, contact);
    return true;
}

bool KinematicShape::contains(glm::vec2 point) const {
    return insideLocal(pose().toLocal(glm::dvec2(point)));
}

void KinematicShape::project(const ProjectContext& context, uint32_t begin, uint32_t end) {
    if (!m_built) {
        return; // no prepare yet: no geometry to test against
    }
    const Sweep w = sweep(context);
    for (uint32_t i = begin; i < end; ++i) {
        projectParticle(w, context, i);
    }
}

void KinematicShape::finish(const StepContext& context) {
    const double dt = context.frameDt;
    // The same expressions as pose(dt), so the pose stored is the one the last projection used
    // (except at the edge of the range below).
    // A position past the declared range would make the world's snapshot unloadable (World::load
    // restores it with setParam, which checks the range): the shape stops at the edge, and its
    // velocity out of the range goes, so that it does not keep sweeping past the edge during
    // each step and jumping back at its end.
    for (const auto& [position, velocity] : {std::pair<std::size_t, std::size_t>{kX, kVx},
                                             std::pair<std::size_t, std::size_t>{kY, kVy}}) {
        const ParamDecl& decl = params()[position];
        const double advanced = value(position) + value(velocity) * dt;
        const double kept = std::clamp(advanced, decl.minValue, decl.maxValue);
        storeValue(position, kept);
        if (kept != advanced) {
            // The position was in range (setParam and this clamp keep it there), so the motion
            // that left the range pointed out of it.
            storeValue(velocity, 0.0);
        }
    }
    const double angle = value(kAngle) + value(kOmega) * dt;
    // Kept in [-pi, pi]: a long-spinning paddle keeps its angle's precision.
    storeValue(kAngle, std::remainder(angle, 2.0 * std::numbers::pi));
}

} // namespace fluid
