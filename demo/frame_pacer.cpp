// fluid-demo — fixed-step pacing (see frame_pacer.h for the rules).
#include "frame_pacer.h"

#include <fluid/error.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace fluid::demo {

namespace {
// Tolerance of the step count, as a share of a step: a frame of k steps of real time measured
// with rounding error still gives k steps. Far below a clock's jitter (1/1000 of a 60 Hz step is
// 17 us), so it never adds a step a real frame did not earn; the accumulator carries the
// borrowed sliver as a small negative value.
constexpr double kSnap = 1e-3;
// Real time over which `speed` and `behind` look back (unit: s).
constexpr double kWindow = 1.0;
// Weight of a new report in the smoothed step cost: one slow step (a page fault, a level
// spawning a blob) should not halve the cap; a machine that stays slow gets there in a few
// frames.
constexpr double kCostWeight = 0.25;

void checkDef(const FramePacerDef& def) {
    std::ostringstream s;
    if (!std::isfinite(def.step) || !(def.step > 0.0) || def.step > 1.0) {
        s << "FramePacerDef: step = " << def.step
          << " s is out of range; expected a finite value in (0, 1] (typically 1/60)";
        throw Error(s.str());
    }
    if (def.maxStepsPerFrame < 1 || def.maxStepsPerFrame > 1000) {
        s << "FramePacerDef: maxStepsPerFrame = " << def.maxStepsPerFrame
          << " is out of range [1, 1000] (unit: count)";
        throw Error(s.str());
    }
    if (!(def.maxFrameTime >= def.step && def.maxFrameTime <= 10.0)) { // NaN fails too
        s << "FramePacerDef: maxFrameTime = " << def.maxFrameTime << " is out of range ["
          << def.step << ", 10] (unit: s; at least one step)";
        throw Error(s.str());
    }
}
} // namespace

FramePacer::FramePacer(const FramePacerDef& def) : m_def(def) {
    checkDef(def);
    m_cap = def.maxStepsPerFrame;
}

uint32_t FramePacer::advance(double realSeconds) {
    // A clock that jumps back or returns garbage must not stall or flood the simulation.
    const double real = std::isfinite(realSeconds) && realSeconds > 0.0 ? realSeconds : 0.0;
    m_sinceDrop += real;

    if (m_paused) {
        // The accumulator stays as it is: resuming must not replay the pause.
        const bool single = m_singleStep;
        m_singleStep = false;
        return single ? 1u : 0u;
    }

    // A hitch longer than maxFrameTime is lost, not caught up.
    const double used = std::min(real, m_def.maxFrameTime);
    double dropped = real - used;
    m_accumulator += used;

    const double whole = std::floor(m_accumulator / m_def.step + kSnap);
    const double due = std::max(whole, 0.0);
    const double run = std::min(due, static_cast<double>(m_cap));
    // Run `run` steps; forget whole steps beyond the cap (slow motion instead of a backlog)
    // and keep only the fraction of a step.
    m_accumulator -= due * m_def.step;
    dropped += (due - run) * m_def.step;

    if (dropped > 0.0) {
        m_droppedTime += dropped;
        m_sinceDrop = 0.0;
        m_everDropped = true;
    }
    recordSample(real, run * m_def.step);
    return static_cast<uint32_t>(run);
}

void FramePacer::reportStepCost(double secondsPerStep) {
    if (!std::isfinite(secondsPerStep) || secondsPerStep < 0.0) {
        return;
    }
    m_stepCost = m_stepCost > 0.0 ? m_stepCost + kCostWeight * (secondsPerStep - m_stepCost)
                                  : secondsPerStep;
    if (m_stepCost <= 0.0) {
        m_cap = m_def.maxStepsPerFrame;
        return;
    }
    // n steps per frame cost n * cost of wall time; keep that within one step's share so a
    // catch-up frame does not lengthen the next one (the spiral).
    const double fit = std::floor(m_def.step / m_stepCost);
    m_cap =
        static_cast<uint32_t>(std::clamp(fit, 1.0, static_cast<double>(m_def.maxStepsPerFrame)));
}

void FramePacer::setPaused(bool paused) {
    m_paused = paused;
    if (!paused) {
        m_singleStep = false;
    }
}

void FramePacer::requestSingleStep() {
    if (m_paused) {
        m_singleStep = true;
    }
}

void FramePacer::reset() {
    const FramePacerDef def = m_def;
    const bool paused = m_paused;
    *this = FramePacer(def);
    m_paused = paused;
}

bool FramePacer::behind() const {
    return m_everDropped && m_sinceDrop < kWindow;
}

double FramePacer::speed() const {
    return m_windowReal > 0.0 ? m_windowSim / m_windowReal : 1.0;
}

uint64_t FramePacer::droppedSteps() const {
    return static_cast<uint64_t>(std::floor(m_droppedTime / m_def.step + kSnap));
}

void FramePacer::recordSample(double real, double sim) {
    m_window.push_back({real, sim});
    m_windowReal += real;
    m_windowSim += sim;
    // Keep the newest frames that cover at least kWindow of real time.
    while (m_window.size() > 1 && m_windowReal - m_window.front().real >= kWindow) {
        m_windowReal -= m_window.front().real;
        m_windowSim -= m_window.front().sim;
        m_window.pop_front();
    }
    if (m_window.size() == 1) {
        // Resynchronise the running sums (no drift over a long session).
        m_windowReal = m_window.front().real;
        m_windowSim = m_window.front().sim;
    }
}

} // namespace fluid::demo
