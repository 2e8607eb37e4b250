// fluid::c — levels (fluid/c.h): fluid::Level behind an opaque handle.
#include "c_internal.h"

#include <box2d/box2d.h>

#include <cstdlib>
#include <cstring>
#include <sstream>

/// The C API's level: the C++ level and the world handle that lends out its world.
struct fluid_level {
    /// The level.
    fluid::Level level;
    /// fluid_level_world's handle (not owning).
    fluid_world world;
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
    throw Failure{FLUID_ERROR_UNKNOWN_NAME, std::string(function) + ": the level has no " +
                                                what + " named '" + Error::printable(name) + "'"};
}

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

void fluid_level_destroy(fluid_level* level) { delete level; }

fluid_status fluid_level_step(fluid_level* level) {
    return guard(FLUID_ERROR_REFUSED, [&] {
        need(level, "fluid_level_step", "level");
        level->level.step();
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
        const std::string text = out.str();
        fluid_bytes made{nullptr, text.size()};
        if (!text.empty()) {
            made.data = static_cast<uint8_t*>(std::malloc(text.size()));
            if (made.data == nullptr) {
                throw std::bad_alloc();
            }
            std::memcpy(made.data, text.data(), text.size());
        }
        *bytes = made;
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
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        const Level& l = levelOf(level, "fluid_level_find_material");
        need(id, "fluid_level_find_material", "id");
        *id = fluid::c::toC(findNamed(l.materials, name, "material", "fluid_level_find_material"));
    });
}

fluid_status fluid_level_find_emitter(const fluid_level* level, const char* name,
                                      fluid_emitter_id* id) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        const Level& l = levelOf(level, "fluid_level_find_emitter");
        need(id, "fluid_level_find_emitter", "id");
        const EmitterId e = findNamed(l.emitters, name, "emitter", "fluid_level_find_emitter");
        *id = {e.index, e.world};
    });
}

fluid_status fluid_level_find_drain(const fluid_level* level, const char* name,
                                    fluid_drain_id* id) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        const Level& l = levelOf(level, "fluid_level_find_drain");
        need(id, "fluid_level_find_drain", "id");
        const DrainId d = findNamed(l.drains, name, "drain", "fluid_level_find_drain");
        *id = {d.index, d.world};
    });
}

fluid_status fluid_level_find_sensor(const fluid_level* level, const char* name,
                                     fluid_sensor_id* id) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        const Level& l = levelOf(level, "fluid_level_find_sensor");
        need(id, "fluid_level_find_sensor", "id");
        const SensorId s = findNamed(l.sensors, name, "sensor", "fluid_level_find_sensor");
        *id = {s.index, s.world};
    });
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
        throw Failure{FLUID_ERROR_UNKNOWN_NAME, "fluid_level_find_plugin: the level has no plugin "
                                                "named '" +
                                                    Error::printable(name) + "'"};
    });
}

fluid_status fluid_level_body_count(const fluid_level* level, uint32_t* count) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        const Level& l = levelOf(level, "fluid_level_body_count");
        need(count, "fluid_level_body_count", "count");
        *count = uint32_t(l.bodies.size());
    });
}

fluid_status fluid_level_body(const fluid_level* level, uint32_t index, const char** name,
                              fluid_vec2* position, float* angle) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        const Level& l = levelOf(level, "fluid_level_body");
        if (index >= l.bodies.size()) {
            throw Failure{FLUID_ERROR_STALE_ID, "fluid_level_body: index " +
                                                    std::to_string(index) +
                                                    " is past the level's " +
                                                    std::to_string(l.bodies.size()) + " bodies"};
        }
        const auto& [bodyName, body] = l.bodies[index];
        if (name != nullptr) {
            *name = bodyName.c_str();
        }
        if (position != nullptr) {
            *position = {body->GetPosition().x, body->GetPosition().y};
        }
        if (angle != nullptr) {
            *angle = body->GetAngle();
        }
    });
}

} // extern "C"
