/* rays_c: ray casts and the liquid at a point from C99 (fluid/c.h, docs/queries.md). A tank
 * half full of water settles; a laser shot down at it stops on the surface; a diver at three
 * depths reads the pressure and the depth; a bullet's path lists the particles it passes.
 *
 *   the CMake target rays_c; run by tests/c/examples.sh
 */
#include <fluid/c.h>

#include <math.h>
#include <stdio.h>

/* Prints the failing call's message and returns from main with 1. */
#define CHECK(call)                                                                                \
    do {                                                                                           \
        fluid_status status_ = (call);                                                             \
        if (status_ != FLUID_OK) {                                                                 \
            fprintf(stderr, "rays_c: %s: %s\n", fluid_status_name(status_), fluid_last_error());   \
            fluid_world_destroy(world);                                                            \
            return 1;                                                                              \
        }                                                                                          \
    } while (0)

/* The particles a bullet passes: counts them and keeps the first one's fraction. */
typedef struct {
    uint32_t passed;
    float first;
} Bullet;

static float bullet_visit(void* user, const fluid_ray_particle_hit* hit) {
    Bullet* b = (Bullet*)user;
    if (b->passed == 0) {
        b->first = hit->fraction;
    }
    b->passed += 1;
    return 1.0f; /* go on: -1 would ignore it, 0 stop, a fraction clip the ray there */
}

int main(void) {
    fluid_world* world = NULL;
    fluid_world_def def = fluid_default_world_def();
    fluid_material_def water;
    fluid_material_id water_id;
    fluid_plugin_id plugin;
    fluid_blob_def blob = fluid_default_blob_def();
    const fluid_param tank[] = {{"minX", 0.0}, {"minY", 0.0}, {"maxX", 0.5}, {"maxY", 1.0}};
    const fluid_param gravity[] = {{"gx", 0.0}, {"gy", -9.81}};
    fluid_ray_hit laser;
    fluid_liquid_sample diver;
    float share[1];
    Bullet bullet = {0, 0.0f};
    uint32_t frame, visited;
    int k;

    CHECK(fluid_world_create(&def, &world));
    CHECK(fluid_material_preset("water", &water));
    CHECK(fluid_world_add_material(world, &water, &water_id));
    CHECK(fluid_world_add_plugin(world, "boundary.box", tank, 4, &plugin));
    CHECK(fluid_world_add_plugin(world, "force.gravity", gravity, 2, &plugin));
    blob.shape = fluid_box_shape((fluid_vec2){0.0f, 0.0f}, (fluid_vec2){0.5f, 0.3f});
    blob.material = water_id;
    CHECK(fluid_world_spawn_blob(world, &blob, NULL));
    for (frame = 0; frame < 90; ++frame) {
        CHECK(fluid_world_step(world, 1.0f / 60.0f));
    }

    /* A laser from above, straight down: it stops where the renderer draws the surface (NULL:
     * the renderer's default field; pass its settings when they differ). */
    CHECK(fluid_world_ray_cast(world, (fluid_vec2){0.25f, 0.9f}, (fluid_vec2){0.25f, 0.0f}, NULL,
                               &laser));
    if (laser.hit) {
        printf("laser: hits the water at y = %.4f m (fraction %.3f), normal (%.2f, %.2f)\n",
               (double)laser.point.y, (double)laser.fraction, (double)laser.normal.x,
               (double)laser.normal.y);
    } else {
        printf("laser: misses\n");
    }

    /* A diver: in the water or not, the depth below the surface, the pressure. */
    for (k = 1; k <= 3; ++k) {
        const float y = 0.3f - 0.075f * (float)k;
        CHECK(fluid_world_sample(world, (fluid_vec2){0.25f, y}, NULL, share, 1, &diver));
        printf("diver at y = %.3f m: %s, depth %.4f m, pressure %.0f Pa (rho g depth %.0f Pa), "
               "speed %.4f m/s, water %.0f%%\n",
               (double)y, diver.in_liquid ? "in the water" : "in the air", (double)diver.depth,
               (double)diver.pressure, (double)(water.rest_density * 9.81f * diver.depth),
               (double)sqrtf(diver.velocity.x * diver.velocity.x +
                             diver.velocity.y * diver.velocity.y),
               (double)(100.0f * share[0]));
    }

    /* A bullet across the tank, 2 cm below the surface: every particle within a spacing. */
    CHECK(fluid_world_ray_cast_particles(world, (fluid_vec2){-0.1f, 0.28f},
                                         (fluid_vec2){0.6f, 0.28f}, 0.01f, bullet_visit, &bullet,
                                         &visited));
    printf("bullet: passes %u particles, the first at fraction %.3f\n", (unsigned)visited,
           (double)bullet.first);
    fluid_world_destroy(world);
    return 0;
}
