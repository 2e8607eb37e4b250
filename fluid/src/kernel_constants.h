// fluid — the smoothing kernels' constants, written once: kernels.h's reference formulas, the
// lane loops (lanes.h: sph_loops.cpp, pbf_loops.cpp, step_common.cpp) and the SIMD pair passes
// (simd/pbf_pairs.inc) all read these (derivations in kernels.h and docs/kernels.md).
//
// Plain constexpr floats at namespace scope, so of internal linkage, and no include: the pair
// passes' object files, compiled once per instruction set, take nothing from here that the
// linker could share between them (see simd/pair_view.h).
#pragma once

namespace fluid::kernel {

constexpr float kPi = 3.14159265358979323846f;
constexpr float kW = 7.0f / kPi;    // Wendland C2: W = kW / h^2 (1-q)^4 (1+4q)
constexpr float kG = -140.0f / kPi; // dW/dr / r = kG / h^4 (1-q)^3
constexpr float kL = 40.0f / kPi;   // viscosity Laplacian = kL / h^4 (1-q)
// Cohesion = kC / h^2 spline(q): the spline of kernel::cohesion integrates to 2 pi h^2 *
// 209/71680 over the disc (exact), so kC = 35840/(209 pi) makes the integral 1.
constexpr float kC = 35840.0f / (209.0f * kPi);

} // namespace fluid::kernel
