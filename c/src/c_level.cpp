// fluid::c — levels (fluid/c.h): fluid::Level behind an opaque handle.
#include "c_internal.h"

#include <fluid/box2d/coupling.h>
#include <fluid/box2d/shapes.h>
#include <fluid/internal/checks.h>

#include <box2d/box2d.h>

#include <cmath>

#include <sstream>

/// The C API's level: the C++ level and the world handle that lends out its world.
struct fluid_level {
    /// The level.
    fluid::Level level;
    /// fluid_level_world's handle (not owning).
    fluid_world world;
    /// The bodies fluid_level_add_body added, after the file's in fluid_level_body's indices.
    std::vector<b2Body*> added;
};

namespace fluid::c {

namespace {

LevelOptions toCpp(const fluid_level_options* options) {
    LevelOptions o;
    if (options != nullptr) {
        o.workerCount = options->worker_count;
        o.maxParticles = options->max_particles;
    }
    return o;
}

void wrap(Level&& loaded, fluid_level** out) {
    auto made = std::make_unique<fluid_level>();
    made->level = std::move(loaded);
    made->world.world = &made->level.world;
    *out = made.release();
}

const Level& levelOf(const fluid_level* level, const char* function) {
    need(level, function, "level");
    return level->level;
}

// The id of the entry called `name` in one of the level's name lists.
template <class Id>
Id findNamed(const std::vector<std::pair<std::string, Id>>& entries, const char* name,
             const char* what, const char* function) {
    need(name, function, "name");
    for (const auto& [entryName, id] : entries) {
        if (entryName == name) {
            return id;
        }
    }
    throw Failure{FLUID_ERROR_UNKNOWN_NAME, std::string(function) + ": the level has no " + what +
                                                " named " + internal::quoted(name)};
}

// fluid_level_find_material, _emitter, _drain, _sensor: the id of the object named `name` in
// the level's list `entries`, written to `*id` as `toId` converts it.
template <class CId, class Id, class ToId>
fluid_status findInLevel(const fluid_level* level, const char* name, CId* id,
                         std::vector<std::pair<std::string, Id>> Level::*entries, const char* what,
                         const char* function, ToId&& toId) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        const Level& l = levelOf(level, function);
        need(id, function, "id");
        *id = toId(findNamed(l.*entries, name, what, function));
    });
}

// Body `index` of fluid_level_body's list: the file's bodies, then the added ones.
b2Body* bodyAt(const fluid_level& level, uint32_t index, const char* function,
               const char** name = nullptr) {
    const auto& named = level.level.bodies;
    if (index < named.size()) {
        if (name != nullptr) {
            *name = named[index].first.c_str();
        }
        return named[index].second;
    }
    if (index - named.size() < level.added.size()) {
        if (name != nullptr) {
            *name = "";
        }
        return level.added[index - named.size()];
    }
    throw Failure{FLUID_ERROR_STALE_ID,
                  std::string(function) + ": index " + std::to_string(index) +
                      " is past the level's " +
                      std::to_string(named.size() + level.added.size()) + " bodies"};
}

bool finite(fluid_vec2 v) { return std::isfinite(v.x) && std::isfinite(v.y); }

} // namespace

} // namespace fluid::c

using namespace fluid;
using namespace fluid::c;

extern "C" {

fluid_level_options fluid_default_level_options(void) { return fluid_level_options{0, 0}; }

fluid_status fluid_level_load(const char* path, const fluid_level_options* options,
                              fluid_level** level) {
    return guard(FLUID_ERROR_BAD_FILE, [&] {
        need(path, "fluid_level_load", "path");
        need(level, "fluid_level_load", "level");
        wrap(loadLevel(path, registry(), toCpp(options)), level);
    });
}

fluid_status fluid_level_parse(const char* text, size_t size, const char* file,
                               const fluid_level_options* options, fluid_level** level) {
    return guard(FLUID_ERROR_BAD_FILE, [&] {
        if (size > 0) {
            need(text, "fluid_level_parse", "text");
        }
        need(file, "fluid_level_parse", "file");
        need(level, "fluid_level_parse", "level");
        wrap(parseLevel(std::string_view(text, size), file, registry(), toCpp(options)), level);
    });
}

fluid_status fluid_level_load_save(const char* path, const fluid_level_options* options,
                                   fluid_level** level) {
    return guard(FLUID_ERROR_BAD_FILE, [&] {
        need(path, "fluid_level_load_save", "path");
        need(level, "fluid_level_load_save", "level");
        wrap(loadLevelSave(path, registry(), toCpp(options)), level);
    });
}

fluid_status fluid_level_read_save(const void* data, size_t size, const char* file,
                                   const fluid_level_options* options, fluid_level** level) {
    return guard(FLUID_ERROR_BAD_FILE, [&] {
        if (size > 0) {
            need(data, "fluid_level_read_save", "data");
        }
        need(file, "fluid_level_read_save", "file");
        need(level, "fluid_level_read_save", "level");
        std::istringstream in(std::string(static_cast<const char*>(data), size),
                              std::ios::binary);
        wrap(readLevelSave(in, file, registry(), toCpp(options)), level);
    });
}

fluid_status fluid_level_destroy(fluid_level* level) {
    return guard(FLUID_ERROR_REFUSED, [&] {
        if (level != nullptr) {
            refuseWhileStepping(level->level.world, "fluid_level_destroy");
            delete level;
        }
    });
}

fluid_status fluid_level_step(fluid_level* level) {
    return guard(FLUID_ERROR_REFUSED, [&] {
        need(level, "fluid_level_step", "level");
        refusedStep([&] { level->level.step(); });
    });
}

fluid_status fluid_level_world(fluid_level* level, fluid_world** world) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        need(level, "fluid_level_world", "level");
        need(world, "fluid_level_world", "world");
        *world = &level->world;
    });
}

fluid_status fluid_level_frame_rate(const fluid_level* level, float* rate) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        const Level& l = levelOf(level, "fluid_level_frame_rate");
        need(rate, "fluid_level_frame_rate", "rate");
        *rate = l.frameRate;
    });
}

fluid_status fluid_level_save(const fluid_level* level, const char* path) {
    return guard(FLUID_ERROR_IO, [&] {
        const Level& l = levelOf(level, "fluid_level_save");
        need(path, "fluid_level_save", "path");
        l.saveFile(path);
    });
}

fluid_status fluid_level_save_bytes(const fluid_level* level, fluid_bytes* bytes) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        const Level& l = levelOf(level, "fluid_level_save_bytes");
        need(bytes, "fluid_level_save_bytes", "bytes");
        std::ostringstream out(std::ios::binary);
        l.save(out);
        *bytes = toBytes(out.str());
    });
}

fluid_status fluid_level_goal(const fluid_level* level, fluid_goal_state* state, double* value) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        const Level& l = levelOf(level, "fluid_level_goal");
        need(state, "fluid_level_goal", "state");
        need(value, "fluid_level_goal", "value");
        switch (l.goalState()) {
        case GoalState::None: *state = FLUID_GOAL_NONE; break;
        case GoalState::Pending: *state = FLUID_GOAL_PENDING; break;
        case GoalState::Won: *state = FLUID_GOAL_WON; break;
        case GoalState::Lost: *state = FLUID_GOAL_LOST; break;
        }
        *value = l.goalValue();
    });
}

fluid_status fluid_level_find_material(const fluid_level* level, const char* name,
                                       fluid_material_id* id) {
    return findInLevel(level, name, id, &Level::materials, "material", "fluid_level_find_material",
                       [](MaterialId m) { return fluid::c::toC(m); });
}

fluid_status fluid_level_find_emitter(const fluid_level* level, const char* name,
                                      fluid_emitter_id* id) {
    return findInLevel(level, name, id, &Level::emitters, "emitter", "fluid_level_find_emitter",
                       [](EmitterId e) { return fluid_emitter_id{e.index, e.world}; });
}

fluid_status fluid_level_find_drain(const fluid_level* level, const char* name,
                                    fluid_drain_id* id) {
    return findInLevel(level, name, id, &Level::drains, "drain", "fluid_level_find_drain",
                       [](DrainId d) { return fluid_drain_id{d.index, d.world}; });
}

fluid_status fluid_level_find_sensor(const fluid_level* level, const char* name,
                                     fluid_sensor_id* id) {
    return findInLevel(level, name, id, &Level::sensors, "sensor", "fluid_level_find_sensor",
                       [](SensorId s) { return fluid_sensor_id{s.index, s.world}; });
}

fluid_status fluid_level_find_plugin(const fluid_level* level, const char* name,
                                     fluid_plugin_id* id) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        const Level& l = levelOf(level, "fluid_level_find_plugin");
        need(name, "fluid_level_find_plugin", "name");
        need(id, "fluid_level_find_plugin", "id");
        for (const Level::PluginEntry& entry : l.plugins) {
            if (entry.name == name) {
                *id = {entry.index,
                       entry.kind == PluginKind::Force ? uint32_t(FLUID_PLUGIN_FORCE)
                                                       : uint32_t(FLUID_PLUGIN_BOUNDARY),
                       tagOf(l.world)};
                return;
            }
        }
        throw Failure{FLUID_ERROR_UNKNOWN_NAME,
                      "fluid_level_find_plugin: the level has no plugin named " +
                          internal::quoted(name)};
    });
}

fluid_status fluid_level_body_count(const fluid_level* level, uint32_t* count) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        const Level& l = levelOf(level, "fluid_level_body_count");
        need(count, "fluid_level_body_count", "count");
        *count = uint32_t(l.bodies.size() + level->added.size());
    });
}

fluid_status fluid_level_body(const fluid_level* level, uint32_t index, const char** name,
                              fluid_vec2* position, float* angle) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        need(level, "fluid_level_body", "level");
        const b2Body* body = bodyAt(*level, index, "fluid_level_body", name);
        if (position != nullptr) {
            *position = {body->GetPosition().x, body->GetPosition().y};
        }
        if (angle != nullptr) {
            *angle = body->GetAngle();
        }
    });
}

fluid_status fluid_level_set_gravity(fluid_level* level, fluid_vec2 gravity) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        need(level, "fluid_level_set_gravity", "level");
        if (!finite(gravity)) {
            throw Failure{FLUID_ERROR_INVALID_ARGUMENT,
                          "fluid_level_set_gravity: gravity must be finite"};
        }
        Level& l = level->level;
        // Checked on every plugin first, so that a refusal changes nothing.
        for (const auto& force : l.world.forces()) {
            if (force->type() == GravityForce::kType) {
                GravityForce probe;
                probe.setParam("gx", gravity.x);
                probe.setParam("gy", gravity.y);
            }
        }
        for (const auto& force : l.world.forces()) {
            if (force->type() == GravityForce::kType) {
                force->setParam("gx", gravity.x);
                force->setParam("gy", gravity.y);
            }
        }
        if (l.physics != nullptr) {
            l.physics->SetGravity({gravity.x, gravity.y});
            for (b2Body* body = l.physics->GetBodyList(); body != nullptr;
                 body = body->GetNext()) {
                body->SetAwake(true);
            }
        }
    });
}

fluid_body_def fluid_default_body_def(void) {
    fluid_body_def def{};
    def.type = FLUID_BODY_DYNAMIC;
    def.shape = fluid_box_shape({-0.05f, -0.05f}, {0.05f, 0.05f});
    def.friction = 0.4f;
    return def;
}

fluid_status fluid_level_areal_density(const fluid_level* level, fluid_material_id material,
                                       float* density) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        const Level& l = levelOf(level, "fluid_level_areal_density");
        need(density, "fluid_level_areal_density", "density");
        try {
            (void)l.world.material(toCpp(material)); // the world's id rule
        } catch (const Error& e) {
            if (e.code() != ErrorCode::StaleId) {
                throw;
            }
            throw Failure{FLUID_ERROR_STALE_ID,
                          "fluid_level_areal_density: no material " +
                              std::to_string(material.index) + " in the level's world"};
        }
        *density = box2d::arealDensity(l.world, toCpp(material));
    });
}

fluid_status fluid_level_add_body(fluid_level* level, const fluid_body_def* def,
                                  uint32_t* index) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        const char* const function = "fluid_level_add_body";
        need(level, function, "level");
        need(def, function, "def");
        Level& l = level->level;
        if (l.physics == nullptr) {
            throw Failure{FLUID_ERROR_REFUSED,
                          std::string(function) + ": the level declares no bodies, so its world "
                                                  "has no Box2D world to add one to"};
        }
        auto bad = [&](const std::string& what) {
            throw Failure{FLUID_ERROR_INVALID_ARGUMENT, std::string(function) + ": " + what};
        };
        if (def->type != FLUID_BODY_STATIC && def->type != FLUID_BODY_KINEMATIC &&
            def->type != FLUID_BODY_DYNAMIC) {
            bad("type " + std::to_string(def->type) +
                " is not FLUID_BODY_STATIC, FLUID_BODY_KINEMATIC or FLUID_BODY_DYNAMIC");
        }
        if (!std::isfinite(def->angle) || !finite(def->velocity) ||
            !std::isfinite(def->angular_velocity) || !finite(def->position)) {
            bad("position, angle and velocities must be finite");
        }
        if (!(def->friction >= 0.0f) || !std::isfinite(def->friction)) {
            bad("friction must be finite and >= 0");
        }
        if (!std::isfinite(def->density) ||
            !(def->type == FLUID_BODY_DYNAMIC ? def->density > 0.0f : def->density >= 0.0f)) {
            bad("density must be finite and > 0 for a dynamic body (>= 0 otherwise), kg/m^2");
        }
        const fluid_shape& shape = def->shape;
        b2PolygonShape polygon;
        b2CircleShape circle;
        b2Vec2 position{def->position.x, def->position.y};
        const b2Shape* fixtureShape = nullptr;
        // The checks a level file's bodies pass (fluid/box2d/shapes.h), before Box2D sees the
        // shape: Box2D asserts on degenerate ones.
        const bool dynamic = def->type == FLUID_BODY_DYNAMIC;
        const auto check = [&](const box2d::ShapeProblem& problem) {
            if (problem) {
                bad(problem.message);
            }
        };
        if (shape.type == FLUID_SHAPE_BOX) {
            if (!finite(shape.center) || !finite(shape.half_extents)) {
                bad("a box needs a finite center and half extents");
            }
            check(box2d::checkBox(2.0f * shape.half_extents.x, 2.0f * shape.half_extents.y));
            polygon.SetAsBox(shape.half_extents.x, shape.half_extents.y);
            position = {shape.center.x, shape.center.y};
            fixtureShape = &polygon;
        } else if (shape.type == FLUID_SHAPE_CIRCLE) {
            if (!finite(shape.center)) {
                bad("a circle needs a finite center");
            }
            check(box2d::checkCircle(shape.radius));
            circle.m_radius = shape.radius;
            position = {shape.center.x, shape.center.y};
            fixtureShape = &circle;
        } else if (shape.type == FLUID_SHAPE_POLYGON) {
            if (shape.vertex_count < 3 || shape.vertex_count > uint32_t(b2_maxPolygonVertices)) {
                bad("a polygon body needs 3 to " + std::to_string(b2_maxPolygonVertices) +
                    " vertices, not " + std::to_string(shape.vertex_count));
            }
            need(shape.vertices, function, "shape.vertices");
            std::vector<glm::vec2> points;
            for (uint32_t i = 0; i < shape.vertex_count; ++i) {
                points.emplace_back(shape.vertices[i].x, shape.vertices[i].y);
            }
            check(box2d::checkPolygon(points, dynamic ? box2d::coarsestSpacing(l.world) : 0.0f));
            std::vector<b2Vec2> b2points;
            for (const glm::vec2 p : points) {
                b2points.emplace_back(p.x, p.y);
            }
            polygon.Set(b2points.data(), int32(b2points.size()));
            if (polygon.m_count != int32(b2points.size())) {
                bad("Box2D made a polygon of " + std::to_string(polygon.m_count) +
                    " vertices from " + std::to_string(b2points.size()));
            }
            fixtureShape = &polygon;
        } else {
            bad("shape type " + std::to_string(shape.type) +
                " is not FLUID_SHAPE_BOX, FLUID_SHAPE_CIRCLE or FLUID_SHAPE_POLYGON");
        }
        if (dynamic) {
            // The mass floors (shapes.h): refused here, not at every later step.
            b2MassData data;
            fixtureShape->ComputeMass(&data, def->density);
            b2MassData unit;
            fixtureShape->ComputeMass(&unit, 1.0f);
            const float centred = data.I - data.mass * b2Dot(data.center, data.center);
            check(box2d::checkDynamicMass(data.mass, unit.mass, centred, false,
                                          box2d::densestArealDensity(l.world)));
        }
        if (!(std::fabs(position.x) <= 1e5f && std::fabs(position.y) <= 1e5f)) {
            bad("the body's position must lie within 1e5 m of the origin");
        }
        b2BodyDef bodyDef;
        bodyDef.type = def->type == FLUID_BODY_STATIC      ? b2_staticBody
                       : def->type == FLUID_BODY_KINEMATIC ? b2_kinematicBody
                                                           : b2_dynamicBody;
        bodyDef.position = position;
        bodyDef.angle = def->angle;
        bodyDef.linearVelocity = {def->velocity.x, def->velocity.y};
        bodyDef.angularVelocity = def->angular_velocity;
        b2Body* body = l.physics->CreateBody(&bodyDef);
        b2FixtureDef fixture;
        fixture.shape = fixtureShape;
        fixture.density = def->density;
        fixture.friction = def->friction;
        body->CreateFixture(&fixture);
        level->added.push_back(body);
        if (index != nullptr) {
            *index = uint32_t(l.bodies.size() + level->added.size() - 1);
        }
    });
}

fluid_status fluid_level_remove_body(fluid_level* level, uint32_t index) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        need(level, "fluid_level_remove_body", "level");
        b2Body* body = bodyAt(*level, index, "fluid_level_remove_body");
        level->level.destroyBody(body);
        std::erase(level->added, body);
    });
}

fluid_status fluid_level_set_body_velocity(fluid_level* level, uint32_t index,
                                           fluid_vec2 velocity, float angular_velocity) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        need(level, "fluid_level_set_body_velocity", "level");
        b2Body* body = bodyAt(*level, index, "fluid_level_set_body_velocity");
        if (!finite(velocity) || !std::isfinite(angular_velocity)) {
            throw Failure{FLUID_ERROR_INVALID_ARGUMENT,
                          "fluid_level_set_body_velocity: the velocities must be finite"};
        }
        body->SetLinearVelocity({velocity.x, velocity.y});
        body->SetAngularVelocity(angular_velocity);
        body->SetAwake(true);
    });
}

} // extern "C"

// ---- The level behind its handle, for c_contacts.cpp --------------------------------------

namespace fluid::c {

Level& levelOf(const fluid_level* level, const char* function) {
    need(level, function, "level");
    return const_cast<fluid_level*>(level)->level;
}

b2Body* levelBody(const fluid_level* level, uint32_t index, const char* function) {
    need(level, function, "level");
    return bodyAt(*level, index, function);
}

bool levelBodyIndex(const fluid_level* level, const b2Body* body, uint32_t& index) {
    const auto& named = level->level.bodies;
    for (uint32_t k = 0; k < named.size(); ++k) {
        if (named[k].second == body) {
            index = k;
            return true;
        }
    }
    for (uint32_t k = 0; k < level->added.size(); ++k) {
        if (level->added[k] == body) {
            index = uint32_t(named.size()) + k;
            return true;
        }
    }
    return false;
}

} // namespace fluid::c
