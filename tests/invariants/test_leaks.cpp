// Leak-proof boundaries: particles fired at 20 m/s at a chain of thin segments splitting a tank,
// and at a rotating paddle in a tank of water, for 10 s; no particle may ever cross the chain,
// end inside the paddle or leave the tank.
#include "test_support.h"

#include <fluid/plugins/boundaries.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

using namespace fluid;
using namespace fluid::test;

namespace {

// A small deterministic generator for the firing pattern (the tests must not depend on the
// platform's std::uniform_real_distribution).
struct Lcg {
    uint64_t state = 0x9e3779b97f4a7c15ull;
    float next() { // [0, 1)
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return float(state >> 40) / float(1ull << 24);
    }
};

// The splitter: monotone in y, reaching below the floor and above the lid, with slanted parts.
const std::vector<glm::vec2> kSplitter{
    {0.45f, -0.05f}, {0.45f, 0.12f}, {0.55f, 0.27f}, {0.5f, 0.42f}, {0.5f, 0.65f}};

// x of the splitter at height y.
double splitterX(double y) {
    for (size_t k = 0; k + 1 < kSplitter.size(); ++k) {
        const glm::dvec2 a = kSplitter[k], b = kSplitter[k + 1];
        if (y <= b.y || k + 2 == kSplitter.size()) {
            return a.x + (b.x - a.x) * (y - a.y) / (b.y - a.y);
        }
    }
    return kSplitter.back().x;
}

struct ChainRun {
    uint32_t crossedMax = 0;   // most particles beyond the splitter at any frame
    uint32_t outsideMax = 0;   // most particles outside the tank at any frame
    uint32_t particles = 0;    // at the end
    double minClearance = 1.0; // smallest distance of a particle from the splitter (m)
    bool finite = true;
};

// Tank [0, 0.8] x [0, 0.6] split by the chain; `perFrame` particles fired at 20 m/s from the
// left towards the splitter each frame, at most `cap`, for `frames` frames.
ChainRun runChain(Solver solver, uint32_t frames, uint32_t perFrame, uint32_t cap) {
    World world(physicsDef(solver));
    const MaterialId water = world.addMaterial(fluid::water());
    world.addForce(std::make_unique<GravityForce>());
    // The splitter (a wall) projects before the tank (a container) whatever the order added:
    // it puts crossing particles back on their side, then the tank keeps them inside.
    world.addBoundary(std::make_unique<BoxContainer>(0.0f, 0.0f, 0.8f, 0.6f));
    world.addBoundary(std::make_unique<ChainBoundary>(kSplitter));
    Lcg rng;
    ChainRun r;
    for (uint32_t f = 0; f < frames; ++f) {
        for (uint32_t k = 0; k < perFrame && world.particleCount() < cap; ++k) {
            const float y = 0.05f + 0.5f * rng.next();
            const float angle = -0.35f + 0.7f * rng.next(); // about the +x axis
            world.addParticle({0.03f + 0.05f * rng.next(), y},
                              {20.0f * std::cos(angle), 20.0f * std::sin(angle)}, water);
        }
        world.step(kFrame);
        const auto px = world.positionX(), py = world.positionY();
        uint32_t crossed = 0;
        for (uint32_t i = 0; i < world.particleCount(); ++i) {
            if (!(px[i] < splitterX(py[i]))) {
                ++crossed;
            }
            const glm::dvec2 p{px[i], py[i]};
            for (size_t s = 0; s + 1 < kSplitter.size(); ++s) {
                r.minClearance =
                    std::min(r.minClearance, segmentDistance(p, kSplitter[s], kSplitter[s + 1]));
            }
        }
        r.crossedMax = std::max(r.crossedMax, crossed);
        r.outsideMax = std::max(r.outsideMax, countOutside(world, 0.0f, 0.0f, 0.8f, 0.6f));
        r.finite = r.finite && allFinite(world);
        if (crossed > 0) {
            std::printf("frame %u: %u particles beyond the splitter\n", f, crossed);
        }
    }
    r.particles = world.particleCount();
    return r;
}

} // namespace

TEST_CASE("leaks: particles fired at 20 m/s at a chain of thin segments never cross it",
          "[slow][leaks]") {
    const float s = particleSpacing(fluid::water(), kDefaultDepth);
    {
        // Position-based (the default): 10 s, 3 particles a frame up to 1,800.
        Stopwatch watch("chain leak, position-based, 600 frames");
        const ChainRun r = runChain(Solver::PositionBased, 600, 3, 1800);
        std::printf("[measure] chain leak (position-based, 600 frames, %u particles fired at "
                    "20 m/s): %u crossed, %u outside the tank, closest to the chain %.3f "
                    "spacing, %.1f s wall\n",
                    r.particles, r.crossedMax, r.outsideMax, r.minClearance / s, watch.seconds());
        CHECK(r.particles == 1800);
        CHECK(r.crossedMax == 0);
        CHECK(r.outsideMax == 0);
        CHECK(r.finite);
        CHECK(r.minClearance > 0.45 * s); // half a spacing, less float rounding
    }
    {
        // Explicit: a hundred or more sub-steps a frame, so fewer particles (600) for the same
        // 10 s.
        Stopwatch watch("chain leak, explicit, 600 frames");
        const ChainRun r = runChain(Solver::Explicit, 600, 2, 600);
        std::printf("[measure] chain leak (explicit, 600 frames, %u particles fired at 20 m/s): "
                    "%u crossed, %u outside the tank, closest to the chain %.3f spacing, %.1f s "
                    "wall\n",
                    r.particles, r.crossedMax, r.outsideMax, r.minClearance / s, watch.seconds());
        CHECK(r.particles == 600);
        CHECK(r.crossedMax == 0);
        CHECK(r.outsideMax == 0);
        CHECK(r.finite);
        CHECK(r.minClearance > 0.45 * s);
    }
}

namespace {

struct PaddleRun {
    uint32_t insideMax = 0;  // most particles inside the paddle at any frame
    uint32_t outsideMax = 0; // most particles outside the tank at any frame
    uint32_t particles = 0;
    double deepest = 0.0; // deepest penetration into the paddle at any frame (m)
    double turned = 0.0;  // angle the paddle turned (rad)
    bool finite = true;
};

constexpr float kHalfLength = 0.2f, kHalfThickness = 0.025f;

// Tank [0, 0.8] x [0, 0.7] with water 0.25 m deep, a 0.4 x 0.05 m paddle about (0.4, 0.3)
// turning at `omega`, particles fired at 20 m/s from the upper left at it. `hostDriven`: the
// host sets the pose and velocities every frame (x swinging, the angle from omega t) instead
// of letting the paddle advance itself.
PaddleRun runPaddle(Solver solver, uint32_t frames, uint32_t perFrame, uint32_t fireCap,
                    uint32_t waterCols, float omega, bool hostDriven) {
    World world(physicsDef(solver));
    const MaterialId water = world.addMaterial(fluid::water());
    const float s = world.spacing(water);
    world.addForce(std::make_unique<GravityForce>());
    world.addBoundary(std::make_unique<BoxContainer>(0.0f, 0.0f, 0.8f, 0.7f));
    auto owned =
        std::make_unique<PolygonBoundary>(std::vector<glm::vec2>{{-kHalfLength, -kHalfThickness},
                                                                 {kHalfLength, -kHalfThickness},
                                                                 {kHalfLength, kHalfThickness},
                                                                 {-kHalfLength, kHalfThickness}});
    owned->setPose({0.4f, 0.3f}, 0.0f);
    owned->setVelocity({0.0f, 0.0f}, omega);
    owned->setParam("friction", 1.0);
    PolygonBoundary& paddle = static_cast<PolygonBoundary&>(world.addBoundary(std::move(owned)));
    // Water below the paddle's lowest reach at angle 0 (0.275 m).
    const float x0 = 0.4f - 0.5f * s * float(waterCols);
    for (uint32_t j = 0; j < 25; ++j) {
        for (uint32_t i = 0; i < waterCols; ++i) {
            world.addParticle({x0 + (float(i) + 0.5f) * s, (float(j) + 0.5f) * s}, {0.0f, 0.0f},
                              water);
        }
    }
    Lcg rng;
    PaddleRun r;
    uint32_t fired = 0;
    double angle = 0.0;
    for (uint32_t f = 0; f < frames; ++f) {
        if (hostDriven) {
            // The host's own animation: a swinging, turning paddle set every frame.
            const double t = double(f) * kFrame;
            paddle.setPose({float(0.4 + 0.1 * std::sin(2.0 * t)), 0.3f},
                           float(std::remainder(omega * t, 2.0 * std::numbers::pi)));
            paddle.setVelocity({float(0.2 * std::cos(2.0 * t)), 0.0f}, omega);
        }
        for (uint32_t k = 0; k < perFrame && fired < fireCap; ++k, ++fired) {
            const glm::vec2 from{0.03f + 0.04f * rng.next(), 0.55f + 0.1f * rng.next()};
            const glm::vec2 to{0.3f + 0.2f * rng.next(), 0.25f + 0.1f * rng.next()};
            const glm::vec2 d = to - from;
            world.addParticle(from, 20.0f / std::sqrt(d.x * d.x + d.y * d.y) * d, water);
        }
        world.step(kFrame);
        angle += double(omega) * kFrame;
        // The paddle's pose after the step is the one the last projection used.
        const KinematicShape::Pose pose = paddle.pose();
        const auto px = world.positionX(), py = world.positionY();
        uint32_t inside = 0;
        for (uint32_t i = 0; i < world.particleCount(); ++i) {
            const glm::dvec2 l = pose.toLocal({px[i], py[i]});
            const double depth =
                std::min(kHalfLength - std::fabs(l.x), kHalfThickness - std::fabs(l.y));
            if (depth > 0.0) {
                ++inside;
                r.deepest = std::max(r.deepest, depth);
            }
        }
        r.insideMax = std::max(r.insideMax, inside);
        r.outsideMax = std::max(r.outsideMax, countOutside(world, 0.0f, 0.0f, 0.8f, 0.7f));
        r.finite = r.finite && allFinite(world);
        if (inside > 0) {
            std::printf("frame %u: %u particles inside the paddle\n", f, inside);
        }
    }
    r.particles = world.particleCount();
    r.turned = angle;
    if (!hostDriven) {
        // The paddle advanced itself: its angle is omega * time, kept in [-pi, pi].
        CHECK(paddle.param("angle") ==
              Approx(std::remainder(angle, 2.0 * std::numbers::pi)).margin(1e-6));
    }
    return r;
}

} // namespace

TEST_CASE("leaks: a rotating paddle in water, fired at, holds every particle out",
          "[slow][long][leaks]") {
    {
        Stopwatch watch("paddle, position-based, 600 frames");
        const PaddleRun r = runPaddle(Solver::PositionBased, 600, 2, 1000, 80, 6.0f, false);
        std::printf("[measure] rotating paddle (position-based, 600 frames, omega 6 rad/s, %u "
                    "particles, 1,000 fired at 20 m/s): %u inside the paddle, deepest %.2g m, "
                    "%u outside the tank, %.1f s wall\n",
                    r.particles, r.insideMax, r.deepest, r.outsideMax, watch.seconds());
        CHECK(r.insideMax == 0);
        CHECK(r.outsideMax == 0);
        CHECK(r.finite);
    }
    {
        Stopwatch watch("paddle, position-based, host-driven, 180 frames");
        const PaddleRun r = runPaddle(Solver::PositionBased, 180, 2, 300, 80, -8.0f, true);
        std::printf("[measure] host-driven swinging paddle (position-based, 180 frames, omega "
                    "-8 rad/s): %u inside, %u outside the tank, %.1f s wall\n",
                    r.insideMax, r.outsideMax, watch.seconds());
        CHECK(r.insideMax == 0);
        CHECK(r.outsideMax == 0);
        CHECK(r.finite);
    }
    {
        // Explicit: 2 s, a narrower pool and fewer shots.
        Stopwatch watch("paddle, explicit, 120 frames");
        const PaddleRun r = runPaddle(Solver::Explicit, 120, 2, 200, 30, 6.0f, false);
        std::printf("[measure] rotating paddle (explicit, 120 frames, %u particles, 200 fired "
                    "at 20 m/s): %u inside, "
                    "%u outside the tank, %.1f s wall\n",
                    r.particles, r.insideMax, r.outsideMax, watch.seconds());
        CHECK(r.insideMax == 0);
        CHECK(r.outsideMax == 0);
        CHECK(r.finite);
    }
}
