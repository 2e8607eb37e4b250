// fluid — the SPH neighbour loops shared by the solvers.
//
// Each particle i gathers over the contiguous index ranges the grid gives for its 3x3 cells.
// Inside a range the loop runs in blocks of kLanes candidates with one accumulator per lane and
// no branch (candidates beyond the support radius contribute an exact 0 through the clamped
// kernels), so the compiler turns it into SIMD code; the lanes are summed in a fixed order at
// the end, so the result depends only on the (deterministic) grid order, never on threads.
// Pair supports are h_ij = (h_i + h_j)/2, so every pair term is symmetric and, multiplied by
// m_i, antisymmetric in (i, j): momentum is conserved. Densities are number densities times the
// particle's own mass, rho_i = m_i sum_j W_ij [Solenthaler & Pajarola 2008]: at an interface
// between materials of different rest density each side reads its own rest density, so
// yoghurt in water neither reads water's lower density (and loses its pressure) nor the
// reverse.
#include "sph_loops.h"

#include "lanes.h"
#include "parallel.h"
#include "sample_pass.h"

#include <algorithm>
#include <cmath>

namespace fluid::detail {

namespace {

// True when the constants fillMaterialChannels reads are the same in a and b (NaN never is).
bool sameChannelValues(const MaterialConstants& a, const MaterialConstants& b) {
    return a.support == b.support && a.massPerDepth == b.massPerDepth &&
           a.viscosity == b.viscosity && a.mass == b.mass && a.restDensity == b.restDensity &&
           a.gamma == b.gamma && a.backgroundPressure == b.backgroundPressure &&
           a.lattice == b.lattice && a.yielding == b.yielding;
}

} // namespace

void fillMaterialChannels(WorldState& s, const TaskHook& tasks) {
    Particles& p = s.particles;
    const uint32_t n = p.size();
    for (auto* channel : {&p.h, &p.massPerDepth, &p.viscosity, &p.mass, &p.restDensity, &p.gamma,
                          &p.invMass, &p.volume, &p.pairPressure, &p.invLattice}) {
        channel->resize(n);
    }
    // A yield-stress material's skin against another material (tuning::kSkinCohesion; the
    // position-based passes read it).
    const bool skin =
        s.def.solver == Solver::PositionBased && s.constants.size() >= 2 &&
        std::any_of(s.constants.begin(), s.constants.end(),
                    [](const MaterialConstants& c) { return c.yielding && c.gamma > 0.0f; });
    for (auto* channel : {&p.skinGamma, &p.materialTag, &p.otherShare}) {
        channel->resize(skin ? n : 0);
    }
    // One material, with the constants, count and skin of the last fill, which was of one
    // material too: each channel holds one value, which the sort cannot have changed (a
    // 100,000-particle dam: 0.28 ms a sub-step on the sort's worker).
    const uint16_t first = n > 0 ? p.material[0] : uint16_t(0);
    const bool uniform = n > 0 && std::all_of(p.material.begin(), p.material.end(),
                                              [first](uint16_t m) { return m == first; });
    WorldState::UniformFill& last = s.materialFill;
    if (uniform && last.uniform && last.material == first && last.count == n && last.skin == skin &&
        sameChannelValues(last.constants, s.constants[first])) {
        return;
    }
    last.uniform = uniform;
    last.skin = skin;
    last.material = first;
    last.count = n;
    if (uniform) {
        last.constants = s.constants[first];
    }
    parallelFor(tasks, n, 1024, [&](uint32_t b, uint32_t e, uint32_t) {
        for (uint32_t i = b; i < e; ++i) {
            const MaterialConstants& c = s.constants[p.material[i]];
            if (skin) {
                p.skinGamma[i] = c.yielding ? tuning::kSkinCohesion * c.gamma : 0.0f;
                p.materialTag[i] = float(p.material[i]);
            }
            p.h[i] = c.support;
            p.massPerDepth[i] = c.massPerDepth;
            p.viscosity[i] = c.viscosity;
            p.mass[i] = c.mass;
            p.restDensity[i] = c.restDensity;
            p.gamma[i] = c.gamma;
            p.invMass[i] = 1.0f / c.mass;
            p.volume[i] = c.massPerDepth / c.restDensity;
            p.pairPressure[i] = c.backgroundPressure;
            p.invLattice[i] = 1.0f / c.lattice;
        }
    });
}

void computeDensity(WorldState& s, float sampleVolume) {
    Particles& p = s.particles;
    const Samples& w = s.samples;
    const float* __restrict px = p.px.data();
    const float* __restrict py = p.py.data();
    const float* __restrict hs = p.h.data();
    const float* __restrict mt = p.massPerDepth.data();
    const float* __restrict wx = w.px.data();
    const float* __restrict wy = w.py.data();
    parallelFor(s.tasks, p.size(), kPairGrain, [&](uint32_t b, uint32_t e, uint32_t) {
        for (uint32_t i = b; i < e; ++i) {
            const float xi = px[i], yi = py[i], hi = hs[i];
            float acc[kLanes] = {};
            s.grid.forEachRange(xi, yi, [&](uint32_t jb, uint32_t je) {
                lanes(jb, je, [&](size_t j, int l) {
                    const float dx = xi - px[j], dy = yi - py[j];
                    const float r = std::sqrt(dx * dx + dy * dy);
                    const float invH = 2.0f / (hi + hs[j]);
                    const float q = r * invH;
                    const float t = std::max(1.0f - q, 0.0f);
                    const float t2 = t * t;
                    acc[l] += (invH * invH) * (t2 * t2) * (1.0f + 4.0f * q);
                });
            });
            // Boundary samples, with the particle's own support.
            const float invH = 1.0f / hi;
            float wall[kLanes] = {};
            w.grid.forEachRange(xi, yi, [&](uint32_t kb, uint32_t ke) {
                lanes(kb, ke, [&](size_t k, int l) {
                    const float dx = xi - wx[k], dy = yi - wy[k];
                    const float q = std::sqrt(dx * dx + dy * dy) * invH;
                    const float t = std::max(1.0f - q, 0.0f);
                    const float t2 = t * t;
                    wall[l] += (t2 * t2) * (1.0f + 4.0f * q);
                });
            });
            // Over the lattice sum, as the position-based solver reads it: a particle inside
            // its material's resting lattice reads the rest density, so a blob starts at rest
            // instead of 0.42% compressed (water; docs/solver.md, Known limits).
            p.density[i] = (mt[i] * kW * laneSum(acc) +
                            p.restDensity[i] * sampleVolume * kW * invH * invH * laneSum(wall)) *
                           p.invLattice[i];
        }
    });
}

void computeNormals(WorldState& s) {
    Particles& p = s.particles;
    ExplicitScratch& x = s.explicitScratch;
    const float* __restrict px = p.px.data();
    const float* __restrict py = p.py.data();
    const float* __restrict hs = p.h.data();
    const float* __restrict mt = p.massPerDepth.data();
    const float* __restrict invRho = p.invRho.data();
    parallelFor(s.tasks, p.size(), kPairGrain, [&](uint32_t b, uint32_t e, uint32_t) {
        for (uint32_t i = b; i < e; ++i) {
            const float xi = px[i], yi = py[i], hi = hs[i];
            float accX[kLanes] = {}, accY[kLanes] = {};
            s.grid.forEachRange(xi, yi, [&](uint32_t jb, uint32_t je) {
                lanes(jb, je, [&](size_t j, int l) {
                    const float dx = xi - px[j], dy = yi - py[j];
                    const float r = std::sqrt(dx * dx + dy * dy);
                    const float invH = 2.0f / (hi + hs[j]);
                    const float t = std::max(1.0f - r * invH, 0.0f);
                    const float invH2 = invH * invH;
                    const float g = mt[j] * invRho[j] * (invH2 * invH2) * (t * t * t);
                    accX[l] += g * dx;
                    accY[l] += g * dy;
                });
            });
            x.nx[i] = hi * kG * laneSum(accX);
            x.ny[i] = hi * kG * laneSum(accY);
        }
    });
}

namespace {

template <bool kSurface> void forces(WorldState& s, float sampleVolume) {
    Particles& p = s.particles;
    ExplicitScratch& x = s.explicitScratch;
    const Samples& w = s.samples;
    const float* __restrict px = p.px.data();
    const float* __restrict py = p.py.data();
    const float* __restrict vx = p.vx.data();
    const float* __restrict vy = p.vy.data();
    const float* __restrict hs = p.h.data();
    const float* __restrict mt = p.massPerDepth.data();
    const float* __restrict mu = p.viscosity.data();
    const float* __restrict mass = p.mass.data();
    const float* __restrict rho0 = p.restDensity.data();
    const float* __restrict gamma = p.gamma.data();
    const float* __restrict rho = p.density.data();
    const float* __restrict invRho = p.invRho.data();
    const float* __restrict p2 = x.pOverRho2.data();
    const float* __restrict nx = x.nx.data();
    const float* __restrict ny = x.ny.data();
    parallelFor(s.tasks, p.size(), kPairGrain, [&](uint32_t b, uint32_t e, uint32_t) {
        for (uint32_t i = b; i < e; ++i) {
            const float xi = px[i], yi = py[i], vxi = vx[i], vyi = vy[i], hi = hs[i];
            const float invRhoi = invRho[i], mui = mu[i], rhoi = rho[i];
            const float piMt = p2[i] * mt[i], invMti = 1.0f / mt[i];
            const float massi = mass[i], rho0i = rho0[i], gammai = gamma[i];
            const float nxi = kSurface ? nx[i] : 0.0f, nyi = kSurface ? ny[i] : 0.0f;
            float accX[kLanes] = {}, accY[kLanes] = {};
            s.grid.forEachRange(xi, yi, [&](uint32_t jb, uint32_t je) {
                lanes(jb, je, [&](size_t j, int l) {
                    const float dx = xi - px[j], dy = yi - py[j];
                    const float r = std::sqrt(dx * dx + dy * dy);
                    const float invH = 2.0f / (hi + hs[j]);
                    const float q = r * invH;
                    const float t = std::max(1.0f - q, 0.0f);
                    const float invH2 = invH * invH;
                    const float invH4 = invH2 * invH2;
                    // Pressure, seed eq. 2.5 in the volume form of [Solenthaler 2008]:
                    // -(1/m_i) (p_i V_i^2 + p_j V_j^2) grad W with V = m/rho; for one
                    // material it is the seed's -m (p_i/rho_i^2 + p_j/rho_j^2) grad W.
                    const float fp =
                        -(piMt + p2[j] * mt[j] * mt[j] * invMti) * kG * invH4 * (t * t * t);
                    // Viscosity, seed eq. 2.6, with the pair's mean mu.
                    const float fv =
                        0.5f * (mui + mu[j]) * invRhoi * mt[j] * invRho[j] * kL * invH4 * t;
                    float fx = fp * dx + fv * (vx[j] - vxi);
                    float fy = fp * dy + fv * (vy[j] - vyi);
                    if constexpr (kSurface) {
                        // Cohesion and curvature [Akinci 2013, eqs. 1-6]; K_ij corrects the
                        // particle deficiency at the surface.
                        const float k =
                            0.5f * (gammai + gamma[j]) * (rho0i + rho0[j]) / (rhoi + rho[j]);
                        const float a = t * q; // (1-u) u, and 0 beyond the support
                        const float a3 = a * a * a;
                        const float spline = 2.0f * q > 1.0f ? a3 : 2.0f * a3 - 1.0f / 64.0f;
                        const float coh = mass[j] * kC * invH2 * spline / std::max(r, 1e-12f);
                        const float inside = t > 0.0f ? 1.0f : 0.0f;
                        const float curv = inside * 2.0f * mass[j] / (massi + mass[j]);
                        fx -= k * (coh * dx + curv * (nxi - nx[j]));
                        fy -= k * (coh * dy + curv * (nyi - ny[j]));
                    }
                    accX[l] += fx;
                    accY[l] += fy;
                });
            });
            float ax = x.ex[i] + laneSum(accX);
            float ay = x.ey[i] + laneSum(accY);

            // Boundary samples: pressure (the sample's density taken equal to the particle's)
            // and friction, with the particle's own support.
            const float invH = 1.0f / hi;
            const float invH4 = invH * invH * invH * invH;
            const float wallP = -rho0i * sampleVolume * kG * invH4;
            const float wallV = mui * invRhoi * sampleVolume * kL * invH4;
            const float invRho2 = invRhoi * invRhoi;
            const float piWall = p.pressure[i] * invRho2; // no background pressure at walls
            float wX[kLanes] = {}, wY[kLanes] = {};
            w.grid.forEachRange(xi, yi, [&](uint32_t kb, uint32_t ke) {
                lanes(kb, ke, [&](size_t k, int l) {
                    const float dx = xi - w.px[k], dy = yi - w.py[k];
                    const float t = std::max(1.0f - std::sqrt(dx * dx + dy * dy) * invH, 0.0f);
                    const float fp = wallP * (piWall + w.pressure[k] * invRho2) * (t * t * t);
                    const float fv = wallV * w.friction[k] * t;
                    wX[l] += fp * dx + fv * (w.vx[k] - vxi);
                    wY[l] += fp * dy + fv * (w.vy[k] - vyi);
                });
            });
            x.ax[i] = ax + laneSum(wX);
            x.ay[i] = ay + laneSum(wY);
        }
    });
}

} // namespace

void computeSamplePressure(WorldState& s) {
    const Particles& p = s.particles;
    const ExplicitScratch& x = s.explicitScratch;
    Samples& w = s.samples;
    const float* __restrict rho = p.density.data();
    const float* __restrict pressure = p.pressure.data();
    const float* __restrict ex = x.ex.data();
    const float* __restrict ey = x.ey.data();
    // Channels: the kernel-weighted pressures with their hydrostatic terms, the kernel weights.
    const SampleReach reach(p);
    samplePass<2>(
        s, w.size(), nullptr,
        [&](uint32_t k) {
            const float xw = w.px[k], yw = w.py[k];
            return [&, xw, yw](size_t j, SampleLane<2> a) {
                // (x_w - x_j): the pair's offset negated, exactly.
                const WallPair d = reach.at(j, xw, yw);
                const float t2 = d.t * d.t;
                const float wk = (d.invH * d.invH) * (t2 * t2) * (1.0f + 4.0f * d.q);
                a[0] += (pressure[j] - rho[j] * (ex[j] * d.dx + ey[j] * d.dy)) * wk;
                a[1] += wk;
            };
        },
        [&](uint32_t, uint32_t k, const float(&sum)[2]) {
            w.pressure[k] = sum[1] > 0.0f ? std::max(0.0f, sum[0] / sum[1]) : 0.0f;
        });
}

void computeSampleForces(WorldState& s, float sampleVolume, float weight) {
    const Particles& p = s.particles;
    Samples& w = s.samples;
    const float* __restrict vx = p.vx.data();
    const float* __restrict vy = p.vy.data();
    const float* __restrict mass = p.mass.data();
    const float* __restrict rho0 = p.restDensity.data();
    const float* __restrict mu = p.viscosity.data();
    const float* __restrict invRho = p.invRho.data();
    const float* __restrict pressure = p.pressure.data();
    // Channels: the force's x and y, and its derivative in the sample's velocity (drag).
    const SampleReach reach(p);
    samplePass<3>(
        s, w.size(), nullptr,
        [&](uint32_t k) {
            const float xw = w.px[k], yw = w.py[k], pw = w.pressure[k];
            const float vxw = w.vx[k], vyw = w.vy[k], friction = w.friction[k];
            return [&, xw, yw, pw, vxw, vyw, friction](size_t j, SampleLane<3> a) {
                const auto [dx, dy, invH, q, t, invH4] = reach.at(j, xw, yw);
                const float fp = mass[j] * rho0[j] * (pressure[j] + pw) * invRho[j] * invRho[j] *
                                 kG * invH4 * (t * t * t);
                const float fv = mass[j] * friction * mu[j] * invRho[j] * kL * invH4 * t;
                a[0] += fp * dx - fv * (vxw - vx[j]);
                a[1] += fp * dy - fv * (vyw - vy[j]);
                a[2] += fv;
            };
        },
        [&](uint32_t, uint32_t k, const float(&sum)[3]) {
            w.fx[w.source[k]] += weight * sampleVolume * sum[0];
            w.fy[w.source[k]] += weight * sampleVolume * sum[1];
            w.drag[w.source[k]] += weight * sampleVolume * sum[2];
        });
}

void computeForces(WorldState& s, float sampleVolume, bool surfaceTension) {
    if (surfaceTension) {
        forces<true>(s, sampleVolume);
    } else {
        forces<false>(s, sampleVolume);
    }
}

} // namespace fluid::detail
