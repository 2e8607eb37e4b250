// fluid — the elastoplastic shear constraint of yielding materials (position-based solver).
//
// Each particle of a yielding material carries an elastic deviatoric stress s (Particles::sxx,
// sxy: s_xx = -s_yy and s_xy), that is an elastic strain s / 2G, and a structure r in [0, 1]
// (Particles::structure). In a sub-step its elastic strain is the stored one, turned by the
// sub-step's spin, plus the deviatoric strain of the sub-step's displacement u = x* - x_n, read
// with a corrected kernel gradient:
//   grad u_i = sum_j (u_j - u_i) (x) M_i^-1 V_j grad W_ij,
//   M_i = sum_j V_j (x_j - x_i) (x) grad W_ij,
// so a linear field reads exactly next to walls and at the free surface [Bonet & Lok 1999]. That
// trial stress is returned to the Herschel-Bulkley surface (yield_law.h: returnStress, the
// plastic rate implicit) of yield stress tau_y (1 + kStructureGain r), and the returned stress
// is the constraint's multiplier, l_i = -2 V_i dt^2 s_i: the force of the elastic energy
// 2 G V |e|^2 (per depth) [XPBD: Macklin et al. 2016; XPBI: Yu et al. 2024]. The sweeps read
// it after every density sweep, at the positions that sweep left, and move each particle and
// its neighbours by the change of their multipliers (dx_j = w_j grad_j C_i^T dl_i, conserving
// momentum). After the sweeps the stress is read once more from the final positions and
// kept: the state the next sub-step starts from. So an unyielded region is an elastic solid
// (stress from its deformation, however long the step), a flowing one holds tau_y + K g^n and
// dissipates in the return. The structure is what yoghurt's thixotropy is: broken by plastic
// flow (r = 0), rebuilt at rest over kStructureTime, so a heap that has stopped holds up to
// (1 + kStructureGain) tau_y and is not set creeping again by the solver's noise
// (docs/yield_stress.md, "Yield stress").
//
// Only yielding particles take part, only with yielding neighbours and the walls (boundary
// samples, as material moving with the wall, weighted by their friction, at most 1). Within a
// support of the walls, each sweep also holds a particle back from moving away from them and,
// once its structure has rebuilt, along them, up to what its yield stress carries
// (holdOnWalls): what keeps a layer on a wall. The
// neighbour sums are pair passes (simd/pbf_pairs.inc: shearRead, shearGather) with the kernel
// gradients at the positions the sweeps started from, kept as reference positions for the
// sub-step. Each pass writes only its own particles' slots, lanes summed in a fixed order: the
// results do not depend on the number of workers or the instruction set.
#include "pbf_shear.h"

#include "kernel_constants.h"
#include "lanes.h"
#include "parallel.h"
#include "sample_pass.h"
#include "simd/pair_view.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fluid::detail {

namespace {

using kernel::kG;

std::vector<uint8_t> yieldingMaterials(const WorldState& s) {
    std::vector<uint8_t> y(s.constants.size());
    for (size_t m = 0; m < y.size(); ++m) {
        y[m] = s.constants[m].yielding ? 1 : 0;
    }
    return y;
}

// f(i) for every particle, in ranges of the pair passes' grain over the workers.
template <class F> void eachParticle(WorldState& s, F&& f) {
    parallelFor(s.tasks, s.particles.size(), kPairGrain, [&](uint32_t b, uint32_t e, uint32_t) {
        for (uint32_t i = b; i < e; ++i) {
            f(i);
        }
    });
}

// The shear passes' channels.
ShearView shearView(WorldState& s) {
    YieldScratch& y = s.yieldScratch;
    ShearView w;
    w.refX = y.refX.data();
    w.refY = y.refY.data();
    w.ux = y.ux.data();
    w.uy = y.uy.data();
    w.yields = y.yields.data();
    w.t00 = y.t00.data();
    w.t01 = y.t01.data();
    w.t10 = y.t10.data();
    w.t11 = y.t11.data();
    w.mxx = y.mxx.data();
    w.mxy = y.mxy.data();
    w.myy = y.myy.data();
    w.hxx = y.hxx.data();
    w.hxy = y.hxy.data();
    w.hyx = y.hyx.data();
    w.hyy = y.hyy.data();
    w.sumX = y.sumX.data();
    w.sumY = y.sumY.data();
    w.trace = y.trace.data();
    w.dx = y.shearDx.data();
    w.dy = y.shearDy.data();
    w.wallX = y.wallX.data();
    w.wallY = y.wallY.data();
    w.wallWeight = y.wallWeight.data();
    w.wallVx = y.wallVx.data();
    w.wallVy = y.wallVy.data();
    return w;
}

// Each particle's displacement over the sub-step so far, u = x - x_start, which shearRead reads.
void displacements(WorldState& s) {
    const Particles& p = s.particles;
    const PositionBasedScratch& x = s.pbfScratch;
    YieldScratch& y = s.yieldScratch;
    eachParticle(s, [&](uint32_t i) {
        y.ux[i] = p.px[i] - x.startX[i];
        y.uy[i] = p.py[i] - x.startY[i];
    });
}

// The displacement gradient L = grad u of particle i over the sub-step so far.
struct Gradient {
    float xx, xy, yx, yy;
};

// Particle i's correction matrix M (as shearRead left it) replaced by its inverse, with
// eigenvalues held in [kLeastCorrection, 1 / kLeastCorrection]: a particle with few neighbours
// reads at most 1 / kLeastCorrection times the plain sum.
void invertCorrection(YieldScratch& y, uint32_t i) {
    const float mxx = y.mxx[i], mxy = y.mxy[i], myy = y.myy[i];
    const float least = tuning::kLeastCorrection;
    const float mean = 0.5f * (mxx + myy);
    const float half = 0.5f * (mxx - myy);
    const float radius = std::sqrt(half * half + mxy * mxy);
    const float l1 = std::clamp(mean + radius, least, 1.0f / least);
    const float l2 = std::clamp(mean - radius, least, 1.0f / least);
    // The first eigenvector at angle theta: cos 2 theta = half / radius, sin 2 theta = mxy /
    // radius (no trigonometry: the same bits wherever the library's differs).
    const float c2 = radius > 0.0f ? half / radius : 1.0f;
    const float s2 = radius > 0.0f ? mxy / radius : 0.0f;
    const float i1 = 1.0f / l1, i2 = 1.0f / l2;
    const float sum = 0.5f * (i1 + i2), difference = 0.5f * (i1 - i2);
    y.mxx[i] = sum + difference * c2;
    y.mxy[i] = difference * s2;
    y.myy[i] = sum - difference * c2;
}

// Particle i's displacement gradient H M^-1 (M^-1 as invertCorrection left it).
Gradient correctedGradient(const YieldScratch& y, uint32_t i) {
    const float ixx = y.mxx[i], ixy = y.mxy[i], iyy = y.myy[i];
    const float hxx = y.hxx[i], hxy = y.hxy[i], hyx = y.hyx[i], hyy = y.hyy[i];
    return {hxx * ixx + hxy * ixy, hxx * ixy + hxy * iyy, hyx * ixx + hyy * ixy,
            hyx * ixy + hyy * iyy};
}

// A yielding particle's trial stress, as readEach's `trial` leaves it for the return: (a, b)
// on the way to the surface of `law`.
struct ShearTrial {
    YieldLaw law;
    float a = 0, b = 0;
};

// Returns read and solved together (plasticSolves): a batch of particles at a time.
inline constexpr uint32_t kReturnBatch = 64;

// One reading at the current positions (shearRead, through the views v and w) and, for each
// yielding particle, `trial(i, L, t)` (filling a ShearTrial t), the trial's return to its law's
// surface over dt, then `commit(i, trial, norm)` with the returned stress in trial and the trial's
// norm (Pa). The first reading of a sub-step also takes M and S and inverts M.
template <class Trial, class Commit>
void readEach(WorldState& s, const PbfView& v, const ShearView& w, float dt, Trial&& trial,
              Commit&& commit) {
    const Particles& p = s.particles;
    YieldScratch& y = s.yieldScratch;
    const PbfPairs& k = pbfPairs();
    const bool matrix = !y.matrixRead;
    y.matrixRead = true;
    displacements(s);
    parallelFor(s.tasks, p.size(), kPairGrain, [&](uint32_t b, uint32_t e, uint32_t) {
        k.shearRead(v, w, matrix, b, e);
        for (uint32_t c = b; c < e; c += kReturnBatch) {
            uint32_t index[kReturnBatch];
            ShearTrial trials[kReturnBatch];
            StressReturn returns[kReturnBatch];
            unsigned active[kReturnBatch];
            uint32_t count = 0;
            for (uint32_t i = c; i < std::min(e, c + kReturnBatch); ++i) {
                if (!(y.yields[i] > 0.0f)) {
                    continue;
                }
                if (matrix) {
                    invertCorrection(y, i);
                }
                ShearTrial& t = trials[count];
                trial(i, correctedGradient(y, i), t);
                returnOpen(t.law, dt, t.a, t.b, returns[count]);
                index[count] = i;
                ++count;
            }
            plasticSolves(returns, active, count);
            for (uint32_t j = 0; j < count; ++j) {
                ShearTrial& t = trials[j];
                returnClose(t.law, returns[j], t.a, t.b);
                commit(index[j], t, returns[j].norm);
            }
        }
    });
}

// The law of particle i: its material's, with the yield stress its structure holds.
YieldLaw structuredLaw(const YieldLaw& law, float structure) {
    YieldLaw l = law;
    l.flowStress = law.flowStress * (1.0f + tuning::kStructureGain * structure);
    return l;
}

// The trial stress the sub-step's displacement gives particle i, for the return to the
// surface of its material's `law` with the yield stress its `structure` holds (structuredLaw;
// readEach): the stored stress (a, b) turned by the spin (a Cayley turn, norm kept, as
// yieldStep), plus 2 G times the deviatoric strain of L. With q > 0 the update from the stress
// the sweeps applied so far (sa, sb) is scaled by 1 / (1 + q), and the return sees G / (1 + q).
// t.law is copied from `law` and changed field by field: a law built aside and copied in stalls
// on the partial stores that built it.
void trialStress(const YieldLaw& law, float structure, const Gradient& l, float a, float b,
                 ShearTrial& t, float q = 0.0f, float sa = 0.0f, float sb = 0.0f) {
    const float u = 0.5f * (l.xy - l.yx);
    const float inv = 1.0f / (1.0f + u * u);
    const float cosine = (1.0f - u * u) * inv, sine = 2.0f * u * inv;
    const float g2 = 2.0f * law.shearModulus;
    t.a = (a * cosine + b * sine) + g2 * 0.5f * (l.xx - l.yy);
    t.b = (b * cosine - a * sine) + g2 * 0.5f * (l.xy + l.yx);
    t.law = law;
    t.law.flowStress = structuredLaw(law, structure).flowStress;
    if (q > 0.0f) {
        const float scale = 1.0f / (1.0f + q);
        t.a = sa + (t.a - sa) * scale;
        t.b = sb + (t.b - sb) * scale;
        t.law.shearModulus = law.shearModulus * scale;
    }
}

// The scale q of particle i's sweep update (trialStress): 0 up to the explicit cap; above it
// kShearJacobi times 2 G over the particle's own compliance, G V dt^2 depth tr(T) (the strain
// its own stress change takes back through the gather: ShearView::trace), times the share of G
// above the cap.
float jacobiScale(const YieldLaw& law, const YieldScratch& y, const Particles& p, float dt,
                  float depth, uint32_t i) {
    if (!(law.shearModulus > law.explicitModulus)) {
        return 0.0f;
    }
    const float above = 1.0f - law.explicitModulus / law.shearModulus;
    return tuning::kShearJacobi * above * law.shearModulus * p.volume[i] * dt * dt * depth *
           y.trace[i];
}

// The walls' hold on yielding particle i, after a sweep's gather: the particle's motion
// relative to the walls since the sub-step's start (at the position the gather leaves) is
// taken back, away from the walls up to kWallHoldAcross and along them up to kWallHoldAlong r^4
// times dt^2 2 tau |S_w| / rho0 in all over the sub-step, however many sweeps apply it (tau the
// yield stress its structure r holds, S_w the walls' part of the kernel gradient sum): what
// holds a layer on a wall and a rested heap on its floor. It only takes back motion, never
// pulls a particle past where the sweeps would put it: nothing for the density sweeps to push
// back. The walls take the reaction (pbfShearSamples).
void holdOnWalls(WorldState& s, std::span<const YieldLaw> laws, float dt, uint32_t i) {
    const Particles& p = s.particles;
    const PositionBasedScratch& x = s.pbfScratch;
    YieldScratch& y = s.yieldScratch;
    const float gx = y.wallX[i], gy = y.wallY[i];
    const float length = std::sqrt(gx * gx + gy * gy);
    if (!(length > 0.0f)) {
        return;
    }
    // The walls' direction from the particle's side (kG < 0: S_w points at the walls).
    const float nx = -gx / length, ny = -gy / length;
    // The motion the particle would have made without the hold (what it made, minus what the
    // hold took back so far in this sub-step): the hold is a bound on its net take-back, not on
    // the sum of its sweeps' (which the density sweeps' pushes back and forth would use up).
    const float mx = (p.px[i] + y.shearDx[i]) - x.startX[i] - y.wallVx[i] * dt - y.holdX[i];
    const float my = (p.py[i] + y.shearDy[i]) - x.startY[i] - y.wallVy[i] * dt - y.holdY[i];
    const float away = mx * nx + my * ny;
    const float r = p.structure[i];
    const float unit = 2.0f * structuredLaw(laws[p.material[i]], r).flowStress /
                       p.restDensity[i] * length * (dt * dt);
    float hx = 0.0f, hy = 0.0f;
    const float across = std::min(away, tuning::kWallHoldAcross * unit);
    if (across > 0.0f) {
        hx -= across * nx;
        hy -= across * ny;
    }
    const float tx = mx - away * nx, ty = my - away * ny;
    const float slip = std::sqrt(tx * tx + ty * ty);
    const float rested = (r * r) * (r * r);
    const float left = tuning::kWallHoldAlong * rested * unit;
    if (slip > 0.0f && left > 0.0f) {
        const float along = std::min(slip, left);
        hx -= tx * (along / slip);
        hy -= ty * (along / slip);
    }
    // The change of the net take-back.
    y.shearDx[i] += hx - y.holdX[i];
    y.shearDy[i] += hy - y.holdY[i];
    y.holdX[i] = hx;
    y.holdY[i] = hy;
}

} // namespace

std::vector<YieldLaw> shearLaws(const WorldState& s, float dt) {
    std::vector<YieldLaw> laws(s.constants.size());
    for (size_t m = 0; m < laws.size(); ++m) {
        const MaterialConstants& mc = s.constants[m];
        // The stiffest shear modulus whose wave crosses kShearWave of the support per sub-step
        // is read explicitly (the stress is read at the positions a sweep leaves): the modulus
        // of a material that asks for none (0), and where a stiffer one's sweeps start to scale
        // their update (jacobiScale). Softer than that cap, a paste's strain stays above the
        // game preset's noise (docs/yield_stress.md, "The shear constraint").
        const float speed = tuning::kShearWave * mc.support / dt;
        const float stiffest = mc.restDensity * speed * speed;
        const float g = mc.shearModulus > 0.0f ? mc.shearModulus : stiffest;
        laws[m] = makeYieldLaw(mc.yielding, mc.yieldStress, mc.consistency, mc.flowIndex, g);
        laws[m].explicitModulus = stiffest;
        // The strain is read from the positions, not accumulated as a rate: no cap on it.
        laws[m].carriedStress = std::numeric_limits<float>::max();
        laws[m].flowStress = mc.yieldStress;
    }
    return laws;
}

void pbfShearPrepare(WorldState& s, const PbfConstants&) {
    const Particles& p = s.particles;
    YieldScratch& y = s.yieldScratch;
    const uint32_t n = p.size();
    for (auto* channel :
         {&y.refX, &y.refY, &y.ux,  &y.uy,       &y.yields,   &y.mxx,     &y.mxy,    &y.myy,
          &y.hxx,  &y.hxy,  &y.hyx, &y.hyy,      &y.sumX,     &y.sumY,    &y.trace,  &y.t00,
          &y.t01,  &y.t10,  &y.t11, &y.appliedA, &y.appliedB, &y.shearDx, &y.shearDy,
          &y.wallX, &y.wallY, &y.wallWeight, &y.wallVx, &y.wallVy, &y.holdX, &y.holdY}) {
        channel->resize(n);
    }
    const std::vector<uint8_t> yields = yieldingMaterials(s);
    eachParticle(s, [&](uint32_t i) {
        y.refX[i] = p.px[i];
        y.refY[i] = p.py[i];
        y.yields[i] = yields[p.material[i]] != 0 ? 1.0f : 0.0f;
        y.appliedA[i] = 0.0f;
        y.appliedB[i] = 0.0f;
        y.holdX[i] = y.holdY[i] = 0.0f;
        // The gather reads 0 for particles of other materials; the sweeps write the others'.
        y.t00[i] = y.t01[i] = y.t10[i] = y.t11[i] = 0.0f;
    });
    y.matrixRead = false;
}

void pbfShearSweep(WorldState& s, const PbfConstants& c, std::span<const YieldLaw> laws) {
    const Particles& p = s.particles;
    YieldScratch& y = s.yieldScratch;
    const float toMultiplier = -2.0f * c.dt * c.dt;
    const float depth = s.def.depth;
    const PbfView v = pbfView(s, c);
    const ShearView w = shearView(s);
    readEach(
        s, v, w, c.dt,
        [&](uint32_t i, const Gradient& l, ShearTrial& t) {
            const YieldLaw& law = laws[p.material[i]];
            // The stress the sweeps applied so far in this sub-step.
            const float toStress = 1.0f / (toMultiplier * p.volume[i]);
            const float q = jacobiScale(law, y, p, c.dt, depth, i);
            trialStress(law, p.structure[i], l, p.sxx[i], p.sxy[i], t, q, y.appliedA[i] * toStress,
                        y.appliedB[i] * toStress);
        },
        [&](uint32_t i, const ShearTrial& t, float) {
            const float na = toMultiplier * p.volume[i] * t.a;
            const float nb = toMultiplier * p.volume[i] * t.b;
            const float da = na - y.appliedA[i], db = nb - y.appliedB[i];
            y.appliedA[i] = na;
            y.appliedB[i] = nb;
            // S(dl) M^-1, which the gather reads for each pair.
            const float mxx = y.mxx[i], mxy = y.mxy[i], myy = y.myy[i];
            y.t00[i] = da * mxx + db * mxy;
            y.t01[i] = da * mxy + db * myy;
            y.t10[i] = db * mxx - da * mxy;
            y.t11[i] = db * mxy - da * myy;
        });
    const PbfPairs& k = pbfPairs();
    parallelFor(s.tasks, p.size(), kPairGrain, [&](uint32_t b, uint32_t e, uint32_t) {
        k.shearGather(v, w, b, e);
        for (uint32_t i = b; i < e; ++i) {
            const float scale = 0.5f * p.invMass[i] * depth;
            y.shearDx[i] *= scale;
            y.shearDy[i] *= scale;
            if (y.yields[i] > 0.0f) {
                holdOnWalls(s, laws, c.dt, i);
            }
        }
    });
}

void pbfShearFinish(WorldState& s, const PbfConstants& c, std::span<const YieldLaw> laws) {
    Particles& p = s.particles;
    // The trial reads only particle i's own stress, so the new one can be written in place.
    readEach(
        s, pbfView(s, c), shearView(s), c.dt,
        [&](uint32_t i, const Gradient& l, ShearTrial& t) {
            // Read in full, unscaled: scaled too, a resting stiff paste would need strain every
            // sub-step to keep its stress, that is creep.
            trialStress(laws[p.material[i]], p.structure[i], l, p.sxx[i], p.sxy[i], t);
        },
        [&](uint32_t i, const ShearTrial& t, float trial) {
            p.sxx[i] = t.a;
            p.sxy[i] = t.b;
            // Plastic flow breaks the structure; at rest it rebuilds towards 1.
            const float r = p.structure[i];
            p.structure[i] = trial > t.law.flowStress
                                 ? 0.0f
                                 : r + (1.0f - r) * std::min(c.dt / tuning::kStructureTime, 1.0f);
        });
}

void pbfShearSamples(WorldState& s, const PbfConstants& c, float weight) {
    const Particles& p = s.particles;
    const YieldScratch& y = s.yieldScratch;
    Samples& w = s.samples;
    const float* __restrict mass = p.mass.data();
    const SampleReach reach(p);
    const uint16_t* __restrict material = p.material.data();
    const std::vector<uint8_t> yields = yieldingMaterials(s);
    const auto count = static_cast<uint32_t>(w.reporting.size());
    // Particle j's own constraint moved it by -w_j/2 S(l_j) M_j^-1 G_jw for each wall sample
    // w (shearGather's self term, l_j the whole multiplier the sweeps applied); the sample
    // takes the opposite momentum over dt^2. G_jw is read at the final positions (the sweeps
    // used the reference positions': a sub-step's motion apart). The walls' hold moved j by
    // (holdX, holdY): each sample takes the opposite momentum in its share of j's wall weight,
    // read at the reference positions as the hold's weights were (the shares sum to 1).
    const float scale = 0.5f * s.def.depth / (c.dt * c.dt) * weight;
    const float holdScale = -weight / (c.dt * c.dt);
    samplePass<4>(
        s, count, w.reporting.data(),
        [&](uint32_t k) {
            const float xw = w.px[k], yw = w.py[k];
            const float friction = std::min(w.friction[k], 1.0f);
            return [&, xw, yw, friction](size_t j, SampleLane<4> a) {
                if (yields[material[j]] == 0 || !(friction > 0.0f)) {
                    return;
                }
                const float invH = 1.0f / reach.hs[j];
                const float rx = y.refX[j] - xw, ry = y.refY[j] - yw;
                const float qr = std::sqrt(rx * rx + ry * ry) * invH;
                if (qr < 1.0f && y.wallWeight[j] > 0.0f) {
                    const float t = 1.0f - qr;
                    const float share = friction * (t * t * t) / y.wallWeight[j] * mass[j];
                    a[2] += share * y.holdX[j];
                    a[3] += share * y.holdY[j];
                }
                const WallPair d = reach.at(j, xw, yw);
                if (!(d.q < 1.0f)) {
                    return;
                }
                const float t = d.t, dx = d.dx, dy = d.dy;
                const float g = friction * c.sampleVolume * kG * (invH * invH) * (invH * invH) *
                                (t * t * t);
                const float gx = g * dx, gy = g * dy;
                const float bx = y.mxx[j] * gx + y.mxy[j] * gy;
                const float by = y.mxy[j] * gx + y.myy[j] * gy;
                const float la = y.appliedA[j], lb = y.appliedB[j];
                a[0] += la * bx + lb * by;
                a[1] += lb * bx - la * by;
            };
        },
        [&](uint32_t, uint32_t k, const float(&sum)[4]) {
            w.fx[w.source[k]] += scale * sum[0] + holdScale * sum[2];
            w.fy[w.source[k]] += scale * sum[1] + holdScale * sum[3];
        });
}

} // namespace fluid::detail
