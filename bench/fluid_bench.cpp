// fluid-bench: times World::step on a standard scene and prints one summary line.
//
//   fluid-bench --scene dam --particles 16000 --frames 600 --threads 2 [--warmup N]
//               [--solver position-based|explicit] [--quality game|precise] [--substeps S]
//               [--iterations I] [--eos tait|linear] [--no-coupling] [--window A:B]
//
// Scenes (see bench/README.md):
//   dam     a water block (width:height 1:2) standing in the left of a closed box four block
//           widths wide and 1.5 block heights tall, floor at y = 0, gravity (0, -9.81) m/s^2.
//   blob    a round water blob in zero gravity, no boundary, no force plugin.
//   crates  the dam with 20 Box2D crates (boxes and circles, 0.25 to 2 times water's areal
//           density) in its path, coupled by fluid::box2d::Coupling::step; with --no-coupling
//           the same bodies are stepped by Box2D but the fluid does not see them.
//   tank    a resting water tank: nx by round(5 nx / 3) water particles (1500 by default: 30 x
//           50, 0.30 x 0.50 m) filling the width of a closed box 1.595 water heights tall,
//           gravity (0, -9.81) m/s^2; 300 frames (5 s, warm-up included) by default.
// Every frame is 1/60 s. --quality picks the position-based preset (fluid::positionBasedPreset,
// default game); --substeps and --iterations override it. After every frame, outside the timed
// part, the bench measures each particle's compression from the positions alone (Wendland C2
// density sum over h = 0.032 m against the same sum on the square lattice, clamped at 0);
// --window A:B (1-based frames, warm-up included; default: the timed frames) picks the frames
// the window_ fields cover. The last stdout line is machine-readable:
//   solver=NAME particles=N frames=F threads=T substeps_per_frame=S iterations=I
//   density_error_max=E ms_per_frame=M ns_per_particle_substep=P ms_per_frame_mean=A
//   ms_per_frame_p90=Q cpu_ms_per_frame=C quality=NAME compression_mean=CM
//   compression_p99=C99 compression_max=CX window=A:B window_compression_mean=WM
//   window_compression_max=WX stacked=K0 [tank: surface_change=D thrown=K ke_per_kg=KE
//   surface_change_last_second=DL]
// stacked: particles at exactly the position of another after the last frame (pair terms have
// no direction to part them). surface_change_last_second: the surface change averaged over the
// last 60 frames.
#include "command_line.h"

#include <fluid/fluid.h>

#if FLUID_BENCH_BOX2D
#include <box2d/box2d.h>
#include <fluid/box2d/coupling.h>
#endif

#include <CLI/CLI.hpp>

#include "compression.h"

#include <algorithm>
#include <bit>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <ctime>
#include <functional>
#include <memory>
#include <numbers>
#include <numeric>
#include <random>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace {

/// Command-line options (see the usage above).
struct Options {
    /// "dam", "blob", "crates" or "tank".
    std::string scene = "dam";
    /// Wanted particle count (unit: count); the lattice gives about this many. 0 = the scene's
    /// default: 1500 for the tank, 16000 for the others.
    uint32_t particles = 0;
    /// Timed frames (unit: count). 0 = the scene's default: 600, for the tank 300 simulated
    /// frames (5 s) less the warm-up.
    uint32_t frames = 0;
    /// Frames stepped before timing starts (unit: count).
    uint32_t warmup = 2;
    /// WorldDef::workerCount (unit: count).
    uint32_t threads = 1;
    /// "position-based" or "explicit".
    std::string solver = "position-based";
    /// Position-based preset the solver settings start from: "game" or "precise".
    std::string quality{fluid::qualityName(fluid::Quality::Game)};
    /// PositionBasedDef::substeps (unit: count; 0 keeps the quality preset's).
    uint32_t substeps = 0;
    /// PositionBasedDef::iterations (unit: count; 0 keeps the quality preset's).
    uint32_t iterations = 0;
    /// PositionBasedDef::viscosityInterval (unit: count; 0 keeps the quality preset's).
    uint32_t viscosityInterval = 0;
    /// PositionBasedDef::coarseCorrection (unit: 1; negative keeps the quality preset's).
    float coarse = -1.0f;
    /// PositionBasedDef::shearConstraint (unit: switch; negative keeps the preset's).
    int shearConstraint = -1;
    /// "tait" or "linear" (explicit solver).
    std::string eos{fluid::equationOfStateName(fluid::EquationOfState::Tait)};
    /// The scene's liquid: "water" or "yoghurt" (the presets of fluid/material.h).
    std::string material = "water";
    /// Crates scene: step Box2D next to the fluid without coupling them (the reference run).
    bool noCoupling = false;
    /// Crates scene: every crate asks for contact events (Coupling::setContactEvents), read
    /// after each frame.
    bool contacts = false;
    /// Region queries timed after the run (unit: count; 0: none): 10 cm boxes at random places
    /// over the liquid's bounding box (fluid/query.h, docs/queries.md).
    uint32_t queries = 0;
    /// Ray casts and samples timed after the run (unit: count of each; 0: none): random rays
    /// across the liquid's bounding box, rays straight down onto it, samples at random points
    /// (fluid/query.h, docs/queries.md).
    uint32_t rays = 0;
    /// Keep the previous sub-step's positions for drawing between steps
    /// (fluid::setInterpolation; fluid/groups.h): its cost is the step's difference.
    bool interpolate = false;
    /// "A:B" as given on the command line (empty: the timed frames); parsed into
    /// `windowFirst` and `windowLast`.
    std::string window;
    /// First frame of the compression window (unit: 1-based frame number counting from the
    /// first simulated frame, warm-up included).
    uint32_t windowFirst = 0;
    /// Last frame of the compression window, included (unit: as `windowFirst`).
    uint32_t windowLast = 0;
};

/// Times `count` region queries (countParticles over 10 cm boxes, places from a fixed seed over
/// the particles' bounding box) on the world as the run left it: the first, which builds the
/// query grid, and the rest; prints one line.
void timeQueries(const fluid::World& world, uint32_t count) {
    const auto px = world.positionX(), py = world.positionY();
    if (px.empty()) {
        return;
    }
    const float x0 = *std::min_element(px.begin(), px.end());
    const float x1 = *std::max_element(px.begin(), px.end());
    const float y0 = *std::min_element(py.begin(), py.end());
    const float y1 = *std::max_element(py.begin(), py.end());
    std::mt19937 rng(12345);
    std::uniform_real_distribution<float> ux(x0, x1), uy(y0, y1);
    std::vector<fluid::Shape> boxes;
    for (uint32_t k = 0; k < count; ++k) {
        const glm::vec2 c{ux(rng), uy(rng)};
        boxes.push_back(fluid::Shape::box(c - glm::vec2(0.05f), c + glm::vec2(0.05f)));
    }
    using Clock = std::chrono::steady_clock;
    uint64_t found = 0;
    const auto t0 = Clock::now();
    found += fluid::countParticles(world, boxes[0]);
    const auto t1 = Clock::now();
    for (uint32_t k = 1; k < count; ++k) {
        found += fluid::countParticles(world, boxes[k]);
    }
    const auto t2 = Clock::now();
    const double first = std::chrono::duration<double, std::milli>(t1 - t0).count();
    const double rest = std::chrono::duration<double, std::milli>(t2 - t1).count();
    std::printf("queries: %u boxes of 0.1 m over the liquid: the first (builds the query grid) "
                "%.3f ms, the other %u %.3f ms in all (%.2f us each), %.1f particles each on "
                "average (one thread)\n",
                count, first, count - 1, rest, count > 1 ? 1000.0 * rest / double(count - 1) : 0.0,
                double(found) / double(count));
}

/// Times `count` ray casts of each kind and `count` samples (places from a fixed seed over the
/// particles' bounding box) on the world as the run left it, after one query that builds the
/// query grid; prints one line per kind.
void timeRays(const fluid::World& world, uint32_t count) {
    const auto px = world.positionX(), py = world.positionY();
    if (px.empty() || count == 0) {
        return;
    }
    const float x0 = *std::min_element(px.begin(), px.end());
    const float x1 = *std::max_element(px.begin(), px.end());
    const float y0 = *std::min_element(py.begin(), py.end());
    const float y1 = *std::max_element(py.begin(), py.end());
    std::mt19937 rng(54321);
    std::uniform_real_distribution<float> ux(x0, x1), uy(y0, y1);
    std::vector<glm::vec2> across, down, points;
    for (uint32_t k = 0; k < count; ++k) {
        across.push_back({ux(rng), uy(rng)});
        across.push_back({ux(rng), uy(rng)});
        const float x = ux(rng);
        down.push_back({x, y1 + 0.1f});
        down.push_back({x, y0});
        points.push_back({ux(rng), uy(rng)});
    }
    using Clock = std::chrono::steady_clock;
    fluid::surfaceField(world, points[0]); // builds the query grid
    const auto time = [&](const char* what, const std::vector<glm::vec2>& ends) {
        uint32_t hits = 0, inside = 0;
        double length = 0.0;
        const auto t0 = Clock::now();
        for (uint32_t k = 0; k < count; ++k) {
            const fluid::RayHit h = fluid::rayCast(world, ends[2 * k], ends[2 * k + 1]);
            hits += h.hit ? 1u : 0u;
            inside += h.startsInside ? 1u : 0u;
        }
        const double ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
        for (uint32_t k = 0; k < count; ++k) {
            const glm::vec2 d = ends[2 * k + 1] - ends[2 * k];
            length += std::sqrt(double(d.x) * d.x + double(d.y) * d.y);
        }
        std::printf("rays: %u %s (%.3f m long on average): %.3f ms in all (%.2f us each); %u hit "
                    "the liquid, %u of them from inside (one thread)\n",
                    count, what, length / count, ms, 1000.0 * ms / count, hits, inside);
    };
    time("random rays across the liquid's bounding box", across);
    time("rays straight down onto the liquid", down);
    // Each sample timed on its own, so that those in the liquid (which cast their depth up to
    // the surface) are told apart from those in the air.
    double wetMs = 0.0, dryMs = 0.0, depth = 0.0;
    uint32_t wet = 0;
    for (const glm::vec2 p : points) {
        const auto t0 = Clock::now();
        const fluid::LiquidSample here = fluid::sample(world, p);
        const double ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
        (here.inLiquid ? wetMs : dryMs) += ms;
        wet += here.inLiquid ? 1u : 0u;
        depth += here.depth;
    }
    std::printf("samples: %u at random points of the liquid's bounding box: %.3f ms in all; %u "
                "in the liquid %.2f us each (their depth cast up to the surface included, %.3f m "
                "on average), the other %u %.2f us each (one thread)\n",
                count, wetMs + dryMs, wet, wet > 0 ? 1000.0 * wetMs / wet : 0.0,
                wet > 0 ? depth / wet : 0.0, count - wet,
                count > wet ? 1000.0 * dryMs / (count - wet) : 0.0);
}

/// What interpolation adds to a frame (fluid::setInterpolation), timed alone because it is far
/// below the step's noise: the copy of the positions at the start of the frame's last sub-step
/// (2 channels), the sort's 2 extra channels in that sub-step (a gather through a random
/// permutation here: an upper bound, the sort's order is close to the identity), and a call of
/// fluid::interpolatedPositions (what drawing reads); each the least of 50 runs. One line.
void timeInterpolation(const fluid::World& world) {
    const auto px = world.positionX(), py = world.positionY();
    const size_t n = px.size();
    if (n == 0) {
        return;
    }
    std::vector<float> lx(n), ly(n), tx(n), ty(n);
    std::vector<uint32_t> order(n);
    for (size_t i = 0; i < n; ++i) {
        order[i] = uint32_t(i);
    }
    std::shuffle(order.begin(), order.end(), std::mt19937(7));
    using Clock = std::chrono::steady_clock;
    const auto least = [](auto&& body) {
        double best = 1e30;
        for (int run = 0; run < 50; ++run) {
            const auto t0 = Clock::now();
            body();
            best = std::min(best, std::chrono::duration<double, std::micro>(Clock::now() - t0)
                                      .count());
        }
        return best;
    };
    const double copy = least([&] {
        std::copy(px.begin(), px.end(), lx.begin());
        std::copy(py.begin(), py.end(), ly.begin());
    });
    const double gather = least([&] {
        for (size_t k = 0; k < n; ++k) {
            tx[k] = lx[order[k]];
        }
        for (size_t k = 0; k < n; ++k) {
            ty[k] = ly[order[k]];
        }
        lx.swap(tx);
        ly.swap(ty);
    });
    const double drawn = least([&] { fluid::interpolatedPositions(world, tx, ty); });
    std::printf("interpolation: %zu particles: capture %.1f us + the sort's 2 extra channels "
                "%.1f us (random order: an upper bound) per frame; interpolatedPositions "
                "%.1f us per call (least of 50, one thread)\n",
                n, copy, gather, drawn);
}

/// What a scene builder made.
struct Scene {
    /// One-line description for the setup line.
    std::string text;
    /// The water material.
    fluid::MaterialId water{};
    /// Width of the water block (unit: m; 0 for the blob).
    float blockWidth = 0.0f;
    /// Inner width and height of the container, floor at y = 0, left wall at x = 0 (unit: m;
    /// 0 for the blob).
    float boxWidth = 0.0f;
    /// See `boxWidth`.
    float boxHeight = 0.0f;
};

/// Spawns a block of `nx` columns by `ny` rows of `water` on its lattice (spacing `s`), lower
/// left corner at the origin; returns its width and height (unit: m).
std::pair<float, float> spawnBlock(fluid::World& world, fluid::MaterialId water, uint32_t nx,
                                   uint32_t ny) {
    const float s = world.spacing(water); // lattice spacing (m): one particle per s^2
    const float width = float(nx) * s, height = float(ny) * s;
    fluid::BlobDef block;
    block.shape.type = fluid::ShapeType::Rectangle;
    block.shape.center = {0.5f * width, 0.5f * height};
    // Half a spacing of slack so floor(extent / spacing) gives exactly nx by ny points.
    block.shape.halfExtents = {0.5f * (width + 0.5f * s), 0.5f * (height + 0.5f * s)};
    block.material = water;
    world.spawnBlob(block);
    return {width, height};
}

/// Fills `world` with the dam-break scene of about `n` particles of `liquid`.
Scene buildDam(fluid::World& world, uint32_t n, const fluid::Material& liquid) {
    const fluid::MaterialId water = world.addMaterial(liquid);
    // nx columns by 2 nx rows hold 2 nx^2 ~ n particles.
    const auto nx = std::max<uint32_t>(1, uint32_t(std::lround(std::sqrt(n / 2.0))));
    const uint32_t ny = 2 * nx;
    const auto [width, height] = spawnBlock(world, water, nx, ny);
    world.addForce(std::make_unique<fluid::GravityForce>(0.0f, -9.81f));
    world.addBoundary(
        std::make_unique<fluid::BoxContainer>(0.0f, 0.0f, 4.0f * width, 1.5f * height));
    char text[160];
    std::snprintf(text, sizeof text, "dam: %u x %u block (%.3f x %.3f m) in a %.3f x %.3f m box",
                  nx, ny, width, height, 4.0f * width, 1.5f * height);
    return {text, water, width, 4.0f * width, 1.5f * height};
}

/// Fills `world` with the resting tank of about `n` water particles: nx = round(sqrt(3 n / 5))
/// columns by ny = round(5 nx / 3) rows (nx ny ~ n), filling the width of a closed box 1.595
/// water heights tall (0.3008 x 0.8 m for 30 x 50).
Scene buildTank(fluid::World& world, uint32_t n, const fluid::Material& liquid) {
    const fluid::MaterialId water = world.addMaterial(liquid);
    const auto nx = std::max<uint32_t>(1, uint32_t(std::lround(std::sqrt(3.0 * n / 5.0))));
    const auto ny = std::max<uint32_t>(1, uint32_t(std::lround(5.0 * nx / 3.0)));
    const auto [width, height] = spawnBlock(world, water, nx, ny);
    const float boxHeight = 1.595f * height;
    world.addForce(std::make_unique<fluid::GravityForce>(0.0f, -9.81f));
    world.addBoundary(std::make_unique<fluid::BoxContainer>(0.0f, 0.0f, width, boxHeight));
    char text[160];
    std::snprintf(text, sizeof text,
                  "tank: %u x %u water (%.4f x %.4f m) resting in a %.4f x %.4f m box", nx, ny,
                  width, height, width, boxHeight);
    return {text, water, width, width, boxHeight};
}

/// Fills `world` with a zero-gravity round blob of about `n` particles of `liquid`.
Scene buildBlob(fluid::World& world, uint32_t n, const fluid::Material& liquid) {
    const fluid::MaterialId water = world.addMaterial(liquid);
    const float s = world.spacing(water);
    fluid::BlobDef blob;
    blob.shape.type = fluid::ShapeType::Circle;
    blob.shape.radius = s * float(std::sqrt(n / std::numbers::pi)); // area n s^2
    blob.material = water;
    world.spawnBlob(blob);
    char text[160];
    std::snprintf(text, sizeof text, "blob: radius %.3f m, zero gravity, no boundary",
                  blob.shape.radius);
    Scene scene;
    scene.text = text;
    scene.water = water;
    return scene;
}

#if FLUID_BENCH_BOX2D

/// Box2D collision category of the container walls: the coupling's mask leaves them out, so
/// the fluid sees only its own `boundary.box` and the crates (unit: bit mask).
constexpr uint16_t kWallCategory = 0x0002;
/// Box2D collision category of the crates, the only fixtures the coupling samples.
constexpr uint16_t kCrateCategory = 0x0001;
/// Number of crates in the crates scene (unit: count).
constexpr int kCrateCount = 20;

/// One crate of the crates scene, as created (the body is owned by the b2World).
struct Crate {
    /// The body.
    b2Body* body = nullptr;
    /// Fixture density over water's areal density (unit: 1; range [0.25, 2]).
    float ratio = 1.0f;
    /// True for a circle, false for a box.
    bool circle = false;
};

/// Adds the crates scene's bodies to `physics`: static walls around the container (outside
/// it, category `kWallCategory`) and 20 dynamic crates in two rows of ten in the dry right part
/// of the box, the lower row resting on the floor, the upper one dropped from one block width.
/// Crate sizes scale with the block (base size a tenth of its width, 0.089 m at 16k particles)
/// so every particle count sees the same scene. Every fourth crate is a circle; the boxes come
/// in three aspect ratios. Densities run from 0.25 to 2 times `fluid::box2d::arealDensity` of
/// water in 20 even steps, shuffled along the rows (k -> 7k mod 20) so floaters and sinkers
/// alternate.
std::vector<Crate> addCrates(b2World& physics, const Scene& scene, float waterArealDensity) {
    const float w = scene.blockWidth, bw = scene.boxWidth, bh = scene.boxHeight;
    // Walls: thick static boxes just outside the container, so that a crate never tunnels.
    b2BodyDef wallDef;
    b2Body* walls = physics.CreateBody(&wallDef);
    const float t = std::max(0.5f, 0.5f * bw); // wall thickness (m)
    const b2Vec2 halves[4] = {{0.5f * bw + t, 0.5f * t},
                              {0.5f * bw + t, 0.5f * t},
                              {0.5f * t, 0.5f * bh + t},
                              {0.5f * t, 0.5f * bh + t}};
    const b2Vec2 centres[4] = {{0.5f * bw, -0.5f * t},
                               {0.5f * bw, bh + 0.5f * t},
                               {-0.5f * t, 0.5f * bh},
                               {bw + 0.5f * t, 0.5f * bh}};
    for (int k = 0; k < 4; ++k) {
        b2PolygonShape box;
        box.SetAsBox(halves[k].x, halves[k].y, centres[k], 0.0f);
        b2FixtureDef fd;
        fd.shape = &box;
        fd.friction = 0.4f;
        fd.filter.categoryBits = kWallCategory;
        walls->CreateFixture(&fd);
    }

    const float c = 0.1f * w;            // base crate size (m)
    const float skin = b2_polygonRadius; // Box2D keeps polygons this far apart (m)
    std::vector<Crate> crates;
    for (int k = 0; k < kCrateCount; ++k) {
        const int row = k / 10, col = k % 10;
        Crate crate;
        crate.ratio = 0.25f + 1.75f * float((7 * k) % kCrateCount) / float(kCrateCount - 1);
        crate.circle = k % 4 == 3;
        const int aspect = k % 3;
        const float hx = crate.circle ? 0.5f * c
                                      : (aspect == 1   ? 0.65f
                                         : aspect == 2 ? 0.4f
                                                       : 0.5f) *
                                            c;
        const float hy = crate.circle ? 0.5f * c
                                      : (aspect == 1   ? 0.4f
                                         : aspect == 2 ? 0.65f
                                                       : 0.5f) *
                                            c;
        b2BodyDef bd;
        bd.type = b2_dynamicBody;
        bd.position.Set(1.3f * w + float(col) * 0.27f * w, row == 0 ? hy + 2.0f * skin : w + hy);
        crate.body = physics.CreateBody(&bd);
        b2PolygonShape box;
        b2CircleShape disc;
        b2FixtureDef fd;
        if (crate.circle) {
            disc.m_radius = hx;
            fd.shape = &disc;
        } else {
            box.SetAsBox(hx, hy);
            fd.shape = &box;
        }
        fd.density = crate.ratio * waterArealDensity;
        fd.friction = 0.4f;
        fd.filter.categoryBits = kCrateCategory;
        crate.body->CreateFixture(&fd);
        crates.push_back(crate);
    }
    return crates;
}

/// Lowest and highest y of a body's fixtures' core shapes (unit: m; polygon skin left out,
/// as the fluid sees the crate).
std::pair<float, float> verticalExtent(const b2Body& body) {
    float lo = 1e30f, hi = -1e30f;
    const b2Transform& xf = body.GetTransform();
    for (const b2Fixture* f = body.GetFixtureList(); f != nullptr; f = f->GetNext()) {
        if (f->GetType() == b2Shape::e_circle) {
            const auto* disc = static_cast<const b2CircleShape*>(f->GetShape());
            const float y = b2Mul(xf, disc->m_p).y;
            lo = std::min(lo, y - disc->m_radius);
            hi = std::max(hi, y + disc->m_radius);
        } else if (f->GetType() == b2Shape::e_polygon) {
            const auto* poly = static_cast<const b2PolygonShape*>(f->GetShape());
            for (int32 i = 0; i < poly->m_count; ++i) {
                const float y = b2Mul(xf, poly->m_vertices[i]).y;
                lo = std::min(lo, y);
                hi = std::max(hi, y);
            }
        }
    }
    return {lo, hi};
}

/// Water surface next to a body (unit: m): half a spacing above the highest particle in the
/// strips three spacings wide either side of its AABB (a particle stands for an s x s cell, so
/// the free surface lies half a cell above the top centres), averaged over the strips that hold
/// water; -1 if neither does.
float surfaceBeside(const fluid::World& world, float s, const b2AABB& box) {
    const auto px = world.positionX();
    const auto py = world.positionY();
    float left = -1.0f, right = -1.0f;
    for (uint32_t i = 0; i < world.particleCount(); ++i) {
        if (px[i] < box.lowerBound.x && px[i] >= box.lowerBound.x - 3.0f * s) {
            left = std::max(left, py[i]);
        } else if (px[i] > box.upperBound.x && px[i] <= box.upperBound.x + 3.0f * s) {
            right = std::max(right, py[i]);
        }
    }
    if (left < 0.0f && right < 0.0f) {
        return -1.0f;
    }
    const float top = left < 0.0f ? right : right < 0.0f ? left : 0.5f * (left + right);
    return top + 0.5f * s;
}

/// Share of a body's area below height `level` (unit: 1), sampled on a 32 x 32 grid over its
/// AABB with `b2Fixture::TestPoint`: the geometric check of `BodyReport::submergedFraction`.
float areaBelow(const b2Body& body, const b2AABB& box, float level) {
    uint32_t inside = 0, below = 0;
    for (int i = 0; i < 32; ++i) {
        for (int j = 0; j < 32; ++j) {
            const b2Vec2 q{box.lowerBound.x +
                               (float(i) + 0.5f) / 32.0f * (box.upperBound.x - box.lowerBound.x),
                           box.lowerBound.y +
                               (float(j) + 0.5f) / 32.0f * (box.upperBound.y - box.lowerBound.y)};
            for (const b2Fixture* f = body.GetFixtureList(); f != nullptr; f = f->GetNext()) {
                if (f->TestPoint(q)) {
                    ++inside;
                    below += q.y < level ? 1 : 0;
                    break;
                }
            }
        }
    }
    return inside > 0 ? float(below) / float(inside) : 0.0f;
}

/// Prints every crate's final pose against the water (once, after the timed frames): its
/// density ratio, centre, bottom and top, the water surface beside it, the share of its area
/// below that surface, the submerged fraction the coupling reports, and whether it floats (top
/// above the surface, bottom off the floor), sits on the floor or hangs below the surface.
/// A settled floater has both fractions close to its density ratio.
void printCrates(const fluid::World& world, const Scene& scene, const std::vector<Crate>& crates,
                 const fluid::box2d::Coupling* coupling) {
    const float s = world.spacing(scene.water);
    float submerged = 0.0f;
    if (coupling != nullptr) {
        for (const fluid::box2d::BodyReport& r : coupling->bodies()) {
            submerged += r.submergedArea;
        }
    }
    // Settled level: the water's rest area plus the area crates displace, over the box width.
    const float level = (float(world.particleCount()) * s * s + submerged) / scene.boxWidth;
    std::printf("crates after %.2f s (%s); settled water level %.3f m (N s^2 + submerged crate "
                "area over the box width):\n",
                world.time(), coupling != nullptr ? "coupled" : "not coupled", double(level));
    std::printf("  crate shape  density  x (m)   y (m)   bottom  top     surface  below  "
                "reported  state\n");
    for (size_t k = 0; k < crates.size(); ++k) {
        const b2Body& body = *crates[k].body;
        const b2Vec2 p = body.GetPosition();
        const auto [lo, hi] = verticalExtent(body);
        b2AABB box; // of the crate's one fixture, skin included
        body.GetFixtureList()->GetShape()->ComputeAABB(&box, body.GetTransform(), 0);
        const float surface = surfaceBeside(world, s, box);
        const fluid::box2d::BodyReport* r = coupling != nullptr ? coupling->report(&body) : nullptr;
        // Resting on the floor leaves Box2D's skin (b2_polygonRadius per polygon) as a gap.
        const char* state = lo < 2.0f * b2_polygonRadius + 0.5f * s ? "on the floor"
                            : surface < 0.0f                        ? "dry, off the floor"
                            : hi > surface                          ? "floating"
                                                                    : "below the surface";
        char fraction[16] = "-";
        if (r != nullptr) {
            std::snprintf(fraction, sizeof fraction, "%.2f", double(r->submergedFraction));
        }
        std::printf("  %5zu %-6s %5.2fx  %6.3f  %6.3f  %6.3f  %6.3f  %7.3f  %5.2f  %8s  %s\n", k,
                    crates[k].circle ? "circle" : "box", double(crates[k].ratio), double(p.x),
                    double(p.y), double(lo), double(hi), double(surface),
                    double(areaBelow(body, box, surface)), fraction, state);
    }
}

#endif // FLUID_BENCH_BOX2D

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const size_t m = v.size() / 2;
    return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

/// The q-quantile (q in [0, 1]) of `v`, nearest rank.
double quantile(std::vector<double> v, double q) {
    std::sort(v.begin(), v.end());
    const auto rank = size_t(std::ceil(q * double(v.size())));
    return v[std::min(v.size() - 1, rank > 0 ? rank - 1 : 0)];
}

using fluid::bench::Compression;
using fluid::bench::CompressionMeter;
using fluid::bench::kCompressionSupport;
using fluid::bench::stackedIndices;
using fluid::bench::surfaceLevel;

int run(const Options& opt) {
    fluid::WorldDef def;
    def.workerCount = opt.threads;
    def.solver = opt.solver == "explicit" ? fluid::Solver::Explicit : fluid::Solver::PositionBased;
    def.positionBased = fluid::positionBasedPreset(
        fluid::qualityFromName(opt.quality).value_or(fluid::Quality::Game));
    if (opt.substeps > 0) {
        def.positionBased.substeps = opt.substeps;
    }
    if (opt.iterations > 0) {
        def.positionBased.iterations = opt.iterations;
    }
    if (opt.viscosityInterval > 0) {
        def.positionBased.viscosityInterval = opt.viscosityInterval;
    }
    if (opt.coarse >= 0.0f) {
        def.positionBased.coarseCorrection = opt.coarse;
    }
    if (opt.shearConstraint >= 0) {
        def.positionBased.shearConstraint = uint32_t(opt.shearConstraint);
    }
    def.equationOfState =
        fluid::equationOfStateFromName(opt.eos).value_or(fluid::EquationOfState::Tait);
    fluid::World world(def);
    const fluid::Material liquid = opt.material == "yoghurt"        ? fluid::yoghurt()
                                   : opt.material == "seed_yoghurt" ? fluid::seedYoghurt()
                                                                    : fluid::water();
    const Scene scene = opt.scene == "blob"   ? buildBlob(world, opt.particles, liquid)
                        : opt.scene == "tank" ? buildTank(world, opt.particles, liquid)
                                              : buildDam(world, opt.particles, liquid);
    std::string what = scene.text;
    what += opt.material == "water" ? "" : ", " + opt.material;
    if (opt.interpolate) {
        fluid::setInterpolation(world, true);
        what += ", interpolation on";
    }

    // One frame of the scene: World::step alone, or (crates) the coupled frame or the uncoupled
    // reference. Declared in this order so the coupling goes before the b2World, and the
    // b2World before the world (the coupling's lifetime rule).
    const float frameDt = 1.0f / 60.0f;
    std::function<void()> frame = [&] { world.step(frameDt); };
    // The frame's profile: World::step's, or the coupling's sum over its rounds.
    std::function<const fluid::Profile&()> profile = [&]() -> const fluid::Profile& {
        return world.profile();
    };
#if FLUID_BENCH_BOX2D
    std::unique_ptr<b2World> physics;
    std::unique_ptr<fluid::box2d::Coupling> coupling;
    std::vector<Crate> crates;
    std::size_t contactsRead = 0; // --contacts: particles the events listed, so none is unused
    if (opt.scene == "crates") {
        physics = std::make_unique<b2World>(b2Vec2(0.0f, -9.81f)); // the fluid's gravity
        crates = addCrates(*physics, scene, fluid::box2d::arealDensity(world, scene.water));
        fluid::box2d::CouplingDef cdef;
        cdef.categoryMask = kCrateCategory; // walls are the fluid's boundary.box already
        if (opt.noCoupling) {
            // Same fluid, same Box2D work (bodies, iterations), but the fluid never sees the
            // crates: the difference to the coupled run is the coupling's cost.
            frame = [&, cdef] {
                world.step(frameDt);
                physics->Step(frameDt, cdef.velocityIterations, cdef.positionIterations);
            };
        } else {
            // The bodies are solids: the dam's boundary.box, a container, projects after them.
            coupling = std::make_unique<fluid::box2d::Coupling>(world, *physics, cdef);
            frame = [&] { coupling->step(world, frameDt); };
            if (opt.contacts) {
                for (const Crate& crate : crates) {
                    coupling->setContactEvents(crate.body, true);
                }
                // Read as a game would: every event and its particles, each frame.
                frame = [&] {
                    coupling->step(world, frameDt);
                    for (uint32_t k = 0; k < coupling->particleContacts().size(); ++k) {
                        contactsRead += coupling->contactParticles(k).size();
                    }
                };
            }
            profile = [&]() -> const fluid::Profile& { return coupling->profile(); };
        }
        what += ", 20 Box2D crates (0.25x-2x water's areal density), ";
        what += opt.noCoupling ? "not coupled" : "coupled";
        what += opt.contacts && !opt.noCoupling ? ", contact events on" : "";
    }
#endif

    const uint32_t n = world.particleCount();
    const bool tank = opt.scene == "tank";
    const double spacing = world.spacing(scene.water); // lattice spacing (m)
    CompressionMeter meter(spacing);
    std::vector<double> scratch;
    // The start (frame 0): compression on the lattice (~0), the tank's level and highest
    // particle.
    const Compression start = meter.measure(world.positionX(), world.positionY());
    const double surface0 = surfaceLevel(world.positionY(), spacing, scratch);
    const float top0 =
        n > 0 ? *std::max_element(world.positionY().begin(), world.positionY().end()) : 0.0f;
    std::fprintf(stderr,
                 "fluid-bench: %s; %u particles, threads=%u, solver=%s, quality=%s (%u x %u), "
                 "eos=%s, %u warm-up + %u timed frames, compression window frames %u-%u\n",
                 what.c_str(), n, opt.threads, opt.solver.c_str(), opt.quality.c_str(),
                 world.def().positionBased.substeps, world.def().positionBased.iterations,
                 opt.eos.c_str(), opt.warmup, opt.frames, opt.windowFirst, opt.windowLast);
    std::fprintf(stderr, "  frame 0: compression mean %.2f%%, max %.2f%% (positions)\n",
                 100.0 * start.mean, 100.0 * start.max);

    std::vector<double> frameMs;
    frameMs.reserve(opt.frames);
    // Stage sums over the timed frames, in the profile's order (unit: ms), and the whole step's.
    std::vector<std::pair<std::string, double>> stages;
    double stepMs = 0.0;
    uint64_t substeps = 0;
    float worstError = 0.0f;
    const uint32_t report = std::max<uint32_t>(1, opt.frames / 5);
    // Process CPU time (all threads; the pool's idle workers block, they do not spin) of the
    // timed frames' frame() calls, summed (unit: clock ticks): the work a frame costs, much
    // less sensitive than wall time to other processes on a busy machine.
    std::clock_t cpuTicks = 0;
    // The bench's compression after the last frame, and over the window: the sum of the
    // frames' means (unit: 1) and the largest max (unit: 1).
    Compression last = start;
    double windowMeanSum = 0.0, windowMax = 0.0;
    // Tank: the most particles above top0 + h in any frame (unit: count), and the surface change
    // over the last second of frames (the tank sloshes: one frame's reading moves by about half
    // a percent from frame to frame), summed with its extremes (unit: 1).
    uint32_t thrown = 0;
    const uint32_t lastSecond = 60;
    double lastSurfaceSum = 0.0, lastSurfaceLow = 0.0, lastSurfaceHigh = 0.0;
    uint32_t lastSurfaceFrames = 0;
    const uint32_t total = opt.warmup + opt.frames; // simulated frames (unit: count)
    for (uint32_t f = 1; f <= total; ++f) {
        if (f <= opt.warmup) {
            frame();
        } else {
            const std::clock_t c0 = std::clock();
            const auto t0 = std::chrono::steady_clock::now();
            frame();
            const auto t1 = std::chrono::steady_clock::now();
            cpuTicks += std::clock() - c0;
            frameMs.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
            const fluid::Profile& p = profile();
            for (const fluid::StageTime& t : p.stageTimes()) {
                auto it = std::find_if(stages.begin(), stages.end(),
                                       [&](const auto& e) { return e.first == t.name; });
                if (it == stages.end()) {
                    it = stages.emplace(stages.end(), t.name, 0.0);
                }
                it->second += t.ms;
            }
            stepMs += p.step;
            substeps += p.substeps;
            worstError = std::max(worstError, p.densityErrorMax);
        }
        // Not timed: the bench's own measurements.
        const auto px = world.positionX();
        const auto py = world.positionY();
        last = meter.measure(px, py);
        if (f >= opt.windowFirst && f <= opt.windowLast) {
            windowMeanSum += last.mean;
            windowMax = std::max(windowMax, last.max);
        }
        if (tank) {
            const auto above = std::count_if(py.begin(), py.end(), [&](float y) {
                return double(y) > double(top0) + kCompressionSupport;
            });
            thrown = std::max(thrown, uint32_t(above));
            if (f + lastSecond > total) {
                const double change = surfaceLevel(py, spacing, scratch) / surface0 - 1.0;
                lastSurfaceLow = lastSurfaceFrames == 0 ? change : std::min(lastSurfaceLow, change);
                lastSurfaceHigh =
                    lastSurfaceFrames == 0 ? change : std::max(lastSurfaceHigh, change);
                lastSurfaceSum += change;
                ++lastSurfaceFrames;
            }
        }
        const uint32_t timed = f > opt.warmup ? f - opt.warmup : 0;
        if (timed > 0 && (timed % report == 0 || timed == opt.frames)) {
            const fluid::Profile& p = profile();
            std::fprintf(stderr,
                         "  frame %u/%u: %.1f ms, %u sub-steps, max compression %.2f%% (solver); "
                         "positions: mean %.2f%%, max %.2f%%\n",
                         timed, opt.frames, frameMs.back(), p.substeps, 100.0 * p.densityErrorMax,
                         100.0 * last.mean, 100.0 * last.max);
        }
    }

    const double frames = opt.frames;
    const double cpuMs = 1e3 * double(cpuTicks) / double(CLOCKS_PER_SEC) / frames;
    const double s = double(substeps) / frames;
    const double m = median(frameMs);
    const double mean = std::accumulate(frameMs.begin(), frameMs.end(), 0.0) / frames;
    const double p = m * 1e6 / (double(n) * s);
    std::printf("scene=%s solver=%s eos=%s sound_speed=%.2f m/s isa=%s\n", opt.scene.c_str(),
                opt.solver.c_str(), opt.eos.c_str(), double(world.profile().soundSpeed),
                fluid::instructionSet());
    std::printf("stages (ms per frame, mean over timed frames):\n");
    for (const auto& [name, ms] : stages) {
        std::printf("  %-15s %10.3f\n", name.c_str(), ms / frames);
    }
    std::printf("  %-15s %10.3f\n", "step (total)", stepMs / frames);
    // For the crates scene: Box2D's step, and with coupling the coupling's own work around
    // World::step (sampling bodies, applying forces, reports).
    std::printf("  %-15s %10.3f\n", "outside step", mean - stepMs / frames);
    std::printf("frame wall time (ms): median %.3f, mean %.3f, p90 %.3f, min %.3f, max %.3f; "
                "CPU time (all threads) %.3f ms per frame\n",
                m, mean, quantile(frameMs, 0.9), *std::min_element(frameMs.begin(), frameMs.end()),
                *std::max_element(frameMs.begin(), frameMs.end()), cpuMs);
#if FLUID_BENCH_BOX2D
    if (opt.scene == "crates") {
        printCrates(world, scene, crates, coupling.get());
        if (opt.contacts && coupling) {
            std::printf("contact events: %zu particle contacts listed over the run (warm-up included), "
                        "%zu crates touching at the end\n",
                        contactsRead, coupling->particleContacts().size());
        }
    }
#endif
    const double windowMean = windowMeanSum / double(opt.windowLast - opt.windowFirst + 1);
    std::printf("compression: mean %.2f%%, p99 %.2f%%, max %.2f%% (after frame %u, from positions: "
                "Wendland C2 sum over h = %.3f m against the lattice's)\n",
                100.0 * last.mean, 100.0 * last.p99, 100.0 * last.max, total, kCompressionSupport);
    std::printf("compression over frames %u-%u: mean of the frames' means %.2f%%, largest %.2f%%\n",
                opt.windowFirst, opt.windowLast, 100.0 * windowMean, 100.0 * windowMax);
    // Tank: level, splashes and kinetic energy at the end.
    double surfaceChange = 0.0, kePerKg = 0.0;
    if (tank) {
        const double surface = surfaceLevel(world.positionY(), spacing, scratch);
        surfaceChange = surface / surface0 - 1.0;
        const auto vx = world.velocityX();
        const auto vy = world.velocityY();
        double ke = 0.0;
        for (size_t i = 0; i < vx.size(); ++i) {
            ke += 0.5 * (double(vx[i]) * double(vx[i]) + double(vy[i]) * double(vy[i]));
        }
        kePerKg = vx.empty() ? 0.0 : ke / double(vx.size());
        std::printf("surface: %.4f m at the start, %.4f m now (%+.2f%%; 95th percentile of y + "
                    "s/2); thrown: at most %u particles above the start's top + h; kinetic "
                    "energy %.3g J/kg\n",
                    surface0, surface, 100.0 * surfaceChange, thrown, kePerKg);
        std::printf("surface over the last %u frames: mean %+.2f%%, from %+.2f%% to %+.2f%%\n",
                    lastSurfaceFrames, 100.0 * lastSurfaceSum / double(lastSurfaceFrames),
                    100.0 * lastSurfaceLow, 100.0 * lastSurfaceHigh);
    }
    if (opt.queries > 0) {
        timeQueries(world, opt.queries);
    }
    if (opt.rays > 0) {
        timeRays(world, opt.rays);
    }
    if (opt.interpolate) {
        timeInterpolation(world);
    }
    const auto stacked = uint32_t(stackedIndices(world.positionX(), world.positionY()).size());
    std::printf("stacked: %u particles share their exact position with another\n", stacked);
    char window[32];
    std::snprintf(window, sizeof window, "%u:%u", opt.windowFirst, opt.windowLast);
    std::printf("solver=%s particles=%u frames=%u threads=%u substeps_per_frame=%.2f iterations=%u "
                "density_error_max=%.4f ms_per_frame=%.3f ns_per_particle_substep=%.1f "
                "ms_per_frame_mean=%.3f ms_per_frame_p90=%.3f cpu_ms_per_frame=%.3f quality=%s "
                "compression_mean=%.4f compression_p99=%.4f compression_max=%.4f window=%s "
                "window_compression_mean=%.4f window_compression_max=%.4f",
                opt.solver.c_str(), n, opt.frames, opt.threads, s, world.profile().iterations,
                double(worstError), m, p, mean, quantile(frameMs, 0.9), cpuMs, opt.quality.c_str(),
                last.mean, last.p99, last.max, window, windowMean, windowMax);
    std::printf(" stacked=%u", stacked);
    if (tank) {
        std::printf(" surface_change=%.4f thrown=%u ke_per_kg=%.4g surface_change_last_second=%.4f",
                    surfaceChange, thrown, kePerKg,
                    lastSurfaceSum / double(std::max(lastSurfaceFrames, 1u)));
    }
    std::printf("\n");
    return 0;
}

/// Parses "A:B" (two unsigned decimal numbers) into `first` and `last`; false if malformed.
bool parseWindow(const std::string& text, uint32_t& first, uint32_t& last) {
    const char* begin = text.data();
    const char* end = begin + text.size();
    const auto a = std::from_chars(begin, end, first);
    if (a.ec != std::errc() || a.ptr == begin || a.ptr == end || *a.ptr != ':') {
        return false;
    }
    const auto b = std::from_chars(a.ptr + 1, end, last);
    return b.ec == std::errc() && b.ptr != a.ptr + 1 && b.ptr == end;
}

} // namespace

int main(int argc, char** argv) {
    Options opt;
    CLI::App app{"fluid-bench: times fluid::World::step on a standard scene"};
    app.add_option("--scene", opt.scene,
                   "Scene: dam (dam break in a box), blob (zero-g blob), crates (the dam with "
                   "20 Box2D crates) or tank (resting water tank)");
    app.add_option("--particles", opt.particles,
                   "About this many particles (default 16000, the tank 1500)")
        ->check(CLI::Range(1u, 1u << 26));
    app.add_option("--frames", opt.frames,
                   "Timed frames of 1/60 s (default 600; the tank 300 simulated frames, 5 s, "
                   "warm-up included)")
        ->check(CLI::Range(1u, 1u << 30));
    app.add_option("--warmup", opt.warmup, "Untimed frames before timing")
        ->check(CLI::Range(0u, 1u << 30));
    app.add_option("--threads", opt.threads, "Worker threads (WorldDef::workerCount)")
        ->check(CLI::Range(1u, 256u));
    app.add_option("--solver", opt.solver, "Solver: position-based (the default) or explicit");
    app.add_option("--quality", opt.quality,
                   "Position-based preset the solver settings start from: game (the default) "
                   "or precise; --substeps and --iterations override it");
    app.add_option("--substeps", opt.substeps,
                   "Position-based sub-steps per frame (0: the preset's)")
        ->check(CLI::Range(0u, 64u));
    app.add_option("--viscosity-interval", opt.viscosityInterval,
                   "Position-based sub-steps between viscosity and surface tension runs (0: the "
                   "preset's)")
        ->check(CLI::Range(0u, 64u));
    app.add_option("--coarse", opt.coarse,
                   "Position-based coarse-grid correction share, 0 to 1 (default: the preset's)")
        ->check(CLI::Range(0.0f, 1.0f));
    app.add_option("--shear-constraint", opt.shearConstraint,
                   "Yield-stress materials: 1 steps them with the shear constraint, 0 with the "
                   "stress pass (default: the preset's)")
        ->check(CLI::Range(0, 1));
    app.add_option("--iterations", opt.iterations,
                   "Position-based constraint iterations per sub-step (0: the preset's)")
        ->check(CLI::Range(0u, 100u));
    app.add_option("--material", opt.material,
                   "The scene's liquid: water (the default), yoghurt (fluid::yoghurt()) or "
                   "seed_yoghurt (fluid::seedYoghurt(), Table 4.1's Newtonian yoghurt)");
    app.add_option("--eos", opt.eos, "Equation of state of the explicit solver: tait or linear");
    app.add_option("--queries", opt.queries,
                   "Time this many region queries (10 cm boxes) after the run (0: none)");
    app.add_option("--rays", opt.rays,
                   "Time this many ray casts (random, and straight down) and samples after the "
                   "run (0: none)");
    app.add_flag("--interpolate", opt.interpolate,
                 "Keep the previous sub-step's positions for drawing between steps "
                 "(fluid::setInterpolation)");
    app.add_flag("--no-coupling", opt.noCoupling,
                 "Crates scene: step the Box2D crates without coupling them to the fluid");
    app.add_flag("--contacts", opt.contacts,
                 "Crates scene: every crate asks for contact events, read after each frame");
    app.add_option("--window", opt.window,
                   "A:B: frames (1-based, counted from the first simulated frame, warm-up "
                   "included) the window_compression fields cover (default: the timed frames)");
    if (const int status = fluid::tools::parseCommandLine(app, argc, argv); status >= 0) {
        return status;
    }
    if (opt.scene != "dam" && opt.scene != "blob" && opt.scene != "crates" && opt.scene != "tank") {
        std::fprintf(stderr,
                     "fluid-bench: unknown scene '%s' (expected dam, blob, crates or tank)\n",
                     opt.scene.c_str());
        return 2;
    }
#if !FLUID_BENCH_BOX2D
    if (opt.scene == "crates") {
        std::fprintf(stderr, "fluid-bench: scene 'crates' needs fluid::box2d (configure with "
                             "FLUID_BUILD_BOX2D=ON)\n");
        return 2;
    }
#endif
    if (opt.noCoupling && opt.scene != "crates") {
        std::fprintf(stderr,
                     "fluid-bench: --no-coupling applies to --scene crates only (got "
                     "scene '%s')\n",
                     opt.scene.c_str());
        return 2;
    }
    if (opt.solver != "position-based" && opt.solver != "explicit") {
        std::fprintf(stderr,
                     "fluid-bench: unknown solver '%s' (expected position-based or explicit)\n",
                     opt.solver.c_str());
        return 2;
    }
    if (!fluid::qualityFromName(opt.quality)) {
        std::fprintf(stderr, "fluid-bench: unknown quality '%s' (expected %s)\n",
                     opt.quality.c_str(), fluid::namesIn(fluid::kQualityNames).c_str());
        return 2;
    }
    if (opt.material != "water" && opt.material != "yoghurt" && opt.material != "seed_yoghurt") {
        std::fprintf(stderr,
                     "fluid-bench: unknown material '%s' (expected water, yoghurt or "
                     "seed_yoghurt)\n",
                     opt.material.c_str());
        return 2;
    }
    if (!fluid::equationOfStateFromName(opt.eos)) {
        std::fprintf(stderr, "fluid-bench: unknown equation of state '%s' (expected %s)\n",
                     opt.eos.c_str(), fluid::namesIn(fluid::kEquationOfStateNames).c_str());
        return 2;
    }
    // Scene defaults: the tank runs 1500 particles for 300 simulated frames (5 s) in all.
    const bool tank = opt.scene == "tank";
    if (opt.particles == 0) {
        opt.particles = tank ? 1500 : 16000;
    }
    if (opt.frames == 0) {
        opt.frames = !tank ? 600 : opt.warmup < 300 ? 300 - opt.warmup : 1;
    }
    const uint32_t total = opt.warmup + opt.frames; // simulated frames
    opt.windowFirst = opt.warmup + 1;
    opt.windowLast = total;
    if (!opt.window.empty() &&
        (!parseWindow(opt.window, opt.windowFirst, opt.windowLast) || opt.windowFirst < 1 ||
         opt.windowFirst > opt.windowLast || opt.windowLast > total)) {
        std::fprintf(stderr,
                     "fluid-bench: bad window '%s' (expected A:B with 1 <= A <= B <= %u, the "
                     "simulated frames: %u warm-up + %u timed)\n",
                     opt.window.c_str(), total, opt.warmup, opt.frames);
        return 2;
    }
    try {
        return run(opt);
    } catch (const fluid::Error& e) {
        std::fprintf(stderr, "fluid-bench: fluid::Error: %s\n", e.what());
        return 1;
    }
}
