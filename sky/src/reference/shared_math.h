// C++ side of the shared-source shim: the GLSL subset in sky/shaders/**/*.glsl compiles as C++
// here, in double precision through GLM, so the CPU reference and the shaders are one text
// (the approach of Bruneton's precomputed_atmospheric_scattering). Keep everything double:
// unsuffixed literals are double in C++ and would not match float GLM overloads.
#pragma once

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>
#include <vector>

#include "bindings.h"  // kMaxLights sizes LightSet

namespace zenith::sky::ref {

using Number = double;
using vec2 = glm::dvec2;
using vec3 = glm::dvec3;
using vec4 = glm::dvec4;
using ivec2 = glm::ivec2;
using ivec3 = glm::ivec3;
using mat3 = glm::dmat3;
using glm::atan;
using glm::clamp;
using glm::cross;
using glm::dot;
using glm::exp;
using glm::fract;
using glm::length;
using glm::max;
using glm::min;
using glm::mix;
using glm::normalize;
using glm::sign;
using glm::smoothstep;
using std::abs;
using std::acos;
using std::asin;
using std::ceil;
using std::cos;
using std::floor;
using std::log;
using std::pow;
using std::sin;
using std::sqrt;

inline constexpr double kPi = 3.14159265358979323846;

// A float RGBA texture with GL_LINEAR + GL_CLAMP_TO_EDGE semantics (texel centres at
// (i + 0.5) / size), so shared code samples the CPU LUTs exactly as the GPU samples its own.
class Texture2D {
  public:
    Texture2D() = default;
    // wrap_u: GL_REPEAT along u (the Sky-View azimuth), else GL_CLAMP_TO_EDGE.
    Texture2D(int width, int height, bool wrap_u = false)
        : width_(width),
          height_(height),
          wrap_u_(wrap_u),
          texels_(static_cast<std::size_t>(width) * static_cast<std::size_t>(height)) {}
    int width() const { return width_; }
    int height() const { return height_; }
    vec4& at(int x, int y) { return texels_[Index(x, y)]; }
    const vec4& at(int x, int y) const { return texels_[Index(x, y)]; }
    const std::vector<vec4>& texels() const { return texels_; }

    vec4 Sample(vec2 uv) const {
        const double x = uv.x * width_ - 0.5, y = uv.y * height_ - 0.5;
        const double fx = std::floor(x), fy = std::floor(y);
        const int x0 = static_cast<int>(fx), y0 = static_cast<int>(fy);
        const double tx = x - fx, ty = y - fy;
        const vec4 a = mix(Clamped(x0, y0), Clamped(x0 + 1, y0), tx);
        const vec4 b = mix(Clamped(x0, y0 + 1), Clamped(x0 + 1, y0 + 1), tx);
        return mix(a, b, ty);
    }

  private:
    std::size_t Index(int x, int y) const {
        return static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
               static_cast<std::size_t>(x);
    }
    const vec4& Clamped(int x, int y) const {
        const int xi = wrap_u_ ? ((x % width_) + width_) % width_ : std::clamp(x, 0, width_ - 1);
        return at(xi, std::clamp(y, 0, height_ - 1));
    }
    int width_ = 0;
    int height_ = 0;
    bool wrap_u_ = false;
    std::vector<vec4> texels_;
};

// A float RGBA volume with GL_LINEAR semantics, clamped (or repeating, for tileable noise).
class Texture3D {
  public:
    Texture3D() = default;
    Texture3D(int width, int height, int depth, bool wrap = false)
        : size_(width, height, depth),
          wrap_(wrap),
          texels_(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) *
                  static_cast<std::size_t>(depth)) {}
    ivec3 size() const { return size_; }
    vec4& at(int x, int y, int z) { return texels_[Index(x, y, z)]; }
    const vec4& at(int x, int y, int z) const { return texels_[Index(x, y, z)]; }

    vec4 Sample(vec3 uvw) const {
        const vec3 p = uvw * vec3(size_) - 0.5;
        const vec3 f = glm::floor(p);
        const ivec3 i = ivec3(f);
        const vec3 t = p - f;
        vec4 result(0.0);
        for (int corner = 0; corner < 8; ++corner) {
            const ivec3 o((corner & 1), (corner >> 1) & 1, (corner >> 2) & 1);
            const double w =
                (o.x ? t.x : 1.0 - t.x) * (o.y ? t.y : 1.0 - t.y) * (o.z ? t.z : 1.0 - t.z);
            result += w * Fetch(i + o);
        }
        return result;
    }

  private:
    std::size_t Index(int x, int y, int z) const {
        return (static_cast<std::size_t>(z) * static_cast<std::size_t>(size_.y) +
                static_cast<std::size_t>(y)) *
                   static_cast<std::size_t>(size_.x) +
               static_cast<std::size_t>(x);
    }
    const vec4& Fetch(ivec3 p) const {
        for (int a = 0; a < 3; ++a) {
            p[a] = wrap_ ? ((p[a] % size_[a]) + size_[a]) % size_[a]
                         : std::clamp(p[a], 0, size_[a] - 1);
        }
        return at(p.x, p.y, p.z);
    }
    ivec3 size_{0};
    bool wrap_ = false;
    std::vector<vec4> texels_;
};

using TransmittanceTexture = Texture2D;
using MultipleScatteringTexture = Texture2D;
using SkyViewTexture = Texture2D;
using IrradianceTexture = Texture2D;
using AerialPerspectiveTexture = Texture3D;

inline vec4 SampleTexture2D(const Texture2D& t, vec2 uv) { return t.Sample(uv); }
inline vec4 SampleTexture3D(const Texture3D& t, vec3 uvw) { return t.Sample(uvw); }
inline ivec2 TextureSize(const Texture2D& t) { return ivec2(t.width(), t.height()); }
inline ivec3 TextureSize(const Texture3D& t) { return t.size(); }

}  // namespace zenith::sky::ref

#define IN(x) const x&
#define OUT(x) x&
#define INOUT(x) x&
