// Compiling and linking GLSL programs; failures throw ShaderError carrying the driver's info log.
// A context must be current (and its functions loaded) when these are created and destroyed.
#pragma once

#include <initializer_list>
#include <string>
#include <string_view>

#include "zenith/sky/gl/error.h"

namespace zenith::sky::gl {

// GLuint / GLenum without pulling the GL header in.
using GlName = unsigned int;
using GlEnum = unsigned int;

class ShaderError : public GlError {
  public:
    using GlError::GlError;
};

// A shader object (owning). `label` names the source in messages, e.g. its file name.
class Shader {
  public:
    // stage: GL_COMPUTE_SHADER, GL_VERTEX_SHADER, GL_FRAGMENT_SHADER, ...
    Shader(GlEnum stage, std::string_view source, std::string_view label);
    ~Shader();
    Shader(Shader&& other) noexcept;
    Shader& operator=(Shader&& other) noexcept;
    Shader(const Shader&) = delete;
    Shader& operator=(const Shader&) = delete;

    GlName name() const { return name_; }
    const std::string& label() const { return label_; }

  private:
    GlName name_ = 0;
    std::string label_;
};

// A linked program object (owning).
class Program {
  public:
    Program(std::initializer_list<const Shader*> shaders, std::string_view label);
    ~Program();
    Program(Program&& other) noexcept;
    Program& operator=(Program&& other) noexcept;
    Program(const Program&) = delete;
    Program& operator=(const Program&) = delete;

    static Program Compute(std::string_view source, std::string_view label);
    static Program Graphics(std::string_view vertex_source, std::string_view fragment_source,
                            std::string_view label);

    GlName name() const { return name_; }
    const std::string& label() const { return label_; }
    void Use() const;

  private:
    GlName name_ = 0;
    std::string label_;
};

// Human-readable name of a GL shader stage, for messages ("compute", "fragment", ...).
std::string_view ShaderStageName(GlEnum stage);

}  // namespace zenith::sky::gl
