// Pixel checks of the screenshots demo.screens and demo.cli saved (tests/demo/CMakeLists.txt):
// what a player would see, measured. The images come from a deterministic simulation, but the
// checks use colour classes and regions with margins, not golden images, so a renderer tweak
// does not break them while a wrong picture does.
#include "demo_shots.h"

#include <catch2/catch.hpp>

#include <SFML/Graphics/Image.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <sstream>
#include <string>

using namespace fluid::test;

namespace {

std::map<std::string, Shot> readSummary() {
    std::map<std::string, Shot> shots;
    for (const Shot& shot : readShots(FLUID_DEMO_SHOTS)) {
        shots[shot.at("level") + "-" + shot.at("view")] = shot;
    }
    return shots;
}

const std::map<std::string, Shot>& summary() {
    static const std::map<std::string, Shot> shots = readSummary();
    return shots;
}

const Shot& shotOf(const std::string& key) {
    const auto it = summary().find(key);
    if (it == summary().end()) {
        FAIL("no screenshot " << key << " in summary.txt");
    }
    return it->second;
}

} // namespace

TEST_CASE("every level renders in every view without GL errors", "[demo]") {
    const auto& shots = summary();
    std::set<std::string> levels;
    for (const auto& [key, shot] : shots) {
        INFO(key);
        levels.insert(shot.at("level"));
        CHECK(shot.at("gl_errors") == "0");
        CHECK(shot.at("frames") == "120");
        CHECK(shot.number("particles") > 0);
        sf::Image image;
        REQUIRE(image.loadFromFile(shot.at("file")));
        CHECK(image.getSize() == sf::Vector2u(480, 270));
    }
    // The playlist's seven levels, each in three views.
    for (const char* level : {"dam_break", "yoghurt_vs_water", "zero_g_arena", "crates",
                              "planetoid", "cup_and_planks", "big_tank"}) {
        INFO(level);
        CHECK(levels.count(level) == 1);
        for (const char* view : {"metaballs", "pressure", "particles"}) {
            CHECK(shots.count(std::string(level) + "-" + view) == 1);
        }
    }
}

TEST_CASE("dam break: water lies on the floor of the tank and nowhere above the fill height",
          "[demo]") {
    // levels/dam_break.json: a 0.15 x 0.3 m column in a closed 0.6 x 0.5 m tank; after 2 s it
    // has run across the floor.
    const Picture pic(shotOf("dam_break-metaballs"));
    int floorTotal = 0;
    const int floorWater = pic.count(0.02, 0.005, 0.58, 0.03, isWater, &floorTotal);
    std::printf("[measure] dam break: %d of %d floor-band pixels are water\n", floorWater,
                floorTotal);
    CHECK(floorTotal > 200);
    CHECK(floorWater >= 0.9 * floorTotal);
    // Nothing above the initial fill height plus a margin (a splash of 2 s does not reach it).
    const int high = pic.count(0.0, 0.35, 0.6, 0.5, isWater);
    CHECK(high == 0);
    // And the picture has a lot of water: the 0.045 m^2 of the column.
    const int all = pic.count(0.0, 0.0, 0.6, 0.5, isWater);
    const double area = all / (pic.ppm * pic.ppm);
    std::printf("[measure] dam break: water covers %.4f m^2 of the picture (column 0.045)\n", area);
    CHECK(area > 0.035);
    CHECK(area < 0.06);
}

TEST_CASE("zero-g arena: water and yoghurt blobs float clear of every wall", "[demo]") {
    // levels/zero_g_arena.json: an arena [-0.5, 0.5] x [-0.35, 0.35] m.
    const Picture pic(shotOf("zero_g_arena-metaballs"));
    const int water = pic.count(-0.5, -0.35, 0.5, 0.35, isWater);
    const int yoghurt = pic.count(-0.5, -0.35, 0.5, 0.35, isYoghurt);
    std::printf("[measure] zero-g arena: %d water and %d yoghurt pixels\n", water, yoghurt);
    CHECK(water > 300);
    CHECK(yoghurt > 300);
    // No liquid within 0.05 m of any wall's inner face.
    constexpr double m = 0.05;
    CHECK(pic.count(-0.5, -0.35, -0.5 + m, 0.35, isLiquid) == 0);
    CHECK(pic.count(0.5 - m, -0.35, 0.5, 0.35, isLiquid) == 0);
    CHECK(pic.count(-0.5, -0.35, 0.5, -0.35 + m, isLiquid) == 0);
    CHECK(pic.count(-0.5, 0.35 - m, 0.5, 0.35, isLiquid) == 0);
}

TEST_CASE("the pressure view shows pressure: it differs from metaballs, more red at depth",
          "[demo]") {
    const Picture balls(shotOf("dam_break-metaballs"));
    const Picture pressure(shotOf("dam_break-pressure"));
    REQUIRE(balls.width == pressure.width);
    REQUIRE(balls.height == pressure.height);
    int liquid = 0, differ = 0;
    for (int y = 0; y < balls.height; ++y) {
        for (int x = 0; x < balls.width; ++x) {
            const sf::Color a = balls.at(x, y);
            if (!isWater(a)) {
                continue;
            }
            ++liquid;
            const sf::Color b = pressure.at(x, y);
            const int d = std::abs(int(a.r) - int(b.r)) + std::abs(int(a.g) - int(b.g)) +
                          std::abs(int(a.b) - int(b.b));
            differ += d > 48 ? 1 : 0;
        }
    }
    std::printf("[measure] pressure view: %d of %d liquid pixels differ from metaballs\n", differ,
                liquid);
    REQUIRE(liquid > 1000);
    CHECK(differ >= 0.9 * liquid);
    // No water blue is left in the pressure view: the liquid is black with red squares.
    CHECK(pressure.count(0.0, 0.0, 0.6, 0.5, isWater) == 0);
    // Hydrostatic pressure: the bottom band is redder than a band 0.04 m higher.
    auto redness = [&](double y0, double y1) {
        long sum = 0;
        int n = 0;
        for (int y = std::max(0, pressure.py(y1)); y <= pressure.py(y0); ++y) {
            for (int x = pressure.px(0.02); x <= pressure.px(0.58); ++x) {
                if (isWater(balls.at(x, y))) {
                    const sf::Color c = pressure.at(x, y);
                    sum += int(c.r) - int(c.g);
                    ++n;
                }
            }
        }
        return n > 0 ? double(sum) / n : 0.0;
    };
    const double bottom = redness(0.0, 0.02);
    const double higher = redness(0.04, 0.06);
    std::printf("[measure] pressure view: mean red excess %.1f at the floor, %.1f 0.04 m up\n",
                bottom, higher);
    CHECK(bottom > 60.0);
    CHECK(bottom > higher + 15.0);
}

TEST_CASE("the particle view colours particles by speed", "[demo]") {
    // demo.cli: the dam break 0.2 s in, mid-collapse: the front runs at about 2 m/s,
    // the water behind it is slower.
    sf::Image image;
    REQUIRE(image.loadFromFile(FLUID_DEMO_CLI_PNG));
    std::set<int> hues;
    for (unsigned y = 0; y < image.getSize().y; ++y) {
        for (unsigned x = 0; x < image.getSize().x; ++x) {
            const sf::Color c = image.getPixel(x, y);
            const int hi = std::max({c.r, c.g, c.b}), lo = std::min({c.r, c.g, c.b});
            if (hi < 120 || hi - lo < 80) {
                continue; // background, walls, edges
            }
            // Hue in six sectors of 60 degrees.
            double h = 0.0;
            if (hi == c.r) {
                h = std::fmod((double(c.g) - c.b) / (hi - lo) + 6.0, 6.0);
            } else if (hi == c.g) {
                h = (double(c.b) - c.r) / (hi - lo) + 2.0;
            } else {
                h = (double(c.r) - c.g) / (hi - lo) + 4.0;
            }
            hues.insert(int(h));
        }
    }
    std::printf("[measure] particle view: %zu hue sectors of 6\n", hues.size());
    CHECK(hues.size() >= 3);
}

TEST_CASE("the documented single-screenshot command writes a PNG of the size asked", "[demo]") {
    sf::Image image;
    REQUIRE(image.loadFromFile(FLUID_DEMO_CLI_PNG));
    CHECK(image.getSize() == sf::Vector2u(320, 180));
}
