// fluid — built-in force plugin: point (radial) gravity.
#pragma once

#include <fluid/plugin.h>

#include <array>

namespace fluid {

/// "force.point_gravity": attraction towards a point (a planetoid, a black hole, a zero-g level's
/// centre of mass), softened so that it stays finite at the centre:
///
///     a(r) = -g0 r0^n r_vec / (|r_vec|^2 + eps^2)^((n + 1) / 2),   r_vec = x - centre,
///
/// g0 = `strength`, r0 = `referenceRadius`, n = `falloff`, eps = `softening`. Without softening
/// |a| = g0 (r0 / r)^n: g0 is the pull at the reference radius, n = 2 is Newton's inverse
/// square (GM = g0 r0^2), n = 1 the 1/r pull of a 2D (line) mass, n = 0 a constant pull of g0.
/// The softening is Plummer's: the pull rises smoothly to 0 at the centre instead of diverging
/// (the largest pull is near r = eps). eps is at least the particle spacing
/// (`StepContext::sampleSpacing`); a smaller `softening` acts as the spacing. The pull is at most
/// a tenth of the spacing per sub-step squared (`kMaxPullShare` s / dt^2: 57.6 m/s^2 for 1 cm
/// water at the game preset's 240 Hz sub-steps): a stronger pull packs liquid at the centre
/// faster than a sub-step's constraints part it (docs/plugins.md, Point gravity). Negative
/// strength repels.
/// Beyond `cutoff` (when > 0) the field is 0 (an island of gravity in an otherwise zero-g level).
/// A particle exactly on the centre gets 0, never NaN. Thread rule: see `ForcePlugin`.
class PointGravityForce final : public ForcePlugin {
public:
    /// Registry type string.
    static constexpr std::string_view kType = "force.point_gravity";
    /// Parameter indices.
    enum : std::size_t { kX, kY, kStrength, kReferenceRadius, kFalloff, kSoftening, kCutoff };
    /// Parameters: centre, pull at the reference radius, falloff exponent, softening, cut-off.
    static constexpr std::array<ParamDecl, 7> kParams{{
        {"x", "m", 0.0, -1e5, 1e5, "Centre x."},
        {"y", "m", 0.0, -1e5, 1e5, "Centre y."},
        {"strength", "m/s^2", 9.81, -1e4, 1e4,
         "Pull at the reference radius (without softening); negative repels."},
        {"referenceRadius", "m", 1.0, 1e-3, 1e4,
         "Distance at which the pull equals the strength (a planetoid's surface)."},
        {"falloff", "1", 2.0, 0.0, 3.0,
         "Exponent n of |a| ~ 1/r^n: 2 Newton, 1 a 2D (line) mass, 0 constant."},
        {"softening", "m", 0.05, 0.0, 1e4,
         "Plummer softening: the pull goes smoothly to 0 inside about this distance; at least "
         "the particle spacing."},
        {"cutoff", "m", 0.0, 0.0, 1e5, "No pull beyond this distance; 0 = unlimited."},
    }};
    /// Newton's pull of 9.81 m/s^2 at 1 m from the origin, softening 0.05 m, no cut-off.
    PointGravityForce() : ForcePlugin(kType, kParams) {}
    /// A pull of `strength` (unit: m/s^2; [-1e4, 1e4]) at `referenceRadius` (unit: m;
    /// [1e-3, 1e4]) from `centre` (unit: m), falling off as 1/r^`falloff` ([0, 3]); softening
    /// 0.05 m, no cut-off.
    PointGravityForce(glm::vec2 centre, float strength, float referenceRadius,
                      float falloff = 2.0f);
    /// Adds the pull to particles [begin, end).
    void apply(const ForceContext& context, uint32_t begin, uint32_t end) override;
    /// Reads the particle spacing the softening and the cap follow.
    void prepare(const StepContext& context) override;

    /// The largest pull as a share of the particle spacing per sub-step squared (unit: 1).
    static constexpr double kMaxPullShare = 0.1;

private:
    double m_spacing = 0.0; // StepContext::sampleSpacing of the step (unit: m)
};

} // namespace fluid
