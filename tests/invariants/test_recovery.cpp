// Recovery from stacked particles: a world knocked into coincident or crushed particles (blobs
// spawned on top of each other, one long frame, a tank moved away in one frame) parts them and
// comes back to its preset's compression within a second, for either preset.
#include "compression.h"
#include "test_support.h"

#include <catch2/catch.hpp>

#include <memory>
#include <string>

using namespace fluid;
using namespace fluid::test;

namespace {

enum class Knock { OverlappingBlobs, OneSecondFrame, TankMovedTenMetres };

const char* knockName(Knock k) {
    switch (k) {
    case Knock::OverlappingBlobs: return "the same block spawned twice";
    case Knock::OneSecondFrame: return "one step(1.0)";
    case Knock::TankMovedTenMetres: return "the tank moved 10 m in one frame";
    }
    return "?";
}

// A 0.3 x 0.3 m block of water in a 0.5 x 0.6 m tank, with the preset's settings.
World tank(Quality quality, BlobDef& block) {
    WorldDef def = physicsDef();
    def.positionBased = positionBasedPreset(quality);
    World world(def);
    const MaterialId water = world.addMaterial(fluid::water());
    world.addForce(std::make_unique<GravityForce>(0.0f, -kG));
    world.addBoundary(std::make_unique<BoxContainer>(0.0f, 0.0f, 0.5f, 0.6f));
    block.shape.type = ShapeType::Rectangle;
    block.shape.center = {0.15f, 0.15f};
    block.shape.halfExtents = {0.15f, 0.15f};
    block.material = water;
    world.spawnBlob(block);
    return world;
}

} // namespace

TEST_CASE("stacked or crushed particles part, and the world recovers within a second",
          "[invariants][slow][stacked]") {
    const Quality quality = GENERATE(Quality::Game, Quality::Precise);
    const Knock knock =
        GENERATE(Knock::OverlappingBlobs, Knock::OneSecondFrame, Knock::TankMovedTenMetres);
    const bool game = quality == Quality::Game;
    INFO((game ? "game" : "precise") << ", " << knockName(knock));
    BlobDef block;
    World world = tank(quality, block);
    float shiftX = 0.0f; // where the tank is at the end
    switch (knock) {
    case Knock::OverlappingBlobs:
        world.spawnBlob(block); // every particle on top of another
        REQUIRE(bench::stackedIndices(world.positionX(), world.positionY()).size() ==
                world.particleCount()); // each particle on one other
        world.step(kFrame);
        break;
    case Knock::OneSecondFrame:
        world.step(1.0f); // the longest frame a step allows
        break;
    case Knock::TankMovedTenMetres:
        for (int f = 0; f < 30; ++f) {
            world.step(kFrame);
        }
        world.boundaries()[0]->setParam("minX", 10.0);
        world.boundaries()[0]->setParam("maxX", 10.5);
        shiftX = 10.0f;
        world.step(kFrame);
        break;
    }
    // A second later: nothing stacked, nothing outside, the compression back near the
    // preset's own in a sloshing tank (before the parting: 361 pairs stacked after 1,200
    // frames, 336% for 20 s, or 1,700% for good).
    uint32_t stackedLast = 0;
    for (int f = 0; f < 60; ++f) {
        world.step(kFrame);
        stackedLast = uint32_t(bench::stackedIndices(world.positionX(), world.positionY()).size());
        REQUIRE(allFinite(world));
    }
    const float largest = world.profile().densityErrorMax;
    std::printf("[measure] %s, %s: after 1 s %u stacked, largest compression %.3f, mean %.4f\n",
                game ? "game" : "precise", knockName(knock), stackedLast, largest,
                world.profile().densityErrorAvg);
    CHECK(stackedLast == 0);
    CHECK(countOutside(world, shiftX, 0.0f, shiftX + 0.5f, 0.6f) == 0);
    CHECK(largest <= (game ? 0.4f : 0.05f));
}
