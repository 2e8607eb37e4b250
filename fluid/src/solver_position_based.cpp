// fluid — the position-based solver [Macklin & Mueller 2013], the default.
//
// One World::step(frameDt) = PositionBasedDef::substeps equal sub-steps of dt:
//   prepare       plugins' prepare hooks, boundary samples, material constants
//   per sub-step:
//     external    force plugins' accelerations at the current positions
//     predict     v += dt a_ext, x* = x + dt v (non-finite accelerations zeroed);
//                 boundary plugins project x* out of solids
//     sort        counting sort by grid cell of x*; the grid serves every pass below
//     warm start  x* moved by last sub-step's multipliers (the pressure a resting tank needs)
//     iterations  density constraint: multipliers (density pass), then corrections (pressure
//                 pass, with the s_corr artificial pressure in the first)
//     velocity    v = (x* - x) / dt
//     viscosity   seed eq. 2.6 as an explicit velocity update, split into as many passes as
//                 its stability asks; vorticity, normals and density at x* on the way
//     surface     vorticity confinement and surface tension [Akinci 2013] into v
//     boundaries  boundary plugins project out of solids (safety net)
// Pressure for readers is p = -lambda rho0 / (m dt^2): the multiplier's displacement
// dx = -dt^2 grad p / rho0 read back.
#include "parallel.h"
#include "pbf_loops.h"
#include "sph_loops.h"
#include "step_common.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstdio>

namespace fluid::detail {
namespace {

// The artificial pressure s_corr stands for, as a share of the cohesion's pressure scale
// rho0 a_gamma h (a_gamma = gamma m / A [Akinci 2013]), and the distance where its kernel
// ratio is 1 [Macklin & Mueller 2013 use 0.1-0.3 h].
static float kArtificial = getenv("ART") ? atof(getenv("ART")) : 0.1f;
constexpr float kDeltaQ = 0.2f;
// Share of last sub-step's multiplier that starts the next one.
static float kWarmStart = getenv("WARM") ? atof(getenv("WARM")) : 1.0f;
// Largest viscosity factor dt nu sum_j V_j L_ij per pass (sum ~ 40 / (3 h^2)): below 0.5 the
// explicit update only smooths, never overshoots.
constexpr float kViscosityFactor = 0.5f;
static float kMaxCorrection = getenv("MAXC") ? atof(getenv("MAXC")) : 0.5f;
static bool kJacobi = !getenv("CG");
static float kRho = getenv("RHO") ? atof(getenv("RHO")) : 0.0f;
static bool kLastPlain = getenv("LASTPLAIN");
static float kRelax = getenv("RELAX") ? atof(getenv("RELAX")) : 0.5f;
static float kMirror = getenv("MIRROR") ? atof(getenv("MIRROR")) : 2.0f;
static float kTolerance = getenv("TOL") ? atof(getenv("TOL")) : 1e-3f;

void setArtificialPressure(WorldState& s) {
    for (size_t i = 0; i < s.materials.size(); ++i) {
        const Material& m = s.materials[i];
        const float cohesion = m.surfaceTension * m.mass / particleArea(m, s.def.depth);
        s.constants[i].backgroundPressure = kArtificial * m.restDensity * cohesion * m.smoothingDistance;
    }
}

struct PredictStats {
    uint32_t repaired = 0;
};

// v += dt a_ext, x* = x + dt v; x kept in ox, oy.
PredictStats predict(WorldState& s, float dt) {
    Particles& p = s.particles;
    return blockReduce<PredictStats>(
        s.tasks, p.size(), PredictStats{},
        [&](uint32_t b, uint32_t e) {
            PredictStats st;
            for (uint32_t i = b; i < e; ++i) {
                float ax = p.ex[i], ay = p.ey[i];
                if (!std::isfinite(ax) || !std::isfinite(ay)) {
                    ax = ay = 0.0f;
                    ++st.repaired;
                }
                p.vx[i] += dt * ax;
                p.vy[i] += dt * ay;
                p.ox[i] = p.px[i];
                p.oy[i] = p.py[i];
                p.px[i] += dt * p.vx[i];
                p.py[i] += dt * p.vy[i];
            }
            return st;
        },
        [](PredictStats a, const PredictStats& b) { return PredictStats{a.repaired + b.repaired}; });
}

// x* += (ax, ay), the corrections of the last pass, each at most kMaxCorrection h long.
void applyCorrections(WorldState& s) {
    Particles& p = s.particles;
    parallelFor(s.tasks, p.size(), 1024, [&](uint32_t b, uint32_t e, uint32_t) {
        for (uint32_t i = b; i < e; ++i) {
            float dx = p.ax[i], dy = p.ay[i];
            const float limit = kMaxCorrection * p.h[i];
            const float len2 = dx * dx + dy * dy;
            if (len2 > limit * limit) {
                const float scale = limit / std::sqrt(len2);
                dx *= scale;
                dy *= scale;
            }
            p.px[i] += dx;
            p.py[i] += dy;
        }
    });
}

// v = (x* - x) / dt, and the pressure the multipliers stand for.
void updateVelocity(WorldState& s, float dt) {
    Particles& p = s.particles;
    const float invDt = 1.0f / dt;
    parallelFor(s.tasks, p.size(), 1024, [&](uint32_t b, uint32_t e, uint32_t) {
        for (uint32_t i = b; i < e; ++i) {
            p.vx[i] = (p.px[i] - p.ox[i]) * invDt;
            p.vy[i] = (p.py[i] - p.oy[i]) * invDt;
            p.pressure[i] = -p.lambda[i] * p.restDensity[i] * p.invMass[i] * invDt * invDt;
        }
    });
}

// Jacobi sweeps of the one-sided constraint [Macklin & Mueller 2013]: per sweep the
// constraint, l_i <- min(l_i - relax C_i / D_i, 0), and the displacement of the change.
uint32_t solveJacobi(WorldState& s, const PbfConstants& c, uint32_t iterations) {
    Particles& p = s.particles;
    const uint32_t n = p.size();
    auto each = [&](auto&& f) {
        parallelFor(s.tasks, n, 1024, [&](uint32_t b, uint32_t e, uint32_t) {
            for (uint32_t i = b; i < e; ++i) {
                f(i);
            }
        });
    };
    std::vector<float>& dl = p.cgDirection;
    if (kWarmStart > 0.0f) {
        each([&](uint32_t i) {
            p.lambda[i] = p.constraint[i] > 0.0f ? std::min(kWarmStart * p.lambda[i], 0.0f) : 0.0f;
            dl[i] = p.lambda[i];
        });
        pbfDisplace(s, c, dl, false);
        applyCorrections(s);
    } else {
        each([&](uint32_t i) { p.lambda[i] = 0.0f; });
    }
    std::vector<float>& prevX = p.cgResidual;
    std::vector<float>& prevY = p.cgProduct;
    float omega = 1.0f;
    for (uint32_t it = 0; it < iterations; ++it) {
        if (it > 0 || kWarmStart > 0.0f) {
            pbfConstraint(s, c);
        }
        each([&](uint32_t i) {
            const float updated = std::min(p.lambda[i] - kRelax * p.constraint[i] / p.diagonal[i], 0.0f);
            dl[i] = updated - p.lambda[i];
            p.lambda[i] = updated;
        });
        pbfDisplace(s, c, dl, it == 0);
        // Chebyshev semi-iterative acceleration [Wang 2015]
        omega = it == 0 ? 1.0f : (it == 1 ? 2.0f / (2.0f - kRho * kRho) : 4.0f / (4.0f - kRho * kRho * omega));
        if (it == 0 || kRho == 0.0f || (kLastPlain && it + 1 == iterations)) {
            each([&](uint32_t i) { prevX[i] = p.px[i]; prevY[i] = p.py[i]; });
            applyCorrections(s);
        } else {
            each([&](uint32_t i) { p.nx[i] = p.px[i]; p.ny[i] = p.py[i]; });
            applyCorrections(s);
            each([&](uint32_t i) {
                const float x = omega * (p.px[i] - prevX[i]) + prevX[i];
                const float y = omega * (p.py[i] - prevY[i]) + prevY[i];
                prevX[i] = p.nx[i];
                prevY[i] = p.ny[i];
                p.px[i] = x;
                p.py[i] = y;
            });
        }
    }
    return iterations;
}

// out = A in, A = J W J^T: the displacement of `in` (pbfDisplace, into ax, ay), then J of it.
void multiplyA(WorldState& s, const PbfConstants& c, std::span<const float> in, std::vector<float>& out) {
    pbfDisplace(s, c, in, false);
    pbfJacobianTimes(s, c, out);
}

template <class F>
double sum(WorldState& s, F&& term) {
    return blockReduce<double>(
        s.tasks, s.particles.size(), 0.0,
        [&](uint32_t begin, uint32_t end) {
            double acc = 0.0;
            for (uint32_t i = begin; i < end; ++i) {
                acc += term(i);
            }
            return acc;
        },
        [](double x, double y) { return x + y; });
}

// The density constraint as a bound-constrained quadratic program, linearised at x*:
//   minimise 1/2 l^T A l + l^T C  subject to  l <= 0,
// whose optimality conditions are those of the one-sided constraint: C + A l = 0 where l < 0
// (compressed particles pushed back to rest density), C + A l <= 0 where l = 0 (nothing
// compressed is left, nothing pulls). Solved by conjugate gradients on the free set
// (l_i < 0, or l_i = 0 with gradient g_i > 0), preconditioned with the diagonal; a step that
// leaves the bound is projected and the search restarts [Dostal's MPRGP, without its
// proportioning test]. Warm-started from the last sub-step's multipliers, at most
// `iterations` products with A. Then x* moves by W J^T l (with s_corr). Returns the products.
uint32_t solveConstraint(WorldState& s, const PbfConstants& c, uint32_t iterations) {
    Particles& p = s.particles;
    const uint32_t n = p.size();
    std::vector<float>& lambda = p.lambda;
    std::vector<float>& g = p.cgResidual; // gradient A l + C
    std::vector<float>& d = p.cgDirection;
    std::vector<float>& q = p.cgProduct;
    std::vector<float>& z = p.cgScratch;
    auto each = [&](auto&& f) {
        parallelFor(s.tasks, n, 1024, [&](uint32_t b, uint32_t e, uint32_t) {
            for (uint32_t i = b; i < e; ++i) {
                f(i);
            }
        });
    };
    each([&](uint32_t i) { lambda[i] = std::min(kWarmStart * lambda[i], 0.0f); });
    uint32_t products = 0;
    auto gradient = [&] {
        multiplyA(s, c, lambda, q);
        ++products;
        each([&](uint32_t i) { g[i] = q[i] + p.constraint[i]; });
    };
    gradient();
    // Free set and its preconditioned residual z = -g / D (0 on the bound set).
    auto restart = [&] {
        each([&](uint32_t i) {
            const bool free = lambda[i] < 0.0f || g[i] > 0.0f;
            z[i] = free ? -g[i] / p.diagonal[i] : 0.0f;
            d[i] = z[i];
        });
        return sum(s, [&](uint32_t i) { return -double(g[i]) * z[i]; });
    };
    double rz = restart();
    const double rz0 = rz;
    while (products < iterations && rz > kTolerance * kTolerance * rz0 && rz > 0.0) {
        multiplyA(s, c, d, q);
        ++products;
        const double dq = sum(s, [&](uint32_t i) { return double(d[i]) * q[i]; });
        if (!(dq > 0.0)) {
            break;
        }
        const auto alpha = float(rz / dq);
        // Largest step that keeps l <= 0 (entries moving up toward the bound).
        const float feasible = float(blockReduce<double>(
            s.tasks, n, 1e30,
            [&](uint32_t b, uint32_t e) {
                double m = 1e30;
                for (uint32_t i = b; i < e; ++i) {
                    if (d[i] > 0.0f) {
                        m = std::min(m, double(-lambda[i]) / d[i]);
                    }
                }
                return m;
            },
            [](double x, double y) { return std::min(x, y); }));
        if (alpha <= feasible) {
            each([&](uint32_t i) {
                lambda[i] += alpha * d[i];
                g[i] += alpha * q[i];
                const bool free = lambda[i] < 0.0f || g[i] > 0.0f;
                z[i] = free ? -g[i] / p.diagonal[i] : 0.0f;
            });
            const double rzNew = sum(s, [&](uint32_t i) { return -double(g[i]) * z[i]; });
            const auto beta = float(rzNew / rz);
            rz = rzNew;
            each([&](uint32_t i) { d[i] = z[i] + beta * d[i]; });
        } else {
            // Projected step, then a fresh gradient and search direction.
            each([&](uint32_t i) { lambda[i] = std::min(lambda[i] + alpha * d[i], 0.0f); });
            if (products >= iterations) {
                break;
            }
            gradient();
            rz = restart();
        }
    }
    each([&](uint32_t i) { lambda[i] = std::isfinite(lambda[i]) ? std::min(lambda[i], 0.0f) : 0.0f; });
    if (getenv("DBG")) {
        float cmax = 0, gmax = 0, lmin = 0; uint32_t ic = 0;
        for (uint32_t i = 0; i < n; ++i) { if (p.constraint[i] > cmax) { cmax = p.constraint[i]; ic = i; } gmax = std::max(gmax, g[i]); lmin = std::min(lmin, lambda[i]); }
        fprintf(stderr, "solve: C max %.4f at (%.4f, %.4f), predicted after %.4f, lambda min %.3g, products %u rz %.3g/%.3g\n", cmax, p.px[ic], p.py[ic], gmax, lmin, products, rz, rz0);
    }
    pbfDisplace(s, c, lambda, true);
    applyCorrections(s);
    if (getenv("DBG")) {
        pbfConstraint(s, c);
        float cmax = 0; uint32_t ic = 0;
        for (uint32_t i = 0; i < n; ++i) { if (p.constraint[i] > cmax) { cmax = p.constraint[i]; ic = i; } }
        fprintf(stderr, "   after: C max %.4f at (%.4f, %.4f)\n", cmax, p.px[ic], p.py[ic]);
    }
    return products;
}

} // namespace

void stepPositionBased(WorldState& s, float frameDt) {
    const Clock::time_point start = Clock::now();
    Profile& prof = s.profile;
    prof = Profile{};
    Particles& p = s.particles;
    const uint32_t n = p.size();
    for (auto* channel : {&p.ax, &p.ay, &p.ex, &p.ey, &p.nx, &p.ny, &p.invRho, &p.ox, &p.oy,
                          &p.vorticity, &p.constraint, &p.diagonal, &p.cgResidual, &p.cgDirection,
                          &p.cgProduct, &p.cgScratch}) {
        channel->resize(n);
    }
    const PositionBasedDef& settings = s.def.positionBased;
    const SceneFacts facts = sceneFacts(s);

    // Prepare: plugins, boundary samples, constants.
    const StepContext context{frameDt, s.time, facts.sampleSpacing, facts.maxSupport};
    for (const auto& plugin : s.forces) {
        plugin->prepare(context);
    }
    gatherSamples(s, context);
    refreshConstants(s);
    setArtificialPressure(s);
    const bool moving = samplesMove(s);

    const uint32_t substeps = settings.substeps;
    const float dt = frameDt / float(substeps);
    PbfConstants c;
    c.dt = dt;
    c.sampleVolume = facts.sampleSpacing * facts.sampleSpacing;
    c.artificial = 2.0f * s.def.depth * dt * dt;
    c.wallMirror = kJacobi ? kMirror : 1.0f;
    const float tq = 1.0f - kDeltaQ;
    c.invWdq = 1.0f / ((tq * tq) * (tq * tq) * (1.0f + 4.0f * kDeltaQ));
    // The denominator's regulariser: 1e-6 of a full neighbourhood's |grad C|^2 w, about
    // 40 / (m h^2) for the lightest, smallest material (only an isolated particle comes near it).
    float heaviest = 0.0f;
    for (const Material& m : s.materials) {
        heaviest = std::max(heaviest, m.mass);
    }
    c.epsilon = 1e-6f * 40.0f / (heaviest * facts.maxSupport * facts.maxSupport);
    const float viscosityFactor = dt * facts.maxNu * std::max(1.0f, facts.maxFriction) * (40.0f / 3.0f) /
                                  (facts.minSupport * facts.minSupport);
    const auto viscosityPasses =
        static_cast<uint32_t>(std::clamp(std::ceil(viscosityFactor / kViscosityFactor), 1.0f, 64.0f));

    for (uint32_t sub = 0; sub < substeps; ++sub) {
        const float inStep = float(sub) * dt;
        const float endInStep = sub + 1 == substeps ? frameDt : float(sub + 1) * dt;
        timed(prof.external, [&] { externalForces(s, dt, s.time + double(inStep)); });
        timed(prof.integrate, [&] {
            prof.nonFiniteRepaired += predict(s, dt).repaired;
            projectBoundaries(s, dt, endInStep, facts.sampleSpacing);
        });
        timed(prof.sort, [&] {
            sortParticles(s, facts.maxSupport, {&p.ox, &p.oy, &p.lambda});
            fillMaterialChannels(s);
            placeSamples(s, endInStep, facts.maxSupport, moving || sub == 0);
        });
        timed(prof.density, [&] { pbfConstraint(s, c); });
        timed(prof.pressure, [&] {
            prof.iterations += kJacobi ? solveJacobi(s, c, settings.iterations) : solveConstraint(s, c, settings.iterations);
        });
        timed(prof.integrate, [&] { updateVelocity(s, dt); });
        timed(prof.forces, [&] {
            for (uint32_t pass = 0; pass < viscosityPasses; ++pass) {
                pbfViscosity(s, c, 1.0f / float(viscosityPasses), pass == 0);
                p.vx.swap(p.ax);
                p.vy.swap(p.ay);
            }
            pbfSurface(s, c, settings.vorticity, facts.surfaceTension);
            if (facts.wantsForces) {
                pbfSampleForces(s, c, dt / frameDt);
            }
        });
        timed(prof.boundaries, [&] { projectBoundaries(s, dt, endInStep, facts.sampleSpacing); });
    }
    densityError(s);
    if (facts.wantsForces) {
        deliverSampleForces(s);
    }
    s.time += frameDt;
    prof.substeps = substeps;
    prof.iterations = (prof.iterations + substeps - 1) / substeps;
    prof.particles = n;
    prof.step = std::chrono::duration<float, std::milli>(Clock::now() - start).count();
}

} // namespace fluid::detail
