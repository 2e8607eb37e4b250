// fluid — the position-based solver [Macklin & Mueller 2013], the default.
//
// The frame driver (frame.cpp) runs its opening ("prepare"), then PositionBasedDef::substeps
// equal sub-steps of dt (more for a frame longer than 1/60 s: fluid::frameSubsteps), each these
// stages, then "finish":
//   external        force plugins' accelerations at the current positions
//   predict         v += dt a_ext, x* = x + dt v (step_common's integrate: non-finite
//                   accelerations zeroed, at most kMaxPredictedMove supports per sub-step);
//                   boundary plugins project x* out of solids, so the constraint starts from
//                   admissible positions
//   sort            counting sort by grid cell of x*; the grid serves every pass below
//   coarse          with PositionBasedDef::coarseCorrection, the large-scale compression
//                   removed on a coarse grid, bodies included (pbf_coarse.cpp)
//   density sweeps  `iterations` Jacobi sweeps of the one-sided density constraint:
//                   multipliers, then the position corrections (s_corr in the first),
//                   Chebyshev-accelerated [Wang 2015]; with PositionBasedDef::shearConstraint
//                   in a yielding world, after each sweep the shear constraint's sweep at the
//                   positions it left (pbf_shear.cpp), its gradients taken at the sweeps'
//                   start
//   velocity        with the shear constraint, the walls' reaction to it and each yielding
//                   particle's stress and structure from the final positions; then
//                   v = (x* - x) / dt, as v + (corrections) / dt
//   viscosity       every PositionBasedDef::viscosityInterval sub-steps, over their time: seed
//                   eq. 2.6 as an explicit velocity update, in as many passes as its stability
//                   asks; vorticity, normals, density and, with the stress pass, the yield
//                   stress at x* on the way
//   surface         then vorticity confinement and surface tension [Akinci 2013] into v; in a
//                   yielding world as a pending change (Particles::kx), to which the stress
//                   pass (without the shear constraint) adds the stress's divergence, rigid
//                   plugs and the walls' grip (yield_law.h)
//   boundaries      boundary plugins project out of solids (safety net)
// Pressure for readers is p = -lambda rho0 / (m dt^2): the multipliers' displacement
// dx = -dt^2 grad p / rho0 read back. Scratch: WorldState::pbfScratch and yieldScratch.
#include "frame.h"
#include "parallel.h"
#include "pbf_loops.h"
#include "pbf_shear.h"
#include "pbf_tuning.h"
#include "sph_loops.h"
#include "step_common.h"

#include <algorithm>
#include <cmath>
#include <iterator>

namespace fluid::detail {
namespace {

using namespace tuning;

template <class F> void each(WorldState& s, F&& f) {
    parallelFor(s.tasks, s.particles.size(), 1024, [&](uint32_t b, uint32_t e, uint32_t) {
        for (uint32_t i = b; i < e; ++i) {
            f(i);
        }
    });
}

void setArtificialPressure(WorldState& s) {
    for (size_t i = 0; i < s.materials.size(); ++i) {
        const Material& m = s.materials[i];
        const float cohesion = m.surfaceTension * m.mass / particleArea(m, s.def.depth);
        s.constants[i].backgroundPressure =
            kArtificial * m.restDensity * cohesion * m.smoothingDistance;
    }
}

// The last pass's correction of particle i, at most kMaxCorrection h long (NaN: none).
inline void correction(const Particles& p, const PositionBasedScratch& x, uint32_t i, float& dx,
                       float& dy) {
    dx = x.dx[i];
    dy = x.dy[i];
    const float limit = kMaxCorrection * p.h[i];
    const float len2 = dx * dx + dy * dy;
    if (!(len2 <= limit * limit)) { // also catches NaN
        const float scale = std::isfinite(len2) ? limit / std::sqrt(len2) : 0.0f;
        dx = std::isfinite(len2) ? dx * scale : 0.0f;
        dy = std::isfinite(len2) ? dy * scale : 0.0f;
    }
}

// The corrections of the last pass (dx, dy), each at most kMaxCorrection h long, added to the
// sub-step's total correction (cx, cy); x* = predicted + total. The total is kept apart from the
// position: far from the origin (16 m) a float position rounds a 1e-6 m correction away, and
// the velocity update would turn that rounding into momentum.
void applyCorrections(WorldState& s) {
    Particles& p = s.particles;
    PositionBasedScratch& x = s.pbfScratch;
    each(s, [&](uint32_t i) {
        float dx = 0.0f, dy = 0.0f;
        correction(p, x, i, dx, dy);
        x.cx[i] += dx;
        x.cy[i] += dy;
        p.px[i] = x.ox[i] + x.cx[i];
        p.py[i] = x.oy[i] + x.cy[i];
    });
}

// The sub-step's solve starts from no correction and no multipliers.
void resetSolve(WorldState& s) {
    PositionBasedScratch& x = s.pbfScratch;
    each(s, [&](uint32_t i) {
        x.lambda[i] = 0.0f;
        x.lambdaTotal[i] = 0.0f;
        x.lambdaPrev[i] = 0.0f;
        x.coarseP[i] = 0.0f;
        x.cx[i] = 0.0f;
        x.cy[i] = 0.0f;
    });
}

// `iterations` Jacobi sweeps of the one-sided density constraint [Macklin & Mueller 2013]:
// each sweep evaluates C and the diagonal D at the current positions, updates the accumulated
// multiplier l_i <- min(l_i - kRelax C_i / D_i, 0) (the constraint pushes, and a later sweep
// may take back a push, never pull), and moves the particles by the displacement of the
// change. Positions are Chebyshev-accelerated between sweeps [Wang 2015]:
// x_k+1 = omega_k+1 (x^_k+1 - x_k-1) + x_k-1. The sweeps start from the coarse correction
// (cx, cy; 0 without one). `push`: the reporting samples take the sweeps' reactions.
void densitySweeps(WorldState& s, const PbfConstants& c, uint32_t iterations, bool push,
                   std::span<const YieldLaw> shearLaws) {
    Particles& p = s.particles;
    PositionBasedScratch& x = s.pbfScratch;
    std::vector<float>& change = x.change;
    std::vector<float>& prevX = x.prevX;
    std::vector<float>& prevY = x.prevY;
    // The multiplier the accelerated positions stand for follows the same recurrence (the
    // displacement is linear in the multipliers): it gives the pressure and the wall forces.
    std::vector<float>& total = x.lambdaTotal;
    std::vector<float>& prevTotal = x.lambdaPrev;
    std::vector<float> relaxation(s.constants.size());
    for (size_t m = 0; m < relaxation.size(); ++m) {
        const float ratio =
            std::min(1.0f, kRelaxNeighbours / std::max(s.constants[m].neighbours, 1.0f));
        relaxation[m] = (iterations == 1 ? kRelaxSingle : kRelax) * ratio * ratio;
    }
    float omega = 1.0f;
    for (uint32_t it = 0; it < iterations; ++it) {
        // C and D at the current positions, and the multipliers' update (their change).
        pbfConstraint(s, c, relaxation.data());
        pbfDisplace(s, c, change, it == 0);
        // The shear constraint after each density sweep, at the positions it left (not
        // accelerated: the Chebyshev recurrence carries its displacement along unchanged).
        const auto shearSweep = [&] {
            if (!s.elastoplastic) {
                return;
            }
            pbfShearSweep(s, c, shearLaws);
            const YieldScratch& y = s.yieldScratch;
            each(s, [&](uint32_t i) {
                x.cx[i] += y.shearDx[i];
                x.cy[i] += y.shearDy[i];
                prevX[i] += y.shearDx[i];
                prevY[i] += y.shearDy[i];
                p.px[i] = x.ox[i] + x.cx[i];
                p.py[i] = x.oy[i] + x.cy[i];
            });
        };
        const float rho2 = kChebyshev * kChebyshev;
        const uint32_t start = iterations >= kChebyshevEarly ? 0 : kChebyshevStart;
        omega = it <= start
                    ? 1.0f
                    : (it == start + 1 ? 2.0f / (2.0f - rho2) : 4.0f / (4.0f - rho2 * omega));
        if (push) {
            pbfSamplePush(s, c, change, omega, it == 0);
        }
        if (it == 0) {
            each(s, [&](uint32_t i) {
                prevX[i] = x.cx[i];
                prevY[i] = x.cy[i];
                total[i] = change[i];
            });
            applyCorrections(s);
            shearSweep();
            continue;
        }
        each(s, [&](uint32_t i) {
            // x^_k+1 = x_k + the corrections, accelerated from x_k-1 (prev).
            float dx = 0.0f, dy = 0.0f;
            correction(p, x, i, dx, dy);
            const float cx = omega * ((x.cx[i] + dx) - prevX[i]) + prevX[i];
            const float cy = omega * ((x.cy[i] + dy) - prevY[i]) + prevY[i];
            prevX[i] = x.cx[i];
            prevY[i] = x.cy[i];
            x.cx[i] = cx;
            x.cy[i] = cy;
            p.px[i] = x.ox[i] + cx;
            p.py[i] = x.oy[i] + cy;
            const float l = omega * (total[i] + change[i] - prevTotal[i]) + prevTotal[i];
            prevTotal[i] = total[i];
            total[i] = l;
        });
        shearSweep();
    }
}

// v = (x* - x) / dt, computed as v + (total correction) / dt: a particle no constraint moved
// keeps its velocity exactly, and no position rounding enters the velocity. Also the pressure the
// multipliers stand for, plus the coarse correction's: its move -share grad psi is the
// displacement -dt^2 grad p / rho0 of the pressure p = rho0 share psi / dt^2.
void updateVelocity(WorldState& s, float dt) {
    Particles& p = s.particles;
    const PositionBasedScratch& x = s.pbfScratch;
    const float invDt = 1.0f / dt;
    each(s, [&](uint32_t i) {
        p.vx[i] += x.cx[i] * invDt;
        p.vy[i] += x.cy[i] * invDt;
        p.pressure[i] = -x.lambdaTotal[i] * p.restDensity[i] * p.invMass[i] * invDt * invDt +
                        x.coarseP[i] * p.restDensity[i] * invDt * invDt;
    });
}

// Adds the pending velocity changes (Particles::kx, ky) and clears them.
void applyPendingKicks(WorldState& s) {
    Particles& p = s.particles;
    each(s, [&](uint32_t i) {
        p.vx[i] += p.kx[i];
        p.vy[i] += p.ky[i];
        p.kx[i] = 0.0f;
        p.ky[i] = 0.0f;
    });
}

// Whether this step is a yielding one (some particle of a yielding material): then its
// channels are sized; else the last yielding step's pending changes go in first.
void beginYielding(WorldState& s) {
    Particles& p = s.particles;
    const uint32_t n = p.size();
    if (s.yielding) {
        // Only particles of a yielding material make this a yielding step.
        const std::vector<MaterialConstants>& mc = s.constants;
        s.yielding = std::any_of(p.material.begin(), p.material.end(),
                                 [&](uint16_t m) { return mc[m].yielding; });
    }
    s.elastoplastic = s.yielding && s.def.positionBased.shearConstraint != 0;
    if (s.yielding) {
        YieldScratch& y = s.yieldScratch;
        for (auto* channel : {&y.tx, &y.ty, &y.rigidity, &y.wallNx, &y.wallNy, &y.wallAdhesion}) {
            channel->resize(n);
        }
    } else if (s.kicksPending) {
        // The last yielding step's changes go in before this Newtonian one.
        applyPendingKicks(s);
        s.kicksPending = false;
    }
}

// The sweeps' constants for sub-steps of dt.
PbfConstants pbfConstants(const WorldState& s, const SceneFacts& facts, float dt) {
    PbfConstants c;
    c.dt = dt;
    c.sampleVolume = facts.sampleSpacing * facts.sampleSpacing;
    c.artificial = 2.0f * s.def.depth * dt * dt;
    const float tq = 1.0f - kDeltaQ;
    c.invWdq = 1.0f / ((tq * tq) * (tq * tq) * (1.0f + 4.0f * kDeltaQ));
    // The denominator's regulariser: 1e-6 of a full neighbourhood's w |grad C|^2, about
    // 40 / (m h^2) for the heaviest particle with the largest support; only an isolated
    // particle comes near it.
    float heaviest = 0.0f;
    for (size_t m = 0; m < s.materials.size(); ++m) {
        heaviest = s.isPresent(m) ? std::max(heaviest, s.materials[m].mass) : heaviest;
    }
    c.epsilon = 1e-6f * 40.0f / (heaviest * facts.maxSupport * facts.maxSupport);
    c.floorShare = kDiagonalFloor;
    return c;
}

// The position-based solver's frame: equal sub-steps, each a prediction, the density solve,
// the velocity update and, every `viscosityInterval` sub-steps, viscosity and the surface pass.
class PositionBasedSolver final : public Solver {
public:
    explicit PositionBasedSolver(WorldState& s) : m_s(s), m_p(s.particles) {}

    std::span<const char* const> stageNames() const override { return kStageNames; }

    FramePlan plan(const SceneFacts& facts, float frameDt) override {
        WorldState& s = m_s;
        Particles& p = m_p;
        PositionBasedScratch& x = s.pbfScratch;
        for (auto* channel : {&x.extX,    &x.extY,        &x.startX,     &x.startY,  &x.ox,
                              &x.oy,      &x.constraint,  &x.diagonal,   &x.lambda,  &x.change,
                              &x.dx,      &x.dy,          &x.cx,         &x.cy,      &x.prevX,
                              &x.prevY,   &x.lambdaTotal, &x.lambdaPrev, &x.coarseP, &x.vorticity,
                              &x.normalX, &x.normalY,     &x.nextVx,     &x.nextVy,  &p.invRho}) {
            channel->resize(p.size());
        }
        const PositionBasedDef& settings = s.def.positionBased;
        m_facts = facts;
        m_frameDt = frameDt;
        setArtificialPressure(s);
        m_moving = samplesMove(s);
        beginYielding(s);
        FramePlan plan;
        // World::step planned the whole sub-steps of fixed length the frame is due.
        plan.count = s.plannedSubsteps > 0 ? s.plannedSubsteps
                                           : fluid::frameSubsteps(settings.substeps, frameDt);
        s.plannedSubsteps = 0;
        plan.dt = frameDt / float(plan.count);
        m_c = pbfConstants(s, facts, plan.dt);
        m_shearLaws = s.elastoplastic ? shearLaws(s, plan.dt) : std::vector<YieldLaw>{};
        // Viscosity, vorticity and surface tension run every `interval` sub-steps, each time
        // over the time since the last run (the frame's last sub-step closes a shorter run).
        m_interval = std::min(settings.viscosityInterval, plan.count);
        m_viscosityFactor = plan.dt * float(m_interval) * facts.maxNu *
                            std::max(1.0f, facts.maxFriction) * (40.0f / 3.0f) /
                            (facts.minSupport * facts.minSupport);
        m_speedCap = kMaxPredictedMove * facts.minSupport / plan.dt;
        // A run is split by viscosity where one pass holds some present material and not
        // another (water beside yoghurt): the low-viscosity pairs take their whole run in the
        // first pass (pbfViscosity's `split`). Not with the stress pass, whose first pass reads
        // the velocity gradient of every particle, nor where boundaries take the fluid's forces
        // (their friction's reaction is read pass by pass).
        m_highViscosity.assign(s.materials.size(), 0);
        bool low = false, high = false;
        for (size_t m = 0; m < s.materials.size(); ++m) {
            if (!s.isPresent(m) || !(facts.maxNu > 0.0f)) {
                continue;
            }
            const float nu = s.materials[m].viscosity / s.materials[m].restDensity;
            const bool more = m_viscosityFactor * (nu / facts.maxNu) > kViscosityFactor;
            m_highViscosity[m] = more ? 1 : 0;
            (more ? high : low) = true;
        }
        m_split = low && high && !facts.wantsForces && !s.stressPass();
        // The coarse correction's share per sub-step: the setting, but at most kCoarseFrame
        // over a frame's sub-steps together.
        m_coarse.share =
            std::min(settings.coarseCorrection,
                     1.0f - std::pow(1.0f - kCoarseFrame, 1.0f / float(plan.count)));
        m_coarse.cellSize = kCoarseCell * facts.minSupport;
        m_coarse.tolerance = kCoarseTolerance;
        m_coarse.maxIterations = kCoarseIterations;
        return plan;
    }

    void substep(Stages& stages, FramePlan&, const Substep& sub) override {
        WorldState& s = m_s;
        PositionBasedScratch& x = s.pbfScratch;
        const float dt = m_c.dt;
        stages.run(kExternal,
                   [&] { externalForces(s, dt, s.time + double(sub.begin), x.extX, x.extY); });
        stages.run(kPredict, [&] { predict(sub); });
        const auto sort = [&](const TaskHook& tasks) {
            if (s.elastoplastic) {
                // The shear constraint measures the displacement from the sub-step's start.
                sortParticles(s, m_facts.maxSupport, {&x.ox, &x.oy, &x.startX, &x.startY},
                              tasks);
            } else {
                sortParticles(s, m_facts.maxSupport, {&x.ox, &x.oy}, tasks);
            }
            s.profile.separated += separateStacked(s, m_facts.maxSupport, &x.ox, &x.oy, tasks);
            fillMaterialChannels(s, tasks);
        };
        bool filled = false;
        stages.run(kSort, [&] {
            // The samples do not depend on the particles' order: placed first, the coarse fill
            // reads them, and the coarse solve (one thread; it touches only the coarse grid and
            // the bodies) runs beside the sort, whose loops then run on the same thread (a task
            // cannot hand out tasks). One worker runs the sort, then the solve.
            placeSamples(s, sub.end, m_facts.maxSupport, m_moving || m_corrected || sub.index == 0);
            m_coarse.startTime = sub.begin;
            m_coarse.endTime = sub.end;
            filled = m_coarse.share > 0.0f && pbfCoarseFill(s, m_c, m_coarse);
            if (!filled) {
                sort(s.tasks);
                return;
            }
            const TaskHook inlineTasks{};
            parallelFor(s.tasks, 2, 1, [&](uint32_t begin, uint32_t end, uint32_t) {
                for (uint32_t item = begin; item < end; ++item) {
                    if (item == 0) {
                        sort(inlineTasks);
                    } else {
                        pbfCoarseSolve(s, m_coarse);
                    }
                }
            });
        });
        stages.run(kCoarse, [&] {
            resetSolve(s);
            // The fill saw the particles in their order before the sort.
            // Bodies it moved are placed again at once, and in every sub-step after this one.
            if (filled && pbfCoarseMove(s, m_coarse, s.grid.order())) {
                placeSamples(s, m_coarse.endTime, m_facts.maxSupport, true);
                m_corrected = true;
            }
        });
        stages.run(kSweeps, [&] {
            if (s.elastoplastic) {
                pbfShearPrepare(s, m_c);
            }
            densitySweeps(s, m_c, s.def.positionBased.iterations, m_facts.wantsForces,
                          m_shearLaws);
        });
        stages.run(kVelocity, [&] {
            if (s.elastoplastic) {
                if (m_facts.wantsForces) {
                    pbfShearSamples(s, m_c, dt / m_frameDt);
                }
                pbfShearFinish(s, m_c, m_shearLaws);
            }
            updateVelocity(s, dt);
            // Each force on a reporting sample is the reaction to what the solver did to the
            // particles, with the positions and velocities it did it with: the fluid's momentum
            // change is the bodies' (up to the correction limit, kMaxCorrection).
            if (m_facts.wantsForces) {
                pbfDeliverPush(s, dt / m_frameDt);
            }
        });
        if ((sub.index + 1) % m_interval == 0 || sub.last) {
            // This run covers `span` sub-steps: the interval, or what the frame has left.
            const uint32_t span = sub.index + 1 - (sub.index / m_interval) * m_interval;
            PbfConstants spanned = m_c;
            spanned.dt = m_c.dt * float(span);
            const std::vector<YieldLaw> laws = yieldLaws(s, spanned.dt);
            stages.run(kViscosity, [&] { viscosity(spanned, span, laws); });
            stages.run(kSurface, [&] { surface(spanned, laws); });
        }
        stages.run(kBoundaries, [&] {
            projectBoundaries(s, dt, sub.end, sub.end, m_facts.sampleSpacing, x.ox, x.oy);
        });
    }

    void close(Profile& profile) override {
        m_s.kicksPending = m_s.yielding;
        profile.iterations = m_s.def.positionBased.iterations;
    }

private:
    enum Stage : uint32_t { kExternal, kPredict, kSort, kCoarse, kSweeps, kVelocity, kViscosity,
                            kSurface, kBoundaries };
    static constexpr const char* kStageNames[] = {
        "external",       "predict",  "sort",      "coarse",  "density sweeps",
        "velocity",       "viscosity", "surface", "boundaries"};
    static_assert(std::size(kStageNames) == kBoundaries + 1, "a name for every stage");

    // v += dt a_ext (and the last surface pass's pending change), x* = x + dt v, projected out
    // of solids: the admissible prediction (ox, oy) that the velocity update measures from.
    void predict(const Substep& sub) {
        WorldState& s = m_s;
        Particles& p = m_p;
        PositionBasedScratch& x = s.pbfScratch;
        if (s.yielding) {
            applyPendingKicks(s);
        }
        if (s.interpolate && (s.interpolateSteps ? sub.index == 0 : sub.last)) {
            // Interpolation (groups.h): where the particles start the frame's last sub-step
            // (Interpolation::Step: its first); the sorts from here to the frame's end carry
            // them along.
            std::copy(p.px.begin(), p.px.end(), p.lastX.begin());
            std::copy(p.py.begin(), p.py.end(), p.lastY.begin());
            s.permuteLast = true;
        }
        const IntegrateStats st =
            integrate(s, x.extX, x.extY, m_c.dt, m_speedCap, x.startX, x.startY);
        s.profile.nonFiniteRepaired += st.repaired;
        s.profile.speedClamped += st.clamped;
        projectBoundaries(s, m_c.dt, sub.begin, sub.end, m_facts.sampleSpacing, x.startX,
                          x.startY);
        each(s, [&](uint32_t i) {
            x.ox[i] = p.px[i];
            x.oy[i] = p.py[i];
        });
    }

    // Viscosity over `span` sub-steps (spanned.dt), in as many passes as its stability asks,
    // with the samples' friction.
    void viscosity(const PbfConstants& spanned, uint32_t span, std::span<const YieldLaw> laws) {
        WorldState& s = m_s;
        Particles& p = m_p;
        // Passes enough that each is stable (at most kViscosityFactor), up to
        // kMaxViscosityPasses; beyond them each pass stays at the limit, so a viscosity higher
        // than the run can hold acts as the highest it holds instead of blowing up.
        const float needed = m_viscosityFactor * float(span) / float(m_interval) / kViscosityFactor;
        const auto passes = static_cast<uint32_t>(
            std::clamp(std::ceil(needed), 1.0f, float(kMaxViscosityPasses)));
        const float weight = spanned.dt / m_frameDt;
        const float passScale = 1.0f / std::max(float(passes), needed);
        const float vorticity = s.def.positionBased.vorticity;
        const bool split = m_split && passes > 1;
        if (split) {
            PositionBasedScratch& x = s.pbfScratch;
            x.viscousTag.resize(p.size());
            x.viscousFlag.resize(p.size());
            each(s, [&](uint32_t i) {
                x.viscousTag[i] = m_highViscosity[p.material[i]] != 0 ? 1.0f : 0.0f;
            });
        }
        for (uint32_t pass = 0; pass < passes; ++pass) {
            if (m_facts.wantsForces) {
                pbfSampleFriction(s, spanned, passScale, weight);
            }
            pbfViscosity(s, spanned, passScale, pass == 0, vorticity > 0.0f, laws,
                         split ? (pass == 0 ? 1 : 2) : 0, 1.0f / passScale);
            p.vx.swap(s.pbfScratch.nextVx);
            p.vy.swap(s.pbfScratch.nextVy);
        }
    }

    // Vorticity confinement, surface tension and the yield stress over spanned.dt, with the
    // walls' reaction to the stress.
    void surface(const PbfConstants& spanned, std::span<const YieldLaw> laws) {
        WorldState& s = m_s;
        // The confinement feeds the spin it reads: over a run longer than kVorticityRun it gives
        // back proportionally less, so what it adds per second stays bounded.
        const float vorticity = s.def.positionBased.vorticity *
                                std::min(1.0f, kVorticityRun / std::max(spanned.dt, 1e-30f));
        pbfSurface(s, spanned, vorticity, m_facts.surfaceTension);
        if (s.stressPass()) {
            pbfStress(s, spanned, laws);
        }
        if (m_facts.wantsForces && s.stressPass()) {
            pbfSampleStress(s, spanned, spanned.dt / m_frameDt);
        }
    }

    WorldState& m_s;
    Particles& m_p;
    SceneFacts m_facts;
    PbfConstants m_c;
    CoarseSettings m_coarse;
    std::vector<YieldLaw> m_shearLaws;
    float m_frameDt = 0.0f;
    uint32_t m_interval = 1;
    float m_viscosityFactor = 0.0f;
    std::vector<uint8_t> m_highViscosity; // per material: needs more than one pass per run
    bool m_split = false;                 // runs split by viscosity (pbfViscosity's `split`)
    float m_speedCap = 0.0f;
    bool m_moving = false;
    // Some rigid body was moved by the coarse solve in this frame: its samples are placed
    // again every sub-step from then on.
    bool m_corrected = false;
};

} // namespace

void stepPositionBased(WorldState& s, float frameDt) {
    PositionBasedSolver solver(s);
    runFrame(s, frameDt, solver);
}

} // namespace fluid::detail
