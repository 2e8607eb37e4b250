// fluid — segment geometry shared by the shape boundaries (internal; double precision).
#pragma once

#include <fluid/plugins/kinematic_shape.h>

#include <glm/common.hpp>
#include <glm/vec2.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <unordered_map>
#include <vector>

namespace fluid::geometry {

inline double cross(glm::dvec2 a, glm::dvec2 b) {
    return a.x * b.y - a.y * b.x;
}
inline double dot(glm::dvec2 a, glm::dvec2 b) {
    return a.x * b.x + a.y * b.y;
}
inline double length(glm::dvec2 a) {
    return std::sqrt(dot(a, a));
}

using Segment = ShapeSegment;

inline Segment makeSegment(glm::dvec2 a, glm::dvec2 b) {
    Segment s;
    s.a = a;
    s.b = b;
    s.length = length(b - a);
    if (s.length > 0.0) {
        s.normal = glm::dvec2(-(b.y - a.y), b.x - a.x) / s.length;
    }
    return s;
}

/// Closest point to p on the segment.
inline glm::dvec2 closestOnSegment(const Segment& s, glm::dvec2 p) {
    const glm::dvec2 e = s.b - s.a;
    const double ee = dot(e, e);
    const double u = ee > 0.0 ? std::clamp(dot(p - s.a, e) / ee, 0.0, 1.0) : 0.0;
    return s.a + u * e;
}

// Tolerance on the segment parameter of a crossing: a path through the shared vertex of two
// segments must count for at least one of them despite rounding.
inline constexpr double kEndSlack = 1e-9;

/// Where the path p -> q leaves the side of the segment's line that p lies strictly on and
/// reaches or passes the line within the segment: the path parameter t in (0, 1], or -1.
/// `from` selects the sides that count: +1 only paths starting on the left, -1 only on the
/// right, 0 both. A path starting exactly on the line never crosses (it has no side yet).
inline double crossing(glm::dvec2 p, glm::dvec2 q, const Segment& s, int from = 0) {
    const glm::dvec2 e = s.b - s.a;
    const double sp = cross(e, p - s.a);
    const double sq = cross(e, q - s.a);
    if (sp == 0.0 || (sp > 0.0 && sq > 0.0) || (sp < 0.0 && sq < 0.0)) {
        return -1.0;
    }
    if ((from > 0 && sp < 0.0) || (from < 0 && sp > 0.0)) {
        return -1.0;
    }
    const double t = sp / (sp - sq);
    const glm::dvec2 x = p + t * (q - p);
    const double ee = dot(e, e);
    const double u = ee > 0.0 ? dot(x - s.a, e) / ee : 0.0;
    if (u < -kEndSlack || u > 1.0 + kEndSlack) {
        return -1.0;
    }
    return std::min(t, 1.0);
}

/// A uniform grid over a shape's segments so that a particle's tests look only at the
/// segments near its path: cells (the segments whose box meets each cell) and rows (the
/// segments whose y-range meets each horizontal band, for the even-odd test). Built on the
/// stepping thread; queries are const and allocate nothing.
class SegmentGrid {
public:
    /// Indexes `segments` over their bounds [lo, hi] with square cells about `cell` wide (at
    /// most 128 a side).
    void build(std::span<const Segment> segments, glm::dvec2 lo, glm::dvec2 hi, double cell) {
        const double extent = std::max(hi.x - lo.x, hi.y - lo.y);
        m_cell = std::max(cell, extent / 128.0);
        if (!(m_cell > 0.0)) {
            m_cell = 1.0;
        }
        m_lo = lo;
        m_nx = static_cast<int>(std::floor((hi.x - lo.x) / m_cell)) + 1;
        m_ny = static_cast<int>(std::floor((hi.y - lo.y) / m_cell)) + 1;
        std::vector<std::vector<uint32_t>> cells(std::size_t(m_nx) * m_ny), rows(m_ny);
        for (std::size_t k = 0; k < segments.size(); ++k) {
            const Segment& s = segments[k];
            const int x0 = cellX(std::min(s.a.x, s.b.x)), x1 = cellX(std::max(s.a.x, s.b.x));
            const int y0 = cellY(std::min(s.a.y, s.b.y)), y1 = cellY(std::max(s.a.y, s.b.y));
            for (int y = y0; y <= y1; ++y) {
                rows[y].push_back(static_cast<uint32_t>(k));
                for (int x = x0; x <= x1; ++x) {
                    cells[std::size_t(y) * m_nx + x].push_back(static_cast<uint32_t>(k));
                }
            }
        }
        flatten(cells, m_cellStart, m_cellItems);
        flatten(rows, m_rowStart, m_rowItems);
    }
    /// Calls f(k) for every segment whose box meets [lo, hi] (some more than once).
    template <class F> void forEach(glm::dvec2 lo, glm::dvec2 hi, F&& f) const {
        if (hi.x < m_lo.x || hi.y < m_lo.y || lo.x > m_lo.x + m_nx * m_cell ||
            lo.y > m_lo.y + m_ny * m_cell) {
            return;
        }
        const int x0 = cellX(lo.x), x1 = cellX(hi.x), y0 = cellY(lo.y), y1 = cellY(hi.y);
        for (int y = y0; y <= y1; ++y) {
            for (int x = x0; x <= x1; ++x) {
                const std::size_t c = std::size_t(y) * m_nx + x;
                for (uint32_t i = m_cellStart[c]; i < m_cellStart[c + 1]; ++i) {
                    f(m_cellItems[i]);
                }
            }
        }
    }
    /// Calls f(k) once for every segment whose y-range may contain `y`.
    template <class F> void forEachInRow(double y, F&& f) const {
        if (y < m_lo.y || y > m_lo.y + m_ny * m_cell) {
            return;
        }
        const int r = cellY(y);
        for (uint32_t i = m_rowStart[r]; i < m_rowStart[r + 1]; ++i) {
            f(m_rowItems[i]);
        }
    }

private:
    int cellX(double x) const { return cellOf((x - m_lo.x) / m_cell, m_nx); }
    int cellY(double y) const { return cellOf((y - m_lo.y) / m_cell, m_ny); }
    // Clamped in double before the cast: a particle far away (or a NaN) gives an edge cell, not
    // an out-of-range float-to-int conversion (undefined behaviour).
    static int cellOf(double f, int n) {
        if (!(f >= 0.0)) {
            return 0;
        }
        return f >= double(n - 1) ? n - 1 : static_cast<int>(f);
    }
    static void flatten(const std::vector<std::vector<uint32_t>>& lists,
                        std::vector<uint32_t>& start, std::vector<uint32_t>& items) {
        start.assign(1, 0);
        items.clear();
        for (const auto& list : lists) {
            items.insert(items.end(), list.begin(), list.end());
            start.push_back(static_cast<uint32_t>(items.size()));
        }
    }
    glm::dvec2 m_lo{0.0, 0.0};
    double m_cell = 1.0;
    int m_nx = 1, m_ny = 1;
    std::vector<uint32_t> m_cellStart{0, 0}, m_cellItems, m_rowStart{0, 0}, m_rowItems;
};

/// A shape's segments with their grid: the queries a projection asks, each looking only at
/// the segments near the point or path. Built on the stepping thread; queries are const.
class SegmentSet {
public:
    /// Takes the segments; `cell` is the grid's cell size (unit: m; about a support radius).
    void build(std::vector<Segment> segments, double cell) {
        m_segments = std::move(segments);
        glm::dvec2 lo = m_segments.empty() ? glm::dvec2(0.0) : m_segments[0].a, hi = lo;
        for (const Segment& s : m_segments) {
            lo = glm::dvec2(std::min({lo.x, s.a.x, s.b.x}), std::min({lo.y, s.a.y, s.b.y}));
            hi = glm::dvec2(std::max({hi.x, s.a.x, s.b.x}), std::max({hi.y, s.a.y, s.b.y}));
        }
        m_grid.build(m_segments, lo, hi, cell);
    }
    /// The segments.
    std::span<const Segment> segments() const { return m_segments; }

    /// The first crossing of p -> q (see `crossing`; `from` as there): its segment, or -1;
    /// `t` gets the path parameter. Ties go to the lowest index.
    int firstCrossing(glm::dvec2 p, glm::dvec2 q, int from, double& t) const {
        int hit = -1;
        t = 2.0;
        m_grid.forEach(glm::min(p, q), glm::max(p, q), [&](uint32_t k) {
            const double tk = crossing(p, q, m_segments[k], from);
            if (tk >= 0.0 && (tk < t || (tk == t && int(k) < hit))) {
                t = tk;
                hit = static_cast<int>(k);
            }
        });
        return hit;
    }
    /// The segment nearest to p among those within `within` of it (unit: m): its index, or -1
    /// when none is that close; `closest` and `distance` get the point and the distance.
    int nearest(glm::dvec2 p, double within, glm::dvec2& closest, double& distance) const {
        int best = -1;
        distance = INFINITY;
        m_grid.forEach(p - within, p + within, [&](uint32_t k) {
            const glm::dvec2 c = closestOnSegment(m_segments[k], p);
            const double d = length(p - c);
            if (d <= within && (d < distance || (d == distance && int(k) < best))) {
                distance = d;
                closest = c;
                best = static_cast<int>(k);
            }
        });
        return best;
    }
    /// The nearest segment of all (for points deep inside a solid): as `nearest`.
    int nearestOfAll(glm::dvec2 p, glm::dvec2& closest, double& distance) const {
        int best = -1;
        distance = INFINITY;
        for (std::size_t k = 0; k < m_segments.size(); ++k) {
            const glm::dvec2 c = closestOnSegment(m_segments[k], p);
            const double d = length(p - c);
            if (d < distance) {
                distance = d;
                closest = c;
                best = static_cast<int>(k);
            }
        }
        return best;
    }
    /// Even-odd test: true when p lies inside the closed outline (any winding). A horizontal
    /// ray to the right crosses only segments whose y-range holds p.y: the row's segments.
    bool inside(glm::dvec2 p) const {
        bool in = false;
        m_grid.forEachInRow(p.y, [&](uint32_t k) {
            const Segment& s = m_segments[k];
            if ((s.a.y > p.y) != (s.b.y > p.y)) {
                const double x = s.a.x + (p.y - s.a.y) * (s.b.x - s.a.x) / (s.b.y - s.a.y);
                if (p.x < x) {
                    in = !in;
                }
            }
        });
        return in;
    }

private:
    std::vector<Segment> m_segments;
    SegmentGrid m_grid;
};

/// Keeps points at least `radius` apart, first come first kept (a hash of cells `radius` wide;
/// deterministic: lookups only, no iteration over the hash).
class SpacedPoints {
public:
    explicit SpacedPoints(double radius) : m_radius(radius) {}
    /// Adds p unless a kept point lies closer than the radius; true when kept.
    bool add(glm::dvec2 p) {
        const int64_t cx = cellOf(p.x / m_radius), cy = cellOf(p.y / m_radius);
        for (int64_t dy = -1; dy <= 1; ++dy) {
            for (int64_t dx = -1; dx <= 1; ++dx) {
                const auto it = m_cells.find(key(cx + dx, cy + dy));
                if (it == m_cells.end()) {
                    continue;
                }
                for (const uint32_t k : it->second) {
                    const glm::dvec2 d = m_points[k] - p;
                    if (dot(d, d) < m_radius * m_radius) {
                        return false;
                    }
                }
            }
        }
        m_cells[key(cx, cy)].push_back(static_cast<uint32_t>(m_points.size()));
        m_points.push_back(p);
        return true;
    }
    /// The kept points, in the order added.
    const std::vector<glm::dvec2>& points() const { return m_points; }

private:
    // Cell index, clamped before the cast (2^50 cells of any radius cover every coordinate a
    // shape may have, and cell +- 1 cannot overflow); a NaN goes to the lowest cell.
    static int64_t cellOf(double f) {
        constexpr double kLimit = 0x1p50;
        const double c = std::floor(f);
        return c >= -kLimit ? static_cast<int64_t>(std::min(c, kLimit)) : int64_t(-kLimit);
    }
    // Hash of a cell, in unsigned arithmetic (wraps by definition; signed overflow would not).
    static uint64_t key(int64_t x, int64_t y) {
        return uint64_t(x) * 73856093u ^ uint64_t(y) * 19349663u;
    }
    double m_radius;
    std::vector<glm::dvec2> m_points;
    std::unordered_map<uint64_t, std::vector<uint32_t>> m_cells;
};

} // namespace fluid::geometry
