// fluid — built-in force plugin: vortex (whirlpool) with a Rankine profile.
#pragma once

#include <fluid/plugin.h>

#include <array>

namespace fluid {

/// "force.vortex": a whirlpool around (x, y) that drives each particle's tangential velocity
/// towards a Rankine vortex [Rankine 1858]: solid-body rotation inside the core, a free vortex
/// outside,
///
///     u(r) = V r / R  (r <= R),   u(r) = V R / r  (r > R),   V = `speed`, R = `radius`,
///
/// counter-clockwise for V > 0. The tangential acceleration is a drag towards u(r),
///
///     a_t = lambda (u(r) - v . t) t,   t = (-dy, dx) / r,   lambda = (1 - exp(-k dt)) / dt,
///
/// k = `rate`, so a lone particle's tangential velocity relaxes to u(r) as exp(-k t) for any
/// sub-step (never overshooting, unlike k dt explicit drag), and a spun-up pool stays at its
/// speed instead of accelerating forever. This part is purely tangential: it changes neither
/// radial velocity nor kinetic energy of radial motion. `pull` (m/s^2) adds an inward
/// acceleration with the same profile (P r / R inside, P R / r outside) that can hold spinning
/// liquid in (about V^2 / R at the core). Beyond `cutoff` (when > 0) nothing. A particle on the
/// centre gets 0. Thread rule: see `ForcePlugin`.
class VortexForce final : public ForcePlugin {
public:
    /// Registry type string.
    static constexpr std::string_view kType = "force.vortex";
    /// Parameter indices.
    enum : std::size_t { kX, kY, kSpeed, kRadius, kRate, kPull, kCutoff };
    /// Parameters: centre, swirl speed at the core radius, core radius, spin-up rate, pull,
    /// cut-off.
    static constexpr std::array<ParamDecl, 7> kParams{{
        {"x", "m", 0.0, -1e5, 1e5, "Centre x."},
        {"y", "m", 0.0, -1e5, 1e5, "Centre y."},
        {"speed", "m/s", 1.0, -1e3, 1e3,
         "Tangential speed at the core radius; positive turns counter-clockwise."},
        {"radius", "m", 0.2, 1e-3, 1e4,
         "Core radius: solid-body rotation inside, speed ~ 1/r outside."},
        {"rate", "1/s", 5.0, 0.0, 1e4,
         "How fast particles take up the swirl: velocity error decays as exp(-rate t)."},
        {"pull", "m/s^2", 0.0, -1e4, 1e4, "Inward acceleration at the core radius (optional)."},
        {"cutoff", "m", 0.0, 0.0, 1e5, "No effect beyond this distance; 0 = unlimited."},
    }};
    /// A 1 m/s counter-clockwise vortex with a 0.2 m core at the origin, rate 5/s, no pull.
    VortexForce() : ForcePlugin(kType, kParams) {}
    /// A vortex at `centre` (unit: m) turning at `speed` (unit: m/s; [-1e3, 1e3], CCW > 0) at
    /// core radius `radius` (unit: m; [1e-3, 1e4]), spin-up `rate` (unit: 1/s; [0, 1e4]).
    VortexForce(glm::vec2 centre, float speed, float radius, float rate = 5.0f);
    /// Adds the swirl (and pull) to particles [begin, end).
    void apply(const ForceContext& context, uint32_t begin, uint32_t end) override;
};

} // namespace fluid
