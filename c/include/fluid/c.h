/* fluid — 2D SPH liquid for games: the C API (C99).
 *
 * The C twin of <fluid/fluid.h> and <fluid/level.h>, for games and engines in any language that
 * can call C: opaque worlds and levels, ids as small structs passed by value, definition structs
 * with fluid_default_*_def() functions, plugins written in C. A thin layer over the C++ library:
 * every rule, limit and message is the C++ API's (docs/c_api.md lists each function's units,
 * ranges and thread rule; <fluid/world.h> and <fluid/level.h> document the C++ behind it).
 *
 * Errors: every call that can fail returns a fluid_status. On anything but FLUID_OK nothing
 * changed, the outputs are left as they were, and fluid_last_error() holds the message, the
 * same text the C++ API throws. No C++ exception crosses this API and no call aborts.
 *
 * Threads: a world (and a level) is used by one thread at a time; different worlds may be used
 * from different threads at once. fluid_last_error() is per thread. Results are bit-identical
 * for any worker count (fluid_world_def.worker_count), as with the C++ API.
 *
 * Link: target fluid::c (static) or fluid::c_shared (libfluid_c.so, exporting only the
 * fluid_* functions below).
 */
#ifndef FLUID_C_H
#define FLUID_C_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#if defined(_WIN32) && defined(FLUID_C_BUILDING)
#define FLUID_C_API __declspec(dllexport)
#elif defined(_WIN32) && defined(FLUID_C_SHARED)
#define FLUID_C_API __declspec(dllimport)
#elif defined(__GNUC__)
#define FLUID_C_API __attribute__((visibility("default")))
#else
#define FLUID_C_API
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------------------------------ */
/* Version and errors                                                                          */
/* ------------------------------------------------------------------------------------------ */

/// The C API's version this header describes: major (incompatible changes), minor (additions).
#define FLUID_C_VERSION_MAJOR 1
/// See FLUID_C_VERSION_MAJOR.
#define FLUID_C_VERSION_MINOR 1
/// major * 100 + minor.
#define FLUID_C_VERSION (FLUID_C_VERSION_MAJOR * 100 + FLUID_C_VERSION_MINOR)

/// The library's FLUID_C_VERSION (unit: major * 100 + minor): a program built against another
/// major version must not use the rest of the library. Any thread.
FLUID_C_API uint32_t fluid_version(void);

/// What a call did. A failure of the C++ API comes with the status of its fluid::ErrorCode
/// (docs/errors.md); the message is the C++ one.
typedef enum fluid_status {
    /// Done.
    FLUID_OK = 0,
    /// An argument is out of its range, NaN or inconsistent (the message names it). C++:
    /// ErrorCode::BadArgument, ErrorCode::OutOfRange.
    FLUID_ERROR_INVALID_ARGUMENT = 1,
    /// A required pointer argument is NULL.
    FLUID_ERROR_NULL_ARGUMENT = 2,
    /// An id or particle handle that no longer exists, or belongs to another world. C++:
    /// ErrorCode::StaleId.
    FLUID_ERROR_STALE_ID = 3,
    /// A name the library does not know: a preset, a plugin type, a field, a parameter. C++:
    /// ErrorCode::UnknownName.
    FLUID_ERROR_UNKNOWN_NAME = 4,
    /// A level file, save or snapshot that cannot be read (the message has file, line, key).
    /// C++: ErrorCode::BadFile.
    FLUID_ERROR_BAD_FILE = 5,
    /// A file that cannot be opened or written. C++: ErrorCode::Io.
    FLUID_ERROR_IO = 6,
    /// A limit reached: the world's maxParticles, 65535 materials. C++: ErrorCode::Full.
    FLUID_ERROR_LIMIT = 7,
    /// Memory ran out, in any call (a blob too large for memory, in a world or a level file:
    /// the message says how many particles it asked for). C++: ErrorCode::OutOfMemory.
    FLUID_ERROR_OUT_OF_MEMORY = 8,
    /// The world refused a step or call in its state (a plugin that threw, a host that must step
    /// it); the message says why. C++: ErrorCode::WrongState, and any error from inside a
    /// step whose frame time is good (fluid_world_step, fluid_level_step).
    FLUID_ERROR_REFUSED = 9
} fluid_status;

/// The message of the last call on this thread that did not return FLUID_OK, "" when none
/// has failed. Valid until the next failing call on this thread. Any thread.
FLUID_C_API const char* fluid_last_error(void);

/// The status's name ("FLUID_ERROR_STALE_ID"); "unknown status" for a value not listed. Any
/// thread.
FLUID_C_API const char* fluid_status_name(fluid_status status);

/* ------------------------------------------------------------------------------------------ */
/* Values and ids                                                                              */
/* ------------------------------------------------------------------------------------------ */

/// A point or vector (unit: m, m/s, N... as the field says).
typedef struct fluid_vec2 {
    /// x (right).
    float x;
    /// y (up).
    float y;
} fluid_vec2;

/// A world: particles, materials, plugins, emitters, drains and sensors. Opaque.
typedef struct fluid_world fluid_world;

/// A level file loaded: its world, its named objects, its Box2D bodies and goal. Opaque.
typedef struct fluid_level fluid_level;

/// A particle, stable while it lives (slots move as the world sorts them). Generation 0 is the
/// null handle.
typedef struct fluid_particle_id {
    /// Slot (unit: index).
    uint32_t slot;
    /// Generation of the slot (0: null).
    uint32_t generation;
    /// The world's tag.
    uint32_t world;
} fluid_particle_id;

/// A material of a world (index in the order added, from 0).
typedef struct fluid_material_id {
    /// Index (unit: index < fluid_world_material_count).
    uint32_t index;
    /// The world's tag.
    uint32_t world;
} fluid_material_id;

/// An emitter of a world.
typedef struct fluid_emitter_id {
    /// Index (unit: index, in the order added).
    uint32_t index;
    /// The world's tag.
    uint32_t world;
} fluid_emitter_id;

/// A drain of a world.
typedef struct fluid_drain_id {
    /// Index (unit: index, in the order added).
    uint32_t index;
    /// The world's tag.
    uint32_t world;
} fluid_drain_id;

/// A sensor of a world.
typedef struct fluid_sensor_id {
    /// Index (unit: index, in the order added).
    uint32_t index;
    /// The world's tag.
    uint32_t world;
} fluid_sensor_id;

/// What a plugin is.
typedef enum fluid_plugin_kind {
    /// Adds accelerations (gravity, wind, the pointer...).
    FLUID_PLUGIN_FORCE = 0,
    /// Keeps particles out of solids or in containers (a tank, a polygon, a body).
    FLUID_PLUGIN_BOUNDARY = 1
} fluid_plugin_kind;

/// A plugin of a world: its kind and index among the world's plugins of that kind.
typedef struct fluid_plugin_id {
    /// Index among the world's forces or boundaries (unit: index, in the order added).
    uint32_t index;
    /// A fluid_plugin_kind.
    uint32_t kind;
    /// The world's tag.
    uint32_t world;
} fluid_plugin_id;

/// Bytes the library allocated (a snapshot, a save); free them with fluid_bytes_free.
typedef struct fluid_bytes {
    /// The bytes (NULL when empty).
    uint8_t* data;
    /// How many (unit: bytes).
    size_t size;
} fluid_bytes;

/// Frees bytes the library returned and empties `bytes`; NULL or empty is fine. Any thread.
FLUID_C_API void fluid_bytes_free(fluid_bytes* bytes);

/* ------------------------------------------------------------------------------------------ */
/* Worlds                                                                                      */
/* ------------------------------------------------------------------------------------------ */

/// The solver.
typedef enum fluid_solver {
    /// Position-based fluids (the default): stable at a game's step.
    FLUID_SOLVER_POSITION_BASED = 0,
    /// The seed report's explicit SPH loop.
    FLUID_SOLVER_EXPLICIT = 1
} fluid_solver;

/// The explicit solver's equation of state.
typedef enum fluid_equation_of_state {
    /// p = k (rho - rho0), the seed report's.
    FLUID_EOS_LINEAR = 0,
    /// Tait's (gamma 7), the default.
    FLUID_EOS_TAIT = 1
} fluid_equation_of_state;

/// How a world is made (C++ fluid::WorldDef with its PositionBasedDef). Start from
/// fluid_default_world_def(); the ranges are fluid_world_def_set's fields'.
typedef struct fluid_world_def {
    /// A fluid_solver.
    int32_t solver;
    /// Position-based: sub-steps per 60 Hz frame (unit: count; [1, 12]).
    uint32_t substeps;
    /// Position-based: constraint sweeps per sub-step (unit: count; [1, 32]).
    uint32_t iterations;
    /// Position-based: viscosity every this many sub-steps (unit: count; [1, 64]).
    uint32_t viscosity_interval;
    /// Position-based: the coarse-grid correction's weight (unit: 1; [0, 1], 0 off).
    float coarse_correction;
    /// Position-based: vorticity confinement (unit: 1; [0, 1]).
    float vorticity;
    /// Position-based: the yield-stress materials' shear constraint (0 off, 1 on).
    uint32_t shear_constraint;
    /// Explicit: a fluid_equation_of_state.
    int32_t equation_of_state;
    /// Explicit: the speed of sound (unit: m/s; 0, the default, derives it from the scene, or
    /// [0.1, 1e4]).
    float sound_speed;
    /// The slab's depth that turns 2D particles into masses (unit: m; [1e-4, 1e3]).
    float depth;
    /// Explicit: CFL number (unit: 1; [0.01, 1]).
    float courant;
    /// Explicit: most sub-steps per step (unit: count; [1, 1000]).
    uint32_t max_substeps;
    /// Most particles the world holds (unit: count; [1, 67108864]).
    uint32_t max_particles;
    /// Threads that step the world, the caller's included (unit: count; [1, 256]; results are
    /// the same for any count).
    uint32_t worker_count;
} fluid_world_def;

/// The C++ WorldDef's defaults: position-based, game preset, one worker. Any thread.
FLUID_C_API fluid_world_def fluid_default_world_def(void);

/// Sets the position-based fields of `def` to a named preset: "game" or "precise" (as a level
/// file's "quality"). FLUID_ERROR_UNKNOWN_NAME otherwise. Any thread.
FLUID_C_API fluid_status fluid_world_def_set_quality(fluid_world_def* def, const char* quality);

/// Sets one field of `def` by the name of the C++ field tables, which level files use too
/// ("substeps", "coarseCorrection", "depth", "maxParticles"...: docs/c_api.md lists them with
/// units and ranges; solver, equation_of_state, sound_speed and worker_count are set in the
/// struct). NaN, and a count that is not a whole number in [0, 2^32), is refused here; the
/// range is checked when the world is made. Any thread.
FLUID_C_API fluid_status fluid_world_def_set(fluid_world_def* def, const char* field,
                                             double value);

/// Makes a world. `*world` receives it; destroy it with fluid_world_destroy. Any thread.
FLUID_C_API fluid_status fluid_world_create(const fluid_world_def* def, fluid_world** world);

/// Destroys a world made by fluid_world_create or fluid_world_load, with its plugins (a C
/// plugin's destroy callback runs). NULL is fine (FLUID_OK). A level's world is the level's:
/// not this. Called from inside the world's own step (a plugin's callback), it destroys nothing
/// and returns FLUID_ERROR_REFUSED: destroy the world after fluid_world_step returns.
FLUID_C_API fluid_status fluid_world_destroy(fluid_world* world);

/// Steps the world by one frame of `frame_dt` (unit: s; (0, 1]): emitters, forces, the
/// solver's sub-steps, boundaries, drains, sensors and events.
FLUID_C_API fluid_status fluid_world_step(fluid_world* world, float frame_dt);

/// Changes the position-based settings between steps (`def`'s position-based fields only).
FLUID_C_API fluid_status fluid_world_set_position_based(fluid_world* world,
                                                        const fluid_world_def* def);

/// Simulated time (unit: s).
FLUID_C_API fluid_status fluid_world_time(const fluid_world* world, double* time);

/// Particles alive (unit: count).
FLUID_C_API fluid_status fluid_world_particle_count(const fluid_world* world, uint32_t* count);

/// The particles' positions as two arrays (unit: m), `*count` long, in the world's array order
/// (which a step may change; fluid_world_particle_at names the particle at an index). Valid
/// until the next call that changes the world (a step, an add, a remove).
FLUID_C_API fluid_status fluid_world_positions(const fluid_world* world, const float** x,
                                               const float** y, uint32_t* count);

/// The particles' velocities (unit: m/s), as fluid_world_positions.
FLUID_C_API fluid_status fluid_world_velocities(const fluid_world* world, const float** x,
                                                const float** y, uint32_t* count);

/// The particles' densities after the last step (unit: kg/m^3), as fluid_world_positions.
FLUID_C_API fluid_status fluid_world_densities(const fluid_world* world, const float** density,
                                               uint32_t* count);

/// The particles' pressures after the last step (unit: Pa), as fluid_world_positions.
FLUID_C_API fluid_status fluid_world_pressures(const fluid_world* world, const float** pressure,
                                               uint32_t* count);

/// The particles' material indices (unit: index < fluid_world_material_count), as
/// fluid_world_positions.
FLUID_C_API fluid_status fluid_world_material_indices(const fluid_world* world,
                                                      const uint16_t** material, uint32_t* count);

/// Saves the whole world (particles, materials, plugins with their state, emitters, drains,
/// sensors, time) into `*bytes` (free with fluid_bytes_free). A world loaded from them steps
/// on bit for bit. A plugin written in C is saved by its type name and parameters:
/// fluid_world_load makes it again when its type is registered (fluid_register_plugin_type),
/// and fails with FLUID_ERROR_UNKNOWN_NAME naming the type otherwise.
FLUID_C_API fluid_status fluid_world_save(const fluid_world* world, fluid_bytes* bytes);

/// Makes a world from fluid_world_save's bytes, with `worker_count` workers (0: as saved;
/// else [1, 256]).
/// FLUID_ERROR_BAD_FILE with the reason for bytes that are not a whole snapshot.
FLUID_C_API fluid_status fluid_world_load(const void* data, size_t size, uint32_t worker_count,
                                          fluid_world** world);

/* ------------------------------------------------------------------------------------------ */
/* Materials                                                                                   */
/* ------------------------------------------------------------------------------------------ */

/// A material (C++ fluid::Material). Start from fluid_default_material_def() or a preset.
typedef struct fluid_material_def {
    /// Mass of one particle (unit: kg; (0, 1e3]).
    float mass;
    /// Rest density (unit: kg/m^3; (0, 1e5]).
    float rest_density;
    /// Viscosity (unit: Pa s; [0, 1e4]).
    float viscosity;
    /// Explicit solver's stiffness k (unit: J/kg; (0, 1e8]).
    float stiffness;
    /// The seed's smoothing distance (unit: m; [3e-3, 0.4]).
    float smoothing_distance;
    /// Particles in a kernel's support (unit: count; [4, 400]).
    float kernel_particles;
    /// Surface tension (unit: m^3/(kg s^2); [0, 0.5]).
    float surface_tension;
    /// Herschel-Bulkley yield stress (unit: Pa; [0, 1e5]).
    float yield_stress;
    /// Herschel-Bulkley consistency (unit: Pa s^n; [0, 1e4]).
    float consistency;
    /// Herschel-Bulkley flow index n (unit: 1; [0.1, 2]).
    float flow_index;
    /// Shear modulus of yield-stress materials (unit: Pa; [0, 1e6]).
    float shear_modulus;
    /// Name (printable UTF-8: no control character, at most 256 bytes; copied when the
    /// material is added or set). Read back from a world, it points to the world's copy and
    /// lives while the world does, until the material is set again with another name (adding
    /// materials does not move it).
    const char* name;
} fluid_material_def;

/// Water (the seed report's Table 4.1). Any thread.
FLUID_C_API fluid_material_def fluid_default_material_def(void);

/// A named preset: "water", "yoghurt" (Herschel-Bulkley) or "seed_yoghurt" (the report's
/// Table 4.1 yoghurt). Any thread.
FLUID_C_API fluid_status fluid_material_preset(const char* preset, fluid_material_def* def);

/// Sets one field of `def` by the name level files use ("viscosity", "restDensity",
/// "yieldStress"...; docs/c_api.md). Checked when added to a world. Any thread.
FLUID_C_API fluid_status fluid_material_def_set(fluid_material_def* def, const char* field,
                                                double value);

/// Adds a material (at most 65535 per world: FLUID_ERROR_LIMIT after).
FLUID_C_API fluid_status fluid_world_add_material(fluid_world* world,
                                                  const fluid_material_def* def,
                                                  fluid_material_id* id);

/// Changes a material between steps.
FLUID_C_API fluid_status fluid_world_set_material(fluid_world* world, fluid_material_id id,
                                                  const fluid_material_def* def);

/// Reads a material back (its name: see fluid_material_def.name).
FLUID_C_API fluid_status fluid_world_get_material(const fluid_world* world, fluid_material_id id,
                                                  fluid_material_def* def);

/// The spacing of a material's particles on their lattice (unit: m): the size of a particle,
/// for drawing and for placing things a whole number of particles apart.
FLUID_C_API fluid_status fluid_world_spacing(const fluid_world* world, fluid_material_id id,
                                             float* spacing);

/// Materials in the world (unit: count).
FLUID_C_API fluid_status fluid_world_material_count(const fluid_world* world, uint32_t* count);

/* ------------------------------------------------------------------------------------------ */
/* Particles and blobs                                                                         */
/* ------------------------------------------------------------------------------------------ */

/// A region: a box, a circle or a simple polygon.
typedef enum fluid_shape_type {
    /// center +- half_extents.
    FLUID_SHAPE_BOX = 0,
    /// center, radius.
    FLUID_SHAPE_CIRCLE = 1,
    /// vertices (3 to 256, counter-clockwise or clockwise, not crossing).
    FLUID_SHAPE_POLYGON = 2
} fluid_shape_type;

/// A region (C++ fluid::Shape). Make one with fluid_box_shape, fluid_circle_shape or
/// fluid_polygon_shape.
typedef struct fluid_shape {
    /// A fluid_shape_type.
    int32_t type;
    /// Box and circle: centre (unit: m).
    fluid_vec2 center;
    /// Box: half width and half height (unit: m; > 0).
    fluid_vec2 half_extents;
    /// Circle: radius (unit: m; > 0).
    float radius;
    /// Polygon: the vertices (unit: m), read when the shape is used (copied then).
    const fluid_vec2* vertices;
    /// Polygon: how many (unit: count; 3 to 256, C++ fluid::kMaxPolygonVertices).
    uint32_t vertex_count;
} fluid_shape;

/// A box from its corners (unit: m). Any thread.
FLUID_C_API fluid_shape fluid_box_shape(fluid_vec2 min, fluid_vec2 max);
/// A circle (unit: m). Any thread.
FLUID_C_API fluid_shape fluid_circle_shape(fluid_vec2 center, float radius);
/// A polygon of `count` vertices at `vertices` (unit: m; not copied until used). Any thread.
FLUID_C_API fluid_shape fluid_polygon_shape(const fluid_vec2* vertices, uint32_t count);

/// A block of liquid filled on the material's lattice; a yield-stress material's circle in rings,
/// for a round outline (C++ fluid::BlobDef).
typedef struct fluid_blob_def {
    /// Where.
    fluid_shape shape;
    /// Its velocity (unit: m/s).
    fluid_vec2 velocity;
    /// Its material.
    fluid_material_id material;
    /// Seconds each particle lives (unit: s; 0 forever).
    float lifetime;
    /// Yield-stress materials: the paste's structure at the start (unit: 1; [0, 1]; 0 freshly
    /// sheared, as an emitter pours it, 1 rested; unused by other materials).
    float structure;
} fluid_blob_def;

/// A box blob of water-index 0, at rest, living forever. Any thread.
FLUID_C_API fluid_blob_def fluid_default_blob_def(void);

/// Fills a blob; `spawned` (may be NULL) receives how many particles it made. Lattice points
/// inside solids are left out. FLUID_ERROR_LIMIT when the world would hold more than its
/// max_particles, FLUID_ERROR_OUT_OF_MEMORY when memory runs out making room.
FLUID_C_API fluid_status fluid_world_spawn_blob(fluid_world* world, const fluid_blob_def* def,
                                                uint32_t* spawned);

/// As fluid_world_spawn_blob, on a lattice turned counter-clockwise by `lattice_angle` (unit:
/// rad; [-6.2832, 6.2832]; C++ BlobDef::latticeAngle): a layer on a slope filled with its rows
/// along the slope has a flat top, where rows along x leave steps a spacing high that a
/// yield-stress material keeps. FLUID_ERROR_INVALID_ARGUMENT for an angle out of range.
FLUID_C_API fluid_status fluid_world_spawn_blob_turned(fluid_world* world,
                                                       const fluid_blob_def* def,
                                                       float lattice_angle, uint32_t* spawned);

/// Adds one particle (unit: m, m/s).
FLUID_C_API fluid_status fluid_world_add_particle(fluid_world* world, fluid_vec2 position,
                                                  fluid_vec2 velocity, fluid_material_id material,
                                                  fluid_particle_id* id);

/// Removes a particle now. FLUID_ERROR_STALE_ID for one already gone.
FLUID_C_API fluid_status fluid_world_remove_particle(fluid_world* world, fluid_particle_id id);

/// True in `*valid` while the particle lives.
FLUID_C_API fluid_status fluid_world_particle_valid(const fluid_world* world,
                                                    fluid_particle_id id, bool* valid);

/// A particle a region query found (C++ fluid::QueryHit).
typedef struct fluid_query_hit {
    /// Its id.
    fluid_particle_id id;
    /// Its index in the arrays fluid_world_positions and the others hand out, until the world
    /// changes (unit: index).
    uint32_t index;
    /// Its material.
    fluid_material_id material;
} fluid_query_hit;

/// Called for each particle a region query finds, in increasing index: return true to go on,
/// false to stop there.
typedef bool (*fluid_query_visitor)(void* user, const fluid_query_hit* hit);

/// Calls `visit` for each particle whose position lies in `region` (boundary points of a box or
/// circle inside, polygons by the even-odd rule), in increasing index (the same for any number
/// of workers, and after a save and load), until it returns false; `visited` (may be NULL)
/// receives how many it was called for. INVALID_ARGUMENT naming the field for a bad region;
/// REFUSED from inside the world's step. Between steps, from any number of threads at once
/// (docs/queries.md).
FLUID_C_API fluid_status fluid_world_query(const fluid_world* world, const fluid_shape* region,
                                           fluid_query_visitor visit, void* user,
                                           uint32_t* visited);

/// Writes the ids of the particles in `region` to `ids`, in increasing index, at most `capacity`
/// of them (`ids` may be NULL with capacity 0); `found` receives how many lie in the region
/// (more than `capacity` when the buffer is too short). Errors as fluid_world_query.
FLUID_C_API fluid_status fluid_world_query_ids(const fluid_world* world,
                                               const fluid_shape* region, fluid_particle_id* ids,
                                               uint32_t capacity, uint32_t* found);

/// Counts the particles in `region`: `per_material[k]` (may be NULL with material_count 0)
/// receives material k's count for k < `material_count`; `total` (may be NULL) all of them.
/// Errors as fluid_world_query.
FLUID_C_API fluid_status fluid_world_count_in(const fluid_world* world, const fluid_shape* region,
                                              uint32_t* per_material, uint32_t material_count,
                                              uint32_t* total);

/* ---- Ray casts and the liquid at a point (C++ fluid/query.h, fluid/surface_field.h) ---- */

/// The field whose level set is the liquid as fluid::gl draws it (C++ fluid::SurfaceField):
/// pass the renderer's settings so that a ray stops where the liquid is drawn.
typedef struct fluid_surface_field {
    /// A particle's reach over its material's spacing (unit: 1; [1, 4]; default 2).
    float field_radius;
    /// Field level at the surface (unit: 1; [0.05, 4]; default 0.6).
    float threshold;
} fluid_surface_field;

/// The renderer's defaults: field_radius 2, threshold 0.6. Any thread.
FLUID_C_API fluid_surface_field fluid_default_surface_field(void);

/// Where a ray first meets the liquid (C++ fluid::RayHit).
typedef struct fluid_ray_hit {
    /// True when the ray meets the liquid; the other fields are set only then.
    bool hit;
    /// True when the ray starts in the liquid: fraction 0, point the start, normal (0, 0).
    bool starts_inside;
    /// Where the ray enters the liquid (unit: m).
    fluid_vec2 point;
    /// The surface's outward unit normal there (unit: 1).
    fluid_vec2 normal;
    /// point = p1 + fraction (p2 - p1) (unit: 1; [0, 1]).
    float fraction;
    /// The material of `particle`.
    fluid_material_id material;
    /// The nearest particle to `point` among those whose field reaches it.
    fluid_particle_id particle;
    /// Its index in the arrays fluid_world_positions hands out, until the world changes.
    uint32_t index;
} fluid_ray_hit;

/// The first point where the segment p1 -> p2 (unit: m; finite) enters the liquid as `field`
/// (may be NULL: the defaults) draws it, into `hit`. INVALID_ARGUMENT naming the value for a
/// non-finite end or a bad field; REFUSED from inside the world's step. Between steps, from any
/// number of threads at once (docs/queries.md).
FLUID_C_API fluid_status fluid_world_ray_cast(const fluid_world* world, fluid_vec2 p1,
                                              fluid_vec2 p2, const fluid_surface_field* field,
                                              fluid_ray_hit* hit);

/// A particle a ray passes within the radius of (C++ fluid::RayParticleHit).
typedef struct fluid_ray_particle_hit {
    /// Its id.
    fluid_particle_id id;
    /// Its index in the arrays fluid_world_positions hands out, until the world changes.
    uint32_t index;
    /// Its material.
    fluid_material_id material;
    /// Where the ray enters its circle (the start when it starts inside) (unit: m).
    fluid_vec2 point;
    /// From the particle to `point`, normalised (unit: 1; (0, 0) when they coincide).
    fluid_vec2 normal;
    /// How far along the ray (unit: 1; [0, 1]).
    float fraction;
} fluid_ray_particle_hit;

/// Called for each particle a ray passes, in increasing fraction: return -1 to ignore it and go
/// on, 0 to stop, a fraction in (0, 1) to clip the ray there, 1 to go on (LiquidFun's rule).
typedef float (*fluid_ray_visitor)(void* user, const fluid_ray_particle_hit* hit);

/// Calls `visit` for each particle whose circle of `radius` (unit: m; finite, > 0) the segment
/// p1 -> p2 passes through, as the visitor steers; `visited` (may be NULL) receives how many it
/// was called for. Errors as fluid_world_ray_cast, and INVALID_ARGUMENT for a bad radius or a
/// NaN the visitor returned.
FLUID_C_API fluid_status fluid_world_ray_cast_particles(const fluid_world* world, fluid_vec2 p1,
                                                        fluid_vec2 p2, float radius,
                                                        fluid_ray_visitor visit, void* user,
                                                        uint32_t* visited);

/// The liquid at a point (C++ fluid::LiquidSample): values interpolated from the particles
/// around it with the solvers' kernel, Shepard-normalised; 0 where no particle reaches.
typedef struct fluid_liquid_sample {
    /// True where the drawn liquid is.
    bool in_liquid;
    /// The drawn field there (unit: 1).
    float field;
    /// Density over rest density (unit: 1).
    float density_ratio;
    /// Pressure (unit: Pa).
    float pressure;
    /// Velocity (unit: m/s).
    fluid_vec2 velocity;
    /// Depth below the free surface straight up (unit: m; 0 when not in the liquid).
    float depth;
    /// The material with the largest share.
    fluid_material_id material;
    /// Particles whose kernel reaches the point (unit: count).
    uint32_t neighbours;
} fluid_liquid_sample;

/// The liquid at `point` (unit: m; finite) into `sample`; `material_fractions[k]` (may be NULL
/// with material_count 0) receives material k's share for k < `material_count`. `field` may be
/// NULL (the defaults). Errors and threads as fluid_world_ray_cast.
FLUID_C_API fluid_status fluid_world_sample(const fluid_world* world, fluid_vec2 point,
                                            const fluid_surface_field* field,
                                            float* material_fractions, uint32_t material_count,
                                            fluid_liquid_sample* sample);

/// The particle's position (unit: m).
FLUID_C_API fluid_status fluid_world_particle_position(const fluid_world* world,
                                                       fluid_particle_id id, fluid_vec2* position);

/// The particle's velocity (unit: m/s).
FLUID_C_API fluid_status fluid_world_particle_velocity(const fluid_world* world,
                                                       fluid_particle_id id, fluid_vec2* velocity);

/// Sets the particle's velocity (unit: m/s; finite).
FLUID_C_API fluid_status fluid_world_set_particle_velocity(fluid_world* world,
                                                           fluid_particle_id id,
                                                           fluid_vec2 velocity);

/// The particle at `index` of the arrays (unit: index < the particle count).
FLUID_C_API fluid_status fluid_world_particle_at(const fluid_world* world, uint32_t index,
                                                 fluid_particle_id* id);

/* ------------------------------------------------------------------------------------------ */
/* Emitters, drains, sensors, events                                                           */
/* ------------------------------------------------------------------------------------------ */

/// A nozzle (C++ fluid::EmitterDef).
typedef struct fluid_emitter_def {
    /// Centre of the nozzle (unit: m).
    fluid_vec2 position;
    /// Direction of the jet (unit: 1; normalised, not zero).
    fluid_vec2 direction;
    /// Exit speed (unit: m/s; [0.01, 100]).
    float speed;
    /// Nozzle width (unit: m; [0, 100]).
    float width;
    /// Particles per second (unit: 1/s; [0, 1e6]).
    float rate;
    /// Material of the particles.
    fluid_material_id material;
    /// Most particles it ever emits (unit: count; 0 no limit).
    uint32_t max_count;
    /// Seconds each particle lives (unit: s; [0, 1e6], 0 forever).
    float lifetime;
    /// Random spread across the nozzle (unit: 1; [0, 0.5]).
    float jitter;
    /// Seed of the jitter.
    uint64_t seed;
} fluid_emitter_def;

/// The C++ EmitterDef's defaults. Any thread.
FLUID_C_API fluid_emitter_def fluid_default_emitter_def(void);
/// Adds an emitter.
FLUID_C_API fluid_status fluid_world_add_emitter(fluid_world* world, const fluid_emitter_def* def,
                                                 fluid_emitter_id* id);
/// Changes an emitter between steps.
FLUID_C_API fluid_status fluid_world_set_emitter(fluid_world* world, fluid_emitter_id id,
                                                 const fluid_emitter_def* def);
/// Particles an emitter has made so far (unit: count).
FLUID_C_API fluid_status fluid_world_emitted_count(const fluid_world* world, fluid_emitter_id id,
                                                   uint32_t* count);

/// A region that removes the particles entering it (C++ fluid::DrainDef).
typedef struct fluid_drain_def {
    /// Where.
    fluid_shape shape;
    /// True: only particles of `material`.
    bool only_material;
    /// See only_material.
    fluid_material_id material;
} fluid_drain_def;

/// Adds a drain.
FLUID_C_API fluid_status fluid_world_add_drain(fluid_world* world, const fluid_drain_def* def,
                                               fluid_drain_id* id);

/// What a sensor measured after the last step, per material.
typedef struct fluid_sensor_reading {
    /// Particles inside (unit: count).
    uint32_t count;
    /// Their mass (unit: kg).
    float mass;
    /// Their area (unit: m^2).
    float area;
    /// Their volume, area times depth (unit: m^3).
    float volume;
} fluid_sensor_reading;

/// Adds a sensor over `shape`.
FLUID_C_API fluid_status fluid_world_add_sensor(fluid_world* world, fluid_shape shape,
                                                fluid_sensor_id* id);

/// A sensor's readings, one per material index (`*count` = the material count), valid until
/// the next step.
FLUID_C_API fluid_status fluid_world_sensor_readings(const fluid_world* world,
                                                     fluid_sensor_id id,
                                                     const fluid_sensor_reading** readings,
                                                     uint32_t* count);

/// Why a particle went.
typedef enum fluid_removal_cause {
    /// A drain took it.
    FLUID_REMOVED_BY_DRAIN = 0,
    /// Its lifetime ran out.
    FLUID_REMOVED_BY_LIFETIME = 1,
    /// It left the world's range.
    FLUID_REMOVED_OUT_OF_RANGE = 2
} fluid_removal_cause;

/// A particle the last step removed.
typedef struct fluid_removed_event {
    /// The particle (no longer valid).
    fluid_particle_id particle;
    /// Where it was (unit: m).
    fluid_vec2 position;
    /// Its velocity (unit: m/s).
    fluid_vec2 velocity;
    /// Its material.
    fluid_material_id material;
    /// A fluid_removal_cause.
    int32_t cause;
    /// The drain, when the cause is a drain.
    fluid_drain_id drain;
} fluid_removed_event;

/// The particles the last step removed, in order, valid until the next step.
FLUID_C_API fluid_status fluid_world_removed_events(const fluid_world* world,
                                                    const fluid_removed_event** events,
                                                    uint32_t* count);

/* ------------------------------------------------------------------------------------------ */
/* Plugins by name (the built-in catalogue: docs/plugins.md)                                   */
/* ------------------------------------------------------------------------------------------ */

/// A parameter value by name (a level file's plugin fields).
typedef struct fluid_param {
    /// Its name ("strength", "x"...).
    const char* name;
    /// Its value, in the parameter's unit and range.
    double value;
} fluid_param;

/// Adds a plugin of a registered type ("force.gravity", "boundary.box", "force.wind"...;
/// docs/plugins.md)
/// with the given parameters (the others at their defaults). FLUID_ERROR_UNKNOWN_NAME for a
/// type or parameter the registry does not know; FLUID_ERROR_INVALID_ARGUMENT for a value out
/// of range.
FLUID_C_API fluid_status fluid_world_add_plugin(fluid_world* world, const char* type,
                                                const fluid_param* params, uint32_t param_count,
                                                fluid_plugin_id* id);

/// Sets a plugin's number parameter between steps.
FLUID_C_API fluid_status fluid_plugin_set_param(fluid_world* world, fluid_plugin_id id,
                                                const char* name, double value);

/// Reads a plugin's number parameter.
FLUID_C_API fluid_status fluid_plugin_get_param(const fluid_world* world, fluid_plugin_id id,
                                                const char* name, double* value);

/// Sets a plugin's point-list parameter (a polygon's vertices, a chain; unit: m; copied).
FLUID_C_API fluid_status fluid_plugin_set_points(fluid_world* world, fluid_plugin_id id,
                                                 const char* name, const fluid_vec2* points,
                                                 uint32_t count);

/// A plugin's registered type name ("force.gravity"; a C plugin's def->type), valid while the
/// world lives.
FLUID_C_API fluid_status fluid_plugin_type(const fluid_world* world, fluid_plugin_id id,
                                           const char** type);

/// Plugins of one kind in the world (unit: count).
FLUID_C_API fluid_status fluid_world_plugin_count(const fluid_world* world, fluid_plugin_kind kind,
                                                  uint32_t* count);

/* ------------------------------------------------------------------------------------------ */
/* Plugins written in C                                                                        */
/* ------------------------------------------------------------------------------------------ */

/// A parameter a C plugin declares (C++ fluid::ParamDecl): fluid_plugin_set_param and
/// fluid_plugin_get_param reach it by name, the callbacks read its value in `params`, saves keep
/// it. The strings are copied when the plugin is added.
typedef struct fluid_param_decl {
    /// Its name (printable UTF-8: no control character, at most 256 bytes).
    const char* name;
    /// Its unit ("m/s^2").
    const char* unit;
    /// Its default value.
    double default_value;
    /// Its range [min_value, max_value].
    double min_value;
    /// See min_value.
    double max_value;
    /// One line for tools.
    const char* description;
} fluid_param_decl;

/// What every plugin callback is told about the step.
typedef struct fluid_step_context {
    /// The frame being stepped (unit: s).
    float frame_dt;
    /// Simulated time at its start (unit: s).
    double time;
    /// The spacing boundaries sample at (unit: m).
    float sample_spacing;
    /// The largest kernel support (unit: m).
    float support_radius;
    /// The plugin's parameter values, in its declarations' order.
    const double* params;
} fluid_step_context;

/// What a force plugin's apply reads and writes.
typedef struct fluid_force_context {
    /// Positions (unit: m), all particles.
    const float* px;
    /// See px.
    const float* py;
    /// Velocities (unit: m/s).
    const float* vx;
    /// See vx.
    const float* vy;
    /// Material indices.
    const uint16_t* material;
    /// Particles (unit: count).
    uint32_t count;
    /// Accelerations to add to (unit: m/s^2): write only [begin, end).
    float* ax;
    /// See ax.
    float* ay;
    /// The sub-step (unit: s).
    float dt;
    /// Simulated time (unit: s).
    double time;
    /// The plugin's parameter values, in its declarations' order.
    const double* params;
} fluid_force_context;

/// A force plugin made of functions (C++ fluid::ForcePlugin).
typedef struct fluid_force_plugin_def {
    /// Its type name (in saves and messages; required; printable UTF-8: no control character,
    /// 1 to 256 bytes).
    const char* type;
    /// Passed to every callback.
    void* user;
    /// Its parameters (may be NULL with param_count 0).
    const fluid_param_decl* params;
    /// How many (unit: count).
    uint32_t param_count;
    /// Once per step before the sub-steps (may be NULL). Stepping thread.
    void (*prepare)(void* user, const fluid_step_context* context);
    /// Adds accelerations to particles [begin, end) (required). Worker threads, several at once
    /// on disjoint ranges: write only your range, keep results independent of the split.
    void (*apply)(void* user, const fluid_force_context* context, uint32_t begin, uint32_t end);
    /// When the world lets the plugin go (may be NULL), on the thread that destroys the world.
    /// Not called when adding the plugin failed.
    void (*destroy)(void* user);
} fluid_force_plugin_def;

/// A def with every callback NULL and no parameters. Any thread.
FLUID_C_API fluid_force_plugin_def fluid_default_force_plugin_def(void);

/// Adds a force plugin written in C. On failure `destroy` is not called.
FLUID_C_API fluid_status fluid_world_add_force(fluid_world* world,
                                               const fluid_force_plugin_def* def,
                                               fluid_plugin_id* id);

/// Where the position-based solver's coarse pressure solve has moved one of a boundary's rigid
/// bodies within the step so far (C++ fluid::BodyShift): at time t into the step the body stands
/// offset + velocity t away from where the plugin's own poses put it.
typedef struct fluid_body_shift {
    /// The velocity the solve gave the body (unit: m/s).
    fluid_vec2 velocity;
    /// The offset at the step's start (unit: m).
    fluid_vec2 offset;
} fluid_body_shift;

/// What a boundary's project moves (C++ fluid::ProjectContext).
typedef struct fluid_project_context {
    /// Positions (unit: m), all particles: move [begin, end) out of the solid.
    float* px;
    /// See px.
    float* py;
    /// Positions at the start of the sub-step (unit: m).
    const float* prev_x;
    /// See prev_x.
    const float* prev_y;
    /// Velocities (unit: m/s): remove the part into the solid.
    float* vx;
    /// See vx.
    float* vy;
    /// Material indices.
    const uint16_t* material;
    /// The sub-step (unit: s).
    float dt;
    /// Where in the step the positions are (unit: s from the step's start).
    float time_in_step;
    /// Where prev_x / prev_y were (unit: s).
    float prev_time_in_step;
    /// The boundary sample spacing (unit: m; fluid_step_context.sample_spacing).
    float spacing;
    /// The plugin's parameter values.
    const double* params;
    /// Per rigid body of the plugin (rigid_bodies order), where the coarse solve has moved it so
    /// far in the step: move the body's shape by it (NULL when none moved). Since C API 1.1.
    const fluid_body_shift* body_shifts;
    /// How many entries body_shifts holds (unit: count).
    uint32_t body_shift_count;
} fluid_project_context;

/// Samples of a boundary's surface, as the plugin's prepare leaves them: the fluid feels them
/// as its neighbours. The arrays stay the plugin's; they are copied after prepare.
typedef struct fluid_boundary_samples {
    /// Positions (unit: m).
    const float* px;
    /// See px.
    const float* py;
    /// Velocities (unit: m/s).
    const float* vx;
    /// See vx.
    const float* vy;
    /// How many (unit: count).
    uint32_t count;
} fluid_boundary_samples;

/// A rigid body among a boundary's samples (C++ fluid::RigidBody).
typedef struct fluid_rigid_body {
    /// Mass (unit: kg; (0, 1e9], or 0 for one the fluid cannot move).
    float mass;
    /// First sample (unit: index).
    uint32_t sample_begin;
    /// One past the last (unit: index).
    uint32_t sample_end;
    /// True to have the world report the liquid's contacts with this body after each step
    /// (fluid_world_contacts); false (zero-initialised) costs nothing.
    bool contacts;
} fluid_rigid_body;

/// What the coarse pressure solve did to a body over a step (C++ fluid::RigidBodyImpulse).
typedef struct fluid_rigid_body_impulse {
    /// Impulse (unit: N s).
    fluid_vec2 impulse;
    /// Displacement beyond its own velocity's path (unit: m).
    fluid_vec2 displacement;
} fluid_rigid_body_impulse;

/// What a boundary's project keeps.
typedef enum fluid_boundary_role {
    /// Particles out of a solid.
    FLUID_ROLE_SOLID = 0,
    /// Particles on their side of a wall.
    FLUID_ROLE_WALL = 1,
    /// Particles inside a container.
    FLUID_ROLE_CONTAINER = 2
} fluid_boundary_role;

/// A boundary plugin made of functions (C++ fluid::BoundaryPlugin): a solid, wall or container,
/// optionally carrying rigid bodies of the game's own physics.
typedef struct fluid_boundary_plugin_def {
    /// Its type name (required; a name as fluid_force_plugin_def.type).
    const char* type;
    /// Passed to every callback.
    void* user;
    /// Its parameters (may be NULL with param_count 0).
    const fluid_param_decl* params;
    /// How many (unit: count).
    uint32_t param_count;
    /// A fluid_boundary_role.
    int32_t role;
    /// Wall friction (unit: 1; >= 0, 0 free slip, 1 the fluid's viscosity).
    float friction;
    /// True to have the fluid's forces on the samples computed after each step and handed to
    /// receive_forces (nothing happens without a receive_forces).
    bool wants_forces;
    /// Once per step (required): fill `samples` with the surface at the step's start. Stepping
    /// thread.
    void (*prepare)(void* user, const fluid_step_context* context,
                    fluid_boundary_samples* samples);
    /// Moves particles [begin, end) that ended inside back out (required). Worker threads, on
    /// disjoint ranges.
    void (*project)(void* user, const fluid_project_context* context, uint32_t begin,
                    uint32_t end);
    /// After the step, with wants_forces: the force on each sample (unit: N) and the drag
    /// -dF/dv >= 0 (unit: N s/m), `count` samples (may be NULL). Stepping thread.
    void (*receive_forces)(void* user, const float* fx, const float* fy, const float* drag,
                           uint32_t count);
    /// The rigid bodies among the samples as the last prepare left them: `*bodies` set to an
    /// array of the plugin's, the count returned (may be NULL: none). Stepping thread.
    uint32_t (*rigid_bodies)(void* user, const fluid_rigid_body** bodies);
    /// After the step, before receive_forces: one impulse per rigid body (may be NULL).
    /// Stepping thread.
    void (*receive_body_impulses)(void* user, const fluid_rigid_body_impulse* impulses,
                                  uint32_t count);
    /// True when `point` (unit: m) is inside body `body` at `time_in_step` seconds into the step
    /// (may be NULL: read from the samples). Stepping thread, read only.
    bool (*body_contains)(void* user, uint32_t body, fluid_vec2 point, float time_in_step);
    /// True when `point` is in what project keeps particles out of (may be NULL: never); blobs
    /// and emitters leave such points out. The thread that calls the world (between steps for
    /// a blob, during a step for an emitter).
    bool (*contains)(void* user, fluid_vec2 point);
    /// When the world lets the plugin go (may be NULL), on the thread that destroys the world.
    /// Not called when adding the plugin failed.
    void (*destroy)(void* user);
} fluid_boundary_plugin_def;

/// A def with every callback NULL, role solid, no friction. Any thread.
FLUID_C_API fluid_boundary_plugin_def fluid_default_boundary_plugin_def(void);

/// Adds a boundary plugin written in C. On failure `destroy` is not called.
FLUID_C_API fluid_status fluid_world_add_boundary(fluid_world* world,
                                                  const fluid_boundary_plugin_def* def,
                                                  fluid_plugin_id* id);

/// A plugin type written in C, registered by name for the whole process: fluid_world_add_plugin
/// adds it by name, level files name it in their "plugins", and fluid_world_load and level saves
/// make it again. Start from fluid_default_plugin_type_def().
typedef struct fluid_plugin_type_def {
    /// Its type name (required; not one already registered, the built-ins' included; a name as
    /// fluid_force_plugin_def.type).
    const char* type;
    /// One line for tools (may be NULL).
    const char* description;
    /// A fluid_plugin_kind.
    int32_t kind;
    /// Its parameters, the same for every instance (may be NULL with param_count 0).
    const fluid_param_decl* params;
    /// How many (unit: count).
    uint32_t param_count;
    /// Passed to create_force or create_boundary.
    void* user;
    /// A force type's factory: fills a new instance's callbacks and user pointer in `*def` (its
    /// type and parameters are the type's, the rest fluid_default_force_plugin_def's); false
    /// refuses (the call that wanted the plugin fails naming the type). On the thread of the
    /// call that makes the plugin.
    bool (*create_force)(void* user, fluid_force_plugin_def* def);
    /// A boundary type's factory, as create_force.
    bool (*create_boundary)(void* user, fluid_boundary_plugin_def* def);
} fluid_plugin_type_def;

/// A def with no name, kind force, no parameters, no factories. Any thread.
FLUID_C_API fluid_plugin_type_def fluid_default_plugin_type_def(void);

/// Registers a plugin type written in C for the rest of the process (types are never removed).
/// FLUID_ERROR_INVALID_ARGUMENT for a name already registered, a type or parameter name that is
/// not printable text of at most 256 bytes, a kind without its factory, or bad parameter
/// declarations (the registry's own message). Any thread: registrations are
/// serialised, and a world or level being made meanwhile uses the types registered before.
FLUID_C_API fluid_status fluid_register_plugin_type(const fluid_plugin_type_def* def);

/* ------------------------------------------------------------------------------------------ */
/* Levels (JSON level files: docs/levels.md)                                                   */
/* ------------------------------------------------------------------------------------------ */

/// How a level is loaded.
typedef struct fluid_level_options {
    /// Workers of the level's world (unit: count; 0 the file's "workers", default 1; a save
    /// keeps its own count).
    uint32_t worker_count;
    /// Most particles (unit: count; 0 the level's own limit).
    uint32_t max_particles;
} fluid_level_options;

/// Zero: the file's worker count and particle limit. Any thread.
FLUID_C_API fluid_level_options fluid_default_level_options(void);

/// Loads a level file (JSON). FLUID_ERROR_BAD_FILE with "FILE:LINE:COLUMN: at /json/path:
/// message" for a malformed one, FLUID_ERROR_UNKNOWN_NAME (same form) for a name nothing is
/// registered or declared under (a plugin type, a preset, a material the file does not
/// declare), FLUID_ERROR_IO for one that cannot be read. `options` may be NULL. Destroy the
/// level with fluid_level_destroy.
FLUID_C_API fluid_status fluid_level_load(const char* path, const fluid_level_options* options,
                                          fluid_level** level);

/// Loads a level save (fluid_level_save's, the demo's F5) from a file.
FLUID_C_API fluid_status fluid_level_load_save(const char* path,
                                               const fluid_level_options* options,
                                               fluid_level** level);

/// Loads a level save from fluid_level_save_bytes's bytes; `file` names it in messages.
FLUID_C_API fluid_status fluid_level_read_save(const void* data, size_t size, const char* file,
                                               const fluid_level_options* options,
                                               fluid_level** level);

/// Parses a level from `size` bytes of text in memory, all of them the document: a NUL byte
/// among them is FLUID_ERROR_BAD_FILE naming its offset. `file` names it in messages.
FLUID_C_API fluid_status fluid_level_parse(const char* text, size_t size, const char* file,
                                           const fluid_level_options* options,
                                           fluid_level** level);

/// Destroys a level with its world and bodies. NULL is fine (FLUID_OK). Called from inside the
/// level's own step (a plugin's callback), it destroys nothing and returns FLUID_ERROR_REFUSED.
FLUID_C_API fluid_status fluid_level_destroy(fluid_level* level);

/// Steps a level by one frame of its frame rate (the world, its Box2D bodies, its goal).
FLUID_C_API fluid_status fluid_level_step(fluid_level* level);

/// The level's world: read it and change it with the world functions, step it with
/// fluid_level_step. The level owns it: never fluid_world_destroy it.
FLUID_C_API fluid_status fluid_level_world(fluid_level* level, fluid_world** world);

/// The level's frame rate (unit: 1/s).
FLUID_C_API fluid_status fluid_level_frame_rate(const fluid_level* level, float* rate);

/// Saves the level (its file's text, the world, the bodies) to `path`: fluid_level_load_save
/// reads it back.
FLUID_C_API fluid_status fluid_level_save(const fluid_level* level, const char* path);

/// Saves the level into `*bytes` (free with fluid_bytes_free).
FLUID_C_API fluid_status fluid_level_save_bytes(const fluid_level* level, fluid_bytes* bytes);

/// The goal's state.
typedef enum fluid_goal_state {
    /// The level has no goal.
    FLUID_GOAL_NONE = 0,
    /// Not reached yet.
    FLUID_GOAL_PENDING = 1,
    /// Reached (final).
    FLUID_GOAL_WON = 2,
    /// Time ran out (final).
    FLUID_GOAL_LOST = 3
} fluid_goal_state;

/// The goal's state and measured value (the goal's unit: count, fraction or m^3).
FLUID_C_API fluid_status fluid_level_goal(const fluid_level* level, fluid_goal_state* state,
                                          double* value);

/// A named object of the level file: its material, emitter, drain, sensor or plugin by the
/// name the file gives it. FLUID_ERROR_UNKNOWN_NAME naming it otherwise.
FLUID_C_API fluid_status fluid_level_find_material(const fluid_level* level, const char* name,
                                                   fluid_material_id* id);
/// See fluid_level_find_material.
FLUID_C_API fluid_status fluid_level_find_emitter(const fluid_level* level, const char* name,
                                                  fluid_emitter_id* id);
/// See fluid_level_find_material.
FLUID_C_API fluid_status fluid_level_find_drain(const fluid_level* level, const char* name,
                                                fluid_drain_id* id);
/// See fluid_level_find_material.
FLUID_C_API fluid_status fluid_level_find_sensor(const fluid_level* level, const char* name,
                                                 fluid_sensor_id* id);
/// See fluid_level_find_material.
FLUID_C_API fluid_status fluid_level_find_plugin(const fluid_level* level, const char* name,
                                                 fluid_plugin_id* id);

/// Box2D bodies of the level: the file's, then those fluid_level_add_body added (unit: count).
FLUID_C_API fluid_status fluid_level_body_count(const fluid_level* level, uint32_t* count);

/// A body of the level by its index (the file's bodies in its order, then the added ones): its
/// name ("" for an added body; valid while the level lives), position (unit: m) and angle
/// (unit: rad). Each output pointer may be NULL (that output is skipped). FLUID_ERROR_STALE_ID
/// for an index past the bodies.
FLUID_C_API fluid_status fluid_level_body(const fluid_level* level, uint32_t index,
                                          const char** name, fluid_vec2* position, float* angle);

/// Sets the level's gravity (unit: m/s^2; finite): every "force.gravity" plugin of its world,
/// and its Box2D world's, whose bodies are woken (the coupling's buoyancy reads Box2D's
/// gravity: the two stay the same). Zero gravity is {0, 0}. Between steps.
FLUID_C_API fluid_status fluid_level_set_gravity(fluid_level* level, fluid_vec2 gravity);

/// What a Box2D body is.
typedef enum fluid_body_type {
    /// Never moves.
    FLUID_BODY_STATIC = 0,
    /// Moves at the velocity it is given (a plank the player drags).
    FLUID_BODY_KINEMATIC = 1,
    /// Moves under gravity, contacts and the fluid (a crate).
    FLUID_BODY_DYNAMIC = 2
} fluid_body_type;

/// A Box2D body for a level with bodies (a crate dropped, a plank placed).
typedef struct fluid_body_def {
    /// A fluid_body_type.
    int32_t type;
    /// Its one fixture: a box or circle whose center is the body's position, or a convex
    /// polygon of 3 to 8 vertices around the body's position (unit: m).
    fluid_shape shape;
    /// For a polygon: the body's position (unit: m; a box or circle takes shape.center).
    fluid_vec2 position;
    /// Angle (unit: rad; finite).
    float angle;
    /// Box2D's density: mass per area of the 2D shape (unit: kg/m^2; > 0 for a dynamic body;
    /// fluid_level_areal_density gives the liquid's, for a body that floats at a ratio of it).
    float density;
    /// Box2D's contact friction (unit: 1; >= 0).
    float friction;
    /// Initial velocity (unit: m/s).
    fluid_vec2 velocity;
    /// Initial angular velocity (unit: rad/s).
    float angular_velocity;
} fluid_body_def;

/// A dynamic box 0.1 m across at the origin, density 0, friction 0.4. Any thread.
FLUID_C_API fluid_body_def fluid_default_body_def(void);

/// The areal density of a material's liquid as Box2D weighs bodies (unit: kg/m^2): a body of
/// half this density floats half submerged.
FLUID_C_API fluid_status fluid_level_areal_density(const fluid_level* level,
                                                   fluid_material_id material, float* density);

/// Adds a Box2D body to a level whose file declares bodies (FLUID_ERROR_REFUSED for one that
/// declares none: its world has no Box2D world to couple); the fluid meets it from the next
/// step. `index` (may be NULL) receives its fluid_level_body index. A level save keeps the
/// body; a level loaded from the save lists only the file's bodies (the added ones are still in
/// its Box2D world and its fluid).
FLUID_C_API fluid_status fluid_level_add_body(fluid_level* level, const fluid_body_def* def,
                                              uint32_t* index);

/// Removes body `index` (fluid_level_body's index: the file's bodies, then the added ones) from
/// the level, with the joints attached to it; the bodies after it move down one index.
/// FLUID_ERROR_STALE_ID for an index past the last body; FLUID_ERROR_REFUSED from inside the
/// level's step. Between steps.
FLUID_C_API fluid_status fluid_level_remove_body(fluid_level* level, uint32_t index);

/// Sets a body's velocity (unit: m/s) and angular velocity (unit: rad/s): how a game drags a
/// kinematic plank or throws a crate. Between steps.
FLUID_C_API fluid_status fluid_level_set_body_velocity(fluid_level* level, uint32_t index,
                                                       fluid_vec2 velocity,
                                                       float angular_velocity);

/* ---- Groups, per-particle user data and colours, positions between steps (fluid/groups.h,
 * docs/groups.md). Calls from inside the world's step fail with FLUID_ERROR_REFUSED; a stale,
 * null or other world's group or particle id with FLUID_ERROR_STALE_ID and the C++ message
 * ("groupCount: stale group handle {index 1, generation 1}: ..."). ---- */

/// A group of particles (C++ fluid::GroupHandle): a blob, an emitter's output, or one made with
/// fluid_world_create_group. All zero is null. A plain value.
typedef struct fluid_group_id {
    /// Index in the world's group table (unit: index).
    uint32_t index;
    /// Generation (unit: count; 0 in the null id).
    uint32_t generation;
    /// Tag of the world that made it.
    uint32_t world;
} fluid_group_id;

/// A particle's colour (C++ fluid::Colour; unit: 0..255 per channel); alpha 0 = none (the
/// material's style).
typedef struct fluid_colour {
    /// Red, green, blue and alpha (unit: 0..255 each; alpha 0 = no colour).
    uint8_t r, g, b, a;
} fluid_colour;

/// What particles that join a group at spawn start with (C++ fluid::GroupDef).
typedef struct fluid_group_def {
    /// User data of each new particle (0 = none).
    uint32_t user_data;
    /// Colour of each new particle (alpha 0 = none).
    fluid_colour colour;
} fluid_group_def;

/// Makes an empty group; `def` may be NULL (no user data, no colour).
FLUID_C_API fluid_status fluid_world_create_group(fluid_world* world, const fluid_group_def* def,
                                                  fluid_group_id* group);

/// Spawns a blob (as fluid_world_spawn_blob) into `into`, or, when `into` is null (all zero),
/// into a new group made with `def` (may be NULL); `group` receives the group, `spawned` (may be
/// NULL) the particle count.
FLUID_C_API fluid_status fluid_world_spawn_group(fluid_world* world, const fluid_blob_def* blob,
                                                 fluid_group_id into, const fluid_group_def* def,
                                                 fluid_group_id* group, uint32_t* spawned);

/// True in `*valid` while the group exists.
FLUID_C_API fluid_status fluid_world_group_valid(const fluid_world* world, fluid_group_id group,
                                                 bool* valid);

/// The particle's group (null when it has none).
FLUID_C_API fluid_status fluid_world_particle_group(const fluid_world* world,
                                                    fluid_particle_id particle,
                                                    fluid_group_id* group);

/// Moves the particle into `group` (it keeps its user data and colour).
FLUID_C_API fluid_status fluid_world_set_particle_group(fluid_world* world,
                                                        fluid_particle_id particle,
                                                        fluid_group_id group);

/// The group an emitter's particles join (made for it by fluid_world_add_emitter).
FLUID_C_API fluid_status fluid_world_emitter_group(const fluid_world* world,
                                                   fluid_emitter_id emitter,
                                                   fluid_group_id* group);

/// Makes an emitter's future particles join `group`.
FLUID_C_API fluid_status fluid_world_set_emitter_group(fluid_world* world,
                                                       fluid_emitter_id emitter,
                                                       fluid_group_id group);

/// Replaces what the group's new particles take (its particles keep theirs).
FLUID_C_API fluid_status fluid_world_set_group_def(fluid_world* world, fluid_group_id group,
                                                   const fluid_group_def* def);

/// Particles in the group (unit: count).
FLUID_C_API fluid_status fluid_world_group_count(const fluid_world* world, fluid_group_id group,
                                                 uint32_t* count);

/// Writes the ids of the group's particles in increasing index, at most `capacity` (`ids` may
/// be NULL with capacity 0); `count` receives the group's count.
FLUID_C_API fluid_status fluid_world_group_particles(const fluid_world* world,
                                                     fluid_group_id group,
                                                     fluid_particle_id* ids, uint32_t capacity,
                                                     uint32_t* count);

/// The group's centre of mass (unit: m; (0, 0) when empty).
FLUID_C_API fluid_status fluid_world_group_centre(const fluid_world* world, fluid_group_id group,
                                                  fluid_vec2* centre);

/// The group's mass-weighted mean velocity (unit: m/s; (0, 0) when empty).
FLUID_C_API fluid_status fluid_world_group_velocity(const fluid_world* world,
                                                    fluid_group_id group, fluid_vec2* velocity);

/// Translates the group by `offset` (unit: m; finite); all or nothing.
FLUID_C_API fluid_status fluid_world_move_group(fluid_world* world, fluid_group_id group,
                                                fluid_vec2 offset);

/// Sets the velocity of every particle of the group (unit: m/s; finite).
FLUID_C_API fluid_status fluid_world_set_group_velocity(fluid_world* world, fluid_group_id group,
                                                        fluid_vec2 velocity);

/// Destroys the group, with its particles when `with_particles`, else leaving them without one.
FLUID_C_API fluid_status fluid_world_destroy_group(fluid_world* world, fluid_group_id group,
                                                   bool with_particles);

/// Moves every particle of `from` into `into` and destroys `from`.
FLUID_C_API fluid_status fluid_world_merge_groups(fluid_world* world, fluid_group_id into,
                                                  fluid_group_id from);

/// A particle's user data (0 when never set).
FLUID_C_API fluid_status fluid_world_particle_user_data(const fluid_world* world,
                                                        fluid_particle_id particle,
                                                        uint32_t* value);

/// Sets a particle's user data.
FLUID_C_API fluid_status fluid_world_set_particle_user_data(fluid_world* world,
                                                            fluid_particle_id particle,
                                                            uint32_t value);

/// Sets the user data of every particle of the group.
FLUID_C_API fluid_status fluid_world_set_group_user_data(fluid_world* world, fluid_group_id group,
                                                         uint32_t value);

/// Writes every particle's user data in index order, at most `capacity` (`values` may be NULL
/// with capacity 0); `count` receives the particle count.
FLUID_C_API fluid_status fluid_world_user_data(const fluid_world* world, uint32_t* values,
                                               uint32_t capacity, uint32_t* count);

/// A particle's colour (alpha 0 when none).
FLUID_C_API fluid_status fluid_world_particle_colour(const fluid_world* world,
                                                     fluid_particle_id particle,
                                                     fluid_colour* colour);

/// Sets a particle's colour (alpha 0 takes it away).
FLUID_C_API fluid_status fluid_world_set_particle_colour(fluid_world* world,
                                                         fluid_particle_id particle,
                                                         fluid_colour colour);

/// Sets the colour of every particle of the group.
FLUID_C_API fluid_status fluid_world_set_group_colour(fluid_world* world, fluid_group_id group,
                                                      fluid_colour colour);

/// Every particle's colour in index order, as fluid_colour (r, g, b, a bytes), valid until the
/// world changes; `*colours` receives NULL and `*count` 0 while no particle ever had one.
FLUID_C_API fluid_status fluid_world_colours(const fluid_world* world,
                                             const fluid_colour** colours, uint32_t* count);

/// Colour mixing between touching coloured particles (unit: 1/s; range [0, 1000]; 0 off).
FLUID_C_API fluid_status fluid_world_set_colour_mixing(fluid_world* world, float rate);

/// Keeps (or drops) the previous sub-step's positions for drawing between steps (off by
/// default; costs nothing while off): fluid_world_set_interpolation_mode with
/// FLUID_INTERPOLATION_SUBSTEP or FLUID_INTERPOLATION_OFF.
FLUID_C_API fluid_status fluid_world_set_interpolation(fluid_world* world, bool on);

/// Which previous positions a world keeps (C++ fluid::Interpolation).
typedef enum fluid_interpolation {
    /// None (the default).
    FLUID_INTERPOLATION_OFF = 0,
    /// The start of the last simulated sub-step: for a game that steps with each display
    /// frame's time; fluid_world_interpolation_factor gives the factor.
    FLUID_INTERPOLATION_SUBSTEP = 1,
    /// The start of the last step that simulated a sub-step: for a game that steps fixed ticks
    /// and draws faster; it passes the fraction of a tick its accumulator holds as the factor.
    FLUID_INTERPOLATION_STEP = 2
} fluid_interpolation;

/// Sets which previous positions the world keeps (`mode`: a fluid_interpolation);
/// FLUID_ERROR_INVALID_ARGUMENT for another value. Between steps.
FLUID_C_API fluid_status fluid_world_set_interpolation_mode(fluid_world* world, uint32_t mode);

/// How far between the previous and current positions to draw now (unit: 1; [0, 1]):
/// carried time over the sub-step plus a half (1 for the explicit solver).
FLUID_C_API fluid_status fluid_world_interpolation_factor(const fluid_world* world,
                                                          float* factor);

/// Writes the positions interpolated at `factor` (unit: 1; [0, 1], negative for
/// fluid_world_interpolation_factor) into `x` and `y`, at most `capacity` each (NULL with
/// capacity 0); `count` (may be NULL) receives the particle count. The current positions while
/// interpolation is off.
FLUID_C_API fluid_status fluid_world_interpolated_positions(const fluid_world* world, float* x,
                                                            float* y, uint32_t capacity,
                                                            float factor, uint32_t* count);

/* ------------------------------------------------------------------------------------------ */
/* Contact events (C++ fluid/contacts.h; docs/c_api_levels.md, "Contact events")                  */
/* ------------------------------------------------------------------------------------------ */

/// What the liquid did to one body that asked for contact events during the last step (C++
/// fluid::BodyContact): reported for each asking body some particle touched (came within 1.5
/// sample spacings of its samples at the end of a sub-step); a dry body reports nothing.
typedef struct fluid_body_contact {
    /// The boundary plugin (kind FLUID_PLUGIN_BOUNDARY).
    fluid_plugin_id plugin;
    /// The body among the plugin's rigid bodies (unit: index; 0 for a boundary shape).
    uint32_t body;
    /// The material most of the touching particles have.
    fluid_material_id material;
    /// The particle group most of them belong to (ties: the lower index); the null id (all
    /// zeros) when none of them is in a group.
    fluid_group_id group;
    /// Distinct particles that touched the body during the step (unit: count; >= 1).
    uint32_t particles;
    /// The liquid's impulse on the body over the step (unit: N s).
    fluid_vec2 impulse;
    /// Mean position of the touching particles (unit: m).
    fluid_vec2 point;
    /// Largest speed at which a touching particle moved towards the body (unit: m/s; >= 0).
    float approach_speed;
} fluid_body_contact;

/// Asks for contact events with a boundary shape ("boundary.polygon", "boundary.chain",
/// "boundary.circle"; a level file's "contacts": true) from the next step on, or stops them
/// (the default: off, at no cost); saved with the world. FLUID_ERROR_STALE_ID for an unknown
/// plugin, FLUID_ERROR_INVALID_ARGUMENT for a force or another boundary type; REFUSED from
/// inside the world's step. Between steps.
FLUID_C_API fluid_status fluid_world_set_contact_events(fluid_world* world, fluid_plugin_id shape,
                                                        bool on);

/// The contacts of the last step, ordered by plugin then body (the same for any number of
/// workers and after a save and load): writes at most `capacity` of them to `contacts` (may be
/// NULL with capacity 0); `count` receives how many there are. REFUSED from inside the world's
/// step. Between steps.
FLUID_C_API fluid_status fluid_world_contacts(const fluid_world* world,
                                              fluid_body_contact* contacts, uint32_t capacity,
                                              uint32_t* count);

/// The particles that touched the body of contact `contact` (an index into
/// fluid_world_contacts' list) during the last step, in increasing slot order: writes at most
/// `capacity` ids to `ids` (may be NULL with capacity 0); `count` receives how many there are.
/// FLUID_ERROR_INVALID_ARGUMENT naming the index for one past the list.
FLUID_C_API fluid_status fluid_world_contact_particles(const fluid_world* world,
                                                       uint32_t contact, fluid_particle_id* ids,
                                                       uint32_t capacity, uint32_t* count);

/// A Box2D body's contacts during the last fluid_level_step (C++ fluid::box2d::ParticleContact):
/// as fluid_body_contact, with the body as its fluid_level_body index, the impulse the
/// coupling's force over the frame's rounds.
typedef struct fluid_level_body_contact {
    /// The body (fluid_level_body's index: the file's bodies, then the added ones).
    uint32_t body;
    /// The material most of the touching particles have.
    fluid_material_id material;
    /// The particle group most of them belong to (ties: the lower index); the null id (all
    /// zeros) when none of them is in a group.
    fluid_group_id group;
    /// Distinct particles that touched the body during the frame (unit: count; >= 1).
    uint32_t particles;
    /// The liquid's impulse on the body over the frame (unit: N s).
    fluid_vec2 impulse;
    /// Mean position of the touching particles (unit: m).
    fluid_vec2 point;
    /// Largest speed at which a touching particle moved towards the body (unit: m/s; >= 0).
    float approach_speed;
} fluid_level_body_contact;

/// Asks for contact events with body `index` (fluid_level_body's index; a level file's
/// "contacts": true on the body) from the next step on, or stops them (the default: off);
/// saved with the level. FLUID_ERROR_STALE_ID for an index past the bodies; REFUSED for a level
/// without bodies. Between steps.
FLUID_C_API fluid_status fluid_level_set_body_contact_events(fluid_level* level, uint32_t index,
                                                             bool on);

/// The Box2D bodies' contacts of the last fluid_level_step, in body order: writes at most
/// `capacity` of them to `contacts` (may be NULL with capacity 0); `count` receives how many
/// there are (0 for a level without bodies). A body the level no longer lists is left out.
FLUID_C_API fluid_status fluid_level_body_contacts(const fluid_level* level,
                                                   fluid_level_body_contact* contacts,
                                                   uint32_t capacity, uint32_t* count);

/// The particles that touched the body of contact `contact` (an index into
/// fluid_level_body_contacts' list) during the last frame, in increasing slot order, as
/// fluid_world_contact_particles.
FLUID_C_API fluid_status fluid_level_body_contact_particles(const fluid_level* level,
                                                            uint32_t contact,
                                                            fluid_particle_id* ids,
                                                            uint32_t capacity, uint32_t* count);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* FLUID_C_H */
