// fluid — ray casts against the liquid, the liquid at a point and the drawn surface's field
// (query.h, surface_field.h), through the query grid (query_grid.h).
//
// Along a ray the field of each particle is a polynomial of the distance t along it:
// u(t) = peak - (t - tc)^2 / R^2 and w = u^3 where u > 0, with tc the particle's closest
// approach and peak = 1 - (its distance from the ray)^2 / R^2. So bounds of the field over an
// interval of t cost one pass over the particles (each kernel's largest and smallest value on
// it), and the first crossing of the threshold is found by splitting the interval where the
// bounds cannot decide: no crossing wider than the final tolerance is missed, whatever the step.
// A crossing once bracketed within a twentieth of a spacing is refined by regula falsi.
#include <fluid/query.h>
#include <fluid/surface_field.h>

#include "kernels.h"
#include "query_grid.h"

#include <fluid/error.h>
#include <fluid/internal/checks.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace fluid {

void validate(const SurfaceField& field, const char* function) {
    const std::string prefix = std::string(function) + ": field.";
    internal::checkRange(prefix, "fieldRadius", field.fieldRadius, SurfaceField::kMinRadius,
                         SurfaceField::kMaxRadius, "1");
    internal::checkRange(prefix, "threshold", field.threshold, SurfaceField::kMinThreshold,
                         SurfaceField::kMaxThreshold, "1");
}

namespace {

using detail::WorldState;

void checkPoint(glm::vec2 p, const char* function, const char* name) {
    if (!internal::finite(p)) {
        std::ostringstream text;
        text << function << ": " << name << " = (" << p.x << ", " << p.y
             << ") is not finite (unit: m)";
        throw Error(text.str(), ErrorCode::BadArgument);
    }
}

// Per material: the field's 1/R^2, the solver kernel's support h and the rest area and density.
struct MaterialTerms {
    double invR2 = 0.0;
    float h = 0.0f;
    float area = 0.0f;
    float restDensity = 1.0f;
};

// What one query reads: the particles, the grid and the field's constants.
struct Setup {
    const detail::Particles& p;
    const detail::GridView& g;
    std::span<const uint32_t> order;
    double cell = 1.0;
    double minX = 0.0, minY = 0.0, maxX = 0.0, maxY = 0.0;
    std::vector<MaterialTerms> terms;
    double k = 0.0, d = 0.0, threshold = 0.0;
    double fieldReach = 0.0;  // the largest R (m)
    double kernelReach = 0.0; // the largest h (m)
    double tolerance = 0.0;   // crossings are found to within this (m)
    double bracket = 0.0;     // below this width a bracketed crossing is refined directly (m)
    double piece = 0.0;       // longer intervals are split into pieces of at most this (m)

    Setup(const WorldState& s, const SurfaceField& field)
        : p(s.particles), g(detail::queryGrid(const_cast<WorldState&>(s)).grid.view()),
          order(s.queryGrid->grid.order()) {
        const WorldState::QueryGrid& q = *s.queryGrid;
        cell = q.cell;
        minX = q.minX;
        minY = q.minY;
        maxX = q.maxX;
        maxY = q.maxY;
        k = field.kernelWeight();
        d = field.dropletLevel();
        threshold = field.threshold;
        double finest = std::numeric_limits<double>::max();
        terms.reserve(s.materials.size());
        for (const Material& m : s.materials) {
            const double spacing = particleSpacing(m, s.def.depth);
            const double radius = double(field.fieldRadius) * spacing;
            terms.push_back({1.0 / (radius * radius), m.smoothingDistance,
                             particleArea(m, s.def.depth), m.restDensity});
            fieldReach = std::max(fieldReach, radius);
            kernelReach = std::max(kernelReach, double(m.smoothingDistance));
            finest = std::min(finest, spacing);
        }
        tolerance = 0.01 * finest;
        bracket = 0.05 * finest;
        piece = finest;
    }

    // Cells on each side of a cell that can hold a particle within `reach` of a point in it.
    int64_t cellsFor(double reach) const {
        return std::max<int64_t>(1, int64_t(std::ceil(reach / cell * (1.0 + 1e-6))));
    }
    int64_t cellOf(double v) const { return int64_t(std::floor(v / cell)); }

    // f(b, e) for each range of sorted positions in the cells within `r` of (cx, cy), each
    // particle once.
    template <class F>
    void forCells(int64_t cx, int64_t cy, int64_t r, std::vector<uint32_t>& buckets, F&& f) const {
        if (!g.hashed) {
            const int64_t x0 = std::max(cx - r, g.ox),
                          x1 = std::min(cx + r, g.ox + int64_t(g.nx) - 1);
            const int64_t y0 = std::max(cy - r, g.oy),
                          y1 = std::min(cy + r, g.oy + int64_t(g.ny) - 1);
            for (int64_t y = y0; y <= y1 && x0 <= x1; ++y) {
                const int64_t row = (y - g.oy) * int64_t(g.nx);
                const uint32_t b = g.start[row + (x0 - g.ox)], e = g.start[row + (x1 - g.ox) + 1];
                if (b < e) {
                    f(b, e);
                }
            }
            return;
        }
        const int64_t side = 2 * r + 1;
        if (double(side) * double(side) > double(g.mask) + 1.0) {
            f(0u, g.count);
            return;
        }
        buckets.clear();
        for (int64_t y = cy - r; y <= cy + r; ++y) {
            for (int64_t x = cx - r; x <= cx + r; ++x) {
                buckets.push_back(detail::gridHash(x, y, g.mask));
            }
        }
        std::sort(buckets.begin(), buckets.end());
        buckets.erase(std::unique(buckets.begin(), buckets.end()), buckets.end());
        for (const uint32_t b : buckets) {
            if (g.start[b] < g.start[b + 1]) {
                f(g.start[b], g.start[b + 1]);
            }
        }
    }
};

// A straight path o + t dir (unit: m, dir a unit vector), t in [0, length].
struct Path {
    double ox = 0.0, oy = 0.0, dx = 0.0, dy = 0.0, length = 0.0;
};

// Clips the segment p1 + t dir, t in [0, length], to the particles' box grown by `grow`;
// false when it misses the box. `enter` and `exit` receive the t range kept.
bool clip(const Setup& S, double px, double py, double dx, double dy, double length, double grow,
          double& enter, double& exit) {
    enter = 0.0;
    exit = length;
    const double lo[2] = {S.minX - grow, S.minY - grow}, hi[2] = {S.maxX + grow, S.maxY + grow};
    const double o[2] = {px, py}, dir[2] = {dx, dy};
    for (int a = 0; a < 2; ++a) {
        if (dir[a] == 0.0) {
            if (o[a] < lo[a] || o[a] > hi[a]) {
                return false;
            }
            continue;
        }
        double t0 = (lo[a] - o[a]) / dir[a], t1 = (hi[a] - o[a]) / dir[a];
        if (t0 > t1) {
            std::swap(t0, t1);
        }
        enter = std::max(enter, t0);
        exit = std::min(exit, t1);
    }
    return enter <= exit;
}

// Calls seg(cx, cy, ta, tb, last) for the cells the path crosses, in order, with the interval
// of t inside each, until it returns true (then returns true).
template <class F> bool walk(const Setup& S, const Path& path, F&& seg) {
    int64_t cx = S.cellOf(path.ox), cy = S.cellOf(path.oy);
    const double inf = std::numeric_limits<double>::infinity();
    const int64_t sx = path.dx > 0.0 ? 1 : -1, sy = path.dy > 0.0 ? 1 : -1;
    double nextX =
        path.dx != 0.0 ? (double(cx + (path.dx > 0.0 ? 1 : 0)) * S.cell - path.ox) / path.dx : inf;
    double nextY =
        path.dy != 0.0 ? (double(cy + (path.dy > 0.0 ? 1 : 0)) * S.cell - path.oy) / path.dy : inf;
    const double stepX = path.dx != 0.0 ? S.cell / std::fabs(path.dx) : inf;
    const double stepY = path.dy != 0.0 ? S.cell / std::fabs(path.dy) : inf;
    double t = 0.0;
    for (;;) {
        const double end = std::min({nextX, nextY, path.length});
        const bool last = end >= path.length;
        if (seg(cx, cy, t, std::max(end, t), last)) {
            return true;
        }
        if (last) {
            return false;
        }
        if (nextX <= nextY) {
            cx += sx;
            t = nextX;
            nextX += stepX;
        } else {
            cy += sy;
            t = nextY;
            nextY += stepY;
        }
    }
}

// A particle whose field reaches the path: u(t) = peak - (t - tc)^2 invR2.
struct Near {
    double tc, peak, invR2;
    uint32_t index;
};

// The particles whose field reaches the path's interval [ta, tb] in cell (cx, cy).
void gather(const Setup& S, const Path& path, int64_t cx, int64_t cy, double ta, double tb,
            std::vector<Near>& out, std::vector<uint32_t>& buckets) {
    out.clear();
    const int64_t r = S.cellsFor(S.fieldReach);
    S.forCells(cx, cy, r, buckets, [&](uint32_t b, uint32_t e) {
        for (uint32_t k = b; k < e; ++k) {
            const uint32_t i = S.order[k];
            const double qx = double(S.p.px[i]) - path.ox, qy = double(S.p.py[i]) - path.oy;
            const double tc = qx * path.dx + qy * path.dy;
            const double across = qy * path.dx - qx * path.dy;
            const double invR2 = S.terms[S.p.material[i]].invR2;
            const double peak = 1.0 - across * across * invR2;
            if (peak <= 0.0) {
                continue;
            }
            // Its support on the path, tc +- sqrt(peak / invR2), must meet [ta, tb].
            const double gap = std::max({ta - tc, tc - tb, 0.0});
            if (gap * gap * invR2 >= peak) {
                continue;
            }
            out.push_back({tc, peak, invR2, i});
        }
    });
}

// The field at t along the path.
double fieldAt(const Setup& S, const std::vector<Near>& near, double t) {
    double sum = 0.0, most = 0.0;
    for (const Near& n : near) {
        const double dt = t - n.tc;
        const double u = n.peak - dt * dt * n.invR2;
        if (u > 0.0) {
            const double w = u * u * u;
            sum += w;
            most = std::max(most, w);
        }
    }
    return std::max(S.k * sum, S.d * most);
}

// The field's largest (`upper`) or smallest possible value over [ta, tb].
double fieldBound(const Setup& S, const std::vector<Near>& near, double ta, double tb, bool upper) {
    double sum = 0.0, most = 0.0;
    for (const Near& n : near) {
        double u = 0.0;
        if (upper) {
            const double dt = std::clamp(n.tc, ta, tb) - n.tc;
            u = n.peak - dt * dt * n.invR2;
        } else {
            const double da = ta - n.tc, db = tb - n.tc;
            u = n.peak - std::max(da * da, db * db) * n.invR2;
        }
        if (u > 0.0) {
            const double w = u * u * u;
            sum += w;
            most = std::max(most, w);
        }
    }
    return std::max(S.k * sum, S.d * most);
}

// How far the field is on the wanted side of the threshold at t: >= 0 there.
double side(const Setup& S, const std::vector<Near>& near, double t, bool inside) {
    const double a = fieldAt(S, near, t) - S.threshold;
    return inside ? a : -a;
}

// The crossing in [lo, hi], side(lo) < 0 <= side(hi), to within the tolerance: regula falsi
// with the Illinois rule (a few passes where bisection takes one per halving).
double refine(const Setup& S, const std::vector<Near>& near, double lo, double flo, double hi,
              double fhi, bool inside) {
    int kept = 0; // which end the last two steps kept: -1 lo, +1 hi
    for (int k = 0; k < 60 && hi - lo > S.tolerance; ++k) {
        double t = hi - fhi * (hi - lo) / (fhi - flo);
        if (!(t > lo && t < hi)) {
            t = 0.5 * (lo + hi);
        }
        // Near the end the estimate moves little: a probe half a tolerance beyond it closes
        // the bracket.
        if (t - lo < 0.5 * S.tolerance) {
            t = lo + 0.5 * S.tolerance;
        } else if (hi - t < 0.5 * S.tolerance) {
            t = hi - 0.5 * S.tolerance;
        }
        const double ft = side(S, near, t, inside);
        if (ft >= 0.0) {
            hi = t;
            fhi = ft;
            if (kept == 1) {
                flo *= 0.5;
            }
            kept = 1;
        } else {
            lo = t;
            flo = ft;
            if (kept == -1) {
                fhi *= 0.5;
            }
            kept = -1;
        }
    }
    return hi;
}

// The first t in [ta, tb] where the field is at least the threshold (`inside`) or below it (not
// `inside`), knowing it is not so at ta; -1 when there is none, and then it is not so at tb
// either. Exact but for crossings narrower than the tolerance, and within a bracket (`S.bracket`)
// the first of several crossings that close to each other.
double firstChange(const Setup& S, const std::vector<Near>& near, double ta, double tb,
                   bool inside) {
    const double width = tb - ta;
    if (width > S.piece) {
        // Pieces of a spacing first: the bounds of a whole cell's segment rarely decide.
        const int n = int(std::ceil(width / S.piece));
        for (int k = 0; k < n; ++k) {
            const double a = ta + width * k / n, b = k + 1 == n ? tb : ta + width * (k + 1) / n;
            const double t = firstChange(S, near, a, b, inside);
            if (t >= 0.0) {
                return t;
            }
        }
        return -1.0;
    }
    const double bound = fieldBound(S, near, ta, tb, inside);
    if (inside ? bound < S.threshold : bound >= S.threshold) {
        return -1.0;
    }
    if (width <= S.tolerance) {
        return side(S, near, tb, inside) >= 0.0 ? tb : -1.0;
    }
    if (width <= S.bracket) {
        const double fb = side(S, near, tb, inside);
        if (fb >= 0.0) {
            return refine(S, near, ta, side(S, near, ta, inside), tb, fb, inside);
        }
    }
    const double mid = 0.5 * (ta + tb);
    const double left = firstChange(S, near, ta, mid, inside);
    return left >= 0.0 ? left : firstChange(S, near, mid, tb, inside);
}

// The first t along the path where the liquid starts (`inside`) or ends (not `inside`); -1 when
// it does not. `near` keeps the particles around that point.
double firstAlong(const Setup& S, const Path& path, bool inside, std::vector<Near>& near,
                  std::vector<uint32_t>& buckets) {
    double found = -1.0;
    walk(S, path, [&](int64_t cx, int64_t cy, double ta, double tb, bool) {
        gather(S, path, cx, cy, ta, tb, near, buckets);
        if (near.empty()) {
            if (!inside) {
                found = ta; // no particle reaches this cell: no liquid
                return true;
            }
            return false;
        }
        if ((fieldAt(S, near, ta) >= S.threshold) == inside) {
            found = ta;
            return true;
        }
        found = firstChange(S, near, ta, tb, inside);
        return found >= 0.0;
    });
    return found;
}

// Scratch of the searches that call no user code (so cannot re-enter): kept per thread.
struct Scratch {
    std::vector<Near> near;
    std::vector<uint32_t> buckets;
};
Scratch& scratch() {
    thread_local Scratch s;
    return s;
}

// The field at a point and what decides it, from the particles around it.
struct PointField {
    double field = 0.0;
    double gx = 0.0, gy = 0.0; // the field's gradient (1/m)
    uint32_t nearest = ~0u;    // nearest particle the field reaches from
};

PointField fieldAround(const Setup& S, double x, double y, std::vector<uint32_t>& buckets) {
    PointField out;
    double sum = 0.0, most = 0.0, sgx = 0.0, sgy = 0.0, mgx = 0.0, mgy = 0.0;
    double nearest2 = std::numeric_limits<double>::infinity();
    S.forCells(S.cellOf(x), S.cellOf(y), S.cellsFor(S.fieldReach), buckets,
               [&](uint32_t b, uint32_t e) {
                   for (uint32_t k = b; k < e; ++k) {
                       const uint32_t i = S.order[k];
                       const double rx = x - double(S.p.px[i]), ry = y - double(S.p.py[i]);
                       const double r2 = rx * rx + ry * ry;
                       const double invR2 = S.terms[S.p.material[i]].invR2;
                       const double u = 1.0 - r2 * invR2;
                       if (u <= 0.0) {
                           continue;
                       }
                       const double w = u * u * u;
                       // d w / d x = 3 u^2 (-2 invR2) (x - x_i)
                       const double g = -6.0 * u * u * invR2;
                       sum += w;
                       sgx += g * rx;
                       sgy += g * ry;
                       if (w > most) {
                           most = w;
                           mgx = g * rx;
                           mgy = g * ry;
                       }
                       if (r2 < nearest2 || (r2 == nearest2 && i < out.nearest)) {
                           nearest2 = r2;
                           out.nearest = i;
                       }
                   }
               });
    if (S.k * sum >= S.d * most) {
        out.field = S.k * sum;
        out.gx = S.k * sgx;
        out.gy = S.k * sgy;
    } else {
        out.field = S.d * most;
        out.gx = S.d * mgx;
        out.gy = S.d * mgy;
    }
    return out;
}

// The depth of (x, y) below the surface straight up (unit: m), for a point in the liquid.
double depthAt(const Setup& S, double x, double y) {
    Scratch& sc = scratch();
    Path up{x, y, 0.0, 1.0, S.maxY + S.fieldReach + S.cell - y};
    if (up.length <= 0.0) {
        return 0.0;
    }
    const double t = firstAlong(S, up, false, sc.near, sc.buckets);
    return t >= 0.0 ? t : up.length;
}

} // namespace

float surfaceField(const World& world, glm::vec2 point, const SurfaceField& field) {
    const WorldState& s = detail::queryState(world, "surfaceField");
    checkPoint(point, "surfaceField", "point");
    validate(field, "surfaceField");
    if (s.particles.size() == 0) {
        return 0.0f;
    }
    const Setup S(s, field);
    return float(fieldAround(S, point.x, point.y, scratch().buckets).field);
}

RayHit rayCast(const World& world, glm::vec2 p1, glm::vec2 p2, const SurfaceField& field) {
    const WorldState& s = detail::queryState(world, "rayCast");
    checkPoint(p1, "rayCast", "p1");
    checkPoint(p2, "rayCast", "p2");
    validate(field, "rayCast");
    RayHit hit;
    if (s.particles.size() == 0) {
        return hit;
    }
    const Setup S(s, field);
    Scratch& sc = scratch();
    const double dx = double(p2.x) - double(p1.x), dy = double(p2.y) - double(p1.y);
    const double length = std::hypot(dx, dy);
    const auto finish = [&](double x, double y, double t, bool inside, double dirX, double dirY) {
        const PointField f = fieldAround(S, x, y, sc.buckets);
        hit.hit = true;
        hit.startsInside = inside;
        hit.point = inside ? p1 : glm::vec2(float(x), float(y));
        hit.fraction = inside || length == 0.0 ? 0.0f : float(std::clamp(t / length, 0.0, 1.0));
        const double g = std::hypot(f.gx, f.gy);
        if (!inside) {
            hit.normal = g > 0.0 ? glm::vec2(float(-f.gx / g), float(-f.gy / g))
                                 : glm::vec2(float(-dirX), float(-dirY));
        }
        if (f.nearest != ~0u) {
            hit.index = f.nearest;
            hit.particle = s.handleOf(s.particles.slot[f.nearest]);
            hit.material = MaterialId{s.particles.material[f.nearest], s.tag.value()};
        }
    };
    if (length == 0.0 || !std::isfinite(length)) {
        if (fieldAround(S, p1.x, p1.y, sc.buckets).field >= S.threshold) {
            finish(p1.x, p1.y, 0.0, true, 0.0, 0.0);
        }
        return hit;
    }
    const double ux = dx / length, uy = dy / length;
    double enter = 0.0, exit = 0.0;
    if (!clip(S, p1.x, p1.y, ux, uy, length, S.fieldReach + S.cell, enter, exit)) {
        return hit;
    }
    const Path path{double(p1.x) + enter * ux, double(p1.y) + enter * uy, ux, uy, exit - enter};
    const double t = firstAlong(S, path, true, sc.near, sc.buckets);
    if (t < 0.0) {
        return hit;
    }
    const bool inside = enter == 0.0 && t == 0.0;
    finish(path.ox + t * ux, path.oy + t * uy, enter + t, inside, ux, uy);
    return hit;
}

namespace {

// rayCastParticles' arguments checked (errors name the value); the world's state.
const WorldState& checkParticleCast(const World& world, glm::vec2 p1, glm::vec2 p2, float radius,
                                    const RayVisitor& visit) {
    const char* const function = "rayCastParticles";
    const WorldState& s = detail::queryState(world, function);
    checkPoint(p1, function, "p1");
    checkPoint(p2, function, "p2");
    if (!visit) {
        throw Error("rayCastParticles: the visitor is empty", ErrorCode::BadArgument);
    }
    if (!(radius > 0.0f) || !std::isfinite(radius)) {
        throw Error("rayCastParticles: radius = " + internal::formatValue(radius) +
                        " is out of range (0, inf) (unit: m)",
                    ErrorCode::OutOfRange);
    }
    return s;
}

// What rayCastParticles reports for particle `index`, entered `t` (m) along the unit direction
// (ux, uy) from p1 (t = 0: the ray starts inside its circle).
RayParticleHit particleHit(const WorldState& s, uint32_t index, glm::vec2 p1, double ux,
                           double uy, double t, float fraction) {
    const detail::Particles& p = s.particles;
    RayParticleHit hit;
    hit.index = index;
    hit.handle = s.handleOf(p.slot[index]);
    hit.material = MaterialId{p.material[index], s.tag.value()};
    const double x = double(p1.x) + t * ux, y = double(p1.y) + t * uy;
    hit.point = t == 0.0 ? p1 : glm::vec2(float(x), float(y));
    const double nx = double(hit.point.x) - p.px[index], ny = double(hit.point.y) - p.py[index];
    const double n = std::hypot(nx, ny);
    hit.normal = n > 0.0 ? glm::vec2(float(nx / n), float(ny / n)) : glm::vec2(0.0f);
    hit.fraction = fraction;
    return hit;
}

// A particle cast's line: from p1 towards p2 (its length 0 when not finite), each particle a
// circle of `radius`.
struct CastLine {
    const detail::Particles& p;
    glm::vec2 p1;
    double length = 0.0, ux = 0.0, uy = 0.0, r2 = 0.0;

    CastLine(const detail::Particles& particles, glm::vec2 from, glm::vec2 to, float radius)
        : p(particles), p1(from), r2(double(radius) * double(radius)) {
        const double dx = double(to.x) - double(from.x), dy = double(to.y) - double(from.y);
        length = std::hypot(dx, dy);
        if (!std::isfinite(length)) {
            length = 0.0;
        }
        ux = length > 0.0 ? dx / length : 0.0;
        uy = length > 0.0 ? dy / length : 0.0;
    }

    // Where the ray enters particle i's circle (t from p1, unit: m; 0 when it starts inside),
    // or -1 when it misses it.
    double entry(uint32_t i) const {
        const double qx = double(p.px[i]) - p1.x, qy = double(p.py[i]) - p1.y;
        if (qx * qx + qy * qy <= r2) {
            return 0.0;
        }
        if (length == 0.0) {
            return -1.0;
        }
        const double tc = qx * ux + qy * uy;
        const double across = qy * ux - qx * uy;
        if (across * across > r2) {
            return -1.0;
        }
        const double t = tc - std::sqrt(r2 - across * across);
        return t >= 0.0 && t <= length ? t : -1.0;
    }

    // t as the fraction of the ray the visitor sees, in [0, 1].
    float fraction(double t) const {
        return length > 0.0 ? float(std::clamp(t / length, 0.0, 1.0)) : 0.0f;
    }
};

} // namespace

uint32_t rayCastParticles(const World& world, glm::vec2 p1, glm::vec2 p2, float radius,
                          const RayVisitor& visit) {
    const WorldState& s = checkParticleCast(world, p1, p2, radius, visit);
    const uint32_t count = s.particles.size();
    if (count == 0) {
        return 0;
    }
    const Setup S(s, SurfaceField{});
    const CastLine line(s.particles, p1, p2, radius);
    const double length = line.length, ux = line.ux, uy = line.uy;

    struct Visit {
        double t;
        uint32_t index;
    };
    // The ray's clip as a fraction: a particle at a fraction above it is not reported (compared
    // as the visitor sees fractions, so returning a hit's own fraction keeps its ties).
    float clipAt = 1.0f;
    uint32_t visited = 0;
    bool stopped = false;
    // Reports `visits` in increasing t (ties: index), as the visitor steers.
    const auto report = [&](std::vector<Visit>& visits) {
        std::sort(visits.begin(), visits.end(), [](const Visit& a, const Visit& b) {
            return a.t < b.t || (a.t == b.t && a.index < b.index);
        });
        for (const Visit& v : visits) {
            if (line.fraction(v.t) > clipAt) {
                stopped = true;
                return;
            }
            const RayParticleHit hit =
                particleHit(s, v.index, p1, ux, uy, v.t, line.fraction(v.t));
            ++visited;
            const float f = visit(hit);
            if (std::isnan(f)) {
                throw Error("rayCastParticles: the visitor returned nan; expected -1 (ignore "
                            "the particle), 0 (stop), a fraction in (0, 1) (clip the ray) or 1 "
                            "(go on)",
                            ErrorCode::BadArgument);
            }
            if (f < 0.0f) {
                continue;
            }
            if (f == 0.0f) {
                stopped = true;
                return;
            }
            clipAt = std::min(clipAt, f);
        }
    };

    std::vector<Visit> visits;
    const int64_t reach = S.cellsFor(radius);
    const double band = double(2 * reach + 1) * double(2 * reach + 1);
    if (length == 0.0 || band * 8.0 >= double(count)) {
        // A point, or a radius wider than the grid helps with: every particle.
        for (uint32_t i = 0; i < count; ++i) {
            const double t = line.entry(i);
            if (t >= 0.0) {
                visits.push_back({t, i});
            }
        }
        report(visits);
        return visited;
    }
    double enter = 0.0, exit = 0.0;
    if (!clip(S, p1.x, p1.y, ux, uy, length, double(radius) + S.cell, enter, exit)) {
        return 0;
    }
    const Path path{double(p1.x) + enter * ux, double(p1.y) + enter * uy, ux, uy, exit - enter};
    std::vector<uint32_t> buckets;
    bool first = true;
    walk(S, path, [&](int64_t cx, int64_t cy, double ta, double tb, bool last) {
        if (line.fraction(enter + ta) > clipAt) {
            return true;
        }
        // Each particle once: in the cell where the ray enters its circle.
        visits.clear();
        const double lo = enter + ta, hi = enter + tb;
        S.forCells(cx, cy, reach, buckets, [&](uint32_t b, uint32_t e) {
            for (uint32_t k = b; k < e; ++k) {
                const uint32_t i = S.order[k];
                const double t = line.entry(i);
                if (t >= 0.0 && (first || t >= lo) && (last || t < hi)) {
                    visits.push_back({t, i});
                }
            }
        });
        first = false;
        report(visits);
        return stopped;
    });
    return visited;
}

LiquidSample sample(const World& world, glm::vec2 point, std::span<float> materialFractions,
                    const SurfaceField& field) {
    const WorldState& s = detail::queryState(world, "sample");
    checkPoint(point, "sample", "point");
    validate(field, "sample");
    std::fill(materialFractions.begin(), materialFractions.end(), 0.0f);
    LiquidSample out;
    if (s.particles.size() == 0) {
        return out;
    }
    const Setup S(s, field);
    const detail::Particles& p = s.particles;
    const double x = point.x, y = point.y;
    std::vector<double> share(S.terms.size(), 0.0);
    double weight = 0.0, density = 0.0, pressure = 0.0, vx = 0.0, vy = 0.0;
    S.forCells(S.cellOf(x), S.cellOf(y), S.cellsFor(S.kernelReach), scratch().buckets,
               [&](uint32_t b, uint32_t e) {
                   for (uint32_t k = b; k < e; ++k) {
                       const uint32_t i = S.order[k];
                       const MaterialTerms& m = S.terms[p.material[i]];
                       const double rx = x - p.px[i], ry = y - p.py[i];
                       const double r = std::sqrt(rx * rx + ry * ry);
                       if (r >= m.h) {
                           continue;
                       }
                       const double w = double(m.area) * kernel::wendland(float(r), m.h);
                       ++out.neighbours;
                       weight += w;
                       density += w * p.density[i] / m.restDensity;
                       pressure += w * p.pressure[i];
                       vx += w * p.vx[i];
                       vy += w * p.vy[i];
                       share[p.material[i]] += w;
                   }
               });
    if (weight > 0.0) {
        out.densityRatio = float(density / weight);
        out.pressure = float(pressure / weight);
        out.velocity = {float(vx / weight), float(vy / weight)};
        size_t most = 0;
        for (size_t m = 0; m < share.size(); ++m) {
            if (share[m] > share[most]) {
                most = m;
            }
            if (m < materialFractions.size()) {
                materialFractions[m] = float(share[m] / weight);
            }
        }
        out.material = MaterialId{uint16_t(most), s.tag.value()};
    }
    const double here = fieldAround(S, x, y, scratch().buckets).field;
    out.field = float(here);
    out.inLiquid = here >= S.threshold;
    if (out.inLiquid) {
        out.depth = float(depthAt(S, x, y));
    }
    return out;
}

} // namespace fluid
