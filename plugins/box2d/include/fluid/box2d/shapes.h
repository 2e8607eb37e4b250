// fluid — the shapes and masses a coupled Box2D body may have: one set of checks for level files,
// the C API's fluid_level_add_body and Box2D saves, run before Box2D sees the shape (Box2D
// asserts on degenerate ones) and before the coupling steps a body it would throw.
#pragma once

#include <fluid/world.h>

#include <glm/vec2.hpp>

#include <span>
#include <string>

namespace fluid::box2d {

/// Box2D's linear slop (unit: m; b2_linearSlop): the smallest box side, circle radius and
/// distance between polygon vertices Box2D handles, and the square root of the smallest
/// polygon area (2.5e-5 m^2). Any thread.
inline constexpr float kLinearSlop = 0.005f;

/// A dynamic body's polygon fixture with a corner sharper than this (unit: degrees) must hold a
/// circle of radius one fluid spacing (`coarsestSpacing`; 1 cm for the water preset): smaller
/// pointed polygons hold too few boundary samples near their corners, and the fluid throws
/// them (figures: docs/box2d.md, "Shapes and masses"). Boxes, circles, and static and
/// kinematic bodies of any shape are not held to it. Any thread.
inline constexpr double kAcuteCorner = 89.0;

/// The lightest a coupled dynamic body may be (unit: 1): its mass over its fixtures' area, as a
/// share of the areal density of the densest material in the world (`arealDensity`). Lighter
/// bodies are thrown by the fluid's pressure faster than the coupling can answer (figures:
/// docs/box2d.md, "Shapes and masses"). Any thread.
inline constexpr float kMinDensityRatio = 0.05f;

/// What is wrong with a shape: `message` (empty when nothing) says what, and what the smallest
/// shape that works is; `vertex` is the polygon vertex it is about (-1: the whole shape).
struct ShapeProblem {
    /// One line, without the caller's prefix.
    std::string message;
    /// Polygon vertex index, or -1.
    int vertex = -1;
    /// True when there is a problem.
    explicit operator bool() const { return !message.empty(); }
};

/// Checks a polygon fixture's vertices (unit: m, in the body's frame) for Box2D: 3 to 8 of them,
/// finite, at least `kLinearSlop` apart, an area of at least kLinearSlop^2, strictly convex and
/// simple (either winding); with `spacing` > 0 (unit: m; a dynamic body's: `coarsestSpacing`)
/// also, when some corner is sharper than `kAcuteCorner`, an inscribed circle of that radius.
/// Pure function; any thread.
ShapeProblem checkPolygon(std::span<const glm::vec2> vertices, float spacing);

/// `checkPolygon`'s last test alone, on a polygon Box2D already holds: with `spacing` > 0, a
/// polygon with a corner sharper than `kAcuteCorner` must hold a circle of that radius. Pure
/// function; any thread.
ShapeProblem checkPointedPolygon(std::span<const glm::vec2> vertices, float spacing);

/// The radius of the largest circle inside a convex polygon (unit: m; vertices in either
/// winding, as `checkPolygon` accepts them). Pure function; any thread.
double inscribedRadius(std::span<const glm::vec2> vertices);

/// Checks a circle fixture's radius (unit: m): finite and at least `kLinearSlop`. Pure
/// function; any thread.
ShapeProblem checkCircle(float radius);

/// Checks a box fixture's width and height (unit: m; full sides): finite and at least
/// `kLinearSlop`. Pure function; any thread.
ShapeProblem checkBox(float width, float height);

/// The spacing a dynamic body's pointed polygon is measured against (unit: m): the largest
/// `World::spacing` of the world's materials, 0 for a world without one. Stepping thread.
float coarsestSpacing(const World& world);

/// The areal density the lightest dynamic body is measured against (unit: kg/m^2): the largest
/// `arealDensity` of the world's materials, 0 for a world without one. Stepping thread.
float densestArealDensity(const World& world);

/// Checks a dynamic body's mass (unit: kg), its fixtures' area (unit: m^2) and its rotational
/// inertia about its centre of mass (unit: kg m^2; ignored with `fixedRotation`) against
/// `kMinBodyMass`, `kMinBodyInertia` and `kMinDensityRatio` x `arealDensity` (unit: kg/m^2; 0
/// skips that check). Pure function; any thread.
ShapeProblem checkDynamicMass(float mass, float area, float centredInertia, bool fixedRotation,
                              float arealDensity);

} // namespace fluid::box2d
