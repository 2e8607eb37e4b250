// Materials: the seed's Table 4.1 presets, validation messages, the 2D reading (slab depth).
#include <fluid/fluid.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <set>
#include <string_view>

TEST_CASE("presets hold the seed's Table 4.1 exactly", "[unit][material]") {
    const fluid::Material w = fluid::water();
    CHECK(w.mass == 0.013f);
    CHECK(w.restDensity == 1000.0f);
    CHECK(w.viscosity == 3.5f);
    CHECK(w.stiffness == 3.0f);
    CHECK(w.smoothingDistance == 0.032f);
    CHECK(w.kernelParticles == 32.0f);
    CHECK(w.name == "water");

    const fluid::Material y = fluid::yoghurt();
    CHECK(y.mass == 0.014f);
    CHECK(y.restDensity == 1050.0f);
    CHECK(y.viscosity == 20.0f);
    CHECK(y.stiffness == 5.0f);
    CHECK(y.smoothingDistance == 0.04f);
    CHECK(y.kernelParticles == 50.0f);
    CHECK(y.name == "yoghurt");

    CHECK_NOTHROW(fluid::validate(w));
    CHECK_NOTHROW(fluid::validate(y));
}

TEST_CASE("seedYoghurt is Table 4.1's yoghurt alone, and the explicit solver steps it",
          "[unit][material]") {
    const fluid::Material s = fluid::seedYoghurt();
    const fluid::Material y = fluid::yoghurt();
    CHECK(s.name == "seed_yoghurt");
    CHECK_FALSE(fluid::hasYield(s));
    CHECK(fluid::hasYield(y));
    CHECK(s.yieldStress == 0.0f);
    CHECK(s.consistency == 0.0f);
    // Every number but the Herschel-Bulkley law's is the yoghurt preset's (Table 4.1's).
    const std::set<std::string_view> law{"yieldStress", "consistency", "flowIndex",
                                         "shearModulus"};
    for (const fluid::MaterialField& f : fluid::materialFields()) {
        CAPTURE(f.name);
        CHECK((law.count(f.name) != 0 || s.*f.real == y.*f.real));
    }
    CHECK_NOTHROW(fluid::validate(s));

    fluid::WorldDef def;
    def.solver = fluid::Solver::Explicit;
    fluid::World world(def);
    CHECK_THROWS_AS(world.addMaterial(y), fluid::Error);
    const fluid::MaterialId id = world.addMaterial(s);
    CHECK(world.material(id).name == "seed_yoghurt");
}

TEST_CASE("kDefaultDepth gives water its 32 kernel particles", "[unit][material]") {
    const fluid::Material w = fluid::water();
    const float area = fluid::particleArea(w, fluid::kDefaultDepth);
    const double n = 3.14159265358979 * double(w.smoothingDistance) * w.smoothingDistance / area;
    CHECK(n == Approx(32.0).margin(1e-4));
    CHECK(fluid::particleSpacing(w, fluid::kDefaultDepth) == Approx(std::sqrt(area)));
    // Area = m / (rho0 depth): the 2D reading documented in material.h.
    CHECK(area == Approx(0.013 / (1000.0 * fluid::kDefaultDepth)));
    // Yoghurt at the same depth: 48.75 particles (documented), spacing about 0.0100 m.
    const fluid::Material y = fluid::yoghurt();
    const double ny = 3.14159265358979 * 0.04 * 0.04 / fluid::particleArea(y, fluid::kDefaultDepth);
    CHECK(ny == Approx(48.75).margin(0.01));
    CHECK(fluid::particleSpacing(y, fluid::kDefaultDepth) == Approx(0.0100).margin(2e-4));
    CHECK(fluid::WorldDef{}.depth == fluid::kDefaultDepth);
}

TEST_CASE("validate names the field, value, range and unit", "[unit][material]") {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    fluid::Material m = fluid::water();

    SECTION("NaN mass") {
        m.mass = nan;
        CHECK_THROWS_MATCHES(fluid::validate(m), fluid::Error,
                             Catch::Message("material 'water': mass = nan is not finite; expected "
                                            "(0, 1000] (unit: kg)"));
    }
    SECTION("negative mass") {
        m.mass = -0.5f;
        CHECK_THROWS_MATCHES(fluid::validate(m), fluid::Error,
                             Catch::Message("material 'water': mass = -0.5 is out of range "
                                            "(0, 1000] (unit: kg)"));
    }
    SECTION("infinite rest density") {
        m.restDensity = inf;
        CHECK_THROWS_MATCHES(fluid::validate(m), fluid::Error,
                             Catch::Message("material 'water': restDensity = inf is not finite; "
                                            "expected (0, 100000] (unit: kg/m^3)"));
    }
    SECTION("negative viscosity") {
        m.viscosity = -1.0f;
        CHECK_THROWS_MATCHES(fluid::validate(m), fluid::Error,
                             Catch::Message("material 'water': viscosity = -1 is out of range "
                                            "[0, 10000] (unit: Pa*s)"));
    }
    SECTION("zero stiffness (open lower bound)") {
        m.stiffness = 0.0f;
        CHECK_THROWS_MATCHES(fluid::validate(m), fluid::Error,
                             Catch::Message("material 'water': stiffness = 0 is out of range "
                                            "(0, 1e+08] (unit: J/kg)"));
    }
    SECTION("smoothing distance too large") {
        m.smoothingDistance = 20.0f;
        CHECK_THROWS_MATCHES(fluid::validate(m), fluid::Error,
                             Catch::Message("material 'water': smoothingDistance = 20 is out of "
                                            "range [0.003, 0.4] (unit: m)"));
    }
    SECTION("too few kernel particles") {
        m.kernelParticles = 2.0f;
        CHECK_THROWS_MATCHES(fluid::validate(m), fluid::Error,
                             Catch::Message("material 'water': kernelParticles = 2 is out of range "
                                            "[4, 400] (unit: count)"));
    }
    SECTION("negative surface tension, named material") {
        m = fluid::yoghurt();
        m.surfaceTension = -0.5f;
        CHECK_THROWS_MATCHES(fluid::validate(m), fluid::Error,
                             Catch::Message("material 'yoghurt': surfaceTension = -0.5 is out of "
                                            "range [0, 0.5] (unit: m^3/(kg s^2))"));
    }
    SECTION("NaN viscosity") {
        m.viscosity = nan;
        CHECK_THROWS_MATCHES(fluid::validate(m), fluid::Error,
                             Catch::Message("material 'water': viscosity = nan is not finite; "
                                            "expected [0, 10000] (unit: Pa*s)"));
    }
}

TEST_CASE("a world rejects a bad material and keeps its table", "[unit][material]") {
    fluid::World world;
    const fluid::MaterialId w = world.addMaterial(fluid::water());
    fluid::Material bad = fluid::water();
    bad.smoothingDistance = std::numeric_limits<float>::quiet_NaN();
    CHECK_THROWS_AS(world.addMaterial(bad), fluid::Error);
    CHECK(world.materialCount() == 1);
    CHECK_THROWS_AS(world.setMaterial(w, bad), fluid::Error);
    CHECK(world.material(w).smoothingDistance == 0.032f);
    CHECK_THROWS_MATCHES(world.material(fluid::MaterialId{5}), fluid::Error,
                         Catch::Message("unknown material id 5; the world has 1 materials"));
    // Materials replace cleanly.
    world.setMaterial(w, fluid::yoghurt());
    CHECK(world.material(w).name == "yoghurt");
}
