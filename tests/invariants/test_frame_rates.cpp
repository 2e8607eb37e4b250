// Long frames: the position-based settings are tuned for 60 Hz frames, and a longer frame is
// split into as many more sub-steps, so a level at 1-30 Hz holds its 60 Hz compression at the
// same cost per simulated second; frames of any length, varying or not, keep resting water at
// rest.
#include "test_support.h"

#include <catch2/catch.hpp>

#include <cstdio>
#include <memory>
#include <sstream>
#include <string>

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

// Frames of any length, in any sequence, keep resting water at rest: the position-based solver
// steps fixed sub-steps (1/240 s with the presets) and carries what is left of a frame, so a
// short frame no longer turns the tank's residual compression into a fast motion (figures:
// docs/position_based.md, "Frame length").
TEST_CASE("frames of any length and any sequence keep resting water at rest",
          "[invariants][slow][frames]") {
    const Quality quality = GENERATE(Quality::Game, Quality::Precise);
    const bool game = quality == Quality::Game;
    INFO((game ? "game" : "precise"));
    Registry registry;
    registerBuiltinPlugins(registry);
    // A tank 0.4 m wide with water 0.25 m deep, settled for 3 s of 60 Hz frames.
    WorldDef def = physicsDef();
    def.positionBased = positionBasedPreset(quality);
    World settled(def);
    const MaterialId water = settled.addMaterial(fluid::water());
    settled.addForce(std::make_unique<GravityForce>(0.0f, -kG));
    settled.addBoundary(std::make_unique<BoxContainer>(0.0f, 0.0f, 0.4f, 0.6f));
    const float s = settled.spacing(water);
    settled.spawnBlob(latticeBlock(settled, water, 0.5f * s, 0.5f * s,
                                   uint32_t(0.4f / s) - 1, uint32_t(0.25f / s)));
    for (int f = 0; f < 180; ++f) {
        settled.step(1.0f / 60.0f);
    }
    std::stringstream saved;
    settled.save(saved);
    const std::string bytes = saved.str();
    const auto copy = [&] {
        std::istringstream in(bytes);
        return World::load(in, registry);
    };
    // Mean kinetic energy over 2 s of simulated time, stepped with the frames `next` gives.
    const auto meanKinetic = [&](World& world, const auto& next) {
        const double start = world.time() + world.carriedTime();
        double sum = 0.0;
        int samples = 0;
        while (world.time() + world.carriedTime() < start + 2.0) {
            world.step(next());
            REQUIRE(allFinite(world));
            sum += energy(world, kG).kinetic;
            ++samples;
        }
        CHECK(countOutside(world, 0.0f, 0.0f, 0.4f, 0.6f) == 0);
        return sum / double(samples);
    };
    World fixed = copy();
    const double reference = meanKinetic(fixed, [] { return 1.0f / 60.0f; });

    World random = copy();
    uint64_t state = 12345;
    const double varying = meanKinetic(random, [&] {
        state = state * 6364136223846793005ull + 1442695040888963407ull; // LCG, fixed seed
        const double u = double(state >> 11) / double(uint64_t(1) << 53);
        return float(1.0 / 240.0 + u * (1.0 / 30.0 - 1.0 / 240.0));
    });
    World kilohertz = copy();
    const double at1000 = meanKinetic(kilohertz, [] { return 0.001f; });
    World tiny = copy();
    CHECK(tiny.carriedTime() == 0.0); // 60 Hz frames are whole sub-steps
    tiny.step(1e-6f);
    CHECK(tiny.lastSubsteps() == 0); // carried, not stepped
    CHECK(tiny.carriedTime() == Approx(1e-6).epsilon(1e-6));
    tiny.step(1e-38f);
    tiny.step(1e-4f);
    CHECK(allFinite(tiny));
    const double afterTiny = meanKinetic(tiny, [] { return 1.0f / 60.0f; });
    std::printf("[measure] resting tank, %s: mean kinetic energy over 2 s, fixed 60 Hz %.3e J, "
                "random 30-240 Hz %.3e J, 1000 Hz %.3e J, after frames of 1e-6, 1e-38 and 1e-4 s "
                "%.3e J\n",
                game ? "game" : "precise", reference, varying, at1000, afterTiny);
    CHECK(varying <= 2.0 * reference);
    CHECK(at1000 <= 2.0 * reference);
    CHECK(afterTiny <= 2.0 * reference);
}
