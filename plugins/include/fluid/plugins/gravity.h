// fluid — built-in force plugin: uniform gravity.
#pragma once

#include <fluid/plugin.h>

#include <array>

namespace fluid {

/// "force.gravity": a uniform acceleration (seed eq. 2.7's g), the same for every particle.
/// Set both components to 0 for zero gravity. Thread rule: see `ForcePlugin`.
class GravityForce final : public ForcePlugin {
public:
    /// Registry type string.
    static constexpr std::string_view kType = "force.gravity";
    /// Parameters: gx, gy.
    static constexpr std::array<ParamDecl, 2> kParams{{
        {"gx", "m/s^2", 0.0, -1000.0, 1000.0, "Acceleration along x."},
        {"gy", "m/s^2", -9.81, -1000.0, 1000.0, "Acceleration along y (Earth: -9.81)."},
    }};
    /// Earth gravity, (0, -9.81) m/s^2.
    GravityForce() : ForcePlugin(kType, kParams) {}
    /// Gravity (gx, gy) (unit: m/s^2; each in [-1000, 1000]).
    GravityForce(float gx, float gy);
    /// Adds (gx, gy) to every particle in the range.
    void apply(const ForceContext& context, uint32_t begin, uint32_t end) override;
};

} // namespace fluid
