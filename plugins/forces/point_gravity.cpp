// fluid — built-in force plugin: point (radial) gravity with Plummer softening.
#include <fluid/plugins/point_gravity.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace fluid {

namespace {
// Floor of |r|^2 + eps^2 (unit: m^2): below a micrometre an unsoftened pull is clamped, so the
// largest acceleration stays about 1e34 m/s^2 for the widest parameters (a finite float; the
// world's speed cap takes it from there) and a particle on the centre gets 0, not 0 * inf.
constexpr double kMinDistance2 = 1e-12;
} // namespace

void PointGravityForce::prepare(const StepContext& context) {
    m_spacing = context.sampleSpacing;
}

PointGravityForce::PointGravityForce(glm::vec2 centre, float strength, float referenceRadius,
                                     float falloff)
    : PointGravityForce() {
    setParam("x", centre.x);
    setParam("y", centre.y);
    setParam("strength", strength);
    setParam("referenceRadius", referenceRadius);
    setParam("falloff", falloff);
}

void PointGravityForce::apply(const ForceContext& context, uint32_t begin, uint32_t end) {
    const double cx = value(kX), cy = value(kY);
    const double n = value(kFalloff);
    // a = -k r_vec / d^(n+1), d^2 = r^2 + eps^2, k = g0 r0^n. Double precision: k reaches 1e16
    // and d^-(n+1) 1e24 before the product comes back into float range.
    const double k = value(kStrength) * std::pow(value(kReferenceRadius), n);
    // Softening at least the spacing; the pull at most kMaxPullShare spacings per sub-step
    // squared (docs/plugins.md, Point gravity).
    const double eps = std::max(value(kSoftening), m_spacing);
    const double eps2 = eps * eps;
    const double dt = context.dt;
    const double maxPull = dt > 0.0 && m_spacing > 0.0 ? kMaxPullShare * m_spacing / (dt * dt)
                                                       : std::numeric_limits<double>::infinity();
    const double cutoff = value(kCutoff);
    const double cut2 = cutoff > 0.0 ? cutoff * cutoff : std::numeric_limits<double>::infinity();
    const double exponent = -0.5 * (n + 1.0);
    const auto px = context.particles.px, py = context.particles.py;
    for (uint32_t i = begin; i < end; ++i) {
        const double dx = double(px[i]) - cx, dy = double(py[i]) - cy;
        const double r2 = dx * dx + dy * dy;
        if (r2 > cut2) {
            continue;
        }
        const double d2 = std::max(r2 + eps2, kMinDistance2);
        double inv; // d^-(n+1); the common exponents without pow
        if (n == 2.0) {
            inv = 1.0 / (d2 * std::sqrt(d2));
        } else if (n == 1.0) {
            inv = 1.0 / d2;
        } else if (n == 0.0) {
            inv = 1.0 / std::sqrt(d2);
        } else {
            inv = std::pow(d2, exponent);
        }
        double s = -k * inv; // the pull is |s| r
        if (std::fabs(s) * std::sqrt(r2) > maxPull) {
            s = std::copysign(maxPull / std::sqrt(r2), s);
        }
        context.ax[i] += static_cast<float>(s * dx);
        context.ay[i] += static_cast<float>(s * dy);
    }
}

} // namespace fluid
