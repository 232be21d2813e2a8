// The GL contract between the renderer (C++) and the shaders: every texture unit, uniform and
// storage block binding, image unit, work-group size and shared limit, written once. Both
// compilers read this text: ComposeShader puts it first in every program (after #version), and
// sky/src/bindings.h includes it as C++ in namespace zenith::sky (shared_math.h and the GL
// mirrors include that). `const int` is a constant expression in both: GLSL 4.40+ accepts it in
// layout qualifiers (binding, local_size_*), C++ as a constexpr-usable namespace constant.
// No include guard: a guard would hide the constants from a second C++ namespace; bindings.h
// has #pragma once instead.
//
// tests/sky/gl_bindings_gl_test.cpp checks every program the renderer builds against these
// values and every block's layout against its C++ mirror.

// Limits shared by the std140 blocks and the renderer.
const int kMaxLights = 2;       // LightSet.light[]: the Sun and the Moon (H20's N_light = 2)
const int kEclipseLimbSamples = 8;  // LightSet.eclipse_limb[]: its table of the Sun's limb
const int kCloudMaxLayers = 4;  // CloudBlock.cloud_layers[], weather_maps[]
const int kMoonShadowSamples = 64;  // FrameBlock.moon_shadow[]: the Earth's shadow on the Moon
// The multiple-scattering LUT's tiles side by side (atmosphere/functions.glsl:
// MultipleScatteringSample): its texture is this many times multiple_scattering_size wide.
const int kMultipleScatteringTiles = 3;

// Uniform block binding points (std140).
const int kAtmosphereBlockBinding = 0;  // atmosphere/interface.glsl: AtmosphereBlock
const int kLightBlockBinding = 1;       // LightBlock
const int kSettingsBlockBinding = 2;    // SettingsBlock
const int kFrameBlockBinding = 3;       // FrameBlock
const int kCloudBlockBinding = 4;       // clouds/interface.glsl: CloudBlock
// atmosphere/precipitation_block.glsl: PrecipitationBlock
const int kPrecipitationBlockBinding = 5;

// Shader storage block binding points (std140).
const int kLightStorageBinding = 1;  // clouds/sky_shade.comp: LightStorage (a LightSet)
// display/*: DisplayStorage (the histogram and the exposure). The same binding point as
// kLightStorageBinding: no pass uses both, and the StateGuard saves only this one.
const int kDisplayStorageBinding = 1;
// atmosphere/environment_sh.comp: EnvironmentShStorage (the environment's nine coefficients).
// The same binding point again, for the same reason.
const int kEnvironmentStorageBinding = 1;
// clouds/geometry_list.glsl: CloudGeometryList (the pixels of a host's geometry marched on their
// own rays, and the indirect draw that marches them). Again the same binding point.
const int kCloudGeometryListBinding = 1;

// Texture units of the samplers. The atmosphere's (0-6) are bound by AtmosphereRenderer before
// every pass, the clouds' (7-18) by CloudPasses.
const int kTransmittanceUnit = 0;
const int kMultipleScatteringUnit = 1;
const int kIrradianceUnit = 2;
const int kSkyViewUnit = 3;
const int kStarUnit = 4;
const int kSceneDepthUnit = 5;
const int kAerialPerspectiveUnit = 6;
const int kShapeNoiseUnit = 7;
const int kDetailNoiseUnit = 8;
const int kWeatherMapsUnit = 9;  // the first of kCloudMaxLayers units (9-12)
const int kCloudTraceUnit = 13;
const int kCloudTraceDepthUnit = 14;
const int kCloudHistoryUnit = 15;
const int kDisplayInputUnit = 16;  // display/*: the linear frame (cd/m^2) to display
const int kCloudShadowMapUnit = 17;
const int kCloudGroundShadowUnit = 18;
const int kNightSkyUnit = 19;  // atmosphere/render.frag: the night sky's light (night_sky.h)
const int kCloudAirShadowUnit = 20;  // clouds/light_shafts.frag's 4 outputs (20-23)
const int kCloudTraceProfileUnit = 24;  // clouds/trace.frag's transmittance profile
const int kCloudGeometryUnit = 25;      // clouds/geometry_march.frag's (L, T) at host geometry
const int kCloudSunDepthUnit = 26;      // clouds/sun_depth.comp's far sun-depth volume
const int kTextureUnitCount = 27;       // units 0 .. kTextureUnitCount - 1 are zenith's

// Image units.
const int kOutputImageUnit = 0;          // what each LUT pass and clouds/shadow_map.comp write
const int kShadeDirectionsImageUnit = 0;  // clouds/sky_shade.comp reads
const int kShadowMapImageUnit = 1;        // clouds/sky_shade.comp reads
const int kScatteringOrderImageUnit = 1;  // atmosphere/multiple_scattering.comp writes...
const int kColumnCorrectionImageUnit = 2;  // ...and reads
const int kEnvironmentImageUnit = 0;      // atmosphere/environment_sh.comp reads the atlas
// The clouds' passes in the compute stage (clouds/*.comp) write their targets, the fragment
// stage's outputs 0, 1, ..., to image units kCloudPassImageUnit + 0, 1, ... (the light shafts'
// four parts the most).
const int kCloudPassImageUnit = 0;
const int kImageUnitCount = 4;  // image units 0 .. kImageUnitCount - 1 are zenith's

// Compute work-group sizes, which the host's dispatches divide by.
const int kLutGroupSize = 8;          // 2-D LUTs and the aerial perspective: 8 x 8 invocations
// The multiple-scattering and ground-irradiance LUTs: one group per texel, its directions spread
// over the invocations (with one invocation per texel, 4096 and 256 of them, a GPU of 132
// multiprocessors was mostly idle: 2.5 ms on an H200, 0.43 ms with 16 invocations, 0.29 ms with
// 64; llvmpipe's pass 1.15x and 1.65x as long, its barriers being coroutine switches).
const int kDirectionsGroupSize = 16;
const int kShadowMapGroupSize = 8;    // clouds/shadow_map.comp and sun_depth.comp: 8 x 8
const int kCloudPassGroupSize = 8;  // the clouds' passes in the compute stage: 8 x 8
const int kEnvironmentShGroupSize = 64;  // atmosphere/environment_sh.comp: one group of 64

// The light shafts are worked out once per kCloudLightShaftCell^2 trace cells.
const int kCloudLightShaftCell = 2;

// The display pass (zenith/sky/display.h): the meter's histogram of log2 luminance has
// kDisplayHistogramBins bins over [kDisplayHistogramMinLog2, kDisplayHistogramMaxLog2) (1e-6 to
// 4.3e9 cd/m^2: the threshold of vision to the Sun's disk), 0.05 EV each.
const int kDisplayGroupSize = 16;            // display/histogram.comp: 16 x 16 invocations...
const int kDisplayPixelsPerInvocation = 4;  // ...of 4 x 4 pixels each
const int kDisplayHistogramBins = 1024;
const int kDisplayHistogramMinLog2 = -20;
const int kDisplayHistogramMaxLog2 = 32;
