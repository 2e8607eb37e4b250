// fluid — emitters, drains, lifetimes and sensors: what happens around the solver's step.
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

} // namespace

uint32_t emitParticles(WorldState& s, float frameDt, uint32_t& blocked) {
    uint32_t total = 0;
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
                // It left the nozzle `age` ago: its lifetime started then.
                s.append(centre + across * lateral, dir * d.speed, d.material.index,
                         expiryTime(s.time - age, d.lifetime));
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
        s.slotIndex[p.slot[i]] = UINT32_MAX;
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
}

uint32_t finishGameplay(WorldState& s) {
    Particles& p = s.particles;
    const uint32_t n = p.size();
    const auto drains = static_cast<uint32_t>(s.drains.size());
    // cause[i]: 0 stays, 1 + d drain d (the first that holds it), drains + 1 lifetime.
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
        removed += cause[i] != 0 ? 1 : 0;
    }
    if (removed > 0) {
        // Events by drain in the order added, lifetimes last, then by slot (array index).
        for (uint32_t c = 1; c <= drains + 1; ++c) {
            for (uint32_t i = 0; i < n; ++i) {
                if (cause[i] != c) {
                    continue;
                }
                RemovedEvent ev;
                ev.particle = ParticleHandle{p.slot[i], s.slotGeneration[p.slot[i]]};
                ev.position = {p.px[i], p.py[i]};
                ev.velocity = {p.vx[i], p.vy[i]};
                ev.material = MaterialId{p.material[i]};
                ev.cause = c <= drains ? RemovalCause::Drain : RemovalCause::Lifetime;
                ev.drain = DrainId{c <= drains ? c - 1 : 0};
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
