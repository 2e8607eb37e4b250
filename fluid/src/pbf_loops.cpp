// fluid — the position-based solver's neighbour passes.
//
// The particle passes run in simd/pbf_pairs.inc, compiled per instruction set; the sample passes
// (reactions on reporting boundary samples) here run in sample_pass.h: each sample gathers over
// the grid's contiguous ranges in branch-free blocks of kLanes, lanes summed in a fixed order.
// Every pass writes only its own slots, so results do not depend on the number of workers.
#include "pbf_loops.h"

#include "lanes.h"
#include "parallel.h"
#include "sample_pass.h"

#include <algorithm>
#include <cmath>

namespace fluid::detail {

namespace {

// The particles, samples and grids as plain data for the pair passes (simd/pbf_pairs.inc).
PbfView makeView(const WorldState& s, const PbfConstants& c) {
    const Particles& p = s.particles;
    const PositionBasedScratch& x = s.pbfScratch;
    const YieldScratch& y = s.yieldScratch;
    const Samples& w = s.samples;
    PbfView v;
    v.n = p.size();
    v.px = p.px.data();
    v.py = p.py.data();
    v.vx = p.vx.data();
    v.vy = p.vy.data();
    v.h = p.h.data();
    v.invMass = p.invMass.data();
    v.volume = p.volume.data();
    v.invLattice = p.invLattice.data();
    v.pairPressure = p.pairPressure.data();
    v.viscosity = p.viscosity.data();
    v.massPerDepth = p.massPerDepth.data();
    v.invRho = p.invRho.data();
    v.mass = p.mass.data();
    v.restDensity = p.restDensity.data();
    v.gamma = p.gamma.data();
    if (!p.skinGamma.empty()) {
        v.skinGamma = p.skinGamma.data();
        v.materialTag = p.materialTag.data();
        v.otherShare = p.otherShare.data();
    }
    v.density = p.density.data();
    // After the density solve its scratch holds the viscosity pass's outputs for the surface
    // pass: the vorticity in `diagonal`, the normals in `prevX`, `prevY` (see world_state.h).
    v.vorticity = x.vorticity.data();
    v.nx = x.normalX.data();
    v.ny = x.normalY.data();
    v.material = p.material.data();
    v.sxx = p.sxx.data();
    v.sxy = p.sxy.data();
    v.tx = y.tx.data();
    v.ty = y.ty.data();
    v.rigidity = y.rigidity.data();
    v.yielding = s.stressPass();
    v.grid = s.grid.view();
    v.samples = w.size();
    v.wx = w.px.data();
    v.wy = w.py.data();
    v.wvx = w.vx.data();
    v.wvy = w.vy.data();
    v.friction = w.friction.data();
    v.sampleGrid = w.grid.view();
    v.dt = c.dt;
    v.sampleVolume = c.sampleVolume;
    v.epsilon = c.epsilon;
    v.artificial = c.artificial;
    v.invWdq = c.invWdq;
    // One support for all: pair supports need no division.
    // Over the materials the particles have.
    float lo = 0.0f, hi = 0.0f;
    uint32_t present = 0;
    for (size_t m = 0; m < s.materials.size(); ++m) {
        if (!s.isPresent(m)) {
            continue;
        }
        const float h = s.constants[m].support;
        lo = present == 0 ? h : std::min(lo, h);
        hi = present == 0 ? h : std::max(hi, h);
        ++present;
    }
    v.invSupport = lo == hi && lo > 0.0f ? 1.0f / lo : 0.0f;
    v.oneMaterial = present == 1;
    return v;
}

template <class F> void pairs(WorldState& s, F&& f) {
    parallelFor(s.tasks, s.particles.size(), kPairGrain,
                [&](uint32_t b, uint32_t e, uint32_t) { f(b, e); });
}

} // namespace

PbfView pbfView(const WorldState& s, const PbfConstants& c) {
    return makeView(s, c);
}

void pbfConstraint(WorldState& s, const PbfConstants& c, const float* relaxation) {
    Particles& p = s.particles;
    PositionBasedScratch& x = s.pbfScratch;
    PbfView v = makeView(s, c);
    std::vector<float> least(s.constants.size());
    for (size_t m = 0; m < least.size(); ++m) {
        least[m] = c.floorShare * s.constants[m].diagonal;
    }
    v.leastDiagonal = least.data();
    PbfOut o;
    o.constraint = x.constraint.data();
    o.diagonal = x.diagonal.data();
    o.density = p.density.data();
    o.invRho = p.invRho.data();
    const PbfPairs& k = pbfPairs();
    pairs(s, [&](uint32_t b, uint32_t e) {
        k.constraint(v, o, b, e);
        if (relaxation == nullptr) {
            return;
        }
        for (uint32_t i = b; i < e; ++i) {
            const float updated = std::min(
                x.lambda[i] - relaxation[p.material[i]] * x.constraint[i] / x.diagonal[i], 0.0f);
            x.change[i] = updated - x.lambda[i];
            x.lambda[i] = updated;
        }
    });
}

void pbfDisplace(WorldState& s, const PbfConstants& c, std::span<const float> multiplier,
                 bool sCorr) {
    PositionBasedScratch& x = s.pbfScratch;
    const PbfView v = makeView(s, c);
    PbfOut o;
    o.ax = x.dx.data();
    o.ay = x.dy.data();
    const PbfPairs& k = pbfPairs();
    pairs(s, [&](uint32_t b, uint32_t e) { k.displace(v, o, multiplier.data(), sCorr, b, e); });
}

std::vector<YieldLaw> yieldLaws(const WorldState& s, float dt) {
    if (!s.yielding) {
        return {};
    }
    std::vector<YieldLaw> laws(s.constants.size());
    for (size_t m = 0; m < laws.size(); ++m) {
        const MaterialConstants& mc = s.constants[m];
        // The stiffest shear modulus whose wave crosses kShearWave of the support per step.
        const float speed = tuning::kShearWave * mc.support / dt;
        const float stiffest = mc.restDensity * speed * speed;
        laws[m] =
            makeYieldLaw(mc.yielding, mc.yieldStress, mc.consistency, mc.flowIndex,
                         mc.shearModulus > 0.0f ? std::min(mc.shearModulus, stiffest) : stiffest);
    }
    return laws;
}

void pbfViscosity(WorldState& s, const PbfConstants& c, float scale, bool first, bool curl,
                  std::span<const YieldLaw> laws, int split, float splitWeight) {
    Particles& p = s.particles;
    PositionBasedScratch& x = s.pbfScratch;
    YieldScratch& y = s.yieldScratch;
    PbfView v = makeView(s, c);
    PbfOut o;
    o.ax = x.nextVx.data();
    o.ay = x.nextVy.data();
    o.vorticity = x.vorticity.data();
    o.nx = x.normalX.data();
    o.ny = x.normalY.data();
    o.density = p.density.data();
    if (first && !p.otherShare.empty()) {
        o.otherShare = p.otherShare.data();
    }
    if (first && s.stressPass()) {
        v.yield = laws.data();
        o.sxx = p.sxx.data();
        o.sxy = p.sxy.data();
        o.tx = y.tx.data();
        o.ty = y.ty.data();
        o.rigidity = y.rigidity.data();
    }
    if (split != 0) {
        v.viscousTag = x.viscousTag.data();
        v.viscousFlag = x.viscousFlag.data();
        v.splitWeight = splitWeight;
        if (split == 1) {
            o.viscousFlag = x.viscousFlag.data();
        }
    }
    const PbfPairs& k = pbfPairs();
    pairs(s, [&](uint32_t b, uint32_t e) { k.viscosity(v, o, scale, first, curl, split, b, e); });
}

void pbfSurface(WorldState& s, const PbfConstants& c, float vorticity, bool surfaceTension) {
    Particles& p = s.particles;
    YieldScratch& y = s.yieldScratch;
    const bool forces = vorticity > 0.0f || surfaceTension;
    if (s.stressPass() && !forces) {
        // The stress pass starts from no acceleration: exactly +0, as a sum of no terms.
        y.surfaceAx.assign(p.size(), 0.0f);
        y.surfaceAy.assign(p.size(), 0.0f);
        return;
    }
    if (!forces) {
        return;
    }
    const PbfView v = makeView(s, c);
    PbfOut o;
    o.vx = p.vx.data();
    o.vy = p.vy.data();
    if (s.yielding) {
        // The acceleration waits for the stress pass's terms (pbfStress), or, with the shear
        // constraint, for the next prediction (Particles::kx).
        y.surfaceAx.resize(p.size());
        y.surfaceAy.resize(p.size());
        o.ax = y.surfaceAx.data();
        o.ay = y.surfaceAy.data();
    }
    const PbfPairs& k = pbfPairs();
    pairs(s, [&](uint32_t b, uint32_t e) { k.surface(v, o, vorticity, surfaceTension, b, e); });
    if (s.elastoplastic) {
        // The change waits for the next prediction (Particles::kx), as the stress pass's.
        parallelFor(s.tasks, p.size(), kPairGrain, [&](uint32_t b, uint32_t e, uint32_t) {
            for (uint32_t i = b; i < e; ++i) {
                p.kx[i] += c.dt * y.surfaceAx[i];
                p.ky[i] += c.dt * y.surfaceAy[i];
            }
        });
    }
}

void pbfStress(WorldState& s, const PbfConstants& c, std::span<const YieldLaw> laws) {
    Particles& p = s.particles;
    YieldScratch& y = s.yieldScratch;
    PbfView v = makeView(s, c);
    v.yield = laws.data();
    v.surfaceAx = y.surfaceAx.data();
    v.surfaceAy = y.surfaceAy.data();
    PbfOut o;
    // The velocity change waits in kx, ky for the next prediction (see Particles::kx).
    o.vx = p.kx.data();
    o.vy = p.ky.data();
    o.wallNx = y.wallNx.data();
    o.wallNy = y.wallNy.data();
    o.wallAdhesion = y.wallAdhesion.data();
    const PbfPairs& k = pbfPairs();
    pairs(s, [&](uint32_t b, uint32_t e) { k.stress(v, o, b, e); });
}

void pbfSamplePush(WorldState& s, const PbfConstants& c, std::span<const float> change, float omega,
                   bool first) {
    const Particles& p = s.particles;
    Samples& w = s.samples;
    const float* __restrict il = p.invLattice.data();
    const float* __restrict dl = change.data();
    const auto count = static_cast<uint32_t>(w.reporting.size());
    if (first) {
        w.pushX.assign(count, 0.0f);
        w.pushY.assign(count, 0.0f);
        w.pushPrevX.assign(count, 0.0f);
        w.pushPrevY.assign(count, 0.0f);
    }
    const float invDt2 = 1.0f / (c.dt * c.dt);
    const SampleReach reach(p);
    samplePass<2>(
        s, count, w.reporting.data(),
        [&](uint32_t k) {
            const float xw = w.px[k], yw = w.py[k];
            return [&, xw, yw](size_t j, SampleLane<2> a) {
                const auto [dx, dy, invH, q, t, invH4] = reach.at(j, xw, yw);
                // pbfDisplace's wall term moves j by w_j kG dl_j V_w L_j h^-4 t^3 (x_j - x_w).
                const float f = -dl[j] * il[j] * kG * invH4 * (t * t * t);
                a[0] += f * dx;
                a[1] += f * dy;
            };
        },
        [&](uint32_t r, uint32_t, const float(&sum)[2]) {
            const float fx = c.sampleVolume * invDt2 * sum[0];
            const float fy = c.sampleVolume * invDt2 * sum[1];
            if (first) {
                w.pushX[r] = fx;
                w.pushY[r] = fy;
                return;
            }
            // As the positions: x_k+1 = omega (x_k + d_k - x_k-1) + x_k-1.
            const float x = omega * (w.pushX[r] + fx - w.pushPrevX[r]) + w.pushPrevX[r];
            const float y = omega * (w.pushY[r] + fy - w.pushPrevY[r]) + w.pushPrevY[r];
            w.pushPrevX[r] = w.pushX[r];
            w.pushPrevY[r] = w.pushY[r];
            w.pushX[r] = x;
            w.pushY[r] = y;
        });
}

void pbfDeliverPush(WorldState& s, float weight) {
    Samples& w = s.samples;
    for (uint32_t r = 0; r < w.pushX.size(); ++r) {
        const uint32_t k = w.reporting[r];
        w.fx[w.source[k]] += weight * w.pushX[r];
        w.fy[w.source[k]] += weight * w.pushY[r];
    }
}

void pbfSampleFriction(WorldState& s, const PbfConstants& c, float scale, float weight) {
    const Particles& p = s.particles;
    Samples& w = s.samples;
    const float* __restrict vx = p.vx.data();
    const float* __restrict vy = p.vy.data();
    const float* __restrict mu = p.viscosity.data();
    const float* __restrict vol = p.volume.data();
    const float depth = s.def.depth;
    const auto count = static_cast<uint32_t>(w.reporting.size());
    // Channels: the force's x and y, and its derivative in the sample's velocity (drag).
    const SampleReach reach(p);
    samplePass<3>(
        s, count, w.reporting.data(),
        [&](uint32_t k) {
            const float xw = w.px[k], yw = w.py[k];
            const float vxw = w.vx[k], vyw = w.vy[k], friction = w.friction[k];
            return [&, xw, yw, vxw, vyw, friction](size_t j, SampleLane<3> a) {
                const auto [dx, dy, invH, q, t, invH4] = reach.at(j, xw, yw);
                // pbfViscosity's wall friction on j: m_j mu_j/rho0_j f V_w L (v_w - v_j),
                // m_j/rho0_j = V_j depth.
                const float fv = depth * vol[j] * friction * mu[j] * kL * invH4 * t;
                a[0] -= fv * (vxw - vx[j]);
                a[1] -= fv * (vyw - vy[j]);
                a[2] += fv;
            };
        },
        [&](uint32_t, uint32_t k, const float(&sum)[3]) {
            const float share = weight * scale * c.sampleVolume;
            w.fx[w.source[k]] += share * sum[0];
            w.fy[w.source[k]] += share * sum[1];
            w.drag[w.source[k]] += share * sum[2];
        });
}

void pbfSampleStress(WorldState& s, const PbfConstants& c, float weight) {
    const Particles& p = s.particles;
    const YieldScratch& y = s.yieldScratch;
    Samples& w = s.samples;
    const float* __restrict tx = y.tx.data();
    const float* __restrict ty = y.ty.data();
    const float* __restrict nx = y.wallNx.data();
    const float* __restrict ny = y.wallNy.data();
    const float* __restrict mass = p.mass.data();
    const float* __restrict rho0 = p.restDensity.data();
    const float* __restrict adhesion = y.wallAdhesion.data();
    const auto count = static_cast<uint32_t>(w.reporting.size());
    const SampleReach reach(p);
    samplePass<2>(
        s, count, w.reporting.data(),
        [&](uint32_t k) {
            const float xw = w.px[k], yw = w.py[k];
            return [&, xw, yw](size_t j, SampleLane<2> a) {
                const auto [dx, dy, invH, q, t, invH4] = reach.at(j, xw, yw);
                // pbfStress's wall terms on j from this sample, the sample takes the
                // opposite: the traction m_j kG 2 rho0_j V_w f h^-4 t^3 (s_j/rho0_j^2) .
                // (x_j - x_w) along the wall, and this sample's share of j's adhesion
                // (its part of the walls' gradient sum along the normal).
                float fx = tx[j] * dx + ty[j] * dy, fy = ty[j] * dx - tx[j] * dy;
                const float normal = fx * nx[j] + fy * ny[j];
                fx -= normal * nx[j];
                fy -= normal * ny[j];
                const float t3 = t * t * t;
                const float f = mass[j] * 2.0f * rho0[j] * invH4 * t3;
                const float share = mass[j] * adhesion[j] * t3 * (dx * nx[j] + dy * ny[j]);
                a[0] -= f * fx + share * nx[j] / (c.sampleVolume * kG);
                a[1] -= f * fy + share * ny[j] / (c.sampleVolume * kG);
            };
        },
        [&](uint32_t, uint32_t k, const float(&sum)[2]) {
            // The friction (at most 1) the wall terms were weighted with, per sample.
            const float share = weight * c.sampleVolume * kG * std::min(w.friction[k], 1.0f);
            w.fx[w.source[k]] += share * sum[0];
            w.fy[w.source[k]] += share * sum[1];
        });
}

} // namespace fluid::detail
