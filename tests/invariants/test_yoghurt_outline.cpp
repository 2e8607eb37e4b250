// A yoghurt drop at rest in zero gravity keeps a round outline (issue 67): a paste keeps the
// outline it starts with, and its circles start in rings (docs/yield_stress.md, "A round
// outline"). Two drops apart each keep their momentum (docs/position_based_method.md, "Coarse
// correction").
#include "test_support.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace fluid;
using namespace fluid::test;

namespace {

// The outline of the particles of `material` around their centroid: per 10-degree bin the
// farthest particle's distance (m); its range over the bins and the RMS of each bin against
// the mean of the three bins either side of it (the bumps a few spacings wide and under).
struct Outline {
    float lo = 0.0f, hi = 0.0f; // least and largest bin (m)
    double noise = 0.0;         // m
    double cx = 0.0, cy = 0.0;  // centroid (m)
};

Outline outlineOf(const World& world, MaterialId material) {
    const auto px = world.positionX(), py = world.positionY();
    const auto mat = world.materialIndex();
    Outline o;
    uint32_t n = 0;
    for (uint32_t i = 0; i < world.particleCount(); ++i) {
        if (mat[i] == material.index) {
            o.cx += px[i];
            o.cy += py[i];
            ++n;
        }
    }
    o.cx /= n;
    o.cy /= n;
    constexpr int kBins = 36;
    std::vector<float> far(kBins, 0.0f);
    for (uint32_t i = 0; i < world.particleCount(); ++i) {
        if (mat[i] == material.index) {
            const double dx = px[i] - o.cx, dy = py[i] - o.cy;
            const int bin = int((std::atan2(dy, dx) + M_PI) / (2.0 * M_PI) * kBins) % kBins;
            far[size_t(bin)] = std::max(far[size_t(bin)], float(std::hypot(dx, dy)));
        }
    }
    const auto [lo, hi] = std::minmax_element(far.begin(), far.end());
    o.lo = *lo;
    o.hi = *hi;
    double sum = 0.0;
    for (int b = 0; b < kBins; ++b) {
        double mean = 0.0;
        for (int d = -3; d <= 3; ++d) {
            mean += far[size_t((b + d + kBins) % kBins)];
        }
        mean /= 7.0;
        sum += (far[size_t(b)] - mean) * (far[size_t(b)] - mean);
    }
    o.noise = std::sqrt(sum / kBins);
    return o;
}

} // namespace

TEST_CASE("a yoghurt drop at rest in zero gravity keeps a round outline, as smooth as a water "
          "drop's, and neither drop drifts",
          "[slow][invariants][materials][yield]") {
    Stopwatch sw("yoghurt outline");
    World world(physicsDef()); // the game preset, no forces: zero gravity
    const MaterialId w = world.addMaterial(water());
    const MaterialId y = world.addMaterial(yoghurt());
    BlobDef drop;
    drop.shape = Shape::circle({-0.15f, 0.0f}, 0.08f);
    drop.material = w;
    world.spawnBlob(drop);
    drop.shape = Shape::circle({0.15f, 0.0f}, 0.08f);
    drop.material = y;
    world.spawnBlob(drop);
    const float s = world.spacing(y);
    const Outline start = outlineOf(world, y), waterStart = outlineOf(world, w);
    for (int frame = 0; frame < 5 * 60; ++frame) {
        world.step(kFrame);
        REQUIRE(allFinite(world));
    }
    const Outline water = outlineOf(world, w), paste = outlineOf(world, y);
    std::printf("[measure] resting drops of 8 cm after 5 s in zero gravity, outline per 10-degree "
                "bin: water %.4f-%.4f m, noise %.5f m; yoghurt %.4f-%.4f m, noise %.5f m "
                "(spacing %.4f m); the centres moved: yoghurt %.5f m, water %.5f m\n",
                double(water.lo), double(water.hi), water.noise, double(paste.lo), double(paste.hi),
                paste.noise, double(s), std::hypot(paste.cx - start.cx, paste.cy - start.cy),
                std::hypot(water.cx - waterStart.cx, water.cy - waterStart.cy));
    // Round: its outline within a quarter spacing all round, its bumps no larger than the
    // water drop's (which surface tension rounds).
    CHECK(paste.hi - paste.lo <= 0.25f * s);
    CHECK(paste.noise <= std::max(water.noise, 0.05 * double(s)));
    // Both at rest where they were put: the coarse correction keeps each drop's momentum on its
    // own (before, kept for the two together, it pushed them apart, 1.2 cm each in 5 s).
    CHECK(std::hypot(paste.cx - start.cx, paste.cy - start.cy) < 0.01 * double(s));
    CHECK(std::hypot(water.cx - waterStart.cx, water.cy - waterStart.cy) < 0.01 * double(s));
}
