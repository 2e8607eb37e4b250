// The Herschel-Bulkley stress update (fluid/src/yield_law.h) and the yield-stress fields of
// Material: the flow curve it settles on, what it refuses, and the explicit solver's refusal.
#include "../../fluid/src/yield_law.h"

#include "test_support.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <sstream>

using namespace fluid;
using namespace fluid::test;

namespace {

detail::YieldLaw lawOf(float tauY, float k, float n, float g) {
    return detail::makeYieldLaw(true, tauY, k, n, g);
}

/// The shear stress a steady simple shear of `rate` (1/s) settles on (unit: Pa).
float steadyShear(const detail::YieldLaw& law, float rate, float dt = 1e-3f) {
    float a = 0.0f, b = 0.0f;
    for (int k = 0; k < 20000; ++k) {
        // Simple shear v_x = rate y: D'_xy = rate / 2, spin = rate / 2.
        detail::yieldStep(law, 0.0f, 0.5f * rate, 0.5f * rate, dt, a, b);
    }
    return std::hypot(a, b);
}

} // namespace

TEST_CASE("steady shear settles on tau_y + K rate^n", "[unit][yield]") {
    const float n = GENERATE(0.2f, 0.7f, 1.0f, 1.5f);
    const float rate = GENERATE(0.1f, 3.0f, 50.0f);
    CAPTURE(n, rate);
    // Stiff (an elastic strain far below 1), so that the spin turns the stress little: a soft
    // material sheared fast also grows normal stresses, as an upper-convected Maxwell one does.
    const detail::YieldLaw law = lawOf(30.0f, 2.0f, n, 1e6f);
    const float expected = 30.0f + 2.0f * std::pow(rate, n);
    CHECK(steadyShear(law, rate) == Approx(expected).epsilon(1e-3));
}

TEST_CASE("below the yield stress the stress is elastic and stays", "[unit][yield]") {
    const detail::YieldLaw law = lawOf(30.0f, 2.0f, 0.7f, 200.0f);
    float a = 0.0f, b = 0.0f;
    // A shear strain of 0.1 over 0.1 s: 20 Pa, below the yield stress.
    for (int k = 0; k < 100; ++k) {
        detail::yieldStep(law, 0.0f, 0.5f, 0.0f, 1e-3f, a, b);
    }
    CHECK(b == Approx(20.0f).epsilon(1e-4));
    CHECK(a == 0.0f);
    // At rest it keeps it: the material holds its shape.
    for (int k = 0; k < 1000; ++k) {
        detail::yieldStep(law, 0.0f, 0.0f, 0.0f, 1e-3f, a, b);
    }
    CHECK(b == Approx(20.0f).epsilon(1e-4));
    // A rigid rotation turns the stress with the material and keeps its size.
    const float before = std::hypot(a, b);
    for (int k = 0; k < 1000; ++k) {
        detail::yieldStep(law, 0.0f, 0.0f, 1.0f, 1e-4f, a, b);
    }
    CHECK(std::hypot(a, b) == Approx(before).epsilon(1e-3));
    CHECK(std::fabs(a) > 1.0f);
}

TEST_CASE("the stress update stays finite at extreme parameters", "[unit][yield]") {
    const float tauY = GENERATE(0.0f, 1e-3f, 30.0f, 1e4f, 1e5f);
    const float k = GENERATE(0.0f, 1e-3f, 4.0f, 1e4f);
    const float n = GENERATE(0.1f, 0.2f, 1.5f, 2.0f);
    const float rate = GENERATE(0.0f, 1e-6f, 1.0f, 1e4f);
    CAPTURE(tauY, k, n, rate);
    const detail::YieldLaw law = lawOf(tauY, k, n, 1e6f);
    float a = 0.0f, b = 0.0f;
    for (int step = 0; step < 50; ++step) {
        detail::yieldStep(law, 0.3f * rate, 0.5f * rate, 0.2f * rate, 1e-3f, a, b);
        REQUIRE(std::isfinite(a));
        REQUIRE(std::isfinite(b));
        // Bounded by the flow curve at the applied rate (2 |D'|); the spin's normal stresses
        // add to it, but never double it.
        const float applied = 2.0f * std::hypot(0.3f * rate, 0.5f * rate);
        REQUIRE(std::hypot(a, b) <= 2.0f * (tauY + k * std::pow(applied, n)) + 1e-3f);
    }
    // A non-finite rate leaves no NaN stress behind.
    const float nan = std::numeric_limits<float>::quiet_NaN();
    detail::yieldStep(law, nan, 0.0f, 0.0f, 1e-3f, a, b);
    CHECK(a == 0.0f);
    CHECK(b == 0.0f);
}

TEST_CASE("yield-stress fields: validation and the explicit solver's refusal", "[unit][yield]") {
    Material m = yoghurt();
    CHECK(m.yieldStress == 400.0f);
    CHECK(m.consistency == 2.0f);
    CHECK(m.flowIndex == 0.7f);
    CHECK(m.shearModulus == 0.0f);
    CHECK(hasYield(m));
    CHECK_FALSE(hasYield(water()));

    m.flowIndex = 0.05f;
    CHECK_THROWS_WITH(validate(m), "material 'yoghurt': flowIndex = 0.05 is out of range [0.1, "
                                   "2] (unit: 1)");
    m = yoghurt();
    m.yieldStress = -1.0f;
    CHECK_THROWS_WITH(validate(m), "material 'yoghurt': yieldStress = -1 is out of range [0, "
                                   "100000] (unit: Pa)");
    m = yoghurt();
    m.consistency = std::numeric_limits<float>::quiet_NaN();
    CHECK_THROWS_WITH(validate(m), "material 'yoghurt': consistency = nan is not finite; "
                                   "expected [0, 10000] (unit: Pa*s^n)");

    WorldDef def;
    def.solver = Solver::Explicit;
    World world(def);
    CHECK_THROWS_WITH(world.addMaterial(yoghurt()),
                      "World::addMaterial: material 'yoghurt' has a Herschel-Bulkley flow law "
                      "(yieldStress = 400 Pa, consistency = 2 Pa*s^n), which the explicit solver "
                      "does not step; use Solver::PositionBased, or set yieldStress and "
                      "consistency to 0");
    Material newtonian = yoghurt();
    newtonian.yieldStress = 0.0f;
    newtonian.consistency = 0.0f;
    const MaterialId id = world.addMaterial(newtonian);
    CHECK_THROWS_WITH(world.setMaterial(id, yoghurt()),
                      "World::setMaterial: material 'yoghurt' has a Herschel-Bulkley flow law "
                      "(yieldStress = 400 Pa, consistency = 2 Pa*s^n), which the explicit solver "
                      "does not step; use Solver::PositionBased, or set yieldStress and "
                      "consistency to 0");
    CHECK(world.material(id).yieldStress == 0.0f);
}

TEST_CASE("a snapshot carries the stress: a yoghurt world continues bit-identically",
          "[unit][yield][snapshot]") {
    WorldDef def;
    def.workerCount = 1;
    World world(def);
    const MaterialId y = world.addMaterial(yoghurt());
    world.addForce(std::make_unique<GravityForce>(0.0f, -kG));
    world.addBoundary(std::make_unique<BoxContainer>(0.0f, 0.0f, 0.4f, 0.4f));
    world.spawnBlob(latticeBlock(world, y, 0.0f, 0.0f, 12, 12));
    for (int k = 0; k < 20; ++k) {
        world.step(kFrame);
    }
    std::stringstream bytes;
    world.save(bytes);
    Registry registry;
    registerBuiltinPlugins(registry);
    World back = World::load(bytes, registry, 1);
    for (int k = 0; k < 20; ++k) {
        world.step(kFrame);
        back.step(kFrame);
    }
    CHECK(stateHash(back) == stateHash(world));
}
