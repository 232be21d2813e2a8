// GLSL side of the cloud textures for clouds/functions.glsl (the C++ side is
// sky/src/reference/cloud_functions.h). Included after common/definitions.glsl by cloud passes.
// The noise volumes and weather maps tile: the renderer binds them with GL_REPEAT on every axis
// and GL_LINEAR filtering, which is what the C++ side reproduces (Texture3D with wrap, and
// RepeatTexture2D). Noise is read with common/definitions.glsl's SampleTexture3D.
#define CloudNoiseTexture sampler3D
#define WeatherTexture sampler2D
#define CloudShadowMapTexture sampler2D
vec4 SampleRepeat2D(sampler2D t, vec2 uv) { return textureLod(t, uv, 0.0); }
