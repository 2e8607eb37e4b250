// fluid::c — the C API's version, errors, worlds, materials, particles, gameplay objects and
// plugins by name (fluid/c.h): each call checks its pointers, converts, calls the C++ API and
// turns what it throws into a status and this thread's message.
#include "c_internal.h"

#include <fluid/internal/checks.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <utility>

namespace fluid::c {

namespace {

thread_local std::string t_lastError;

// Whether `name` is one of `fields`' names; the field when it is.
template <class Def>
const Field<Def>* findField(std::span<const Field<Def>> fields, std::string_view name) {
    for (const Field<Def>& field : fields) {
        if (field.name == name) {
            return &field;
        }
    }
    return nullptr;
}

// Every field name of the tables, for the message about an unknown one.
template <class... Tables> std::string fieldNames(const Tables&... tables) {
    std::string names;
    auto add = [&](const auto& table) {
        for (const auto& field : table) {
            names += (names.empty() ? "" : ", ") + std::string(field.name);
        }
    };
    (add(tables), ...);
    return names;
}

// Sets `field` of `def` to `value` after checking that the value can be stored: whole-number
// fields take whole numbers in [0, 2^32) (the range itself is checked where the def is used).
template <class Def>
void setField(const Field<Def>& field, Def& def, double value, const char* function) {
    if (std::isnan(value) ||
        (field.whole != nullptr && !(value >= 0.0 && value < 4294967296.0 &&
                                     value == std::floor(value)))) {
        std::ostringstream message;
        message << function << ": '" << field.name << "' = " << value << " is not "
                << (field.whole != nullptr ? "a whole number " : "a number ") << "in ["
                << field.lo << ", " << field.hi << "] (unit: " << field.unit << ")";
        throw Failure{FLUID_ERROR_INVALID_ARGUMENT, message.str()};
    }
    field.set(def, value);
}

WorldDef worldDefOf(const fluid_world_def& d) {
    WorldDef def;
    def.solver = d.solver == FLUID_SOLVER_EXPLICIT ? Solver::Explicit : Solver::PositionBased;
    if (d.solver != FLUID_SOLVER_EXPLICIT && d.solver != FLUID_SOLVER_POSITION_BASED) {
        throw Failure{FLUID_ERROR_INVALID_ARGUMENT,
                      "fluid_world_create: solver " + std::to_string(d.solver) +
                          " is not FLUID_SOLVER_POSITION_BASED (0) or FLUID_SOLVER_EXPLICIT (1)"};
    }
    if (d.equation_of_state != FLUID_EOS_LINEAR && d.equation_of_state != FLUID_EOS_TAIT) {
        throw Failure{FLUID_ERROR_INVALID_ARGUMENT,
                      "fluid_world_create: equation_of_state " +
                          std::to_string(d.equation_of_state) +
                          " is not FLUID_EOS_LINEAR (0) or FLUID_EOS_TAIT (1)"};
    }
    def.positionBased.substeps = d.substeps;
    def.positionBased.iterations = d.iterations;
    def.positionBased.viscosityInterval = d.viscosity_interval;
    def.positionBased.coarseCorrection = d.coarse_correction;
    def.positionBased.vorticity = d.vorticity;
    def.positionBased.shearConstraint = d.shear_constraint;
    def.equationOfState =
        d.equation_of_state == FLUID_EOS_LINEAR ? EquationOfState::Linear : EquationOfState::Tait;
    def.soundSpeed = d.sound_speed;
    def.depth = d.depth;
    def.courant = d.courant;
    def.maxSubsteps = d.max_substeps;
    def.maxParticles = d.max_particles;
    def.workerCount = d.worker_count;
    return def;
}

fluid_world_def worldDefToC(const WorldDef& def) {
    fluid_world_def d{};
    d.solver = def.solver == Solver::Explicit ? FLUID_SOLVER_EXPLICIT : FLUID_SOLVER_POSITION_BASED;
    d.substeps = def.positionBased.substeps;
    d.iterations = def.positionBased.iterations;
    d.viscosity_interval = def.positionBased.viscosityInterval;
    d.coarse_correction = def.positionBased.coarseCorrection;
    d.vorticity = def.positionBased.vorticity;
    d.shear_constraint = def.positionBased.shearConstraint;
    d.equation_of_state =
        def.equationOfState == EquationOfState::Linear ? FLUID_EOS_LINEAR : FLUID_EOS_TAIT;
    d.sound_speed = def.soundSpeed;
    d.depth = def.depth;
    d.courant = def.courant;
    d.max_substeps = def.maxSubsteps;
    d.max_particles = def.maxParticles;
    d.worker_count = def.workerCount;
    return d;
}

Material materialOf(const fluid_material_def& d) {
    Material m;
    m.mass = d.mass;
    m.restDensity = d.rest_density;
    m.viscosity = d.viscosity;
    m.stiffness = d.stiffness;
    m.smoothingDistance = d.smoothing_distance;
    m.kernelParticles = d.kernel_particles;
    m.surfaceTension = d.surface_tension;
    m.yieldStress = d.yield_stress;
    m.consistency = d.consistency;
    m.flowIndex = d.flow_index;
    m.shearModulus = d.shear_modulus;
    m.name = d.name != nullptr ? d.name : "";
    return m;
}

// `name` points into `m`: valid while it lives unchanged.
fluid_material_def materialToC(const Material& m) {
    fluid_material_def d{};
    d.mass = m.mass;
    d.rest_density = m.restDensity;
    d.viscosity = m.viscosity;
    d.stiffness = m.stiffness;
    d.smoothing_distance = m.smoothingDistance;
    d.kernel_particles = m.kernelParticles;
    d.surface_tension = m.surfaceTension;
    d.yield_stress = m.yieldStress;
    d.consistency = m.consistency;
    d.flow_index = m.flowIndex;
    d.shear_modulus = m.shearModulus;
    d.name = m.name.c_str();
    return d;
}

// Presets' names stay valid forever.
fluid_material_def presetToC(const Material& m, const char* name) {
    fluid_material_def d = materialToC(m);
    d.name = name;
    return d;
}

EmitterDef emitterOf(const fluid_emitter_def& d) {
    EmitterDef def;
    def.position = toVec(d.position);
    def.direction = toVec(d.direction);
    def.speed = d.speed;
    def.width = d.width;
    def.rate = d.rate;
    def.material = toCpp(d.material);
    def.maxCount = d.max_count;
    def.lifetime = d.lifetime;
    def.jitter = d.jitter;
    def.seed = d.seed;
    return def;
}

// A particle call's handle checked first: a stale one fails with the C++ API's error for it
// (from `probe`, which throws it: ErrorCode::StaleId, FLUID_ERROR_STALE_ID), before the call's
// other arguments are looked at.
template <class Probe> void checkParticle(const World& world, ParticleHandle h, Probe&& probe) {
    if (!world.isValid(h)) {
        probe();
        throw Failure{FLUID_ERROR_STALE_ID, "stale particle handle"};
    }
}

// A material id checked first, by the C++ API (a stale one throws ErrorCode::StaleId).
void checkMaterial(const World& world, fluid_material_id id) {
    (void)world.material(toCpp(id));
}

} // namespace

namespace {

// fluid_world_get_material's name for material `index`: the world handle's own copy, which
// stays where it is while the world lives unless the material's name changes.
const char* stableName(const fluid_world& world, uint32_t index, const std::string& name) {
    std::vector<std::unique_ptr<std::string>>& names = world.materialNames;
    if (names.size() <= index) {
        names.resize(size_t(index) + 1);
    }
    std::unique_ptr<std::string>& copy = names[index];
    if (copy == nullptr || *copy != name) {
        copy = std::make_unique<std::string>(name);
    }
    return copy->c_str();
}

} // namespace

fluid_status fail(fluid_status status, std::string_view message) {
    try {
        t_lastError.assign(message);
    } catch (...) {
        t_lastError.clear();
    }
    return status;
}

fluid_bytes toBytes(const std::string& text) {
    fluid_bytes bytes{nullptr, text.size()};
    if (!text.empty()) {
        bytes.data = static_cast<uint8_t*>(std::malloc(text.size()));
        if (bytes.data == nullptr) {
            throw std::bad_alloc();
        }
        std::memcpy(bytes.data, text.data(), text.size());
    }
    return bytes;
}

MaterialId toCpp(fluid_material_id id) {
    if (id.index > 0xffffu) {
        throw Failure{FLUID_ERROR_STALE_ID,
                      "material index " + std::to_string(id.index) + " is past 65535"};
    }
    return {uint16_t(id.index), id.world};
}

Shape toCpp(const fluid_shape& s, const char* function) {
    switch (s.type) {
    case FLUID_SHAPE_BOX: {
        Shape shape;
        shape.center = toVec(s.center);
        shape.halfExtents = toVec(s.half_extents);
        return shape;
    }
    case FLUID_SHAPE_CIRCLE:
        return Shape::circle(toVec(s.center), s.radius);
    case FLUID_SHAPE_POLYGON: {
        if (s.vertex_count > 0) {
            need(s.vertices, function, "shape.vertices");
        }
        std::vector<glm::vec2> vertices(s.vertex_count);
        for (uint32_t i = 0; i < s.vertex_count; ++i) {
            vertices[i] = toVec(s.vertices[i]);
        }
        return Shape::polygon(std::move(vertices));
    }
    default:
        throw Failure{FLUID_ERROR_INVALID_ARGUMENT,
                      std::string(function) + ": shape type " + std::to_string(s.type) +
                          " is not FLUID_SHAPE_BOX, FLUID_SHAPE_CIRCLE or FLUID_SHAPE_POLYGON"};
    }
}

Plugin& pluginOf(World& world, fluid_plugin_id id, const char* function) {
    if (id.kind != FLUID_PLUGIN_FORCE && id.kind != FLUID_PLUGIN_BOUNDARY) {
        throw Failure{FLUID_ERROR_INVALID_ARGUMENT,
                      std::string(function) + ": plugin kind " + std::to_string(id.kind) +
                          " is not FLUID_PLUGIN_FORCE (0) or FLUID_PLUGIN_BOUNDARY (1)"};
    }
    const bool force = id.kind == FLUID_PLUGIN_FORCE;
    const size_t count = force ? world.forces().size() : world.boundaries().size();
    const bool foreign = id.world != 0 && id.world != tagOf(world);
    if (foreign || id.index >= count) {
        throw Failure{FLUID_ERROR_STALE_ID,
                      std::string(function) + ": no " + (force ? "force" : "boundary") +
                          " plugin " + std::to_string(id.index) +
                          (foreign ? " of this world (the id is another world's)"
                                                    : " in this world (it has " +
                                                          std::to_string(count) + ")")};
    }
    return force ? static_cast<Plugin&>(*world.forces()[id.index])
                 : static_cast<Plugin&>(*world.boundaries()[id.index]);
}

} // namespace fluid::c

using namespace fluid;
using namespace fluid::c;

extern "C" {

// ---- Version and errors -------------------------------------------------------------------

uint32_t fluid_version(void) { return FLUID_C_VERSION; }

const char* fluid_last_error(void) { return t_lastError.c_str(); }

const char* fluid_status_name(fluid_status status) {
    // A C caller may pass any int; read it as one (in C++ an enum holding a value it does not
    // list may not be read as the enum).
    static_assert(sizeof(fluid_status) == sizeof(int));
    int code = 0;
    std::memcpy(&code, &status, sizeof code);
    switch (code) {
    case FLUID_OK: return "FLUID_OK";
    case FLUID_ERROR_INVALID_ARGUMENT: return "FLUID_ERROR_INVALID_ARGUMENT";
    case FLUID_ERROR_NULL_ARGUMENT: return "FLUID_ERROR_NULL_ARGUMENT";
    case FLUID_ERROR_STALE_ID: return "FLUID_ERROR_STALE_ID";
    case FLUID_ERROR_UNKNOWN_NAME: return "FLUID_ERROR_UNKNOWN_NAME";
    case FLUID_ERROR_BAD_FILE: return "FLUID_ERROR_BAD_FILE";
    case FLUID_ERROR_IO: return "FLUID_ERROR_IO";
    case FLUID_ERROR_LIMIT: return "FLUID_ERROR_LIMIT";
    case FLUID_ERROR_OUT_OF_MEMORY: return "FLUID_ERROR_OUT_OF_MEMORY";
    case FLUID_ERROR_REFUSED: return "FLUID_ERROR_REFUSED";
    }
    return "unknown status";
}

void fluid_bytes_free(fluid_bytes* bytes) {
    if (bytes != nullptr) {
        std::free(bytes->data);
        bytes->data = nullptr;
        bytes->size = 0;
    }
}

// ---- Worlds -------------------------------------------------------------------------------

fluid_world_def fluid_default_world_def(void) { return worldDefToC(WorldDef{}); }

fluid_status fluid_world_def_set_quality(fluid_world_def* def, const char* quality) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        need(def, "fluid_world_def_set_quality", "def");
        need(quality, "fluid_world_def_set_quality", "quality");
        const std::string_view name(quality);
        const std::optional<Quality> named = qualityFromName(name);
        if (!named) {
            throw Failure{FLUID_ERROR_UNKNOWN_NAME,
                          "fluid_world_def_set_quality: unknown quality " + internal::quoted(name) +
                              " (expected " + namesIn(kQualityNames) + ")"};
        }
        WorldDef cpp = worldDefOf(*def);
        cpp.positionBased = positionBasedPreset(*named);
        *def = worldDefToC(cpp);
    });
}

fluid_status fluid_world_def_set(fluid_world_def* def, const char* field, double value) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        need(def, "fluid_world_def_set", "def");
        need(field, "fluid_world_def_set", "field");
        WorldDef cpp = worldDefOf(*def);
        if (const auto* f = findField(worldFields(), field)) {
            setField(*f, cpp, value, "fluid_world_def_set");
        } else if (const auto* p = findField(positionBasedFields(), field)) {
            setField(*p, cpp.positionBased, value, "fluid_world_def_set");
        } else {
            throw Failure{FLUID_ERROR_UNKNOWN_NAME,
                          "fluid_world_def_set: unknown field " + internal::quoted(field) +
                              " (fields: " + fieldNames(worldFields(), positionBasedFields()) +
                              ")"};
        }
        *def = worldDefToC(cpp);
    });
}

fluid_status fluid_world_create(const fluid_world_def* def, fluid_world** world) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        need(def, "fluid_world_create", "def");
        need(world, "fluid_world_create", "world");
        auto made = std::make_unique<fluid_world>();
        made->owned = std::make_unique<World>(worldDefOf(*def));
        made->world = made->owned.get();
        *world = made.release();
    });
}

fluid_status fluid_world_destroy(fluid_world* world) {
    return guard(FLUID_ERROR_REFUSED, [&] {
        if (world != nullptr && world->owned != nullptr) {
            refuseWhileStepping(*world->world, "fluid_world_destroy");
            delete world;
        }
    });
}

fluid_status fluid_world_step(fluid_world* world, float frame_dt) {
    // A frame the C++ API refuses (outside (0, 1] s) is a bad argument (ErrorCode::OutOfRange);
    // anything else it refuses is the world's state (a plugin that threw, a host that must step
    // the world).
    const bool goodFrame = std::isfinite(frame_dt) && frame_dt > 0.0f && frame_dt <= 1.0f;
    return guard(goodFrame ? FLUID_ERROR_REFUSED : FLUID_ERROR_INVALID_ARGUMENT, [&] {
        World& w = worldOf(world, "fluid_world_step");
        if (goodFrame) {
            refusedStep([&] { w.step(frame_dt); });
        } else {
            w.step(frame_dt);
        }
    });
}

fluid_status fluid_world_set_position_based(fluid_world* world, const fluid_world_def* def) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        World& w = worldOf(world, "fluid_world_set_position_based");
        need(def, "fluid_world_set_position_based", "def");
        w.setPositionBased(worldDefOf(*def).positionBased);
    });
}

fluid_status fluid_world_time(const fluid_world* world, double* time) {
    return readWorld(world, "fluid_world_time", time, "time",
                     [&](const World& w) { return w.time(); });
}

fluid_status fluid_world_particle_count(const fluid_world* world, uint32_t* count) {
    return readWorld(world, "fluid_world_particle_count", count, "count",
                     [&](const World& w) { return w.particleCount(); });
}

fluid_status fluid_world_positions(const fluid_world* world, const float** x, const float** y,
                                   uint32_t* count) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        const World& w = worldOf(world, "fluid_world_positions");
        need(x, "fluid_world_positions", "x");
        need(y, "fluid_world_positions", "y");
        need(count, "fluid_world_positions", "count");
        *x = w.positionX().data();
        *y = w.positionY().data();
        *count = w.particleCount();
    });
}

fluid_status fluid_world_velocities(const fluid_world* world, const float** x, const float** y,
                                    uint32_t* count) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        const World& w = worldOf(world, "fluid_world_velocities");
        need(x, "fluid_world_velocities", "x");
        need(y, "fluid_world_velocities", "y");
        need(count, "fluid_world_velocities", "count");
        *x = w.velocityX().data();
        *y = w.velocityY().data();
        *count = w.particleCount();
    });
}

fluid_status fluid_world_densities(const fluid_world* world, const float** density,
                                   uint32_t* count) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        const World& w = worldOf(world, "fluid_world_densities");
        need(density, "fluid_world_densities", "density");
        need(count, "fluid_world_densities", "count");
        *density = w.density().data();
        *count = w.particleCount();
    });
}

fluid_status fluid_world_pressures(const fluid_world* world, const float** pressure,
                                   uint32_t* count) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        const World& w = worldOf(world, "fluid_world_pressures");
        need(pressure, "fluid_world_pressures", "pressure");
        need(count, "fluid_world_pressures", "count");
        *pressure = w.pressure().data();
        *count = w.particleCount();
    });
}

fluid_status fluid_world_material_indices(const fluid_world* world, const uint16_t** material,
                                          uint32_t* count) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        const World& w = worldOf(world, "fluid_world_material_indices");
        need(material, "fluid_world_material_indices", "material");
        need(count, "fluid_world_material_indices", "count");
        *material = w.materialIndex().data();
        *count = w.particleCount();
    });
}

fluid_status fluid_world_save(const fluid_world* world, fluid_bytes* bytes) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        const World& w = worldOf(world, "fluid_world_save");
        need(bytes, "fluid_world_save", "bytes");
        std::ostringstream out(std::ios::binary);
        w.save(out);
        *bytes = toBytes(out.str());
    });
}

fluid_status fluid_world_load(const void* data, size_t size, uint32_t worker_count,
                              fluid_world** world) {
    return guard(FLUID_ERROR_BAD_FILE, [&] {
        need(world, "fluid_world_load", "world");
        if (worker_count > 256) {
            throw Failure{FLUID_ERROR_INVALID_ARGUMENT,
                          "fluid_world_load: worker_count = " + std::to_string(worker_count) +
                              " is out of range; expected 0 (as saved) or [1, 256]"};
        }
        if (size > 0) {
            need(data, "fluid_world_load", "data");
        }
        std::istringstream in(std::string(static_cast<const char*>(data), size),
                              std::ios::binary);
        auto made = std::make_unique<fluid_world>();
        made->owned = std::make_unique<World>(World::load(in, registry(), worker_count));
        made->world = made->owned.get();
        *world = made.release();
    });
}

// ---- Materials ----------------------------------------------------------------------------

fluid_material_def fluid_default_material_def(void) { return presetToC(water(), "water"); }

fluid_status fluid_material_preset(const char* preset, fluid_material_def* def) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        need(preset, "fluid_material_preset", "preset");
        need(def, "fluid_material_preset", "def");
        const std::string_view name(preset);
        if (name == "water") {
            *def = presetToC(water(), "water");
        } else if (name == "yoghurt") {
            *def = presetToC(yoghurt(), "yoghurt");
        } else if (name == "seed_yoghurt") {
            *def = presetToC(seedYoghurt(), "seed_yoghurt");
        } else {
            throw Failure{FLUID_ERROR_UNKNOWN_NAME,
                          "fluid_material_preset: unknown preset " + internal::quoted(name) +
                              " (expected water, yoghurt or seed_yoghurt)"};
        }
    });
}

fluid_status fluid_material_def_set(fluid_material_def* def, const char* field, double value) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        need(def, "fluid_material_def_set", "def");
        need(field, "fluid_material_def_set", "field");
        const auto* f = findField(materialFields(), field);
        if (f == nullptr) {
            throw Failure{FLUID_ERROR_UNKNOWN_NAME,
                          "fluid_material_def_set: unknown field " + internal::quoted(field) +
                              " (fields: " + fieldNames(materialFields()) + ")"};
        }
        const char* name = def->name;
        Material m = materialOf(*def);
        setField(*f, m, value, "fluid_material_def_set");
        *def = materialToC(m);
        def->name = name;
    });
}

fluid_status fluid_world_add_material(fluid_world* world, const fluid_material_def* def,
                                      fluid_material_id* id) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        World& w = worldOf(world, "fluid_world_add_material");
        need(def, "fluid_world_add_material", "def");
        need(id, "fluid_world_add_material", "id");
        const Material material = materialOf(*def);
        *id = fluid::c::toC(w.addMaterial(material));
    });
}

fluid_status fluid_world_set_material(fluid_world* world, fluid_material_id id,
                                      const fluid_material_def* def) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        World& w = worldOf(world, "fluid_world_set_material");
        need(def, "fluid_world_set_material", "def");
        checkMaterial(w, id);
        w.setMaterial(toCpp(id), materialOf(*def));
    });
}

fluid_status fluid_world_get_material(const fluid_world* world, fluid_material_id id,
                                      fluid_material_def* def) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        const World& w = worldOf(world, "fluid_world_get_material");
        need(def, "fluid_world_get_material", "def");
        checkMaterial(w, id);
        const Material& m = w.material(toCpp(id));
        *def = materialToC(m);
        def->name = stableName(*world, id.index, m.name);
    });
}

fluid_status fluid_world_spacing(const fluid_world* world, fluid_material_id id,
                                 float* spacing) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        const World& w = worldOf(world, "fluid_world_spacing");
        need(spacing, "fluid_world_spacing", "spacing");
        checkMaterial(w, id);
        *spacing = w.spacing(toCpp(id));
    });
}

fluid_status fluid_world_material_count(const fluid_world* world, uint32_t* count) {
    return readWorld(world, "fluid_world_material_count", count, "count",
                     [&](const World& w) { return w.materialCount(); });
}

// ---- Particles and blobs ------------------------------------------------------------------

fluid_shape fluid_box_shape(fluid_vec2 min, fluid_vec2 max) {
    fluid_shape s{};
    s.type = FLUID_SHAPE_BOX;
    s.center = {0.5f * (min.x + max.x), 0.5f * (min.y + max.y)};
    s.half_extents = {0.5f * (max.x - min.x), 0.5f * (max.y - min.y)};
    return s;
}

fluid_shape fluid_circle_shape(fluid_vec2 center, float radius) {
    fluid_shape s{};
    s.type = FLUID_SHAPE_CIRCLE;
    s.center = center;
    s.radius = radius;
    return s;
}

fluid_shape fluid_polygon_shape(const fluid_vec2* vertices, uint32_t count) {
    fluid_shape s{};
    s.type = FLUID_SHAPE_POLYGON;
    s.vertices = vertices;
    s.vertex_count = count;
    return s;
}

fluid_blob_def fluid_default_blob_def(void) {
    fluid_blob_def d{};
    const BlobDef blob;
    d.shape = fluid_box_shape({blob.shape.center.x - blob.shape.halfExtents.x,
                               blob.shape.center.y - blob.shape.halfExtents.y},
                              {blob.shape.center.x + blob.shape.halfExtents.x,
                               blob.shape.center.y + blob.shape.halfExtents.y});
    d.velocity = fluid::c::toC(blob.velocity);
    d.material = {blob.material.index, 0};
    d.lifetime = blob.lifetime;
    d.structure = blob.structure;
    return d;
}

namespace {

fluid_status spawnBlob(fluid_world* world, const fluid_blob_def* def, float latticeAngle,
                       uint32_t* spawned, const char* function) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        World& w = worldOf(world, function);
        need(def, function, "def");
        checkMaterial(w, def->material);
        BlobDef blob;
        blob.shape = toCpp(def->shape, function);
        blob.velocity = toVec(def->velocity);
        blob.material = toCpp(def->material);
        blob.lifetime = def->lifetime;
        blob.structure = def->structure;
        blob.latticeAngle = latticeAngle;
        const uint32_t made = w.spawnBlob(blob);
        if (spawned != nullptr) {
            *spawned = made;
        }
    });
}

} // namespace

fluid_status fluid_world_spawn_blob(fluid_world* world, const fluid_blob_def* def,
                                    uint32_t* spawned) {
    return spawnBlob(world, def, 0.0f, spawned, "fluid_world_spawn_blob");
}

fluid_status fluid_world_spawn_blob_turned(fluid_world* world, const fluid_blob_def* def,
                                           float lattice_angle, uint32_t* spawned) {
    return spawnBlob(world, def, lattice_angle, spawned, "fluid_world_spawn_blob_turned");
}

fluid_status fluid_world_add_particle(fluid_world* world, fluid_vec2 position,
                                      fluid_vec2 velocity, fluid_material_id material,
                                      fluid_particle_id* id) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        World& w = worldOf(world, "fluid_world_add_particle");
        need(id, "fluid_world_add_particle", "id");
        checkMaterial(w, material);
        ParticleHandle h;
        h = w.addParticle(toVec(position), toVec(velocity), toCpp(material));
        *id = fluid::c::toC(h);
    });
}

fluid_status fluid_world_remove_particle(fluid_world* world, fluid_particle_id id) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        World& w = worldOf(world, "fluid_world_remove_particle");
        const ParticleHandle h = toCpp(id);
        checkParticle(w, h, [&] { w.removeParticle(h); });
        w.removeParticle(h);
    });
}

fluid_status fluid_world_particle_valid(const fluid_world* world, fluid_particle_id id,
                                        bool* valid) {
    return readWorld(world, "fluid_world_particle_valid", valid, "valid",
                     [&](const World& w) { return w.isValid(toCpp(id)); });
}

fluid_status fluid_world_particle_position(const fluid_world* world, fluid_particle_id id,
                                           fluid_vec2* position) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        const World& w = worldOf(world, "fluid_world_particle_position");
        need(position, "fluid_world_particle_position", "position");
        const ParticleHandle h = toCpp(id);
        checkParticle(w, h, [&] { (void)w.position(h); });
        *position = fluid::c::toC(w.position(h));
    });
}

fluid_status fluid_world_particle_velocity(const fluid_world* world, fluid_particle_id id,
                                           fluid_vec2* velocity) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        const World& w = worldOf(world, "fluid_world_particle_velocity");
        need(velocity, "fluid_world_particle_velocity", "velocity");
        const ParticleHandle h = toCpp(id);
        checkParticle(w, h, [&] { (void)w.velocity(h); });
        *velocity = fluid::c::toC(w.velocity(h));
    });
}

fluid_status fluid_world_set_particle_velocity(fluid_world* world, fluid_particle_id id,
                                               fluid_vec2 velocity) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        World& w = worldOf(world, "fluid_world_set_particle_velocity");
        const ParticleHandle h = toCpp(id);
        checkParticle(w, h, [&] { w.setVelocity(h, toVec(velocity)); });
        w.setVelocity(h, toVec(velocity));
    });
}

fluid_status fluid_world_particle_at(const fluid_world* world, uint32_t index,
                                     fluid_particle_id* id) {
    return readWorld(world, "fluid_world_particle_at", id, "id",
                     [&](const World& w) { return fluid::c::toC(w.handleAt(index)); });
}

// ---- Emitters, drains, sensors, events ----------------------------------------------------

fluid_emitter_def fluid_default_emitter_def(void) {
    const EmitterDef e;
    fluid_emitter_def d{};
    d.position = fluid::c::toC(e.position);
    d.direction = fluid::c::toC(e.direction);
    d.speed = e.speed;
    d.width = e.width;
    d.rate = e.rate;
    d.material = {e.material.index, 0};
    d.max_count = e.maxCount;
    d.lifetime = e.lifetime;
    d.jitter = e.jitter;
    d.seed = e.seed;
    return d;
}

fluid_status fluid_world_add_emitter(fluid_world* world, const fluid_emitter_def* def,
                                     fluid_emitter_id* id) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        World& w = worldOf(world, "fluid_world_add_emitter");
        need(def, "fluid_world_add_emitter", "def");
        need(id, "fluid_world_add_emitter", "id");
        checkMaterial(w, def->material);
        const EmitterId e = w.addEmitter(emitterOf(*def));
        *id = {e.index, e.world};
    });
}

fluid_status fluid_world_set_emitter(fluid_world* world, fluid_emitter_id id,
                                     const fluid_emitter_def* def) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        World& w = worldOf(world, "fluid_world_set_emitter");
        need(def, "fluid_world_set_emitter", "def");
        checkMaterial(w, def->material);
        const EmitterDef cpp = emitterOf(*def);
        w.setEmitter(toCpp(id), cpp);
    });
}

fluid_status fluid_world_emitted_count(const fluid_world* world, fluid_emitter_id id,
                                       uint32_t* count) {
    return readWorld(world, "fluid_world_emitted_count", count, "count",
                     [&](const World& w) { return w.emittedCount(toCpp(id)); });
}

fluid_status fluid_world_add_drain(fluid_world* world, const fluid_drain_def* def,
                                   fluid_drain_id* id) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        World& w = worldOf(world, "fluid_world_add_drain");
        need(def, "fluid_world_add_drain", "def");
        need(id, "fluid_world_add_drain", "id");
        if (def->only_material) {
            checkMaterial(w, def->material);
        }
        DrainDef drain;
        drain.shape = toCpp(def->shape, "fluid_world_add_drain");
        drain.onlyMaterial = def->only_material;
        drain.material = toCpp(def->material);
        const DrainId d = w.addDrain(drain);
        *id = {d.index, d.world};
    });
}

fluid_status fluid_world_add_sensor(fluid_world* world, fluid_shape shape, fluid_sensor_id* id) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        World& w = worldOf(world, "fluid_world_add_sensor");
        need(id, "fluid_world_add_sensor", "id");
        SensorDef sensor;
        sensor.shape = toCpp(shape, "fluid_world_add_sensor");
        const SensorId s = w.addSensor(sensor);
        *id = {s.index, s.world};
    });
}

fluid_status fluid_world_sensor_readings(const fluid_world* world, fluid_sensor_id id,
                                         const fluid_sensor_reading** readings,
                                         uint32_t* count) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        const World& w = worldOf(world, "fluid_world_sensor_readings");
        need(readings, "fluid_world_sensor_readings", "readings");
        need(count, "fluid_world_sensor_readings", "count");
        const std::span<const SensorReading> r = w.sensorReading(toCpp(id));
        if (world->readings.size() <= id.index) {
            world->readings.resize(size_t(id.index) + 1);
        }
        std::vector<fluid_sensor_reading>& copy = world->readings[id.index];
        copy.resize(r.size());
        for (size_t m = 0; m < r.size(); ++m) {
            copy[m] = {r[m].count, r[m].mass, r[m].area, r[m].volume};
        }
        *readings = copy.data();
        *count = uint32_t(r.size());
    });
}

fluid_status fluid_world_removed_events(const fluid_world* world,
                                        const fluid_removed_event** events, uint32_t* count) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        const World& w = worldOf(world, "fluid_world_removed_events");
        need(events, "fluid_world_removed_events", "events");
        need(count, "fluid_world_removed_events", "count");
        const std::span<const RemovedEvent> removed = w.removedEvents();
        world->removed.resize(removed.size());
        for (size_t i = 0; i < removed.size(); ++i) {
            const RemovedEvent& e = removed[i];
            fluid_removed_event& out = world->removed[i];
            out.particle = fluid::c::toC(e.particle);
            out.position = fluid::c::toC(e.position);
            out.velocity = fluid::c::toC(e.velocity);
            out.material = fluid::c::toC(e.material);
            out.cause = e.cause == RemovalCause::Drain      ? FLUID_REMOVED_BY_DRAIN
                        : e.cause == RemovalCause::Lifetime ? FLUID_REMOVED_BY_LIFETIME
                                                            : FLUID_REMOVED_OUT_OF_RANGE;
            out.drain = {e.drain.index, e.drain.world};
        }
        *events = world->removed.data();
        *count = uint32_t(removed.size());
    });
}

// ---- Plugins by name ----------------------------------------------------------------------

fluid_status fluid_world_add_plugin(fluid_world* world, const char* type,
                                    const fluid_param* params, uint32_t param_count,
                                    fluid_plugin_id* id) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        World& w = worldOf(world, "fluid_world_add_plugin");
        need(type, "fluid_world_add_plugin", "type");
        need(id, "fluid_world_add_plugin", "id");
        if (param_count > 0) {
            need(params, "fluid_world_add_plugin", "params");
        }
        std::vector<ParamValue> values;
        values.reserve(param_count);
        for (uint32_t i = 0; i < param_count; ++i) {
            need(params[i].name, "fluid_world_add_plugin", "a parameter's name");
            values.emplace_back(params[i].name, params[i].value);
        }
        // An unknown type or parameter: the registry's own error (ErrorCode::UnknownName).
        std::unique_ptr<Plugin> plugin = registry().create(type, values);
        if (plugin->kind() == PluginKind::Force) {
            std::unique_ptr<ForcePlugin> force(static_cast<ForcePlugin*>(plugin.release()));
            w.addForce(std::move(force));
            *id = {uint32_t(w.forces().size() - 1), FLUID_PLUGIN_FORCE, tagOf(w)};
        } else {
            std::unique_ptr<BoundaryPlugin> boundary(
                static_cast<BoundaryPlugin*>(plugin.release()));
            w.addBoundary(std::move(boundary));
            *id = {uint32_t(w.boundaries().size() - 1), FLUID_PLUGIN_BOUNDARY, tagOf(w)};
        }
    });
}

fluid_status fluid_plugin_set_param(fluid_world* world, fluid_plugin_id id, const char* name,
                                    double value) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        World& w = worldOf(world, "fluid_plugin_set_param");
        need(name, "fluid_plugin_set_param", "name");
        Plugin& plugin = pluginOf(w, id, "fluid_plugin_set_param");
        plugin.setParam(name, value);
    });
}

fluid_status fluid_plugin_get_param(const fluid_world* world, fluid_plugin_id id,
                                    const char* name, double* value) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        need(world, "fluid_plugin_get_param", "world");
        need(name, "fluid_plugin_get_param", "name");
        need(value, "fluid_plugin_get_param", "value");
        const Plugin& plugin = pluginOf(*world->world, id, "fluid_plugin_get_param");
        *value = plugin.param(name);
    });
}

fluid_status fluid_plugin_set_points(fluid_world* world, fluid_plugin_id id, const char* name,
                                     const fluid_vec2* points, uint32_t count) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        World& w = worldOf(world, "fluid_plugin_set_points");
        need(name, "fluid_plugin_set_points", "name");
        if (count > 0) {
            need(points, "fluid_plugin_set_points", "points");
        }
        Plugin& plugin = pluginOf(w, id, "fluid_plugin_set_points");
        std::vector<glm::vec2> copy(count);
        for (uint32_t i = 0; i < count; ++i) {
            copy[i] = toVec(points[i]);
        }
        plugin.setPoints(name, copy);
    });
}

fluid_status fluid_plugin_type(const fluid_world* world, fluid_plugin_id id, const char** type) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        need(world, "fluid_plugin_type", "world");
        need(type, "fluid_plugin_type", "type");
        const Plugin& plugin = pluginOf(*world->world, id, "fluid_plugin_type");
        *type = plugin.type().data(); // a std::string's: NUL-terminated
    });
}

fluid_status fluid_world_plugin_count(const fluid_world* world, fluid_plugin_kind kind,
                                      uint32_t* count) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        const World& w = worldOf(world, "fluid_world_plugin_count");
        need(count, "fluid_world_plugin_count", "count");
        if (kind != FLUID_PLUGIN_FORCE && kind != FLUID_PLUGIN_BOUNDARY) {
            throw Failure{FLUID_ERROR_INVALID_ARGUMENT,
                          "fluid_world_plugin_count: kind " + std::to_string(int(kind)) +
                              " is not FLUID_PLUGIN_FORCE (0) or FLUID_PLUGIN_BOUNDARY (1)"};
        }
        *count = uint32_t(kind == FLUID_PLUGIN_FORCE ? w.forces().size() : w.boundaries().size());
    });
}

} // extern "C"
