// Invariants in zero gravity without boundaries: total momentum and mass are conserved (every
// pair force is antisymmetric once multiplied by the masses).
#include "test_support.h"

#include <catch2/catch.hpp>

#include <random>

using namespace fluid;
using namespace fluid::test;

namespace {

// Adds seeded random internal velocities (each component uniform in [-0.3, 0.3] m/s) to every
// particle of `material`.
void stir(World& world, int material, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-0.3f, 0.3f);
    const auto mat = world.materialIndex();
    for (uint32_t i = 0; i < world.particleCount(); ++i) {
        if (mat[i] != material) {
            continue;
        }
        const ParticleHandle h = world.handleAt(i);
        const glm::vec2 v = world.velocity(h);
        world.setVelocity(h, {v.x + u(rng), v.y + u(rng)});
    }
}

struct Drift {
    double worst = 0.0; // max over checkpoints of |P - P0| / scale
    double atEnd = 0.0;
};

Drift runSteps(World& world, int steps, double scale) {
    const glm::dvec2 p0 = momentum(world);
    Drift d;
    for (int s = 1; s <= steps; ++s) {
        world.step(kFrame);
        if (s % 50 == 0 || s == steps) {
            const glm::dvec2 p = momentum(world);
            const double e = std::hypot(p.x - p0.x, p.y - p0.y) / scale;
            d.worst = std::max(d.worst, e);
            d.atEnd = e;
            INFO("step " << s << ": P = (" << p.x << ", " << p.y << "), drift " << e);
            REQUIRE(allFinite(world));
        }
    }
    return d;
}

// Two discs of `radius` (m) at (-x, y) and (x, -y), of materials `a` and `b`, moving towards
// each other at `va` and `vb` (m/s, along x); returns the particles spawned.
uint32_t spawnPair(World& world, MaterialId a, MaterialId b, float x, float y, float radius,
                   float va, float vb) {
    BlobDef left;
    left.shape.type = ShapeType::Circle;
    left.shape.center = {-x, y};
    left.shape.radius = radius;
    left.velocity = {va, 0.0f};
    left.material = a;
    BlobDef right = left;
    right.shape.center = {x, -y};
    right.velocity = {vb, 0.0f};
    right.material = b;
    return world.spawnBlob(left) + world.spawnBlob(right);
}

} // namespace

TEST_CASE("zero-g blob launched at 1 m/s keeps its momentum over 1,000 steps",
          "[slow][long][invariants][momentum]") {
    const Solver solver = GENERATE(Solver::PositionBased, Solver::Explicit);
    CAPTURE(solverLabel(solver));
    Stopwatch sw(std::string("momentum, one material, ") + solverLabel(solver));
    World world(physicsDef(solver));
    const MaterialId w = world.addMaterial(water());
    BlobDef blob;
    blob.shape.type = ShapeType::Circle;
    blob.shape.radius = 0.125f;
    blob.velocity = {1.0f, 0.0f};
    blob.material = w;
    const uint32_t n = world.spawnBlob(blob);
    REQUIRE(n >= 400);
    REQUIRE(n <= 600);
    stir(world, w.index, 2024);
    const double mass0 = totalMass(world);
    const glm::dvec2 p0 = momentum(world);
    const double scale = std::hypot(p0.x, p0.y);
    REQUIRE(scale == Approx(mass0).epsilon(0.05)); // about M * 1 m/s

    const Drift d = runSteps(world, 1000, scale);
    const glm::dvec2 p = momentum(world);
    CAPTURE(n, p0.x, p0.y, p.x, p.y, d.worst, d.atEnd, world.lastSubsteps());
    std::printf("[measure] %s momentum one material: n %u, relative drift max %.3g, end %.3g\n",
                solverLabel(solver), n, d.worst, d.atEnd);
    CHECK(d.worst <= 1e-5);
    CHECK(world.particleCount() == n);
    CHECK(totalMass(world) == mass0);
    CHECK(world.profile().speedClamped == 0);
    // It travelled: 1,000 frames at 1 m/s.
    const Bounds b = bounds(world);
    CHECK((b.x0 + b.x1) / 2 == Approx(1000.0 / 60.0).margin(0.5));
}

TEST_CASE("zero-g water and yoghurt blobs collide and keep their momentum over 1,000 steps",
          "[slow][long][invariants][momentum]") {
    const Solver solver = GENERATE(Solver::PositionBased, Solver::Explicit);
    CAPTURE(solverLabel(solver));
    Stopwatch sw(std::string("momentum, two materials, ") + solverLabel(solver));
    World world(physicsDef(solver));
    const MaterialId w = world.addMaterial(water());
    const MaterialId y = world.addMaterial(forSolver(yoghurt(), solver));
    const uint32_t n = spawnPair(world, w, y, 0.12f, 0.02f, 0.08f, 1.0f, -0.3f);
    stir(world, w.index, 7);
    stir(world, y.index, 8);
    const double mass0 = totalMass(world);
    const glm::dvec2 p0 = momentum(world);
    // Scale: the momentum each blob carries (the total alone is smaller, as they oppose).
    double scale = 0.0;
    {
        const auto vx = world.velocityX();
        const auto mat = world.materialIndex();
        double pw = 0.0, py = 0.0;
        for (uint32_t i = 0; i < n; ++i) {
            (mat[i] == w.index ? pw : py) += world.material(MaterialId{mat[i]}).mass * vx[i];
        }
        scale = std::max(std::fabs(pw), std::fabs(py));
        REQUIRE(std::fabs(p0.x) > 0.3 * scale);
    }
    scale = std::max(scale, std::hypot(p0.x, p0.y));

    // They meet after about 0.1 s and travel on as one merged blob.
    const Drift d = runSteps(world, 1000, scale);
    const glm::dvec2 p = momentum(world);
    CAPTURE(n, p0.x, p0.y, p.x, p.y, scale, d.worst, d.atEnd);
    std::printf("[measure] %s momentum two materials: n %u, relative drift max %.3g, end %.3g\n",
                solverLabel(solver), n, d.worst, d.atEnd);
    CHECK(d.worst <= 1e-5);
    CHECK(world.particleCount() == n);
    CHECK(totalMass(world) == mass0);
    // They did collide: the water's x velocity is no longer 1 m/s on average.
    const auto vx = world.velocityX();
    const auto mat = world.materialIndex();
    double sum = 0.0;
    uint32_t count = 0;
    for (uint32_t i = 0; i < n; ++i) {
        if (mat[i] == w.index) {
            sum += vx[i];
            ++count;
        }
    }
    CHECK(sum / count < 0.8);
}

// Two blobs meeting head on at 10 m/s (each at 5 m/s), zero gravity, no walls: the sweeps and
// the viscosity act in pairs and the coarse solve's moves sum to zero where no wall is in reach,
// so the total momentum stays within 1e-3 of the sum of |m v| over 2 s, with both presets, water
// against water and against yoghurt. The precise preset with yoghurt is held to 1.2e-3: the
// impact loses a little where neighbours are found from one side and where the correction
// limit clips (1.06e-3 with the blob on the lattice, 1.17e-3 with it filled in rings;
// docs/position_based_method.md, "Coarse correction").
TEST_CASE("zero-g blobs meeting at 10 m/s keep their momentum, game and precise presets",
          "[slow][invariants][momentum]") {
    const Quality quality = GENERATE(Quality::Game, Quality::Precise);
    const bool yoghurtToo = GENERATE(false, true);
    const char* name = quality == Quality::Game ? "game" : "precise";
    CAPTURE(name, yoghurtToo);
    WorldDef def = physicsDef();
    def.positionBased = positionBasedPreset(quality);
    World world(def);
    const MaterialId w = world.addMaterial(water());
    const MaterialId other = yoghurtToo ? world.addMaterial(yoghurt()) : w;
    spawnPair(world, w, other, 0.15f, 0.01f, 0.1f, 5.0f, -5.0f);
    double scale = 0.0; // sum of |m v| at the start
    {
        const auto vx = world.velocityX(), vy = world.velocityY();
        const auto mat = world.materialIndex();
        for (uint32_t i = 0; i < world.particleCount(); ++i) {
            scale += world.material(MaterialId{mat[i]}).mass * std::hypot(vx[i], vy[i]);
        }
    }
    const glm::dvec2 p0 = momentum(world);
    double worst = 0.0;
    for (int f = 0; f < 120; ++f) {
        world.step(kFrame);
        const glm::dvec2 p = momentum(world);
        worst = std::max(worst, std::hypot(p.x - p0.x, p.y - p0.y) / scale);
        REQUIRE(allFinite(world));
    }
    std::printf("[measure] momentum, blobs meeting at 10 m/s, %s, %s: %u particles, largest "
                "change %.3g of the sum of |m v| (%.3f kg m/s)\n",
                name, yoghurtToo ? "water and yoghurt" : "water", world.particleCount(), worst,
                scale);
    CHECK(worst <= (quality == Quality::Precise && yoghurtToo ? 1.2e-3 : 1e-3));
}

// The coarse solve's momentum correction (no wall in reach) sums over the particles in fixed
// blocks: the same bits for 1, 2 and 4 workers.
TEST_CASE("zero-g blobs meeting at 10 m/s, game preset: the same bits for 1, 2 and 4 workers",
          "[slow][invariants][momentum][determinism]") {
    std::vector<uint64_t> hashes;
    for (const uint32_t workers : {1u, 2u, 4u}) {
        WorldDef def;
        def.workerCount = workers;
        def.positionBased = positionBasedPreset(Quality::Game);
        World world(def);
        const MaterialId w = world.addMaterial(water());
        spawnPair(world, w, w, 0.15f, 0.01f, 0.1f, 5.0f, -5.0f);
        for (int f = 0; f < 60; ++f) {
            world.step(kFrame);
        }
        hashes.push_back(stateHash(world));
    }
    CHECK(hashes[0] == hashes[1]);
    CHECK(hashes[0] == hashes[2]);
}
