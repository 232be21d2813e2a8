#include "zenith/geo/observer.h"

#include <GeographicLib/Geocentric.hpp>
#include <cmath>
#include <glm/gtc/constants.hpp>
#include <string>

#include "zenith/geo/angles.h"
#include "zenith/geo/earth_orientation.h"

namespace zenith::geo {
namespace {

constexpr double kEarthRotationRate = 7.292115e-5;  // rad/s (WGS84 / IERS)
constexpr double kSpeedOfLight = 299792458.0;       // m/s
constexpr double kMinHeight = -12000.0;             // below the deepest ocean trench
constexpr double kMaxHeight = 1.0e8;                // 100,000 km: beyond that "observer" is moot

[[noreturn]] void Reject(const char* name, double value, const char* expected) {
    throw ObserverError(std::string(name) + " = " + std::to_string(value) +
                        " is out of range (expected " + expected + ")");
}

}  // namespace

Observer Observer::FromEcef(const glm::dvec3& ecef) {
    if (!(std::isfinite(ecef.x) && std::isfinite(ecef.y) && std::isfinite(ecef.z))) {
        throw ObserverError("ecef = (" + std::to_string(ecef.x) + ", " + std::to_string(ecef.y) +
                            ", " + std::to_string(ecef.z) + ") m is not a finite position");
    }
    double lat = 0.0, lon = 0.0, h = 0.0;
    GeographicLib::Geocentric::WGS84().Reverse(ecef.x, ecef.y, ecef.z, lat, lon, h);
    Observer observer(lat, lon, h);
    observer.ecef_ = ecef;
    return observer;
}

Horizontal HorizontalFromEnu(const glm::dvec3& enu) {
    Horizontal h;
    h.distance = glm::length(enu);
    h.direction_enu = enu / h.distance;
    h.azimuth = WrapTwoPi(std::atan2(enu.x, enu.y));
    h.elevation = std::atan2(enu.z, std::hypot(enu.x, enu.y));
    return h;
}

Observer::Observer(double lat_deg, double lon_deg, double height_m)
    : lat_deg_(lat_deg), lon_deg_(lon_deg), height_m_(height_m) {
    if (!(lat_deg >= -90.0 && lat_deg <= 90.0)) Reject("lat_deg", lat_deg, "-90..90 degrees");
    if (!(lon_deg >= -540.0 && lon_deg <= 540.0))
        Reject("lon_deg", lon_deg, "-180..180 degrees; up to +-540 is wrapped");
    if (!(height_m >= kMinHeight && height_m <= kMaxHeight)) {
        Reject("height_m", height_m, "-12000..1e8 metres above the WGS84 ellipsoid");
    }
    // Longitude to [-180, 180): +180 and -180 are the same meridian.
    lon_deg_ = std::remainder(lon_deg, 360.0);
    if (lon_deg_ >= 180.0) lon_deg_ -= 360.0;

    const GeographicLib::Geocentric& earth = GeographicLib::Geocentric::WGS84();
    std::vector<double> rotation(9);
    double x, y, z;
    earth.Forward(lat_deg_, lon_deg_, height_m_, x, y, z, rotation);
    ecef_ = {x, y, z};
    // GeographicLib's M is row-major and maps local ENU to ECEF: ecef = M * enu.
    for (int row = 0; row < 3; ++row) {
        for (int col = 0; col < 3; ++col) {
            ecef_from_enu_[col][row] = rotation[static_cast<std::size_t>(3 * row + col)];
        }
    }
}

Topocentric TopocentricFromGeocentricTod(const glm::dvec3& geocentric_tod, const Time& t,
                                         const Observer& observer, bool diurnal_aberration) {
    return TopocentricFromGeocentricTod(geocentric_tod, EcefFromTod(t), observer,
                                        diurnal_aberration);
}

Topocentric TopocentricFromGeocentricTod(const glm::dvec3& geocentric_tod,
                                         const glm::dmat3& ecef_from_tod, const Observer& observer,
                                         bool diurnal_aberration) {
    const glm::dmat3 tod_from_ecef = glm::transpose(ecef_from_tod);
    const glm::dvec3 observer_tod = tod_from_ecef * observer.ecef();

    Topocentric topo;
    topo.position_tod = geocentric_tod - observer_tod;
    if (diurnal_aberration) {
        // First-order aberration by the observer's velocity from Earth rotation: the apparent
        // direction tilts toward the velocity by v/c (0.32" at the equator).
        const glm::dvec3 omega{0.0, 0.0, kEarthRotationRate};
        const glm::dvec3 velocity_tod = tod_from_ecef * glm::cross(omega, observer.ecef());
        const double distance = glm::length(topo.position_tod);
        const glm::dvec3 u = topo.position_tod / distance;
        const glm::dvec3 beta = velocity_tod / kSpeedOfLight;
        topo.position_tod = glm::normalize(u + beta - u * glm::dot(u, beta)) * distance;
    }
    const glm::dvec3& p = topo.position_tod;
    topo.right_ascension = WrapTwoPi(std::atan2(p.y, p.x));
    topo.declination = std::atan2(p.z, std::hypot(p.x, p.y));
    topo.horizontal = HorizontalFromEnu(observer.enu_from_ecef() * (ecef_from_tod * p));
    return topo;
}

double RefractionBennett(double geometric_elevation, double pressure_hpa, double temperature_c,
                         double below_horizon_limit) {
    if (!(geometric_elevation >= below_horizon_limit)) return 0.0;
    const double e0_deg = glm::degrees(geometric_elevation);
    // Reda & Andreas (2004) Eq. 42, degrees.
    const double refraction_deg = (pressure_hpa / 1010.0) * (283.0 / (273.0 + temperature_c)) *
                                  1.02 /
                                  (60.0 * std::tan(glm::radians(e0_deg + 10.3 / (e0_deg + 5.11))));
    return glm::radians(refraction_deg);
}

}  // namespace zenith::geo
