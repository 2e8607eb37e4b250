/* level_c: a level file played from C (fluid/c.h) with what the demo's player does: the pointer
 * pushes the liquid, a blob drops in, gravity goes off and on, a crate drops into a level with
 * Box2D bodies. Then its goal and bodies, and a save loaded back.
 *
 *   level_c LEVEL.json [FRAMES]        e.g. level_c levels/crates.json 240 */
#include <fluid/c.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int fail(fluid_level* level, fluid_level* restored) {
    fprintf(stderr, "level_c: %s\n", fluid_last_error());
    fluid_level_destroy(restored);
    fluid_level_destroy(level);
    return 1;
}

/* The liquid's centre of mass (m). */
static fluid_vec2 centre(const fluid_world* world) {
    const float *x = NULL, *y = NULL;
    uint32_t n = 0, i;
    double cx = 0.0, cy = 0.0;
    fluid_vec2 c = {0.0f, 0.0f};
    if (fluid_world_positions(world, &x, &y, &n) != FLUID_OK || n == 0) {
        return c;
    }
    for (i = 0; i < n; ++i) {
        cx += x[i];
        cy += y[i];
    }
    c.x = (float)(cx / n);
    c.y = (float)(cy / n);
    return c;
}

/* The level's gravity: its first "force.gravity" plugin's (m/s^2), or {0, 0}. */
static fluid_vec2 level_gravity(const fluid_world* world) {
    fluid_vec2 g = {0.0f, 0.0f};
    uint32_t count = 0, i;
    fluid_world_plugin_count(world, FLUID_PLUGIN_FORCE, &count);
    for (i = 0; i < count; ++i) {
        const fluid_plugin_id id = {i, FLUID_PLUGIN_FORCE, 0};
        const char* type = NULL;
        double gx = 0.0, gy = 0.0;
        if (fluid_plugin_type(world, id, &type) == FLUID_OK &&
            strcmp(type, "force.gravity") == 0 &&
            fluid_plugin_get_param(world, id, "gx", &gx) == FLUID_OK &&
            fluid_plugin_get_param(world, id, "gy", &gy) == FLUID_OK) {
            g.x = (float)gx;
            g.y = (float)gy;
            break;
        }
    }
    return g;
}

int main(int argc, char** argv) {
    static const char* const kGoal[] = {"none", "pending", "won", "lost"};
    fluid_level* level = NULL;
    fluid_level* restored = NULL;
    fluid_world* world = NULL;
    fluid_level_options options = fluid_default_level_options();
    fluid_goal_state goal = FLUID_GOAL_NONE;
    fluid_plugin_id pointer;
    fluid_material_id liquid = {0, 0};
    fluid_vec2 gravity, at;
    const fluid_param reach[] = {{"radius", 0.1}, {"strength", 30.0}};
    double value = 0.0, time = 0.0;
    uint32_t bodies = 0, particles = 0, b;
    long frames = argc > 2 ? strtol(argv[2], NULL, 10) : 180, f;

    if (argc < 2 || frames < 1) {
        fprintf(stderr, "usage: level_c LEVEL.json [FRAMES >= 1]\n");
        return 2;
    }
    /* A bad file says where: "FILE:LINE:COLUMN: at /json/path: message". */
    if (fluid_level_load(argv[1], &options, &level) != FLUID_OK ||
        fluid_level_world(level, &world) != FLUID_OK ||
        fluid_level_body_count(level, &bodies) != FLUID_OK) {
        return fail(level, restored);
    }
    /* The player's pointer: a built-in force the game moves each frame. */
    if (fluid_world_add_plugin(world, "force.pointer", reach, 2, &pointer) != FLUID_OK) {
        return fail(level, restored);
    }
    gravity = level_gravity(world);
    for (f = 1; f <= frames; ++f) {
        at = centre(world);
        if (f == 30) { /* push at the liquid's centre for half a second */
            if (fluid_plugin_set_param(world, pointer, "x", at.x) != FLUID_OK ||
                fluid_plugin_set_param(world, pointer, "y", at.y) != FLUID_OK ||
                fluid_plugin_set_param(world, pointer, "active", 1.0) != FLUID_OK) {
                return fail(level, restored);
            }
        } else if (f == 60) {
            fluid_blob_def blob = fluid_default_blob_def();
            uint32_t spawned = 0;
            fluid_plugin_set_param(world, pointer, "active", 0.0);
            blob.shape = fluid_circle_shape((fluid_vec2){at.x, at.y + 0.2f}, 0.04f);
            blob.material = liquid;
            if (fluid_world_spawn_blob(world, &blob, &spawned) != FLUID_OK) {
                return fail(level, restored);
            }
            printf("level_c: frame %ld: a blob of %u particles at (%.3f, %.3f)\n", f,
                   (unsigned)spawned, (double)at.x, (double)at.y + 0.2);
        } else if (f == 90 || f == 120) { /* zero gravity for half a second */
            const fluid_vec2 zero = {0.0f, 0.0f};
            if (fluid_level_set_gravity(level, f == 90 ? zero : gravity) != FLUID_OK) {
                return fail(level, restored);
            }
        } else if (f == 150 && bodies > 0) { /* a crate at half the liquid's density */
            fluid_body_def crate = fluid_default_body_def();
            float areal = 0.0f;
            uint32_t index = 0;
            if (fluid_level_areal_density(level, liquid, &areal) != FLUID_OK) {
                return fail(level, restored);
            }
            crate.shape.center = (fluid_vec2){at.x, at.y + 0.15f};
            crate.density = 0.5f * areal;
            if (fluid_level_add_body(level, &crate, &index) != FLUID_OK) {
                return fail(level, restored);
            }
            printf("level_c: frame %ld: a crate (body %u) at (%.3f, %.3f)\n", f,
                   (unsigned)index, (double)at.x, (double)at.y + 0.15);
        }
        if (fluid_level_step(level) != FLUID_OK) { /* the world and its bodies, one frame */
            return fail(level, restored);
        }
    }
    if (fluid_world_time(world, &time) != FLUID_OK ||
        fluid_world_particle_count(world, &particles) != FLUID_OK ||
        fluid_level_goal(level, &goal, &value) != FLUID_OK ||
        fluid_level_body_count(level, &bodies) != FLUID_OK) {
        return fail(level, restored);
    }
    printf("level_c: %s after %ld frames: t = %.3f s, %u particles, goal %s (%.4f)\n", argv[1],
           frames, time, (unsigned)particles, kGoal[goal], value);
    for (b = 0; b < bodies; ++b) {
        const char* name = NULL;
        float angle = 0.0f;
        if (fluid_level_body(level, b, &name, &at, &angle) != FLUID_OK) {
            return fail(level, restored);
        }
        printf("  body %-8s at (%.4f, %.4f) m, %+.4f rad\n", name[0] ? name : "(added)",
               (double)at.x, (double)at.y, (double)angle);
    }
    /* A save in memory (a file: fluid_level_save), loaded back as a second level. */
    {
        fluid_bytes save = {NULL, 0};
        fluid_world* copy = NULL;
        uint32_t copied = 0;
        if (fluid_level_save_bytes(level, &save) != FLUID_OK) {
            return fail(level, restored);
        }
        if (fluid_level_read_save(save.data, save.size, "level_c.save", &options, &restored) !=
            FLUID_OK) {
            fluid_bytes_free(&save);
            return fail(level, restored);
        }
        printf("level_c: saved %lu bytes", (unsigned long)save.size);
        fluid_bytes_free(&save);
        if (fluid_level_world(restored, &copy) != FLUID_OK ||
            fluid_world_particle_count(copy, &copied) != FLUID_OK) {
            return fail(level, restored);
        }
        printf(", loaded back with %u particles\n", (unsigned)copied);
    }
    fluid_level_destroy(restored);
    fluid_level_destroy(level);
    return 0;
}
