// The position-based presets and the settings between them, measured as fluid-bench measures
// them (bench/compression.h: compression from the positions alone, the tank's surface as
// the 95th percentile of y plus half a spacing).
//
// - Each preset's accuracy on the resting 0.5 m water tank of `fluid-bench --scene tank`.
// - The game preset's 4k dam: its front hits the far corner without stacking particles.
// - Coherence: at the settings listed below, from 1 x 4 and 2 x 2 up to the precise preset, a
//   resting tank of water, of yoghurt and of both ends no higher than it started,
//   throws nothing off its surface, has nothing non-finite, and no particle compressed beyond
//   93% (LiquidFun's largest in the same tank). Fewer sweeps trade compression, not coherence.
#include "compression.h"
#include "test_support.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <string>
#include <vector>

using namespace fluid;
using namespace fluid::test;

namespace {

/// What a resting tank measured after its frames.
struct TankResult {
    /// Compression at the end (unit: 1).
    bench::Compression end;
    /// Surface at the end over the surface at the start, minus 1 (unit: 1).
    double surfaceChange = 0.0;
    /// The same, averaged over the last second's 60 frames (unit: 1): a sloshing tank's surface
    /// moves by about half a percent from frame to frame.
    double surfaceLastSecond = 0.0;
    /// Largest count, over every frame, of particles more than one support above the highest
    /// particle at the start (unit: count).
    uint32_t thrown = 0;
    /// Frames with a non-finite position or velocity (unit: count).
    uint32_t nonFiniteFrames = 0;
    /// Mean kinetic energy per kg at the end (unit: J/kg).
    double kinetic = 0.0;
};

/// What fills a tank.
enum class Fill { Water, Yoghurt, Mix };

const char* fillName(Fill fill) {
    return fill == Fill::Water ? "water" : fill == Fill::Yoghurt ? "yoghurt" : "water + yoghurt";
}

/// A tank `cols` water spacings wide holding `rows` spacings of liquid (the mix: water below,
/// yoghurt above, half each), in a box 1.595 liquid heights tall, under gravity, `frames`
/// frames of 1/60 s with `settings`.
TankResult restingTank(const PositionBasedDef& settings, Fill fill, uint32_t cols, uint32_t rows,
                       int frames) {
    WorldDef def = physicsDef();
    def.positionBased = settings;
    World world(def);
    const MaterialId w = world.addMaterial(water());
    const MaterialId y = world.addMaterial(yoghurt());
    const float s = world.spacing(w);
    const float width = float(cols) * s, height = float(rows) * s;
    world.addForce(std::make_unique<GravityForce>(0.0f, -kG));
    world.addBoundary(std::make_unique<BoxContainer>(0.0f, 0.0f, width, 1.595f * height));
    const auto fillWith = [&](MaterialId m, float y0, float y1) {
        const float sm = world.spacing(m);
        const auto c = uint32_t(width / sm + 1e-3f), r = uint32_t((y1 - y0) / sm + 1e-3f);
        world.spawnBlob(latticeBlock(world, m, 0.5f * (width - float(c) * sm), y0, c, r));
    };
    if (fill == Fill::Water) {
        fillWith(w, 0.0f, height);
    } else if (fill == Fill::Yoghurt) {
        fillWith(y, 0.0f, height);
    } else {
        fillWith(w, 0.0f, 0.5f * height);
        fillWith(y, 0.5f * height, height);
    }
    bench::CompressionMeter meter(s);
    std::vector<double> scratch;
    const double surface0 = bench::surfaceLevel(world.positionY(), s, scratch);
    const float top0 = *std::max_element(world.positionY().begin(), world.positionY().end());
    const float h = world.material(w).smoothingDistance;
    TankResult r;
    for (int frame = 0; frame < frames; ++frame) {
        world.step(kFrame);
        if (!allFinite(world)) {
            ++r.nonFiniteFrames;
        }
        const auto py = world.positionY();
        const auto thrown =
            uint32_t(std::count_if(py.begin(), py.end(), [&](float v) { return v > top0 + h; }));
        r.thrown = std::max(r.thrown, thrown);
        if (frame + 60 >= frames) {
            r.surfaceLastSecond += (bench::surfaceLevel(py, s, scratch) / surface0 - 1.0) / 60.0;
        }
    }
    r.end = meter.measure(world.positionX(), world.positionY());
    r.surfaceChange = bench::surfaceLevel(world.positionY(), s, scratch) / surface0 - 1.0;
    const auto vx = world.velocityX(), vy = world.velocityY();
    for (uint32_t i = 0; i < world.particleCount(); ++i) {
        r.kinetic += 0.5 * (double(vx[i]) * vx[i] + double(vy[i]) * vy[i]);
    }
    r.kinetic /= world.particleCount();
    return r;
}

} // namespace

TEST_CASE("each preset holds the 0.5 m resting tank to its stated accuracy",
          "[slow][invariants][presets]") {
    // fluid-bench --scene tank: 30 x 50 water particles (0.30 x 0.50 m), 5 s.
    SECTION("game: mean <= 5%, max <= 10% (a tenth of LiquidFun's), surface within 3% over the "
            "last second") {
        Stopwatch sw("game preset tank");
        const TankResult r =
            restingTank(positionBasedPreset(Quality::Game), Fill::Water, 30, 50, 300);
        std::printf("[measure] game preset tank: compression mean %.4f p99 %.4f max %.4f, surface "
                    "%+.4f (last second %+.4f), thrown %u, KE/m %.3g J/kg\n",
                    r.end.mean, r.end.p99, r.end.max, r.surfaceChange, r.surfaceLastSecond,
                    r.thrown, r.kinetic);
        CHECK(r.nonFiniteFrames == 0);
        CHECK(r.end.mean <= 0.05);
        CHECK(r.end.max <= 0.10);
        // The game preset's surface target, as decided for bodies in its coarse solve: within
        // 3%, averaged over the last second (docs/position_based.md, "Which preset").
        CHECK(std::fabs(r.surfaceLastSecond) <= 0.03);
        CHECK(r.thrown == 0);
        // One sweep per sub-step leaves the tank moving a little (7e-4 J/kg, 4 cm/s rms; the
        // precise preset rests at 2e-5); a boiling tank reads 0.1-6 J/kg.
        CHECK(r.kinetic < 1e-2);
    }
    SECTION("precise: mean <= 1%, max <= 3%") {
        Stopwatch sw("precise preset tank");
        const TankResult r =
            restingTank(positionBasedPreset(Quality::Precise), Fill::Water, 30, 50, 300);
        std::printf("[measure] precise preset tank: compression mean %.4f p99 %.4f max %.4f, "
                    "surface %+.4f, thrown %u, KE/m %.3g J/kg\n",
                    r.end.mean, r.end.p99, r.end.max, r.surfaceChange, r.thrown, r.kinetic);
        CHECK(r.nonFiniteFrames == 0);
        CHECK(r.end.mean <= 0.01);
        CHECK(r.end.max <= 0.03);
        CHECK(std::fabs(r.surfaceChange) <= 0.02);
        CHECK(r.thrown == 0);
        CHECK(r.kinetic < 1e-4);
    }
}

TEST_CASE("fewer sweeps trade compression, not coherence: resting tanks at every setting",
          "[slow][sweep][invariants][presets]") {
    // Settings from the game preset's (4 x 1 with the coarse correction 0.4, viscosity every
    // second sub-step) down to 3 x 1 (viscosity once a frame), 1 x 4 and 2 x 2, and the precise
    // preset. Not yet here: 1 x 1
    // (the 0.6 m water tank ends 2.3% above its start) and 2 x 1 (particles thrown while the
    // water tank settles); docs/position_based_method.md, "Coarse correction".
    struct Setting {
        uint32_t substeps, iterations, interval;
        float coarse;
    };
    const Setting setting =
        GENERATE(Setting{4, 1, 2, 0.4f}, Setting{3, 1, 3, 0.4f}, Setting{1, 4, 1, 0.4f},
                 Setting{2, 2, 2, 0.4f}, Setting{4, 2, 2, 0.4f}, Setting{8, 1, 2, 0.4f},
                 Setting{4, 8, 1, 0.0f});
    const Fill fill = GENERATE(Fill::Water, Fill::Yoghurt, Fill::Mix);
    // The game tank's width, a little deeper than it (0.6 m).
    PositionBasedDef settings;
    settings.substeps = setting.substeps;
    settings.iterations = setting.iterations;
    settings.viscosityInterval = setting.interval;
    settings.coarseCorrection = setting.coarse;
    const TankResult r = restingTank(settings, fill, 30, 60, 300);
    CAPTURE(setting.substeps, setting.iterations, setting.interval, setting.coarse, fillName(fill),
            r.end.mean, r.end.p99, r.end.max, r.surfaceChange, r.thrown, r.kinetic);
    std::printf("[measure] %u x %u (viscosity every %u, coarse %.1f) %s: compression mean %.4f "
                "max %.4f, surface %+.4f, thrown %u, KE/m %.3g J/kg\n",
                setting.substeps, setting.iterations, setting.interval, double(setting.coarse),
                fillName(fill), r.end.mean, r.end.max, r.surfaceChange, r.thrown, r.kinetic);
    CHECK(r.nonFiniteFrames == 0);
    CHECK(r.surfaceChange <= 0.0);
    CHECK(r.thrown == 0);
    CHECK(r.end.max <= 0.93);
}

namespace {

/// A handle as one number (slot and generation).
uint64_t handleKey(ParticleHandle h) {
    return (uint64_t(h.slot) << 32) | h.generation;
}

/// Handles of the particles that share their exact position with another (sorted).
std::vector<uint64_t> stacked(const World& world) {
    std::vector<uint64_t> out;
    for (const uint32_t i : bench::stackedIndices(world.positionX(), world.positionY())) {
        out.push_back(handleKey(world.handleAt(i)));
    }
    std::sort(out.begin(), out.end());
    return out;
}

} // namespace

TEST_CASE("the game preset's dam: the front hits the far corner and stacks no particles",
          "[slow][invariants][presets]") {
    // fluid-bench --scene dam --particles 4000: a 45 x 90 block in a box four blocks wide. The
    // front reaches the far wall at frame 30, and the box clamps particles past its corner onto
    // the corner. Before separateStacked, particles stacked there on one point, where the pair
    // terms have no direction to part them, and stayed stacked for good (in the 16k dam, 52
    // stacked particles read 250% compression to the end of the run). A stack the last
    // sub-step's projection makes can stand at a frame's end; the next sub-step parts it.
    Stopwatch sw("game preset dam");
    WorldDef def = physicsDef();
    def.positionBased = positionBasedPreset(Quality::Game);
    World world(def);
    const MaterialId w = world.addMaterial(water());
    const float s = world.spacing(w);
    const uint32_t nx = 45, ny = 90;
    world.spawnBlob(latticeBlock(world, w, 0.0f, 0.0f, nx, ny));
    world.addForce(std::make_unique<GravityForce>(0.0f, -kG));
    world.addBoundary(
        std::make_unique<BoxContainer>(0.0f, 0.0f, 4.0f * float(nx) * s, 1.5f * float(ny) * s));
    bench::CompressionMeter meter(s);
    std::vector<uint64_t> before;
    size_t most = 0, persisted = 0;
    uint32_t separated = 0;
    double worst = 0.0;
    int worstFrame = 0;
    for (int f = 1; f <= 90; ++f) {
        world.step(kFrame);
        separated += world.profile().separated;
        const std::vector<uint64_t> now = stacked(world);
        most = std::max(most, now.size());
        std::vector<uint64_t> both;
        std::set_intersection(before.begin(), before.end(), now.begin(), now.end(),
                              std::back_inserter(both));
        persisted = std::max(persisted, both.size());
        before = now;
        const double c = meter.measure(world.positionX(), world.positionY()).max;
        if (c > worst) {
            worst = c;
            worstFrame = f;
        }
    }
    std::printf("[measure] game preset 4k dam, frames 1-90: %u particles parted, at most %zu "
                "stacked at a frame's end, at most %zu stacked two frames running, %zu at the "
                "end; largest compression %.4f (frame %d)\n",
                separated, most, persisted, before.size(), worst, worstFrame);
    CHECK(allFinite(world));
    CHECK(persisted == 0);
    CHECK(before.empty());
    // Coherent through the impact: at most LiquidFun's largest in its own tank.
    CHECK(worst <= 0.93);
}
