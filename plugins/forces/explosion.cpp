// fluid — built-in force plugin: explosion, a one-shot radial impulse.
#include <fluid/plugins/explosion.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace fluid {

ExplosionForce::ExplosionForce(glm::vec2 centre, float radius, float impulse) : ExplosionForce() {
    setParam("x", centre.x);
    setParam("y", centre.y);
    setParam("radius", radius);
    setParam("impulse", impulse);
}

void ExplosionForce::prepare(const StepContext& context) {
    m_armed = value(kTrigger) >= 0.5;
    m_stepStart = context.time;
    m_core = 0.5 * double(context.sampleSpacing);
}

void ExplosionForce::apply(const ForceContext& context, uint32_t begin, uint32_t end) {
    // Only the sub-step that starts the armed step: both solvers start their first sub-step at
    // exactly StepContext::time (time + 0.0), later ones strictly after it. A comparison of
    // times rather than a "fired" flag keeps apply free of writes (it runs on many threads).
    if (!m_armed || context.time != m_stepStart || !(context.dt > 0.0f)) {
        return;
    }
    const double cx = value(kX), cy = value(kY), radius = value(kRadius);
    const double invR2 = 1.0 / (radius * radius);
    const double perDt = value(kImpulse) / double(context.dt); // dv / dt at the centre
    const auto px = context.particles.px, py = context.particles.py;
    for (uint32_t i = begin; i < end; ++i) {
        const double dx = double(px[i]) - cx, dy = double(py[i]) - cy;
        const double r2 = dx * dx + dy * dy;
        const double q2 = r2 * invR2;
        if (q2 < 1.0 && r2 > 0.0) {
            const double w = 1.0 - q2;
            // Times r_vec: radial, |dv| = J w^2 from c outward, fading linearly inside c.
            const double s = perDt * w * w / std::max(std::sqrt(r2), m_core);
            context.ax[i] += static_cast<float>(s * dx);
            context.ay[i] += static_cast<float>(s * dy);
        }
    }
}

void ExplosionForce::finish(const StepContext& /*context*/) {
    if (m_armed) {
        storeValue(kTrigger, 0.0);
        m_armed = false;
    }
}

void ExplosionForce::saveState(StateWriter& out) const {
    out.write(static_cast<uint8_t>(m_armed ? 1 : 0));
    out.write(m_stepStart);
    out.write(m_core);
}

void ExplosionForce::restoreState(StateReader& in) {
    const auto armed = in.read<uint8_t>();
    const auto start = in.read<double>();
    const auto core = in.read<double>();
    if (armed > 1 || !std::isfinite(start) || !(core >= 0.0 && core <= 1e4)) {
        throw Error(
            "plugin 'force.explosion': bad snapshot state (armed = " + std::to_string(armed) +
                ", step start = " + std::to_string(start) + " s, core = " + std::to_string(core) +
                " m; expected armed 0 or 1, a finite time and a core in [0, 10000] m)",
            ErrorCode::BadFile);
    }
    m_armed = armed == 1;
    m_stepStart = start;
    m_core = core;
}

} // namespace fluid
