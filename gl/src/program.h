// fluid::gl internals — a linked GLSL program built from two embedded shaders.
#pragma once
#include "gl_api.h"

#include <string_view>

namespace fluid::gl::detail {

/// Owns one program object. Thread rule: the thread whose context is current.
class Program {
public:
    Program() = default;
    /// Compiles the embedded shaders `vertexName` and `fragmentName` and links them; throws
    /// `fluid::Error` naming the shader and quoting the compiler's or linker's log.
    Program(std::string_view vertexName, std::string_view fragmentName);
    ~Program();
    Program(Program&& other) noexcept;
    Program& operator=(Program&& other) noexcept;
    Program(const Program&) = delete;
    Program& operator=(const Program&) = delete;

    /// The program name (0 when empty).
    GLuint id() const { return m_id; }
    /// Location of uniform `name`; -1 when the linker removed it (GL ignores -1).
    GLint uniform(const char* name) const;

private:
    GLuint m_id = 0;
};

} // namespace fluid::gl::detail
