// The night sky's photometry and models (zenith/sky/night_sky.h) against closed forms and the
// published numbers they come from.
#include "zenith/sky/night_sky.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <optional>

#include "luminance.h"
#include "zenith/base/error.h"
#include "zenith/geo/stars.h"

namespace zenith::sky {
namespace {

using zenith::test::Luminance;

constexpr double kArcsec2 = 2.3504430539097885e-11;  // sr

TEST(NightSkyPhotometry, SurfaceBrightnessZeroPointIsSchaefersConversion) {
    // Schaefer (1990) Eq. 1 in nanolamberts, 1 nL = 1e-5 / pi cd/m^2.
    for (double m : {18.0, 21.0, 22.0}) {
        const double schaefer = 34.08 * std::exp(20.7233 - 0.92104 * m) * 1e-5 / M_PI;
        EXPECT_NEAR(LuminanceFromSurfaceBrightness(m) / schaefer, 1.0, 1e-3) << m;
    }
    // The 10.8e4 cd/m^2 of the literature: a V = 0 star of 2.54e-6 lux per square arcsecond.
    EXPECT_NEAR(kSurfaceBrightnessZeroPoint / (2.54e-6 / kArcsec2), 1.0, 5e-3);
    EXPECT_NEAR(LuminanceFromSurfaceBrightness(22.0), 1.720e-4, 1e-6);
    // S10: one V = 10 star (same zero point) per square degree.
    const double square_degree = std::pow(M_PI / 180.0, 2);
    EXPECT_NEAR(LuminanceFromSurfaceBrightness(kS10Magnitude) / (2.54e-6 * 1e-4 / square_degree),
                1.0, 6e-3);  // the two zero points' 0.4 % and the 27.78's rounding
    EXPECT_NEAR(SurfaceBrightnessFromLuminance(LuminanceFromSurfaceBrightness(21.3)), 21.3, 1e-12);
    EXPECT_TRUE(std::isinf(SurfaceBrightnessFromLuminance(0.0)));
}

TEST(NightSkyAirglow, ShellChordIsVanRhijn) {
    const double R = 6360.0, low = R + 85.0, high = R + 95.0;
    const double layer = R + 90.0;
    // Straight up: the thickness itself.
    EXPECT_NEAR(ShellChord(R, 1.0, low, high, R) / 10.0, 1.0, 1e-12);
    for (double z_deg : {30.0, 60.0, 80.0, 90.0}) {
        const double z = z_deg * M_PI / 180.0;
        const double van_rhijn =
            1.0 / std::sqrt(1.0 - std::pow(R / layer, 2) * std::sin(z) * std::sin(z));
        const double chord = ShellChord(R, std::cos(z), low, high, R) / 10.0;
        std::printf("van Rhijn at z = %2.0f deg: chord %.4f, thin-layer law %.4f\n", z_deg, chord,
                    van_rhijn);
        EXPECT_NEAR(chord / van_rhijn, 1.0, z_deg < 85.0 ? 1e-3 : 5e-3);
    }
    // The horizon/zenith ratio of a 90 km layer seen from the ground: 6.0.
    EXPECT_NEAR(ShellChord(R, 0.0, low, high, R) / ShellChord(R, 1.0, low, high, R), 6.0, 0.05);
    // Looking down from below the layer: nothing (the ground is in the way).
    EXPECT_EQ(ShellChord(R + 1.0, -0.5, low, high, R), 0.0);
    // From above (400 km) straight down: the shell once, the ground stops the ray.
    EXPECT_NEAR(ShellChord(R + 400.0, -1.0, low, high, R), 10.0, 1e-9);
}

TEST(NightSkyZodiacal, LeinertTable17) {
    EXPECT_EQ(ZodiacalTable(90.0, 0.0), 259.0);
    EXPECT_EQ(ZodiacalTable(180.0, 0.0), 230.0);  // the gegenschein
    EXPECT_EQ(ZodiacalTable(-180.0, -0.0), 230.0);
    EXPECT_EQ(ZodiacalTable(123.0, 90.0), 77.0);  // the ecliptic pole
    EXPECT_NEAR(ZodiacalTable(97.5, 0.0), 0.5 * (259.0 + 212.0), 1e-9);
    EXPECT_NEAR(ZodiacalTable(270.0, 10.0), ZodiacalTable(90.0, 10.0), 1e-12);  // folded
    // Within 15 deg of the Sun the table is empty: the row's nearest entry.
    EXPECT_EQ(ZodiacalTable(0.0, 0.0), 3140.0);
    // The ecliptic pole, 1.81e-18 erg s^-1 cm^-2 A^-1 arcsec^-2 at 500 nm (the table's 77),
    // against V = 0 at 3.63e-9 erg s^-1 cm^-2 A^-1: 23.26 mag/arcsec^2.
    EXPECT_NEAR(ZodiacalSurfaceBrightness(77.0), -2.5 * std::log10(1.81e-18 / 3.63e-9), 0.01);
    EXPECT_NEAR(ZodiacalSurfaceBrightness(1.0), 27.97, 0.01);
}

TEST(NightSkyLightPollution, BortleMapping) {
    EXPECT_DOUBLE_EQ(BortleZenithBrightness(1), 21.88);
    EXPECT_DOUBLE_EQ(BortleZenithBrightness(4), 21.05);
    EXPECT_DOUBLE_EQ(BortleZenithBrightness(7), 18.25);
    for (int c = 1; c < 9; ++c) EXPECT_GT(BortleZenithBrightness(c), BortleZenithBrightness(c + 1));
    EXPECT_THROW(BortleZenithBrightness(0), ArgumentError);
    EXPECT_THROW(BortleZenithBrightness(10), ArgumentError);
    // Artificial part of class 4: 10^(-0.4 21.05) - 10^(-0.4 21.9) = 2.064e-9 -> 21.71.
    EXPECT_NEAR(ArtificialZenithBrightness(BortleZenithBrightness(4)), 21.713, 0.005);
    // A city sky is all artificial; a sky darker than the natural one has none.
    EXPECT_NEAR(ArtificialZenithBrightness(17.0), 17.0, 0.02);
    EXPECT_TRUE(std::isinf(ArtificialZenithBrightness(22.5)));
    NightSkySettings s;
    s.artificial_zenith_brightness = 5.0;
    EXPECT_THROW(s.Validate(), ArgumentError);
}

TEST(StarVisibilityThreshold, SchaefersLimitingMagnitudes) {
    // Magnitudes with the 2.54e-6 lux zero point of the surface-brightness conversion.
    const auto magnitude = [](double lux) { return -2.5 * std::log10(lux / 2.54e-6); };
    // A dark sky of 22 mag/arcsec^2 (54 nL): the naked eye's V = 6.6.
    const double dark = LuminanceFromSurfaceBrightness(22.0);
    EXPECT_NEAR(magnitude(StarThresholdIlluminance(dark)), 6.63, 0.02);
    // A 5000 cd/m^2 day sky: -4.0, Venus (-4.5) but not Sirius (-1.46).
    EXPECT_NEAR(magnitude(StarThresholdIlluminance(5000.0)), -3.98, 0.03);
    // No background: the absolute threshold, 10^-9.8 foot-candles.
    EXPECT_NEAR(StarThresholdIlluminance(0.0), std::pow(10.0, -9.8) * 10.7639, 1e-13);
    // The two branches meet near Schaefer's 1479 nL switch: continuous there.
    const double switch_cd = 1479.0 * 1e-5 / M_PI;
    EXPECT_NEAR(StarThresholdIlluminance(switch_cd * 0.999) / StarThresholdIlluminance(switch_cd),
                1.0, 0.01);
    // Across the threshold: none at or under it, all from one magnitude above, half between.
    const double t = StarThresholdIlluminance(dark);
    EXPECT_EQ(StarVisibility(0.99 * t, dark), 0.0);
    EXPECT_EQ(StarVisibility(t, dark), 0.0);
    EXPECT_NEAR(StarVisibility(t * std::pow(10.0, 0.2), dark), 0.5, 1e-9);
    EXPECT_EQ(StarVisibility(2.52 * t, dark), 1.0);
    // Venus at noon is seen (0.52 mag over the threshold: half of it), Sirius is not.
    EXPECT_NEAR(StarVisibility(2.54e-6 * std::pow(10.0, 0.4 * 4.5), 5000.0), 0.52, 0.03);
    EXPECT_EQ(StarVisibility(2.54e-6 * std::pow(10.0, 0.4 * 1.46), 5000.0), 0.0);
}

TEST(StarlightMap, ModelFollowsGalacticLatitude) {
    const StarlightMap map = StarlightMap::ModelOnly();
    const double s10 = LuminanceFromSurfaceBrightness(kS10Magnitude);
    // The north galactic pole (RA 192.859 deg, Dec 27.128 deg) and the galactic centre
    // (RA 266.405, Dec -28.936): 20 and 150 S10 (bilinear over 2 deg texels).
    const auto icrs = [](double ra_deg, double dec_deg) {
        const double ra = ra_deg * M_PI / 180.0, dec = dec_deg * M_PI / 180.0;
        return glm::dvec3(std::cos(dec) * std::cos(ra), std::cos(dec) * std::sin(ra),
                          std::sin(dec));
    };
    EXPECT_NEAR(Luminance(map.Sample(icrs(192.859, 27.128))) / s10, 20.0, 0.5);
    EXPECT_NEAR(Luminance(map.Sample(icrs(266.405, -28.936))) / s10, 150.0, 15.0);
}

TEST(StarlightMap, CatalogueStarsKeepTheirLight) {
    // The binned stars past the drawn limit integrate over the sphere to their illuminance.
    std::optional<geo::StarCatalog> catalog;
    try {
        catalog = geo::StarCatalog::Load(8.0);
    } catch (const geo::CatalogError& e) {
        GTEST_SKIP() << e.what();
    }
    const StarlightMap model = StarlightMap::ModelOnly();
    const StarlightMap map = StarlightMap::FromCatalog(*catalog, 6.5);
    double binned = 0.0, expected = 0.0;
    for (int j = 0; j < map.height; ++j) {
        const double lo = (-90.0 + j * 180.0 / map.height) * M_PI / 180.0;
        const double hi = (-90.0 + (j + 1) * 180.0 / map.height) * M_PI / 180.0;
        const double solid_angle = 2.0 * M_PI / map.width * (std::sin(hi) - std::sin(lo));
        for (int i = 0; i < map.width; ++i) {
            const std::size_t k = static_cast<std::size_t>(j * map.width + i);
            const glm::dvec3 d = map.texels[k] - model.texels[k];
            binned += (Luminance(d)) * solid_angle;
        }
    }
    std::size_t count = 0;
    for (const geo::Star& star : catalog->stars()) {
        if (star.magnitude_v > 6.5) {
            expected += geo::IlluminanceFromMagnitude(star.magnitude_v);
            ++count;
        }
    }
    std::printf("%zu catalogue stars of V 6.5-8: %.4g lux binned, %.4g lux in the catalogue\n",
                count, binned, expected);
    EXPECT_GT(count, 30000u);
    EXPECT_NEAR(binned / expected, 1.0, 1e-3);  // the colours' Y = 1 to their rounding
}

}  // namespace
}  // namespace zenith::sky
