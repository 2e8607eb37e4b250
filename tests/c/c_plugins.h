/* Plugins written in C for the C API's tests (c_plugins.c). */
#ifndef FLUID_TESTS_C_PLUGINS_H
#define FLUID_TESTS_C_PLUGINS_H

#include <fluid/c.h>

#ifdef __cplusplus
extern "C" {
#endif

/* fluid_status_name called from C with any int, as a C caller may. */
const char* c_test_status_name(int code);

/* What the acceleration plugin's callbacks counted. */
typedef struct c_test_counters {
    int prepared;
    int destroyed;
} c_test_counters;

/* A uniform acceleration (gx, gy; m/s^2, default 0 and -9.81) that counts its prepare and
 * destroy calls in `counters`. */
fluid_force_plugin_def c_test_acceleration(c_test_counters* counters);

/* The acceleration as a plugin type named `name`, its instances counting in `counters`; with
 * `refuse`, a factory that refuses every instance. */
fluid_plugin_type_def c_test_acceleration_type(const char* name, c_test_counters* counters,
                                               bool refuse);

/* A box that floats: the game's own rigid body (vertical motion only) as a boundary plugin. */
typedef struct c_test_box {
    float x, y;                     /* centre (m) */
    float vy;                       /* vertical velocity (m/s) */
    float half_width, half_height;  /* (m) */
    float mass;                     /* (kg) */
    float added_mass;               /* (kg): in the integrator's denominator only */
    float gravity;                  /* (m/s^2, negative: down) */
    float frame_dt;                 /* the step being taken (s) */
    float lift;                     /* the fluid's vertical force over the last step (N) */
    int destroyed;                  /* destroy calls */
    fluid_rigid_body body;
    float *px, *py, *svx, *svy;     /* the samples */
    uint32_t sample_count, sample_capacity;
} c_test_box;

/* Sets up `box` (its sample arrays grow in prepare). */
bool c_test_box_init(c_test_box* box, float x, float y, float half_width, float half_height,
                     float mass, float added_mass, float gravity);
/* Frees the sample arrays. */
void c_test_box_free(c_test_box* box);
/* The plugin's def, its user pointer `box`. */
fluid_boundary_plugin_def c_test_box_plugin(c_test_box* box);

#ifdef __cplusplus
}
#endif

#endif
