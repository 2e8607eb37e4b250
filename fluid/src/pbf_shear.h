// fluid — the elastoplastic shear constraint of yielding materials (pbf_shear.cpp).
#pragma once

#include "pbf_loops.h"
#include "world_state.h"
#include "yield_law.h"

#include <span>
#include <vector>

namespace fluid::detail {

/// Each material's Herschel-Bulkley law for the shear constraint over sub-steps of `dt` (s):
/// the shear modulus capped by kShearWave of the support per sub-step.
std::vector<YieldLaw> shearLaws(const WorldState& s, float dt);

/// Before a sub-step's sweeps (x* as they start; PositionBasedScratch::startX the sub-step's
/// start): each yielding particle's displacement so far and its kernel gradient's correction;
/// nothing applied yet.
void pbfShearPrepare(WorldState& s, const PbfConstants& c);

/// One sweep of the shear constraint at the current positions: each yielding particle's stress
/// read and returned, its multiplier's change, and the displacement of the changes into
/// YieldScratch::shearDx, shearDy (momentum kept, walls aside), with the walls' hold added.
void pbfShearSweep(WorldState& s, const PbfConstants& c, std::span<const YieldLaw> laws);

/// After the sweeps: each yielding particle's stress (Particles::sxx, sxy) read from the final
/// positions and returned, and its structure broken by plastic flow or rebuilt at rest.
void pbfShearFinish(WorldState& s, const PbfConstants& c, std::span<const YieldLaw> laws);

/// The reaction of each reporting sample to the sub-step's shear constraint and walls' hold
/// (N), times `weight`, added to the sample's force. After the sweeps, before pbfShearFinish.
void pbfShearSamples(WorldState& s, const PbfConstants& c, float weight);

} // namespace fluid::detail
