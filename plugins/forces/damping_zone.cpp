// fluid — built-in force plugin: damping zone, an exact exponential velocity decay.
#include <fluid/plugins/damping_zone.h>

#include "relaxation.h"

#include <cmath>

namespace fluid {

DampingZoneForce::DampingZoneForce(float rate, glm::vec2 min, glm::vec2 max) : DampingZoneForce() {
    setParam("rate", rate);
    setParam("minX", min.x);
    setParam("minY", min.y);
    setParam("maxX", max.x);
    setParam("maxY", max.y);
}

void DampingZoneForce::apply(const ForceContext& context, uint32_t begin, uint32_t end) {
    const auto x0 = static_cast<float>(value(kMinX)), y0 = static_cast<float>(value(kMinY));
    const auto x1 = static_cast<float>(value(kMaxX)), y1 = static_cast<float>(value(kMaxY));
    // As the wind with zero wind velocity: keeps exactly exp(-c dt) of the velocity per
    // sub-step and never reverses it.
    const auto lambda = static_cast<float>(detail::relaxationRate(value(kRate), context.dt));
    const auto px = context.particles.px, py = context.particles.py;
    const auto vx = context.particles.vx, vy = context.particles.vy;
    for (uint32_t i = begin; i < end; ++i) {
        if (px[i] >= x0 && px[i] <= x1 && py[i] >= y0 && py[i] <= y1) {
            context.ax[i] -= lambda * vx[i];
            context.ay[i] -= lambda * vy[i];
        }
    }
}

} // namespace fluid
