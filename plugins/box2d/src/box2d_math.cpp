// fluid::box2d — the sinf, cosf and atan2f Box2D turns its bodies with, and the double sin and
// cos the coupling turns their outlines with: the same bits on every platform (docs/box2d.md,
// "The same bits everywhere").
//
// Box2D 2.4 calls the C library's sinf and cosf (GCC makes a sincosf of the pair) for every
// awake body every step (b2Rot::Set) and atan2f for joint angles. C libraries round some arguments differently (glibc against
// emscripten's musl; glibc itself picks an FMA variant on CPUs that have it), so a body could
// turn by another last bit on another machine, and a game's state part from there. These
// definitions take the C library's place in every program that links fluid::box2d: natively
// the program's own sinf is the one the shared Box2D library binds to (ELF interposition), in a
// static WebAssembly link the C library's is never pulled in. They use +, -, * and / on doubles
// only (no fused multiply-add: the project builds with -ffp-contract=off), the same operations
// in the same order everywhere: fdlibm's argument reduction and kernels (Sun Microsystems,
// 1993, freely redistributable), rounded once to float at the end; within one unit in the last
// place of the exact value (tests/box2d/test_box2d_math.cpp measures it against the C library).
#include "box2d_math.h"

#include <cmath>
#include <cstdint>

namespace fluid::box2d::detail {

namespace {

// pi/2 as the sum of three parts (fdlibm's pio2_1, pio2_2 and pio2_2t): the first two of 33
// bits, so k * kPio2Hi and k * kPio2Mid are exact for |k| < 2^20, the last the rest to double
// precision.
constexpr double kPio2Hi = 1.57079632673412561417e+00;
constexpr double kPio2Mid = 6.07710050630396597660e-11;
constexpr double kPio2Lo = 2.02226624879595063154e-21;
constexpr double kTwoOverPi = 6.36619772367581382433e-01;
constexpr double kTwoPi = 6.28318530717958623200e+00;

// sin(r) and cos(r) for |r| <= pi/4 (fdlibm's __kernel_sin and __kernel_cos polynomials).
double sinKernel(double r) {
    constexpr double s1 = -1.66666666666666324348e-01, s2 = 8.33333333332248946124e-03,
                     s3 = -1.98412698298579493134e-04, s4 = 2.75573137070700676789e-06,
                     s5 = -2.50507602534068634195e-08, s6 = 1.58969099521155010221e-10;
    const double z = r * r;
    return r + r * z * (s1 + z * (s2 + z * (s3 + z * (s4 + z * (s5 + z * s6)))));
}

double cosKernel(double r) {
    constexpr double c1 = 4.16666666666666019037e-02, c2 = -1.38888888888741095749e-03,
                     c3 = 2.48015872894767294178e-05, c4 = -2.75573143513906633035e-07,
                     c5 = 2.08757232129817482790e-09, c6 = -1.13596475577881948265e-11;
    const double z = r * r;
    return 1.0 - 0.5 * z + z * z * (c1 + z * (c2 + z * (c3 + z * (c4 + z * (c5 + z * c6)))));
}

// x reduced to r in [-pi/4, pi/4] and the quadrant q (0-3) with x = r + q pi/2 (mod 2 pi).
double reduce(double x, int& q) {
    if (std::fabs(x) <= 0.785398163397448279) {
        q = 0;
        return x;
    }
    if (std::fabs(x) > 1.0e6) {
        // Far out the float itself is coarser than a turn's share; fmod is exact everywhere.
        x = std::fmod(x, kTwoPi);
    }
    const double t = x * kTwoOverPi;
    const double k = static_cast<double>(static_cast<int64_t>(t + (t >= 0.0 ? 0.5 : -0.5)));
    q = static_cast<int>(static_cast<int64_t>(k) & 3);
    return ((x - k * kPio2Hi) - k * kPio2Mid) - k * kPio2Lo;
}

// atan(t) for t >= 0 (fdlibm's s_atan.c: four breakpoints, then one polynomial).
double atanPositive(double t) {
    constexpr double hi[] = {4.63647609000806093515e-01, 7.85398163397448278999e-01,
                             9.82793723247329054082e-01, 1.57079632679489655800e+00};
    constexpr double lo[] = {2.26987774529616870924e-17, 3.06161699786838301793e-17,
                             1.39033110312309984516e-17, 6.12323399573676603587e-17};
    constexpr double a[] = {3.33333333333329318027e-01,  -1.99999999998764832476e-01,
                            1.42857142725034663711e-01,  -1.11111104054623557880e-01,
                            9.09088713343650656196e-02,  -7.69187620504482999495e-02,
                            6.66107313738753120669e-02,  -5.83357013379057348645e-02,
                            4.97687799461593236017e-02,  -3.65315727442169155270e-02,
                            1.62858201153657823623e-02};
    if (t >= 7.3786976294838206464e19) { // 2^66: atan is pi/2 to double precision
        return hi[3] + lo[3];
    }
    int id = -1;
    if (t >= 0.4375) {
        if (t < 0.6875) {
            id = 0;
            t = (2.0 * t - 1.0) / (2.0 + t);
        } else if (t < 1.1875) {
            id = 1;
            t = (t - 1.0) / (t + 1.0);
        } else if (t < 2.4375) {
            id = 2;
            t = (t - 1.5) / (1.0 + 1.5 * t);
        } else {
            id = 3;
            t = -1.0 / t;
        }
    }
    const double z = t * t, w = z * z;
    const double s1 = z * (a[0] + w * (a[2] + w * (a[4] + w * (a[6] + w * (a[8] + w * a[10])))));
    const double s2 = w * (a[1] + w * (a[3] + w * (a[5] + w * (a[7] + w * a[9]))));
    if (id < 0) {
        return t - t * (s1 + s2);
    }
    return hi[id] - ((t * (s1 + s2) - lo[id]) - t);
}

} // namespace

float sin(float x) {
    if (!std::isfinite(x)) {
        return x - x; // NaN for NaN and the infinities
    }
    if (x == 0.0f) {
        return x; // +-0 keeps its sign
    }
    int q = 0;
    const double r = reduce(double(x), q);
    const double v = (q & 1) == 0 ? sinKernel(r) : cosKernel(r);
    return static_cast<float>(q >= 2 ? -v : v);
}

float cos(float x) {
    if (!std::isfinite(x)) {
        return x - x;
    }
    int q = 0;
    const double r = reduce(double(x), q);
    const double v = (q & 1) == 0 ? cosKernel(r) : sinKernel(r);
    return static_cast<float>((q == 1 || q == 2) ? -v : v);
}

double sin(double x) {
    if (!std::isfinite(x)) {
        return x - x;
    }
    if (x == 0.0) {
        return x;
    }
    int q = 0;
    const double r = reduce(x, q);
    const double v = (q & 1) == 0 ? sinKernel(r) : cosKernel(r);
    return q >= 2 ? -v : v;
}

double cos(double x) {
    if (!std::isfinite(x)) {
        return x - x;
    }
    int q = 0;
    const double r = reduce(x, q);
    const double v = (q & 1) == 0 ? cosKernel(r) : sinKernel(r);
    return (q == 1 || q == 2) ? -v : v;
}

float atan2(float y, float x) {
    constexpr double kPi = 3.14159265358979311600e+00, kPiLo = 1.22464679914735317720e-16;
    constexpr double kHalfPi = 1.57079632679489655800e+00;
    if (std::isnan(x) || std::isnan(y)) {
        return x + y;
    }
    const double yd = y, xd = x;
    const bool negativeY = std::signbit(y);
    const double sign = negativeY ? -1.0 : 1.0;
    if (y == 0.0f) {
        // +-0 for x > 0 or +0, +-pi for x < 0 or -0 (the sign of y kept).
        return std::signbit(x) ? static_cast<float>(sign * kPi) : y;
    }
    if (x == 0.0f) {
        return static_cast<float>(sign * kHalfPi);
    }
    if (std::isinf(x)) {
        if (std::isinf(y)) {
            return static_cast<float>(sign * (x > 0.0f ? 0.25 * kPi : 0.75 * kPi));
        }
        return x > 0.0f ? static_cast<float>(sign * 0.0) : static_cast<float>(sign * kPi);
    }
    if (std::isinf(y)) {
        return static_cast<float>(sign * kHalfPi);
    }
    const double a = atanPositive(std::fabs(yd / xd));
    const double angle = x > 0.0f ? a : (kPi - (a - kPiLo));
    return static_cast<float>(sign * angle);
}

} // namespace fluid::box2d::detail
