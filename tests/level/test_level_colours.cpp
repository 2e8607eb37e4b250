// Level files' colours (docs/levels.md, docs/groups.md): a blob's "colour" makes it a group of
// that colour, the world's "colourMixing" sets the rate; bad values are errors naming the file,
// line, column and key; the shipped level colour_mixing.json mixes its three colours.
#include <catch2/catch.hpp>

#include "level_support.h"

#include <fluid/groups.h>
#include <fluid/level.h>

#include <string>

using namespace fluid;
using namespace fluid::test;

namespace {

std::string colourLevel(const std::string& world, const std::string& colour) {
    return R"({"version": 1, "world": {)" + world +
           R"(}, "materials": [{"name": "water"}], "blobs": [{"material": "water", )" +
           R"("shape": "box", "min": [0, 0], "max": [0.1, 0.1])" + colour + "}]}";
}

} // namespace

TEST_CASE("level colours: a blob's colour and the world's mixing rate", "[level][groups]") {
    const Level lvl = parseLevel(colourLevel(R"("colourMixing": 2.5)", R"(, "colour": "#e0302A")"),
                                 "t.json", builtins());
    CHECK(colourMixing(lvl.world) == 2.5f);
    REQUIRE(lvl.world.particleCount() > 0);
    const GroupHandle g = groupOf(lvl.world, lvl.world.handleAt(0));
    CHECK(groupCount(lvl.world, g) == lvl.world.particleCount());
    for (uint32_t i = 0; i < lvl.world.particleCount(); ++i) {
        CHECK(colour(lvl.world, lvl.world.handleAt(i)) == (Colour{0xe0, 0x30, 0x2a, 255}));
    }
    const Level translucent =
        parseLevel(colourLevel("", R"(, "colour": "#10203080")"), "t.json", builtins());
    CHECK(colour(translucent.world, translucent.world.handleAt(0)) == (Colour{16, 32, 48, 128}));
    CHECK(colourMixing(translucent.world) == 0.0f);
    // Without a colour: a group all the same, and no colour channel.
    const Level plain = parseLevel(colourLevel("", ""), "t.json", builtins());
    CHECK(colours(plain.world).empty());
    CHECK_FALSE(groupOf(plain.world, plain.world.handleAt(0)).isNull());
}

TEST_CASE("level colours: bad colours and rates name the file, line and key",
          "[level][groups][errors]") {
    CHECK(errorOf(colourLevel("", R"(, "colour": "red")")) ==
          "t.json:1:155: at /blobs/0/colour: expected \"#rrggbb\" or \"#rrggbbaa\" "
          "(hexadecimal sRGB, alpha not 00), got 'red'");
    CHECK(errorOf(colourLevel("", R"(, "colour": "#12345g")"))
              .find("at /blobs/0/colour: expected \"#rrggbb\" or \"#rrggbbaa\"") !=
          std::string::npos);
    CHECK(errorOf(colourLevel("", R"(, "colour": "#11223300")")).find("got '#11223300'") !=
          std::string::npos);
    CHECK(errorOf(colourLevel("", R"(, "colour": 255)"))
              .find("at /blobs/0/colour: expected a string") != std::string::npos);
    CHECK(errorOf(colourLevel(R"("colourMixing": -1)", "")) ==
          "t.json:1:42: at /world/colourMixing: -1 is out of range [0, 1000] (unit: 1/s)");
}

TEST_CASE("level colours: colour_mixing.json blends its colours and keeps their sums",
          "[level][groups]") {
    Level lvl = loadLevel(std::string(FLUID_LEVELS_DIR) + "/colour_mixing.json", builtins());
    const auto sums = [&] {
        std::array<uint64_t, 4> s{};
        for (const uint32_t c : colours(lvl.world)) {
            for (int k = 0; k < 4; ++k) {
                s[size_t(k)] += (c >> (8 * k)) & 255u;
            }
        }
        return s;
    };
    const auto before = sums();
    const std::vector<uint32_t> start(colours(lvl.world).begin(), colours(lvl.world).end());
    for (int frame = 0; frame < 120; ++frame) {
        lvl.step();
    }
    // Kept to 1/256 of a level: the visible bytes sum within one level per particle below.
    const auto after = sums();
    const auto count = uint64_t(lvl.world.particleCount());
    for (size_t k = 0; k < 4; ++k) {
        CHECK(after[k] <= before[k]);
        CHECK(after[k] + count > before[k]);
    }
    uint32_t blended = 0;
    for (const uint32_t c : colours(lvl.world)) {
        blended += std::find(start.begin(), start.end(), c) == start.end() ? 1 : 0;
    }
    CHECK(blended > 50); // colours none of the three blobs started with
}
