// fluid — built-in boundary plugin: axis-aligned box container.
#pragma once

#include <fluid/plugin.h>

#include <array>

namespace fluid {

/// "boundary.box": an axis-aligned box the fluid lives inside (a tank). The walls are solid
/// beyond the inner rectangle [minX, maxX] x [minY, maxY]: boundary samples fill them layer by
/// layer at half a spacing behind the surface [Adami 2012], and `project` keeps every particle
/// centre inside the rectangle. Thread rule: see `BoundaryPlugin`.
class BoxContainer final : public BoundaryPlugin {
public:
    /// Registry type string.
    static constexpr std::string_view kType = "boundary.box";
    /// Parameter indices.
    enum : std::size_t { kMinX, kMinY, kMaxX, kMaxY, kFriction, kOpenTop };
    /// Parameters: the inner rectangle, wall friction, and whether the top wall is left out.
    static constexpr std::array<ParamDecl, 6> kParams{{
        {"minX", "m", -1.0, -1e5, 1e5, "Inner left wall."},
        {"minY", "m", 0.0, -1e5, 1e5, "Inner floor."},
        {"maxX", "m", 1.0, -1e5, 1e5, "Inner right wall."},
        {"maxY", "m", 2.0, -1e5, 1e5, "Inner ceiling."},
        {"friction", "1", 1.0, 0.0, 10.0,
         "Wall viscosity scale: 0 free slip, 1 the fluid's own viscosity (no slip)."},
        {"openTop", "1", 0.0, 0.0, 1.0, "1 leaves the ceiling out (an open tank)."},
    }};
    /// The default box: [-1, 1] x [0, 2] m, closed, wall friction 1 (the fluid's viscosity).
    BoxContainer() : BoundaryPlugin(kType, kParams) {}
    /// A closed box with inner corners `min` and `max` (unit: m; min < max on both axes, else
    /// throws as `checkParams`), wall friction 1.
    BoxContainer(float minX, float minY, float maxX, float maxY);

    /// Throws `fluid::Error` "plugin 'boundary.box': the inner rectangle [minX, maxX] x [minY,
    /// maxY] is empty; expected minX < maxX and minY < maxY" unless both hold.
    void checkParams() const override;
    /// Lays the wall samples (only when the box or the spacing changed); throws as
    /// `checkParams` for an empty rectangle.
    void prepare(const StepContext& context) override;
    /// Clamps particle centres into the inner rectangle; removes velocity into the wall.
    void project(const ProjectContext& context, uint32_t begin, uint32_t end) override;
    /// The `friction` parameter.
    float friction() const override { return static_cast<float>(value(kFriction)); }
    /// A container: it projects after every solid and wall.
    BoundaryRole role() const override { return BoundaryRole::Container; }
    /// True outside the box (below, beside, or above a closed one): where `project` acts.
    bool contains(glm::vec2 point) const override;

private:
    void onParamChanged(std::size_t index) override;
    float m_builtSpacing = 0.0f;
    float m_builtSupport = 0.0f;
};

} // namespace fluid
