// Surface tension pulls a zero-g square blob of 2,000 water particles round within 3 s.
#include "test_support.h"

#include <catch2/catch.hpp>

using namespace fluid;
using namespace fluid::test;

TEST_CASE("zero-g square blob of 2,000 particles pulls round in 3 s",
          "[slow][invariants][surface-tension]") {
    const Solver solver = GENERATE(Solver::PositionBased, Solver::Explicit);
    CAPTURE(solverLabel(solver));
    Stopwatch sw(std::string("zero-g square blob 3 s, ") + solverLabel(solver));
    World world(physicsDef(solver)); // no gravity, no walls; Tait with the scene's sound speed
    const MaterialId w = world.addMaterial(water());
    const float s = world.spacing(w);
    const uint32_t side = 45; // 2,025 particles
    REQUIRE(world.spawnBlob(latticeBlock(world, w, -0.5f * side * s, -0.5f * side * s, side,
                                         side)) == side * side);
    const double area0 = double(side * s) * double(side * s);
    const double radius = std::sqrt(area0 / 3.14159265358979);

    auto measure = [&](double& circularity, double& farthest) {
        std::vector<glm::dvec2> pts;
        glm::dvec2 com{0.0, 0.0};
        for (const glm::vec2 p : positions(world)) {
            pts.emplace_back(p.x, p.y);
            com += glm::dvec2(p.x, p.y);
        }
        com /= double(pts.size());
        const std::vector<glm::dvec2> hull = convexHull(pts);
        const double a = polygonArea(hull), l = polygonPerimeter(hull);
        circularity = 4.0 * 3.14159265358979 * a / (l * l);
        farthest = 0.0;
        for (const glm::dvec2 p : pts) {
            farthest = std::max(farthest, std::hypot(p.x - com.x, p.y - com.y));
        }
    };
    double c0 = 0.0, f0 = 0.0;
    measure(c0, f0);
    CHECK(c0 < 0.8); // a square: pi/4

    double c1 = 0.0, f1 = 0.0;
    for (int frame = 1; frame <= 60; ++frame) {
        world.step(kFrame);
    }
    measure(c1, f1);
    for (int frame = 61; frame <= 180; ++frame) {
        world.step(kFrame);
        REQUIRE(allFinite(world));
    }
    double c3 = 0.0, f3 = 0.0;
    measure(c3, f3);
    CAPTURE(c0, c1, c3, f3, radius, f3 / radius, world.lastSubsteps());
    std::printf("[measure] %s zero-g blob: circularity %.4f -> %.4f (1 s) -> %.4f (3 s), farthest "
                "%.3f R, substeps/frame %u\n",
                solverLabel(solver), c0, c1, c3, f3 / radius, world.lastSubsteps());
    CHECK(c3 >= 0.95);
    CHECK(f3 <= 1.5 * radius);
    // Momentum of a blob at rest stays zero: it does not drift off.
    const Bounds b = bounds(world);
    CHECK((b.x0 + b.x1) / 2 == Approx(0.0).margin(0.02));
    CHECK((b.y0 + b.y1) / 2 == Approx(0.0).margin(0.02));
}
