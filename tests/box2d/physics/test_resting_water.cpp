// Resting water rests (issue 61's target 1): a tank of water 0.2 m deep and 0.6 m wide, left
// alone for 10 s, its particles' mean and largest speed over seconds 8-10; alone in the fluid's
// own `boundary.box`, and with the Box2D tank's static walls coupled too (the floor and walls
// twice, as a user gets who builds Box2D walls where the fluid's box is and does not filter them
// out). `fluid-float --no-body [--doubled]` measures the same tanks (and 0.6 m deep ones);
// docs/notes/pbf_resting_water.md, "Resting water", has every variant's figures.
#include "box2d_support.h"

#include <fluid/box2d/coupling.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

using namespace fluid;
using namespace fluid::test;

namespace {

struct Rest {
    double mean = 0.0, largest = 0.0; // m/s, over seconds 8-10
};

Rest settle(Quality quality, bool doubled) {
    WorldDef def = physicsDef();
    def.positionBased = positionBasedPreset(quality);
    World world(def);
    const MaterialId water = world.addMaterial(fluid::water());
    const float s = world.spacing(water);
    const uint32_t cols = 60, rows = 20; // 0.6 m x 0.2 m
    const float top = float(rows) * s + 0.5f;
    const float width = fillTank(world, water, cols, rows, top);
    b2World physics(b2Vec2(0.0f, -kG));
    addTankWalls(physics, 0.0f, 0.0f, width, top);
    box2d::CouplingDef cdef;
    cdef.categoryMask = doubled ? uint16_t(0xFFFF) : kFluidMask;
    box2d::Coupling coupling(world, physics, cdef);
    Rest r;
    const int frames = 600, window = 120;
    for (int f = 0; f < frames; ++f) {
        coupling.step(world, kFrame);
        if (f < frames - window) {
            continue;
        }
        r.mean += meanSpeed(world) / window;
        r.largest = std::max(r.largest, double(maxSpeed(world)));
    }
    REQUIRE(allFinite(world));
    REQUIRE(world.particleCount() == cols * rows);
    return r;
}

} // namespace

TEST_CASE("resting water: a 0.2 m tank comes to rest, its floor and walls single or doubled",
          "[slow][box2d][rest]") {
    const bool doubled = GENERATE(false, true);
    CAPTURE(doubled);
    // The precise preset meets the target: under 0.5 cm/s on average and 3 cm/s at most.
    const Rest precise = settle(Quality::Precise, doubled);
    // The game preset (the default) does not yet: held against getting worse than its shipped
    // figures by more than a quarter until a fix lands (docs/notes/pbf_resting_water.md, "Resting
    // water", has both presets' figures).
    const Rest game = settle(Quality::Game, doubled);
    std::printf("[measure] resting water 0.2 m%s, seconds 8-10: precise mean %.4f largest %.4f "
                "m/s; game mean %.4f largest %.4f m/s\n",
                doubled ? ", floor and walls doubled" : "", precise.mean, precise.largest,
                game.mean, game.largest);
    CAPTURE(precise.mean, precise.largest, game.mean, game.largest);
    CHECK(precise.mean <= 0.005);
    CHECK(precise.largest <= 0.03);
    CHECK(game.mean <= (doubled ? 0.029 : 0.027));
    CHECK(game.largest <= (doubled ? 0.48 : 0.095));
}
