// fluid — built-in force plugin: damping zone.
#pragma once

#include <fluid/plugin.h>

#include <array>

namespace fluid {

/// "force.damping": slows particles inside an axis-aligned zone (a pool of syrup, a calm area,
/// a sponge layer at a level's edge; everywhere by default; nothing outside, nor when
/// min > max):
///
///     a = -lambda v,   lambda = (1 - exp(-c dt)) / dt   (c as dt -> 0),   c = `rate`,
///
/// the exact integral of dv/dt = -c v over the sub-step: a lone particle's speed decays as
/// exp(-c t) and its kinetic energy as exp(-2 c t), for any rate and sub-step (explicit drag
/// would reverse velocities once c dt > 1). Direction of motion is kept. Thread rule: see
/// `ForcePlugin`.
class DampingZoneForce final : public ForcePlugin {
public:
    /// Registry type string.
    static constexpr std::string_view kType = "force.damping";
    /// Parameter indices.
    enum : std::size_t { kRate, kMinX, kMinY, kMaxX, kMaxY };
    /// Parameters: damping rate and zone.
    static constexpr std::array<ParamDecl, 5> kParams{{
        {"rate", "1/s", 1.0, 0.0, 1e4, "Damping rate c: speed decays as exp(-c t) inside."},
        {"minX", "m", -1e6, -1e6, 1e6, "Zone's left edge (default: everywhere)."},
        {"minY", "m", -1e6, -1e6, 1e6, "Zone's bottom edge (default: everywhere)."},
        {"maxX", "m", 1e6, -1e6, 1e6, "Zone's right edge (default: everywhere)."},
        {"maxY", "m", 1e6, -1e6, 1e6, "Zone's top edge (default: everywhere)."},
    }};
    /// Damping at 1/s everywhere.
    DampingZoneForce() : ForcePlugin(kType, kParams) {}
    /// Damping `rate` (unit: 1/s; [0, 1e4]) inside [min, max] (unit: m; [-1e6, 1e6]).
    DampingZoneForce(float rate, glm::vec2 min, glm::vec2 max);
    /// Adds the damping to particles [begin, end) inside the zone.
    void apply(const ForceContext& context, uint32_t begin, uint32_t end) override;
};

} // namespace fluid
