/* The dam the Python tests build (tests/python/test_world.py), built and stepped through the C
 * API alone: prints the particle count and an FNV-1a hash of the positions and velocities, which
 * the Python side must match bit for bit.
 *
 *   fluid-python-dam-c FRAMES WORKERS     prints "COUNT HASH" (HASH: 16 hex digits)
 */
#include <fluid/c.h>

#include <stdio.h>
#include <stdlib.h>

static uint64_t fnv1a(uint64_t hash, const void* data, size_t size) {
    const unsigned char* bytes = (const unsigned char*)data;
    size_t i;
    for (i = 0; i < size; ++i) {
        hash ^= bytes[i];
        hash *= 1099511628211ull;
    }
    return hash;
}

static int fail(fluid_world* world) {
    fprintf(stderr, "fluid-python-dam-c: %s\n", fluid_last_error());
    fluid_world_destroy(world);
    return 1;
}

int main(int argc, char** argv) {
    const long frames = argc > 1 ? strtol(argv[1], NULL, 10) : 60;
    const long workers = argc > 2 ? strtol(argv[2], NULL, 10) : 1;
    fluid_world* world = NULL;
    fluid_world_def def = fluid_default_world_def();
    fluid_material_def water;
    fluid_material_id water_id;
    fluid_plugin_id plugin;
    fluid_blob_def blob = fluid_default_blob_def();
    const fluid_param tank[] = {{"minX", 0.0}, {"minY", 0.0}, {"maxX", 1.0}, {"maxY", 1.0}};
    const fluid_param gravity[] = {{"gx", 0.0}, {"gy", -9.81}};
    const float *x, *y, *vx, *vy;
    uint32_t count = 0;
    uint64_t hash = 14695981039346656037ull;
    long f;

    def.worker_count = (uint32_t)workers;
    if (fluid_world_def_set_quality(&def, "game") != FLUID_OK ||
        fluid_world_create(&def, &world) != FLUID_OK ||
        fluid_material_preset("water", &water) != FLUID_OK ||
        fluid_world_add_material(world, &water, &water_id) != FLUID_OK ||
        fluid_world_add_plugin(world, "boundary.box", tank, 4, &plugin) != FLUID_OK ||
        fluid_world_add_plugin(world, "force.gravity", gravity, 2, &plugin) != FLUID_OK) {
        return fail(world);
    }
    blob.shape = fluid_box_shape((fluid_vec2){0.0f, 0.0f}, (fluid_vec2){0.25f, 0.5f});
    blob.material = water_id;
    if (fluid_world_spawn_blob(world, &blob, NULL) != FLUID_OK) {
        return fail(world);
    }
    for (f = 0; f < frames; ++f) {
        if (fluid_world_step(world, 1.0f / 60.0f) != FLUID_OK) {
            return fail(world);
        }
    }
    if (fluid_world_positions(world, &x, &y, &count) != FLUID_OK ||
        fluid_world_velocities(world, &vx, &vy, &count) != FLUID_OK) {
        return fail(world);
    }
    hash = fnv1a(hash, x, count * sizeof(float));
    hash = fnv1a(hash, y, count * sizeof(float));
    hash = fnv1a(hash, vx, count * sizeof(float));
    hash = fnv1a(hash, vy, count * sizeof(float));
    printf("%u %016llx\n", (unsigned)count, (unsigned long long)hash);
    fluid_world_destroy(world);
    return 0;
}
