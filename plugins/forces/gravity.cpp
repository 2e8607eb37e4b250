// fluid — built-in force plugin: uniform gravity (seed eq. 2.7's g).
#include <fluid/plugins/gravity.h>

namespace fluid {

GravityForce::GravityForce(float gx, float gy) : GravityForce() {
    setParam("gx", gx);
    setParam("gy", gy);
}

void GravityForce::apply(const ForceContext& context, uint32_t begin, uint32_t end) {
    const auto gx = static_cast<float>(value(0));
    const auto gy = static_cast<float>(value(1));
    for (uint32_t i = begin; i < end; ++i) {
        context.ax[i] += gx;
        context.ay[i] += gy;
    }
}

} // namespace fluid
