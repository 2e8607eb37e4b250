// fluid — built-in force plugin: pointer push and pull (the mouse or a finger).
#pragma once

#include <fluid/plugin.h>

#include <array>

namespace fluid {

/// "force.pointer": pushes particles away from (strength > 0) or pulls them towards
/// (strength < 0) a point the host moves every frame (the mouse), inside a radius R:
///
///     a = S A g(r / R) r_vec / r,   g(q) = q (1 - q^2)^2 / g_max  (q < 1),   0 beyond R,
///
/// S = `strength`, A = `active`, g_max = 16 / (25 sqrt 5) so that |a| peaks at |S| at
/// r = R / sqrt 5. g rises linearly from the centre (a pull holds liquid at the pointer like a
/// spring instead of flinging it through a direction jump; no division by r, so r = 0 is safe)
/// and reaches 0 with zero slope at R (no kick when a particle crosses the rim).
/// Host use, between steps on the stepping thread: `setParam("x", ...)`, `setParam("y", ...)`
/// each frame, `active` 1 while the button is held (values in between scale the strength, for a
/// pressure-sensitive input), 0 otherwise. Thread rule: see `ForcePlugin`.
class PointerForce final : public ForcePlugin {
public:
    /// Registry type string.
    static constexpr std::string_view kType = "force.pointer";
    /// Parameter indices.
    enum : std::size_t { kX, kY, kRadius, kStrength, kActive };
    /// Parameters: pointer position, reach, strength, on/off.
    static constexpr std::array<ParamDecl, 5> kParams{{
        {"x", "m", 0.0, -1e5, 1e5, "Pointer x (the host sets it each frame)."},
        {"y", "m", 0.0, -1e5, 1e5, "Pointer y (the host sets it each frame)."},
        {"radius", "m", 0.25, 1e-3, 1e4, "Reach: no effect at or beyond this distance."},
        {"strength", "m/s^2", 30.0, -1e4, 1e4,
         "Largest acceleration (at radius / sqrt 5); positive pushes away, negative pulls in."},
        {"active", "1", 0.0, 0.0, 1.0,
         "0 off, 1 on (button held); values in between scale the strength."},
    }};
    /// An inactive pointer at the origin: radius 0.25 m, strength 30 m/s^2 (a push).
    PointerForce() : ForcePlugin(kType, kParams) {}
    /// A pointer of `radius` (unit: m; [1e-3, 1e4]) and `strength` (unit: m/s^2; [-1e4, 1e4],
    /// positive pushes), inactive, at the origin.
    PointerForce(float radius, float strength);
    /// Moves the pointer (unit: m; each in [-1e5, 1e5]) and sets `active` (unit: 1; [0, 1]).
    /// Between steps, stepping thread. Throws `fluid::Error` as `setParam`.
    void setPointer(glm::vec2 position, float active);
    /// Adds the push or pull to particles [begin, end).
    void apply(const ForceContext& context, uint32_t begin, uint32_t end) override;
};

} // namespace fluid
