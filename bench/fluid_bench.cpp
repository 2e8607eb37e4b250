// fluid-bench: times World::step on a standard scene and prints one summary line.
//
//   fluid-bench --scene dam --particles 16000 --frames 600 --threads 2 [--warmup N]
//               [--solver position-based|explicit] [--substeps S] [--iterations I]
//               [--eos tait|linear]
//
// Scenes (see bench/README.md):
//   dam   a water block (width:height 1:2) standing in the left of a closed box four block
//         widths wide and 1.5 block heights tall, floor at y = 0, gravity (0, -9.81) m/s^2.
//   blob  a round water blob in zero gravity, no boundary, no force plugin.
// Every frame is 1/60 s. The last stdout line is machine-readable:
//   solver=NAME particles=N frames=F threads=T substeps_per_frame=S iterations=I
//   density_error_max=E ms_per_frame=M ns_per_particle_substep=P
#include <fluid/fluid.h>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

namespace {

/// Command-line options (see the usage above).
struct Options {
    /// "dam" or "blob".
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
};

/// Fills `world` with the dam-break scene of about `n` water particles; returns a description.
std::string buildDam(fluid::World& world, uint32_t n) {
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
    return text;
}

/// Fills `world` with a zero-gravity round blob of about `n` water particles.
std::string buildBlob(fluid::World& world, uint32_t n) {
    const fluid::MaterialId water = world.addMaterial(fluid::water());
    const float s = world.spacing(water);
    fluid::BlobDef blob;
    blob.shape = fluid::BlobShape::Circle;
    blob.radius = s * float(std::sqrt(n / std::numbers::pi)); // area n s^2
    blob.material = water;
    world.spawnBlob(blob);
    char text[160];
    std::snprintf(text, sizeof text, "blob: radius %.3f m, zero gravity, no boundary", blob.radius);
    return text;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const size_t m = v.size() / 2;
    return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
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
    const std::string what =
        opt.scene == "dam" ? buildDam(world, opt.particles) : buildBlob(world, opt.particles);
    const uint32_t n = world.particleCount();
    std::fprintf(stderr,
                 "fluid-bench: %s; %u particles, threads=%u, solver=%s, eos=%s, %u warm-up + %u "
                 "timed frames\n",
                 what.c_str(), n, opt.threads, opt.solver.c_str(), opt.eos.c_str(), opt.warmup,
                 opt.frames);

    const float frameDt = 1.0f / 60.0f;
    for (uint32_t f = 0; f < opt.warmup; ++f) {
        world.step(frameDt);
    }
    std::vector<double> frameMs;
    frameMs.reserve(opt.frames);
    // Stage sums over the timed frames (unit: ms): sort, external, density, pressure, forces,
    // integrate, boundaries, whole step.
    double stage[8] = {};
    uint64_t substeps = 0;
    float worstError = 0.0f;
    const uint32_t report = std::max<uint32_t>(1, opt.frames / 5);
    for (uint32_t f = 0; f < opt.frames; ++f) {
        const auto t0 = std::chrono::steady_clock::now();
        world.step(frameDt);
        const auto t1 = std::chrono::steady_clock::now();
        frameMs.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
        const fluid::Profile& p = world.profile();
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

    const double frames = opt.frames;
    const double s = double(substeps) / frames;
    const double m = median(frameMs);
    const double p = m * 1e6 / (double(n) * s);
    std::printf("scene=%s solver=%s eos=%s sound_speed=%.2f m/s\n", opt.scene.c_str(),
                opt.solver.c_str(), opt.eos.c_str(), double(world.profile().soundSpeed));
    std::printf("stages (ms per frame, mean over timed frames):\n");
    const char* names[8] = {"sort",   "external",  "density",    "pressure",
                            "forces", "integrate", "boundaries", "step (total)"};
    for (int k = 0; k < 8; ++k) {
        std::printf("  %-13s %10.3f\n", names[k], stage[k] / frames);
    }
    std::printf("frame wall time (ms): median %.3f, min %.3f, max %.3f\n", m,
                *std::min_element(frameMs.begin(), frameMs.end()),
                *std::max_element(frameMs.begin(), frameMs.end()));
    std::printf("solver=%s particles=%u frames=%u threads=%u substeps_per_frame=%.2f iterations=%u "
                "density_error_max=%.4f ms_per_frame=%.3f ns_per_particle_substep=%.1f\n",
                opt.solver.c_str(), n, opt.frames, opt.threads, s, world.profile().iterations,
                double(worstError), m, p);
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    Options opt;
    CLI::App app{"fluid-bench: times fluid::World::step on a standard scene"};
    app.add_option("--scene", opt.scene, "Scene: dam (dam break in a box) or blob (zero-g blob)");
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
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        app.exit(e); // prints the message and the usage hint
        return 2;
    }
    if (opt.scene != "dam" && opt.scene != "blob") {
        std::fprintf(stderr, "fluid-bench: unknown scene '%s' (expected dam or blob)\n",
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
