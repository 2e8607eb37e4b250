// Bit-identical state for 1, 2 and 4 workers of the world's own pool and for a host task hook:
// every stage gathers and writes only its own range, reductions use fixed blocks.
#include "test_support.h"

#include <catch2/catch.hpp>

#include <cinttypes>
#include <cstdio>
#include <filesystem>
#include <string>

using namespace fluid;
using namespace fluid::test;

namespace {

// A host task hook that runs every task inline, its ranges in reverse order, each range
// reporting a different worker index: the worst order a real scheduler could pick.
struct ReverseHook {
    static constexpr uint32_t kWorkers = 3;
    uint32_t tasks = 0;
    uint32_t ranges = 0;

    static void* enqueue(TaskCallback* callback, uint32_t itemCount, uint32_t minRange,
                         void* taskContext, void* userContext) {
        auto* self = static_cast<ReverseHook*>(userContext);
        ++self->tasks;
        // Ranges of minRange items, and an odd split so boundaries differ from any pool's.
        const uint32_t size = std::max(1u, minRange) + 7;
        const uint32_t count = (itemCount + size - 1) / size;
        for (uint32_t k = count; k-- > 0;) {
            const uint32_t begin = k * size;
            const uint32_t end = std::min(itemCount, begin + size);
            callback(begin, end, k % kWorkers, taskContext);
            ++self->ranges;
        }
        return nullptr; // done already
    }
    static void finish(void*, void*) {}

    TaskHook hook() {
        TaskHook h;
        h.enqueue = &ReverseHook::enqueue;
        h.finish = &ReverseHook::finish;
        h.workerCount = kWorkers;
        h.userContext = this;
        return h;
    }
};

// A small dam break: 50 x 42 = 2,100 particles (more than one 2,048-particle reduction block,
// nine 256-particle force ranges), gravity, a box. Explicit: 300 steps of 1 ms (about 6
// sub-steps each; 0.3 s: the column is collapsing and its front running, particles change
// cells, the walls project). Position-based: 90 frames of 1/60 s (4 sub-steps each; 1.5 s: the
// front hits the far wall and climbs it).
uint64_t damBits(const WorldDef& def, uint32_t* substeps = nullptr) {
    World world(def);
    const MaterialId w = world.addMaterial(water());
    const float s = world.spacing(w);
    const uint32_t cols = 50, rows = 42;
    world.addForce(std::make_unique<GravityForce>(0.0f, -kG));
    world.addBoundary(std::make_unique<BoxContainer>(0.0f, 0.0f, 4.0f * cols * s, 2.0f * rows * s));
    world.spawnBlob(latticeBlock(world, w, 0.0f, 0.0f, cols, rows));
    uint32_t total = 0;
    const bool explicitSolver = def.solver == Solver::Explicit;
    for (int step = 0; step < (explicitSolver ? 300 : 90); ++step) {
        world.step(explicitSolver ? 0.001f : kFrame);
        total += world.lastSubsteps();
    }
    REQUIRE(allFinite(world));
    if (substeps != nullptr) {
        *substeps = total;
    }
    return stateHash(world);
}

} // namespace

TEST_CASE("bit-identical state for 1, 2 and 4 workers and a host task hook",
          "[slow][long][determinism]") {
    const Solver solver = GENERATE(Solver::PositionBased, Solver::Explicit);
    CAPTURE(solverLabel(solver));
    Stopwatch sw(std::string("determinism, 4 runs, ") + solverLabel(solver));
    WorldDef def;
    def.solver = solver;
    def.workerCount = 1;
    uint32_t substeps = 0;
    const uint64_t serial = damBits(def, &substeps);
    CAPTURE(substeps);
    CHECK(substeps >= (solver == Solver::Explicit ? 1200u : 360u)); // several sub-steps per step

    def.workerCount = 2;
    const uint64_t two = damBits(def);
    def.workerCount = 4;
    const uint64_t four = damBits(def);

    ReverseHook reverse;
    WorldDef hooked;
    hooked.solver = solver;
    hooked.tasks = reverse.hook();
    const uint64_t host = damBits(hooked);

    INFO("hashes: serial " << std::hex << serial << ", 2 workers " << two << ", 4 workers " << four
                           << ", reverse hook " << host);
    std::printf("[measure] %s determinism: %u sub-steps; hashes %016" PRIx64 " %016" PRIx64
                " %016" PRIx64 " %016" PRIx64 "\n",
                solverLabel(solver), substeps, serial, two, four, host);
    CHECK(two == serial);
    CHECK(four == serial);
    CHECK(host == serial);
    // The hook was really used, with many ranges per task.
    CHECK(reverse.tasks > 1000);
    CHECK(reverse.ranges > 2 * reverse.tasks);
}

namespace {

// A water dam (one material: the pair passes' one-material path, one support), and the same
// with a yoghurt block beside it (two materials and supports: their general path), 40 frames of
// the position-based solver each; the hash of the final state. `shear`: the yoghurt steps with
// the shear constraint (PositionBasedDef::shearConstraint), whose pair passes have the same two
// paths.
uint64_t runDams(bool mixed, bool shear = false) {
    WorldDef def;
    def.positionBased.shearConstraint = shear ? 1 : 0;
    World world(def);
    const MaterialId w = world.addMaterial(water());
    const float s = world.spacing(w);
    const uint32_t cols = 30, rows = 40;
    world.addForce(std::make_unique<GravityForce>(0.0f, -kG));
    world.addBoundary(std::make_unique<BoxContainer>(0.0f, 0.0f, 4.0f * cols * s, 2.0f * rows * s));
    world.spawnBlob(latticeBlock(world, w, 0.0f, 0.0f, cols, rows));
    if (mixed) {
        const MaterialId y = world.addMaterial(yoghurt());
        world.spawnBlob(latticeBlock(world, y, 3.0f * cols * s, 0.0f, 20, 20));
    }
    for (int step = 0; step < 40; ++step) {
        world.step(kFrame);
    }
    REQUIRE(allFinite(world));
    return stateHash(world);
}

// A yoghurt block alone with the shear constraint (its passes' one-material path), 40 frames.
uint64_t runPaste() {
    WorldDef def;
    def.positionBased.shearConstraint = 1;
    World world(def);
    const MaterialId y = world.addMaterial(yoghurt());
    const float s = world.spacing(y);
    world.addForce(std::make_unique<GravityForce>(0.0f, -kG));
    world.addBoundary(std::make_unique<BoxContainer>(0.0f, 0.0f, 60.0f * s, 40.0f * s));
    world.spawnBlob(latticeBlock(world, y, 0.0f, 0.0f, 20, 20));
    for (int step = 0; step < 40; ++step) {
        world.step(kFrame);
    }
    REQUIRE(allFinite(world));
    return stateHash(world);
}

} // namespace

// Run by the test below in a child process with FLUID_SIMD set: prints the instruction set the
// pair passes used and the hashes.
TEST_CASE("the game preset (coarse correction) is bit-identical for 1, 2 and 4 workers",
          "[slow][determinism]") {
    Stopwatch sw("determinism, game preset, 3 runs");
    WorldDef def;
    def.positionBased = positionBasedPreset(Quality::Game);
    def.workerCount = 1;
    const uint64_t serial = damBits(def);
    def.workerCount = 2;
    const uint64_t two = damBits(def);
    def.workerCount = 4;
    const uint64_t four = damBits(def);
    INFO("hashes: serial " << std::hex << serial << ", 2 workers " << two << ", 4 workers "
                           << four);
    CHECK(two == serial);
    CHECK(four == serial);
}

TEST_CASE("instruction-set hash (child of the test below)", "[.isa-hash]") {
    std::printf("isa=%s hash=%016" PRIx64 "\n", instructionSet(),
                ((runDams(false) * 31u + runDams(true)) * 31u + runDams(true, true)) * 31u +
                    runPaste());
}

TEST_CASE("bit-identical state on every instruction set the machine runs", "[slow][determinism]") {
    struct Set {
        const char* name;
        bool runs;
    };
#if defined(__x86_64__)
    const Set sets[] = {{"sse2", true},
                        {"avx2", __builtin_cpu_supports("avx2") != 0},
                        {"avx512", __builtin_cpu_supports("avx512f") != 0}};
#else
    const Set sets[] = {{"sse2", true}};
#endif
    const std::string self = std::filesystem::read_symlink("/proc/self/exe").string();
    std::string first;
    for (const Set& set : sets) {
        if (!set.runs) {
            continue;
        }
        const std::string command =
            std::string("FLUID_SIMD=") + set.name + " '" + self + "' '[.isa-hash]' 2>&1";
        const ShellRun child = runShell(command);
        REQUIRE(child.started);
        CHECK(child.status == 0);
        const std::string& out = child.output;
        const size_t at = out.find("isa=");
        REQUIRE(at != std::string::npos);
        const std::string line = out.substr(at, out.find('\n', at) - at);
        CAPTURE(set.name, line);
        std::printf("[measure] %s\n", line.c_str());
        CHECK(line.rfind(std::string("isa=") + set.name + " ", 0) == 0); // the set really ran
        const std::string hash = line.substr(line.find("hash="));
        if (first.empty()) {
            first = hash;
        }
        CHECK(hash == first);
    }
}
