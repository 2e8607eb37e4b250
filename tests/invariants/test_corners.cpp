// fluid tests — every documented range is one the solver holds: each number of Material,
// WorldDef and PositionBasedDef at its minimum and at its maximum (the others at the preset's),
// a 2,000-particle dam break stays finite, keeps every particle and (the position-based solver)
// gains no energy. A corner whose settings do not fit together (a spacing the smoothing
// distance cannot cover) is refused when the material is added, with a message naming both.
// Prints one row per corner for docs/levels.md's table, its frame time included; the time is
// not asserted here (speed lives in the benchmarks). The long test set steps each dam 2 s (the
// explicit solver's 10 frames: its capped corners take 0.7 s per frame, and its explosions
// came within 1-34 frames); bench/corners.sh runs the full 5 s the table reports
// (FLUID_CORNER_FRAMES=300).
#include "test_support.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>
#include <vector>

using namespace fluid;
using namespace fluid::test;

namespace {

constexpr double kGravity = 9.81; // unit: m/s^2, in double for the energies
// Frames of 1/60 s each dam runs: FLUID_CORNER_FRAMES, else `fallback`.
int frameCount(int fallback) {
    const char* env = std::getenv("FLUID_CORNER_FRAMES");
    return env != nullptr ? std::max(1, std::atoi(env)) : fallback;
}

struct Corner {
    std::string name;  // "viscosity = 10000"
    bool refused = false;
    std::string error; // the refusal
    double e0 = 0.0, eMax = 0.0, eEnd = 0.0; // kinetic + potential (unit: J)
    double compression = 0.0; // largest mean compression over the frames (unit: 1)
    double vMax = 0.0;        // fastest particle (unit: m/s)
    double fall = 0.0;        // a free fall's speed from the box's lid to its floor (unit: m/s)
    double msPerFrame = 0.0;
    bool finite = true;
    uint32_t particles = 0, lost = 0; // at the start; lost by the end
    int frames = 0;                   // stepped (fewer when a survey's time budget ran out)
};

// FLUID_CORNER_BUDGET (unit: s) stops a survey's corner early; the test runs every frame.
bool budgetSpent(std::chrono::steady_clock::time_point start) {
    const char* env = std::getenv("FLUID_CORNER_BUDGET");
    return env != nullptr && std::chrono::steady_clock::now() - start >
                                 std::chrono::duration<double>(std::atof(env));
}

// Kinetic + gravitational potential energy, potential from the box's floor (unit: J).
double totalEnergy(const World& world) {
    const Energy e = energy(world, kGravity);
    return e.kinetic + e.potential;
}

// A 50 x 40 dam break in a box 4 columns wide and 2 rows high per lattice column and row, the
// box's floor at 0: 2,000 particles.
Corner runCorner(const std::string& name, const WorldDef& def, const Material& material) {
    const int frames = frameCount(def.solver == Solver::Explicit ? 10 : 120);
    Corner c;
    c.name = name;
    try {
        World world(def);
        const MaterialId w = world.addMaterial(material);
        const float s = world.spacing(w);
        const uint32_t cols = 50, rows = 40;
        world.addForce(std::make_unique<GravityForce>(0.0f, -float(kGravity)));
        world.addBoundary(
            std::make_unique<BoxContainer>(0.0f, 0.0f, 4.0f * cols * s, 2.0f * rows * s));
        world.spawnBlob(latticeBlock(world, w, 0.0f, 0.0f, cols, rows));
        c.fall = std::sqrt(2.0 * kGravity * 2.0 * rows * double(s));
        c.e0 = totalEnergy(world);
        c.eMax = c.e0;
        c.particles = world.particleCount();
        const auto start = std::chrono::steady_clock::now();
        for (int frame = 0; frame < frames; ++frame) {
            world.step(kFrame);
            ++c.frames;
            c.lost = c.particles - world.particleCount();
            if (!allFinite(world)) {
                c.finite = false;
                break;
            }
            const double e = totalEnergy(world);
            c.eMax = std::max(c.eMax, e);
            c.eEnd = e;
            c.compression = std::max(c.compression, double(world.profile().densityErrorAvg));
            c.vMax = std::max(c.vMax, double(maxSpeed(world)));
            if (budgetSpent(start)) {
                break;
            }
        }
        c.msPerFrame =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count() /
            c.frames;
    } catch (const Error& error) {
        c.refused = true;
        c.error = error.what();
    }
    return c;
}

void report(const char* setting, const Corner& c) {
    if (c.refused) {
        std::printf("[corner] %s | %s | refused: %s\n", setting, c.name.c_str(), c.error.c_str());
        return;
    }
    std::printf("[corner] %s | %s | E0 %.4g J | Emax-E0 %+.3g J (%+.2g%%) | Eend %.4g J | mean "
                "compression max %.2f%% | vmax %.3g m/s | %.2f ms/frame | %s | lost %u of %u | %d frames\n",
                setting, c.name.c_str(), c.e0, c.eMax - c.e0, 100.0 * (c.eMax - c.e0) / c.e0,
                c.eEnd, 100.0 * c.compression, c.vMax, c.msPerFrame,
                c.finite ? "finite" : "NOT FINITE", c.lost, c.particles, c.frames);
}

template <class Def> std::string cornerName(const Field<Def>& f, double value) {
    char text[96];
    std::snprintf(text, sizeof text, "%.*s = %g", int(f.name.size()), f.name.data(), value);
    return text;
}

// The smallest value a field accepts: its bound, or the next float above an open bound.
template <class Def> double lowest(const Field<Def>& f) {
    if (!f.openLow) {
        return f.lo;
    }
    return f.real != nullptr ? double(std::nextafter(float(f.lo), 1.0f)) : f.lo + 1.0;
}

// Every corner of one setting: the material's numbers, the world's (depth and the explicit
// solver's) and the position-based solver's.
std::vector<Corner> sweep(const char* setting, const WorldDef& base, const Material& preset) {
    std::vector<Corner> corners;
    const auto check = [&](Corner c) {
        report(setting, c);
        corners.push_back(std::move(c));
    };
    for (const MaterialField& f : materialFields()) {
        if (f.name == "kernelParticles") {
            continue; // informational: the solver never reads it
        }
        for (const double value : {lowest(f), f.hi}) {
            Material m = preset;
            f.set(m, value);
            check(runCorner(cornerName(f, value), base, m));
        }
    }
    for (const Field<WorldDef>& f : worldFields()) {
        if (f.name == "maxParticles") {
            continue; // a cap on adding, not a step setting
        }
        const bool explicitOnly = f.name == "courant" || f.name == "maxSubsteps";
        if (explicitOnly != (base.solver == Solver::Explicit) && f.name != "depth") {
            continue;
        }
        for (const double value : {lowest(f), f.hi}) {
            WorldDef def = base;
            f.set(def, value);
            check(runCorner(cornerName(f, value), def, preset));
        }
    }
    if (base.solver == Solver::PositionBased) {
        for (const Field<PositionBasedDef>& f : positionBasedFields()) {
            for (const double value : {lowest(f), f.hi}) {
                WorldDef def = base;
                f.set(def.positionBased, value);
                check(runCorner(cornerName(f, value), def, preset));
            }
        }
    } else {
        for (const double c : {0.1, 1e4}) {
            WorldDef def = base;
            def.soundSpeed = float(c);
            char name[32];
            std::snprintf(name, sizeof name, "soundSpeed = %g", c);
            check(runCorner(name, def, preset));
        }
        WorldDef linear = base;
        linear.equationOfState = EquationOfState::Linear;
        for (const MaterialField& f : materialFields()) {
            if (f.name == "stiffness") {
                for (const double value : {lowest(f), f.hi}) {
                    Material m = preset;
                    f.set(m, value);
                    check(runCorner("linear, " + cornerName(f, value), linear, m));
                }
            }
        }
    }
    return corners;
}

// Every corner runs, or is refused by a check of settings that only make sense together, which
// names them: the spacing (mass, rest density, depth, smoothing distance), the explicit solver
// and a flow law, one sweep and the coarse correction.
// `energy(corner)` says whether the corner's kinetic + potential energy must stay at or below
// the start's.
template <class EnergyRule>
void checkCorners(const std::vector<Corner>& corners, EnergyRule energy) {
    for (const Corner& c : corners) {
        INFO(c.name << (c.refused ? ": refused: " + c.error : ""));
        if (c.refused) {
            const bool spacing = c.error.find("particle spacing") != std::string::npos;
            const bool flowLaw = c.error.find("Herschel-Bulkley") != std::string::npos;
            const bool sweep = c.error.find("needs the coarse correction") != std::string::npos;
            CHECK((spacing || flowLaw || sweep));
            continue;
        }
        CHECK(c.finite);
        CHECK(c.lost == 0); // a closed box keeps every particle
        if (energy(c)) {
            // No energy from nowhere: gravity is in the potential, the walls and the solver
            // only take. A thousandth of the start's for the float sums.
            CHECK(c.eMax <= c.e0 * 1.001);
            // Nor from one particle: none at twice the speed of a fall from the lid (vorticity
            // confinement at 1 threw particles at 46-64 m/s, with the total within the bound
            // above, before its run counted at most a radian; now 5.9 m/s, the fall 4 m/s).
            CHECK(c.vMax <= 2.0 * c.fall);
        }
    }
}

} // namespace

TEST_CASE("every setting of the game preset at its documented minimum and maximum holds a dam",
          "[long][corners]") {
    WorldDef def;
    def.positionBased = positionBasedPreset(Quality::Game);
    checkCorners(sweep("game", def, water()), [](const Corner&) { return true; });
}

TEST_CASE("every setting of the precise preset at its documented minimum and maximum holds a dam",
          "[sweep][corners]") {
    WorldDef def;
    def.positionBased = positionBasedPreset(Quality::Precise);
    checkCorners(sweep("precise", def, water()), [](const Corner&) { return true; });
}

// The explicit solver's corners stay finite and keep their particles (a frame whose sub-step
// cap cannot hold the sound speed, stiffness or viscosity steps with the largest it holds) and
// gain no energy, but for two corners reported, not asserted (docs/solver.md, Known limits):
// the linear equation of state starts with its free surface under tension, energy that the
// kinetic and potential terms do not count (tests/invariants/test_energy.cpp counts it), and
// without viscosity the dam gains energy at the walls as it runs.
TEST_CASE("every setting of the explicit solver at its documented minimum and maximum stays "
          "finite, keeps every particle and gains no energy",
          "[sweep][corners]") {
    WorldDef def;
    def.solver = Solver::Explicit;
    checkCorners(sweep("explicit", def, forSolver(water(), Solver::Explicit)),
                 [](const Corner& c) {
                     return c.name.rfind("linear, ", 0) != 0 && c.name != "viscosity = 0";
                 });
}
