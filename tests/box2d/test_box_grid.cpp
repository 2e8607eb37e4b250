// fluid::box2d's BoxGrid (plugins/box2d/src/body_boundary.h): the bodies' sweep boxes each
// particle's projection asks about. Its visits must be exactly the boxes that meet the query, each
// once and in box order, whatever cells the query spans: the projection runs the colliders in the
// order visited, so the order is part of the bits.
#include "../../plugins/box2d/src/body_boundary.h"

#include <catch2/catch.hpp>

#include <cstdint>
#include <random>
#include <vector>

namespace {

using fluid::box2d::Box;
using fluid::box2d::BoxGrid;

// The boxes that meet `query`, in box order: what BoxGrid::forEach must visit.
std::vector<uint32_t> bruteForce(const std::vector<Box>& boxes, const Box& query) {
    std::vector<uint32_t> out;
    for (uint32_t k = 0; k < boxes.size(); ++k) {
        if (boxes[k].overlaps(query)) {
            out.push_back(k);
        }
    }
    return out;
}

} // namespace

TEST_CASE("BoxGrid visits every box that meets a query, once each, in box order", "[box2d][grid]") {
    std::mt19937 rng(20261130);
    std::uniform_real_distribution<float> at(-1.0f, 1.0f), size(0.0f, 0.3f);
    // Queries from a point to 0.4 m: within one cell, across two to four of 0.05 m, and more.
    std::uniform_real_distribution<float> reach(0.0f, 0.4f);
    for (const float cellSize : {0.05f, 0.1f, 1.0f}) {
        for (const int count : {1, 7, 60}) {
            std::vector<Box> boxes;
            for (int k = 0; k < count; ++k) {
                const float x = at(rng), y = at(rng);
                boxes.push_back({x, y, x + size(rng), y + size(rng)});
            }
            BoxGrid grid;
            grid.build(boxes, cellSize);
            uint32_t spanning = 0, met = 0;
            for (int q = 0; q < 2000; ++q) {
                const float x = 1.2f * at(rng), y = 1.2f * at(rng);
                const float w = q % 4 == 0 ? 0.0f : reach(rng) * reach(rng);
                const float h = q % 4 == 0 ? 0.0f : reach(rng) * reach(rng);
                const Box query{x, y, x + w, y + h};
                std::vector<uint32_t> visited;
                grid.forEach(query, boxes, [&](uint32_t k) { visited.push_back(k); });
                const std::vector<uint32_t> expected = bruteForce(boxes, query);
                CAPTURE(cellSize, count, q, query.loX, query.loY, query.hiX, query.hiY);
                REQUIRE(visited == expected);
                spanning += w > cellSize || h > cellSize ? 1 : 0;
                met += expected.empty() ? 0 : 1;
            }
            // The draw did what the test is for: queries that met boxes, and with the small
            // cells queries across several.
            CHECK(met > 0);
            if (cellSize < 0.5f) {
                CHECK(spanning > 100);
            }
        }
    }
}
