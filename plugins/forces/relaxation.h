// fluid — built-in force plugins: the exact relaxation shared by drag-type forces.
#pragma once

#include <fluid/plugin.h>

#include <cmath>
#include <cstdint>

namespace fluid::detail {

/// The acceleration factor lambda for a drag a = lambda (target - v) over a sub-step of `dt`
/// seconds at `rate` (1/s): lambda dt = 1 - exp(-rate dt), so a sub-step leaves exactly
/// exp(-rate dt) of the velocity difference, however large rate dt (the explicit rate would
/// overshoot past the target at rate dt > 1 and diverge at rate dt > 2). dt = 0 (the
/// instantaneous field) gives `rate`.
inline double relaxationRate(double rate, double dt) {
    return dt > 0.0 ? -std::expm1(-rate * dt) / dt : rate;
}

/// The wind's and the damping zone's loop: particles [begin, end) inside the box [x0, x1] x
/// [y0, y1] (unit: m) are pulled towards the velocity (wx, wy) (unit: m/s) by
/// a += lambda (w - v), lambda from `relaxationRate` (unit: 1/s).
inline void relaxInBox(const ForceContext& context, uint32_t begin, uint32_t end, glm::vec2 min,
                       glm::vec2 max, float lambda, float wx, float wy) {
    const auto px = context.particles.px, py = context.particles.py;
    const auto vx = context.particles.vx, vy = context.particles.vy;
    for (uint32_t i = begin; i < end; ++i) {
        if (px[i] >= min.x && px[i] <= max.x && py[i] >= min.y && py[i] <= max.y) {
            context.ax[i] += lambda * (wx - vx[i]);
            context.ay[i] += lambda * (wy - vy[i]);
        }
    }
}

} // namespace fluid::detail
