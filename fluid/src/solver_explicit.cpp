// fluid — the explicit solver: the seed's SPH loop, sub-stepped by a CFL condition.
//
// The frame driver (frame.cpp) runs its opening ("prepare"), then the plan (scene sound speed,
// CFL sub-steps) and, per sub-step, these stages (seed section 2.3, in order), then "finish":
//   sort        counting sort by grid cell; every channel follows (grid.cpp)
//   external    force plugins' accelerations (seed step 5, computed first: the boundary
//               pressure extrapolation needs them)
//   probe       the first frame's first sub-step only: the field measured, the frame replanned
//   density     rho_i = ((m_i/depth) sum_j W_ij + boundary samples) / L      (seed eq. 2.3; L the
//               kernel sum of the material's resting square lattice, 1.0042 for water)
//   pressure    p_i = k (rho_i - rho0) or Tait; boundary pressure [Adami 2012] (seed eq. 2.4)
//   forces      symmetric pressure force (2.5), viscosity (2.6), surface tension [Akinci 2013]
//   integrate   v += dt a, x += dt v: symplectic Euler                        (seed eq. 2.8, 2.9)
//   boundaries  boundary plugins keep particles out of solids (safety net)
// Its scratch channels are WorldState::explicitScratch.
#include "frame.h"
#include "parallel.h"
#include "sph_loops.h"
#include "step_common.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>

namespace fluid::detail {
namespace {

// Explicit viscous diffusion holds dt <= kViscousStep h^2 / nu: the 2D viscosity Laplacian's
// largest eigenvalue is about 27/h^2, so forward Euler is stable with margin.
constexpr float kViscousStep = 0.06f;

// Background pressure of the Tait equation of state in fluid-fluid pairs, p_b = min(kBackground
// rho0 a_gamma h, kBackgroundStiff rho0 c^2): it keeps the particles of a splash apart without
// pushing the free surface out or inflating a soft blob (docs/solver.md, "Background pressure").
constexpr float kBackground = 0.1f;
constexpr float kBackgroundStiff = 2e-4f;

// Everything one sub-step reads that does not change inside it.
struct SubstepConstants {
    const MaterialConstants* mat = nullptr;
    float sampleVolume = 0; // V_w = spacing^2 (m^2)
    bool tait = true;
    bool surfaceTension = false;
};

// ---- prepare -------------------------------------------------------------------------------

// The equation of state's per-material constants for sound speed c.
void setEquationOfState(WorldState& s, float soundSpeed) {
    for (size_t i = 0; i < s.materials.size(); ++i) {
        const Material& mat = s.materials[i];
        MaterialConstants& c = s.constants[i];
        c.taitB = mat.restDensity * soundSpeed * soundSpeed / 7.0f;
        const float cohesion = mat.surfaceTension * mat.mass / particleArea(mat, s.def.depth);
        c.backgroundPressure =
            std::min(kBackground * mat.restDensity * cohesion * mat.smoothingDistance,
                     kBackgroundStiff * mat.restDensity * soundSpeed * soundSpeed);
    }
}

// The external field the fluid sits in, measured from a sub-step's plugin accelerations: the
// largest acceleration g times the fluid's extent H along the mean acceleration (or the
// diagonal of its bounding box when the accelerations point many ways, as around a planetoid).
// Called after the external stage of each step's last sub-step; the next step's sound speed
// uses it, so plugins' apply runs exactly once per sub-step.
void measureField(WorldState& s) {
    const Particles& p = s.particles;
    const ExplicitScratch& x = s.explicitScratch;
    if (p.size() == 0) {
        s.fieldGH = 0.0f;
        return;
    }
    struct Acc {
        double sx = 0, sy = 0, sabs = 0;
        float gmax = 0;
        float x0 = std::numeric_limits<float>::max(), y0 = std::numeric_limits<float>::max();
        float x1 = std::numeric_limits<float>::lowest(), y1 = std::numeric_limits<float>::lowest();
    };
    const Acc acc = blockReduce<Acc>(
        s.tasks, p.size(), Acc{},
        [&](uint32_t b, uint32_t e) {
            Acc a;
            for (uint32_t i = b; i < e; ++i) {
                const float g = std::sqrt(x.ex[i] * x.ex[i] + x.ey[i] * x.ey[i]);
                a.sx += x.ex[i];
                a.sy += x.ey[i];
                a.sabs += g;
                a.gmax = std::max(a.gmax, g);
                a.x0 = std::min(a.x0, p.px[i]);
                a.x1 = std::max(a.x1, p.px[i]);
                a.y0 = std::min(a.y0, p.py[i]);
                a.y1 = std::max(a.y1, p.py[i]);
            }
            return a;
        },
        [](Acc a, const Acc& b) {
            a.sx += b.sx;
            a.sy += b.sy;
            a.sabs += b.sabs;
            a.gmax = std::max(a.gmax, b.gmax);
            a.x0 = std::min(a.x0, b.x0);
            a.x1 = std::max(a.x1, b.x1);
            a.y0 = std::min(a.y0, b.y0);
            a.y1 = std::max(a.y1, b.y1);
            return a;
        });
    double height = std::hypot(double(acc.x1) - acc.x0, double(acc.y1) - acc.y0);
    const double mean = std::hypot(acc.sx, acc.sy);
    if (acc.sabs > 0.0 && mean >= 0.5 * acc.sabs) {
        const float dx = float(acc.sx / mean);
        const float dy = float(acc.sy / mean);
        struct Range {
            float lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
        };
        const Range r = blockReduce<Range>(
            s.tasks, p.size(), Range{},
            [&](uint32_t b, uint32_t e) {
                Range q;
                for (uint32_t i = b; i < e; ++i) {
                    const float d = dx * p.px[i] + dy * p.py[i];
                    q.lo = std::min(q.lo, d);
                    q.hi = std::max(q.hi, d);
                }
                return q;
            },
            [](Range a, const Range& b) {
                return Range{std::min(a.lo, b.lo), std::max(a.hi, b.hi)};
            });
        height = double(r.hi) - r.lo;
    }
    s.fieldGH = float(acc.gmax * height);
}

// The scene's Tait sound speed, the largest of
//   sqrt(k_max)            the seed's stiffness (all there is in zero gravity without cohesion),
//   10 sqrt(g H)           ten times the fastest free-surface wave of a column of height H in
//                          the field measured last step: density then varies by about 1%,
//   10 sqrt(a_gamma h)     the same for the surface layer that cohesion squeezes, with
//                          a_gamma = gamma m / A the cohesion acceleration scale of a material
//                          [Akinci 2013] and h its support: a resting zero-g blob then reads its
//                          rest density within 1% instead of about 2% at sqrt(k),
// never decreasing over the world's life (a dam-break column collapses, its speed does not).
float sceneSoundSpeed(WorldState& s) {
    float c = 10.0f * std::sqrt(s.fieldGH);
    for (const Material& m : s.materials) {
        c = std::max(c, std::sqrt(m.stiffness));
        const float cohesion = m.surfaceTension * m.mass / particleArea(m, s.def.depth);
        c = std::max(c, 10.0f * std::sqrt(cohesion * m.smoothingDistance));
    }
    s.soundSpeed = std::max(s.soundSpeed, c);
    return s.soundSpeed;
}

// ---- sub-step stages ---------------------------------------------------------------------

// Seed eq. 2.4 (or Tait), then each boundary sample's pressure extrapolated from the fluid
// around it, hydrostatic term included [Adami 2012, eq. 27]: walls push back as hard as the
// fluid presses, with no pressure mirroring (which pumps energy into a resting tank).
void computePressure(WorldState& s, const SubstepConstants& c) {
    Particles& p = s.particles;
    ExplicitScratch& x = s.explicitScratch;
    parallelFor(s.tasks, p.size(), 1024, [&](uint32_t b, uint32_t e, uint32_t) {
        for (uint32_t i = b; i < e; ++i) {
            const MaterialConstants& mc = c.mat[p.material[i]];
            if (c.tait) {
                const float ratio = p.density[i] / mc.restDensity;
                const float r2 = ratio * ratio;
                const float r7 = r2 * r2 * r2 * ratio;
                p.pressure[i] = std::max(0.0f, mc.taitB * (r7 - 1.0f));
            } else {
                p.pressure[i] = mc.stiffness * (p.density[i] - mc.restDensity);
            }
            p.invRho[i] = 1.0f / p.density[i];
            // The pair term's pressure carries the background pressure (fluid-fluid pairs only:
            // walls and readers see the equation of state's pressure).
            const float pair = p.pressure[i] + (c.tait ? mc.backgroundPressure : 0.0f);
            x.pOverRho2[i] = pair * p.invRho[i] * p.invRho[i];
        }
    });
    computeSamplePressure(s);
}

// The explicit solver's frame: its plan (sound speed, CFL sub-steps) and its sub-step.
class ExplicitSolver final : public Solver {
public:
    explicit ExplicitSolver(WorldState& s) : m_s(s), m_p(s.particles) {}

    std::span<const char* const> stageNames() const override { return kStageNames; }

    FramePlan plan(const SceneFacts& facts, float frameDt) override {
        WorldState& s = m_s;
        Particles& p = m_p;
        ExplicitScratch& x = s.explicitScratch;
        for (auto* channel :
             {&x.ax, &x.ay, &x.ex, &x.ey, &x.nx, &x.ny, &x.pOverRho2, &p.invRho}) {
            channel->resize(p.size());
        }
        m_facts = facts;
        m_frameDt = frameDt;
        m_tait = s.def.equationOfState == EquationOfState::Tait;
        const bool derived = m_tait && s.def.soundSpeed <= 0.0f;
        if (m_tait) {
            m_soundSpeed = derived ? sceneSoundSpeed(s) : s.def.soundSpeed;
        }
        setEquationOfState(s, m_soundSpeed);
        m_maxSpeed = maxSpeed();
        m_c.mat = s.constants.data();
        m_c.sampleVolume = facts.sampleSpacing * facts.sampleSpacing;
        m_c.tait = m_tait;
        m_c.surfaceTension = facts.surfaceTension;
        m_moving = samplesMove(s);

        // A world whose sound speed is derived but whose external field was never measured (its
        // first step with particles) starts with one short probe sub-step at the CFL limit of
        // the largest sound speed the sub-step cap allows; its external stage measures the
        // field, and the rest of the frame is planned with the sound speed that field asks for
        // (the probe stage). So the first frame is as stiff as the others, and plugins still
        // see one apply per sub-step.
        m_probe = derived && !s.fieldMeasured && p.size() > 0 && s.def.maxSubsteps >= 2;
        m_cflDt = cflDt();
        FramePlan plan;
        plan.lastTakesRest = true;
        plan.count = substepsFor(frameDt, m_cflDt, s.def.maxSubsteps);
        plan.dt = frameDt / float(plan.count);
        if (m_probe) {
            plan.dt = std::min(plan.dt, frameDt / float(s.def.maxSubsteps));
            plan.count = s.def.maxSubsteps; // provisional, replanned by the probe stage
        } else {
            holdToSubsteps(plan.dt);
        }
        return plan;
    }

    // Seed section 2.3, in order.
    void substep(Stages& stages, FramePlan& plan, const Substep& sub) override {
        WorldState& s = m_s;
        ExplicitScratch& x = s.explicitScratch;
        const float h = sub.dt;
        stages.run(kSort, [&] {
            sortParticles(s, m_facts.maxSupport);
            s.profile.separated += separateStacked(s, m_facts.maxSupport);
            fillMaterialChannels(s);
            placeSamples(s, sub.begin, m_facts.maxSupport, m_moving || sub.index == 0);
        });
        stages.run(kExternal, [&] {
            externalForces(s, h, s.time + sub.elapsed, x.ex, x.ey);
            if (sub.last) {
                measureField(s);
                s.fieldMeasured = true;
            }
        });
        if (m_probe && sub.index == 0) {
            stages.run(kProbe, [&] { replan(plan, h); });
        }
        stages.run(kDensity, [&] { computeDensity(s, m_c.sampleVolume); });
        stages.run(kPressure, [&] {
            computePressure(s, m_c);
            if (m_c.surfaceTension) {
                computeNormals(s);
            }
        });
        stages.run(kForces, [&] {
            computeForces(s, m_c.sampleVolume, m_c.surfaceTension);
            if (m_facts.wantsForces) {
                computeSampleForces(s, m_c.sampleVolume, h / m_frameDt);
            }
        });
        stages.run(kIntegrate, [&] {
            // The speed cap: half a support radius per sub-step.
            const IntegrateStats st =
                integrate(s, x.ax, x.ay, h, 0.5f * m_facts.minSupport / h, x.qx, x.qy);
            s.profile.speedClamped += st.clamped;
            s.profile.nonFiniteRepaired += st.repaired;
            s.lastMaxAccel = std::sqrt(st.maxAccel2);
        });
        stages.run(kBoundaries, [&] {
            projectBoundaries(s, h, sub.begin, sub.end, m_facts.sampleSpacing, x.qx, x.qy);
        });
    }

    void close(Profile& profile) override {
        profile.cflDt = m_cflDt;
        profile.soundSpeed = m_soundSpeed;
    }

private:
    enum Stage : uint32_t { kSort, kExternal, kProbe, kDensity, kPressure, kForces, kIntegrate,
                            kBoundaries };
    static constexpr const char* kStageNames[] = {"sort",     "external", "probe",
                                                  "density",  "pressure", "forces",
                                                  "integrate", "boundaries"};
    static_assert(std::size(kStageNames) == kBoundaries + 1, "a name for every stage");

    // The probe sub-step's field measured: the frame's sound speed, and the rest of the frame
    // planned with it (after this sub-step of h seconds).
    void replan(FramePlan& plan, float h) {
        measureField(m_s);
        m_s.fieldMeasured = true;
        m_soundSpeed = sceneSoundSpeed(m_s);
        setEquationOfState(m_s, m_soundSpeed);
        m_cflDt = cflDt();
        plan.count = 1 + substepsFor(m_frameDt - h, m_cflDt, m_s.def.maxSubsteps - 1);
        plan.respread = true;
        holdToSubsteps((m_frameDt - h) / float(plan.count - 1));
    }

    // A frame whose sub-steps of `dt` are longer than the sound speed or the viscosity allow
    // (the CFL limit asked for more than maxSubsteps): it steps with the largest sound speed
    // (Tait), stiffness (linear) and viscosity those sub-steps hold, so a value beyond what
    // maxSubsteps allows makes the liquid softer or thinner for the frame, never unstable
    // (docs/solver.md, Sub-steps).
    // Profile::soundSpeed reports the speed used. The materials are untouched: the constants
    // are refreshed from them every frame.
    void holdToSubsteps(float dt) {
        const SceneFacts& f = m_facts;
        const float wave = m_s.def.courant * f.minSpacing / dt;
        const float speed = std::max(wave - m_maxSpeed, 0.5f * wave);
        if (m_tait) {
            if (m_soundSpeed > speed) {
                m_soundSpeed = speed;
                setEquationOfState(m_s, speed);
            }
        } else {
            for (MaterialConstants& c : m_s.constants) {
                c.stiffness = std::min(c.stiffness, speed * speed);
            }
        }
        const float nu = kViscousStep * f.minSupport * f.minSupport /
                         (dt * std::max(1.0f, f.maxFriction));
        for (MaterialConstants& c : m_s.constants) {
            c.viscosity = std::min(c.viscosity, nu * c.restDensity);
        }
    }

    // Equal sub-steps of at most dt over `span` seconds, at most `cap` of them.
    static uint32_t substepsFor(float span, float dt, uint32_t cap) {
        const auto wanted = static_cast<uint32_t>(std::min(1e6, std::ceil(double(span) / dt)));
        return std::clamp(wanted, 1u, cap);
    }

    // The largest particle speed at the frame's start (m/s).
    float maxSpeed() const {
        const Particles& p = m_p;
        return std::sqrt(blockReduce<float>(
            m_s.tasks, p.size(), 0.0f,
            [&](uint32_t b, uint32_t e) {
                float v2 = 0.0f;
                for (uint32_t i = b; i < e; ++i) {
                    v2 = std::max(v2, p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i]);
                }
                return v2;
            },
            [](float a, float b) { return std::max(a, b); }));
    }

    // CFL: sound and flow speed [Monaghan 1992], acceleration, and explicit viscous diffusion
    // (the 2D viscosity Laplacian's largest eigenvalue is about 27/h^2, so 0.06 h^2/nu keeps
    // forward Euler stable with margin); wall friction adds to the viscosity.
    float cflDt() const {
        const SceneFacts& f = m_facts;
        const float speed = m_tait ? m_soundSpeed : std::sqrt(f.maxK);
        float dt = m_s.def.courant * f.minSpacing / (speed + m_maxSpeed);
        if (m_s.lastMaxAccel > 0.0f) {
            dt = std::min(dt, 0.25f * std::sqrt(f.minSupport / m_s.lastMaxAccel));
        }
        if (f.maxNu > 0.0f) {
            dt = std::min(dt, kViscousStep * f.minSupport * f.minSupport /
                                  (f.maxNu * std::max(1.0f, f.maxFriction)));
        }
        return dt;
    }

    WorldState& m_s;
    Particles& m_p;
    SceneFacts m_facts;
    SubstepConstants m_c;
    float m_frameDt = 0.0f;
    bool m_tait = true;
    float m_soundSpeed = 0.0f;
    float m_maxSpeed = 0.0f;
    float m_cflDt = 0.0f;
    bool m_moving = false;
    bool m_probe = false;
};

} // namespace

void stepExplicit(WorldState& s, float frameDt) {
    ExplicitSolver solver(s);
    runFrame(s, frameDt, solver);
}

} // namespace fluid::detail
