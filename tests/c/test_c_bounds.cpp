// The C API at its bounds: a material's name read back outlives more materials, memory that
// runs out is FLUID_ERROR_OUT_OF_MEMORY (a full world stays FLUID_ERROR_LIMIT), a level text
// is its whole length (a NUL byte in it is an error), polygons past the core's vertex cap are
// refused at once, and names follow one rule while messages quote a bounded prefix of any string.
#include "c_plugins.h"
#include "c_test_support.h"
#include "test_support.h"

#include <fluid/c.h>
#include <fluid/error.h>
#include <fluid/shape.h>

#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

namespace {

fluid_material_id addWater(fluid_world* world, const char* name) {
    fluid_material_def water{};
    C_OK(fluid_material_preset("water", &water));
    water.name = name;
    fluid_material_id id{};
    C_OK(fluid_world_add_material(world, &water, &id));
    return id;
}

// `text` as messages quote it when it is longer than fluid::kMaxNameBytes (ASCII text).
std::string quotedLong(const std::string& text) {
    std::string out = "'";
    out.append(text, 0, fluid::kMaxNameBytes).append("...' (");
    return out.append(std::to_string(text.size())).append(" bytes)");
}


} // namespace

using namespace fluid;
using fluid::test::CWorld;

TEST_CASE("C API: a material's name read back stays where it is while 200 more materials are "
          "added",
          "[c][bounds]") {
    CWorld w(fluid_default_world_def());
    const fluid_material_id first = addWater(w.world, "w"); // short: kept inside a std::string
    fluid_material_def back{};
    C_OK(fluid_world_get_material(w.world, first, &back));
    const char* name = back.name;
    REQUIRE(std::string(name) == "w");
    for (int k = 0; k < 200; ++k) {
        addWater(w.world, std::string("m").append(std::to_string(k)).c_str());
    }
    // Read after the world's materials moved (a use after free under AddressSanitizer when the
    // name pointed into them).
    CHECK(std::strcmp(name, "w") == 0);
    fluid_material_def again{};
    C_OK(fluid_world_get_material(w.world, first, &again));
    CHECK(again.name == name);
    // Set again with the same name: the same pointer; with another: the new name.
    C_OK(fluid_world_set_material(w.world, first, &again));
    C_OK(fluid_world_get_material(w.world, first, &again));
    CHECK(again.name == name);
    fluid_material_def renamed = again;
    renamed.name = "river";
    C_OK(fluid_world_set_material(w.world, first, &renamed));
    C_OK(fluid_world_get_material(w.world, first, &again));
    CHECK(std::string(again.name) == "river");
}

// Run by the next test in a child process under a memory limit: prints the status and message
// of a blob larger than memory, through a world and through a level. Hidden, and it does
// nothing unless the parent set FLUID_TEST_MEMORY_CHILD: run by hand without the limit it
// would fill the machine's memory.
TEST_CASE("C API child: a blob larger than memory", "[.c_memory_child]") {
    if (std::getenv("FLUID_TEST_MEMORY_CHILD") == nullptr) {
        return;
    }
    fluid_world_def def = fluid_default_world_def();
    def.max_particles = 67108864;
    fluid_world* world = nullptr;
    if (fluid_world_create(&def, &world) != FLUID_OK) {
        std::printf("world: %s\n", fluid_last_error());
        return;
    }
    fluid_blob_def blob = fluid_default_blob_def();
    blob.material = addWater(world, "water");
    blob.shape = fluid_box_shape({0.0f, 0.0f}, {80.0f, 80.0f});
    uint32_t spawned = 0;
    fluid_status s = fluid_world_spawn_blob(world, &blob, &spawned);
    std::printf("spawn: %s: %s\n", fluid_status_name(s), fluid_last_error());
    fluid_world_destroy(world);
    fluid_level* level = nullptr;
    const char* const text = fluid::test::kHugeBlobLevel;
    s = fluid_level_parse(text, std::strlen(text), "t.json", nullptr, &level);
    std::printf("level: %s: %s\n", fluid_status_name(s), fluid_last_error());
    fluid_level_destroy(level);
    std::fflush(stdout);
}

TEST_CASE("C API: memory that runs out is FLUID_ERROR_OUT_OF_MEMORY, a full world "
          "FLUID_ERROR_LIMIT",
          "[c][bounds]") {
    // A full world: the blob needs more particles than max_particles.
    {
        CWorld w(fluid_default_world_def());
        fluid_blob_def blob = fluid_default_blob_def();
        blob.material = addWater(w.world, "water");
        blob.shape = fluid_box_shape({0.0f, 0.0f}, {80.0f, 80.0f});
        CHECK(fluid_world_spawn_blob(w.world, &blob, nullptr) == FLUID_ERROR_LIMIT);
        CHECK(std::string(fluid_last_error()) ==
              "spawnBlob: particle cap exceeded: the blob needs about 6.36485e+07 particles; "
              "maxParticles = 1048576");
    }
#if defined(__linux__) && !defined(FLUID_TEST_SANITIZED)
    // Memory that runs out: this binary again, under a 600 MB address-space limit, where the
    // blob's 63.6 million particles (12.7 GB) do not fit; the child touches at most the
    // limit's worth while it tries.
    const std::string self = std::filesystem::read_symlink("/proc/self/exe").string();
    const std::string command = "ulimit -v 600000 && FLUID_TEST_MEMORY_CHILD=1 '" + self +
                                "' '[.c_memory_child]' --use-colour no 2>&1";
    const fluid::test::ShellRun child = fluid::test::runShell(command);
    REQUIRE(child.started);
    INFO(child.output);
    const std::string text = "memory ran out making room for the blob's about 63648484 particles "
                             "beside the world's 0; make the blob smaller or lower "
                             "WorldDef::maxParticles";
    CHECK(child.output.find("spawn: FLUID_ERROR_OUT_OF_MEMORY: spawnBlob: " + text + "\n") !=
          std::string::npos);
    CHECK(child.output.find("level: FLUID_ERROR_OUT_OF_MEMORY: t.json:1:97: at /blobs/0: "
                            "spawnBlob: " +
                            text + "\n") != std::string::npos);
#else
    WARN("the memory half skipped: needs /proc/self/exe and ulimit -v, and no sanitizer");
#endif
}

TEST_CASE("C API: fluid_level_parse reads the whole length given: a NUL byte in it is an error "
          "naming its offset",
          "[c][bounds]") {
    const std::string good = R"({"version": 1, "materials": [{"name": "water"}]})";
    fluid_level* level = nullptr;
    C_OK(fluid_level_parse(good.data(), good.size(), "t.json", nullptr, &level));
    fluid_level_destroy(level);
    level = nullptr;
    // Garbage after the document, with and without a NUL before it.
    const std::string garbage = good + "garbage";
    CHECK(fluid_level_parse(garbage.data(), garbage.size(), "t.json", nullptr, &level) ==
          FLUID_ERROR_BAD_FILE);
    const std::string nul = good + std::string(1, '\0') + "garbage";
    CHECK(fluid_level_parse(nul.data(), nul.size(), "t.json", nullptr, &level) ==
          FLUID_ERROR_BAD_FILE);
    CHECK(std::string(fluid_last_error()) ==
          "t.json:1:49: a NUL byte at byte offset 48 of the 56-byte text; a level file is JSON "
          "text and holds none");
    CHECK(level == nullptr);
    // A NUL alone at the end, and one on a later line.
    const std::string last = good + std::string(1, '\0');
    CHECK(fluid_level_parse(last.data(), last.size(), "t.json", nullptr, &level) ==
          FLUID_ERROR_BAD_FILE);
    CHECK(std::string(fluid_last_error()) ==
          "t.json:1:49: a NUL byte at byte offset 48 of the 49-byte text; a level file is JSON "
          "text and holds none");
    const std::string inside =
        "{\"version\": 1,\n \"materials\": [{\"name\": \"wa" + std::string(1, '\0') + "ter\"}]}";
    CHECK(fluid_level_parse(inside.data(), inside.size(), "t.json", nullptr, &level) ==
          FLUID_ERROR_BAD_FILE);
    CHECK(std::string(fluid_last_error()) ==
          "t.json:2:28: a NUL byte at byte offset 42 of the 50-byte text; a level file is JSON "
          "text and holds none");
}

TEST_CASE("C API: a polygon of 65,536 vertices is refused at once by blobs, drains and sensors",
          "[c][bounds]") {
    CWorld w(fluid_default_world_def());
    const fluid_material_id water = addWater(w.world, "water");
    // A simple polygon: a circle of radius 1 m.
    std::vector<fluid_vec2> ring(65536);
    for (size_t k = 0; k < ring.size(); ++k) {
        const double a = 2.0 * 3.14159265358979 * double(k) / double(ring.size());
        ring[k] = {float(std::cos(a)), float(1.0 + std::sin(a))};
    }
    const fluid_shape big = fluid_polygon_shape(ring.data(), uint32_t(ring.size()));
    const auto start = std::chrono::steady_clock::now();
    fluid_blob_def blob = fluid_default_blob_def();
    blob.material = water;
    blob.shape = big;
    CHECK(fluid_world_spawn_blob(w.world, &blob, nullptr) == FLUID_ERROR_INVALID_ARGUMENT);
    CHECK(std::string(fluid_last_error()) ==
          "spawnBlob: polygon has 65536 vertices; expected 3 to 256");
    fluid_drain_def drain{};
    drain.shape = big;
    fluid_drain_id d{};
    CHECK(fluid_world_add_drain(w.world, &drain, &d) == FLUID_ERROR_INVALID_ARGUMENT);
    CHECK(std::string(fluid_last_error()) ==
          "World::addDrain: polygon has 65536 vertices; expected 3 to 256");
    fluid_sensor_id s{};
    CHECK(fluid_world_add_sensor(w.world, big, &s) == FLUID_ERROR_INVALID_ARGUMENT);
    CHECK(std::string(fluid_last_error()) ==
          "World::addSensor: polygon has 65536 vertices; expected 3 to 256");
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    CHECK(seconds < 0.1); // 13.7 s each when every pair of edges was tested
    // The cap itself is a good polygon.
    std::vector<fluid_vec2> cap(fluid::kMaxPolygonVertices);
    for (size_t k = 0; k < cap.size(); ++k) {
        const double a = 2.0 * 3.14159265358979 * double(k) / double(cap.size());
        cap[k] = {float(0.2 * std::cos(a)), float(0.2 + 0.2 * std::sin(a))};
    }
    CHECK(fluid_world_add_sensor(w.world, fluid_polygon_shape(cap.data(), uint32_t(cap.size())),
                                 &s) == FLUID_OK);
}

TEST_CASE("C API: plugin type and parameter names follow the names' rule, and messages quote at "
          "most 256 bytes of a caller's string",
          "[c][bounds]") {
    c_test_counters counters{};
    fluid_plugin_type_def type = c_test_acceleration_type("c_test.bounds", &counters, false);
    // A control character in the type.
    type.type = "c_test.bell\a";
    CHECK(fluid_register_plugin_type(&type) == FLUID_ERROR_INVALID_ARGUMENT);
    CHECK(std::string(fluid_last_error()) ==
          "fluid_register_plugin_type: plugin type 'c_test.bell\\x07': the name holds a control "
          "character (byte 0x07 at offset 11); names are printable text");
    // A megabyte of type.
    const std::string huge = "c_test." + std::string(size_t(1) << 20, 'x');
    type.type = huge.c_str();
    CHECK(fluid_register_plugin_type(&type) == FLUID_ERROR_INVALID_ARGUMENT);
    CHECK(std::string(fluid_last_error()) ==
          "fluid_register_plugin_type: plugin type " + quotedLong(huge) +
              ": the name is 1048583 bytes long; names are at most 256 bytes");
    // The longest name is a name.
    const std::string longest = "c_test." + std::string(fluid::kMaxNameBytes - 7, 'y');
    type.type = longest.c_str();
    C_OK(fluid_register_plugin_type(&type));
    // A parameter's name, declared with the type.
    const fluid_param_decl newline[] = {{"g\n", "m/s^2", 0.0, -1.0, 1.0, "bad"}};
    type.type = "c_test.newline_param";
    type.params = newline;
    type.param_count = 1;
    CHECK(fluid_register_plugin_type(&type) == FLUID_ERROR_INVALID_ARGUMENT);
    CHECK(std::string(fluid_last_error()) ==
          "fluid_register_plugin_type: plugin type 'c_test.newline_param' parameter 'g\\x0a': "
          "the name holds a control character (byte 0x0a at offset 1); names are printable "
          "text");
    // A force added directly: the same rule for its type, its messages bounded.
    CWorld w(fluid_default_world_def());
    fluid_force_plugin_def force = c_test_acceleration(&counters);
    force.type = huge.c_str();
    fluid_plugin_id id{};
    CHECK(fluid_world_add_force(w.world, &force, &id) == FLUID_ERROR_INVALID_ARGUMENT);
    CHECK(std::string(fluid_last_error()) ==
          "fluid_world_add_force: plugin type " + quotedLong(huge) +
              ": the name is 1048583 bytes long; names are at most 256 bytes");
    force.apply = nullptr;
    CHECK(fluid_world_add_force(w.world, &force, &id) == FLUID_ERROR_NULL_ARGUMENT);
    CHECK(std::string(fluid_last_error()) ==
          "fluid_world_add_force: plugin type " + quotedLong(huge) + ": def->apply is NULL");
    // Strings looked up by name: a megabyte of it is quoted as 256 bytes.
    CHECK(fluid_world_add_plugin(w.world, huge.c_str(), nullptr, 0, &id) ==
          FLUID_ERROR_UNKNOWN_NAME);
    CHECK_THAT(fluid_last_error(),
               Catch::StartsWith("unknown plugin type " + quotedLong(huge) + "; known: "));
    CHECK(std::strlen(fluid_last_error()) < 4096);
    C_OK(fluid_world_add_plugin(w.world, "force.gravity", nullptr, 0, &id));
    CHECK(fluid_plugin_set_param(w.world, id, huge.c_str(), 1.0) == FLUID_ERROR_UNKNOWN_NAME);
    CHECK(std::string(fluid_last_error()) ==
          "plugin 'force.gravity': unknown parameter " + quotedLong(huge) + "; known: gx gy");
    fluid_world_def def = fluid_default_world_def();
    CHECK(fluid_world_def_set(&def, huge.c_str(), 1.0) == FLUID_ERROR_UNKNOWN_NAME);
    CHECK_THAT(fluid_last_error(),
               Catch::StartsWith("fluid_world_def_set: unknown field " + quotedLong(huge)));
    fluid_material_def material{};
    CHECK(fluid_material_preset(huge.c_str(), &material) == FLUID_ERROR_UNKNOWN_NAME);
    CHECK(std::string(fluid_last_error()) == "fluid_material_preset: unknown preset " +
                                                 quotedLong(huge) +
                                                 " (expected water, yoghurt or seed_yoghurt)");
    // A material's name: the same rule.
    const std::string longName(fluid::kMaxNameBytes + 1, 'm');
    C_OK(fluid_material_preset("water", &material));
    material.name = longName.c_str();
    fluid_material_id m{};
    CHECK(fluid_world_add_material(w.world, &material, &m) == FLUID_ERROR_INVALID_ARGUMENT);
    CHECK(std::string(fluid_last_error()) ==
          "material " + quotedLong(longName) +
              ": the name is 257 bytes long; names are at most 256 bytes");
}
