#include "zenith/sky/sky_state.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/gtc/constants.hpp>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "error_matchers.h"
#include "zenith/base/error.h"
#include "zenith/geo/planets.h"
#include "zenith/geo/stars.h"
#include "zenith/geo/sun.h"

namespace zenith::sky {
namespace {

constexpr double kDeg = glm::pi<double>() / 180.0;

void ExpectNear(const glm::dvec3& a, const glm::dvec3& b, double tolerance) {
    EXPECT_NEAR(glm::length(a - b), 0.0, tolerance) << a.x << " " << a.y << " " << a.z;
}

TEST(MoonLight, LambertSphereClosedForms) {
    const double s = std::sin(0.0045);
    // Full: (2/3) A sin^2(r); quarter (90 deg): Phi = 1 / pi; new: 0.
    EXPECT_NEAR(LambertSphereIlluminanceFactor(0.12, 0.0, 0.0045), 2.0 / 3.0 * 0.12 * s * s, 1e-15);
    EXPECT_NEAR(LambertSphereIlluminanceFactor(0.12, glm::half_pi<double>(), 0.0045),
                2.0 / 3.0 * 0.12 * s * s / glm::pi<double>(), 1e-15);
    EXPECT_NEAR(LambertSphereIlluminanceFactor(0.12, glm::pi<double>(), 0.0045), 0.0, 1e-18);
}

TEST(SkyStateFromEphemeris, PlacesCameraAndScalesLights) {
    const geo::Time t = geo::TimeFromIso8601("2024-01-25T17:54:00Z");  // full Moon
    const geo::Observer observer(45.0, 7.0, 3000.0);
    const geo::SkyEphemeris e = geo::Ephemeris().Compute(t, observer);
    const Atmosphere earth;
    const SkyState state = MakeSkyState(e, observer, earth, {}, 1.0, 1.5);
    // The ground under the camera is at its ellipsoidal height; up is the ENU z axis.
    EXPECT_NEAR(glm::length(state.view.camera.position) - earth.bottom_radius, 3000.0, 1e-6);
    ExpectNear(glm::normalize(state.view.camera.position), {0, 0, 1}, 1e-15);
    ExpectNear(state.scene.lights.sun_direction, e.sun.topocentric.horizontal.direction_enu, 1e-15);
    // January: the Earth is near perihelion, the Sun 3 % brighter than at 1 au.
    const double au = e.sun.topocentric.horizontal.distance / geo::kAstronomicalUnit;
    EXPECT_NEAR(state.scene.lights.sun_illuminance.y, earth.solar_illuminance.y / (au * au), 1e-6);
    EXPECT_GT(state.scene.lights.sun_illuminance.y / earth.solar_illuminance.y, 1.03);
    // Full Moon: a Lambertian sphere of albedo 0.12 gives ~0.2 lux at the top of the
    // atmosphere; the real Moon gives ~0.3 (opposition surge, not modelled).
    EXPECT_GT(state.scene.lights.moon_illuminance.y, 0.15);
    EXPECT_LT(state.scene.lights.moon_illuminance.y, 0.35);
}

// Venus at its greatest brilliancy (2020-04-28, V = -4.7), an hour after sunset over the Alps:
// drawn as the brightest point of the sky, where the ephemeris puts it; planets under
// MinStarElevation are not drawn.
TEST(SkyStateFromEphemeris, PlanetsAreDrawnLikeStars) {
    const geo::Time t = geo::TimeFromIso8601("2020-04-28T19:45:00Z");
    const geo::Observer observer(45.0, 7.0, 500.0);
    const geo::SkyEphemeris e = geo::Ephemeris().Compute(t, observer);
    ASSERT_EQ(e.planets.size(), geo::kSkyPlanets.size());
    const SkyState state = MakeSkyState(e, observer, Atmosphere{}, {}, 1.0, 1.5);
    std::size_t planets_up = 0;
    for (const geo::PlanetPosition& p : e.planets) {
        planets_up +=
            p.topocentric.horizontal.elevation >= MinStarElevation(6360e3, 500.0) ? 1u : 0u;
    }
    ASSERT_EQ(state.scene.stars.size(), e.stars.size() + planets_up);
    const geo::PlanetPosition& venus = e.planets[1];
    ASSERT_EQ(venus.planet, geo::Planet::kVenus);
    EXPECT_LT(venus.magnitude_v, -4.5);
    EXPECT_GT(venus.topocentric.horizontal.elevation, 0.2);
    const auto brightest = std::max_element(
        state.scene.stars.begin(), state.scene.stars.end(),
        [](const StarPoint& a, const StarPoint& b) { return a.illuminance.y < b.illuminance.y; });
    ExpectNear(brightest->direction, venus.topocentric.horizontal.direction_enu, 1e-15);
    // Its luminous part: the magnitude's illuminance, within its colour's green weight.
    const double expected = geo::IlluminanceFromMagnitude(venus.magnitude_v);
    EXPECT_NEAR(brightest->illuminance.y / expected, 1.0, 0.1);
    EXPECT_GT(brightest->illuminance.y, 10.0 * geo::IlluminanceFromMagnitude(-1.46));  // Sirius
    // Its disk (ResolveDisks draws it when wider than a pixel), lit from the Sun: the angle
    // between the Sun and the observer seen from Venus is the ephemeris' phase angle.
    EXPECT_NEAR(brightest->angular_radius,
                0.5 * glm::radians(venus.angular_diameter_arcsec / 3600.0), 1e-15);
    EXPECT_NEAR(std::acos(glm::dot(brightest->sunward, -brightest->direction)), venus.phase_angle,
                1e-3);
}

// A disk wider than a pixel is spread over it with its light kept: at quadrature (the Sun 90
// deg off the line of sight) the lit half of a Lambertian sphere weighs u over the half disk,
// whose centroid is 3 pi / 16 of the radius toward the Sun; at opposition sqrt(1 - rho^2),
// centred. Points narrower than half a pixel, and stars, stay as they are.
TEST(ResolveDisks, SpreadsALitSphereAndKeepsItsLight) {
    const double radius = 1e-4;  // rad, 20": 20 pixels of 1e-5 rad
    const glm::dvec3 toward(0.0, 1.0, 0.0);
    const glm::dvec3 east(1.0, 0.0, 0.0);
    StarPoint planet{toward, glm::dvec3(2e-5, 3e-5, 1e-5), radius, east};
    StarPoint star{glm::dvec3(0.0, 0.0, 1.0), glm::dvec3(1e-6), 0.0, glm::dvec3(0.0)};
    const auto disk_of = [](const std::vector<StarPoint>& points) {
        glm::dvec3 sum(0.0), centroid(0.0);
        double widest = 0.0;
        for (const StarPoint& p : points) {
            sum += p.illuminance;
            centroid += p.illuminance.y * p.direction;
            widest = std::max(widest, std::acos(std::min(p.direction.y, 1.0)));
        }
        return std::tuple{sum, centroid / sum.y, widest};
    };
    const std::vector<StarPoint> quadrature = ResolveDisks({planet, star}, 1e-5);
    ASSERT_GT(quadrature.size(), 200u);
    EXPECT_EQ(quadrature.back().direction, star.direction);  // the star untouched
    const std::vector<StarPoint> lit(quadrature.begin(), quadrature.end() - 1);
    const auto [sum, centroid, widest] = disk_of(lit);
    ExpectNear(sum, planet.illuminance, 1e-18);
    EXPECT_NEAR(centroid.x / radius, 3.0 * glm::pi<double>() / 16.0, 0.02);
    EXPECT_NEAR(centroid.z / radius, 0.0, 1e-3);
    EXPECT_LE(widest, radius * 1.0001);
    for (const StarPoint& p : lit) EXPECT_GT(p.direction.x, 0.0);  // the night side is dark

    planet.sunward = -toward;  // opposition: full
    const auto [full_sum, full_centroid, full_widest] = disk_of(ResolveDisks({planet}, 1e-5));
    ExpectNear(full_sum, planet.illuminance, 1e-18);
    EXPECT_NEAR(glm::length(glm::dvec2(full_centroid.x, full_centroid.z)) / radius, 0.0, 1e-3);
    EXPECT_GT(full_widest, 0.9 * radius);

    // Unresolved: one pixel of 1e-3 rad holds the whole disk.
    const std::vector<StarPoint> small = ResolveDisks({planet}, 1e-3);
    ASSERT_EQ(small.size(), 1u);
    EXPECT_EQ(small[0].direction, planet.direction);
}

// From altitude the horizon dips: from 100 km the limb is 10.1 deg below the horizontal plane
// (acos(R / (R + h))), and the stars between the plane and the limb are in the sky.
TEST(SkyFrame, StarsDownToTheLimbAreDrawnFromAltitude) {
    EXPECT_NEAR(MinStarElevation(6360e3, 0.0), -glm::radians(0.6), 1e-15);
    EXPECT_NEAR(MinStarElevation(6360e3, 100e3), -(std::acos(6360.0 / 6460.0) + glm::radians(0.6)),
                1e-12);
    EXPECT_NEAR(glm::degrees(std::acos(6360.0 / 6460.0)), 10.1, 0.05);

    std::optional<geo::StarCatalog> catalog;
    try {
        catalog = geo::StarCatalog::Load(6.5);
    } catch (const geo::CatalogError& e) {
        GTEST_SKIP() << "star catalogue not installed: " << e.what();
    }
    FrameSetup setup;
    setup.time = geo::TimeFromIso8601("2024-06-21T23:30:00Z");
    setup.observer = geo::Observer(46.45, 6.6, 100e3);
    const SkyFrame frame = BuildSkyFrame(geo::Ephemeris(&*catalog), setup, Atmosphere{});
    const double lowest = MinStarElevation(Atmosphere{}.bottom_radius, 100e3);
    int below_the_plane = 0;
    for (const geo::StarState& star : frame.ephemeris.stars) {
        EXPECT_GE(star.horizontal.elevation, lowest);
        below_the_plane += star.horizontal.elevation < 0.0 ? 1 : 0;
    }
    // A band 10 deg high around the whole horizon holds ~9 % of the ~9,000 stars to 6.5 mag.
    std::printf("stars between the horizontal plane and the limb from 100 km: %d\n",
                below_the_plane);
    EXPECT_GT(below_the_plane, 300);
}

TEST(SkyFrame, BuildsTheSameFrameAsMakeSkyStateAndChecksTheProjection) {
    FrameSetup setup;
    setup.time = geo::TimeFromIso8601("2024-06-21T19:00:00Z");
    setup.observer = geo::Observer(47.45, 8.56, 10000.0);
    setup.attitude = geo::Attitude::FromDegrees(300.0, 5.0, -2.0);
    setup.vertical_fov = glm::radians(50.0);
    setup.aspect = 1.5;
    const Atmosphere earth;
    const SkyFrame frame = BuildSkyFrame(geo::Ephemeris(), setup, earth);
    const SkyState state = MakeSkyState(frame.ephemeris, setup.observer, earth, setup.attitude,
                                        setup.vertical_fov, setup.aspect);
    EXPECT_EQ(frame.view.camera.world_from_view, state.view.camera.world_from_view);
    EXPECT_EQ(frame.view.camera.position, state.view.camera.position);
    EXPECT_EQ(frame.scene.lights.sun_direction, state.scene.lights.sun_direction);
    EXPECT_EQ(frame.scene.stars.size(), state.scene.stars.size());
    EXPECT_EQ(frame.sun_elevation, state.sun_elevation);

    // A view matrix given instead of the attitude is taken as it is.
    const glm::dmat3 looking_up(glm::dvec3(1, 0, 0), glm::dvec3(0, -1, 0), glm::dvec3(0, 0, -1));
    setup.enu_from_view = looking_up;
    EXPECT_EQ(BuildSkyFrame(geo::Ephemeris(), setup, earth).view.camera.world_from_view,
              looking_up);

    for (const double fov_deg : {0.0, 180.0, -10.0, std::nan("")}) {
        setup.vertical_fov = glm::radians(fov_deg);
        EXPECT_THAT([&] { BuildSkyFrame(geo::Ephemeris(), setup, earth); },
                    test::ThrowsArgumentError("fov_deg", ::testing::HasSubstr("(0, 180) deg")))
            << fov_deg;
    }
    setup.vertical_fov = 1.0;
    setup.aspect = 0.0;
    EXPECT_THAT([&] { BuildSkyFrame(geo::Ephemeris(), setup, earth); },
                test::ThrowsArgumentError("aspect", ::testing::HasSubstr("aspect = 0")));
}

}  // namespace
}  // namespace zenith::sky

namespace zenith::sky {
namespace {

// The frame's bodies seen through the air (FrameSetup::refraction): every star lifted to the
// table's apparent elevation with its azimuth kept, the disks' apparent places set and their
// light still coming from the geometric directions; none of it without refraction.
TEST(SkyFrame, RefractionLiftsWhatIsSeenAndKeepsTheLight) {
    std::optional<geo::StarCatalog> catalog;
    try {
        catalog = geo::StarCatalog::Load(4.0);
    } catch (const geo::CatalogError& e) {
        GTEST_SKIP() << "star catalogue not installed: " << e.what();
    }
    FrameSetup setup;
    setup.time = geo::TimeFromIso8601("2024-06-21T19:30:00Z");  // the Sun 0.8 deg below
    setup.observer = geo::Observer(46.45, 6.6, 10000.0);
    const Atmosphere earth;
    const SkyFrame seen = BuildSkyFrame(geo::Ephemeris(&*catalog), setup, earth);
    setup.refraction.reset();
    const SkyFrame geometric = BuildSkyFrame(geo::Ephemeris(&*catalog), setup, earth);
    const geo::RefractionTable table(geo::RefractionAir{}, 10000.0, earth.bottom_radius);

    ASSERT_EQ(seen.scene.stars.size(), geometric.scene.stars.size());
    ASSERT_GT(seen.scene.stars.size(), 100u);
    int lifted = 0;
    for (std::size_t i = 0; i < seen.scene.stars.size(); ++i) {
        const glm::dvec3& a = seen.scene.stars[i].direction;
        const glm::dvec3& g = geometric.scene.stars[i].direction;
        EXPECT_NEAR(glm::length(a), 1.0, 1e-12);
        EXPECT_NEAR(std::atan2(a.x, a.y), std::atan2(g.x, g.y), 1e-9);
        const std::optional<double> apparent = table.Apparent(std::asin(g.z));
        EXPECT_NEAR(std::asin(a.z), apparent.value_or(std::asin(g.z)), 1e-12);
        lifted += std::asin(a.z) > std::asin(g.z) ? 1 : 0;
    }
    EXPECT_GT(lifted, static_cast<int>(seen.scene.stars.size()) * 9 / 10);

    EXPECT_EQ(seen.scene.lights.sun_direction, geometric.scene.lights.sun_direction);
    ASSERT_TRUE(seen.scene.sun_apparent);
    const double sun = std::asin(seen.scene.lights.sun_direction.z);
    EXPECT_NEAR(std::asin(seen.scene.sun_apparent->direction.z), *table.Apparent(sun), 1e-12);
    EXPECT_NEAR(seen.scene.sun_apparent->vertical_scale, table.VerticalScale(sun), 1e-12);
    ASSERT_TRUE(seen.scene.moon.apparent);
    EXPECT_EQ(seen.scene.moon.direction, geometric.scene.moon.direction);
    EXPECT_FALSE(geometric.scene.sun_apparent);
    EXPECT_FALSE(geometric.scene.moon.apparent);
}

// The cache traces a new table only when the dip would move by more than 5".
TEST(SkyFrame, RefractionCacheKeepsTheTableWhileTheHorizonHolds) {
    RefractionCache cache;
    const geo::RefractionAir air;
    EXPECT_EQ(cache.Get(air, 10000.0, 6360e3).height_m(), 10000.0);
    EXPECT_EQ(cache.Get(air, 10005.0, 6360e3).height_m(), 10000.0);  // 8.7 m allowed at 10 km
    EXPECT_EQ(cache.Get(air, 10020.0, 6360e3).height_m(), 10020.0);
    geo::RefractionAir warm;
    warm.sea_level_temperature_c = 30.0;
    EXPECT_EQ(cache.Get(warm, 10020.0, 6360e3).air(), warm);
    EXPECT_EQ(cache.Get(air, 100.0, 6360e3).height_m(), 100.0);
    EXPECT_EQ(cache.Get(air, 100.4, 6360e3).height_m(), 100.0);
    EXPECT_EQ(cache.Get(air, 101.0, 6360e3).height_m(), 101.0);  // 0.5 m at 100 m
}

}  // namespace
}  // namespace zenith::sky
