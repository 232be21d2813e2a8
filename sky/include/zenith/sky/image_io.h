// Frame output: linear HDR OpenEXR (luminance in cd/m², unchanged) and tone-mapped 8-bit sRGB PNG.
//
// Images are linear RGB luminance in cd/m² per channel, Rec.709 primaries (the renderer's working
// space), alpha in [0, 1]. Exposure is photometric, as EV100 (exposure value at ISO 100).
//
// Every write is atomic: the whole file is encoded in memory, written to `<path>.partial` in the
// same directory, flushed to disk (fsync) and renamed over `path`. An interrupted run leaves at
// most a stale `.partial` (replaced by the next attempt), never a truncated `path`, and a failed
// write never touches an existing `path`. Two writers of the same path at once are not supported.
//
// References
//   [LR14] S. Lagarde, C. de Rousiers, "Moving Frostbite to Physically Based Rendering 3.0",
//          SIGGRAPH 2014 course notes, §5.1 "A Physically Based Camera" (exposure; EV100).
//   [N16]  K. Narkowicz, "ACES Filmic Tone Mapping Curve", blog post, 2016-01-06.
//   [sRGB] IEC 61966-2-1:1999, the sRGB transfer function.
#pragma once

#include <cstdint>
#include <filesystem>
#include <glm/glm.hpp>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "zenith/base/error.h"
#include "zenith/sky/lut.h"

namespace zenith::sky {

// An HDR frame: RGBA, x fastest, row 0 at the top. RGB in cd/m² (Rec.709), A in [0, 1].
// (LutImage in lut.h is for look-up tables, with z slices and no units.)
struct Image {
    int width = 0;
    int height = 0;
    std::vector<glm::vec4> pixels;

    Image() = default;
    Image(int w, int h, const glm::vec4& fill = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f))
        : width(w),
          height(h),
          pixels(static_cast<std::size_t>(w > 0 ? w : 0) * static_cast<std::size_t>(h > 0 ? h : 0),
                 fill) {}
    std::size_t Index(int x, int y) const {
        return static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
               static_cast<std::size_t>(x);
    }
    glm::vec4& at(int x, int y) { return pixels[Index(x, y)]; }
    const glm::vec4& at(int x, int y) const { return pixels[Index(x, y)]; }
};

// A frame read back from GL (row 0 at the bottom, RendererInspection::ReadFrame,
// SkySystem::RenderOffscreen) as an Image (row 0 at the top).
Image ImageFromFrame(const LutImage& frame);

// 8-bit sRGB-encoded RGB, 3 bytes per pixel, row 0 at the top: what a PNG holds.
struct Srgb8Image {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgb;
};

// Any failure to write or read an image file: the message names the path and the cause.
class ImageError : public Error {
  public:
    using Error::Error;
};

// --- Exposure and tone mapping ------------------------------------------------------------------

// Limits of a usable EV100: -20 is far below starlight (~-6), 30 far above the sun's disk (~+27).
inline constexpr double kMinExposureEV100 = -20.0;
inline constexpr double kMaxExposureEV100 = 30.0;

// The luminance that saturates a camera at ISO 100, [LR14] §5.1: L_max = 78 / (q·S) · 2^EV100
// with lens attenuation q = 0.65 and S = 100, i.e. L_max = 1.2 · 2^EV100 cd/m². Returns
// 1 / L_max (in m²/cd): scene luminance times this is the normalised sensor value, 1 = saturated.
double ExposureScale(double ev100);

// EV100 chosen from the frame as a reflected-light meter would, [LR14] §5.1:
// EV100 = log2(L_avg · S / K) with S = 100 and calibration constant K = 12.5, L_avg the
// log-average (geometric mean) of the pixels' Rec.709 luminance Y = 0.2126 R + 0.7152 G + 0.0722 B,
// taken over the pixels between the kMeteredLowPercentile-th and kMeteredHighPercentile-th
// percentiles of Y (histogram metering: space beside a planet, or the sun disk, does not set it).
// Non-finite pixels are skipped; Y below kMinMeteredLuminance counts as that. The result is clamped
// to [kMinExposureEV100, kMaxExposureEV100]. Throws zenith::ArgumentError for an empty image or one
// with no finite pixel.
inline constexpr double kMinMeteredLuminance =
    1e-6;  // cd/m², about the absolute threshold of vision
inline constexpr std::size_t kMeteredLowPercentile = 50;
inline constexpr std::size_t kMeteredHighPercentile = 95;
double AutoExposureEV100(const Image& image);

// The exposure a caller (CLI `--exposure`) asks for: metered from each frame, or a fixed EV100.
struct Exposure {
    bool automatic = true;
    double ev100 = 0.0;  // used when !automatic
};

// Parses "auto" or a number in [kMinExposureEV100, kMaxExposureEV100] (e.g. "12.5", "-3").
// Throws zenith::ArgumentError (field "exposure") naming the value and the allowed range.
Exposure ExposureFromString(std::string_view text);

// The EV100 to use for `image`: exposure.ev100, or AutoExposureEV100(image) when automatic.
double ResolveEV100(const Exposure& exposure, const Image& image);

// ACES filmic curve fitted by [N16]: (x (2.51 x + 0.03)) / (x (2.43 x + 0.59) + 0.14), clamped to
// [0, 1]. Input is the exposed linear value (ExposureScale · L); monotonic non-decreasing on
// [0, ∞) (the derivative's numerator, 1.4080 x² + 0.7028 x + 0.0042, is positive). It is the
// pre-exposed fit: 1 maps to ~0.8. NaN and values <= 0 give 0; +inf gives 1.
double ToneMapAcesFitted(double x);

// The sRGB transfer function [sRGB] (linear [0, 1] to encoded [0, 1]), input clamped to [0, 1].
double SrgbEncode(double linear);

// Per channel: SrgbEncode(ToneMapAcesFitted(ExposureScale(ev100) · L)), rounded to 8 bits, after
// the night (scotopic) adaptation of each colour when `night_adaptation`. Alpha is dropped. The
// formulas are one text with the GPU display pass (sky/shaders/common/display.glsl; zenith/sky/
// display.h). Throws ImageError for an inconsistent image, zenith::ArgumentError for an ev100
// outside [kMinExposureEV100, kMaxExposureEV100].
Srgb8Image ToneMapToSrgb8(const Image& image, double ev100, bool night_adaptation = false);

// --- Files --------------------------------------------------------------------------------------

// kHalf: 16-bit float, ~3 significant digits; finite values beyond ±65504 cd/m² (the half range;
// the sun's disk is ~1.6e9 cd/m²) are clamped to ±65504, not turned into infinities. kFloat:
// 32-bit, exact. Both are written ZIP-compressed (lossless).
enum class ExrPixelType { kHalf, kFloat };

// OpenEXR with channels R, G, B, A holding the pixels unchanged (cd/m²), with the standard
// attributes whiteLuminance = 1 (a value of 1.0 is 1 cd/m²) and chromaticities = Rec.709 / D65.
void WriteExr(const std::filesystem::path& path, const Image& image,
              ExrPixelType pixel_type = ExrPixelType::kFloat);

// 8-bit sRGB PNG of ToneMapToSrgb8(image, ev100), tagged sRGB (perceptual intent).
void WritePng(const std::filesystem::path& path, const Image& image, double ev100);

struct ImageWriteOptions {
    ExrPixelType exr_pixel_type = ExrPixelType::kFloat;
    Exposure exposure;  // for .png
};

// Dispatches on the extension (case-insensitive): ".exr" to WriteExr, ".png" to WritePng with
// ResolveEV100(options.exposure, image). Anything else is an ImageError naming the extension and
// the allowed ones.
void WriteImage(const std::filesystem::path& path, const Image& image,
                const ImageWriteOptions& options = {});

// Checks an OpenEXR file's header before OpenEXR reads it, since OpenEXR allocates what a header
// declares (an attribute of gigabytes in a 600-byte file, pixels for any data window). Throws
// ImageError naming the path for: no OpenEXR magic; a multi-part or deep file; an attribute
// that declares more bytes than the header holds; a header over 1 MiB; no dataWindow or one
// wider or taller than max_side.
void CheckExrHeader(const std::filesystem::path& path, int max_side);

// Reads an OpenEXR file's R, G, B, A channels as float (half is widened exactly; a missing
// channel reads as 0, missing A as 1) after CheckExrHeader. Throws ImageError naming the path
// and the cause.
Image ReadExr(const std::filesystem::path& path, int max_side = 16384);

// Reads an 8-bit RGB PNG (any PNG is converted to 8-bit RGB by libpng; alpha is dropped against
// black). Throws ImageError naming the path and the cause.
Srgb8Image ReadPng(const std::filesystem::path& path);

}  // namespace zenith::sky
