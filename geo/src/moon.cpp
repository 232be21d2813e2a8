// The Moon's geocentric position from the ELP/MPP02 lunar theory (Chapront & Francou 2003,
// A&A 404, 735) with the constants fitted to JPL DE405 ("icor = 1" of the authors' Fortran
// ELPMPP02.for, which this file follows for the arguments, the fit corrections and the scaling).
//
// Frames. The series give V (longitude), U (latitude) and r in the mean ecliptic of date, V being
// counted from the departure point of J2000 (the Fortran rotates them to the fixed J2000 ecliptic
// with Laskar's P, Q). The longitude from the mean equinox of date is V + p_A, p_A the general
// precession in longitude (IAU 2006, Capitaine et al. 2003, eq. 39; ELP's own rate
// 5029.0966 - 0.29965 "/cy is the same to 0.001 "/cy).
//
// Apparent place (geocentric): the observer sees the Moon where it was one light time tau ~ 1.28 s
// earlier. The annual aberration the Earth's orbital velocity causes is common to the Moon and the
// Earth-Moon geometry (both are carried along with the barycentre), so in the geocentric frame only
// the Moon's motion relative to the Earth during tau matters: the apparent direction is the
// geometric position at t - tau (~0.7" shift). Nutation in longitude then refers it to the true
// equinox. Diurnal aberration (< 0.3") and the Sun's deflection (< 1 mas) are neglected.
//
// Truncation: see elpmpp02_series.inc and data/ephemeris/ELPMPP02.md (estimated < 0.5" RSS in
// longitude over 1950-2100). Accuracy against references: tests/geo/moon_test.cpp.
#include "zenith/geo/moon.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "zenith/geo/angles.h"
#include "zenith/geo/earth_orientation.h"

namespace zenith::geo {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kArcsecPerRad = 648000.0 / std::numbers::pi;
constexpr double kSpeedOfLight = 299792458.0;  // m/s

struct ElpMainTerm {
    std::array<std::int8_t, 4> i;  // multipliers of D, F, l, l'
    double a;                      // arcsec (V, U) or km (r)
    std::array<double, 5> b;       // partials B1..B5 for the fit corrections
};

struct ElpPertTerm {
    std::size_t power;              // the term is multiplied by t^power
    double s, c;                    // arcsec or km: s sin(arg) + c cos(arg)
    std::array<std::int8_t, 13> i;  // D, F, l, l', Me, V, EMB, Ma, J, Sa, U, N, zeta
};

#include "elpmpp02_series.inc"

double Dms(int deg, int min, double sec) { return (deg + min / 60.0 + sec / 3600.0) * kPi / 180.0; }

// Polynomial of degree 4 in t (Julian centuries TT from J2000), radians.
using Poly = std::array<double, 5>;

double Eval(const Poly& p, double t) {
    return p[0] + t * (p[1] + t * (p[2] + t * (p[3] + t * p[4])));
}

// Constants of ELPMPP02.for, subroutine INITIAL, with icor = 1 (fit to DE405 over 1950-2060).
struct ElpConstants {
    std::array<Poly, 4> delaunay{};  // D, F, l, l'
    std::array<Poly, 8> planets{};   // mean longitudes Me..Ne (degree 1)
    Poly zeta{};                     // W1 + precession
    Poly w1{};                       // Moon's mean longitude
    // Corrected main-problem amplitudes, in table order (at most the size of the tables).
    std::array<double, std::size(kElpMainLongitude)> main_v{};
    std::array<double, std::size(kElpMainLatitude)> main_u{};
    std::array<double, std::size(kElpMainDistance)> main_r{};
};

ElpConstants MakeConstants() {
    ElpConstants k;
    const double rad = kArcsecPerRad;
    // DE405 corrections to the constants (arcsec, arcsec/cy).
    const double dw1_0 = -0.07008, dw2_0 = 0.20794, dw3_0 = -0.07215;
    const double deart_0 = -0.00033, dperi = -0.00749, dw1_1 = -0.35106;
    const double dgam = 0.00085, de = -0.00006, deart_1 = 0.00732, dep = 0.00224;
    const double dw2_1 = 0.08017, dw3_1 = -0.04317, dw1_2 = -0.03743;

    Poly w1 = {Dms(218, 18, 59.95571 + dw1_0), (1732559343.73604 + dw1_1) / rad,
               (-6.8084 + dw1_2) / rad, (0.66040e-2 - 0.00018865) / rad,
               (-0.31690e-4 - 0.00001024) / rad};
    Poly w2 = {Dms(83, 21, 11.67475 + dw2_0), (14643420.3171 + dw2_1) / rad,
               (-38.2631 + 0.00470602) / rad, (-0.45047e-1 - 0.00025213) / rad, 0.21301e-3 / rad};
    Poly w3 = {Dms(125, 2, 40.39816 + dw3_0), (-6967919.5383 + dw3_1) / rad,
               (6.3590 - 0.00261070) / rad, (0.76250e-2 - 0.00010712) / rad, -0.35860e-4 / rad};
    const Poly eart = {Dms(100, 27, 59.13885 + deart_0), (129597742.29300 + deart_1) / rad,
                       -0.020200 / rad, 0.90000e-5 / rad, 0.15000e-6 / rad};
    const Poly peri = {Dms(102, 56, 14.45766 + dperi), 1161.24342 / rad, 0.529265 / rad,
                       -0.11814e-3 / rad, 0.11379e-4 / rad};

    // Mean motions of W2 and W3 follow from the corrected constants (INITIAL, "Corrections to
    // the mean motions of the Moon angles W2 and W3").
    const double am = 0.074801329;
    const double alpha = 0.002571881;
    const double dtasm = 2.0 * alpha / (3.0 * am);
    const double xa = 2.0 * alpha / 3.0;
    const double bp[2][5] = {
        {0.311079095, -0.4482398e-2, -0.110248500e-2, 0.1056062e-2, 0.50928e-4},
        {-0.103837907, 0.6682870e-3, -0.129807200e-2, -0.1780280e-3, -0.37342e-4}};
    for (int j = 0; j < 2; ++j) {
        Poly& w = j == 0 ? w2 : w3;
        const double x = w[1] / w1[1];
        const double y = am * bp[j][0] + xa * bp[j][4];
        const double correction = (x - y) * dw1_1 + (y / am) * deart_1 +
                                  w1[1] * (bp[j][1] * dgam + bp[j][2] * de + bp[j][3] * dep);
        w[1] += correction / rad;
    }

    for (std::size_t n = 0; n < 5; ++n) {
        k.delaunay[0][n] = w1[n] - eart[n];    // D
        k.delaunay[1][n] = w1[n] - w3[n];      // F
        k.delaunay[2][n] = w1[n] - w2[n];      // l
        k.delaunay[3][n] = eart[n] - peri[n];  // l'
    }
    k.delaunay[0][0] += kPi;

    // VSOP2000 mean longitudes of the planets (the EMB one is eart(0:1) without correction).
    const double p0[8][4] = {
        {252, 15, 3.216919, 538101628.66888},  {181, 58, 44.758419, 210664136.45777},
        {100, 27, 59.138850, 129597742.29300}, {355, 26, 3.642778, 68905077.65936},
        {34, 21, 5.379392, 10925660.57335},    {50, 4, 38.902495, 4399609.33632},
        {314, 3, 4.354234, 1542482.57845},     {304, 20, 56.808371, 786547.89700}};
    for (std::size_t p = 0; p < 8; ++p) {
        k.planets[p] = {Dms(static_cast<int>(p0[p][0]), static_cast<int>(p0[p][1]), p0[p][2]),
                        p0[p][3] / rad, 0.0, 0.0, 0.0};
    }
    const double dprec = -0.29965;  // IAU 2000A correction to the precession constant
    k.zeta = w1;
    k.zeta[1] += (5029.0966 + dprec) / rad;
    k.w1 = w1;

    // Corrections of the main-problem amplitudes through the partials (READFILE).
    const double delnu = (0.55604 + dw1_1) / rad / w1[1];
    const double dele = (0.01789 + de) / rad;
    const double delg = (-0.08066 + dgam) / rad;
    const double delnp = (-0.06424 + deart_1) / rad / w1[1];
    const double delep = (-0.12879 + dep) / rad;
    auto corrected = [&](const ElpMainTerm& term, bool distance) {
        const double tgv = term.b[0] + dtasm * term.b[4];
        double a = term.a;
        if (distance) a -= 2.0 * a * delnu / 3.0;
        return a + tgv * (delnp - am * delnu) + term.b[1] * delg + term.b[2] * dele +
               term.b[3] * delep;
    };
    for (std::size_t n = 0; n < std::size(kElpMainLongitude); ++n) {
        k.main_v[n] = corrected(kElpMainLongitude[n], false);
    }
    for (std::size_t n = 0; n < std::size(kElpMainLatitude); ++n) {
        k.main_u[n] = corrected(kElpMainLatitude[n], false);
    }
    for (std::size_t n = 0; n < std::size(kElpMainDistance); ++n) {
        k.main_r[n] = corrected(kElpMainDistance[n], true);
    }
    return k;
}

const ElpConstants& Constants() {
    static const ElpConstants k = MakeConstants();
    return k;
}

// Arguments of one instant: Delaunay D, F, l, l', 8 planetary longitudes, zeta.
struct Arguments {
    std::array<double, 13> a{};
};

Arguments MakeArguments(const ElpConstants& k, double t) {
    Arguments args;
    for (std::size_t n = 0; n < 4; ++n) args.a[n] = Eval(k.delaunay[n], t);
    for (std::size_t n = 0; n < 8; ++n) args.a[4 + n] = Eval(k.planets[n], t);
    args.a[12] = Eval(k.zeta, t);
    return args;
}

template <std::size_t N>
double SumMain(const ElpMainTerm (&terms)[N], const std::array<double, N>& amplitude,
               const Arguments& args, double phase) {
    double sum = 0.0;
    for (std::size_t n = N; n-- > 0;) {  // smallest terms last in the file; order is harmless
        const auto& i = terms[n].i;
        const double y =
            i[0] * args.a[0] + i[1] * args.a[1] + i[2] * args.a[2] + i[3] * args.a[3] + phase;
        sum += amplitude[n] * std::sin(y);
    }
    return sum;
}

template <std::size_t N>
double SumPert(const ElpPertTerm (&terms)[N], const Arguments& args, double t) {
    std::array<double, 4> by_power{};
    for (std::size_t n = N; n-- > 0;) {
        const ElpPertTerm& term = terms[n];
        double y = 0.0;
        for (std::size_t j = 0; j < 13; ++j) y += term.i[j] * args.a[j];
        by_power[term.power] += term.s * std::sin(y) + term.c * std::cos(y);
    }
    return by_power[0] + t * (by_power[1] + t * (by_power[2] + t * by_power[3]));
}

// General precession in longitude p_A, IAU 2006 (Capitaine et al. 2003, eq. 39), radians.
double GeneralPrecessionInLongitude(double t) {
    return (t * (5028.796195 +
                 t * (1.1054348 + t * (0.00007964 + t * (-0.000023857 + t * -0.0000000383))))) /
           kArcsecPerRad;
}

glm::dvec3 FromSpherical(const EclipticPosition& p) {
    const double cb = std::cos(p.latitude);
    return p.distance *
           glm::dvec3(cb * std::cos(p.longitude), cb * std::sin(p.longitude), std::sin(p.latitude));
}

// Geometric position at jd_tt followed back by the light time (fixed-point, 2 iterations reach
// 1e-9 s since the Moon's distance changes by < 0.1 km/s).
EclipticPosition LightTimeCorrected(double jd_tt) {
    EclipticPosition p = MoonGeometricEcliptic(jd_tt);
    for (int iteration = 0; iteration < 2; ++iteration) {
        const double tau = p.distance / kSpeedOfLight;
        p = MoonGeometricEcliptic(jd_tt - tau / kSecondsPerDay);
    }
    return p;
}

}  // namespace

EclipticPosition MoonGeometricEcliptic(double jd_tt) {
    const ElpConstants& k = Constants();
    const double t = (jd_tt - kJ2000) / kDaysPerCentury;
    const Arguments args = MakeArguments(k, t);

    const double v_arcsec =
        SumMain(kElpMainLongitude, k.main_v, args, 0.0) + SumPert(kElpPertLongitude, args, t);
    const double u_arcsec =
        SumMain(kElpMainLatitude, k.main_u, args, 0.0) + SumPert(kElpPertLatitude, args, t);
    // Distance is a cosine series: the Fortran adds pi/2 to the argument.
    const double r_km =
        SumMain(kElpMainDistance, k.main_r, args, 0.5 * kPi) + SumPert(kElpPertDistance, args, t);
    // ELP's distance unit follows its own semi-major axis; DE405's is a405 (ELPMPP02.for EVALUATE).
    constexpr double kA405 = 384747.9613701725;
    constexpr double kAElp = 384747.980674318;

    EclipticPosition p;
    p.longitude =
        WrapTwoPi(v_arcsec / kArcsecPerRad + Eval(k.w1, t) + GeneralPrecessionInLongitude(t));
    p.latitude = u_arcsec / kArcsecPerRad;
    p.distance = r_km * (kA405 / kAElp) * 1000.0;
    return p;
}

EclipticPosition MoonApparentEcliptic(double jd_tt) {
    EclipticPosition p = LightTimeCorrected(jd_tt);
    p.longitude = WrapTwoPi(p.longitude + Nutation2000B(jd_tt).dpsi);
    return p;
}

glm::dvec3 MoonApparentTod(double jd_tt) {
    // TodFromEclipticOfDate applies nutation itself, so it takes the mean-of-date position.
    return TodFromEclipticOfDate(jd_tt) * FromSpherical(LightTimeCorrected(jd_tt));
}

}  // namespace zenith::geo
