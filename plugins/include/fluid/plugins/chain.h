// fluid — built-in boundary plugin: a chain of thin wall segments, open or closed.
#pragma once

#include <fluid/plugins/kinematic_shape.h>

#include <array>
#include <memory>
#include <span>
#include <vector>

namespace fluid {

namespace geometry {
class SegmentSet;
}

/// "boundary.chain": a polyline of thin walls (one segment thick) that fluid on either side
/// cannot cross: a splitter in a tank, a thin lid, a funnel, a closed loop. `points` in the
/// local frame (unit: m; 2 to 4096, 3 when closed; coordinates in [-1e5, 1e5]; consecutive
/// points distinct); `closed` = 1 joins the last point to the first. Both are checked when set,
/// whichever comes last (see `KinematicShape`). Placed and moved by the pose parameters of
/// `KinematicShape`. At most `kMaxSamples` samples: about 20 km of wall at water spacing.
///
/// Samples: one row along the segments at the spacing (both sides see it). `project` follows
/// each particle's path: one that crosses a segment goes back to the side it came from (keeping
/// its motion along the wall), and particles keep a clearance of half a spacing from every
/// segment (round the open ends too), never by crossing one. Thread rule: see `BoundaryPlugin`.
class ChainBoundary final : public KinematicShape {
public:
    /// Registry type string.
    static constexpr std::string_view kType = "boundary.chain";
    /// Parameter indices (after the pose parameters).
    enum : std::size_t { kPoints = kPoseParamCount, kClosed };
    /// Parameters: pose, velocities, friction, the points and the closed flag.
    static constexpr auto kParams = withPoseParams(std::array<ParamDecl, 2>{{
        {"points", "m", 0.0, 2.0, 4096.0, "Polyline points in the local frame.", ParamType::Points},
        {"closed", "1", 0.0, 0.0, 1.0, "1 joins the last point to the first (a loop)."},
    }});
    /// Clearance particles keep from the segments, in spacings (unit: 1).
    static constexpr double kClearance = 0.5;

    /// A chain with no points yet (set them with `setPoints("points", ...)` before the first
    /// step), open, at the origin, at rest, friction 1.
    ChainBoundary();
    /// A static chain through `points` (unit: m), closed when `closed`.
    explicit ChainBoundary(std::span<const glm::vec2> points, bool closed = false);
    /// Destroyed by its owner, not while a step runs.
    ~ChainBoundary() override;
    /// A wall: it projects after the solids, before the containers.
    BoundaryRole role() const override { return BoundaryRole::Wall; }

    /// The segments in the local frame, as last built (unit: m). Valid after the first `prepare`.
    std::span<const ShapeSegment> segments() const;

private:
    void validate() const override;
    // The checks of `validate` for a chain whose points are set (throws for none).
    void checkShape() const;
    void build(double spacing, double support, std::vector<glm::dvec2>& out,
               LocalBounds& bounds) override;
    bool collide(glm::dvec2 prev, glm::dvec2 cur, double spacing, double eps,
                 Contact& out) const override;
    double reach(double spacing) const override { return kClearance * spacing; }
    bool crossesAny(glm::dvec2 from, glm::dvec2 to) const;

    std::unique_ptr<geometry::SegmentSet> m_segments;
};

} // namespace fluid
