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

// Adds one particle at the end of the arrays (the caller checked the capacity).
void append(WorldState& s, glm::vec2 x, glm::vec2 v, uint16_t material, float life) {
    Particles& p = s.particles;
    uint32_t slot = 0;
    if (!s.freeSlots.empty()) {
        slot = s.freeSlots.back();
        s.freeSlots.pop_back();
    } else {
        slot = static_cast<uint32_t>(s.slotIndex.size());
        s.slotIndex.push_back(UINT32_MAX);
        s.slotGeneration.push_back(1);
    }
    s.slotIndex[slot] = p.size();
    p.px.push_back(x.x);
    p.py.push_back(x.y);
    p.vx.push_back(v.x);
    p.vy.push_back(v.y);
    p.material.push_back(material);
    p.slot.push_back(slot);
    p.density.push_back(0.0f);
    p.pressure.push_back(0.0f);
    p.life.push_back(life);
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
        const auto lanes = static_cast<uint32_t>(1.0f + std::round(d.width / spacing));
        const double rowRate = double(d.rate) / double(lanes); // rows per second
        e.carry += rowRate * double(frameDt);
        const auto rows = static_cast<uint32_t>(std::floor(e.carry));
        e.carry -= double(rows);
        const glm::vec2 dir = d.direction / std::sqrt(glm::dot(d.direction, d.direction));
        const glm::vec2 across{-dir.y, dir.x};
        const float life = d.lifetime > 0.0f ? d.lifetime : std::numeric_limits<float>::infinity();
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
                append(s, centre + across * lateral, dir * d.speed, d.material.index, life);
                ++e.emitted;
                ++total;
            }
        }
    }
    return total;
}

void WorldState::removeMarked(const std::vector<uint8_t>& kill) {
    Particles& p = particles;
    const uint32_t n = p.size();
    uint32_t w = 0;
    for (uint32_t i = 0; i < n; ++i) {
        const uint32_t slot = p.slot[i];
        if (kill[i] != 0) {
            slotIndex[slot] = UINT32_MAX;
            // Generation 0 is the null handle's: skip it when a slot's counter wraps.
            slotGeneration[slot] = slotGeneration[slot] + 1 == 0 ? 1 : slotGeneration[slot] + 1;
            freeSlots.push_back(slot);
            continue;
        }
        if (w != i) {
            p.px[w] = p.px[i];
            p.py[w] = p.py[i];
            p.vx[w] = p.vx[i];
            p.vy[w] = p.vy[i];
            p.material[w] = p.material[i];
            p.slot[w] = slot;
            p.density[w] = p.density[i];
            p.pressure[w] = p.pressure[i];
            p.life[w] = p.life[i];
        }
        slotIndex[slot] = w;
        ++w;
    }
    for (auto* channel : {&p.px, &p.py, &p.vx, &p.vy, &p.density, &p.pressure, &p.life}) {
        channel->resize(w);
    }
    p.material.resize(w);
    p.slot.resize(w);
}

uint32_t finishGameplay(WorldState& s, float frameDt) {
    Particles& p = s.particles;
    const uint32_t n = p.size();
    const auto drains = static_cast<uint32_t>(s.drains.size());
    // cause[i]: 0 stays, 1 + d drain d (the first that holds it), drains + 1 lifetime.
    std::vector<uint32_t> cause(n, 0);
    uint32_t removed = 0;
    for (uint32_t i = 0; i < n; ++i) {
        p.life[i] -= frameDt; // infinity stays infinity
        const glm::vec2 x{p.px[i], p.py[i]};
        for (uint32_t d = 0; d < drains && cause[i] == 0; ++d) {
            const DrainDef& drain = s.drains[d];
            if ((!drain.onlyMaterial || drain.material.index == p.material[i]) &&
                contains(drain.shape, x)) {
                cause[i] = 1 + d;
            }
        }
        if (cause[i] == 0 && p.life[i] <= 0.0f) {
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
