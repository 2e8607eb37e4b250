// Error codes: each kind of failure the core reports carries its ErrorCode (docs/errors.md), and
// the name tables (error codes, qualities, solvers, equations of state) map every value to one
// name and back.
#include "test_support.h"

#include <catch2/catch.hpp>

#include <limits>
#include <optional>
#include <set>
#include <sstream>
#include <string>

using namespace fluid;
using namespace fluid::test;

namespace {

struct Failure {
    ErrorCode code = ErrorCode::BadArgument;
    std::string message;
};

// What `f` threw: its code and message (a test failure when it threw no fluid::Error).
template <class F> Failure failureOf(F&& f) {
    try {
        f();
    } catch (const Error& e) {
        return {e.code(), e.what()};
    }
    FAIL("no fluid::Error thrown");
    return {};
}

// Every value of `table` round-trips value -> name -> value, every name is unique and not
// empty, and a name not in the table is refused.
template <class Enum, std::size_t N, class Name, class From>
void checkTable(const EnumName<Enum> (&table)[N], Name name, From from) {
    std::set<std::string_view> names;
    for (const EnumName<Enum>& row : table) {
        CHECK(!row.name.empty());
        CHECK(names.insert(row.name).second);
        CHECK(name(row.value) == row.name);
        CHECK(from(row.name) == std::optional<Enum>(row.value));
        CHECK(from(std::string(row.name) + "x") == std::nullopt);
    }
    CHECK(from("") == std::nullopt);
    CHECK(from("no such name") == std::nullopt);
}

} // namespace

TEST_CASE("error codes: numeric values and names are stable", "[unit][errors]") {
    CHECK(int(ErrorCode::BadArgument) == 0);
    CHECK(int(ErrorCode::WrongState) == 1);
    CHECK(int(ErrorCode::OutOfRange) == 2);
    CHECK(int(ErrorCode::StaleId) == 3);
    CHECK(int(ErrorCode::UnknownName) == 4);
    CHECK(int(ErrorCode::Full) == 5);
    CHECK(int(ErrorCode::BadFile) == 6);
    CHECK(int(ErrorCode::Io) == 7);
    CHECK(int(ErrorCode::OutOfMemory) == 8);
    // The table lists every code once, in numeric order.
    REQUIRE(std::size(kErrorCodeNames) == 9);
    for (std::size_t k = 0; k < std::size(kErrorCodeNames); ++k) {
        CHECK(int(kErrorCodeNames[k].value) == int(k));
    }
    CHECK(errorCodeName(ErrorCode::BadArgument) == "bad argument");
    CHECK(errorCodeName(ErrorCode::WrongState) == "wrong state");
    CHECK(errorCodeName(ErrorCode::OutOfRange) == "out of range");
    CHECK(errorCodeName(ErrorCode::StaleId) == "stale id");
    CHECK(errorCodeName(ErrorCode::UnknownName) == "unknown name");
    CHECK(errorCodeName(ErrorCode::Full) == "full");
    CHECK(errorCodeName(ErrorCode::BadFile) == "bad file");
    CHECK(errorCodeName(ErrorCode::Io) == "i/o");
    CHECK(errorCodeName(ErrorCode::OutOfMemory) == "out of memory");
    CHECK(errorCodeName(ErrorCode(200)).empty());
    static_assert(errorCodeName(ErrorCode::StaleId) == "stale id");
    static_assert(errorCodeFromName("full") == ErrorCode::Full);
    checkTable(kErrorCodeNames, errorCodeName, errorCodeFromName);
    // The default code of an Error made without one.
    CHECK(Error("x").code() == ErrorCode::BadArgument);
}

TEST_CASE("name tables: every value round-trips name -> value -> name", "[unit][errors]") {
    checkTable(kQualityNames, qualityName, qualityFromName);
    checkTable(kSolverNames, solverName, solverFromName);
    checkTable(kEquationOfStateNames, equationOfStateName, equationOfStateFromName);
    CHECK(qualityName(Quality::Game) == "game");
    CHECK(qualityName(Quality::Precise) == "precise");
    CHECK(qualityFromName("Game") == std::nullopt); // exact, case-sensitive
    CHECK(solverName(Solver::PositionBased) == "position_based");
    CHECK(solverName(Solver::Explicit) == "explicit");
    CHECK(equationOfStateName(EquationOfState::Tait) == "tait");
    CHECK(equationOfStateName(EquationOfState::Linear) == "linear");
    // The lists messages quote, built from the tables.
    CHECK(namesIn(kQualityNames) == "game or precise");
    CHECK(namesIn(kQualityNames, ", ") == "game, precise");
    CHECK(namesIn(kSolverNames, ", ") == "position_based, explicit");
    CHECK(namesIn(kEquationOfStateNames) == "tait or linear");
    CHECK(namesIn(kErrorCodeNames, ", ").rfind("bad argument, wrong state, out of range, ", 0) ==
          0);
}

TEST_CASE("error codes: the core reports each kind with its code", "[unit][errors]") {
    World world;
    const MaterialId water = world.addMaterial(fluid::water());

    SECTION("bad argument: a null plugin, a value that is not finite, a bad shape") {
        Failure f = failureOf([&] { world.addForce(nullptr); });
        CHECK(f.code == ErrorCode::BadArgument);
        CHECK(f.message == "World::addForce: null plugin");
        f = failureOf([&] {
            world.addParticle({std::numeric_limits<float>::quiet_NaN(), 0.0f}, {0.0f, 0.0f}, water);
        });
        CHECK(f.code == ErrorCode::BadArgument);
        CHECK_THAT(f.message, Catch::Contains("is not finite"));
        f = failureOf([&] { validate(Shape::circle({0.0f, 0.0f}, -1.0f), "test"); });
        CHECK(f.code == ErrorCode::BadArgument);
        CHECK(f.message == "test: radius = -1 must be finite and > 0 (unit: m)");
        CHECK(shapeProblem(Shape::circle({0.0f, 0.0f}, -1.0f)) ==
              "radius = -1 must be finite and > 0 (unit: m)");
        CHECK(shapeProblem(Shape::circle({0.0f, 0.0f}, 1.0f)).empty());
    }
    SECTION("out of range: a frame time, a setting, a plugin parameter") {
        Failure f = failureOf([&] { world.step(-1.0f); });
        CHECK(f.code == ErrorCode::OutOfRange);
        CHECK_THAT(f.message, Catch::StartsWith("World::step: frameDt = -1 s is out of range"));
        WorldDef def;
        def.depth = -1.0f;
        f = failureOf([&] { World bad(def); });
        CHECK(f.code == ErrorCode::OutOfRange);
        GravityForce gravity;
        f = failureOf([&] { gravity.setParam("gy", 1e9); });
        CHECK(f.code == ErrorCode::OutOfRange);
        f = failureOf([&] { gravity.setParam("gy", std::numeric_limits<double>::quiet_NaN()); });
        CHECK(f.code == ErrorCode::BadArgument); // not finite
    }
    SECTION("stale id: a removed particle, an unknown material, another world's id") {
        const ParticleHandle h = world.addParticle({0.0f, 0.0f}, {0.0f, 0.0f}, water);
        world.removeParticle(h);
        Failure f = failureOf([&] { world.removeParticle(h); });
        CHECK(f.code == ErrorCode::StaleId);
        CHECK_THAT(f.message, Catch::Contains("stale particle handle"));
        f = failureOf([&] { (void)world.material(MaterialId{7}); });
        CHECK(f.code == ErrorCode::StaleId);
        CHECK(f.message == "unknown material id 7; the world has 1 materials");
        World other;
        const MaterialId foreign = other.addMaterial(fluid::water());
        f = failureOf([&] { (void)world.material(foreign); });
        CHECK(f.code == ErrorCode::StaleId);
        f = failureOf([&] { (void)groupCount(world, GroupHandle{}); });
        CHECK(f.code == ErrorCode::StaleId);
    }
    SECTION("unknown name: a plugin type or parameter") {
        Registry registry;
        registerBuiltinPlugins(registry);
        Failure f = failureOf([&] { (void)registry.create("force.nope"); });
        CHECK(f.code == ErrorCode::UnknownName);
        CHECK_THAT(f.message, Catch::StartsWith("unknown plugin type 'force.nope'; known: "));
        GravityForce gravity;
        f = failureOf([&] { gravity.setParam("strength", 1.0); });
        CHECK(f.code == ErrorCode::UnknownName);
    }
    SECTION("full: the particle cap") {
        BlobDef blob;
        blob.shape = Shape::box({0.0f, 0.0f}, {80.0f, 80.0f});
        blob.material = water;
        const Failure f = failureOf([&] { world.spawnBlob(blob); });
        CHECK(f.code == ErrorCode::Full);
        CHECK(f.message == "spawnBlob: particle cap exceeded: the blob needs about 6.36485e+07 "
                           "particles; maxParticles = 1048576");
    }
    SECTION("bad file: bytes that are not a snapshot, a snapshot the checks refuse") {
        Registry registry;
        registerBuiltinPlugins(registry);
        std::istringstream garbage("not a snapshot at all", std::ios::binary);
        Failure f = failureOf([&] { (void)World::load(garbage, registry); });
        CHECK(f.code == ErrorCode::BadFile);
        CHECK(f.message == "snapshot: not a fluid snapshot (no FLUIDSNP header)");
        // A snapshot with a plugin the registry lacks: an unknown name, not a bad file.
        world.addForce(std::make_unique<GravityForce>());
        std::ostringstream out(std::ios::binary);
        world.save(out);
        std::istringstream in(out.str(), std::ios::binary);
        f = failureOf([&] { (void)World::load(in, Registry{}); });
        CHECK(f.code == ErrorCode::UnknownName);
        CHECK_THAT(f.message, Catch::StartsWith("snapshot: plugin type 'force.gravity' is not in "
                                                "the registry"));
    }
    SECTION("i/o: a file that cannot be opened") {
        Registry registry;
        Failure f = failureOf([&] { (void)World::loadFile("/nonexistent/w.snap", registry); });
        CHECK(f.code == ErrorCode::Io);
        CHECK(f.message == "World::loadFile: cannot open '/nonexistent/w.snap'");
        f = failureOf([&] { world.saveFile("/nonexistent/w.snap"); });
        CHECK(f.code == ErrorCode::Io);
        CHECK(f.message == "World::saveFile: cannot open '/nonexistent/w.snap' for writing");
    }
}
