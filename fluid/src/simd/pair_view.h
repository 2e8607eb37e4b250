// fluid — plain views of the particles, samples and grids for the pair passes (pbf_pairs.inc),
// and the table of those passes for the instruction set the machine has.
//
// The passes are compiled once per instruction set (pbf_pairs_*.cpp). Their object files
// include nothing but this header (with ../yield_law.h), ../kernel_constants.h,
// ../pbf_tuning.h, <immintrin.h> and <cstdint>, and define everything they use with internal linkage, so no inline function of
// the standard library can be linked from a wider instruction set than the machine runs.
#pragma once

#include "../yield_law.h"

#include <cstdint>

// Forces inlining of the pair passes' per-range and per-block lambdas: a call per block would
// keep the lane accumulators in memory (measured: half of a pass's time).
#define FLUID_INLINE __attribute__((always_inline))

namespace fluid::detail {

/// Rows above and below a point's row that a grid query visits, at most.
inline constexpr int kGridMaxRows = 4;

/// A counting-sorted grid (grid.h) as plain data.
struct GridView {
    const uint32_t* start = nullptr; // cell (or bucket) -> first sorted position; cells + 1
    int64_t ox = 0, oy = 0;          // dense: cell coordinates of the first cell
    uint32_t nx = 0, ny = 0;         // dense: cells across and up
    uint32_t mask = 0;               // hashed: buckets - 1
    float invCellX = 1.0f;           // 1 / cell width (1/m)
    float invCellY = 1.0f;           // 1 / cell height (1/m)
    uint32_t count = 0;              // points sorted
    bool hashed = false;
    // Dense: a query visits rows -rows..rows around the point's row, and in row k the cells
    // -span[|k|]..span[|k|] around its column: every cell that can hold a point within the
    // query radius of some point of the query's cell.
    int32_t rows = 1;
    int32_t span[kGridMaxRows + 1] = {1, 1, 0, 0, 0};
};

/// Cell coordinate of `v` in cells of 1/`invCell` (clamped, so absurd coordinates cannot
/// overflow; such points only lose neighbours). Static: every instruction set's object file
/// keeps its own copy (see the file comment), and grid.h sorts with the same one.
static inline int64_t gridCell(float v, float invCell) {
    const double c = __builtin_floor(double(v) * double(invCell));
    // Clamped so that the cast is defined; NaN (which no comparison holds for) takes the low end.
    return int64_t(c >= -1.0e15 ? (c <= 1.0e15 ? c : 1.0e15) : -1.0e15);
}

/// Bucket of cell (cx, cy) in a hashed grid of mask + 1 buckets.
static inline uint32_t gridHash(int64_t cx, int64_t cy, uint32_t mask) {
    const uint64_t h = uint64_t(cx) * 73856093ull ^ uint64_t(cy) * 19349663ull;
    return uint32_t((h ^ (h >> 29)) & mask);
}

/// f(b, e) for each range of sorted points that may hold a point within the grid's query
/// radius of (x, y), in a fixed order: dense grids one range per row (a row's cells are
/// contiguous in sorted order), bottom to top; hashed grids each distinct bucket of the 3x3
/// cells once, in bucket order. Static for the same reason as gridCell.
template <class Fn>
FLUID_INLINE static inline void gridRanges(const GridView& g, float x, float y, Fn&& f) {
    if (g.count == 0) {
        return;
    }
    const int64_t cx = gridCell(x, g.invCellX);
    const int64_t cy = gridCell(y, g.invCellY);
    if (!g.hashed) {
        const int64_t col = cx - g.ox, nx = int64_t(g.nx);
        for (int64_t k = -g.rows; k <= g.rows; ++k) {
            const int64_t row = cy - g.oy + k;
            if (row < 0 || row >= int64_t(g.ny)) {
                continue;
            }
            const int64_t w = g.span[k < 0 ? -k : k];
            const int64_t x0 = col - w < 0 ? 0 : col - w;
            const int64_t x1 = col + w > nx - 1 ? nx - 1 : col + w;
            if (x0 > x1) {
                continue;
            }
            const uint32_t b = g.start[row * nx + x0];
            const uint32_t e = g.start[row * nx + x1 + 1];
            if (b < e) {
                f(b, e);
            }
        }
        return;
    }
    uint32_t buckets[9];
    int n = 0;
    for (int64_t dy = -1; dy <= 1; ++dy) {
        for (int64_t dx = -1; dx <= 1; ++dx) {
            const uint32_t key = gridHash(cx + dx, cy + dy, g.mask);
            int k = n++;
            while (k > 0 && buckets[k - 1] > key) { // insertion sort: bucket order
                buckets[k] = buckets[k - 1];
                --k;
            }
            buckets[k] = key;
        }
    }
    for (int k = 0; k < n; ++k) {
        if (k > 0 && buckets[k] == buckets[k - 1]) {
            continue;
        }
        const uint32_t b = g.start[buckets[k]];
        const uint32_t e = g.start[buckets[k] + 1];
        if (b < e) {
            f(b, e);
        }
    }
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
    // A yield-stress material's skin (Particles::skinGamma; null in worlds without one): the
    // extra cohesion gamma, the material index as a float and the share of the kernel weight
    // other materials hold (1).
    const float *skinGamma = nullptr, *materialTag = nullptr, *otherShare = nullptr;
    const float* leastDiagonal = nullptr; // per material: least denominator of a multiplier
    // A viscosity run split by viscosity (pbfViscosity's `split`): 1 for a particle of a
    // material that needs the run's passes, 0 for one that one pass holds; from the first
    // pass, 1 for a particle with such a particle in its support (itself included); and what a
    // pair of two low-viscosity particles is weighted by in the first pass (the run's passes).
    const float *viscousTag = nullptr, *viscousFlag = nullptr;
    float splitWeight = 0;
    // Yielding worlds (Material::yieldStress): each particle's deviatoric stress (Pa) and the
    // same over rho0^2 (m^2/s^2), and per material its Herschel-Bulkley law this step.
    const float *sxx = nullptr, *sxy = nullptr, *tx = nullptr, *ty = nullptr;
    const float* rigidity = nullptr; // 1 - |s| / tau_y in [0, 1]; 0 for Newtonian particles
    const YieldLaw* yield = nullptr;
    // ... and the surface pass's acceleration (m/s^2), which the stress pass adds to.
    const float *surfaceAx = nullptr, *surfaceAy = nullptr;
    bool yielding = false; // some material yields: the stress passes run
    GridView grid;
    // Boundary samples (sorted by their own grid): positions, velocities, friction.
    uint32_t samples = 0;
    const float *wx = nullptr, *wy = nullptr, *wvx = nullptr, *wvy = nullptr;
    const float* friction = nullptr;
    GridView sampleGrid;
    // 1/h when every particle has the same support h (1/m), else 0.
    float invSupport = 0;
    // True when the world has one material: every pair's material values are particle i's.
    bool oneMaterial = false;
    // Constants of the sub-step (see PbfConstants).
    float dt = 0, sampleVolume = 0, epsilon = 0, artificial = 0, invWdq = 0;
};

/// Outputs of the passes (each pass writes only slots [b, e) of the arrays it names).
struct PbfOut {
    float *constraint = nullptr, *diagonal = nullptr, *density = nullptr, *invRho = nullptr;
    float *ax = nullptr, *ay = nullptr, *vorticity = nullptr, *nx = nullptr, *ny = nullptr;
    float *vx = nullptr, *vy = nullptr;
    float *sxx = nullptr, *sxy = nullptr, *tx = nullptr, *ty = nullptr, *rigidity = nullptr;
    float *wallNx = nullptr, *wallNy = nullptr, *wallAdhesion = nullptr;
    float* otherShare = nullptr; // the viscosity run's first pass, in a world with a skin
    float* viscousFlag = nullptr; // the first pass of a split viscosity run (PbfView)
};

/// The shear constraint's channels (pbf_shear.cpp), all in sorted order: its inputs (the
/// reference positions the kernel gradients are taken at (the sweeps' start) and the
/// displacement since the sub-step's start u = x - x_start (m), 1 for a particle of a yielding
/// material and 0 for the others, and each particle's multiplier change times its inverse
/// correction matrix, S(dl) M^-1: xx, xy, yx, yy) and its outputs (each pass writes only
/// particle i's slots).
struct ShearView {
    const float *refX = nullptr, *refY = nullptr, *ux = nullptr, *uy = nullptr;
    const float* yields = nullptr;
    const float *t00 = nullptr, *t01 = nullptr, *t10 = nullptr, *t11 = nullptr;
    // shearRead: the gradient sum H = sum (u_j - u_i) (x) V_j grad W_ij (xx, xy, yx, yy; 1)
    // and, with `matrix`, the correction matrix M (xx, xy, yy; 1) and S = sum V_j grad W_ij
    // (1/m), walls included.
    float *mxx = nullptr, *mxy = nullptr, *myy = nullptr;
    float *hxx = nullptr, *hxy = nullptr, *hyx = nullptr, *hyy = nullptr;
    float *sumX = nullptr, *sumY = nullptr;
    float* trace = nullptr; // tr (sum_j w_j G_ij (x) G_ij + w_i S_i (x) S_i) (1/(kg m^2))
    // With `matrix`: the walls' part of S (1/m), their friction-weighted kernel sum (1) and
    // their velocity weighted by it (m/s).
    float *wallX = nullptr, *wallY = nullptr, *wallWeight = nullptr;
    float *wallVx = nullptr, *wallVy = nullptr;
    // shearGather: sum_j S(dl_j) M_j^-1 V_i grad_j W_ji - S(dl_i) M_i^-1 sum (kg m per depth).
    float *dx = nullptr, *dy = nullptr;
};

/// One instruction set's pair passes over particles [b, e); see pbf_loops.h for what each
/// computes.
struct PbfPairs {
    const char* name; // "sse2", "avx2" or "avx512"
    void (*constraint)(const PbfView&, const PbfOut&, uint32_t b, uint32_t e);
    void (*displace)(const PbfView&, const PbfOut&, const float* multiplier, bool sCorr, uint32_t b,
                     uint32_t e);
    void (*viscosity)(const PbfView&, const PbfOut&, float scale, bool first, bool curl, int split,
                      uint32_t b, uint32_t e);
    void (*surface)(const PbfView&, const PbfOut&, float vorticity, bool surfaceTension, uint32_t b,
                    uint32_t e);
    void (*stress)(const PbfView&, const PbfOut&, uint32_t b, uint32_t e);
    void (*shearRead)(const PbfView&, const ShearView&, bool matrix, uint32_t b, uint32_t e);
    void (*shearGather)(const PbfView&, const ShearView&, uint32_t b, uint32_t e);
};

/// The passes of each instruction set (pbf_pairs_*.cpp; "sse2" is plain C++ off x86).
extern const PbfPairs kPbfPairsSse2;
extern const PbfPairs kPbfPairsAvx2;
extern const PbfPairs kPbfPairsAvx512;

/// The widest set this machine runs, or the narrower one the FLUID_SIMD environment variable
/// names (read once, at the first call; thread-safe).
const PbfPairs& pbfPairs();

} // namespace fluid::detail
