// fluid::gl — CPU tessellation of shapes into triangles: ear clipping for polygons, fans for
// discs, quads with mitred (or bevelled) joints for thick lines.
#include <fluid/gl/shapes.h>
#include <fluid/internal/checks.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace fluid::gl {

namespace {

// Mitre length over half the line width above which a joint is bevelled (a turn sharper than
// about 140 degrees): a longer spike would poke far out of the line.
constexpr float kMitreLimit = 3.0f;
// Automatic disc segments: the chord may deviate from the circle by this (unit: px) at the
// highest zoom the header promises.
constexpr float kMaxChordError = 0.25f;
constexpr float kMaxPixelsPerMetre = 4000.0f;
constexpr uint32_t kMinSegments = 12;
constexpr uint32_t kMaxSegments = 256;

float cross(glm::vec2 a, glm::vec2 b) {
    return a.x * b.y - a.y * b.x;
}

using internal::finite;

// Scratch buffers for one tessellation, reused across calls so a frame's shapes do not
// allocate once warm. thread_local: batches may be built on several threads at once.
struct Scratch {
    std::vector<glm::vec2> points;
    std::vector<uint32_t> ring;
    std::vector<glm::vec2> startLeft, startRight, endLeft, endRight;
};

Scratch& scratch() {
    thread_local Scratch s;
    return s;
}

// Copies the finite points without consecutive duplicates (and without a repeated first point
// at the end): zero-length edges have no direction.
void cleanPoints(std::span<const glm::vec2> in, std::vector<glm::vec2>& out) {
    out.clear();
    for (const glm::vec2 p : in) {
        if (finite(p) && (out.empty() || p != out.back())) {
            out.push_back(p);
        }
    }
    if (out.size() > 1 && out.back() == out.front()) {
        out.pop_back();
    }
}

uint32_t autoSegments(float radius) {
    // Chord error r (1 - cos(pi / n)) ~ r pi^2 / (2 n^2) <= e / s  =>  n >= pi sqrt(r s / 2e).
    const float n = std::numbers::pi_v<float> *
                    std::sqrt(radius * kMaxPixelsPerMetre / (2.0f * kMaxChordError));
    if (!(n < float(kMaxSegments))) {
        return kMaxSegments;
    }
    return std::max(kMinSegments, static_cast<uint32_t>(std::ceil(n)));
}

// Inclusive point-in-triangle test for a counter-clockwise triangle.
bool insideCcw(glm::vec2 p, glm::vec2 a, glm::vec2 b, glm::vec2 c) {
    return cross(b - a, p - a) >= 0.0f && cross(c - b, p - b) >= 0.0f &&
           cross(a - c, p - c) >= 0.0f;
}

} // namespace

void ShapeBatch::clear() {
    m_vertices.clear();
}

void ShapeBatch::polygon(std::span<const glm::vec2> points, glm::vec4 colour) {
    Scratch& s = scratch();
    std::vector<glm::vec2>& p = s.points;
    cleanPoints(points, p);
    const size_t n = p.size();
    if (n < 3) {
        return;
    }
    // Shoelace: the sign gives the winding; ear tests below are written for counter-clockwise.
    float area2 = 0.0f;
    for (size_t i = 0; i < n; ++i) {
        area2 += cross(p[i], p[(i + 1) % n]);
    }
    if (area2 == 0.0f || !std::isfinite(area2)) {
        return;
    }
    const float orient = area2 > 0.0f ? 1.0f : -1.0f;
    auto emit = [&](uint32_t a, uint32_t b, uint32_t c) {
        m_vertices.push_back({p[a], colour});
        m_vertices.push_back({p[b], colour});
        m_vertices.push_back({p[c], colour});
    };

    // Convex: a fan, no search.
    bool convex = true;
    for (size_t i = 0; i < n && convex; ++i) {
        const glm::vec2 e0 = p[(i + 1) % n] - p[i];
        const glm::vec2 e1 = p[(i + 2) % n] - p[(i + 1) % n];
        convex = cross(e0, e1) * orient >= 0.0f;
    }
    if (convex) {
        for (uint32_t i = 1; i + 1 < n; ++i) {
            emit(0, i, i + 1);
        }
        return;
    }

    // Ear clipping [Eberly, "Triangulation by Ear Clipping"]: O(n^2) per ear, fine for the
    // tens of points of level geometry.
    std::vector<uint32_t>& ring = s.ring;
    ring.resize(n);
    for (uint32_t i = 0; i < n; ++i) {
        ring[i] = i;
    }
    auto isEar = [&](size_t at) {
        const size_t m = ring.size();
        const uint32_t ia = ring[(at + m - 1) % m], ib = ring[at], ic = ring[(at + 1) % m];
        glm::vec2 a = p[ia], b = p[ib], c = p[ic];
        if (cross(b - a, c - b) * orient <= 0.0f) {
            return false; // reflex or flat corner
        }
        if (orient < 0.0f) {
            std::swap(a, c);
        }
        for (const uint32_t j : ring) {
            const glm::vec2 q = p[j];
            if (j == ia || j == ib || j == ic || q == a || q == b || q == c) {
                continue;
            }
            if (insideCcw(q, a, b, c)) {
                return false;
            }
        }
        return true;
    };
    size_t at = 0;
    while (ring.size() > 3) {
        const size_t m = ring.size();
        // Look for an ear from where the last one was cut. If there is none (a self-intersecting
        // or degenerate polygon), the corner we come back to is cut anyway so the loop ends; the
        // header allows gaps for such polygons.
        for (size_t tries = 0; tries < m && !isEar(at); ++tries) {
            at = (at + 1) % m;
        }
        emit(ring[(at + m - 1) % m], ring[at], ring[(at + 1) % m]);
        ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(at));
        if (at >= ring.size()) {
            at = 0;
        }
    }
    emit(ring[0], ring[1], ring[2]);
}

void ShapeBatch::rect(glm::vec2 lo, glm::vec2 hi, glm::vec4 colour) {
    const glm::vec2 a = glm::min(lo, hi), b = glm::max(lo, hi);
    const glm::vec2 corners[4] = {a, {b.x, a.y}, b, {a.x, b.y}};
    m_vertices.push_back({corners[0], colour});
    m_vertices.push_back({corners[1], colour});
    m_vertices.push_back({corners[2], colour});
    m_vertices.push_back({corners[0], colour});
    m_vertices.push_back({corners[2], colour});
    m_vertices.push_back({corners[3], colour});
}

void ShapeBatch::disc(glm::vec2 center, float radius, glm::vec4 colour, uint32_t segments) {
    if (!(radius > 0.0f) || !std::isfinite(radius) || !finite(center)) {
        return;
    }
    const uint32_t n = segments == 0 ? autoSegments(radius) : std::max(segments, 3u);
    const float step = 2.0f * std::numbers::pi_v<float> / float(n);
    glm::vec2 previous = center + glm::vec2(radius, 0.0f);
    for (uint32_t i = 1; i <= n; ++i) {
        const float angle = step * float(i % n);
        const glm::vec2 next = center + radius * glm::vec2(std::cos(angle), std::sin(angle));
        m_vertices.push_back({center, colour});
        m_vertices.push_back({previous, colour});
        m_vertices.push_back({next, colour});
        previous = next;
    }
}

void ShapeBatch::ring(glm::vec2 center, float radius, float width, glm::vec4 colour,
                      uint32_t segments) {
    if (!(radius > 0.0f) || !(width > 0.0f) || !std::isfinite(radius) || !finite(center)) {
        return;
    }
    if (width >= radius) {
        disc(center, radius, colour, segments);
        return;
    }
    const float inner = radius - width;
    const uint32_t n = segments == 0 ? autoSegments(radius) : std::max(segments, 3u);
    const float step = 2.0f * std::numbers::pi_v<float> / float(n);
    glm::vec2 dirPrev(1.0f, 0.0f);
    for (uint32_t i = 1; i <= n; ++i) {
        const float angle = step * float(i % n);
        const glm::vec2 dir(std::cos(angle), std::sin(angle));
        const glm::vec2 o0 = center + radius * dirPrev, o1 = center + radius * dir;
        const glm::vec2 i0 = center + inner * dirPrev, i1 = center + inner * dir;
        m_vertices.push_back({o0, colour});
        m_vertices.push_back({o1, colour});
        m_vertices.push_back({i1, colour});
        m_vertices.push_back({o0, colour});
        m_vertices.push_back({i1, colour});
        m_vertices.push_back({i0, colour});
        dirPrev = dir;
    }
}

void ShapeBatch::polyline(std::span<const glm::vec2> points, float width, glm::vec4 colour,
                          bool closed) {
    if (!(width > 0.0f) || !std::isfinite(width)) {
        return;
    }
    Scratch& s = scratch();
    std::vector<glm::vec2>& p = s.points;
    cleanPoints(points, p);
    const size_t n = p.size();
    if (n < 2) {
        return;
    }
    if (n < 3) {
        closed = false; // a closed two-point line is the same segment twice
    }
    const float hw = 0.5f * width;
    const size_t segments = closed ? n : n - 1;
    auto direction = [&](size_t seg) { return glm::normalize(p[(seg + 1) % n] - p[seg]); };
    auto normalOf = [](glm::vec2 d) { return glm::vec2(-d.y, d.x); };

    // Per vertex: where the segment leaving it starts and where the one arriving ends, on the
    // left (+normal) and right side. A mitre joint shares one pair; a bevel has two.
    s.startLeft.resize(n);
    s.startRight.resize(n);
    s.endLeft.resize(n);
    s.endRight.resize(n);
    for (size_t i = 0; i < n; ++i) {
        const bool hasIn = closed || i > 0;
        const bool hasOut = closed || i + 1 < n;
        const glm::vec2 dOut = hasOut ? direction(i) : direction((i + n - 1) % n);
        const glm::vec2 dIn = hasIn ? direction((i + n - 1) % n) : dOut;
        const glm::vec2 nIn = normalOf(dIn), nOut = normalOf(dOut);
        if (!hasIn || !hasOut) {
            // Open end: square cut across the segment.
            s.startLeft[i] = s.endLeft[i] = p[i] + nOut * hw;
            s.startRight[i] = s.endRight[i] = p[i] - nOut * hw;
            continue;
        }
        const glm::vec2 sum = nIn + nOut;
        const float sumLength = glm::length(sum);
        const glm::vec2 mitre = sumLength > 1e-6f ? sum / sumLength : nIn;
        const float cosHalf = glm::dot(mitre, nIn);
        if (cosHalf * kMitreLimit >= 1.0f) {
            const glm::vec2 offset = mitre * (hw / cosHalf);
            s.startLeft[i] = s.endLeft[i] = p[i] + offset;
            s.startRight[i] = s.endRight[i] = p[i] - offset;
            continue;
        }
        // Bevel: each segment ends square and a triangle fills the outer side of the turn.
        s.endLeft[i] = p[i] + nIn * hw;
        s.endRight[i] = p[i] - nIn * hw;
        s.startLeft[i] = p[i] + nOut * hw;
        s.startRight[i] = p[i] - nOut * hw;
        const bool turnsLeft = cross(dIn, dOut) > 0.0f;
        m_vertices.push_back({p[i], colour});
        m_vertices.push_back({turnsLeft ? s.endRight[i] : s.endLeft[i], colour});
        m_vertices.push_back({turnsLeft ? s.startRight[i] : s.startLeft[i], colour});
    }
    for (size_t seg = 0; seg < segments; ++seg) {
        const size_t a = seg, b = (seg + 1) % n;
        m_vertices.push_back({s.startLeft[a], colour});
        m_vertices.push_back({s.startRight[a], colour});
        m_vertices.push_back({s.endRight[b], colour});
        m_vertices.push_back({s.startLeft[a], colour});
        m_vertices.push_back({s.endRight[b], colour});
        m_vertices.push_back({s.endLeft[b], colour});
    }
}

void ShapeBatch::line(glm::vec2 a, glm::vec2 b, float width, glm::vec4 colour) {
    const glm::vec2 points[2] = {a, b};
    polyline(points, width, colour, false);
}

} // namespace fluid::gl
