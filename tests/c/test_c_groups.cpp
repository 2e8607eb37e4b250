// Groups, user data, colours and interpolation through the C API (fluid_world_*group*,
// _user_data, _colour*, _interpolat*): the C++ results, statuses with the C++ messages for
// stale ids and bad values, survival of a save and load.
#include "c_test_support.h"

#include <fluid/c.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

namespace {

fluid_blob_def boxBlob(fluid_material_id material, fluid_vec2 lo, fluid_vec2 hi) {
    fluid_blob_def blob = fluid_default_blob_def();
    blob.shape = fluid_box_shape(lo, hi);
    blob.material = material;
    return blob;
}

} // namespace

TEST_CASE("C: blobs and emitters are groups, and members, user data and colours follow them",
          "[c][groups]") {
    fluid_world_def def = fluid_default_world_def();
    fluid::test::CWorld w(def);
    const fluid_material_id water =
        fluid::test::waterTank(w.world, {-0.3f, 0.0f}, {0.3f, 0.6f}, {-0.3f, 0.0f}, {-0.1f, 0.2f});
    const fluid_group_def red{7, {255, 0, 0, 255}};
    fluid_group_id g{};
    uint32_t spawned = 0;
    const fluid_blob_def blob = boxBlob(water, {0.05f, 0.0f}, {0.25f, 0.2f});
    C_OK(fluid_world_spawn_group(w.world, &blob, fluid_group_id{}, &red, &g, &spawned));
    REQUIRE(spawned > 100);
    uint32_t count = 0;
    C_OK(fluid_world_group_count(w.world, g, &count));
    CHECK(count == spawned);

    fluid_emitter_def e = fluid_default_emitter_def();
    e.position = {0.0f, 0.5f};
    e.rate = 100.0f;
    e.max_count = 40;
    e.material = water;
    fluid_emitter_id emitter{};
    C_OK(fluid_world_add_emitter(w.world, &e, &emitter));
    fluid_group_id poured{};
    C_OK(fluid_world_emitter_group(w.world, emitter, &poured));
    bool valid = false;
    C_OK(fluid_world_group_valid(w.world, poured, &valid));
    CHECK(valid);
    const fluid_group_def green{9, {0, 255, 0, 255}};
    C_OK(fluid_world_set_group_def(w.world, poured, &green));
    C_OK(fluid_world_set_colour_mixing(w.world, 2.0f));
    C_OK(fluid_world_set_interpolation(w.world, true));
    for (int frame = 0; frame < 144; ++frame) { // one second: the emitter's 40 are out
        C_OK(fluid_world_step(w.world, 1.0f / 144.0f));
    }
    std::vector<fluid_particle_id> ids(spawned);
    C_OK(fluid_world_group_particles(w.world, g, ids.data(), uint32_t(ids.size()), &count));
    CHECK(count == spawned);
    for (const fluid_particle_id id : ids) {
        fluid_group_id of{};
        C_OK(fluid_world_particle_group(w.world, id, &of));
        CHECK((of.index == g.index && of.generation == g.generation));
        uint32_t data = 0;
        C_OK(fluid_world_particle_user_data(w.world, id, &data));
        CHECK(data == 7u);
    }
    C_OK(fluid_world_group_count(w.world, poured, &count));
    CHECK(count == 40);
    // Colours as one array, in index order, the same as per particle.
    const fluid_colour* colours = nullptr;
    uint32_t n = 0;
    C_OK(fluid_world_colours(w.world, &colours, &n));
    uint32_t particles = 0;
    C_OK(fluid_world_particle_count(w.world, &particles));
    REQUIRE(n == particles);
    fluid_colour one{};
    C_OK(fluid_world_particle_colour(w.world, ids[0], &one));
    uint32_t greenish = 0;
    for (uint32_t i = 0; i < n; ++i) {
        greenish += colours[i].g > 0 ? 1 : 0;
    }
    CHECK(greenish >= 40);
    // User data as one array.
    std::vector<uint32_t> data(n);
    C_OK(fluid_world_user_data(w.world, data.data(), n, &count));
    CHECK(count == n);
    // Centre and velocity: the C++ sums.
    fluid_vec2 centre{}, velocity{};
    C_OK(fluid_world_group_centre(w.world, g, &centre));
    C_OK(fluid_world_group_velocity(w.world, g, &velocity));
    CHECK(std::isfinite(centre.x));
    CHECK(centre.y > 0.0f);
    // Interpolated positions between the previous and current ones.
    float factor = -1.0f;
    C_OK(fluid_world_interpolation_factor(w.world, &factor));
    CHECK((factor >= 0.0f && factor < 1.0f));
    std::vector<float> x(n), y(n);
    C_OK(fluid_world_interpolated_positions(w.world, x.data(), y.data(), n, 1.0f, &count));
    const float* px = nullptr;
    const float* py = nullptr;
    C_OK(fluid_world_positions(w.world, &px, &py, &count));
    CHECK(std::equal(x.begin(), x.end(), px));
    // Move and velocity.
    C_OK(fluid_world_set_group_velocity(w.world, g, {0.0f, 1.0f}));
    C_OK(fluid_world_group_velocity(w.world, g, &velocity));
    CHECK((velocity.x == 0.0f && velocity.y == 1.0f));
    const fluid_vec2 before = centre;
    C_OK(fluid_world_move_group(w.world, g, {0.0f, 0.25f}));
    C_OK(fluid_world_group_centre(w.world, g, &centre));
    CHECK(std::fabs(centre.y - (before.y + 0.25f)) < 1e-5f);

    // A save and load keeps groups, user data and colours.
    fluid_bytes bytes{};
    C_OK(fluid_world_save(w.world, &bytes));
    fluid_world* loaded = nullptr;
    C_OK(fluid_world_load(bytes.data, bytes.size, 0, &loaded));
    fluid_bytes again{};
    C_OK(fluid_world_save(loaded, &again));
    CHECK(std::string(reinterpret_cast<const char*>(bytes.data), bytes.size) ==
          std::string(reinterpret_cast<const char*>(again.data), again.size));
    fluid_bytes_free(&bytes);
    fluid_bytes_free(&again);
    fluid_world_destroy(loaded);

    // Merge and destroy.
    C_OK(fluid_world_merge_groups(w.world, g, poured));
    C_OK(fluid_world_group_valid(w.world, poured, &valid));
    CHECK_FALSE(valid);
    C_OK(fluid_world_group_count(w.world, g, &count));
    CHECK(count == spawned + 40);
    C_OK(fluid_world_destroy_group(w.world, g, true));
    uint32_t left = 0;
    C_OK(fluid_world_particle_count(w.world, &left));
    CHECK(left == particles - spawned - 40);
}

TEST_CASE("C: stale ids and bad values fail with a status and the C++ message", "[c][groups]") {
    fluid_world_def def = fluid_default_world_def();
    fluid::test::CWorld w(def);
    const fluid_material_id water =
        fluid::test::waterTank(w.world, {-0.3f, 0.0f}, {0.3f, 0.6f}, {-0.3f, 0.0f}, {-0.1f, 0.2f});
    fluid_group_id g{};
    C_OK(fluid_world_create_group(w.world, nullptr, &g));
    C_OK(fluid_world_destroy_group(w.world, g, true));
    uint32_t count = 0;
    CHECK(fluid_world_group_count(w.world, g, &count) == FLUID_ERROR_STALE_ID);
    CHECK(std::string(fluid_last_error()) ==
          "groupCount: stale group handle {index " + std::to_string(g.index) +
              ", generation 1}: that group was destroyed or merged into another");
    CHECK(fluid_world_move_group(w.world, fluid_group_id{}, {0.0f, 0.0f}) == FLUID_ERROR_STALE_ID);
    CHECK(std::string(fluid_last_error()) == "moveGroup: null group handle");
    fluid_group_id live{};
    C_OK(fluid_world_create_group(w.world, nullptr, &live));
    CHECK(fluid_world_move_group(w.world, live, {NAN, 0.0f}) == FLUID_ERROR_INVALID_ARGUMENT);
    CHECK(std::string(fluid_last_error()) ==
          "moveGroup: offset = (nan, 0) is not finite (unit: m)");
    CHECK(fluid_world_set_interpolation_mode(w.world, 258) == FLUID_ERROR_INVALID_ARGUMENT);
    CHECK(std::string(fluid_last_error()) ==
          "fluid_world_set_interpolation_mode: mode = 258 is not a fluid_interpolation "
          "(FLUID_INTERPOLATION_OFF 0, FLUID_INTERPOLATION_SUBSTEP 1, FLUID_INTERPOLATION_STEP 2)");
    // Over whole steps: the world's factor reads 1 (the game's own counts), and the previous
    // positions are those at the step's start.
    C_OK(fluid_world_set_interpolation_mode(w.world, FLUID_INTERPOLATION_STEP));
    C_OK(fluid_world_step(w.world, 1.0f / 60.0f));
    float stepFactor = 0.0f;
    C_OK(fluid_world_interpolation_factor(w.world, &stepFactor));
    CHECK(stepFactor == 1.0f);
    C_OK(fluid_world_set_interpolation_mode(w.world, FLUID_INTERPOLATION_OFF));
    CHECK(fluid_world_set_colour_mixing(w.world, 5000.0f) == FLUID_ERROR_INVALID_ARGUMENT);
    CHECK_THAT(fluid_last_error(),
               Catch::Matchers::StartsWith("setColourMixing: rate = 5000 is out of range"));
    CHECK(fluid_world_interpolated_positions(w.world, nullptr, nullptr, 0, 2.0f, nullptr) ==
          FLUID_ERROR_INVALID_ARGUMENT);
    CHECK(fluid_world_group_count(w.world, live, nullptr) == FLUID_ERROR_NULL_ARGUMENT);
    CHECK(fluid_world_colours(w.world, nullptr, &count) == FLUID_ERROR_NULL_ARGUMENT);
    const fluid_colour* colours = reinterpret_cast<const fluid_colour*>(&count);
    C_OK(fluid_world_colours(w.world, &colours, &count));
    CHECK(colours == nullptr); // no particle ever had a colour
    CHECK(count == 0);
    fluid_particle_id gone{};
    C_OK(fluid_world_add_particle(w.world, {0.0f, 0.3f}, {0.0f, 0.0f}, water, &gone));
    C_OK(fluid_world_remove_particle(w.world, gone));
    CHECK(fluid_world_set_particle_colour(w.world, gone, {1, 2, 3, 4}) == FLUID_ERROR_STALE_ID);
    CHECK_THAT(fluid_last_error(),
               Catch::Matchers::StartsWith("setColour: stale particle handle {slot "));
    fluid_emitter_id nowhere{3, 0};
    fluid_group_id out{};
    CHECK(fluid_world_emitter_group(w.world, nowhere, &out) == FLUID_ERROR_STALE_ID);
    CHECK(std::string(fluid_last_error()) ==
          "emitterGroup: unknown emitter id 3; the world has 0 emitters");
}
