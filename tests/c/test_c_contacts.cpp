// Contact events through the C API (fluid_world_set_contact_events, fluid_world_contacts,
// fluid_world_contact_particles; the level's fluid_level_set_body_contact_events,
// fluid_level_body_contacts, fluid_level_body_contact_particles): the C++ events bit for bit,
// a crate's through a level and its save, and the statuses of bad calls.
#include "c_test_support.h"

#include <fluid/c.h>
#include <fluid/contacts.h>
#include <fluid/fluid.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

namespace {

constexpr float kFrameDt = 1.0f / 60.0f;

// Water in a tank (fluid::test::waterTank: box, then gravity, then the blob) and a disc of 5 cm
// at (0.3, 0.2) asking for contact events: plugin 2.
fluid_plugin_id discTank(fluid_world* world) {
    fluid::test::waterTank(world, {0.0f, 0.0f}, {0.6f, 1.0f}, {0.0f, 0.0f}, {0.6f, 0.3f});
    const fluid_param disc[] = {{"x", 0.3}, {"y", 0.2}, {"radius", 0.05}};
    fluid_plugin_id id{};
    C_OK(fluid_world_add_plugin(world, "boundary.circle", disc, 3, &id));
    C_OK(fluid_world_set_contact_events(world, id, true));
    return id;
}

// The same world through the C++ API.
fluid::World cppDiscTank() {
    fluid::World world;
    const fluid::MaterialId water = world.addMaterial(fluid::water());
    // Parameters are doubles: set as the C calls set them (0.6, not 0.6f).
    auto box = std::make_unique<fluid::BoxContainer>();
    box->setParam("minX", 0.0);
    box->setParam("minY", 0.0);
    box->setParam("maxX", 0.6);
    box->setParam("maxY", 1.0);
    world.addBoundary(std::move(box));
    world.addForce(std::make_unique<fluid::GravityForce>(0.0f, -9.81f));
    fluid::BlobDef blob;
    blob.shape = fluid::Shape::box({0.0f, 0.0f}, {0.6f, 0.3f});
    blob.material = water;
    world.spawnBlob(blob);
    auto disc = std::make_unique<fluid::CircleBoundary>();
    disc->setParam("x", 0.3);
    disc->setParam("y", 0.2);
    disc->setParam("radius", 0.05);
    disc->setContactEvents(true);
    world.addBoundary(std::move(disc));
    return world;
}

std::string lastError() {
    return fluid_last_error();
}

} // namespace

TEST_CASE("C: a shape's contact events are the C++ events", "[c][contacts]") {
    fluid_world_def def = fluid_default_world_def();
    fluid::test::CWorld c(def);
    const fluid_plugin_id disc = discTank(c.world);
    fluid::World cpp = cppDiscTank();
    for (int frame = 0; frame < 20; ++frame) {
        C_OK(fluid_world_step(c.world, kFrameDt));
        cpp.step(kFrameDt);
        uint32_t count = 0;
        C_OK(fluid_world_contacts(c.world, nullptr, 0, &count));
        const std::span<const fluid::BodyContact> expected = fluid::bodyContacts(cpp);
        REQUIRE(count == expected.size());
        REQUIRE(count == 1);
        std::vector<fluid_body_contact> got(count);
        C_OK(fluid_world_contacts(c.world, got.data(), count, &count));
        const fluid_body_contact& g = got[0];
        const fluid::BodyContact& e = expected[0];
        CHECK(g.plugin.index == disc.index);
        CHECK(g.plugin.kind == FLUID_PLUGIN_BOUNDARY);
        CHECK(g.plugin.world == disc.world);
        CHECK(g.body == 0);
        CHECK(g.material.index == e.material.index);
        CHECK(g.group.index == e.group.index);
        CHECK(g.group.generation == e.group.generation);
        CHECK(g.group.world == g.plugin.world); // the C world's tag (e is another world's)
        CHECK(g.group.generation != 0);
        CHECK(g.particles == e.particles);
        CHECK(std::memcmp(&g.impulse, &e.impulse, sizeof g.impulse) == 0);
        CHECK(std::memcmp(&g.point, &e.point, sizeof g.point) == 0);
        CHECK(std::memcmp(&g.approach_speed, &e.approachSpeed, sizeof g.approach_speed) == 0);
        // The particles: the C++ list, each one alive, a short buffer filled as far as it goes.
        uint32_t n = 0;
        C_OK(fluid_world_contact_particles(c.world, 0, nullptr, 0, &n));
        REQUIRE(n == g.particles);
        std::vector<fluid_particle_id> ids(n + 2);
        C_OK(fluid_world_contact_particles(c.world, 0, ids.data(), n - 1, &n));
        CHECK(n == g.particles);
        CHECK(ids[n - 1].generation == 0); // not written: the buffer held n - 1
        C_OK(fluid_world_contact_particles(c.world, 0, ids.data(), uint32_t(ids.size()), &n));
        const std::span<const fluid::ParticleHandle> handles = fluid::contactParticles(cpp, 0);
        for (uint32_t k = 0; k < n; ++k) {
            CHECK(ids[k].slot == handles[k].slot);
            CHECK(ids[k].generation == handles[k].generation);
            bool valid = false;
            C_OK(fluid_world_particle_valid(c.world, ids[k], &valid));
            CHECK(valid);
        }
    }
    // Off: the next step reports none.
    C_OK(fluid_world_set_contact_events(c.world, disc, false));
    C_OK(fluid_world_step(c.world, kFrameDt));
    uint32_t count = 7;
    C_OK(fluid_world_contacts(c.world, nullptr, 0, &count));
    CHECK(count == 0);
}

TEST_CASE("C: bad contact calls return their status and name the problem", "[c][contacts]") {
    fluid_world_def def = fluid_default_world_def();
    fluid::test::CWorld c(def);
    const fluid_plugin_id disc = discTank(c.world);
    C_OK(fluid_world_step(c.world, kFrameDt));
    // The tank (boundary.box) and gravity are no shapes.
    fluid_plugin_id box = disc;
    box.index = 0;
    CHECK(fluid_world_set_contact_events(c.world, box, true) == FLUID_ERROR_INVALID_ARGUMENT);
    CHECK(lastError() == "fluid_world_set_contact_events: plugin 'boundary.box' is not a boundary "
                         "shape (boundary.polygon, boundary.chain, boundary.circle): it has no "
                         "contact events");
    fluid_plugin_id gravity{0, FLUID_PLUGIN_FORCE, disc.world};
    CHECK(fluid_world_set_contact_events(c.world, gravity, true) == FLUID_ERROR_INVALID_ARGUMENT);
    fluid_plugin_id missing = disc;
    missing.index = 9;
    CHECK(fluid_world_set_contact_events(c.world, missing, true) == FLUID_ERROR_STALE_ID);
    uint32_t n = 0;
    CHECK(fluid_world_contact_particles(c.world, 1, nullptr, 0, &n) ==
          FLUID_ERROR_INVALID_ARGUMENT);
    CHECK(lastError() == "fluid_world_contact_particles: contact = 1 is out of range: the last "
                         "step reported 1 contacts");
    CHECK(fluid_world_contacts(c.world, nullptr, 1, &n) == FLUID_ERROR_NULL_ARGUMENT);
    CHECK(fluid_world_contacts(c.world, nullptr, 0, nullptr) == FLUID_ERROR_NULL_ARGUMENT);
    CHECK(fluid_world_contacts(nullptr, nullptr, 0, &n) == FLUID_ERROR_NULL_ARGUMENT);
}

TEST_CASE("C: a level's crate reports its contacts, through a save too", "[c][contacts]") {
    // A crate at half the water's density dropped into a tank, asking in the file; a dry box
    // above the water asking through the C API; the tank's walls as a body the liquid passes.
    const std::string text = R"({"version": 1,
      "world": {"gravity": [0, -9.81], "quality": "precise"},
      "materials": [{"name": "water", "preset": "water"}],
      "plugins": [{"type": "boundary.box", "params": {"minX": 0, "minY": 0, "maxX": 0.6, "maxY": 1}}],
      "blobs": [{"material": "water", "shape": "box", "min": [0, 0], "max": [0.6, 0.2]}],
      "bodies": [
        {"name": "tank", "type": "static", "fluid": false, "fixtures": [
          {"shape": "box", "width": 0.8, "height": 0.1, "center": [0.3, -0.05]}]},
        {"name": "crate", "position": [0.3, 0.35], "contacts": true,
         "fixtures": [{"shape": "box", "width": 0.1, "height": 0.1, "densityRatio": 0.5}]},
        {"name": "lamp", "type": "static", "position": [0.1, 0.6],
         "fixtures": [{"shape": "circle", "radius": 0.03}]}]})";
    fluid_level* level = nullptr;
    C_OK(fluid_level_parse(text.data(), text.size(), "crate.json", nullptr, &level));
    C_OK(fluid_level_set_body_contact_events(level, 2, true));
    uint32_t touched = 0;
    for (int frame = 0; frame < 30; ++frame) {
        C_OK(fluid_level_step(level));
        uint32_t count = 0;
        C_OK(fluid_level_body_contacts(level, nullptr, 0, &count));
        REQUIRE(count <= 1); // the lamp never touches, the tank does not ask
        if (count == 1) {
            fluid_level_body_contact e{};
            C_OK(fluid_level_body_contacts(level, &e, 1, &count));
            CHECK(e.body == 1);
            CHECK(e.material.index == 0);
            CHECK(e.particles > 0);
            uint32_t n = 0;
            C_OK(fluid_level_body_contact_particles(level, 0, nullptr, 0, &n));
            CHECK(n == e.particles);
            ++touched;
        }
    }
    CHECK(touched > 10);

    // Saved and read back: the settings come with it, and both step to the same events.
    fluid_bytes bytes{};
    C_OK(fluid_level_save_bytes(level, &bytes));
    fluid_level* loaded = nullptr;
    C_OK(fluid_level_read_save(bytes.data, bytes.size, "crate.save", nullptr, &loaded));
    fluid_bytes_free(&bytes);
    for (int frame = 0; frame < 5; ++frame) {
        C_OK(fluid_level_step(level));
        C_OK(fluid_level_step(loaded));
        fluid_level_body_contact a{}, b{};
        uint32_t na = 0, nb = 0;
        C_OK(fluid_level_body_contacts(level, &a, 1, &na));
        C_OK(fluid_level_body_contacts(loaded, &b, 1, &nb));
        REQUIRE(na == 1);
        REQUIRE(nb == 1);
        CHECK(a.body == b.body);
        CHECK(a.particles == b.particles);
        CHECK(std::memcmp(&a.impulse, &b.impulse, sizeof a.impulse) == 0);
        CHECK(std::memcmp(&a.point, &b.point, sizeof a.point) == 0);
        CHECK(std::memcmp(&a.approach_speed, &b.approach_speed, sizeof a.approach_speed) == 0);
    }

    // Off through the API; bad indices.
    C_OK(fluid_level_set_body_contact_events(level, 1, false));
    C_OK(fluid_level_step(level));
    uint32_t count = 5;
    C_OK(fluid_level_body_contacts(level, nullptr, 0, &count));
    CHECK(count == 0);
    CHECK(fluid_level_set_body_contact_events(level, 3, true) == FLUID_ERROR_STALE_ID);
    CHECK(lastError() == "fluid_level_set_body_contact_events: index 3 is past the level's 3 "
                         "bodies");
    uint32_t n = 0;
    CHECK(fluid_level_body_contact_particles(level, 0, nullptr, 0, &n) ==
          FLUID_ERROR_INVALID_ARGUMENT);
    CHECK(lastError() == "fluid_level_body_contact_particles: contact = 0 is out of range: the "
                         "last step reported 0 contacts");
    C_OK(fluid_level_destroy(loaded));
    C_OK(fluid_level_destroy(level));

    // A level without bodies has no Box2D bodies to ask about.
    const std::string plain = R"({"version": 1, "materials": [{"name": "water"}]})";
    C_OK(fluid_level_parse(plain.data(), plain.size(), "plain.json", nullptr, &level));
    CHECK(fluid_level_set_body_contact_events(level, 0, true) == FLUID_ERROR_REFUSED);
    C_OK(fluid_level_body_contacts(level, nullptr, 0, &count));
    CHECK(count == 0);
    C_OK(fluid_level_destroy(level));
}
