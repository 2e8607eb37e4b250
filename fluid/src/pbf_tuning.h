// fluid — every tuning constant of the position-based solver, each with its reason in one line.
// The measurements that chose them are in docs/notes/pbf_tuning_constants.md, "Tuning constants",
// under the constant's name; change one only with a measurement there. Only <cstdint> (types, no
// functions), so the per-instruction-set pair passes may include it (simd/pair_view.h).
#pragma once

#include <cstdint>

namespace fluid::detail::tuning {

// ---- the density constraint (solver_position_based.cpp) -----------------------------------

/// s_corr's artificial pressure as a share of the cohesion's pressure scale rho0 a_gamma h
/// (a_gamma = gamma m / A [Akinci 2013], the explicit solver's background-pressure bound).
inline constexpr float kArtificial = 0.1f;
/// Where s_corr's kernel ratio is 1, in supports (Macklin & Mueller use 0.1-0.3).
inline constexpr float kDeltaQ = 0.2f;
/// Share of a Jacobi update a sweep takes: the full update overshoots where many neighbours
/// push together.
inline constexpr float kRelax = 0.5f;
/// ... with a single sweep per sub-step, whose overshoot goes straight into the velocity.
inline constexpr float kRelaxSingle = 0.35f;
/// Lattice neighbours up to which a material relaxes by kRelax; above, by kRelax (this / n)^2.
inline constexpr float kRelaxNeighbours = 36.0f;
/// Estimated spectral radius of a sweep for the Chebyshev acceleration [Wang 2015]: higher
/// boils yoghurt.
inline constexpr float kChebyshev = 0.8f;
/// Sweeps before the acceleration starts, with fewer than kChebyshevEarly sweeps per sub-step.
inline constexpr uint32_t kChebyshevStart = 1;
/// From this many sweeps per sub-step the acceleration starts with the first one.
inline constexpr uint32_t kChebyshevEarly = 8;
/// Least denominator of a multiplier, as a share of the material's lattice value: a particle
/// squeezed between solids otherwise gets an unbounded multiplier.
inline constexpr float kDiagonalFloor = 0.1f;
/// Longest move of one correction, in supports: a bad sweep cannot fling a particle across the
/// grid.
inline constexpr float kMaxCorrection = 0.5f;
/// Fastest predicted move per sub-step, in supports: the grid is rebuilt once per sub-step, and
/// faster a particle could skip a wall's sample layers.
inline constexpr float kMaxPredictedMove = 2.0f;

// ---- viscosity and the yield stress (pbf_loops.cpp, simd/pbf_pairs.inc, yield_law.h) -------

/// Largest viscosity factor dt nu sum_j V_j L_ij per pass: below 0.5 the explicit update only
/// smooths, never overshoots.
inline constexpr float kViscosityFactor = 0.5f;
// Longest run (unit: s) over which vorticity confinement gives back its full share (both
// presets' runs: the game preset's 1/120 s, the precise one's 1/240 s); longer runs (fewer
// sub-steps, a longer viscosityInterval) give back proportionally less: at full share the
// confinement outgrows the damping (docs/position_based_method.md, "Velocity, viscosity, surface").
inline constexpr float kVorticityRun = 1.0f / 120.0f;
// Most viscosity passes per run: beyond them each pass stays at kViscosityFactor, and the
// viscosity the run applies is capped (docs/position_based_method.md, "Velocity, viscosity,
// surface").
inline constexpr uint32_t kMaxViscosityPasses = 32;
/// Share of the support a shear wave may cross per viscosity run: the cap on a yielding
/// material's shear modulus, G <= rho0 (kShearWave h / dt)^2.
inline constexpr float kShearWave = 0.15f;
/// Share of the yield stress a yielding material holds on to a wall with at rest.
inline constexpr float kAdhesion = 0.5f;
/// The largest elastic strain a yielding material stores: the stress is advanced as a rate,
/// true to small strains only.
inline constexpr float kCarriedStrain = 1.0f;
/// The shear constraint (pbf_shear.cpp): how much a rebuilt structure raises the yield stress
/// at rest (tau_y (1 + this r)), so the solver's noise does not set a resting heap creeping
/// again (the figures for 0, 0.5 and 1: docs/yield_stress.md, "The shear constraint").
inline constexpr float kStructureGain = 1.0f;
/// Time over which a structure rebuilds at rest (s): r += (1 - r) dt / this per sub-step.
inline constexpr float kStructureTime = 0.5f;
/// The shear constraint's walls (pbf_shear.cpp): how far a yielding particle is held back, per
/// sub-step, from moving away from the walls within its support, and along them, in units of
/// dt^2 2 tau |S_w| / rho0 (what its yield stress carries across the walls' band, S_w the walls'
/// kernel gradient sum: the stress pass's adhesion). Along the walls times r^4 of its structure
/// r, so only paste that has rested there sticks (the figures: docs/yield_stress.md, "The
/// shear constraint").
inline constexpr float kWallHoldAcross = 3.0f;
inline constexpr float kWallHoldAlong = 1.5f;
/// Least eigenvalue of the kernel gradient's correction matrix before it is inverted (1): a
/// particle with few neighbours reads at most 1 / this times the plain kernel sum.
inline constexpr float kLeastCorrection = 0.25f;
/// The shear constraint with a shear modulus above the cap kShearWave sets (a material's own
/// Material::shearModulus): each sweep's stress update is scaled by 1 / (1 + q), q this times
/// 2 G over the particle's own compliance (a Jacobi step whose diagonal stands for its
/// neighbours' too), times the share of G above the cap. Below the cap q is 0: the explicit
/// update (docs/yield_stress.md, "The shear constraint": *Stiff pastes*).
inline constexpr float kShearJacobi = 20.0f;

/// A yield-stress material's skin against another liquid: the cohesion [Akinci 2013] between two
/// of its particles, one of them with particles of another material in its support, is raised
/// by this many times the material's own (Material::surfaceTension), in proportion to the share
/// of the support's kernel weight the other material holds. It stands for the paste's network,
/// which holds its skin together where the liquid around it drags (figures: docs/yield_stress.md,
/// "Its skin against the water"). In air, and in worlds of one material, nothing changes.
inline constexpr float kSkinCohesion = 6.0f;

// ---- the coarse correction (pbf_coarse.cpp) -------------------------------------------------

/// Coarse grid cell, in the smallest support (2.4 water spacings).
inline constexpr float kCoarseCell = 0.75f;
/// Compression the coarse correction leaves to the sweeps (1).
inline constexpr float kCoarseTolerance = 0.05f;
/// Conjugate-gradient iterations at most per solve.
inline constexpr uint32_t kCoarseIterations = 100;
/// Residual, relative to the start, that ends the solve: tighter changed no figure of the tank
/// or the dam (read with the MIC(0) preconditioner the multigrid one replaced).
inline constexpr float kCoarseResidual = 1e-2f;
/// Diagonal shift of the coarse operator: a closed container full of fluid has no free surface
/// to anchor the potential.
inline constexpr float kCoarseShift = 1e-3f;
/// Largest share of the coarse correction over one frame's sub-steps together: a sub-step's
/// correction becomes velocity over its dt.
inline constexpr float kCoarseFrame = 0.9f;
/// Longest coarse move of a particle per sub-step, in its supports.
inline constexpr float kCoarseMaxMove = 0.25f;
/// Longest coarse move of a rigid body per sub-step, in coarse cells: the body's plugin projects
/// the particles out of it without this move, which reaches it only after the step
/// (docs/notes/pbf_tuning_constants.md, "Tuning constants").
inline constexpr float kCoarseBodyMaxMove = 0.05f;
/// Share of a node's cell a rigid body's outline fills (its bilinear fill, CoarseGrid::bodyFill)
/// from which the node is the body's, solid in the coarse solve. The fill moves smoothly with
/// the body; the inside test at the node's point, used before, switched a whole row of nodes
/// under a flat bottom as the body moved a fraction of a millimetre, and the solve's push on it
/// stepped with them (docs/notes/bodies_coarse_solve.md, "Nodes a body owns").
inline constexpr float kCoarseBodyOwn = 0.5f;
/// Below kCoarseBodyOwn, a fluid node is open to the flow by its share
/// (kCoarseBodyOwn - fill) / kCoarseBodyFade of the bodies' fill, at most 1: its compression,
/// its faces' coefficients and its part in a body's rows of the solve fade with that share, so
/// that nothing the solve does steps when the node becomes the body's
/// (docs/notes/bodies_coarse_solve.md, "Open nodes").
inline constexpr float kCoarseBodyFade = 0.25f;
/// How far beyond the particles' bounds the coarse grid reaches to take in the bodies' samples
/// (coarse cells): a grid that ended at the particles cut a crate resting on a paste through
/// its bottom row, and the cut stepped as the particles' top moved.
inline constexpr float kCoarseBodyReach = 4.0f;
/// Nearest a fluid node's zero of the potential may lie to it, in cells (the free surface,
/// placed where the fill crosses 1/2 between the node and its air neighbour): the operator's
/// diagonal grows by 1/theta, so this bounds it at 10 (docs/notes/pbf_tuning_constants.md, "Tuning
/// constants").
inline constexpr float kCoarseSurfaceMin = 0.1f;

} // namespace fluid::detail::tuning
