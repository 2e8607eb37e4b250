// fluid — the position-based solver's neighbour passes.
//
// Same scheme as sph_loops.cpp: each particle gathers over the grid's contiguous ranges in
// branch-free blocks of kLanes, lanes summed in a fixed order, pair supports h_ij = (h_i+h_j)/2,
// boundary samples with the particle's own support. Every pass writes only particle i's slots,
// so results do not depend on the number of workers.
#include "pbf_loops.h"

#include "lanes.h"
#include "parallel.h"

#include <algorithm>
#include <cmath>

namespace fluid::detail {

void pbfConstraint(WorldState& s, const PbfConstants& c) {
    Particles& p = s.particles;
    const Samples& w = s.samples;
    const float* __restrict px = p.px.data();
    const float* __restrict py = p.py.data();
    const float* __restrict hs = p.h.data();
    const float* __restrict wm = p.invMass.data();
    const float* __restrict wx = w.px.data();
    const float* __restrict wy = w.py.data();
    parallelFor(s.tasks, p.size(), kPairGrain, [&](uint32_t b, uint32_t e, uint32_t) {
        for (uint32_t i = b; i < e; ++i) {
            const float xi = px[i], yi = py[i], hi = hs[i];
            float sw[kLanes] = {}, gx[kLanes] = {}, gy[kLanes] = {}, sq[kLanes] = {};
            s.grid.forEachRange(xi, yi, [&](uint32_t jb, uint32_t je) {
                lanes(jb, je, [&](size_t j, int l) {
                    const float dx = xi - px[j], dy = yi - py[j];
                    const float r2 = dx * dx + dy * dy;
                    const float invH = 2.0f / (hi + hs[j]);
                    const float q = std::sqrt(r2) * invH;
                    const float t = std::max(1.0f - q, 0.0f);
                    const float t2 = t * t;
                    const float invH2 = invH * invH;
                    sw[l] += invH2 * (t2 * t2) * (1.0f + 4.0f * q);
                    const float g = invH2 * invH2 * (t2 * t); // grad W / (kG r)
                    gx[l] += g * dx;
                    gy[l] += g * dy;
                    sq[l] += wm[j] * g * g * r2;
                });
            });
            const float invH = 1.0f / hi;
            float ww[kLanes] = {}, wgx[kLanes] = {}, wgy[kLanes] = {};
            w.grid.forEachRange(xi, yi, [&](uint32_t kb, uint32_t ke) {
                lanes(kb, ke, [&](size_t k, int l) {
                    const float dx = xi - wx[k], dy = yi - wy[k];
                    const float q = std::sqrt(dx * dx + dy * dy) * invH;
                    const float t = std::max(1.0f - q, 0.0f);
                    const float t2 = t * t;
                    ww[l] += (t2 * t2) * (1.0f + 4.0f * q);
                    wgx[l] += (t2 * t) * dx;
                    wgy[l] += (t2 * t) * dy;
                });
            });
            // Volumes over the lattice sum: a particle inside its material's lattice reads C = 0.
            const float li = p.invLattice[i];
            const float vi = p.volume[i] * li, vw = c.sampleVolume * li;
            const float invH4 = (invH * invH) * (invH * invH);
            // At least the particle's own term: one that strayed out of the cells it was sorted
            // into finds no neighbour, not even itself.
            const float number = std::max(vi * kW * laneSum(sw), vi * kW * invH * invH) +
                                 vw * kW * invH * invH * laneSum(ww);
            const float constraint = number - 1.0f;
            const float fluidX = vi * kG * laneSum(gx), fluidY = vi * kG * laneSum(gy);
            const float wallX = vw * kG * invH4 * laneSum(wgx);
            const float wallY = vw * kG * invH4 * laneSum(wgy);
            const float gradX = fluidX + wallX, gradY = fluidY + wallY;
            const float others = vi * vi * kG * kG * laneSum(sq);
            p.constraint[i] = constraint;
            const float least = c.floorShare * s.constants[p.material[i]].diagonal;
            p.diagonal[i] =
                std::max(wm[i] * (gradX * gradX + gradY * gradY) + others, least) + c.epsilon;
            p.density[i] = p.restDensity[i] * number;
            p.invRho[i] = 1.0f / p.density[i];
        }
    });
}

namespace {

template <bool kSCorr>
void displace(WorldState& s, const PbfConstants& c, std::span<const float> multiplier) {
    Particles& p = s.particles;
    const Samples& w = s.samples;
    const float* __restrict px = p.px.data();
    const float* __restrict py = p.py.data();
    const float* __restrict hs = p.h.data();
    const float* __restrict vol = p.volume.data();
    const float* __restrict il = p.invLattice.data();
    const float* __restrict dl = multiplier.data();
    const float* __restrict pa = p.pairPressure.data();
    const float* __restrict wx = w.px.data();
    const float* __restrict wy = w.py.data();
    parallelFor(s.tasks, p.size(), kPairGrain, [&](uint32_t b, uint32_t e, uint32_t) {
        for (uint32_t i = b; i < e; ++i) {
            const float xi = px[i], yi = py[i], hi = hs[i], vi = vol[i];
            const float dli = dl[i] * vi * il[i], pai = pa[i];
            float ax[kLanes] = {}, ay[kLanes] = {};
            s.grid.forEachRange(xi, yi, [&](uint32_t jb, uint32_t je) {
                lanes(jb, je, [&](size_t j, int l) {
                    const float dx = xi - px[j], dy = yi - py[j];
                    const float invH = 2.0f / (hi + hs[j]);
                    const float q = std::sqrt(dx * dx + dy * dy) * invH;
                    const float t = std::max(1.0f - q, 0.0f);
                    const float t2 = t * t;
                    const float invH2 = invH * invH;
                    float m = dli + dl[j] * vol[j] * il[j];
                    if constexpr (kSCorr) {
                        // s_corr = -k (W_ij / W(dq))^4 [Macklin & Mueller 2013, eq. 13], k from
                        // the pair's artificial pressure (Pa) so that it means the same at any dt.
                        const float ratio = (t2 * t2) * (1.0f + 4.0f * q) * c.invWdq;
                        const float r2 = ratio * ratio;
                        m -= c.artificial * 0.5f * (pai + pa[j]) * vi * vol[j] * (r2 * r2);
                    }
                    const float f = m * (invH2 * invH2) * (t2 * t);
                    ax[l] += f * dx;
                    ay[l] += f * dy;
                });
            });
            const float invH = 1.0f / hi;
            float wX[kLanes] = {}, wY[kLanes] = {};
            w.grid.forEachRange(xi, yi, [&](uint32_t kb, uint32_t ke) {
                lanes(kb, ke, [&](size_t k, int l) {
                    const float dx = xi - wx[k], dy = yi - wy[k];
                    const float t = std::max(1.0f - std::sqrt(dx * dx + dy * dy) * invH, 0.0f);
                    wX[l] += (t * t * t) * dx;
                    wY[l] += (t * t * t) * dy;
                });
            });
            const float wall = dl[i] * c.sampleVolume * il[i] * (invH * invH) * (invH * invH);
            const float scale = p.invMass[i] * kG;
            p.ax[i] = scale * (laneSum(ax) + wall * laneSum(wX));
            p.ay[i] = scale * (laneSum(ay) + wall * laneSum(wY));
        }
    });
}

} // namespace

void pbfDisplace(WorldState& s, const PbfConstants& c, std::span<const float> multiplier,
                 bool sCorr) {
    if (sCorr) {
        displace<true>(s, c, multiplier);
    } else {
        displace<false>(s, c, multiplier);
    }
}

namespace {

template <bool kFirst> void viscosity(WorldState& s, const PbfConstants& c, float scale) {
    Particles& p = s.particles;
    const Samples& w = s.samples;
    const float* __restrict px = p.px.data();
    const float* __restrict py = p.py.data();
    const float* __restrict vx = p.vx.data();
    const float* __restrict vy = p.vy.data();
    const float* __restrict hs = p.h.data();
    const float* __restrict mu = p.viscosity.data();
    const float* __restrict vol = p.volume.data();
    const float* __restrict mt = p.massPerDepth.data();
    const float* __restrict invRho = p.invRho.data();
    const float dt = c.dt * scale;
    parallelFor(s.tasks, p.size(), kPairGrain, [&](uint32_t b, uint32_t e, uint32_t) {
        for (uint32_t i = b; i < e; ++i) {
            const float xi = px[i], yi = py[i], vxi = vx[i], vyi = vy[i], hi = hs[i];
            const float mui = mu[i];
            float ax[kLanes] = {}, ay[kLanes] = {};
            float curl[kLanes] = {}, nx[kLanes] = {}, ny[kLanes] = {}, sw[kLanes] = {};
            s.grid.forEachRange(xi, yi, [&](uint32_t jb, uint32_t je) {
                lanes(jb, je, [&](size_t j, int l) {
                    const float dx = xi - px[j], dy = yi - py[j];
                    const float invH = 2.0f / (hi + hs[j]);
                    const float q = std::sqrt(dx * dx + dy * dy) * invH;
                    const float t = std::max(1.0f - q, 0.0f);
                    const float invH2 = invH * invH;
                    const float invH4 = invH2 * invH2;
                    const float dvx = vx[j] - vxi, dvy = vy[j] - vyi;
                    const float fv = 0.5f * (mui + mu[j]) * vol[j] * invH4 * t;
                    ax[l] += fv * dvx;
                    ay[l] += fv * dvy;
                    if constexpr (kFirst) {
                        const float t2 = t * t;
                        const float g = invH4 * (t2 * t); // grad W / (kG r)
                        curl[l] += vol[j] * g * (dx * dvy - dy * dvx);
                        const float gn = mt[j] * invRho[j] * g;
                        nx[l] += gn * dx;
                        ny[l] += gn * dy;
                        sw[l] += invH2 * (t2 * t2) * (1.0f + 4.0f * q);
                    }
                });
            });
            const float invH = 1.0f / hi;
            float wX[kLanes] = {}, wY[kLanes] = {}, ww[kLanes] = {};
            w.grid.forEachRange(xi, yi, [&](uint32_t kb, uint32_t ke) {
                lanes(kb, ke, [&](size_t k, int l) {
                    const float dx = xi - w.px[k], dy = yi - w.py[k];
                    const float q = std::sqrt(dx * dx + dy * dy) * invH;
                    const float t = std::max(1.0f - q, 0.0f);
                    wX[l] += w.friction[k] * t * (w.vx[k] - vxi);
                    wY[l] += w.friction[k] * t * (w.vy[k] - vyi);
                    if constexpr (kFirst) {
                        const float t2 = t * t;
                        ww[l] += (t2 * t2) * (1.0f + 4.0f * q);
                    }
                });
            });
            const float invRho0 = 1.0f / p.restDensity[i];
            const float invH4 = (invH * invH) * (invH * invH);
            const float wall = mui * c.sampleVolume * invH4;
            p.ax[i] = vxi + dt * invRho0 * kL * (laneSum(ax) + wall * laneSum(wX));
            p.ay[i] = vyi + dt * invRho0 * kL * (laneSum(ay) + wall * laneSum(wY));
            if constexpr (kFirst) {
                p.vorticity[i] = kG * laneSum(curl);
                p.nx[i] = hi * kG * laneSum(nx);
                p.ny[i] = hi * kG * laneSum(ny);
                p.density[i] =
                    (mt[i] * kW * std::max(laneSum(sw), invH * invH) +
                     p.restDensity[i] * c.sampleVolume * kW * invH * invH * laneSum(ww)) *
                    p.invLattice[i];
            }
        }
    });
}

} // namespace

void pbfViscosity(WorldState& s, const PbfConstants& c, float scale, bool first) {
    if (first) {
        viscosity<true>(s, c, scale);
    } else {
        viscosity<false>(s, c, scale);
    }
}

namespace {

template <bool kSurface, bool kVorticity>
void surface(WorldState& s, const PbfConstants& c, float vorticity) {
    Particles& p = s.particles;
    const float* __restrict px = p.px.data();
    const float* __restrict py = p.py.data();
    const float* __restrict hs = p.h.data();
    const float* __restrict vol = p.volume.data();
    const float* __restrict mass = p.mass.data();
    const float* __restrict rho0 = p.restDensity.data();
    const float* __restrict gamma = p.gamma.data();
    const float* __restrict rho = p.density.data();
    const float* __restrict omega = p.vorticity.data();
    const float* __restrict nx = p.nx.data();
    const float* __restrict ny = p.ny.data();
    parallelFor(s.tasks, p.size(), kPairGrain, [&](uint32_t b, uint32_t e, uint32_t) {
        for (uint32_t i = b; i < e; ++i) {
            const float xi = px[i], yi = py[i], hi = hs[i];
            const float absOmega = std::fabs(omega[i]);
            const float massi = mass[i], rho0i = rho0[i], gammai = gamma[i], rhoi = rho[i];
            const float nxi = kSurface ? nx[i] : 0.0f, nyi = kSurface ? ny[i] : 0.0f;
            float etaX[kLanes] = {}, etaY[kLanes] = {}, ax[kLanes] = {}, ay[kLanes] = {};
            s.grid.forEachRange(xi, yi, [&](uint32_t jb, uint32_t je) {
                lanes(jb, je, [&](size_t j, int l) {
                    const float dx = xi - px[j], dy = yi - py[j];
                    const float r = std::sqrt(dx * dx + dy * dy);
                    const float invH = 2.0f / (hi + hs[j]);
                    const float q = r * invH;
                    const float t = std::max(1.0f - q, 0.0f);
                    const float invH2 = invH * invH;
                    if constexpr (kVorticity) {
                        // eta = grad |omega| [Macklin & Mueller 2013, eq. 16], difference form.
                        const float g = kG * vol[j] * (std::fabs(omega[j]) - absOmega) *
                                        (invH2 * invH2) * (t * t * t);
                        etaX[l] += g * dx;
                        etaY[l] += g * dy;
                    }
                    if constexpr (kSurface) {
                        // Cohesion and curvature [Akinci 2013, eqs. 1-6], as in sph_loops.cpp.
                        const float k =
                            0.5f * (gammai + gamma[j]) * (rho0i + rho0[j]) / (rhoi + rho[j]);
                        const float a = t * q;
                        const float a3 = a * a * a;
                        const float spline = 2.0f * q > 1.0f ? a3 : 2.0f * a3 - 1.0f / 64.0f;
                        const float coh = mass[j] * kC * invH2 * spline / std::max(r, 1e-12f);
                        const float inside = t > 0.0f ? 1.0f : 0.0f;
                        const float curv = inside * 2.0f * mass[j] / (massi + mass[j]);
                        ax[l] -= k * (coh * dx + curv * (nxi - nx[j]));
                        ay[l] -= k * (coh * dy + curv * (nyi - ny[j]));
                    }
                });
            });
            float fx = laneSum(ax), fy = laneSum(ay);
            if constexpr (kVorticity) {
                // f = eps h |omega| (N x omega), N = eta / |eta|: a vortex's rotation speed at
                // radius h, given back at rate eps per radian [Macklin & Mueller 2013, eq. 15].
                const float ex = laneSum(etaX), ey = laneSum(etaY);
                const float len = std::sqrt(ex * ex + ey * ey);
                if (len > 0.0f) {
                    const float scale = vorticity * hi * absOmega * omega[i] / len;
                    fx += scale * ey;
                    fy -= scale * ex;
                }
            }
            p.vx[i] += c.dt * fx;
            p.vy[i] += c.dt * fy;
        }
    });
}

} // namespace

void pbfSurface(WorldState& s, const PbfConstants& c, float vorticity, bool surfaceTension) {
    const bool spin = vorticity > 0.0f;
    if (surfaceTension && spin) {
        surface<true, true>(s, c, vorticity);
    } else if (surfaceTension) {
        surface<true, false>(s, c, vorticity);
    } else if (spin) {
        surface<false, true>(s, c, vorticity);
    }
}

void pbfSamplePush(WorldState& s, const PbfConstants& c, std::span<const float> change, float omega,
                   bool first) {
    const Particles& p = s.particles;
    Samples& w = s.samples;
    const float* __restrict px = p.px.data();
    const float* __restrict py = p.py.data();
    const float* __restrict hs = p.h.data();
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
    parallelFor(s.tasks, count, kPairGrain, [&](uint32_t b, uint32_t e, uint32_t) {
        for (uint32_t r = b; r < e; ++r) {
            const uint32_t k = w.reporting[r];
            const float xw = w.px[k], yw = w.py[k];
            float accX[kLanes] = {}, accY[kLanes] = {};
            s.grid.forEachRange(xw, yw, [&](uint32_t jb, uint32_t je) {
                lanes(jb, je, [&](size_t j, int l) {
                    const float dx = px[j] - xw, dy = py[j] - yw;
                    const float invH = 1.0f / hs[j];
                    const float t = std::max(1.0f - std::sqrt(dx * dx + dy * dy) * invH, 0.0f);
                    const float invH4 = (invH * invH) * (invH * invH);
                    // pbfDisplace's wall term moves j by w_j kG dl_j V_w L_j h^-4 t^3 (x_j - x_w).
                    const float f = -dl[j] * il[j] * kG * invH4 * (t * t * t);
                    accX[l] += f * dx;
                    accY[l] += f * dy;
                });
            });
            const float fx = c.sampleVolume * invDt2 * laneSum(accX);
            const float fy = c.sampleVolume * invDt2 * laneSum(accY);
            if (first) {
                w.pushX[r] = fx;
                w.pushY[r] = fy;
            } else {
                // As the positions: x_k+1 = omega (x_k + d_k - x_k-1) + x_k-1.
                const float x = omega * (w.pushX[r] + fx - w.pushPrevX[r]) + w.pushPrevX[r];
                const float y = omega * (w.pushY[r] + fy - w.pushPrevY[r]) + w.pushPrevY[r];
                w.pushPrevX[r] = w.pushX[r];
                w.pushPrevY[r] = w.pushY[r];
                w.pushX[r] = x;
                w.pushY[r] = y;
            }
        }
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
    const float* __restrict px = p.px.data();
    const float* __restrict py = p.py.data();
    const float* __restrict vx = p.vx.data();
    const float* __restrict vy = p.vy.data();
    const float* __restrict hs = p.h.data();
    const float* __restrict mu = p.viscosity.data();
    const float* __restrict vol = p.volume.data();
    const float depth = s.def.depth;
    const auto count = static_cast<uint32_t>(w.reporting.size());
    parallelFor(s.tasks, count, kPairGrain, [&](uint32_t b, uint32_t e, uint32_t) {
        for (uint32_t r = b; r < e; ++r) {
            const uint32_t k = w.reporting[r];
            const float xw = w.px[k], yw = w.py[k];
            const float vxw = w.vx[k], vyw = w.vy[k], friction = w.friction[k];
            float accX[kLanes] = {}, accY[kLanes] = {}, accD[kLanes] = {};
            s.grid.forEachRange(xw, yw, [&](uint32_t jb, uint32_t je) {
                lanes(jb, je, [&](size_t j, int l) {
                    const float dx = px[j] - xw, dy = py[j] - yw;
                    const float invH = 1.0f / hs[j];
                    const float t = std::max(1.0f - std::sqrt(dx * dx + dy * dy) * invH, 0.0f);
                    const float invH4 = (invH * invH) * (invH * invH);
                    // pbfViscosity's wall friction on j: m_j mu_j/rho0_j f V_w L (v_w - v_j),
                    // m_j/rho0_j = V_j depth.
                    const float fv = depth * vol[j] * friction * mu[j] * kL * invH4 * t;
                    accX[l] -= fv * (vxw - vx[j]);
                    accY[l] -= fv * (vyw - vy[j]);
                    accD[l] += fv;
                });
            });
            const float share = weight * scale * c.sampleVolume;
            w.fx[w.source[k]] += share * laneSum(accX);
            w.fy[w.source[k]] += share * laneSum(accY);
            w.drag[w.source[k]] += share * laneSum(accD);
        }
    });
}

} // namespace fluid::detail
