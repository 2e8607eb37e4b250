// fluid — built-in boundary plugin: a solid polygon, convex or concave, static or kinematic.
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

/// "boundary.polygon": a solid polygon the fluid stays outside of (an obstacle, a sloped floor,
/// a paddle; a container when the polygon is a thick U or bowl around the fluid). `vertices` in
/// the local frame (unit: m; 3 to 4096, coordinates in [-1e5, 1e5], either winding, convex or
/// concave, simple: no edge may cross another, no repeated vertex, some area), checked by
/// `setPoints` (see `KinematicShape`). Placed and moved by the pose parameters of
/// `KinematicShape`. At most `kMaxSamples` samples: a perimeter of about 5 km at water spacing.
///
/// Samples: layers at (l + 0.5) spacing inside every edge, as many as cover one support radius,
/// arcs around the reflex corners (where the solid wraps round the fluid), shallow layers first
/// and none closer than 0.55 spacing to another, so that the fluid next to any part of the
/// surface sees a full neighbourhood. `project` puts a particle whose path entered the polygon
/// back outside the edge it crossed (keeping its motion along the edge), and one found inside
/// (swept over by the moving polygon) on the nearest surface point. Thread rule: see
/// `BoundaryPlugin`.
class PolygonBoundary final : public KinematicShape {
public:
    /// Registry type string.
    static constexpr std::string_view kType = "boundary.polygon";
    /// Parameter indices (after the pose parameters).
    enum : std::size_t { kVertices = kPoseParamCount };
    /// Parameters: pose, velocities, friction, and the vertices.
    static constexpr auto kParams = withPoseParams(std::array<ParamDecl, 1>{{
        {"vertices", "m", 0.0, 3.0, 4096.0,
         "Vertices in the local frame, either winding; convex or concave, not self-crossing.",
         ParamType::Points},
    }});
    /// A polygon with no vertices yet (set them with `setPoints("vertices", ...)` before the
    /// first step), at the origin, at rest, friction 1.
    PolygonBoundary();
    /// A static polygon with `vertices` (local = world frame at the default pose; unit: m).
    explicit PolygonBoundary(std::span<const glm::vec2> vertices);
    /// Destroyed by its owner, not while a step runs.
    ~PolygonBoundary() override;

    /// True when the local point lies inside the polygon (even-odd; unit: m). Valid after the
    /// first `prepare`.
    bool containsLocal(glm::dvec2 local) const;

private:
    void validate() const override;
    void build(double spacing, double support, std::vector<glm::dvec2>& out,
               LocalBounds& bounds) override;
    bool collide(glm::dvec2 prev, glm::dvec2 cur, double spacing, double eps,
                 Contact& out) const override;
    bool insideLocal(glm::dvec2 local) const override;
    bool pushOut(glm::dvec2 c, double eps, Contact& out) const;
    bool admissible(glm::dvec2 from, glm::dvec2 to) const;

    // The edges, counter-clockwise (the solid on their left), with their grid.
    std::unique_ptr<geometry::SegmentSet> m_edges;
};

} // namespace fluid
