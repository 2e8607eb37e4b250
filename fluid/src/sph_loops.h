// fluid — the SPH neighbour loops shared by the solvers: density, normals, forces.
#pragma once

#include "world_state.h"

namespace fluid::detail {

/// Copies each particle's material properties into the per-particle channels (after a sort),
/// its loop on `tasks` (the world's by default).
void fillMaterialChannels(WorldState& s, const TaskHook& tasks);
inline void fillMaterialChannels(WorldState& s) { fillMaterialChannels(s, s.tasks); }

/// Seed eq. 2.3 in the multi-material form of [Solenthaler & Pajarola 2008]:
/// rho_i = (m_i/depth) sum_j W(r_ij, h_ij) over fluid neighbours (identical to the seed's sum
/// for one material), plus rho0_i V_w W(r_iw, h_i) over boundary samples (they stand in for
/// fluid at rest density).
void computeDensity(WorldState& s, float sampleVolume);

/// Surface normals n_i = h_i sum_j (m_j/depth)/rho_j grad W_ij, pointing into the fluid
/// [Akinci 2013, eq. 4]. Needs density and invRho.
void computeNormals(WorldState& s);

/// Seed eqs. 2.5-2.7 into ax, ay: external (ex, ey) + symmetric pressure + viscosity +, when
/// `surfaceTension`, cohesion and curvature [Akinci 2013]; then the boundary samples' pressure
/// and friction. Needs density, pressure (pOverRho2, invRho), normals, the samples' pressure.
void computeForces(WorldState& s, float sampleVolume, bool surfaceTension);

/// Each boundary sample's pressure, extrapolated from the fluid around it with the hydrostatic
/// term [Adami 2012, eq. 27]: p_w = sum_f (p_f + rho_f (g_f - a_w).(x_w - x_f)) W / sum_f W,
/// clamped at 0. Samples move at constant velocity within a step (a_w = 0), and g_f is the
/// fluid's external acceleration (ex, ey). Needs density and pressure.
void computeSamplePressure(WorldState& s);

/// The fluid's force on each boundary sample (N): minus what the sample exerts on the fluid in
/// `computeForces`, times `weight`, added to the sample's entry in concatenation order.
void computeSampleForces(WorldState& s, float sampleVolume, float weight);

} // namespace fluid::detail
