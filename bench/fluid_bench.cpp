// fluid-bench: times World::step on a standard scene and prints one summary line.
//
//   fluid-bench --scene dam --particles 16000 --frames 600 --threads 2 [--warmup N]
//               [--solver position-based|explicit] [--substeps S] [--iterations I]
//               [--eos tait|linear] [--no-coupling]
//
// Scenes (see bench/README.md):
//   dam     a water block (width:height 1:2) standing in the left of a closed box four block
//           widths wide and 1.5 block heights tall, floor at y = 0, gravity (0, -9.81) m/s^2.
//   blob    a round water blob in zero gravity, no boundary, no force plugin.
//   crates  the dam with 20 Box2D crates (boxes and circles, 0.25 to 2 times water's areal
//           density) in its path, coupled by fluid::box2d::Coupling::step; with --no-coupling
//           the same bodies are stepped by Box2D but the fluid does not see them.
// Every frame is 1/60 s. The last stdout line is machine-readable:
//   solver=NAME particles=N frames=F threads=T substeps_per_frame=S iterations=I
//   density_error_max=E ms_per_frame=M ns_per_particle_substep=P ms_per_frame_mean=A
//   ms_per_frame_p90=Q cpu_ms_per_frame=C
#include <fluid/fluid.h>

#if FLUID_BENCH_BOX2D
#include <box2d/box2d.h>
#include <fluid/box2d/coupling.h>
#endif

#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <ctime>
#include <functional>
#include <memory>
#include <numbers>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

namespace {

/// Command-line options (see the usage above).
struct Options {
    /// "dam", "blob" or "crates".
    std::string scene = "dam";
    /// Wanted particle count (unit: count); the lattice gives about this many.
    uint32_t particles = 16000;
    /// Timed frames (unit: count).
    uint32_t frames = 600;
    /// Frames stepped before timing starts (unit: count).
    uint32_t warmup = 2;
    /// WorldDef::workerCount (unit: count).
    uint32_t threads = 1;
    /// "position-based" or "explicit".
    std::string solver = "position-based";
    /// PositionBasedDef::substeps (unit: count; 0 keeps the default).
    uint32_t substeps = 0;
    /// PositionBasedDef::iterations (unit: count; 0 keeps the default).
    uint32_t iterations = 0;
    /// "tait" or "linear" (explicit solver).
    std::string eos = "tait";
    /// Crates scene: step Box2D next to the fluid without coupling them (the reference run).
    bool noCoupling = false;
};

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

/// Fills `world` with the dam-break scene of about `n` water particles.
Scene buildDam(fluid::World& world, uint32_t n) {
    const fluid::MaterialId water = world.addMaterial(fluid::water());
    const float s = world.spacing(water); // lattice spacing (m): one particle per s^2
    // nx columns by 2 nx rows hold 2 nx^2 ~ n particles.
    const auto nx = std::max<uint32_t>(1, uint32_t(std::lround(std::sqrt(n / 2.0))));
    const uint32_t ny = 2 * nx;
    const float width = float(nx) * s, height = float(ny) * s;
    fluid::BlobDef block;
    block.shape = fluid::BlobShape::Rectangle;
    block.center = {0.5f * width, 0.5f * height};
    // Half a spacing of slack so floor(extent / spacing) gives exactly nx by ny points.
    block.halfExtents = {0.5f * (width + 0.5f * s), 0.5f * (height + 0.5f * s)};
    block.material = water;
    world.spawnBlob(block);
    world.addForce(std::make_unique<fluid::GravityForce>(0.0f, -9.81f));
    world.addBoundary(
        std::make_unique<fluid::BoxContainer>(0.0f, 0.0f, 4.0f * width, 1.5f * height));
    char text[160];
    std::snprintf(text, sizeof text, "dam: %u x %u block (%.3f x %.3f m) in a %.3f x %.3f m box",
                  nx, ny, width, height, 4.0f * width, 1.5f * height);
    return {text, water, width, 4.0f * width, 1.5f * height};
}

/// Fills `world` with a zero-gravity round blob of about `n` water particles.
Scene buildBlob(fluid::World& world, uint32_t n) {
    const fluid::MaterialId water = world.addMaterial(fluid::water());
    const float s = world.spacing(water);
    fluid::BlobDef blob;
    blob.shape = fluid::BlobShape::Circle;
    blob.radius = s * float(std::sqrt(n / std::numbers::pi)); // area n s^2
    blob.material = water;
    world.spawnBlob(blob);
    char text[160];
    std::snprintf(text, sizeof text, "blob: radius %.3f m, zero gravity, no boundary", blob.radius);
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

int run(const Options& opt) {
    fluid::WorldDef def;
    def.workerCount = opt.threads;
    def.solver = opt.solver == "explicit" ? fluid::Solver::Explicit : fluid::Solver::PositionBased;
    if (opt.substeps > 0) {
        def.positionBased.substeps = opt.substeps;
    }
    if (opt.iterations > 0) {
        def.positionBased.iterations = opt.iterations;
    }
    def.equationOfState =
        opt.eos == "linear" ? fluid::EquationOfState::Linear : fluid::EquationOfState::Tait;
    fluid::World world(def);
    const Scene scene =
        opt.scene == "blob" ? buildBlob(world, opt.particles) : buildDam(world, opt.particles);
    std::string what = scene.text;

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
            // After the dam's boundary.box: the container has the last word (see Coupling).
            coupling = std::make_unique<fluid::box2d::Coupling>(world, *physics, cdef);
            frame = [&] { coupling->step(world, frameDt); };
            profile = [&]() -> const fluid::Profile& { return coupling->profile(); };
        }
        what += ", 20 Box2D crates (0.25x-2x water's areal density), ";
        what += opt.noCoupling ? "not coupled" : "coupled";
    }
#endif

    const uint32_t n = world.particleCount();
    std::fprintf(stderr,
                 "fluid-bench: %s; %u particles, threads=%u, solver=%s, eos=%s, %u warm-up + %u "
                 "timed frames\n",
                 what.c_str(), n, opt.threads, opt.solver.c_str(), opt.eos.c_str(), opt.warmup,
                 opt.frames);

    for (uint32_t f = 0; f < opt.warmup; ++f) {
        frame();
    }
    std::vector<double> frameMs;
    frameMs.reserve(opt.frames);
    // Stage sums over the timed frames (unit: ms): sort, external, density, pressure, forces,
    // integrate, boundaries, whole step.
    double stage[8] = {};
    uint64_t substeps = 0;
    float worstError = 0.0f;
    const uint32_t report = std::max<uint32_t>(1, opt.frames / 5);
    // Process CPU time (all threads; the pool's idle workers block, they do not spin) over the
    // timed frames: the work a frame costs, much less sensitive than wall time to other
    // processes on a busy machine.
    const std::clock_t cpu0 = std::clock();
    for (uint32_t f = 0; f < opt.frames; ++f) {
        const auto t0 = std::chrono::steady_clock::now();
        frame();
        const auto t1 = std::chrono::steady_clock::now();
        frameMs.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
        const fluid::Profile& p = profile();
        const float parts[8] = {p.sort,   p.external,  p.density,    p.pressure,
                                p.forces, p.integrate, p.boundaries, p.step};
        for (int k = 0; k < 8; ++k) {
            stage[k] += parts[k];
        }
        substeps += p.substeps;
        worstError = std::max(worstError, p.densityErrorMax);
        if ((f + 1) % report == 0 || f + 1 == opt.frames) {
            std::fprintf(stderr, "  frame %u/%u: %.1f ms, %u sub-steps, max compression %.2f%%\n",
                         f + 1, opt.frames, frameMs.back(), p.substeps, 100.0 * p.densityErrorMax);
        }
    }

    const std::clock_t cpu1 = std::clock();
    const double frames = opt.frames;
    const double cpuMs = 1e3 * double(cpu1 - cpu0) / double(CLOCKS_PER_SEC) / frames;
    const double s = double(substeps) / frames;
    const double m = median(frameMs);
    const double mean = std::accumulate(frameMs.begin(), frameMs.end(), 0.0) / frames;
    const double p = m * 1e6 / (double(n) * s);
    std::printf("scene=%s solver=%s eos=%s sound_speed=%.2f m/s isa=%s\n", opt.scene.c_str(),
                opt.solver.c_str(), opt.eos.c_str(), double(world.profile().soundSpeed),
                fluid::instructionSet());
    std::printf("stages (ms per frame, mean over timed frames):\n");
    const char* names[8] = {"sort",   "external",  "density",    "pressure",
                            "forces", "integrate", "boundaries", "step (total)"};
    for (int k = 0; k < 8; ++k) {
        std::printf("  %-13s %10.3f\n", names[k], stage[k] / frames);
    }
    // For the crates scene: Box2D's step, and with coupling the coupling's own work around
    // World::step (sampling bodies, applying forces, reports).
    std::printf("  %-13s %10.3f\n", "outside step", mean - stage[7] / frames);
    std::printf("frame wall time (ms): median %.3f, mean %.3f, p90 %.3f, min %.3f, max %.3f; "
                "CPU time (all threads) %.3f ms per frame\n",
                m, mean, quantile(frameMs, 0.9), *std::min_element(frameMs.begin(), frameMs.end()),
                *std::max_element(frameMs.begin(), frameMs.end()), cpuMs);
#if FLUID_BENCH_BOX2D
    if (opt.scene == "crates") {
        printCrates(world, scene, crates, coupling.get());
    }
#endif
    std::printf("solver=%s particles=%u frames=%u threads=%u substeps_per_frame=%.2f iterations=%u "
                "density_error_max=%.4f ms_per_frame=%.3f ns_per_particle_substep=%.1f "
                "ms_per_frame_mean=%.3f ms_per_frame_p90=%.3f cpu_ms_per_frame=%.3f\n",
                opt.solver.c_str(), n, opt.frames, opt.threads, s, world.profile().iterations,
                double(worstError), m, p, mean, quantile(frameMs, 0.9), cpuMs);
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    Options opt;
    CLI::App app{"fluid-bench: times fluid::World::step on a standard scene"};
    app.add_option("--scene", opt.scene,
                   "Scene: dam (dam break in a box), blob (zero-g blob) or crates (the dam with "
                   "20 Box2D crates)");
    app.add_option("--particles", opt.particles, "About this many particles")
        ->check(CLI::Range(1u, 1u << 26));
    app.add_option("--frames", opt.frames, "Timed frames of 1/60 s")
        ->check(CLI::Range(1u, 1u << 30));
    app.add_option("--warmup", opt.warmup, "Untimed frames before timing")
        ->check(CLI::Range(0u, 1u << 30));
    app.add_option("--threads", opt.threads, "Worker threads (WorldDef::workerCount)")
        ->check(CLI::Range(1u, 256u));
    app.add_option("--solver", opt.solver, "Solver: position-based (the default) or explicit");
    app.add_option("--substeps", opt.substeps, "Position-based sub-steps per frame (0: default)")
        ->check(CLI::Range(0u, 64u));
    app.add_option("--iterations", opt.iterations,
                   "Position-based constraint iterations per sub-step (0: default)")
        ->check(CLI::Range(0u, 100u));
    app.add_option("--eos", opt.eos, "Equation of state of the explicit solver: tait or linear");
    app.add_flag("--no-coupling", opt.noCoupling,
                 "Crates scene: step the Box2D crates without coupling them to the fluid");
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        app.exit(e); // prints the message and the usage hint
        return 2;
    }
    if (opt.scene != "dam" && opt.scene != "blob" && opt.scene != "crates") {
        std::fprintf(stderr, "fluid-bench: unknown scene '%s' (expected dam, blob or crates)\n",
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
    if (opt.eos != "tait" && opt.eos != "linear") {
        std::fprintf(stderr,
                     "fluid-bench: unknown equation of state '%s' (expected tait or linear)\n",
                     opt.eos.c_str());
        return 2;
    }
    try {
        return run(opt);
    } catch (const fluid::Error& e) {
        std::fprintf(stderr, "fluid-bench: fluid::Error: %s\n", e.what());
        return 1;
    }
}
