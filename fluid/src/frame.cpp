// fluid — the frame driver (frame.h).
#include "frame.h"

#include <cassert>

namespace fluid::detail {

Stages::Stages(Profile& profile, std::span<const char* const> solverStages, const StageProbe* probe)
    : m_profile(profile), m_probe(probe) {
    assert(solverStages.size() + 2 <= kMaxProfileStages);
    m_last = uint32_t(solverStages.size()) + 1;
    m_profile.stages[0].name = "prepare";
    for (uint32_t k = 0; k < solverStages.size(); ++k) {
        m_profile.stages[1 + k].name = solverStages[k];
    }
    m_profile.stages[m_last].name = "finish";
    m_profile.stageCount = m_last + 1;
}

void runFrame(WorldState& s, float frameDt, Solver& solver) {
    const Clock::time_point start = Clock::now();
    Profile& prof = s.profile;
    prof = Profile{};
    Stages stages(prof, solver.stageNames(), &s.stageProbe);
    const uint32_t n = s.particles.size();
    s.present = presentMaterials(s);
    SceneFacts facts = sceneFacts(s);
    const StepContext context{frameDt, s.time, facts.sampleSpacing, facts.maxSupport};

    // Opening: plugins, boundary samples, material constants, then the solver's plan.
    FramePlan plan;
    stages.prepare([&] {
        for (const auto& plugin : s.forces) {
            plugin->prepare(context);
        }
        gatherSamples(s, context);
        // Bodies asking for contact events need the forces on their samples.
        facts.wantsForces = facts.wantsForces || !s.contacts.bodies.empty();
        refreshConstants(s);
        plan = solver.plan(facts, frameDt);
    });

    // The sub-steps. Time into the frame is summed in double, so that the last sub-step's
    // rest stays at float precision.
    double elapsed = 0.0;
    float dt = plan.dt;
    for (uint32_t index = 0; index < plan.count; ++index) {
        Substep sub;
        sub.index = index;
        sub.last = index + 1 == plan.count;
        if (sub.last && plan.lastTakesRest) {
            dt = float(double(frameDt) - elapsed); // the frame ends exactly at frameDt
        }
        sub.dt = dt;
        sub.elapsed = elapsed;
        sub.begin = float(elapsed);
        sub.end = sub.last && !plan.lastTakesRest ? frameDt : float(elapsed + double(dt));
        solver.substep(stages, plan, sub);
        contactPass(s); // nothing unless a body asks for contact events
        elapsed += double(dt);
        if (plan.respread) {
            dt = float((double(frameDt) - elapsed) / double(plan.count - index - 1));
            plan.respread = false;
        }
    }

    // Closing: what the step did goes out to the plugins.
    solver.close(prof);
    stages.finish([&] {
        densityError(s);
        deliverBodyImpulses(s, frameDt); // zeros without a coarse solve
        if (facts.wantsForces) {
            deliverSampleForces(s);
        }
        finishContacts(s, frameDt);
        finishPlugins(s, context);
    });
    s.time += frameDt;
    prof.substeps = plan.count;
    prof.particles = n;
    prof.threads = s.threads();
    prof.step = std::chrono::duration<float, std::milli>(Clock::now() - start).count();
}

} // namespace fluid::detail
