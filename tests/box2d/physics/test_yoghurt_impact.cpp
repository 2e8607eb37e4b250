// Issue 47, target 3: yoghurt flows when a crate hits it and comes to rest again. A crate as
// dense as the paste, thrown down onto a rested layer of the yoghurt preset (400 Pa, the shear
// constraint, the game preset), pushes paste aside as it lands and stays in the dent it made.
//
// Issue 67: every landing comes to rest, the crate under 1 cm/s after 5 s. Over the seven throws
// at three places (scripts/readings.sh, `landing/`) the crate moves at 0.0-0.6 mm/s and the
// paste at 2.8e-8 to 3.4e-7 J/kg (docs/notes/bodies_coarse_solve.md, "Open nodes"; before the
// coarse solve's nodes opened by degrees, up to 4.3 mm/s and 1.5e-6 J/kg). So this test asserts the
// flow, the dent and the crate's rest for every landing, the paste's rest (under 1e-6 J/kg with the
// crate under 5 mm/s) for five of the seven; the fastest let a particle or two into the crate for a
// moment.
#include "box2d_support.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace fluid;
using namespace fluid::test;

namespace {

struct Landing {
    uint32_t pushed = 0, inside = 0;
    float depth = 0.0f, settled = 0.0f, speed = 0.0f, spin = 0.0f;
    double rest = 0.0;
    bool finite = false, kept = false;
};

// The game preset's world with a tank 0.8 m wide and a rested layer of the yoghurt preset, 70 x 10
// spacings (0.81 x 0.12 m), coupled to Box2D and settled for 1 s: the scene every case here
// drops or sets its crate into.
struct RestedLayer {
    static WorldDef gameDef() {
        WorldDef def = physicsDef();
        def.positionBased = positionBasedPreset(Quality::Game);
        return def;
    }
    // The material, the tank and the layer, before the coupling is made.
    struct Layer {
        MaterialId yog;
        float width = 0.0f;
        uint32_t count = 0;
    };
    static Layer fill(World& world) {
        Layer l;
        l.yog = world.addMaterial(fluid::yoghurt());
        l.width = 70.0f * world.spacing(l.yog);
        world.addForce(std::make_unique<GravityForce>(0.0f, -kG));
        world.addBoundary(std::make_unique<BoxContainer>(0.0f, 0.0f, l.width, 1.0f));
        BlobDef layer = latticeBlock(world, l.yog, 0.0f, 0.0f, 70, 10);
        layer.structure = 1.0f;
        l.count = world.spawnBlob(layer);
        return l;
    }

    World world{gameDef()};
    Layer layer = fill(world);
    b2World physics{b2Vec2(0.0f, -kG)};
    box2d::Coupling coupling{world, physics};
    float surface = 0.0f; // the layer's top after settling (m)

    RestedLayer() {
        for (int f = 0; f < 60; ++f) { // 1 s to settle
            coupling.step(world, kFrame);
        }
        surface = bounds(world).y1;
    }
};

// The crate thrown down at `throwSpeed` (m/s) onto the rested layer, its centre `offset` (m)
// right of the tank's middle; 1 s of impact, 4 s more.
Landing land(float throwSpeed, float offset = 0.0f) {
    RestedLayer scene;
    World& world = scene.world;
    b2World& physics = scene.physics;
    box2d::Coupling& coupling = scene.coupling;
    const uint32_t count = scene.layer.count;
    REQUIRE(count == 700);
    const float width = scene.layer.width, surface = scene.surface;
    std::vector<glm::vec2> before(count);
    for (uint32_t i = 0; i < count; ++i) {
        before[i] = world.position(world.handleAt(i));
    }
    // A 0.16 x 0.08 m crate as dense as the paste, its base 0.2 m over the surface: even a
    // crate let fall lands at 2 m/s, a dynamic pressure rho v^2 / 2 of 2 kPa, five times the
    // yield stress.
    const float rho = box2d::arealDensity(world, scene.layer.yog);
    b2Body* crate = addBox(physics, b2_dynamicBody, {0.5f * width + offset, surface + 0.24f}, 0.08f,
                           0.04f, rho);
    crate->SetLinearVelocity({0.0f, -throwSpeed});
    Landing out;
    for (int f = 0; f < 60; ++f) { // 1 s: the impact
        coupling.step(world, kFrame);
        out.inside = std::max(out.inside, intrusion(world, physics).count);
    }
    for (uint32_t i = 0; i < count; ++i) {
        const glm::vec2 d = world.position(world.handleAt(i)) - before[i];
        out.pushed += std::hypot(d.x, d.y) > 0.02f ? 1 : 0;
    }
    out.depth = surface - (crate->GetPosition().y - 0.04f);
    for (int f = 0; f < 240; ++f) { // 4 s more
        coupling.step(world, kFrame);
        out.inside = std::max(out.inside, intrusion(world, physics).count);
    }
    out.settled = surface - (crate->GetPosition().y - 0.04f);
    out.rest = kineticPerMass(world);
    out.speed = crate->GetLinearVelocity().Length();
    out.spin = std::abs(crate->GetAngularVelocity());
    out.finite = allFinite(world);
    out.kept = world.particleCount() == count;
    return out;
}

} // namespace

TEST_CASE("a crate dropped on yoghurt pushes the paste aside and stays in its dent",
          "[slow][box2d][yield][shear]") {
    Stopwatch sw("yoghurt hit by a crate, seven landings");
    uint32_t resting = 0;
    for (const float throwSpeed : {0.5f, 0.8f, 1.0f, 1.2f, 1.5f, 2.0f, 3.0f}) {
        const Landing l = land(throwSpeed);
        std::printf("[measure] yoghurt hit by a crate thrown at %.1f m/s: %u of 700 particles "
                    "pushed over 2 cm; the crate's base %.3f m under the surface 1 s after the "
                    "drop, %.3f m after 5 s; the paste at %.3g J/kg, the crate at %.4f m/s and "
                    "%.4f rad/s after 5 s; %u particles inside it at most\n",
                    throwSpeed, l.pushed, l.depth, l.settled, l.rest, l.speed, l.spin, l.inside);
        CAPTURE(throwSpeed, l.pushed, l.depth, l.settled, l.rest, l.speed, l.inside);
        CHECK(l.kept);
        CHECK(l.finite);
        CHECK(l.pushed >= 100);                        // the impact made the paste flow
        CHECK(l.depth > 0.01f);                        // the crate went into the paste
        CHECK(l.settled < 0.08f);                      // but not through it
        CHECK(std::abs(l.settled - l.depth) < 0.005f); // and stays in its dent
        CHECK(l.rest < 3e-6);                          // the paste still
        CHECK(l.speed < 0.01f);                        // and the crate at rest
        CHECK(l.inside <= 2);
        resting += l.rest < 1e-6 && l.speed < 0.005f ? 1 : 0;
    }
    CHECK(resting >= 5);
}

// Not run by ctest (hidden): the seven landings with the crate also 7 and 13 mm right of the
// middle, for scripts/readings.sh: whether a landing comes to rest by 5 s moves with any change
// of the solver's bits (docs/notes/shear_constraint.md, "Hit by a crate").
TEST_CASE("readings: seven crate landings on yoghurt at three places", "[.readings]") {
    for (const float offset : {0.0f, 0.007f, 0.013f}) {
        for (const float throwSpeed : {0.5f, 0.8f, 1.0f, 1.2f, 1.5f, 2.0f, 3.0f}) {
            const Landing l = land(throwSpeed, offset);
            const int mm = int(std::lround(1000.0f * offset));
            std::printf("[reading] landing/offset=%dmm/throw=%.1f/crate-speed-mm/s %.1f\n", mm,
                        double(throwSpeed), 1000.0 * double(l.speed));
            std::printf("[reading] landing/offset=%dmm/throw=%.1f/paste-J/kg %.2g\n", mm,
                        double(throwSpeed), l.rest);
        }
    }
}

namespace {

struct SetDown {
    double rmsSpeed = 0.0; // m/s, over the last 2 s
    float range = 0.0f;    // m, its height's over the last 2 s
};

// A crate of `density` x the paste's set down on the rested layer (its base 5 mm over the
// surface, at rest), `offset` (m) right of the middle; 2 s to settle, 2 s read frame by frame.
SetDown setDown(float density, float offset) {
    RestedLayer scene;
    const float rho = density * box2d::arealDensity(scene.world, scene.layer.yog);
    b2Body* crate =
        addBox(scene.physics, b2_dynamicBody,
               {0.5f * scene.layer.width + offset, scene.surface + 0.045f}, 0.08f, 0.04f, rho);
    double squares = 0.0;
    float low = 1e9f, high = -1e9f;
    for (int f = 0; f < 240; ++f) {
        scene.coupling.step(scene.world, kFrame);
        if (f >= 120) {
            squares += double(crate->GetLinearVelocity().LengthSquared());
            low = std::min(low, crate->GetPosition().y);
            high = std::max(high, crate->GetPosition().y);
        }
    }
    return {std::sqrt(squares / 120.0), high - low};
}

} // namespace

// Issue 67: a crate set down on the paste's surface (not thrown into it) comes to rest on it.
// It shook (RMS speed 2.4-19 mm/s over seconds 2-4, its height over up to 1.3 mm) while the
// coarse solve's push on it stepped by a third of its weight from one round to the next, as a
// node under it became the body's and back, and as the grid's top row, which ended at the
// particles, came and went through the crate; and while the coupling cut the steady force it
// was owed whenever its tiny speed pointed up (docs/notes/bodies_coarse_solve.md, "Open
// nodes"): now 0.1-0.3 mm/s. A crate half as dense as the paste chatters sideways at 8-9 mm/s
// (the readings below; same note).
TEST_CASE("a crate as dense as the paste, or twice as dense, set down on it comes to rest",
          "[slow][box2d][yield][shear]") {
    Stopwatch sw("yoghurt, crates set down");
    for (const float offset : {0.0f, 0.007f}) {
        for (const float density : {1.0f, 2.0f}) {
            const SetDown s = setDown(density, offset);
            std::printf("[measure] a crate of %.1f x the paste's density set down %.0f mm right "
                        "of the middle: RMS speed %.2f mm/s over seconds 2-4, its height within "
                        "%.3f mm\n",
                        double(density), 1000.0 * double(offset), 1000.0 * s.rmsSpeed,
                        1000.0 * double(s.range));
            CAPTURE(offset, density, s.rmsSpeed, s.range);
            CHECK(s.rmsSpeed < 0.01); // at rest: under 1 cm/s
            CHECK(s.range < 0.0005f); // and still: its height within half a millimetre
        }
    }
}

// Not run by ctest (hidden), for scripts/readings.sh: the set-down crates, with one half as
// dense as the paste, which still chatters (docs/notes/bodies_coarse_solve.md, "Open nodes").
TEST_CASE("readings: a crate set down on yoghurt", "[.readings]") {
    for (const float offset : {0.0f, 0.007f}) {
        for (const float density : {0.5f, 1.0f, 2.0f}) {
            const SetDown s = setDown(density, offset);
            const int mm = int(std::lround(1000.0f * offset));
            std::printf("[reading] set-down/offset=%dmm/density=%.1f/crate-rms-mm/s %.1f\n", mm,
                        double(density), 1000.0 * s.rmsSpeed);
            std::printf("[reading] set-down/offset=%dmm/density=%.1f/height-range-mm %.2f\n", mm,
                        double(density), 1000.0 * double(s.range));
        }
    }
}
