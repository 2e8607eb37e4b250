// fluid tests — shared helpers: scene builders, measurements, hashing. Header-only, no Catch2.
#pragma once

#include <fluid/fluid.h>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

// FLUID_TEST_SANITIZED: 1 in a build with a sanitizer, which reserves terabytes of shadow
// memory, so a test that runs under a memory limit (ulimit -v) needs a build without one (GCC
// says so with __SANITIZE_*__, clang with __has_feature; tests/CMakeLists.txt defines it for
// the asan preset, whose test files are compiled without the sanitizers).
#if defined(FLUID_TEST_SANITIZED)
#elif defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define FLUID_TEST_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) ||                         \
    __has_feature(memory_sanitizer)
#define FLUID_TEST_SANITIZED 1
#endif
#endif

namespace fluid::test {

/// The registry with every built-in plugin, made once (read-only: safe from any thread).
inline const Registry& builtins() {
    static const Registry registry = [] {
        Registry r;
        registerBuiltinPlugins(r);
        return r;
    }();
    return registry;
}

/// The bytes of `world`'s save.
inline std::string saved(const World& world) {
    std::ostringstream out;
    world.save(out);
    return out.str();
}

/// A world loaded from saved `bytes` with `registry`'s plugins, on `workers` workers (0: the
/// saved count).
inline World restored(const std::string& bytes, const Registry& registry, uint32_t workers = 0) {
    std::istringstream in(bytes);
    return World::load(in, registry, workers);
}

/// A world loaded from saved `bytes` with the built-in plugins, on `workers` workers (0: the
/// saved count).
inline World restored(const std::string& bytes, uint32_t workers = 0) {
    return restored(bytes, builtins(), workers);
}

/// `world` saved and loaded again with the built-in plugins, on `workers` workers (0: the
/// saved count).
inline World reloaded(const World& world, uint32_t workers = 0) {
    return restored(saved(world), workers);
}

/// Not-a-number and infinity, for bad input.
inline constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
inline constexpr float kInf = std::numeric_limits<float>::infinity();

/// Pi, in double.
inline constexpr double kPi = 3.14159265358979323846;

/// Distance from `p` to the segment from `a` to `b` (unit: m).
inline double segmentDistance(glm::dvec2 p, glm::dvec2 a, glm::dvec2 b) {
    const glm::dvec2 e = b - a;
    const double u =
        std::clamp(((p.x - a.x) * e.x + (p.y - a.y) * e.y) / (e.x * e.x + e.y * e.y), 0.0, 1.0);
    const glm::dvec2 d = p - (a + u * e);
    return std::sqrt(d.x * d.x + d.y * d.y);
}

/// Particles of `material` in `world` (unit: count).
inline uint32_t countOf(const World& world, MaterialId material) {
    const auto mat = world.materialIndex();
    return uint32_t(std::count(mat.begin(), mat.end(), material.index));
}

/// A level whose one blob asks for about 63.6 million particles (about 12.7 GB): loading it
/// runs out of memory under a memory limit.
inline constexpr const char* kHugeBlobLevel =
    R"({"version": 1, "world": {"maxParticles": 67108864}, "materials": [{"name": "water"}], "blobs": [{"shape": "box", "min": [0, 0], "max": [80, 80], "material": "water"}]})";

/// Standard gravity used by the scenes (unit: m/s^2).
inline constexpr float kG = 9.81f;
/// The game frame (unit: s).
inline constexpr float kFrame = 1.0f / 60.0f;

/// Positions of all particles as vec2, in slot order.
inline std::vector<glm::vec2> positions(const World& world) {
    std::vector<glm::vec2> out(world.particleCount());
    const auto px = world.positionX();
    const auto py = world.positionY();
    for (uint32_t i = 0; i < world.particleCount(); ++i) {
        out[i] = {px[i], py[i]};
    }
    return out;
}

/// True when every position, velocity and density is finite.
inline bool allFinite(const World& world) {
    const auto px = world.positionX(), py = world.positionY();
    const auto vx = world.velocityX(), vy = world.velocityY();
    const auto rho = world.density();
    for (uint32_t i = 0; i < world.particleCount(); ++i) {
        if (!std::isfinite(px[i]) || !std::isfinite(py[i]) || !std::isfinite(vx[i]) ||
            !std::isfinite(vy[i]) || !std::isfinite(rho[i])) {
            return false;
        }
    }
    return true;
}

/// Total momentum sum m v (unit: kg m/s), in double, masses from the world's materials.
inline glm::dvec2 momentum(const World& world) {
    const auto vx = world.velocityX(), vy = world.velocityY();
    const auto mat = world.materialIndex();
    glm::dvec2 p{0.0, 0.0};
    for (uint32_t i = 0; i < world.particleCount(); ++i) {
        const double m = world.material(MaterialId{mat[i]}).mass;
        p.x += m * vx[i];
        p.y += m * vy[i];
    }
    return p;
}

/// Angular momentum about (cx, cy), z component (unit: kg m^2/s), in double.
inline double angularMomentum(const World& world, double cx, double cy) {
    const auto px = world.positionX(), py = world.positionY();
    const auto vx = world.velocityX(), vy = world.velocityY();
    const auto mat = world.materialIndex();
    double l = 0.0;
    for (uint32_t i = 0; i < world.particleCount(); ++i) {
        const double m = world.material(MaterialId{mat[i]}).mass;
        l += m * ((px[i] - cx) * vy[i] - (py[i] - cy) * vx[i]);
    }
    return l;
}

/// Total mass (unit: kg).
inline double totalMass(const World& world) {
    const auto mat = world.materialIndex();
    double m = 0.0;
    for (uint32_t i = 0; i < world.particleCount(); ++i) {
        m += world.material(MaterialId{mat[i]}).mass;
    }
    return m;
}

/// Kinetic energy plus the potential energy in gravity `g` (m/s^2, pulling along -y) above
/// y = 0 (unit: J per m of depth as the particles' masses give it: kg m^2/s^2).
struct Energy {
    double kinetic = 0.0, potential = 0.0;
};
inline Energy energy(const World& world, double g) {
    const auto mat = world.materialIndex();
    const auto vx = world.velocityX(), vy = world.velocityY(), py = world.positionY();
    Energy e;
    for (uint32_t i = 0; i < world.particleCount(); ++i) {
        const double m = world.material(MaterialId{mat[i]}).mass;
        e.kinetic += 0.5 * m * (double(vx[i]) * vx[i] + double(vy[i]) * vy[i]);
        e.potential += m * g * py[i];
    }
    return e;
}

/// Kinetic energy per unit mass, sum v^2 / 2 over the particles (one material: equal masses)
/// (unit: J/kg).
inline double kineticPerMass(const World& world) {
    double e = 0.0;
    const std::span<const float> vx = world.velocityX(), vy = world.velocityY();
    for (size_t i = 0; i < vx.size(); ++i) {
        e += 0.5 * (double(vx[i]) * vx[i] + double(vy[i]) * vy[i]);
    }
    return vx.empty() ? 0.0 : e / double(vx.size());
}

// A force plugin whose prepare runs the test's hook (a game's plugin calling back into the
// world, or into what steps it) and adds no acceleration.
class HookForce final : public ForcePlugin {
public:
    static constexpr std::array<ParamDecl, 0> kParams{};
    explicit HookForce(std::function<void()> hook)
        : ForcePlugin("force.test-hook", kParams), m_hook(std::move(hook)) {}
    void prepare(const StepContext&) override { m_hook(); }
    void apply(const ForceContext&, uint32_t, uint32_t) override {}

private:
    std::function<void()> m_hook;
};

/// Largest speed (unit: m/s).
inline float maxSpeed(const World& world) {
    const auto vx = world.velocityX(), vy = world.velocityY();
    float v2 = 0.0f;
    for (uint32_t i = 0; i < world.particleCount(); ++i) {
        v2 = std::max(v2, vx[i] * vx[i] + vy[i] * vy[i]);
    }
    return std::sqrt(v2);
}

/// Mean particle speed (unit: m/s; 0 without particles).
inline double meanSpeed(const World& world) {
    const auto vx = world.velocityX(), vy = world.velocityY();
    double sum = 0.0;
    for (uint32_t i = 0; i < world.particleCount(); ++i) {
        sum += std::hypot(double(vx[i]), double(vy[i]));
    }
    return world.particleCount() > 0 ? sum / world.particleCount() : 0.0;
}

/// Axis-aligned bounds of the particles (optionally of one material only).
struct Bounds {
    float x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
    uint32_t count = 0;
};
inline Bounds bounds(const World& world, int material = -1) {
    Bounds b;
    const auto px = world.positionX(), py = world.positionY();
    const auto mat = world.materialIndex();
    for (uint32_t i = 0; i < world.particleCount(); ++i) {
        if (material >= 0 && mat[i] != material) {
            continue;
        }
        b.x0 = std::min(b.x0, px[i]);
        b.x1 = std::max(b.x1, px[i]);
        b.y0 = std::min(b.y0, py[i]);
        b.y1 = std::max(b.y1, py[i]);
        ++b.count;
    }
    return b;
}

/// How smooth the liquid's outline is as the player sees it (`outlineRoughness`).
struct OutlineRoughness {
    /// RMS distance of the outline from the outline smoothed over `window` (unit: m).
    double rms = 0.0;
    /// Its curvature noise: how far the outline, resampled every `step`, turns back and forth:
    /// its total absolute turning less its net turning, per length of outline (unit: rad/m); 0
    /// for an outline that turns one way only (a drop, a smooth mound).
    double excessTurning = 0.0;
    /// Outline points fitted (rays that met the liquid with at least 5 points within the
    /// window).
    uint32_t points = 0;
};

/// The value at u = 0 of the least-squares quadratic through the points (u_k, r_k) of `u`
/// and `r`; nothing when the points leave it undetermined (fewer than 3 distinct u).
inline std::optional<double> quadraticAtZero(std::span<const double> u, std::span<const double> r) {
    // The normal equations of r = c0 + c1 u + c2 u^2, by Gaussian elimination with partial
    // pivoting.
    double m[3][4] = {};
    for (size_t k = 0; k < u.size(); ++k) {
        const double basis[3] = {1.0, u[k], u[k] * u[k]};
        for (int i = 0; i < 3; ++i) {
            for (int j = 0; j < 3; ++j) {
                m[i][j] += basis[i] * basis[j];
            }
            m[i][3] += basis[i] * r[k];
        }
    }
    for (int c = 0; c < 3; ++c) {
        int p = c;
        for (int i = c + 1; i < 3; ++i) {
            if (std::abs(m[i][c]) > std::abs(m[p][c])) {
                p = i;
            }
        }
        std::swap(m[c], m[p]);
        if (std::abs(m[c][c]) < 1e-300) {
            return std::nullopt;
        }
        for (int i = c + 1; i < 3; ++i) {
            const double f = m[i][c] / m[c][c];
            for (int j = c; j < 4; ++j) {
                m[i][j] -= f * m[c][j];
            }
        }
    }
    const double c2 = m[2][3] / m[2][2];
    const double c1 = (m[1][3] - m[1][2] * c2) / m[1][1];
    return (m[0][3] - m[0][1] * c1 - m[0][2] * c2) / m[0][0];
}

/// Total absolute turning less net turning of the polyline `at` (closed: its last point joins
/// the first), resampled every `step` of its length (m), per length (rad/m).
inline double excessTurning(std::span<const glm::dvec2> at, bool closed, double step) {
    const size_t n = at.size();
    std::vector<glm::dvec2> q{at[0]};
    double carry = 0.0; // length since the last resampled point
    const size_t segments = closed ? n : n - 1;
    for (size_t k = 0; k < segments; ++k) {
        const glm::dvec2 a = at[k], b = at[(k + 1) % n];
        const double len = std::hypot(b.x - a.x, b.y - a.y);
        double t = step - carry;
        while (t <= len) {
            q.push_back(a + (b - a) * (t / len));
            t += step;
        }
        carry = len - (t - step);
    }
    double all = 0.0, net = 0.0;
    for (size_t k = 1; k + 1 < q.size(); ++k) {
        const glm::dvec2 e0 = q[k] - q[k - 1], e1 = q[k + 1] - q[k];
        const double turn = std::atan2(e0.x * e1.y - e0.y * e1.x, e0.x * e1.x + e0.y * e1.y);
        all += std::abs(turn);
        net += turn;
    }
    return (all - std::abs(net)) / (double(q.size()) * step);
}

/// The outline of the liquid as drawn (the renderer's field, `fluid::rayCast`) seen from
/// outside: `rays` rays from the circle of radius `reach` (m) around `centre` towards it, at
/// angles from `from` to `to` (rad, counter-clockwise from +x; `to - from` = 2 pi closes the
/// outline). Each ray's first hit is one outline point at distance r from the centre; r is
/// fitted by a quadratic in the outline's arc length over `window` (m) around each point, and
/// the point's distance from its fit is its roughness at scales below the window. A round drop
/// reads only its particles' graininess; a heap of drops frozen where they landed reads its
/// bumps. Counts every material's particles (the field does); `field` as `fluid::rayCast`.
inline OutlineRoughness outlineRoughness(const World& world, glm::vec2 centre, float reach,
                                         double from, double to, uint32_t rays, double window,
                                         double step, const SurfaceField& field = {}) {
    std::vector<glm::dvec2> at;
    std::vector<double> r;
    const bool closed = to - from >= 2.0 * kPi - 1e-9;
    const uint32_t steps = closed ? rays : rays - 1;
    for (uint32_t k = 0; k < rays; ++k) {
        const double a = from + (to - from) * double(k) / double(steps);
        const glm::vec2 start = centre + reach * glm::vec2(float(std::cos(a)), float(std::sin(a)));
        const RayHit hit = rayCast(world, start, centre, field);
        if (hit.hit && hit.fraction > 0.0f) {
            at.push_back({hit.point.x, hit.point.y});
            r.push_back(std::hypot(double(hit.point.x - centre.x), double(hit.point.y - centre.y)));
        }
    }
    OutlineRoughness out;
    const size_t n = at.size();
    out.points = uint32_t(n);
    if (n < 8) {
        return out;
    }
    // Arc length along the outline; a closed one's arc lengths are taken the short way round.
    std::vector<double> s(n, 0.0);
    for (size_t k = 1; k < n; ++k) {
        s[k] = s[k - 1] + std::hypot(at[k].x - at[k - 1].x, at[k].y - at[k - 1].y);
    }
    const double length =
        closed ? s[n - 1] + std::hypot(at[0].x - at[n - 1].x, at[0].y - at[n - 1].y) : s[n - 1];
    double sum2 = 0.0;
    uint32_t fitted = 0;
    std::vector<double> u, rw;
    for (size_t k = 0; k < n; ++k) {
        // The points within half a window of point k, at their arc length from it.
        u.clear();
        rw.clear();
        for (size_t j = 0; j < n; ++j) {
            double d = s[j] - s[k];
            if (closed) {
                d -= length * std::round(d / length);
            }
            if (std::abs(d) <= 0.5 * window) {
                u.push_back(d);
                rw.push_back(r[j]);
            }
        }
        if (u.size() < 5) {
            continue; // a gap in the outline (a step the rays jump across): no fit here
        }
        if (const std::optional<double> fit = quadraticAtZero(u, rw)) {
            ++fitted;
            sum2 += (r[k] - *fit) * (r[k] - *fit);
        }
    }
    out.rms = fitted > 0 ? std::sqrt(sum2 / double(fitted)) : 0.0;
    out.points = fitted;
    out.excessTurning = excessTurning(at, closed, step);
    return out;
}

/// A heap's free-surface profile: per lattice column, the top particle's height plus half a
/// spacing, and the fronts (outermost particles plus half a spacing).
struct HeapProfile {
    float left = 0.0f, right = 0.0f; // fronts (m)
    std::map<int, float> top;        // column index -> surface height (m)
    float spacing = 0.0f;
    float halfWidth() const { return 0.5f * (right - left); }
};

inline HeapProfile profileOf(const World& world, float spacing) {
    HeapProfile p;
    p.spacing = spacing;
    p.left = 1e9f;
    p.right = -1e9f;
    for (const glm::vec2 x : positions(world)) {
        const int column = int(std::floor(x.x / spacing));
        auto [it, fresh] = p.top.try_emplace(column, x.y + 0.5f * spacing);
        if (!fresh) {
            it->second = std::max(it->second, x.y + 0.5f * spacing);
        }
        p.left = std::min(p.left, x.x - 0.5f * spacing);
        p.right = std::max(p.right, x.x + 0.5f * spacing);
    }
    return p;
}

/// A heap against the law h^2 = c d (d the distance from the nearer front, c = 2 tau_y /
/// (rho g), m): the mean of h / sqrt(c d) and its farthest from 1 over the columns with d in
/// [dMin, dMax] (m), and their number.
struct HeapLawFit {
    double mean = 0.0, worst = 0.0;
    int columns = 0;
};
inline HeapLawFit heapLawFit(const HeapProfile& p, float c, float dMin, float dMax) {
    HeapLawFit f;
    for (const auto& [column, height] : p.top) {
        const float x = (float(column) + 0.5f) * p.spacing;
        const float d = std::min(x - p.left, p.right - x);
        if (d >= dMin && d <= dMax) {
            const double ratio = double(height) / std::sqrt(double(c) * d);
            f.worst = std::max(f.worst, std::fabs(ratio - 1.0));
            f.mean += ratio;
            ++f.columns;
        }
    }
    f.mean /= std::max(f.columns, 1);
    return f;
}

/// Count of particles whose centre lies outside [x0, x1] x [y0, y1] (or is NaN).
inline uint32_t countOutside(const World& world, float x0, float y0, float x1, float y1) {
    const auto px = world.positionX(), py = world.positionY();
    uint32_t n = 0;
    for (uint32_t i = 0; i < world.particleCount(); ++i) {
        if (!(px[i] >= x0 && px[i] <= x1 && py[i] >= y0 && py[i] <= y1)) {
            ++n;
        }
    }
    return n;
}

/// Convex hull (Andrew's monotone chain), counter-clockwise, no collinear points.
inline std::vector<glm::dvec2> convexHull(std::vector<glm::dvec2> pts) {
    std::sort(pts.begin(), pts.end(),
              [](glm::dvec2 a, glm::dvec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
    pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
    if (pts.size() < 3) {
        return pts;
    }
    auto cross = [](glm::dvec2 o, glm::dvec2 a, glm::dvec2 b) {
        return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
    };
    std::vector<glm::dvec2> hull(2 * pts.size());
    size_t k = 0;
    for (size_t i = 0; i < pts.size(); ++i) {
        while (k >= 2 && cross(hull[k - 2], hull[k - 1], pts[i]) <= 0) {
            --k;
        }
        hull[k++] = pts[i];
    }
    for (size_t i = pts.size() - 1, t = k + 1; i > 0; --i) {
        while (k >= t && cross(hull[k - 2], hull[k - 1], pts[i - 1]) <= 0) {
            --k;
        }
        hull[k++] = pts[i - 1];
    }
    hull.resize(k - 1);
    return hull;
}

/// Area and perimeter of a simple polygon (unit: m^2, m).
inline double polygonArea(const std::vector<glm::dvec2>& poly) {
    double a = 0.0;
    for (size_t i = 0; i < poly.size(); ++i) {
        const glm::dvec2 p = poly[i], q = poly[(i + 1) % poly.size()];
        a += p.x * q.y - q.x * p.y;
    }
    return 0.5 * std::fabs(a);
}
inline double polygonPerimeter(const std::vector<glm::dvec2>& poly) {
    double l = 0.0;
    for (size_t i = 0; i < poly.size(); ++i) {
        const glm::dvec2 d = poly[(i + 1) % poly.size()] - poly[i];
        l += std::sqrt(d.x * d.x + d.y * d.y);
    }
    return l;
}

/// Distance from p to the boundary of a convex CCW polygon (positive inside).
inline double insideDistance(const std::vector<glm::dvec2>& hull, glm::dvec2 p) {
    double d = INFINITY;
    for (size_t i = 0; i < hull.size(); ++i) {
        const glm::dvec2 a = hull[i], b = hull[(i + 1) % hull.size()];
        const glm::dvec2 e = b - a;
        const double len = std::sqrt(e.x * e.x + e.y * e.y);
        d = std::min(d, (e.x * (p.y - a.y) - e.y * (p.x - a.x)) / len);
    }
    return d;
}

/// Density reading of a body's interior (see readInterior).
struct Reading {
    uint32_t interior = 0;
    double worst = 0.0;       // max |rho/rho0 - 1| over interior particles
    double mean = 0.0;        // mean rho/rho0 - 1 over interior particles
    double compression = 0.0; // max rho/rho0 - 1 over interior particles
};

// Interior: particles farther than one smoothing distance (plus half a spacing: where the body's
// edge lies beyond its outermost particles) inside the convex hull of the body.
inline Reading readInterior(const World& world, MaterialId id) {
    const Material& m = world.material(id);
    const float s = world.spacing(id);
    std::vector<glm::dvec2> pts;
    for (const glm::vec2 p : positions(world)) {
        pts.emplace_back(p.x, p.y);
    }
    const std::vector<glm::dvec2> hull = convexHull(pts);
    const auto rho = world.density();
    Reading r;
    for (uint32_t i = 0; i < world.particleCount(); ++i) {
        if (insideDistance(hull, pts[i]) + 0.5 * s > m.smoothingDistance) {
            const double e = rho[i] / m.restDensity - 1.0;
            r.worst = std::max(r.worst, std::fabs(e));
            r.compression = std::max(r.compression, e);
            r.mean += e;
            ++r.interior;
        }
    }
    r.mean /= std::max(1u, r.interior);
    return r;
}

/// A removal event's fields as bytes, without the world tags of its handle and ids (each World
/// object has a tag of its own; two runs compare what the tags name) and without padding.
/// The group most of `handles` belong to, by a plain count (ties: the lower index; handles in no
/// group not counted): what a contact event's `group` must say. Null when none is in a group.
inline GroupHandle majorityGroup(const World& world, std::span<const ParticleHandle> handles) {
    std::map<uint32_t, std::pair<uint32_t, GroupHandle>> counts;
    for (const ParticleHandle h : handles) {
        const GroupHandle g = groupOf(world, h);
        if (g.generation != 0) {
            auto& c = counts[g.index];
            ++c.first;
            c.second = g;
        }
    }
    GroupHandle best{};
    uint32_t most = 0;
    for (const auto& [index, c] : counts) { // increasing index: a tie keeps the lower one
        if (c.first > most) {
            most = c.first;
            best = c.second;
        }
    }
    return best;
}

inline std::string removalRecord(const RemovedEvent& e) {
    std::string out;
    const auto add = [&](const auto& value) {
        out.append(reinterpret_cast<const char*>(&value), sizeof(value));
    };
    add(e.particle.slot);
    add(e.particle.generation);
    add(e.position);
    add(e.velocity);
    add(e.material.index);
    add(e.cause);
    add(e.drain.index);
    return out;
}

/// FNV-1a (64 bit) over raw bytes.
inline uint64_t fnv1a(const void* data, size_t size, uint64_t hash = 1469598103934665603ull) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < size; ++i) {
        hash ^= bytes[i];
        hash *= 1099511628211ull;
    }
    return hash;
}

/// Hash of positions and velocities, particle by particle in handle order (slot, then
/// generation), so that it does not depend on where the grid sort left each particle.
inline uint64_t stateHash(const World& world) {
    const uint32_t n = world.particleCount();
    std::vector<std::pair<ParticleHandle, uint32_t>> byHandle(n);
    for (uint32_t i = 0; i < n; ++i) {
        byHandle[i] = {world.handleAt(i), i};
    }
    std::sort(byHandle.begin(), byHandle.end(), [](const auto& a, const auto& b) {
        return a.first.slot < b.first.slot ||
               (a.first.slot == b.first.slot && a.first.generation < b.first.generation);
    });
    const auto px = world.positionX(), py = world.positionY();
    const auto vx = world.velocityX(), vy = world.velocityY();
    uint64_t h = 1469598103934665603ull;
    for (const auto& [handle, i] : byHandle) {
        const float v[4] = {px[i], py[i], vx[i], vy[i]};
        h = fnv1a(&handle.slot, sizeof handle.slot, h);
        h = fnv1a(v, sizeof v, h);
    }
    return h;
}

/// A rectangle blob of exactly `cols` x `rows` lattice points whose lower-left point sits at
/// (x0 + s/2, y0 + s/2), s the material's spacing: a block filling [x0, x0 + cols s] x
/// [y0, y0 + rows s] the way a lattice fills a tank (half a spacing from each wall).
inline BlobDef latticeBlock(const World& world, MaterialId material, float x0, float y0,
                            uint32_t cols, uint32_t rows, glm::vec2 velocity = {0.0f, 0.0f}) {
    const float s = world.spacing(material);
    BlobDef b;
    b.shape.type = ShapeType::Rectangle;
    b.material = material;
    b.velocity = velocity;
    // A quarter spacing of slack on each side so that floor(width / s) is exactly cols.
    b.shape.halfExtents = {0.5f * s * (float(cols) + 0.5f), 0.5f * s * (float(rows) + 0.5f)};
    b.shape.center = {x0 + 0.5f * s * float(cols), y0 + 0.5f * s * float(rows)};
    return b;
}

/// What a stirred paste did (stirAndRelease): the farthest any particle moved while stirred
/// (m), the kinetic energy per kilogram at the end of the stirring and of the rest (J/kg), and
/// how far the stir moved the paste for good (m): each particle's move from before the stir to
/// the end of the rest, less the block's best rigid move (translation and turn, least squares),
/// at the 75th percentile. A paste the stir yields keeps that flow; one it does not springs back
/// and keeps only what its surface threw off.
struct Stirred {
    uint32_t particles = 0; // spawned (800 asked for)
    double moved = 0.0, stirred = 0.0, rest = 0.0, kept = 0.0;
};

/// The 75th percentile of |b_i - (R a_i + t)| over the points, with R and t the rigid move that
/// best takes `a` onto `b` (least squares: Procrustes in 2D) (m).
inline double nonRigidMove(const std::vector<glm::dvec2>& a, const std::vector<glm::dvec2>& b) {
    glm::dvec2 ca{0.0, 0.0}, cb{0.0, 0.0};
    for (size_t i = 0; i < a.size(); ++i) {
        ca += a[i];
        cb += b[i];
    }
    ca /= double(a.size());
    cb /= double(b.size());
    double dot = 0.0, cross = 0.0;
    for (size_t i = 0; i < a.size(); ++i) {
        const glm::dvec2 p = a[i] - ca, q = b[i] - cb;
        dot += p.x * q.x + p.y * q.y;
        cross += p.x * q.y - p.y * q.x;
    }
    const double angle = std::atan2(cross, dot), c = std::cos(angle), s = std::sin(angle);
    std::vector<double> r(a.size());
    for (size_t i = 0; i < a.size(); ++i) {
        const glm::dvec2 p = a[i] - ca;
        const glm::dvec2 fit = cb + glm::dvec2(c * p.x - s * p.y, s * p.x + c * p.y);
        r[i] = glm::length(b[i] - fit);
    }
    std::sort(r.begin(), r.end());
    return r[(3 * (r.size() - 1)) / 4];
}

/// In `world`, holding `material` and nothing else yet: gravity, a 40 x 20 lattice block in a
/// closed 0.45 x 0.6 m box, settled for 1 s, stirred in a circle for 1 s by a pointer force of
/// `acceleration` (m/s^2, radius 0.1 m), then released for `restFrames` frames of kFrame.
inline Stirred stirAndRelease(World& world, MaterialId material, float acceleration,
                              int restFrames) {
    Stirred out;
    world.addForce(std::make_unique<GravityForce>(0.0f, -kG));
    auto pointer = std::make_unique<PointerForce>(0.1f, acceleration);
    PointerForce* stir = pointer.get();
    world.addForce(std::move(pointer));
    world.addBoundary(std::make_unique<BoxContainer>(0.0f, 0.0f, 0.45f, 0.6f));
    out.particles = world.spawnBlob(latticeBlock(world, material, 0.0f, 0.0f, 40, 20));
    for (int frame = 1; frame <= 60; ++frame) { // settle
        world.step(kFrame);
    }
    std::vector<std::pair<ParticleHandle, glm::vec2>> before;
    for (uint32_t i = 0; i < world.particleCount(); ++i) {
        const ParticleHandle h = world.handleAt(i);
        before.emplace_back(h, world.position(h));
    }
    for (int frame = 1; frame <= 60; ++frame) { // stir in a circle for 1 s
        const float angle = 2.0f * 3.14159265f * float(frame) / 60.0f;
        stir->setPointer({0.2f + 0.08f * std::cos(angle), 0.1f + 0.05f * std::sin(angle)}, 1.0f);
        world.step(kFrame);
    }
    out.stirred = kineticPerMass(world);
    stir->setPointer({0.2f, 0.1f}, 0.0f);
    for (const auto& [h, x] : before) {
        const glm::vec2 now = world.position(h);
        out.moved = std::max(out.moved, std::hypot(double(now.x - x.x), double(now.y - x.y)));
    }
    for (int frame = 1; frame <= restFrames; ++frame) {
        world.step(kFrame);
    }
    out.rest = kineticPerMass(world);
    std::vector<glm::dvec2> from, to;
    for (const auto& [h, x] : before) {
        from.push_back(glm::dvec2(x));
        to.push_back(glm::dvec2(world.position(h)));
    }
    out.kept = nonRigidMove(from, to);
    return out;
}

/// Wall-clock and process CPU seconds since construction; prints one line with the label on
/// destruction, so each test's cost shows in its log (CPU time counts every worker thread, and
/// is the better measure when the machine is shared).
class Stopwatch {
public:
    explicit Stopwatch(std::string label)
        : m_label(std::move(label)), m_t0(std::chrono::steady_clock::now()), m_c0(std::clock()) {}
    ~Stopwatch() {
        std::printf("[time] %s: wall %.2f s, cpu %.2f s\n", m_label.c_str(), seconds(),
                    cpuSeconds());
        std::fflush(stdout);
    }
    Stopwatch(const Stopwatch&) = delete;
    Stopwatch& operator=(const Stopwatch&) = delete;
    double seconds() const {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - m_t0).count();
    }
    double cpuSeconds() const { return double(std::clock() - m_c0) / CLOCKS_PER_SEC; }

private:
    std::string m_label;
    std::chrono::steady_clock::time_point m_t0;
    std::clock_t m_c0;
};

} // namespace fluid::test

namespace fluid::test {

/// Worker threads for the slow physics scenes: FLUID_TEST_WORKERS from the environment, else 2
/// (the machine class has 2 cores). The release test preset sets 1 and runs two tests at a
/// time: the whole suite then takes 284 s instead of 410 s with 2 workers one test at a time.
/// Results do not depend on it: tests/determinism checks bit-identical state for 1, 2 and 4
/// workers.
inline uint32_t physicsWorkers() {
    if (const char* env = std::getenv("FLUID_TEST_WORKERS")) {
        const long n = std::strtol(env, nullptr, 10);
        if (n >= 1 && n <= 256) {
            return static_cast<uint32_t>(n);
        }
    }
    return 2;
}

/// What a shell command wrote on standard output (add "2>&1" for standard error too), whether
/// it could be started, and its status as `pclose` gives it (0: it exited with 0). Test thread.
struct ShellRun {
    bool started = false;
    std::string output;
    int status = -1;
};
inline ShellRun runShell(const std::string& command) {
    ShellRun run;
    FILE* child = ::popen(command.c_str(), "r");
    if (child == nullptr) {
        return run;
    }
    run.started = true;
    char buffer[4096];
    size_t n = 0;
    while ((n = std::fread(buffer, 1, sizeof buffer, child)) > 0) {
        run.output.append(buffer, n);
    }
    run.status = ::pclose(child);
    return run;
}

/// A WorldDef for the slow scenes (see physicsWorkers) with the given solver.
inline WorldDef physicsDef(Solver solver = Solver::PositionBased) {
    WorldDef def;
    def.workerCount = physicsWorkers();
    def.solver = solver;
    return def;
}

/// `physicsDef` with the precise preset (the default is the game preset): for the tests whose
/// figures only the precise preset reaches yet. Each caller says why, with the game preset's
/// figure.
inline WorldDef preciseDef(Solver solver = Solver::PositionBased) {
    WorldDef def = physicsDef(solver);
    def.positionBased = positionBasedPreset(Quality::Precise);
    return def;
}

/// `material` as `solver` steps it: the explicit solver takes Newtonian materials only, so there
/// a yield stress and consistency are dropped (the seed's yoghurt, Table 4.1 alone).
inline Material forSolver(Material material, Solver solver) {
    if (solver == Solver::Explicit) {
        material.yieldStress = 0.0f;
        material.consistency = 0.0f;
    }
    return material;
}

/// The solver's name in test output.
/// The three ways a game may step a world: the explicit solver and the position-based
/// solver's two presets.
enum class Setting { Explicit, Game, Precise };

/// "explicit", "game" or "precise".
inline const char* settingName(Setting s) {
    return s == Setting::Explicit ? "explicit" : s == Setting::Game ? "game" : "precise";
}

/// A world definition of `setting` on `workers` threads.
inline WorldDef defFor(Setting setting, uint32_t workers) {
    WorldDef def;
    def.workerCount = workers;
    def.solver = setting == Setting::Explicit ? Solver::Explicit : Solver::PositionBased;
    def.positionBased =
        positionBasedPreset(setting == Setting::Precise ? Quality::Precise : Quality::Game);
    return def;
}

// The solver's name for test output: fluid::solverName's (a NUL-terminated literal).
inline const char* solverLabel(Solver solver) {
    return fluid::solverName(solver).data();
}

} // namespace fluid::test
