// Atmospheric refraction traced through a model of the air, for any observer height: what the
// renderer draws the Sun, the Moon, the planets and the stars with (sky::FrameSetup::refraction).
//
// Bennett's formula (observer.h) fits refraction at the ground; an aircraft at 10 km sees
// stars down to the dip of its horizon, 3.2 deg below the astronomical one, through rays that
// pass below it, which no formula for the ground gives. So the ray is traced instead:
//  - The air: the layers of the 1976 US Standard Atmosphere (ISA, ICAO Doc 7488, up to
//    84.852 km geopotential), every temperature shifted by the same amount so that the sea-level
//    temperature is the one given, and hydrostatic pressure from the sea-level pressure given
//    (a METAR's QNH and its temperature reduced to sea level along ISA's lapse rate). Heights
//    are taken as geopotential (0.3 % off at 20 km).
//  - The refractivity n - 1 = kAirRefractivity p / p_ISA T_ISA / T: dry air at 550 nm (Edlen
//    1966), proportional to the density.
//  - A spherically stratified planet: along the ray n r cos(e) = k stays constant (Bouguer), and
//    the bending is the integral of -(dn/dr / n) k / sqrt(n^2 r^2 - k^2) dr along the path:
//    from the observer up to the top of the air when the ray rises, and for a ray leaving
//    below the horizontal, from its lowest point r_p (n(r_p) r_p = k) back to the observer plus
//    from r_p up to the top. r = r_a + x^2 takes the inverse square root away at both ends; each
//    stretch between the layers' boundaries is integrated by Gauss-Legendre.
// Not modelled: humidity (< 1 % of the refractivity at optical wavelengths), inversions and
// ducts (the path tracing assumes n r grows with r), dispersion (the colours' separation).
#pragma once

#include <array>
#include <optional>

#include "zenith/geo/standard_atmosphere.h"

namespace zenith::geo {

// (n - 1) of dry air at 550 nm, 15 deg C and 1013.25 hPa (Edlen 1966's dispersion formula).
inline constexpr double kAirRefractivity = 2.7783e-4;

// The air the rays are traced through (see the file comment).
struct RefractionAir {
    double sea_level_pressure_hpa = kIsaPressureHpa;  // QNH
    double sea_level_temperature_c = 15.0;
    // Throws zenith::ArgumentError for a pressure outside 850..1100 hPa or a temperature outside
    // -90..60 deg C (what a sea-level report can hold).
    void Validate() const;
    friend bool operator==(const RefractionAir&, const RefractionAir&) = default;
};

// The bending (rad, > 0 lifts the body) of the ray that reaches an observer `height_m` above a
// planet of `planet_radius_m` at `apparent_elevation` (rad, may be below the horizontal): the
// apparent elevation minus the geometric one of a body outside the air. None when that ray
// comes from the ground (below the horizon). Validates the air.
std::optional<double> TraceRefraction(const RefractionAir& air, double height_m,
                                      double apparent_elevation,
                                      double planet_radius_m = 6371000.0);

// TraceRefraction at 128 apparent elevations, from the lowest ray that clears the ground to the
// zenith, for one observer height; each body is then placed by interpolation (within 2" of the
// traced value, tests/geo/refraction_test.cpp).
class RefractionTable {
  public:
    RefractionTable(const RefractionAir& air, double height_m, double planet_radius_m = 6371000.0);

    // The apparent elevation of a body at `geometric_elevation` (rad); none when it is behind
    // the ground even after refraction.
    std::optional<double> Apparent(double geometric_elevation) const;
    // d(apparent) / d(geometric) there: how much refraction squeezes a disk vertically (about
    // 0.8 for the Sun on the horizon at sea level; 1 at the zenith). 1 when it is behind the
    // ground.
    double VerticalScale(double geometric_elevation) const;

    // The apparent elevation of the horizon (rad): the dip of the ray that grazes the ground,
    // with refraction (0 on the ground).
    double horizon() const { return apparent_.front(); }
    const RefractionAir& air() const { return air_; }
    double height_m() const { return height_m_; }
    double planet_radius_m() const { return planet_radius_m_; }

  private:
    static constexpr int kSamples = 128;
    RefractionAir air_;
    double height_m_;
    double planet_radius_m_;
    std::array<double, kSamples> apparent_{};
    std::array<double, kSamples> geometric_{};
};

}  // namespace zenith::geo
