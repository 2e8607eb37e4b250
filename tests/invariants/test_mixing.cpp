// Several materials interact both ways: a yoghurt blob dropped into a water tank.
#include "test_support.h"

#include <catch2/catch.hpp>

using namespace fluid;
using namespace fluid::test;

namespace {

// Smallest distance between any two particles (brute force; unit: m).
float minPairDistance(const World& world) {
    const auto px = world.positionX(), py = world.positionY();
    float best2 = INFINITY;
    for (uint32_t i = 0; i < world.particleCount(); ++i) {
        for (uint32_t j = i + 1; j < world.particleCount(); ++j) {
            const float dx = px[i] - px[j], dy = py[i] - py[j];
            best2 = std::min(best2, dx * dx + dy * dy);
        }
    }
    return std::sqrt(best2);
}

struct MaterialStats {
    double comY = 0.0, vy = 0.0, speed2 = 0.0; // mean y, mean vy, mean v^2
    float minY = INFINITY, maxY = -INFINITY;
    uint32_t count = 0;
};

MaterialStats stats(const World& world, uint16_t material) {
    MaterialStats st;
    const auto py = world.positionY();
    const auto vx = world.velocityX(), vy = world.velocityY();
    const auto mat = world.materialIndex();
    for (uint32_t i = 0; i < world.particleCount(); ++i) {
        if (mat[i] != material) {
            continue;
        }
        st.comY += py[i];
        st.vy += vy[i];
        st.speed2 += double(vx[i]) * vx[i] + double(vy[i]) * vy[i];
        st.minY = std::min(st.minY, py[i]);
        st.maxY = std::max(st.maxY, py[i]);
        ++st.count;
    }
    st.comY /= st.count;
    st.vy /= st.count;
    st.speed2 /= st.count;
    return st;
}

} // namespace

TEST_CASE("a yoghurt blob dropped into water: both materials interact",
          "[slow][invariants][materials]") {
    const Solver solver = GENERATE(Solver::PositionBased, Solver::Explicit);
    CAPTURE(solverLabel(solver));
    Stopwatch sw(std::string("yoghurt into water 1.2 s, ") + solverLabel(solver));
    // The precise preset: the game preset's single sweep lets the two materials' particles come
    // closer than asked at the impact (docs/position_based.md, "Which preset").
    World world(preciseDef(solver));
    const MaterialId w = world.addMaterial(water()); // first: the walls are sampled at its spacing
    const MaterialId y = world.addMaterial(forSolver(yoghurt(), solver));
    const float s = world.spacing(w);
    const uint32_t cols = 40, rows = 20;
    const float width = float(cols) * s, depth = float(rows) * s, top = 0.5f;
    world.addForce(std::make_unique<GravityForce>(0.0f, -kG));
    world.addBoundary(std::make_unique<BoxContainer>(0.0f, 0.0f, width, top));
    world.spawnBlob(latticeBlock(world, w, 0.0f, 0.0f, cols, rows));
    // Let the water settle a little before the drop.
    for (int frame = 0; frame < 15; ++frame) {
        world.step(kFrame);
    }
    BlobDef drop;
    drop.shape.type = ShapeType::Circle;
    drop.shape.center = {0.5f * width, depth + 0.1f};
    drop.shape.radius = 0.05f;
    drop.material = y;
    const uint32_t ny = world.spawnBlob(drop);
    REQUIRE(ny > 50);
    const uint32_t n = world.particleCount();
    const double mass0 = totalMass(world);
    const MaterialStats y0 = stats(world, y.index);
    const float spacing = std::min(s, world.spacing(y));

    float closest = INFINITY;
    float peakWaterSpeed2 = 0.0f;
    double yoghurtVyAtImpact = 0.0;
    const int frames = 72; // 1.2 s
    for (int frame = 1; frame <= frames; ++frame) {
        world.step(kFrame);
        REQUIRE(allFinite(world));
        REQUIRE(countOutside(world, 0.0f, 0.0f, width, top) == 0);
        if (frame % 3 == 0) {
            closest = std::min(closest, minPairDistance(world));
        }
        const MaterialStats ws = stats(world, w.index);
        peakWaterSpeed2 = std::max(peakWaterSpeed2, float(ws.speed2));
        if (frame == 6) {
            yoghurtVyAtImpact = stats(world, y.index).vy;
        }
    }
    const MaterialStats ye = stats(world, y.index);
    const MaterialStats we = stats(world, w.index);
    const double freeFallVy = -kG * frames * kFrame;
    CAPTURE(n, ny, y0.comY, ye.comY, ye.minY, ye.maxY, ye.vy, we.maxY, depth, closest, spacing,
            std::sqrt(peakWaterSpeed2), yoghurtVyAtImpact, freeFallVy);
    std::printf("[measure] %s mixing: %u water + %u yoghurt, closest pair %.5f m (%.3f spacing), "
                "yoghurt com y %.4f -> %.4f (water surface %.4f), yoghurt min y %.4f, end vy "
                "%.4f, peak water rms speed %.3f m/s\n",
                solverLabel(solver), n - ny, ny, closest, closest / spacing, y0.comY, ye.comY,
                we.maxY, ye.minY, ye.vy, std::sqrt(peakWaterSpeed2));

    // No leaks, nothing created or lost.
    CHECK(world.particleCount() == n);
    CHECK(totalMass(world) == mass0);
    // No particle inside another: pressure keeps every pair apart.
    CHECK(closest > 0.3f * spacing);
    // Momentum exchange: the water was set moving by the impact...
    CHECK(std::sqrt(peakWaterSpeed2) > 0.05f);
    // ...and the yoghurt stopped falling (free fall would be at -11.8 m/s).
    CHECK(std::fabs(ye.vy) < 0.1);
    // The yoghurt ends up among the water: its centre below the water's free surface, above the
    // floor, and water particles above its lowest ones (it sank in, it did not bounce off or
    // fall through).
    CHECK(ye.comY < we.maxY);
    CHECK(ye.comY < y0.comY - 0.05);
    CHECK(ye.minY > 0.0f);
    CHECK(ye.minY < depth);
}
