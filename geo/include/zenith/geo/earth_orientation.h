// The Earth's orientation: IAU 2006 precession, IAU 2000B nutation, frame bias, obliquity, and
// Earth rotation (ERA, GMST, GAST). Frames are named target_from_source:
//   GCRS  geocentric celestial reference system (ICRS axes)
//   TOD   true equator and equinox of date
//   ECEF  Earth-fixed (ITRS without polar motion, which is < 0.5 arcsec and ignored)
// Angles in radians, time arguments as Julian dates (see time.h). These are low-level math
// functions: dates must be finite (validated where instants are made, time.h); NaN in gives NaN
// out. Accuracy against ERFA (IAU 2006/2000A), 1950-2100, is measured in
// tests/geo/earth_orientation_test.cpp.
#pragma once

#include <glm/glm.hpp>

#include "zenith/geo/time.h"

namespace zenith::geo {

struct Nutation {
    double dpsi = 0.0;  // nutation in longitude, radians
    double deps = 0.0;  // nutation in obliquity, radians
};

// IAU 2000B nutation (McCarthy & Luzum 2003): 77 luni-solar terms plus the fixed planetary offset
// (-0.135 mas, +0.388 mas). Matches eraNut00b to < 1 uas. Against IAU 2000A, 1950-2100: the
// celestial pole within 1.1 mas; dpsi alone differs by up to 2.5 mas (an equinox error that
// shows in GAST and the TOD axes but cancels in the Earth-fixed frame).
Nutation Nutation2000B(double jd_tt);

// Mean obliquity of the ecliptic of date, IAU 2006 (Hilton et al. 2006), radians.
double MeanObliquity2006(double jd_tt);

// Rotation GCRS -> true equator and equinox of date: frame bias, IAU 2006 precession
// (Fukushima-Williams angles) and IAU 2000B nutation, R1(-(eps_A + deps)) R3(-(psi_bar + dpsi))
// R1(phi_bar) R3(gamma_bar) as eraPn06 (to < 1 uas given the same nutation).
glm::dmat3 TodFromGcrs(double jd_tt);

// Rotation mean ecliptic and equinox of date -> TOD (true obliquity and nutation in longitude),
// for series such as ELP/MPP02 that give ecliptic-of-date coordinates.
glm::dmat3 TodFromEclipticOfDate(double jd_tt);

// Earth rotation angle (IAU 2000), radians in [0, 2pi).
double EarthRotationAngle(double jd_ut1);
// Greenwich mean sidereal time, IAU 2006 (consistent with ERA), radians in [0, 2pi).
double GreenwichMeanSiderealTime(double jd_ut1, double jd_tt);
// Greenwich apparent sidereal time: GMST + equation of the equinoxes (dpsi cos eps_A with the
// complementary terms above 1 uas), radians in [0, 2pi). Within 2.3 mas of eraGst06a (2000B).
double GreenwichApparentSiderealTime(double jd_ut1, double jd_tt);

// Rotation TOD -> ECEF: about the pole by GAST.
glm::dmat3 EcefFromTod(const Time& t);

}  // namespace zenith::geo
