// fluid tests — Box2D bodies, joints and coupling settings in level files: every error class with
// its exact message (file, line, column, JSON pointer), and what a valid file builds (body types,
// masses from density and densityRatio, fixtures, joints, gravity, the coupling's settings).
// Columns are 1-based bytes; texts stay on one line so that columns can be counted.
#include <catch2/catch.hpp>

#include "level_support.h"

#include <fluid/level.h>

#include <box2d/box2d.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

using namespace fluid;
using namespace fluid::test;

namespace {

// A level with one material and the bodies `bodies` (the array's contents); `extra` follows the
// array (starting with ", "). The bodies array opens at column 59, its first body at 60.
std::string withBodies(const std::string& bodies, const std::string& extra = "") {
    return R"({"version": 1, "materials": [{"name": "water"}], "bodies": [)" + bodies + "]" +
           extra + "}";
}

// A dynamic body with one fixture `fixture` (the fixture object's contents).
std::string withFixture(const std::string& fixture) {
    return withBodies(R"({"fixtures": [{)" + fixture + "}]}");
}

// A valid dynamic ball, for levels that need a body but test something else.
const std::string kBall =
    R"({"name": "ball", "fixtures": [{"shape": "circle", "radius": 0.1, "density": 9}]})";

std::vector<const b2Fixture*> fixturesOf(const b2Body* body) {
    std::vector<const b2Fixture*> out;
    for (const b2Fixture* f = body->GetFixtureList(); f != nullptr; f = f->GetNext()) {
        out.push_back(f);
    }
    std::reverse(out.begin(), out.end()); // Box2D lists the newest first: back to file order
    return out;
}

} // namespace

TEST_CASE("level bodies: errors in a body name the key, value and range", "[level][bodies]") {
    CHECK(errorOf(withBodies(R"({"fixtures": [], "mass": 1})")) ==
          "t.json:1:78: at /bodies/0/mass: unknown key 'mass'; allowed: name, type, position, "
          "angle, velocity, angularVelocity, linearDamping, angularDamping, fixedRotation, bullet, "
          "fluid, contacts, fixtures");
    CHECK(errorOf(withBodies(R"({"type": "ghost", "fixtures": []})")) ==
          "t.json:1:70: at /bodies/0/type: unknown body type 'ghost'; known: static, kinematic, "
          "dynamic");
    CHECK(codeOf(withBodies(R"({"type": "ghost", "fixtures": []})")) == ErrorCode::UnknownName);
    CHECK(codeOf(withBodies(R"({"fixtures": [], "mass": 1})")) == ErrorCode::BadFile);
    CHECK(errorOf(withBodies(R"({"position": "here", "fixtures": []})")) ==
          "t.json:1:74: at /bodies/0/position: expected a point [x, y] of two numbers in [-100000, "
          "100000] (unit: m), got a string");
    CHECK(
        errorOf(withBodies(R"({"position": [0, 2e5], "fixtures": []})")) ==
        "t.json:1:78: at /bodies/0/position/1: 200000 is out of range [-100000, 100000] (unit: m)");
    CHECK(errorOf(withBodies(R"({"angle": 1e999, "fixtures": []})")) ==
          "t.json:1:71: at /bodies/0/angle: 1e999 is not finite (it overflows a double); expected "
          "a finite number");
    CHECK(errorOf(withBodies(R"({"angularVelocity": -2000, "fixtures": []})")) ==
          "t.json:1:81: at /bodies/0/angularVelocity: -2000 is out of range [-1000, 1000] (unit: "
          "rad/s)");
    CHECK(errorOf(withBodies(R"({"linearDamping": -1, "fixtures": []})")) ==
          "t.json:1:79: at /bodies/0/linearDamping: -1 is out of range [0, 1000] (unit: 1/s)");
    CHECK(errorOf(withBodies(R"({"bullet": 1, "fixtures": []})")) ==
          "t.json:1:72: at /bodies/0/bullet: expected true or false, got a number");
    CHECK(errorOf(withBodies(R"({"name": "", "fixtures": []})")) ==
          "t.json:1:70: at /bodies/0/name: expected a non-empty name");
    CHECK(errorOf(withBodies(R"({"type": "static"})")) ==
          "t.json:1:61: at /bodies/0: missing key 'fixtures'; expected an array of at least one "
          "fixture");
    CHECK(errorOf(withBodies(R"({"fixtures": []})")) ==
          "t.json:1:74: at /bodies/0/fixtures: expected at least one fixture, got an empty array");
    CHECK(errorOf(withBodies(R"({"fixtures": {}})")) ==
          "t.json:1:74: at /bodies/0/fixtures: expected an array of fixtures, got an object");
    CHECK(errorOf(withBodies(R"(7)")) ==
          "t.json:1:61: at /bodies/0: expected a body (an object), got a number");
    CHECK(errorOf(R"({"version": 1, "materials": [{"name": "water"}], "bodies": {}})") ==
          "t.json:1:60: at /bodies: expected an array of bodies, got an object");
    // A static body does not move.
    CHECK(
        errorOf(withBodies(
            R"({"type": "static", "velocity": [1, 0], "fixtures": [{"shape": "circle", "radius": 1}]})")) ==
        "t.json:1:92: at /bodies/0/velocity: a static body does not move; give it type 'kinematic' "
        "(moved by its velocity) or 'dynamic'");
    CHECK(
        errorOf(withBodies(
            R"({"type": "static", "angularVelocity": 1, "fixtures": [{"shape": "circle", "radius": 1}]})")) ==
        "t.json:1:99: at /bodies/0/angularVelocity: a static body does not move; give it type "
        "'kinematic' (moved by its velocity) or 'dynamic'");
}

TEST_CASE("level bodies: names are unique, unnamed bodies are body<k>", "[level][bodies]") {
    CHECK(errorOf(withBodies(kBall + ", " + kBall)) ==
          "t.json:1:152: at /bodies/1/name: duplicate body name 'ball' (first used at "
          "/bodies/0/name); names must be unique");
    // The second body is "body1" unnamed: a body named so clashes with it.
    CHECK(
        errorOf(withBodies(
            kBall +
            R"(, {"fixtures": [{"shape": "circle", "radius": 0.1, "density": 9}]}, {"name": "body1", "fixtures": [{"shape": "circle", "radius": 0.1, "density": 9}]})")) ==
        "t.json:1:218: at /bodies/2/name: duplicate body name 'body1' (first used at /bodies/1); "
        "names must be unique");
}

TEST_CASE("level bodies: fixture shapes, sizes and settings are checked", "[level][bodies]") {
    CHECK(errorOf(withFixture(R"("shape": "star")")) ==
          "t.json:1:85: at /bodies/0/fixtures/0/shape: unknown shape 'star'; known: box, circle, "
          "polygon, edge, chain");
    CHECK(errorOf(withFixture(R"("radius": 1)")) ==
          "t.json:1:75: at /bodies/0/fixtures/0: missing key 'shape'; expected a shape: box, "
          "circle, polygon, edge or chain");
    CHECK(errorOf(withFixture(
              R"("shape": "box", "width": 1, "height": 1, "radius": 1, "density": 1)")) ==
          "t.json:1:117: at /bodies/0/fixtures/0/radius: unknown key 'radius'; allowed: shape, "
          "friction, restitution, width, height, center, angle, density, densityRatio");
    CHECK(
        errorOf(withFixture(R"("shape": "box", "width": 0, "height": 1, "density": 1)")) ==
        "t.json:1:101: at /bodies/0/fixtures/0/width: 0 is out of range [0.005, 10000] (unit: m)");
    CHECK(errorOf(withFixture(R"("shape": "box", "width": 1, "height": 20000, "density": 1)")) ==
          "t.json:1:114: at /bodies/0/fixtures/0/height: 20000 is out of range [0.005, 10000] "
          "(unit: m)");
    CHECK(errorOf(withFixture(R"("shape": "box", "height": 1, "density": 1)")) ==
          "t.json:1:75: at /bodies/0/fixtures/0: missing key 'width'; expected a number in [0.005, "
          "10000] (unit: m)");
    CHECK(errorOf(withFixture(
              R"("shape": "box", "width": 1, "height": 1, "center": [2e4, 0], "density": 1)")) ==
          "t.json:1:128: at /bodies/0/fixtures/0/center/0: 20000 is out of range [-10000, 10000] "
          "(unit: m)");
    CHECK(errorOf(withFixture(R"("shape": "circle", "radius": 0.001, "density": 1)")) ==
          "t.json:1:105: at /bodies/0/fixtures/0/radius: 0.001 is out of range [0.005, 10000] "
          "(unit: m)");
    CHECK(errorOf(withFixture(R"("shape": "circle", "radius": 1, "density": 9, "friction": -1)")) ==
          "t.json:1:134: at /bodies/0/fixtures/0/friction: -1 is out of range [0, 1000] (unit: 1)");
    CHECK(
        errorOf(
            withFixture(R"("shape": "circle", "radius": 1, "density": 9, "restitution": 1.5)")) ==
        "t.json:1:137: at /bodies/0/fixtures/0/restitution: 1.5 is out of range [0, 1] (unit: 1)");
    CHECK(errorOf(withFixture(R"("shape": "circle", "radius": 1, "density": -1)")) ==
          "t.json:1:119: at /bodies/0/fixtures/0/density: -1 is out of range [0, 1000000] (unit: "
          "kg/m^2)");
    CHECK(errorOf(withFixture(R"("shape": "circle", "radius": 1, "densityRatio": 2000)")) ==
          "t.json:1:124: at /bodies/0/fixtures/0/densityRatio: 2000 is out of range [0, 1000] "
          "(unit: 1)");
}

TEST_CASE("level bodies: densities: exactly one of density and densityRatio, and mass",
          "[level][bodies]") {
    CHECK(errorOf(withFixture(R"("shape": "circle", "radius": 1)")) ==
          "t.json:1:75: at /bodies/0/fixtures/0: missing the density of a dynamic body's fixture; "
          "expected 'density' (kg/m^2) or 'densityRatio' (1, a multiple of the first material's "
          "areal density)");
    CHECK(errorOf(
              withFixture(R"("shape": "circle", "radius": 1, "densityRatio": 1, "density": 1)")) ==
          "t.json:1:127: at /bodies/0/fixtures/0/density: expected only one of 'density', "
          "'densityRatio'; 'densityRatio' is given too");
    CHECK(errorOf(
              withFixture(R"("shape": "circle", "radius": 1, "density": 9, "densityRatio": 1)")) ==
          "t.json:1:122: at /bodies/0/fixtures/0/densityRatio: expected only one of 'density', "
          "'densityRatio'; 'density' is given too");
    CHECK(errorOf(withFixture(R"("shape": "edge", "from": [0, 0], "to": [1, 0], "density": 1)")) ==
          "t.json:1:123: at /bodies/0/fixtures/0/density: an edge has no area, hence no mass: "
          "'density' applies to box, circle and polygon");
    // A dynamic body whose fixtures have no mass: Box2D would silently make it 1 kg.
    CHECK(errorOf(withFixture(R"("shape": "edge", "from": [0, 0], "to": [1, 0])")) ==
          "t.json:1:74: at /bodies/0/fixtures: a dynamic body needs mass: expected a box, circle "
          "or polygon fixture with a density above 0");
    CHECK(errorOf(withFixture(R"("shape": "circle", "radius": 1, "density": 0)")) ==
          "t.json:1:74: at /bodies/0/fixtures: a dynamic body needs mass: expected a box, circle "
          "or polygon fixture with a density above 0");
    // So light that Box2D's inverse mass would overflow or the fluid's impulses throw it out.
    CHECK(errorOf(withFixture(R"("shape": "circle", "radius": 0.02, "density": 1e-40)")) ==
          "t.json:1:74: at /bodies/0/fixtures: the fixtures weigh 1.26e-43 kg, less than the "
          "1e-06 kg a dynamic body needs (Box2D divides by its mass); raise their density or "
          "size");
    CHECK(errorOf(
              withFixture(R"("shape": "box", "width": 0.01, "height": 0.01, "density": 0.009)")) ==
          "t.json:1:74: at /bodies/0/fixtures: the fixtures weigh 8.999999e-07 kg, less than the "
          "1e-06 kg a dynamic body needs (Box2D divides by its mass); raise their density or "
          "size");
    // Heavy enough for Box2D, but so light beside the water that the fluid throws it: under
    // kMinDensityRatio of the densest material's areal density (129 kg/m^2 here).
    CHECK(errorOf(withFixture(
              R"("shape": "box", "width": 0.01, "height": 0.01, "density": 0.01)")) ==
          "t.json:1:74: at /bodies/0/fixtures: the fixtures weigh 1e-06 kg over 0.0001 m^2, an "
          "areal density of 0.01 kg/m^2, 7.73e-05 of the densest material's (129 kg/m^2); a "
          "dynamic body needs at least 0.05 of it (kMinDensityRatio), or the fluid throws it: "
          "raise their density to 6.47 kg/m^2 or more");
    CHECK(errorOf(withFixture(
              R"("shape": "box", "width": 0.01, "height": 0.01, "density": 6.47)")) ==
          "no error");
    CHECK(errorOf(withFixture(
              R"("shape": "box", "width": 0.01, "height": 0.01, "densityRatio": 0.05)")) ==
          "no error");
    CHECK_THAT(errorOf(withFixture(
                   R"("shape": "box", "width": 0.01, "height": 0.01, "densityRatio": 0.049)")),
               Catch::Contains("0.049 of the densest material's"));
    // A body with "fluid": false floats in nothing: only Box2D's floor holds.
    CHECK(errorOf(withBodies(
              R"({"fluid": false, "fixtures": [{"shape": "box", "width": 0.01, "height": 0.01, "density": 0.01}]})")) ==
          "no error");
    // Static and kinematic bodies need no density.
    CHECK(errorOf(withBodies(
              R"({"type": "static", "fixtures": [{"shape": "circle", "radius": 1}]})")) ==
          "no error");
    CHECK(
        errorOf(withBodies(
            R"({"type": "kinematic", "velocity": [1, 0], "fixtures": [{"shape": "box", "width": 1, "height": 1}]})")) ==
        "no error");
    // Fixtures far from the body's position: Box2D's float inertia would come out <= 0.
    CHECK(errorOf(withFixture(
              R"("shape": "circle", "radius": 0.01, "center": [9000, 0], "density": 9)")) ==
          "t.json:1:74: at /bodies/0/fixtures: the fixtures' centre of mass lies 9000 m from the "
          "body's position, too far for Box2D's single-precision inertia; move the body's position "
          "to its fixtures");
    // ...unless the body does not rotate.
    CHECK(
        errorOf(withBodies(
            R"({"fixedRotation": true, "fixtures": [{"shape": "circle", "radius": 0.01, "center": [9000, 0], "density": 9}]})")) ==
        "no error");
}

TEST_CASE("level bodies: polygons are convex, 3 to 8 distinct vertices, with area",
          "[level][bodies]") {
    const auto polygon = [](const std::string& vertices) {
        return errorOf(withFixture(R"("shape": "polygon", "density": 9, "vertices": )" + vertices));
    };
    CHECK(polygon("[[0, 0], [1, 0]]") ==
          "t.json:1:122: at /bodies/0/fixtures/0/vertices: expected a list of 3 to 8 points [[x, "
          "y], ...] (unit: m), got 2 points");
    CHECK(polygon("[[0, 0], [1, 0], [2, 0], [3, 0], [4, 1], [3, 2], [2, 2], [1, 2], [0, 1]]") ==
          "t.json:1:122: at /bodies/0/fixtures/0/vertices: expected a list of 3 to 8 points [[x, "
          "y], ...] (unit: m), got 9 points");
    CHECK(polygon("[[0, 0], [1, 0], [0.2, 0.2], [0, 1]]") ==
          "t.json:1:139: at /bodies/0/fixtures/0/vertices/2: the polygon is not convex at vertex "
          "2; a Box2D polygon is convex (split a concave shape into several fixtures)");
    CHECK(polygon("[[0, 0], [1, 0], [2, 0], [1, 1]]") ==
          "t.json:1:131: at /bodies/0/fixtures/0/vertices/1: vertex 1 lies on the line through its "
          "neighbours; a Box2D polygon is strictly convex (leave the vertex out)");
    CHECK(polygon("[[0, 0], [1, 0], [1, 1], [1.001, 1.001], [0, 1]]") ==
          "t.json:1:147: at /bodies/0/fixtures/0/vertices/3: vertex 3 is 0.0014142797 m from "
          "vertex 2; polygon vertices must be at least 0.005 m apart (Box2D's linear slop)");
    CHECK(polygon("[[0, 0], [1, 0], [2, 0.000001]]") ==
          "t.json:1:122: at /bodies/0/fixtures/0/vertices: the polygon's area is 5e-07 m^2; "
          "expected at least 2.5e-05 m^2 (Box2D's linear slop squared)");
    // A five-pointed star drawn in one stroke: every corner turns left, the outline goes round
    // twice.
    CHECK(polygon("[[0, 1], [0.588, -0.809], [-0.951, 0.309], [0.951, 0.309], [-0.588, -0.809]]") ==
          "t.json:1:122: at /bodies/0/fixtures/0/vertices: the polygon's edges cross (it winds "
          "round more than once); a Box2D polygon is convex and simple");
    // Either winding.
    CHECK(polygon("[[0, 0], [0, 1], [1, 1], [1, 0]]") == "no error");
}

TEST_CASE("level bodies: edges and chains have links longer than Box2D's slop", "[level][bodies]") {
    const auto fixture = [](const std::string& text) {
        return errorOf(withBodies(R"({"type": "static", "fixtures": [{)" + text + "}]}"));
    };
    CHECK(fixture(R"("shape": "edge", "from": [0, 0], "to": [0.001, 0])") ==
          "t.json:1:133: at /bodies/0/fixtures/0/to: the edge is 0.001 m long; expected more than "
          "0.005 m (Box2D's linear slop)");
    CHECK(fixture(R"("shape": "chain", "points": [[0, 0]])") ==
          "t.json:1:122: at /bodies/0/fixtures/0/points: expected a list of 2 to 4096 points [[x, "
          "y], ...] (unit: m), got 1 point");
    CHECK(fixture(R"("shape": "chain", "points": [[0, 0], [1, 0], [1, 0], [2, 1]])") ==
          "t.json:1:139: at /bodies/0/fixtures/0/points/2: point 2 is 0 m from point 1; "
          "consecutive points must be more than 0.005 m apart (Box2D's linear slop)");
    CHECK(fixture(R"("shape": "chain", "points": [[0, 0], [1, 0]], "loop": true)") ==
          "t.json:1:122: at /bodies/0/fixtures/0/points: a loop needs at least 3 points, got 2");
    CHECK(
        fixture(
            R"("shape": "chain", "points": [[0, 0], [1, 0], [1, 1], [0, 0.002]], "loop": true)") ==
        "t.json:1:123: at /bodies/0/fixtures/0/points/0: point 0 is 0.002 m from point 3; "
        "consecutive points must be more than 0.005 m apart (Box2D's linear slop)");
    CHECK(fixture(R"("shape": "chain", "points": [[0, 0], [1, 0], [1, 1], [0, 0.002]])") ==
          "no error");
    CHECK(fixture(R"("shape": "chain", "points": [[0, 0], [1, 0]], "loop": 1)") ==
          "t.json:1:148: at /bodies/0/fixtures/0/loop: expected true or false, got a number");
}

TEST_CASE("level bodies: joints name existing, distinct bodies", "[level][bodies]") {
    const std::string two =
        kBall +
        R"(, {"name": "axle", "type": "static", "fixtures": [{"shape": "circle", "radius": 0.01}]})";
    const auto joint = [&](const std::string& text) {
        return errorOf(withBodies(two, R"(, "joints": [{)" + text + "}]"));
    };
    CHECK(joint(R"("type": "weld", "bodyA": "axle", "bodyB": "ball", "anchor": [0, 0])") ==
          "t.json:1:251: at /joints/0/type: unknown joint type 'weld'; known: revolute");
    CHECK(joint(R"("bodyA": "axle", "bodyB": "ball", "anchor": [0, 0])") ==
          "t.json:1:242: at /joints/0: missing key 'type'; expected a joint type: revolute");
    CHECK(joint(R"("type": "revolute", "bodyA": "axel", "bodyB": "ball", "anchor": [0, 0])") ==
          "t.json:1:272: at /joints/0/bodyA: unknown body 'axel'; known: ball, axle");
    CHECK(joint(R"("type": "revolute", "bodyA": "ball", "bodyB": "ball", "anchor": [0, 0])") ==
          "t.json:1:289: at /joints/0/bodyB: expected a body other than bodyA ('ball'); a joint "
          "connects two bodies");
    CHECK(joint(R"("type": "revolute", "bodyA": "axle", "bodyB": "ball")") ==
          "t.json:1:242: at /joints/0: missing key 'anchor'; expected a point [x, y] of two "
          "numbers in [-100000, 100000] (unit: m)");
    CHECK(
        joint(
            R"("type": "revolute", "bodyA": "axle", "bodyB": "ball", "anchor": [0, 0], "speed": 1)") ==
        "t.json:1:315: at /joints/0/speed: unknown key 'speed'; allowed: type, name, bodyA, bodyB, "
        "anchor, collideConnected, enableMotor, motorSpeed, maxMotorTorque, enableLimit, "
        "lowerAngle, upperAngle");
    CHECK(
        joint(
            R"("type": "revolute", "bodyA": "axle", "bodyB": "ball", "anchor": [0, 0], "lowerAngle": 1, "upperAngle": -1)") ==
        "t.json:1:346: at /joints/0/upperAngle: expected upperAngle >= lowerAngle (1 rad), got -1");
    CHECK(
        joint(
            R"("type": "revolute", "bodyA": "axle", "bodyB": "ball", "anchor": [0, 0], "maxMotorTorque": -1)") ==
        "t.json:1:333: at /joints/0/maxMotorTorque: -1 is out of range [0, 1000000000] (unit: N "
        "m)");
    CHECK(
        errorOf(withBodies(
            two,
            R"(, "joints": [{"type": "revolute", "name": "j", "bodyA": "axle", "bodyB": "ball", "anchor": [0, 0]}, {"type": "revolute", "name": "j", "bodyA": "axle", "bodyB": "ball", "anchor": [0, 0]}])")) ==
        "t.json:1:358: at /joints/1/name: duplicate joint name 'j' (first used at /joints/0/name); "
        "names must be unique");
    CHECK(
        errorOf(
            R"({"version": 1, "materials": [{"name": "water"}], "joints": [{"type": "revolute"}]})") ==
        "t.json:1:60: at /joints: joints need bodies; the level declares none");
}

TEST_CASE("level bodies: coupling settings are checked and need bodies", "[level][bodies]") {
    CHECK(errorOf(withBodies(kBall, R"(, "coupling": {"friction": 11})")) ==
          "t.json:1:169: at /coupling/friction: 11 is out of range [0, 10] (unit: 1)");
    CHECK(
        errorOf(withBodies(kBall, R"(, "coupling": {"velocityIterations": 0})")) ==
        "t.json:1:179: at /coupling/velocityIterations: 0 is out of range [1, 1000] (unit: count)");
    CHECK(errorOf(withBodies(kBall, R"(, "coupling": {"positionIterations": 2.5})")) ==
          "t.json:1:179: at /coupling/positionIterations: expected a whole number in [1, 1000] "
          "(unit: count), got 2.5");
    CHECK(errorOf(withBodies(kBall, R"(, "coupling": {"splashSpeed": -1})")) ==
          "t.json:1:172: at /coupling/splashSpeed: -1 is out of range [0, 1000] (unit: m/s)");
    CHECK(errorOf(withBodies(kBall, R"(, "coupling": {"stiffness": 1})")) ==
          "t.json:1:157: at /coupling/stiffness: unknown key 'stiffness'; allowed: friction, "
          "splashSpeed, velocityIterations, positionIterations");
    CHECK(errorOf(R"({"version": 1, "materials": [{"name": "water"}], "coupling": {}})") ==
          "t.json:1:62: at /coupling: coupling settings need bodies; the level declares none");
}

TEST_CASE("level bodies: a file's bodies, fixtures, joints and coupling are built as written",
          "[level][bodies]") {
    const std::string text = R"({"version": 1, "world": {"gravity": [0, -9.81]},
  "materials": [{"name": "water"}],
  "bodies": [
    {"name": "ground", "type": "static", "fluid": false, "fixtures": [
      {"shape": "edge", "from": [-1, 0], "to": [1, 0]},
      {"shape": "chain", "points": [[-1, 1], [-1, 0], [1, 0], [1, 1]]},
      {"shape": "chain", "points": [[2, 0], [3, 0], [3, 1]], "loop": true, "friction": 0.5}]},
    {"name": "crate", "position": [0.5, 0.3], "angle": 0.25, "velocity": [1, -2],
     "angularVelocity": 3, "linearDamping": 0.1, "angularDamping": 0.2, "bullet": true,
     "fixtures": [{"shape": "box", "width": 0.2, "height": 0.1, "density": 50, "friction": 0.4,
                   "restitution": 0.3}]},
    {"fixedRotation": true, "fixtures": [
      {"shape": "circle", "radius": 0.05, "center": [0.1, 0], "densityRatio": 0.5},
      {"shape": "polygon", "vertices": [[0, 0], [0, 0.1], [0.1, 0]], "densityRatio": 2}]},
    {"name": "lift", "type": "kinematic", "velocity": [0, 0.5],
     "fixtures": [{"shape": "box", "width": 0.3, "height": 0.02, "center": [0.1, 0], "angle": 0.5}]}
  ],
  "joints": [
    {"type": "revolute", "bodyA": "ground", "bodyB": "crate", "anchor": [0.5, 0.3],
     "enableMotor": true, "motorSpeed": -2, "maxMotorTorque": 5, "enableLimit": true,
     "lowerAngle": -1, "upperAngle": 1.5, "collideConnected": true}
  ],
  "coupling": {"friction": 0.5, "splashSpeed": 2, "velocityIterations": 10,
               "positionIterations": 4}})";
    const Level level = parseLevel(text, "t.json", builtins());
    REQUIRE(level.physics != nullptr);
    REQUIRE(level.coupling != nullptr);
    CHECK(level.physics->GetBodyCount() == 4);
    CHECK(level.physics->GetJointCount() == 1);
    CHECK(level.physics->GetGravity().x == 0.0f);
    CHECK(level.physics->GetGravity().y == -9.81f);
    REQUIRE(level.bodies.size() == 4);
    CHECK(level.bodies[0].first == "ground");
    CHECK(level.bodies[1].first == "crate");
    CHECK(level.bodies[2].first == "body2"); // unnamed: its index
    CHECK(level.bodies[3].first == "lift");

    // Static ground, kept out of the fluid by its category.
    const b2Body* ground = bodyNamed(level, "ground");
    CHECK(ground->GetType() == b2_staticBody);
    const auto groundFixtures = fixturesOf(ground);
    REQUIRE(groundFixtures.size() == 3);
    CHECK(groundFixtures[0]->GetType() == b2Shape::e_edge);
    CHECK(groundFixtures[1]->GetType() == b2Shape::e_chain);
    CHECK(groundFixtures[1]->GetShape()->GetChildCount() == 3); // open: 3 links
    CHECK(groundFixtures[2]->GetShape()->GetChildCount() == 3); // loop of 3 points: 3 links
    CHECK(groundFixtures[2]->GetFriction() == 0.5f);
    for (const b2Fixture* f : groundFixtures) {
        CHECK(f->GetFilterData().categoryBits == kDryFixtureCategory);
        CHECK(f->GetFilterData().maskBits == 0xFFFF);
    }
    CHECK(level.coupling->def().categoryMask == 0x7FFF);

    // Dynamic crate: pose, motion, damping, mass = density x area.
    const b2Body* crate = bodyNamed(level, "crate");
    CHECK(crate->GetType() == b2_dynamicBody);
    CHECK(crate->GetPosition() == b2Vec2(0.5f, 0.3f));
    CHECK(crate->GetAngle() == 0.25f);
    CHECK(crate->GetLinearVelocity() == b2Vec2(1.0f, -2.0f));
    CHECK(crate->GetAngularVelocity() == 3.0f);
    CHECK(crate->GetLinearDamping() == 0.1f);
    CHECK(crate->GetAngularDamping() == 0.2f);
    CHECK(crate->IsBullet());
    CHECK(crate->IsAwake());
    CHECK(crate->GetMass() == Approx(50.0 * 0.2 * 0.1).epsilon(1e-5));
    // A box's inertia about its centre: m (w^2 + h^2) / 12.
    CHECK(crate->GetInertia() == Approx(1.0 * (0.04 + 0.01) / 12.0).epsilon(1e-4));
    const b2Fixture* box = crate->GetFixtureList();
    CHECK(box->GetFriction() == 0.4f);
    CHECK(box->GetRestitution() == 0.3f);
    CHECK(box->GetFilterData().categoryBits == 0x0001);

    // densityRatio: a multiple of the first material's areal density.
    const double areal = box2d::arealDensity(level.world, level.materials[0].second);
    CHECK(areal == Approx(water().restDensity * level.world.def().depth).epsilon(1e-6));
    const b2Body* unnamed = level.bodies[2].second;
    const double circle = 0.5 * areal * M_PI * 0.05 * 0.05;
    const double triangle = 2.0 * areal * 0.5 * 0.1 * 0.1;
    CHECK(unnamed->GetMass() == Approx(circle + triangle).epsilon(1e-5));
    CHECK(unnamed->IsFixedRotation());
    // No rotational inertia of its own: GetInertia (about the origin) is m |c|^2 alone.
    const b2Vec2 c = unnamed->GetLocalCenter();
    CHECK(unnamed->GetInertia() == Approx(unnamed->GetMass() * b2Dot(c, c)));
    // The triangle was given clockwise; Box2D holds it counter-clockwise, same area.
    const auto* triangleShape =
        static_cast<const b2PolygonShape*>(fixturesOf(unnamed)[1]->GetShape());
    CHECK(triangleShape->m_count == 3);

    // Kinematic lift: moves at its velocity, has no mass.
    const b2Body* lift = bodyNamed(level, "lift");
    CHECK(lift->GetType() == b2_kinematicBody);
    CHECK(lift->GetLinearVelocity() == b2Vec2(0.0f, 0.5f));
    CHECK(lift->GetMass() == 0.0f);
    const auto* liftBox = static_cast<const b2PolygonShape*>(lift->GetFixtureList()->GetShape());
    CHECK(liftBox->m_centroid.x == Approx(0.1f));

    // The revolute joint, with its motor and limits.
    REQUIRE(level.joints.size() == 1);
    CHECK(level.joints[0].first == "joint0");
    REQUIRE(level.joints[0].second->GetType() == e_revoluteJoint);
    auto* hinge = static_cast<b2RevoluteJoint*>(level.joints[0].second);
    CHECK(hinge->GetBodyA() == ground);
    CHECK(hinge->GetBodyB() == crate);
    CHECK(hinge->GetAnchorA().x == Approx(0.5f));
    CHECK(hinge->GetAnchorB().y == Approx(0.3f));
    CHECK(hinge->IsMotorEnabled());
    CHECK(hinge->GetMotorSpeed() == -2.0f);
    CHECK(hinge->GetMaxMotorTorque() == 5.0f);
    CHECK(hinge->IsLimitEnabled());
    CHECK(hinge->GetLowerLimit() == -1.0f);
    CHECK(hinge->GetUpperLimit() == 1.5f);
    CHECK(hinge->GetCollideConnected());

    const box2d::CouplingDef& def = level.coupling->def();
    CHECK(def.friction == 0.5f);
    CHECK(def.splashSpeed == 2.0f);
    CHECK(def.velocityIterations == 10);
    CHECK(def.positionIterations == 4);
}

TEST_CASE("level bodies: Box2D's gravity is the level's uniform gravity", "[level][bodies]") {
    const auto gravityOf = [](const std::string& head) {
        const Level level = parseLevel(R"({"version": 1, "materials": [{"name": "water"}], )" +
                                           head + R"("bodies": [)" + kBall + "]}",
                                       "t.json", builtins());
        return level.physics->GetGravity();
    };
    CHECK(gravityOf(R"("world": {"gravity": [1, -5]}, )") == b2Vec2(1.0f, -5.0f));
    // Zero-g: no gravity plugin.
    CHECK(gravityOf("") == b2Vec2(0.0f, 0.0f));
    // force.gravity plugins add up, world.gravity included; other forces do not count.
    CHECK(
        gravityOf(
            R"("world": {"gravity": [0, -2]}, "plugins": [{"type": "force.gravity", "params": {"gx": 0.5, "gy": -3}}, {"type": "force.point_gravity"}], )") ==
        b2Vec2(0.5f, -5.0f));
}

TEST_CASE("level bodies: without bodies there is no Box2D world and Level::step steps the "
          "fluid alone",
          "[level][bodies]") {
    for (const std::string bodies : {"", R"(, "bodies": [])"}) {
        Level level = parseLevel(
            R"({"version": 1, "world": {"gravity": [0, -9.81]}, "materials": [{"name": "water"}], "blobs": [{"material": "water", "shape": "box", "min": [0, 0], "max": [0.05, 0.05]}])" +
                bodies + "}",
            "t.json", builtins());
        CHECK(level.physics == nullptr);
        CHECK(level.coupling == nullptr);
        CHECK(level.bodies.empty());
        CHECK(level.world.boundaries().empty());
        level.step();
        CHECK(level.world.time() == Approx(1.0 / 60.0));
    }
}

TEST_CASE("level bodies: Level::step runs the coupling, a level with bodies moves and "
          "move-assigns",
          "[level][bodies]") {
    // A ball resting on water, a dry marker body that the fluid must not see.
    const std::string text =
        R"({"version": 1, "world": {"gravity": [0, -9.81]}, "materials": [{"name": "water"}],
  "plugins": [{"type": "boundary.box", "params": {"minX": 0, "minY": 0, "maxX": 0.3, "maxY": 0.5}}],
  "blobs": [{"material": "water", "shape": "box", "min": [0, 0], "max": [0.3, 0.1]}],
  "bodies": [{"name": "ball", "position": [0.15, 0.13], "fixtures": [{"shape": "circle", "radius": 0.04, "densityRatio": 0.5}]},
             {"name": "ghost", "type": "static", "fluid": false, "position": [0.05, 0.05], "fixtures": [{"shape": "box", "width": 0.05, "height": 0.05}]}]})";
    Level a = parseLevel(text, "t.json", builtins());
    // The coupling's boundary plugin joins after the file's container.
    REQUIRE(a.world.boundaries().size() == 2);
    CHECK(a.world.boundaries()[0]->type() == "boundary.box");
    CHECK(a.world.boundaries()[1]->type() == "box2d.bodies");
    b2Body* ball = a.bodies[0].second;
    const b2Body* ghost = a.bodies[1].second;
    const uint32_t particles = a.world.particleCount();

    Level b = std::move(a);
    CHECK(a.physics == nullptr);
    CHECK(a.coupling == nullptr);
    CHECK(a.bodies.empty());
    for (int f = 0; f < 10; ++f) {
        b.step();
    }
    // The coupling ran: Box2D stepped, the ball is coupled and wet, the dry body is not coupled.
    CHECK(b.world.time() == Approx(10.0 / 60.0));
    CHECK(ball->GetPosition().y != 0.13f);
    const box2d::BodyReport* report = b.coupling->report(ball);
    REQUIRE(report != nullptr);
    CHECK(report->wetPoints > 0);
    CHECK(b.coupling->report(ghost) == nullptr);
    // The dry body lies inside the water yet the fluid does not see it: no particle removed or
    // pushed out of it by a boundary. (Particles keep their count either way; the check is that
    // particles remain inside the dry body's box.)
    CHECK(b.world.particleCount() == particles);
    uint32_t insideGhost = 0;
    const auto px = b.world.positionX(), py = b.world.positionY();
    for (uint32_t i = 0; i < b.world.particleCount(); ++i) {
        insideGhost += px[i] > 0.03f && px[i] < 0.07f && py[i] > 0.03f && py[i] < 0.07f;
    }
    CHECK(insideGhost > 0);

    // Move-assigning over a level with bodies destroys its coupling before its worlds.
    Level c = parseLevel(text, "t.json", builtins());
    c = std::move(b);
    CHECK(c.bodies[0].second == ball);
    const float y = ball->GetPosition().y;
    c.step();
    CHECK(ball->GetPosition().y != y);
    CHECK(c.world.time() == Approx(11.0 / 60.0));
}

TEST_CASE("level bodies: every body type name loads as its Box2D type", "[level][bodies]") {
    const std::pair<const char*, b2BodyType> types[] = {
        {"static", b2_staticBody}, {"kinematic", b2_kinematicBody}, {"dynamic", b2_dynamicBody}};
    for (const auto& [name, type] : types) {
        const Level level = parseLevel(
            withBodies(R"({"name": "b", "type": ")" + std::string(name) +
                       R"(", "fixtures": [{"shape": "circle", "radius": 0.1, "density": 9}]})"),
            "t.json", builtins());
        INFO(name);
        REQUIRE(bodyNamed(level, "b") != nullptr);
        CHECK(bodyNamed(level, "b")->GetType() == type);
    }
}
