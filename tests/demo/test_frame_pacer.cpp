// The demo's fixed-step pacer: exact step counts, catch-up cap, dropped time, no spiral of
// death on a slow machine, pause and single step, reset, definition errors.
#include "demo/frame_pacer.h"

#include <fluid/error.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <limits>

using fluid::demo::FramePacer;
using fluid::demo::FramePacerDef;

namespace {
constexpr double kStep = 1.0 / 60.0;

// Sum of advance() over `frames` frames of `dt` seconds each.
uint64_t runFrames(FramePacer& pacer, int frames, double dt) {
    uint64_t steps = 0;
    for (int i = 0; i < frames; ++i) {
        steps += pacer.advance(dt);
    }
    return steps;
}
} // namespace

TEST_CASE("FramePacer: real time of k steps gives exactly k steps", "[demo][pacer]") {
    SECTION("3 frames of 1/60 s give 3 steps, one per frame") {
        FramePacer pacer;
        for (int i = 0; i < 3; ++i) {
            CHECK(pacer.advance(kStep) == 1);
        }
        CHECK(std::abs(pacer.backlog()) < 1e-3 * kStep);
    }
    SECTION("600 frames of 1/60 s give 600 steps, none dropped") {
        FramePacer pacer;
        CHECK(runFrames(pacer, 600, kStep) == 600);
        CHECK(pacer.droppedSteps() == 0);
        CHECK_FALSE(pacer.behind());
        CHECK(pacer.speed() == Approx(1.0).margin(0.02));
    }
    SECTION("one frame of 3 steps gives 3 steps") {
        FramePacer pacer;
        CHECK(pacer.advance(3 * kStep) == 3);
        CHECK(pacer.advance(3.0 / 60.0) == 3);
    }
    SECTION("120 Hz frames alternate 0 and 1 steps") {
        FramePacer pacer;
        for (int i = 0; i < 60; ++i) {
            CHECK(pacer.advance(kStep / 2) == 0);
            CHECK(pacer.advance(kStep / 2) == 1);
        }
    }
    SECTION("30 Hz frames give 2 steps each") {
        FramePacer pacer;
        for (int i = 0; i < 30; ++i) {
            CHECK(pacer.advance(2 * kStep) == 2);
        }
    }
    SECTION("a step of 0.1 s: 10 frames of 0.01 s give 1 step") {
        FramePacer pacer(FramePacerDef{0.1, 4, 0.25});
        CHECK(runFrames(pacer, 9, 0.01) == 0);
        CHECK(pacer.advance(0.01) == 1);
    }
    SECTION("a microsecond clock (16667 us frames) loses no step over 10 s") {
        FramePacer pacer;
        // 600 frames of 16667 us = 10.0002 s: 600 steps, nothing dropped.
        CHECK(runFrames(pacer, 600, 16667e-6) == 600);
        CHECK(pacer.droppedSteps() == 0);
    }
}

TEST_CASE("FramePacer: the per-frame cap and dropped time", "[demo][pacer]") {
    SECTION("a 0.1 s frame (6 steps) with cap 4 runs 4 and drops 2") {
        FramePacer pacer;
        CHECK(pacer.advance(0.1) == 4);
        CHECK(pacer.droppedSteps() == 2);
        CHECK(pacer.behind());
        // Nothing carried over: the next normal frame runs one step.
        CHECK(std::abs(pacer.backlog()) < 1e-3 * kStep);
        CHECK(pacer.advance(kStep) == 1);
        CHECK(pacer.droppedSteps() == 2);
    }
    SECTION("a 1 s hitch is clamped to 0.25 s: 4 steps run, 56 dropped") {
        FramePacer pacer;
        CHECK(pacer.advance(1.0) == 4);
        // 0.75 s over maxFrameTime (45 steps) + 15 - 4 over the cap.
        CHECK(pacer.droppedSteps() == 56);
    }
    SECTION("cap 1: 10 frames of 2 steps run 10 and drop 10") {
        FramePacer pacer(FramePacerDef{kStep, 1, 0.25});
        CHECK(runFrames(pacer, 10, 2 * kStep) == 10);
        CHECK(pacer.droppedSteps() == 10);
    }
    SECTION("the fraction of a step is kept, whole steps beyond the cap are not") {
        FramePacer pacer;
        CHECK(pacer.advance(6.5 * kStep) == 4);
        CHECK(pacer.backlog() == Approx(0.5 * kStep).epsilon(1e-9));
        CHECK(pacer.droppedSteps() == 2);
        CHECK(pacer.advance(0.5 * kStep) == 1);
    }
    SECTION("behind clears after a second without drops") {
        FramePacer pacer;
        pacer.advance(0.1);
        REQUIRE(pacer.behind());
        runFrames(pacer, 59, kStep);
        CHECK(pacer.behind());
        runFrames(pacer, 2, kStep);
        CHECK_FALSE(pacer.behind());
        CHECK(pacer.droppedSteps() == 2);
    }
    SECTION("negative and non-finite times read as 0") {
        FramePacer pacer;
        CHECK(pacer.advance(-1.0) == 0);
        CHECK(pacer.advance(std::numeric_limits<double>::quiet_NaN()) == 0);
        CHECK(pacer.advance(std::numeric_limits<double>::infinity()) == 0);
        CHECK(pacer.droppedSteps() == 0);
        CHECK(pacer.advance(kStep) == 1);
    }
}

TEST_CASE("FramePacer: the cap follows the step cost", "[demo][pacer]") {
    FramePacer pacer; // cap 4
    CHECK(pacer.stepCap() == 4);
    pacer.reportStepCost(0.2 * kStep); // 5 fit in one step's share: cap stays 4
    CHECK(pacer.stepCap() == 4);
    FramePacer slow;
    slow.reportStepCost(0.4 * kStep); // first report taken as is: 2 fit
    CHECK(slow.stepCap() == 2);
    FramePacer slower;
    slower.reportStepCost(0.6 * kStep); // more than half its share: one step per frame
    CHECK(slower.stepCap() == 1);
    CHECK(slower.advance(3 * kStep) == 1);
    CHECK(slower.droppedSteps() == 2);
    // Smoothed: one cheap report does not restore the full cap at once (the estimate moves a
    // quarter of the way, to 0.475 of a step: 2 per frame), a few do.
    slower.reportStepCost(0.1 * kStep);
    CHECK(slower.stepCap() == 2);
    for (int i = 0; i < 20; ++i) {
        slower.reportStepCost(0.1 * kStep);
    }
    CHECK(slower.stepCap() == 4);
    // Garbage reports are ignored.
    slower.reportStepCost(-1.0);
    slower.reportStepCost(std::numeric_limits<double>::quiet_NaN());
    CHECK(slower.stepCap() == 4);
}

TEST_CASE("FramePacer: no spiral of death when a step costs twice its share", "[demo][pacer]") {
    // Simulated main loop: a frame's real time is the render time plus what its steps cost.
    const double render = 0.002;
    const double cost = 2.0 * kStep;
    auto simulate = [&](bool report, uint32_t& maxSteps, double& maxFrame, double& maxBacklog,
                        double& simulated, double& elapsed) {
        FramePacer pacer;
        double frame = kStep;
        maxSteps = 0;
        maxFrame = 0.0;
        maxBacklog = 0.0;
        simulated = 0.0;
        elapsed = 0.0;
        for (int i = 0; i < 1000; ++i) {
            const uint32_t steps = pacer.advance(frame);
            if (report && steps > 0) {
                pacer.reportStepCost(cost);
            }
            simulated += steps * kStep;
            elapsed += frame;
            frame = render + steps * cost;
            maxSteps = std::max(maxSteps, steps);
            maxFrame = std::max(maxFrame, frame);
            maxBacklog = std::max(maxBacklog, pacer.backlog());
        }
        return pacer;
    };
    uint32_t maxSteps = 0;
    double maxFrame = 0.0, maxBacklog = 0.0, simulated = 0.0, elapsed = 0.0;

    SECTION("with cost reports: one step per frame, slow motion at ~47% speed") {
        const FramePacer pacer = simulate(true, maxSteps, maxFrame, maxBacklog, simulated, elapsed);
        CHECK(maxSteps == 1);
        CHECK(maxFrame <= render + cost + 1e-12);
        CHECK(maxBacklog < kStep);
        const double expected = kStep / (render + cost); // 0.4717
        CHECK(pacer.speed() == Approx(expected).epsilon(0.03));
        CHECK(simulated / elapsed == Approx(expected).epsilon(0.01));
        CHECK(pacer.behind());
        // Every frame of 2.2 steps of real time drops 1.2 of them; the count is whole steps.
        CHECK(static_cast<double>(pacer.droppedSteps()) ==
              Approx((elapsed - simulated) / kStep).margin(1.0));
        std::printf("[measure] pacer, step cost 2x share, 1000 frames: speed %.3f, "
                    "%llu steps dropped, longest frame %.1f ms\n",
                    pacer.speed(), static_cast<unsigned long long>(pacer.droppedSteps()),
                    maxFrame * 1e3);
    }
    SECTION("without cost reports the cap still bounds the frame and the backlog") {
        const FramePacer pacer =
            simulate(false, maxSteps, maxFrame, maxBacklog, simulated, elapsed);
        CHECK(maxSteps == 4);
        CHECK(maxFrame <= render + 4 * cost + 1e-12);
        CHECK(maxBacklog < kStep);
        CHECK(pacer.speed() < 0.6);
        std::printf("[measure] pacer, step cost 2x share, no reports: speed %.3f, "
                    "longest frame %.1f ms\n",
                    pacer.speed(), maxFrame * 1e3);
    }
}

TEST_CASE("FramePacer: pause and single step", "[demo][pacer]") {
    FramePacer pacer;
    CHECK(pacer.advance(0.5 * kStep) == 0);
    const double before = pacer.backlog();
    pacer.setPaused(true);
    CHECK(pacer.paused());
    CHECK(runFrames(pacer, 100, kStep) == 0);
    CHECK(pacer.backlog() == before); // the accumulator did not grow
    CHECK(pacer.droppedSteps() == 0);
    CHECK_FALSE(pacer.behind());

    pacer.requestSingleStep();
    CHECK(pacer.advance(kStep) == 1);
    CHECK(pacer.advance(kStep) == 0); // exactly one
    pacer.requestSingleStep();
    pacer.requestSingleStep(); // two requests in one frame are still one step
    CHECK(pacer.advance(0.0) == 1);
    CHECK(pacer.advance(0.0) == 0);
    CHECK(pacer.backlog() == before);

    // A request pending at resume is dropped; the half step waiting since before the pause
    // completes with the next half frame.
    pacer.requestSingleStep();
    pacer.setPaused(false);
    CHECK_FALSE(pacer.paused());
    CHECK(pacer.advance(0.5 * kStep) == 1);
    // A request while running is ignored.
    pacer.requestSingleStep();
    CHECK(pacer.advance(0.0) == 0);
}

TEST_CASE("FramePacer: reset forgets everything measured", "[demo][pacer]") {
    FramePacer pacer;
    pacer.reportStepCost(kStep);
    pacer.advance(0.7 * kStep);
    pacer.advance(1.0);
    pacer.setPaused(true);
    REQUIRE(pacer.droppedSteps() > 0);
    REQUIRE(pacer.behind());
    REQUIRE(pacer.stepCap() == 1);
    pacer.reset();
    CHECK(pacer.droppedSteps() == 0);
    CHECK_FALSE(pacer.behind());
    CHECK(pacer.speed() == 1.0);
    CHECK(pacer.backlog() == 0.0);
    CHECK(pacer.stepCap() == 4);
    CHECK(pacer.paused()); // the player's pause survives a level reload
    pacer.setPaused(false);
    CHECK(pacer.advance(kStep) == 1);
}

TEST_CASE("FramePacer: bad definitions are refused with exact messages", "[demo][pacer]") {
    using Catch::Matchers::Message;
    const double inf = std::numeric_limits<double>::infinity();
    CHECK_THROWS_MATCHES(FramePacer(FramePacerDef{0.0, 4, 0.25}), fluid::Error,
                         Message("FramePacerDef: step = 0 s is out of range; expected a finite "
                                 "value in (0, 1] (typically 1/60)"));
    CHECK_THROWS_MATCHES(FramePacer(FramePacerDef{-1.0, 4, 0.25}), fluid::Error,
                         Message("FramePacerDef: step = -1 s is out of range; expected a finite "
                                 "value in (0, 1] (typically 1/60)"));
    CHECK_THROWS_MATCHES(FramePacer(FramePacerDef{inf, 4, 0.25}), fluid::Error,
                         Message("FramePacerDef: step = inf s is out of range; expected a finite "
                                 "value in (0, 1] (typically 1/60)"));
    CHECK_THROWS_MATCHES(FramePacer(FramePacerDef{2.0, 4, 10.0}), fluid::Error,
                         Message("FramePacerDef: step = 2 s is out of range; expected a finite "
                                 "value in (0, 1] (typically 1/60)"));
    CHECK_THROWS_MATCHES(FramePacer(FramePacerDef{kStep, 0, 0.25}), fluid::Error,
                         Message("FramePacerDef: maxStepsPerFrame = 0 is out of range [1, "
                                 "1000] (unit: count)"));
    CHECK_THROWS_MATCHES(FramePacer(FramePacerDef{kStep, 1001, 0.25}), fluid::Error,
                         Message("FramePacerDef: maxStepsPerFrame = 1001 is out of range [1, "
                                 "1000] (unit: count)"));
    CHECK_THROWS_MATCHES(FramePacer(FramePacerDef{kStep, 4, 0.01}), fluid::Error,
                         Message("FramePacerDef: maxFrameTime = 0.01 is out of range "
                                 "[0.0166667, 10] (unit: s; at least one step)"));
    CHECK_THROWS_MATCHES(FramePacer(FramePacerDef{kStep, 4, 11.0}), fluid::Error,
                         Message("FramePacerDef: maxFrameTime = 11 is out of range "
                                 "[0.0166667, 10] (unit: s; at least one step)"));
    CHECK_THROWS_MATCHES(FramePacer(FramePacerDef{kStep, 4, inf}), fluid::Error,
                         Message("FramePacerDef: maxFrameTime = inf is out of range "
                                 "[0.0166667, 10] (unit: s; at least one step)"));
    // The edges are accepted.
    CHECK_NOTHROW(FramePacer(FramePacerDef{1.0, 1000, 1.0}));
    CHECK_NOTHROW(FramePacer(FramePacerDef{kStep, 1, kStep}));
}
