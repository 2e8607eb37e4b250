// fluid::gl shape tessellation: triangle counts and areas (the triangles must cover the shape
// exactly once, whatever the winding).
#include <catch2/catch.hpp>
#include <fluid/gl/shapes.h>

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

using fluid::gl::ShapeBatch;
using fluid::gl::ShapeVertex;

namespace {

const glm::vec4 kWhite{1.0f, 1.0f, 1.0f, 1.0f};

double triangleArea(const ShapeVertex& a, const ShapeVertex& b, const ShapeVertex& c) {
    const double ux = double(b.position.x) - a.position.x, uy = double(b.position.y) - a.position.y;
    const double vx = double(c.position.x) - a.position.x, vy = double(c.position.y) - a.position.y;
    return 0.5 * std::abs(ux * vy - uy * vx);
}

// Sum of the triangles' unsigned areas (unit: m^2): equals the shape's area only if the
// triangles neither overlap nor leave holes.
double totalArea(const ShapeBatch& batch) {
    const auto v = batch.vertices();
    double area = 0.0;
    for (size_t i = 0; i + 2 < v.size(); i += 3) {
        area += triangleArea(v[i], v[i + 1], v[i + 2]);
    }
    return area;
}

// True when a point is covered by some triangle of the batch.
bool covered(const ShapeBatch& batch, glm::vec2 p) {
    const auto v = batch.vertices();
    for (size_t i = 0; i + 2 < v.size(); i += 3) {
        const glm::vec2 a = v[i].position, b = v[i + 1].position, c = v[i + 2].position;
        const float d1 = (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
        const float d2 = (c.x - b.x) * (p.y - b.y) - (c.y - b.y) * (p.x - b.x);
        const float d3 = (a.x - c.x) * (p.y - c.y) - (a.y - c.y) * (p.x - c.x);
        const bool hasNeg = d1 < 0 || d2 < 0 || d3<0, hasPos = d1> 0 || d2 > 0 || d3 > 0;
        if (!(hasNeg && hasPos)) {
            return true;
        }
    }
    return false;
}

} // namespace

TEST_CASE("ShapeBatch::polygon ear-clips a concave L in both windings", "[gl][shapes]") {
    // An L: 2 x 2 square minus its upper-right 1 x 1 quarter; area 3 m^2, 6 corners.
    std::vector<glm::vec2> ccw{{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
    for (int winding = 0; winding < 2; ++winding) {
        std::vector<glm::vec2> points = ccw;
        if (winding == 1) {
            std::reverse(points.begin(), points.end());
        }
        // Every starting corner: the reflex corner must not end up in a wrong ear.
        for (size_t start = 0; start < points.size(); ++start) {
            std::vector<glm::vec2> rotated(points.begin() + long(start), points.end());
            rotated.insert(rotated.end(), points.begin(), points.begin() + long(start));
            ShapeBatch batch;
            batch.polygon(rotated, kWhite);
            INFO("winding " << winding << ", start " << start);
            REQUIRE(batch.vertices().size() == 3 * (6 - 2));
            CHECK(totalArea(batch) == Approx(3.0).epsilon(1e-6));
            CHECK(covered(batch, {0.5f, 1.5f}));
            CHECK(covered(batch, {1.5f, 0.5f}));
            CHECK_FALSE(covered(batch, {1.5f, 1.5f})); // the notch stays empty
        }
    }
}

TEST_CASE("ShapeBatch::polygon: a comb-shaped polygon and convex fans", "[gl][shapes]") {
    // A comb with three teeth (12 corners, several reflex): area 3 x (1 x 2) + base 5 x 1 - ...
    // built as base [0,5]x[0,1] plus teeth [0,1],[2,3],[4,5] x [1,3]: 5 + 3 x 2 = 11 m^2.
    const std::vector<glm::vec2> comb{{0, 0}, {5, 0}, {5, 3}, {4, 3}, {4, 1}, {3, 1},
                                      {3, 3}, {2, 3}, {2, 1}, {1, 1}, {1, 3}, {0, 3}};
    ShapeBatch batch;
    batch.polygon(comb, kWhite);
    CHECK(batch.vertices().size() == 3 * (comb.size() - 2));
    CHECK(totalArea(batch) == Approx(11.0).epsilon(1e-6));
    CHECK_FALSE(covered(batch, {1.5f, 2.0f}));
    CHECK_FALSE(covered(batch, {3.5f, 2.0f}));

    // A regular hexagon, clockwise: a fan of 4 triangles with the hexagon's area.
    std::vector<glm::vec2> hexagon;
    for (int i = 0; i < 6; ++i) {
        const float angle = -float(i) * std::numbers::pi_v<float> / 3.0f;
        hexagon.push_back({std::cos(angle), std::sin(angle)});
    }
    batch.clear();
    CHECK(batch.vertices().empty());
    batch.polygon(hexagon, kWhite);
    CHECK(batch.vertices().size() == 3 * 4);
    CHECK(totalArea(batch) == Approx(3.0 * std::sqrt(3.0) / 2.0).epsilon(1e-5));

    // Fewer than 3 distinct points, or no area, draw nothing.
    batch.clear();
    const std::vector<glm::vec2> line{{0, 0}, {1, 1}, {1, 1}, {2, 2}};
    batch.polygon(line, kWhite);
    CHECK(batch.vertices().empty());
}

TEST_CASE("ShapeBatch::rect, disc and ring areas", "[gl][shapes]") {
    ShapeBatch batch;
    batch.rect({1.0f, 3.0f}, {-1.0f, 2.0f}, kWhite); // corners in any order
    CHECK(batch.vertices().size() == 6);
    CHECK(totalArea(batch) == Approx(2.0));

    for (const float radius : {0.01f, 0.1f, 1.0f}) {
        batch.clear();
        batch.disc({0.3f, -0.2f}, radius, kWhite);
        const double exact = std::numbers::pi * radius * radius;
        INFO("radius " << radius << ", triangles " << batch.vertices().size() / 3);
        // Automatic segments (chord within 0.25 px at 4000 px/m): within 1% of pi r^2, and an
        // inscribed polygon is always slightly smaller.
        CHECK(totalArea(batch) < exact);
        CHECK(totalArea(batch) > exact * 0.99);
    }
    batch.clear();
    batch.disc({0.0f, 0.0f}, 1.0f, kWhite, 8);
    CHECK(batch.vertices().size() == 3 * 8);
    CHECK(totalArea(batch) == Approx(8.0 * 0.5 * std::sin(std::numbers::pi / 4.0)));

    batch.clear();
    batch.ring({0.0f, 0.0f}, 1.0f, 0.25f, kWhite, 64);
    const double polygonArea = 0.5 * 64 * std::sin(2.0 * std::numbers::pi / 64);
    CHECK(totalArea(batch) == Approx(polygonArea * (1.0 - 0.75 * 0.75)).epsilon(1e-5));
    CHECK_FALSE(covered(batch, {0.0f, 0.0f}));
    CHECK(covered(batch, {0.0f, 0.9f}));

    batch.clear();
    batch.disc({0.0f, 0.0f}, -1.0f, kWhite);
    batch.disc({0.0f, 0.0f}, std::nanf(""), kWhite);
    CHECK(batch.vertices().empty());
}

TEST_CASE("ShapeBatch::polyline: width, mitres, bevels, closed outlines", "[gl][shapes]") {
    ShapeBatch batch;
    // A straight line through 3 collinear points: length x width.
    const std::vector<glm::vec2> straight{{0.0f, 0.0f}, {0.4f, 0.3f}, {0.8f, 0.6f}};
    batch.polyline(straight, 0.02f, kWhite);
    CHECK(totalArea(batch) == Approx(1.0 * 0.02).epsilon(1e-5));

    batch.clear();
    batch.line({0.0f, 0.0f}, {0.0f, 2.0f}, 0.1f, kWhite);
    CHECK(batch.vertices().size() == 6);
    CHECK(totalArea(batch) == Approx(0.2).epsilon(1e-6));
    CHECK(covered(batch, {0.04f, 1.0f}));
    CHECK_FALSE(covered(batch, {0.06f, 1.0f}));

    // A closed square outline of side L and width w (centred on the path) with mitred
    // corners: (L + w)^2 - (L - w)^2 = 4 L w, in either winding.
    const float side = 1.0f, width = 0.1f;
    std::vector<glm::vec2> square{{0, 0}, {side, 0}, {side, side}, {0, side}};
    for (int winding = 0; winding < 2; ++winding) {
        if (winding == 1) {
            std::reverse(square.begin(), square.end());
        }
        batch.clear();
        batch.polyline(square, width, kWhite, true);
        CHECK(totalArea(batch) == Approx(4.0 * side * width).epsilon(1e-5));
        CHECK(covered(batch, {-0.049f, -0.049f})); // the mitred corner is filled
        CHECK_FALSE(covered(batch, {0.5f, 0.5f}));
    }
    // The same outline with the first point repeated at the end is the same outline.
    batch.clear();
    std::vector<glm::vec2> repeated = square;
    repeated.push_back(square.front());
    batch.polyline(repeated, width, kWhite, true);
    CHECK(totalArea(batch) == Approx(4.0 * side * width).epsilon(1e-5));

    // A hairpin turn is bevelled: nothing pokes far past the turning point.
    batch.clear();
    const std::vector<glm::vec2> hairpin{{0.0f, 0.0f}, {1.0f, 0.0f}, {0.0f, 0.05f}};
    batch.polyline(hairpin, 0.02f, kWhite);
    float maxX = 0.0f;
    for (const ShapeVertex& v : batch.vertices()) {
        maxX = std::max(maxX, v.position.x);
    }
    CHECK(maxX < 1.02f);

    // Fewer than 2 distinct points or a non-positive width draw nothing.
    batch.clear();
    const std::vector<glm::vec2> one{{1.0f, 1.0f}, {1.0f, 1.0f}};
    batch.polyline(one, 0.1f, kWhite);
    batch.polyline(straight, 0.0f, kWhite);
    CHECK(batch.vertices().empty());
}
