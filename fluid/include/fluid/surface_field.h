// fluid — the liquid's surface as it is drawn: one field, shared by the renderer (fluid::gl's
// metaball view), the ray casts and `sample` (fluid/query.h), so that a laser stops where the
// player sees the water.
#pragma once

#include <glm/vec2.hpp>

#include <cmath>
#include <numbers>

namespace fluid {

class World;

/// The field whose level set is the liquid's drawn surface (docs/rendering.md, "The field and
/// its surface"). Each particle adds the kernel `w = (1 - r^2/R^2)^3` (0 beyond `R =
/// fieldRadius x` its material's spacing); the field at a point is `max(k sum w, d max w)`, with
/// `k = kernelWeight()` (a filled lattice sums to `kInteriorSum`) and `d = dropletLevel()` (every
/// particle shows at least as a disc of half a spacing); the liquid is where the field is at
/// least `threshold`. Plain values; any thread.
struct SurfaceField {
    /// What the field sums to inside the liquid (unit: 1).
    static constexpr float kInteriorSum = 1.2f;
    /// The threshold the droplet level is made for: at it a lone particle shows as a disc of
    /// half a spacing (unit: 1).
    static constexpr float kDropletThreshold = 0.6f;
    /// Range of `fieldRadius` (unit: 1).
    static constexpr float kMinRadius = 1.0f, kMaxRadius = 4.0f;
    /// Range of `threshold` (unit: 1).
    static constexpr float kMinThreshold = 0.05f, kMaxThreshold = 4.0f;

    /// A particle's reach over its material's spacing (unit: 1; [1, 4]).
    float fieldRadius = 2.0f;
    /// Field level at the liquid's surface (unit: 1; [0.05, 4]); lower makes the liquid fatter.
    /// At 0.6 the surface stands about half a spacing outside the outer particles' centres.
    float threshold = 0.6f;

    /// `k`: the kernel integrates to pi R^2 / 4 and a particle stands for spacing^2 of area,
    /// so this weight makes a filled lattice sum to `kInteriorSum` whatever the radius (unit:
    /// 1).
    constexpr float kernelWeight() const {
        return kInteriorSum * 4.0f / (std::numbers::pi_v<float> * fieldRadius * fieldRadius);
    }
    /// `d`: the largest single kernel's scale, so that at `kDropletThreshold` every particle
    /// shows at least as a disc of radius half a spacing (unit: 1).
    float dropletLevel() const {
        const float edge = 0.5f / fieldRadius;
        return kDropletThreshold / std::pow(1.0f - edge * edge, 3.0f);
    }
};

/// Throws `fluid::Error` "<function>: field.fieldRadius = <value> is out of range [1, 4] (unit:
/// 1)" (or `threshold`, [0.05, 4]) for a value outside its range or not finite. Any thread.
void validate(const SurfaceField& field, const char* function);

/// The field at `point` (unit: 1; 0 where no particle reaches; the liquid is where it is at least
/// `field.threshold`). Throws `fluid::Error` naming the value for a non-finite point or a field
/// `validate` refuses, and with `ErrorCode::WrongState` during the world's own step. Cost: the
/// query grid's cells around the point. Thread rule: as `queryParticles` (fluid/query.h).
float surfaceField(const World& world, glm::vec2 point, const SurfaceField& field = {});

} // namespace fluid
