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
// (docs/position_based.md, "Yield stress").
//
// Only yielding particles take part, only with yielding neighbours and the walls (boundary
// samples, as material moving with the wall, weighted by their friction, at most 1). Each pass
// writes only its own particles' slots, in the grid's fixed order: the results do not depend on
// the number of workers.
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

// f(j, gx, gy) for every yielding particle j != i (yields: per material, 1 when it yields)
// within the pair support (h_i + h_j) / 2 of i, with (gx, gy) = V_j grad_i W_ij (1/m), in the
// grid's fixed order.
template <class Fn>
inline void eachYielding(const PbfView& v, const uint8_t* yields, uint32_t i, Fn&& f) {
    const float xi = v.px[i], yi = v.py[i], hi = v.h[i];
    gridRanges(v.grid, xi, yi, [&](uint32_t b, uint32_t e) {
        // Blocks of 16: every lane's kernel gradient first (a loop the compiler vectorises;
        // 0 outside the support), then the pairs inside the support one by one.
        constexpr uint32_t kChunk = 16;
        float gxs[kChunk], gys[kChunk], ts[kChunk];
        for (uint32_t c = b; c < e; c += kChunk) {
            const uint32_t m = std::min(kChunk, e - c);
            for (uint32_t l = 0; l < m; ++l) {
                const float dx = xi - v.px[c + l], dy = yi - v.py[c + l];
                const float invH = 2.0f / (hi + v.h[c + l]);
                const float q = std::sqrt(dx * dx + dy * dy) * invH;
                const float t = std::max(1.0f - q, 0.0f);
                const float invH2 = invH * invH;
                const float g = v.volume[c + l] * kG * (invH2 * invH2) * (t * t * t);
                ts[l] = t;
                gxs[l] = g * dx;
                gys[l] = g * dy;
            }
            for (uint32_t l = 0; l < m; ++l) {
                const uint32_t j = c + l;
                if (!(ts[l] > 0.0f) || j == i || yields[v.material[j]] == 0) {
                    continue;
                }
                f(j, gxs[l], gys[l]);
            }
        }
    });
}

// f(k, gx, gy, ux, uy) for every boundary sample k within the support of particle i, with
// (gx, gy) = friction V_w grad_i W_ik (1/m) and (ux, uy) the sample's displacement over the
// sub-step (m). Frictionless samples do not take part: the particle reads the gradient from
// its material alone, as at a free surface.
template <class Fn> inline void eachSample(const PbfView& v, uint32_t i, Fn&& f) {
    const float xi = v.px[i], yi = v.py[i];
    const float invH = 1.0f / v.h[i];
    const float invH2 = invH * invH;
    gridRanges(v.sampleGrid, xi, yi, [&](uint32_t b, uint32_t e) {
        for (uint32_t k = b; k < e; ++k) {
            const float dx = xi - v.wx[k], dy = yi - v.wy[k];
            const float q = std::sqrt(dx * dx + dy * dy) * invH;
            const float friction = std::min(v.friction[k], 1.0f);
            if (!(q < 1.0f) || !(friction > 0.0f)) {
                continue;
            }
            const float t = 1.0f - q;
            const float g = friction * v.sampleVolume * kG * (invH2 * invH2) * (t * t * t);
            f(k, g * dx, g * dy, v.wvx[k] * v.dt, v.wvy[k] * v.dt);
        }
    });
}

template <class F> void eachParticle(WorldState& s, F&& f) {
    parallelFor(s.tasks, s.particles.size(), kPairGrain, [&](uint32_t b, uint32_t e, uint32_t) {
        for (uint32_t i = b; i < e; ++i) {
            f(i);
        }
    });
}

// The displacement gradient L = grad u of particle i over the sub-step so far.
struct Gradient {
    float xx, xy, yx, yy;
};

Gradient displacementGradient(const PbfView& v, const YieldScratch& y, uint32_t n,
                              const float* cx, const float* cy, uint32_t i) {
    const float uxi = y.ux0[i] + cx[i], uyi = y.uy0[i] + cy[i];
    float hxx = 0.0f, hxy = 0.0f, hyx = 0.0f, hyy = 0.0f;
    for (uint32_t e = y.first[i]; e < y.first[i + 1]; ++e) {
        const uint32_t j = y.neighbour[e];
        const float gx = y.gradX[e], gy = y.gradY[e];
        // A sample's displacement over the sub-step is its velocity times dt.
        const float uxj = j < n ? y.ux0[j] + cx[j] : v.wvx[j - n] * v.dt;
        const float uyj = j < n ? y.uy0[j] + cy[j] : v.wvy[j - n] * v.dt;
        const float ux = uxj - uxi, uy = uyj - uyi;
        hxx += ux * gx;
        hxy += ux * gy;
        hyx += uy * gx;
        hyy += uy * gy;
    }
    const float mxx = y.mxx[i], mxy = y.mxy[i], myy = y.myy[i];
    return {hxx * mxx + hxy * mxy, hxx * mxy + hxy * myy, hyx * mxx + hyy * mxy,
            hyx * mxy + hyy * myy};
}

// The law of particle i: its material's, with the yield stress its structure holds.
YieldLaw structuredLaw(const YieldLaw& law, float structure) {
    YieldLaw l = law;
    l.flowStress = law.flowStress * (1.0f + tuning::kStructureGain * structure);
    return l;
}

// The stress the sub-step's displacement gives particle i: the stored stress (a, b) turned by
// the spin (a Cayley turn, norm kept, as yieldStep), plus 2 G times the deviatoric strain of L,
// returned to the surface of `law`. `trial` takes the norm before the return (Pa).
void shearStress(const YieldLaw& law, const Gradient& l, float dt, float& a, float& b,
                 float& trial) {
    const float u = 0.5f * (l.xy - l.yx);
    const float inv = 1.0f / (1.0f + u * u);
    const float cosine = (1.0f - u * u) * inv, sine = 2.0f * u * inv;
    const float g2 = 2.0f * law.shearModulus;
    const float ta = (a * cosine + b * sine) + g2 * 0.5f * (l.xx - l.yy);
    const float tb = (b * cosine - a * sine) + g2 * 0.5f * (l.xy + l.yx);
    trial = std::sqrt(ta * ta + tb * tb);
    a = ta;
    b = tb;
    returnStress(law, dt, a, b);
}

// The displacement of the multipliers' change (changeA, changeB) into shearDx, shearDy:
// dx_j = 1/(2 m_j/depth) [sum_i S(dl_i) M_i^-1 G_ij - S(dl_j) M_j^-1 sum_k G_jk], S(l) the
// symmetric traceless tensor of l, G_ij = V_j grad_i W_ij, k over neighbours and walls.
void gatherShear(WorldState& s) {
    const Particles& p = s.particles;
    YieldScratch& y = s.yieldScratch;
    const uint32_t n = p.size();
    const float depth = s.def.depth;
    eachParticle(s, [&](uint32_t j) {
        if (y.first[j] == y.first[j + 1]) {
            y.shearDx[j] = 0.0f;
            y.shearDy[j] = 0.0f;
            return;
        }
        float dx = 0.0f, dy = 0.0f, sx = 0.0f, sy = 0.0f;
        const float volJ = p.volume[j];
        for (uint32_t e = y.first[j]; e < y.first[j + 1]; ++e) {
            const uint32_t i = y.neighbour[e];
            const float gx = y.gradX[e], gy = y.gradY[e];
            sx += gx;
            sy += gy;
            if (i >= n) {
                continue;
            }
            // G_ij from i's side: V_j grad_i W_ij = -(V_j / V_i) times j's entry.
            const float k = -volJ / p.volume[i];
            const float ex = k * gx, ey = k * gy;
            const float bx = y.mxx[i] * ex + y.mxy[i] * ey, by = y.mxy[i] * ex + y.myy[i] * ey;
            const float da = y.changeA[i], db = y.changeB[i];
            dx += da * bx + db * by;
            dy += db * bx - da * by;
        }
        const float bx = y.mxx[j] * sx + y.mxy[j] * sy, by = y.mxy[j] * sx + y.myy[j] * sy;
        const float da = y.changeA[j], db = y.changeB[j];
        dx -= da * bx + db * by;
        dy -= db * bx - da * by;
        const float scale = 0.5f * p.invMass[j] * depth;
        y.shearDx[j] = scale * dx;
        y.shearDy[j] = scale * dy;
    });
}

} // namespace

std::vector<YieldLaw> shearLaws(const WorldState& s, float dt) {
    std::vector<YieldLaw> laws(s.constants.size());
    for (size_t m = 0; m < laws.size(); ++m) {
        const MaterialConstants& mc = s.constants[m];
        // The stiffest shear modulus whose wave crosses kShearWave of the support per sub-step:
        // the stress is read at the positions a sweep leaves, so the elastic part is explicit in
        // the sub-step (what a stiffer one did: docs/position_based.md, "The shear constraint").
        const float speed = tuning::kShearWave * mc.support / dt;
        const float stiffest = mc.restDensity * speed * speed;
        const float g =
            mc.shearModulus > 0.0f ? std::min(mc.shearModulus, stiffest) : stiffest;
        laws[m] = makeYieldLaw(mc.yielding, mc.yieldStress, mc.consistency, mc.flowIndex, g);
        // The strain is read from the positions, not accumulated as a rate: no cap on it.
        laws[m].carriedStress = std::numeric_limits<float>::max();
        laws[m].flowStress = mc.yieldStress;
    }
    return laws;
}

void pbfShearPrepare(WorldState& s, const PbfConstants& c) {
    const Particles& p = s.particles;
    const PositionBasedScratch& x = s.pbfScratch;
    YieldScratch& y = s.yieldScratch;
    const uint32_t n = p.size();
    for (auto* channel : {&y.ux0, &y.uy0, &y.mxx, &y.mxy, &y.myy, &y.appliedA, &y.appliedB,
                          &y.changeA, &y.changeB, &y.shearDx, &y.shearDy}) {
        channel->resize(n);
    }
    const std::vector<uint8_t> yields = yieldingMaterials(s);
    const PbfView v = pbfView(s, c);
    // The lists: each block of kBlock particles fills its own (blocks in parallel, each in
    // the grid's order), then they are joined in block order: the same lists for any number
    // of workers.
    constexpr uint32_t kBlock = 256;
    const uint32_t blocks = (n + kBlock - 1) / kBlock;
    y.first.resize(size_t(n) + 1);
    y.first[0] = 0;
    if (y.blocks.size() < blocks) {
        y.blocks.resize(blocks);
    }
    parallelFor(s.tasks, blocks, 1, [&](uint32_t bb, uint32_t be, uint32_t) {
        for (uint32_t block = bb; block < be; ++block) {
            YieldScratch::Block& out = y.blocks[block];
            out.neighbour.clear();
            out.gradX.clear();
            out.gradY.clear();
            const uint32_t end = std::min(n, (block + 1) * kBlock);
            for (uint32_t i = block * kBlock; i < end; ++i) {
                y.appliedA[i] = 0.0f;
                y.appliedB[i] = 0.0f;
                y.ux0[i] = x.ox[i] - x.startX[i];
                y.uy0[i] = x.oy[i] - x.startY[i];
                y.mxx[i] = y.mxy[i] = y.myy[i] = 0.0f;
                const size_t start = out.neighbour.size();
                if (yields[p.material[i]] != 0) {
                    eachYielding(v, yields.data(), i, [&](uint32_t j, float gx, float gy) {
                        out.neighbour.push_back(j);
                        out.gradX.push_back(gx);
                        out.gradY.push_back(gy);
                    });
                    eachSample(v, i, [&](uint32_t k, float gx, float gy, float, float) {
                        out.neighbour.push_back(n + k);
                        out.gradX.push_back(gx);
                        out.gradY.push_back(gy);
                    });
                }
                // The count for now; the prefix sum below makes it the list's end.
                y.first[i + 1] = uint32_t(out.neighbour.size() - start);
            }
        }
    });
    for (uint32_t i = 0; i < n; ++i) {
        y.first[i + 1] += y.first[i];
    }
    y.neighbour.resize(y.first[n]);
    y.gradX.resize(y.first[n]);
    y.gradY.resize(y.first[n]);
    parallelFor(s.tasks, blocks, 1, [&](uint32_t bb, uint32_t be, uint32_t) {
        for (uint32_t block = bb; block < be; ++block) {
            const YieldScratch::Block& in = y.blocks[block];
            const uint32_t at = y.first[block * kBlock];
            std::copy(in.neighbour.begin(), in.neighbour.end(), y.neighbour.begin() + at);
            std::copy(in.gradX.begin(), in.gradX.end(), y.gradX.begin() + at);
            std::copy(in.gradY.begin(), in.gradY.end(), y.gradY.begin() + at);
        }
    });
    eachParticle(s, [&](uint32_t i) {
        if (y.first[i] == y.first[i + 1]) {
            return;
        }
        const float xi = p.px[i], yi = p.py[i];
        // M = sum V_j (x_j - x_i) (x) grad W_ij: symmetric, about the identity inside.
        float mxx = 0.0f, mxy = 0.0f, myy = 0.0f;
        for (uint32_t e = y.first[i]; e < y.first[i + 1]; ++e) {
            const uint32_t j = y.neighbour[e];
            const float gx = y.gradX[e], gy = y.gradY[e];
            const float rx = (j < n ? v.px[j] : v.wx[j - n]) - xi;
            const float ry = (j < n ? v.py[j] : v.wy[j - n]) - yi;
            mxx += rx * gx;
            mxy += 0.5f * (rx * gy + ry * gx);
            myy += ry * gy;
        }
        // The inverse with eigenvalues held in [kLeastCorrection, 1 / kLeastCorrection]: a
        // particle with few neighbours reads at most 1 / kLeastCorrection times the plain sum.
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
    });
}

void pbfShearSweep(WorldState& s, const PbfConstants& c, std::span<const YieldLaw> laws) {
    const Particles& p = s.particles;
    const PositionBasedScratch& x = s.pbfScratch;
    YieldScratch& y = s.yieldScratch;
    const PbfView v = pbfView(s, c);
    const uint32_t n = p.size();
    const float toMultiplier = -2.0f * c.dt * c.dt;
    eachParticle(s, [&](uint32_t i) {
        const YieldLaw& law = laws[p.material[i]];
        if (!law.yielding) {
            y.changeA[i] = 0.0f;
            y.changeB[i] = 0.0f;
            return;
        }
        const Gradient l = displacementGradient(v, y, n, x.cx.data(), x.cy.data(), i);
        float a = p.sxx[i], b = p.sxy[i], trial = 0.0f;
        const YieldLaw structured = structuredLaw(law, p.structure[i]);
        shearStress(structured, l, c.dt, a, b, trial);
        const float na = toMultiplier * p.volume[i] * a, nb = toMultiplier * p.volume[i] * b;
        y.changeA[i] = na - y.appliedA[i];
        y.changeB[i] = nb - y.appliedB[i];
        y.appliedA[i] = na;
        y.appliedB[i] = nb;
    });
    gatherShear(s);
}

void pbfShearFinish(WorldState& s, const PbfConstants& c, std::span<const YieldLaw> laws) {
    Particles& p = s.particles;
    const PositionBasedScratch& x = s.pbfScratch;
    YieldScratch& y = s.yieldScratch;
    const PbfView v = pbfView(s, c);
    const uint32_t n = p.size();
    // The trial reads only particle i's own stress, so the new one can be written in place.
    eachParticle(s, [&](uint32_t i) {
        const YieldLaw& law = laws[p.material[i]];
        if (!law.yielding) {
            return;
        }
        const Gradient l = displacementGradient(v, y, n, x.cx.data(), x.cy.data(), i);
        const YieldLaw structured = structuredLaw(law, p.structure[i]);
        float a = p.sxx[i], b = p.sxy[i], trial = 0.0f;
        shearStress(structured, l, c.dt, a, b, trial);
        p.sxx[i] = a;
        p.sxy[i] = b;
        // Plastic flow breaks the structure; at rest it rebuilds towards 1.
        const float r = p.structure[i];
        p.structure[i] = trial > structured.flowStress
                             ? 0.0f
                             : r + (1.0f - r) * std::min(c.dt / tuning::kStructureTime, 1.0f);
    });
}

void pbfShearSamples(WorldState& s, const PbfConstants& c, float weight) {
    const Particles& p = s.particles;
    const YieldScratch& y = s.yieldScratch;
    Samples& w = s.samples;
    const float* __restrict px = p.px.data();
    const float* __restrict py = p.py.data();
    const float* __restrict hs = p.h.data();
    const uint16_t* __restrict material = p.material.data();
    const std::vector<uint8_t> yields = yieldingMaterials(s);
    const auto count = static_cast<uint32_t>(w.reporting.size());
    // Particle j's own constraint moved it by -w_j/2 S(l_j) M_j^-1 G_jw for each wall sample
    // w (gatherShear's self term, l_j the whole multiplier the sweeps applied); the sample
    // takes the opposite momentum over dt^2. G_jw is read at the final positions (the sweeps
    // used the lists' from their start: a sub-step's motion apart).
    const float scale = 0.5f * s.def.depth / (c.dt * c.dt) * weight;
    samplePass<2>(
        s, count, w.reporting.data(),
        [&](uint32_t k) {
            const float xw = w.px[k], yw = w.py[k];
            const float friction = std::min(w.friction[k], 1.0f);
            return [&, xw, yw, friction](size_t j, SampleLane<2> a) {
                if (yields[material[j]] == 0 || !(friction > 0.0f)) {
                    return;
                }
                const float dx = px[j] - xw, dy = py[j] - yw;
                const float invH = 1.0f / hs[j];
                const float q = std::sqrt(dx * dx + dy * dy) * invH;
                if (!(q < 1.0f)) {
                    return;
                }
                const float t = 1.0f - q;
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
        [&](uint32_t, uint32_t k, const float(&sum)[2]) {
            w.fx[w.source[k]] += scale * sum[0];
            w.fy[w.source[k]] += scale * sum[1];
        });
}

} // namespace fluid::detail
