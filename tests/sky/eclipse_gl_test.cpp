// Solar and lunar eclipses as the renderer draws them, from the ephemeris: the partial eclipse's
// crescent carries the eclipsed sunlight, the sky dims with the Sun's uncovered light, totality
// is dark at the zenith with a bright horizon, and the eclipsed Moon is lit by the penumbra's
// sunlight and the umbra's refracted light.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/gtc/constants.hpp>
#include <optional>
#include <string>
#include <tuple>

#include "draw_frame.h"
#include "gl_test_support.h"
#include "luminance.h"
#include "zenith/geo/eclipse.h"
#include "zenith/geo/ephemeris.h"
#include "zenith/geo/moon.h"
#include "zenith/sky/atmosphere_renderer.h"
#include "zenith/sky/clouds/weather.h"
#include "zenith/sky/inspection.h"
#include "zenith/sky/lighting.h"
#include "zenith/sky/reference/atmosphere_reference.h"
#include "zenith/sky/sky_state.h"

namespace zenith::sky {
namespace {

using test::Luminance;

struct Scene {
    geo::SkyEphemeris ephemeris;
    geo::Observer observer;
};

Scene At(const std::string& utc, double lat, double lon, double height_m) {
    geo::EphemerisOptions options;
    options.planets = false;
    const geo::Observer observer(lat, lon, height_m);
    return {geo::Ephemeris().Compute(geo::TimeFromIso8601(utc), observer, options), observer};
}

// The same lights without the eclipse: the Sun's whole light everywhere.
Lights Uneclipsed(Lights lights) {
    if (lights.eclipse.active) lights.sun_illuminance = lights.eclipse.unobscured_illuminance;
    lights.eclipse = {};
    return lights;
}

// The distance (m) from the Earth's shadow's axis (the Earth-Sun line through the planet's centre)
// of the point of the Moon, `moon_distance` m away, seen along `direction` from the state's
// camera; none off the Moon.
std::optional<double> MoonPointAxisDistance(const SkyState& state, double moon_distance,
                                            const glm::dvec3& direction) {
    const glm::dvec3 c = moon_distance * state.scene.moon.direction;
    const double b = glm::dot(direction, c);
    const double disc = b * b - (glm::dot(c, c) - geo::kMoonRadius * geo::kMoonRadius);
    if (disc <= 0.0) return std::nullopt;
    const glm::dvec3 point = state.view.camera.position + direction * (b - std::sqrt(disc));
    const glm::dvec3 sun = state.scene.lights.sun_direction;
    return glm::length(point - glm::dot(point, sun) * sun);
}

class EclipseFrames : public gl::test::HeadlessGlTest {
  protected:
    static void SetUpTestSuite() {
        HeadlessGlTest::SetUpTestSuite();
        renderer_ = new AtmosphereRenderer(Atmosphere{});
    }
    static void TearDownTestSuite() {
        delete renderer_;
        HeadlessGlTest::TearDownTestSuite();
    }
    // One frame: `lights` for the sky, the state's Moon; draw_sun_disk as given.
    static LutImage Render(const SkyState& state, const Lights& lights, glm::ivec2 size,
                           bool sun_disk = true) {
        SkyScene scene = test::LightsOnly(lights, sun_disk);
        scene.moon = state.scene.moon;
        return test::DrawFrame(*renderer_, scene, state.view, size);
    }
    static inline AtmosphereRenderer* renderer_ = nullptr;
};

// Chicago at maximum (93.9 % covered, tests/geo/eclipse_test.cpp), looking at the Sun through a
// 1 degree field: the disk pass's light, summed over its pixels, is the eclipsed illuminance
// MakeSkyState gives the lights (the uncovered, limb-darkened share of the Sun), through the
// air; and the sky around it is dimmed by about the same share.
TEST_F(EclipseFrames, PartialEclipseCrescentCarriesTheUncoveredLight) {
    const Scene scene = At("2024-04-08T19:07:41Z", 41.8781, -87.6298, 180.0);
    const geo::SolarEclipse eclipse = geo::ComputeSolarEclipse(scene.ephemeris);
    ASSERT_NEAR(eclipse.obscuration, 0.939, 0.002);
    const auto& sun = scene.ephemeris.sun.topocentric.horizontal;
    const double fov = glm::radians(1.0);
    const glm::ivec2 size(256, 256);
    const SkyState state = MakeSkyState(scene.ephemeris, scene.observer, Atmosphere{},
                                        {sun.azimuth, sun.elevation, 0.0}, fov, 1.0);
    ASSERT_TRUE(state.scene.lights.eclipse.active);
    // The lights carry the limb-darkened share of the Sun.
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(state.scene.lights.sun_illuminance[c] /
                        state.scene.lights.eclipse.unobscured_illuminance[c],
                    eclipse.uncovered_flux[c], 1e-12);
    }
    const LutImage with_disk = Render(state, state.scene.lights, size, true);
    const LutImage sky = Render(state, state.scene.lights, size, false);
    const double pixel = 2.0 * std::tan(0.5 * fov) / size.y;  // side, rad (near the axis)
    glm::dvec3 disk(0.0);
    int lit = 0;
    for (int y = 0; y < size.y; ++y) {
        for (int x = 0; x < size.x; ++x) {
            const glm::vec4 d = with_disk.at(x, y) - sky.at(x, y);
            disk += glm::dvec3(d.x, d.y, d.z) * pixel * pixel;
            if (Luminance(d) > 1e6) ++lit;
        }
    }
    const glm::dvec3 through_air =
        state.scene.lights.sun_illuminance *
        TransmittanceToLight(Atmosphere{}, 180.0, sun.direction_enu.z, eclipse.sun_radius);
    std::printf("crescent: %.0f lux drawn, %.0f lux expected (%d pixels lit of %.0f in the disk)\n",
                Luminance(disk), Luminance(through_air), lit,
                glm::pi<double>() * std::pow(eclipse.sun_radius / pixel, 2));
    EXPECT_NEAR(Luminance(disk) / Luminance(through_air), 1.0, 0.03);
    // A crescent: far fewer lit pixels than the whole disk, but some.
    const double disk_pixels = glm::pi<double>() * std::pow(eclipse.sun_radius / pixel, 2);
    EXPECT_GT(lit, 0.5 * (1.0 - eclipse.obscuration) * disk_pixels);
    EXPECT_LT(lit, 1.5 * (1.0 - eclipse.obscuration) * disk_pixels);

    // The sky at the zenith: dimmed by the Sun's uncovered light (the air within tens of km has
    // nearly the camera's share).
    const SkyState up = MakeSkyState(scene.ephemeris, scene.observer, Atmosphere{},
                                     {0.0, glm::radians(90.0), 0.0}, glm::radians(10.0), 1.0);
    const glm::ivec2 small(32, 32);
    const double eclipsed = Luminance(Render(up, up.scene.lights, small, false).at(16, 16));
    const double clear =
        Luminance(Render(up, Uneclipsed(up.scene.lights), small, false).at(16, 16));
    std::printf("zenith sky: %.1f cd/m^2 eclipsed, %.1f clear: ratio %.4f, light left %.4f\n",
                eclipsed, clear, eclipsed / clear, Luminance(eclipse.uncovered_flux));
    EXPECT_NEAR(eclipsed / clear, Luminance(eclipse.uncovered_flux),
                0.15 * Luminance(eclipse.uncovered_flux));
}

// Dallas in totality (2024-04-08 18:42 UT, 2 min into its 3 min 52 s): the zenith three orders
// of magnitude below the same sky uneclipsed, the horizon (sunlit air beyond the umbra, ~100 km
// away) far brighter than the zenith, and the corona around the Moon's black disk.
TEST_F(EclipseFrames, TotalityIsDarkAtTheZenithWithABrightHorizon) {
    const Scene scene = At("2024-04-08T18:42:00Z", 32.7767, -96.797, 140.0);
    const geo::SolarEclipse eclipse = geo::ComputeSolarEclipse(scene.ephemeris);
    ASSERT_TRUE(eclipse.total());
    const glm::ivec2 small(32, 32);
    const SkyState up = MakeSkyState(scene.ephemeris, scene.observer, Atmosphere{},
                                     {0.0, glm::radians(90.0), 0.0}, glm::radians(10.0), 1.0);
    EXPECT_EQ(up.scene.lights.sun_illuminance, glm::dvec3(0.0));
    const double zenith = Luminance(Render(up, up.scene.lights, small, false).at(16, 16));
    const double daylight =
        Luminance(Render(up, Uneclipsed(up.scene.lights), small, false).at(16, 16));
    // The horizon opposite the Sun (the Sun is at 188 deg azimuth, 65 deg up), 1 deg up.
    const SkyState level = MakeSkyState(scene.ephemeris, scene.observer, Atmosphere{},
                                        {0.0, glm::radians(1.0), 0.0}, glm::radians(10.0), 1.0);
    const double horizon = Luminance(Render(level, level.scene.lights, small, false).at(16, 16));
    std::printf("totality: zenith %.3g cd/m^2 (daylight %.3g, ratio %.2g), north horizon %.3g\n",
                zenith, daylight, zenith / daylight, horizon);
    // Measured: "about four orders of magnitude" below the day sky (Dandekar & Turtle 1971,
    // Appl. Opt. 10, 1220). Here only the light scattered in the sunlit air beyond the umbra
    // and again in it lights the zenith (EclipsedSkyIlluminance): 7e-4 of the day sky, within
    // an order of magnitude of that, and far below the horizon.
    EXPECT_GT(zenith / daylight, 1e-5);
    EXPECT_LT(zenith / daylight, 1e-3);
    EXPECT_GT(horizon / zenith, 10.0);
    EXPECT_LT(horizon, 0.5 * daylight);

    // The corona: around the Sun, 1e-6-ish of its disk's luminance, nothing on the Moon.
    const auto& sun = scene.ephemeris.sun.topocentric.horizontal;
    const double fov = glm::radians(3.0);
    const glm::ivec2 size(128, 128);
    const SkyState view = MakeSkyState(scene.ephemeris, scene.observer, Atmosphere{},
                                       {sun.azimuth, sun.elevation, 0.0}, fov, 1.0);
    const LutImage with_disk = Render(view, view.scene.lights, size, true);
    const LutImage sky = Render(view, view.scene.lights, size, false);
    const double pixel = 2.0 * std::tan(0.5 * fov) / size.y;
    const double mean_disk = Luminance(view.scene.lights.eclipse.unobscured_illuminance) /
                             (glm::pi<double>() * eclipse.sun_radius * eclipse.sun_radius);
    const auto corona_at = [&](double radii) {  // to the right of the centre (pixel 64 + r)
        const int x = 64 + static_cast<int>(std::lround(radii * eclipse.sun_radius / pixel));
        return Luminance(with_disk.at(x, 64) - sky.at(x, 64));
    };
    const double centre = Luminance(with_disk.at(64, 64) - sky.at(64, 64));
    std::printf("corona / mean disk: %.3g at 1.1, %.3g at 2, %.3g at 3 radii; centre %.3g\n",
                corona_at(1.1) / mean_disk, corona_at(2.0) / mean_disk, corona_at(3.0) / mean_disk,
                centre);
    EXPECT_EQ(centre, 0.0);  // the Moon
    const double t = Luminance(TransmittanceToLight(Atmosphere{}, 140.0, sun.direction_enu.z, 0.0));
    EXPECT_GT(corona_at(1.1) / mean_disk / t, 0.5e-6);
    EXPECT_LT(corona_at(1.1) / mean_disk / t, 3e-6);
    EXPECT_GT(corona_at(1.1), 10.0 * corona_at(2.0));
    EXPECT_GT(corona_at(2.0), corona_at(3.0));
}

// The clouds' shade is copied into the light block each frame; the eclipse's members lie after
// it and must survive the copy. Totality at Dallas under the cirrus preset (optical depth up to
// ~0.3 at 9 km), looking up: lit, as the clear sky's zenith is in the same eclipse, by the
// sunlit air beyond the umbra (1e-5 to 1e-3 of daylight through the same clouds). With the
// eclipse's members zeroed by the copy the Sun was simply gone: 3.6e-15 of daylight.
TEST_F(EclipseFrames, UnderCloudsTheEclipseIsKept) {
    const Scene scene = At("2024-04-08T18:42:00Z", 32.7767, -96.797, 140.0);
    const SkyState up = MakeSkyState(scene.ephemeris, scene.observer, Atmosphere{},
                                     {0.0, glm::radians(90.0), 0.0}, glm::radians(10.0), 1.0);
    AtmosphereRenderer clouded(Atmosphere{});
    clouded.SetWeather(clouds::LoadWeather("cirrus"));
    const glm::ivec2 small(16, 16);
    const auto zenith = [&](const Lights& lights) {
        SkyScene frame = test::LightsOnly(lights, false);
        frame.moon = up.scene.moon;
        return Luminance(test::DrawFrame(clouded, frame, up.view, small, 4).at(8, 8));
    };
    const double eclipsed = zenith(up.scene.lights);
    const double daylight = zenith(Uneclipsed(up.scene.lights));
    std::printf("totality under cirrus: zenith %.3g cd/m^2, daylight %.3g (ratio %.2g)\n", eclipsed,
                daylight, eclipsed / daylight);
    EXPECT_GT(eclipsed / daylight, 1e-5);
    EXPECT_LT(eclipsed / daylight, 1e-3);
}

// The eclipsed Sky-View LUT on the GPU against the shared code compiled as C++ in double (the
// CPU reference): the shadow's per-sample geometry in float holds in totality and in the
// partial eclipse beside the path. Texels compared relative to max(|CPU|, 1e-3 of the LUT's
// mean luminance), so the black umbra's texels count by absolute difference.
TEST_F(EclipseFrames, EclipsedSkyViewMatchesTheCpuReference) {
    const reference::AtmosphereReference cpu(Atmosphere{});
    for (const auto& [utc, lat, lon] : {std::tuple("2024-04-08T18:42:00Z", 32.7767, -96.797),
                                        std::tuple("2024-04-08T19:07:41Z", 41.8781, -87.6298)}) {
        const Scene scene = At(utc, lat, lon, 140.0);
        const SkyState state =
            MakeSkyState(scene.ephemeris, scene.observer, Atmosphere{}, {}, 1.0, 1.0);
        ASSERT_TRUE(state.scene.lights.eclipse.active);
        renderer_->Update(test::LightsOnly(state.scene.lights), state.view);
        const LutImage gpu = Inspect(*renderer_).ReadSkyView();
        const LutImage reference = cpu.SkyView(state.view.camera.position, state.scene.lights);
        ASSERT_EQ(gpu.size, reference.size);
        double mean = 0.0;
        for (const glm::vec4& t : reference.texels) mean += Luminance(t);
        mean /= static_cast<double>(reference.texels.size());
        double worst = 0.0;
        for (std::size_t i = 0; i < gpu.texels.size(); ++i) {
            const double a = Luminance(gpu.texels[i]), b = Luminance(reference.texels[i]);
            worst = std::max(worst, std::abs(a - b) / std::max(std::abs(b), 1e-3 * mean));
        }
        std::printf("%s: eclipsed Sky-View GPU vs CPU max relative %.2e (mean %.3g cd/m^2)\n", utc,
                    worst, mean);
        EXPECT_LT(worst, 2e-2) << utc;
    }
}

// The 2022-11-08 lunar eclipse: the Moon's light through the penumbra follows the direct
// sunlight reaching it, and in the umbra it is the refracted light, reddened by the air's own
// transmittance (red over blue >> 1) and 1e-5-1e-3 of the full Moon's. The Moon's centre's share
// is the shadow's table's (MoonDisk::Shadow) at its distance from the axis; the Moon's light is
// the mean over its face.
TEST_F(EclipseFrames, EclipsedMoonFollowsThePenumbraAndIsRedInTheUmbra) {
    const auto moon_state = [](const char* utc) {
        // Honolulu, where the Moon was high.
        const Scene scene = At(utc, 21.3, -157.86, 10.0);
        return std::pair(MakeSkyState(scene.ephemeris, scene.observer, Atmosphere{}, {}, 1.0, 1.0),
                         geo::ComputeLunarEclipse(scene.ephemeris,
                                                  geo::kEarthShadowRadius + 100e3));  // + air
    };
    const auto [before, before_geometry] = moon_state("2022-11-08T07:30:00Z");
    EXPECT_EQ(before.scene.moon.sunlight, glm::dvec3(1.0));
    double previous = 1.0;
    for (const char* utc : {"2022-11-08T08:40:00Z", "2022-11-08T08:55:00Z", "2022-11-08T09:10:00Z",
                            "2022-11-08T09:25:00Z"}) {
        const auto [state, geometry] = moon_state(utc);
        ASSERT_TRUE(state.scene.moon.shadow.has_value()) << utc;
        const double direct = Luminance(geometry.direct_sunlight);
        const double refracted =
            Luminance(ShadowSunlight(*state.scene.moon.shadow, geometry.axis_distance) -
                      geometry.direct_sunlight);
        const double mean = Luminance(state.scene.moon.sunlight);
        const double ratio = Luminance(state.scene.lights.moon_illuminance) /
                             Luminance(before.scene.lights.moon_illuminance);
        std::printf(
            "%s: at the centre direct sunlight %.4f + refracted %.4f; over the face %.4f; Moon "
            "illuminance / uneclipsed %.4f\n",
            utc, direct, refracted, mean, ratio);
        EXPECT_GT(direct, 0.0);
        EXPECT_LT(direct, previous);
        previous = direct;
        // The distance and phase change the uneclipsed light by < 1 % over these two hours.
        EXPECT_NEAR(ratio, mean, 0.01);
        // The refracted light: a few % of the Sun's at most, where the air's upper, clear layers
        // bend it into the inner penumbra.
        EXPECT_GE(refracted, -0.005);
        EXPECT_LT(refracted, 0.1);
    }
    const auto [total, total_geometry] = moon_state("2022-11-08T10:59:08Z");
    EXPECT_EQ(total_geometry.direct_sunlight, glm::dvec3(0.0));
    glm::dvec3 umbra = ShadowSunlight(*total.scene.moon.shadow, total_geometry.axis_distance);
    std::printf("umbra: refracted light %.3g %.3g %.3g (rgb) of the Sun's, red/blue %.1f\n",
                umbra.x, umbra.y, umbra.z, umbra.x / umbra.z);
    EXPECT_GT(Luminance(umbra), 1e-5);
    EXPECT_LT(Luminance(umbra), 1e-3);
    EXPECT_GT(umbra.x / umbra.z, 5.0);
    EXPECT_GT(umbra.x, umbra.y);

    // Drawn: the Moon's disk scaled by it (the disk pass's MoonLuminance).
    const double fov = glm::radians(2.0);
    const Scene scene = At("2022-11-08T10:59:08Z", 21.3, -157.86, 10.0);
    const auto& moon = scene.ephemeris.moon.topocentric.horizontal;
    const SkyState view = MakeSkyState(scene.ephemeris, scene.observer, Atmosphere{},
                                       {moon.azimuth, moon.elevation, 0.0}, fov, 1.0);
    SkyState uneclipsed = view;
    uneclipsed.scene.moon.sunlight = glm::dvec3(1.0);
    uneclipsed.scene.moon.shadow.reset();
    const glm::ivec2 size(64, 64);
    const LutImage eclipsed_frame = Render(view, view.scene.lights, size);
    const LutImage full_frame = Render(uneclipsed, view.scene.lights, size);
    const glm::vec4 e = eclipsed_frame.at(32, 32), f = full_frame.at(32, 32);
    std::printf("Moon's centre: %.4g cd/m^2 eclipsed, %.4g full\n", Luminance(e), Luminance(f));
    // The refracted light varies across the umbra: the table's at the point the pixel shows.
    const std::optional<double> axis = MoonPointAxisDistance(
        view, moon.distance, view.view.camera.Direction(1.0 / size.x, 1.0 / size.y));
    ASSERT_TRUE(axis.has_value());
    umbra = ShadowSunlight(*view.scene.moon.shadow, *axis);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(e[c] / f[c], umbra[c], 0.02 * umbra[c] + 1e-7) << c;
    }
}

// The umbra's edge across the Moon's face, 2022-11-08T09:50Z from Honolulu (the umbra over
// part of the disk): every pixel of the disk, eclipsed over uneclipsed, is the sunlight reaching
// the point of the Moon it shows, worked out here from the geometry alone (the point's distance
// from the Earth-Sun line, geo::LunarEclipseAt's direct light past the Earth and its air plus
// UmbraRefractedLight), not from the renderer's table, within the interpolation of the table's
// 64 samples across the disk; and the dark part is nearer the shadow's centre (its axis at the
// Moon's distance, as seen from the camera) than the lit part. Near the umbra's edge, where the
// air bends light into it, the refracted light the table interpolates from 16 points differs
// from UmbraRefractedLight's value at a point, whose quadrature over 16 offsets of the Sun's
// disk moves by 0.02 of the Sun's light between points 15 km apart: there the pixel is checked
// to lie between the direct light and it plus twice the refracted. Pixels within 95 % of the disk's
// radius, the night sky's light taken off (a frame without the Moon).
TEST_F(EclipseFrames, TheUmbrasEdgeCrossesTheMoonsFace) {
    const Scene scene = At("2022-11-08T09:50:00Z", 21.3, -157.86, 10.0);
    const auto& moon = scene.ephemeris.moon.topocentric.horizontal;
    const Atmosphere air;
    const SkyState view = MakeSkyState(scene.ephemeris, scene.observer, air,
                                       {moon.azimuth, moon.elevation, 0.0}, glm::radians(0.6), 1.0);
    ASSERT_TRUE(view.scene.moon.shadow.has_value());
    SkyState uneclipsed = view;
    uneclipsed.scene.moon.sunlight = glm::dvec3(1.0);
    uneclipsed.scene.moon.shadow.reset();
    const glm::ivec2 size(96, 96);
    const LutImage eclipsed_frame = Render(view, view.scene.lights, size, false);
    const LutImage full_frame = Render(uneclipsed, view.scene.lights, size, false);
    SkyState moonless = view;
    moonless.scene.moon.enabled = false;
    const LutImage sky_frame = Render(moonless, view.scene.lights, size, false);

    const double shadow_radius = geo::kEarthShadowRadius + air.top_radius - air.bottom_radius;
    const geo::LunarEclipse centre = geo::ComputeLunarEclipse(scene.ephemeris, shadow_radius);
    const double along = centre.moon_distance * std::cos(centre.axis_angle);
    const Camera& camera = view.view.camera;
    const glm::dvec3 sun = view.scene.lights.sun_direction;
    const glm::dvec3 axis_seen = glm::normalize(-sun * along - camera.position);
    int pixels = 0, dark = 0, near_the_edge = 0;
    double worst = 0.0, farthest_dark = 0.0, nearest_lit = 1.0;
    for (int y = 0; y < size.y; ++y) {
        for (int x = 0; x < size.x; ++x) {
            const glm::dvec3 d =
                camera.Direction(2.0 * (x + 0.5) / size.x - 1.0, 2.0 * (y + 0.5) / size.y - 1.0);
            // The Moon's sphere, from the camera (planet-centred, m).
            if (glm::length(d - view.scene.moon.direction) >
                0.95 * view.scene.moon.angular_radius) {
                continue;
            }
            const std::optional<double> on_moon = MoonPointAxisDistance(view, moon.distance, d);
            if (!on_moon) continue;
            const double axis = *on_moon;
            const geo::LunarEclipse at = geo::LunarEclipseAt(
                std::hypot(along, axis), glm::pi<double>() - std::atan2(axis, along),
                scene.ephemeris.sun.geocentric_distance, shadow_radius);
            const double direct = Luminance(at.direct_sunlight);
            const double refracted =
                Luminance(UmbraRefractedLight(air, axis, at.moon_distance, at.sun_radius));
            const double expected = direct + refracted;
            const double sky = Luminance(sky_frame.at(x, y));
            const double seen =
                (Luminance(eclipsed_frame.at(x, y)) - sky) / (Luminance(full_frame.at(x, y)) - sky);
            ++pixels;
            if (refracted < 0.005) {
                worst = std::max(worst, std::abs(seen - expected));
            } else {
                ++near_the_edge;
                EXPECT_GT(seen, direct - 0.02) << x << ", " << y;
                EXPECT_LT(seen, direct + 2.0 * refracted + 0.02) << x << ", " << y;
            }
            const double from_axis = glm::length(d - axis_seen);
            if (seen < 0.01) {
                ++dark;
                farthest_dark = std::max(farthest_dark, from_axis);
            } else if (seen > 0.05) {
                nearest_lit = std::min(nearest_lit, from_axis);
            }
        }
    }
    std::printf(
        "umbral magnitude %.3f: %d pixels of the Moon, %d dark (< 1 %% of the Sun's light) out to "
        "%.4f deg from the shadow's centre, lit (> 5 %%) from %.4f deg; worst |eclipsed / full - "
        "expected| %.4f where the refracted light is < 0.005 (%d pixels near the edge)\n",
        centre.umbral_magnitude, pixels, dark, glm::degrees(farthest_dark),
        glm::degrees(nearest_lit), worst, near_the_edge);
    ASSERT_GT(centre.umbral_magnitude, 0.2);
    ASSERT_LT(centre.umbral_magnitude, 0.8);
    EXPECT_GT(pixels, 3000);
    EXPECT_GT(dark, pixels / 10);
    EXPECT_LT(dark, pixels * 9 / 10);
    EXPECT_LT(farthest_dark, nearest_lit);
    EXPECT_LT(worst, 0.02);
}

}  // namespace
}  // namespace zenith::sky
