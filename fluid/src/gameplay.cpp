// fluid — emitters, drains, lifetimes and sensors: what happens around the solver's step.
#include "kernels.h"
#include "step_common.h"
#include "world_state.h"

#include <fluid/shape.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace fluid::detail {

namespace {

// splitmix64 [Steele et al. 2014]: tiny, fast, and its whole state is one integer, which a
// snapshot stores.
uint64_t nextRandom(uint64_t& state) {
    uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

// Uniform in [-1, 1) from the top 24 bits (exact in float).
float symmetricUnit(uint64_t& state) {
    return float(nextRandom(state) >> 40) * (2.0f / 16777216.0f) - 1.0f;
}

// Where the liquid already stands at its rest density an emitter adds nothing: a full cup
// takes no more water, and a faucet in a closed box stops when the box is full instead of
// crushing the liquid. The fill at a point is the constraint's density, (sum_j V_j W + V_w
// sum_w W) / L, over the particles as they stand before the step and the boundary samples of
// the last step (1 inside the material's resting lattice); a new particle is placed only if
// the fill with its own term stays at or below 1 (without its own term a faucet's rows piled
// into a closed box: docs/gameplay.md, "Emitters"). The particles' grid is built at the first question; particles placed
// since then count as well, so that the rows of a long frame do not each fill the same room.
// A place inside a solid or outside a container has no room: the boundary would throw the
// particle into the liquid at the first step (docs/gameplay.md, "Emitters").
class Room {
public:
    explicit Room(WorldState& s) : m_s(s) {}

    bool fits(glm::vec2 x, uint16_t material) {
        for (const auto& boundary : m_s.boundaries) {
            if (boundary->contains(x)) {
                return false;
            }
        }
        const Particles& p = m_s.particles;
        if (p.size() == 0 && m_s.samples.size() == 0) {
            return true;
        }
        if (!m_ready) {
            refreshConstants(m_s);
            m_support = 0.0f;
            for (const MaterialConstants& c : m_s.constants) {
                m_support = std::max(m_support, c.support);
            }
            m_areas.resize(m_s.materials.size());
            for (size_t m = 0; m < m_areas.size(); ++m) {
                m_areas[m] = particleArea(m_s.materials[m], m_s.def.depth);
            }
            // The samples lie on the lattice of the first material the particles have (as a
            // step lays them), read from the particles as they stand: the same in a world
            // restored from a save.
            const std::vector<uint8_t> present = presentMaterials(m_s);
            const size_t first = size_t(
                std::find(present.begin(), present.end(), uint8_t(1)) - present.begin());
            const float spacing = particleSpacing(
                m_s.materials[first < present.size() ? first : 0], m_s.def.depth);
            m_sampleArea = spacing * spacing;
            m_ready = true;
            m_gridded = UINT32_MAX;
        }
        if (m_gridded > p.size() || p.size() - m_gridded > kUngridded) {
            m_grid.build(p.px, p.py, m_support, TaskHook{});
            m_gridded = p.size();
        }
        const MaterialConstants& c = m_s.constants[material];
        const float h = c.support;
        double sum = double(m_areas[material]) * kernel::wendland(0.0f, h); // its own term
        const std::span<const uint32_t> order = m_grid.order();
        m_grid.forEachRange(x.x, x.y, [&](uint32_t b, uint32_t e) {
            for (uint32_t k = b; k < e; ++k) {
                const uint32_t j = order[k];
                const float r = glm::length(glm::vec2(p.px[j], p.py[j]) - x);
                sum += double(m_areas[p.material[j]]) * kernel::wendland(r, h);
            }
        });
        for (uint32_t j = m_gridded; j < p.size(); ++j) { // placed after the grid was built
            const float r = glm::length(glm::vec2(p.px[j], p.py[j]) - x);
            sum += double(m_areas[p.material[j]]) * kernel::wendland(r, h);
        }
        const Samples& w = m_s.samples;
        if (w.size() > 0 && w.grid.size() == w.size()) {
            w.grid.forEachRange(x.x, x.y, [&](uint32_t b, uint32_t e) {
                for (uint32_t k = b; k < e; ++k) {
                    const float r = glm::length(glm::vec2(w.px[k], w.py[k]) - x);
                    sum += double(m_sampleArea) * kernel::wendland(r, h);
                }
            });
        }
        return sum / double(c.lattice) <= 1.0;
    }

private:
    // Particles placed since the grid was built that are summed one by one; more rebuild it.
    static constexpr uint32_t kUngridded = 256;
    WorldState& m_s;
    bool m_ready = false;
    Grid m_grid;
    uint32_t m_gridded = 0; // particles [0, m_gridded) are in m_grid
    float m_support = 0.0f;
    std::vector<float> m_areas;
    float m_sampleArea = 0.0f; // the boundary samples' area, spacing^2 (m^2)
};

} // namespace

uint32_t emitParticles(WorldState& s, float frameDt, uint32_t& blocked, uint32_t& skipped) {
    uint32_t total = 0;
    Room room(s);
    for (EmitterState& e : s.emitters) {
        const EmitterDef& d = e.def;
        if (d.rate <= 0.0f || (d.maxCount > 0 && e.emitted >= d.maxCount)) {
            continue;
        }
        const Material& mat = s.materials[d.material.index];
        const float spacing = particleSpacing(mat, s.def.depth);
        const auto lanes = static_cast<uint32_t>(emitterLanes(d.width, spacing)); // <= 10,000
        const double rowRate = double(d.rate) / double(lanes);                    // rows per second
        e.carry += rowRate * double(frameDt);
        const auto rows = static_cast<uint32_t>(std::floor(e.carry));
        e.carry -= double(rows);
        const glm::vec2 dir = unitDirection(d.direction);
        const glm::vec2 across{-dir.y, dir.x};
        // Oldest row first: row r left the nozzle (carry + rows - 1 - r) row periods ago, so a
        // jet is evenly spaced whatever the frame rate.
        for (uint32_t r = 0; r < rows; ++r) {
            const double age = (e.carry + double(rows - 1 - r)) / rowRate;
            const glm::vec2 centre = d.position + dir * float(double(d.speed) * age);
            for (uint32_t k = 0; k < lanes; ++k) {
                if (d.maxCount > 0 && e.emitted >= d.maxCount) {
                    break;
                }
                float lateral = (float(k) - 0.5f * float(lanes - 1)) * spacing;
                if (d.jitter > 0.0f) {
                    lateral += d.jitter * spacing * symmetricUnit(e.random);
                }
                if (s.particles.size() >= s.def.maxParticles) {
                    ++blocked;
                    continue;
                }
                if (!room.fits(centre + across * lateral, d.material.index)) {
                    ++skipped; // the liquid there is at rest density already
                    continue;
                }
                // It left the nozzle `age` ago: its lifetime started then.
                s.append(centre + across * lateral, dir * d.speed, d.material.index,
                         expiryTime(s.time - age, d.lifetime));
                const auto emitter = size_t(&e - s.emitters.data());
                if (emitter < s.emitterGroup.size() &&
                    s.emitterGroup[emitter] != WorldState::kNoGroup) {
                    s.joinGroup(s.particles.size() - 1, s.emitterGroup[emitter], true);
                }
                ++e.emitted;
                ++total;
            }
        }
    }
    return total;
}

EmissionUndo::EmissionUndo(const WorldState& s)
    : m_count(s.particles.size()), m_sorts(s.sorts), m_profile(s.profile) {
    for (const EmitterState& e : s.emitters) {
        m_active = m_active || e.def.rate > 0.0f;
    }
    if (m_active) {
        m_emitters = s.emitters;
        m_freeSlots = s.freeSlots;
        m_slots = s.slotIndex.size();
    }
}

void EmissionUndo::restore(WorldState& s) const {
    s.profile = m_profile;
    Particles& p = s.particles;
    // Once the solver sorted, the emitted particles are no longer the last ones and the step
    // cannot be taken back.
    if (!m_active || p.size() < m_count || s.sorts != m_sorts) {
        return;
    }
    for (uint32_t i = m_count; i < p.size(); ++i) {
        s.leaveSlot(p.slot[i]);
        s.slotIndex[p.slot[i]] = UINT32_MAX;
    }
    for (std::vector<float>* channel : {&p.lastX, &p.lastY}) {
        if (!channel->empty()) {
            channel->resize(m_count);
        }
    }
    if (!p.colour.empty()) {
        p.colour.resize(m_count);
    }
    for (std::vector<float>* channel : p.keptFloats()) {
        channel->resize(m_count);
    }
    p.material.resize(m_count);
    p.slot.resize(m_count);
    p.expiry.resize(m_count);
    s.freeSlots = m_freeSlots;
    s.slotIndex.resize(m_slots);
    s.slotGeneration.resize(m_slots);
    s.emitters = m_emitters;
}

void WorldState::removeMarked(const std::vector<uint8_t>& kill) {
    Particles& p = particles;
    const uint32_t n = p.size();
    uint32_t w = 0;
    for (uint32_t i = 0; i < n; ++i) {
        const uint32_t slot = p.slot[i];
        if (kill[i] != 0) {
            releaseSlot(slot);
            continue;
        }
        if (w != i) {
            for (std::vector<float>* channel : p.keptFloats()) {
                (*channel)[w] = (*channel)[i];
            }
            p.material[w] = p.material[i];
            p.slot[w] = slot;
            p.expiry[w] = p.expiry[i];
            if (!p.lastX.empty()) {
                p.lastX[w] = p.lastX[i];
                p.lastY[w] = p.lastY[i];
            }
            if (!p.colour.empty()) {
                p.colour[w] = p.colour[i];
            }
        }
        slotIndex[slot] = w;
        ++w;
    }
    for (std::vector<float>* channel : p.keptFloats()) {
        channel->resize(w);
    }
    p.material.resize(w);
    p.slot.resize(w);
    p.expiry.resize(w);
    for (std::vector<float>* channel : {&p.lastX, &p.lastY}) {
        if (!channel->empty()) {
            channel->resize(w);
        }
    }
    if (!p.colour.empty()) {
        p.colour.resize(w);
    }
}

uint32_t finishGameplay(WorldState& s) {
    Particles& p = s.particles;
    const uint32_t n = p.size();
    const auto drains = static_cast<uint32_t>(s.drains.size());
    const float limit = s.positionLimit();
    // cause[i]: 0 stays, 1 + d drain d (the first that holds it), drains + 1 lifetime,
    // drains + 2 out of the position range.
    std::vector<uint32_t> cause(n, 0);
    uint32_t removed = 0;
    for (uint32_t i = 0; i < n; ++i) {
        const glm::vec2 x{p.px[i], p.py[i]};
        for (uint32_t d = 0; d < drains && cause[i] == 0; ++d) {
            const DrainDef& drain = s.drains[d];
            if ((!drain.onlyMaterial || drain.material.index == p.material[i]) &&
                contains(drain.shape, x)) {
                cause[i] = 1 + d;
            }
        }
        if (cause[i] == 0 && p.expiry[i] <= s.time) {
            cause[i] = drains + 1;
        }
        if (cause[i] == 0 && !(std::fabs(x.x) <= limit && std::fabs(x.y) <= limit)) {
            cause[i] = drains + 2;
        }
        removed += cause[i] != 0 ? 1 : 0;
    }
    if (removed > 0) {
        // Events by drain in the order added, then lifetimes, then out of range; each by slot
        // (array index).
        for (uint32_t c = 1; c <= drains + 2; ++c) {
            for (uint32_t i = 0; i < n; ++i) {
                if (cause[i] != c) {
                    continue;
                }
                RemovedEvent ev;
                ev.particle = s.handleOf(p.slot[i]);
                ev.position = {p.px[i], p.py[i]};
                ev.velocity = {p.vx[i], p.vy[i]};
                ev.material = MaterialId{p.material[i], s.tag.value()};
                ev.cause = c <= drains      ? RemovalCause::Drain
                           : c == drains + 1 ? RemovalCause::Lifetime
                                             : RemovalCause::OutOfRange;
                ev.drain = DrainId{c <= drains ? c - 1 : 0, s.tag.value()};
                s.removed.push_back(ev);
            }
        }
        std::vector<uint8_t> kill(n);
        for (uint32_t i = 0; i < n; ++i) {
            kill[i] = cause[i] != 0 ? 1 : 0;
        }
        s.removeMarked(kill);
    }

    // Sensors: what each holds now, per material.
    const size_t m = s.materials.size();
    s.sensorReadings.assign(s.sensors.size() * m, SensorReading{});
    std::vector<float> area(m);
    for (size_t k = 0; k < m; ++k) {
        area[k] = particleArea(s.materials[k], s.def.depth);
    }
    for (size_t k = 0; k < s.sensors.size(); ++k) {
        const Shape& shape = s.sensors[k].shape;
        SensorReading* out = s.sensorReadings.data() + k * m;
        for (uint32_t i = 0; i < p.size(); ++i) {
            if (contains(shape, {p.px[i], p.py[i]})) {
                ++out[p.material[i]].count;
            }
        }
        for (size_t j = 0; j < m; ++j) {
            const float c = float(out[j].count);
            out[j].mass = c * s.materials[j].mass;
            out[j].area = c * area[j];
            out[j].volume = out[j].area * s.def.depth;
        }
    }
    return removed;
}

} // namespace fluid::detail
