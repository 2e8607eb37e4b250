// fluid — built-in force plugin: wind (a drag towards a wind velocity).
#pragma once

#include <fluid/plugin.h>

#include <array>

namespace fluid {

/// "force.wind": linear drag towards the wind velocity w = (vx, vy) inside an axis-aligned
/// region (everywhere by default; nothing outside it, nor when min > max):
///
///     a = lambda (w - v),   lambda = (1 - exp(-k dt)) / dt   (k as dt -> 0),   k = `rate`,
///
/// the exact integral of dv/dt = k (w - v) over the sub-step, so a lone particle's velocity
/// relaxes to the wind as v - w ~ exp(-k t) (its terminal velocity is the wind) for any rate
/// and sub-step, without the overshoot of explicit drag when k dt > 1 (or its divergence when
/// k dt > 2). Under a constant acceleration g as well, the terminal velocity is w + g / lambda:
/// w + g / k to within k dt / 2 (1% for k = 5/s at 240 sub-steps per second).
/// Thread rule: see `ForcePlugin`.
class WindForce final : public ForcePlugin {
public:
    /// Registry type string.
    static constexpr std::string_view kType = "force.wind";
    /// Parameter indices.
    enum : std::size_t { kVx, kVy, kRate, kMinX, kMinY, kMaxX, kMaxY };
    /// Parameters: wind velocity, drag rate, region.
    static constexpr std::array<ParamDecl, 7> kParams{{
        {"vx", "m/s", 1.0, -1e3, 1e3, "Wind velocity x."},
        {"vy", "m/s", 0.0, -1e3, 1e3, "Wind velocity y."},
        {"rate", "1/s", 1.0, 0.0, 1e4,
         "Drag rate k: the velocity difference to the wind decays as exp(-k t)."},
        {"minX", "m", -1e6, -1e6, 1e6, "Region's left edge (default: everywhere)."},
        {"minY", "m", -1e6, -1e6, 1e6, "Region's bottom edge (default: everywhere)."},
        {"maxX", "m", 1e6, -1e6, 1e6, "Region's right edge (default: everywhere)."},
        {"maxY", "m", 1e6, -1e6, 1e6, "Region's top edge (default: everywhere)."},
    }};
    /// A 1 m/s breeze along +x with drag rate 1/s, everywhere.
    WindForce() : ForcePlugin(kType, kParams) {}
    /// Wind `velocity` (unit: m/s; each component in [-1e3, 1e3]) with drag `rate` (unit: 1/s;
    /// [0, 1e4]), everywhere.
    WindForce(glm::vec2 velocity, float rate);
    /// Adds the drag to particles [begin, end) inside the region.
    void apply(const ForceContext& context, uint32_t begin, uint32_t end) override;
};

} // namespace fluid
