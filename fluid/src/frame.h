// fluid — the frame driver: one World::step of either solver (frame.cpp).
//
// The driver owns the frame: the opening both solvers share (plugins' prepare hooks, boundary
// samples, material constants), the sub-step loop and its clock, the closing (density error,
// bodies' impulses and samples' forces delivered, plugins' finish hooks, the world's time) and
// the profile. A solver supplies its plan for the frame and its sub-step, as a list of named
// stages that the driver times: solver_explicit.cpp and solver_position_based.cpp.
#pragma once

#include "step_common.h"

#include <cstdint>
#include <span>

namespace fluid::detail {

/// The solver's plan for a frame; a sub-step may change it (the explicit solver's probe).
struct FramePlan {
    uint32_t count = 1; // sub-steps (count; >= 1)
    float dt = 0.0f;    // length of each (s)
    // The last sub-step takes exactly what is left of the frame (the explicit solver's CFL
    // sub-steps); else it is `dt` long like the others and ends at the frame's end by definition.
    bool lastTakesRest = false;
    // Set by a sub-step: after it, the rest of the frame is spread evenly over the remaining
    // `count` - (index + 1) sub-steps.
    bool respread = false;
};

/// One sub-step as the driver hands it to the solver.
struct Substep {
    uint32_t index = 0; // 0 .. count - 1
    bool last = false;  // index + 1 == count (as planned when the sub-step starts)
    float dt = 0.0f;    // its length (s)
    double elapsed = 0; // time into the frame at its start (s)
    float begin = 0.0f; // the same as a float (s)
    float end = 0.0f;   // time into the frame at its end (s; the frame's length for the last)
};

/// The stages of a step as the profile names them: the driver's "prepare" first and "finish"
/// last; a solver's own stages in between, in the order its sub-step runs them.
class Stages {
public:
    /// `probe` (WorldState::stageProbe) is called after each of the solver's stages when set.
    Stages(Profile& profile, std::span<const char* const> solverStages,
           const StageProbe* probe = nullptr);
    /// Runs f and adds its wall-clock time to the solver's stage `id` (an index into the
    /// solver's list), then calls the stage probe, if any, with `id`.
    template <class F> void run(uint32_t id, F&& f) {
        timed(m_profile.stages[1 + id].ms, f);
        if (m_probe != nullptr && *m_probe) {
            (*m_probe)(id);
        }
    }
    /// The driver's own stages.
    template <class F> void prepare(F&& f) { timed(m_profile.stages[0].ms, f); }
    template <class F> void finish(F&& f) { timed(m_profile.stages[m_last].ms, f); }

private:
    Profile& m_profile;
    const StageProbe* m_probe = nullptr;
    uint32_t m_last = 0;
};

/// What a solver does in a frame; the driver calls it in this order.
class Solver {
public:
    virtual ~Solver() = default;
    /// The names of the solver's sub-step stages, in order (string literals).
    virtual std::span<const char* const> stageNames() const = 0;
    /// After the shared opening: the solver's own constants and its plan for the frame.
    virtual FramePlan plan(const SceneFacts& facts, float frameDt) = 0;
    /// One sub-step, stage by stage (`stages.run`); may change `plan` (see FramePlan).
    virtual void substep(Stages& stages, FramePlan& plan, const Substep& sub) = 0;
    /// After the last sub-step, before the shared closing: the solver's state and profile
    /// fields.
    virtual void close(Profile& profile) = 0;
};

/// One frame of `frameDt` seconds of `solver` on the world.
void runFrame(WorldState& s, float frameDt, Solver& solver);

} // namespace fluid::detail
