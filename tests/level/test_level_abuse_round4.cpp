// Bodies the fluid would throw (pointed polygons thinner than a spacing, bodies much lighter than
// the liquid) refused by the level loader with the smallest that works; the rest step calmly.
// docs/box2d.md, "Shapes and masses".
#include "level_support.h"

#include <fluid/box2d/shapes.h>
#include <fluid/level.h>

#include <box2d/box2d.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <sstream>

using namespace fluid;
using namespace fluid::test;

namespace {

// Water 0.2 m deep in a 1 m Box2D tank (static walls, "fluid": false), one dynamic body `b`
// with `fixture` at `position`.
std::string bodyTank(const std::string& fixture, const std::string& position = "[0.45, 0.25]",
                     const std::string& quality = "game") {
    return R"({"version": 1, "world": {"gravity": [0, -9.81], "maxParticles": 20000, "quality": ")" +
           quality + R"("},
 "materials": [{"name": "water", "preset": "water"}],
 "plugins": [{"type": "boundary.box", "params": {"minX": 0, "minY": 0, "maxX": 1, "maxY": 1, "openTop": 1}}],
 "blobs": [{"material": "water", "shape": "box", "min": [0, 0], "max": [1, 0.2]}],
 "bodies": [{"name": "tank", "type": "static", "fluid": false, "fixtures": [
   {"shape": "box", "width": 1.2, "height": 0.1, "center": [0.5, -0.05]},
   {"shape": "box", "width": 0.1, "height": 1.1, "center": [-0.05, 0.5]},
   {"shape": "box", "width": 0.1, "height": 1.1, "center": [1.05, 0.5]}]},
  {"name": "b", "position": )" +
           position + R"(, "fixtures": [)" + fixture + R"(]}]})";
}

std::string triangle(double base, double height, double ratio) {
    std::ostringstream s;
    s << R"({"shape": "polygon", "vertices": [[0, 0], [)" << base << ", 0], [" << base / 2 << ", "
      << height << R"(]], "densityRatio": )" << ratio << "}";
    return s.str();
}

} // namespace

TEST_CASE("level bodies: a pointed polygon thinner than the fluid's spacing is refused",
          "[level][bodies][abuse]") {
    // The wedge that spun up to Box2D's limits in 30 frames (480 m/s, 377 rad/s).
    CHECK(errorOf(bodyTank(triangle(0.1, 0.005, 0.5))) ==
          "t.json:9:90: at /bodies/1/fixtures/0/vertices/0: the corner at vertex 0 is 5.71 "
          "degrees and the polygon holds a circle of radius 0.00249 m at most; a dynamic body's "
          "polygon with a corner under 90 degrees must hold one of the fluid's spacing, 0.01 m, "
          "or the fluid throws it (make it larger or blunter, a box or a circle, or the body "
          "static or kinematic)");
    // The family: triangles whose inscribed circle is under a spacing, whatever their corners
    // (every one of these spun up or left the water in game or precise), are refused; those
    // that hold one are not.
    struct Case {
        double base, height;
        bool refused;
    };
    for (const Case c : {Case{0.1, 0.0006, true}, Case{0.1, 0.01, true}, Case{0.1, 0.0182, true},
                         Case{0.05, 0.0144, true}, Case{0.05, 0.021, true}, Case{0.03, 0.015, true},
                         Case{0.05, 0.025, false}, Case{0.1, 0.05, false}, Case{0.3, 0.1, false}}) {
        CAPTURE(c.base, c.height);
        const std::string error = errorOf(bodyTank(triangle(c.base, c.height, 0.5)));
        CHECK((error.find("must hold one of the fluid's spacing") != std::string::npos) ==
              c.refused);
        if (!c.refused) {
            CHECK(error == "no error");
        }
    }
    // Right angles are not pointed: a box 5 mm thin steps calmly, and so does a 5 mm circle.
    CHECK(errorOf(bodyTank(
              R"({"shape": "box", "width": 0.1, "height": 0.005, "densityRatio": 0.5})")) ==
          "no error");
    CHECK(errorOf(bodyTank(R"({"shape": "circle", "radius": 0.005, "densityRatio": 0.5})")) ==
          "no error");
    // Static and kinematic bodies, and dry ones, may be pointed: the fluid does not move them.
    for (const char* kind :
         {R"("type": "static", )", R"("type": "kinematic", )", R"("fluid": false, )"}) {
        CAPTURE(kind);
        std::string text = bodyTank(triangle(0.1, 0.005, 0.5));
        text.replace(text.find(R"({"name": "b", )"), 14, std::string(R"({"name": "b", )") + kind);
        CHECK(errorOf(text) == "no error");
    }
    // The shared check, as the C API and the coupling run it.
    const std::vector<glm::vec2> wedge{{0.0f, 0.0f}, {0.1f, 0.0f}, {0.05f, 0.005f}};
    CHECK(box2d::inscribedRadius(wedge) == Approx(0.0024938).epsilon(1e-3));
    const std::vector<glm::vec2> square{{0.0f, 0.0f}, {0.1f, 0.0f}, {0.1f, 0.1f}, {0.0f, 0.1f}};
    CHECK(box2d::inscribedRadius(square) == Approx(0.05).epsilon(1e-6));
    CHECK_FALSE(
        box2d::checkPointedPolygon(square, 0.2f)); // right angles: no inscribed circle asked
    CHECK(box2d::checkPointedPolygon(wedge, 0.01f).vertex == 0);
}

TEST_CASE("level bodies: a body lighter than kMinDensityRatio of the liquid is refused",
          "[level][bodies][abuse]") {
    for (const double ratio : {1e-4, 1e-3, 0.01, 0.049}) {
        CAPTURE(ratio);
        std::ostringstream fixture;
        fixture << R"({"shape": "box", "width": 0.02, "height": 0.02, "densityRatio": )" << ratio
                << "}";
        CHECK_THAT(errorOf(bodyTank(fixture.str(), "[0.5, 0.21]")),
                   Catch::StartsWith("t.json:9:54: at /bodies/1/fixtures: the fixtures weigh ") &&
                       Catch::Contains("a dynamic body needs at least 0.05 of it "
                                       "(kMinDensityRatio), or the fluid throws it: raise their "
                                       "density to 6.47 kg/m^2 or more"));
    }
    CHECK(
        errorOf(bodyTank(R"({"shape": "box", "width": 0.02, "height": 0.02, "densityRatio": 0.05})",
                         "[0.5, 0.21]")) == "no error");
}

TEST_CASE("level bodies: the lightest and the most pointed bodies allowed ride the water calmly",
          "[level][bodies][abuse][slow]") {
    // At the floors (kMinDensityRatio; a triangle whose inscribed circle is just over a spacing)
    // in both presets: dropped from a few centimetres, no faster than the drop made them and no
    // energy gained by the water.
    struct Case {
        std::string fixture, position;
    };
    const Case cases[] = {
        {R"({"shape": "box", "width": 0.02, "height": 0.02, "densityRatio": 0.05})", "[0.5, 0.23]"},
        {triangle(0.05, 0.025, 0.05), "[0.45, 0.25]"},
        {triangle(0.05, 0.025, 0.25), "[0.45, 0.25]"},
        {triangle(0.1, 0.05, 0.5), "[0.45, 0.25]"},
    };
    for (const char* quality : {"game", "precise"}) {
        for (const Case& c : cases) {
            CAPTURE(quality, c.fixture);
            Level level =
                parseLevel(bodyTank(c.fixture, c.position, quality), "t.json", builtins());
            b2Body* body = level.bodies.back().second;
            double fastest = 0.0, spin = 0.0, energy = 0.0;
            const float mass = level.world.material(level.materials[0].second).mass;
            for (int frame = 0; frame < 180; ++frame) {
                level.step();
                fastest = std::max(fastest, double(body->GetLinearVelocity().Length()));
                spin = std::max(spin, double(std::abs(body->GetAngularVelocity())));
                if (frame >= 120) {
                    double e = 0.0;
                    const auto vx = level.world.velocityX(), vy = level.world.velocityY();
                    for (uint32_t i = 0; i < level.world.particleCount(); ++i) {
                        e += 0.5 * mass * (vx[i] * vx[i] + vy[i] * vy[i]);
                    }
                    energy = std::max(energy, e);
                }
            }
            CHECK(fastest < 1.5);                // m/s: the drop gives about 0.9
            CHECK(spin < 25.0);                  // rad/s: a rocking, not a spin-up (377 before)
            CHECK(energy < 0.1);                 // J in the last second: the water settles
            CHECK(body->GetPosition().y > 0.1f); // it floats (or rests) in the water
        }
    }
}
