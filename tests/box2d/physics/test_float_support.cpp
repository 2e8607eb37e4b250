// Where a floating body's support comes from, against the water it displaces. A Box2D box
// floats free in a tank of water until it has settled; in a twin world, the same tank with no
// body, its "ghost" is the water that fills the body's submerged outline (as it settled). Per
// sub-step the position-based solver supports each twice: by the coarse solve (the body: its
// impulse, share M^-1 G^T psi, as a force; the ghost: its particles' coarse moves, mass x move /
// dt^2) and by the density sweeps (the body: the reactions on its samples; the ghost: its
// particles' sweep moves). At rest the body's two parts add up to its weight and the ghost's to
// its load (its weight and its top row's cohesion), and the body floats at Archimedes' draft;
// the split shows which part of the body's support differs from the water's
// (docs/position_based.md, "Bodies in the coarse solve").
#include "box2d_support.h"

#include "world_state.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <vector>

using namespace fluid;
using namespace fluid::test;

namespace {

// Stage indices of the position-based solver (solver_position_based.cpp's stage list).
constexpr uint32_t kStagePredict = 1, kStageCoarse = 3, kStageSweeps = 4, kStageVelocity = 5,
                   kStageBoundaries = 8;

struct Support {
    double coarse = 0.0, sweeps = 0.0; // mean vertical support over the measured frames (N)
    double weight = 0.0;               // the body's or the ghost's weight (N)
    double load = 0.0;      // the ghost: what its prediction moves it down by, as a force (N)
    double submerged = 0.0; // the body: its area's fraction below the waterline beside it
    double bottom = 0.0;    // the body: its bottom's mean height (m)
    double level = 0.0;     // the body: the waterline's mean height beside it (m)
};

struct Tank {
    float s = 0.0f, width = 0.0f, surface = 0.0f;
    uint32_t cols = 0, rows = 0;
};

// A tank `width` m wide with `depth` m of water: gravity, the fluid's container, the lattice.
Tank makeTank(World& world, MaterialId water, float width, float depth) {
    Tank t;
    t.s = world.spacing(water);
    t.cols = uint32_t(std::floor(width / t.s));
    t.rows = uint32_t(std::lround(depth / t.s));
    t.width = float(t.cols) * t.s;
    t.surface = float(t.rows) * t.s;
    world.addForce(std::make_unique<GravityForce>(0.0f, -kG));
    world.addBoundary(std::make_unique<BoxContainer>(0.0f, 0.0f, t.width, t.surface + 0.5f));
    return t;
}

WorldDef presetDef(Quality quality) {
    WorldDef def = physicsDef();
    def.positionBased = positionBasedPreset(quality);
    return def;
}

// The body: a box of half extents `hw` x `hh` at `ratio` of water's density, started at its
// Archimedes draft below the lattice's surface, free; measured over frames [settle, settle +
// frames).
Support bodySupport(Quality quality, float width, float depth, float hw, float hh, float ratio,
                    int settle, int frames) {
    World world(presetDef(quality));
    const MaterialId water = world.addMaterial(fluid::water());
    const Tank t = makeTank(world, water, width, depth);
    b2World physics(b2Vec2(0.0f, -kG));
    addTankWalls(physics, 0.0f, 0.0f, t.width, t.surface + 0.5f);
    b2Body* body =
        addBox(physics, b2_dynamicBody, {0.5f * t.width, t.surface - ratio * 2.0f * hh + hh}, hw,
               hh, ratio * box2d::arealDensity(world, water));
    body->GetFixtureList()->SetFriction(0.0f);
    box2d::CouplingDef cdef;
    cdef.categoryMask = kFluidMask;
    box2d::Coupling coupling(world, physics, cdef);
    world.spawnBlob(latticeBlock(world, water, 0.0f, 0.0f, t.cols, t.rows));
    detail::WorldState& state = detail::stateOf(world);

    Support out;
    out.weight = double(body->GetMass()) * kG;
    // Each frame is one round (a World::step of one sub-step) per sub-step (Coupling): per
    // round, its coarse impulse over its length, and its sweeps' pushes on the body's samples
    // (delivered after the velocity stage, as forces over the round).
    const double round = double(kFrame) / double(world.substepsFor(kFrame));
    uint32_t rounds = 0;
    bool measuring = false;
    state.stageProbe = [&](uint32_t stage) {
        if (!measuring) {
            return;
        }
        REQUIRE(state.bodies.size() == 1);
        if (stage == kStageCoarse) {
            out.coarse += state.bodies[0].impulseY / round;
            ++rounds;
        } else if (stage == kStageVelocity) {
            const detail::Samples& w = state.samples;
            for (size_t k = 0; k < w.bodyOf.size(); ++k) {
                out.sweeps += w.bodyOf[k] == 0 ? double(w.fy[k]) : 0.0;
            }
        }
    };
    const float h = world.material(water).smoothingDistance;
    for (int f = 0; f < settle + frames; ++f) {
        measuring = f >= settle;
        coupling.step(world, kFrame);
        if (!measuring) {
            continue;
        }
        // The waterline beside the body, one support radius from it and the walls.
        const Box box = bodyBounds(*body);
        const std::vector<std::pair<double, double>> none;
        const Waterline left = waterline(world, t.s, h, box.x0 - h, none, 0.0);
        const Waterline right = waterline(world, t.s, box.x1 + h, t.width - h, none, 0.0);
        const double level = 0.5 * (left.height + right.height);
        const auto [below, area] = bodyAreaBelow(*body, level);
        out.submerged += below / area / frames;
        out.bottom += box.y0 / frames;
        out.level += level / frames;
    }
    REQUIRE(rounds > 0);
    out.coarse /= rounds;
    out.sweeps /= rounds;
    return out;
}

// The twin: the same tank without the body; its ghost is the water inside x0 < x < x1 above
// y0 (the body's submerged outline as it settled). Per sub-step, the ghost particles' coarse
// moves (cy after the coarse stage), sweep moves (their heights across the sweeps) and
// prediction moves, as forces.
Support ghostSupport(Quality quality, float width, float depth, float x0, float x1, float y0,
                     int settle, int frames) {
    World world(presetDef(quality));
    const MaterialId water = world.addMaterial(fluid::water());
    const Tank t = makeTank(world, water, width, depth);
    world.spawnBlob(latticeBlock(world, water, 0.0f, 0.0f, t.cols, t.rows));
    detail::WorldState& state = detail::stateOf(world);
    const detail::Particles& p = state.particles;
    // Every particle is water: one mass (the per-particle channels fill during the step).
    const double m = world.material(water).mass;
    // The sub-steps are of equal length at 60 Hz.
    const double dt = double(kFrame) / double(world.substepsFor(kFrame));
    std::vector<uint8_t> ghost;
    std::vector<float> before, ended;
    uint32_t substeps = 0, loaded = 0;
    bool measuring = false;
    Support out;
    state.stageProbe = [&](uint32_t stage) {
        if (stage == kStageBoundaries) {
            // Each slot's height at the end of the sub-step (the next prediction's start).
            ended.resize(p.size());
            for (uint32_t i = 0; i < p.size(); ++i) {
                ended[p.slot[i]] = p.py[i];
            }
            return;
        }
        if (!measuring) {
            return;
        }
        double sum = 0.0;
        if (stage == kStagePredict && ended.size() == p.size()) {
            // The prediction's move (velocity, gravity and every force) is the load the
            // solver takes back at rest.
            for (uint32_t i = 0; i < p.size(); ++i) {
                sum += ghost[p.slot[i]] != 0 ? m * double(ended[p.slot[i]] - p.py[i]) : 0.0;
            }
            out.load += sum / (dt * dt);
            ++loaded;
        } else if (stage == kStageCoarse) {
            before.assign(p.py.begin(), p.py.end());
            for (uint32_t i = 0; i < p.size(); ++i) {
                sum += ghost[p.slot[i]] != 0 ? m * double(state.pbfScratch.cy[i]) : 0.0;
            }
            out.coarse += sum / (dt * dt);
            ++substeps;
        } else if (stage == kStageSweeps && before.size() == p.size()) {
            for (uint32_t i = 0; i < p.size(); ++i) {
                sum += ghost[p.slot[i]] != 0 ? m * double(p.py[i] - before[i]) : 0.0;
            }
            out.sweeps += sum / (dt * dt);
        }
    };
    for (int f = 0; f < settle + frames; ++f) {
        if (f == settle) {
            // The ghost: the particles in the body's submerged outline now.
            ghost.assign(p.size(), 0);
            for (uint32_t i = 0; i < p.size(); ++i) {
                if (p.px[i] > x0 && p.px[i] < x1 && p.py[i] > y0) {
                    ghost[p.slot[i]] = 1;
                    out.weight += m * kG;
                }
            }
            measuring = true;
        }
        world.step(kFrame);
    }
    REQUIRE(out.weight > 0.0);
    REQUIRE(substeps > 0);
    REQUIRE(loaded > 0);
    out.coarse /= substeps;
    out.sweeps /= substeps;
    out.load /= loaded;
    return out;
}

} // namespace

TEST_CASE("Floating support: a floating box is carried by its weight at Archimedes' draft, and "
          "its water ghost by its load",
          "[slow][box2d][archimedes][diagnostic]") {
    const Quality quality = GENERATE(Quality::Game, Quality::Precise);
    const char* name = quality == Quality::Game ? "game" : "precise";
    CAPTURE(name);
    // Water 0.2 m deep in a 0.6 m tank; a box 12 spacings wide and 8 tall at half water's
    // density. 4 s to settle, the fifth measured.
    const float width = 0.6f, depth = 0.2f, ratio = 0.5f;
    World probe;
    const float s = probe.spacing(probe.addMaterial(fluid::water()));
    const float hw = 6.0f * s, hh = 4.0f * s;
    const int settle = 240, frames = 60;
    const Support body = bodySupport(quality, width, depth, hw, hh, ratio, settle, frames);
    const float x0 = 0.3f - hw, x1 = 0.3f + hw; // the tank's middle (0.6 m wide to a spacing)
    const Support ghost =
        ghostSupport(quality, width, depth, x0, x1, float(body.bottom), settle, frames);
    const auto percent = [](double part, double whole) { return 100.0 * part / whole; };
    std::printf("[measure] floating support (%s), the box: submerged %.3f (%+.1f%% of its "
                "density ratio), bottom %.4f m, waterline %.4f m; coarse %.1f%%, sweeps %.1f%%, "
                "total %.1f%% of its weight %.3f N\n",
                name, body.submerged, 100.0 * (body.submerged / ratio - 1.0), body.bottom,
                body.level, percent(body.coarse, body.weight), percent(body.sweeps, body.weight),
                percent(body.coarse + body.sweeps, body.weight), body.weight);
    std::printf("[measure] floating support (%s), its water ghost: coarse %.1f%%, sweeps %.1f%%, "
                "total %.1f%% of its load %.3f N (its weight %.3f N)\n",
                name, percent(ghost.coarse, ghost.load), percent(ghost.sweeps, ghost.load),
                percent(ghost.coarse + ghost.sweeps, ghost.load), ghost.load, ghost.weight);
    // At rest each is carried: the water by what its prediction moved it, the body by its
    // weight (5%: a second's mean of a body that still bobs).
    CHECK((ghost.coarse + ghost.sweeps) / ghost.load == Approx(1.0).margin(0.03));
    CHECK((body.coarse + body.sweeps) / body.weight == Approx(1.0).margin(0.05));
    // And it floats at Archimedes' draft: within the float targets' 10% with both presets.
    CHECK(body.submerged / ratio == Approx(1.0).margin(0.10));
}
