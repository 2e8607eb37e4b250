// fluid::gl — an OpenGL 3.3 core renderer for fluid worlds: metaball liquid, the seed report's
// pressure view, a particle view coloured by speed, and filled shapes (walls, bodies) drawn
// under and over the liquid. A game links fluid::gl, creates a context (SFML, SDL, GLFW, ...),
// calls `loadFunctions()` once and feeds a `Renderer` with the world's particle spans.
// Public headers hold no GL types, so a game never has to order its GL includes around ours.
#pragma once
#include <cstdint>
#include <fluid/error.h>
#include <fluid/gl/camera.h>
#include <fluid/gl/shapes.h>
#include <fluid/groups.h>
#include <fluid/surface_field.h>
#include <fluid/world.h>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace fluid::gl {

/// Loads the GL entry points (GLEW, with `glewExperimental`) for the current context and checks
/// that it is OpenGL 3.3 core or later. Call once per process after the first context is
/// current; later calls (after one succeeded) do nothing. Clears any GL error `glewInit` leaves
/// behind (GLEW 1.x raises GL_INVALID_ENUM in core contexts; GLEW 2.2 on Mesa raises none).
/// Throws `fluid::Error` naming the version and renderer found when the context is older than
/// 3.3 or GLEW fails (GLEW built for GLX cannot load through EGL-only contexts).
/// Thread rule: the thread whose context is current.
void loadFunctions();

/// "OpenGL 4.5 (Core Profile) Mesa 22.3.6 / llvmpipe (LLVM 15.0.6, 256 bits)": the current
/// context's version and renderer strings. Thread rule: the thread whose context is current.
std::string describeContext();

/// Reads and clears every pending GL error of the current context; returns how many there
/// were (unit: count) and appends their names ("GL_INVALID_ENUM") to `names` if given.
/// Thread rule: the thread whose context is current.
uint32_t drainErrors(std::vector<std::string>* names = nullptr);

/// The text of an embedded shader ("metaball_composite.frag"); empty if there is none. The
/// shaders in shaders/ are compiled into the library at build time, so nothing is read from
/// disk at run time. Needs no context. Thread rule: any thread.
std::string_view shaderSource(std::string_view name);

/// Names of all embedded shaders, sorted. Thread rule: any thread.
std::span<const std::string_view> shaderNames();

/// The particle data the renderer draws, one entry per particle in each span. Every span must
/// have the size of `x`, except that `pressure`, `vx` and `vy` may be empty when the view does
/// not use them (they then read as 0) and `material` may be empty (every particle gets the
/// first style). Valid for the duration of the `render` call only.
struct ParticleSpans {
    /// Positions (unit: m).
    std::span<const float> x, y;
    /// Velocities (unit: m/s); read by the particle view.
    std::span<const float> vx, vy;
    /// Pressure (unit: Pa); read by the pressure view.
    std::span<const float> pressure;
    /// Material index per particle (index into `Renderer::setMaterials`).
    std::span<const uint16_t> material;
    /// Colour per particle, packed RGBA8 (`fluid::Colour::pack`, sRGB; may be empty): the
    /// metaball view draws a particle whose alpha is not 0 in its own colour instead of its
    /// material's, and mixes colours where they meet as it mixes materials.
    std::span<const uint32_t> colour;
    /// Positions at the start of the last sub-step (unit: m; may be empty, else both sizes of
    /// `x`): when given, particles are drawn at `previous + factor (current - previous)`,
    /// positions between steps (fluid/groups.h, `fluid::setInterpolation`).
    std::span<const float> previousX, previousY;
    /// How far from the previous to the current positions to draw (unit: 1; range [0, 1]; read
    /// only with `previousX`); `fluid::interpolationFactor(world)`.
    float factor = 1.0f;
};

/// The spans of `world`'s particles, valid until its next step: with its colours
/// (`fluid::colours`) and, when the world interpolates (`fluid::setInterpolation`), its
/// previous positions and interpolation factor. Thread rule: as `World`.
inline ParticleSpans particles(const World& world) {
    ParticleSpans spans;
    spans.x = world.positionX();
    spans.y = world.positionY();
    spans.vx = world.velocityX();
    spans.vy = world.velocityY();
    spans.pressure = world.pressure();
    spans.material = world.materialIndex();
    spans.colour = fluid::colours(world);
    if (fluid::interpolating(world)) {
        spans.previousX = fluid::previousPositionX(world);
        spans.previousY = fluid::previousPositionY(world);
        spans.factor = fluid::interpolationFactor(world);
    }
    return spans;
}

/// What the liquid looks like.
enum class View : uint8_t {
    /// Metaballs: a smooth liquid surface with anti-aliased edges, a light rim and per-material
    /// colour; where materials mix, their colours blend. Every particle shows at least as a disc
    /// about one spacing across (lone droplets, spray); the surface touches walls and bodies.
    Metaballs,
    /// The seed report's pressure view: black liquid with translucent red squares, one per
    /// particle, more opaque under more pressure.
    Pressure,
    /// One disc per particle, coloured by speed (blue slow, through cyan and yellow, red fast).
    Particles,
};

/// The views' names, as the demo's --view and screenshots write them: the one table of them.
inline constexpr EnumName<View> kViewNames[] = {
    {View::Metaballs, "metaballs"},
    {View::Pressure, "pressure"},
    {View::Particles, "particles"},
};

/// Name of a view: "metaballs", "pressure", "particles" (`kViewNames`); "unknown" for a value not
/// listed. Pure function; any thread.
std::string_view viewName(View view);

/// The view named `name` (as `viewName` writes it), nothing for an unknown name. Pure function;
/// any thread.
constexpr std::optional<View> viewFromName(std::string_view name) {
    return valueIn(kViewNames, name);
}

/// How one material is drawn.
struct MaterialStyle {
    /// Colour of the pure material (unit: linear RGB, each in [0, 1]).
    glm::vec3 colour{0.15f, 0.45f, 0.95f};
    /// Particle spacing of the material (unit: m; > 0): sets the metaball radius and the size
    /// of pressure squares and particle discs.
    float spacing = 0.01f;
};

/// Colour of the liquid by material name: "water" blue, "yoghurt" creamy white, any other
/// name a colour from a fixed list picked by `index` (unit: linear RGB).
glm::vec3 defaultColour(std::string_view materialName, uint32_t index);

/// Per-frame render settings. Out-of-range values are clamped to their range.
struct RenderSettings {
    /// Which view to draw.
    View view = View::Metaballs;
    /// Metaball reach over the material's spacing (unit: 1; [1, 4]): `SurfaceField::fieldRadius`
    /// (fluid/surface_field.h), the field the ray casts and `sample` read; pass the same value
    /// to them so that a ray stops where the liquid is drawn.
    float fieldRadius = SurfaceField{}.fieldRadius;
    /// Field level at the liquid's surface (unit: 1; [0.05, 4]); lower makes blobs fatter. The
    /// field sums to about 1.2 inside the liquid; at 0.6 the surface stands about half a
    /// spacing outside the outer particles' centres. `SurfaceField::threshold`.
    float threshold = SurfaceField{}.threshold;
    /// Pressure drawn fully opaque in the pressure view (unit: Pa; 0 = automatic: the 95th
    /// percentile of the frame's positive pressures, at least 0.001 Pa).
    float pressureScale = 0.0f;
    /// Speed at the red end of the particle view's colour ramp (unit: m/s; > 0).
    float speedScale = 2.0f;
    /// Resolution of the metaball field over the target's (unit: 1; [0.25, 1]); 0.5 quarters
    /// the fill cost on software renderers.
    float fieldResolution = 0.5f;
    /// Field level at the surface where the liquid touches a solid (unit: 1; [0.05, 4]; used
    /// only where it is below `threshold`). Particles rest up to about a spacing from walls and
    /// bodies, where the field has fallen to about 0.25: at `threshold` the background would
    /// show between the liquid and the solid. Solids are the opaque triangles (alpha >= 0.999)
    /// of `under` and `over`; the metaball and pressure views draw the opaque triangles of
    /// `under` again over the liquid, so the lower level reaches into a wall unseen.
    float solidThreshold = 0.15f;
    /// Distance from a solid over which the surface level goes smoothly from `solidThreshold`
    /// back to `threshold` (unit: spacings of the widest material; [0, 4]; 0 = no solid
    /// treatment). Beyond it the liquid is drawn as if there were no solids. Within it the gap
    /// between the liquid and the solid closes, a thin or sparse film on a solid (yoghurt on a
    /// plank) reads as one film, a free surface that meets a solid rises by at most about half
    /// a spacing (a meniscus), and the light rim fades out where the liquid touches the solid.
    float solidReach = 3.0f;
    /// Background colour (unit: linear RGB).
    glm::vec3 background{0.08f, 0.09f, 0.11f};
};

/// What a `render` call drew and measured.
struct RenderStats {
    /// Particles drawn (unit: count).
    uint32_t particles = 0;
    /// Pressure at full opacity in the pressure view (unit: Pa; the automatic scale when
    /// `RenderSettings::pressureScale` is 0).
    float pressureScale = 0.0f;
    /// GL errors raised during the call (unit: count; 0 in a healthy context). Errors pending
    /// before the call are cleared, not counted.
    uint32_t glErrors = 0;
};

/// Draws particles and shapes into its own framebuffer (RGBA8, `size()` pixels), which the
/// host presents to the window with `present`, reads back with `readPixels`, or draws its own
/// UI into after binding `framebuffer()`. Owns GL objects: create, use and destroy it on the
/// thread whose context is current, with the same context (or one sharing its objects;
/// framebuffers and vertex arrays are never shared, so recreate the renderer with the window).
/// Not copyable; movable: a moved-from renderer throws `fluid::Error` from every member but
/// assignment and the destructor.
class Renderer {
public:
    /// Compiles the shaders and allocates targets of `size` (unit: px; each in [1, 16384] and
    /// at most the context's GL_MAX_TEXTURE_SIZE). Throws `fluid::Error` for a size out of
    /// range, with the shader's name and the compiler's log if a shader does not compile, or
    /// naming the formats if no float framebuffer is complete, or if `loadFunctions` has not
    /// run.
    explicit Renderer(glm::ivec2 size);
    /// Releases the GL objects (the context must still be current).
    ~Renderer();
    Renderer(Renderer&&) noexcept;
    Renderer& operator=(Renderer&&) noexcept;
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    /// Reallocates the targets at `size` (unit: px; each in [1, 16384]); nothing if unchanged.
    /// Throws `fluid::Error` for a size out of range (the renderer keeps its old size).
    void resize(glm::ivec2 size);
    /// Target size (unit: px).
    glm::ivec2 size() const;

    /// How each material index is drawn (at most 16; index i styles material i). Particles
    /// of a material without a style are drawn with the first style; an empty span restores
    /// the default `MaterialStyle`. Throws `fluid::Error` for more than 16 styles, a spacing
    /// that is not > 0 or a colour that is not finite (the styles stay unchanged).
    void setMaterials(std::span<const MaterialStyle> styles);

    /// Clears the target to the background, draws `under` (walls, sensors), the liquid in
    /// `settings.view`, then `over` (bodies, cursor). In the metaball and pressure views the
    /// opaque triangles of `under` (alpha >= 0.999: walls) are drawn once more over the liquid,
    /// which therefore never covers a wall, and the liquid's surface reaches every opaque
    /// triangle of either batch it comes near (see `RenderSettings::solidThreshold`); a
    /// translucent `under` triangle drawn after an opaque one it overlaps loses its tint there.
    /// The camera's view (`worldMin()` to `worldMax()`) fills the target: give it the target's
    /// size as viewport for square pixels. Throws `fluid::Error`, before drawing anything, if the
    /// spans' sizes disagree or the camera's zoom is not > 0. Leaves `framebuffer()` bound and
    /// changes the viewport, blending, scissor, program, vertex array and texture bindings.
    RenderStats render(const Camera& camera, const ParticleSpans& particles,
                       const ShapeBatch& under, const ShapeBatch& over,
                       const RenderSettings& settings);

    /// The GL name of the RGBA8 framebuffer object `render` draws into: bind it to draw more
    /// (a HUD) on top of the frame.
    uint32_t framebuffer() const;
    /// Copies the target to the default framebuffer (the window), scaled to `windowSize`
    /// (unit: px) without changing its aspect (letterboxed, bars black), and leaves framebuffer
    /// 0 bound with the viewport covering the window. Does nothing more for an empty window.
    void present(glm::ivec2 windowSize) const;
    /// Reads the target into `rgba`: size().x * size().y * 4 bytes, rows top to bottom (the
    /// order image files use).
    void readPixels(std::vector<uint8_t>& rgba) const;

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

} // namespace fluid::gl
