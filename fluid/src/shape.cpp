// fluid — shapes: validation, containment, bounds and area.
#include <fluid/error.h>
#include <fluid/internal/checks.h>
#include <fluid/shape.h>

#include <glm/common.hpp>
#include <glm/vec2.hpp>

#include <cmath>
#include <sstream>
#include <string>

namespace fluid {

namespace {

using internal::finite;

// In double: differences of float coordinates are exact there, so the signs are right far
// from the origin too.
double cross(glm::dvec2 a, glm::dvec2 b) {
    return a.x * b.y - a.y * b.x;
}

bool segmentsCross(glm::dvec2 a, glm::dvec2 b, glm::dvec2 c, glm::dvec2 d) {
    const double d1 = cross(b - a, c - a);
    const double d2 = cross(b - a, d - a);
    const double d3 = cross(d - c, a - c);
    const double d4 = cross(d - c, b - c);
    return ((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0));
}

// What is wrong with a shape, thrown by `check` and caught by `shapeProblem`.
struct Problem {
    std::string what;
};

[[noreturn]] void fail(const std::string& what) {
    throw Problem{what};
}

void checkPoint(const std::string& name, glm::vec2 v) {
    if (!finite(v)) {
        std::ostringstream s;
        s << name << " = (" << v.x << ", " << v.y << ") is not finite";
        fail(s.str());
    }
}

// Twice the signed area, in double and relative to the first vertex: a small polygon far from
// the origin (a cup at x = 1000 m) keeps its area to float precision.
double signedArea2(const std::vector<glm::vec2>& v) {
    const glm::dvec2 o = v[0];
    double area2 = 0.0;
    for (size_t i = 1; i + 1 < v.size(); ++i) {
        const glm::dvec2 a = glm::dvec2(v[i]) - o, b = glm::dvec2(v[i + 1]) - o;
        area2 += a.x * b.y - a.y * b.x;
    }
    return area2;
}

// Throws Problem for a shape `validate` refuses.
void check(const Shape& shape) {
    switch (shape.type) {
    case ShapeType::Rectangle:
        checkPoint("center", shape.center);
        if (!(shape.halfExtents.x > 0.0f && shape.halfExtents.y > 0.0f) ||
            !finite(shape.halfExtents)) {
            std::ostringstream s;
            s << "halfExtents = (" << shape.halfExtents.x << ", " << shape.halfExtents.y
              << ") must be finite and > 0 (unit: m)";
            fail(s.str());
        }
        return;
    case ShapeType::Circle:
        checkPoint("center", shape.center);
        if (!(shape.radius > 0.0f) || !std::isfinite(shape.radius)) {
            std::ostringstream s;
            s << "radius = " << shape.radius << " must be finite and > 0 (unit: m)";
            fail(s.str());
        }
        return;
    case ShapeType::Polygon: {
        const std::vector<glm::vec2>& v = shape.vertices;
        if (v.size() < 3 || v.size() > kMaxPolygonVertices) {
            fail("polygon has " + std::to_string(v.size()) + " vertices; expected 3 to " +
                 std::to_string(kMaxPolygonVertices));
        }
        for (size_t i = 0; i < v.size(); ++i) {
            checkPoint("polygon vertex " + std::to_string(i), v[i]);
        }
        if (!(std::fabs(signedArea2(v)) > 0.0)) {
            fail("polygon has zero area");
        }
        const size_t n = v.size();
        for (size_t i = 0; i < n; ++i) {
            for (size_t j = i + 2; j < n; ++j) {
                if (i == 0 && j == n - 1) {
                    continue; // adjacent through the closing edge
                }
                if (segmentsCross(v[i], v[(i + 1) % n], v[j], v[(j + 1) % n])) {
                    fail("polygon edges " + std::to_string(i) + " and " + std::to_string(j) +
                         " cross; expected a simple polygon");
                }
            }
        }
        return;
    }
    }
    fail("unknown shape type " + std::to_string(int(shape.type)));
}

} // namespace

std::string shapeProblem(const Shape& shape) {
    try {
        check(shape);
    } catch (const Problem& problem) {
        return problem.what;
    }
    return {};
}

void validate(const Shape& shape, std::string_view who) {
    if (std::string problem = shapeProblem(shape); !problem.empty()) {
        throw Error(std::string(who) + ": " + problem, ErrorCode::BadArgument);
    }
}

bool contains(const Shape& shape, glm::vec2 p) {
    switch (shape.type) {
    case ShapeType::Rectangle: {
        const glm::vec2 d = p - shape.center;
        return std::fabs(d.x) <= shape.halfExtents.x && std::fabs(d.y) <= shape.halfExtents.y;
    }
    case ShapeType::Circle: {
        const glm::vec2 d = p - shape.center;
        return d.x * d.x + d.y * d.y <= shape.radius * shape.radius;
    }
    case ShapeType::Polygon:
        return insidePolygon(std::span<const glm::vec2>(shape.vertices), p);
    }
    return false;
}

void bounds(const Shape& shape, glm::vec2& lo, glm::vec2& hi) {
    switch (shape.type) {
    case ShapeType::Rectangle:
        lo = shape.center - shape.halfExtents;
        hi = shape.center + shape.halfExtents;
        return;
    case ShapeType::Circle:
        lo = shape.center - glm::vec2(shape.radius);
        hi = shape.center + glm::vec2(shape.radius);
        return;
    case ShapeType::Polygon:
        lo = hi = shape.vertices.front();
        for (const glm::vec2 v : shape.vertices) {
            lo = glm::min(lo, v);
            hi = glm::max(hi, v);
        }
        return;
    }
}

float area(const Shape& shape) {
    switch (shape.type) {
    case ShapeType::Rectangle:
        return 4.0f * shape.halfExtents.x * shape.halfExtents.y;
    case ShapeType::Circle:
        return 3.14159265f * shape.radius * shape.radius;
    case ShapeType::Polygon:
        return float(0.5 * std::fabs(signedArea2(shape.vertices)));
    }
    return 0.0f;
}

} // namespace fluid
