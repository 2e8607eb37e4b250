// fluid::gl — the renderer: render targets, particle uploads and the passes of each view.
//
// Per frame (see docs/rendering.md):
//   1. clear the RGBA8 composite target to the background, draw the `under` shapes;
//   2. Metaballs: add every particle's kernel into a float field target (additive blending),
//      rasterise the opaque shapes into a solid mask and take each field texel's distance to
//      it (two passes), then one full-screen triangle turns the field into a surface over the
//      composite, with a lower surface level next to solids; the opaque `under` shapes are
//      drawn again over it;
//      Pressure: the same surface in black, then one red square per particle;
//      Particles: one disc per particle;
//   3. draw the `over` shapes.
#include "gl_api.h"
#include "program.h"

#include <fluid/gl/renderer.h>

#include <glm/common.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <limits>
#include <numbers>
#include <string>

namespace fluid::gl {

namespace {

constexpr int kMaxSize = 16384;
constexpr size_t kMaxMaterials = 16;
// The automatic pressure scale never goes below this (unit: Pa), so a frame without positive
// pressure does not divide by zero.
constexpr float kMinPressureScale = 1e-3f;
// The field and its surface are the core's (fluid::SurfaceField, fluid/surface_field.h): the
// interior sums to SurfaceField::kInteriorSum (1.2), the default threshold 0.6 puts the surface
// about half a spacing outside the outer particles' centres, and the largest single kernel,
// scaled by SurfaceField::dropletLevel, shows every particle at least as a disc of half a
// spacing. The ray casts and `sample` read the same field. See docs/rendering.md.
// A shape triangle whose three vertices have at least this alpha is opaque: a solid.
constexpr float kOpaqueAlpha = 0.999f;
// Most taps on each side of a texel in a solid distance pass; a wider reach samples every
// few texels instead (thin solids may then be missed at extreme zoom).
constexpr int kMaxDistanceTaps = 16;

// Vertex attribute locations, as the shaders declare them.
enum Attribute : GLuint {
    kCorner = 0,
    kX = 1,
    kY = 2,
    kVx = 3,
    kVy = 4,
    kPressure = 5,
    kMaterial = 6,
    kColour = 7,
    kShapePosition = 0,
    kShapeColour = 1,
};

// Per-particle buffers, one per channel.
enum Channel : size_t {
    kChX,
    kChY,
    kChVx,
    kChVy,
    kChPressure,
    kChMaterial,
    kChColour,
    kChannelCount
};
constexpr std::array<GLuint, kChannelCount> kChannelAttribute{kX,        kY,        kVx,    kVy,
                                                              kPressure, kMaterial, kColour};

std::string sizeText(glm::ivec2 size) {
    return "(" + std::to_string(size.x) + ", " + std::to_string(size.y) + ")";
}

float finiteOr(float value, float fallback) {
    return std::isfinite(value) ? value : fallback;
}

// Pixel rectangle (x, y, width, height; GL's y up) of a target of `size` covering the world
// rectangle [lo, hi] under the column-major world-to-clip matrix `m`, grown by `margin` pixels
// and clipped to the target. Width or height 0 when nothing of it shows.
glm::ivec4 pixelRect(const float* m, glm::vec2 lo, glm::vec2 hi, glm::ivec2 size, int margin) {
    const glm::vec2 clipLo(m[0] * lo.x + m[6], m[4] * lo.y + m[7]);
    const glm::vec2 clipHi(m[0] * hi.x + m[6], m[4] * hi.y + m[7]);
    const glm::vec2 a = (glm::min(clipLo, clipHi) * 0.5f + 0.5f) * glm::vec2(size);
    const glm::vec2 b = (glm::max(clipLo, clipHi) * 0.5f + 0.5f) * glm::vec2(size);
    // Clamp in float first: far-off liquid must not overflow the int conversion.
    const glm::vec2 limit(size);
    const glm::ivec2 x0(glm::clamp(glm::floor(a) - float(margin), glm::vec2(0.0f), limit));
    const glm::ivec2 x1(glm::clamp(glm::ceil(b) + float(margin), glm::vec2(0.0f), limit));
    return {x0.x, x0.y, std::max(x1.x - x0.x, 0), std::max(x1.y - x0.y, 0)};
}

// `rect` (x, y, width, height) grown by `margin` texels on every side, clipped to [0, size).
glm::ivec4 grownRect(glm::ivec4 rect, int margin, glm::ivec2 size) {
    const int x0 = std::max(rect.x - margin, 0), y0 = std::max(rect.y - margin, 0);
    const int x1 = std::min(rect.x + rect.z + margin, size.x);
    const int y1 = std::min(rect.y + rect.w + margin, size.y);
    return {x0, y0, std::max(x1 - x0, 0), std::max(y1 - y0, 0)};
}

// Locations of the uniforms one particle program uses (-1 when it has none of that name).
struct ParticleUniforms {
    GLint worldToClip = -1, spacing = -1, colour = -1, materialCount = -1;
    void locate(const detail::Program& program) {
        worldToClip = program.uniform("uWorldToClip");
        spacing = program.uniform("uSpacing");
        colour = program.uniform("uColour");
        materialCount = program.uniform("uMaterialCount");
    }
};

} // namespace

namespace {
// One metaball surface: the field pass and the composite pass.
struct SurfacePass {
    const float* worldToClip = nullptr; // column-major mat3, world (m) to clip
    size_t particles = 0;
    float fieldRadius = 2.0f;     // R over spacing (1)
    float threshold = 0.6f;       // field level at the surface (1)
    float rimWidth = 3.0f;        // rim band (target px)
    bool dark = false;            // pressure view: black liquid, grey rim
    glm::vec2 lo{0.0f}, hi{0.0f}; // every particle's kernel lies in [lo, hi] (m)
    // Solids: the opaque triangles at [solidFirst, solidFirst + solidCount) of the shape
    // buffer; within solidReach (solid texels; 0 = off) of them the surface level goes down
    // to solidThreshold (1).
    GLint solidFirst = 0;
    GLsizei solidCount = 0;
    std::span<const ShapeVertex> solids; // the same triangles (for the cache)
    float solidReach = 0.0f;
    float solidThreshold = 0.15f;
};
} // namespace

struct Renderer::Impl {
    glm::ivec2 size{0, 0};
    glm::ivec2 fieldSize{0, 0};
    // The solid targets' size: half the field's (a quarter of the target's at the default
    // fieldResolution), plenty for a distance that only sets where the surface level eases.
    glm::ivec2 solidSize{0, 0};
    GLint maxTextureSize = 0;

    // Targets: the composite (what the host sees) and the metaball field.
    GLuint compositeFbo = 0, compositeTexture = 0;
    // The field has two attachments: colour (rgb = sum of colour x w, a = max of w) and weight
    // (r = sum of w; g, b = its parts from materials 0 and 1 in their own colours, for the
    // composite's edge between them). The max lets a lone droplet show (see
    // SurfaceField::dropletLevel).
    GLuint fieldFbo = 0;
    std::array<GLuint, 2> fieldTextures{};
    bool fieldHalfFloat = true;
    // Solid targets, at solidSize: the mask of opaque shapes (R8), the distance to the nearest
    // solid texel along the row (R16F) and the distance itself (R16F; solid texels).
    enum SolidTarget : size_t { kSolidMask, kSolidRows, kSolidDistance, kSolidTargets };
    std::array<GLuint, kSolidTargets> solidFbos{};
    std::array<GLuint, kSolidTargets> solidTextures{};
    // What the solid distance holds: for these solids, camera and reach, valid inside
    // solidCacheRect (solid texels). Walls stand still, so most frames reuse it; a moving body
    // or liquid that leaves the rectangle computes it again.
    std::vector<ShapeVertex> solidCache;
    std::array<float, 9> solidCacheCamera{};
    float solidCacheReach = -1.0f;
    glm::ivec4 solidCacheRect{0, 0, 0, 0};

    detail::Program shapeProgram, fieldProgram, compositeProgram, squareProgram, discProgram;
    detail::Program maskProgram, distanceProgram;
    GLint maskWorldToClip = -1;
    GLint distanceSource = -1, distancePass = -1, distanceTaps = -1, distanceStride = -1,
          distanceFar = -1;
    GLint compositeSolidDistance = -1, compositeSolidReach = -1, compositeSolidThreshold = -1;
    GLint shapeWorldToClip = -1;
    ParticleUniforms fieldUniforms, squareUniforms, discUniforms;
    GLint fieldRadius = -1, fieldWeight = -1;
    GLint compositeThreshold = -1, compositeRimWidth = -1, compositeDark = -1, compositeField = -1,
          compositeWeight = -1, compositeDropletLevel = -1, compositeMaterialColour = -1;
    GLint squareInvScale = -1;
    GLint discPixel = -1, discInvSpeedScale = -1;

    GLuint shapeVao = 0, shapeVbo = 0;
    GLuint particleVao = 0, quadVbo = 0;
    std::array<GLuint, kChannelCount> channelVbo{};
    GLuint emptyVao = 0;

    // Material styles as uniform arrays (index 0 stands in for unknown indices).
    std::array<float, kMaxMaterials> spacing{};
    std::array<float, kMaxMaterials * 3> colour{};
    GLint materialCount = 1;

    // Reused every frame: positive pressures for the automatic scale, and the opaque
    // triangles of both shape batches (the solids).
    std::vector<float> pressureScratch;
    std::vector<ShapeVertex> solidScratch;
    // Positions between steps (ParticleSpans::previousX): the interpolated x and y.
    std::vector<float> drawnX, drawnY;

    explicit Impl(glm::ivec2 targetSize);
    ~Impl();
    Impl(const Impl&) = delete;
    Impl& operator=(const Impl&) = delete;

    void allocateComposite();
    void allocateField(glm::ivec2 newFieldSize);
    void setStyles(std::span<const MaterialStyle> styles);
    void uploadMaterials(const ParticleUniforms& uniforms) const;
    void uploadChannel(Channel channel, const void* data, size_t bytes, bool present);
    // Draws shape triangles [first, first + count) with straight alpha; `opaque` ones (alpha
    // >= kOpaqueAlpha) without blending, which a software renderer fills faster.
    void drawShapes(GLint first, GLsizei count, bool opaque = false) const;
    void drawSurface(const SurfacePass& pass);
};

namespace {

void checkSize(glm::ivec2 size, GLint maxTextureSize, const char* function) {
    if (size.x < 1 || size.y < 1 || size.x > kMaxSize || size.y > kMaxSize) {
        throw Error(std::string("fluid::gl: ") + function + ": size " + sizeText(size) +
                        " is out of range [1, " + std::to_string(kMaxSize) + "] (unit: px)",
                    ErrorCode::OutOfRange);
    }
    if (maxTextureSize > 0 && (size.x > maxTextureSize || size.y > maxTextureSize)) {
        throw Error(std::string("fluid::gl: ") + function + ": size " + sizeText(size) +
                        " exceeds this context's GL_MAX_TEXTURE_SIZE " +
                        std::to_string(maxTextureSize) + " (unit: px)",
                    ErrorCode::OutOfRange);
    }
}

void setTextureParameters(GLenum filter) {
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, static_cast<GLint>(filter));
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, static_cast<GLint>(filter));
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

} // namespace

Renderer::Impl::Impl(glm::ivec2 targetSize) {
#if !defined(FLUID_GL_ES) // OpenGL ES links its entry points
    // GLEW's entry points past OpenGL 1.1 are null until loadFunctions() ran: calling one
    // would crash instead of throwing.
    if (glCreateShader == nullptr || glGenVertexArrays == nullptr ||
        glDrawArraysInstanced == nullptr) {
        throw Error("fluid::gl: Renderer: OpenGL entry points are not loaded; call "
                    "fluid::gl::loadFunctions() with the context current first",
                    ErrorCode::WrongState);
    }
#endif
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTextureSize);
    checkSize(targetSize, maxTextureSize, "Renderer");
    size = targetSize;

    shapeProgram = detail::Program("shape.vert", "shape.frag");
    fieldProgram = detail::Program("metaball_field.vert", "metaball_field.frag");
    maskProgram = detail::Program("shape.vert", "solid_mask.frag");
    distanceProgram = detail::Program("fullscreen.vert", "solid_distance.frag");
    compositeProgram = detail::Program("fullscreen.vert", "metaball_composite.frag");
    squareProgram = detail::Program("pressure_square.vert", "pressure_square.frag");
    discProgram = detail::Program("particle_disc.vert", "particle_disc.frag");

    shapeWorldToClip = shapeProgram.uniform("uWorldToClip");
    fieldUniforms.locate(fieldProgram);
    squareUniforms.locate(squareProgram);
    discUniforms.locate(discProgram);
    fieldRadius = fieldProgram.uniform("uFieldRadius");
    fieldWeight = fieldProgram.uniform("uWeight");
    compositeThreshold = compositeProgram.uniform("uThreshold");
    compositeRimWidth = compositeProgram.uniform("uRimWidth");
    compositeDark = compositeProgram.uniform("uDark");
    compositeField = compositeProgram.uniform("uField");
    compositeWeight = compositeProgram.uniform("uWeight");
    compositeDropletLevel = compositeProgram.uniform("uDropletLevel");
    compositeMaterialColour = compositeProgram.uniform("uMaterialColour");
    compositeSolidDistance = compositeProgram.uniform("uSolidDistance");
    compositeSolidReach = compositeProgram.uniform("uSolidReach");
    compositeSolidThreshold = compositeProgram.uniform("uSolidThreshold");
    maskWorldToClip = maskProgram.uniform("uWorldToClip");
    distanceSource = distanceProgram.uniform("uSource");
    distancePass = distanceProgram.uniform("uPass");
    distanceTaps = distanceProgram.uniform("uTaps");
    distanceStride = distanceProgram.uniform("uStride");
    distanceFar = distanceProgram.uniform("uFar");
    squareInvScale = squareProgram.uniform("uInvScale");
    discPixel = discProgram.uniform("uPixel");
    discInvSpeedScale = discProgram.uniform("uInvSpeedScale");
    glUseProgram(compositeProgram.id());
    glUniform1i(compositeField, 0);
    glUniform1i(compositeWeight, 1);
    glUniform1i(compositeSolidDistance, 2);
    glUseProgram(distanceProgram.id());
    glUniform1i(distanceSource, 0);
    glUseProgram(0);

    // Shapes: interleaved position + colour, refilled every frame.
    glGenVertexArrays(1, &shapeVao);
    glGenBuffers(1, &shapeVbo);
    glBindVertexArray(shapeVao);
    glBindBuffer(GL_ARRAY_BUFFER, shapeVbo);
    glEnableVertexAttribArray(kShapePosition);
    glVertexAttribPointer(kShapePosition, 2, GL_FLOAT, GL_FALSE, sizeof(ShapeVertex),
                          reinterpret_cast<const void*>(offsetof(ShapeVertex, position)));
    glEnableVertexAttribArray(kShapeColour);
    glVertexAttribPointer(kShapeColour, 4, GL_FLOAT, GL_FALSE, sizeof(ShapeVertex),
                          reinterpret_cast<const void*>(offsetof(ShapeVertex, colour)));

    // Particles: a unit quad per vertex, then one buffer per channel per instance (divisor 1),
    // each filled straight from the world's spans (structure of arrays, no interleaving copy).
    glGenVertexArrays(1, &particleVao);
    glGenBuffers(1, &quadVbo);
    glGenBuffers(static_cast<GLsizei>(channelVbo.size()), channelVbo.data());
    glBindVertexArray(particleVao);
    static constexpr float kQuad[8] = {-1.0f, -1.0f, 1.0f, -1.0f, -1.0f, 1.0f, 1.0f, 1.0f};
    glBindBuffer(GL_ARRAY_BUFFER, quadVbo);
    glBufferData(GL_ARRAY_BUFFER, sizeof kQuad, kQuad, GL_STATIC_DRAW);
    glEnableVertexAttribArray(kCorner);
    glVertexAttribPointer(kCorner, 2, GL_FLOAT, GL_FALSE, 0, nullptr);
    for (size_t c = 0; c < kChannelCount; ++c) {
        const GLuint location = kChannelAttribute[c];
        glBindBuffer(GL_ARRAY_BUFFER, channelVbo[c]);
        if (c == kChMaterial) {
            // Integer attribute: the shader indexes the style arrays with it.
            glVertexAttribIPointer(location, 1, GL_UNSIGNED_SHORT, 0, nullptr);
        } else if (c == kChColour) {
            // RGBA8 per particle, read as normalised floats (alpha 0: the material's colour).
            glVertexAttribPointer(location, 4, GL_UNSIGNED_BYTE, GL_TRUE, 0, nullptr);
        } else {
            glVertexAttribPointer(location, 1, GL_FLOAT, GL_FALSE, 0, nullptr);
        }
        glVertexAttribDivisor(location, 1);
    }
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);

    // The full-screen triangle has no attributes, but core profile draws need a bound VAO.
    glGenVertexArrays(1, &emptyVao);

    glGenFramebuffers(1, &compositeFbo);
    glGenTextures(1, &compositeTexture);
    glGenFramebuffers(1, &fieldFbo);
    glGenTextures(2, fieldTextures.data());
    glGenFramebuffers(GLsizei(kSolidTargets), solidFbos.data());
    glGenTextures(GLsizei(kSolidTargets), solidTextures.data());
    allocateComposite();
    setStyles({});
}

Renderer::Impl::~Impl() {
    glDeleteFramebuffers(1, &compositeFbo);
    glDeleteFramebuffers(1, &fieldFbo);
    glDeleteTextures(1, &compositeTexture);
    glDeleteTextures(2, fieldTextures.data());
    glDeleteFramebuffers(GLsizei(kSolidTargets), solidFbos.data());
    glDeleteTextures(GLsizei(kSolidTargets), solidTextures.data());
    glDeleteVertexArrays(1, &shapeVao);
    glDeleteVertexArrays(1, &particleVao);
    glDeleteVertexArrays(1, &emptyVao);
    glDeleteBuffers(1, &shapeVbo);
    glDeleteBuffers(1, &quadVbo);
    glDeleteBuffers(static_cast<GLsizei>(channelVbo.size()), channelVbo.data());
}

void Renderer::Impl::allocateComposite() {
    // A pixel-unpack buffer the host left bound would turn the null pointer into an offset.
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    glBindTexture(GL_TEXTURE_2D, compositeTexture);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, size.x, size.y, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    setTextureParameters(GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, compositeFbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, compositeTexture,
                           0);
    const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    glBindTexture(GL_TEXTURE_2D, 0);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        char hex[16];
        std::snprintf(hex, sizeof hex, "0x%04X", static_cast<unsigned>(status));
        throw Error("fluid::gl: Renderer: the GL_RGBA8 framebuffer of size " + sizeText(size) +
                        " is incomplete (status " + hex + ")",
                    ErrorCode::WrongState);
    }
    // The field follows the composite's size at the next render.
    fieldSize = {0, 0};
}

void Renderer::Impl::allocateField(glm::ivec2 newFieldSize) {
    fieldSize = newFieldSize;
    solidCacheReach = -1.0f; // the solid targets are allocated anew
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, fieldFbo);
    // Half floats are enough for sums of a few dozen weights and half the bandwidth of 32-bit;
    // 32-bit floats are the fallback for drivers that cannot render to 16-bit ones.
    GLenum status = GL_FRAMEBUFFER_UNSUPPORTED;
    for (const bool half : {fieldHalfFloat, true, false}) {
        const GLenum format = half ? GL_RGBA16F : GL_RGBA32F;
        for (size_t i = 0; i < 2; ++i) {
            glBindTexture(GL_TEXTURE_2D, fieldTextures[i]);
            glTexImage2D(GL_TEXTURE_2D, 0, static_cast<GLint>(format), fieldSize.x, fieldSize.y,
                         0, GL_RGBA, GL_FLOAT, nullptr);
            setTextureParameters(GL_LINEAR);
            glFramebufferTexture2D(GL_FRAMEBUFFER, GLenum(GL_COLOR_ATTACHMENT0 + i), GL_TEXTURE_2D,
                                   fieldTextures[i], 0);
        }
        status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
        if (status == GL_FRAMEBUFFER_COMPLETE) {
            fieldHalfFloat = half;
            break;
        }
    }
    glBindTexture(GL_TEXTURE_2D, 0);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        char hex[16];
        std::snprintf(hex, sizeof hex, "0x%04X", static_cast<unsigned>(status));
        fieldSize = {0, 0};
        throw Error("fluid::gl: Renderer: no float framebuffer is complete for the metaball "
                    "field (tried GL_RGBA16F and GL_RGBA32F at " +
                        sizeText(newFieldSize) + "; last status " + hex + ")",
                    ErrorCode::WrongState);
    }
    static constexpr GLenum kDrawBuffers[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glDrawBuffers(2, kDrawBuffers);

    // The solid targets: R8 is always renderable; the distances use the field's float format
    // (complete above), one channel.
    solidSize = glm::max((fieldSize + 1) / 2, glm::ivec2(1));
    for (size_t i = 0; i < kSolidTargets; ++i) {
        const bool mask = i == kSolidMask;
        const GLenum format = mask ? GL_R8 : (fieldHalfFloat ? GL_R16F : GL_R32F);
        glBindTexture(GL_TEXTURE_2D, solidTextures[i]);
        glTexImage2D(GL_TEXTURE_2D, 0, static_cast<GLint>(format), solidSize.x, solidSize.y, 0,
                     GL_RED, mask ? GL_UNSIGNED_BYTE : GL_FLOAT, nullptr);
        // The distance passes fetch texels; the composite samples the distance bilinearly.
        setTextureParameters(i == kSolidDistance ? GL_LINEAR : GL_NEAREST);
        glBindFramebuffer(GL_FRAMEBUFFER, solidFbos[i]);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D,
                               solidTextures[i], 0);
        const GLenum solidStatus = glCheckFramebufferStatus(GL_FRAMEBUFFER);
        if (solidStatus != GL_FRAMEBUFFER_COMPLETE) {
            glBindTexture(GL_TEXTURE_2D, 0);
            char text[160];
            std::snprintf(text, sizeof text,
                          "fluid::gl: Renderer: the solid %s framebuffer of size (%d, %d) is "
                          "incomplete (status 0x%04X)",
                          mask ? "mask (GL_R8)" : "distance (one-channel float)", solidSize.x,
                          solidSize.y, static_cast<unsigned>(solidStatus));
            fieldSize = {0, 0};
            throw Error(text, ErrorCode::WrongState);
        }
    }
    glBindTexture(GL_TEXTURE_2D, 0);
}

void Renderer::Impl::setStyles(std::span<const MaterialStyle> styles) {
    const MaterialStyle fallback{};
    if (styles.empty()) {
        styles = {&fallback, 1};
    }
    materialCount = static_cast<GLint>(styles.size());
    for (size_t i = 0; i < kMaxMaterials; ++i) {
        // Unused slots copy style 0; the shaders map unknown indices to it anyway.
        const MaterialStyle& style = i < styles.size() ? styles[i] : styles[0];
        spacing[i] = style.spacing;
        colour[3 * i + 0] = style.colour.r;
        colour[3 * i + 1] = style.colour.g;
        colour[3 * i + 2] = style.colour.b;
    }
}

void Renderer::Impl::uploadMaterials(const ParticleUniforms& uniforms) const {
    glUniform1fv(uniforms.spacing, GLsizei(kMaxMaterials), spacing.data());
    if (uniforms.colour >= 0) {
        glUniform3fv(uniforms.colour, GLsizei(kMaxMaterials), colour.data());
    }
    glUniform1i(uniforms.materialCount, materialCount);
}

void Renderer::Impl::uploadChannel(Channel channel, const void* data, size_t bytes, bool present) {
    const GLuint location = kChannelAttribute[channel];
    if (!present) {
        // An empty span: a constant 0 instead of an array (which the VAO must not read).
        glDisableVertexAttribArray(location);
        if (channel == kChMaterial) {
            glVertexAttribI4ui(location, 0, 0, 0, 0);
        } else if (channel == kChColour) {
            glVertexAttrib4f(location, 0.0f, 0.0f, 0.0f, 0.0f); // no colour: the material's
        } else {
            glVertexAttrib1f(location, 0.0f);
        }
        return;
    }
    glBindBuffer(GL_ARRAY_BUFFER, channelVbo[channel]);
    // glBufferData with the data orphans last frame's storage: the driver hands out fresh
    // memory instead of waiting for draws that still read the old one.
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(bytes), data, GL_STREAM_DRAW);
    glEnableVertexAttribArray(location);
}

void Renderer::Impl::drawShapes(GLint first, GLsizei count, bool opaque) const {
    if (count == 0) {
        return;
    }
    glUseProgram(shapeProgram.id());
    glBindVertexArray(shapeVao);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    // Straight alpha over an opaque target; the target's alpha stays 1.
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    if (opaque) {
        glDisable(GL_BLEND);
    }
    glDrawArrays(GL_TRIANGLES, first, count);
    glEnable(GL_BLEND);
}

void Renderer::Impl::drawSurface(const SurfacePass& pass) {
    // Both passes only touch the liquid's bounding rectangle (scissored): the composite is a
    // full-screen pass otherwise, the largest cost on software renderers. Field margin: the
    // composite's bilinear taps reach a texel past its own rectangle.
    const glm::ivec4 fieldRect = pixelRect(pass.worldToClip, pass.lo, pass.hi, fieldSize, 2);
    const glm::ivec4 targetRect = pixelRect(pass.worldToClip, pass.lo, pass.hi, size, 1);
    if (fieldRect.z == 0 || fieldRect.w == 0 || targetRect.z == 0 || targetRect.w == 0) {
        return; // the liquid is off screen
    }
    glEnable(GL_SCISSOR_TEST);

    // Field pass: sum every particle's kernel into the float target.
    glBindFramebuffer(GL_FRAMEBUFFER, fieldFbo);
    glViewport(0, 0, fieldSize.x, fieldSize.y);
    glScissor(fieldRect.x, fieldRect.y, fieldRect.z, fieldRect.w);
    glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glEnable(GL_BLEND);
    // Sums (rgb of both attachments), except the colour attachment's alpha: a maximum.
    glBlendEquationSeparate(GL_FUNC_ADD, GL_MAX);
    glBlendFunc(GL_ONE, GL_ONE);
    glUseProgram(fieldProgram.id());
    glUniformMatrix3fv(fieldUniforms.worldToClip, 1, GL_FALSE, pass.worldToClip);
    uploadMaterials(fieldUniforms);
    glUniform1f(fieldRadius, pass.fieldRadius);
    // The kernel integrates to pi R^2 / 4 and a particle stands for spacing^2 of area, so
    // this weight makes a filled lattice sum to SurfaceField::kInteriorSum whatever the radius.
    SurfaceField surface;
    surface.fieldRadius = pass.fieldRadius;
    glUniform1f(fieldWeight, surface.kernelWeight());
    glBindVertexArray(particleVao);
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, static_cast<GLsizei>(pass.particles));

    // Solid passes: the opaque shapes into a mask, then each texel's distance to the mask, in
    // two separable passes (rows, then columns) that are exact within the reach. Each pass
    // reads up to `window` texels beyond the rectangle the next one writes.
    const bool solids = pass.solidCount > 0 && pass.solidReach > 0.0f;
    auto contains = [](glm::ivec4 outer, glm::ivec4 inner) {
        return inner.x >= outer.x && inner.y >= outer.y && inner.x + inner.z <= outer.x + outer.z &&
               inner.y + inner.w <= outer.y + outer.w;
    };
    const glm::ivec4 solidRect = pixelRect(pass.worldToClip, pass.lo, pass.hi, solidSize, 2);
    const bool cached =
        solids && solidCacheReach == pass.solidReach && contains(solidCacheRect, solidRect) &&
        std::equal(solidCacheCamera.begin(), solidCacheCamera.end(), pass.worldToClip) &&
        solidCache.size() == pass.solids.size() &&
        std::memcmp(solidCache.data(), pass.solids.data(),
                    pass.solids.size() * sizeof(ShapeVertex)) == 0;
    if (solids && !cached) {
        const int window = int(std::ceil(pass.solidReach)) + 1;
        const int stride = (window + kMaxDistanceTaps - 1) / kMaxDistanceTaps;
        const int taps = (window + stride - 1) / stride;
        // Some room round the liquid, so that it can move a little before this runs again.
        const glm::ivec4 region = grownRect(solidRect, 4, solidSize);
        solidCache.assign(pass.solids.begin(), pass.solids.end());
        std::copy(pass.worldToClip, pass.worldToClip + 9, solidCacheCamera.begin());
        solidCacheReach = pass.solidReach;
        solidCacheRect = region;
        glDisable(GL_BLEND);
        glViewport(0, 0, solidSize.x, solidSize.y);
        glBindFramebuffer(GL_FRAMEBUFFER, solidFbos[kSolidMask]);
        const glm::ivec4 maskRect = grownRect(region, 2 * taps * stride, solidSize);
        glScissor(maskRect.x, maskRect.y, maskRect.z, maskRect.w);
        glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
        glClear(GL_COLOR_BUFFER_BIT);
        glUseProgram(maskProgram.id());
        glUniformMatrix3fv(maskWorldToClip, 1, GL_FALSE, pass.worldToClip);
        glBindVertexArray(shapeVao);
        glDrawArrays(GL_TRIANGLES, pass.solidFirst, pass.solidCount);

        glUseProgram(distanceProgram.id());
        glUniform1i(distanceTaps, taps);
        glUniform1i(distanceStride, stride);
        glUniform1f(distanceFar, float(taps * stride + 1));
        glBindVertexArray(emptyVao);
        glActiveTexture(GL_TEXTURE0);
        for (const int step : {0, 1}) {
            const SolidTarget source = step == 0 ? kSolidMask : kSolidRows;
            const SolidTarget target = step == 0 ? kSolidRows : kSolidDistance;
            const glm::ivec4 rect =
                step == 0 ? grownRect(region, taps * stride, solidSize) : region;
            glBindFramebuffer(GL_FRAMEBUFFER, solidFbos[target]);
            glScissor(rect.x, rect.y, rect.z, rect.w);
            glUniform1i(distancePass, step);
            glBindTexture(GL_TEXTURE_2D, solidTextures[source]);
            glDrawArrays(GL_TRIANGLES, 0, 3);
        }
        glBindTexture(GL_TEXTURE_2D, 0);
        glEnable(GL_BLEND);
    }

    // Composite pass: one full-screen triangle samples the field (bilinear) over the target.
    glBindFramebuffer(GL_FRAMEBUFFER, compositeFbo);
    glViewport(0, 0, size.x, size.y);
    glScissor(targetRect.x, targetRect.y, targetRect.z, targetRect.w);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glUseProgram(compositeProgram.id());
    glUniform1f(compositeThreshold, pass.threshold);
    glUniform1f(compositeDropletLevel, surface.dropletLevel());
    glUniform1f(compositeRimWidth, pass.rimWidth);
    glUniform1i(compositeDark, pass.dark ? 1 : 0);
    glUniform3fv(compositeMaterialColour, 2, colour.data()); // materials 0 and 1
    glUniform1f(compositeSolidReach, solids ? pass.solidReach : 0.0f);
    glUniform1f(compositeSolidThreshold, std::min(pass.solidThreshold, pass.threshold));
    glActiveTexture(GL_TEXTURE2);
    glBindTexture(GL_TEXTURE_2D, solids ? solidTextures[kSolidDistance] : 0);
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, fieldTextures[1]);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, fieldTextures[0]);
    glBindVertexArray(emptyVao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindTexture(GL_TEXTURE_2D, 0);
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, 0);
    glActiveTexture(GL_TEXTURE2);
    glBindTexture(GL_TEXTURE_2D, 0);
    glActiveTexture(GL_TEXTURE0);
    glDisable(GL_SCISSOR_TEST);
}

Renderer::Renderer(glm::ivec2 size) : m_impl(std::make_unique<Impl>(size)) {}
Renderer::~Renderer() = default;
Renderer::Renderer(Renderer&&) noexcept = default;
Renderer& Renderer::operator=(Renderer&&) noexcept = default;

namespace {
// A template so that it can take the private Impl type without naming it.
template <class T> T& checked(const std::unique_ptr<T>& impl, const char* function) {
    if (!impl) {
        throw Error(std::string("fluid::gl: Renderer::") + function +
                        ": the renderer was moved from",
                    ErrorCode::WrongState);
    }
    return *impl;
}
} // namespace

void Renderer::resize(glm::ivec2 size) {
    Impl& m = checked(m_impl, "resize");
    checkSize(size, m.maxTextureSize, "Renderer::resize");
    if (size == m.size) {
        return;
    }
    m.size = size;
    m.allocateComposite();
}

glm::ivec2 Renderer::size() const {
    return checked(m_impl, "size").size;
}

void Renderer::setMaterials(std::span<const MaterialStyle> styles) {
    Impl& m = checked(m_impl, "setMaterials");
    if (styles.size() > kMaxMaterials) {
        throw Error("fluid::gl: Renderer::setMaterials: " + std::to_string(styles.size()) +
                        " styles is out of range [0, " + std::to_string(kMaxMaterials) + "]",
                    ErrorCode::OutOfRange);
    }
    for (size_t i = 0; i < styles.size(); ++i) {
        const MaterialStyle& style = styles[i];
        if (!(style.spacing > 0.0f) || !std::isfinite(style.spacing)) {
            throw Error("fluid::gl: Renderer::setMaterials: style " + std::to_string(i) +
                            ": spacing = " + std::to_string(style.spacing) +
                            " is out of range (0, inf) (unit: m)",
                        ErrorCode::OutOfRange);
        }
        if (!std::isfinite(style.colour.r) || !std::isfinite(style.colour.g) ||
            !std::isfinite(style.colour.b)) {
            throw Error("fluid::gl: Renderer::setMaterials: style " + std::to_string(i) +
                            ": colour is not finite",
                        ErrorCode::BadArgument);
        }
    }
    m.setStyles(styles);
}

RenderStats Renderer::render(const Camera& camera, const ParticleSpans& particles,
                             const ShapeBatch& under, const ShapeBatch& over,
                             const RenderSettings& settings) {
    Impl& m = checked(m_impl, "render");

    // ---- check the input before touching GL ----
    const size_t n = particles.x.size();
    auto checkSpan = [n](size_t count, const char* name, bool mayBeEmpty) {
        if (count != n && !(mayBeEmpty && count == 0)) {
            throw Error(std::string("fluid::gl: Renderer: particle spans disagree: x has ") +
                            std::to_string(n) + " entries, " + name + " " + std::to_string(count),
                        ErrorCode::BadArgument);
        }
    };
    checkSpan(particles.y.size(), "y", false);
    checkSpan(particles.vx.size(), "vx", true);
    checkSpan(particles.vy.size(), "vy", true);
    checkSpan(particles.pressure.size(), "pressure", true);
    checkSpan(particles.material.size(), "material", true);
    checkSpan(particles.colour.size(), "colour", true);
    checkSpan(particles.previousX.size(), "previousX", true);
    checkSpan(particles.previousY.size(), "previousY", particles.previousX.empty());
    if (!(particles.factor >= 0.0f && particles.factor <= 1.0f)) {
        throw Error("fluid::gl: Renderer: particle spans' factor = " +
                        std::to_string(particles.factor) + " is out of range [0, 1]",
                    ErrorCode::OutOfRange);
    }
    if (n > size_t(1) << 30) {
        throw Error("fluid::gl: Renderer: " + std::to_string(n) +
                        " particles is out of range [0, 2^30]",
                    ErrorCode::OutOfRange);
    }
    if (!(camera.pixelsPerMetre > 0.0f) || !std::isfinite(camera.pixelsPerMetre) ||
        !std::isfinite(camera.center.x) || !std::isfinite(camera.center.y)) {
        throw Error("fluid::gl: Renderer: camera.pixelsPerMetre = " +
                        std::to_string(camera.pixelsPerMetre) +
                        " is out of range (0, inf) (unit: px/m), or its center is not finite",
                    ErrorCode::OutOfRange);
    }
    const size_t underCount = under.vertices().size();
    const size_t overCount = over.vertices().size();
    if (underCount + overCount > size_t(1) << 30) {
        throw Error("fluid::gl: Renderer: " + std::to_string(underCount + overCount) +
                        " shape vertices is out of range [0, 2^30]",
                    ErrorCode::OutOfRange);
    }

    // ---- settings, clamped to their documented ranges ----
    const SurfaceField surfaceDefaults;
    const float fieldRadius =
        std::clamp(finiteOr(settings.fieldRadius, surfaceDefaults.fieldRadius),
                   SurfaceField::kMinRadius, SurfaceField::kMaxRadius);
    const float threshold = std::clamp(finiteOr(settings.threshold, surfaceDefaults.threshold),
                                       SurfaceField::kMinThreshold, SurfaceField::kMaxThreshold);
    const float resolution = std::clamp(finiteOr(settings.fieldResolution, 0.5f), 0.25f, 1.0f);
    const float speedScale = std::max(finiteOr(settings.speedScale, 2.0f), 1e-6f);
    const float fixedPressureScale = std::max(finiteOr(settings.pressureScale, 0.0f), 0.0f);
    const float solidThreshold = std::clamp(finiteOr(settings.solidThreshold, 0.15f), 0.05f, 4.0f);
    const float solidReach = std::clamp(finiteOr(settings.solidReach, 3.0f), 0.0f, 4.0f);

    RenderStats stats;
    stats.particles = static_cast<uint32_t>(n);
    // Errors the host left pending are not ours to count.
    drainErrors();

    // Camera to clip space: the camera's view rectangle fills the target (column-major mat3).
    const glm::vec2 viewport = glm::max(glm::vec2(camera.viewport), glm::vec2(1.0f));
    const float sx = 2.0f * camera.pixelsPerMetre / viewport.x;
    const float sy = 2.0f * camera.pixelsPerMetre / viewport.y;
    const float worldToClip[9] = {
        sx, 0.0f, 0.0f, 0.0f, sy, 0.0f, -camera.center.x * sx, -camera.center.y * sy, 1.0f};
    // Target pixels per metre along x (the camera's viewport may differ from the target).
    const float targetPixelsPerMetre = camera.pixelsPerMetre * float(m.size.x) / viewport.x;

    // ---- 1. background and the shapes under the liquid ----
    // State the host (an ImGui pass, say) may have changed.
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_CULL_FACE);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);

    glBindFramebuffer(GL_FRAMEBUFFER, m.compositeFbo);
    glViewport(0, 0, m.size.x, m.size.y);
    glClearColor(settings.background.r, settings.background.g, settings.background.b, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);

    // The views with a surface treat opaque triangles as solids: copied after both batches,
    // those of `under` first (drawn again over the liquid), then those of `over`.
    const bool surfaceView =
        n > 0 && (settings.view == View::Metaballs || settings.view == View::Pressure);
    std::vector<ShapeVertex>& solids = m.solidScratch;
    solids.clear();
    size_t solidUnderCount = 0;
    if (surfaceView) {
        for (const ShapeBatch* batch : {&under, &over}) {
            const std::span<const ShapeVertex> v = batch->vertices();
            for (size_t i = 0; i + 2 < v.size(); i += 3) {
                if (v[i].colour.a >= kOpaqueAlpha && v[i + 1].colour.a >= kOpaqueAlpha &&
                    v[i + 2].colour.a >= kOpaqueAlpha) {
                    solids.insert(solids.end(), v.begin() + std::ptrdiff_t(i),
                                  v.begin() + std::ptrdiff_t(i + 3));
                }
            }
            if (batch == &under) {
                solidUnderCount = solids.size();
            }
        }
    }
    const size_t solidFirst = underCount + overCount;
    const size_t shapeCount = solidFirst + solids.size();

    if (shapeCount > 0) {
        // Both batches (and the solids) in one buffer, one orphaning allocation per frame.
        glBindBuffer(GL_ARRAY_BUFFER, m.shapeVbo);
        glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(shapeCount * sizeof(ShapeVertex)),
                     nullptr, GL_STREAM_DRAW);
        if (underCount > 0) {
            glBufferSubData(GL_ARRAY_BUFFER, 0,
                            static_cast<GLsizeiptr>(underCount * sizeof(ShapeVertex)),
                            under.vertices().data());
        }
        if (overCount > 0) {
            glBufferSubData(
                GL_ARRAY_BUFFER, static_cast<GLintptr>(underCount * sizeof(ShapeVertex)),
                static_cast<GLsizeiptr>(overCount * sizeof(ShapeVertex)), over.vertices().data());
        }
        if (!solids.empty()) {
            glBufferSubData(
                GL_ARRAY_BUFFER, static_cast<GLintptr>(solidFirst * sizeof(ShapeVertex)),
                static_cast<GLsizeiptr>(solids.size() * sizeof(ShapeVertex)), solids.data());
        }
        glUseProgram(m.shapeProgram.id());
        glUniformMatrix3fv(m.shapeWorldToClip, 1, GL_FALSE, worldToClip);
    }
    m.drawShapes(0, static_cast<GLsizei>(underCount));

    // ---- 2. the liquid ----
    // Positions between steps: previous + factor (current - previous), as
    // fluid::interpolatedPositions computes them.
    std::span<const float> drawnX = particles.x, drawnY = particles.y;
    if (n > 0 && !particles.previousX.empty()) {
        const float f = particles.factor;
        m.drawnX.resize(n);
        m.drawnY.resize(n);
        for (size_t i = 0; i < n; ++i) {
            m.drawnX[i] = (1.0f - f) * particles.previousX[i] + f * particles.x[i];
            m.drawnY[i] = (1.0f - f) * particles.previousY[i] + f * particles.y[i];
        }
        drawnX = m.drawnX;
        drawnY = m.drawnY;
    }
    if (n > 0) {
        const View view = settings.view;
        const bool usePressure = view == View::Pressure && !particles.pressure.empty();
        const bool useVelocity = view == View::Particles;
        // Enabling and disabling attribute arrays is state of the bound vertex array.
        glBindVertexArray(m.particleVao);
        m.uploadChannel(kChX, drawnX.data(), n * sizeof(float), true);
        m.uploadChannel(kChY, drawnY.data(), n * sizeof(float), true);
        m.uploadChannel(kChVx, particles.vx.data(), n * sizeof(float),
                        useVelocity && !particles.vx.empty());
        m.uploadChannel(kChVy, particles.vy.data(), n * sizeof(float),
                        useVelocity && !particles.vy.empty());
        m.uploadChannel(kChPressure, particles.pressure.data(), n * sizeof(float), usePressure);
        m.uploadChannel(kChMaterial, particles.material.data(), n * sizeof(uint16_t),
                        !particles.material.empty());
        m.uploadChannel(kChColour, particles.colour.data(), n * sizeof(uint32_t),
                        !particles.colour.empty());

        // The rim band: about a third of a spacing of the first material, 1.5 to 12 px.
        const float rimWidth = std::clamp(0.3f * m.spacing[0] * targetPixelsPerMetre, 1.5f, 12.0f);

        if (view == View::Metaballs || view == View::Pressure) {
            const glm::ivec2 wanted =
                glm::max(glm::ivec2(glm::round(glm::vec2(m.size) * resolution)), glm::ivec2(1));
            if (wanted != m.fieldSize) {
                m.allocateField(wanted);
            }
            SurfacePass pass;
            pass.worldToClip = worldToClip;
            pass.particles = n;
            pass.fieldRadius = fieldRadius;
            pass.threshold = threshold;
            pass.rimWidth = view == View::Pressure ? 1.5f : rimWidth;
            pass.dark = view == View::Pressure;
            // Bounding box of the particles (non-finite ones drop out of the comparisons),
            // grown by the largest kernel radius.
            glm::vec2 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
            for (size_t i = 0; i < n; ++i) {
                const float x = drawnX[i], y = drawnY[i];
                lo.x = x < lo.x ? x : lo.x;
                hi.x = x > hi.x ? x : hi.x;
                lo.y = y < lo.y ? y : lo.y;
                hi.y = y > hi.y ? y : hi.y;
            }
            const float widest = *std::max_element(m.spacing.begin(), m.spacing.end());
            const float reach = fieldRadius * widest;
            pass.lo = lo - reach;
            pass.hi = hi + reach;
            pass.solidFirst = static_cast<GLint>(solidFirst);
            pass.solidCount = static_cast<GLsizei>(solids.size());
            pass.solids = solids;
            // The reach in solid texels (the field, and so the solid targets, may be a little
            // more or less than `resolution` times the target: rounding).
            pass.solidReach =
                solidReach * widest * targetPixelsPerMetre * float(m.solidSize.x) / float(m.size.x);
            pass.solidThreshold = solidThreshold;
            if (lo.x <= hi.x && lo.y <= hi.y) {
                m.drawSurface(pass);
                // Walls hide whatever of the liquid's surface reaches into them.
                m.drawShapes(static_cast<GLint>(solidFirst), static_cast<GLsizei>(solidUnderCount),
                             true);
            }
        }

        if (view == View::Pressure) {
            float scale = fixedPressureScale;
            if (scale == 0.0f) {
                // Automatic: the 95th percentile of the positive pressures, so a few spikes
                // at walls do not wash the rest of the liquid out.
                std::vector<float>& positive = m.pressureScratch;
                positive.clear();
                for (const float p : particles.pressure) {
                    if (p > 0.0f && std::isfinite(p)) {
                        positive.push_back(p);
                    }
                }
                if (!positive.empty()) {
                    const size_t k = static_cast<size_t>(0.95 * double(positive.size() - 1));
                    std::nth_element(positive.begin(),
                                     positive.begin() + static_cast<std::ptrdiff_t>(k),
                                     positive.end());
                    scale = positive[k];
                }
            }
            scale = std::max(scale, kMinPressureScale);
            stats.pressureScale = scale;
            glUseProgram(m.squareProgram.id());
            glUniformMatrix3fv(m.squareUniforms.worldToClip, 1, GL_FALSE, worldToClip);
            m.uploadMaterials(m.squareUniforms);
            glUniform1f(m.squareInvScale, 1.0f / scale);
            glBindVertexArray(m.particleVao);
            glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE,
                                GL_ONE_MINUS_SRC_ALPHA);
            glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, static_cast<GLsizei>(n));
        } else if (view == View::Particles) {
            glEnable(GL_BLEND);
            glBlendEquation(GL_FUNC_ADD);
            glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE,
                                GL_ONE_MINUS_SRC_ALPHA);
            glUseProgram(m.discProgram.id());
            glUniformMatrix3fv(m.discUniforms.worldToClip, 1, GL_FALSE, worldToClip);
            m.uploadMaterials(m.discUniforms);
            glUniform1f(m.discPixel, 1.0f / targetPixelsPerMetre);
            glUniform1f(m.discInvSpeedScale, 1.0f / speedScale);
            glBindVertexArray(m.particleVao);
            glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, static_cast<GLsizei>(n));
        }
    }

    // ---- 3. the shapes over the liquid ----
    if (overCount > 0) {
        glUseProgram(m.shapeProgram.id());
        m.drawShapes(static_cast<GLint>(underCount), static_cast<GLsizei>(overCount));
    }

    glBindVertexArray(0);
    glUseProgram(0);
    glDisable(GL_BLEND);
    stats.glErrors = drainErrors();
    return stats;
}

uint32_t Renderer::framebuffer() const {
    return checked(m_impl, "framebuffer").compositeFbo;
}

void Renderer::present(glm::ivec2 windowSize) const {
    const Impl& m = checked(m_impl, "present");
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    if (windowSize.x < 1 || windowSize.y < 1) {
        return; // a minimised window
    }
    glDisable(GL_SCISSOR_TEST);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glViewport(0, 0, windowSize.x, windowSize.y);
    glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    // Letterbox: the largest copy with the target's aspect, centred.
    const float scale =
        std::min(float(windowSize.x) / float(m.size.x), float(windowSize.y) / float(m.size.y));
    const int w = std::clamp(int(std::lround(float(m.size.x) * scale)), 1, windowSize.x);
    const int h = std::clamp(int(std::lround(float(m.size.y) * scale)), 1, windowSize.y);
    const int x0 = (windowSize.x - w) / 2;
    const int y0 = (windowSize.y - h) / 2;
    glBindFramebuffer(GL_READ_FRAMEBUFFER, m.compositeFbo);
    glBlitFramebuffer(0, 0, m.size.x, m.size.y, x0, y0, x0 + w, y0 + h, GL_COLOR_BUFFER_BIT,
                      (w == m.size.x && h == m.size.y) ? GL_NEAREST : GL_LINEAR);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void Renderer::readPixels(std::vector<uint8_t>& rgba) const {
    const Impl& m = checked(m_impl, "readPixels");
    const size_t rowBytes = size_t(m.size.x) * 4;
    rgba.resize(rowBytes * size_t(m.size.y));
    GLint previousRead = 0;
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &previousRead);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, m.compositeFbo);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    // A pack buffer the host left bound would receive the pixels instead of `rgba`.
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glPixelStorei(GL_PACK_ROW_LENGTH, 0);
    glReadPixels(0, 0, m.size.x, m.size.y, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(previousRead));
    // GL rows go bottom to top; image files go top to bottom.
    for (size_t top = 0, bottom = size_t(m.size.y) - 1; top < bottom; ++top, --bottom) {
        std::swap_ranges(rgba.begin() + static_cast<std::ptrdiff_t>(top * rowBytes),
                         rgba.begin() + static_cast<std::ptrdiff_t>((top + 1) * rowBytes),
                         rgba.begin() + static_cast<std::ptrdiff_t>(bottom * rowBytes));
    }
}

} // namespace fluid::gl
