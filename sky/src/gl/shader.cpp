#include "gl/shader.h"

#include <glad/gl.h>

#include <string>
#include <utility>
#include <vector>

namespace zenith::sky::gl {
namespace {

static_assert(std::is_same_v<GlName, GLuint> && std::is_same_v<GlEnum, GLenum>);

std::string ShaderInfoLog(GLuint shader) {
    GLint length = 0;
    glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
    if (length <= 1) return "(empty info log)";
    std::string log(static_cast<size_t>(length), '\0');
    glGetShaderInfoLog(shader, length, nullptr, log.data());
    log.resize(log.find('\0'));
    return log;
}

std::string ProgramInfoLog(GLuint program) {
    GLint length = 0;
    glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
    if (length <= 1) return "(empty info log)";
    std::string log(static_cast<size_t>(length), '\0');
    glGetProgramInfoLog(program, length, nullptr, log.data());
    log.resize(log.find('\0'));
    return log;
}

}  // namespace

std::string_view ShaderStageName(GlEnum stage) {
    switch (stage) {
        case GL_VERTEX_SHADER:
            return "vertex";
        case GL_TESS_CONTROL_SHADER:
            return "tessellation control";
        case GL_TESS_EVALUATION_SHADER:
            return "tessellation evaluation";
        case GL_GEOMETRY_SHADER:
            return "geometry";
        case GL_FRAGMENT_SHADER:
            return "fragment";
        case GL_COMPUTE_SHADER:
            return "compute";
        default:
            return "unknown-stage";
    }
}

Shader::Shader(GlEnum stage, std::string_view source, std::string_view label) : label_(label) {
    name_ = glCreateShader(stage);
    if (name_ == 0) {
        throw ShaderError(label_ + ": glCreateShader(" + std::string(ShaderStageName(stage)) +
                          ") failed (GL error " + std::to_string(glGetError()) + ")");
    }
    const GLchar* text = source.data();
    const auto length = static_cast<GLint>(source.size());
    glShaderSource(name_, 1, &text, &length);
    glObjectLabel(GL_SHADER, name_, static_cast<GLsizei>(label_.size()), label_.data());
    glCompileShader(name_);
    GLint ok = GL_FALSE;
    glGetShaderiv(name_, GL_COMPILE_STATUS, &ok);
    if (ok != GL_TRUE) {
        const std::string log = ShaderInfoLog(name_);
        glDeleteShader(name_);
        name_ = 0;
        throw ShaderError(label_ + ": " + std::string(ShaderStageName(stage)) +
                          " shader failed to compile:\n" + log);
    }
}

Shader::~Shader() {
    if (name_ != 0) glDeleteShader(name_);
}

Shader::Shader(Shader&& other) noexcept
    : name_(std::exchange(other.name_, 0)), label_(std::move(other.label_)) {}

Shader& Shader::operator=(Shader&& other) noexcept {
    if (this != &other) {
        if (name_ != 0) glDeleteShader(name_);
        name_ = std::exchange(other.name_, 0);
        label_ = std::move(other.label_);
    }
    return *this;
}

Program::Program(std::initializer_list<const Shader*> shaders, std::string_view label)
    : label_(label) {
    name_ = glCreateProgram();
    if (name_ == 0) throw ShaderError(label_ + ": glCreateProgram failed");
    for (const Shader* shader : shaders) glAttachShader(name_, shader->name());
    glObjectLabel(GL_PROGRAM, name_, static_cast<GLsizei>(label_.size()), label_.data());
    glLinkProgram(name_);
    for (const Shader* shader : shaders) glDetachShader(name_, shader->name());
    GLint ok = GL_FALSE;
    glGetProgramiv(name_, GL_LINK_STATUS, &ok);
    if (ok != GL_TRUE) {
        const std::string log = ProgramInfoLog(name_);
        glDeleteProgram(name_);
        name_ = 0;
        throw ShaderError(label_ + ": program failed to link:\n" + log);
    }
}

Program::~Program() {
    if (name_ != 0) glDeleteProgram(name_);
}

Program::Program(Program&& other) noexcept
    : name_(std::exchange(other.name_, 0)), label_(std::move(other.label_)) {}

Program& Program::operator=(Program&& other) noexcept {
    if (this != &other) {
        if (name_ != 0) glDeleteProgram(name_);
        name_ = std::exchange(other.name_, 0);
        label_ = std::move(other.label_);
    }
    return *this;
}

Program Program::Compute(std::string_view source, std::string_view label) {
    const Shader shader(GL_COMPUTE_SHADER, source, label);
    return Program({&shader}, label);
}

Program Program::Graphics(std::string_view vertex_source, std::string_view fragment_source,
                          std::string_view label) {
    const std::string name(label);
    const Shader vertex(GL_VERTEX_SHADER, vertex_source, name + " (vertex)");
    const Shader fragment(GL_FRAGMENT_SHADER, fragment_source, name + " (fragment)");
    return Program({&vertex, &fragment}, label);
}

void Program::Use() const { glUseProgram(name_); }

}  // namespace zenith::sky::gl
