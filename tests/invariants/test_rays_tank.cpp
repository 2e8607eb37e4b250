// A resting tank read through the ray casts and `sample` (fluid/query.h): a ray cast down reads the
// surface within half a spacing of the far-field surface, `sample` the depth within half a spacing
// and the hydrostatic pressure, with the explicit solver and both position-based presets. Slow: the
// tank settles for 2.5 s with each solver.
#include "test_support.h"

#include <fluid/query.h>

#include <catch2/catch.hpp>
#include <glm/geometric.hpp>

#include <array>
#include <cmath>

using namespace fluid;
using namespace fluid::test;

namespace {

// A tank of 30 x 30 spacings of water at `setting`, let settle for `frames` frames.
World settledRayTank(Setting setting, int frames) {
    World world(defFor(setting, 2));
    const MaterialId w = world.addMaterial(water());
    const float s = world.spacing(w);
    const uint32_t cols = 30, rows = 30;
    world.addForce(std::make_unique<GravityForce>(0.0f, -kG));
    world.addBoundary(std::make_unique<BoxContainer>(0.0f, 0.0f, float(cols) * s, 0.6f));
    world.spawnBlob(latticeBlock(world, w, 0.0f, 0.0f, cols, rows));
    for (int frame = 0; frame < frames; ++frame) {
        world.step(kFrame);
    }
    return world;
}

// The far-field surface of a tank `width` wide: the top row's mean height away from the walls,
// plus the half spacing the field's surface stands above the outer particles (0 when fewer
// than 8 particles stand there).
double tankSurface(const World& world, float width) {
    const float s = world.spacing(MaterialId{0});
    double topSum = 0.0;
    uint32_t topCount = 0;
    const auto px = world.positionX(), py = world.positionY();
    const float highest = bounds(world).y1;
    for (uint32_t i = 0; i < world.particleCount(); ++i) {
        if (px[i] > 8.0f * s && px[i] < width - 8.0f * s && py[i] > highest - 0.5f * s) {
            topSum += py[i];
            ++topCount;
        }
    }
    return topCount >= 8 ? topSum / topCount + 0.5 * s : 0.0;
}

} // namespace

TEST_CASE("rays: a resting tank's surface, hydrostatic pressure and depth",
          "[slow][invariants][rays]") {
    const Setting setting = GENERATE(Setting::Explicit, Setting::Game, Setting::Precise);
    CAPTURE(settingName(setting));
    World world = settledRayTank(setting, 150);
    const MaterialId w{0};
    const float s = world.spacing(w);
    const float width = 30.0f * s;
    REQUIRE(allFinite(world));
    const double surface = tankSurface(world, width);
    REQUIRE(surface > 0.0);
    // Down onto the surface, at several places across the middle.
    for (float x = 10.0f * s; x <= width - 10.0f * s; x += 2.5f * s) {
        const RayHit down = rayCast(world, {x, 0.55f}, {x, 0.0f});
        REQUIRE(down.hit);
        CAPTURE(x, down.point.y, surface);
        CHECK(std::fabs(down.point.y - surface) <= 0.5 * s);
        CHECK(down.normal.y > 0.95f);
    }
    // In the middle column: depth within half a spacing; the pressure rho0 g depth within 5%
    // with the explicit solver. The position-based solver's own pressure (World::pressure, which
    // `sample` interpolates) is less exact, so it is held to the 25% test_position_based.cpp
    // allows it (figures per preset: docs/queries.md, "Ray casts and the liquid at a point").
    const double pressureTolerance = setting == Setting::Explicit ? 0.05 : 0.25;
    const float rho0 = world.material(w).restDensity;
    for (const double fraction : {0.3, 0.5, 0.7, 0.85}) {
        const float y = float(surface * (1.0 - fraction));
        std::array<float, 1> share{};
        const LiquidSample here = sample(world, {0.5f * width, y}, share);
        const double depth = surface - y;
        CAPTURE(fraction, y, here.pressure, here.depth, depth, here.densityRatio);
        CHECK(here.inLiquid);
        CHECK(here.depth == Approx(depth).margin(0.5 * s));
        CHECK(here.pressure == Approx(rho0 * kG * depth).epsilon(pressureTolerance));
        CHECK(here.densityRatio == Approx(1.0).margin(0.05));
        CHECK(glm::length(here.velocity) < 0.05f);
        CHECK(share[0] == Approx(1.0f));
        CHECK(here.material == w);
        CHECK(here.neighbours > 20);
    }
    // Above the liquid: not in it, no depth.
    const LiquidSample above = sample(world, {0.5f * width, float(surface + s)});
    CHECK_FALSE(above.inLiquid);
    CHECK(above.depth == 0.0f);
}

// Not run by ctest (hidden): the game preset's pressure at the test's four depths after 140 to
// 170 frames, for scripts/readings.sh: the test reads it after 150 frames, where it sits a few
// points from its 25% (docs/position_based_method.md, "Coarse correction").
TEST_CASE("readings: the game preset's tank pressure after 140 to 170 frames", "[.readings]") {
    for (int frames = 140; frames <= 170; frames += 5) {
        const World world = settledRayTank(Setting::Game, frames);
        const float s = world.spacing(MaterialId{0});
        const double surface = tankSurface(world, 30.0f * s);
        const float rho0 = world.material(MaterialId{0}).restDensity;
        for (const double fraction : {0.3, 0.5, 0.7, 0.85}) {
            const float y = float(surface * (1.0 - fraction));
            const LiquidSample here = sample(world, {15.0f * s, y});
            std::printf("[reading] tank-pressure/game/depth=%.2f/frames=%d/error %+.1f%%\n",
                        fraction, frames,
                        100.0 * (here.pressure / (rho0 * kG * (surface - y)) - 1.0));
        }
    }
}
