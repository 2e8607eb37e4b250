// fluid — built-in force plugin: wind, an exact exponential drag towards a wind velocity.
#include <fluid/plugins/wind.h>

#include "relaxation.h"

#include <cmath>

namespace fluid {

WindForce::WindForce(glm::vec2 velocity, float rate) : WindForce() {
    setParam("vx", velocity.x);
    setParam("vy", velocity.y);
    setParam("rate", rate);
}

void WindForce::apply(const ForceContext& context, uint32_t begin, uint32_t end) {
    const auto wx = static_cast<float>(value(kVx)), wy = static_cast<float>(value(kVy));
    const auto x0 = static_cast<float>(value(kMinX)), y0 = static_cast<float>(value(kMinY));
    const auto x1 = static_cast<float>(value(kMaxX)), y1 = static_cast<float>(value(kMaxY));
    const auto lambda = static_cast<float>(detail::relaxationRate(value(kRate), context.dt));
    detail::relaxInBox(context, begin, end, {x0, y0}, {x1, y1}, lambda, wx, wy);
}

} // namespace fluid
