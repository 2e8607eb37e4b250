// The yoghurt dollop's outline as the player sees it (issue 67, "the surface"): the heap that
// yoghurt_dollop.json pours, against a water drop of the same count at rest in zero-g.
#include "level_support.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <string>

using namespace fluid;
using namespace fluid::test;

namespace {

// The outline's roughness is read over windows of this many spacings: bumps narrower than it
// count, the heap's and the drop's own shapes do not.
constexpr double kOutlineWindow = 4.0;
// The outline is resampled every this many spacings for its turning: the field's own
// smoothness, finer than any bump a player sees.
constexpr double kOutlineStep = 0.5;
// Rays per radian of outline: about four per spacing at the heap's 7 cm radius.
constexpr double kRaysPerRadian = 30.0;

// An outline's two figures in spacings: RMS roughness (spacings) and curvature noise (rad per
// spacing of outline).
struct OutlineFigures {
    double rms = 0.0, turning = 0.0;
};

OutlineFigures inSpacings(const OutlineRoughness& o, double spacing) {
    return {o.rms / spacing, o.excessTurning * spacing};
}

// The yoghurt spout of yoghurt_dollop.json: where it stands (m), how fast it pours (m/s), how
// wide (m) and how many particles a second.
struct Spout {
    double x = 0.93, y = 0.24, speed = 0.5, width = 0.03, rate = 60.0;
};

// yoghurt_dollop.json left alone for 10 s with its yoghurt spout `spout` and its quality
// `quality` ("" as shipped): the yoghurt heap's outline seen from above, a half circle of rays
// around its centroid.
OutlineFigures dollopOutline(const Spout& spout, const std::string& quality,
                             uint32_t* poured = nullptr) {
    std::string text = readLevel("yoghurt_dollop.json");
    const std::string shippedSpout = "\"position\": [0.93, 0.24], \"direction\": [0, -1],\n"
                                     "      \"speed\": 0.5, \"width\": 0.03, \"rate\": 60";
    const size_t at = text.find(shippedSpout);
    REQUIRE(at != std::string::npos);
    char moved[256];
    std::snprintf(moved, sizeof moved,
                  "\"position\": [%.4f, %.4f], \"direction\": [0, -1],\n"
                  "      \"speed\": %.3f, \"width\": %.3f, \"rate\": %.1f",
                  spout.x, spout.y, spout.speed, spout.width, spout.rate);
    text.replace(at, shippedSpout.size(), moved);
    if (!quality.empty()) {
        const std::string shipped = "\"quality\": \"precise\"";
        const size_t q = text.find(shipped);
        REQUIRE(q != std::string::npos);
        text.replace(q, shipped.size(), "\"quality\": \"" + quality + "\"");
    }
    Level level = parseLevel(text, "yoghurt_dollop.json (spout moved)", builtins());
    REQUIRE(level.materials.size() == 2);
    REQUIRE(level.materials[1].first == "yoghurt");
    const MaterialId yog = level.materials[1].second;
    playFrames(level, 600);
    const auto px = level.world.positionX(), py = level.world.positionY();
    const auto mat = level.world.materialIndex();
    glm::dvec2 c{0.0, 0.0};
    uint32_t n = 0;
    for (uint32_t i = 0; i < level.world.particleCount(); ++i) {
        if (mat[i] == yog.index) {
            c += glm::dvec2(px[i], py[i]);
            ++n;
        }
    }
    if (poured != nullptr) {
        *poured = n;
    } else {
        REQUIRE(n == 160);
    }
    c /= double(n);
    const double s = level.world.spacing(yog);
    const OutlineRoughness o =
        outlineRoughness(level.world, glm::vec2(c), 0.25f, 0.0, kPi, uint32_t(kRaysPerRadian * kPi),
                         kOutlineWindow * s, kOutlineStep * s);
    REQUIRE(o.points > 30); // a third of the rays: enough outline to read
    return inSpacings(o, s);
}

// 160 particles of `material` as a round blob in zero-g at `quality`, stepped 5 s: the outline
// all round its centre.
OutlineFigures dropOutline(Material material, Quality quality) {
    WorldDef def;
    def.positionBased = positionBasedPreset(quality);
    World world(def);
    const MaterialId m = world.addMaterial(std::move(material));
    const float s = world.spacing(m);
    BlobDef blob;
    blob.shape = Shape::circle({0.0f, 0.0f}, s * std::sqrt(160.0f / float(kPi)));
    blob.material = m;
    world.spawnBlob(blob);
    for (int f = 0; f < 300; ++f) {
        world.step(kFrame);
    }
    const Bounds b = bounds(world);
    const glm::vec2 c{0.5f * (b.x0 + b.x1), 0.5f * (b.y0 + b.y1)};
    const OutlineRoughness o =
        outlineRoughness(world, c, 0.3f, 0.0, 2.0 * kPi, uint32_t(kRaysPerRadian * 2.0 * kPi),
                         kOutlineWindow * s, kOutlineStep * s);
    REQUIRE(o.points > 100);
    return inSpacings(o, s);
}

} // namespace

TEST_CASE("yoghurt_dollop.json: the poured heap's outline, poured from eight places, against a "
          "water drop's",
          "[level][demo][yield][slow]") {
    // The yardstick: a water drop of the same count at rest in zero-g reads 0.010 spacings and
    // 0.009 rad per spacing (the field's own smoothness); a measure that read it rough would
    // read nothing of the heap.
    const OutlineFigures drop = dropOutline(fluid::water(), Quality::Precise);
    std::printf("[measure] outline of a 160-particle water drop at rest in zero-g: RMS %.3f "
                "spacings, curvature noise %.3f rad per spacing\n",
                drop.rms, drop.turning);
    CHECK(drop.rms < 0.02);
    CHECK(drop.turning < 0.05);
    // The level as shipped (precise preset), its spout moved -6 to +8 mm: the heap its 160
    // particles freeze into after 10 s reads RMS 0.056-0.107 spacings (mean 0.079) and
    // curvature noise 0.39-0.69 rad per spacing (mean 0.58): the lumps of the drops its stream
    // lands in, which the yield stress holds. Issue 67 asks for a smooth outline; what was
    // tried, and what it cost: docs/yield_stress.md, "The dollop's outline". Until then these
    // bounds keep the heap from getting rougher.
    double rms = 0.0, turning = 0.0;
    for (int k = -3; k <= 4; ++k) {
        Spout spout;
        spout.x += 0.002 * k;
        const OutlineFigures d = dollopOutline(spout, "");
        std::printf("[measure] yoghurt_dollop's heap, spout moved %+d mm: RMS %.3f spacings, "
                    "curvature noise %.3f rad per spacing\n",
                    2 * k, d.rms, d.turning);
        rms += d.rms / 8.0;
        turning += d.turning / 8.0;
    }
    std::printf("[measure] yoghurt_dollop's heap over eight pours: RMS %.3f spacings, curvature "
                "noise %.3f rad per spacing (mean)\n",
                rms, turning);
    CHECK(rms < 0.095);
    CHECK(turning < 0.7);
    // And the measure tells the two apart.
    CHECK(rms > 3.0 * drop.rms);
}

// Not run by ctest (hidden): the outlines of the test above at both presets, each pour on its
// own, for scripts/readings.sh.
TEST_CASE("readings: the yoghurt dollop's outline against a water drop's", "[.readings]") {
    for (const Quality q : {Quality::Game, Quality::Precise}) {
        const std::string name(qualityName(q));
        const OutlineFigures w = dropOutline(fluid::water(), q);
        const OutlineFigures y = dropOutline(fluid::yoghurt(), q);
        std::printf("[reading] outline/water-drop/%s/rms %.3f\n", name.c_str(), w.rms);
        std::printf("[reading] outline/water-drop/%s/turning %.3f\n", name.c_str(), w.turning);
        std::printf("[reading] outline/yoghurt-drop/%s/rms %.3f\n", name.c_str(), y.rms);
        std::printf("[reading] outline/yoghurt-drop/%s/turning %.3f\n", name.c_str(), y.turning);
        for (int k = -3; k <= 4; ++k) {
            Spout spout;
            spout.x += 0.002 * k;
            const OutlineFigures d = dollopOutline(spout, name);
            std::printf("[reading] outline/dollop/%s/spout=%+dmm/rms %.3f\n", name.c_str(), 2 * k,
                        d.rms);
            std::printf("[reading] outline/dollop/%s/spout=%+dmm/turning %.3f\n", name.c_str(),
                        2 * k, d.turning);
        }
    }
}

// Not run by ctest (hidden): the dollop poured by other spouts, whether a stream that lands
// whole rounds the heap (docs/yield_stress.md, "The dollop's outline"): as shipped (24 cm
// up, 60 particles a second), lower, a wide slow extruder whose rows touch as they leave it
// (12 and 7 cm up), and a rate at which the shipped spout's rows touch as they leave it. Four pours
// each (spout moved -3 to +3 mm), game preset.
TEST_CASE("readings: the yoghurt dollop's outline under other spouts", "[.readings]") {
    struct Case {
        const char* name;
        Spout spout;
    };
    const Case cases[] = {
        {"shipped", {}},
        {"low", {0.93, 0.12, 0.5, 0.03, 60.0}},
        {"extruder", {0.93, 0.12, 0.1, 0.05, 50.0}},
        {"extruder-low", {0.93, 0.07, 0.1, 0.05, 50.0}},
        {"fast", {0.93, 0.24, 0.5, 0.03, 150.0}},
    };
    for (const Case& c : cases) {
        for (int k = -1; k <= 2; ++k) {
            Spout spout = c.spout;
            spout.x += 0.002 * k - 0.001;
            uint32_t poured = 0;
            const OutlineFigures d = dollopOutline(spout, "game", &poured);
            std::printf("[reading] outline/spout/%s/at=%+dmm/poured %u\n", c.name, 2 * k - 1,
                        poured);
            std::printf("[reading] outline/spout/%s/at=%+dmm/rms %.3f\n", c.name, 2 * k - 1, d.rms);
            std::printf("[reading] outline/spout/%s/at=%+dmm/turning %.3f\n", c.name, 2 * k - 1,
                        d.turning);
        }
    }
}
