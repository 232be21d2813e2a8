// The observer on or above the WGS84 ellipsoid, and the reduction of geocentric apparent
// positions to topocentric azimuth/elevation in the observer's local ENU frame.
//
// Azimuth is measured from true north, clockwise (north = 0, east = pi/2). Elevation is relative
// to the plane normal to the WGS84 ellipsoid at the observer (geodetic vertical), geometric unless
// refraction is requested. Polar motion (< 0.5") is ignored.
#pragma once

#include <glm/glm.hpp>
#include <stdexcept>

#include "zenith/base/error.h"
#include "zenith/geo/time.h"

namespace zenith::geo {

class ObserverError : public ArgumentError {
  public:
    using ArgumentError::ArgumentError;
};

class Observer {
  public:
    // Throws ObserverError naming the parameter, its value and the allowed range for latitude
    // outside [-90, 90], longitude outside [-540, 540] (wrapped to [-180, 180)), or a height
    // outside [-12000 m, 1e8 m], or any NaN/infinity.
    Observer(double lat_deg, double lon_deg, double height_m);
    // The observer at an ECEF position (metres, WGS84), keeping that position exactly rather
    // than the one its rounded geodetic coordinates would give back. Throws ObserverError for a
    // non-finite position or a height outside the range above.
    static Observer FromEcef(const glm::dvec3& ecef);

    double lat_deg() const { return lat_deg_; }
    double lon_deg() const { return lon_deg_; }
    double height_m() const { return height_m_; }

    // Position in ECEF (WGS84), metres, via GeographicLib::Geocentric.
    const glm::dvec3& ecef() const { return ecef_; }
    // Columns are the local east, north and up unit vectors in ECEF.
    const glm::dmat3& ecef_from_enu() const { return ecef_from_enu_; }
    glm::dmat3 enu_from_ecef() const { return glm::transpose(ecef_from_enu_); }

  private:
    double lat_deg_;
    double lon_deg_;
    double height_m_;
    glm::dvec3 ecef_;
    glm::dmat3 ecef_from_enu_;
};

struct Horizontal {
    glm::dvec3 direction_enu{0.0, 0.0, 1.0};  // unit vector toward the body
    double azimuth = 0.0;                     // radians, [0, 2pi), from north through east
    double elevation = 0.0;                   // radians
    double distance = 0.0;                    // metres, topocentric
};

// A position expressed in the TOD frame (true equator and equinox of date) as seen from the
// observer: topocentric vector and its right ascension/declination.
struct Topocentric {
    glm::dvec3 position_tod{0.0};  // metres, observer -> body, TOD axes
    double right_ascension = 0.0;  // radians, [0, 2pi)
    double declination = 0.0;      // radians
    Horizontal horizontal;
};

// Reduces a geocentric apparent TOD position (metres) to the observer. Applies diurnal
// aberration (observer velocity from Earth rotation, up to 0.32") unless disabled.
Topocentric TopocentricFromGeocentricTod(const glm::dvec3& geocentric_tod, const Time& t,
                                         const Observer& observer, bool diurnal_aberration = true);
// The same with EcefFromTod(t) already computed (earth_orientation.h), for many bodies at one
// instant: the sidereal time and nutation behind it are most of the cost.
Topocentric TopocentricFromGeocentricTod(const glm::dvec3& geocentric_tod,
                                         const glm::dmat3& ecef_from_tod, const Observer& observer,
                                         bool diurnal_aberration = true);

// Azimuth/elevation of a vector in the observer's ENU frame; distance is its length.
Horizontal HorizontalFromEnu(const glm::dvec3& enu);

// Atmospheric refraction at a geometric elevation (radians -> radians to add), the formula of
// Bennett (1982) as used by NREL SPA (Reda & Andreas 2004, Eq. 42), scaled by pressure and
// temperature. Returns 0 below the geometric elevation `below_horizon_limit` (SPA uses
// -(0.26667 + 0.5667) degrees for the Sun), where the formula is meaningless.
double RefractionBennett(double geometric_elevation, double pressure_hpa, double temperature_c,
                         double below_horizon_limit = -0.0145528);  // -0.8338 deg

}  // namespace zenith::geo
