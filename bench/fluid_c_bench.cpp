// fluid-c-bench: what the C API (fluid/c.h) costs on top of the C++ API. The same dam (a water
// block twice as tall as wide in a box four blocks wide, gravity) is built and stepped through
// both, in alternating rounds on the same thread count, and must end with the same bits; prints
// each side's ms per frame and ns per particle per sub-step, and the C side's over the C++.
//
//   fluid-c-bench [--particles 4000] [--frames 120] [--rounds 6] [--threads 1] [--quality game]
#include "bench/command_line.h"

#include <fluid/c.h>
#include <fluid/fluid.h>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

namespace {

constexpr float kFrame = 1.0f / 60.0f;

// The dam's size for about `particles` particles at `spacing` (m): the block's width and height.
struct Dam {
    float width = 0.0f, height = 0.0f, boxWidth = 0.0f, boxHeight = 0.0f;
};

Dam damFor(uint32_t particles, float spacing) {
    Dam d;
    const float columns = std::round(std::sqrt(float(particles) / 2.0f));
    d.width = columns * spacing;
    d.height = 2.0f * d.width;
    d.boxWidth = 4.0f * d.width;
    d.boxHeight = 1.5f * d.height;
    return d;
}

bool check(fluid_status status, const char* what) {
    if (status != FLUID_OK) {
        std::fprintf(stderr, "fluid-c-bench: %s: %s\n", what, fluid_last_error());
        return false;
    }
    return true;
}

double millisecondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app{"fluid-c-bench: the C API's cost over the C++ API on the dam"};
    uint32_t particles = 4000, frames = 120, rounds = 6, threads = 1;
    std::string quality;
    app.add_option("--particles", particles, "Particles, about")->check(CLI::Range(100u, 1000000u));
    app.add_option("--frames", frames, "Frames per round and side")->check(CLI::Range(1u, 100000u));
    app.add_option("--rounds", rounds, "Rounds, each side in turn")->check(CLI::Range(1u, 1000u));
    app.add_option("--threads", threads, "Workers of each world")->check(CLI::Range(1u, 256u));
    fluid::tools::addQualityOption(app, quality, "game or precise");
    if (const int status = fluid::tools::parseCommandLine(app, argc, argv); status >= 0) {
        return status;
    }

    // The C++ side.
    fluid::WorldDef def = fluid::tools::presetWorldDef(quality, threads);
    fluid::World cpp(def);
    const fluid::MaterialId water = cpp.addMaterial(fluid::water());
    const Dam dam = damFor(particles, cpp.spacing(water));
    cpp.addBoundary(
        std::make_unique<fluid::BoxContainer>(0.0f, 0.0f, dam.boxWidth, dam.boxHeight));
    cpp.addForce(std::make_unique<fluid::GravityForce>(0.0f, -9.81f));
    fluid::BlobDef blob;
    blob.shape = fluid::Shape::box({0.0f, 0.0f}, {dam.width, dam.height});
    blob.material = water;
    cpp.spawnBlob(blob);

    // The C side, by names.
    fluid_world_def cdef = fluid_default_world_def();
    fluid_world* c = nullptr;
    fluid_material_def cwater{};
    fluid_material_id cid{};
    fluid_plugin_id plugin{};
    const fluid_param box[] = {{"minX", 0.0},
                               {"minY", 0.0},
                               {"maxX", double(dam.boxWidth)},
                               {"maxY", double(dam.boxHeight)}};
    const fluid_param gravity[] = {{"gx", 0.0}, {"gy", -9.81}};
    fluid_blob_def cblob = fluid_default_blob_def();
    cblob.shape = fluid_box_shape({0.0f, 0.0f}, {dam.width, dam.height});
    cdef.worker_count = threads;
    if (!check(fluid_world_def_set_quality(&cdef, quality.c_str()), "quality") ||
        !check(fluid_world_create(&cdef, &c), "world") ||
        !check(fluid_material_preset("water", &cwater), "water") ||
        !check(fluid_world_add_material(c, &cwater, &cid), "material") ||
        !check(fluid_world_add_plugin(c, "boundary.box", box, 4, &plugin), "box") ||
        !check(fluid_world_add_plugin(c, "force.gravity", gravity, 2, &plugin), "gravity")) {
        fluid_world_destroy(c);
        return 1;
    }
    cblob.material = cid;
    if (!check(fluid_world_spawn_blob(c, &cblob, nullptr), "blob")) {
        fluid_world_destroy(c);
        return 1;
    }

    double cppMs = 0.0, cMs = 0.0;
    uint64_t substeps = 0;
    for (uint32_t r = 0; r < rounds; ++r) {
        auto start = std::chrono::steady_clock::now();
        for (uint32_t f = 0; f < frames; ++f) {
            cpp.step(kFrame);
            substeps += cpp.lastSubsteps();
        }
        cppMs += millisecondsSince(start);
        start = std::chrono::steady_clock::now();
        for (uint32_t f = 0; f < frames; ++f) {
            if (!check(fluid_world_step(c, kFrame), "step")) {
                fluid_world_destroy(c);
                return 1;
            }
        }
        cMs += millisecondsSince(start);
    }
    const float *x = nullptr, *y = nullptr;
    uint32_t count = 0;
    check(fluid_world_positions(c, &x, &y, &count), "positions");
    const bool same = count == cpp.particleCount() &&
                      std::memcmp(x, cpp.positionX().data(), count * sizeof(float)) == 0 &&
                      std::memcmp(y, cpp.positionY().data(), count * sizeof(float)) == 0;
    fluid_world_destroy(c);
    const double totalFrames = double(frames) * rounds;
    const double perSubstep = double(substeps) / totalFrames;
    auto ns = [&](double ms) { return ms * 1e6 / totalFrames / perSubstep / double(count); };
    std::printf("fluid-c-bench: dam %u particles, %s, %u thread(s), %u rounds of %u frames, "
                "%.1f sub-steps a frame\n",
                count, quality.c_str(), threads, rounds, frames, perSubstep);
    std::printf("fluid-c-bench: C++ %.3f ms/frame (%.1f ns per particle per sub-step), C %.3f "
                "ms/frame (%.1f ns), C / C++ %.4f, same bits: %s\n",
                cppMs / totalFrames, ns(cppMs), cMs / totalFrames, ns(cMs), cMs / cppMs,
                same ? "yes" : "no");
    return same ? 0 : 1;
}
