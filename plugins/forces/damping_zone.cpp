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
    detail::relaxInBox(context, begin, end, {x0, y0}, {x1, y1}, lambda, 0.0f, 0.0f);
}

} // namespace fluid
