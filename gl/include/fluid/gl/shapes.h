// fluid::gl — shapes tessellated into triangles on the CPU: filled polygons, discs, thick
// lines and outlines. Core-profile GL has no wide lines, so every outline is triangles.
#pragma once
#include <cstdint>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>
#include <span>
#include <vector>

namespace fluid::gl {

/// One vertex of a shape triangle.
struct ShapeVertex {
    /// Position (unit: m, world coordinates).
    glm::vec2 position;
    /// Colour with straight alpha (unit: 1; each in [0, 1]).
    glm::vec4 colour;
};

/// A list of coloured triangles in world coordinates, drawn in the order added. Build it each
/// frame on any thread (a plain container); the `Renderer` uploads it.
class ShapeBatch {
public:
    /// Removes every triangle (keeps the memory).
    void clear();
    /// A filled simple polygon (convex or concave, either winding; at least 3 points) (unit: m).
    /// Self-intersecting polygons draw but may show gaps.
    void polygon(std::span<const glm::vec2> points, glm::vec4 colour);
    /// A filled axis-aligned rectangle [lo, hi] (unit: m).
    void rect(glm::vec2 lo, glm::vec2 hi, glm::vec4 colour);
    /// A filled disc of `radius` (unit: m; > 0) around `center`; `segments` 0 picks enough to
    /// look round at any zoom up to 4000 px/m.
    void disc(glm::vec2 center, float radius, glm::vec4 colour, uint32_t segments = 0);
    /// A ring from `radius - width` to `radius` (unit: m); a disc when `width >= radius`.
    void ring(glm::vec2 center, float radius, float width, glm::vec4 colour, uint32_t segments = 0);
    /// A line of `width` (unit: m; > 0) through `points` with mitred joints (bevelled when
    /// sharp); `closed` joins the last point to the first. Fewer than 2 points draw nothing.
    void polyline(std::span<const glm::vec2> points, float width, glm::vec4 colour,
                  bool closed = false);
    /// One segment of `width` (unit: m).
    void line(glm::vec2 a, glm::vec2 b, float width, glm::vec4 colour);
    /// The triangles, three vertices each.
    std::span<const ShapeVertex> vertices() const { return m_vertices; }

private:
    std::vector<ShapeVertex> m_vertices;
};

} // namespace fluid::gl
