/* A game written in C99 against the installed C API (fluid/c.h), built by
 * tests/install/check_install.cmake: by CMake from a C-only project (CMakeLists.txt here), by make
 * (Makefile here) and by cc on the command line, both through pkg-config; each against the
 * static and the shared library. It checks what a working link must give and exits 0 only
 * then, printing "consumer_c: ok ...":
 *   - the library's C API major version is the header's;
 *   - a C++ exception thrown inside the library comes back as a status and a message (a C link
 *     without the C++ runtime's unwinding would abort there);
 *   - a block of water in a tank, stepped for one second, keeps every particle, stays in the
 *     tank and falls (the solver and the worker threads run). */
#include <fluid/c.h>

#include <stdio.h>
#include <string.h>

#define FAIL(...)                                                                                 \
    do {                                                                                          \
        fprintf(stderr, "consumer_c: " __VA_ARGS__);                                              \
        fluid_world_destroy(world);                                                               \
        return 1;                                                                                 \
    } while (0)

#define CHECK(call)                                                                               \
    do {                                                                                          \
        fluid_status status_ = (call);                                                            \
        if (status_ != FLUID_OK) {                                                                \
            FAIL("%s: %s: %s\n", #call, fluid_status_name(status_), fluid_last_error());         \
        }                                                                                         \
    } while (0)

/* Mean height of the particles, and whether all are inside the tank (1 cm of slack). */
static int mean_height(const fluid_world* world, uint32_t* count, double* mean) {
    const float *x, *y;
    uint32_t i;
    double sum = 0.0;
    if (fluid_world_positions(world, &x, &y, count) != FLUID_OK || *count == 0) {
        return 0;
    }
    for (i = 0; i < *count; ++i) {
        if (!(x[i] >= -0.01f && x[i] <= 1.01f && y[i] >= -0.01f && y[i] <= 1.01f)) {
            return 0;
        }
        sum += y[i];
    }
    *mean = sum / *count;
    return 1;
}

int main(void) {
    static const char expected_error[] =
        "fluid_material_preset: unknown preset 'lava' (expected water, yoghurt or seed_yoghurt)";
    fluid_world* world = NULL;
    fluid_world_def def = fluid_default_world_def();
    fluid_material_def water;
    fluid_material_id water_id;
    fluid_plugin_id plugin;
    fluid_blob_def blob = fluid_default_blob_def();
    const fluid_param tank[] = {{"minX", 0.0}, {"minY", 0.0}, {"maxX", 1.0}, {"maxY", 1.0}};
    const fluid_param gravity[] = {{"gx", 0.0}, {"gy", -9.81}};
    uint32_t spawned = 0, count = 0, frame;
    double before = 0.0, after = 0.0;
    fluid_status status;

    if (fluid_version() / 100 != FLUID_C_VERSION_MAJOR) {
        FAIL("the library's C API is version %u, the header's major version %d\n",
             (unsigned)fluid_version(), FLUID_C_VERSION_MAJOR);
    }
    status = fluid_material_preset("lava", &water);
    if (status != FLUID_ERROR_UNKNOWN_NAME || strcmp(fluid_last_error(), expected_error) != 0) {
        FAIL("fluid_material_preset(\"lava\") gave %s \"%s\", expected "
             "FLUID_ERROR_UNKNOWN_NAME \"%s\"\n",
             fluid_status_name(status), fluid_last_error(), expected_error);
    }

    CHECK(fluid_world_def_set_quality(&def, "game"));
    def.worker_count = 2;
    CHECK(fluid_world_create(&def, &world));
    CHECK(fluid_material_preset("water", &water));
    CHECK(fluid_world_add_material(world, &water, &water_id));
    CHECK(fluid_world_add_plugin(world, "boundary.box", tank, 4, &plugin));
    CHECK(fluid_world_add_plugin(world, "force.gravity", gravity, 2, &plugin));
    blob.shape = fluid_box_shape((fluid_vec2){0.0f, 0.4f}, (fluid_vec2){0.3f, 0.7f});
    blob.material = water_id;
    CHECK(fluid_world_spawn_blob(world, &blob, &spawned));
    if (spawned < 100 || !mean_height(world, &count, &before) || count != spawned) {
        FAIL("the blob spawned %u particles (%u in the tank); expected at least 100\n",
             (unsigned)spawned, (unsigned)count);
    }

    for (frame = 0; frame < 60; ++frame) {
        CHECK(fluid_world_step(world, 1.0f / 60.0f));
    }
    if (!mean_height(world, &count, &after) || count != spawned) {
        FAIL("after 1 s, %u particles, not the %u spawned, or some left the tank\n",
             (unsigned)count, (unsigned)spawned);
    }
    /* Released from 0.4-0.7 m, the water spreads on the floor: its mean height falls from
     * 0.55 m to about 0.1 m. */
    if (!(after < before - 0.2)) {
        FAIL("after 1 s the water's mean height is %.3f m, from %.3f m: it did not fall\n",
             after, before);
    }
    printf("consumer_c: ok: %u particles, mean height %.3f m -> %.3f m\n", (unsigned)count,
           before, after);
    fluid_world_destroy(world);
    return 0;
}
