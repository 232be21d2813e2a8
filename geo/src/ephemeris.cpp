#include "zenith/geo/ephemeris.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/constants.hpp>

#include "zenith/base/error.h"
#include "zenith/geo/angles.h"
#include "zenith/geo/earth_orientation.h"
#include "zenith/geo/moon.h"
#include "zenith/geo/sun.h"

namespace zenith::geo {
namespace {

BodyState MakeBody(const glm::dvec3& geocentric_tod, double radius, const Time& t,
                   const Observer& observer, const EphemerisOptions& options) {
    BodyState body;
    body.topocentric =
        TopocentricFromGeocentricTod(geocentric_tod, t, observer, options.diurnal_aberration);
    body.geocentric_distance = glm::length(geocentric_tod);
    body.angular_diameter = 2.0 * std::asin(radius / body.topocentric.horizontal.distance);
    body.elevation = body.topocentric.horizontal.elevation;
    if (options.refraction) {
        body.elevation += RefractionBennett(body.elevation, options.refraction->pressure_hpa,
                                            options.refraction->temperature_c);
    }
    return body;
}

}  // namespace

double PositionAngle(const glm::dvec3& from, const glm::dvec3& to, const glm::dvec3& pole) {
    // Tangent-plane basis at `from`: east = pole x from, north = from x east. The great circle
    // toward `to` leaves `from` along the component of `to` perpendicular to `from`.
    const glm::dvec3 east = glm::normalize(glm::cross(pole, from));
    const glm::dvec3 north = glm::cross(from, east);
    const glm::dvec3 toward = to - from * glm::dot(to, from);
    double pa = std::atan2(glm::dot(toward, east), glm::dot(toward, north));
    return pa < 0.0 ? pa + glm::two_pi<double>() : pa;
}

MoonPhase ComputeMoonPhase(const glm::dvec3& sun_tod, const glm::dvec3& moon_tod,
                           const glm::dvec3& zenith_tod) {
    MoonPhase phase;
    phase.elongation = AngleBetween(sun_tod, moon_tod);
    // Phase angle at the Moon between the directions to the Sun and to the Earth (Meeus 48.3).
    phase.phase_angle = AngleBetween(sun_tod - moon_tod, -moon_tod);
    phase.illuminated_fraction = 0.5 * (1.0 + std::cos(phase.phase_angle));
    const glm::dvec3 moon_dir = glm::normalize(moon_tod);
    const glm::dvec3 sun_dir = glm::normalize(sun_tod);
    const glm::dvec3 celestial_pole{0.0, 0.0, 1.0};
    phase.bright_limb_angle = PositionAngle(moon_dir, sun_dir, celestial_pole);
    // Waxing while the Moon is east of the Sun: its ecliptic longitude leads, which in equatorial
    // terms means the Sun lies to the west (bright limb position angle in (180, 360)).
    phase.waxing = phase.bright_limb_angle > glm::pi<double>();
    if (glm::length(zenith_tod) > 0.0) {
        const double parallactic =
            PositionAngle(moon_dir, glm::normalize(zenith_tod), celestial_pole);
        double chi_minus_q = phase.bright_limb_angle - parallactic;
        chi_minus_q = std::fmod(chi_minus_q + glm::two_pi<double>(), glm::two_pi<double>());
        phase.bright_limb_from_zenith = chi_minus_q;
    }
    return phase;
}

Ephemeris::Ephemeris(const StarCatalog* catalog, double star_epoch_s)
    : catalog_(catalog), star_epoch_s_(star_epoch_s) {
    Require("star_epoch_s", star_epoch_s, "s", Range::Closed(0.0, 86400.0));
}

SkyEphemeris Ephemeris::Compute(const Time& t, const Observer& observer,
                                const EphemerisOptions& options) const {
    SkyEphemeris result;
    result.time = t;
    const glm::dvec3 sun_tod = SunApparentTod(t.jd_tt);
    const glm::dvec3 moon_tod = MoonApparentTod(t.jd_tt);
    result.sun = MakeBody(sun_tod, kSunRadius, t, observer, options);
    result.moon = MakeBody(moon_tod, kMoonRadius, t, observer, options);

    const glm::dmat3 tod_from_ecef = glm::transpose(EcefFromTod(t));
    const glm::dvec3 zenith_tod = tod_from_ecef * observer.ecef_from_enu()[2];
    result.moon_phase = ComputeMoonPhase(sun_tod, moon_tod, zenith_tod);

    if (options.planets) {
        result.planets = PlanetsTopocentric(t, observer, options.diurnal_aberration);
        if (options.refraction) {
            for (PlanetPosition& p : result.planets) {
                p.elevation += RefractionBennett(p.elevation, options.refraction->pressure_hpa,
                                                 options.refraction->temperature_c);
            }
        }
    }

    if (catalog_ != nullptr) {
        std::vector<glm::dvec3> exact;
        if (star_epoch_s_ > 0.0) {
            const double step_days = star_epoch_s_ / kSecondsPerDay;
            const double epoch = std::floor(t.jd_tt / step_days) * step_days;
            if (epoch != cached_epoch_jd_tt_) {
                cached_directions_ = catalog_->ApparentTod(epoch);
                cached_epoch_jd_tt_ = epoch;
            }
        } else {
            exact = catalog_->ApparentTod(t.jd_tt);
        }
        const std::vector<glm::dvec3>& directions =
            star_epoch_s_ > 0.0 ? cached_directions_ : exact;
        const glm::dmat3 enu_from_tod = observer.enu_from_ecef() * EcefFromTod(t);
        const auto& stars = catalog_->stars();
        for (std::size_t i = 0; i < stars.size(); ++i) {
            StarState s;
            s.horizontal = HorizontalFromEnu(enu_from_tod * directions[i]);
            if (s.horizontal.elevation < options.star_min_elevation) continue;
            s.star = &stars[i];
            s.illuminance_lux = IlluminanceFromMagnitude(stars[i].magnitude_v);
            result.stars.push_back(s);
        }
        std::stable_sort(result.stars.begin(), result.stars.end(),
                         [](const StarState& a, const StarState& b) {
                             return a.star->magnitude_v < b.star->magnitude_v;
                         });
    }
    return result;
}

}  // namespace zenith::geo
