// Bright-star catalogue: Hipparcos-based star data as shipped by Debian's kstars-data
// (GPL, installed at set-up time, not committed), reduced to apparent directions of date.
#pragma once

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace zenith::geo {

class CatalogError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

struct Star {
    double ra_j2000 = 0.0;       // radians, ICRS, epoch J2000.0
    double dec_j2000 = 0.0;      // radians
    double pm_ra_mas_per_yr = 0.0;   // proper motion in RA * cos(dec), mas/yr
    double pm_dec_mas_per_yr = 0.0;  // mas/yr
    float magnitude_v = 0.0f;    // visual magnitude
    float b_minus_v = 0.0f;      // colour index
    std::uint32_t hd = 0;        // Henry Draper number, 0 if none
    std::string name;            // proper name where the catalogue has one
};

// Illuminance at the top of the atmosphere from a visual magnitude, lux
// (m = -14.18 - 2.5 log10(E / 1 lux), i.e. E(m=0) = 2.08e-6 lux).
double IlluminanceFromMagnitude(double magnitude_v);

// Linear sRGB (Rec. 709 primaries, unit luminance) of a black body at the temperature that B-V
// indicates (Ballesteros 2012), for tinting star sprites.
glm::dvec3 ColourFromBMinusV(double b_minus_v);
double TemperatureFromBMinusV(double b_minus_v);

class StarCatalog {
public:
    // Reads the catalogue files in `directory` (default: $ZENITH_STAR_DIR, else
    // /usr/share/kstars) down to `magnitude_limit`. Throws CatalogError naming the file and
    // what is wrong, and what to install when the files are missing.
    static StarCatalog Load(double magnitude_limit = 6.5, std::filesystem::path directory = {});

    const std::vector<Star>& stars() const { return stars_; }
    double magnitude_limit() const { return magnitude_limit_; }

    // Geocentric apparent unit vectors in TOD for all stars: proper motion to the date,
    // annual aberration, frame bias + precession + nutation.
    std::vector<glm::dvec3> ApparentTod(double jd_tt) const;

private:
    std::vector<Star> stars_;
    double magnitude_limit_ = 0.0;
};

}  // namespace zenith::geo
