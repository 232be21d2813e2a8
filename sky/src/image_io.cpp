// Frame output: OpenEXR (linear cd/m²) and tone-mapped sRGB PNG, written atomically.
// Formulas and references are in image_io.h.
#include "zenith/sky/image_io.h"

#include <ImfChannelList.h>
#include <ImfChromaticities.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStandardAttributes.h>
#include <half.h>
#include <png.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <system_error>
#include <vector>

#include "reference/display_functions.h"
#include "zenith/base/atomic_file.h"
#include "zenith/base/error.h"

namespace zenith::sky {

// The public constants are the shared display text's (common/display.glsl).
static_assert(kMeteredLowPercentile == static_cast<std::size_t>(ref::kDisplayMeteredLowPercentile));
static_assert(kMeteredHighPercentile ==
              static_cast<std::size_t>(ref::kDisplayMeteredHighPercentile));

namespace {

// --- Helpers --------------------------------------------------------------------------------

// Appends instead of "'" + s + "'": g++ 12 reports a false -Wrestrict on the latter at -O3.
std::string Quoted(const std::filesystem::path& path) {
    std::string quoted = "'";
    quoted += path.string();
    quoted += '\'';
    return quoted;
}

[[noreturn]] void Fail(const std::filesystem::path& path, const std::string& cause) {
    throw ImageError("cannot write image " + Quoted(path) + ": " + cause);
}

[[noreturn]] void FailRead(const std::filesystem::path& path, const std::string& cause) {
    throw ImageError("cannot read image " + Quoted(path) + ": " + cause);
}

// Why `image` cannot be encoded (empty if it can): encoders must never read past the vector.
std::string ImageProblem(const Image& image) {
    const std::string size = std::to_string(image.width) + " x " + std::to_string(image.height);
    if (!(image.width > 0 && image.height > 0)) return "image size " + size + " (both must be > 0)";
    const auto expected =
        static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
    if (image.pixels.size() != expected) {
        return "image of " + size + " has " + std::to_string(image.pixels.size()) +
               " pixels, expected " + std::to_string(expected);
    }
    return {};
}

void ValidateImage(const std::filesystem::path& path, const Image& image) {
    if (const std::string problem = ImageProblem(image); !problem.empty()) Fail(path, problem);
}

void CheckEV100(double ev100) {
    if (!(ev100 >= kMinExposureEV100 && ev100 <= kMaxExposureEV100)) {
        std::ostringstream message;
        message << "exposure " << ev100 << " EV100 is outside [" << kMinExposureEV100 << ", "
                << kMaxExposureEV100 << "]";
        throw ArgumentError(message.str());
    }
}

// The bytes of an encoded image, written with zenith::WriteFileAtomically; its FileError
// becomes the ImageError this file promises, naming the same path and cause.
void WriteFileAtomically(const std::filesystem::path& path, const std::vector<char>& bytes) {
    try {
        zenith::WriteFileAtomically(path, std::string_view(bytes.data(), bytes.size()));
    } catch (const zenith::FileError& error) {
        throw ImageError(std::string("cannot write image: ") + error.what());
    }
}

// --- OpenEXR --------------------------------------------------------------------------------

// An OpenEXR output stream in memory: the file is complete (OutputFile's destructor writes the
// line-offset table and swallows its own errors) before a byte reaches the disk, so disk errors
// are all seen by WriteFileAtomically.
class MemoryOStream : public Imf::OStream {
  public:
    MemoryOStream() : Imf::OStream("<memory>") {}
    void write(const char c[], int n) override {
        const std::size_t end = position_ + static_cast<std::size_t>(n);
        if (end > bytes_.size()) bytes_.resize(end);
        std::memcpy(bytes_.data() + position_, c, static_cast<std::size_t>(n));
        position_ = end;
    }
    uint64_t tellp() override { return position_; }
    void seekp(uint64_t pos) override { position_ = static_cast<std::size_t>(pos); }
    const std::vector<char>& bytes() const { return bytes_; }

  private:
    std::vector<char> bytes_;
    std::size_t position_ = 0;
};

constexpr const char* kExrChannels[4] = {"R", "G", "B", "A"};

std::vector<char> EncodeExr(const Image& image, ExrPixelType pixel_type) {
    Imf::Header header(image.width, image.height);
    header.compression() = Imf::ZIP_COMPRESSION;
    // 1.0 in the file is 1 cd/m²; Imf::Chromaticities() is Rec.709 primaries with D65 white.
    Imf::addWhiteLuminance(header, 1.0f);
    Imf::addChromaticities(header, Imf::Chromaticities());
    const Imf::PixelType type = pixel_type == ExrPixelType::kHalf ? Imf::HALF : Imf::FLOAT;
    for (const char* name : kExrChannels) header.channels().insert(name, Imf::Channel(type));

    MemoryOStream stream;
    std::vector<Imath::half> halves;  // only for kHalf; must outlive the OutputFile
    Imf::FrameBuffer frame_buffer;
    if (pixel_type == ExrPixelType::kFloat) {
        const char* base = reinterpret_cast<const char*>(image.pixels.data());
        for (int c = 0; c < 4; ++c) {
            frame_buffer.insert(
                kExrChannels[c],
                Imf::Slice(Imf::FLOAT,
                           const_cast<char*>(base) + static_cast<std::size_t>(c) * sizeof(float),
                           sizeof(glm::vec4),
                           sizeof(glm::vec4) * static_cast<std::size_t>(image.width)));
        }
    } else {
        // Clamp to the largest finite half so a sun disk reads as very bright, not as +inf (which
        // would poison any later filtering of the file); NaN and inf pass through as themselves.
        constexpr float kHalfMax = 65504.0f;
        halves.resize(image.pixels.size() * 4);
        for (std::size_t i = 0; i < image.pixels.size(); ++i) {
            for (int c = 0; c < 4; ++c) {
                float value = image.pixels[i][c];
                if (std::isfinite(value)) value = std::clamp(value, -kHalfMax, kHalfMax);
                halves[i * 4 + static_cast<std::size_t>(c)] = Imath::half(value);
            }
        }
        char* base = reinterpret_cast<char*>(halves.data());
        for (int c = 0; c < 4; ++c) {
            frame_buffer.insert(
                kExrChannels[c],
                Imf::Slice(Imf::HALF, base + static_cast<std::size_t>(c) * sizeof(Imath::half),
                           4 * sizeof(Imath::half),
                           4 * sizeof(Imath::half) * static_cast<std::size_t>(image.width)));
        }
    }
    {
        Imf::OutputFile file(stream, header);
        file.setFrameBuffer(frame_buffer);
        file.writePixels(image.height);
    }
    return stream.bytes();
}

// --- PNG ------------------------------------------------------------------------------------

std::vector<char> EncodePng(const Srgb8Image& srgb) {
    // libpng's simplified API: errors come back as a return value and image.message instead of a
    // longjmp through C++ frames.
    png_image png{};
    png.version = PNG_IMAGE_VERSION;
    png.width = static_cast<png_uint_32>(srgb.width);
    png.height = static_cast<png_uint_32>(srgb.height);
    png.format = PNG_FORMAT_RGB;  // 8-bit sRGB; libpng adds the sRGB chunk (perceptual intent)
    const auto stride = static_cast<png_int_32>(3 * srgb.width);
    png_alloc_size_t size = 0;
    if (!png_image_write_get_memory_size(png, size, 0, srgb.rgb.data(), stride, nullptr)) {
        const std::string message = png.message;
        png_image_free(&png);
        throw Error("PNG encoding failed: " + message);
    }
    std::vector<char> bytes(size);
    if (!png_image_write_to_memory(&png, bytes.data(), &size, 0, srgb.rgb.data(), stride,
                                   nullptr)) {
        const std::string message = png.message;
        png_image_free(&png);
        throw Error("PNG encoding failed: " + message);
    }
    bytes.resize(size);
    return bytes;
}

}  // namespace

// --- Exposure and tone mapping ----------------------------------------------------------------

double ExposureScale(double ev100) {
    // [LR14] §5.1: L_max = 78 / (q · S) · 2^EV100, q = 0.65, S = 100 → 78 / 65 = 1.2; the formula
    // is common/display.glsl's, which the GPU display pass runs.
    return ref::DisplayExposureScale(ev100);
}

double AutoExposureEV100(const Image& image) {
    if (image.pixels.empty()) throw ArgumentError("AutoExposureEV100: empty image");
    std::vector<double> log_luminance;
    log_luminance.reserve(image.pixels.size());
    for (const glm::vec4& p : image.pixels) {
        // Rec.709 / sRGB luminance weights (ITU-R BT.709-6, item 3.2).
        const double y = ref::DisplayLuminance(glm::dvec3(p.r, p.g, p.b));
        if (!std::isfinite(y)) continue;
        log_luminance.push_back(std::log2(std::max(y, kMinMeteredLuminance)));
    }
    if (log_luminance.empty()) {
        throw ArgumentError("AutoExposureEV100: no pixel of the " + std::to_string(image.width) +
                            " x " + std::to_string(image.height) + " image is finite");
    }
    // Metered like an engine's histogram: only the pixels between the 50th and 95th percentiles,
    // so black space filling half of an orbital view, or a sun disk, does not decide it.
    std::sort(log_luminance.begin(), log_luminance.end());
    const std::size_t n = log_luminance.size();
    const std::size_t first = n * kMeteredLowPercentile / 100;
    const std::size_t last = std::max(first + 1, n * kMeteredHighPercentile / 100);
    double sum_log = 0.0;
    for (std::size_t i = first; i < last; ++i) sum_log += log_luminance[i];
    const std::size_t count = last - first;
    // [LR14] §5.1: EV100 = log2(L_avg · S / K), S = 100, K = 12.5; log2 of the geometric mean is
    // the mean of log2. The display pass's meter (display/meter.comp) uses the same function.
    const double ev100 = ref::DisplayMeteredEV100(sum_log / static_cast<double>(count));
    return std::clamp(ev100, kMinExposureEV100, kMaxExposureEV100);
}

Exposure ExposureFromString(std::string_view text) {
    if (text == "auto") return Exposure{};
    std::ostringstream range;
    range << "[" << kMinExposureEV100 << ", " << kMaxExposureEV100 << "]";
    double value = 0.0;
    const char* end = text.data() + text.size();
    const auto [ptr, error] = std::from_chars(text.data(), end, value);
    if (text.empty() || error != std::errc() || ptr != end) {
        throw ArgumentError("exposure", "exposure = '" + std::string(text) +
                                            "' is neither 'auto' nor a number (EV100 in " +
                                            range.str() + ")");
    }
    if (!(value >= kMinExposureEV100 && value <= kMaxExposureEV100)) {
        throw ArgumentError("exposure",
                            "exposure = " + std::string(text) + " EV100 is outside " + range.str());
    }
    return Exposure{false, value};
}

double ResolveEV100(const Exposure& exposure, const Image& image) {
    return exposure.automatic ? AutoExposureEV100(image) : exposure.ev100;
}

double ToneMapAcesFitted(double x) {
    if (!(x > 0.0)) return 0.0;  // also NaN
    if (std::isinf(x)) return 1.0;
    // [N16], coefficients a..e as published (common/display.glsl).
    return ref::DisplayToneMapAces(x);
}

double SrgbEncode(double linear) {
    if (!(linear > 0.0)) return 0.0;
    if (linear >= 1.0) return 1.0;
    // IEC 61966-2-1: linear segment below 0.0031308, then 1.055 · L^(1/2.4) - 0.055.
    return ref::DisplaySrgbEncode(linear);
}

Srgb8Image ToneMapToSrgb8(const Image& image, double ev100, bool night_adaptation) {
    if (const std::string problem = ImageProblem(image); !problem.empty()) {
        throw ImageError("ToneMapToSrgb8: " + problem);
    }
    CheckEV100(ev100);
    const double scale = ExposureScale(ev100);
    Srgb8Image out;
    out.width = image.width;
    out.height = image.height;
    out.rgb.resize(image.pixels.size() * 3);
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        const glm::vec4& p = image.pixels[i];
        // The display pass's transform (common/display.glsl), in double precision.
        const glm::dvec3 encoded =
            ref::DisplayTransform(glm::dvec3(p.r, p.g, p.b), scale, night_adaptation);
        for (int c = 0; c < 3; ++c) {
            out.rgb[i * 3 + static_cast<std::size_t>(c)] =
                static_cast<std::uint8_t>(std::lround(encoded[c] * 255.0));
        }
    }
    return out;
}

// --- Files ------------------------------------------------------------------------------------

void WriteExr(const std::filesystem::path& path, const Image& image, ExrPixelType pixel_type) {
    ValidateImage(path, image);
    std::vector<char> bytes;
    try {
        bytes = EncodeExr(image, pixel_type);
    } catch (const std::exception& e) {
        Fail(path, std::string("OpenEXR encoding failed: ") + e.what());
    }
    WriteFileAtomically(path, bytes);
}

void WritePng(const std::filesystem::path& path, const Image& image, double ev100) {
    ValidateImage(path, image);
    std::vector<char> bytes;
    try {
        bytes = EncodePng(ToneMapToSrgb8(image, ev100));
    } catch (const std::exception& e) {
        Fail(path, e.what());
    }
    WriteFileAtomically(path, bytes);
}

void WriteImage(const std::filesystem::path& path, const Image& image,
                const ImageWriteOptions& options) {
    std::string extension = path.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
    if (extension == ".exr") {
        WriteExr(path, image, options.exr_pixel_type);
    } else if (extension == ".png") {
        ValidateImage(path, image);  // before metering, so the message is about the image
        double ev100 = 0.0;
        try {
            ev100 = ResolveEV100(options.exposure, image);
        } catch (const std::exception& e) {
            Fail(path, e.what());
        }
        WritePng(path, image, ev100);
    } else {
        Fail(path, (extension.empty() ? std::string("no extension")
                                      : "unknown extension '" + path.extension().string() + "'") +
                       " (allowed: .exr, .png)");
    }
}

void CheckExrHeader(const std::filesystem::path& path, int max_side) {
    // The header is a magic number, a version word and attributes (name\0 type\0 int32 size,
    // value) up to an empty name (OpenEXR file layout, "Header"). Only the header is read:
    // attributes are small, so 1 MiB is far more than any real header.
    constexpr std::size_t kMaxHeaderBytes = 1u << 20;
    std::ifstream in(path, std::ios::binary);
    if (!in) FailRead(path, "cannot open");
    std::vector<unsigned char> bytes(kMaxHeaderBytes);
    in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    bytes.resize(static_cast<std::size_t>(in.gcount()));
    const auto u32 = [&](std::size_t at) {
        return static_cast<std::uint32_t>(bytes[at]) |
               static_cast<std::uint32_t>(bytes[at + 1]) << 8 |
               static_cast<std::uint32_t>(bytes[at + 2]) << 16 |
               static_cast<std::uint32_t>(bytes[at + 3]) << 24;
    };
    if (bytes.size() < 8 || u32(0) != 20000630u) FailRead(path, "not an OpenEXR file");
    const std::uint32_t flags = u32(4);
    if ((flags & 0xffu) != 2u || (flags & 0x1800u) != 0u) {
        FailRead(path, "only single-part, non-deep OpenEXR version 2 files are read");
    }
    std::size_t at = 8;
    const auto read_string = [&](const char* what) {
        const auto end = std::find(bytes.begin() + static_cast<std::ptrdiff_t>(at), bytes.end(), 0);
        if (end == bytes.end()) FailRead(path, std::string("header ends inside an ") + what);
        std::string text(bytes.begin() + static_cast<std::ptrdiff_t>(at), end);
        at = static_cast<std::size_t>(end - bytes.begin()) + 1;
        return text;
    };
    bool has_window = false;
    for (;;) {
        const std::string name = read_string("attribute name");
        if (name.empty()) break;
        const std::string type = read_string("attribute type");
        if (at + 4 > bytes.size()) FailRead(path, "header ends inside attribute " + name);
        const std::uint32_t size = u32(at);
        at += 4;
        // OpenEXR allocates what the size declares before reading it: a 600-byte file could ask
        // for gigabytes.
        if (size > bytes.size() - at) {
            FailRead(path, "attribute " + name + " declares " + std::to_string(size) +
                               " bytes, more than the header holds");
        }
        if (name == "dataWindow") {
            if (type != "box2i" || size != 16) FailRead(path, "dataWindow is not a box2i");
            const auto coordinate = [&](std::size_t k) {
                return static_cast<std::int64_t>(static_cast<std::int32_t>(u32(at + 4 * k)));
            };
            const std::int64_t width = coordinate(2) - coordinate(0) + 1;
            const std::int64_t height = coordinate(3) - coordinate(1) + 1;
            if (width < 1 || height < 1 || width > max_side || height > max_side) {
                FailRead(path, "data window " + std::to_string(width) + "x" +
                                   std::to_string(height) + " (expected 1 to " +
                                   std::to_string(max_side) + " pixels a side)");
            }
            has_window = true;
        }
        at += size;
    }
    if (!has_window) FailRead(path, "header has no dataWindow");
}

Image ImageFromFrame(const LutImage& frame) {
    Image image(frame.size.x, frame.size.y);
    for (int y = 0; y < image.height; ++y) {  // GL rows run bottom-up; images top-down
        for (int x = 0; x < image.width; ++x) image.at(x, y) = frame.at(x, image.height - 1 - y);
    }
    return image;
}

Image ReadExr(const std::filesystem::path& path, int max_side) {
    CheckExrHeader(path, max_side);
    try {
        Imf::InputFile file(path.c_str());
        const Imath::Box2i window = file.header().dataWindow();
        const int64_t width = int64_t{window.max.x} - window.min.x + 1;
        const int64_t height = int64_t{window.max.y} - window.min.y + 1;
        if (!(width > 0 && height > 0 && width <= std::numeric_limits<int>::max() &&
              height <= std::numeric_limits<int>::max())) {
            FailRead(path, "bad data window");
        }
        Image image(static_cast<int>(width), static_cast<int>(height));
        Imf::FrameBuffer frame_buffer;
        char* base = reinterpret_cast<char*>(image.pixels.data());
        for (int c = 0; c < 4; ++c) {
            frame_buffer.insert(
                kExrChannels[c],
                Imf::Slice::Make(Imf::FLOAT, base + static_cast<std::size_t>(c) * sizeof(float),
                                 window, sizeof(glm::vec4),
                                 sizeof(glm::vec4) * static_cast<std::size_t>(width), 1, 1,
                                 c == 3 ? 1.0 : 0.0));
        }
        file.setFrameBuffer(frame_buffer);
        file.readPixels(window.min.y, window.max.y);
        return image;
    } catch (const ImageError&) {
        throw;
    } catch (const std::exception& e) {
        FailRead(path, e.what());
    }
}

Srgb8Image ReadPng(const std::filesystem::path& path) {
    png_image png{};
    png.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&png, path.c_str())) {
        const std::string message = png.message;
        png_image_free(&png);
        FailRead(path, message);
    }
    png.format = PNG_FORMAT_RGB;
    Srgb8Image out;
    out.width = static_cast<int>(png.width);
    out.height = static_cast<int>(png.height);
    out.rgb.assign(PNG_IMAGE_SIZE(png), 0);
    const png_color black{0, 0, 0};
    if (!png_image_finish_read(&png, &black, out.rgb.data(), 0, nullptr)) {
        const std::string message = png.message;
        png_image_free(&png);
        FailRead(path, message);
    }
    return out;
}

}  // namespace zenith::sky
