// fluid — smoothing kernels, normalised over the plane (2D).
//
// Why Wendland C2 for density and pressure (see docs/kernels.md for the numbers): its Fourier
// transform is non-negative, so it has no pairing instability at any neighbour count [Dehnen &
// Aly 2012] — the seed's materials run at 32-50 neighbours, where poly6 and the cubic spline,
// whose transforms dip below zero, let particles clump into pairs; one kernel then serves
// density and pressure, so the pair force is the gradient of the density it came from (Mueller
// 2003 takes density from poly6 and pressure from "spiky"); and it reads a square lattice at
// the presets' spacings within 0.42% (water) and 0.13% (yoghurt). Like every smooth kernel its
// gradient vanishes at r = 0: what keeps two particles apart is pressure, not the kernel.
#pragma once

#include "kernel_constants.h"

#include <cmath>

namespace fluid::kernel {

/// Wendland C2, support radius h: W = 7/(pi h^2) (1-q)^4 (1+4q), q = r/h < 1 [Wendland 1995].
inline float wendland(float r, float h) {
    const float q = r / h;
    if (q >= 1.0f) {
        return 0.0f;
    }
    const float t = 1.0f - q;
    const float t2 = t * t;
    return 7.0f / (kPi * h * h) * (t2 * t2) * (1.0f + 4.0f * q);
}

/// dW/dr divided by r for Wendland C2: -140/(pi h^4) (1-q)^3. Finite at r = 0, so the gradient
/// is this value times (x_i - x_j), with no division by r.
inline float wendlandGradOverR(float r, float h) {
    const float q = r / h;
    if (q >= 1.0f) {
        return 0.0f;
    }
    const float t = 1.0f - q;
    const float h2 = h * h;
    return -140.0f / (kPi * h2 * h2) * (t * t * t);
}

/// The seed's viscosity Laplacian (eq. 2.6, Mueller 2003) normalised for 2D:
/// L = 40/(pi h^5) (h - r). The constant makes sum_j V_j (v_j - v_i) L a consistent Laplacian:
/// for v = x^2 the integral of x^2 L over the disc is 2, i.e. int_0^h r^3 L dr = 2/pi.
inline float viscosityLaplacian(float r, float h) {
    if (r >= h) {
        return 0.0f;
    }
    const float h2 = h * h;
    return 40.0f / (kPi * h2 * h2 * h) * (h - r);
}

/// Cohesion spline of [Akinci 2013, eq. 2] in 2D, normalised so that its integral over the disc
/// of radius h is 1 (unit: 1/m^2). Akinci's 32/(pi h^9) is the 3D normalisation; in 2D it would
/// make gamma depend on h and on the dimension, so we fix the integral instead (kC, in
/// kernel_constants.h).
inline float cohesion(float r, float h) {
    if (r >= h || r <= 0.0f) {
        return 0.0f;
    }
    const float u = r / h;
    const float a = (1.0f - u) * u;
    const float a3 = a * a * a;
    const float s = (2.0f * u > 1.0f) ? a3 : 2.0f * a3 - 1.0f / 64.0f;
    return kC / (h * h) * s;
}

} // namespace fluid::kernel
