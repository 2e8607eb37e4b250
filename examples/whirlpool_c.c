/* whirlpool_c: a force plugin written in C (fluid/c.h; docs/c_api_plugins.md, "Plugins written
 * in C"): examples/custom_force.cpp's whirlpool, in C99. A round blob of water in zero gravity, the
 * whirlpool at its centre; the blob's angular momentum about the centre every 0.2 s. */
#include <fluid/c.h>

#include <math.h>
#include <stdio.h>

/* Parameters, in the order `whirlpool_apply` reads them from context->params. A tuning panel,
 * fluid_plugin_set_param and saves reach them by name. */
static const fluid_param_decl kParams[] = {
    {"cx", "m", 0.0, -1e5, 1e5, "Centre x."},
    {"cy", "m", 0.0, -1e5, 1e5, "Centre y."},
    {"strength", "m/s^2", 1.0, -1e3, 1e3, "Tangential acceleration at the radius (CCW > 0)."},
    {"radius", "m", 0.2, 1e-3, 1e3, "Where the swirl peaks; it is 0 beyond twice this."},
    {"pull", "m/s^2", 0.0, -1e3, 1e3, "Inward acceleration at the radius (optional)."},
};

/* Adds the swirl to particles [begin, end): worker threads call it at once on disjoint ranges,
 * so it writes only its own slots and keeps no state. */
static void whirlpool_apply(void* user, const fluid_force_context* ctx, uint32_t begin,
                            uint32_t end) {
    const float cx = (float)ctx->params[0], cy = (float)ctx->params[1];
    const float strength = (float)ctx->params[2], radius = (float)ctx->params[3];
    const float pull = (float)ctx->params[4];
    uint32_t i;
    (void)user;
    for (i = begin; i < end; ++i) {
        const float dx = ctx->px[i] - cx, dy = ctx->py[i] - cy;
        const float r = sqrtf(dx * dx + dy * dy);
        /* Profile f: r/R inside, then a smoothstep from 1 at R down to 0 at 2R and beyond. */
        const float u = r / radius - 1.0f;
        const float t = u < 0.0f ? 0.0f : (u > 1.0f ? 1.0f : u);
        const float f = r < radius ? r / radius : 1.0f - t * t * (3.0f - 2.0f * t);
        /* (-dy, dx)/r turns counter-clockwise, -(dx, dy)/r points in; the centre gets 0. */
        const float s = r > 1e-6f ? f / r : 0.0f;
        ctx->ax[i] += s * (-strength * dy - pull * dx);
        ctx->ay[i] += s * (strength * dx - pull * dy);
    }
}

int main(void) {
    fluid_world_def def = fluid_default_world_def();
    fluid_world* world = NULL;
    fluid_material_def water;
    fluid_material_id water_id;
    fluid_force_plugin_def whirlpool = fluid_default_force_plugin_def();
    fluid_plugin_id plugin;
    fluid_blob_def blob = fluid_default_blob_def();
    uint32_t spawned = 0;
    int line, frame;

    if (fluid_world_create(&def, &world) != FLUID_OK ||
        fluid_material_preset("water", &water) != FLUID_OK ||
        fluid_world_add_material(world, &water, &water_id) != FLUID_OK) {
        fprintf(stderr, "whirlpool_c: %s\n", fluid_last_error());
        fluid_world_destroy(world);
        return 1;
    }
    /* No gravity plugin: zero gravity. The whirlpool: its type name, its parameters, apply. */
    whirlpool.type = "force.whirlpool_c";
    whirlpool.params = kParams;
    whirlpool.param_count = sizeof kParams / sizeof kParams[0];
    whirlpool.apply = whirlpool_apply;
    if (fluid_world_add_force(world, &whirlpool, &plugin) != FLUID_OK ||
        fluid_plugin_set_param(world, plugin, "radius", 0.3) != FLUID_OK ||
        fluid_plugin_set_param(world, plugin, "pull", 2.0) != FLUID_OK) {
        fprintf(stderr, "whirlpool_c: %s\n", fluid_last_error());
        fluid_world_destroy(world);
        return 1;
    }
    blob.shape = fluid_circle_shape((fluid_vec2){0.0f, 0.0f}, 0.15f);
    blob.material = water_id;
    if (fluid_world_spawn_blob(world, &blob, &spawned) != FLUID_OK) {
        fprintf(stderr, "whirlpool_c: %s\n", fluid_last_error());
        fluid_world_destroy(world);
        return 1;
    }
    printf("whirlpool_c: %u water particles in zero gravity, whirlpool at (0, 0), 2 s\n"
           "t [s]  Lz [kg m^2/s] (angular momentum about the centre)\n",
           (unsigned)spawned);
    for (line = 1; line <= 10; ++line) {
        const float *px, *py, *vx, *vy;
        uint32_t n, i;
        double lz = 0.0, time = 0.0;
        for (frame = 0; frame < 12; ++frame) {
            if (fluid_world_step(world, 1.0f / 60.0f) != FLUID_OK) {
                fprintf(stderr, "whirlpool_c: %s\n", fluid_last_error());
                fluid_world_destroy(world);
                return 1;
            }
        }
        fluid_world_positions(world, &px, &py, &n);
        fluid_world_velocities(world, &vx, &vy, &n);
        fluid_world_time(world, &time);
        for (i = 0; i < n; ++i) {
            lz += water.mass * ((double)px[i] * vy[i] - (double)py[i] * vx[i]);
        }
        printf("%5.2f  %.5f\n", time, lz);
    }
    fluid_world_destroy(world);
    return 0;
}
