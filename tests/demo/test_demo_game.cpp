// The interactive game driven by scripted input (fluid-demo --script): every control does what
// docs/demo.md says, measured from the summary line the game prints at the end. Each run plays
// a fixed number of frames of one step each, so results do not depend on the machine's speed.
#include "demo_support.h"

#include <SFML/Graphics/Image.hpp>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

namespace {

struct Summary {
    int status = -1;
    std::string output;
    std::map<std::string, std::string> fields;
    double number(const std::string& key) const {
        const auto it = fields.find(key);
        if (it == fields.end()) {
            FAIL("no '" << key << "' in the summary: " << output);
        }
        return std::stod(it->second);
    }
    std::string text(const std::string& key) const {
        const auto it = fields.find(key);
        if (it == fields.end()) {
            FAIL("no '" << key << "' in the summary: " << output);
        }
        return it->second;
    }
    // "x,y" fields (body positions).
    std::pair<double, double> point(const std::string& key) const {
        const std::string v = text(key);
        return {std::stod(v.substr(0, v.find(','))), std::stod(v.substr(v.find(',') + 1))};
    }
};

// Plays `script` in `level` for `frames` frames and parses the summary line.
Summary play(const std::string& name, const std::string& level, int frames,
             const std::string& script, const std::string& extra = "") {
    const std::string path = std::string(FLUID_DEMO_WORK_DIR) + "/" + name + ".script";
    std::ofstream(path) << script;
    const demo_test::Run run =
        demo_test::runDemo("--level " + level + " --size 480x270 --threads 1 --frames " +
                           std::to_string(frames) + " --script '" + path + "'" + extra);
    Summary summary;
    summary.status = run.status;
    summary.output = run.output;
    // What the demo said, for any failure below (a run without its summary line included).
    INFO("fluid-demo exited with " << summary.status << ", saying: " << summary.output);
    const auto at = summary.output.rfind("fluid-demo: level=");
    REQUIRE(at != std::string::npos);
    std::istringstream words(summary.output.substr(at + 12));
    std::string word;
    while (words >> word) {
        const auto eq = word.find('=');
        if (eq != std::string::npos) {
            summary.fields[word.substr(0, eq)] = word.substr(eq + 1);
        }
    }
    REQUIRE(summary.status == 0);
    return summary;
}

} // namespace

TEST_CASE("game: G switches gravity on in the zero-g arena and the blobs fall", "[demo]") {
    const Summary still = play("zero_g_still", "zero_g_arena", 60, "");
    const Summary fall = play("zero_g_fall", "zero_g_arena", 60, "2 key G\n");
    std::printf("[measure] zero-g arena after 1 s: centre of mass y %.3f without G, %.3f with\n",
                still.number("cy"), fall.number("cy"));
    CHECK(still.text("gravity") == "off");
    CHECK(fall.text("gravity") == "on");
    CHECK(fall.number("cy") < still.number("cy") - 0.1);
    // G twice is zero-g again.
    const Summary twice = play("zero_g_twice", "zero_g_arena", 10, "2 key G\n3 key G\n");
    CHECK(twice.text("gravity") == "off");
}

TEST_CASE("game: Space drops a blob of the current material, M switches it", "[demo]") {
    const Summary plain = play("drop_none", "dam_break", 10, "");
    const Summary drops = play("drop_two", "dam_break", 10,
                               "1 move 0.45 0.3\n2 key Space\n3 key M\n4 move 0.3 0.4\n"
                               "5 key Space\n");
    std::printf("[measure] drops: water %s -> %s, yoghurt %s -> %s\n",
                plain.text("m_water").c_str(), drops.text("m_water").c_str(),
                plain.text("m_yoghurt").c_str(), drops.text("m_yoghurt").c_str());
    CHECK(drops.number("m_water") > plain.number("m_water") + 10);
    CHECK(plain.number("m_yoghurt") == 0);
    CHECK(drops.number("m_yoghurt") > 10);
    CHECK(drops.text("material") == "yoghurt");
}

TEST_CASE("game: S cycles the views, P pauses and period steps one frame", "[demo]") {
    CHECK(play("view1", "dam_break", 3, "1 key S\n").text("view") == "pressure");
    CHECK(play("view2", "dam_break", 3, "1 key S\n2 key S\n").text("view") == "particles");
    CHECK(play("view3", "dam_break", 4, "1 key S\n2 key S\n3 key S\n").text("view") == "metaballs");
    const Summary paused = play("pause", "dam_break", 30, "1 key P\n");
    CHECK(paused.text("paused") == "1");
    CHECK(paused.number("time") == 0.0);
    const Summary stepped = play("step", "dam_break", 30, "1 key P\n10 key Period\n");
    CHECK(stepped.number("time") == Approx(1.0 / 60.0).epsilon(1e-5));
    const Summary resumed = play("resume", "dam_break", 30, "1 key P\n11 key P\n");
    CHECK(resumed.text("paused") == "0");
    CHECK(resumed.number("time") == Approx(20.0 / 60.0).epsilon(1e-5));
}

TEST_CASE("game: N, B and the number keys change level, R restarts it", "[demo]") {
    CHECK(play("next", "dam_break", 3, "1 key N\n").text("level") == "yoghurt_vs_water");
    CHECK(play("jump", "dam_break", 3, "1 key Num3\n").text("level") == "zero_g_arena");
    CHECK(play("back", "yoghurt_vs_water", 3, "1 key B\n").text("level") == "dam_break");
    // R at frame 31: the level restarts, then frames 31..40 step it again.
    const Summary reset = play("reset", "dam_break", 40, "31 key R\n");
    CHECK(reset.text("level") == "dam_break");
    CHECK(reset.number("time") == Approx(10.0 / 60.0).epsilon(1e-5));
}

TEST_CASE("game: the right button pulls liquid towards the pointer", "[demo]") {
    // The arena's water blob starts at (-0.25, 0); pull from 0.1 m above it for half a second.
    const Summary still = play("pull_none", "zero_g_arena", 30, "");
    const Summary pulled = play("pull", "zero_g_arena", 30, "1 press right -0.25 0.1\n");
    std::printf("[measure] pull: centre of mass y %.4f without, %.4f with the pull\n",
                still.number("cy"), pulled.number("cy"));
    CHECK(pulled.number("cy") > still.number("cy") + 0.002);
    // The left button pushes the other way.
    const Summary pushed = play("push", "zero_g_arena", 30, "1 press left -0.25 0.1\n");
    CHECK(pushed.number("cy") < still.number("cy") - 0.002);
}

TEST_CASE("game: ctrl + click drops a crate in a level with bodies", "[demo]") {
    const Summary plain = play("crate_none", "crates", 5, "");
    const Summary crate = play("crate", "crates", 5, "1 press left 1.0 0.8 ctrl\n2 release left\n");
    CHECK(crate.number("bodies") == plain.number("bodies") + 1);
}

TEST_CASE("game: fill the cup is won by dragging the three planks into a slide", "[demo]") {
    // levels/cup_and_planks.json: planks at (0.55, 0.8), (0.55, 0.72), (0.55, 0.64); a slide
    // from the faucet to the cup is (0.2, 0.6), (0.44, 0.5), (0.68, 0.4). Shift + drag each, in
    // steps slower than the grab's 3 m/s cap, then let the water run.
    std::ostringstream script;
    int frame = 1;
    auto drag = [&](double x0, double y0, double x1, double y1) {
        script << frame << " press left " << x0 << " " << y0 << " shift\n";
        constexpr int kSteps = 30;
        for (int k = 1; k <= kSteps; ++k) {
            const double t = double(k) / kSteps;
            script << frame + k << " move " << x0 + t * (x1 - x0) << " " << y0 + t * (y1 - y0)
                   << "\n";
        }
        frame += kSteps + 5; // let it arrive
        script << frame << " release left\n";
        ++frame;
    };
    drag(0.55, 0.8, 0.2, 0.6);
    drag(0.55, 0.72, 0.44, 0.5);
    drag(0.55, 0.64, 0.68, 0.4);
    const Summary won = play("cup_won", "cup_and_planks", 720, script.str());
    const auto [x1, y1] = won.point("b_plank1");
    const auto [x2, y2] = won.point("b_plank2");
    const auto [x3, y3] = won.point("b_plank3");
    std::printf("[measure] planks at (%.3f, %.3f) (%.3f, %.3f) (%.3f, %.3f); goal %s at %.3f\n", x1,
                y1, x2, y2, x3, y3, won.text("goal").c_str(), won.number("goal_value"));
    CHECK(std::hypot(x1 - 0.2, y1 - 0.6) < 0.01);
    CHECK(std::hypot(x2 - 0.44, y2 - 0.5) < 0.01);
    CHECK(std::hypot(x3 - 0.68, y3 - 0.4) < 0.01);
    CHECK(won.text("goal") == "won");
    // Left alone, the planks stay put and the cup stays empty.
    const Summary idle = play("cup_idle", "cup_and_planks", 120, "");
    CHECK(idle.point("b_plank1") == std::pair<double, double>(0.55, 0.8));
    CHECK(idle.text("goal") == "pending");
    CHECK(idle.number("goal_value") == 0.0);
}

TEST_CASE("game: a bad script is refused with its file and line", "[demo]") {
    const std::string path = std::string(FLUID_DEMO_WORK_DIR) + "/bad.script";
    std::ofstream(path) << "# comment\n1 key S\n2 jump 0 0\n";
    const demo_test::Run run =
        demo_test::runDemo("--level dam_break --frames 3 --script '" + path + "'");
    CHECK(run.status == 2);
    CHECK(run.output == "fluid-demo: " + path +
                            ":3: unknown action 'jump' (expected key, move, press or release)\n");
}

TEST_CASE("game: a script position that is not a finite number, or a directory given as the "
          "script, is refused before the game starts",
          "[demo]") {
    const std::string dir = std::string(FLUID_DEMO_WORK_DIR) + "/bad_positions";
    std::filesystem::create_directories(dir);
    const std::pair<const char*, const char*> lines[] = {
        {"1 move nan 0.3\n", ":1: 'move' needs a position X Y in metres"},
        {"1 key G\n2 press left inf 0.3\n", ":2: 'press' needs a position X Y in metres"},
        {"1 move -inf -inf\n", ":1: 'move' needs a position X Y in metres"},
        {"1 move 0.3 1e39\n", ":1: 'move' needs a position X Y in metres"}, // beyond a float
        {"1 press left 0.3\n", ":1: 'press' needs a position X Y in metres"},
    };
    int k = 0;
    for (const auto& [script, message] : lines) {
        const std::string path = dir + "/" + std::to_string(k++) + ".script";
        std::ofstream(path) << script;
        INFO(script);
        const demo_test::Run run =
            demo_test::runDemo("--level crates --frames 3 --script '" + path + "'");
        CHECK(run.status == 2);
        CHECK(run.output == "fluid-demo: " + path + message + "\n");
    }
    // A directory reads as an empty stream: it played the level with no input, silently.
    const demo_test::Run folder =
        demo_test::runDemo("--level crates --frames 3 --script '" + dir + "'");
    CHECK(folder.status == 2);
    CHECK(folder.output == "fluid-demo: " + dir + ": is a directory, not a script\n");
}

TEST_CASE("game: a script position off the window is refused with its file and line, the game "
          "ends without a summary",
          "[demo]") {
    // At 480x270 crates.json shows x in [-0.485, 2.485] m and y in [-0.1685, 1.502] m (the
    // level framed below the overlays' band, demo/layout.h).
    const std::string view = " window, which shows x in [-0.485, 2.485] m and y in "
                             "[-0.1685, 1.502] m of level crates\n";
    const std::pair<const char*, const char*> lines[] = {
        // Once the pixel wrapped through int: a crate dropped near 3e6 m, every step after it
        // failed and the run still exited 0.
        {"2 key G\n5 press left 3e9 -3e9 ctrl\n6 release left\n",
         ":2: 'press' at 3e+09 -3e+09 m is off the 480x270"},
        {"2 move 0.4 0.1\n3 press left -1 0.3\n", ":2: 'press' at -1 0.3 m is off the 480x270"},
        {"1 move 0.5 -0.5\n", ":1: 'move' at 0.5 -0.5 m is off the 480x270"},
        {"1 move 1e30 0.5\n", ":1: 'move' at 1e+30 0.5 m is off the 480x270"},
        {"1 move 0.5 1.6\n", ":1: 'move' at 0.5 1.6 m is off the 480x270"},
    };
    int k = 0;
    for (const auto& [script, message] : lines) {
        const std::string path =
            std::string(FLUID_DEMO_WORK_DIR) + "/off_window_" + std::to_string(k++) + ".script";
        std::ofstream(path) << script;
        INFO(script);
        const demo_test::Run run = demo_test::runDemo(
            "--level crates --size 480x270 --threads 1 --frames 10 --script '" + path + "'");
        CHECK(run.status == 2);
        CHECK(run.output == "fluid-demo: " + path + message + view);
    }
    // Just inside the window's corners plays.
    const Summary corners = play("on_window", "crates", 4,
                                 "1 move -0.48 1.5\n2 press left 2.48 -0.165\n3 release left\n");
    CHECK(corners.number("particles") > 0.0);
}

TEST_CASE("game: F5 saves the level with its crates, F9 goes back to it", "[demo]") {
    const std::string dir = std::string(FLUID_DEMO_WORK_DIR) + "/saves";
    std::filesystem::remove_all(dir);
    const std::string args = " --save-dir '" + dir + "'";
    // F9 before any F5: nothing to load, the level plays on.
    const Summary none = play("load_none", "crates", 3, "1 key F9\n", args);
    CHECK(none.number("time") > 0.0);
    // The reference: 60 frames, saved at the start of frame 30.
    const Summary straight = play("save_ref", "crates", 60, "30 key F5\n", args);
    REQUIRE(std::filesystem::exists(dir + "/crates.level"));
    // Saved at frame 30, loaded at frame 60, played on to frame 90: the state of frame 60.
    const Summary back = play("save_back", "crates", 90, "30 key F5\n60 key F9\n", args);
    std::printf("[measure] F5/F9 in crates: time %s vs %s, centre of mass (%s, %s) vs (%s, %s)\n",
                back.text("time").c_str(), straight.text("time").c_str(),
                back.text("cx").c_str(), back.text("cy").c_str(), straight.text("cx").c_str(),
                straight.text("cy").c_str());
    // A level save with bodies continues bit-identically (docs/box2d.md, "Saving"): every figure
    // the summary prints is the uninterrupted run's, digit for digit.
    CHECK(back.text("time") == straight.text("time"));
    CHECK(back.number("particles") == straight.number("particles"));
    CHECK(back.text("cx") == straight.text("cx"));
    CHECK(back.text("cy") == straight.text("cy"));
    for (const auto& [key, value] : straight.fields) {
        if (key.rfind("b_", 0) == 0) {
            INFO(key);
            CHECK(back.text(key) == value);
        }
    }
    std::filesystem::remove_all(dir);
}

TEST_CASE("game: --record writes the input down as a script that replays to the same state",
          "[demo]") {
    // The input goes through the game as a player's would (a script's actions are played as
    // window events), and the recorder writes down what the game received.
    const std::string recording = std::string(FLUID_DEMO_WORK_DIR) + "/recorded.script";
    std::filesystem::remove(recording);
    const std::string input = "2 key G\n"
                              "5 press left 0.9 0.35 ctrl\n"
                              "6 release left\n"
                              "10 move 0.4 0.1\n"
                              "11 press right 0.4 0.1\n"
                              "25 move 0.6 0.12\n"
                              "40 release right\n"
                              "45 key M\n"
                              "46 key Space\n"
                              "50 key G\n";
    const Summary original =
        play("record_original", "crates", 90, input, " --record '" + recording + "'");
    std::ifstream in(recording);
    REQUIRE(in);
    std::stringstream text;
    text << in.rdbuf();
    const std::string written = text.str();
    INFO("the recording:\n" << written);
    CHECK(written.find("\n5 press left ") != std::string::npos); // at the pixel nearest 0.9 0.35
    CHECK(written.find("ctrl  # pixel ") != std::string::npos);
    CHECK(written.find("\n11 press right ") != std::string::npos);
    CHECK(written.find("40 release right") != std::string::npos);
    CHECK(written.find("46 key Space") != std::string::npos);
    const Summary replayed = play("record_replay", "crates", 90, written);
    CHECK(replayed.text("hash") == original.text("hash"));
    CHECK(replayed.text("bodies") == original.text("bodies"));
    CHECK(std::stoi(original.text("bodies")) == 10); // the level's nine and the dropped crate
}

TEST_CASE("game: the HUD reads the liquid under the cursor, L casts the laser to its surface",
          "[demo]") {
    // From above the settled pool: the laser meets the surface (about 7 cm high after 2.5 s),
    // its normal pointing up; the cursor is in the air.
    const Summary laser = play("laser", "dam_break", 150, "1 move 0.12 0.42\n2 key L\n");
    CHECK(laser.text("probe") == "out");
    CHECK(laser.number("probe_depth") == 0.0);
    const auto [x, y] = laser.point("laser");
    const auto [nx, ny] = laser.point("laser_normal");
    std::printf("[measure] laser: hits at (%.4f, %.4f), normal (%.3f, %.3f)\n", x, y, nx, ny);
    CHECK(x == Approx(0.12 + 0.5 / 0.8660254 * (0.42 - y)).margin(1e-3)); // on the beam
    CHECK(y > 0.04);
    CHECK(y < 0.10);
    CHECK(ny > 0.9);
    // L twice is off: no laser fields. Into the side wall above the pool: a miss.
    CHECK(play("laser_off", "dam_break", 10, "1 key L\n2 key L\n").fields.count("laser") == 0);
    CHECK(play("laser_miss", "dam_break", 150, "1 move 0.5 0.45\n2 key L\n").text("laser") ==
          "miss");
    // The cursor in the water below the laser's hit: in, as deep as the surface is above it.
    std::ostringstream move;
    move << "1 move " << x << " 0.03\n";
    const Summary probe = play("probe", "dam_break", 150, move.str());
    CHECK(probe.text("probe") == "in");
    CHECK(probe.number("probe_depth") == Approx(y - 0.03).margin(0.005));
}

TEST_CASE("game: no pointer ring before the pointer is seen, and one after a move",
          "[demo]") {
    // The camera of dam_break at 960 x 540: a headless run's px_per_m and center.
    const demo_test::Run shot = demo_test::runDemo(
        "--level dam_break --frames 1 --size 960x540 --no-hud --threads 1 --screenshot '" +
        std::string(FLUID_DEMO_WORK_DIR) + "/pointer_camera.png'");
    REQUIRE(shot.status == 0);
    const auto field = [&](const std::string& key) {
        const auto at = shot.output.find(key + "=");
        REQUIRE(at != std::string::npos);
        return shot.output.substr(at + key.size() + 1);
    };
    const double ppm = std::stod(field("px_per_m"));
    const std::string center = field("center");
    const double cx = std::stod(center), cy = std::stod(center.substr(center.find(',') + 1));
    // The pixels the overlays leave bare along the window's top and left edges (10 px), as
    // many as are the background colour (the bottom-right corner's).
    auto bareEdge = [](const std::string& png, int& background, int& total) {
        sf::Image image;
        REQUIRE(image.loadFromFile(png));
        const sf::Vector2u size = image.getSize();
        const sf::Color back = image.getPixel(size.x - 1, size.y - 1);
        background = total = 0;
        for (unsigned y = 0; y < size.y; ++y) {
            for (unsigned x = 0; x < size.x; ++x) {
                if (x < 10 || y < 10) {
                    ++total;
                    background += image.getPixel(x, y) == back ? 1 : 0;
                }
            }
        }
    };
    auto run = [&](const std::string& name, const std::string& script) {
        const std::string script_path = std::string(FLUID_DEMO_WORK_DIR) + "/" + name + ".script";
        const std::string png = std::string(FLUID_DEMO_WORK_DIR) + "/" + name + ".png";
        std::ofstream(script_path) << script;
        const demo_test::Run r =
            demo_test::runDemo("--level dam_break --size 960x540 --threads 1 --frames 5 "
                               "--script '" + script_path + "' --screenshot '" + png + "'");
        INFO(r.output);
        REQUIRE(r.status == 0);
        return png;
    };
    int background = 0, total = 0;
    // Keys only: the pointer was never over the window, so no ring (at the pixel (0, 0) it
    // would cross both edges).
    bareEdge(run("pointer_unseen", "1 key P\n"), background, total);
    std::printf("[measure] pointer unseen: %d of %d edge pixels background\n", background, total);
    CHECK(total > 10000);
    CHECK(background == total);
    // A move to the window's left edge at mid height (left of the tank): the ring crosses it.
    char move[96];
    std::snprintf(move, sizeof move, "1 move %.6f %.6f\n", cx + (4.0 - 480.0) / ppm,
                  cy - (300.0 - 270.0) / ppm);
    bareEdge(run("pointer_seen", move), background, total);
    std::printf("[measure] pointer seen: %d of %d edge pixels background\n", background, total);
    CHECK(total - background > 20);
}
