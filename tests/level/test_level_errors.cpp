// fluid tests — level loader errors: one test per error class, each asserting the exact message
// with its file, line, column and JSON pointer. Columns are 1-based bytes; the texts are kept on
// one line where the column matters, so that it can be counted by eye.
#include <catch2/catch.hpp>

#include "level_support.h"

#include <fluid/level.h>
#include <fluid/plugins/gravity.h>

#include <cstdio>
#include <string>

using namespace fluid;
using namespace fluid::test;

namespace {} // namespace

TEST_CASE("level errors: the smallest valid level loads", "[level][errors]") {
    CHECK(errorOf(levelWith("")) == "no error");
    const Level lvl = parseLevel(levelWith(""), "t.json", builtins());
    CHECK(lvl.version == 1);
    CHECK(lvl.world.forces().empty());
    CHECK(lvl.world.particleCount() == 0);
    CHECK(lvl.world.material(lvl.materials[0].second).viscosity == water().viscosity);
}

TEST_CASE("level errors: syntax errors name the line and column", "[level][errors]") {
    CHECK(errorOf("{\"version\": 1,\n  \"name\": x}") ==
          "t.json:2:11: syntax error while parsing value - invalid literal; last read: "
          "'\"name\": x'");
    CHECK(errorOf("{\"version\": 1,\n\n  \"materials\": [}") ==
          "t.json:3:17: syntax error while parsing value - unexpected '}'; expected '[', '{', "
          "or a literal");
    CHECK(errorOf("") == "t.json:1:1: syntax error while parsing value - unexpected end of "
                         "input; expected '[', '{', or a literal");
    CHECK(errorOf("{\"version\": 1} 2") ==
          "t.json:1:16: syntax error while parsing value - unexpected number literal; expected "
          "end of input");
    // Comments are not JSON.
    CHECK(errorOf("// level\n{}").rfind("t.json:1:1: syntax error while parsing value", 0) == 0);
}

TEST_CASE("level errors: the document must be an object with a supported version",
          "[level][errors]") {
    CHECK(errorOf("[1, 2]") == "t.json:1:1: expected a level (an object), got an array");
    CHECK(errorOf(R"({"materials": [{"name": "water"}]})") ==
          "t.json:1:1: missing key 'version'; expected the format version (1)");
    CHECK(errorOf(R"({"version": 2, "materials": [{"name": "water"}]})") ==
          "t.json:1:13: at /version: unsupported version 2; this loader reads version 1");
    CHECK(errorOf(R"({"version": "1", "materials": [{"name": "water"}]})") ==
          "t.json:1:13: at /version: expected a whole number in [1, 1000000000] (unit: 1), got "
          "a string");
    CHECK(errorOf(R"({"version": 1.5})") ==
          "t.json:1:13: at /version: expected a whole number in [1, 1000000000] (unit: 1), got "
          "1.5");
    CHECK(errorOf(R"({"version": 1})") ==
          "t.json:1:1: missing key 'materials'; expected an array of at least one material");
    CHECK(errorOf(R"({"version": 1, "materials": []})") ==
          "t.json:1:29: at /materials: expected at least one material, got an empty array");
}

TEST_CASE("level errors: unknown keys are named with the allowed ones", "[level][errors]") {
    CHECK(errorOf(levelWith(R"(, "wrld": {})")) ==
          "t.json:1:50: at /wrld: unknown key 'wrld'; allowed: version, name, description, "
          "world, materials, blobs, plugins, emitters, drains, sensors, goal, bodies, joints, "
          "coupling");
    // The first unknown key in text order (nlohmann keeps members sorted by name).
    CHECK(errorOf(levelWith(R"(, "world": {"zz": 1, "frameRate": 60, "aa": 2})")) ==
          "t.json:1:60: at /world/zz: unknown key 'zz'; allowed: gravity, frameRate, solver, "
          "quality, substeps, iterations, viscosityInterval, coarseCorrection, vorticity, "
          "shearConstraint, equationOfState, soundSpeed, workers, colourMixing, depth, "
          "courant, maxSubsteps, maxParticles");
    // Keys that belong to another shape are unknown too.
    CHECK(
        errorOf(levelWith(
            R"(, "blobs": [{"material": "water", "shape": "box", "min": [0, 0], "max": [1, 1], "radius": 1}])")) ==
        "t.json:1:128: at /blobs/0/radius: unknown key 'radius'; allowed: material, velocity, "
        "lifetime, structure, latticeAngle, colour, shape, min, max");
    // A blob's starting structure is a share in [0, 1].
    CHECK(
        errorOf(levelWith(
            R"(, "blobs": [{"material": "water", "shape": "box", "min": [0, 0], "max": [1, 1], "structure": 1.5}])")) ==
        "t.json:1:141: at /blobs/0/structure: 1.5 is out of range [0, 1] (unit: 1)");
    // The lattice's angle is within a turn either way.
    CHECK(
        errorOf(levelWith(
            R"(, "blobs": [{"material": "water", "shape": "box", "min": [0, 0], "max": [1, 1], "latticeAngle": 7}])")) ==
        "t.json:1:144: at /blobs/0/latticeAngle: 7 is out of range [-6.2832, 6.2832] (unit: rad)");
    // Pointers escape '/' and '~' (RFC 6901).
    CHECK(errorOf(levelWith(R"(, "a/b~": 1)")) ==
          "t.json:1:50: at /a~1b~0: unknown key 'a/b~'; allowed: version, name, description, "
          "world, materials, blobs, plugins, emitters, drains, sensors, goal, bodies, joints, "
          "coupling");
}

TEST_CASE("level errors: a repeated key is an error, not a silent overwrite", "[level][errors]") {
    CHECK(errorOf(levelWith(R"(, "world": {"frameRate": 30, "frameRate": 60})")) ==
          "t.json:1:77: at /world/frameRate: duplicate key 'frameRate'; each key may appear "
          "once per object");
}

TEST_CASE("level errors: wrong types say what was expected and what was found", "[level][errors]") {
    CHECK(errorOf(levelWith(R"(, "world": {"frameRate": "60"})")) ==
          "t.json:1:73: at /world/frameRate: expected a number in [1, 1000] (unit: Hz), got a "
          "string");
    CHECK(errorOf(levelWith(R"(, "world": {"gravity": 9.81})")) ==
          "t.json:1:71: at /world/gravity: expected a vector [gx, gy] of two numbers (unit: "
          "m/s^2), got a number");
    CHECK(errorOf(levelWith(R"(, "world": {"solver": true})")) ==
          "t.json:1:70: at /world/solver: expected a string, got a boolean");
    CHECK(errorOf(levelWith(R"(, "world": {"substeps": 2.5})")) ==
          "t.json:1:72: at /world/substeps: expected a whole number in [1, 12] (unit: count), "
          "got 2.5");
    CHECK(errorOf(levelWith(R"(, "blobs": {})")) ==
          "t.json:1:59: at /blobs: expected an array of blobs, got an object");
    CHECK(errorOf(levelWith(R"(, "blobs": [null])")) ==
          "t.json:1:60: at /blobs/0: expected a blob (an object), got null");
    CHECK(errorOf(R"({"version": 1, "materials": [{"name": 7}]})") ==
          "t.json:1:39: at /materials/0/name: expected the material's name (a string), got a "
          "number");
    CHECK(
        errorOf(levelWith(
            R"(, "blobs": [{"material": "water", "shape": "circle", "center": [0, "0"], "radius": 0.1}])")) ==
        "t.json:1:115: at /blobs/0/center/1: expected a number in [-100000, 100000] (unit: m), "
        "got a string");
    CHECK(
        errorOf(levelWith(
            R"(, "blobs": [{"material": "water", "shape": "circle", "center": [0, 0, 0], "radius": 0.1}])")) ==
        "t.json:1:111: at /blobs/0/center: expected a point [x, y] of two numbers in "
        "[-100000, 100000] (unit: m), got an array of 3");
}

TEST_CASE("level errors: out-of-range values give the range and unit", "[level][errors]") {
    CHECK(errorOf(levelWith(R"(, "world": {"frameRate": 5000})")) ==
          "t.json:1:73: at /world/frameRate: 5000 is out of range [1, 1000] (unit: Hz)");
    CHECK(errorOf(levelWith(R"(, "world": {"maxSubsteps": 10000})")) ==
          "t.json:1:75: at /world/maxSubsteps: 10000 is out of range [1, 1000] (unit: count)");
    CHECK(errorOf(levelWith(R"(, "world": {"workers": 0})")) ==
          "t.json:1:71: at /world/workers: 0 is out of range [1, 256] (unit: count)");
    CHECK(errorOf(levelWith(R"(, "world": {"soundSpeed": 0.05})")) ==
          "t.json:1:74: at /world/soundSpeed: 0.05 is out of range: 0 (derive from the scene) or "
          "[0.1, 10000] (unit: m/s)");
    CHECK(errorOf(R"({"version": 1, "materials": [{"name": "w", "viscosity": -1}]})") ==
          "t.json:1:57: at /materials/0/viscosity: -1 is out of range [0, 10000] (unit: Pa*s)");
    CHECK(errorOf(R"({"version": 1, "materials": [{"name": "w", "mass": 0}]})") ==
          "t.json:1:52: at /materials/0/mass: 0 is out of range (0, 1000] (unit: kg)");
    CHECK(errorOf(R"({"version": 1, "materials": [{"name": "w", "flowIndex": 3}]})") ==
          "t.json:1:57: at /materials/0/flowIndex: 3 is out of range [0.1, 2] (unit: 1)");
    // A yield stress needs the position-based solver.
    CHECK(errorOf(R"({"version": 1, "world": {"solver": "explicit"},
  "materials": [{"name": "y", "preset": "yoghurt"}]})") ==
          "t.json:2:17: at /materials/0: World::addMaterial: material 'y' has a Herschel-Bulkley "
          "flow law (yieldStress = 400 Pa, consistency = 2 Pa*s^n), which the explicit solver "
          "does not step; use Solver::PositionBased, or set yieldStress and consistency to 0");
    // Plugin parameters: the registry's declared range.
    CHECK(errorOf(levelWith(
              R"(, "plugins": [{"type": "boundary.box", "params": {"friction": 11}}])")) ==
          "t.json:1:110: at /plugins/0/params/friction: 11 is out of range [0, 10] (unit: 1)");
    CHECK(errorOf(levelWith(R"(, "world": {"gravity": [0, -2000]})")) ==
          "t.json:1:75: at /world/gravity/1: -2000 is out of range [-1000, 1000] (unit: m/s^2)");
}

TEST_CASE("level errors: non-finite numbers are rejected", "[level][errors]") {
    // JSON has no NaN or infinity, but 1e999 overflows a double.
    CHECK(errorOf(levelWith(R"(, "world": {"gravity": [0, -1e999]})")) ==
          "t.json:1:75: at /world/gravity/1: -1e999 is not finite (it overflows a double); "
          "expected a finite number");
    CHECK(errorOf("{\"version\": 1,\n \"materials\": [{\"name\": \"w\", \"mass\": 1e400}]}") ==
          "t.json:2:38: at /materials/0/mass: 1e400 is not finite (it overflows a double); "
          "expected a finite number");
    CHECK(errorOf("{\"version\": 1e309}") ==
          "t.json:1:13: at /version: 1e309 is not finite (it overflows a double); expected a "
          "finite number");
}

TEST_CASE("level errors: unknown plugin types, presets, solvers and shapes list the known ones",
          "[level][errors]") {
    Registry small;
    small.add<GravityForce>("test");
    try {
        parseLevel(levelWith(R"(, "plugins": [{"type": "force.vortx"}])"), "t.json", small);
        FAIL("no error");
    } catch (const LevelError& e) {
        CHECK(std::string(e.what()) == "t.json:1:71: at /plugins/0/type: unknown plugin type "
                                       "'force.vortx'; known: force.gravity");
    }
    CHECK(errorOf(R"({"version": 1, "materials": [{"name": "m", "preset": "milk"}]})") ==
          "t.json:1:54: at /materials/0/preset: unknown preset 'milk'; known: water, yoghurt, "
          "seed_yoghurt");
    CHECK(errorOf(levelWith(R"(, "world": {"solver": "pbd"})")) ==
          "t.json:1:70: at /world/solver: unknown solver 'pbd'; known: position_based, explicit");
    CHECK(errorOf(levelWith(R"(, "world": {"quality": "fast"})")) ==
          "t.json:1:71: at /world/quality: unknown quality 'fast'; known: game, precise");
    CHECK(errorOf(levelWith(R"(, "world": {"viscosityInterval": 0})")) ==
          "t.json:1:81: at /world/viscosityInterval: 0 is out of range [1, 64] (unit: count)");
    CHECK(errorOf(levelWith(R"(, "world": {"coarseCorrection": 1.5})")) ==
          "t.json:1:80: at /world/coarseCorrection: 1.5 is out of range [0, 1] (unit: 1)");
    CHECK(errorOf(levelWith(R"(, "sensors": [{"name": "s", "shape": "star"}])")) ==
          "t.json:1:85: at /sensors/0/shape: unknown shape 'star'; known: box, circle, polygon");
    // Each with ErrorCode::UnknownName (docs/errors.md); a value out of range is a bad file.
    CHECK(codeOf(R"({"version": 1, "materials": [{"name": "m", "preset": "milk"}]})") ==
          ErrorCode::UnknownName);
    CHECK(codeOf(levelWith(R"(, "plugins": [{"type": "force.vortx"}])")) == ErrorCode::UnknownName);
    CHECK(codeOf(levelWith(R"(, "world": {"solver": "pbd"})")) == ErrorCode::UnknownName);
    CHECK(codeOf(levelWith(R"(, "world": {"quality": "fast"})")) == ErrorCode::UnknownName);
    CHECK(codeOf(levelWith(R"(, "world": {"equationOfState": "ideal"})")) ==
          ErrorCode::UnknownName);
    CHECK(errorOf(levelWith(R"(, "world": {"equationOfState": "ideal"})")) ==
          "t.json:1:79: at /world/equationOfState: unknown equation of state 'ideal'; known: "
          "tait, linear");
    CHECK(codeOf(levelWith(R"(, "sensors": [{"name": "s", "shape": "star"}])")) ==
          ErrorCode::UnknownName);
    CHECK(codeOf(levelWith(R"(, "world": {"viscosityInterval": 0})")) == ErrorCode::BadFile);
}

TEST_CASE("level errors: every name of the solver, quality and equation-of-state tables loads",
          "[level][errors]") {
    for (const EnumName<Solver>& row : kSolverNames) {
        const std::string text = levelWith(R"(, "world": {"solver": ")" + std::string(row.name) +
                                           R"(", "equationOfState": "tait"})");
        INFO(text);
        CHECK(parseLevel(text, "t.json", builtins()).world.def().solver == row.value);
    }
    for (const EnumName<EquationOfState>& row : kEquationOfStateNames) {
        const std::string text =
            levelWith(R"(, "world": {"equationOfState": ")" + std::string(row.name) + R"("})");
        CHECK(parseLevel(text, "t.json", builtins()).world.def().equationOfState == row.value);
    }
    for (const EnumName<Quality>& row : kQualityNames) {
        const std::string text =
            levelWith(R"(, "world": {"quality": ")" + std::string(row.name) + R"("})");
        CHECK(parseLevel(text, "t.json", builtins()).world.def().positionBased.iterations ==
              positionBasedPreset(row.value).iterations);
    }
}

TEST_CASE("level errors: the kinds of failure carry their codes", "[level][errors]") {
    // Malformed contents: a bad file.
    CHECK(codeOf("{\"version\": 1,\n  \"name\": x}") == ErrorCode::BadFile);
    CHECK(codeOf(levelWith(R"(, "bogus": 1)")) == ErrorCode::BadFile);
    // A value the world refuses, re-located at the file's block: the file's fault.
    CHECK(
        codeOf(levelWith(
            R"(, "blobs": [{"material": "water", "shape": "box", "min": [0, 0], "max": [80, 80]}])")) ==
        ErrorCode::BadFile);
    // A name the file refers to but does not declare.
    CHECK(
        codeOf(levelWith(
            R"(, "blobs": [{"material": "milk", "shape": "box", "min": [0, 0], "max": [1, 1]}])")) ==
        ErrorCode::UnknownName);
    // A file that cannot be opened.
    try {
        (void)loadLevel("/nonexistent/level.json", builtins());
        FAIL("no error");
    } catch (const Error& e) {
        CHECK(e.code() == ErrorCode::Io);
        CHECK_THAT(std::string(e.what()),
                   Catch::StartsWith("loadLevel: cannot open '/nonexistent/level.json'"));
    }
}

TEST_CASE("level errors: unknown plugin parameters list the declared ones", "[level][errors]") {
    CHECK(errorOf(levelWith(
              R"(, "plugins": [{"type": "boundary.box", "params": {"minX": 0, "width": 2}}])")) ==
          "t.json:1:109: at /plugins/0/params/width: unknown parameter 'width' of plugin "
          "'boundary.box'; known: minX, minY, maxX, maxY, friction, openTop");
    CHECK(errorOf(levelWith(R"(, "plugins": [{"type": "force.gravity", "params": {"g": 1}}])")) ==
          "t.json:1:99: at /plugins/0/params/g: unknown parameter 'g' of plugin "
          "'force.gravity'; known: gx, gy");
}

TEST_CASE("level errors: point-list parameters need [[x, y], ...]", "[level][errors]") {
    CHECK(errorOf(levelWith(
              R"(, "plugins": [{"type": "boundary.polygon", "params": {"vertices": 5}}])")) ==
          "t.json:1:114: at /plugins/0/params/vertices: expected a list of 3 to 4096 points "
          "[[x, y], ...] (unit: m), got a number");
    CHECK(
        errorOf(levelWith(
            R"(, "plugins": [{"type": "boundary.polygon", "params": {"vertices": [[0, 0], [1, 0]]}}])")) ==
        "t.json:1:114: at /plugins/0/params/vertices: expected a list of 3 to 4096 points "
        "[[x, y], ...] (unit: m), got 2 points");
    CHECK(
        errorOf(levelWith(
            R"(, "plugins": [{"type": "boundary.polygon", "params": {"vertices": [[0, 0], [1, 0], 1]}}])")) ==
        "t.json:1:131: at /plugins/0/params/vertices/2: expected a point [x, y] of two numbers "
        "(unit: m), got a number");
    // A number parameter given points.
    CHECK(
        errorOf(levelWith(
            R"(, "plugins": [{"type": "boundary.polygon", "params": {"x": [0, 0], "vertices": [[0, 0], [1, 0], [0, 1]]}}])")) ==
        "t.json:1:107: at /plugins/0/params/x: expected a number in [-100000, 100000] (unit: "
        "m), got an array");
    // A plugin starts with no points: required point lists must be given.
    CHECK(
        errorOf(levelWith(R"(, "plugins": [{"type": "boundary.polygon", "params": {"x": 1}}])")) ==
        "t.json:1:101: at /plugins/0/params: missing parameter 'vertices' of plugin "
        "'boundary.polygon'; expected a list of 3 to 4096 points [[x, y], ...] (unit: m)");
    CHECK(errorOf(levelWith(R"(, "plugins": [{"type": "boundary.chain"}])")) ==
          "t.json:1:62: at /plugins/0: missing parameter 'points' of plugin 'boundary.chain'; "
          "expected a list of 2 to 4096 points [[x, y], ...] (unit: m)");
}

TEST_CASE("level errors: bad shapes", "[level][errors]") {
    const std::string blob =
        R"(, "blobs": [{"material": "water", "shape": "polygon", "vertices": )";
    CHECK(errorOf(levelWith(blob + "[[0, 0], [1, 0]]}]")) ==
          "t.json:1:114: at /blobs/0/vertices: expected a list of 3 to 256 points [[x, y], ...] "
          "(unit: m), got 2 points");
    // A bow tie: edges 0 and 2 cross.
    CHECK(errorOf(levelWith(blob + "[[0, 0], [0.3, 0.2], [0.3, 0], [0, 0.1]]}]")) ==
          "t.json:1:114: at /blobs/0/vertices: polygon edges 0 and 2 cross; expected a simple "
          "polygon");
    CHECK(errorOf(levelWith(blob + "[[0, 0], [1, 1], [2, 2]]}]")) ==
          "t.json:1:114: at /blobs/0/vertices: polygon has zero area");
    CHECK(errorOf(levelWith(
              R"(, "sensors": [{"name": "s", "shape": "box", "min": [0, 0], "max": [1, 0]}])")) ==
          "t.json:1:114: at /sensors/0/max: expected max > min on both axes, got min [0, 0], max "
          "[1, 0]");
    CHECK(
        errorOf(levelWith(
            R"(, "drains": [{"name": "d", "shape": "circle", "center": [0, 0], "radius": 0}])")) ==
        "t.json:1:122: at /drains/0/radius: 0 is out of range (0, 100000] (unit: m)");
    CHECK(errorOf(
              levelWith(R"(, "sensors": [{"name": "s", "shape": "circle", "center": [0, 0]}])")) ==
          "t.json:1:62: at /sensors/0: missing key 'radius'; expected a number in (0, 100000] "
          "(unit: m)");
    // Smaller than one lattice spacing: no particle, which is an error, not a silent no-op.
    CHECK(
        errorOf(levelWith(
            R"(, "blobs": [{"material": "water", "shape": "circle", "center": [0, 0], "radius": 0.001}])")) ==
        "t.json:1:60: at /blobs/0: the blob holds no particle: it is smaller than the "
        "material's lattice spacing 0.010026513 m");
    // Larger than the world may hold.
    CHECK(
        errorOf(levelWith(
            R"(, "world": {"maxParticles": 100}, "blobs": [{"material": "water", "shape": "box", "min": [0, 0], "max": [1, 1]}])")) ==
        "t.json:1:92: at /blobs/0: the blob spans about 9801 lattice points (spacing "
        "0.010026513 m); the world holds at most 100 particles (world.maxParticles)");
}

TEST_CASE("level errors: names are unique within their list", "[level][errors]") {
    CHECK(
        errorOf(
            R"({"version": 1, "materials": [{"name": "w"}, {"name": "w", "preset": "yoghurt"}]})") ==
        "t.json:1:54: at /materials/1/name: duplicate material name 'w' (first used at "
        "/materials/0/name); names must be unique");
    CHECK(
        errorOf(levelWith(
            R"(, "sensors": [{"name": "s", "shape": "circle", "center": [0, 0], "radius": 1}, {"name": "s", "shape": "circle", "center": [1, 0], "radius": 1}])")) ==
        "t.json:1:136: at /sensors/1/name: duplicate sensor name 's' (first used at "
        "/sensors/0/name); names must be unique");
    // world.gravity takes the plugin name "gravity".
    CHECK(
        errorOf(levelWith(
            R"(, "world": {"gravity": [0, -1]}, "plugins": [{"type": "force.gravity", "name": "gravity"}])")) ==
        "t.json:1:127: at /plugins/0/name: duplicate plugin name 'gravity' (first used at "
        "/world/gravity); names must be unique");
    CHECK(errorOf(levelWith(
              R"(, "emitters": [{"name": "", "material": "water", "position": [0, 0]}])")) ==
          "t.json:1:72: at /emitters/0/name: expected a non-empty name");
}

TEST_CASE("level errors: references must name an existing entry", "[level][errors]") {
    CHECK(
        errorOf(
            R"({"version": 1, "materials": [{"name": "water"}, {"name": "yoghurt", "preset": "yoghurt"}], "blobs": [{"material": "milk", "shape": "circle", "center": [0, 0], "radius": 0.1}]})") ==
        "t.json:1:115: at /blobs/0/material: unknown material 'milk'; known: water, yoghurt");
    CHECK(errorOf(
              levelWith(R"(, "goal": {"sensor": "cup", "material": "water", "fraction": 0.5})")) ==
          "t.json:1:69: at /goal/sensor: unknown sensor 'cup'; known: (none)");
    const std::string sensor =
        R"(, "sensors": [{"name": "cup", "shape": "box", "min": [0, 0], "max": [1, 1]}])";
    CHECK(errorOf(levelWith(sensor +
                            R"(, "goal": {"sensor": "cup", "material": "oil", "count": 5})")) ==
          "t.json:1:164: at /goal/material: unknown material 'oil'; known: water");
    CHECK(errorOf(levelWith(sensor + R"(, "goal": {"sensor": "cup", "material": "water"})")) ==
          "t.json:1:134: at /goal: missing the amount; expected one of 'fraction', 'count', "
          "'volume'");
    CHECK(errorOf(levelWith(
              sensor +
              R"(, "goal": {"sensor": "cup", "material": "water", "volume": 1, "count": 5})")) ==
          "t.json:1:186: at /goal/count: expected only one of 'fraction', 'count', 'volume'; "
          "'volume' is given too");
    CHECK(errorOf(levelWith(
              sensor + R"(, "goal": {"sensor": "cup", "material": "water", "fraction": 1.5})")) ==
          "t.json:1:185: at /goal/fraction: 1.5 is out of range (0, 1] (unit: 1)");
    // Every amount's name loads as its measure; a reference to nothing is an unknown name.
    const std::pair<const char*, GoalMeasure> measures[] = {{"fraction", GoalMeasure::Fraction},
                                                            {"count", GoalMeasure::Count},
                                                            {"volume", GoalMeasure::Volume}};
    for (const auto& [name, measure] : measures) {
        const Level lvl = parseLevel(levelWith(sensor +
                                               R"(, "goal": {"sensor": "cup", "material": )"
                                               R"("water", ")" +
                                               std::string(name) + R"(": 1})"),
                                     "t.json", builtins());
        CHECK(lvl.goal.measure == measure);
    }
    CHECK(
        codeOf(levelWith(R"(, "goal": {"sensor": "cup", "material": "water", "fraction": 0.5})")) ==
        ErrorCode::UnknownName);
}

TEST_CASE("level errors: world, material and plugin errors come back located at their block",
          "[level][errors]") {
    // An emitter whose rate its nozzle cannot fit: World::addEmitter's own message.
    EmitterDef def;
    def.position = {0.0f, 0.0f};
    def.width = 0.0f;
    def.rate = 10000.0f;
    std::string worldMessage;
    try {
        World world;
        def.material = world.addMaterial(water());
        world.addEmitter(def);
    } catch (const Error& e) {
        worldMessage = e.what();
    }
    REQUIRE_FALSE(worldMessage.empty());
    CHECK(
        errorOf(levelWith(
            R"(, "emitters": [{"name": "f", "material": "water", "position": [0, 0], "width": 0, "rate": 10000}])")) ==
        "t.json:1:63: at /emitters/0: " + worldMessage);

    // 1e-50 kg is in range as a double but 0 as a float: validate(Material) says so.
    CHECK(errorOf(R"({"version": 1, "materials": [{"name": "w", "mass": 1e-50}]})") ==
          "t.json:1:30: at /materials/0: material 'w': mass = 0 is out of range (0, 1000] "
          "(unit: kg)");

    // The WorldDef from the file and the options together: the world's message at /world.
    LevelOptions options;
    options.workerCount = 1000;
    CHECK(errorOf(levelWith(R"(, "world": {"frameRate": 60})"), options) ==
          "t.json:1:59: at /world: WorldDef: workerCount = 1000 is out of range [1, 256] (unit: "
          "count)");
}

TEST_CASE("level errors: LevelError carries its parts, lines count from 1", "[level][errors]") {
    const std::string text = "{\n"
                             "  \"version\": 1,\n"
                             "  \"materials\": [ { \"name\": \"water\" } ],\n"
                             "  \"world\": {\n"
                             "    \"frameRate\": -5\n"
                             "  }\n"
                             "}\n";
    try {
        parseLevel(text, "levels/multi.json", builtins());
        FAIL("no error");
    } catch (const LevelError& e) {
        CHECK(e.file() == "levels/multi.json");
        CHECK(e.line() == 5);
        CHECK(e.column() == 18);
        CHECK(e.path() == "/world/frameRate");
        CHECK(e.message() == "-5 is out of range [1, 1000] (unit: Hz)");
        CHECK(std::string(e.what()) ==
              "levels/multi.json:5:18: at /world/frameRate: -5 is out of range [1, 1000] (unit: "
              "Hz)");
    }
    // A byte order mark is skipped (as nlohmann does) and not counted as a column.
    CHECK(errorOf("\xEF\xBB\xBF{\"version\": 2, \"materials\": []}") ==
          "t.json:1:16: at /version: unsupported version 2; this loader reads version 1");
}

TEST_CASE("level errors: a file that cannot be read is a fluid::Error naming it",
          "[level][errors]") {
    const std::string path = std::string(FLUID_TEST_DATA_DIR) + "/does_not_exist.json";
    try {
        loadLevel(path, builtins());
        FAIL("no error");
    } catch (const LevelError&) {
        FAIL("a LevelError for a missing file");
    } catch (const Error& e) {
        CHECK(std::string(e.what()) ==
              "loadLevel: cannot open '" + path + "': No such file or directory");
    }
    // A directory opens but does not read.
    try {
        loadLevel(FLUID_TEST_DATA_DIR, builtins());
        FAIL("no error");
    } catch (const Error& e) {
        CHECK(std::string(e.what()) ==
              "loadLevel: cannot read '" + std::string(FLUID_TEST_DATA_DIR) + "': Is a directory");
    }
}

TEST_CASE("level errors: errors in a file name the file", "[level][errors]") {
    const std::string path = std::string(FLUID_TEST_DATA_DIR) + "/bad_plugin_param.json";
    try {
        loadLevel(path, builtins());
        FAIL("no error");
    } catch (const LevelError& e) {
        CHECK(std::string(e.what()) ==
              path + ":11:27: at /plugins/0/params/radius: 0 is out of range [0.0001, 10000] "
                     "(unit: m)");
    }
}
