// fluid — built-in boundary plugin: chain of thin wall segments (open or closed).
#include "shape_geometry.h"

#include <fluid/error.h>
#include <fluid/plugins/chain.h>

#include <glm/common.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

namespace fluid {

using geometry::cross;
using geometry::dot;

ChainBoundary::ChainBoundary(std::span<const glm::vec2> points, bool closed) : ChainBoundary() {
    setPoints("points", points);
    setParam("closed", closed ? 1.0 : 0.0);
}

ChainBoundary::ChainBoundary() : KinematicShape(kType, kParams) {}

ChainBoundary::~ChainBoundary() = default;

std::span<const ShapeSegment> ChainBoundary::segments() const {
    return m_segments ? m_segments->segments() : std::span<const ShapeSegment>();
}

void ChainBoundary::checkShape() const {
    const std::span<const glm::vec2> points = pointsAt(kPoints);
    const std::size_t n = points.size();
    const bool closed = value(kClosed) >= 0.5;
    if (n < 2 || (closed && n < 3)) {
        throw Error("plugin 'boundary.chain': parameter 'points' has " + std::to_string(n) +
                        " points; set " + (closed ? "3" : "2") +
                        " to 4096 with setPoints before the first step" +
                        (closed ? " (a closed chain needs 3)" : ""),
                    ErrorCode::OutOfRange);
    }
    checkCoordinates(kPoints);
    const std::size_t count = closed ? n : n - 1;
    for (std::size_t i = 0; i < count; ++i) {
        const glm::vec2 a = points[i], b = points[(i + 1) % n];
        if (a == b) {
            std::ostringstream s;
            s << "plugin 'boundary.chain': parameter 'points' repeats point " << i << " = (" << a.x
              << ", " << a.y << ") as point " << (i + 1) % n
              << "; expected distinct consecutive points (unit: m)";
            throw Error(s.str(), ErrorCode::BadArgument);
        }
    }
}

void ChainBoundary::validate() const {
    if (!pointsAt(kPoints).empty()) {
        checkShape(); // else not set yet (`closed` may come first): the first step says so
    }
}

void ChainBoundary::build(double spacing, double support, std::vector<glm::dvec2>& out,
                          LocalBounds& bounds) {
    checkShape();
    const std::span<const glm::vec2> points = pointsAt(kPoints);
    const std::size_t n = points.size();
    const bool closed = value(kClosed) >= 0.5;
    std::vector<glm::dvec2> v(points.begin(), points.end());
    const std::size_t count = closed ? n : n - 1;
    std::vector<ShapeSegment> segments;
    bounds.lo = glm::dvec2(INFINITY);
    bounds.hi = glm::dvec2(-INFINITY);
    // How many samples the row below lays, in double before any integer cast.
    double length = 0.0, estimate = 1.0;
    for (std::size_t i = 0; i < count; ++i) {
        segments.push_back(geometry::makeSegment(v[i], v[(i + 1) % n]));
        length += segments.back().length;
        estimate += std::max(1.0, segments.back().length / spacing);
    }
    std::ostringstream what;
    what << "length " << length << " m";
    checkSampleCount(estimate, what.str(), spacing);
    for (const glm::dvec2 p : v) {
        bounds.lo = glm::min(bounds.lo, p);
        bounds.hi = glm::max(bounds.hi, p);
    }
    // One row along the wall, about one spacing apart, vertices included (where short segments
    // crowd the row, the first sample within 0.55 spacing wins).
    geometry::SpacedPoints kept(0.55 * spacing);
    for (const ShapeSegment& s : segments) {
        const int pieces = std::max(1, static_cast<int>(std::lround(s.length / spacing)));
        for (int k = 0; k < pieces; ++k) {
            kept.add(s.a + (s.b - s.a) * (double(k) / pieces));
        }
    }
    if (!closed) {
        kept.add(v[n - 1]);
    }
    out = kept.points();
    m_segments = std::make_unique<geometry::SegmentSet>();
    m_segments->build(std::move(segments), support);
}

bool ChainBoundary::crossesAny(glm::dvec2 from, glm::dvec2 to) const {
    double t = 0.0;
    return m_segments->firstCrossing(from, to, 0, t) >= 0;
}

bool ChainBoundary::collide(glm::dvec2 prev, glm::dvec2 cur, double spacing, double /*eps*/,
                            Contact& out) const {
    const double clearance = kClearance * spacing;
    glm::dvec2 q = cur;
    glm::dvec2 normal{0.0, 1.0};
    bool moved = false;
    // A path through a segment goes back to the side it came from. Every candidate is checked
    // against all segments from `prev`, so no resolution can carry it through another wall.
    double t = 0.0;
    const int hit = m_segments->firstCrossing(prev, cur, 0, t);
    if (hit >= 0) {
        const ShapeSegment& e = m_segments->segments()[hit];
        // prev lies strictly on one side (a path from the line itself crosses nothing).
        const glm::dvec2 side = cross(e.b - e.a, prev - e.a) > 0.0 ? e.normal : -e.normal;
        const glm::dvec2 slid = cur + (clearance - dot(cur - e.a, side)) * side;
        const glm::dvec2 stopped = geometry::closestOnSegment(e, cur) + clearance * side;
        if (!crossesAny(prev, slid)) {
            q = slid; // keeps its motion along the wall
        } else if (!crossesAny(prev, stopped)) {
            q = stopped; // slid into a corner: stopped at the segment's end
        } else {
            // Where the path met the wall, backed off by the clearance: the path up to its
            // first crossing crosses nothing.
            const double len = geometry::length(cur - prev);
            q = prev + std::max(0.0, t - clearance / len) * (cur - prev);
        }
        normal = side;
        moved = true;
    }
    // Clearance: out along the way from the nearest wall point, unless that would cross
    // another segment (a sharp corner); a few rounds settle a particle between two segments.
    for (int round = 0; round < 4; ++round) {
        glm::dvec2 closest{0.0, 0.0};
        double distance = 0.0;
        const int k = m_segments->nearest(q, clearance, closest, distance);
        if (k < 0 || distance >= clearance * (1.0 - 1e-9)) {
            break;
        }
        glm::dvec2 dir;
        if (distance > 1e-12 * clearance) {
            dir = (q - closest) / distance;
        } else {
            // On the wall itself: to the side the particle came from.
            const ShapeSegment& s = m_segments->segments()[k];
            dir = cross(s.b - s.a, prev - s.a) >= 0.0 ? s.normal : -s.normal;
        }
        const glm::dvec2 pushed = closest + clearance * dir;
        if (crossesAny(q, pushed)) {
            break;
        }
        q = pushed;
        normal = dir;
        moved = true;
    }
    if (moved) {
        out = {q, normal};
    }
    return moved;
}

} // namespace fluid
