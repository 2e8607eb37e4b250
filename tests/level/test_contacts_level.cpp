// Contact events in level files: "contacts": true on a body asks the coupling, on a boundary
// shape asks the world; both come back from a level save and step on to the same events; keys
// where they cannot apply are refused, naming file, line and key.
#include "level_support.h"

#include <fluid/box2d/coupling.h>
#include <fluid/contacts.h>
#include <fluid/level.h>

#include <catch2/catch.hpp>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <string>

using namespace fluid;
using namespace fluid::test;

namespace {

// Water in a tank, a disc (plugin "post", asking) standing in it, a crate (asking) dropped into
// it and a lamp above it (not asking).
const std::string kLevel = R"({"version": 1,
  "world": {"gravity": [0, -9.81]},
  "materials": [{"name": "water", "preset": "water"}],
  "plugins": [
    {"type": "boundary.box", "params": {"minX": 0, "minY": 0, "maxX": 0.6, "maxY": 1}},
    {"type": "boundary.circle", "name": "post", "contacts": true,
     "params": {"x": 0.1, "y": 0.1, "radius": 0.04}}],
  "blobs": [{"material": "water", "shape": "box", "min": [0, 0], "max": [0.6, 0.2]}],
  "bodies": [
    {"name": "crate", "position": [0.4, 0.3], "contacts": true,
     "fixtures": [{"shape": "box", "width": 0.1, "height": 0.1, "densityRatio": 0.5}]},
    {"name": "lamp", "type": "static", "position": [0.1, 0.6],
     "fixtures": [{"shape": "circle", "radius": 0.03}]}]})";

// The frame's events of both kinds as bytes.
std::string events(const Level& level) {
    std::string out;
    const auto add = [&](const void* data, size_t size) {
        out.append(static_cast<const char*>(data), size);
    };
    for (const BodyContact& e : bodyContacts(level.world)) {
        add(&e.plugin, sizeof e.plugin);
        add(&e.particles, sizeof e.particles);
        add(&e.impulse, sizeof e.impulse);
        add(&e.point, sizeof e.point);
        add(&e.approachSpeed, sizeof e.approachSpeed);
    }
    for (const box2d::ParticleContact& e : level.coupling->particleContacts()) {
        uint32_t body = 0;
        while (body < level.bodies.size() && level.bodies[body].second != e.body) {
            ++body;
        }
        add(&body, sizeof body);
        add(&e.particles, sizeof e.particles);
        add(&e.impulse, sizeof e.impulse);
        add(&e.point, sizeof e.point);
        add(&e.approachSpeed, sizeof e.approachSpeed);
    }
    return out;
}

} // namespace

TEST_CASE("level contacts: a body and a shape that ask report, through a save too",
          "[level][contacts]") {
    Level level = parseLevel(kLevel, "t.json", builtins());
    b2Body* crate = bodyNamed(level, "crate");
    REQUIRE(crate != nullptr);
    CHECK(level.coupling->contactEvents(crate));
    CHECK(!level.coupling->contactEvents(bodyNamed(level, "lamp")));
    uint32_t crateFrames = 0;
    for (int frame = 0; frame < 30; ++frame) {
        level.step();
        // The post stands in the water from the start (plugin 1); the crate lands after a few
        // frames (the world reports it too, as a body of the coupling's plugin, 2).
        const std::span<const BodyContact> world = bodyContacts(level.world);
        REQUIRE(!world.empty());
        CHECK(world[0].plugin == 1);
        CHECK(world.back().plugin == (world.size() == 2 ? 2u : 1u));
        for (const box2d::ParticleContact& e : level.coupling->particleContacts()) {
            CHECK(e.body == crate);
            ++crateFrames;
        }
    }
    CHECK(crateFrames > 15);

    Level loaded = restore(saveOf(level));
    CHECK(loaded.coupling->contactEvents(bodyNamed(loaded, "crate")));
    for (int frame = 0; frame < 10; ++frame) {
        level.step();
        loaded.step();
        CHECK(events(loaded) == events(level));
        CHECK(!events(level).empty());
    }
}

TEST_CASE("level contacts: the key where it cannot apply is refused", "[level][contacts]") {
    const std::string materials = R"({"version": 1, "materials": [{"name": "water"}], )";
    CHECK(errorOf(materials + R"("plugins": [{"type": "force.gravity", "contacts": true}]})") ==
          "t.json:1:100: at /plugins/0/contacts: contact events are reported for the shapes "
          "boundary.polygon, boundary.chain and boundary.circle; 'force.gravity' has none");
    CHECK(errorOf(materials + R"("plugins": [{"type": "boundary.box", "contacts": true}]})") ==
          "t.json:1:99: at /plugins/0/contacts: contact events are reported for the shapes "
          "boundary.polygon, boundary.chain and boundary.circle; 'boundary.box' has none");
    CHECK(errorOf(materials + R"("plugins": [{"type": "boundary.circle", "contacts": 1}]})") ==
          "t.json:1:102: at /plugins/0/contacts: expected true or false, got a number");
    CHECK(errorOf(materials + R"("bodies": [{"fluid": false, "contacts": true, "fixtures": [
          {"shape": "circle", "radius": 0.1, "density": 1}]}]})") ==
          "t.json:1:90: at /bodies/0/contacts: a body with \"fluid\": false never touches the "
          "liquid: it has no contact events");
}

TEST_CASE("level contacts: fluid-run writes the asking bodies' and shapes' contacts to its CSV",
          "[level][contacts][fluid-run]") {
    namespace fs = std::filesystem;
    const fs::path dir = fs::temp_directory_path() / "fluid_run_contacts";
    fs::create_directories(dir);
    { std::ofstream(dir / "contacts.json") << kLevel; }
    std::ostringstream command;
    command << std::quoted(FLUID_RUN_PATH) << ' ' << std::quoted((dir / "contacts.json").string())
            << " --frames 20 --csv " << std::quoted((dir / "c.csv").string())
            << " >/dev/null 2>&1 </dev/null";
    REQUIRE(std::system(command.str().c_str()) == 0);
    std::ifstream in(dir / "c.csv");
    std::string header, line, last;
    std::getline(in, header);
    while (std::getline(in, line)) {
        last = line;
    }
    // The columns: the crate's and the post's four each, last; the lamp (not asking) has none.
    const std::string columns = ",b_crate_contact_particles,b_crate_contact_ix,b_crate_contact_iy,"
                                "b_crate_contact_speed,p_post_contact_particles,p_post_contact_ix,"
                                "p_post_contact_iy,p_post_contact_speed";
    REQUIRE(header.size() > columns.size());
    CHECK(header.substr(header.size() - columns.size()) == columns);
    CHECK(header.find("b_lamp_contact") == std::string::npos);
    // The last frame's: the level stepped in this process gives the same numbers.
    Level level = parseLevel(kLevel, "t.json", builtins());
    for (int frame = 0; frame < 20; ++frame) {
        level.step();
    }
    REQUIRE(level.coupling->particleContacts().size() == 1);
    const box2d::ParticleContact& crate = level.coupling->particleContacts()[0];
    const BodyContact& post = bodyContacts(level.world)[0];
    std::ostringstream expected;
    expected << std::setprecision(9) << ',' << crate.particles << ',' << crate.impulse.x << ','
             << crate.impulse.y << ',' << crate.approachSpeed << ',' << post.particles << ','
             << post.impulse.x << ',' << post.impulse.y << ',' << post.approachSpeed;
    REQUIRE(last.size() > expected.str().size());
    CHECK(last.substr(last.size() - expected.str().size()) == expected.str());
}

TEST_CASE("level contacts: a destroyed body's setting goes with it", "[level][contacts]") {
    Level level = parseLevel(kLevel, "t.json", builtins());
    b2Body* crate = bodyNamed(level, "crate");
    level.step();
    level.destroyBody(crate);
    // A body made at once may take the freed address: it does not ask.
    b2BodyDef def;
    def.type = b2_dynamicBody;
    def.position.Set(0.3f, 0.5f);
    b2Body* next = level.physics->CreateBody(&def);
    b2CircleShape circle;
    circle.m_radius = 0.03f;
    next->CreateFixture(&circle, 60.0f);
    CHECK(!level.coupling->contactEvents(next));
    for (int frame = 0; frame < 40; ++frame) {
        level.step();
        CHECK(level.coupling->particleContacts().empty());
    }
}
