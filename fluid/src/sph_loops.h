// fluid — the SPH neighbour loops shared by the solvers: density, normals, forces.
#pragma once

#include "world_state.h"

namespace fluid::detail {

/// Copies each particle's material properties into the per-particle channels (after a sort).
void fillMaterialChannels(WorldState& s);

/// Seed eq. 2.3: rho_i = sum_j (m_j/depth) W(r_ij, h_ij) over fluid neighbours, plus
/// rho0_i V_w W(r_iw, h_i) over boundary samples (they stand in for fluid at rest density).
void computeDensity(WorldState& s, float sampleVolume);

/// Surface normals n_i = h_i sum_j (m_j/depth)/rho_j grad W_ij, pointing into the fluid
/// [Akinci 2013, eq. 4]. Needs density and invRho.
void computeNormals(WorldState& s);

/// Seed eqs. 2.5-2.7 into ax, ay: external (ex, ey) + symmetric pressure + viscosity +, when
/// `surfaceTension`, cohesion and curvature [Akinci 2013]; then the boundary samples' pressure
/// and friction. Needs density, pressure (pOverRho2, invRho), normals, the samples' pressure.
void computeForces(WorldState& s, float sampleVolume, bool surfaceTension);

} // namespace fluid::detail
