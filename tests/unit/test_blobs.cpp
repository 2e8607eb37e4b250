// Blobs: rectangle, circle and polygon (convex and concave) fills on the material's lattice;
// geometry errors.
#include "test_support.h"

#include <catch2/catch.hpp>

#include <limits>

using namespace fluid;
using namespace fluid::test;

namespace {

// Even-odd point-in-polygon, with points within `tol` of an edge counted as inside.
bool insideOrOn(const std::vector<glm::vec2>& poly, glm::vec2 p, float tol) {
    bool inside = false;
    for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
        const glm::vec2 a = poly[i], b = poly[j];
        const glm::vec2 e = b - a;
        const float len2 = e.x * e.x + e.y * e.y;
        const float t = std::clamp(((p.x - a.x) * e.x + (p.y - a.y) * e.y) / len2, 0.0f, 1.0f);
        const glm::vec2 c = a + t * e - p;
        if (c.x * c.x + c.y * c.y <= tol * tol) {
            return true;
        }
        if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x) {
            inside = !inside;
        }
    }
    return inside;
}

double shoelace(const std::vector<glm::vec2>& poly) {
    double a = 0.0;
    for (size_t i = 0; i < poly.size(); ++i) {
        const glm::vec2 p = poly[i], q = poly[(i + 1) % poly.size()];
        a += double(p.x) * q.y - double(q.x) * p.y;
    }
    return 0.5 * std::fabs(a);
}

double perimeter(const std::vector<glm::vec2>& poly) {
    double l = 0.0;
    for (size_t i = 0; i < poly.size(); ++i) {
        const glm::vec2 d = poly[(i + 1) % poly.size()] - poly[i];
        l += std::sqrt(double(d.x) * d.x + double(d.y) * d.y);
    }
    return l;
}

// The count matches area / spacing^2 within `relative`, and within the lattice's unavoidable
// perimeter error (half a spacing all around, plus one cell).
void checkCount(uint32_t count, double area, double perim, double s, double relative) {
    const double expected = area / (s * s);
    CAPTURE(count, expected, (count - expected) / expected);
    CHECK(std::fabs(count - expected) <= relative * expected);
    CHECK(std::fabs(count - expected) <= 0.5 * perim / s + 1.0);
}

} // namespace

TEST_CASE("rectangle blob: count, placement, velocity, material", "[unit][blob]") {
    World world;
    world.addMaterial(water());
    const MaterialId y = world.addMaterial(yoghurt());
    const float s = world.spacing(y);
    BlobDef b;
    b.shape.type = ShapeType::Rectangle;
    b.shape.center = {-0.3f, 0.7f};
    b.shape.halfExtents = {0.25f, 0.2f};
    b.velocity = {0.5f, -1.0f};
    b.material = y;
    const uint32_t n = world.spawnBlob(b);
    REQUIRE(n == world.particleCount());
    checkCount(n, 0.5 * 0.4, 2 * (0.5 + 0.4), s, 0.04);
    const auto px = world.positionX(), py = world.positionY();
    for (uint32_t i = 0; i < n; ++i) {
        REQUIRE(px[i] >= -0.55f);
        REQUIRE(px[i] <= -0.05f);
        REQUIRE(py[i] >= 0.5f);
        REQUIRE(py[i] <= 0.9f);
        REQUIRE(world.velocityX()[i] == 0.5f);
        REQUIRE(world.velocityY()[i] == -1.0f);
        REQUIRE(world.materialIndex()[i] == y.index);
    }
    // A lattice at the material's spacing: nearest neighbours are one spacing apart.
    CHECK(std::fabs(px[1] - px[0]) == Approx(s).epsilon(1e-4));
    // A shape smaller than one spacing holds no lattice point.
    b.shape.halfExtents = {0.2f * s, 0.2f * s};
    CHECK(world.spawnBlob(b) == 0);
    CHECK(world.particleCount() == n);
}

TEST_CASE("circle blob: count and placement", "[unit][blob]") {
    World world;
    const MaterialId w = world.addMaterial(water());
    const float s = world.spacing(w);
    BlobDef b;
    b.shape.type = ShapeType::Circle;
    b.shape.center = {1.0f, -2.0f};
    b.shape.radius = 0.25f;
    b.material = w;
    const uint32_t n = world.spawnBlob(b);
    checkCount(n, 3.14159265 * 0.25 * 0.25, 2 * 3.14159265 * 0.25, s, 0.04);
    const auto px = world.positionX(), py = world.positionY();
    for (uint32_t i = 0; i < n; ++i) {
        const float dx = px[i] - 1.0f, dy = py[i] + 2.0f;
        REQUIRE(dx * dx + dy * dy <= 0.25f * 0.25f * (1.0f + 1e-5f));
    }
}

// A yield-stress paste keeps the outline it starts with, so its circles are filled in rings: the
// outermost ring stands half a spacing inside the circle all the way round, where the lattice's
// farthest points step in and out by up to a spacing (the notches a resting drop kept).
TEST_CASE("a yielding material's circle is filled in rings: a round outline, the lattice's "
          "count, no two points closer than 0.8 spacings",
          "[unit][blob]") {
    const float radius = 0.08f;
    for (const bool yields : {true, false}) {
        CAPTURE(yields);
        World world;
        const MaterialId m = world.addMaterial(yields ? yoghurt() : water());
        // Per 10-degree bin around the centre, the farthest point's distance (0: none in the bin).
        const auto outline = [&](uint32_t first, uint32_t count) {
            std::vector<float> far(36, 0.0f);
            const auto px = world.positionX(), py = world.positionY();
            for (uint32_t i = first; i < first + count; ++i) {
                const float dx = px[i] - 0.3f, dy = py[i] - 0.1f;
                const auto bin =
                    size_t((std::atan2(dy, dx) + 3.14159265f) / 6.2831853f * 36.0f) % 36;
                far[bin] = std::max(far[bin], std::hypot(dx, dy));
            }
            return far;
        };
        const float s = world.spacing(m);
        BlobDef b;
        b.shape = Shape::circle({0.3f, 0.1f}, radius);
        b.material = m;
        b.latticeAngle = 0.3f;
        const uint32_t first = world.particleCount();
        const uint32_t n = world.spawnBlob(b);
        checkCount(n, 3.14159265 * radius * radius, 2 * 3.14159265 * radius, s, 0.04);
        const std::vector<float> far = outline(first, n);
        const auto [lo, hi] = std::minmax_element(far.begin(), far.end());
        std::printf("[measure] %s circle of %.2f m: %u particles, the farthest per 10-degree bin "
                    "%.4f-%.4f m (%.2f-%.2f spacings in from the outline)\n",
                    yields ? "yoghurt" : "water", double(radius), n, double(*lo), double(*hi),
                    double((radius - *hi) / s), double((radius - *lo) / s));
        if (yields) {
            CHECK(*lo >= radius - 0.5f * s - 1e-5f);
            CHECK(*hi <= radius - 0.5f * s + 1e-5f);
        } else {
            CHECK(*hi - *lo > 0.3f * s); // the lattice's staircase
        }
        const auto px = world.positionX(), py = world.positionY();
        float nearest = INFINITY;
        for (uint32_t i = first; i < first + n; ++i) {
            for (uint32_t j = i + 1; j < first + n; ++j) {
                nearest = std::min(nearest, std::hypot(px[i] - px[j], py[i] - py[j]));
            }
        }
        CHECK(nearest >= 0.8f * s);
    }
    // Small circles: one ring of four points, or the centre alone.
    World world;
    const MaterialId y = world.addMaterial(yoghurt());
    BlobDef small;
    small.shape = Shape::circle({0.0f, 0.0f}, 1.2f * world.spacing(y));
    small.material = y;
    CHECK(world.spawnBlob(small) == 4);
    small.shape = Shape::circle({0.5f, 0.0f}, 0.6f * world.spacing(y));
    CHECK(world.spawnBlob(small) == 1);
}

TEST_CASE("polygon blobs: convex and concave", "[unit][blob]") {
    World world;
    const MaterialId w = world.addMaterial(water());
    const float s = world.spacing(w);

    SECTION("convex triangle, clockwise") {
        const std::vector<glm::vec2> tri{{0.0f, 0.0f}, {0.3f, 0.5f}, {0.6f, 0.0f}};
        BlobDef b;
        b.shape.type = ShapeType::Polygon;
        b.shape.vertices = tri;
        b.material = w;
        const uint32_t n = world.spawnBlob(b);
        checkCount(n, shoelace(tri), perimeter(tri), s, 0.05);
        for (const glm::vec2 p : positions(world)) {
            REQUIRE(insideOrOn(tri, p, 1e-6f));
        }
    }
    SECTION("concave L shape") {
        const std::vector<glm::vec2> l{{-0.2f, -0.2f},   {0.3f, -0.2f},  {0.3f, -0.05f},
                                       {-0.05f, -0.05f}, {-0.05f, 0.3f}, {-0.2f, 0.3f}};
        BlobDef b;
        b.shape.type = ShapeType::Polygon;
        b.shape.vertices = l;
        b.material = w;
        const uint32_t n = world.spawnBlob(b);
        checkCount(n, shoelace(l), perimeter(l), s, 0.05);
        uint32_t inNotch = 0;
        for (const glm::vec2 p : positions(world)) {
            REQUIRE(insideOrOn(l, p, 1e-6f));
            inNotch += (p.x > -0.05f + 1e-6f && p.y > -0.05f + 1e-6f) ? 1 : 0;
        }
        CHECK(inNotch == 0);
        // Both arms are filled.
        const Bounds bb = bounds(world);
        CHECK(bb.x1 > 0.28f);
        CHECK(bb.y1 > 0.28f);
    }
}

TEST_CASE("blob geometry errors", "[unit][blob][bad-input]") {
    World world;
    const MaterialId w = world.addMaterial(water());
    BlobDef b;
    b.shape.type = ShapeType::Polygon;
    b.material = w;

    SECTION("two vertices") {
        b.shape.vertices = {{0.0f, 0.0f}, {1.0f, 0.0f}};
        CHECK_THROWS_MATCHES(
            world.spawnBlob(b), Error,
            Catch::Message("spawnBlob: polygon has 2 vertices; expected 3 to 256"));
    }
    SECTION("self-intersecting bow tie") {
        b.shape.vertices = {{0.0f, 0.0f}, {0.1f, 0.1f}, {0.1f, 0.0f}, {0.0f, 0.2f}};
        CHECK_THROWS_MATCHES(
            world.spawnBlob(b), Error,
            Catch::Message("spawnBlob: polygon edges 0 and 2 cross; expected a simple polygon"));
    }
    SECTION("NaN vertex") {
        b.shape.vertices = {
            {0.0f, 0.0f}, {std::numeric_limits<float>::quiet_NaN(), 0.0f}, {0.0f, 0.1f}};
        CHECK_THROWS_MATCHES(
            world.spawnBlob(b), Error,
            Catch::Message("spawnBlob: polygon vertex 1 = (nan, 0) is not finite"));
    }
    SECTION("a starting structure outside [0, 1] or NaN") {
        b.shape.type = ShapeType::Circle;
        b.shape.radius = 0.05f;
        const auto [value, text] = GENERATE(table<float, const char*>(
            {{-0.5f, "-0.5"}, {1.5f, "1.5"}, {std::numeric_limits<float>::quiet_NaN(), "nan"}}));
        b.structure = value;
        CHECK_THROWS_MATCHES(world.spawnBlob(b), Error,
                             Catch::Message(std::string("spawnBlob: structure = ") + text +
                                            " is out of range [0, 1] (unit: 1)"));
        CHECK(world.particleCount() == 0);
    }
    SECTION("a lattice angle outside [-6.2832, 6.2832] or NaN") {
        b.shape.type = ShapeType::Circle;
        b.shape.radius = 0.05f;
        const auto [value, text] = GENERATE(table<float, const char*>(
            {{-7.0f, "-7"}, {7.0f, "7"}, {std::numeric_limits<float>::quiet_NaN(), "nan"}}));
        b.latticeAngle = value;
        CHECK_THROWS_MATCHES(world.spawnBlob(b), Error,
                             Catch::Message(std::string("spawnBlob: latticeAngle = ") + text +
                                            " is out of range [-6.2832, 6.2832] (unit: rad)"));
        CHECK(world.particleCount() == 0);
    }
    SECTION("degenerate (zero area)") {
        b.shape.vertices = {{0.0f, 0.0f}, {0.1f, 0.1f}, {0.2f, 0.2f}};
        CHECK_THROWS_MATCHES(world.spawnBlob(b), Error,
                             Catch::Message("spawnBlob: polygon has zero area"));
    }
    SECTION("negative rectangle extents") {
        b.shape.type = ShapeType::Rectangle;
        b.shape.halfExtents = {-0.1f, 0.1f};
        CHECK_THROWS_MATCHES(world.spawnBlob(b), Error,
                             Catch::Message("spawnBlob: halfExtents = (-0.1, 0.1) must be finite "
                                            "and > 0 (unit: m)"));
    }
    SECTION("NaN circle radius") {
        b.shape.type = ShapeType::Circle;
        b.shape.radius = std::numeric_limits<float>::quiet_NaN();
        CHECK_THROWS_MATCHES(
            world.spawnBlob(b), Error,
            Catch::Message("spawnBlob: radius = nan must be finite and > 0 (unit: m)"));
    }
    SECTION("infinite velocity") {
        b.shape.type = ShapeType::Circle;
        b.velocity = {std::numeric_limits<float>::infinity(), 0.0f};
        CHECK_THROWS_MATCHES(world.spawnBlob(b), Error,
                             Catch::Message("spawnBlob: velocity = (inf, 0) is not finite"));
    }
    SECTION("unknown material") {
        b.shape.type = ShapeType::Circle;
        b.material = MaterialId{3};
        CHECK_THROWS_AS(world.spawnBlob(b), Error);
    }
    CHECK(world.particleCount() == 0);
}

TEST_CASE("a layer on a slope filled along it has a flat top, rows along x leave steps",
          "[unit][blob]") {
    // A 0.49 x 0.0425 m layer turned by -0.4 rad (23 degrees, the sticky plank's): filled with
    // its rows along the slope, every particle's distance to the layer's top edge is one of its
    // rows' (a flat top); filled with rows along x, the top row's distances spread by most of a
    // spacing (steps that a yield-stress layer keeps).
    const float angle = -0.4f;
    const glm::vec2 along{std::cos(angle), std::sin(angle)}, across{-along.y, along.x};
    const glm::vec2 base{0.1f, 0.6f};
    const float length = 0.49f, thickness = 0.0425f;
    BlobDef b;
    b.shape.type = ShapeType::Polygon;
    b.shape.vertices = {base, base + length * along, base + length * along + thickness * across,
                        base + thickness * across};
    const auto depths = [&](float latticeAngle) {
        World world(WorldDef{});
        b.material = world.addMaterial(yoghurt());
        b.latticeAngle = latticeAngle;
        const uint32_t n = world.spawnBlob(b);
        std::vector<float> d; // each particle's distance below the top edge (m)
        const auto px = world.positionX(), py = world.positionY();
        for (uint32_t i = 0; i < n; ++i) {
            const glm::vec2 r = glm::vec2(px[i], py[i]) - base;
            d.push_back(thickness - (r.x * across.x + r.y * across.y));
        }
        return std::make_pair(d, world.spacing(b.material));
    };
    const auto [turned, s] = depths(angle);
    // 4 rows of 48: the layer's own lattice, centred in it.
    CHECK(turned.size() == 4 * uint32_t(std::floor(length / s)));
    for (const float d : turned) {
        const float row = (d - 0.5f * (thickness - 3.0f * s)) / s; // 0..3 for rows top to bottom
        CHECK(std::fabs(row - std::round(row)) < 1e-3f);
    }
    const auto [upright, s0] = depths(0.0f);
    // Rows along x: the particles nearest the top edge, one per column of the lattice, stand
    // at depths spread over most of a spacing.
    const float top = *std::min_element(upright.begin(), upright.end());
    float deepestTop = top;
    for (const float d : upright) {
        if (d < top + s0) {
            deepestTop = std::max(deepestTop, d);
        }
    }
    CHECK(deepestTop - top > 0.5f * s0);
}
