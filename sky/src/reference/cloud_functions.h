// sky/shaders/clouds/functions.glsl compiled as C++ (double precision) in namespace
// zenith::sky::ref, with the C++ side of clouds/definitions.glsl: tiling textures with
// GL_LINEAR + GL_REPEAT semantics on every axis. Internal linkage, like a shader (see
// atmosphere_functions.h); unused functions are expected per translation unit.
#pragma once

#include <cstddef>
#include <vector>

#include "reference/shared_math.h"
#include "zenith/sky/clouds/noise.h"
#include "zenith/sky/clouds/weather.h"

namespace zenith::sky::ref {

// A GL_REPEAT, GL_LINEAR 2-D texture (weather maps): shared_math.h's Texture2D repeats along u
// only, so this is a repeating Texture3D one texel deep, which samples exactly as a 2-D texture
// since both z neighbours are the one slice.
class RepeatTexture2D {
  public:
    RepeatTexture2D() = default;
    RepeatTexture2D(int width, int height) : volume_(width, height, 1, /*wrap=*/true) {}
    int width() const { return volume_.size().x; }
    int height() const { return volume_.size().y; }
    vec4& at(int x, int y) { return volume_.at(x, y, 0); }
    const vec4& at(int x, int y) const { return volume_.at(x, y, 0); }
    vec4 Sample(vec2 uv) const { return volume_.Sample(vec3(uv.x, uv.y, 0.5)); }

  private:
    Texture3D volume_;
};

// Noise volumes are Texture3D with wrap = true (GL_REPEAT on every axis).
using CloudNoiseTexture = Texture3D;
using WeatherTexture = RepeatTexture2D;
// The ground shadow map: clamped at its edges (GL_CLAMP_TO_EDGE), linear.
using CloudShadowMapTexture = Texture2D;
// The far sun-depth volume (clouds/march.glsl): clamped, linear.
using CloudSunDepthTexture = Texture3D;

inline vec4 SampleRepeat2D(const RepeatTexture2D& t, vec2 uv) { return t.Sample(uv); }

// The values the GPU sees for an 8-bit UNORM upload of a noise volume: byte / 255 per channel,
// missing channels 0 (as GL fills them for RG8/RGB8), alpha of a 3-channel volume 1.
inline Texture3D ToTexture(const clouds::NoiseVolume& volume) {
    Texture3D texture(volume.size.x, volume.size.y, volume.size.z, /*wrap=*/true);
    for (int z = 0; z < volume.size.z; ++z) {
        for (int y = 0; y < volume.size.y; ++y) {
            for (int x = 0; x < volume.size.x; ++x) {
                vec4 v(0.0, 0.0, 0.0, 1.0);
                for (int c = 0; c < volume.channels; ++c) v[c] = volume.Value(x, y, z, c);
                texture.at(x, y, z) = v;
            }
        }
    }
    return texture;
}

// A weather map as uploaded in float (RGBA32F): the same values on both sides.
inline RepeatTexture2D ToTexture(const clouds::WeatherMap& map) {
    RepeatTexture2D texture(map.size, map.size);
    for (int y = 0; y < map.size; ++y) {
        for (int x = 0; x < map.size; ++x) texture.at(x, y) = vec4(map.at(x, y));
    }
    return texture;
}

}  // namespace zenith::sky::ref

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wunused-variable"
namespace zenith::sky::ref {
namespace {
#include "clouds/functions.glsl"
}  // namespace
}  // namespace zenith::sky::ref
#pragma GCC diagnostic pop
