#include "zenith/sky/sky_state.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/constants.hpp>

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
    EXPECT_NEAR(glm::length(state.camera.position) - earth.bottom_radius, 3000.0, 1e-6);
    ExpectNear(glm::normalize(state.camera.position), {0, 0, 1}, 1e-15);
    ExpectNear(state.lights.sun_direction, e.sun.topocentric.horizontal.direction_enu, 1e-15);
    // January: the Earth is near perihelion, the Sun 3 % brighter than at 1 au.
    const double au = e.sun.topocentric.horizontal.distance / geo::kAstronomicalUnit;
    EXPECT_NEAR(state.lights.sun_illuminance.y, earth.solar_illuminance.y / (au * au), 1e-6);
    EXPECT_GT(state.lights.sun_illuminance.y / earth.solar_illuminance.y, 1.03);
    // Full Moon: a Lambertian sphere of albedo 0.12 gives ~0.2 lux at the top of the
    // atmosphere; the real Moon gives ~0.3 (opposition surge, not modelled).
    EXPECT_GT(state.lights.moon_illuminance.y, 0.15);
    EXPECT_LT(state.lights.moon_illuminance.y, 0.35);
}

// Venus at its greatest brilliancy (2020-04-28, V = -4.7), an hour after sunset over the Alps:
// drawn as the brightest point of the sky, where the ephemeris puts it; planets under
// kMinStarElevation are not drawn.
TEST(SkyStateFromEphemeris, PlanetsAreDrawnLikeStars) {
    const geo::Time t = geo::TimeFromIso8601("2020-04-28T19:45:00Z");
    const geo::Observer observer(45.0, 7.0, 500.0);
    const geo::SkyEphemeris e = geo::Ephemeris().Compute(t, observer);
    ASSERT_EQ(e.planets.size(), geo::kSkyPlanets.size());
    const SkyState state = MakeSkyState(e, observer, Atmosphere{}, {}, 1.0, 1.5);
    std::size_t planets_up = 0;
    for (const geo::PlanetPosition& p : e.planets) {
        planets_up += p.topocentric.horizontal.elevation >= kMinStarElevation ? 1 : 0;
    }
    ASSERT_EQ(state.stars.size(), e.stars.size() + planets_up);
    const geo::PlanetPosition& venus = e.planets[1];
    ASSERT_EQ(venus.planet, geo::Planet::kVenus);
    EXPECT_LT(venus.magnitude_v, -4.5);
    EXPECT_GT(venus.topocentric.horizontal.elevation, 0.2);
    const auto brightest = std::max_element(
        state.stars.begin(), state.stars.end(),
        [](const StarPoint& a, const StarPoint& b) { return a.illuminance.y < b.illuminance.y; });
    ExpectNear(brightest->direction, venus.topocentric.horizontal.direction_enu, 1e-15);
    // Its luminous part: the magnitude's illuminance, within its colour's green weight.
    const double expected = geo::IlluminanceFromMagnitude(venus.magnitude_v);
    EXPECT_NEAR(brightest->illuminance.y / expected, 1.0, 0.1);
    EXPECT_GT(brightest->illuminance.y, 10.0 * geo::IlluminanceFromMagnitude(-1.46));  // Sirius
}

}  // namespace
}  // namespace zenith::sky
