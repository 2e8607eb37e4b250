// fluid tests — a world's steps depend only on the materials its particles have: a material
// registered for later (a level's yoghurt before its first blob) changes no bit of a water dam,
// whatever its index (the boundary samples lie on the first present material's lattice, the
// grid, the coarse cells and the viscosity's passes follow the present materials).
#include "test_support.h"

#include <catch2/catch.hpp>

using namespace fluid;
using namespace fluid::test;

namespace {

// A 20 x 20 water block at the left wall of a box 4 blocks wide, gravity, `frames` frames.
// `before` and `after`: materials registered before and after water, no particle of theirs.
uint64_t damHash(const WorldDef& def, const std::vector<Material>& before,
                 const std::vector<Material>& after, int frames) {
    World world(def);
    for (const Material& m : before) {
        world.addMaterial(m);
    }
    const MaterialId water = world.addMaterial(forSolver(fluid::water(), def.solver));
    for (const Material& m : after) {
        world.addMaterial(m);
    }
    const float s = world.spacing(water);
    world.addForce(std::make_unique<GravityForce>(0.0f, -kG));
    world.addBoundary(std::make_unique<BoxContainer>(0.0f, 0.0f, 80.0f * s, 40.0f * s));
    world.spawnBlob(latticeBlock(world, water, 0.0f, 0.0f, 20, 20));
    for (int f = 0; f < frames; ++f) {
        world.step(kFrame);
    }
    REQUIRE(allFinite(world));
    return stateHash(world);
}

} // namespace

TEST_CASE("a registered material no particle has changes no bit of a step", "[determinism]") {
    struct Setting {
        const char* name;
        WorldDef def;
        int frames;
        std::vector<Material> others;
    };
    WorldDef game, precise, explicitSolver;
    game.positionBased = positionBasedPreset(Quality::Game);
    precise.positionBased = positionBasedPreset(Quality::Precise);
    explicitSolver.solver = Solver::Explicit;
    // Yoghurt has a larger support (0.04 m), a 6x viscosity, a yield stress and another
    // spacing; a thick syrup has 30x the viscosity.
    Material syrup = seedYoghurt();
    syrup.viscosity = 100.0f;
    const std::vector<Setting> settings = {
        {"game", game, 60, {yoghurt(), syrup}},
        {"precise", precise, 30, {yoghurt(), syrup}},
        {"explicit", explicitSolver, 4, {seedYoghurt(), syrup}},
    };
    for (const Setting& setting : settings) {
        INFO(setting.name);
        const uint64_t alone = damHash(setting.def, {}, {}, setting.frames);
        // Registered after water, and before it (water is then not material 0).
        CHECK(damHash(setting.def, {}, setting.others, setting.frames) == alone);
        CHECK(damHash(setting.def, setting.others, {}, setting.frames) == alone);
    }
}
