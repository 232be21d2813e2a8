// GLSL side of the shared-source shim (see sky/src/reference/shared_math.h for the C++ side).
// Shared files use only these names, GLSL built-ins that GLM also has, and no gl_* variables;
// texture reads go through the Sample*() functions each side defines, and a texture's size
// through TextureSize(), so the functions take a texture without its size beside it.
#define Number float
#define IN(x) const in x
#define OUT(x) out x
#define INOUT(x) inout x
#define TransmittanceTexture sampler2D
#define MultipleScatteringTexture sampler2D
#define SkyViewTexture sampler2D
#define IrradianceTexture sampler2D
#define AerialPerspectiveTexture sampler3D
#define kPi 3.14159265358979323846
vec4 SampleTexture2D(sampler2D t, vec2 uv) { return textureLod(t, uv, 0.0); }
vec4 SampleTexture3D(sampler3D t, vec3 uvw) { return textureLod(t, uvw, 0.0); }
ivec2 TextureSize(sampler2D t) { return textureSize(t, 0); }
ivec3 TextureSize(sampler3D t) { return textureSize(t, 0); }
