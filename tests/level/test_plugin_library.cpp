// Plugin libraries loaded at run time (fluid::loadPluginLibrary): the whirlpool example built as
// libfluid_whirlpool.so registers and works in a World exactly like the same class compiled
// into the host; broken libraries (tests/level/plugins) are refused with exact messages and
// leave the registry unchanged.
#include "test_support.h"

#include "examples/custom_force.h"

#include <fluid/level.h>
#include <fluid/plugin_abi.h>
#include <fluid/plugin_library.h>

#include <catch2/catch.hpp>

#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using namespace fluid;
using namespace fluid::test;

namespace {

// Names of the registered types, in order: what "the registry is unchanged" compares.
std::vector<std::string> typeNames(const Registry& registry) {
    std::vector<std::string> names;
    for (const PluginInfo& info : registry.types()) {
        names.push_back(info.type);
    }
    return names;
}

// The message of the fluid::Error that `load` throws ("" if it throws nothing).
template <class F> std::string errorOf(F&& load) {
    try {
        load();
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

// A zero-g disc of water centred on a whirlpool made by `registry`; returns the angular
// momentum every 6 frames over 30 frames and the final state hash.
struct SpinResult {
    std::vector<double> momentum;
    uint64_t hash = 0;
};
SpinResult spin(const Registry& registry) {
    World world;
    const MaterialId w = world.addMaterial(water());
    const std::vector<ParamValue> params{
        {"cx", 0.1}, {"cy", -0.05}, {"strength", 1.5}, {"radius", 0.08}};
    world.addForce(registry.createForce("force.whirlpool", params));
    BlobDef disc;
    disc.shape.type = ShapeType::Circle;
    disc.shape.center = {0.1f, -0.05f};
    disc.shape.radius = 0.08f;
    disc.material = w;
    REQUIRE(world.spawnBlob(disc) > 150);
    SpinResult result;
    for (int frame = 1; frame <= 30; ++frame) {
        world.step(kFrame);
        if (frame % 6 == 0) {
            result.momentum.push_back(angularMomentum(world, 0.1, -0.05));
        }
    }
    REQUIRE(allFinite(world));
    result.hash = stateHash(world);
    return result;
}

std::string readFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    REQUIRE(in.good());
    std::string text(std::size_t(in.tellg()), '\0');
    in.seekg(0);
    in.read(text.data(), std::streamsize(text.size()));
    REQUIRE(in.good());
    return text;
}

} // namespace

#ifdef FLUID_WHIRLPOOL_PLUGIN

TEST_CASE("the whirlpool plugin library registers force.whirlpool and spins a disc",
          "[level][plugin-library]") {
    Registry registry;
    registerBuiltinPlugins(registry);
    const std::vector<std::string> before = typeNames(registry);
    const PluginLibrary library = loadPluginLibrary(FLUID_WHIRLPOOL_PLUGIN, registry);
    CHECK(library.path == FLUID_WHIRLPOOL_PLUGIN);
    REQUIRE(library.types == std::vector<std::string>{"force.whirlpool"});
    // Appended after the built-ins, which are untouched.
    std::vector<std::string> expected = before;
    expected.push_back("force.whirlpool");
    CHECK(typeNames(registry) == expected);

    const PluginInfo* info = registry.find("force.whirlpool");
    REQUIRE(info != nullptr);
    CHECK(info->kind == PluginKind::Force);
    REQUIRE(info->params.size() == 5);
    CHECK(info->params[2].name == "strength");
    CHECK(info->params[2].unit == "m/s^2");
    // Parameter checks run in the host's copy of Plugin::setParam on the module's declarations.
    const ParamValue bad[] = {{"radius", -1.0}};
    CHECK(errorOf([&] { (void)registry.createForce("force.whirlpool", bad); }) ==
          "plugin 'force.whirlpool': parameter 'radius' = -1 is out of range [0.001, 1000] "
          "(unit: m)");

    const SpinResult loaded = spin(registry);
    std::printf("[measure] loaded whirlpool: Lz every 0.1 s = %.3e %.3e %.3e %.3e %.3e kg m^2/s\n",
                loaded.momentum[0], loaded.momentum[1], loaded.momentum[2], loaded.momentum[3],
                loaded.momentum[4]);
    CHECK(loaded.momentum.front() > 0.0); // counter-clockwise for a positive strength
    for (std::size_t k = 1; k < loaded.momentum.size(); ++k) {
        CAPTURE(k, loaded.momentum[k - 1], loaded.momentum[k]);
        CHECK(loaded.momentum[k] > loaded.momentum[k - 1]);
    }

    // The same class compiled into this test binary gives bit-identical results: the module's
    // code is the host's code, only loaded differently.
    Registry inProcess;
    registerWhirlpool(inProcess);
    const SpinResult local = spin(inProcess);
    CHECK(local.momentum == loaded.momentum);
    CHECK(local.hash == loaded.hash);
}

TEST_CASE("plugins from a library outlive the registry that made them", "[level][plugin-library]") {
    // The library stays loaded for the process: a plugin keeps working (vtable, apply, its
    // parameter declarations) after every registry holding the library's factories is gone.
    std::unique_ptr<ForcePlugin> force;
    {
        Registry registry;
        (void)loadPluginLibrary(FLUID_WHIRLPOOL_PLUGIN, registry);
        force = registry.createForce("force.whirlpool");
    }
    force->setParam("strength", 2.0);
    CHECK(force->param("strength") == 2.0);
    CHECK(force->type() == "force.whirlpool");
    World world;
    const MaterialId w = world.addMaterial(water());
    world.addForce(std::move(force));
    BlobDef disc;
    disc.shape.type = ShapeType::Circle;
    disc.shape.radius = 0.05f;
    disc.material = w;
    world.spawnBlob(disc);
    for (int frame = 0; frame < 6; ++frame) {
        world.step(kFrame);
    }
    CHECK(allFinite(world));
    CHECK(angularMomentum(world, 0.0, 0.0) > 0.0);
}

TEST_CASE("loading a plugin library twice reports the duplicate type with the path",
          "[level][plugin-library]") {
    Registry registry;
    registerBuiltinPlugins(registry);
    (void)loadPluginLibrary(FLUID_WHIRLPOOL_PLUGIN, registry);
    const std::vector<std::string> before = typeNames(registry);
    CHECK(errorOf([&] { (void)loadPluginLibrary(FLUID_WHIRLPOOL_PLUGIN, registry); }) ==
          std::string("plugin library '") + FLUID_WHIRLPOOL_PLUGIN +
              "': Registry::add: plugin type 'force.whirlpool' is already registered");
    CHECK(typeNames(registry) == before);
    // Another registry can still take the same (already mapped) library.
    Registry other;
    CHECK(loadPluginLibrary(FLUID_WHIRLPOOL_PLUGIN, other).types ==
          std::vector<std::string>{"force.whirlpool"});
}

TEST_CASE("a level file names a plugin type from a loaded library", "[level][plugin-library]") {
    // A zero-g disc of water on a whirlpool, as a level would ship it next to its .so.
    const std::string text = R"({
  "version": 1,
  "name": "Whirlpool",
  "materials": [ { "name": "water", "preset": "water" } ],
  "blobs": [ { "material": "water", "shape": "circle", "center": [0, 0], "radius": 0.08 } ],
  "plugins": [
    { "type": "force.whirlpool", "name": "swirl",
      "params": { "strength": 1.5, "radius": 0.08 } }
  ]
})";
    Registry registry;
    registerBuiltinPlugins(registry);
    // Without the library the type is unknown, located at the plugin's "type".
    try {
        (void)parseLevel(text, "whirlpool.json", registry);
        FAIL("the level loaded without the plugin library");
    } catch (const LevelError& e) {
        CHECK(e.path() == "/plugins/0/type");
        CHECK(e.message().rfind("unknown plugin type 'force.whirlpool'", 0) == 0);
    }

    (void)loadPluginLibrary(FLUID_WHIRLPOOL_PLUGIN, registry);
    Level level = parseLevel(text, "whirlpool.json", registry);
    REQUIRE(level.plugins.size() == 1);
    CHECK(level.plugins[0].name == "swirl");
    CHECK(level.plugins[0].kind == PluginKind::Force);
    REQUIRE(level.world.forces().size() == level.plugins[0].index + 1);
    const ForcePlugin& swirl = *level.world.forces()[level.plugins[0].index];
    CHECK(swirl.type() == "force.whirlpool");
    CHECK(swirl.param("strength") == 1.5);
    CHECK(swirl.param("radius") == 0.08);
    double previous = angularMomentum(level.world, 0.0, 0.0);
    CHECK(previous == 0.0);
    for (int frame = 1; frame <= 24; ++frame) {
        level.step();
        if (frame % 6 == 0) {
            const double l = angularMomentum(level.world, 0.0, 0.0);
            CAPTURE(frame, l, previous);
            CHECK(l > previous);
            previous = l;
        }
    }
    std::printf("[measure] level with the loaded whirlpool: Lz after 0.4 s = %.3e kg m^2/s\n",
                previous);
    CHECK(allFinite(level.world));
}

#else
TEST_CASE("the whirlpool plugin library is not built (FLUID_BUILD_EXAMPLES is OFF)",
          "[level][plugin-library]") {
    WARN("examples are off: the whirlpool plugin library tests did not run");
}
#endif

TEST_CASE("a library with another plugin ABI version is refused before registration",
          "[level][plugin-library]") {
    Registry registry;
    registerBuiltinPlugins(registry);
    const std::vector<std::string> before = typeNames(registry);
    // Its fluid_register_plugins aborts the process: reaching it fails the whole run.
    CHECK(errorOf([&] { (void)loadPluginLibrary(FLUID_TEST_PLUGIN_WRONG_ABI, registry); }) ==
          std::string("'") + FLUID_TEST_PLUGIN_WRONG_ABI +
              "' was built for plugin ABI 999; this fluid has ABI " +
              std::to_string(kPluginAbiVersion) + ": rebuild the plugin against this fluid");
    CHECK(typeNames(registry) == before);
}

TEST_CASE("a library built against other plugin headers is refused, naming the difference",
          "[level][plugin-library]") {
    Registry registry;
    const std::size_t plugin = sizeof(Plugin);
    CHECK(errorOf([&] { (void)loadPluginLibrary(FLUID_TEST_PLUGIN_WRONG_DETAILS, registry); }) ==
          std::string("'") + FLUID_TEST_PLUGIN_WRONG_DETAILS + "' was built for plugin ABI " +
              std::to_string(kPluginAbiVersion) +
              " but does not match this fluid: sizeof(fluid::Plugin) is " +
              std::to_string(plugin + 8) + " in the plugin, " + std::to_string(plugin) +
              " here: rebuild the plugin against this fluid's headers with the same compiler "
              "and settings");
    CHECK(registry.types().empty());
}

TEST_CASE("a shared library without the entry points is not a plugin library",
          "[level][plugin-library]") {
    Registry registry;
    registerBuiltinPlugins(registry);
    const std::vector<std::string> before = typeNames(registry);
    CHECK(errorOf([&] { (void)loadPluginLibrary(FLUID_TEST_PLUGIN_NO_ENTRY, registry); }) ==
          std::string("'") + FLUID_TEST_PLUGIN_NO_ENTRY +
              "' is not a fluid plugin library: it has no fluid_plugin_abi_version / "
              "fluid_register_plugins entry point");
    CHECK(typeNames(registry) == before);
}

TEST_CASE("a registration that throws fails the load and registers nothing",
          "[level][plugin-library]") {
    Registry registry;
    registerBuiltinPlugins(registry);
    const std::vector<std::string> before = typeNames(registry);
    // The library adds force.test_good, then a type whose default is out of range: the module's
    // Registry::add throws, and force.test_good must not reach the host's registry either.
    CHECK(errorOf([&] { (void)loadPluginLibrary(FLUID_TEST_PLUGIN_THROWS, registry); }) ==
          std::string("plugin library '") + FLUID_TEST_PLUGIN_THROWS +
              "': fluid_register_plugins failed: plugin 'force.test_bad_default': parameter "
              "'k' = 5 is out of range [0, 1] (unit: 1)");
    CHECK(typeNames(registry) == before);
    CHECK(registry.find("force.test_good") == nullptr);
}

TEST_CASE("a missing file or a file that is not a shared library names the path",
          "[level][plugin-library]") {
    Registry registry;
    registerBuiltinPlugins(registry);
    const std::vector<std::string> before = typeNames(registry);

    const std::string missing = std::string(FLUID_BINARY_DIR) + "/no/such/libplugin.so";
    const std::string missingError = errorOf([&] { (void)loadPluginLibrary(missing, registry); });
    CAPTURE(missingError);
    // The dlerror() text follows the prefix; glibc's names the file and the reason.
    CHECK(missingError.rfind("cannot load plugin library '" + missing + "': ", 0) == 0);
    CHECK(missingError.find("No such file or directory") != std::string::npos);

    const std::string notLibrary = std::string(FLUID_SOURCE_DIR) + "/README.md";
    const std::string notLibraryError =
        errorOf([&] { (void)loadPluginLibrary(notLibrary, registry); });
    CAPTURE(notLibraryError);
    CHECK(notLibraryError.rfind("cannot load plugin library '" + notLibrary + "': ", 0) == 0);
    CHECK(notLibraryError.size() > ("cannot load plugin library '" + notLibrary + "': ").size());

    // A bare file name means the current directory, not the system library path.
    const std::string bare = "libfluid_no_such_plugin.so";
    const std::string bareError = errorOf([&] { (void)loadPluginLibrary(bare, registry); });
    CAPTURE(bareError);
    CHECK(bareError.rfind("cannot load plugin library 'libfluid_no_such_plugin.so': ./", 0) == 0);

    CHECK(typeNames(registry) == before);
}

TEST_CASE("the plugin ABI declaration hash is current", "[level][plugin-library]") {
    // kPluginAbiDeclHash enters every plugin library's ABI details, so a library compiled
    // against other plugin.h / registry.h declarations is refused. When this fails, the
    // declarations changed: bump kPluginAbiVersion if a layout, a virtual function or an entry
    // point changed, and set kPluginAbiDeclHash to the value printed below.
    const std::string root = FLUID_SOURCE_DIR;
    const std::string text = readFile(root + "/fluid/include/fluid/plugin.h") +
                             readFile(root + "/fluid/include/fluid/registry.h");
    const uint32_t hash = pluginAbiDeclHash(text);
    char printed[16];
    std::snprintf(printed, sizeof printed, "0x%08xu", hash);
    std::printf("[measure] plugin ABI %u, declaration hash of plugin.h + registry.h: %s\n",
                kPluginAbiVersion, printed);
    INFO("plugin.h/registry.h declarations changed: review kPluginAbiVersion and set "
         "kPluginAbiDeclHash = "
         << printed << " in fluid/include/fluid/plugin_abi.h");
    CHECK(hash == kPluginAbiDeclHash);
    // Comments and layout do not count; a token does.
    CHECK(pluginAbiDeclHash("int  a; // note\n") == pluginAbiDeclHash("int a;"));
    CHECK(pluginAbiDeclHash("int a;") != pluginAbiDeclHash("int b;"));
}

TEST_CASE("docs/plugins.md quotes the example's whirlpool as it is", "[level][docs]") {
    // The example marks the lines the page quotes; the page's block after "### A force" must be
    // exactly those lines, so the two cannot drift apart.
    const std::string root = FLUID_SOURCE_DIR;
    const std::string example = readFile(root + "/examples/custom_force.cpp");
    const std::string page = readFile(root + "/docs/plugins.md");
    const std::string begin = "// [docs/plugins.md: A force]";
    const size_t marker = example.find(begin);
    REQUIRE(marker != std::string::npos);
    const size_t from = example.find("///", marker); // the quote starts at the doc comment
    const size_t to = example.find("// [end]\n", from);
    REQUIRE(from != std::string::npos);
    REQUIRE(to != std::string::npos);
    const std::string quoted = example.substr(from, to - from);

    const size_t section = page.find("### A force");
    REQUIRE(section != std::string::npos);
    const size_t open = page.find("```cpp\n", section);
    REQUIRE(open != std::string::npos);
    const size_t start = open + 7;
    const size_t close = page.find("```\n", start);
    REQUIRE(close != std::string::npos);
    const std::string block = page.substr(start, close - start);
    INFO("docs/plugins.md, \"A force\": copy the lines of examples/custom_force.cpp between its "
         "markers into the block");
    CHECK(block == quoted);
    CHECK(quoted.find("class WhirlpoolForce") != std::string::npos);
}

namespace {

// A declared number as docs/level_format.md prints it: the shortest form that reads back.
template <class T> std::string docNumber(T value) {
    char text[32];
    const auto [end, error] = std::to_chars(text, text + sizeof text, value);
    REQUIRE(error == std::errc());
    std::string out(text, end);
    // 1e+05 reads 1e5, 1e-03 reads 1e-3.
    for (const auto& [from, to] : {std::pair{"e+0", "e"}, {"e+", "e"}, {"e-0", "e-"}}) {
        if (const size_t at = out.find(from); at != std::string::npos) {
            out.replace(at, std::strlen(from), to);
        }
    }
    return out;
}

// A description in a table cell (a '|' would end the cell).
std::string cell(std::string_view text) {
    std::string out;
    for (const char c : text) {
        out += c == '|' ? std::string("\\|") : std::string(1, c);
    }
    return out;
}

// docs/level_format.md's table of the built-in plugin types, made from the registry's declarations:
// one row per parameter, the type named on its first row.
std::string pluginTable(const Registry& registry) {
    std::string out = "| type | parameter | unit | default | range | meaning |\n"
                      "|---|---|---|---|---|---|\n";
    for (const PluginInfo& info : registry.types()) {
        bool first = true;
        for (const ParamDecl& p : info.params) {
            out += "| " + (first ? "`" + info.type + "`" : std::string()) + " | `" +
                   std::string(p.name) + "` | ";
            if (p.type == ParamType::Points) {
                out += "points | none | " + docNumber(p.minValue) + " to " + docNumber(p.maxValue) +
                       " points";
            } else {
                out += std::string(p.unit) + " | " + docNumber(p.defaultValue) + " | [" +
                       docNumber(p.minValue) + ", " + docNumber(p.maxValue) + "]";
            }
            out += " | " + cell(p.description) + " |\n";
            first = false;
        }
    }
    return out;
}

} // namespace

namespace {

// A field's value in `def` as docs/level_format.md prints it, in the member's own type.
template <class Def> std::string valueText(const Field<Def>& f, const Def& def) {
    return f.real != nullptr ? docNumber(def.*f.real) : docNumber(def.*f.whole);
}

// docs/level_format.md's numbers of a material, made from materialFields(): range and both presets.
std::string materialTable() {
    std::string out = "| key | unit | range | water | yoghurt | meaning |\n"
                      "|---|---|---|---|---|---|\n";
    for (const MaterialField& f : materialFields()) {
        out += "| `" + std::string(f.name) + "` | " + std::string(f.unit) + " | " +
               (f.openLow ? "(" : "[") + docNumber(f.lo) + ", " + docNumber(f.hi) + "] | " +
               valueText(f, water()) + " | " + valueText(f, yoghurt()) + " | " +
               cell(f.description) + " |\n";
    }
    return out;
}

// docs/level_format.md's rows for `fields`, their defaults read from `defaults`.
template <class Def>
std::string fieldRows(std::span<const Field<Def>> fields, const Def& defaults) {
    std::string out;
    for (const Field<Def>& f : fields) {
        out += "| `" + std::string(f.name) + "` | " + (f.whole != nullptr ? "whole" : "number") +
               " | " + std::string(f.unit) + " | " + (f.openLow ? "(" : "[") + docNumber(f.lo) +
               ", " + docNumber(f.hi) + "] | " + valueText(f, defaults) + " | " +
               cell(f.description) + " |\n";
    }
    return out;
}

// Fails unless the text of docs/level_format.md between `begin` and `end` is `expected`; with
// FLUID_UPDATE_DOCS=1 in the environment it writes `expected` there instead.
void checkGenerated(const std::string& begin, const std::string& end,
                    const std::string& expected) {
    const std::string path = std::string(FLUID_SOURCE_DIR) + "/docs/level_format.md";
    const std::string page = readFile(path);
    const size_t from = page.find(begin);
    REQUIRE(from != std::string::npos);
    const size_t to = page.find(end, from);
    REQUIRE(to != std::string::npos);
    const std::string table = page.substr(from + begin.size(), to - from - begin.size());
    const char* update = std::getenv("FLUID_UPDATE_DOCS");
    if (table != expected && update != nullptr && std::string(update) == "1") {
        std::ofstream(path, std::ios::binary)
            << page.substr(0, from + begin.size()) + expected + page.substr(to);
        WARN("docs/level_format.md: a generated table was written anew");
        return;
    }
    INFO("docs/level_format.md's generated table differs from the declarations; write it anew with "
         "FLUID_UPDATE_DOCS=1 fluid-tests-level \"docs/level_format.md*\"");
    CHECK(table == expected);
}

} // namespace

TEST_CASE("docs/level_format.md's plugin table is the registry's declarations", "[level][docs]") {
    // The table between the markers is generated from every built-in type's ParamDecl array, so
    // a parameter, range, default or unit changed in a plugin's header changes the page. To
    // write the page anew: FLUID_UPDATE_DOCS=1 fluid-tests-level "docs/level_format.md*".
    Registry registry;
    registerBuiltinPlugins(registry);
    const std::string expected = pluginTable(registry);
    checkGenerated("<!-- plugin table: generated from the registry; see the test \"docs/"
                   "level_format.md's plugin table is the registry's declarations\" -->\n",
                   "<!-- end of the plugin table -->\n", expected);
    // Every built-in type is there, with its parameters.
    CHECK(expected.find("| `force.gravity` | `gx` | m/s^2 | 0 | [-1000, 1000] |") !=
          std::string::npos);
    CHECK(expected.find("| `boundary.polygon` |") != std::string::npos);
}

TEST_CASE("docs/level_format.md's material table is materialFields()", "[level][docs]") {
    // The same for the numbers of a material: what validation, the loader, snapshots and the
    // demo's panel read.
    const std::string expected = materialTable();
    checkGenerated("<!-- material table: generated from fluid::materialFields(); see the test "
                   "\"docs/level_format.md's material table is materialFields()\" -->\n",
                   "<!-- end of the material table -->\n", expected);
    CHECK(expected.find("| `yieldStress` | Pa | [0, 1e5] | 0 | 400 |") != std::string::npos);
    CHECK(expected.find("| `mass` | kg | (0, 1000] | 0.013 | 0.014 |") != std::string::npos);
}

TEST_CASE("docs/level_format.md's world and emitter numbers are their field tables",
          "[level][docs]") {
    const std::string header = "| key | type | unit | range | default | meaning |\n"
                               "|---|---|---|---|---|---|\n";
    const WorldDef world;
    const std::string settings = header + fieldRows(positionBasedFields(), world.positionBased) +
                                 fieldRows(worldFields(), world);
    checkGenerated("<!-- world table: generated from fluid::positionBasedFields() and "
                   "fluid::worldFields(); see the test \"docs/level_format.md's world and emitter "
                   "numbers are their field tables\" -->\n",
                   "<!-- end of the world table -->\n", settings);
    CHECK(settings.find("| `substeps` | whole | count | [1, 12] | 4 |") != std::string::npos);
    const std::string emitter = header + fieldRows(emitterFields(), EmitterDef{});
    checkGenerated("<!-- emitter table: generated from fluid::emitterFields(); see the test "
                   "\"docs/level_format.md's world and emitter numbers are their field "
                   "tables\" -->\n",
                   "<!-- end of the emitter table -->\n", emitter);
    CHECK(emitter.find("| `jitter` | number | 1 | [0, 0.5] | 0 |") != std::string::npos);
}
