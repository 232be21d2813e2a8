// Bright-star catalogue: Hipparcos-based star data as shipped by Debian's kstars-data
// (GPL, installed at set-up time, not committed), reduced to apparent directions of date.
//
// Source files (data/stars/README.md has the byte layout and how it was verified):
//   namedstars.dat    1615 stars that KStars names, paired one to one with starnames.dat
//   unnamedstars.dat  41249 other stars
// Both hold Hipparcos (ESA 1997) positions in ICRS at the catalogue epoch J1991.25, complete to
// V = 8.0; Load() moves them to epoch J2000.0. There are 42864 stars in all, 8411 of them with
// V <= 6.5 (kstars-data 3.6 in Debian 12).
#pragma once

#include <cstdint>
#include <filesystem>
#include <glm/glm.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "zenith/base/error.h"

namespace zenith::geo {

class CatalogError : public InputError {
  public:
    using InputError::InputError;
};

struct Star {
    double ra_j2000 = 0.0;           // radians in [0, 2pi), ICRS, epoch J2000.0
    double dec_j2000 = 0.0;          // radians
    double pm_ra_mas_per_yr = 0.0;   // proper motion in RA * cos(dec), mas/yr
    double pm_dec_mas_per_yr = 0.0;  // mas/yr
    double parallax_mas = 0.0;       // Hipparcos parallax (not applied by ApparentTod)
    float magnitude_v = 0.0f;        // visual magnitude
    float b_minus_v = 0.0f;          // colour index
    std::uint32_t hd = 0;            // Henry Draper number, 0 if none
    std::string name;                // proper name where the catalogue has one ("Sirius")
    std::string designation;         // Bayer/Flamsteed as KStars abbreviates it ("alp CMa")
    std::string spectral_type;       // two characters, e.g. "A0", "K2"; may hold blanks
};

// Illuminance at the top of the atmosphere from a visual magnitude, lux:
// m = -14.18 - 2.5 log10(E / 1 lux) (Wikipedia, "Illuminance", section Astronomy), so
// E(m = 0) = 10^(-14.18 / 2.5) lux = 2.128e-6 lux. The zero point is uncertain by ~0.2 mag:
// with it the Sun (V = -26.74) gives 1.06e5 lux, against 1.28e5 lux for the solar illuminance
// constant.
inline constexpr double kZeroMagnitudeIlluminance = 2.1281390459827e-6;  // lux
double IlluminanceFromMagnitude(double magnitude_v);

// Linear sRGB (Rec. 709 primaries, unit luminance Y = 1) of a black body at the temperature that
// B-V indicates (Ballesteros 2012), for tinting star sprites. Components outside the gamut are
// clipped to 0 before normalising. NaN in, NaN out. About 4 us a call (Planck integrated over
// 95 wavelengths); the catalogue's B-V comes in steps of 0.01, so at most 441 distinct values
// after clamping: cache by value when tinting every star.
glm::dvec3 ColourFromBMinusV(double b_minus_v);
// Black-body temperature, kelvin, from B-V: Ballesteros (2012, EPL 97, 34008):
// T = 4600 K (1 / (0.92 BV + 1.7) + 1 / (0.92 BV + 0.62)).
// B-V is clamped to [kMinBMinusV, kMaxBMinusV] (see stars.cpp). NaN in, NaN out.
double TemperatureFromBMinusV(double b_minus_v);
inline constexpr double kMinBMinusV = -0.4;
inline constexpr double kMaxBMinusV = 4.0;

// $ZENITH_STAR_DIR when set and not empty, else /usr/share/kstars.
std::filesystem::path DefaultStarDirectory();

class StarCatalog {
  public:
    // Reads the catalogue files in `directory` (default: DefaultStarDirectory()) down to
    // `magnitude_limit` (stars with V <= limit). Throws CatalogError naming the file and what is
    // wrong, and what to install when the files are missing. Stars come sorted by magnitude,
    // brightest first (ties in file order).
    static StarCatalog Load(double magnitude_limit = 6.5, std::filesystem::path directory = {});

    const std::vector<Star>& stars() const { return stars_; }
    double magnitude_limit() const { return magnitude_limit_; }

    // Geocentric apparent unit vectors in TOD for all stars, in the order of stars(): proper
    // motion to the date (linear space motion, parallax and radial velocity ignored), annual
    // aberration (special-relativistic, with the Earth's heliocentric velocity), then frame
    // bias + precession + nutation (TodFromGcrs). Ignored: light deflection by the Sun
    // (< 10 mas beyond 45 degrees from the Sun), the Sun's motion about the barycentre in the
    // aberration (<= 10 mas) and annual parallax (<= 0.74 arcsec, alpha Centauri; 0.38 arcsec
    // for Sirius). Within 0.012 arcsec of ERFA's chain without parallax and deflection over
    // all stars to V = 6.5, 1950-2100 (tests/geo/stars_test.cpp); ~0.15 ms for 8,411 stars.
    std::vector<glm::dvec3> ApparentTod(double jd_tt) const;

  private:
    std::vector<Star> stars_;
    // Per star, parallel to stars_: GCRS unit vector at J2000.0 and its rate of change, rad/yr.
    std::vector<glm::dvec3> directions_j2000_;
    std::vector<glm::dvec3> motions_per_yr_;
    double magnitude_limit_ = 0.0;
};

}  // namespace zenith::geo
