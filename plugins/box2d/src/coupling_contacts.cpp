// fluid::box2d — the coupling's contact events (Coupling::setContactEvents, particleContacts):
// the world's events for the coupling's plugin, summed over a frame's rounds per b2Body.
#include <fluid/box2d/coupling.h>

#include "body_boundary.h"

#include <fluid/contacts.h>
#include <fluid/error.h>
#include <fluid/groups.h>

#include <box2d/box2d.h>

#include <algorithm>
#include <string>
#include <unordered_set>
#include <vector>

namespace fluid::box2d {

void Coupling::setContactEvents(const b2Body* body, bool on) {
    bool found = false;
    for (const b2Body* b = m_physics->GetBodyList(); b != nullptr && !found; b = b->GetNext()) {
        found = b == body;
    }
    if (!found) {
        throw Error("fluid::box2d::Coupling::setContactEvents: the body is not one of the "
                    "coupling's b2World (a null, destroyed or another world's body)",
                    ErrorCode::StaleId);
    }
    if (on) {
        m_contactBodies.insert(body);
    } else {
        m_contactBodies.erase(body);
    }
}

bool Coupling::contactEvents(const b2Body* body) const {
    return m_contactBodies.count(body) != 0;
}

std::span<const ParticleContact> Coupling::particleContacts() const {
    return m_particleContacts;
}

std::span<const ParticleHandle> Coupling::contactParticles(uint32_t contact) const {
    if (contact >= m_particleContacts.size()) {
        throw Error("fluid::box2d::Coupling::contactParticles: contact = " +
                        std::to_string(contact) + " is out of range: the last step reported " +
                        std::to_string(m_particleContacts.size()) + " contacts",
                    ErrorCode::OutOfRange);
    }
    const uint32_t b = m_contactBegin[contact], e = m_contactBegin[contact + 1];
    return std::span<const ParticleHandle>(m_contactHandles).subspan(b, e - b);
}

// One round's contact events of the world, for the bodies of this coupling's plugin, added to
// the frame's sums (bodies in the order they first report).
void Coupling::collectContacts(const World& world, float dt) {
    const std::span<const BodyContact> contacts = bodyContacts(world);
    if (contacts.empty()) {
        return;
    }
    uint32_t plugin = 0;
    while (plugin < world.boundaries().size() && world.boundaries()[plugin].get() != m_boundary) {
        ++plugin;
    }
    const std::span<const BodyEntry> bodies = m_boundary->bodies();
    for (uint32_t i = 0; i < contacts.size(); ++i) {
        const BodyContact& e = contacts[i];
        if (e.plugin != plugin || e.body >= bodies.size()) {
            continue;
        }
        b2Body* body = bodies[e.body].body;
        auto sum = std::find_if(m_contactSums.begin(), m_contactSums.end(),
                                [&](const ContactSum& c) { return c.body == body; });
        if (sum == m_contactSums.end()) {
            m_contactSums.push_back(ContactSum{});
            sum = m_contactSums.end() - 1;
            sum->body = body;
        }
        const std::span<const ParticleHandle> handles = fluid::contactParticles(world, i);
        sum->handles.insert(sum->handles.end(), handles.begin(), handles.end());
        if (sum->materials.size() <= e.material.index) {
            sum->materials.resize(std::size_t(e.material.index) + 1, 0);
        }
        sum->materials[e.material.index] += e.particles;
        // The round's force as the coupling measures it (m_reports is in bodies() order).
        sum->impulse += double(dt) * glm::dvec2(m_reports[e.body].force);
        sum->pointSum += double(e.particles) * glm::dvec2(e.point);
        sum->touches += double(e.particles);
        sum->approach = std::max(sum->approach, e.approachSpeed);
    }
}

namespace {

// The group most of `handles` belong to (ties: the lower index; particles in no group, and
// those removed since they touched, are not counted); null when none is in a group.
GroupHandle majorityGroup(const World& world, std::span<const ParticleHandle> handles) {
    std::vector<std::pair<uint32_t, GroupHandle>> counts; // (count, group), by group index
    for (const ParticleHandle h : handles) {
        if (!world.isValid(h)) {
            continue;
        }
        const GroupHandle g = groupOf(world, h);
        if (g.generation == 0) {
            continue;
        }
        auto it = std::find_if(counts.begin(), counts.end(),
                               [&](const auto& c) { return c.second.index == g.index; });
        if (it == counts.end()) {
            counts.push_back({0, g});
            it = counts.end() - 1;
        }
        ++it->first;
    }
    GroupHandle best{};
    uint32_t most = 0;
    for (const auto& [count, g] : counts) {
        if (count > most || (count == most && g.index < best.index)) {
            most = count;
            best = g;
        }
    }
    return best;
}

} // namespace

// The frame's events from its sums, in the b2World's body order.
void Coupling::finishContacts(const World& world) {
    m_particleContacts.clear();
    m_contactHandles.clear();
    m_contactBegin.clear();
    if (!m_contactSums.empty()) {
        for (b2Body* b = m_physics->GetBodyList(); b != nullptr; b = b->GetNext()) {
            const auto sum = std::find_if(m_contactSums.begin(), m_contactSums.end(),
                                          [&](const ContactSum& c) { return c.body == b; });
            if (sum == m_contactSums.end()) {
                continue;
            }
            std::vector<ParticleHandle> handles = sum->handles;
            std::sort(handles.begin(), handles.end(), [](ParticleHandle x, ParticleHandle y) {
                return x.slot != y.slot ? x.slot < y.slot : x.generation < y.generation;
            });
            handles.erase(std::unique(handles.begin(), handles.end()), handles.end());
            ParticleContact c;
            c.body = b;
            c.material = world.adopt(
                MaterialId{uint16_t(std::max_element(sum->materials.begin(), sum->materials.end()) -
                                    sum->materials.begin())});
            c.group = majorityGroup(world, handles);
            c.particles = uint32_t(handles.size());
            c.impulse = glm::vec2(sum->impulse);
            c.point = glm::vec2(sum->pointSum / sum->touches);
            c.approachSpeed = sum->approach;
            m_contactBegin.push_back(uint32_t(m_contactHandles.size()));
            m_contactHandles.insert(m_contactHandles.end(), handles.begin(), handles.end());
            m_particleContacts.push_back(c);
        }
    }
    m_contactBegin.push_back(uint32_t(m_contactHandles.size()));
}

// Forgets the contact settings of bodies no longer in the b2World (destroyed since).
void Coupling::forgetDestroyedContactBodies() {
    if (m_contactBodies.empty()) {
        return;
    }
    std::unordered_set<const b2Body*> alive; // lookup only
    for (const b2Body* b = m_physics->GetBodyList(); b != nullptr; b = b->GetNext()) {
        if (m_contactBodies.count(b) != 0) {
            alive.insert(b);
        }
    }
    m_contactBodies = std::move(alive);
}

} // namespace fluid::box2d
