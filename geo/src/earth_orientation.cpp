// IAU 2000B nutation, IAU 2006 precession (Fukushima-Williams angles with frame bias), and Earth
// rotation (ERA 2000, GMST 2006, GAST with the equation of the equinoxes).
//
// References:
//   McCarthy & Luzum 2003, Cel. Mech. Dyn. Astr. 85, 37 (IAU 2000B nutation).
//   Simon et al. 1994, A&A 282, 663 (linear Delaunay arguments used by 2000B).
//   Hilton et al. 2006, Celest. Mech. Dyn. Astr. 94, 351 (IAU 2006 precession, obliquity).
//   Capitaine, Wallace & Chapront 2003, A&A 412, 567 (P03 precession); Fukushima 2003, AJ 126, 494
//   and Capitaine et al. 2006 for the Fukushima-Williams angles including frame bias.
//   IERS Conventions 2010 (IERS TN 36), ch. 5: eqs. 5.15 (ERA), 5.32 (GMST), 5.30 and Table 5.2e
//   (equation of the equinoxes and its complementary terms).
//
// All functions expect finite Julian dates; NaN propagates to NaN (no validation here: input
// instants are validated where they are made, in time.h).
#include "zenith/geo/earth_orientation.h"

#include <array>
#include <cmath>
#include <iterator>
#include <numbers>

#include "zenith/geo/angles.h"

namespace zenith::geo {
namespace {

constexpr double kMicroarcsecToRad = kArcsecToRad * 1e-6;
constexpr double kArcsecPerTurn = 1296000.0;

// Passive (frame) rotations about x and z, as in the IERS Conventions: R1(a) and R3(a) rotate the
// coordinate axes by +a, so a fixed vector's coordinates turn by -a. glm is column-major, hence
// the element order below (m[column][row]).
glm::dmat3 R1(double a) {
    const double c = std::cos(a);
    const double s = std::sin(a);
    glm::dmat3 m(1.0);
    m[1][1] = c;
    m[2][1] = s;
    m[1][2] = -s;
    m[2][2] = c;
    return m;
}

glm::dmat3 R3(double a) {
    const double c = std::cos(a);
    const double s = std::sin(a);
    glm::dmat3 m(1.0);
    m[0][0] = c;
    m[1][0] = s;
    m[0][1] = -s;
    m[1][1] = c;
    return m;
}

double CenturiesSinceJ2000(double jd) { return (jd - kJ2000) / kDaysPerCentury; }

// Delaunay arguments l, l', F, D, Omega. IAU 2000B defines them as the linear part of Simon et al.
// (1994): the higher-order terms are absorbed in the fit and adding them would move the result away
// from the standard model (by up to ~0.1 mas at |t| = 1).
struct Delaunay {
    std::array<double, 5> arg{};  // radians
};

Delaunay DelaunayArguments2000B(double t) {
    // (arcsec at J2000, arcsec per Julian century), Simon et al. 1994 via McCarthy & Luzum 2003.
    constexpr std::array<std::array<double, 2>, 5> kPoly = {{
        {485868.249036, 1717915923.2178},  // l: mean anomaly of the Moon
        {1287104.79305, 129596581.0481},   // l': mean anomaly of the Sun
        {335779.526232, 1739527262.8478},  // F: Moon's mean argument of latitude
        {1072260.70369, 1602961601.2090},  // D: mean elongation of the Moon from the Sun
        {450160.398036, -6962890.5431},    // Omega: Moon's mean ascending node
    }};
    Delaunay d;
    for (std::size_t i = 0; i < kPoly.size(); ++i) {
        // fmod in arcseconds before scaling keeps the full double precision of the angle.
        d.arg[i] = std::fmod(kPoly[i][0] + kPoly[i][1] * t, kArcsecPerTurn) * kArcsecToRad;
    }
    return d;
}

// One luni-solar term of IAU 2000B (IERS Conventions 2010, Table 5.3a/b truncated to the 77 terms
// of McCarthy & Luzum 2003). Amplitudes in microarcseconds, rates in microarcseconds per century:
//   dpsi += (psi_sin + psi_sin_t t) sin(arg) + psi_cos cos(arg)
//   deps += (eps_cos + eps_cos_t t) cos(arg) + eps_sin sin(arg)
struct NutationTerm {
    std::array<int, 5> n;  // multipliers of l, l', F, D, Omega
    double psi_sin, psi_sin_t, psi_cos;
    double eps_cos, eps_cos_t, eps_sin;
};

// clang-format off
constexpr NutationTerm kNutation2000B[] = {
    {{ 0,  0,  0,  0,  1}, -17206416.1, -17466.6, 3338.6, 9205233.1, 908.6, 1537.7},
    {{ 0,  0,  2, -2,  2}, -1317090.6, -167.5, -1369.6, 573033.6, -301.5, -458.7},
    {{ 0,  0,  2,  0,  2}, -227641.3, -23.4, 279.6, 97845.9, -48.5, 137.4},
    {{ 0,  0,  0,  0,  2}, 207455.4, 20.7, -69.8, -89749.2, 47.0, -29.1},
    {{ 0,  1,  0,  0,  0}, 147587.7, -363.3, 1181.7, 7387.1, -18.4, -192.4},
    {{ 0,  1,  2, -2,  2}, -51682.1, 122.6, -52.4, 22438.6, -67.7, -17.4},
    {{ 1,  0,  0,  0,  0}, 71115.9, 7.3, -87.2, -675.0, 0.0, 35.8},
    {{ 0,  0,  2,  0,  1}, -38729.8, -36.7, 38.0, 20072.8, 1.8, 31.8},
    {{ 1,  0,  2,  0,  2}, -30146.1, -3.6, 81.6, 12902.5, -6.3, 36.7},
    {{ 0, -1,  2, -2,  2}, 21582.9, -49.4, 11.1, -9592.9, 29.9, 13.2},
    {{ 0,  0,  2, -2,  1}, 12822.7, 13.7, 18.1, -6898.2, -0.9, 3.9},
    {{-1,  0,  2,  0,  2}, 12345.7, 1.1, 1.9, -5331.1, 3.2, -0.4},
    {{-1,  0,  0,  2,  0}, 15699.4, 1.0, -16.8, -123.5, 0.0, 8.2},
    {{ 1,  0,  0,  0,  1}, 6311.0, 6.3, 2.7, -3322.8, 0.0, -0.9},
    {{-1,  0,  0,  0,  1}, -5797.6, -6.3, -18.9, 3142.9, 0.0, -7.5},
    {{-1,  0,  2,  2,  2}, -5964.1, -1.1, 14.9, 2554.3, -1.1, 6.6},
    {{ 1,  0,  2,  0,  1}, -5161.3, -4.2, 12.9, 2636.6, 0.0, 7.8},
    {{-2,  0,  2,  0,  1}, 4589.3, 5.0, 3.1, -2423.6, -1.0, 2.0},
    {{ 0,  0,  0,  2,  0}, 6338.4, 1.1, -15.0, -122.0, 0.0, 2.9},
    {{ 0,  0,  2,  2,  2}, -3857.1, -0.1, 15.8, 1645.2, -1.1, 6.8},
    {{ 0, -2,  2, -2,  2}, 3248.1, 0.0, 0.0, -1387.0, 0.0, 0.0},
    {{-2,  0,  0,  2,  0}, -4772.2, 0.0, -1.8, 47.7, 0.0, -2.5},
    {{ 2,  0,  2,  0,  2}, -3104.6, -0.1, 13.1, 1323.8, -1.1, 5.9},
    {{ 1,  0,  2, -2,  2}, 2859.3, 0.0, -0.1, -1233.8, 1.0, -0.3},
    {{-1,  0,  2,  0,  1}, 2044.1, 2.1, 1.0, -1075.8, 0.0, -0.3},
    {{ 2,  0,  0,  0,  0}, 2924.3, 0.0, -7.4, -60.9, 0.0, 1.3},
    {{ 0,  0,  2,  0,  0}, 2588.7, 0.0, -6.6, -55.0, 0.0, 1.1},
    {{ 0,  1,  0,  0,  1}, -1405.3, -2.5, 7.9, 855.1, -0.2, -4.5},
    {{-1,  0,  0,  2,  1}, 1516.4, 1.0, 1.1, -800.1, 0.0, -0.1},
    {{ 0,  2,  2, -2,  2}, -1579.4, 7.2, -1.6, 685.0, -4.2, -0.5},
    {{ 0,  0, -2,  2,  0}, 2178.3, 0.0, 1.3, -16.7, 0.0, 1.3},
    {{ 1,  0,  0, -2,  1}, -1287.3, -1.0, -3.7, 695.3, 0.0, -1.4},
    {{ 0, -1,  0,  0,  1}, -1265.4, 1.1, 6.3, 641.5, 0.0, 2.6},
    {{-1,  0,  2,  2,  1}, -1020.4, 0.0, 2.5, 522.2, 0.0, 1.5},
    {{ 0,  2,  0,  0,  0}, 1670.7, -8.5, -1.0, 16.8, -0.1, 1.0},
    {{ 1,  0,  2,  2,  2}, -769.1, 0.0, 4.4, 326.8, 0.0, 1.9},
    {{-2,  0,  2,  0,  0}, -1102.4, 0.0, -1.4, 10.4, 0.0, 0.2},
    {{ 0,  1,  2,  0,  2}, 756.6, -2.1, -1.1, -325.0, 0.0, -0.5},
    {{ 0,  0,  2,  2,  1}, -663.7, -1.1, 2.5, 335.3, 0.0, 1.4},
    {{ 0, -1,  2,  0,  2}, -714.1, 2.1, 0.8, 307.0, 0.0, 0.4},
    {{ 0,  0,  0,  2,  1}, -630.2, -1.1, 0.2, 327.2, 0.0, 0.4},
    {{ 1,  0,  2, -2,  1}, 580.0, 1.0, 0.2, -304.5, 0.0, -0.1},
    {{ 2,  0,  2, -2,  2}, 644.3, 0.0, -0.7, -276.8, 0.0, -0.4},
    {{-2,  0,  0,  2,  1}, -577.4, -1.1, -1.5, 304.1, 0.0, -0.5},
    {{ 2,  0,  2,  0,  1}, -535.0, 0.0, 2.1, 269.5, 0.0, 1.2},
    {{ 0, -1,  2, -2,  1}, -475.2, -1.1, -0.3, 271.9, 0.0, -0.3},
    {{ 0,  0,  0, -2,  1}, -494.0, -1.1, -2.1, 272.0, 0.0, -0.9},
    {{-1, -1,  0,  2,  0}, 735.0, 0.0, -0.8, -5.1, 0.0, 0.4},
    {{ 2,  0,  0, -2,  1}, 406.5, 0.0, 0.6, -220.6, 0.0, 0.1},
    {{ 1,  0,  0,  2,  0}, 657.9, 0.0, -2.4, -19.9, 0.0, 0.2},
    {{ 0,  1,  2, -2,  1}, 357.9, 0.0, 0.5, -190.0, 0.0, 0.1},
    {{ 1, -1,  0,  0,  0}, 472.5, 0.0, -0.6, -4.1, 0.0, 0.3},
    {{-2,  0,  2,  0,  2}, -307.5, 0.0, -0.2, 131.3, 0.0, -0.1},
    {{ 3,  0,  2,  0,  2}, -290.4, 0.0, 1.5, 123.3, 0.0, 0.7},
    {{ 0, -1,  0,  2,  0}, 434.8, 0.0, -1.0, -8.1, 0.0, 0.2},
    {{ 1, -1,  2,  0,  2}, -287.8, 0.0, 0.8, 123.2, 0.0, 0.4},
    {{ 0,  0,  0,  1,  0}, -423.0, 0.0, 0.5, -2.0, 0.0, -0.2},
    {{-1, -1,  2,  2,  2}, -281.9, 0.0, 0.7, 120.7, 0.0, 0.3},
    {{-1,  0,  2,  0,  0}, -405.6, 0.0, 0.5, 4.0, 0.0, -0.2},
    {{ 0, -1,  2,  2,  2}, -264.7, 0.0, 1.1, 112.9, 0.0, 0.5},
    {{-2,  0,  0,  0,  1}, -229.4, 0.0, -1.0, 126.6, 0.0, -0.4},
    {{ 1,  1,  2,  0,  2}, 248.1, 0.0, -0.7, -106.2, 0.0, -0.3},
    {{ 2,  0,  0,  0,  1}, 217.9, 0.0, -0.2, -112.9, 0.0, -0.2},
    {{-1,  1,  0,  1,  0}, 327.6, 0.0, 0.1, -0.9, 0.0, 0.0},
    {{ 1,  1,  0,  0,  0}, -338.9, 0.0, 0.5, 3.5, 0.0, -0.2},
    {{ 1,  0,  2,  0,  0}, 333.9, 0.0, -1.3, -10.7, 0.0, 0.1},
    {{-1,  0,  2, -2,  1}, -198.7, 0.0, -0.6, 107.3, 0.0, -0.2},
    {{ 1,  0,  0,  0,  2}, -198.1, 0.0, 0.0, 85.4, 0.0, 0.0},
    {{-1,  0,  0,  1,  0}, 402.6, 0.0, -35.3, -55.3, 0.0, -13.9},
    {{ 0,  0,  2,  1,  2}, 166.0, 0.0, -0.5, -71.0, 0.0, -0.2},
    {{-1,  0,  2,  4,  2}, -152.1, 0.0, 0.9, 64.7, 0.0, 0.4},
    {{-1,  1,  0,  1,  1}, 131.4, 0.0, 0.0, -70.0, 0.0, 0.0},
    {{ 0, -2,  2, -2,  1}, -128.3, 0.0, 0.0, 67.2, 0.0, 0.0},
    {{ 1,  0,  2,  2,  1}, -133.1, 0.0, 0.8, 66.3, 0.0, 0.4},
    {{-2,  0,  2,  2,  2}, 138.3, 0.0, -0.2, -59.4, 0.0, -0.2},
    {{-1,  0,  0,  0,  2}, 140.5, 0.0, 0.4, -61.0, 0.0, 0.2},
    {{ 1,  1,  2, -2,  2}, 129.0, 0.0, 0.0, -55.6, 0.0, 0.0},
};
// clang-format on
static_assert(std::size(kNutation2000B) == 77, "IAU 2000B has 77 luni-solar terms");

// Fixed offsets standing in for the omitted planetary terms, in the values optimised for the
// rigorous bias-precession-nutation chain (Luzum 2001, as adopted by SOFA/ERFA), not the
// "total nutation" values -1.5835/+1.6339 mas quoted in McCarthy & Luzum 2003.
constexpr double kPlanetaryDpsi = -0.135e-3 * kArcsecToRad;
constexpr double kPlanetaryDeps = 0.388e-3 * kArcsecToRad;

struct FukushimaWilliams {
    double gamma_bar, phi_bar, psi_bar, eps_a;  // radians
};

// IAU 2006 Fukushima-Williams bias-precession angles (Hilton et al. 2006, Table 1; IERS
// Conventions 2010, eq. 5.40), arcseconds, t in Julian centuries TT.
FukushimaWilliams FukushimaWilliams2006(double jd_tt) {
    const double t = CenturiesSinceJ2000(jd_tt);
    FukushimaWilliams fw;
    fw.gamma_bar =
        (-0.052928 +
         (10.556378 + (0.4932044 + (-0.00031238 + (-0.000002788 + 0.0000000260 * t) * t) * t) * t) *
             t) *
        kArcsecToRad;
    fw.phi_bar =
        (84381.412819 +
         (-46.811016 + (0.0511268 + (0.00053289 + (-0.000000440 - 0.0000000176 * t) * t) * t) * t) *
             t) *
        kArcsecToRad;
    fw.psi_bar =
        (-0.041775 + (5038.481484 +
                      (1.5584175 + (-0.00018522 + (-0.000026452 - 0.0000000148 * t) * t) * t) * t) *
                         t) *
        kArcsecToRad;
    fw.eps_a = MeanObliquity2006(jd_tt);
    return fw;
}

// Complementary terms of the equation of the equinoxes (IERS Conventions 2010, Table 5.2e), the
// terms above 1 microarcsecond: the full series adds < 6 uas beyond these.
double EquationOfEquinoxesComplement(double t) {
    struct Term {
        std::array<int, 5> n;  // multipliers of l, l', F, D, Omega
        double sin_uas;
    };
    constexpr Term kTerms[] = {
        {{0, 0, 0, 0, 1}, 2640.96}, {{0, 0, 0, 0, 2}, 63.52},  {{0, 0, 2, -2, 3}, 11.75},
        {{0, 0, 2, -2, 1}, 11.21},  {{0, 0, 2, -2, 2}, -4.55}, {{0, 0, 2, 0, 3}, 2.02},
        {{0, 0, 2, 0, 1}, 1.98},    {{0, 0, 0, 0, 3}, -1.72},  {{0, 1, 0, 0, 1}, -1.41},
        {{0, 1, 0, 0, -1}, -1.26},
    };
    constexpr double kOmegaRateTermUas = -0.87;  // t * sin(Omega)
    const Delaunay d = DelaunayArguments2000B(t);
    double sum = 0.0;
    for (const Term& term : kTerms) {
        double arg = 0.0;
        for (std::size_t j = 0; j < 5; ++j) arg += term.n[j] * d.arg[j];
        sum += term.sin_uas * std::sin(arg);
    }
    sum += kOmegaRateTermUas * t * std::sin(d.arg[4]);
    return sum * kMicroarcsecToRad;
}

}  // namespace

Nutation Nutation2000B(double jd_tt) {
    const double t = CenturiesSinceJ2000(jd_tt);
    const Delaunay d = DelaunayArguments2000B(t);
    double dpsi_uas = 0.0;
    double deps_uas = 0.0;
    // Smallest terms first, so they are not lost against the 17" leading term.
    for (auto it = std::rbegin(kNutation2000B); it != std::rend(kNutation2000B); ++it) {
        double arg = 0.0;
        for (std::size_t j = 0; j < 5; ++j) arg += it->n[j] * d.arg[j];
        const double s = std::sin(arg);
        const double c = std::cos(arg);
        dpsi_uas += (it->psi_sin + it->psi_sin_t * t) * s + it->psi_cos * c;
        deps_uas += (it->eps_cos + it->eps_cos_t * t) * c + it->eps_sin * s;
    }
    return {dpsi_uas * kMicroarcsecToRad + kPlanetaryDpsi,
            deps_uas * kMicroarcsecToRad + kPlanetaryDeps};
}

double MeanObliquity2006(double jd_tt) {
    // Hilton et al. 2006, eq. 39 (IERS Conventions 2010, eq. 5.40), arcseconds.
    const double t = CenturiesSinceJ2000(jd_tt);
    return (84381.406 +
            (-46.836769 +
             (-0.0001831 + (0.00200340 + (-0.000000576 - 0.0000000434 * t) * t) * t) * t) *
                t) *
           kArcsecToRad;
}

glm::dmat3 TodFromGcrs(double jd_tt) {
    // IERS Conventions 2010, eq. 5.39 with nutation added to psi_bar and eps_A (eq. 5.40 ff.):
    // N P B = R1(-(eps_A + deps)) R3(-(psi_bar + dpsi)) R1(phi_bar) R3(gamma_bar), as eraFw2m.
    // The IAU 2006 adjustments to IAU 2000 nutation (eraNut06a: factors 1 + 0.4697e-6 - 2.7774e-6
    // t) are left out: < 0.06 mas over 1900-2100, well inside 2000B's own 1 mas.
    const FukushimaWilliams fw = FukushimaWilliams2006(jd_tt);
    const Nutation n = Nutation2000B(jd_tt);
    return R1(-(fw.eps_a + n.deps)) * R3(-(fw.psi_bar + n.dpsi)) * R1(fw.phi_bar) *
           R3(fw.gamma_bar);
}

glm::dmat3 TodFromEclipticOfDate(double jd_tt) {
    // Ecliptic of date -> true equator: move the equinox by dpsi along the ecliptic, then tilt by
    // the true obliquity (Meeus, Astronomical Algorithms, ch. 23 in matrix form).
    const Nutation n = Nutation2000B(jd_tt);
    return R1(-(MeanObliquity2006(jd_tt) + n.deps)) * R3(-n.dpsi);
}

double EarthRotationAngle(double jd_ut1) {
    // IERS Conventions 2010, eq. 5.15. The whole days of Du are taken out before multiplying so
    // that the large number of turns does not cost precision.
    const double du = jd_ut1 - kJ2000;
    const double turns = std::fmod(du, 1.0) + 0.7790572732640 + 0.00273781191135448 * du;
    return WrapTwoPi(kTwoPi * turns);
}

double GreenwichMeanSiderealTime(double jd_ut1, double jd_tt) {
    // IERS Conventions 2010, eq. 5.32: ERA plus the accumulated precession in RA, t in TT.
    const double t = CenturiesSinceJ2000(jd_tt);
    const double poly_arcsec =
        0.014506 + (4612.156534 +
                    (1.3915817 + (-0.00000044 + (-0.000029956 - 0.0000000368 * t) * t) * t) * t) *
                       t;
    return WrapTwoPi(EarthRotationAngle(jd_ut1) + poly_arcsec * kArcsecToRad);
}

double GreenwichApparentSiderealTime(double jd_ut1, double jd_tt) {
    // IERS Conventions 2010, eq. 5.30 (equation of the equinoxes, IAU 1994 resolution C7 form).
    const double t = CenturiesSinceJ2000(jd_tt);
    const Nutation n = Nutation2000B(jd_tt);
    const double ee =
        n.dpsi * std::cos(MeanObliquity2006(jd_tt)) + EquationOfEquinoxesComplement(t);
    return WrapTwoPi(GreenwichMeanSiderealTime(jd_ut1, jd_tt) + ee);
}

glm::dmat3 EcefFromTod(const Time& t) {
    // Polar motion (< 0.5") is neglected, as documented in the header.
    return R3(GreenwichApparentSiderealTime(t.jd_ut1, t.jd_tt));
}

}  // namespace zenith::geo
