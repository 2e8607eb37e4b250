// fluid — plain views of the particles, samples and grids for the pair passes (pbf_pairs.inc),
// and the table of those passes for the instruction set the machine has.
//
// The passes are compiled once per instruction set (pbf_pairs_*.cpp). Their object files
// include nothing but this header, <immintrin.h> and <cstdint>, and define everything they use
// with internal linkage, so no inline function of the standard library can be linked from a
// wider instruction set than the machine runs.
#pragma once

#include <cstdint>

namespace fluid::detail {

/// A counting-sorted grid (grid.h) as plain data.
struct GridView {
    const uint32_t* start = nullptr; // cell (or bucket) -> first sorted position; cells + 1
    int64_t ox = 0, oy = 0;          // dense: cell coordinates of the first cell
    uint32_t nx = 0, ny = 0;         // dense: cells across and up
    uint32_t mask = 0;               // hashed: buckets - 1
    float invCell = 1.0f;            // 1 / cell size (1/m)
    uint32_t count = 0;              // points sorted
    bool hashed = false;
};

/// Cell coordinate of `v` in cells of 1/`invCell` (clamped, so absurd coordinates cannot
/// overflow; such points only lose neighbours). Static: every instruction set's object file
/// keeps its own copy (see the file comment), and grid.h sorts with the same one.
static inline int64_t gridCell(float v, float invCell) {
    const double c = __builtin_floor(double(v) * double(invCell));
    return int64_t(c < -1.0e15 ? -1.0e15 : (c > 1.0e15 ? 1.0e15 : c));
}

/// Bucket of cell (cx, cy) in a hashed grid of mask + 1 buckets.
static inline uint32_t gridHash(int64_t cx, int64_t cy, uint32_t mask) {
    const uint64_t h = uint64_t(cx) * 73856093ull ^ uint64_t(cy) * 19349663ull;
    return uint32_t((h ^ (h >> 29)) & mask);
}

/// Inputs and outputs of the position-based solver's pair passes, all in sorted order.
struct PbfView {
    uint32_t n = 0; // particles
    // Particles: positions (m), velocities (m/s), support h (m), 1/mass (1/kg), rest area
    // V = m/(depth rho0) (m^2), 1 / lattice sum, pair pressure of s_corr (Pa), viscosity mu (Pa
    // s), mass / depth (kg/m), 1/rho, mass (kg), rest density and density (kg/m^3), surface
    // tension gamma, vorticity (1/s), normals, material index.
    const float *px = nullptr, *py = nullptr, *vx = nullptr, *vy = nullptr, *h = nullptr;
    const float *invMass = nullptr, *volume = nullptr, *invLattice = nullptr;
    const float *pairPressure = nullptr, *viscosity = nullptr, *massPerDepth = nullptr;
    const float *invRho = nullptr, *mass = nullptr, *restDensity = nullptr, *gamma = nullptr;
    const float *density = nullptr, *vorticity = nullptr, *nx = nullptr, *ny = nullptr;
    const uint16_t* material = nullptr;
    const float* leastDiagonal = nullptr; // per material: least denominator of a multiplier
    GridView grid;
    // Boundary samples (sorted by their own grid): positions, velocities, friction.
    uint32_t samples = 0;
    const float *wx = nullptr, *wy = nullptr, *wvx = nullptr, *wvy = nullptr;
    const float* friction = nullptr;
    GridView sampleGrid;
    // 1/h when every particle has the same support h (1/m), else 0.
    float invSupport = 0;
    // Constants of the sub-step (see PbfConstants).
    float dt = 0, sampleVolume = 0, epsilon = 0, artificial = 0, invWdq = 0;
};

/// Outputs of the passes (each pass writes only slots [b, e) of the arrays it names).
struct PbfOut {
    float *constraint = nullptr, *diagonal = nullptr, *density = nullptr, *invRho = nullptr;
    float *ax = nullptr, *ay = nullptr, *vorticity = nullptr, *nx = nullptr, *ny = nullptr;
    float *vx = nullptr, *vy = nullptr;
};

/// One instruction set's pair passes over particles [b, e); see pbf_loops.h for what each
/// computes.
struct PbfPairs {
    const char* name; // "sse2", "avx2" or "avx512"
    void (*constraint)(const PbfView&, const PbfOut&, uint32_t b, uint32_t e);
    void (*displace)(const PbfView&, const PbfOut&, const float* multiplier, bool sCorr, uint32_t b,
                     uint32_t e);
    void (*viscosity)(const PbfView&, const PbfOut&, float scale, bool first, uint32_t b,
                      uint32_t e);
    void (*surface)(const PbfView&, const PbfOut&, float vorticity, bool surfaceTension, uint32_t b,
                    uint32_t e);
};

/// The passes of each instruction set (pbf_pairs_*.cpp; "sse2" is plain C++ off x86).
extern const PbfPairs kPbfPairsSse2;
extern const PbfPairs kPbfPairsAvx2;
extern const PbfPairs kPbfPairsAvx512;

/// The widest set this machine runs, or the narrower one the FLUID_SIMD environment variable
/// names (read once, at the first call; thread-safe).
const PbfPairs& pbfPairs();

} // namespace fluid::detail
