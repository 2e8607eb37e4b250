// Snapshots: a restored world continues bit-identically; damaged files are refused clearly.
#include "test_support.h"
#include "virtual_file.h"

#include <catch2/catch.hpp>

#include <cstdio>
#include <cstring>
#include <sstream>
#include <string>

using namespace fluid;
using fluid::test::builtins;
using fluid::test::kFrame;
using fluid::test::restored;
using fluid::test::saved;

namespace {

// A scene with every kind of saved state: two materials, gravity, a tank, an emitter with
// jitter and lifetimes, a drain, a sensor, removed particles (free slots in the handle table).
World scene(Solver solver, uint32_t workers) {
    WorldDef def;
    def.solver = solver;
    def.workerCount = workers;
    World world(def);
    const MaterialId water = world.addMaterial(fluid::water());
    const MaterialId yoghurt = world.addMaterial(fluid::test::forSolver(fluid::yoghurt(), solver));
    Registry registry;
    registerBuiltinPlugins(registry);
    world.addForce(registry.createForce("force.gravity"));
    const std::array<ParamValue, 4> tank{
        {{"minX", 0.0}, {"minY", 0.0}, {"maxX", 0.4}, {"maxY", 0.6}}};
    world.addBoundary(registry.createBoundary("boundary.box", tank));
    world.spawnBlob(fluid::test::latticeBlock(world, water, 0.0f, 0.0f, 12, 10));
    BlobDef ball;
    ball.shape.type = ShapeType::Circle;
    ball.shape.center = {0.3f, 0.2f};
    ball.shape.radius = 0.05f;
    ball.material = yoghurt;
    ball.lifetime = 0.4f;
    world.spawnBlob(ball);
    EmitterDef faucet;
    faucet.position = {0.2f, 0.5f};
    faucet.direction = {0.3f, -1.0f};
    faucet.width = 0.03f;
    faucet.rate = 200.0f;
    faucet.jitter = 0.25f;
    faucet.seed = 42;
    faucet.lifetime = 0.7f;
    world.addEmitter(faucet);
    DrainDef drain;
    drain.shape = Shape::box({0.3f, 0.0f}, {0.4f, 0.05f});
    world.addDrain(drain);
    SensorDef sensor;
    sensor.shape = Shape::circle({0.1f, 0.05f}, 0.1f);
    world.addSensor(sensor);
    return world;
}

// Raw bytes of everything a reader sees, in slot order.
std::string fingerprint(const World& world) {
    std::string out;
    auto add = [&](const void* data, size_t size) {
        out.append(static_cast<const char*>(data), size);
    };
    for (auto span : {world.positionX(), world.positionY(), world.velocityX(), world.velocityY(),
                      world.density(), world.pressure()}) {
        add(span.data(), span.size_bytes());
    }
    add(world.materialIndex().data(), world.materialIndex().size_bytes());
    // Handles by slot and generation: their world tag names the World object, not its state
    // (a loaded copy has its own).
    for (uint32_t i = 0; i < world.particleCount(); ++i) {
        const ParticleHandle h = world.handleAt(i);
        add(&h.slot, sizeof(h.slot));
        add(&h.generation, sizeof(h.generation));
        const float life = world.lifetime(h);
        add(&life, sizeof(life));
    }
    for (const RemovedEvent& e : world.removedEvents()) {
        out += fluid::test::removalRecord(e);
    }
    const auto r = world.sensorReading(SensorId{0});
    add(r.data(), r.size_bytes());
    const uint32_t emitted = world.emittedCount(EmitterId{0});
    add(&emitted, sizeof(emitted));
    const double t = world.time();
    add(&t, sizeof(t));
    return out;
}

} // namespace

TEST_CASE("snapshot: a restored world continues bit-identically", "[snapshot]") {
    const Solver solver = GENERATE(Solver::PositionBased, Solver::Explicit);
    INFO(fluid::test::solverLabel(solver));
    const Registry& registry = builtins();
    World original = scene(solver, 1);
    const int before = solver == Solver::Explicit ? 8 : 30;
    for (int f = 0; f < before; ++f) {
        original.step(kFrame);
    }
    const std::string bytes = saved(original);
    World copy = restored(bytes, registry);
    World copyTwoWorkers = restored(bytes, registry, 2);
    CHECK(copy.particleCount() == original.particleCount());
    CHECK(copy.time() == original.time());
    // Saving the restored world gives the same bytes.
    CHECK(saved(copy) == bytes);
    for (int f = 0; f < before; ++f) {
        original.step(kFrame);
        copy.step(kFrame);
        copyTwoWorkers.step(kFrame);
    }
    REQUIRE(original.particleCount() > 0);
    CHECK(fingerprint(copy) == fingerprint(original));
    CHECK(fingerprint(copyTwoWorkers) == fingerprint(original));
    CHECK(copyTwoWorkers.def().workerCount == 2);
}

TEST_CASE("snapshot: the same state saves to the same bytes, without wall-clock times",
          "[snapshot]") {
    const Solver solver = GENERATE(Solver::PositionBased, Solver::Explicit);
    INFO(fluid::test::solverLabel(solver));
    // Two worlds stepped alike reach the same state in different wall-clock times.
    World first = scene(solver, 1);
    World second = scene(solver, 1);
    for (int f = 0; f < 6; ++f) {
        first.step(kFrame);
        second.step(kFrame);
    }
    REQUIRE(fingerprint(first) == fingerprint(second));
    REQUIRE(first.profile().step > 0.0f);
    const std::string bytes = saved(first);
    CHECK(saved(second).size() == bytes.size());
    CHECK(saved(second) == bytes);
    // The counts survive; the stage times read 0 after a load.
    const World copy = restored(bytes, builtins());
    CHECK(copy.profile().particles == first.profile().particles);
    CHECK(copy.profile().substeps == first.profile().substeps);
    REQUIRE(first.profile().stageCount > 0);
    CHECK(copy.profile().step == 0.0f);
    CHECK(copy.profile().stageCount == 0);
    CHECK(copy.profile().stage("sort") == 0.0f);
}

TEST_CASE("snapshot: files round-trip, a missing file names its path", "[snapshot]") {
    const Registry& registry = builtins();
    World world = scene(Solver::PositionBased, 1);
    world.step(kFrame);
    const std::string path = "fluid_test_snapshot.bin";
    world.saveFile(path);
    World back = World::loadFile(path, registry);
    CHECK(fingerprint(back) == fingerprint(world));
    std::remove(path.c_str());
    CHECK_THROWS_WITH(World::loadFile("no/such/file.snap", registry),
                      "World::loadFile: cannot open 'no/such/file.snap'");
}

TEST_CASE("snapshot: truncated, corrupt or foreign data is refused", "[snapshot]") {
    const Registry& registry = builtins();
    World world = scene(Solver::PositionBased, 1);
    world.step(kFrame);
    const std::string bytes = saved(world);

    CHECK_THROWS_WITH(
        restored(bytes.substr(0, bytes.size() - 9), registry),
        Catch::Matchers::StartsWith("snapshot: truncated or padded: the header promises"));
    CHECK_THROWS_WITH(restored(bytes.substr(0, 10), registry),
                      "snapshot: not a fluid snapshot (no FLUIDSNP header)");
    CHECK_THROWS_WITH(restored("not a snapshot at all, just text", registry),
                      "snapshot: not a fluid snapshot (no FLUIDSNP header)");
    std::string flipped = bytes;
    flipped[bytes.size() / 2] = char(flipped[bytes.size() / 2] ^ 0x10);
    CHECK_THROWS_WITH(restored(flipped, registry), "snapshot: corrupt: checksum mismatch");
    std::string version = bytes;
    version[8] = 8;
    CHECK_THROWS_WITH(
        restored(version, registry),
        "snapshot: format version 8 is not supported; this fluid reads versions 6 to 7");
    version[8] = 5;
    CHECK_THROWS_WITH(
        restored(version, registry),
        "snapshot: format version 5 is not supported; this fluid reads versions 6 to 7");
    // Every truncation point is refused, none crashes.
    for (size_t cut = 0; cut < bytes.size(); cut += 97) {
        CHECK_THROWS_AS(restored(bytes.substr(0, cut), registry), Error);
    }
    const Registry empty;
    CHECK_THROWS_WITH(restored(bytes, empty),
                      "snapshot: plugin type 'force.gravity' is not in the registry; register it "
                      "(or load its plugin library) before loading the snapshot");
}

namespace {

// `bytes` with the carried frame time (the double after the time, found by both values)
// replaced by `carry` and the checksum made right again.
std::string withCarry(const World& world, std::string bytes, double carry) {
    char pair[16];
    const double time = world.time(), old = world.carriedTime();
    std::memcpy(pair, &time, 8);
    std::memcpy(pair + 8, &old, 8);
    const size_t at = bytes.find(std::string(pair, 16));
    REQUIRE(at != std::string::npos);
    REQUIRE(bytes.find(std::string(pair, 16), at + 1) == std::string::npos);
    std::memcpy(bytes.data() + at + 8, &carry, 8);
    const size_t payload = 8 + 4 + 8; // magic, version, size
    const uint64_t sum = fluid::test::fnv1a(bytes.data() + payload, bytes.size() - payload - 8,
                                            14695981039346656037ull); // FNV-1a 64's basis
    std::memcpy(bytes.data() + bytes.size() - 8, &sum, 8);
    return bytes;
}

} // namespace

TEST_CASE("snapshot: a negative carried frame time saves and steps on bit-identically, and one "
          "beyond half the longest sub-step is refused",
          "[snapshot][clock]") {
    const Registry& registry = builtins();
    World original = scene(Solver::PositionBased, 1);
    for (int f = 0; f < 5; ++f) {
        original.step(kFrame);
    }
    original.step(float(1.0 / 240.0 - 1e-7)); // takes its sub-step, owes the rest
    CHECK(original.lastSubsteps() == 1);
    REQUIRE(original.carriedTime() < 0.0);
    const std::string bytes = saved(original);
    World copy = restored(bytes, registry);
    CHECK(copy.carriedTime() == original.carriedTime());
    CHECK(saved(copy) == bytes);
    for (const float dt : {float(1.0 / 240.0 - 1e-7), 0.001f, kFrame, 1.0f / 59.94f}) {
        original.step(dt);
        copy.step(dt);
        CHECK(copy.lastSubsteps() == original.lastSubsteps());
        CHECK(copy.carriedTime() == original.carriedTime());
    }
    CHECK(fingerprint(copy) == fingerprint(original));

    // Half the longest sub-step (1/60 s with one per frame) is the most it can owe.
    CHECK_THROWS_WITH(restored(withCarry(original, saved(original), -0.01), registry),
                      "snapshot: corrupt: the carried frame time is -0.01 s, less than minus half "
                      "the longest sub-step (-1/120 s)");
    // Up to one sub-step, as earlier releases carried, loads and steps on.
    World earlier = restored(withCarry(original, saved(original), 0.004), registry);
    CHECK(earlier.carriedTime() == 0.004);
    earlier.step(1.0f / 240.0f);
    CHECK(earlier.lastSubsteps() == 2); // 1.96 sub-steps due
}

TEST_CASE("snapshot: a plugin's parameters pass the plugin's own checks, all together",
          "[snapshot][bad-input]") {
    const Registry& registry = builtins();
    World world = scene(Solver::PositionBased, 1);
    world.step(kFrame);
    const std::string bytes = saved(world);
    // The tank's maxY (0.6), stored as a double after its name, set to -0 and the checksum
    // made right again: each value is in range, but the box is empty. Before, the snapshot
    // loaded and every step failed in the box's prepare.
    const std::size_t name = bytes.find("maxY");
    REQUIRE(name != std::string::npos);
    REQUIRE(bytes.find("maxY", name + 1) == std::string::npos);
    double maxY = 0.0;
    std::memcpy(&maxY, bytes.data() + name + 4, sizeof(maxY));
    REQUIRE(maxY == 0.6);
    const auto forged = [&](double value) {
        std::string out = bytes;
        std::memcpy(out.data() + name + 4, &value, sizeof(value));
        uint64_t size = 0;
        std::memcpy(&size, out.data() + 12, sizeof(size));
        uint64_t sum = 0xcbf29ce484222325ull; // FNV-1a 64 of the payload
        for (std::size_t k = 20; k < 20 + size; ++k) {
            sum ^= uint8_t(out[k]);
            sum *= 0x100000001b3ull;
        }
        std::memcpy(out.data() + 20 + size, &sum, sizeof(sum));
        return out;
    };
    REQUIRE_NOTHROW(restored(forged(0.5), registry)); // resealed right
    CHECK_THROWS_MATCHES(restored(forged(-0.0), registry), Error,
                         Catch::Message("snapshot: boundary plugin 0: plugin 'boundary.box': the "
                                        "inner rectangle [0, 0.4] x [0, -0] is empty; expected "
                                        "minX < maxX and minY < maxY"));
    // A value out of its declared range names the plugin's place too.
    CHECK_THROWS_MATCHES(restored(forged(1e300), registry), Error,
                         Catch::Message("snapshot: boundary plugin 0: plugin 'boundary.box': "
                                        "parameter 'maxY' = 1e+300 is out of range [-100000, "
                                        "100000] (unit: m)"));
}

TEST_CASE("snapshot: a huge file is refused from its header, before its body is read",
          "[snapshot]") {
    const Registry& registry = builtins();
    const auto header = [](uint32_t version, uint64_t size) {
        std::string head("FLUIDSNP", 8);
        head.append(reinterpret_cast<const char*>(&version), sizeof(version));
        head.append(reinterpret_cast<const char*>(&size), sizeof(size));
        return head;
    };
    const uint64_t body = uint64_t(256) << 20; // 256 MiB that are never needed
    {
        test::VirtualFile file(header(9, body - 8), body);
        std::istream in(&file);
        CHECK_THROWS_MATCHES(
            World::load(in, registry), Error,
            Catch::Message("snapshot: format version 9 is not supported; this fluid reads "
                           "versions 6 to 7"));
        CHECK(file.served() <= 65536); // the first window only
    }
    {
        // The right version, but the header promises more than the file holds.
        test::VirtualFile file(header(6, uint64_t(1) << 40), body);
        std::istream in(&file);
        CHECK_THROWS_MATCHES(
            World::load(in, registry), Error,
            Catch::Message("snapshot: truncated or padded: the header promises 1099511627776 "
                           "bytes of data and a checksum, the file holds 268435456 bytes after "
                           "the header"));
        CHECK(file.served() <= 65536);
    }
}
