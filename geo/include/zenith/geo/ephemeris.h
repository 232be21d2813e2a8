// Everything the sky needs to know about where the Sun, the Moon, the planets and the stars are,
// for one instant and one observer.
#pragma once

#include <glm/glm.hpp>
#include <optional>
#include <vector>

#include "zenith/geo/observer.h"
#include "zenith/geo/planets.h"
#include "zenith/geo/stars.h"
#include "zenith/geo/time.h"

namespace zenith::geo {

inline constexpr double kSunRadius = 695700000.0;  // m, IAU 2015 nominal solar radius

struct RefractionOptions {
    double pressure_hpa = 1010.0;
    double temperature_c = 10.0;
};

struct EphemerisOptions {
    std::optional<RefractionOptions> refraction;  // elevations are geometric when absent
    bool diurnal_aberration = true;
    double star_min_elevation = 0.0;  // radians: stars below are dropped from the result
    // Mercury to Neptune (planets.h). Between 1950 and 2100 only (the window the truncated
    // VSOP87 series are measured for); outside it SkyEphemeris::planets stays empty.
    bool planets = true;
};

struct BodyState {
    Topocentric topocentric;           // apparent, topocentric, TOD + horizontal
    double elevation = 0.0;            // radians: geometric, or refracted if requested
    double angular_diameter = 0.0;     // radians, topocentric
    double geocentric_distance = 0.0;  // metres
};

struct MoonPhase {
    double illuminated_fraction = 0.0;  // geocentric, 0..1 (Meeus Eq. 48.1)
    double phase_angle = 0.0;           // radians, Sun-Moon-Earth angle, geocentric
    double elongation = 0.0;            // radians, geocentric Sun-Moon separation
    // Position angle of the midpoint of the bright limb, from the north celestial pole through
    // east (Meeus Eq. 48.5), geocentric as in almanacs.
    double bright_limb_angle = 0.0;
    // The same angle for this observer, measured from the direction toward the zenith (Meeus
    // ch. 48: chi - q, q the parallactic angle), for lighting the disk in an upright view.
    double bright_limb_from_zenith = 0.0;
    bool waxing = true;
};

struct StarState {
    const Star* star = nullptr;
    Horizontal horizontal;
    double illuminance_lux = 0.0;  // top of atmosphere
};

struct SkyEphemeris {
    Time time;
    BodyState sun;
    BodyState moon;
    MoonPhase moon_phase;
    std::vector<StarState> stars;  // above star_min_elevation, brightest first
    // Mercury ... Neptune in kSkyPlanets order, all of them whatever their elevation; empty when
    // EphemerisOptions::planets is off or the instant is outside 1950-2100.
    std::vector<PlanetPosition> planets;
};

// Phase and bright limb from geocentric apparent positions (TOD, metres). `zenith_tod` is the
// observer's zenith direction in TOD (unit); bright_limb_from_zenith is 0 if it is zero.
MoonPhase ComputeMoonPhase(const glm::dvec3& sun_tod, const glm::dvec3& moon_tod,
                           const glm::dvec3& zenith_tod = glm::dvec3(0.0));

// Position angle of the direction from `from` toward `to` on the celestial sphere, measured
// from `pole` through east (both unit vectors; pole is the north celestial pole or the zenith).
double PositionAngle(const glm::dvec3& from, const glm::dvec3& to, const glm::dvec3& pole);

class Ephemeris {
  public:
    // The catalogue is optional; without it SkyEphemeris::stars stays empty. It must outlive
    // this object.
    //
    // star_epoch_s > 0 computes the stars' apparent places (proper motion, aberration,
    // precession-nutation: ~0.9 ms for 8,400 stars) at TT instants that are whole multiples of
    // it and keeps the last set; the Earth's rotation and the observer are applied exactly at
    // every Compute. So a result depends only on its own time and place, never on which calls
    // came before (replayed, resumed and sharded frames match), and the stars are off by at most
    // the drift of apparent places over star_epoch_s (< 0.02"/s). 0: exact places every call.
    // With a cache, an Ephemeris must not be shared between threads.
    explicit Ephemeris(const StarCatalog* catalog = nullptr, double star_epoch_s = 0.0);

    SkyEphemeris Compute(const Time& t, const Observer& observer,
                         const EphemerisOptions& options = {}) const;

  private:
    const StarCatalog* catalog_;
    double star_epoch_s_;
    mutable double cached_epoch_jd_tt_ = -1.0;  // < 0: nothing cached
    mutable std::vector<glm::dvec3> cached_directions_;
};

}  // namespace zenith::geo
