// Blobs leave out the lattice points inside solids: BoundaryPlugin::contains for the built-in
// boundaries (circle, polygon at its pose, box container: outside it; chain: nothing), and
// World::spawnBlob's count of the points left out.
#include "test_support.h"

#include <fluid/plugins/boundaries.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

using namespace fluid;
using namespace fluid::test;

TEST_CASE("built-in boundaries say which points lie in their solid", "[boundaries][blobs]") {
    CircleBoundary circle({1.0f, 1.0f}, 0.2f);
    CHECK(circle.contains({1.1f, 1.0f}));
    CHECK_FALSE(circle.contains({1.25f, 1.0f}));
    circle.setPose({2.0f, 1.0f}, 0.0f); // moved: the test follows the pose, before any step
    CHECK_FALSE(circle.contains({1.1f, 1.0f}));
    CHECK(circle.contains({2.1f, 1.0f}));

    const std::vector<glm::vec2> ell{{0, 0}, {0.4f, 0}, {0.4f, 0.1f}, {0.1f, 0.1f},
                                     {0.1f, 0.4f}, {0, 0.4f}};
    PolygonBoundary polygon(ell);
    CHECK(polygon.contains({0.05f, 0.3f}));
    CHECK(polygon.contains({0.3f, 0.05f}));
    CHECK_FALSE(polygon.contains({0.3f, 0.3f})); // the notch of the L
    polygon.setPose({1.0f, 0.0f}, float(M_PI / 2)); // turned a quarter about its origin
    CHECK(polygon.contains({0.95f, 0.3f}));
    CHECK_FALSE(polygon.contains({0.05f, 0.3f}));

    BoxContainer box;
    box.setParam("minX", 0.0);
    box.setParam("maxX", 1.0);
    box.setParam("maxY", 1.0);
    CHECK_FALSE(box.contains({0.5f, 0.5f}));
    CHECK(box.contains({-0.01f, 0.5f}));
    CHECK(box.contains({0.5f, 1.01f}));
    box.setParam("openTop", 1.0);
    CHECK_FALSE(box.contains({0.5f, 1.01f}));

    ChainBoundary chain(std::vector<glm::vec2>{{0, 0}, {1, 0}, {1, 1}}, false);
    CHECK_FALSE(chain.contains({0.9f, 0.1f})); // a wall has no inside
}

TEST_CASE("spawnBlob leaves out the lattice points inside solids and outside the container",
          "[boundaries][blobs]") {
    for (const Solver solver : {Solver::PositionBased, Solver::Explicit}) {
        INFO(solverLabel(solver));
        World world(physicsDef(solver));
        const MaterialId water = world.addMaterial(fluid::water());
        auto box = std::make_unique<BoxContainer>();
        box->setParam("minX", 0.0);
        box->setParam("maxX", 0.5);
        box->setParam("maxY", 0.5);
        world.addBoundary(std::move(box));
        world.addBoundary(std::make_unique<CircleBoundary>(glm::vec2(0.25f, 0.15f), 0.06f));

        BlobDef blob;
        blob.material = water;
        blob.shape.center = {0.25f, 0.15f};
        blob.shape.halfExtents = {0.15f, 0.1f};
        uint32_t inside = 0;
        const uint32_t added = world.spawnBlob(blob, &inside);
        const float s = world.spacing(water);
        // About the disc's area in lattice cells is left out.
        const double discPoints = M_PI * 0.06 * 0.06 / (double(s) * s);
        CHECK(inside == Approx(discPoints).epsilon(0.1));
        CHECK(added + inside == uint32_t(std::floor(0.3 / s)) * uint32_t(std::floor(0.2 / s)));
        for (uint32_t i = 0; i < world.particleCount(); ++i) {
            const float dx = world.positionX()[i] - 0.25f, dy = world.positionY()[i] - 0.15f;
            CHECK(dx * dx + dy * dy >= 0.06f * 0.06f);
        }

        // Half over the tank's right wall: the outer half is left out.
        BlobDef over = blob;
        over.shape.center = {0.5f, 0.4f};
        over.shape.halfExtents = {0.05f, 0.05f};
        uint32_t outside = 0;
        const uint32_t kept = world.spawnBlob(over, &outside);
        CHECK(kept == Approx(outside).margin(uint32_t(0.1f / s) + 1));
        CHECK(outside > 0);

        // Wholly inside the disc: nothing added, every point counted.
        BlobDef buried = blob;
        buried.shape.halfExtents = {0.03f, 0.03f};
        uint32_t all = 0;
        CHECK(world.spawnBlob(buried, &all) == 0);
        CHECK(all > 0);

        // The first frames: nobody is thrown out of a solid (free fall alone reaches 0.8 m/s).
        float fastest = 0.0f;
        for (int f = 0; f < 5; ++f) {
            world.step(1.0f / 60.0f);
            for (uint32_t i = 0; i < world.particleCount(); ++i) {
                fastest = std::max(fastest, std::hypot(world.velocityX()[i], world.velocityY()[i]));
            }
        }
        INFO("fastest " << fastest << " m/s");
        CHECK(fastest < 1.5f);
    }
}
