// The user-written whirlpool of examples/custom_force.cpp (compiled into this test with
// FLUID_EXAMPLE_NO_MAIN): registered next to the built-ins, it spins a zero-g blob up.
#include "test_support.h"

#include "examples/custom_force.h"

#include <catch2/catch.hpp>

using namespace fluid;
using namespace fluid::test;

TEST_CASE("the whirlpool example registers next to the built-ins", "[unit][plugins][example]") {
    Registry registry;
    registerBuiltinPlugins(registry);
    registerWhirlpool(registry);
    const PluginInfo* info = registry.find("force.whirlpool");
    REQUIRE(info != nullptr);
    CHECK(info->kind == PluginKind::Force);
    bool hasStrength = false;
    for (const ParamDecl& d : info->params) {
        CHECK_FALSE(d.unit.empty());
        CHECK_FALSE(d.description.empty());
        CHECK(d.minValue <= d.defaultValue);
        CHECK(d.defaultValue <= d.maxValue);
        hasStrength = hasStrength || d.name == "strength";
    }
    CHECK(hasStrength);
    CHECK_THROWS_AS(registerWhirlpool(registry), Error);
}

TEST_CASE("the whirlpool makes angular momentum about its centre grow",
          "[unit][plugins][example]") {
    Stopwatch sw("whirlpool 1 s");
    Registry registry;
    registerBuiltinPlugins(registry);
    registerWhirlpool(registry);
    const double cx = 0.3, cy = -0.2;
    const std::vector<ParamValue> params{
        {"cx", cx}, {"cy", cy}, {"strength", 1.0}, {"radius", 0.15}};
    World world; // zero gravity, no walls
    const MaterialId w = world.addMaterial(water());
    world.addForce(registry.createForce("force.whirlpool", params));
    BlobDef blob;
    blob.shape.type = ShapeType::Circle;
    blob.shape.center = {float(cx), float(cy)};
    blob.shape.radius = 0.12f;
    blob.material = w;
    const uint32_t n = world.spawnBlob(blob);
    REQUIRE(n > 300);
    const double mass0 = totalMass(world);

    double previous = angularMomentum(world, cx, cy);
    CHECK(previous == 0.0);
    std::vector<double> checkpoints;
    for (int frame = 1; frame <= 60; ++frame) {
        world.step(kFrame);
        if (frame % 12 == 0) {
            const double l = angularMomentum(world, cx, cy);
            checkpoints.push_back(l);
            CAPTURE(frame, l, previous);
            CHECK(l > previous); // strictly increasing
            previous = l;
        }
    }
    CAPTURE(checkpoints[0], checkpoints[1], checkpoints[2], checkpoints[3], checkpoints[4]);
    CHECK(checkpoints.front() > 0.0); // counter-clockwise for a positive strength
    CHECK(allFinite(world));
    CHECK(world.particleCount() == n);
    CHECK(totalMass(world) == mass0);
    // The blob spins in place: its centre of mass stays near the whirlpool's centre.
    const Bounds b = bounds(world);
    CHECK((b.x0 + b.x1) / 2 == Approx(cx).margin(0.05));
    CHECK((b.y0 + b.y1) / 2 == Approx(cy).margin(0.05));
}
