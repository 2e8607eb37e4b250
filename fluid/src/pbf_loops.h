// fluid — the neighbour passes of the position-based solver (pbf_loops.cpp).
#pragma once

#include "pbf_tuning.h"
#include "world_state.h"
#include "yield_law.h"

#include <span>
#include <vector>

namespace fluid::detail {

/// Constants of one position-based sub-step.
struct PbfConstants {
    float dt = 0;           // sub-step (s)
    float sampleVolume = 0; // V_w, area of a boundary sample (m^2)
    float epsilon = 0;      // regulariser of the multiplier's denominator (1/(kg m^2))
    float floorShare = 0;   // least denominator, as a share of the material's lattice diagonal
    float artificial = 0;   // s_corr scale: 2 depth dt^2 (unit: m s^2, times Pa m^4 per pair)
    float invWdq = 0;       // 1 / ((1-dq)^4 (1+4 dq)): s_corr's kernel ratio at r = dq h
};

struct PbfView;

/// The particles, samples and grids of the current sub-step as plain data for the neighbour
/// passes (simd/pair_view.h).
PbfView pbfView(const WorldState& s, const PbfConstants& c);

/// The density constraint C_i = (V_i sum_j W_ij + V_w sum_w W_iw) / L_i - 1 at the current
/// positions (rest area V = m/(depth rho0), boundary samples of area V_w, L_i the kernel sum of
/// the material's own lattice, so the spawn lattice reads 0) into `constraint`, the diagonal of
/// A = J W J^T, w_i |grad_i C_i|^2 + sum_j w_j |grad_j C_i|^2 + eps (w = 1/m), into `diagonal`,
/// the density rho_i = rho0_i (C_i + 1) and 1/rho_i [Macklin & Mueller 2013].
/// With `relaxation` (per material), each particle's multiplier is then updated in the same
/// task: l_i <- min(l_i - relaxation C_i / D_i, 0), and `constraint` takes the change (one
/// hand-over to the workers less per sweep).
void pbfConstraint(WorldState& s, const PbfConstants& c, const float* relaxation = nullptr);

/// The displacement W J^T lambda of multipliers `multiplier` into ax, ay (m), with V and V_w
/// over the lattice sums L as in `pbfConstraint`:
///   dx_i = w_i [sum_j (l_i V_i + l_j V_j + s_ij) grad W_ij + l_i V_w sum_w grad W_iw],
/// s_ij the artificial pressure term [Macklin & Mueller 2013, eq. 13] when `sCorr`. Every fluid
/// pair term is antisymmetric times m_i, so displacements conserve momentum.
void pbfDisplace(WorldState& s, const PbfConstants& c, std::span<const float> multiplier,
                 bool sCorr);

/// Each material's Herschel-Bulkley law (yield_law.h) over a viscosity run of `dt`, its shear
/// modulus capped by kShearWave; empty in a world without a yielding material. Built once per
/// run, for `pbfViscosity`'s first pass and `pbfStress`.
std::vector<YieldLaw> yieldLaws(const WorldState& s, float dt);

/// Viscosity, seed eq. 2.6 with rest volumes, as an explicit velocity update over dt * `scale`
/// into ax, ay (wall friction from the boundary samples). When `first`, also each particle's
/// Akinci surface normals (from invRho of the last constraint sweep) and density at the current
/// positions (over the lattice sum, as the constraint reads it), with `curl` its vorticity
/// (for vorticity confinement; without it the vorticity is left unwritten), and in a yielding
/// world the stress of its yielding particles advanced over dt under `laws` (yieldLaws; into
/// sxx, sxy and over rho0^2 into tx, ty). `split` > 0 splits the run by viscosity (a world of
/// low- and high-viscosity particles, without the stress pass; PositionBasedScratch::viscousTag
/// filled): 1 for its first pass, which takes the pairs of two low-viscosity particles and
/// their walls over the whole run (`splitWeight` = 1 / `scale` times the pass) and marks
/// the particles with a high-viscosity one in their support (viscousFlag), 2 for the passes
/// after it, which step only those, over their pairs with a high-viscosity particle.
void pbfViscosity(WorldState& s, const PbfConstants& c, float scale, bool first, bool curl,
                  std::span<const YieldLaw> laws, int split = 0, float splitWeight = 0.0f);

/// Vorticity confinement (strength `vorticity`) and, when `surfaceTension`, cohesion and
/// curvature [Akinci 2013], added to vx, vy over dt; in a yielding world the acceleration goes
/// to surfaceAx, surfaceAy instead (0 without either force), for `pbfStress`. Needs vorticity,
/// normals and density from pbfViscosity's first pass.
void pbfSurface(WorldState& s, const PbfConstants& c, float vorticity, bool surfaceTension);

/// Yielding worlds, after `pbfSurface`: the divergence of the deviatoric stress pbfViscosity's
/// first pass advanced, the rigid motion of unyielded pairs, and the walls' traction and
/// adhesion (into wallNx, wallNy, wallAdhesion), added to the surface pass's acceleration; the
/// velocity change over dt waits in kx, ky for the next prediction (Particles::kx). `laws` as
/// for pbfViscosity.
void pbfStress(WorldState& s, const PbfConstants& c, std::span<const YieldLaw> laws);

/// The reaction of each reporting sample to pbfStress's wall stress (N), at the positions and
/// stresses that pass reads, times `weight`, added to the sample's force.
void pbfSampleStress(WorldState& s, const PbfConstants& c, float weight);

/// The reaction of each reporting sample (`Samples::reporting`) to one density sweep: the
/// sweep's wall term moves particle j by w_j dl_j V_j... (see pbfDisplace) at the current
/// positions, and the sample takes -m_j times that over dt^2 (N). Called right after
/// `pbfDisplace` with the same multipliers `change`; the pushes follow the positions'
/// Chebyshev recurrence with `omega` (`first`: the sub-step's first sweep starts them), so at
/// the end of the solve they hold exactly the momentum the walls gave the particles.
void pbfSamplePush(WorldState& s, const PbfConstants& c, std::span<const float> change, float omega,
                   bool first);

/// Adds the reporting samples' pushes of the sub-step, times `weight`, to their forces (in
/// concatenation order).
void pbfDeliverPush(WorldState& s, float weight);

/// The reaction of each reporting sample to one viscosity pass's wall friction (N), with the
/// velocities the pass reads (call it before `pbfViscosity` with the same `scale`), times
/// `weight`, added to the sample's force and drag rate.
void pbfSampleFriction(WorldState& s, const PbfConstants& c, float scale, float weight);

/// What one coarse correction works with.
struct CoarseSettings {
    float share = 0;            // share of the displacement applied (1)
    float cellSize = 0;         // grid spacing (m)
    float tolerance = 0;        // compression left alone (1)
    uint32_t maxIterations = 0; // conjugate-gradient iterations at most
    float startTime = 0;        // the sub-step's start and end, in the step (s): the samples
    float endTime = 0;          // stand at endTime; a body's correction counts from startTime
};

/// The coarse-level density correction (pbf_coarse.cpp): moves the predicted positions (px,
/// py = ox, oy + cx, cy, writing cx, cy) by `share` of the displacement that removes the
/// compression above `tolerance` on a grid of `cellSize` (m), with at most `maxIterations`
/// conjugate-gradient iterations. The rigid bodies of `WorldState::bodies` are unknowns of the
/// same solve: each gets `share` of its displacement as a velocity change from `startTime`
/// (BodyState's corrections; placeSamples moves its samples). Moves nothing when nothing is
/// compressed or the world is too wide for the grid.
///
/// In three phases, so that the solve, which runs on one thread, can run beside the particles'
/// sort. The fill reads the positions and the samples (its loops on the world's workers) and
/// returns false when there is nothing to solve; the solve touches only the coarse grid and the
/// bodies (no particle, no task hook); the move runs after, with `order` mapping each
/// particle's index now to its index at the fill (a sort's order; empty when none ran in
/// between), and returns true when a body moved (its samples must be placed again).
bool pbfCoarseFill(WorldState& s, const PbfConstants& c, const CoarseSettings& settings);
void pbfCoarseSolve(WorldState& s, const CoarseSettings& settings);
bool pbfCoarseMove(WorldState& s, const CoarseSettings& settings,
                   std::span<const uint32_t> order);

} // namespace fluid::detail
