// fluid — built-in force plugin: pointer push and pull.
#include <fluid/plugins/pointer.h>

#include <cmath>

namespace fluid {

namespace {
// Peak of q (1 - q^2)^2 on [0, 1], at q = 1 / sqrt 5: 16 / (25 sqrt 5).
constexpr double kProfilePeak = 16.0 / (25.0 * 2.2360679774997896964);
} // namespace

PointerForce::PointerForce(float radius, float strength) : PointerForce() {
    setParam("radius", radius);
    setParam("strength", strength);
}

void PointerForce::setPointer(glm::vec2 position, float active) {
    setParam("x", position.x);
    setParam("y", position.y);
    setParam("active", active);
}

void PointerForce::apply(const ForceContext& context, uint32_t begin, uint32_t end) {
    const double scale = value(kStrength) * value(kActive);
    if (scale == 0.0) {
        return; // released (or no strength): leave the accumulators untouched
    }
    const auto cx = static_cast<float>(value(kX)), cy = static_cast<float>(value(kY));
    const auto radius = static_cast<float>(value(kRadius));
    const float invR2 = 1.0f / (radius * radius);
    // a = S g(q) r_vec / r = [S / (R g_max)] (1 - q^2)^2 r_vec: no division by r.
    const auto k = static_cast<float>(scale / (double(radius) * kProfilePeak));
    const auto px = context.particles.px, py = context.particles.py;
    for (uint32_t i = begin; i < end; ++i) {
        const float dx = px[i] - cx, dy = py[i] - cy;
        const float q2 = (dx * dx + dy * dy) * invR2;
        if (q2 < 1.0f) {
            const float w = 1.0f - q2;
            const float s = k * w * w;
            context.ax[i] += s * dx;
            context.ay[i] += s * dy;
        }
    }
}

} // namespace fluid
