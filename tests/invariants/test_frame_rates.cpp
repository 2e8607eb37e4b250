// Long frames: the position-based settings are tuned for 60 Hz frames, and a longer frame is
// split into as many more sub-steps, so a level at 1-30 Hz holds its 60 Hz compression at the
// same cost per simulated second.
#include "test_support.h"

#include <catch2/catch.hpp>

#include <cstdio>
#include <memory>

using namespace fluid;
using namespace fluid::test;

TEST_CASE("a frame longer than 1/60 s takes more sub-steps and holds the 60 Hz compression",
          "[invariants][slow][frames]") {
    const Quality quality = GENERATE(Quality::Game, Quality::Precise);
    const float rate = GENERATE(30.0f, 10.0f, 1.0f);
    const bool game = quality == Quality::Game;
    INFO((game ? "game" : "precise") << " at " << rate << " Hz");
    // The Dam break level's column (0.15 x 0.3 m in a 0.6 x 0.5 m tank), 10 s.
    WorldDef def = physicsDef();
    def.positionBased = positionBasedPreset(quality);
    World world(def);
    const MaterialId water = world.addMaterial(fluid::water());
    world.addForce(std::make_unique<GravityForce>(0.0f, -kG));
    world.addBoundary(std::make_unique<BoxContainer>(0.0f, 0.0f, 0.6f, 0.5f));
    BlobDef column;
    column.shape.type = ShapeType::Rectangle;
    column.shape.center = {0.075f, 0.15f};
    column.shape.halfExtents = {0.075f, 0.15f};
    column.material = water;
    world.spawnBlob(column);
    const int frames = int(10.0f * rate);
    float worst = 0.0f; // largest compression over the second half
    for (int f = 0; f < frames; ++f) {
        world.step(1.0f / rate);
        REQUIRE(allFinite(world));
        if (f >= frames / 2) {
            worst = std::max(worst, world.profile().densityErrorMax);
        }
    }
    std::printf("[measure] %s at %.0f Hz: %u sub-steps per frame, largest compression over the "
                "last 5 s %.4f\n",
                game ? "game" : "precise", double(rate), world.profile().substeps, double(worst));
    // The long-frame rule: the preset's sub-steps per 1/60 s whatever the frame
    // (docs/position_based.md, "One step").
    CHECK(world.profile().substeps ==
          uint32_t(std::lround(float(def.positionBased.substeps) * 60.0f / rate)));
    CHECK(worst <= (game ? 0.1f : 0.01f));
    CHECK(countOutside(world, 0.0f, 0.0f, 0.6f, 0.5f) == 0);
}
