// fluid — groups, per-particle user data and colours, colour mixing, and positions between
// steps (groups.h). Membership and user data live per handle slot (WorldState::slotGroup,
// slotUserData), so the sort never moves them; colours and previous positions are channels of
// the particle arrays, present only in the worlds that use them.
#include <fluid/groups.h>

#include "grid.h"
#include "parallel.h"
#include "world_state.h"

#include <fluid/error.h>
#include <fluid/internal/checks.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

namespace fluid {

namespace detail {

uint32_t WorldState::newGroup(uint32_t userData, uint32_t colour) {
    uint32_t g = 0;
    if (!freeGroups.empty()) {
        g = freeGroups.back();
        freeGroups.pop_back();
    } else {
        g = uint32_t(groups.size());
        groups.emplace_back();
    }
    Group& e = groups[g];
    e.live = true;
    e.count = 0;
    e.userData = userData;
    e.colour = colour;
    return g;
}

std::vector<uint32_t>& WorldState::colourChannel() {
    if (particles.colour.size() != particles.size()) {
        particles.colour.assign(particles.size(), 0u);
    }
    return particles.colour;
}

void WorldState::joinGroup(uint32_t index, uint32_t g, bool spawn) {
    const uint32_t slot = particles.slot[index];
    if (slotGroup.size() < slotIndex.size()) {
        slotGroup.resize(slotIndex.size(), kNoGroup);
    }
    uint32_t& current = slotGroup[slot];
    if (current != kNoGroup) {
        --groups[current].count;
    }
    current = g;
    if (g == kNoGroup) {
        return;
    }
    ++groups[g].count;
    if (spawn) {
        if (groups[g].userData != 0) {
            if (slotUserData.size() < slotIndex.size()) {
                slotUserData.resize(slotIndex.size(), 0u);
            }
            slotUserData[slot] = groups[g].userData;
        }
        if (Colour::unpack(groups[g].colour).isSet()) {
            colourChannel()[index] = groups[g].colour;
            if (slot < slotColourFraction.size()) {
                slotColourFraction[slot] = 0;
            }
        }
    }
}

void WorldState::leaveSlot(uint32_t slot) {
    if (slot < slotGroup.size() && slotGroup[slot] != kNoGroup) {
        --groups[slotGroup[slot]].count;
        slotGroup[slot] = kNoGroup;
    }
    if (slot < slotUserData.size()) {
        slotUserData[slot] = 0;
    }
    if (slot < slotColourFraction.size()) {
        slotColourFraction[slot] = 0;
    }
}

uint32_t checkedGroup(const WorldState& s, GroupHandle group, const char* function) {
    std::ostringstream text;
    text << function << ": ";
    if (group.isNull()) {
        text << "null group handle";
        throw Error(text.str(), ErrorCode::StaleId);
    }
    const auto name = [&] {
        text << "group handle {index " << group.index << ", generation " << group.generation << "}";
    };
    if (group.world != s.tag.value()) {
        name();
        text << " belongs to another world (world " << group.world << "; this is world "
             << s.tag.value() << "; a handle saved with a snapshot needs fluid::adopt)";
        throw Error(text.str(), ErrorCode::StaleId);
    }
    if (group.index >= s.groups.size() || !s.groups[group.index].live ||
        s.groups[group.index].generation != group.generation) {
        text << "stale ";
        name();
        text << ": that group was destroyed or merged into another";
        throw Error(text.str(), ErrorCode::StaleId);
    }
    return group.index;
}

void resetPrevious(WorldState& s) {
    s.particles.lastX = s.particles.px;
    s.particles.lastY = s.particles.py;
}

namespace {

// The pair weight (1 - r^2 / R^2)^3 summed over a particle's neighbours inside a square
// lattice of `spacing` for a reach R (m).
double latticeWeightSum(float spacing, float reach) {
    const double reach2 = double(reach) * double(reach);
    double lattice = 0.0;
    const int span = int(std::ceil(reach / spacing));
    for (int k = -span; k <= span; ++k) {
        for (int l = -span; l <= span; ++l) {
            const double r2 = double(spacing) * double(spacing) * double(k * k + l * l);
            if ((k != 0 || l != 0) && r2 < reach2) {
                const double q = 1.0 - r2 / reach2;
                lattice += q * q * q;
            }
        }
    }
    return lattice;
}

// One frame of colour mixing over the particles in the grid's order (mixColours): each channel
// in 8.8 fixed point, the colour's byte over the slot's fraction byte. A pair's trade
// trunc(K (c_j - c_i) / 65536) is exactly the negative of the reverse pair's (the same weight K
// from the same r^2; integer division truncates toward zero), so every channel's sum is kept,
// and integer sums give the same result in any order or split. A neighbour of the same colour
// and fraction trades nothing and is passed over before its distance is taken.
struct ColourTrades {
    static constexpr uint64_t kAlpha = uint64_t(0xFF00) << 48; // alpha's whole byte

    const Grid& grid;
    std::span<const uint32_t> order;
    std::span<const float> x, y;     // positions in the grid's order (m)
    std::span<const uint64_t> words; // 8.8 colours in the grid's order
    float reach2, invReach2;         // m^2, 1/m^2
    float weightScale;               // the weight K at r = 0
    // What they write, by particle index: the new colour and its fraction byte per channel.
    std::span<uint32_t> next, nextFraction;

    static void channels(uint64_t c, int64_t (&out)[4]) {
        for (int ch = 0; ch < 4; ++ch) {
            out[ch] = int64_t((c >> (16 * ch)) & 0xFFFFu);
        }
    }

    // Channel c's trade of a particle with channels `own` from the word cj at weight w.
    static int64_t trade(int64_t w, uint64_t cj, const int64_t (&own)[4], int c) {
        return w * (int64_t((cj >> (16 * c)) & 0xFFFFu) - own[c]) / 65536;
    }

    // The weight k and m trade with, or -1 where they trade nothing: the same word (k itself
    // among them), a particle without alpha, or beyond the reach. In float: both particles of
    // a pair compute it from the same r^2 with the same operations, so it is the same integer
    // from either side.
    int64_t weightOf(uint32_t k, uint32_t m, uint64_t ci, uint64_t cj) const {
        if (cj == ci || (cj & kAlpha) == 0) {
            return -1;
        }
        const float dx = x[m] - x[k], dy = y[m] - y[k];
        const float r2 = dx * dx + dy * dy;
        if (!(r2 < reach2)) {
            return -1;
        }
        const float q = 1.0f - r2 * invReach2;
        return int64_t(weightScale * (q * q * q));
    }

    // Sorted point k's new colour from its old channels and their trades.
    void finish(uint32_t k, const int64_t (&own)[4], const int64_t* acc) const {
        uint32_t out = 0, fraction = 0;
        for (int c = 0; c < 4; ++c) {
            // A convex combination of old values: in range (alpha stays at least 1.0).
            const int64_t v = std::clamp<int64_t>(own[c] + acc[c], c == 3 ? 256 : 0, 0xFFFF);
            out |= uint32_t(v >> 8) << (8 * c);
            fraction |= uint32_t(v & 255) << (8 * c);
        }
        next[order[k]] = out;
        nextFraction[order[k]] = fraction;
    }

    // Sorted point k, without alpha, keeps its colour and fraction.
    void keep(uint32_t k) const {
        const uint64_t w = words[k];
        uint32_t out = 0, fraction = 0;
        for (int c = 0; c < 4; ++c) {
            out |= uint32_t((w >> (16 * c + 8)) & 255u) << (8 * c);
            fraction |= uint32_t((w >> (16 * c)) & 255u) << (8 * c);
        }
        next[order[k]] = out;
        nextFraction[order[k]] = fraction;
    }

    // One thread: each pair once, its trade added to one side and taken from the other (the
    // reverse pair's trade is exactly its negative), so the sums are the ones `gather` makes,
    // in half the work. `acc`: 4 channels per sorted point.
    void pairsOnce(std::vector<int64_t>& acc) const {
        const auto n = uint32_t(words.size());
        acc.assign(size_t(n) * 4, 0);
        for (uint32_t k = 0; k < n; ++k) {
            const uint64_t ci = words[k];
            if ((ci & kAlpha) == 0) {
                continue;
            }
            int64_t own[4];
            channels(ci, own);
            int64_t* const mine = &acc[size_t(k) * 4];
            grid.forEachRange(x[k], y[k], [&](uint32_t mb, uint32_t me) {
                for (uint32_t m = std::max(mb, k + 1); m < me; ++m) {
                    const uint64_t cj = words[m];
                    const int64_t weight = weightOf(k, m, ci, cj);
                    if (weight < 0) {
                        continue;
                    }
                    int64_t* const other = &acc[size_t(m) * 4];
                    for (int c = 0; c < 4; ++c) {
                        const int64_t t = trade(weight, cj, own, c);
                        mine[c] += t;
                        other[c] -= t;
                    }
                }
            });
        }
        for (uint32_t k = 0; k < n; ++k) {
            if ((words[k] & kAlpha) == 0) {
                keep(k);
                continue;
            }
            int64_t own[4];
            channels(words[k], own);
            finish(k, own, &acc[size_t(k) * 4]);
        }
    }

    // Workers: each particle gathers its own trades from the old colours and writes only its
    // new one.
    void gather(const TaskHook& tasks) const {
        parallelFor(tasks, uint32_t(words.size()), 256, [&](uint32_t b, uint32_t e, uint32_t) {
            for (uint32_t k = b; k < e; ++k) {
                const uint64_t ci = words[k];
                if ((ci & kAlpha) == 0) {
                    keep(k);
                    continue;
                }
                int64_t own[4];
                channels(ci, own);
                int64_t acc[4] = {0, 0, 0, 0};
                grid.forEachRange(x[k], y[k], [&](uint32_t mb, uint32_t me) {
                    for (uint32_t m = mb; m < me; ++m) {
                        const uint64_t cj = words[m];
                        const int64_t weight = weightOf(k, m, ci, cj);
                        if (weight < 0) {
                            continue;
                        }
                        for (int c = 0; c < 4; ++c) {
                            acc[c] += trade(weight, cj, own, c);
                        }
                    }
                });
                finish(k, own, acc);
            }
        });
    }
};

} // namespace

void mixColours(WorldState& s, double seconds) {
    Particles& p = s.particles;
    const uint32_t n = p.size();
    if (!(s.colourMixing > 0.0f) || p.colour.size() != n || n < 2 || !(seconds > 0.0) ||
        s.materials.empty()) {
        return;
    }
    float reach = 0.0f;
    for (const Material& m : s.materials) {
        reach = std::max(reach, m.smoothingDistance);
    }
    const float spacing = particleSpacing(s.materials[s.finestMaterial()], s.def.depth);
    // The pair weight over its sum at a particle inside the finest material's lattice, with
    // half as much again for compression: a particle's weights sum below 1, so each new colour
    // is a convex combination of old ones (stays in 0..255).
    const double share = 1.0 - std::exp(-double(s.colourMixing) * seconds);
    const double scale = 65536.0 * share / (1.5 * std::max(latticeWeightSum(spacing, reach), 1.0));

    WorldState::ColourMixScratch& x = s.colourMix;
    x.grid.build(p.px, p.py, reach, s.tasks);
    const std::span<const uint32_t> order = x.grid.order();
    if (s.slotColourFraction.size() < s.slotIndex.size()) {
        s.slotColourFraction.resize(s.slotIndex.size(), 0u);
    }
    x.x.resize(n);
    x.y.resize(n);
    x.colour.resize(n);
    x.next.resize(n);
    x.nextFraction.resize(n);
    for (uint32_t k = 0; k < n; ++k) {
        const uint32_t i = order[k];
        const uint32_t c = p.colour[i], f = s.slotColourFraction[p.slot[i]];
        uint64_t word = 0;
        for (int ch = 0; ch < 4; ++ch) {
            word |= uint64_t(((c >> (8 * ch)) & 255u) << 8 | ((f >> (8 * ch)) & 255u)) << (16 * ch);
        }
        x.x[k] = p.px[i];
        x.y[k] = p.py[i];
        x.colour[k] = word;
    }
    const ColourTrades trades{
        x.grid,       order,  x.x,           x.y, x.colour, reach * reach, 1.0f / (reach * reach),
        float(scale), x.next, x.nextFraction};
    if (s.tasks.enqueue == nullptr || s.tasks.workerCount <= 1 || n <= 256) {
        trades.pairsOnce(x.acc);
    } else {
        trades.gather(s.tasks);
    }
    p.colour.swap(x.next);
    for (uint32_t i = 0; i < n; ++i) {
        s.slotColourFraction[p.slot[i]] = x.nextFraction[i];
    }
}

} // namespace detail

namespace {

using detail::WorldState;

// The world's state for reading between steps (readers change nothing).
const WorldState& reading(const World& world, const char* function) {
    const WorldState& s = detail::stateOf(const_cast<World&>(world));
    s.checkIdle(function);
    return s;
}

// The world's state for a change between steps (counted, so the query grid knows).
WorldState& changing(World& world, const char* function) {
    WorldState& s = detail::stateOf(world);
    s.changing(function);
    return s;
}

GroupHandle handleOf(const WorldState& s, uint32_t g) {
    return GroupHandle{g, s.groups[g].generation, s.tag.value()};
}

uint32_t emitterIndex(const WorldState& s, EmitterId id, const char* function) {
    if (id.world != 0 && id.world != s.tag.value()) {
        throw Error(std::string(function) + ": emitter id " + std::to_string(id.index) +
                        " was made by another world (world " + std::to_string(id.world) +
                        "; this is world " + std::to_string(s.tag.value()) +
                        "; an id kept from the world a snapshot was saved from needs World::adopt)",
                    ErrorCode::StaleId);
    }
    if (id.index >= s.emitters.size()) {
        throw Error(std::string(function) + ": unknown emitter id " + std::to_string(id.index) +
                        "; the world has " + std::to_string(s.emitters.size()) + " emitters",
                    ErrorCode::StaleId);
    }
    return id.index;
}

void freeGroup(WorldState& s, uint32_t g) {
    WorldState::Group& e = s.groups[g];
    e.live = false;
    e.count = 0;
    e.generation = e.generation + 1 == 0 ? 1 : e.generation + 1;
    s.freeGroups.push_back(g);
}

template <class F> void eachMember(const WorldState& s, uint32_t g, F&& f) {
    const detail::Particles& p = s.particles;
    if (s.groups[g].count == 0) {
        return;
    }
    for (uint32_t i = 0; i < p.size(); ++i) {
        if (s.groupOfSlot(p.slot[i]) == g) {
            f(i);
        }
    }
}

void checkFinite(const char* function, const char* what, glm::vec2 v, const char* unit) {
    if (!internal::finite(v)) {
        std::ostringstream text;
        text << function << ": " << what << " = (" << v.x << ", " << v.y
             << ") is not finite (unit: " << unit << ")";
        throw Error(text.str(), ErrorCode::BadArgument);
    }
}

// Sum of m_i and m_i v_i over the group, in double, in increasing array index.
glm::vec2 massWeighted(const WorldState& s, uint32_t g, const std::vector<float>& x,
                       const std::vector<float>& y) {
    double mass = 0.0, sx = 0.0, sy = 0.0;
    eachMember(s, g, [&](uint32_t i) {
        const double m = double(s.materials[s.particles.material[i]].mass);
        mass += m;
        sx += m * double(x[i]);
        sy += m * double(y[i]);
    });
    if (!(mass > 0.0)) {
        return {0.0f, 0.0f};
    }
    return {float(sx / mass), float(sy / mass)};
}

} // namespace

GroupHandle createGroup(World& world, const GroupDef& def) {
    WorldState& s = changing(world, "createGroup");
    return handleOf(s, s.newGroup(def.userData, def.colour.pack()));
}

GroupHandle spawnGroup(World& world, const BlobDef& blob, const GroupDef& def,
                       uint32_t* insideSolids) {
    WorldState& s = changing(world, "spawnGroup");
    BlobDef named = blob;
    bool made = false;
    if (blob.group.isNull()) {
        named.group = handleOf(s, s.newGroup(def.userData, def.colour.pack()));
        made = true;
    } else {
        (void)detail::checkedGroup(s, blob.group, "spawnGroup");
    }
    try {
        world.spawnBlob(named, insideSolids);
    } catch (...) {
        if (made) {
            freeGroup(s, named.group.index);
        }
        throw;
    }
    return named.group;
}

bool isValid(const World& world, GroupHandle group) {
    const WorldState& s = detail::stateOf(const_cast<World&>(world));
    return !group.isNull() && group.world == s.tag.value() && group.index < s.groups.size() &&
           s.groups[group.index].live && s.groups[group.index].generation == group.generation;
}

GroupHandle adopt(const World& world, GroupHandle group) {
    const WorldState& s = detail::stateOf(const_cast<World&>(world));
    group.world = group.isNull() ? 0 : s.tag.value();
    return group;
}

GroupHandle groupOf(const World& world, ParticleHandle particle) {
    const WorldState& s = reading(world, "groupOf");
    const uint32_t i = s.checkedIndex(particle, "groupOf");
    const uint32_t g = s.groupOfSlot(s.particles.slot[i]);
    return g == WorldState::kNoGroup ? GroupHandle{} : handleOf(s, g);
}

void setGroup(World& world, ParticleHandle particle, GroupHandle group) {
    WorldState& s = changing(world, "setGroup");
    const uint32_t i = s.checkedIndex(particle, "setGroup");
    s.joinGroup(i, detail::checkedGroup(s, group, "setGroup"), false);
}

GroupHandle emitterGroup(const World& world, EmitterId emitter) {
    const WorldState& s = reading(world, "emitterGroup");
    const uint32_t e = emitterIndex(s, emitter, "emitterGroup");
    const uint32_t g = e < s.emitterGroup.size() ? s.emitterGroup[e] : WorldState::kNoGroup;
    return g == WorldState::kNoGroup ? GroupHandle{} : handleOf(s, g);
}

void setEmitterGroup(World& world, EmitterId emitter, GroupHandle group) {
    WorldState& s = changing(world, "setEmitterGroup");
    const uint32_t e = emitterIndex(s, emitter, "setEmitterGroup");
    const uint32_t g = detail::checkedGroup(s, group, "setEmitterGroup");
    s.emitterGroup.resize(s.emitters.size(), WorldState::kNoGroup);
    s.emitterGroup[e] = g;
}

GroupDef groupDef(const World& world, GroupHandle group) {
    const WorldState& s = reading(world, "groupDef");
    const WorldState::Group& e = s.groups[detail::checkedGroup(s, group, "groupDef")];
    return GroupDef{e.userData, Colour::unpack(e.colour)};
}

void setGroupDef(World& world, GroupHandle group, const GroupDef& def) {
    WorldState& s = changing(world, "setGroupDef");
    WorldState::Group& e = s.groups[detail::checkedGroup(s, group, "setGroupDef")];
    e.userData = def.userData;
    e.colour = def.colour.pack();
}

uint32_t groupCount(const World& world, GroupHandle group) {
    const WorldState& s = reading(world, "groupCount");
    return s.groups[detail::checkedGroup(s, group, "groupCount")].count;
}

uint32_t groupParticles(const World& world, GroupHandle group, std::span<ParticleHandle> out) {
    const WorldState& s = reading(world, "groupParticles");
    const uint32_t g = detail::checkedGroup(s, group, "groupParticles");
    size_t written = 0;
    eachMember(s, g, [&](uint32_t i) {
        if (written < out.size()) {
            out[written++] = s.handleOf(s.particles.slot[i]);
        }
    });
    return s.groups[g].count;
}

glm::vec2 groupCentre(const World& world, GroupHandle group) {
    const WorldState& s = reading(world, "groupCentre");
    return massWeighted(s, detail::checkedGroup(s, group, "groupCentre"), s.particles.px,
                        s.particles.py);
}

glm::vec2 groupVelocity(const World& world, GroupHandle group) {
    const WorldState& s = reading(world, "groupVelocity");
    return massWeighted(s, detail::checkedGroup(s, group, "groupVelocity"), s.particles.vx,
                        s.particles.vy);
}

void moveGroup(World& world, GroupHandle group, glm::vec2 offset) {
    WorldState& s = changing(world, "moveGroup");
    const uint32_t g = detail::checkedGroup(s, group, "moveGroup");
    checkFinite("moveGroup", "offset", offset, "m");
    detail::Particles& p = s.particles;
    // All or nothing: every new position is checked before any moves.
    eachMember(s, g, [&](uint32_t i) {
        const glm::vec2 to{p.px[i] + offset.x, p.py[i] + offset.y};
        const std::string what = "particle " + std::to_string(i) + "'s new position";
        s.checkInRange("moveGroup", what.c_str(), to);
    });
    eachMember(s, g, [&](uint32_t i) {
        p.px[i] += offset.x;
        p.py[i] += offset.y;
        if (!p.lastX.empty()) { // moved, not flown: no streak
            p.lastX[i] = p.px[i];
            p.lastY[i] = p.py[i];
        }
    });
}

void setGroupVelocity(World& world, GroupHandle group, glm::vec2 velocity) {
    WorldState& s = changing(world, "setGroupVelocity");
    const uint32_t g = detail::checkedGroup(s, group, "setGroupVelocity");
    checkFinite("setGroupVelocity", "velocity", velocity, "m/s");
    eachMember(s, g, [&](uint32_t i) {
        s.particles.vx[i] = velocity.x;
        s.particles.vy[i] = velocity.y;
    });
}

void destroyGroup(World& world, GroupHandle group, bool withParticles) {
    WorldState& s = changing(world, "destroyGroup");
    const uint32_t g = detail::checkedGroup(s, group, "destroyGroup");
    if (withParticles) {
        std::vector<uint8_t> kill(s.particles.size(), 0);
        uint32_t marked = 0;
        eachMember(s, g, [&](uint32_t i) {
            kill[i] = 1;
            ++marked;
        });
        if (marked > 0) {
            s.removeMarked(kill);
        }
    } else {
        for (uint32_t& member : s.slotGroup) {
            if (member == g) {
                member = WorldState::kNoGroup;
            }
        }
    }
    const WorldState::Group def = s.groups[g];
    freeGroup(s, g);
    for (uint32_t& fed : s.emitterGroup) {
        if (fed == g) {
            fed = s.newGroup(def.userData, def.colour);
        }
    }
}

void mergeGroups(World& world, GroupHandle into, GroupHandle from) {
    WorldState& s = changing(world, "mergeGroups");
    const uint32_t a = detail::checkedGroup(s, into, "mergeGroups");
    const uint32_t b = detail::checkedGroup(s, from, "mergeGroups");
    if (a == b) {
        throw Error("mergeGroups: into and from are the same group {index " + std::to_string(a) +
                        "}; merge two different groups",
                    ErrorCode::BadArgument);
    }
    for (uint32_t& member : s.slotGroup) {
        if (member == b) {
            member = a;
        }
    }
    s.groups[a].count += s.groups[b].count;
    freeGroup(s, b);
    for (uint32_t& fed : s.emitterGroup) {
        if (fed == b) {
            fed = a;
        }
    }
}

uint32_t userData(const World& world, ParticleHandle particle) {
    const WorldState& s = reading(world, "userData");
    (void)s.checkedIndex(particle, "userData");
    return particle.slot < s.slotUserData.size() ? s.slotUserData[particle.slot] : 0u;
}

void setUserData(World& world, ParticleHandle particle, uint32_t value) {
    WorldState& s = changing(world, "setUserData");
    (void)s.checkedIndex(particle, "setUserData");
    if (value == 0 && particle.slot >= s.slotUserData.size()) {
        return; // reads 0 already
    }
    if (s.slotUserData.size() < s.slotIndex.size()) {
        s.slotUserData.resize(s.slotIndex.size(), 0u);
    }
    s.slotUserData[particle.slot] = value;
}

void setGroupUserData(World& world, GroupHandle group, uint32_t value) {
    WorldState& s = changing(world, "setGroupUserData");
    const uint32_t g = detail::checkedGroup(s, group, "setGroupUserData");
    if (value == 0 && s.slotUserData.empty()) {
        return;
    }
    if (s.slotUserData.size() < s.slotIndex.size()) {
        s.slotUserData.resize(s.slotIndex.size(), 0u);
    }
    eachMember(s, g, [&](uint32_t i) { s.slotUserData[s.particles.slot[i]] = value; });
}

uint32_t fillUserData(const World& world, std::span<uint32_t> out) {
    const WorldState& s = reading(world, "fillUserData");
    const detail::Particles& p = s.particles;
    for (uint32_t i = 0; i < p.size() && i < out.size(); ++i) {
        const uint32_t slot = p.slot[i];
        out[i] = slot < s.slotUserData.size() ? s.slotUserData[slot] : 0u;
    }
    return p.size();
}

Colour colour(const World& world, ParticleHandle particle) {
    const WorldState& s = reading(world, "colour");
    const uint32_t i = s.checkedIndex(particle, "colour");
    return s.particles.colour.empty() ? Colour{} : Colour::unpack(s.particles.colour[i]);
}

void setColour(World& world, ParticleHandle particle, Colour c) {
    WorldState& s = changing(world, "setColour");
    const uint32_t i = s.checkedIndex(particle, "setColour");
    if (!c.isSet() && s.particles.colour.empty()) {
        return;
    }
    s.colourChannel()[i] = c.isSet() ? c.pack() : 0u;
    if (particle.slot < s.slotColourFraction.size()) {
        s.slotColourFraction[particle.slot] = 0;
    }
}

void setGroupColour(World& world, GroupHandle group, Colour c) {
    WorldState& s = changing(world, "setGroupColour");
    const uint32_t g = detail::checkedGroup(s, group, "setGroupColour");
    if ((!c.isSet() && s.particles.colour.empty()) || s.groups[g].count == 0) {
        return;
    }
    std::vector<uint32_t>& channel = s.colourChannel();
    eachMember(s, g, [&](uint32_t i) {
        channel[i] = c.isSet() ? c.pack() : 0u;
        const uint32_t slot = s.particles.slot[i];
        if (slot < s.slotColourFraction.size()) {
            s.slotColourFraction[slot] = 0;
        }
    });
}

std::span<const uint32_t> colours(const World& world) {
    const WorldState& s = reading(world, "colours");
    return s.particles.colour;
}

void setColourMixing(World& world, float rate) {
    WorldState& s = changing(world, "setColourMixing");
    internal::checkRange<float>("setColourMixing: ", "rate", rate, 0.0f, 1000.0f, "1/s");
    s.colourMixing = rate;
}

float colourMixing(const World& world) {
    return reading(world, "colourMixing").colourMixing;
}

void setInterpolation(World& world, bool on) {
    setInterpolation(world, on ? Interpolation::Substep : Interpolation::Off);
}

Interpolation interpolation(const World& world) {
    const WorldState& s = reading(world, "interpolation");
    return !s.interpolate        ? Interpolation::Off
           : s.interpolateSteps ? Interpolation::Step
                                : Interpolation::Substep;
}

void setInterpolation(World& world, Interpolation mode) {
    if (mode != Interpolation::Off && mode != Interpolation::Substep &&
        mode != Interpolation::Step) {
        throw Error("setInterpolation: mode = " + std::to_string(int(mode)) +
                        " is not an Interpolation (Off 0, Substep 1, Step 2)",
                    ErrorCode::OutOfRange);
    }
    WorldState& s = changing(world, "setInterpolation");
    const bool on = mode != Interpolation::Off;
    s.interpolate = on;
    s.interpolateSteps = mode == Interpolation::Step;
    s.permuteLast = false;
    if (on) {
        detail::resetPrevious(s);
    } else {
        std::vector<float>().swap(s.particles.lastX);
        std::vector<float>().swap(s.particles.lastY);
    }
}

bool interpolating(const World& world) {
    return reading(world, "interpolating").interpolate;
}

float interpolationFactor(const World& world) {
    const WorldState& s = reading(world, "interpolationFactor");
    if (s.def.solver != Solver::PositionBased || s.interpolateSteps) {
        return 1.0f;
    }
    const double h = detail::substepLength(s.def.positionBased.substeps);
    return float(std::clamp(s.carry / h + 0.5, 0.0, 1.0));
}

std::span<const float> previousPositionX(const World& world) {
    return reading(world, "previousPositionX").particles.lastX;
}

std::span<const float> previousPositionY(const World& world) {
    return reading(world, "previousPositionY").particles.lastY;
}

uint32_t interpolatedPositions(const World& world, std::span<float> x, std::span<float> y,
                               float factor) {
    const WorldState& s = reading(world, "interpolatedPositions");
    if (std::isnan(factor) || factor > 1.0f) {
        std::ostringstream text;
        text << "interpolatedPositions: factor = " << factor
             << " is out of range; expected [0, 1], or a negative value for "
                "interpolationFactor(world)";
        throw Error(text.str(), ErrorCode::OutOfRange);
    }
    const float f = factor < 0.0f ? interpolationFactor(world) : factor;
    const detail::Particles& p = s.particles;
    const size_t n = std::min({size_t(p.size()), x.size(), y.size()});
    const bool kept = p.lastX.size() == p.size();
    for (size_t i = 0; i < n; ++i) {
        if (kept) {
            x[i] = (1.0f - f) * p.lastX[i] + f * p.px[i];
            y[i] = (1.0f - f) * p.lastY[i] + f * p.py[i];
        } else {
            x[i] = p.px[i];
            y[i] = p.py[i];
        }
    }
    return p.size();
}

} // namespace fluid
