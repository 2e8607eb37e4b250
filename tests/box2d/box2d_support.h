// fluid tests — helpers for the Box2D coupling tests: body builders, exact fixture geometry
// (area below a waterline, depth of a point inside the core polygon), the waterline of a tank
// measured from the particles, a hash of the bodies' state. Header-only, no Catch2.
#pragma once

#include "test_support.h"

#include <fluid/box2d/coupling.h>

#include <box2d/box2d.h>

#include <glm/vec2.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <utility>
#include <vector>

namespace fluid::test {

/// Category bit of the tests' tank walls and floors in Box2D: kept out of the fluid with
/// `kFluidMask`, because `boundary.box` already is the fluid's wall (two boundaries in one place
/// would double the wall's density contribution).
inline constexpr uint16_t kWallCategory = 0x0002;
/// Coupling mask that leaves the walls out.
inline constexpr uint16_t kFluidMask = uint16_t(0xFFFF & ~kWallCategory);

inline b2Vec2 toB2(glm::vec2 v) {
    return {v.x, v.y};
}
inline glm::dvec2 toD(b2Vec2 v) {
    return {v.x, v.y};
}

/// A body of `type` at `center` turned by `angle` (unit: m, rad) with one fixture of `shape`,
/// `density` (kg/m^2), friction 0.5 and collision category `category`.
inline b2Body* addBody(b2World& physics, b2BodyType type, glm::vec2 center, float angle,
                       const b2Shape& shape, float density, uint16_t category) {
    b2BodyDef bd;
    bd.type = type;
    bd.position = toB2(center);
    bd.angle = angle;
    b2Body* body = physics.CreateBody(&bd);
    b2FixtureDef fd;
    fd.shape = &shape;
    fd.density = density;
    fd.friction = 0.5f;
    fd.filter.categoryBits = category;
    body->CreateFixture(&fd);
    return body;
}

/// A body with one box fixture of half extents (hx, hy) (unit: m) and `density` (kg/m^2).
inline b2Body* addBox(b2World& physics, b2BodyType type, glm::vec2 center, float hx, float hy,
                      float density, float angle = 0.0f, uint16_t category = 0x0001) {
    b2PolygonShape shape;
    shape.SetAsBox(hx, hy);
    return addBody(physics, type, center, angle, shape, density, category);
}

/// A body with one circle fixture of `radius` (unit: m) and `density` (kg/m^2).
inline b2Body* addCircle(b2World& physics, b2BodyType type, glm::vec2 center, float radius,
                         float density, uint16_t category = 0x0001) {
    b2CircleShape shape;
    shape.m_radius = radius;
    return addBody(physics, type, center, 0.0f, shape, density, category);
}

/// A tank of `material`: gravity -kG, a `boundary.box` from (0, 0) to (cols spacings, top)
/// and a lattice block `cols` x `rows` filling its bottom. Returns the tank's width (unit: m).
inline float fillTank(World& world, MaterialId material, uint32_t cols, uint32_t rows, float top) {
    const float width = float(cols) * world.spacing(material);
    world.addForce(std::make_unique<GravityForce>(0.0f, -kG));
    world.addBoundary(std::make_unique<BoxContainer>(0.0f, 0.0f, width, top));
    world.spawnBlob(latticeBlock(world, material, 0.0f, 0.0f, cols, rows));
    return width;
}

/// Static Box2D walls (category kWallCategory) around the inner rectangle [x0, x1] x [y0, y1]:
/// floor, left and right walls, and a lid when `lid`; 0.2 m thick, outside the rectangle.
inline b2Body* addTankWalls(b2World& physics, float x0, float y0, float x1, float y1,
                            bool lid = false) {
    b2BodyDef bd;
    b2Body* body = physics.CreateBody(&bd);
    const float t = 0.1f; // half thickness
    auto wall = [&](float cx, float cy, float hx, float hy) {
        b2PolygonShape shape;
        shape.SetAsBox(hx, hy, {cx, cy}, 0.0f);
        b2FixtureDef fd;
        fd.shape = &shape;
        fd.friction = 0.5f;
        fd.filter.categoryBits = kWallCategory;
        body->CreateFixture(&fd);
    };
    const float cx = 0.5f * (x0 + x1), hw = 0.5f * (x1 - x0) + 2.0f * t;
    const float cy = 0.5f * (y0 + y1), hh = 0.5f * (y1 - y0);
    wall(cx, y0 - t, hw, t);
    wall(x0 - t, cy, t, hh);
    wall(x1 + t, cy, t, hh);
    if (lid) {
        wall(cx, y1 + t, hw, t);
    }
    return body;
}

/// World-space vertices of a polygon fixture's core polygon (counter-clockwise; Box2D's skin
/// radius left out, as the fluid sees it), in double.
inline std::vector<glm::dvec2> worldPolygon(const b2Fixture& fixture) {
    const auto& shape = *static_cast<const b2PolygonShape*>(fixture.GetShape());
    const b2Transform& xf = fixture.GetBody()->GetTransform();
    std::vector<glm::dvec2> out;
    for (int32 k = 0; k < shape.m_count; ++k) {
        const b2Vec2 v = shape.m_vertices[k];
        // b2Mul(xf, v) in double, so the reference is not limited by float rounding.
        const double c = xf.q.c, s = xf.q.s;
        out.emplace_back(double(xf.p.x) + c * v.x - s * v.y, double(xf.p.y) + s * v.x + c * v.y);
    }
    return out;
}

/// World-space centre of a circle fixture (unit: m).
inline glm::dvec2 worldCircleCenter(const b2Fixture& fixture) {
    const auto& shape = *static_cast<const b2CircleShape*>(fixture.GetShape());
    const b2Transform& xf = fixture.GetBody()->GetTransform();
    const double c = xf.q.c, s = xf.q.s;
    return {double(xf.p.x) + c * shape.m_p.x - s * shape.m_p.y,
            double(xf.p.y) + s * shape.m_p.x + c * shape.m_p.y};
}

/// Area of a circle of radius r whose centre is at height cy that lies below y = level
/// (unit: m^2), exact (circular segment).
inline double circleAreaBelow(double cy, double r, double level) {
    const double d = level - (cy - r); // depth of the lowest point under the line
    if (d <= 0.0) {
        return 0.0;
    }
    if (d >= 2.0 * r) {
        return std::numbers::pi * r * r;
    }
    const double u = r - d;
    return r * r * std::acos(u / r) - u * std::sqrt(std::max(0.0, r * r - u * u));
}

/// Area of a polygon that lies below y = level (unit: m^2), exact (Sutherland-Hodgman clip
/// against the half plane, then the shoelace formula).
inline double polygonAreaBelow(const std::vector<glm::dvec2>& poly, double level) {
    std::vector<glm::dvec2> clipped;
    for (size_t k = 0; k < poly.size(); ++k) {
        const glm::dvec2 a = poly[k], b = poly[(k + 1) % poly.size()];
        const bool ain = a.y <= level, bin = b.y <= level;
        if (ain) {
            clipped.push_back(a);
        }
        if (ain != bin) {
            const double t = (level - a.y) / (b.y - a.y);
            clipped.push_back({a.x + t * (b.x - a.x), level});
        }
    }
    return clipped.size() < 3 ? 0.0 : polygonArea(clipped);
}

/// True for the fixture kinds that have an area (circle, polygon).
inline bool hasArea(const b2Fixture& fixture) {
    const b2Shape::Type t = fixture.GetType();
    return t == b2Shape::e_circle || t == b2Shape::e_polygon;
}

/// Area of a circle or polygon fixture below y = level (unit: m^2; core polygon).
inline double fixtureAreaBelow(const b2Fixture& fixture, double level) {
    if (fixture.GetType() == b2Shape::e_circle) {
        const double r = fixture.GetShape()->m_radius;
        return circleAreaBelow(worldCircleCenter(fixture).y, r, level);
    }
    if (fixture.GetType() == b2Shape::e_polygon) {
        return polygonAreaBelow(worldPolygon(fixture), level);
    }
    return 0.0;
}

/// Area of a circle or polygon fixture (unit: m^2; core polygon).
inline double fixtureArea(const b2Fixture& fixture) {
    return fixtureAreaBelow(fixture, 1e30);
}

/// Area of the body's circle and polygon fixtures below y = level, and their whole area
/// (unit: m^2; fixtures assumed not to overlap).
inline std::pair<double, double> bodyAreaBelow(const b2Body& body, double level) {
    double below = 0.0, total = 0.0;
    for (const b2Fixture* f = body.GetFixtureList(); f != nullptr; f = f->GetNext()) {
        below += fixtureAreaBelow(*f, level);
        total += fixtureArea(*f);
    }
    return {below, total};
}

/// How deep p lies inside the fixture (unit: m): > 0 strictly inside the circle or the core
/// polygon, <= 0 on or outside it. Edges and chains have no inside (returns -1).
inline double insideDepth(const b2Fixture& fixture, glm::dvec2 p) {
    if (fixture.GetType() == b2Shape::e_circle) {
        const glm::dvec2 c = worldCircleCenter(fixture);
        const double dx = p.x - c.x, dy = p.y - c.y;
        return double(fixture.GetShape()->m_radius) - std::sqrt(dx * dx + dy * dy);
    }
    if (fixture.GetType() == b2Shape::e_polygon) {
        return insideDistance(worldPolygon(fixture), p);
    }
    return -1.0;
}

/// Axis-aligned bounds of a body's circle and polygon fixtures (unit: m).
struct Box {
    double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
};
inline Box bodyBounds(const b2Body& body) {
    Box b;
    for (const b2Fixture* f = body.GetFixtureList(); f != nullptr; f = f->GetNext()) {
        if (f->GetType() == b2Shape::e_circle) {
            const glm::dvec2 c = worldCircleCenter(*f);
            const double r = f->GetShape()->m_radius;
            b.x0 = std::min(b.x0, c.x - r);
            b.x1 = std::max(b.x1, c.x + r);
            b.y0 = std::min(b.y0, c.y - r);
            b.y1 = std::max(b.y1, c.y + r);
        } else if (f->GetType() == b2Shape::e_polygon) {
            for (const glm::dvec2 v : worldPolygon(*f)) {
                b.x0 = std::min(b.x0, v.x);
                b.x1 = std::max(b.x1, v.x);
                b.y0 = std::min(b.y0, v.y);
                b.y1 = std::max(b.y1, v.y);
            }
        }
    }
    return b;
}

/// The free surface of a tank measured from the particles, away from bodies: the fluid's
/// columns (bins one spacing wide across [x0, x1]) that keep `margin` from every excluded
/// x interval; in each, the highest particle centre plus half a spacing (the lattice's surface
/// lies half a spacing above its top row). `height` is their mean, `lo`/`hi` the extremes.
struct Waterline {
    double height = 0.0;
    double lo = INFINITY, hi = -INFINITY;
    uint32_t columns = 0;
};
inline Waterline waterline(const World& world, float spacing, double x0, double x1,
                           const std::vector<std::pair<double, double>>& excluded, double margin) {
    Waterline w;
    if (!(x1 > x0 + spacing)) {
        return w; // no room (a body against a wall): no columns
    }
    const auto n = size_t(std::floor((x1 - x0) / spacing));
    std::vector<double> top(n, -INFINITY);
    const auto px = world.positionX(), py = world.positionY();
    for (uint32_t i = 0; i < world.particleCount(); ++i) {
        const double k = std::floor((px[i] - x0) / spacing);
        if (k >= 0.0 && k < double(n)) {
            top[size_t(k)] = std::max(top[size_t(k)], double(py[i]));
        }
    }
    for (size_t k = 0; k < n; ++k) {
        const double a = x0 + double(k) * spacing, b = a + spacing;
        bool keep = std::isfinite(top[k]);
        for (const auto& [e0, e1] : excluded) {
            keep = keep && (b < e0 - margin || a > e1 + margin);
        }
        if (keep) {
            const double y = top[k] + 0.5 * spacing;
            w.height += y;
            w.lo = std::min(w.lo, y);
            w.hi = std::max(w.hi, y);
            ++w.columns;
        }
    }
    w.height /= std::max(1u, w.columns);
    return w;
}

/// The level of a tank's liquid beside one body (unit: m): the mean of the waterlines between
/// each of the tank's walls (at x = 0 and `width`) and the body, `gap` from either, and the share
/// of the body's area below it (1).
struct Immersion {
    double level = 0.0;
    double submerged = 0.0;
};
inline Immersion immersion(const World& world, const b2Body& body, float spacing, float width,
                           float gap) {
    const Box box = bodyBounds(body);
    const std::vector<std::pair<double, double>> none;
    const Waterline left = waterline(world, spacing, gap, box.x0 - gap, none, 0.0);
    const Waterline right = waterline(world, spacing, box.x1 + gap, width - gap, none, 0.0);
    Immersion out;
    out.level = 0.5 * (left.height + right.height);
    const auto [below, total] = bodyAreaBelow(body, out.level);
    out.submerged = below / total;
    return out;
}

/// FNV-1a of every body's position, angle and velocities as bytes, in body-list order.
inline uint64_t bodiesHash(const b2World& physics) {
    uint64_t h = 1469598103934665603ull;
    for (const b2Body* b = physics.GetBodyList(); b != nullptr; b = b->GetNext()) {
        const b2Vec2 p = b->GetPosition(), v = b->GetLinearVelocity();
        const float state[6] = {p.x, p.y, b->GetAngle(), v.x, v.y, b->GetAngularVelocity()};
        h = fnv1a(state, sizeof state, h);
    }
    return h;
}

/// How deep a particle must lie inside a fixture to count as inside (unit: m). Positions are
/// floats (1.2e-7 m apart at 1 m), and Box2D's float transform of a turned body and the pose
/// the fluid swept it to differ by about 1e-8 m: a particle the fluid left on the surface may
/// read a few nanometres inside (measured: 9.3e-9 m, a crate pressed into a corner).
inline constexpr double kOnSurface = 1e-6;

/// Particles inside a coupled circle or polygon fixture by more than kOnSurface (one whose
/// category passes `mask`; sensors only when `sensors`), and the deepest of them (unit:
/// count, m).
struct Intrusion {
    uint32_t count = 0;
    double deepest = 0.0;
};
/// Of one body.
inline Intrusion intrusion(const World& world, const b2Body& body, uint16_t mask = 0xFFFF,
                           bool sensors = false) {
    Intrusion r;
    const auto px = world.positionX(), py = world.positionY();
    for (const b2Fixture* f = body.GetFixtureList(); f != nullptr; f = f->GetNext()) {
        if (!hasArea(*f) || (f->IsSensor() && !sensors) ||
            (f->GetFilterData().categoryBits & mask) == 0) {
            continue;
        }
        const b2AABB box = f->GetAABB(0);
        for (uint32_t i = 0; i < world.particleCount(); ++i) {
            // The AABB holds the skin radius too: a cheap, safe reject.
            if (px[i] < box.lowerBound.x || px[i] > box.upperBound.x || py[i] < box.lowerBound.y ||
                py[i] > box.upperBound.y) {
                continue;
            }
            const double d = insideDepth(*f, {px[i], py[i]});
            if (d > kOnSurface) {
                ++r.count;
                r.deepest = std::max(r.deepest, d);
            }
        }
    }
    return r;
}
/// Of every body of the b2World.
inline Intrusion intrusion(const World& world, const b2World& physics, uint16_t mask = 0xFFFF,
                           bool sensors = false) {
    Intrusion r;
    for (const b2Body* b = physics.GetBodyList(); b != nullptr; b = b->GetNext()) {
        const Intrusion one = intrusion(world, *b, mask, sensors);
        r.count += one.count;
        r.deepest = std::max(r.deepest, one.deepest);
    }
    return r;
}

/// Linear momentum of every dynamic body: mass x centre-of-mass velocity (unit: kg m/s).
inline glm::dvec2 bodiesMomentum(const b2World& physics) {
    glm::dvec2 p{0.0, 0.0};
    for (const b2Body* b = physics.GetBodyList(); b != nullptr; b = b->GetNext()) {
        if (b->GetType() == b2_dynamicBody) {
            const b2Vec2 v = b->GetLinearVelocity();
            p += double(b->GetMass()) * glm::dvec2(v.x, v.y);
        }
    }
    return p;
}

inline double length(glm::dvec2 v) {
    return std::sqrt(v.x * v.x + v.y * v.y);
}

} // namespace fluid::test
