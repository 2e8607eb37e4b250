// fluid-demo — walls, shapes, sensors, drains, emitters and Box2D bodies as triangles.
#include "demo/scene_draw.h"

#include <fluid/box2d/coupling.h>
#include <fluid/plugins/boundaries.h>

#include <box2d/box2d.h>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <glm/vector_relational.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace fluid::demo {
namespace {

// Palette (straight alpha).
constexpr glm::vec4 kWall{0.42f, 0.45f, 0.50f, 1.0f};
constexpr glm::vec4 kWallEdge{0.62f, 0.66f, 0.72f, 1.0f};
constexpr glm::vec4 kSensor{0.35f, 0.85f, 0.45f, 0.16f};
constexpr glm::vec4 kSensorFill{0.35f, 0.85f, 0.45f, 0.30f};
constexpr glm::vec4 kSensorEdge{0.35f, 0.85f, 0.45f, 0.75f};
constexpr glm::vec4 kDrain{0.55f, 0.10f, 0.12f, 0.45f};
constexpr glm::vec4 kNozzle{0.78f, 0.80f, 0.84f, 1.0f};
constexpr glm::vec4 kBodyEdge{0.10f, 0.08f, 0.06f, 1.0f};
constexpr glm::vec4 kDryBody{0.50f, 0.52f, 0.55f, 1.0f};

// Grows [lo, hi] to hold p.
struct Extent {
    glm::vec2 lo{std::numeric_limits<float>::max()};
    glm::vec2 hi{-std::numeric_limits<float>::max()};
    void add(glm::vec2 p) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    bool empty() const { return lo.x > hi.x; }
};

glm::vec2 toGlm(const b2Vec2& v) {
    return {v.x, v.y};
}

// The world-space outline of a shape plugin's points at its current pose.
std::vector<glm::vec2> placed(const KinematicShape& shape, std::span<const glm::vec2> local) {
    const KinematicShape::Pose pose = shape.pose();
    std::vector<glm::vec2> out;
    out.reserve(local.size());
    for (const glm::vec2 p : local) {
        out.push_back(glm::vec2(pose.toWorld(glm::dvec2(p))));
    }
    return out;
}

// Thickness of the walls drawn round a box tank [lo, hi] (unit: m).
float wallThickness(glm::vec2 lo, glm::vec2 hi) {
    return 0.04f * std::max(hi.x - lo.x, hi.y - lo.y);
}

// Walls of a box tank: four slabs outside the inner rectangle (no ceiling when open).
void drawBox(const BoundaryPlugin& box, gl::ShapeBatch& batch) {
    const glm::vec2 lo{float(box.param("minX")), float(box.param("minY"))};
    const glm::vec2 hi{float(box.param("maxX")), float(box.param("maxY"))};
    const float t = wallThickness(lo, hi);
    batch.rect({lo.x - t, lo.y - t}, {hi.x + t, lo.y}, kWall);
    batch.rect({lo.x - t, lo.y}, {lo.x, hi.y}, kWall);
    batch.rect({hi.x, lo.y}, {hi.x + t, hi.y}, kWall);
    if (box.param("openTop") < 0.5) {
        batch.rect({lo.x - t, hi.y}, {hi.x + t, hi.y + t}, kWall);
    }
}

void drawShape(const Shape& shape, glm::vec4 fill, glm::vec4 edge, float lineWidth,
               gl::ShapeBatch& batch) {
    switch (shape.type) {
    case ShapeType::Rectangle: {
        const glm::vec2 lo = shape.center - shape.halfExtents;
        const glm::vec2 hi = shape.center + shape.halfExtents;
        batch.rect(lo, hi, fill);
        const std::array<glm::vec2, 4> corners{{lo, {hi.x, lo.y}, hi, {lo.x, hi.y}}};
        batch.polyline(corners, lineWidth, edge, true);
        break;
    }
    case ShapeType::Circle:
        batch.disc(shape.center, shape.radius, fill);
        batch.ring(shape.center, shape.radius, lineWidth, edge);
        break;
    case ShapeType::Polygon:
        batch.polygon(shape.vertices, fill);
        batch.polyline(shape.vertices, lineWidth, edge, true);
        break;
    }
}

// Colour of a Box2D body by how its density compares with water's: pale wood floats high,
// dark iron sinks; bodies the fluid does not see are grey.
glm::vec4 bodyColour(const Level& level, const b2Body& body) {
    const b2Fixture* fixture = body.GetFixtureList();
    if (fixture == nullptr) {
        return kDryBody;
    }
    if ((fixture->GetFilterData().categoryBits & kDryFixtureCategory) != 0 ||
        body.GetType() == b2_staticBody) {
        return kWall;
    }
    float reference = 1.0f;
    if (level.world.materialCount() > 0) {
        reference = box2d::arealDensity(level.world, MaterialId{0});
    }
    const float ratio = fixture->GetDensity() / std::max(reference, 1e-6f);
    if (body.GetType() == b2_kinematicBody) {
        return {0.86f, 0.62f, 0.28f, 1.0f}; // planks the player moves: warm orange
    }
    // 0.25 -> light wood, 1 -> mid brown, 2+ -> dark iron.
    const float s = std::clamp((ratio - 0.25f) / 1.75f, 0.0f, 1.0f);
    const glm::vec3 light{0.88f, 0.74f, 0.50f}, dark{0.30f, 0.26f, 0.26f};
    return {glm::mix(light, dark, s), 1.0f};
}

void drawBody(const Level& level, const b2Body& body, const b2Transform& xf, float lineWidth,
              gl::ShapeBatch& batch) {
    const glm::vec4 fill = bodyColour(level, body);
    for (const b2Fixture* f = body.GetFixtureList(); f != nullptr; f = f->GetNext()) {
        const b2Shape* shape = f->GetShape();
        switch (shape->GetType()) {
        case b2Shape::e_polygon: {
            const auto* poly = static_cast<const b2PolygonShape*>(shape);
            std::vector<glm::vec2> pts;
            for (int i = 0; i < poly->m_count; ++i) {
                pts.push_back(toGlm(b2Mul(xf, poly->m_vertices[i])));
            }
            batch.polygon(pts, fill);
            batch.polyline(pts, lineWidth, kBodyEdge, true);
            break;
        }
        case b2Shape::e_circle: {
            const auto* circle = static_cast<const b2CircleShape*>(shape);
            const glm::vec2 c = toGlm(b2Mul(xf, circle->m_p));
            const float r = circle->m_radius;
            batch.disc(c, r, fill);
            batch.ring(c, r, lineWidth, kBodyEdge);
            // A radius line shows the rotation.
            const glm::vec2 dir{xf.q.c, xf.q.s};
            batch.line(c, c + 0.9f * r * dir, lineWidth, kBodyEdge);
            break;
        }
        case b2Shape::e_edge: {
            const auto* edge = static_cast<const b2EdgeShape*>(shape);
            batch.line(toGlm(b2Mul(xf, edge->m_vertex1)), toGlm(b2Mul(xf, edge->m_vertex2)),
                       3.0f * lineWidth, kWall);
            break;
        }
        case b2Shape::e_chain: {
            const auto* chain = static_cast<const b2ChainShape*>(shape);
            std::vector<glm::vec2> pts;
            for (int i = 0; i < chain->m_count; ++i) {
                pts.push_back(toGlm(b2Mul(xf, chain->m_vertices[i])));
            }
            batch.polyline(pts, 3.0f * lineWidth, kWall, false);
            break;
        }
        default:
            break;
        }
    }
}

} // namespace

ViewBounds levelBounds(const Level& level) {
    Extent tank, all;
    for (const auto& plugin : level.world.boundaries()) {
        const std::string_view type = plugin->type();
        if (type == "boundary.box" && tank.empty()) {
            // The tank with the walls drawBox draws round it, so they show whole.
            const glm::vec2 lo{float(plugin->param("minX")), float(plugin->param("minY"))};
            const glm::vec2 hi{float(plugin->param("maxX")), float(plugin->param("maxY"))};
            const float t = wallThickness(lo, hi);
            tank.add(lo - glm::vec2(t));
            tank.add(hi + glm::vec2(t, plugin->param("openTop") < 0.5 ? t : 0.0f));
        } else if (type == "boundary.polygon" || type == "boundary.chain") {
            const auto& shape = static_cast<const KinematicShape&>(*plugin);
            const char* key = type == "boundary.polygon" ? "vertices" : "points";
            for (const glm::vec2 p : placed(shape, plugin->points(key))) {
                all.add(p);
            }
        } else if (type == "boundary.circle") {
            const auto& shape = static_cast<const KinematicShape&>(*plugin);
            const glm::vec2 c(shape.pose().origin);
            const float r = float(plugin->param("radius"));
            all.add(c - glm::vec2(r));
            all.add(c + glm::vec2(r));
        }
    }
    const World& world = level.world;
    const auto x = world.positionX(), y = world.positionY();
    for (std::size_t i = 0; i < x.size(); ++i) {
        all.add({x[i], y[i]});
    }
    for (const auto& [name, id] : level.emitters) {
        all.add(world.emitter(id).position);
    }
    for (const auto& [name, id] : level.sensors) {
        const Shape& s = world.sensor(id).shape;
        all.add(s.center);
    }
    if (level.physics) {
        for (const auto& [name, body] : level.bodies) {
            for (const b2Fixture* f = body->GetFixtureList(); f != nullptr; f = f->GetNext()) {
                b2AABB box;
                f->GetShape()->ComputeAABB(&box, body->GetTransform(), 0);
                // Static ground bodies may reach far beyond the play area; frame the rest, and
                // static fixtures that stay within a tenth of the tank's size of it (a tank's
                // own Box2D walls).
                const glm::vec2 lower = toGlm(box.lowerBound), upper = toGlm(box.upperBound);
                const glm::vec2 slack = 0.1f * (tank.hi - tank.lo);
                const bool nearTank = !tank.empty() &&
                                      glm::all(glm::greaterThanEqual(lower, tank.lo - slack)) &&
                                      glm::all(glm::lessThanEqual(upper, tank.hi + slack));
                if (body->GetType() != b2_staticBody || tank.empty() || nearTank) {
                    all.add(lower);
                    all.add(upper);
                }
            }
        }
    }
    ViewBounds bounds;
    if (!tank.empty()) {
        Extent framed = tank;
        if (!all.empty()) {
            // Emitters or bodies above an open tank stay in the picture.
            framed.add(glm::max(all.lo, tank.lo - 0.5f * (tank.hi - tank.lo)));
            framed.add(glm::min(all.hi, tank.hi + 0.5f * (tank.hi - tank.lo)));
        }
        bounds.lo = framed.lo;
        bounds.hi = framed.hi;
        return bounds;
    }
    if (all.empty()) {
        return bounds;
    }
    // No tank: blobs drift, so leave them room (half the extent on every side, at least 0.2 m).
    const glm::vec2 size = all.hi - all.lo;
    const glm::vec2 room = glm::max(0.5f * size, glm::vec2(0.2f));
    bounds.lo = all.lo - room;
    bounds.hi = all.hi + room;
    return bounds;
}

void drawUnder(const Level& level, double goalFill, float lineWidth, gl::ShapeBatch& batch) {
    const World& world = level.world;
    for (const auto& [name, id] : level.drains) {
        drawShape(world.drain(id).shape, kDrain, kDrain, lineWidth, batch);
    }
    for (const auto& [name, id] : level.sensors) {
        const Shape& shape = world.sensor(id).shape;
        drawShape(shape, kSensor, kSensorEdge, lineWidth, batch);
        if (level.goal.present && level.goal.sensor == id && shape.type == ShapeType::Rectangle) {
            // The goal's progress as a level rising in the sensor.
            const float fill = float(std::clamp(goalFill, 0.0, 1.0));
            const glm::vec2 lo = shape.center - shape.halfExtents;
            const glm::vec2 hi = shape.center + shape.halfExtents;
            batch.rect(lo, {hi.x, lo.y + fill * (hi.y - lo.y)}, kSensorFill);
        }
    }
    for (const auto& plugin : world.boundaries()) {
        const std::string_view type = plugin->type();
        if (type == "boundary.box") {
            drawBox(*plugin, batch);
            continue;
        }
        const auto* shape = dynamic_cast<const KinematicShape*>(plugin.get());
        if (shape == nullptr) {
            continue; // the Box2D coupling and user plugins: drawn by drawOver or not at all
        }
        if (type == "boundary.polygon") {
            const auto pts = placed(*shape, plugin->points("vertices"));
            batch.polygon(pts, kWall);
            batch.polyline(pts, lineWidth, kWallEdge, true);
        } else if (type == "boundary.chain") {
            const auto pts = placed(*shape, plugin->points("points"));
            batch.polyline(pts, 2.5f * lineWidth, kWall, plugin->param("closed") > 0.5);
        } else if (type == "boundary.circle") {
            const glm::vec2 c(shape->pose().origin);
            const float r = float(plugin->param("radius"));
            batch.disc(c, r, {0.36f, 0.32f, 0.30f, 1.0f});
            batch.ring(c, r, lineWidth, kWallEdge);
        }
    }
}

void drawOver(const Level& level, float lineWidth, gl::ShapeBatch& batch,
              std::span<const BodyPose> previous, float factor) {
    const World& world = level.world;
    for (const auto& [name, id] : level.emitters) {
        const EmitterDef& e = world.emitter(id);
        const glm::vec2 dir = glm::normalize(e.direction);
        const glm::vec2 across{-dir.y, dir.x};
        const float half = 0.5f * e.width + 2.0f * lineWidth;
        const float length = 4.0f * lineWidth + 0.5f * e.width;
        const glm::vec2 back = e.position - length * dir;
        const std::array<glm::vec2, 4> nozzle{{back - half * across, e.position - half * across,
                                               e.position + half * across, back + half * across}};
        batch.polygon(nozzle, kNozzle);
    }
    if (!level.physics) {
        return;
    }
    for (const b2Body* body = level.physics->GetBodyList(); body != nullptr;
         body = body->GetNext()) {
        b2Transform xf = body->GetTransform();
        const auto was = std::find_if(previous.begin(), previous.end(),
                                      [&](const BodyPose& p) { return p.body == body; });
        if (was != previous.end() && factor < 1.0f) {
            // Between the frame's start and its end: the angle the short way round.
            const float turn = std::remainder(body->GetAngle() - was->angle, 2.0f * b2_pi);
            const glm::vec2 at = glm::mix(was->position, toGlm(body->GetPosition()), factor);
            xf.Set({at.x, at.y}, was->angle + factor * turn);
        }
        drawBody(level, *body, xf, lineWidth, batch);
    }
}

} // namespace fluid::demo
