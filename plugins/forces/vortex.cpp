// fluid — built-in force plugin: vortex with a Rankine profile and exponential spin-up.
#include <fluid/plugins/vortex.h>

#include "relaxation.h"

#include <cmath>
#include <limits>

namespace fluid {

VortexForce::VortexForce(glm::vec2 centre, float speed, float radius, float rate) : VortexForce() {
    setParam("x", centre.x);
    setParam("y", centre.y);
    setParam("speed", speed);
    setParam("radius", radius);
    setParam("rate", rate);
}

void VortexForce::apply(const ForceContext& context, uint32_t begin, uint32_t end) {
    const double cx = value(kX), cy = value(kY);
    const double speed = value(kSpeed), radius = value(kRadius), pull = value(kPull);
    const double rate = value(kRate);
    const double cutoff = value(kCutoff);
    const double cut2 = cutoff > 0.0 ? cutoff * cutoff : std::numeric_limits<double>::infinity();
    const double r2Core = radius * radius;
    // The exact drag over the sub-step: v_t - u -> (v_t - u) exp(-k dt).
    const double lambda = detail::relaxationRate(rate, context.dt);
    const auto px = context.particles.px, py = context.particles.py;
    const auto vx = context.particles.vx, vy = context.particles.vy;
    for (uint32_t i = begin; i < end; ++i) {
        // Double for the geometry: r^2 of a particle micrometres from the centre neither
        // underflows nor loses the bits the division by r^2 needs.
        const double dx = double(px[i]) - cx, dy = double(py[i]) - cy;
        const double r2 = dx * dx + dy * dy;
        if (r2 > cut2 || !(r2 > 0.0)) {
            continue; // beyond the cut-off, or on the centre where no direction exists
        }
        // u(r) / r and the pull profile over r: both 1/R inside the core, R/r^2 outside, so
        // u(r) (-dy, dx) / r = speed * profile * (-dy, dx) needs no square root.
        const double profile = r2 <= r2Core ? 1.0 / radius : radius / r2;
        // v . t / r with t = (-dy, dx) / r: the particle's angular velocity about the centre.
        const double omega = (double(vx[i]) * -dy + double(vy[i]) * dx) / r2;
        const double tangential = lambda * (speed * profile - omega); // times (-dy, dx)
        const double inward = pull * profile;                         // times -(dx, dy)
        context.ax[i] += static_cast<float>(-tangential * dy - inward * dx);
        context.ay[i] += static_cast<float>(tangential * dx - inward * dy);
    }
}

} // namespace fluid
