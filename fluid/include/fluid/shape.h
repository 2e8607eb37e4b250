// fluid — 2D SPH liquid for games.
#pragma once

#include <glm/vec2.hpp>

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace fluid {

/// The most vertices a polygon `Shape` may have (unit: count): blobs, drains and sensors in C++,
/// in C and in level files alike. `validate` refuses more ("spawnBlob: polygon has 300
/// vertices; expected 3 to 256"): checking that no two edges cross takes time quadratic in the
/// count (about 0.13 ms at 256), and a drain's or sensor's test of every particle each step time
/// linear in it. Compile-time constant; any thread.
inline constexpr std::size_t kMaxPolygonVertices = 256;

/// Kind of a `Shape`.
enum class ShapeType : uint8_t {
    /// Axis-aligned rectangle: `center`, `halfExtents`.
    Rectangle,
    /// Circle: `center`, `radius`.
    Circle,
    /// Simple polygon (convex or concave, either winding): `vertices`.
    Polygon,
};

/// A region of the plane: what blobs fill, drains empty and sensors measure. Only the fields of
/// `type` are read. Thread rule: a plain value.
struct Shape {
    /// Which fields are read.
    ShapeType type = ShapeType::Rectangle;
    /// Centre of a rectangle or circle (unit: m; finite).
    glm::vec2 center{0.0f, 0.0f};
    /// Half width and half height of a rectangle (unit: m; each finite and > 0). Typical: 0.25.
    glm::vec2 halfExtents{0.25f, 0.25f};
    /// Radius of a circle (unit: m; finite and > 0). Typical: 0.2.
    float radius = 0.2f;
    /// Polygon vertices in world space (unit: m; 3 to `kMaxPolygonVertices`, finite, no two
    /// edges crossing).
    std::vector<glm::vec2> vertices;

    /// An axis-aligned rectangle from its corners (unit: m).
    static Shape box(glm::vec2 min, glm::vec2 max) {
        Shape s;
        s.center = 0.5f * (min + max);
        s.halfExtents = 0.5f * (max - min);
        return s;
    }
    /// A circle (unit: m).
    static Shape circle(glm::vec2 center, float radius) {
        Shape s;
        s.type = ShapeType::Circle;
        s.center = center;
        s.radius = radius;
        return s;
    }
    /// A polygon (unit: m).
    static Shape polygon(std::vector<glm::vec2> vertices) {
        Shape s;
        s.type = ShapeType::Polygon;
        s.vertices = std::move(vertices);
        return s;
    }
};

/// Throws `fluid::Error` (`ErrorCode::BadArgument`) if `shape` is not usable (non-finite or
/// non-positive sizes, fewer than three vertices or more than `kMaxPolygonVertices`, zero area,
/// crossing edges): "<who>: <shapeProblem(shape)>", e.g. who = "World::addSensor". Time: quadratic
/// in the vertex count, so at most about 0.13 ms; a longer polygon is refused before any work.
/// Thread rule: any thread.
void validate(const Shape& shape, std::string_view who);

/// What `validate` would refuse in `shape`, without the caller's name ("polygon has zero area",
/// "radius = -1 must be finite and > 0 (unit: m)"), or "" for a usable shape: for a caller
/// that reports the problem at its own place (a level file's field). Time and thread rule: as
/// `validate`.
std::string shapeProblem(const Shape& shape);

/// True when `point` (unit: m) lies inside `shape` (boundary points of a rectangle or circle
/// count as inside; polygons use the even-odd rule). Thread rule: any thread.
bool contains(const Shape& shape, glm::vec2 point);

/// True when `point` (unit: m) lies inside the polygon `vertices` (either winding) by the
/// even-odd rule; a point on an edge counts as whichever side the rule puts it. Computed in the
/// point's precision (`glm::vec2` or `glm::dvec2`). Thread rule: any thread.
template <class Vec> bool insidePolygon(std::span<const glm::vec2> vertices, Vec point) {
    bool inside = false;
    for (std::size_t i = 0, j = vertices.size() - 1; i < vertices.size(); j = i++) {
        const Vec a(vertices[i]), b(vertices[j]);
        if ((a.y > point.y) != (b.y > point.y) &&
            point.x < (b.x - a.x) * (point.y - a.y) / (b.y - a.y) + a.x) {
            inside = !inside;
        }
    }
    return inside;
}

/// The axis-aligned box around `shape` (unit: m): its lower-left corner in `lo`, its upper-right
/// in `hi`; for a shape `validate` accepts. Thread rule: any thread.
void bounds(const Shape& shape, glm::vec2& lo, glm::vec2& hi);

/// Area of `shape` (unit: m^2). Thread rule: any thread.
float area(const Shape& shape);

} // namespace fluid
