#include "zenith/geo/observer.h"

#include <gtest/gtest.h>

#include <GeographicLib/Geocentric.hpp>
#include <cmath>
#include <glm/gtc/constants.hpp>
#include <string>

#include "zenith/geo/earth_orientation.h"

namespace zenith::geo {
namespace {

constexpr double kMetreTolerance = 1e-6;
constexpr double kUnitTolerance = 1e-12;
constexpr double kWgs84A = 6378137.0;
constexpr double kWgs84B = 6356752.314245179;

void ExpectObserverError(double lat, double lon, double h, const std::string& mentions) {
    try {
        Observer o(lat, lon, h);
        FAIL() << "accepted " << lat << ", " << lon << ", " << h;
    } catch (const ObserverError& e) {
        EXPECT_NE(std::string(e.what()).find(mentions), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("expected"), std::string::npos) << e.what();
    }
}

TEST(Observer, RejectsBadInputNamingParameterAndRange) {
    ExpectObserverError(90.5, 0, 0, "lat_deg = 90.5");
    ExpectObserverError(-91, 0, 0, "lat_deg");
    ExpectObserverError(NAN, 0, 0, "lat_deg");
    ExpectObserverError(0, NAN, 0, "lon_deg");
    ExpectObserverError(0, 1000, 0, "lon_deg");
    ExpectObserverError(0, 0, NAN, "height_m");
    ExpectObserverError(0, 0, INFINITY, "height_m");
    ExpectObserverError(0, 0, -20000, "height_m");
}

TEST(Observer, WrapsLongitude) {
    EXPECT_EQ(Observer(0, 180, 0).lon_deg(), -180.0);
    EXPECT_EQ(Observer(0, -180, 0).lon_deg(), -180.0);
    EXPECT_NEAR(Observer(0, 540, 0).lon_deg(), -180.0, 1e-12);
    EXPECT_NEAR(Observer(0, 359, 0).lon_deg(), -1.0, 1e-12);
    // +180 and -180 are the same place.
    const glm::dvec3 a = Observer(10, 180, 0).ecef();
    const glm::dvec3 b = Observer(10, -180, 0).ecef();
    EXPECT_NEAR(glm::length(a - b), 0.0, kMetreTolerance);
}

TEST(Observer, EcefOnTheWgs84Ellipsoid) {
    const glm::dvec3 equator = Observer(0, 0, 0).ecef();
    EXPECT_NEAR(equator.x, kWgs84A, kMetreTolerance);
    EXPECT_NEAR(equator.y, 0.0, kMetreTolerance);
    EXPECT_NEAR(equator.z, 0.0, kMetreTolerance);
    const glm::dvec3 pole = Observer(90, 0, 0).ecef();
    EXPECT_NEAR(pole.z, kWgs84B, kMetreTolerance);
    EXPECT_NEAR(std::hypot(pole.x, pole.y), 0.0, kMetreTolerance);
    const glm::dvec3 south = Observer(-90, 123, 100000).ecef();
    EXPECT_NEAR(south.z, -kWgs84B - 100000.0, kMetreTolerance);
}

TEST(Observer, EnuFrameIsOrthonormalAndUpIsTheEllipsoidNormal) {
    for (double lat : {-90.0, -45.0, 0.0, 31.0, 89.999, 90.0}) {
        for (double lon : {-180.0, -104.0, 0.0, 179.9}) {
            const Observer o(lat, lon, 1000);
            const glm::dmat3 m = o.ecef_from_enu();
            for (int i = 0; i < 3; ++i) {
                EXPECT_NEAR(glm::length(m[i]), 1.0, kUnitTolerance);
                for (int j = i + 1; j < 3; ++j) {
                    EXPECT_NEAR(glm::dot(m[i], m[j]), 0.0, kUnitTolerance);
                }
            }
            // Right-handed: east x north = up.
            EXPECT_NEAR(glm::length(glm::cross(m[0], m[1]) - m[2]), 0.0, kUnitTolerance);
            const double phi = glm::radians(lat), lambda = glm::radians(lon);
            const glm::dvec3 normal{std::cos(phi) * std::cos(lambda),
                                    std::cos(phi) * std::sin(lambda), std::sin(phi)};
            EXPECT_NEAR(glm::length(m[2] - normal), 0.0, 1e-12) << lat << " " << lon;
        }
    }
}

TEST(Observer, RoundTripsThroughGeographicLib) {
    for (double h : {-400.0, 0.0, 11000.0, 100000.0}) {
        const Observer o(-33.9, 151.2, h);
        double lat, lon, height;
        GeographicLib::Geocentric::WGS84().Reverse(o.ecef().x, o.ecef().y, o.ecef().z, lat, lon,
                                                   height);
        EXPECT_NEAR(lat, -33.9, 1e-11);
        EXPECT_NEAR(lon, 151.2, 1e-11);
        EXPECT_NEAR(height, h, 1e-6);
    }
}

TEST(Topocentric, BodyAboveTheObserverIsAtTheZenith) {
    const Time t = TimeFromIso8601("2024-06-01T00:00:00Z");
    for (double lat : {-90.0, -20.0, 0.0, 45.0, 90.0}) {
        const Observer o(lat, 77.0, 500);
        const glm::dmat3 tod_from_ecef = glm::transpose(EcefFromTod(t));
        const glm::dvec3 up_tod = tod_from_ecef * o.ecef_from_enu()[2];
        const glm::dvec3 body = tod_from_ecef * o.ecef() + up_tod * 3.8e8;
        const Topocentric topo = TopocentricFromGeocentricTod(body, t, o, false);
        EXPECT_NEAR(topo.horizontal.elevation, glm::half_pi<double>(), 1e-9) << lat;
        EXPECT_NEAR(topo.horizontal.distance, 3.8e8, 1e-3);
    }
}

TEST(Topocentric, AzimuthIsFromNorthThroughEast) {
    EXPECT_NEAR(HorizontalFromEnu({0, 1, 0}).azimuth, 0.0, 1e-15);
    EXPECT_NEAR(HorizontalFromEnu({1, 0, 0}).azimuth, glm::half_pi<double>(), 1e-15);
    EXPECT_NEAR(HorizontalFromEnu({0, -1, 0}).azimuth, glm::pi<double>(), 1e-15);
    EXPECT_NEAR(HorizontalFromEnu({-1, 0, 0}).azimuth, 1.5 * glm::pi<double>(), 1e-15);
    EXPECT_NEAR(HorizontalFromEnu({1, 1, -std::sqrt(2.0)}).elevation, -glm::quarter_pi<double>(),
                1e-15);
}

TEST(Refraction, BennettAtTheHorizonAndZenith) {
    // Standard conditions: about 29' at the horizon (SPA's formula), 0 at the zenith.
    EXPECT_NEAR(glm::degrees(RefractionBennett(0.0, 1010.0, 10.0)) * 60.0, 28.9, 0.2);
    EXPECT_NEAR(RefractionBennett(glm::half_pi<double>(), 1010.0, 10.0), 0.0, 1e-6);
    // Scales with pressure / absolute temperature.
    EXPECT_NEAR(RefractionBennett(0.3, 505.0, 10.0) / RefractionBennett(0.3, 1010.0, 10.0), 0.5,
                1e-12);
    EXPECT_EQ(RefractionBennett(glm::radians(-5.0), 1010.0, 10.0), 0.0);
}

}  // namespace
}  // namespace zenith::geo
