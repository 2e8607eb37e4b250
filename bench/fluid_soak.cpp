// fluid-soak: a long scripted game scene that checks, after every frame, what a game that runs
// for hours must never lose. See scripts/soak.sh and bench/soak.md.
//
// The scene: a closed 2.5 x 1.5 m tank with about 19,000 particles of water and yoghurt, Box2D
// crates and a motor-driven paddle wheel, two faucets (the yoghurt one with lifetimes) and two
// drains, a pointer that pushes and pulls, explosions, gravity flipping between down, up and
// sideways, kinematic planks the script moves (one fast; crates collide with their Box2D
// twins), and blobs dropped onto each other.
// The overflow drains keep the liquid near 0.8 m deep while the faucets pour.
// After every frame:
//   - particles = start + emitted + dropped in blobs - removed (drained or expired, each
//     removal reported once in the coupling's events);
//   - no particle outside the tank, none deeper than a quarter spacing inside a plank or a body
//     (plus, for a body, how far it moves in a coupling round: the fluid projects against the
//     body's pose advanced over the round, Box2D's pose lags it). The planks have kinematic
//     Box2D twins the crates collide with; where Box2D still lets a crate touch a plank, a
//     particle between them has no admissible place, and the body's projection (the last)
//     leaves it on the body's surface inside the plank: a particle inside a plank that touches
//     a body at the pose the fluid used is counted as squeezed, not failed;
//   - every position and velocity finite; every body inside the tank;
//   - resident memory, after the first minute (a third of shorter runs), within 5% of its value
//     then.
// The first failure prints the frame, the check and the figures, and exits 1.
#include "command_line.h"

#include <fluid/box2d/coupling.h>
#include <fluid/box2d/physics_save.h>
#include <fluid/fluid.h>

#include <box2d/box2d.h>
#include <CLI/CLI.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;

constexpr float kFrame = 1.0f / 60.0f;
constexpr float kWidth = 2.5f, kHeight = 1.5f; // the tank (m)
constexpr float kG = 9.81f;

// Resident memory of this process (unit: bytes; 0 when /proc is not there).
double residentBytes() {
    std::ifstream statm("/proc/self/statm");
    double pages = 0.0, resident = 0.0;
    if (!(statm >> pages >> resident)) {
        return 0.0;
    }
    return resident * 4096.0;
}

// Depth of `p` inside a Box2D fixture (unit: m; <= 0 outside). Polygons and circles only.
float depthInside(const b2Fixture* fixture, b2Vec2 p) {
    const b2Transform& xf = fixture->GetBody()->GetTransform();
    const b2Vec2 local = b2MulT(xf, p);
    if (fixture->GetType() == b2Shape::e_circle) {
        const auto* c = static_cast<const b2CircleShape*>(fixture->GetShape());
        return c->m_radius - (local - c->m_p).Length();
    }
    if (fixture->GetType() == b2Shape::e_polygon) {
        const auto* poly = static_cast<const b2PolygonShape*>(fixture->GetShape());
        float depth = 1e30f;
        for (int32 k = 0; k < poly->m_count; ++k) {
            depth = std::min(depth, -b2Dot(poly->m_normals[k], local - poly->m_vertices[k]));
        }
        return depth;
    }
    return 0.0f;
}

// Depth of `p` inside a convex plank polygon given in world coordinates (counter-clockwise).
float depthInside(const std::vector<glm::dvec2>& poly, glm::dvec2 p) {
    double depth = 1e30;
    for (size_t k = 0; k < poly.size(); ++k) {
        const glm::dvec2 a = poly[k], b = poly[(k + 1) % poly.size()];
        const glm::dvec2 edge = b - a;
        const glm::dvec2 normal = glm::normalize(glm::dvec2(edge.y, -edge.x)); // outward
        depth = std::min(depth, -glm::dot(normal, p - a));
    }
    return float(depth);
}

struct Plank {
    fluid::PolygonBoundary* plugin = nullptr;
    b2Body* body = nullptr; // its Box2D twin (kinematic, not coupled): crates collide with it
    std::vector<glm::vec2> local;
    float speed = 0.0f; // along x (m/s), reversed at the ends of its lane
    float lo = 0.0f, hi = 0.0f;
};

b2Body* addBox(b2World& physics, b2BodyType type, b2Vec2 center, float hx, float hy,
               float density, uint16_t category = 0x0001) {
    b2BodyDef def;
    def.type = type;
    def.position = center;
    b2Body* body = physics.CreateBody(&def);
    b2PolygonShape shape;
    shape.SetAsBox(hx, hy);
    b2FixtureDef fixture;
    fixture.shape = &shape;
    fixture.density = density;
    fixture.friction = 0.4f;
    fixture.filter.categoryBits = category;
    body->CreateFixture(&fixture);
    return body;
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app{"fluid-soak: a long scripted scene checked after every frame"};
    double seconds = 60.0;
    uint32_t threads = 2;
    app.add_option("--seconds", seconds, "Wall-clock time to run (s)")->check(CLI::Range(1.0, 1e6));
    app.add_option("--threads", threads, "Worker threads")->check(CLI::Range(1u, 256u));
    uint32_t dumpFrame = 0;
    std::string dumpPrefix;
    app.add_option("--dump-frame", dumpFrame,
                   "Before this frame's step, save the world, the Box2D world and the coupling "
                   "to PREFIX.world, PREFIX.b2d and PREFIX.coupling (to replay a failure)");
    app.add_option("--dump", dumpPrefix, "PREFIX for --dump-frame");
    std::string quality;
    fluid::tools::addQualityOption(app, quality, "The position-based preset: game (the default) or precise");
    if (const int status = fluid::tools::parseCommandLine(app, argc, argv); status >= 0) {
        return status;
    }

    fluid::WorldDef def = fluid::tools::presetWorldDef(quality, threads);
    def.maxParticles = 40000;
    fluid::World world(def);
    const fluid::MaterialId water = world.addMaterial(fluid::water());
    const fluid::MaterialId yoghurt = world.addMaterial(fluid::yoghurt());
    auto& gravity = static_cast<fluid::GravityForce&>(
        world.addForce(std::make_unique<fluid::GravityForce>(0.0f, -kG)));
    auto& pointer = static_cast<fluid::PointerForce&>(
        world.addForce(std::make_unique<fluid::PointerForce>(0.2f, 60.0f)));
    auto& blast = static_cast<fluid::ExplosionForce&>(world.addForce(
        std::make_unique<fluid::ExplosionForce>(glm::vec2(1.0f, 0.3f), 0.3f, 2.0f)));

    // Kinematic planks: a slow one low in the water, a fast one higher up.
    std::vector<Plank> planks(2);
    planks[0].local = {{-0.15f, -0.02f}, {0.15f, -0.02f}, {0.15f, 0.02f}, {-0.15f, 0.02f}};
    planks[0].speed = 0.4f;
    planks[0].lo = 0.4f;
    planks[0].hi = 2.1f;
    planks[1].local = {{-0.1f, -0.015f}, {0.1f, -0.015f}, {0.1f, 0.015f}, {-0.1f, 0.015f}};
    planks[1].speed = 6.0f;
    planks[1].lo = 0.3f;
    planks[1].hi = 2.2f;
    const float plankY[2] = {0.3f, 0.95f};
    for (size_t k = 0; k < planks.size(); ++k) {
        auto plugin = std::make_unique<fluid::PolygonBoundary>(planks[k].local);
        plugin->setPose({0.5f * (planks[k].lo + planks[k].hi), plankY[k]}, 0.0f);
        plugin->setVelocity({planks[k].speed, 0.0f}, 0.0f);
        planks[k].plugin = plugin.get();
        world.addBoundary(std::move(plugin));
    }
    world.addBoundary(std::make_unique<fluid::BoxContainer>(0.0f, 0.0f, kWidth, kHeight));

    // The liquid: water over the floor, a yoghurt block on the right.
    fluid::BlobDef pool;
    pool.material = water;
    pool.shape.center = {0.95f, 0.4f};
    pool.shape.halfExtents = {0.945f, 0.395f};
    world.spawnBlob(pool);
    fluid::BlobDef block;
    block.material = yoghurt;
    block.shape.center = {2.2f, 0.4f};
    block.shape.halfExtents = {0.295f, 0.395f};
    world.spawnBlob(block);

    // Faucets, overflow drains in the side walls 0.8 m up, and the yoghurt's particles live
    // 20 s.
    fluid::EmitterDef tap;
    tap.position = {0.5f, 1.35f};
    tap.direction = {0.2f, -1.0f};
    tap.speed = 1.5f;
    tap.width = 0.05f;
    tap.rate = 250.0f;
    tap.material = water;
    world.addEmitter(tap);
    tap.position = {1.8f, 1.35f};
    tap.direction = {-0.2f, -1.0f};
    tap.material = yoghurt;
    tap.rate = 150.0f;
    tap.lifetime = 20.0f;
    world.addEmitter(tap);
    fluid::DrainDef drain;
    drain.shape = fluid::Shape::box({0.0f, 0.8f}, {0.04f, 0.86f});
    world.addDrain(drain);
    drain.shape = fluid::Shape::box({kWidth - 0.04f, 0.8f}, {kWidth, 0.86f});
    world.addDrain(drain);

    // Box2D: static walls just outside the tank (not coupled), crates, a paddle wheel.
    b2World physics(b2Vec2(0.0f, -kG));
    constexpr uint16_t kWall = 0x0002;
    const float t = 0.1f;
    addBox(physics, b2_staticBody, {0.5f * kWidth, -t}, 0.5f * kWidth + t, t, 0.0f, kWall);
    addBox(physics, b2_staticBody, {0.5f * kWidth, kHeight + t}, 0.5f * kWidth + t, t, 0.0f, kWall);
    addBox(physics, b2_staticBody, {-t, 0.5f * kHeight}, t, 0.5f * kHeight + t, 0.0f, kWall);
    addBox(physics, b2_staticBody, {kWidth + t, 0.5f * kHeight}, t, 0.5f * kHeight + t, 0.0f,
           kWall);
    // Each plank has a kinematic Box2D twin that the crates collide with, as a game would make
    // its moving platforms: without it a crate sinks onto a plank and overlaps it, and the
    // liquid between them has no admissible place.
    for (size_t k = 0; k < planks.size(); ++k) {
        const fluid::KinematicShape::Pose pose = planks[k].plugin->pose();
        const glm::vec2 half = planks[k].local[2]; // the top-right corner: half extents
        planks[k].body = addBox(physics, b2_kinematicBody,
                                {float(pose.origin.x), float(pose.origin.y)}, half.x, half.y, 0.0f,
                                kWall);
        planks[k].body->SetLinearVelocity({planks[k].speed, 0.0f});
    }
    const float rho = fluid::box2d::arealDensity(world, water);
    std::vector<b2Body*> bodies;
    for (int k = 0; k < 6; ++k) {
        const float ratio = 0.3f + 0.3f * float(k); // 0.3 to 1.8 times water
        bodies.push_back(addBox(physics, b2_dynamicBody, {0.3f + 0.35f * float(k), 1.0f}, 0.05f,
                                0.04f, ratio * rho));
    }
    b2BodyDef hubDef;
    hubDef.position.Set(1.25f, 0.6f);
    b2Body* anchor = physics.CreateBody(&hubDef);
    hubDef.type = b2_dynamicBody;
    b2Body* wheel = physics.CreateBody(&hubDef);
    for (int k = 0; k < 4; ++k) {
        b2PolygonShape blade;
        const float a = float(k) * 0.5f * b2_pi;
        blade.SetAsBox(0.12f, 0.012f, b2Vec2(0.12f * std::cos(a), 0.12f * std::sin(a)), a);
        wheel->CreateFixture(&blade, 0.8f * rho);
    }
    b2RevoluteJointDef hinge;
    hinge.Initialize(anchor, wheel, anchor->GetPosition());
    hinge.enableMotor = true;
    hinge.motorSpeed = 2.0f;
    hinge.maxMotorTorque = 5.0f;
    physics.CreateJoint(&hinge);
    bodies.push_back(wheel);
    fluid::box2d::CouplingDef cdef;
    cdef.categoryMask = uint16_t(0xFFFF & ~kWall);
    fluid::box2d::Coupling coupling(world, physics, cdef);

    const uint32_t rounds = world.def().positionBased.substeps; // the coupling's per frame
    const float spacing = world.spacing(water);
    const float deep = 0.25f * spacing;
    const uint32_t start = world.particleCount();
    uint64_t emitted = 0, removed = 0, dropped = 0, expired = 0, skipped = 0, squeezed = 0;
    std::printf("fluid-soak: %u particles (water and yoghurt), %zu bodies, %u threads, %.0f s\n",
                start, bodies.size(), threads, seconds);

    const Clock::time_point begin = Clock::now();
    const double baselineAt = std::min(60.0, seconds / 3.0);
    double baseline = 0.0, peak = 0.0;
    uint32_t frame = 0;
    auto fail = [&](const std::string& what) {
        std::printf("fluid-soak: FAILED at frame %u (%.1f s simulated): %s\n", frame,
                    double(frame) * kFrame, what.c_str());
        std::exit(1);
    };
    for (;;) {
        const double elapsed = std::chrono::duration<double>(Clock::now() - begin).count();
        if (elapsed >= seconds) {
            break;
        }
        ++frame;
        const float time = float(frame) * kFrame;
        // The script.
        const int phase = int(time / 3.0f) % 4; // gravity, 3 s each: down, up, down, sideways
        const glm::vec2 g = phase == 1 ? glm::vec2(0.0f, kG)
                                       : (phase == 3 ? glm::vec2(kG, -kG) : glm::vec2(0.0f, -kG));
        gravity.setParam("gx", g.x);
        gravity.setParam("gy", g.y);
        physics.SetGravity(b2Vec2(g.x, g.y));
        const float a = 0.7f * time;
        pointer.setPointer({1.25f + 0.8f * std::cos(a), 0.6f + 0.4f * std::sin(a)}, 1.0f);
        pointer.setParam("strength", (int(time) % 2 == 0) ? 60.0 : -60.0); // push, pull
        if (frame % 120 == 0) { // an explosion every 2 s, somewhere else each time
            blast.setParam("x", 0.3 + double(frame % 1700) / 1700.0 * 1.9);
            blast.setParam("y", 0.2);
            blast.fire();
        }
        for (Plank& p : planks) {
            const fluid::KinematicShape::Pose pose = p.plugin->pose();
            if ((pose.origin.x > p.hi && p.speed > 0.0f) || (pose.origin.x < p.lo && p.speed < 0.0f)) {
                p.speed = -p.speed;
                p.plugin->setVelocity({p.speed, 0.0f}, 0.0f);
            }
            p.body->SetTransform({float(pose.origin.x), float(pose.origin.y)}, 0.0f);
            p.body->SetLinearVelocity({p.speed, 0.0f});
        }
        if (frame % 150 == 0) {
            // Two blobs dropped onto each other where nothing stands yet.
            const float x = 0.4f + float((frame / 150) % 5) * 0.4f;
            const float y = phase == 1 ? 0.3f : 1.15f; // away from where gravity gathers it
            bool clear = true;
            const auto px = world.positionX(), py = world.positionY();
            for (uint32_t i = 0; i < world.particleCount() && clear; ++i) {
                clear = std::fabs(px[i] - x) > 0.1f || std::fabs(py[i] - y) > 0.2f;
            }
            if (clear) {
                fluid::BlobDef drop;
                drop.material = (frame / 150) % 2 == 0 ? water : yoghurt;
                drop.shape.type = fluid::ShapeType::Circle;
                drop.shape.radius = 0.05f;
                drop.shape.center = {x, y - 0.07f};
                dropped += world.spawnBlob(drop);
                drop.shape.center = {x, y + 0.07f};
                drop.velocity = {0.0f, -1.0f};
                dropped += world.spawnBlob(drop);
            }
        }

        const uint32_t before = world.particleCount();
        if (frame == dumpFrame && !dumpPrefix.empty()) {
            world.saveFile(dumpPrefix + ".world");
            std::ofstream b2d(dumpPrefix + ".b2d", std::ios::binary);
            fluid::box2d::savePhysics(physics, b2d);
            std::ofstream state(dumpPrefix + ".coupling", std::ios::binary);
            coupling.save(state);
            std::printf("fluid-soak: saved frame %u to %s.*\n", frame, dumpPrefix.c_str());
        }
        coupling.step(world, kFrame);

        // The checks.
        const fluid::Profile& prof = coupling.profile();
        emitted += prof.emitted;
        skipped += prof.emitSkipped;
        for (const fluid::RemovedEvent& e : coupling.removedEvents()) {
            ++removed;
            expired += e.cause == fluid::RemovalCause::Lifetime ? 1 : 0;
        }
        const uint64_t expected = uint64_t(start) + emitted + dropped - removed;
        if (world.particleCount() != expected) {
            fail("particles " + std::to_string(world.particleCount()) + " != start " +
                 std::to_string(start) + " + emitted " + std::to_string(emitted) + " + dropped " +
                 std::to_string(dropped) + " - removed " + std::to_string(removed) +
                 " (before the frame " + std::to_string(before) + ")");
        }
        const auto px = world.positionX(), py = world.positionY();
        const auto vx = world.velocityX(), vy = world.velocityY();
        // The fluid's last projection saw each body where its velocity takes it over the last
        // round (the coupling moves bodies as kinematic shapes through the fluid's step, after
        // Box2D's): behind a moving body, particles stand up to that far inside its Box2D pose.
        std::vector<float> bodyDeep(bodies.size());
        for (size_t b = 0; b < bodies.size(); ++b) {
            const float reach = bodies[b] == wheel ? 0.25f : 0.07f; // farthest fixture point
            const float speed = bodies[b]->GetLinearVelocity().Length() +
                                std::fabs(bodies[b]->GetAngularVelocity()) * reach;
            bodyDeep[b] = deep + speed * (kFrame / float(rounds));
        }
        // A point moved back by a body's motion over one coupling round: where it stands
        // against the pose the fluid's last projection used (Box2D's pose advanced over the
        // round), in Box2D's pose.
        const auto poseBack = [&](const b2Body* body, b2Vec2 p) {
            const float h = kFrame / float(rounds);
            const b2Vec2 c = body->GetWorldCenter();
            const float turn = -body->GetAngularVelocity() * h;
            const b2Vec2 d = p - c;
            return c +
                   b2Vec2(std::cos(turn) * d.x - std::sin(turn) * d.y,
                          std::sin(turn) * d.x + std::cos(turn) * d.y) -
                   h * body->GetLinearVelocity();
        };
        std::vector<std::vector<glm::dvec2>> plankPolys;
        for (const Plank& p : planks) {
            const fluid::KinematicShape::Pose pose = p.plugin->pose();
            std::vector<glm::dvec2> poly;
            for (glm::vec2 v : p.local) {
                poly.push_back(pose.toWorld(glm::dvec2(v)));
            }
            plankPolys.push_back(std::move(poly));
        }
        for (uint32_t i = 0; i < world.particleCount(); ++i) {
            if (!std::isfinite(px[i]) || !std::isfinite(py[i]) || !std::isfinite(vx[i]) ||
                !std::isfinite(vy[i])) {
                fail("particle " + std::to_string(i) + " is not finite");
            }
            if (px[i] < 0.0f || px[i] > kWidth || py[i] < 0.0f || py[i] > kHeight) {
                fail("particle " + std::to_string(i) + " outside the tank at (" +
                     std::to_string(px[i]) + ", " + std::to_string(py[i]) + ")");
            }
            for (size_t k = 0; k < plankPolys.size(); ++k) {
                const float depth = depthInside(plankPolys[k], glm::dvec2(px[i], py[i]));
                if (depth > deep) {
                    // Pressed there by a body: it touches the particle at the pose the fluid
                    // used (its own put the particle on its surface).
                    bool pressed = false;
                    for (size_t b = 0; b < bodies.size() && !pressed; ++b) {
                        const b2Vec2 back = poseBack(bodies[b], b2Vec2(px[i], py[i]));
                        for (b2Fixture* f = bodies[b]->GetFixtureList(); f != nullptr;
                             f = f->GetNext()) {
                            pressed = pressed || depthInside(f, back) > -deep;
                        }
                    }
                    if (pressed) {
                        ++squeezed;
                        continue;
                    }
                    // Whether a body presses it there: the nearest body fixture's depth (< 0:
                    // that far outside it).
                    float nearest = -1e30f;
                    size_t nearestBody = 0;
                    for (size_t b = 0; b < bodies.size(); ++b) {
                        for (b2Fixture* f = bodies[b]->GetFixtureList(); f != nullptr;
                             f = f->GetNext()) {
                            const float d = depthInside(f, b2Vec2(px[i], py[i]));
                            if (d > nearest) {
                                nearest = d;
                                nearestBody = b;
                            }
                        }
                    }
                    fail("particle " + std::to_string(i) + " " + std::to_string(depth) +
                         " m inside plank " + std::to_string(k) + " (allowed " +
                         std::to_string(deep) + " m; plank at " +
                         std::to_string(planks[k].plugin->pose().velocity.x) +
                         " m/s; particle at (" + std::to_string(px[i]) + ", " +
                         std::to_string(py[i]) + "), (" + std::to_string(vx[i]) + ", " +
                         std::to_string(vy[i]) + ") m/s; nearest body " +
                         std::to_string(nearestBody) + " at depth " + std::to_string(nearest) +
                         " m)");
                }
            }
            for (size_t b = 0; b < bodies.size(); ++b) {
                for (b2Fixture* f = bodies[b]->GetFixtureList(); f != nullptr; f = f->GetNext()) {
                    const float depth = depthInside(f, b2Vec2(px[i], py[i]));
                    if (depth > bodyDeep[b]) {
                        // The same depth in the body's frame moved back by its motion over a
                        // round: what it would read against the pose the fluid used.
                        const b2Body* body = bodies[b];
                        const b2Vec2 c = body->GetWorldCenter();
                        const b2Vec2 back = poseBack(body, b2Vec2(px[i], py[i]));
                        fail("particle " + std::to_string(i) + " " + std::to_string(depth) +
                             " m inside body " + std::to_string(b) + " (allowed " +
                             std::to_string(bodyDeep[b]) + " m; body at " +
                             std::to_string(body->GetLinearVelocity().Length()) + " m/s, " +
                             std::to_string(body->GetAngularVelocity()) + " rad/s; particle at " +
                             std::to_string(std::hypot(vx[i], vy[i])) + " m/s, " +
                             std::to_string(std::hypot(px[i] - c.x, py[i] - c.y)) +
                             " m from its centre; against the pose a round ahead " +
                             std::to_string(depthInside(f, back)) + " m)");
                    }
                }
            }
        }
        for (b2Body* body : bodies) {
            const b2Vec2 c = body->GetPosition();
            if (!std::isfinite(c.x) || !std::isfinite(c.y) || c.x < 0.0f || c.x > kWidth ||
                c.y < 0.0f || c.y > kHeight) {
                fail("a body left the tank: (" + std::to_string(c.x) + ", " +
                     std::to_string(c.y) + ")");
            }
        }
        const double rss = residentBytes();
        const double now = std::chrono::duration<double>(Clock::now() - begin).count();
        if (baseline == 0.0 && now >= baselineAt) {
            baseline = rss;
        }
        peak = std::max(peak, rss);
        if (baseline > 0.0 && rss > 1.05 * baseline) {
            fail("resident memory " + std::to_string(rss / 1048576.0) + " MB, more than 5% over " +
                 std::to_string(baseline / 1048576.0) + " MB at " + std::to_string(baselineAt) +
                 " s");
        }
        if (frame % 300 == 0) {
            std::printf("fluid-soak: %.0f s simulated, %u particles, emitted %llu (skipped "
                        "%llu), dropped %llu, drained %llu, expired %llu, squeezed %llu, %.1f MB "
                        "resident\n",
                        double(time), world.particleCount(), (unsigned long long)emitted,
                        (unsigned long long)skipped, (unsigned long long)dropped,
                        (unsigned long long)(removed - expired), (unsigned long long)expired,
                        (unsigned long long)squeezed, rss / 1048576.0);
            std::fflush(stdout); // progress shows in a log file as it happens
        }
    }
    std::printf("fluid-soak: passed: %u frames (%.1f s simulated) in %.0f s, %u particles at the "
                "end, emitted %llu (skipped %llu), dropped %llu, removed %llu (%llu expired), "
                "squeezed between a body and a plank %llu particle-frames, resident memory "
                "%.1f MB at %.0f s, peak %.1f MB\n",
                frame, double(frame) * kFrame, seconds, world.particleCount(),
                (unsigned long long)emitted, (unsigned long long)skipped,
                (unsigned long long)dropped, (unsigned long long)removed,
                (unsigned long long)expired, (unsigned long long)squeezed, baseline / 1048576.0,
                baselineAt, peak / 1048576.0);
    return 0;
}
