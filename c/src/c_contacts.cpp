// fluid::c — contact events (fluid/c.h, fluid/contacts.h, fluid/box2d/coupling.h).
#include "c_internal.h"

#include <fluid/box2d/coupling.h>
#include <fluid/contacts.h>
#include <fluid/level.h>
#include <fluid/plugins/kinematic_shape.h>

#include <box2d/box2d.h>

#include <string>

using namespace fluid;
using namespace fluid::c;

namespace fluid::c {

// The level behind a handle, its body by fluid_level_body's index and back (c_level.cpp).
Level& levelOf(const fluid_level* level, const char* function);
b2Body* levelBody(const fluid_level* level, uint32_t index, const char* function);
bool levelBodyIndex(const fluid_level* level, const b2Body* body, uint32_t& index);

} // namespace fluid::c

namespace {

// Writes the first `capacity` of `values` to `out` (converted by `convert`) and their count to
// `count`.
template <class T, class C, class Convert>
void copyOut(std::span<const T> values, C* out, uint32_t capacity, uint32_t* count,
             const char* function, const char* what, Convert&& convert) {
    need(count, function, "count");
    if (capacity > 0) {
        need(out, function, what);
    }
    for (uint32_t k = 0; k < values.size() && k < capacity; ++k) {
        out[k] = convert(values[k]);
    }
    *count = uint32_t(values.size());
}

fluid_particle_id idOf(const ParticleHandle& h) {
    return toC(h);
}

// The coupling's contacts whose bodies the level lists, with their fluid_level_body indices.
struct LevelContact {
    uint32_t index = 0; // in the coupling's particleContacts()
    uint32_t body = 0;  // fluid_level_body's index
};
std::vector<LevelContact> levelContacts(const fluid_level* level, const Level& l) {
    std::vector<LevelContact> out;
    if (!l.coupling) {
        return out;
    }
    const std::span<const box2d::ParticleContact> all = l.coupling->particleContacts();
    for (uint32_t k = 0; k < all.size(); ++k) {
        uint32_t body = 0;
        if (levelBodyIndex(level, all[k].body, body)) {
            out.push_back({k, body});
        }
    }
    return out;
}

// The fields a world's contact (fluid::BodyContact) and a coupling's (box2d::ParticleContact)
// share, into their C records.
template <class CRecord, class Event> void fillShared(CRecord& c, const Event& e) {
    c.material = toC(e.material);
    c.group = {e.group.index, e.group.generation, e.group.world};
    c.particles = e.particles;
    c.impulse = toC(e.impulse);
    c.point = toC(e.point);
    c.approach_speed = e.approachSpeed;
}

} // namespace

fluid_status fluid_world_set_contact_events(fluid_world* world, fluid_plugin_id shape, bool on) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        const char* const function = "fluid_world_set_contact_events";
        World& w = worldOf(world, function);
        if (w.stepping()) {
            throw Failure{FLUID_ERROR_REFUSED,
                          std::string(function) +
                              ": called during the world's own step (from a plugin's callback); "
                              "ask for contact events between steps"};
        }
        Plugin& plugin = pluginOf(w, shape, function);
        auto* kinematic = dynamic_cast<KinematicShape*>(&plugin);
        if (kinematic == nullptr) {
            throw Failure{FLUID_ERROR_INVALID_ARGUMENT,
                          std::string(function) + ": plugin '" + std::string(plugin.type()) +
                              "' is not a boundary shape (boundary.polygon, boundary.chain, "
                              "boundary.circle): it has no contact events"};
        }
        kinematic->setContactEvents(on);
    });
}

fluid_status fluid_world_contacts(const fluid_world* world, fluid_body_contact* contacts,
                                  uint32_t capacity, uint32_t* count) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        const char* const function = "fluid_world_contacts";
        const World& w = worldOf(world, function);
        const uint32_t tag = tagOf(w);
        copyOut(bodyContacts(w), contacts, capacity, count, function, "contacts",
                [&](const BodyContact& e) {
                    fluid_body_contact c{};
                    c.plugin = {e.plugin, FLUID_PLUGIN_BOUNDARY, tag};
                    c.body = e.body;
                    fillShared(c, e);
                    return c;
                });
    });
}

fluid_status fluid_world_contact_particles(const fluid_world* world, uint32_t contact,
                                           fluid_particle_id* ids, uint32_t capacity,
                                           uint32_t* count) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        const char* const function = "fluid_world_contact_particles";
        const World& w = worldOf(world, function);
        need(count, function, "count");
        const uint32_t contacts = uint32_t(bodyContacts(w).size());
        if (contact >= contacts) {
            throw Failure{FLUID_ERROR_INVALID_ARGUMENT,
                          std::string(function) + ": contact = " + std::to_string(contact) +
                              " is out of range: the last step reported " +
                              std::to_string(contacts) + " contacts"};
        }
        copyOut(contactParticles(w, contact), ids, capacity, count, function, "ids", idOf);
    });
}

fluid_status fluid_level_set_body_contact_events(fluid_level* level, uint32_t index, bool on) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        const char* const function = "fluid_level_set_body_contact_events";
        Level& l = levelOf(level, function);
        if (!l.coupling) {
            throw Failure{FLUID_ERROR_REFUSED,
                          std::string(function) +
                              ": the level declares no bodies (its world has no Box2D world)"};
        }
        if (l.world.stepping()) {
            throw Failure{FLUID_ERROR_REFUSED,
                          std::string(function) +
                              ": called during the level's own step (from a plugin's "
                              "callback); ask for contact events between steps"};
        }
        l.coupling->setContactEvents(levelBody(level, index, function), on);
    });
}

fluid_status fluid_level_body_contacts(const fluid_level* level, fluid_level_body_contact* contacts,
                                       uint32_t capacity, uint32_t* count) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        const char* const function = "fluid_level_body_contacts";
        const Level& l = levelOf(level, function);
        const std::vector<LevelContact> listed = levelContacts(level, l);
        copyOut(std::span<const LevelContact>(listed), contacts, capacity, count, function,
                "contacts", [&](const LevelContact& lc) {
                    const box2d::ParticleContact& e = l.coupling->particleContacts()[lc.index];
                    fluid_level_body_contact c{};
                    c.body = lc.body;
                    fillShared(c, e);
                    return c;
                });
    });
}

fluid_status fluid_level_body_contact_particles(const fluid_level* level, uint32_t contact,
                                                fluid_particle_id* ids, uint32_t capacity,
                                                uint32_t* count) {
    return guard(FLUID_ERROR_INVALID_ARGUMENT, [&] {
        const char* const function = "fluid_level_body_contact_particles";
        const Level& l = levelOf(level, function);
        need(count, function, "count");
        const std::vector<LevelContact> listed = levelContacts(level, l);
        if (contact >= listed.size()) {
            throw Failure{FLUID_ERROR_INVALID_ARGUMENT,
                          std::string(function) + ": contact = " + std::to_string(contact) +
                              " is out of range: the last step reported " +
                              std::to_string(listed.size()) + " contacts"};
        }
        copyOut(l.coupling->contactParticles(listed[contact].index), ids, capacity, count, function,
                "ids", idOf);
    });
}
