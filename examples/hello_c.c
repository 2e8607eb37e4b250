/* hello_c: fluid from C99 (fluid/c.h, docs/c_api.md). A tank with a block of water and a blob
 * of yoghurt; two seconds of simulation; where the liquid ended up.
 *
 *   cc -std=c99 hello_c.c $(pkg-config --cflags --libs fluid-c-static)   (an installed fluid:
 *   docs/c_api.md), or the CMake target hello_c
 */
#include <fluid/c.h>

#include <stdio.h>

/* Prints the failing call's message and returns from main with 1. */
#define CHECK(call)                                                                               \
    do {                                                                                          \
        fluid_status status_ = (call);                                                            \
        if (status_ != FLUID_OK) {                                                                \
            fprintf(stderr, "hello_c: %s: %s\n", fluid_status_name(status_), fluid_last_error()); \
            fluid_world_destroy(world);                                                           \
            return 1;                                                                             \
        }                                                                                         \
    } while (0)

int main(void) {
    fluid_world* world = NULL;
    fluid_world_def def = fluid_default_world_def();
    fluid_material_def water, yoghurt;
    fluid_material_id water_id, yoghurt_id;
    fluid_plugin_id plugin;
    fluid_blob_def blob = fluid_default_blob_def();
    const fluid_param tank[] = {{"minX", 0.0}, {"minY", 0.0}, {"maxX", 1.0}, {"maxY", 1.0}};
    const fluid_param gravity[] = {{"gx", 0.0}, {"gy", -9.81}};
    const float *x, *y;
    const uint16_t* material;
    uint32_t count, spawned, i, frame;
    double mean_y[2] = {0.0, 0.0};
    uint32_t of[2] = {0, 0};

    printf("fluid C API %u.%u\n", (unsigned)(fluid_version() / 100),
           (unsigned)(fluid_version() % 100));
    /* The game preset: a game's speed, water within a few percent of its rest density. */
    CHECK(fluid_world_def_set_quality(&def, "game"));
    def.worker_count = 2;
    CHECK(fluid_world_create(&def, &world));

    CHECK(fluid_material_preset("water", &water));
    CHECK(fluid_material_preset("yoghurt", &yoghurt));
    CHECK(fluid_world_add_material(world, &water, &water_id));
    CHECK(fluid_world_add_material(world, &yoghurt, &yoghurt_id));

    /* Built-in plugins by their registry names and parameters (docs/plugins.md). */
    CHECK(fluid_world_add_plugin(world, "boundary.box", tank, 4, &plugin));
    CHECK(fluid_world_add_plugin(world, "force.gravity", gravity, 2, &plugin));

    blob.shape = fluid_box_shape((fluid_vec2){0.0f, 0.0f}, (fluid_vec2){0.3f, 0.5f});
    blob.material = water_id;
    CHECK(fluid_world_spawn_blob(world, &blob, &spawned));
    printf("water: %u particles\n", (unsigned)spawned);
    blob.shape = fluid_circle_shape((fluid_vec2){0.7f, 0.6f}, 0.1f);
    blob.material = yoghurt_id;
    CHECK(fluid_world_spawn_blob(world, &blob, &spawned));
    printf("yoghurt: %u particles\n", (unsigned)spawned);

    for (frame = 0; frame < 120; ++frame) {
        CHECK(fluid_world_step(world, 1.0f / 60.0f));
    }

    /* The arrays stay valid until the world changes. */
    CHECK(fluid_world_positions(world, &x, &y, &count));
    CHECK(fluid_world_material_indices(world, &material, &count));
    for (i = 0; i < count; ++i) {
        mean_y[material[i]] += y[i];
        of[material[i]] += 1;
    }
    printf("after 2 s: water at %.3f m mean height, yoghurt at %.3f m (%u particles, x[0] = %.3f)\n",
           of[0] ? mean_y[0] / of[0] : 0.0, of[1] ? mean_y[1] / of[1] : 0.0, (unsigned)count,
           count ? (double)x[0] : 0.0);
    fluid_world_destroy(world);
    return 0;
}
