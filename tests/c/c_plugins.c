/* Plugins written in C for the C API's tests (tests/c/test_c_api.cpp), compiled as C99:
 *  - a uniform acceleration (parameters gx, gy), the C twin of the built-in force.gravity;
 *  - a floating box: a boundary plugin carrying one rigid body of its own physics (a box that
 *    moves up and down only), integrated from the fluid's forces and impulses as a game's
 *    physics engine would. */
#include "c_plugins.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

const char* c_test_status_name(int code) { return fluid_status_name((fluid_status)code); }

/* ---- The uniform acceleration --------------------------------------------------------------- */

static const fluid_param_decl kAccelerationParams[] = {
    {"gx", "m/s^2", 0.0, -1000.0, 1000.0, "Acceleration along x."},
    {"gy", "m/s^2", -9.81, -1000.0, 1000.0, "Acceleration along y."},
};

static void acceleration_prepare(void* user, const fluid_step_context* context) {
    c_test_counters* counters = (c_test_counters*)user;
    (void)context;
    counters->prepared += 1;
}

static void acceleration_apply(void* user, const fluid_force_context* context, uint32_t begin,
                               uint32_t end) {
    const float gx = (float)context->params[0];
    const float gy = (float)context->params[1];
    uint32_t i;
    (void)user;
    for (i = begin; i < end; ++i) {
        context->ax[i] += gx;
        context->ay[i] += gy;
    }
}

static void acceleration_destroy(void* user) {
    c_test_counters* counters = (c_test_counters*)user;
    counters->destroyed += 1;
}

fluid_force_plugin_def c_test_acceleration(c_test_counters* counters) {
    fluid_force_plugin_def def = fluid_default_force_plugin_def();
    def.type = "c_test.acceleration";
    def.user = counters;
    def.params = kAccelerationParams;
    def.param_count = 2;
    def.prepare = acceleration_prepare;
    def.apply = acceleration_apply;
    def.destroy = acceleration_destroy;
    return def;
}

/* The acceleration as a registered type: each instance counts in the type's counters. */
static bool acceleration_create(void* user, fluid_force_plugin_def* def) {
    def->user = user;
    def->prepare = acceleration_prepare;
    def->apply = acceleration_apply;
    def->destroy = acceleration_destroy;
    return true;
}

static bool refusing_create(void* user, fluid_force_plugin_def* def) {
    (void)user;
    (void)def;
    return false;
}

fluid_plugin_type_def c_test_acceleration_type(const char* name, c_test_counters* counters,
                                               bool refuse) {
    fluid_plugin_type_def def = fluid_default_plugin_type_def();
    def.type = name;
    def.description = "A uniform acceleration written in C (tests/c/c_plugins.c).";
    def.kind = FLUID_PLUGIN_FORCE;
    def.params = kAccelerationParams;
    def.param_count = 2;
    def.user = counters;
    def.create_force = refuse ? refusing_create : acceleration_create;
    return def;
}

/* ---- The floating box ----------------------------------------------------------------------- */

/* The box's centre at `t` seconds into the step: it moves with its velocity. */
static float box_y_at(const c_test_box* box, float t) { return box->y + box->vy * t; }

static bool box_inside(const c_test_box* box, fluid_vec2 p, float t) {
    return fabsf(p.x - box->x) < box->half_width && fabsf(p.y - box_y_at(box, t)) < box->half_height;
}

static void box_add_sample(c_test_box* box, float x, float y) {
    if (box->sample_count == box->sample_capacity) {
        const uint32_t capacity = 2u * box->sample_capacity + 64u;
        float* arrays[4];
        float** fields[4];
        int k;
        fields[0] = &box->px;
        fields[1] = &box->py;
        fields[2] = &box->svx;
        fields[3] = &box->svy;
        for (k = 0; k < 4; ++k) {
            arrays[k] = (float*)realloc(*fields[k], capacity * sizeof(float));
            if (arrays[k] == NULL) {
                return; /* out of memory: fewer samples */
            }
            *fields[k] = arrays[k];
        }
        box->sample_capacity = capacity;
    }
    box->px[box->sample_count] = x;
    box->py[box->sample_count] = y;
    box->svx[box->sample_count] = 0.0f;
    box->svy[box->sample_count] = box->vy;
    box->sample_count += 1;
}

/* Points along a -> b at most `spacing` apart, a included, b not (the next side starts
 * there). */
static void box_side(c_test_box* box, float ax, float ay, float bx, float by, float spacing) {
    const float length = sqrtf((bx - ax) * (bx - ax) + (by - ay) * (by - ay));
    const uint32_t n = (uint32_t)ceilf(length / spacing);
    uint32_t k;
    for (k = 0; k < n; ++k) {
        const float f = (float)k / (float)n;
        box_add_sample(box, ax + f * (bx - ax), ay + f * (by - ay));
    }
}

/* The samples stand in for the solid in the fluid's density sum (docs/plugins.md, "A
 * boundary"): rings at the sample spacing, the first half a spacing inside the surface, as many
 * as cover one support radius behind it (or fill the box). */
static void box_prepare(void* user, const fluid_step_context* context,
                        fluid_boundary_samples* samples) {
    c_test_box* box = (c_test_box*)user;
    const float s = context->sample_spacing;
    const uint32_t layers = (uint32_t)ceilf(context->support_radius / s);
    uint32_t l;
    box->frame_dt = context->frame_dt;
    box->sample_count = 0;
    for (l = 0; l < layers; ++l) {
        const float d = ((float)l + 0.5f) * s;
        const float x0 = box->x - box->half_width + d, x1 = box->x + box->half_width - d;
        const float y0 = box->y - box->half_height + d, y1 = box->y + box->half_height - d;
        if (x1 < x0 || y1 < y0) {
            break;
        }
        if (x1 - x0 < s || y1 - y0 < s) {
            box_side(box, x0, y0, x1 > x0 ? x1 : x0 + 0.5f * s, y1, s); /* the core: a line */
            break;
        }
        box_side(box, x0, y0, x1, y0, s);
        box_side(box, x1, y0, x1, y1, s);
        box_side(box, x1, y1, x0, y1, s);
        box_side(box, x0, y1, x0, y0, s);
    }
    samples->px = box->px;
    samples->py = box->py;
    samples->vx = box->svx;
    samples->vy = box->svy;
    samples->count = box->sample_count;
    box->body.mass = box->mass;
    box->body.sample_begin = 0;
    box->body.sample_end = box->sample_count;
    box->body.contacts = false;
}

/* Particles inside the box go to its nearest side; their velocity into the box becomes the
 * box's. The box stands as high as the coarse solve has moved it so far in the step
 * (body_shifts), as its samples do (it moves up and down only: box_receive_impulses takes the
 * vertical part). */
static void box_project(void* user, const fluid_project_context* context, uint32_t begin,
                        uint32_t end) {
    const c_test_box* box = (const c_test_box*)user;
    const float cx = box->x;
    float cy = box_y_at(box, context->time_in_step), vy = box->vy;
    uint32_t i;
    if (context->body_shift_count == 1) {
        const fluid_body_shift s = context->body_shifts[0];
        cy += s.offset.y + s.velocity.y * context->time_in_step;
        vy += s.velocity.y;
    }
    for (i = begin; i < end; ++i) {
        const float dx = context->px[i] - cx, dy = context->py[i] - cy;
        const float gapX = box->half_width - fabsf(dx), gapY = box->half_height - fabsf(dy);
        if (gapX <= 0.0f || gapY <= 0.0f) {
            continue;
        }
        if (gapX < gapY) {
            context->px[i] = cx + (dx < 0.0f ? -box->half_width : box->half_width);
            if ((dx < 0.0f) == (context->vx[i] > 0.0f)) {
                context->vx[i] = 0.0f;
            }
        } else {
            const bool below = dy < 0.0f;
            context->py[i] = cy + (below ? -box->half_height : box->half_height);
            if (below ? context->vy[i] > vy : context->vy[i] < vy) {
                context->vy[i] = vy;
            }
        }
    }
}

static uint32_t box_rigid_bodies(void* user, const fluid_rigid_body** bodies) {
    c_test_box* box = (c_test_box*)user;
    *bodies = &box->body;
    return 1;
}

static void box_receive_impulses(void* user, const fluid_rigid_body_impulse* impulses,
                                 uint32_t count) {
    c_test_box* box = (c_test_box*)user;
    if (count == 1) {
        box->vy += impulses[0].impulse.y / box->mass;
        box->y += impulses[0].displacement.y;
    }
}

/* The game's physics step for the box, from the fluid's forces over the step: vertical only,
 * semi-implicit in the drag, and with an added mass in the denominator (the water a plate
 * moving up and down drags along, rho pi (w/2)^2 per metre of depth), which keeps a light
 * body's explicit coupling stable and does not change where it comes to rest. */
static void box_receive_forces(void* user, const float* fx, const float* fy, const float* drag,
                               uint32_t count) {
    c_test_box* box = (c_test_box*)user;
    const float dt = box->frame_dt;
    double force = 0.0, d = 0.0;
    uint32_t i;
    (void)fx;
    for (i = 0; i < count; ++i) {
        force += fy[i];
        d += drag[i];
    }
    box->lift = (float)force;
    box->vy += dt * (float)(force + box->mass * box->gravity) /
               (float)(box->mass + box->added_mass + dt * d);
    box->y += dt * box->vy;
}

static bool box_body_contains(void* user, uint32_t body, fluid_vec2 point, float time_in_step) {
    (void)body;
    return box_inside((const c_test_box*)user, point, time_in_step);
}

static bool box_contains(void* user, fluid_vec2 point) {
    return box_inside((const c_test_box*)user, point, 0.0f);
}

static void box_destroy(void* user) {
    c_test_box* box = (c_test_box*)user;
    box->destroyed += 1;
}

bool c_test_box_init(c_test_box* box, float x, float y, float half_width, float half_height,
                     float mass, float added_mass, float gravity) {
    memset(box, 0, sizeof *box);
    box->x = x;
    box->y = y;
    box->half_width = half_width;
    box->half_height = half_height;
    box->mass = mass;
    box->added_mass = added_mass;
    box->gravity = gravity;
    return true;
}

void c_test_box_free(c_test_box* box) {
    free(box->px);
    free(box->py);
    free(box->svx);
    free(box->svy);
    box->px = box->py = box->svx = box->svy = NULL;
}

fluid_boundary_plugin_def c_test_box_plugin(c_test_box* box) {
    fluid_boundary_plugin_def def = fluid_default_boundary_plugin_def();
    def.type = "c_test.floating_box";
    def.user = box;
    def.role = FLUID_ROLE_SOLID;
    def.friction = 0.0f;
    def.wants_forces = true;
    def.prepare = box_prepare;
    def.project = box_project;
    def.receive_forces = box_receive_forces;
    def.rigid_bodies = box_rigid_bodies;
    def.receive_body_impulses = box_receive_impulses;
    def.body_contains = box_body_contains;
    def.contains = box_contains;
    def.destroy = box_destroy;
    return def;
}
