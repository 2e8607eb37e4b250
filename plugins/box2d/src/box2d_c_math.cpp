// fluid::box2d — the C library's sinf, cosf, sincosf and atan2f, replaced for Box2D by the deterministic
// ones of box2d_math.cpp (see there, and docs/box2d.md, "The same bits everywhere"). No C
// library header here: they would declare these names with their own attributes.
#include "box2d_math.h"

extern "C" {

float sinf(float x);
float cosf(float x);
void sincosf(float x, float* s, float* c);
float atan2f(float y, float x);

float sinf(float x) {
    return fluid::box2d::detail::sin(x);
}

float cosf(float x) {
    return fluid::box2d::detail::cos(x);
}

// GCC turns a sinf and a cosf of one angle into one sincosf (Debian's Box2D calls it).
void sincosf(float x, float* s, float* c) {
    *s = fluid::box2d::detail::sin(x);
    *c = fluid::box2d::detail::cos(x);
}

float atan2f(float y, float x) {
    return fluid::box2d::detail::atan2(y, x);
}

} // extern "C"

namespace fluid::box2d::detail {

void linkMath() {}

} // namespace fluid::box2d::detail
