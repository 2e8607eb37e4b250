// fluid::box2d internals — deterministic sin, cos and atan2 for Box2D and the coupling
// (box2d_math.cpp).
#pragma once

namespace fluid::box2d::detail {

/// sin(x) rounded to float, the same bits on every platform (unit: rad; any float, NaN for
/// NaN and the infinities). Any thread.
float sin(float x);
/// cos(x), as `sin`.
float cos(float x);
/// sin(x) in double, within about one unit in the last place, the same bits on every platform
/// (unit: rad; any double, NaN for NaN and the infinities): the coupling turns bodies' outlines
/// with it, as Box2D turns their fixtures with `sin(float)`. Any thread.
double sin(double x);
/// cos(x) in double, as `sin(double)`.
double cos(double x);
/// atan2(y, x) in [-pi, pi] rounded to float, the same bits everywhere, with the C standard's
/// zeros, infinities and NaN. Any thread.
float atan2(float y, float x);
/// Does nothing: coupling.cpp calls it so that every program linking fluid::box2d links
/// box2d_c_math.cpp's sinf, cosf, sincosf and atan2f too (a static library's member is linked only
/// when something names it).
void linkMath();

} // namespace fluid::box2d::detail
