// fluid-demo — fixed-step pacing: how many simulation steps to run per rendered frame.
#pragma once

#include <algorithm>
#include <cstdint>
#include <deque>

namespace fluid::demo {

/// Settings of a `FramePacer`. Every field has a usable default.
struct FramePacerDef {
    /// Simulated time of one fixed step (unit: s; finite, range (0, 1]). Default 1/60: one
    /// `Level::step` of a 60 Hz level.
    double step = 1.0 / 60.0;
    /// Most steps one `advance` may ask for (unit: count; range [1, 1000]). Default 4: a
    /// 15 fps frame still catches up at full speed. `reportStepCost` may lower the cap used.
    uint32_t maxStepsPerFrame = 4;
    /// Longest real frame time taken into account (unit: s; finite, range [step, 10]).
    /// Default 0.25: a longer hitch (window dragged, debugger break) costs the simulation the
    /// excess instead of a burst of catch-up steps. The excess counts as dropped time.
    double maxFrameTime = 0.25;
};

/// Fixed-step accumulator, decoupled from the render rate, without a spiral of death.
///
/// Every frame the real time since the last frame goes into an accumulator; `advance` returns
/// the number of whole steps it holds, at most the per-frame cap, and keeps the fraction of a
/// step left over. Whole steps beyond the cap are dropped (counted in `droppedSteps`), so a
/// machine too slow for real time gets slow motion, never a growing backlog: after `advance`
/// the accumulator always holds less than one step.
///
/// Rounding: a frame of exactly k steps of real time gives k steps despite floating-point
/// error (3 frames of 1/60 s give 3 steps): the step count is rounded down with a tolerance of
/// 1/1000 of a step, and the accumulator may go that much below zero, so no time is gained
/// over many frames.
///
/// Adaptive cap: `reportStepCost` tells the pacer what a step costs in wall time (smoothed
/// over a few reports). The cap becomes floor(step / cost), between 1 and `maxStepsPerFrame`:
/// a catch-up frame then costs at most one step of wall time, so catching up cannot make the
/// next frame longer. A step costing more than half its share runs one step per frame.
///
/// Thread rule: plain value type, used from one thread (the demo's main loop).
class FramePacer {
public:
    /// Validates `def`; throws `fluid::Error` naming the field, e.g. "FramePacerDef:
    /// maxStepsPerFrame = 0 is out of range [1, 1000] (unit: count)".
    explicit FramePacer(const FramePacerDef& def = {});

    /// Adds the real time since the last call (unit: s; negative or non-finite reads as 0;
    /// clamped to `maxFrameTime`, the excess dropped) and returns how many fixed steps to run
    /// now (unit: count; at most the current cap). While paused: 0, or 1 after
    /// `requestSingleStep`, and the accumulator does not change.
    uint32_t advance(double realSeconds);
    /// What each of the steps just run cost (unit: s of wall time per step; negative or
    /// non-finite values are ignored). Call after running at least one step; it sets the cap
    /// of later frames (see the class comment).
    void reportStepCost(double secondsPerStep);

    /// Pauses or resumes. Pausing keeps the accumulator as it is; resuming drops a pending
    /// single step.
    void setPaused(bool paused);
    /// True while paused.
    bool paused() const { return m_paused; }
    /// While paused: the next `advance` returns exactly 1 (the '.' key). Ignored while running.
    void requestSingleStep();
    /// Forgets everything measured (accumulator, step cost, cap, speed, dropped steps) as for a
    /// freshly loaded level; keeps the definition and the paused state.
    void reset();

    /// True while steps were dropped during the last second of real time.
    bool behind() const;
    /// Simulated seconds per real second over the last ~1 s of running (not paused) frames
    /// (unit: 1; 1.0 = real time; 1.0 before the first frame). Quantised to whole steps, so a
    /// pacer running at real time reads within about step / 1 s of 1.0.
    double speed() const;
    /// Steps dropped since creation or `reset` (unit: count): the time the simulation did not
    /// catch up (per-frame cap and `maxFrameTime` clamp), in whole steps.
    uint64_t droppedSteps() const;

    /// The per-frame cap in use (unit: count; in [1, maxStepsPerFrame]).
    uint32_t stepCap() const { return m_cap; }
    /// Real time waiting in the accumulator (unit: s; in [-step/1000, step) after `advance`).
    /// step fraction = backlog() / def().step, e.g. for render interpolation.
    double backlog() const { return m_accumulator; }
    /// How far between the last two steps to draw (unit: 1; [0, 1]): backlog() / def().step,
    /// clamped; the factor of positions interpolated over whole steps
    /// (`fluid::Interpolation::Step`).
    float drawFactor() const {
        return float(std::clamp(m_accumulator / m_def.step, 0.0, 1.0));
    }
    /// The definition the pacer was made from.
    const FramePacerDef& def() const { return m_def; }

private:
    // One running frame in the speed window.
    struct Sample {
        double real; // s of wall time
        double sim;  // s simulated
    };
    void recordSample(double real, double sim);

    FramePacerDef m_def;
    double m_accumulator = 0.0;  // s of real time not simulated yet
    double m_stepCost = 0.0;     // smoothed s of wall time per step; 0 = unknown
    uint32_t m_cap = 1;          // steps per frame allowed now
    bool m_paused = false;       //
    bool m_singleStep = false;   // one step requested while paused
    double m_droppedTime = 0.0;  // s of real time never simulated
    double m_sinceDrop = 0.0;    // s of real time since the last drop
    bool m_everDropped = false;  //
    std::deque<Sample> m_window; // the last ~1 s of running frames
    double m_windowReal = 0.0;   // sum of m_window's real
    double m_windowSim = 0.0;    // sum of m_window's sim
};

} // namespace fluid::demo
