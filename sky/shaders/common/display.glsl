// The display transform: exposure, night (scotopic) adaptation, tone map and sRGB encoding, one
// text for the GPU display pass (sky/shaders/display/*) and the CPU (sky/src/image_io.cpp, the
// PNGs of `zenith render`), which includes it as C++ through sky/src/reference/display_functions.h.
// Scene values are linear Rec.709 luminance in cd/m^2 per channel.
//
// References
//   [LR14] S. Lagarde, C. de Rousiers, "Moving Frostbite to Physically Based Rendering 3.0",
//          SIGGRAPH 2014 course notes, §5.1 "A Physically Based Camera" (EV100, metering, the
//          saturation-based L_max).
//   [N16]  K. Narkowicz, "ACES Filmic Tone Mapping Curve", blog post, 2016-01-06.
//   [sRGB] IEC 61966-2-1:1999, the sRGB transfer function.
//   [J00]  H. W. Jensen, F. Durand, M. M. Stark, S. Premoze, J. Dorsey, P. Shirley, "A
//          Physically-Based Night Sky Model", SIGGRAPH 2000, §7 (tone mapping night scenes):
//          scotopic luminance, a mesopic weight between rod and cone vision over the luminance,
//          and a blue shift of what the rods see.
//   [L97]  G. W. Larson, H. Rushmeier, C. Piatko, "A Visibility Matching Tone Reproduction
//          Operator for High Dynamic Range Scenes", IEEE TVCG 3(4), 1997: the scotopic luminance
//          from CIE XYZ, V = Y (1.33 (1 + (Y + Z) / X) - 1.68), and the mesopic range
//          0.0056-5.6 cd/m^2 (here 0.01-4 cd/m^2, as [J00] uses log10 Y from -2 to 0.6).
//   [K05]  G. Krawczyk, K. Myszkowski, H.-P. Seidel, "Lightness Perception in Tone Reproduction
//          for High Dynamic Range Images", Eurographics 2005, Eq. (11): the key value
//          a = 1.03 - 2 / (2 + log10(L_avg + 1)), lower for darker scenes.

// Camera constants of [LR14] §5.1.
const Number kDisplayIso = 100.0;               // S
const Number kDisplayCalibration = 12.5;        // K, reflected-light meter calibration
const Number kDisplayLensAttenuation = 0.65;    // q
const Number kDisplayMinEV100 = -20.0;          // far below starlight (~-6)
const Number kDisplayMaxEV100 = 30.0;           // far above the Sun's disk (~+27)
const Number kDisplayMinMeteredLuminance = 1e-6;  // cd/m^2, about the threshold of vision
// The meter reads the pixels between these percentiles of luminance (histogram metering: black
// space beside a planet, or the Sun's disk, does not set the exposure).
const int kDisplayMeteredLowPercentile = 50;
const int kDisplayMeteredHighPercentile = 95;
// Night adaptation: fully scotopic below 10^-2 cd/m^2, fully photopic above 10^0.6 = 4 cd/m^2
// ([J00], [L97]); the rods' colour is this blue-grey chromaticity (CIE 1931 x, y). [J00] blends
// toward a fixed bluish chromaticity; ours is zenith's choice, nearer D65 (0.3127, 0.3290) so
// that a moonlit frame is bluish but less saturated than the day sky.
const Number kDisplayScotopicLog10 = -2.0;
const Number kDisplayPhotopicLog10 = 0.6;
const Number kDisplayNightX = 0.30;
const Number kDisplayNightY = 0.31;

// The luminance that saturates the camera, [LR14] §5.1: L_max = 78 / (q S) 2^EV100 (1.2 2^EV100
// cd/m^2). Its inverse scales scene luminance to the normalised sensor value (1 = saturated).
Number DisplayMaxLuminance(Number ev100) {
    return 78.0 / (kDisplayLensAttenuation * kDisplayIso) * exp2(ev100);
}
Number DisplayExposureScale(Number ev100) { return 1.0 / DisplayMaxLuminance(ev100); }

// Rec.709 luminance (ITU-R BT.709-6 item 3.2).
Number DisplayLuminance(vec3 rgb) { return 0.2126 * rgb.r + 0.7152 * rgb.g + 0.0722 * rgb.b; }

// A reflected-light meter, [LR14] §5.1: EV100 = log2(L_avg S / K), given log2 L_avg (the mean of
// log2 Y over the metered pixels, log2 of their geometric mean).
Number DisplayMeteredEV100(Number log2_average_luminance) {
    return log2_average_luminance + log2(kDisplayIso / kDisplayCalibration);
}

// [K05] Eq. (11): the key value of a scene of log-average luminance L (cd/m^2).
Number DisplayKey(Number average_luminance) {
    return 1.03 - 2.0 / (2.0 + log(average_luminance + 1.0) / log(10.0));
}

// How much darker (EV, >= 0) the metered exposure is made for a scene of log-average luminance
// L: the meter alone brings every scene to the same grey, a moonlit sky as bright as noon. Below
// photopic levels the scene keeps [K05]'s key relative to the key at 4 cd/m^2 (10^0.6, where
// vision is photopic): 0 EV in daylight, 1.0 EV at 0.5 cd/m^2, 3.2 EV at 10^-3 cd/m^2, 3.3 EV
// at most.
Number DisplayNightCompensationEV(Number average_luminance) {
    Number reference = DisplayKey(pow(10.0, kDisplayPhotopicLog10));
    return max(0.0, log2(reference / DisplayKey(average_luminance)));
}

// The rods' share of vision at a luminance Y (cd/m^2): 1 below 10^-2, 0 above 10^0.6, a
// smoothstep of log10 Y between ([J00] §7).
Number DisplayScotopicWeight(Number luminance) {
    Number l = log(max(luminance, kDisplayMinMeteredLuminance)) / log(10.0);
    return 1.0 - smoothstep(kDisplayScotopicLog10, kDisplayPhotopicLog10, l);
}

// Night adaptation of a scene colour (linear Rec.709, cd/m^2), [J00] §7: with the rods' share w,
// the luminance becomes (1 - w) Y + w V' and the chromaticity moves from the colour's own toward
// the night blue-grey by w. V' = 0.4468 V is [L97]'s scotopic luminance scaled so that a
// surface lit by moonlight-coloured light keeps its luminance; here it is clamped to Y, so the
// rods never brighten a colour (a red light at night looks dim, not bright).
vec3 DisplayNightAdaptation(vec3 rgb) {
    // Rec.709 / D65 to CIE XYZ (IEC 61966-2-1), and back.
    mat3 xyz_from_rgb = mat3(0.4124, 0.2126, 0.0193, 0.3576, 0.7152, 0.1192, 0.1805, 0.0722, 0.9505);
    mat3 rgb_from_xyz =
        mat3(3.2406, -0.9689, 0.0557, -1.5372, 1.8758, -0.2040, -0.4986, 0.0415, 1.0570);
    // A colour with a NaN or infinite channel is left alone (DisplayTransform gives those
    // channels 0 or 1), and so is black.
    Number y = DisplayLuminance(rgb);
    if (isnan(y) || isinf(y)) return rgb;
    vec3 xyz = xyz_from_rgb * max(rgb, vec3(0.0));
    Number sum = xyz.x + xyz.y + xyz.z;
    if (!(sum > 0.0)) return rgb;
    Number w = DisplayScotopicWeight(xyz.y);
    if (w <= 0.0) return rgb;
    Number scotopic = xyz.x > 0.0 ? xyz.y * (1.33 * (1.0 + (xyz.y + xyz.z) / xyz.x) - 1.68) : 0.0;
    Number luminance = mix(xyz.y, min(0.4468 * max(scotopic, 0.0), xyz.y), w);
    Number cx = mix(xyz.x / sum, kDisplayNightX, w);
    Number cy = mix(xyz.y / sum, kDisplayNightY, w);
    vec3 adapted = vec3(cx * luminance / cy, luminance, (1.0 - cx - cy) * luminance / cy);
    return max(rgb_from_xyz * adapted, vec3(0.0));
}

// ACES filmic curve fitted by [N16] for an exposed value x >= 0, clamped to [0, 1].
Number DisplayToneMapAces(Number x) {
    Number a = 2.51, b = 0.03, c = 2.43, d = 0.59, e = 0.14;
    return clamp((x * (a * x + b)) / (x * (c * x + d) + e), 0.0, 1.0);
}

// The sRGB transfer function [sRGB] for linear l in [0, 1].
Number DisplaySrgbEncode(Number l) {
    return l <= 0.0031308 ? 12.92 * l : 1.055 * pow(l, 1.0 / 2.4) - 0.055;
}

// Scene colour (cd/m^2) to encoded display values in [0, 1]: night adaptation (when `night`),
// exposure, [N16], [sRGB]. Non-finite and negative channels give 0.
vec3 DisplayTransform(vec3 rgb, Number exposure_scale, bool night) {
    vec3 scene = night ? DisplayNightAdaptation(rgb) : rgb;
    vec3 encoded = vec3(0.0);
    for (int c = 0; c < 3; ++c) {
        Number x = exposure_scale * scene[c];
        // NaN and values <= 0 give 0 (x > 0.0 is false for NaN); above 1e18 (+inf included, and
        // before x * x overflows a float) the curve is 1.
        Number tone = x > 0.0 ? (x < 1e18 ? DisplayToneMapAces(x) : 1.0) : 0.0;
        encoded[c] = DisplaySrgbEncode(clamp(tone, 0.0, 1.0));
    }
    return encoded;
}
