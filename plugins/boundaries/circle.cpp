// fluid — built-in boundary plugin: solid disc, static or kinematic.
#include "shape_geometry.h"

#include <fluid/plugins/circle.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

namespace fluid {

using geometry::dot;

CircleBoundary::CircleBoundary(glm::vec2 center, float radius) : CircleBoundary() {
    setParam("radius", radius);
    setParam("x", center.x);
    setParam("y", center.y);
}

void CircleBoundary::build(double spacing, double support, std::vector<glm::dvec2>& out,
                           LocalBounds& bounds) {
    m_radius = value(kRadius);
    bounds.lo = {-m_radius, -m_radius};
    bounds.hi = {m_radius, m_radius};
    // How many samples the rings below lay, in double before any integer cast: `rings` rings
    // of radius R - (l + 0.5) spacing, each split into about 2 pi r / spacing pieces (3 at
    // least), and one at the centre.
    const double layerCountD = layerCount(spacing, support);
    const double rings = std::clamp(std::floor(m_radius / spacing - 0.75) + 1.0, 0.0, layerCountD);
    const double estimate =
        std::max(3.0 * rings, 2.0 * std::numbers::pi *
                                  (rings * m_radius - 0.5 * spacing * rings * rings) / spacing) +
        1.0;
    std::ostringstream what;
    what << "radius " << m_radius << " m";
    checkSampleCount(estimate, what.str(), spacing);
    // Rings where the fluid lattice's next rows would be, one support radius deep; what is left
    // at the centre of a small disc (less than half a spacing) gets one sample.
    // No more than the rings (and the centre) that fit: a tiny disc in a world whose support is
    // many spacings passes the estimate, but its layer count need not fit an int.
    const int layers = static_cast<int>(std::min(layerCountD, rings + 1.0));
    for (int l = 0; l < layers; ++l) {
        const double r = m_radius - (l + 0.5) * spacing;
        if (r < 0.25 * spacing) {
            out.emplace_back(0.0, 0.0);
            break;
        }
        const int count =
            std::max(3, static_cast<int>(std::lround(2.0 * std::numbers::pi * r / spacing)));
        // Alternate rings are turned by half a piece, as the rows of a packed lattice.
        const double offset = (l % 2) * 0.5;
        for (int k = 0; k < count; ++k) {
            const double a = 2.0 * std::numbers::pi * (k + offset) / count;
            out.emplace_back(r * std::cos(a), r * std::sin(a));
        }
    }
}

bool CircleBoundary::insideLocal(glm::dvec2 local) const {
    const double r = value(kRadius);
    return local.x * local.x + local.y * local.y < r * r;
}

bool CircleBoundary::collide(glm::dvec2 prev, glm::dvec2 cur, double /*spacing*/, double eps,
                             Contact& out) const {
    const double r2 = m_radius * m_radius;
    const double rim = m_radius + eps;
    auto radial = [&](glm::dvec2 from, glm::dvec2 fallback) {
        const double len = geometry::length(from);
        const glm::dvec2 n = len > 1e-12 * m_radius ? from / len : fallback;
        out = {rim * n, n};
        return true;
    };
    const bool curInside = dot(cur, cur) < r2;
    if (dot(prev, prev) < r2) {
        // Swept over by the moving disc (or the host moved it there): nearest rim point.
        return curInside && radial(cur, glm::dvec2(1.0, 0.0));
    }
    // First entry of the path prev + t d into the disc: |prev + t d|^2 = R^2.
    const glm::dvec2 d = cur - prev;
    const double a = dot(d, d);
    const double b = dot(prev, d);
    const double c = dot(prev, prev) - r2;
    const double disc = b * b - a * c;
    if (a > 0.0 && disc >= 0.0) {
        const double t = (-b - std::sqrt(disc)) / a;
        if (t >= 0.0 && t <= 1.0) {
            const glm::dvec2 entry = prev + t * d;
            // Radially out keeps the motion round the rim; a path past the centre (a small disc
            // and a fast particle) or through the disc goes back to its entry point instead.
            if (curInside && dot(cur, entry) > 0.0) {
                return radial(cur, entry / m_radius);
            }
            return radial(entry, glm::dvec2(1.0, 0.0));
        }
    }
    return curInside && radial(cur, glm::dvec2(1.0, 0.0)); // rounding at the rim
}

} // namespace fluid
