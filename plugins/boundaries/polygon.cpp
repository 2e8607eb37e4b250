// fluid — built-in boundary plugin: solid polygon (convex or concave), static or kinematic.
#include "shape_geometry.h"

#include <fluid/error.h>
#include <fluid/plugins/polygon.h>
#include <fluid/shape.h>

#include <glm/common.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

namespace fluid {

using geometry::cross;
using geometry::dot;

PolygonBoundary::PolygonBoundary(std::span<const glm::vec2> vertices) : PolygonBoundary() {
    setPoints("vertices", vertices);
}

PolygonBoundary::PolygonBoundary() : KinematicShape(kType, kParams) {}

PolygonBoundary::~PolygonBoundary() = default;

namespace {

[[noreturn]] void fail(const std::string& what) {
    throw Error("plugin 'boundary.polygon': parameter 'vertices' " + what, ErrorCode::BadArgument);
}

// Orientation of c against a -> b: +1 left, -1 right, 0 on the line.
int orientation(glm::dvec2 a, glm::dvec2 b, glm::dvec2 c) {
    const double v = cross(b - a, c - a);
    return (v > 0.0) - (v < 0.0);
}

bool onSegment(glm::dvec2 a, glm::dvec2 b, glm::dvec2 c) {
    return std::min(a.x, b.x) <= c.x && c.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= c.y &&
           c.y <= std::max(a.y, b.y);
}

// Closed segments [a, b] and [c, d] share a point.
bool segmentsTouch(glm::dvec2 a, glm::dvec2 b, glm::dvec2 c, glm::dvec2 d) {
    const int o1 = orientation(a, b, c), o2 = orientation(a, b, d);
    const int o3 = orientation(c, d, a), o4 = orientation(c, d, b);
    if (o1 != o2 && o3 != o4) {
        return true;
    }
    return (o1 == 0 && onSegment(a, b, c)) || (o2 == 0 && onSegment(a, b, d)) ||
           (o3 == 0 && onSegment(c, d, a)) || (o4 == 0 && onSegment(c, d, b));
}

// Checks the user's vertices (in their order, so messages name their indices) and returns them
// counter-clockwise.
std::vector<glm::dvec2> checkedVertices(std::span<const glm::vec2> points) {
    const std::size_t n = points.size();
    if (n < 3) {
        fail("has " + std::to_string(n) +
             " points; set 3 to 4096 vertices with setPoints before the first step");
    }
    std::vector<glm::dvec2> v(points.begin(), points.end());
    double area2 = 0.0, extent = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        const glm::dvec2 a = v[i], b = v[(i + 1) % n];
        if (a == b) {
            std::ostringstream s;
            s << "repeats vertex " << i << " = (" << a.x << ", " << a.y << ") as vertex "
              << (i + 1) % n << "; expected distinct consecutive vertices (unit: m)";
            fail(s.str());
        }
        area2 += cross(a, b);
        extent = std::max({extent, std::fabs(a.x), std::fabs(a.y)});
    }
    for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t j = i + 1; j < n; ++j) {
            const bool adjacent = j == i + 1 || (i == 0 && j == n - 1);
            if (adjacent) {
                // Neighbours share a vertex; they may not fold back onto each other.
                const glm::dvec2 a = v[i], b = v[(i + 1) % n], c = v[j], d = v[(j + 1) % n];
                const glm::dvec2 shared = j == i + 1 ? b : a;
                const glm::dvec2 other1 = j == i + 1 ? a : b;
                const glm::dvec2 other2 = j == i + 1 ? d : c;
                const glm::dvec2 e1 = other1 - shared, e2 = other2 - shared;
                if (cross(e1, e2) == 0.0 && dot(e1, e2) > 0.0) {
                    std::ostringstream s;
                    s << "folds back at vertex " << (j == i + 1 ? j : i) << ": edges " << i
                      << " and " << j << " overlap";
                    fail(s.str());
                }
                continue;
            }
            if (segmentsTouch(v[i], v[(i + 1) % n], v[j], v[(j + 1) % n])) {
                std::ostringstream s;
                s << "is not simple: edge " << i << " (vertex " << i << " to " << (i + 1) % n
                  << ") meets edge " << j << " (vertex " << j << " to " << (j + 1) % n << ")";
                fail(s.str());
            }
        }
    }
    // After the crossing test: a bow tie's halves cancel.
    if (std::fabs(area2) <= 1e-12 * extent * extent) {
        fail("encloses no area (collinear vertices)");
    }
    if (area2 < 0.0) {
        std::reverse(v.begin(), v.end());
    }
    return v;
}

} // namespace

bool PolygonBoundary::containsLocal(glm::dvec2 local) const {
    return m_edges && m_edges->inside(local);
}

bool PolygonBoundary::insideLocal(glm::dvec2 local) const {
    // Over the vertices as set (no build needed).
    return insidePolygon(pointsAt(kVertices), local);
}

void PolygonBoundary::validate() const {
    if (pointsAt(kVertices).empty()) {
        return; // not set yet: the first step says so
    }
    checkCoordinates(kVertices);
    checkedVertices(pointsAt(kVertices));
}

void PolygonBoundary::build(double spacing, double support, std::vector<glm::dvec2>& out,
                            LocalBounds& bounds) {
    checkCoordinates(kVertices);
    const std::vector<glm::dvec2> v = checkedVertices(pointsAt(kVertices));
    const std::size_t n = v.size();
    // How many candidates the layers below lay, in double before any integer cast: every edge's
    // pieces in every layer, and at most a half turn of arc per layer at each reflex corner.
    const double layerCountD = layerCount(spacing, support);
    double perimeter = 0.0, pieceCount = 0.0, reflexCount = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        const glm::dvec2 a = v[(i + n - 1) % n], b = v[i], c = v[(i + 1) % n];
        const double len = geometry::length(c - b);
        perimeter += len;
        pieceCount += std::max(1.0, len / spacing);
        reflexCount += cross(b - a, c - b) < 0.0 ? 1.0 : 0.0;
    }
    const double estimate =
        layerCountD * pieceCount + reflexCount * std::numbers::pi * 0.5 * layerCountD * layerCountD;
    std::ostringstream what;
    what << "perimeter " << perimeter << " m";
    checkSampleCount(estimate, what.str(), spacing);

    std::vector<ShapeSegment> edges;
    bounds.lo = bounds.hi = v[0];
    for (std::size_t i = 0; i < n; ++i) {
        edges.push_back(geometry::makeSegment(v[i], v[(i + 1) % n]));
        bounds.lo = glm::min(bounds.lo, v[i]);
        bounds.hi = glm::max(bounds.hi, v[i]);
    }
    m_edges = std::make_unique<geometry::SegmentSet>();
    m_edges->build(std::move(edges), support);
    const std::span<const ShapeSegment> edge = m_edges->segments();

    // Layers at (l + 0.5) spacing behind the surface, enough to fill one support radius, where
    // the fluid lattice's next rows would be. Shallow layers first: where layers of different
    // edges meet (thin parts, corners) the ones nearest the surface are kept.
    const int layers = static_cast<int>(layerCountD); // <= estimate <= kMaxSamples
    geometry::SpacedPoints kept(0.55 * spacing);
    // A candidate belongs to its layer only if no other part of the surface is clearly nearer
    // (else another edge's layer covers that spot) and it lies inside.
    auto consider = [&](glm::dvec2 q, double depth) {
        if (!containsLocal(q)) {
            return;
        }
        glm::dvec2 closest{0.0, 0.0};
        double distance = 0.0;
        if (m_edges->nearest(q, depth, closest, distance) >= 0 &&
            distance < depth - 0.45 * spacing) {
            return;
        }
        kept.add(q);
    };
    for (int l = 0; l < layers; ++l) {
        const double depth = (l + 0.5) * spacing;
        for (const ShapeSegment& e : edge) {
            // The edge split into whole pieces about one spacing long, one sample per piece.
            const int pieces = std::max(1, static_cast<int>(std::lround(e.length / spacing)));
            const glm::dvec2 dir = (e.b - e.a) / e.length;
            for (int k = 0; k < pieces; ++k) {
                const double u = (k + 0.5) * e.length / pieces;
                consider(e.a + u * dir + depth * e.normal, depth);
            }
        }
        // Reflex corners (the solid wraps round the fluid there): the interior points nearest
        // to the corner form a sector between the two edges' inward normals; fill it with arcs.
        for (std::size_t i = 0; i < n; ++i) {
            const ShapeSegment& in = edge[(i + n - 1) % n];
            const ShapeSegment& outEdge = edge[i];
            const double turn = cross(in.b - in.a, outEdge.b - outEdge.a);
            if (turn >= 0.0) {
                continue; // convex (or straight): the edges' layers meet inside
            }
            const double phi = std::atan2(cross(in.normal, outEdge.normal),
                                          dot(in.normal, outEdge.normal)); // < 0: clockwise
            const double theta0 = std::atan2(in.normal.y, in.normal.x);
            const int count = static_cast<int>(std::lround(std::fabs(phi) * depth / spacing));
            for (int j = 0; j < count; ++j) {
                const double theta = theta0 + phi * (j + 0.5) / count;
                consider(v[i] + depth * glm::dvec2(std::cos(theta), std::sin(theta)), depth);
            }
        }
    }
    out = kept.points();
}

bool PolygonBoundary::admissible(glm::dvec2 from, glm::dvec2 to) const {
    double t = 0.0;
    return !containsLocal(to) && m_edges->firstCrossing(from, to, -1, t) < 0;
}

bool PolygonBoundary::pushOut(glm::dvec2 c, double eps, Contact& out) const {
    glm::dvec2 closest{0.0, 0.0};
    double distance = 0.0;
    const int k = m_edges->nearestOfAll(c, closest, distance);
    if (k < 0) {
        return false;
    }
    const ShapeSegment& e = m_edges->segments()[k];
    // From inside, the way to the nearest surface point continues outward (also at a reflex
    // corner, where the nearest point is the vertex).
    const glm::dvec2 dir = distance > 1e-12 ? (closest - c) / distance : -e.normal;
    for (const double scale : {1.0, 4.0, 16.0}) {
        const glm::dvec2 q = closest + scale * eps * dir;
        if (!containsLocal(q)) {
            out = {q, dir};
            return true;
        }
    }
    out = {closest - eps * e.normal, -e.normal};
    return true;
}

bool PolygonBoundary::collide(glm::dvec2 prev, glm::dvec2 cur, double /*spacing*/, double eps,
                              Contact& out) const {
    if (containsLocal(prev)) {
        // Inside at the start: the moving polygon swept over the particle (or the host moved
        // it onto the particle). Nearest surface point.
        return containsLocal(cur) && pushOut(cur, eps, out);
    }
    // Edges are counter-clockwise, so the outside of each edge is its right (-1) side.
    double t = 0.0;
    const int hit = m_edges->firstCrossing(prev, cur, -1, t);
    if (hit < 0) {
        return containsLocal(cur) && pushOut(cur, eps, out); // rounding at a vertex
    }
    const ShapeSegment& e = m_edges->segments()[hit];
    const glm::dvec2 n = -e.normal; // outward
    // Back outside the crossed edge's line, keeping the motion along it (a particle sliding on
    // a slope keeps sliding) ...
    const glm::dvec2 slid = cur + (eps - dot(cur - e.a, n)) * n;
    if (admissible(prev, slid)) {
        out = {slid, n};
        return true;
    }
    // ... or stopped at the end of that edge (it slid into a reflex corner) ...
    const glm::dvec2 stopped = geometry::closestOnSegment(e, cur) + eps * n;
    if (admissible(prev, stopped)) {
        out = {stopped, n};
        return true;
    }
    // ... or where its path met the surface, just before it (always outside: the path up to
    // the first crossing is).
    const double len = geometry::length(cur - prev);
    const double back = len > 0.0 ? std::max(0.0, t - eps / len) : 0.0;
    out = {prev + back * (cur - prev), n};
    return true;
}

} // namespace fluid
