// fluid — contact events (contacts.h): the rigid bodies that ask for them, the particles that
// touch them in each sub-step, and the events made from both at the end of the step.
#include <fluid/contacts.h>

#include "step_common.h"

#include <fluid/error.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace fluid {

namespace detail {

void gatherContactBodies(WorldState& s, const StepContext& context) {
    ContactState& c = s.contacts;
    c.bodies.clear();
    const Samples& w = s.samples;
    size_t state = 0; // s.bodies is in (plugin, body) order too
    for (size_t p = 0; p < s.boundaries.size(); ++p) {
        const std::span<const RigidBody> bodies = s.boundaries[p]->rigidBodies();
        for (size_t b = 0; b < bodies.size(); ++b) {
            const RigidBody& rb = bodies[b];
            // gatherSamples checked the range already.
            if (!rb.contacts || rb.sampleBegin == rb.sampleEnd) {
                continue;
            }
            ContactState::Body body;
            body.plugin = uint32_t(p);
            body.index = uint32_t(b);
            body.sampleBegin = w.pluginBegin[p] + rb.sampleBegin;
            body.sampleEnd = w.pluginBegin[p] + rb.sampleEnd;
            while (state < s.bodies.size() &&
                   (s.bodies[state].plugin < p ||
                    (s.bodies[state].plugin == p && s.bodies[state].index < b))) {
                ++state;
            }
            if (state < s.bodies.size() && s.bodies[state].plugin == p &&
                s.bodies[state].index == b) {
                body.state = int32_t(state);
            }
            c.bodies.push_back(body);
        }
    }
    if (c.bodies.empty()) {
        c.bodyOf.clear();
        c.samples.clear();
        return;
    }
    c.bodyOf.assign(w.pluginBegin.back(), -1);
    for (size_t k = 0; k < c.bodies.size(); ++k) {
        for (uint32_t i = c.bodies[k].sampleBegin; i < c.bodies[k].sampleEnd; ++i) {
            if (c.bodyOf[i] < 0) { // a sample listed twice stays with its first body
                c.bodyOf[i] = int32_t(k);
            }
        }
    }
    c.reach = kContactReach * context.sampleSpacing;
    c.touches.resize(c.bodies.size());
    for (auto& t : c.touches) {
        t.clear();
    }
    c.sumX.assign(c.bodies.size(), 0.0);
    c.sumY.assign(c.bodies.size(), 0.0);
    c.approach.assign(c.bodies.size(), 0.0f);
    c.stamp.assign(s.particles.size(), 0);
    c.mark = 1;
}

void contactPass(WorldState& s) {
    ContactState& c = s.contacts;
    if (c.bodies.empty()) {
        return;
    }
    const auto count = uint32_t(c.bodies.size());
    const Particles& p = s.particles;
    const Samples& w = s.samples;
    if (p.size() == 0 || s.grid.view().count != p.size() || c.stamp.size() != p.size()) {
        c.mark += count;
        return;
    }
    const float r2 = c.reach * c.reach;
    // Serial, in the samples' sorted order: the same sums for any number of workers. The
    // asking bodies' samples are few (a crate's outline, a few layers deep).
    for (const uint32_t k : c.samples) {
        const auto b = uint32_t(c.bodyOf[w.source[k]]);
        const uint32_t mark = c.mark + b;
        const float xw = w.px[k], yw = w.py[k], vxw = w.vx[k], vyw = w.vy[k];
        float& approach = c.approach[b];
        s.grid.forEachRange(xw, yw, [&](uint32_t jb, uint32_t je) {
            for (uint32_t j = jb; j < je; ++j) {
                const float dx = p.px[j] - xw, dy = p.py[j] - yw;
                const float d2 = dx * dx + dy * dy;
                if (!(d2 <= r2)) {
                    continue;
                }
                if (d2 > 0.0f) {
                    const float towards =
                        -((p.vx[j] - vxw) * dx + (p.vy[j] - vyw) * dy) / std::sqrt(d2);
                    approach = std::max(approach, towards);
                }
                if (c.stamp[j] != mark) {
                    c.stamp[j] = mark;
                    c.touches[b].push_back({p.slot[j], p.material[j]});
                    c.sumX[b] += double(p.px[j]);
                    c.sumY[b] += double(p.py[j]);
                }
            }
        });
    }
    c.mark += count;
}

namespace {

// The group a contact reports: the group most of its (distinct) particles belong to, ties to
// the lower index; null when none of them is in a group. Membership is kept per handle slot, so
// it reads the same at any point of the step.
GroupHandle contactGroup(const WorldState& s, std::span<const ContactState::Touch> touches,
                         std::vector<uint32_t>& counts) {
    counts.assign(s.groups.size(), 0);
    bool any = false;
    for (const ContactState::Touch& t : touches) {
        const uint32_t g = s.groupOfSlot(t.slot);
        if (g != WorldState::kNoGroup && g < counts.size()) {
            ++counts[g];
            any = true;
        }
    }
    if (!any) {
        return {};
    }
    const auto g = uint32_t(std::max_element(counts.begin(), counts.end()) - counts.begin());
    return GroupHandle{g, s.groups[g].generation, s.tag.value()};
}

} // namespace

void finishContacts(WorldState& s, float frameDt) {
    ContactState& c = s.contacts;
    c.events.clear();
    c.handles.clear();
    c.handleBegin.clear();
    std::vector<uint32_t> materials, groups;
    for (size_t b = 0; b < c.bodies.size(); ++b) {
        std::vector<ContactState::Touch>& touches = c.touches[b];
        if (touches.empty()) {
            continue;
        }
        const ContactState::Body& body = c.bodies[b];
        BodyContact e;
        e.plugin = body.plugin;
        e.body = body.index;
        const double n = double(touches.size());
        e.point = glm::vec2(float(c.sumX[b] / n), float(c.sumY[b] / n));
        e.approachSpeed = c.approach[b];
        // The distinct particles, by slot (a particle keeps its material for life).
        std::sort(touches.begin(), touches.end(),
                  [](const ContactState::Touch& x, const ContactState::Touch& y) {
                      return x.slot < y.slot;
                  });
        touches.erase(std::unique(touches.begin(), touches.end(),
                                  [](const ContactState::Touch& x, const ContactState::Touch& y) {
                                      return x.slot == y.slot;
                                  }),
                      touches.end());
        e.particles = uint32_t(touches.size());
        materials.assign(s.materials.size(), 0);
        c.handleBegin.push_back(uint32_t(c.handles.size()));
        for (const ContactState::Touch& t : touches) {
            ++materials[t.material];
            c.handles.push_back(s.handleOf(t.slot));
        }
        e.material = MaterialId{
            uint16_t(std::max_element(materials.begin(), materials.end()) - materials.begin()),
            s.tag.value()};
        e.group = contactGroup(s, touches, groups);
        // The forces on its samples, averaged over the step, times the step; and the coarse
        // solve's push, an impulse already.
        double ix = 0.0, iy = 0.0;
        for (uint32_t k = body.sampleBegin; k < body.sampleEnd; ++k) {
            ix += double(s.samples.fx[k]);
            iy += double(s.samples.fy[k]);
        }
        ix *= double(frameDt);
        iy *= double(frameDt);
        if (body.state >= 0) {
            ix += s.bodies[size_t(body.state)].impulseX;
            iy += s.bodies[size_t(body.state)].impulseY;
        }
        e.impulse = glm::vec2(float(ix), float(iy));
        c.events.push_back(e);
    }
    c.handleBegin.push_back(uint32_t(c.handles.size()));
}

void clearContacts(WorldState& s) {
    s.contacts.events.clear();
    s.contacts.handles.clear();
    s.contacts.handleBegin.assign(1, 0);
}

} // namespace detail

namespace {

const detail::WorldState& contactState(const World& world, const char* function) {
    const detail::WorldState& s = detail::stateOf(const_cast<World&>(world));
    if (s.stepping) {
        throw Error(std::string(function) +
                        ": called during the world's own step (from a plugin's hook or a task); "
                        "read the contacts between steps",
                    ErrorCode::WrongState);
    }
    return s;
}

} // namespace

std::span<const BodyContact> bodyContacts(const World& world) {
    return contactState(world, "fluid::bodyContacts").contacts.events;
}

std::span<const ParticleHandle> contactParticles(const World& world, uint32_t contact) {
    const detail::ContactState& c = contactState(world, "fluid::contactParticles").contacts;
    if (contact >= c.events.size()) {
        throw Error("fluid::contactParticles: contact = " + std::to_string(contact) +
                        " is out of range: the last step reported " +
                        std::to_string(c.events.size()) + " contacts",
                    ErrorCode::OutOfRange);
    }
    const uint32_t b = c.handleBegin[contact], e = c.handleBegin[contact + 1];
    return std::span<const ParticleHandle>(c.handles).subspan(b, e - b);
}

} // namespace fluid
