// fluid-run, the headless runner: CSV statistics, level saves, threads, bad input.
#include "test_support.h"

#include <fluid/level.h>

#include <catch2/catch.hpp>

#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

#ifdef FLUID_RUN_PATH

namespace fs = std::filesystem;
using namespace fluid;

namespace {

struct Run {
    int status = -1;
    std::string out, err;
};

std::string slurp(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// Runs fluid-run with `args` (each quoted for the shell) in a scratch directory, capturing its
// output and exit status.
Run fluidRun(const std::vector<std::string>& args, const fs::path& dir) {
    fs::create_directories(dir);
    const fs::path out = dir / "stdout.txt", err = dir / "stderr.txt";
    std::ostringstream command;
    command << std::quoted(FLUID_RUN_PATH);
    for (const std::string& arg : args) {
        command << ' ' << std::quoted(arg);
    }
    command << " >" << std::quoted(out.string()) << " 2>" << std::quoted(err.string())
            << " </dev/null";
    const int raw = std::system(command.str().c_str());
    Run run;
    run.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    run.out = slurp(out);
    run.err = slurp(err);
    return run;
}

std::vector<std::vector<std::string>> readCsv(const fs::path& path) {
    std::vector<std::vector<std::string>> rows;
    std::ifstream in(path);
    std::string line;
    while (std::getline(in, line)) {
        std::vector<std::string> cells;
        std::stringstream s(line);
        std::string cell;
        while (std::getline(s, cell, ',')) {
            cells.push_back(cell);
        }
        if (!line.empty() && line.back() == ',') {
            cells.emplace_back();
        }
        rows.push_back(cells);
    }
    return rows;
}

const std::string kDam = std::string(FLUID_LEVELS_DIR) + "/dam_break.json";

} // namespace

TEST_CASE("fluid-run writes one CSV row per frame with the documented columns", "[fluid-run]") {
    const fs::path dir = fs::temp_directory_path() / "fluid_run_csv";
    fs::remove_all(dir);
    const Run run = fluidRun({kDam, "--frames", "20", "--csv", (dir / "a.csv").string()}, dir);
    INFO(run.err);
    REQUIRE(run.status == 0);
    CHECK(run.out.find("fluid-run: ") == 0);
    const auto rows = readCsv(dir / "a.csv");
    REQUIRE(rows.size() == 21);
    const std::vector<std::string> first{"frame",
                                         "time",
                                         "particles",
                                         "substeps",
                                         "kinetic_energy",
                                         "density_error_mean",
                                         "density_error_max"};
    REQUIRE(rows[0].size() > first.size());
    for (size_t k = 0; k < first.size(); ++k) {
        CHECK(rows[0][k] == first[k]);
    }
    // Per material: count, extent and centre of mass.
    CHECK(std::find(rows[0].begin(), rows[0].end(), "m_water_cx") != rows[0].end());
    CHECK(std::find(rows[0].begin(), rows[0].end(), "m_water_xmax") != rows[0].end());
    // The same numbers as playing the level in-process.
    Registry registry;
    registerBuiltinPlugins(registry);
    Level level = loadLevel(kDam, registry);
    double kinetic = 0.0;
    for (int f = 1; f <= 20; ++f) {
        level.world.step(1.0f / level.frameRate);
        REQUIRE(rows[f].size() == rows[0].size());
        CHECK(std::stoi(rows[f][0]) == f);
        CHECK(std::stod(rows[f][1]) == Approx(level.world.time()));
        CHECK(std::stoul(rows[f][2]) == level.world.particleCount());
        CHECK(std::stoul(rows[f][3]) == level.world.profile().substeps);
        kinetic = std::stod(rows[f][4]);
    }
    // The dam is falling: kinetic energy is positive by frame 20.
    CHECK(kinetic > 0.0);
    fs::remove_all(dir);
}

TEST_CASE("fluid-run: the CSV is identical for 1 and 2 threads", "[fluid-run]") {
    const fs::path dir = fs::temp_directory_path() / "fluid_run_threads";
    fs::remove_all(dir);
    const Run one = fluidRun(
        {kDam, "--frames", "15", "--threads", "1", "--csv", (dir / "1.csv").string()}, dir);
    const Run two = fluidRun(
        {kDam, "--frames", "15", "--threads", "2", "--csv", (dir / "2.csv").string()}, dir);
    REQUIRE(one.status == 0);
    REQUIRE(two.status == 0);
    CHECK(slurp(dir / "1.csv") == slurp(dir / "2.csv"));
    fs::remove_all(dir);
}

TEST_CASE("fluid-run's saves restore to the state the run reached, and fluid-run plays on "
          "from them bit-identically",
          "[fluid-run]") {
    const fs::path dir = fs::temp_directory_path() / "fluid_run_snap";
    fs::remove_all(dir);
    const Run run = fluidRun({kDam, "--frames", "12", "--snapshot-every", "5", "--csv",
                              (dir / "full.csv").string(), "--out", (dir / "snaps").string()},
                             dir);
    INFO(run.err);
    REQUIRE(run.status == 0);
    // Level saves, for a level without bodies too: a file fluid-run writes, fluid-run reads.
    CHECK(fs::exists(dir / "snaps" / "frame_000005.level"));
    CHECK(fs::exists(dir / "snaps" / "frame_000010.level"));
    CHECK(!fs::exists(dir / "snaps" / "frame_000010.snap"));
    CHECK(!fs::exists(dir / "snaps" / "frame_000012.level"));
    Registry registry;
    registerBuiltinPlugins(registry);
    const Level restored =
        loadLevelSave((dir / "snaps" / "frame_000010.level").string(), registry);
    Level level = loadLevel(kDam, registry);
    for (int f = 0; f < 10; ++f) {
        level.world.step(1.0f / level.frameRate);
    }
    CHECK(fluid::test::stateHash(restored.world) == fluid::test::stateHash(level.world));
    CHECK(restored.frameRate == level.frameRate);
    // Played on from frame 10 for 2 frames: frame 12's row of the whole run, every column.
    const Run resumed = fluidRun({(dir / "snaps" / "frame_000010.level").string(), "--frames",
                                  "2", "--csv", (dir / "resumed.csv").string()},
                                 dir);
    INFO(resumed.err);
    REQUIRE(resumed.status == 0);
    const auto full = readCsv(dir / "full.csv");
    const auto part = readCsv(dir / "resumed.csv");
    REQUIRE(full.size() == 13);
    REQUIRE(part.size() == 3);
    CHECK(part[0] == full[0]);
    for (size_t k = 1; k < full[12].size(); ++k) { // all but the frame number
        INFO(full[0][k]);
        CHECK(part[2][k] == full[12][k]);
    }
    fs::remove_all(dir);
}

TEST_CASE("fluid-run: a world snapshot is refused by its magic, saying what it is and what to "
          "give",
          "[fluid-run]") {
    const fs::path dir = fs::temp_directory_path() / "fluid_run_world_snap";
    fs::remove_all(dir);
    fs::create_directories(dir);
    Registry registry;
    registerBuiltinPlugins(registry);
    Level level = loadLevel(kDam, registry);
    level.step();
    for (const char* name : {"world.snap", "world.json"}) {
        const fs::path snap = dir / name;
        level.world.saveFile(snap.string());
        const Run run = fluidRun({snap.string(), "--frames", "1"}, dir);
        CHECK(run.status == 1);
        CHECK(run.err == "fluid-run: '" + snap.string() +
                             "' is a world snapshot (World::saveFile), not a level: it holds no "
                             "goal, names or frame rate to play on with; give a level file "
                             "(.json) or a level save (.level, as --snapshot-every writes)\n");
    }
    fs::remove_all(dir);
}

TEST_CASE("fluid-run: bad input exits non-zero with the loader's message", "[fluid-run]") {
    const fs::path dir = fs::temp_directory_path() / "fluid_run_bad";
    fs::remove_all(dir);
    fs::create_directories(dir);
    const fs::path bad = dir / "bad.json";
    std::ofstream(bad) << "{\n  \"version\": 1,\n  \"wrold\": {}\n}\n";
    const Run run = fluidRun({bad.string(), "--frames", "5"}, dir);
    CHECK(run.status == 1);
    CHECK(run.err.find(bad.string() + ":3:") == 0);
    CHECK(run.err.find("wrold") != std::string::npos);

    const Run missing = fluidRun({(dir / "nope.json").string(), "--frames", "5"}, dir);
    CHECK(missing.status == 1);
    CHECK(missing.err.find("nope.json") != std::string::npos);

    const Run noOut = fluidRun({kDam, "--frames", "5", "--snapshot-every", "2"}, dir);
    CHECK(noOut.status == 2);
    CHECK(noOut.err == "fluid-run: --snapshot-every needs --out DIR\n");

    const Run noFrames = fluidRun({kDam}, dir);
    CHECK(noFrames.status != 0);
    CHECK(noFrames.err.find("--frames") != std::string::npos);
    fs::remove_all(dir);
}

TEST_CASE("fluid-run: an empty or damaged .level file is refused as a save, by its name",
          "[fluid-run]") {
    const fs::path dir = fs::temp_directory_path() / "fluid_run_empty_save";
    fs::remove_all(dir);
    fs::create_directories(dir);
    const fs::path empty = dir / "empty.level";
    std::ofstream(empty, std::ios::binary).close();
    const Run run = fluidRun({empty.string(), "--frames", "1"}, dir);
    CHECK(run.status == 1);
    CHECK(run.err ==
          "level save '" + empty.string() + "': not a level save (no FLUIDLVL header)\n");
    fs::remove_all(dir);
}

TEST_CASE("fluid-run writes each Box2D body's pose, velocity and submerged fraction",
          "[fluid-run][bodies]") {
    const fs::path dir = fs::temp_directory_path() / "fluid_run_bodies";
    fs::remove_all(dir);
    const std::string crates = std::string(FLUID_LEVELS_DIR) + "/crates.json";
    const Run run = fluidRun({crates, "--frames", "30", "--csv", (dir / "b.csv").string()}, dir);
    INFO(run.err);
    REQUIRE(run.status == 0);
    CHECK(run.out.find(", 9 bodies") != std::string::npos);
    const auto rows = readCsv(dir / "b.csv");
    REQUIRE(rows.size() == 31);
    const std::vector<std::string>& header = rows[0];
    // Seven columns per body, in file order, after the fluid's.
    const std::vector<std::string> bodies{"tank",  "cork",  "pine", "oak",   "ball",
                                          "brick", "stone", "hull", "barrel"};
    const std::vector<std::string> fields{"x", "y", "angle", "vx", "vy", "omega", "submerged"};
    REQUIRE(header.size() >= bodies.size() * fields.size());
    const size_t first = header.size() - bodies.size() * fields.size();
    CHECK(header[first - 1] == "m_water_cy");
    for (size_t b = 0; b < bodies.size(); ++b) {
        for (size_t f = 0; f < fields.size(); ++f) {
            CHECK(header[first + b * fields.size() + f] == "b_" + bodies[b] + "_" + fields[f]);
        }
    }
    const auto column = [&](const std::string& name) {
        const auto it = std::find(header.begin(), header.end(), name);
        REQUIRE(it != header.end());
        return size_t(it - header.begin());
    };
    // The same numbers as playing the level in-process, all finite; the tank is dry (not coupled):
    // its submerged cell is empty.
    Registry registry;
    registerBuiltinPlugins(registry);
    Level level = loadLevel(crates, registry);
    for (int f = 1; f <= 30; ++f) {
        level.step();
        REQUIRE(rows[f].size() == header.size());
        for (size_t k = first; k < header.size(); ++k) {
            if (header[k] == "b_tank_submerged") {
                CHECK(rows[f][k].empty());
                continue;
            }
            INFO(header[k] << " at frame " << f);
            REQUIRE_FALSE(rows[f][k].empty());
            CHECK(std::isfinite(std::stod(rows[f][k])));
        }
    }
    const b2Body* brick = level.bodies[5].second;
    CHECK(std::stod(rows[30][column("b_brick_x")]) == Approx(brick->GetPosition().x));
    CHECK(std::stod(rows[30][column("b_brick_y")]) == Approx(brick->GetPosition().y));
    CHECK(std::stod(rows[30][column("b_brick_angle")]) == Approx(brick->GetAngle()));
    CHECK(std::stod(rows[30][column("b_brick_vy")]) ==
          Approx(brick->GetLinearVelocity().y).margin(1e-6));
    CHECK(std::stod(rows[30][column("b_brick_submerged")]) ==
          Approx(level.coupling->report(brick)->submergedFraction));
    // The stone falls from 0.6 m: by frame 30 (0.5 s) it has dropped into the water.
    CHECK(std::stod(rows[30][column("b_stone_y")]) < 0.3);
    // The barrel was given 2 rad/s: it turns.
    CHECK(std::stod(rows[1][column("b_barrel_omega")]) == Approx(2.0).margin(0.1));
    fs::remove_all(dir);
}

TEST_CASE("fluid-run: with Box2D bodies the CSV is identical for 1 and 2 threads",
          "[fluid-run][bodies]") {
    const fs::path dir = fs::temp_directory_path() / "fluid_run_bodies_threads";
    fs::remove_all(dir);
    const std::string crates = std::string(FLUID_LEVELS_DIR) + "/crates.json";
    const Run one = fluidRun(
        {crates, "--frames", "20", "--threads", "1", "--csv", (dir / "1.csv").string()}, dir);
    const Run two = fluidRun(
        {crates, "--frames", "20", "--threads", "2", "--csv", (dir / "2.csv").string()}, dir);
    REQUIRE(one.status == 0);
    REQUIRE(two.status == 0);
    CHECK(slurp(dir / "1.csv") == slurp(dir / "2.csv"));
    fs::remove_all(dir);
}

TEST_CASE("fluid-run saves a level with bodies as level saves and plays on from one",
          "[fluid-run][bodies]") {
    const fs::path dir = fs::temp_directory_path() / "fluid_run_bodies_snap";
    fs::remove_all(dir);
    const std::string wheel = std::string(FLUID_LEVELS_DIR) + "/paddle_wheel.json";
    const Run run = fluidRun({wheel, "--frames", "4", "--snapshot-every", "2", "--csv",
                              (dir / "full.csv").string(), "--out", (dir / "s").string()},
                             dir);
    REQUIRE(run.status == 0);
    CHECK(run.err.find("warning") == std::string::npos);
    REQUIRE(fs::exists(dir / "s" / "frame_000002.level"));
    REQUIRE(fs::exists(dir / "s" / "frame_000004.level"));
    // The save holds the Box2D world: it loads with the built-in registry.
    Registry registry;
    registerBuiltinPlugins(registry);
    const Level saved = loadLevelSave((dir / "s" / "frame_000002.level").string(), registry);
    CHECK(saved.bodies.size() == 2);
    // Played on from frame 2 for 2 frames, it reaches frame 4's time and particle count.
    const Run resumed = fluidRun({(dir / "s" / "frame_000002.level").string(), "--frames", "2",
                                  "--csv", (dir / "resumed.csv").string()},
                                 dir);
    REQUIRE(resumed.status == 0);
    const auto lastRow = [](const std::string& text) {
        std::vector<std::string> lines;
        std::istringstream in(text);
        for (std::string line; std::getline(in, line);) {
            lines.push_back(line);
        }
        std::vector<std::string> cells;
        std::istringstream row(lines.back());
        for (std::string cell; std::getline(row, cell, ',');) {
            cells.push_back(cell);
        }
        return cells;
    };
    const std::vector<std::string> full = lastRow(slurp(dir / "full.csv"));
    const std::vector<std::string> part = lastRow(slurp(dir / "resumed.csv"));
    REQUIRE(full.size() == part.size());
    CHECK(part[1] == full[1]); // time
    CHECK(part[2] == full[2]); // particles
    // A bad save is refused with its name.
    std::ofstream((dir / "bad.level").string(), std::ios::binary) << "FLUIDLVL broken";
    const Run bad = fluidRun({(dir / "bad.level").string(), "--frames", "1"}, dir);
    CHECK(bad.status == 1);
    CHECK(bad.err.find("level save '" + (dir / "bad.level").string() + "': ") !=
          std::string::npos);
    fs::remove_all(dir);
}

#endif // FLUID_RUN_PATH
