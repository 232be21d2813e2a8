// GLSL side of the cloud textures for clouds/functions.glsl (the C++ side is
// sky/src/reference/cloud_functions.h). Included after common/definitions.glsl by cloud passes.
// The noise volumes and weather maps tile: the renderer binds them with GL_REPEAT on every axis
// and GL_LINEAR filtering, which is what the C++ side reproduces (Texture3D with wrap, and
// RepeatTexture2D). Noise is read with common/definitions.glsl's SampleTexture3D.
#define CloudNoiseTexture sampler3D
#define CloudShadowMapTexture sampler2D
#define CloudSunDepthTexture sampler3D  // the far sun-depth volume (clouds/march.glsl)
//
// A layer's weather map as the march takes it: the sampler, or in compute programs
// (CLOUD_COMPUTE_STAGE) its index into interface.glsl's weather_maps, read there with constant
// indices: Mesa's llvmpipe (22.3) read the wrong texels through a dynamically uniform index into
// that sampler array in a compute shader that also samples the atmosphere's LUTs (the compute
// trace lost all of the clouds' light), which GLSL allows and its fragment stage reads right.
// Fragment programs keep the index: the constant indices made llvmpipe's fragment trace 1.4x
// slower (it runs every branch under a mask), and cost nothing in its compute stage or on an
// NVIDIA H200.
#ifdef CLOUD_COMPUTE_STAGE
#define WeatherTexture int
vec4 SampleRepeat2D(int map, vec2 uv);  // clouds/interface.glsl
#else
#define WeatherTexture sampler2D
vec4 SampleRepeat2D(sampler2D t, vec2 uv) { return textureLod(t, uv, 0.0); }
#endif
