// fluid::box2d — the shapes and masses a coupled body may have (shapes.h).
#include <fluid/box2d/shapes.h>

#include <fluid/box2d/coupling.h>

#include <fluid/internal/number_text.h>

#include <box2d/box2d.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <vector>

namespace fluid::box2d {

namespace {

// Numbers in messages as the level loader writes a float's.
std::string number(double value) {
    return internal::formatNumber(float(value));
}

// A derived figure to three significant digits ("0.0001", "6.47").
std::string brief(double value) {
    char text[32];
    std::snprintf(text, sizeof(text), "%.3g", value);
    return text;
}

double cross(glm::dvec2 a, glm::dvec2 b) {
    return a.x * b.y - a.y * b.x;
}

} // namespace

ShapeProblem checkPolygon(std::span<const glm::vec2> vertices, float spacing) {
    const std::size_t n = vertices.size();
    if (n < 3 || n > std::size_t(b2_maxPolygonVertices)) {
        return {"a polygon needs 3 to " + std::to_string(b2_maxPolygonVertices) +
                    " vertices, not " + std::to_string(n),
                -1};
    }
    std::vector<glm::dvec2> v(vertices.begin(), vertices.end());
    for (std::size_t i = 0; i < n; ++i) {
        if (!std::isfinite(v[i].x) || !std::isfinite(v[i].y)) {
            return {"vertex " + std::to_string(i) + " is not finite", int(i)};
        }
    }
    for (std::size_t j = 1; j < n; ++j) {
        for (std::size_t i = 0; i < j; ++i) {
            const double d = glm::length(v[i] - v[j]);
            if (d < kLinearSlop) {
                return {"vertex " + std::to_string(j) + " is " + number(d) + " m from vertex " +
                            std::to_string(i) +
                            "; polygon vertices must be at least 0.005 m apart (Box2D's linear "
                            "slop)",
                        int(j)};
            }
        }
    }
    double twiceArea = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        twiceArea += cross(v[i], v[(i + 1) % n]);
    }
    const double area = 0.5 * std::abs(twiceArea);
    if (!(area >= double(kLinearSlop) * double(kLinearSlop))) {
        return {"the polygon's area is " + number(area) +
                    " m^2; expected at least 2.5e-05 m^2 (Box2D's linear slop squared)",
                -1};
    }
    const double sign = twiceArea > 0.0 ? 1.0 : -1.0;
    // Every corner turns the same way as the whole outline...
    for (std::size_t i = 0; i < n; ++i) {
        const glm::dvec2 prev = v[(i + n - 1) % n], next = v[(i + 1) % n];
        const double turn = sign * cross(v[i] - prev, next - v[i]);
        if (turn == 0.0) {
            return {"vertex " + std::to_string(i) +
                        " lies on the line through its neighbours; a Box2D polygon is strictly "
                        "convex (leave the vertex out)",
                    int(i)};
        }
        if (turn < 0.0) {
            return {"the polygon is not convex at vertex " + std::to_string(i) +
                        "; a Box2D polygon is convex (split a concave shape into several "
                        "fixtures)",
                    int(i)};
        }
    }
    // ...and the outline goes round once: every vertex lies inside every edge (a star whose
    // corners all turn left passes the first test).
    for (std::size_t i = 0; i < n; ++i) {
        const glm::dvec2 a = v[i], b = v[(i + 1) % n];
        for (std::size_t j = 0; j < n; ++j) {
            if (j != i && j != (i + 1) % n && !(sign * cross(b - a, v[j] - a) > 0.0)) {
                return {"the polygon's edges cross (it winds round more than once); a Box2D "
                        "polygon is convex and simple",
                        -1};
            }
        }
    }
    return checkPointedPolygon(vertices, spacing);
}

ShapeProblem checkPointedPolygon(std::span<const glm::vec2> vertices, float spacing) {
    const std::size_t n = vertices.size();
    const std::vector<glm::dvec2> v(vertices.begin(), vertices.end());
    if (spacing > 0.0f && n >= 3) {
        double sharpest = 180.0;
        std::size_t at = 0;
        for (std::size_t i = 0; i < n; ++i) {
            const glm::dvec2 a = v[(i + n - 1) % n] - v[i], b = v[(i + 1) % n] - v[i];
            const double degrees =
                std::atan2(std::abs(cross(a, b)), a.x * b.x + a.y * b.y) * 180.0 / std::numbers::pi;
            if (degrees < sharpest) {
                sharpest = degrees;
                at = i;
            }
        }
        const double radius = inscribedRadius(vertices);
        if (sharpest < kAcuteCorner && radius < double(spacing)) {
            return {"the corner at vertex " + std::to_string(at) + " is " + brief(sharpest) +
                        " degrees and the polygon holds a circle of radius " + brief(radius) +
                        " m at most; a dynamic body's polygon with a corner under 90 degrees "
                        "must hold one of the fluid's spacing, " +
                        brief(spacing) +
                        " m, or the fluid throws it (make it larger or blunter, a box or a "
                        "circle, or the body static or kinematic)",
                    int(at)};
        }
    }
    return {};
}

ShapeProblem checkCircle(float radius) {
    if (!(radius >= kLinearSlop) || !std::isfinite(radius)) {
        return {"a circle's radius is " + number(radius) +
                    " m; expected at least 0.005 m (Box2D's linear slop)",
                -1};
    }
    return {};
}

ShapeProblem checkBox(float width, float height) {
    for (const auto& [what, size] : {std::pair{"width", width}, std::pair{"height", height}}) {
        if (!(size >= kLinearSlop) || !std::isfinite(size)) {
            return {std::string("a box's ") + what + " is " + number(size) +
                        " m; expected at least 0.005 m (Box2D's linear slop)",
                    -1};
        }
    }
    return {};
}

double inscribedRadius(std::span<const glm::vec2> vertices) {
    // The largest inscribed circle touches three edges (two when they are parallel and the
    // circle is pinned by their gap): try the point equidistant from each triple of edge lines
    // and keep the best one inside.
    const std::size_t n = vertices.size();
    if (n < 3) {
        return 0.0;
    }
    double twiceArea = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        twiceArea += cross(glm::dvec2(vertices[i]), glm::dvec2(vertices[(i + 1) % n]));
    }
    const double sign = twiceArea > 0.0 ? 1.0 : -1.0;
    // Edge lines as inward unit normal m and offset c: the distance inside is m . x - c.
    std::vector<glm::dvec2> m(n);
    std::vector<double> c(n);
    for (std::size_t i = 0; i < n; ++i) {
        const glm::dvec2 a(vertices[i]), b(vertices[(i + 1) % n]);
        const glm::dvec2 d = b - a;
        const double length = glm::length(d);
        if (!(length > 0.0)) {
            return 0.0;
        }
        m[i] = sign * glm::dvec2(-d.y, d.x) / length;
        c[i] = glm::dot(m[i], a);
    }
    const auto depth = [&](glm::dvec2 x) {
        double least = std::numeric_limits<double>::infinity();
        for (std::size_t i = 0; i < n; ++i) {
            least = std::min(least, glm::dot(m[i], x) - c[i]);
        }
        return least;
    };
    double best = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t j = i + 1; j < n; ++j) {
            for (std::size_t k = j + 1; k < n; ++k) {
                // m_i . x - r = c_i for the three lines: (x, y, r) from a 3 x 3 system.
                const double a[3][4] = {{m[i].x, m[i].y, -1.0, c[i]},
                                        {m[j].x, m[j].y, -1.0, c[j]},
                                        {m[k].x, m[k].y, -1.0, c[k]}};
                const auto det3 = [](double p00, double p01, double p02, double p10, double p11,
                                     double p12, double p20, double p21, double p22) {
                    return p00 * (p11 * p22 - p12 * p21) - p01 * (p10 * p22 - p12 * p20) +
                           p02 * (p10 * p21 - p11 * p20);
                };
                const double det = det3(a[0][0], a[0][1], a[0][2], a[1][0], a[1][1], a[1][2],
                                        a[2][0], a[2][1], a[2][2]);
                if (std::abs(det) < 1e-12) {
                    continue;
                }
                const double x = det3(a[0][3], a[0][1], a[0][2], a[1][3], a[1][1], a[1][2], a[2][3],
                                      a[2][1], a[2][2]) /
                                 det;
                const double y = det3(a[0][0], a[0][3], a[0][2], a[1][0], a[1][3], a[1][2], a[2][0],
                                      a[2][3], a[2][2]) /
                                 det;
                best = std::max(best, depth({x, y}));
            }
        }
    }
    return best;
}

float coarsestSpacing(const World& world) {
    float coarsest = 0.0f;
    for (uint32_t k = 0; k < world.materialCount(); ++k) {
        coarsest = std::max(coarsest, world.spacing(MaterialId{uint16_t(k), 0}));
    }
    return coarsest;
}

float densestArealDensity(const World& world) {
    float densest = 0.0f;
    for (uint32_t k = 0; k < world.materialCount(); ++k) {
        densest = std::max(densest, arealDensity(world, MaterialId{uint16_t(k), 0}));
    }
    return densest;
}

ShapeProblem checkDynamicMass(float mass, float area, float centredInertia, bool fixedRotation,
                              float density) {
    if (!(mass >= kMinBodyMass)) {
        return {"the fixtures weigh " + number(mass) + " kg, less than the " +
                    number(kMinBodyMass) +
                    " kg a dynamic body needs (Box2D divides by its mass); raise their density or "
                    "size",
                -1};
    }
    if (density > 0.0f && area > 0.0f && !(mass >= kMinDensityRatio * density * area)) {
        return {"the fixtures weigh " + number(mass) + " kg over " + number(area) +
                    " m^2, an areal density of " + brief(mass / area) + " kg/m^2, " +
                    brief(mass / (area * density)) + " of the densest material's (" +
                    brief(density) + " kg/m^2); a dynamic body needs at least " +
                    number(kMinDensityRatio) +
                    " of it (kMinDensityRatio), or the fluid throws it: raise their density to " +
                    brief(kMinDensityRatio * density) + " kg/m^2 or more",
                -1};
    }
    if (!fixedRotation && centredInertia < kMinBodyInertia) {
        return {"the fixtures' rotational inertia about their centre of mass is " +
                    number(centredInertia) + " kg m^2, less than the " + number(kMinBodyInertia) +
                    " kg m^2 a dynamic body that turns needs (Box2D divides by it); make them "
                    "wider or fix the body's rotation",
                -1};
    }
    return {};
}

} // namespace fluid::box2d
