// The demo's text wrapping (demo/banner.cpp wrapWords), which the level banner and the help use:
// lines break at spaces only, so a number such as "5,000" or a word never splits.
#include "demo/banner.h"

#include <catch2/catch.hpp>

#include <string>
#include <string_view>
#include <vector>

namespace {
// Every character one unit wide.
float characters(std::string_view s) {
    return float(s.size());
}

std::vector<std::string> wrap(std::string_view text, float width) {
    std::vector<std::string> lines;
    for (const std::string_view line : fluid::demo::wrapWords(text, width, characters)) {
        lines.emplace_back(line);
    }
    return lines;
}
} // namespace

TEST_CASE("wrapWords breaks at spaces, never inside a number or a word", "[demo][ui]") {
    // ImGui's own wrapping breaks after a comma: "5," / "000".
    const std::string text = "The stress level: 5,000 particles, off-centre.";
    for (float width = 6.0f; width <= 50.0f; width += 1.0f) {
        INFO("width " << width);
        const auto lines = wrap(text, width);
        std::string joined;
        for (const std::string& line : lines) {
            // Only a single word wider than the line ("off-centre.") overflows it.
            const bool fits = line.size() <= size_t(width) || line.find(' ') == std::string::npos;
            CHECK(fits);
            CHECK(line.front() != ' ');
            CHECK(line.back() != ' ');
            joined += (joined.empty() ? "" : " ") + line;
        }
        // Nothing lost or split: the words come back in order.
        CHECK(joined == text);
        for (const std::string& line : lines) {
            const bool wholeNumber =
                line.find("5,") == std::string::npos || line.find("5,000") != std::string::npos;
            CHECK(wholeNumber);
            CHECK(line.rfind("000", 0) == std::string::npos);
        }
    }
    CHECK(wrap(text, 20.0f) ==
          std::vector<std::string>{"The stress level:", "5,000 particles,", "off-centre."});
}

TEST_CASE("wrapWords keeps a word wider than the line whole, on a line of its own", "[demo][ui]") {
    CHECK(wrap("a 0123456789 b", 4.0f) == std::vector<std::string>{"a", "0123456789", "b"});
    CHECK(wrap("0123456789", 4.0f) == std::vector<std::string>{"0123456789"});
}

TEST_CASE("wrapWords drops runs of spaces at breaks and keeps newlines", "[demo][ui]") {
    CHECK(wrap("  one   two  ", 100.0f) == std::vector<std::string>{"one   two"});
    CHECK(wrap("one\ntwo three", 100.0f) == std::vector<std::string>{"one", "two three"});
    CHECK(wrap("one   two", 4.0f) == std::vector<std::string>{"one", "two"});
    CHECK(wrap("", 10.0f).empty());
    CHECK(wrap("   ", 10.0f).empty());
}
