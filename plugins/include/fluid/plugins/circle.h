// fluid — built-in boundary plugin: a solid disc, static or kinematic.
#pragma once

#include <fluid/plugins/kinematic_shape.h>

#include <array>
#include <vector>

namespace fluid {

/// "boundary.circle": a solid disc of `radius` centred on the local origin, fluid outside (a
/// post, a ball, a rotating drum). Placed and moved by the pose parameters of `KinematicShape`.
///
/// Samples: rings at (l + 0.5) spacing inside the rim, as many as cover one support radius
/// (down to the centre for small discs), each ring evenly split into pieces about one spacing
/// long. `project` puts a particle whose path entered the disc back on the rim (radially, so it
/// keeps its motion round it; at the entry point if it went past the centre), and one found
/// inside (swept over) on the nearest rim point. At most `kMaxSamples` samples: a radius of
/// about 800 m at water spacing (0.01 m, 4 rings); the first step throws `fluid::Error` beyond.
/// Thread rule: see `BoundaryPlugin`.
class CircleBoundary final : public KinematicShape {
public:
    /// Registry type string.
    static constexpr std::string_view kType = "boundary.circle";
    /// Parameter indices (after the pose parameters).
    enum : std::size_t { kRadius = kPoseParamCount };
    /// Parameters: pose, velocities, friction, and the radius.
    static constexpr auto kParams = withPoseParams(std::array<ParamDecl, 1>{{
        {"radius", "m", 0.1, 1e-4, 1e4, "Radius of the disc."},
    }});
    /// A disc of radius 0.1 m at the origin, at rest, friction 1.
    CircleBoundary() : KinematicShape(kType, kParams) {}
    /// A static disc centred at `center` (unit: m) with `radius` (unit: m; range [1e-4, 1e4]).
    CircleBoundary(glm::vec2 center, float radius);

private:
    void build(double spacing, double support, std::vector<glm::dvec2>& out,
               LocalBounds& bounds) override;
    bool collide(glm::dvec2 prev, glm::dvec2 cur, double spacing, double eps,
                 Contact& out) const override;
    bool insideLocal(glm::dvec2 local) const override;

    double m_radius = 0.1;
};

} // namespace fluid
