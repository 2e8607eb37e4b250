// Neighbour grid (fluid/src/grid.h): queries equal brute force in dense and hashed mode, cell
// borders and negative coordinates included; the counting sort is stable.
#include "grid.h"

#include <fluid/task.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <vector>

namespace {

struct Points {
    std::vector<float> x, y;
    void add(float px, float py) {
        x.push_back(px);
        y.push_back(py);
    }
    size_t size() const { return x.size(); }
};

// ~2000 points: random ones around the origin (negative coordinates included), points exactly
// on cell borders (multiples of the cell size, both axes and one), and pairs exactly one cell
// size apart across a border.
Points makePoints(float cell, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-0.3f, 0.2f);
    std::uniform_int_distribution<int> k(-9, 5);
    Points p;
    // x is drawn in a statement of its own: the order a call's arguments are evaluated in is
    // the compiler's, and g++ and clang would make different points.
    for (int i = 0; i < 1400; ++i) {
        const float x = u(rng);
        p.add(x, u(rng));
    }
    for (int i = 0; i < 200; ++i) {
        const float vx = float(k(rng)) * cell;
        p.add(vx, u(rng)); // on a vertical border
        const float hx = u(rng);
        p.add(hx, float(k(rng)) * cell); // on a horizontal border
        const float cx = float(k(rng)) * cell;
        p.add(cx, float(k(rng)) * cell); // on a corner
    }
    for (int i = 0; i < 100; ++i) {
        const int c = k(rng);
        const float y = u(rng);
        p.add(float(c) * cell, y);
        p.add(float(c + 1) * cell, y); // exactly one cell size apart (to float rounding)
    }
    return p;
}

// For every point, the multiset of neighbours (r^2 < h^2, as the solver tests) found through
// the grid must equal brute force: nothing missing, nothing visited twice.
void checkAgainstBruteForce(const Points& p, float cell, const fluid::detail::Grid& grid) {
    const auto n = static_cast<uint32_t>(p.size());
    REQUIRE(grid.size() == n);
    const auto order = grid.order();
    // order() is a permutation.
    std::vector<uint32_t> sorted(order.begin(), order.end());
    std::sort(sorted.begin(), sorted.end());
    for (uint32_t i = 0; i < n; ++i) {
        REQUIRE(sorted[i] == i);
    }
    const float h2 = cell * cell;
    uint64_t pairs = 0;
    uint32_t mismatches = 0;
    std::vector<uint32_t> viaGrid, brute;
    for (uint32_t i = 0; i < n; ++i) {
        viaGrid.clear();
        brute.clear();
        grid.forEachRange(p.x[i], p.y[i], [&](uint32_t b, uint32_t e) {
            for (uint32_t k = b; k < e; ++k) {
                const uint32_t j = order[k];
                const float dx = p.x[i] - p.x[j], dy = p.y[i] - p.y[j];
                if (dx * dx + dy * dy < h2) {
                    viaGrid.push_back(j);
                }
            }
        });
        for (uint32_t j = 0; j < n; ++j) {
            const float dx = p.x[i] - p.x[j], dy = p.y[i] - p.y[j];
            if (dx * dx + dy * dy < h2) {
                brute.push_back(j);
            }
        }
        std::sort(viaGrid.begin(), viaGrid.end());
        pairs += brute.size();
        if (viaGrid != brute) {
            ++mismatches;
            if (mismatches <= 5) {
                UNSCOPED_INFO("point " << i << " at (" << p.x[i] << ", " << p.y[i] << "): grid "
                                       << viaGrid.size() << " neighbours, brute force "
                                       << brute.size());
            }
        }
    }
    CHECK(mismatches == 0);
    CHECK(pairs > 8 * uint64_t(n)); // the scene is dense enough to mean something
}

} // namespace

TEST_CASE("grid neighbours equal brute force (dense mode)", "[unit][grid]") {
    for (const float cell : {0.032f, 0.04f, 0.036f}) {
        CAPTURE(cell);
        const Points p = makePoints(cell, 7);
        fluid::detail::Grid grid;
        grid.build(p.x, p.y, cell, fluid::TaskHook{});
        REQUIRE_FALSE(grid.hashed());
        checkAgainstBruteForce(p, cell, grid);
    }
}

TEST_CASE("grid neighbours equal brute force (hashed mode)", "[unit][grid]") {
    const float cell = 0.032f;
    Points p = makePoints(cell, 11);
    // A few far-flung points make the bounding box far too sparse for dense cells.
    p.add(1e5f, 3.0f);
    p.add(1e5f + 0.01f, 3.0f); // a neighbour of the far point
    p.add(-2.5e4f, -7e4f);
    p.add(0.0f, 5e4f);
    fluid::detail::Grid grid;
    grid.build(p.x, p.y, cell, fluid::TaskHook{});
    REQUIRE(grid.hashed());
    checkAgainstBruteForce(p, cell, grid);
}

TEST_CASE("grid build is the same with a thread pool", "[unit][grid]") {
    // Above the grid's 4096-point grain the keys are computed in parallel.
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-2.0f, 2.0f);
    Points p;
    for (int i = 0; i < 12000; ++i) {
        const float x = u(rng);
        p.add(x, u(rng));
    }
    fluid::detail::Grid serial, pooled;
    serial.build(p.x, p.y, 0.04f, fluid::TaskHook{});
    fluid::ThreadPool pool(3);
    pooled.build(p.x, p.y, 0.04f, pool.hook());
    REQUIRE(serial.hashed() == pooled.hashed());
    const auto a = serial.order(), b = pooled.order();
    REQUIRE(std::equal(a.begin(), a.end(), b.begin(), b.end()));
}

TEST_CASE("grid counting sort is stable", "[unit][grid]") {
    // Many points per cell, in random input order: along every cell's (or bucket's) range of
    // sorted positions the input indices must increase.
    const float cell = 0.04f;
    std::mt19937 rng(99);
    std::uniform_real_distribution<float> u(-0.25f, 0.25f);
    Points p;
    for (int i = 0; i < 3000; ++i) {
        const float x = u(rng);
        p.add(x, u(rng));
    }
    for (const bool hashed : {false, true}) {
        CAPTURE(hashed);
        Points q = p;
        if (hashed) {
            q.add(1e5f, 1e5f);
        }
        fluid::detail::Grid grid;
        grid.build(q.x, q.y, cell, fluid::TaskHook{});
        REQUIRE(grid.hashed() == hashed);
        const auto order = grid.order();
        const fluid::detail::GridView& v = grid.view();
        const size_t cells = hashed ? size_t(v.mask) + 1 : size_t(v.nx) * v.ny;
        REQUIRE(v.start[cells] == q.size());
        uint32_t violations = 0, shared = 0;
        for (size_t c = 0; c < cells; ++c) {
            for (uint32_t k = v.start[c] + 1; k < v.start[c + 1]; ++k) {
                ++shared;
                violations += order[k] > order[k - 1] ? 0 : 1;
            }
        }
        CHECK(shared > 1000); // many cells hold several points
        CHECK(violations == 0);
    }
}

TEST_CASE("grid cells are narrower than the query radius, and a query skips the corners",
          "[unit][grid]") {
    // On a 0.01 m lattice (the solver's spacing for a 0.04 m support: ~36 neighbours), a
    // query's ranges hold well under the 3x3 cells of one radius (~144 points): the rows are
    // R / GridLayout::subY high and clipped to the circle. Every neighbour is still found (see the
    // brute-force tests above); this checks that the clipping does its job.
    const float cell = 0.04f;
    Points p;
    for (int i = 0; i < 60; ++i) {
        for (int j = 0; j < 60; ++j) {
            p.add(0.005f + 0.01f * float(i), 0.005f + 0.01f * float(j));
        }
    }
    fluid::detail::Grid grid;
    grid.build(p.x, p.y, cell, fluid::TaskHook{});
    REQUIRE_FALSE(grid.hashed());
    uint64_t candidates = 0, queries = 0;
    for (size_t i = 0; i < p.size(); ++i) {
        if (p.x[i] < 0.1f || p.x[i] > 0.5f || p.y[i] < 0.1f || p.y[i] > 0.5f) {
            continue; // interior points only
        }
        ++queries;
        grid.forEachRange(p.x[i], p.y[i], [&](uint32_t b, uint32_t e) { candidates += e - b; });
    }
    REQUIRE(queries > 1000);
    const double perQuery = double(candidates) / double(queries);
    CHECK(perQuery < 0.7 * 144.0);
    CHECK(perQuery > 3.14159 * 16.0); // at least the circle's own ~50 points
}

TEST_CASE("grid handles empty input and a single point", "[unit][grid]") {
    fluid::detail::Grid grid;
    std::vector<float> none;
    grid.build(none, none, 0.04f, fluid::TaskHook{});
    CHECK(grid.size() == 0);
    int calls = 0;
    grid.forEachRange(0.0f, 0.0f, [&](uint32_t, uint32_t) { ++calls; });
    CHECK(calls == 0);
    std::vector<float> x{-3.0f}, y{2.0f};
    grid.build(x, y, 0.04f, fluid::TaskHook{});
    uint32_t found = 0;
    grid.forEachRange(-3.0f, 2.0f, [&](uint32_t b, uint32_t e) { found += e - b; });
    CHECK(found == 1);
    found = 0;
    grid.forEachRange(5.0f, 5.0f, [&](uint32_t b, uint32_t e) { found += e - b; });
    CHECK(found == 0);
}
