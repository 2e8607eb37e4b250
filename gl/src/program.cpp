// fluid::gl internals — shader compilation and linking with readable errors.
#include "program.h"

#include <fluid/error.h>
#include <fluid/gl/renderer.h>

#include <string>
#include <utility>

namespace fluid::gl::detail {

namespace {

// fluid::Error messages are one line: the log's lines are joined with " | ".
std::string oneLine(std::string log) {
    while (!log.empty() &&
           (log.back() == '\n' || log.back() == '\r' || log.back() == ' ' || log.back() == '\0')) {
        log.pop_back();
    }
    std::string out;
    out.reserve(log.size());
    for (char c : log) {
        if (c == '\n') {
            out += " | ";
        } else if (c != '\r') {
            out += c;
        }
    }
    return out.empty() ? std::string("(empty log)") : out;
}

std::string shaderLog(GLuint shader) {
    GLint length = 0;
    glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<size_t>(length > 0 ? length : 0), '\0');
    if (length > 0) {
        glGetShaderInfoLog(shader, length, nullptr, log.data());
    }
    return oneLine(std::move(log));
}

std::string programLog(GLuint program) {
    GLint length = 0;
    glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<size_t>(length > 0 ? length : 0), '\0');
    if (length > 0) {
        glGetProgramInfoLog(program, length, nullptr, log.data());
    }
    return oneLine(std::move(log));
}

GLuint compile(GLenum stage, std::string_view name) {
    const std::string_view source = shaderSource(name);
    if (source.empty()) {
        throw Error("fluid::gl: shader '" + std::string(name) + "' is not embedded",
                    ErrorCode::BadArgument);
    }
    const GLuint shader = glCreateShader(stage);
    if (shader == 0) {
        throw Error("fluid::gl: shader '" + std::string(name) +
                        "': glCreateShader failed (no current context?)",
                    ErrorCode::WrongState);
    }
    const GLchar* text = source.data();
    const GLint length = static_cast<GLint>(source.size());
    glShaderSource(shader, 1, &text, &length);
    glCompileShader(shader);
    GLint ok = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (ok != GL_TRUE) {
        const std::string log = shaderLog(shader);
        glDeleteShader(shader);
        throw Error("fluid::gl: shader '" + std::string(name) + "' does not compile: " + log,
                    ErrorCode::WrongState);
    }
    return shader;
}

} // namespace

Program::Program(std::string_view vertexName, std::string_view fragmentName) {
    const GLuint vertex = compile(GL_VERTEX_SHADER, vertexName);
    GLuint fragment = 0;
    try {
        fragment = compile(GL_FRAGMENT_SHADER, fragmentName);
    } catch (...) {
        glDeleteShader(vertex);
        throw;
    }
    m_id = glCreateProgram();
    glAttachShader(m_id, vertex);
    glAttachShader(m_id, fragment);
    glLinkProgram(m_id);
    // The program keeps the compiled code; the shader objects can go now.
    glDetachShader(m_id, vertex);
    glDetachShader(m_id, fragment);
    glDeleteShader(vertex);
    glDeleteShader(fragment);
    GLint ok = GL_FALSE;
    glGetProgramiv(m_id, GL_LINK_STATUS, &ok);
    if (ok != GL_TRUE) {
        const std::string log = programLog(m_id);
        glDeleteProgram(m_id);
        m_id = 0;
        throw Error("fluid::gl: program '" + std::string(vertexName) + "' + '" +
                        std::string(fragmentName) + "' does not link: " + log,
                    ErrorCode::WrongState);
    }
}

Program::~Program() {
    if (m_id != 0) {
        glDeleteProgram(m_id);
    }
}

Program::Program(Program&& other) noexcept : m_id(std::exchange(other.m_id, 0)) {}

Program& Program::operator=(Program&& other) noexcept {
    if (this != &other) {
        if (m_id != 0) {
            glDeleteProgram(m_id);
        }
        m_id = std::exchange(other.m_id, 0);
    }
    return *this;
}

GLint Program::uniform(const char* name) const {
    return glGetUniformLocation(m_id, name);
}

} // namespace fluid::gl::detail
