// fluid tests — what a level's text may hold: its whole length is the document (a NUL byte in
// it is an error naming its offset, through parseLevel and loadLevel alike), names follow the
// core's rule (printable, at most kMaxNameBytes bytes) and messages quote at most that much of
// a string from the file. Columns are 1-based bytes.
#include <catch2/catch.hpp>

#include "level_support.h"

#include <fluid/error.h>
#include <fluid/level.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

using namespace fluid;
using namespace fluid::test;

namespace {

const std::string kGood = R"({"version": 1, "materials": [{"name": "water"}]})";

// The message of the Error that loading the file holding `text` throws ("no error" when none).
std::string fileErrorOf(const std::string& text) {
    const std::filesystem::path path =
        std::filesystem::temp_directory_path() / "fluid_test_level_text.json";
    {
        std::ofstream out(path, std::ios::binary);
        out.write(text.data(), std::streamsize(text.size()));
    }
    std::string message = "no error";
    try {
        loadLevel(path.string(), builtins());
    } catch (const Error& e) {
        message = e.what();
    }
    std::filesystem::remove(path);
    return message;
}

} // namespace

TEST_CASE("level text: a NUL byte anywhere in the text is an error naming its offset",
          "[level][text]") {
    REQUIRE(errorOf(kGood) == "no error");
    // Garbage after the document is refused, with or without a NUL before it.
    CHECK_THAT(errorOf(kGood + "garbage"), Catch::StartsWith("t.json:1:49: "));
    const std::string nul = kGood + std::string(1, '\0') + "garbage";
    CHECK(errorOf(nul) == "t.json:1:49: a NUL byte at byte offset 48 of the 56-byte text; a "
                          "level file is JSON text and holds none");
    CHECK(errorOf(kGood + std::string(1, '\0')) ==
          "t.json:1:49: a NUL byte at byte offset 48 of the 49-byte text; a level file is JSON "
          "text and holds none");
    // The same from a file.
    const std::string message = fileErrorOf(nul);
    CHECK_THAT(message, Catch::EndsWith("fluid_test_level_text.json:1:49: a NUL byte at byte "
                                        "offset 48 of the 56-byte text; a level file is JSON "
                                        "text and holds none"));
}

TEST_CASE("level text: names are at most kMaxNameBytes bytes, and messages quote at most that "
          "much of a string",
          "[level][text]") {
    const std::string longest(kMaxNameBytes, 'w');
    CHECK(errorOf(R"({"version": 1, "materials": [{"name": ")" + longest + R"("}]})") ==
          "no error");
    const std::string tooLong(kMaxNameBytes + 1, 'w');
    CHECK(errorOf(R"({"version": 1, "materials": [{"name": ")" + tooLong + R"("}]})") ==
          "t.json:1:39: at /materials/0/name: the name is 257 bytes long; names are at most 256 "
          "bytes");
    CHECK(errorOf(R"({"version": 1, "name": ")" + tooLong + R"(", "materials": []})") ==
          "t.json:1:24: at /name: the name is 257 bytes long; names are at most 256 bytes");
    // A megabyte of plugin type or reference, quoted as 256 bytes.
    const std::string huge(std::size_t(1) << 20, 'x');
    const std::string quoted = "'" + huge.substr(0, kMaxNameBytes) + "...' (1048576 bytes)";
    const std::string type = errorOf(kGood.substr(0, kGood.size() - 1) +
                                     R"(, "plugins": [{"type": ")" + huge + R"("}]})");
    CHECK_THAT(type, Catch::StartsWith("t.json:1:71: at /plugins/0/type: unknown plugin type " +
                                       quoted + "; known: force.gravity, "));
    CHECK(type.size() < 4096);
    CHECK(errorOf(kGood.substr(0, kGood.size() - 1) +
                  R"(, "emitters": [{"name": "e", "material": ")" + huge +
                  R"(", "position": [0, 0]}]})") ==
          "t.json:1:89: at /emitters/0/material: unknown material " + quoted + "; known: water");
}
