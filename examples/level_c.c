/* level_c: a level file played from C (fluid/c.h): load it, play it headless, follow its goal
 * and its Box2D bodies, save it and load the save back.
 *
 *   level_c LEVEL.json [FRAMES]        e.g. level_c levels/crates.json 300 */
#include <fluid/c.h>

#include <stdio.h>
#include <stdlib.h>

static int fail(fluid_level* level, fluid_level* restored) {
    fprintf(stderr, "level_c: %s\n", fluid_last_error());
    fluid_level_destroy(restored);
    fluid_level_destroy(level);
    return 1;
}

int main(int argc, char** argv) {
    static const char* const kGoal[] = {"none", "pending", "won", "lost"};
    fluid_level* level = NULL;
    fluid_level* restored = NULL;
    fluid_world* world = NULL;
    fluid_level_options options = fluid_default_level_options();
    fluid_goal_state goal = FLUID_GOAL_NONE;
    double value = 0.0, time = 0.0;
    uint32_t bodies = 0, particles = 0, b;
    float rate = 60.0f;
    long frames = argc > 2 ? strtol(argv[2], NULL, 10) : 180, f;

    if (argc < 2 || frames < 1) {
        fprintf(stderr, "usage: level_c LEVEL.json [FRAMES >= 1]\n");
        return 2;
    }
    /* A bad file says where: "FILE:LINE:COLUMN: at /json/path: message". */
    if (fluid_level_load(argv[1], &options, &level) != FLUID_OK) {
        return fail(level, restored);
    }
    if (fluid_level_frame_rate(level, &rate) != FLUID_OK ||
        fluid_level_world(level, &world) != FLUID_OK) {
        return fail(level, restored);
    }
    for (f = 0; f < frames; ++f) {
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
    printf("level_c: %s after %ld frames at %.0f Hz: t = %.3f s, %u particles, goal %s (%.4f)\n",
           argv[1], frames, (double)rate, time, (unsigned)particles, kGoal[goal], value);
    for (b = 0; b < bodies; ++b) {
        const char* name = NULL;
        fluid_vec2 at;
        float angle = 0.0f;
        if (fluid_level_body(level, b, &name, &at, &angle) != FLUID_OK) {
            return fail(level, restored);
        }
        printf("  body %-8s at (%.4f, %.4f) m, %+.4f rad\n", name, (double)at.x, (double)at.y,
               (double)angle);
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
