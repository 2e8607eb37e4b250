// fluid — built-in force plugins: the exact relaxation rate shared by drag-type forces.
#pragma once

#include <cmath>

namespace fluid::detail {

/// The acceleration factor lambda for a drag a = lambda (target - v) over a sub-step of `dt`
/// seconds at `rate` (1/s): lambda dt = 1 - exp(-rate dt), so a sub-step leaves exactly
/// exp(-rate dt) of the velocity difference, however large rate dt (the explicit rate would
/// overshoot past the target at rate dt > 1 and diverge at rate dt > 2). dt = 0 (the
/// instantaneous field) gives `rate`.
inline double relaxationRate(double rate, double dt) {
    return dt > 0.0 ? -std::expm1(-rate * dt) / dt : rate;
}

} // namespace fluid::detail
