// fluid::box2d internals — deterministic sin, cos and atan2 for Box2D (box2d_math.cpp).
#pragma once

namespace fluid::box2d::detail {

/// sin(x) rounded to float, the same bits on every platform (unit: rad; any float, NaN for
/// NaN and the infinities). Any thread.
float sin(float x);
/// cos(x), as `sin`.
float cos(float x);
/// atan2(y, x) in [-pi, pi] rounded to float, the same bits everywhere, with the C standard's
/// zeros, infinities and NaN. Any thread.
float atan2(float y, float x);
/// Does nothing: coupling.cpp calls it so that every program linking fluid::box2d links
/// box2d_c_math.cpp's sinf, cosf, sincosf and atan2f too (a static library's member is linked only
/// when something names it).
void linkMath();

} // namespace fluid::box2d::detail
