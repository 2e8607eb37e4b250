// fluid tests — what the screenshot checks share: the headless demo's summary.txt lines, a
// picture with the camera it was taken with (world metres to pixels), and the liquid's colour
// classes (tuned on the screenshots: water is blue, yoghurt cream).
#pragma once

#include <catch2/catch.hpp>

#include <SFML/Graphics/Image.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace fluid::test {

// One line of summary.txt: key=value pairs.
struct Shot {
    std::map<std::string, std::string> fields;
    const std::string& at(const std::string& key) const {
        const auto it = fields.find(key);
        if (it == fields.end()) {
            FAIL("summary.txt line has no '" << key << "'");
        }
        return it->second;
    }
    double number(const std::string& key) const { return std::stod(at(key)); }
};

// The lines of DIR/summary.txt that name a level, in file order.
inline std::vector<Shot> readShots(const std::string& dir) {
    std::ifstream in(dir + "/summary.txt");
    INFO("reading " << dir << "/summary.txt");
    REQUIRE(in.good());
    std::vector<Shot> shots;
    std::string line;
    while (std::getline(in, line)) {
        Shot shot;
        std::istringstream words(line);
        std::string word;
        while (words >> word) {
            const auto eq = word.find('=');
            if (eq != std::string::npos) {
                shot.fields[word.substr(0, eq)] = word.substr(eq + 1);
            }
        }
        if (shot.fields.count("level") != 0) {
            shots.push_back(shot);
        }
    }
    return shots;
}

// An image and the camera it was taken with: world metres to pixels and back.
struct Picture {
    sf::Image image;
    double ppm = 1.0, cx = 0.0, cy = 0.0;
    int width = 0, height = 0;

    explicit Picture(const Shot& shot) {
        INFO("loading " << shot.at("file"));
        REQUIRE(image.loadFromFile(shot.at("file")));
        ppm = shot.number("px_per_m");
        const std::string center = shot.at("center");
        cx = std::stod(center.substr(0, center.find(',')));
        cy = std::stod(center.substr(center.find(',') + 1));
        width = int(image.getSize().x);
        height = int(image.getSize().y);
    }
    int px(double x) const { return int(std::lround((x - cx) * ppm + 0.5 * width)); }
    int py(double y) const { return int(std::lround(0.5 * height - (y - cy) * ppm)); }
    double wx(int x) const { return cx + (x + 0.5 - 0.5 * width) / ppm; }
    double wy(int y) const { return cy - (y + 0.5 - 0.5 * height) / ppm; }
    sf::Color at(int x, int y) const { return image.getPixel(unsigned(x), unsigned(y)); }
    // Counts pixels of a class in the world rectangle [x0, x1] x [y0, y1]; `total` gets the
    // pixel count of the rectangle.
    template <class Pred>
    int count(double x0, double y0, double x1, double y1, Pred pred, int* total = nullptr) const {
        int n = 0, all = 0;
        for (int y = std::max(0, py(y1)); y <= std::min(height - 1, py(y0)); ++y) {
            for (int x = std::max(0, px(x0)); x <= std::min(width - 1, px(x1)); ++x) {
                ++all;
                n += pred(at(x, y)) ? 1 : 0;
            }
        }
        if (total != nullptr) {
            *total = all;
        }
        return n;
    }
};

// Colour classes: water blue, yoghurt cream (their mixes fall in one or the other).
inline bool isWater(sf::Color c) {
    return c.b > 110 && c.b > c.r + 50 && c.b > c.g + 10;
}
inline bool isYoghurt(sf::Color c) {
    return c.r > 170 && c.g > 160 && c.b > 120 && std::abs(int(c.r) - int(c.b)) < 80;
}
inline bool isLiquid(sf::Color c) {
    return isWater(c) || isYoghurt(c);
}

} // namespace fluid::test
