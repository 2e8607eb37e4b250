// fluid::gl — entry points (GLEW), context description and error draining.
#include "gl_api.h"

#include <fluid/gl/renderer.h>

#include <atomic>
#include <cstdio>

namespace fluid::gl {

namespace {

// Bound on one drain: a lost context may report errors forever.
constexpr uint32_t kMaxDrainedErrors = 1024;

// GL entry points are per process (GLEW keeps them in globals), so this is too.
std::atomic<bool> g_loaded{false};

std::string errorName(GLenum error) {
    switch (error) {
    case GL_INVALID_ENUM:
        return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE:
        return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION:
        return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION:
        return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY:
        return "GL_OUT_OF_MEMORY";
#if !defined(FLUID_GL_ES) // OpenGL ES 3.0 has no matrix stacks
    case GL_STACK_UNDERFLOW:
        return "GL_STACK_UNDERFLOW";
    case GL_STACK_OVERFLOW:
        return "GL_STACK_OVERFLOW";
#endif
    default: {
        char buffer[32];
        std::snprintf(buffer, sizeof buffer, "GL error 0x%04X", static_cast<unsigned>(error));
        return buffer;
    }
    }
}

const char* glString(GLenum name) {
    // glGetString is OpenGL 1.1, exported by libGL itself: callable before glewInit.
    const GLubyte* text = glGetString(name);
    return text != nullptr ? reinterpret_cast<const char*>(text) : nullptr;
}

} // namespace

std::string describeContext() {
    const char* version = glString(GL_VERSION);
    const char* renderer = glString(GL_RENDERER);
    if (version == nullptr) {
        return "no current OpenGL context";
    }
    return std::string("OpenGL ") + version + " / " + (renderer != nullptr ? renderer : "?");
}

uint32_t drainErrors(std::vector<std::string>* names) {
    uint32_t count = 0;
    for (GLenum error = glGetError(); error != GL_NO_ERROR && count < kMaxDrainedErrors;
         error = glGetError()) {
        ++count;
        if (names != nullptr) {
            names->push_back(errorName(error));
        }
    }
    return count;
}

void loadFunctions() {
    if (g_loaded.load()) {
        return;
    }
#if defined(FLUID_GL_ES)
    // OpenGL ES 3.0 / WebGL2: the entry points are linked, nothing to load. The renderer's
    // half-float field needs float colour buffers (EXT_color_buffer_float; WebGL2 names it
    // the same), checked where the field is made.
    if (glGetString(GL_VERSION) == nullptr) {
        throw Error("fluid::gl: loadFunctions: no current OpenGL ES context",
                    ErrorCode::WrongState);
    }
    GLint major = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    drainErrors();
    if (major < 3) {
        throw Error("fluid::gl: loadFunctions: OpenGL ES 3.0 or later is needed, the current "
                    "context is " +
                        describeContext(),
                    ErrorCode::WrongState);
    }
#else
    // Core profiles have no GL_EXTENSIONS string: without glewExperimental GLEW would leave
    // every entry point past 1.1 null.
    glewExperimental = GL_TRUE;
    const GLenum status = glewInit();
    if (status != GLEW_OK) {
        throw Error(std::string("fluid::gl: loadFunctions: glewInit failed: ") +
                        reinterpret_cast<const char*>(glewGetErrorString(status)) + " (" +
                        describeContext() + ")",
                    ErrorCode::WrongState);
    }
    // GLEW 1.x asks for glGetString(GL_EXTENSIONS), which a core context rejects with
    // GL_INVALID_ENUM; clear it so the host's first error check does not blame itself.
    // (GLEW 2.2 uses glGetStringi in 3.0+ contexts: measured, it leaves no error on Mesa.)
    drainErrors();
    GLint major = 0;
    GLint minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    // Contexts older than 3.0 do not know these names: the values stay 0 and raise an error.
    drainErrors();
    if (major < 3 || (major == 3 && minor < 3)) {
        throw Error("fluid::gl: loadFunctions: OpenGL 3.3 core or later is needed, the current "
                    "context is " +
                        describeContext() + " (version " + std::to_string(major) + "." +
                        std::to_string(minor) + ")",
                    ErrorCode::WrongState);
    }
#endif
    g_loaded.store(true);
}

} // namespace fluid::gl
