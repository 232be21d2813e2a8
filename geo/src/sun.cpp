// The Sun's geocentric apparent position from the VSOP87 Earth series, following the chain of
// Meeus, Astronomical Algorithms (2nd ed. 1998), ch. 25 "higher accuracy", with IAU 2000B
// nutation and IAU 2006 obliquity in place of IAU 1980 and Lieske 1976.
//
// The series is VSOP87 version B (ecliptic and equinox of J2000; the copy available to the
// generator, Debian kstars-data, ships B, not D). It is precessed to the ecliptic and equinox of
// date with the IAU 2006 model through GCRS:
//   ecliptic(date) <- ecliptic(J2000) = E(t) E(J2000)^T,
//   E(t) = R3(-psi_bar) R1(phi_bar) R3(gamma_bar),
// the mean-ecliptic-of-date part of the Fukushima-Williams chain (IERS Conventions 2010, eq. 5.39).
// E(t) is obtained as TodFromEclipticOfDate(t)^T TodFromGcrs(t), in which nutation cancels.
//
// Light time needs no separate step for the Sun: in the heliocentric two-body picture the Sun
// does not move, and the annual aberration term (Meeus eq. 25.10) accounts for the Earth's motion
// during the 8.3 minutes (the Sun's own barycentric motion, ~13 m/s, shifts it by < 0.01").
//
// Accuracy (tests/geo/sun_test.cpp, against ERFA's eraEpv00 fitted to JPL DE405, 1950-2100): see
// the constants there; the truncation of the series alone is < 0.02" (vsop87b_earth.inc header).
//
// All functions expect finite Julian dates (TT); NaN propagates to NaN.
#include "zenith/geo/sun.h"

#include <cmath>
#include <numbers>

#include "vsop87.h"
#include "zenith/geo/angles.h"
#include "zenith/geo/earth_orientation.h"

namespace zenith::geo {
namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;

using detail::EarthHeliocentricEclipticJ2000;
using detail::FromSpherical;
using detail::GcrsFromEclipticJ2000;
using detail::VsopTerm;

#include "vsop87b_earth.inc"

// Mean ecliptic and equinox of date <- GCRS (IAU 2006, frame bias included).
glm::dmat3 EclipticOfDateFromGcrs(double jd_tt) {
    return glm::transpose(TodFromEclipticOfDate(jd_tt)) * TodFromGcrs(jd_tt);
}

// The apparent Sun referred to the mean equinox of date: geometric VSOP87 position, FK5 frame
// correction and annual aberration, but no nutation. Shared by the ecliptic and TOD outputs,
// which add nutation in their own way.
EclipticPosition SunAberratedMeanEcliptic(double jd_tt) {
    const EclipticPosition earth = EarthHeliocentricVsop87(jd_tt);
    // Geocentric Sun = heliocentric Earth reversed.
    double longitude = earth.longitude + std::numbers::pi;
    double latitude = -earth.latitude;

    // VSOP87 dynamical ecliptic and equinox -> FK5 (Meeus eq. 25.9 / 32.3).
    const double t = (jd_tt - kJ2000) / kDaysPerCentury;
    const double lambda_prime = longitude - (1.397 * t + 0.00031 * t * t) * kDegToRad;
    longitude += -0.09033 * kArcsecToRad;
    latitude += 0.03916 * kArcsecToRad * (std::cos(lambda_prime) - std::sin(lambda_prime));

    // Annual aberration, Meeus eq. 25.10: 20.4898" = kappa a sqrt(1 - e^2) makes -kappa a / R
    // exact for the transverse velocity of a Keplerian orbit (angular momentum / R).
    const double r_au = earth.distance / kAstronomicalUnit;
    longitude += -20.4898 * kArcsecToRad / r_au;

    return {WrapTwoPi(longitude), latitude, earth.distance};
}

}  // namespace

namespace detail {

// GCRS <- VSOP87 ecliptic and equinox of J2000, taken as the IAU 2006 ecliptic of J2000 (the
// VSOP87/DE200 and DE405-based frames differ by a few 0.01").
const glm::dmat3& GcrsFromEclipticJ2000() {
    static const glm::dmat3 m = glm::transpose(EclipticOfDateFromGcrs(kJ2000));
    return m;
}

glm::dvec3 EarthHeliocentricEclipticJ2000(double jd_tt) {
    const double tau = (jd_tt - kJ2000) / kDaysPerMillennium;
    return FromSpherical(EvaluateVsop(kEarthL, tau), EvaluateVsop(kEarthB, tau),
                         EvaluateVsop(kEarthR, tau) * kAstronomicalUnit);
}

}  // namespace detail

glm::dvec3 EarthHeliocentricGcrs(double jd_tt) {
    return GcrsFromEclipticJ2000() * EarthHeliocentricEclipticJ2000(jd_tt);
}

EclipticPosition EarthHeliocentricVsop87(double jd_tt) {
    const glm::dvec3 p = EclipticOfDateFromGcrs(jd_tt) * GcrsFromEclipticJ2000() *
                         EarthHeliocentricEclipticJ2000(jd_tt);
    const double distance = glm::length(p);
    return {WrapTwoPi(std::atan2(p.y, p.x)), std::asin(p.z / distance), distance};
}

EclipticPosition SunApparentEcliptic(double jd_tt) {
    EclipticPosition sun = SunAberratedMeanEcliptic(jd_tt);
    sun.longitude = WrapTwoPi(sun.longitude + Nutation2000B(jd_tt).dpsi);
    return sun;
}

glm::dvec3 SunApparentTod(double jd_tt) {
    const EclipticPosition sun = SunAberratedMeanEcliptic(jd_tt);
    return TodFromEclipticOfDate(jd_tt) * FromSpherical(sun.longitude, sun.latitude, sun.distance);
}

glm::dvec3 EarthVelocityGcrs(double jd_tt) {
    // Central difference of the heliocentric position in the fixed J2000 frame, so no frame
    // rotation enters the velocity. The step error is (omega h)^2 / 6 ~ 5e-7 relative for
    // h = 0.1 d; rounding of the Julian date (~5e-10 d) costs ~3e-9.
    constexpr double kStepDays = 0.1;
    const glm::dvec3 ahead = EarthHeliocentricEclipticJ2000(jd_tt + kStepDays);
    const glm::dvec3 behind = EarthHeliocentricEclipticJ2000(jd_tt - kStepDays);
    return GcrsFromEclipticJ2000() * (ahead - behind) / (2.0 * kStepDays * kSecondsPerDay);
}

}  // namespace zenith::geo
