// fluid — particles a game can tell apart (groups, per-particle user data and colours) and
// draws between steps (interpolated positions). docs/groups.md has the guide.
#pragma once

#include <fluid/handle.h>
#include <fluid/world.h>

#include <glm/vec2.hpp>

#include <cstdint>
#include <span>

namespace fluid {

/// A particle's colour, 8 bits per channel (unit: 0..255, sRGB as the game means it). Alpha 0
/// means "no colour": the renderer draws such a particle in its material's style, and colour
/// mixing leaves it alone. Stored packed as `pack()` (r in the low byte), so the bytes of the
/// `colours` span read r, g, b, a on the little-endian machines fluid runs on. Plain data.
struct Colour {
    /// Red, green, blue and alpha (unit: 0..255 each; alpha 0 = no colour).
    uint8_t r = 0, g = 0, b = 0, a = 0;
    /// r | g << 8 | b << 16 | a << 24.
    constexpr uint32_t pack() const {
        return uint32_t(r) | uint32_t(g) << 8 | uint32_t(b) << 16 | uint32_t(a) << 24;
    }
    /// The inverse of `pack`.
    static constexpr Colour unpack(uint32_t v) {
        return {uint8_t(v), uint8_t(v >> 8), uint8_t(v >> 16), uint8_t(v >> 24)};
    }
    /// True when alpha is not 0.
    constexpr bool isSet() const { return a != 0; }
    /// Colours are equal when all four channels are.
    friend constexpr bool operator==(Colour, Colour) = default;
};

/// What particles that join a group at spawn (a blob spawned into it, its emitters' output)
/// start with. Plain data.
struct GroupDef {
    /// User data of each new particle (unit: the game's; any value, 0 = none).
    uint32_t userData = 0;
    /// Colour of each new particle (alpha 0, the default: none).
    Colour colour{};
};

// ---- Groups ---------------------------------------------------------------------------------
// Every blob and every emitter's output is a group; a particle belongs to at most one. A
// group's membership lives in the handle table, not the particle arrays, so sorts never move
// it and a world pays nothing per step for its groups. Groups, their members, user data and
// colours are saved in snapshots and come back bit for bit. A group stays (with a count of 0)
// when its last particle is removed, until `destroyGroup` or `mergeGroups` frees it.
//
// Thread rule for everything in this header: the functions that change the world (the ones
// taking `World&`) on the stepping thread between steps; the readers (taking `const World&`)
// from any thread between steps while nothing changes the world. During the world's own step
// (a plugin's hook) every call throws `fluid::Error` with `ErrorCode::WrongState`. Stale or
// null handles, handles of another world, and non-finite values throw `fluid::Error` naming
// the function and the value.

/// Makes an empty group whose new particles take `def`'s user data and colour.
GroupHandle createGroup(World& world, const GroupDef& def = {});
/// Spawns `blob` as `World::spawnBlob` does and returns its group: `blob.group` when given,
/// else a new group made with `def` (ignored when `blob.group` is set). The group is made even
/// when no lattice point fits (count 0). Errors as `spawnBlob`.
GroupHandle spawnGroup(World& world, const BlobDef& blob, const GroupDef& def = {},
                       uint32_t* insideSolids = nullptr);
/// True while the group behind `group` exists (false for null, stale and other worlds').
bool isValid(const World& world, GroupHandle group);
/// `group` with this world's tag (same index and generation), for a handle saved alongside a
/// snapshot. Checks nothing.
GroupHandle adopt(const World& world, GroupHandle group);
/// The group of a particle, or the null handle when it has none (`World::addParticle`'s).
/// Throws for a stale particle handle.
GroupHandle groupOf(const World& world, ParticleHandle particle);
/// Moves a particle into `group` (from its old group, if any); the particle keeps its user
/// data and colour.
void setGroup(World& world, ParticleHandle particle, GroupHandle group);
/// The group the emitter's particles join: one made for it by `World::addEmitter` unless
/// `setEmitterGroup` named another. Throws for an unknown emitter.
GroupHandle emitterGroup(const World& world, EmitterId emitter);
/// Makes the emitter's future particles join `group` (the ones emitted so far stay where
/// they are).
void setEmitterGroup(World& world, EmitterId emitter, GroupHandle group);
/// What the group's new particles take (`GroupDef`).
GroupDef groupDef(const World& world, GroupHandle group);
/// Replaces what the group's new particles take; its particles keep theirs.
void setGroupDef(World& world, GroupHandle group, const GroupDef& def);

/// Particles in the group (unit: count). O(1).
uint32_t groupCount(const World& world, GroupHandle group);
/// Writes the handles of the group's particles to `out`, in increasing array index, at most
/// `out.size()` of them; returns the group's count (unit: count; more than `out.size()` when
/// `out` is too short). O(particles in the world).
uint32_t groupParticles(const World& world, GroupHandle group, std::span<ParticleHandle> out);
/// The group's centre of mass (unit: m): sum m_i x_i / sum m_i with each particle's material
/// mass, summed in double in increasing array index; (0, 0) for an empty group.
glm::vec2 groupCentre(const World& world, GroupHandle group);
/// The group's mass-weighted mean velocity (unit: m/s; its momentum over its mass), summed as
/// `groupCentre`; (0, 0) for an empty group.
glm::vec2 groupVelocity(const World& world, GroupHandle group);
/// Translates every particle of the group by `offset` (unit: m; finite); all or nothing: a
/// particle that would leave `World::positionLimit` refuses the move, naming it. The moved
/// particles do not streak in interpolated pictures (their previous positions move too).
void moveGroup(World& world, GroupHandle group, glm::vec2 offset);
/// Sets the velocity of every particle of the group (unit: m/s; finite).
void setGroupVelocity(World& world, GroupHandle group, glm::vec2 velocity);
/// Destroys the group; with `withParticles` (the default) its particles are removed too (no
/// removal events: as `World::removeParticle`), else they stay without a group. Its handles
/// go stale; emitters that fed it get a new group each.
void destroyGroup(World& world, GroupHandle group, bool withParticles = true);
/// Moves every particle of `from` into `into` and destroys `from` (its handles go stale, its
/// emitters feed `into`). `into` keeps its `GroupDef`. Throws when both are the same group.
void mergeGroups(World& world, GroupHandle into, GroupHandle from);

// ---- Per-particle user data ------------------------------------------------------------------
// A 32-bit value per particle for the game (an owner, a team, a score), 0 unless set. Kept per
// handle slot, so sorts never move it; allocated when first set to non-zero.

/// A particle's user data (0 when never set).
uint32_t userData(const World& world, ParticleHandle particle);
/// Sets a particle's user data (any value).
void setUserData(World& world, ParticleHandle particle, uint32_t value);
/// Sets the user data of every particle of the group (not its `GroupDef`).
void setGroupUserData(World& world, GroupHandle group, uint32_t value);
/// Writes every particle's user data to `out` in array index order (the order of
/// `World::positionX()`), at most `out.size()` values; returns `World::particleCount()`.
uint32_t fillUserData(const World& world, std::span<uint32_t> out);

// ---- Per-particle colours --------------------------------------------------------------------
// An RGBA8 colour per particle, alpha 0 = none (the material's style). A channel of the
// particle arrays, sorted with them; allocated when some particle first gets a colour, so a
// world without colours pays nothing.

/// A particle's colour (alpha 0 when it has none).
Colour colour(const World& world, ParticleHandle particle);
/// Sets a particle's colour (alpha 0 takes it away).
void setColour(World& world, ParticleHandle particle, Colour colour);
/// Sets the colour of every particle of the group (not its `GroupDef`).
void setGroupColour(World& world, GroupHandle group, Colour colour);
/// Every particle's colour packed (`Colour::pack`) in array index order, or an empty span when
/// no particle ever had one (draw the material style). Valid until the next call that changes
/// the world; `fluid::gl::particles(world)` hands it to the renderer.
std::span<const uint32_t> colours(const World& world);
/// Colour mixing: at each step, every pair of coloured particles closer than the larger
/// support radius of their world's materials trades a share of the difference of their
/// colours, channel by channel: a coloured blob that meets another blends where they touch
/// (LiquidFun's colour mixing). `rate` (unit: 1/s; range [0, 1000]; 0, the default, is off)
/// sets how fast: a particle inside a liquid of two colours moves about 1 - exp(-rate t) of
/// the way to their mean in time t. Each channel carries 8 more bits below the visible byte
/// (kept per handle slot and saved; 0 for a colour just set), and the trades are integers of
/// 1/256 of a level, pair by pair antisymmetric: the sum of each channel over the coloured
/// particles never changes at that precision (the visible bytes' sum stays within one level per
/// particle of it), and the result is the same on any number of workers.
void setColourMixing(World& world, float rate);
/// The colour mixing rate (unit: 1/s; 0 = off).
float colourMixing(const World& world);

// ---- Positions between steps -----------------------------------------------------------------
// A game that draws faster than its world steps (a 144 Hz display, 240 Hz sub-steps) draws the
// particles between the last two simulated sub-steps. With interpolation on, the world keeps
// each particle's position at the start of its last sub-step ("previous"); the picture is drawn
// `interpolationFactor` of the way from there to the current position. The factor is
// `carriedTime() / substepLength() + 1/2`: the picture shows the liquid half a sub-step behind
// the frames given, so the drawn time advances exactly as the frames' time does, every frame,
// also when a frame simulates no sub-step (docs/groups.md, "Positions between steps").
// The explicit solver steps whole frames: its factor is 1 (the current positions).

/// Which previous positions a world keeps (`setInterpolation`). Thread rule: a plain value.
enum class Interpolation : uint8_t {
    /// None (the default): the world keeps nothing and pays nothing.
    Off,
    /// The positions at the start of the last simulated sub-step, for a game that steps its
    /// world with each display frame's time: `interpolationFactor` gives the factor.
    Substep,
    /// The positions at the start of the last `World::step` that simulated a sub-step, for a
    /// game that steps fixed ticks (`step(1/60)` from an accumulator) and draws faster: the game
    /// passes its own factor, the fraction of a tick its accumulator holds after the ticks it
    /// ran, to `interpolatedPositions` (and `fluid::gl::ParticleSpans::factor`); the picture is
    /// one tick behind. `interpolationFactor` reads 1 in this mode. Both solvers.
    Step,
};

/// Chooses which previous positions the world keeps (`Interpolation`; off by default; the
/// setting is saved in snapshots, the previous positions are not: a loaded world's previous
/// positions are its current ones). Setting a mode other than `Off` sets every previous
/// position to the current one. Thread rule: between steps.
void setInterpolation(World& world, Interpolation mode);
/// `setInterpolation(world, on ? Interpolation::Substep : Interpolation::Off)`.
void setInterpolation(World& world, bool on);
/// The world's interpolation mode. Thread rule: between steps, any number of readers.
Interpolation interpolation(const World& world);
/// True when the world keeps previous positions (a mode other than `Off`).
bool interpolating(const World& world);
/// How far between the previous and the current positions to draw (unit: 1; range [0, 1]):
/// in `Interpolation::Substep`, `carriedTime() / substepLength() + 0.5` clamped to [0, 1] for
/// the position-based solver and 1 for the explicit solver; 1 otherwise.
float interpolationFactor(const World& world);
/// Previous positions x and y per array index (unit: m; empty while interpolation is off). New,
/// emitted, moved (`moveGroup`) and loaded particles have previous = current.
std::span<const float> previousPositionX(const World& world);
/// See `previousPositionX`.
std::span<const float> previousPositionY(const World& world);
/// Writes `previous + factor (current - previous)` for every particle (the current positions
/// while interpolation is off) to `x` and `y`, at most their common size; returns
/// `World::particleCount()`. `factor` (unit: 1; range [0, 1]; default: `interpolationFactor`,
/// pass a negative value for it); throws `fluid::Error` naming it when out of range or NaN.
uint32_t interpolatedPositions(const World& world, std::span<float> x, std::span<float> y,
                               float factor = -1.0f);

} // namespace fluid
