// fluid tests — the bounds of what a caller may name and draw: one rule for names (printable
// text of at most kMaxNameBytes bytes) for materials, plugin types and declared parameters;
// messages that quote at most kMaxNameBytes bytes of any string they were given; polygons of
// at most kMaxPolygonVertices vertices, refused at once beyond it.
#include "test_support.h"

#include <catch2/catch.hpp>

#include <fluid/error.h>
#include <fluid/gameplay.h>
#include <fluid/material.h>
#include <fluid/plugins/builtin.h>
#include <fluid/plugins/gravity.h>
#include <fluid/registry.h>
#include <fluid/shape.h>
#include <fluid/world.h>

#include <chrono>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

using namespace fluid;

namespace {

// `text` as messages quote it when it is longer than kMaxNameBytes (ASCII text).
std::string quotedLong(const std::string& text) {
    std::string out = "'";
    out.append(text, 0, kMaxNameBytes).append("...' (");
    return out.append(std::to_string(text.size())).append(" bytes)");
}

// A force type named `type` declaring `params`, made as a gravity.
PluginInfo forceType(std::string type, std::span<const ParamDecl> params = {}) {
    return PluginInfo{std::move(type), PluginKind::Force, "a test force", params,
                      [] { return std::unique_ptr<Plugin>(new GravityForce()); }};
}

// The message `body` throws as fluid::Error ("no error" when it throws none).
template <class Body> std::string errorOf(Body&& body) {
    try {
        body();
    } catch (const Error& e) {
        return e.what();
    }
    return "no error";
}

// A circle of `n` vertices, radius `r` (m), centred at (0, r): a simple polygon.
std::vector<glm::vec2> ring(std::size_t n, float r) {
    std::vector<glm::vec2> v(n);
    for (std::size_t k = 0; k < n; ++k) {
        const double a = 2.0 * 3.14159265358979 * double(k) / double(n);
        v[k] = {float(r * std::cos(a)), float(r + r * std::sin(a))};
    }
    return v;
}

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

} // namespace

TEST_CASE("a polygon past kMaxPolygonVertices is refused at once by blobs, drains and sensors",
          "[names][shapes]") {
    World world;
    BlobDef blob;
    blob.material = world.addMaterial(water());
    blob.shape = Shape::polygon(ring(65536, 1.0f));
    const auto start = std::chrono::steady_clock::now();
    CHECK(errorOf([&] { world.spawnBlob(blob); }) ==
          "spawnBlob: polygon has 65536 vertices; expected 3 to 256");
    DrainDef drain;
    drain.shape = blob.shape;
    CHECK(errorOf([&] { world.addDrain(drain); }) ==
          "World::addDrain: polygon has 65536 vertices; expected 3 to 256");
    SensorDef sensor;
    sensor.shape = blob.shape;
    CHECK(errorOf([&] { world.addSensor(sensor); }) ==
          "World::addSensor: polygon has 65536 vertices; expected 3 to 256");
    CHECK(secondsSince(start) < 0.1); // 13.7 s each when every pair of edges was tested
    blob.shape.vertices = ring(kMaxPolygonVertices + 1, 1.0f);
    CHECK(errorOf([&] { validate(blob.shape, "shape"); }) ==
          "shape: polygon has 257 vertices; expected 3 to 256");
    // At the cap: a good polygon, validated in well under 10 ms.
    blob.shape.vertices = ring(kMaxPolygonVertices, 0.1f);
    const auto capStart = std::chrono::steady_clock::now();
    CHECK(errorOf([&] { validate(blob.shape, "shape"); }) == "no error");
    CHECK(secondsSince(capStart) < 0.01);
    CHECK(world.spawnBlob(blob) > 0);
}

TEST_CASE("plugin types and declared parameter names follow the names' rule", "[names]") {
    Registry registry;
    CHECK(errorOf([&] { registry.add(forceType("force.bell\a")); }) ==
          "Registry::add: plugin type 'force.bell\\x07': the name holds a control character "
          "(byte 0x07 at offset 10); names are printable text");
    const std::string huge = "force." + std::string(std::size_t(1) << 20, 'x');
    CHECK(errorOf([&] { registry.add(forceType(huge)); }) ==
          "Registry::add: plugin type " + quotedLong(huge) +
              ": the name is 1048582 bytes long; names are at most 256 bytes");
    static constexpr ParamDecl kNewline[] = {{"g\n", "m/s^2", 0.0, -1.0, 1.0, "bad"}};
    CHECK(errorOf([&] { registry.add(forceType("force.newline", kNewline)); }) ==
          "Registry::add: plugin type 'force.newline' parameter 'g\\x0a': the name holds a "
          "control character (byte 0x0a at offset 1); names are printable text");
    CHECK(registry.types().empty());
    // The longest name is a name, UTF-8 included.
    const std::string longest = "force." + std::string(kMaxNameBytes - 8, 'y') + "\xc3\xa4";
    REQUIRE(longest.size() == kMaxNameBytes);
    CHECK(errorOf([&] { registry.add(forceType(longest)); }) == "no error");
    CHECK(registry.find(longest) != nullptr);
}

TEST_CASE("a material's name is at most kMaxNameBytes bytes", "[names][materials]") {
    Material m = water();
    m.name = std::string(kMaxNameBytes, 'w');
    CHECK_NOTHROW(validate(m));
    m.name = std::string(kMaxNameBytes + 1, 'w');
    CHECK(errorOf([&] { validate(m); }) ==
          "material " + quotedLong(m.name) +
              ": the name is 257 bytes long; names are at most 256 bytes");
    World world;
    CHECK(errorOf([&] { world.addMaterial(m); }) ==
          "material " + quotedLong(m.name) +
              ": the name is 257 bytes long; names are at most 256 bytes");
    CHECK(world.materialCount() == 0);
}

TEST_CASE("messages quote at most kMaxNameBytes bytes of a caller's string, cut between UTF-8 "
          "characters",
          "[names][errors]") {
    Registry registry;
    registerBuiltinPlugins(registry);
    const std::string huge(std::size_t(1) << 20, 'x');
    const std::string unknown = errorOf([&] { (void)registry.create(huge); });
    CHECK_THAT(unknown, Catch::StartsWith("unknown plugin type " + quotedLong(huge) + "; known: "));
    CHECK(unknown.size() < 4096);
    GravityForce gravity;
    CHECK(errorOf([&] { gravity.setParam(huge, 1.0); }) ==
          "plugin 'force.gravity': unknown parameter " + quotedLong(huge) + "; known: gx gy");
    CHECK(errorOf([&] { (void)gravity.param(huge); }) ==
          "plugin 'force.gravity': unknown parameter " + quotedLong(huge) + "; known: gx gy");
    // "a" then 150 two-byte characters (301 bytes): byte 256 continues the 128th character,
    // which is left out whole.
    std::string utf8 = "a";
    for (int k = 0; k < 150; ++k) {
        utf8 += "\xc3\xa4";
    }
    std::string shown = "a";
    for (int k = 0; k < 127; ++k) {
        shown += "\xc3\xa4";
    }
    CHECK(errorOf([&] { gravity.setParam(utf8, 1.0); }) ==
          "plugin 'force.gravity': unknown parameter '" + shown + "...' (301 bytes); known: gx gy");
}
