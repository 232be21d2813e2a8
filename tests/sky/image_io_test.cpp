// Image output: EXR round trips, the exposure → tone curve → sRGB chain, auto exposure, atomic
// writes and their error messages.
#include "zenith/sky/image_io.h"

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cmath>
#include <csignal>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "zenith/base/error.h"

namespace zenith::sky {
namespace {

namespace fs = std::filesystem;

// A fresh directory per test under the build tree's temp dir, removed afterwards.
class ImageIoTest : public ::testing::Test {
  protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() /
               ("zenith_image_io_" + std::to_string(::getpid()) + "_" + info->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override {
        std::error_code ignored;
        fs::remove_all(dir_, ignored);
    }
    fs::path dir_;
};

std::string ReadBytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Luminances across the range a sky frame holds: starlight to sunlit cloud, plus the sun's disk.
Image TestImage() {
    const float values[] = {0.0f, 1e-4f, 3.3e-3f, 0.18f, 1.0f, 42.5f, 8000.0f, 1e5f, 1.6e9f};
    Image image(7, 5);
    int i = 0;
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x, ++i) {
            image.at(x, y) = glm::vec4(values[i % 9], values[(i + 3) % 9], values[(i + 5) % 9],
                                       static_cast<float>(i) / 35.0f);
        }
    }
    return image;
}

// Expected per-channel 8-bit value, from the formulas in image_io.h written out independently.
int ExpectedSrgb8(double luminance, double ev100) {
    const double x = luminance / (1.2 * std::pow(2.0, ev100));
    double t = (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14);
    t = std::min(std::max(t, 0.0), 1.0);
    const double e = t <= 0.0031308 ? 12.92 * t : 1.055 * std::pow(t, 1.0 / 2.4) - 0.055;
    return static_cast<int>(std::lround(e * 255.0));
}

// --- EXR ----------------------------------------------------------------------------------------

TEST_F(ImageIoTest, ExrFloatRoundTripIsExact) {
    const Image image = TestImage();
    const fs::path path = dir_ / "frame.exr";
    WriteExr(path, image, ExrPixelType::kFloat);
    const Image back = ReadExr(path);
    ASSERT_EQ(back.width, image.width);
    ASSERT_EQ(back.height, image.height);
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        for (int c = 0; c < 4; ++c) {
            ASSERT_EQ(back.pixels[i][c], image.pixels[i][c]) << "pixel " << i << " channel " << c;
        }
    }
    EXPECT_FALSE(fs::exists(dir_ / "frame.exr.partial"));
}

TEST_F(ImageIoTest, ExrHalfRoundTripWithinHalfPrecision) {
    const Image image = TestImage();
    const fs::path path = dir_ / "frame.exr";
    WriteExr(path, image, ExrPixelType::kHalf);
    const Image back = ReadExr(path);
    ASSERT_EQ(back.width, image.width);
    ASSERT_EQ(back.height, image.height);
    // Half has an 11-bit significand: round to nearest is within 2^-11 relative for normal
    // values (>= 6.1e-5, so 1e-4 cd/m² is still normal). Finite values above the largest half,
    // 65504 (1e5 cd/m² and the sun's 1.6e9 here), are documented to clamp to it.
    constexpr double kHalfRelative = 1.0 / 2048.0;
    constexpr float kHalfMax = 65504.0f;
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        for (int c = 0; c < 4; ++c) {
            const float in = image.pixels[i][c];
            const float out = back.pixels[i][c];
            if (in > kHalfMax) {
                EXPECT_EQ(out, kHalfMax) << "pixel " << i << " channel " << c << " in " << in;
            } else {
                EXPECT_LE(std::abs(out - in), kHalfRelative * in)
                    << "pixel " << i << " channel " << c << " in " << in << " out " << out;
            }
        }
    }
}

TEST_F(ImageIoTest, ExrCarriesWhiteLuminanceAndRec709) {
    // The header attributes are what tells a reader 1.0 = 1 cd/m² in Rec.709; check they are in
    // the file by name (the attribute names are part of the OpenEXR file format).
    const fs::path path = dir_ / "frame.exr";
    WriteExr(path, TestImage());
    const std::string bytes = ReadBytes(path);
    EXPECT_NE(bytes.find(std::string("whiteLuminance\0float\0", 21)), std::string::npos);
    EXPECT_NE(bytes.find(std::string("chromaticities\0chromaticities\0", 30)), std::string::npos);
}

TEST_F(ImageIoTest, ReadExrOfMissingFileNamesPath) {
    const fs::path path = dir_ / "missing.exr";
    try {
        ReadExr(path);
        FAIL() << "no exception";
    } catch (const ImageError& e) {
        EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
    }
}

// --- Exposure and tone curve --------------------------------------------------------------------

TEST(ImageIoExposure, ExposureScaleIsLagardeSaturation) {
    // L_max = 1.2 · 2^EV100 cd/m² saturates the sensor: at EV100 = 0, 1.2 cd/m²; each EV halves.
    EXPECT_DOUBLE_EQ(ExposureScale(0.0), 1.0 / 1.2);
    EXPECT_DOUBLE_EQ(ExposureScale(15.0), 1.0 / (1.2 * 32768.0));
    EXPECT_DOUBLE_EQ(ExposureScale(3.0) / ExposureScale(4.0), 2.0);
}

TEST(ImageIoExposure, AutoExposureOfUniformImage) {
    for (const double luminance : {1e-4, 0.18, 1.0, 12.5, 5000.0, 3e4}) {
        const Image image(4, 3, glm::vec4(glm::vec3(static_cast<float>(luminance)), 1.0f));
        // The float image holds float(luminance), so the expectation uses the same value.
        const double l = static_cast<float>(luminance);
        EXPECT_NEAR(AutoExposureEV100(image), std::log2(l * 100.0 / 12.5), 1e-9) << luminance;
    }
}

TEST(ImageIoExposure, AutoExposureMetersTheMiddleOfTheHistogram) {
    // A uniform image of L meters as log2(L * 100 / 12.5) ([LR14] §5.1).
    EXPECT_NEAR(AutoExposureEV100(Image(4, 4, glm::vec4(10.0f, 10.0f, 10.0f, 1.0f))),
                std::log2(10.0 * 8.0), 1e-9);
    // An orbital view: half the frame black space, half a planet at 1000 cd/m^2. The 50th-95th
    // percentile band is the planet, so the planet is exposed for, not the average with space.
    Image orbit(10, 10, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    for (int y = 5; y < 10; ++y) {
        for (int x = 0; x < 10; ++x) orbit.at(x, y) = glm::vec4(1000.0f, 1000.0f, 1000.0f, 1.0f);
    }
    EXPECT_NEAR(AutoExposureEV100(orbit), std::log2(1000.0 * 8.0), 1e-9);
    // A sun disk (1 % of the pixels at 1.6e9 cd/m^2) on a 5000 cd/m^2 sky does not move it.
    Image sky(10, 10, glm::vec4(5000.0f, 5000.0f, 5000.0f, 1.0f));
    sky.at(3, 3) = glm::vec4(1.6e9f, 1.6e9f, 1.6e9f, 1.0f);
    EXPECT_NEAR(AutoExposureEV100(sky), std::log2(5000.0 * 8.0), 1e-9);
    // NaN and inf pixels are not metered; black is clamped, not -inf.
    Image with_bad(4, 4, glm::vec4(10.0f, 10.0f, 10.0f, 1.0f));
    with_bad.pixels.push_back(glm::vec4(std::numeric_limits<float>::quiet_NaN()));
    with_bad.pixels.push_back(glm::vec4(std::numeric_limits<float>::infinity()));
    EXPECT_NEAR(AutoExposureEV100(with_bad), std::log2(10.0 * 8.0), 1e-9);
    const Image black(3, 3, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    EXPECT_NEAR(AutoExposureEV100(black), std::log2(kMinMeteredLuminance * 8.0), 1e-9);
    // Luminance is Rec.709 Y: pure green of 1/0.7152 cd/m² meters as 1 cd/m².
    const Image green(2, 2, glm::vec4(0.0f, 1.0f / 0.7152f, 0.0f, 1.0f));
    EXPECT_NEAR(AutoExposureEV100(green), 3.0, 1e-6);
    EXPECT_THROW(AutoExposureEV100(Image{}), zenith::ArgumentError);
}

TEST(ImageIoExposure, ToneCurveIsMonotonicAndInUnitRange) {
    double previous = ToneMapAcesFitted(0.0);
    EXPECT_EQ(previous, 0.0);
    for (double x = 1e-6; x < 1e4; x *= 1.01) {
        const double t = ToneMapAcesFitted(x);
        ASSERT_GE(t, previous) << x;
        ASSERT_GE(t, 0.0) << x;
        ASSERT_LE(t, 1.0) << x;
        previous = t;
    }
    EXPECT_EQ(ToneMapAcesFitted(std::numeric_limits<double>::infinity()), 1.0);
    EXPECT_EQ(ToneMapAcesFitted(std::numeric_limits<double>::quiet_NaN()), 0.0);
    EXPECT_EQ(ToneMapAcesFitted(-5.0), 0.0);
    // [N16]: pre-exposed so that 1 maps to about 0.8.
    EXPECT_NEAR(ToneMapAcesFitted(1.0), 0.8, 0.01);
}

TEST(ImageIoExposure, SrgbEncodeMatchesStandard) {
    EXPECT_EQ(SrgbEncode(0.0), 0.0);
    EXPECT_EQ(SrgbEncode(1.0), 1.0);
    EXPECT_DOUBLE_EQ(SrgbEncode(0.002), 12.92 * 0.002);
    // IEC 61966-2-1: linear 0.214 encodes to ~0.5 (the well-known "50 % grey is 21 % light").
    EXPECT_NEAR(SrgbEncode(0.21404), 0.5, 1e-4);
    // Continuity at the knee.
    EXPECT_NEAR(12.92 * 0.0031308, 1.055 * std::pow(0.0031308, 1.0 / 2.4) - 0.055, 1e-6);
}

TEST(ImageIoExposure, ExposureFromString) {
    EXPECT_TRUE(ExposureFromString("auto").automatic);
    const Exposure e = ExposureFromString("12.5");
    EXPECT_FALSE(e.automatic);
    EXPECT_EQ(e.ev100, 12.5);
    EXPECT_EQ(ExposureFromString("-20").ev100, -20.0);
    EXPECT_EQ(ExposureFromString("30").ev100, 30.0);
    for (const char* bad : {"", "abc", "12.5x", " 3", "nan", "inf", "30.01", "-21", "1e9"}) {
        try {
            ExposureFromString(bad);
            ADD_FAILURE() << "accepted '" << bad << "'";
        } catch (const zenith::ArgumentError& error) {
            const std::string message = error.what();
            EXPECT_EQ(error.field(), "exposure");  // the CLI maps it to --exposure
            EXPECT_EQ(message.find("--exposure"), std::string::npos) << message;
            EXPECT_NE(message.find(bad), std::string::npos) << message;
            EXPECT_NE(message.find("[-20, 30]"), std::string::npos) << message;
        }
    }
}

// --- PNG ----------------------------------------------------------------------------------------

TEST_F(ImageIoTest, PngDecodesAndMidGreyLandsMidScale) {
    // A uniform grey scene metered by AutoExposureEV100 is exposed so that L · scale =
    // L / (1.2 · 2^log2(8 L)) = 1 / 9.6 = 0.104 for any L (the meter puts the average at 12.5/120
    // of saturation). The ACES fit maps 0.104 to 0.133 and sRGB encodes that to 0.400, i.e.
    // 8-bit 102: a mid-grey, a bit darker than sRGB 0.5 because the filmic toe darkens shadows.
    constexpr int kExpected = 102;
    for (const float luminance : {0.01f, 1.0f, 4000.0f}) {
        const Image image(16, 9, glm::vec4(luminance, luminance, luminance, 1.0f));
        const double ev100 = AutoExposureEV100(image);
        EXPECT_EQ(ExpectedSrgb8(luminance, ev100), kExpected);
        const fs::path path = dir_ / "grey.png";
        ImageWriteOptions options;
        options.exposure = ExposureFromString("auto");
        WriteImage(path, image, options);
        const Srgb8Image png = ReadPng(path);
        ASSERT_EQ(png.width, 16);
        ASSERT_EQ(png.height, 9);
        ASSERT_EQ(png.rgb.size(), 16u * 9u * 3u);
        for (std::size_t i = 0; i < png.rgb.size(); ++i) {
            ASSERT_EQ(png.rgb[i], kExpected) << "byte " << i << " at " << luminance << " cd/m²";
        }
        EXPECT_FALSE(fs::exists(dir_ / "grey.png.partial"));
    }
}

TEST_F(ImageIoTest, PngRowZeroIsTop) {
    Image image(3, 2, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    image.at(0, 0) = glm::vec4(1e6f, 0.0f, 0.0f, 1.0f);  // top left: saturated red
    const fs::path path = dir_ / "marker.png";
    WritePng(path, image, 10.0);
    const Srgb8Image png = ReadPng(path);
    ASSERT_EQ(png.rgb.size(), 18u);
    EXPECT_EQ(png.rgb[0], 255);
    for (std::size_t i = 1; i < png.rgb.size(); ++i) EXPECT_EQ(png.rgb[i], 0) << i;
    // Tagged as sRGB so viewers do not guess: the sRGB chunk's type code is in the file.
    EXPECT_NE(ReadBytes(path).find("sRGB"), std::string::npos);
}

TEST_F(ImageIoTest, PngMatchesFormulaAcrossExposures) {
    const Image image = TestImage();
    for (const double ev100 : {-6.0, 0.0, 9.5, 15.0}) {
        const fs::path path = dir_ / "frame.png";
        WritePng(path, image, ev100);
        const Srgb8Image png = ReadPng(path);
        ASSERT_EQ(png.width, image.width);
        ASSERT_EQ(png.height, image.height);
        for (std::size_t i = 0; i < image.pixels.size(); ++i) {
            for (int c = 0; c < 3; ++c) {
                ASSERT_NEAR(png.rgb[i * 3 + static_cast<std::size_t>(c)],
                            ExpectedSrgb8(image.pixels[i][c], ev100), 1)
                    << "pixel " << i << " channel " << c << " EV100 " << ev100;
            }
        }
    }
    EXPECT_THROW(WritePng(dir_ / "bad.png", image, 31.0), ImageError);
}

// --- Errors and atomicity -----------------------------------------------------------------------

void ExpectImageError(const std::function<void()>& write, const std::vector<std::string>& parts) {
    try {
        write();
        ADD_FAILURE() << "no exception";
    } catch (const ImageError& error) {
        for (const std::string& part : parts) {
            EXPECT_NE(std::string(error.what()).find(part), std::string::npos)
                << "'" << part << "' not in: " << error.what();
        }
    }
}

TEST_F(ImageIoTest, UnwritableDirectoryNamesPathAndLeavesNoPartial) {
    // Tests may run as root, which ignores permission bits: use a directory that does not exist
    // and a "directory" that is a regular file instead.
    const Image image = TestImage();
    const fs::path missing = dir_ / "no_such_dir" / "frame.exr";
    ExpectImageError([&] { WriteExr(missing, image); },
                     {missing.string(), "No such file or directory"});
    EXPECT_FALSE(fs::exists(missing.string() + ".partial"));

    std::ofstream(dir_ / "file") << "x";
    const fs::path under_file = dir_ / "file" / "frame.png";
    ExpectImageError([&] { WritePng(under_file, image, 10.0); },
                     {under_file.string(), "Not a directory"});
}

TEST_F(ImageIoTest, FailedRenameRemovesPartial) {
    // A non-empty directory where the file should go: the partial is written, the rename fails.
    const fs::path path = dir_ / "frame.exr";
    fs::create_directories(path / "occupied");
    ExpectImageError([&] { WriteExr(path, TestImage()); }, {path.string(), "renaming"});
    EXPECT_FALSE(fs::exists(path.string() + ".partial"));
    EXPECT_TRUE(fs::is_directory(path / "occupied"));
}

TEST_F(ImageIoTest, DiskFullKeepsPreviousFileAndRemovesPartial) {
    const fs::path path = dir_ / "frame.exr";
    WriteExr(path, Image(2, 2, glm::vec4(1.0f)));
    const std::string good = ReadBytes(path);

    // Simulate a full disk with a file-size limit: write() then fails with EFBIG (SIGXFSZ is
    // ignored so that it does not kill the process). The limit is restored right after.
    Image big(256, 256);
    for (std::size_t i = 0; i < big.pixels.size(); ++i) {
        big.pixels[i] = glm::vec4(static_cast<float>(i) * 1.37f, 0.5f, 3.0f, 1.0f);
    }
    rlimit old_limit{};
    ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &old_limit), 0);
    rlimit small = old_limit;
    small.rlim_cur = 4096;
    const auto old_handler = std::signal(SIGXFSZ, SIG_IGN);
    ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
    std::string message;
    try {
        WriteExr(path, big);
    } catch (const ImageError& error) {
        message = error.what();
    }
    ::setrlimit(RLIMIT_FSIZE, &old_limit);
    std::signal(SIGXFSZ, old_handler);

    EXPECT_NE(message.find(path.string()), std::string::npos) << message;
    EXPECT_NE(message.find("File too large"), std::string::npos) << message;
    EXPECT_FALSE(fs::exists(path.string() + ".partial"));
    EXPECT_EQ(ReadBytes(path), good);
}

TEST_F(ImageIoTest, InvalidImageDoesNotClobberExistingFile) {
    const fs::path path = dir_ / "frame.png";
    WritePng(path, TestImage(), 10.0);
    const std::string good = ReadBytes(path);
    Image broken(4, 4);
    broken.pixels.pop_back();
    ExpectImageError([&] { WritePng(path, broken, 10.0); }, {path.string(), "15 pixels"});
    ExpectImageError([&] { WriteImage(path, Image{}); }, {path.string(), "0 x 0"});
    EXPECT_EQ(ReadBytes(path), good);
    EXPECT_FALSE(fs::exists(path.string() + ".partial"));
}

TEST_F(ImageIoTest, WriteImageDispatchesOnExtension) {
    const Image image = TestImage();
    WriteImage(dir_ / "a.EXR", image);
    EXPECT_EQ(ReadExr(dir_ / "a.EXR").pixels[10], image.pixels[10]);  // float by default
    WriteImage(dir_ / "a.png", image);
    EXPECT_EQ(ReadPng(dir_ / "a.png").width, image.width);

    const fs::path jpg = dir_ / "frame.jpg";
    ExpectImageError([&] { WriteImage(jpg, image); }, {jpg.string(), "'.jpg'", ".exr", ".png"});
    ExpectImageError([&] { WriteImage(dir_ / "frame", image); }, {"no extension", ".exr"});
    EXPECT_FALSE(fs::exists(jpg));
    EXPECT_FALSE(fs::exists(jpg.string() + ".partial"));
}

}  // namespace
}  // namespace zenith::sky
