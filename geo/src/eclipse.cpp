#include "zenith/geo/eclipse.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "zenith/base/gauss_legendre.h"
#include "zenith/base/units.h"
#include "zenith/geo/moon.h"

namespace zenith::geo {
namespace {

double AngleBetween(const glm::dvec3& a, const glm::dvec3& b) {
    return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

// The n-point rule on [0, pi].
const GaussLegendreRule& Nodes(int n) {
    static const GaussLegendreRule standard = GaussLegendre(48, 0.0, kPi);
    if (n == 48) return standard;
    thread_local GaussLegendreRule other;
    if (static_cast<int>(other.nodes.size()) != n) other = GaussLegendre(n, 0.0, kPi);
    return other;
}

double Intensity(const LimbDarkeningLaw& law, double mu) {
    double v = 0.0;
    for (int k = 5; k >= 0; --k) v = v * mu + law[static_cast<std::size_t>(k)];
    return v;
}

// Angle of the ring of radius r about the disk's centre that lies inside the occulter.
double CoveredArc(double r, double occulter_radius, double separation) {
    if (separation <= 0.0 || r <= 0.0) return r < occulter_radius - separation ? 2.0 * kPi : 0.0;
    const double c = (r * r + separation * separation - occulter_radius * occulter_radius) /
                     (2.0 * r * separation);
    if (c >= 1.0) return 0.0;
    if (c <= -1.0) return 2.0 * kPi;
    return 2.0 * std::acos(c);
}

}  // namespace

double DiskOverlapArea(double r1, double r2, double d) {
    if (d >= r1 + r2) return 0.0;
    const double small = std::min(r1, r2);
    if (d <= std::abs(r1 - r2)) return kPi * small * small;
    const double c1 = std::clamp((d * d + r1 * r1 - r2 * r2) / (2.0 * d * r1), -1.0, 1.0);
    const double c2 = std::clamp((d * d + r2 * r2 - r1 * r1) / (2.0 * d * r2), -1.0, 1.0);
    const double k = (-d + r1 + r2) * (d + r1 - r2) * (d - r1 + r2) * (d + r1 + r2);
    return r1 * r1 * std::acos(c1) + r2 * r2 * std::acos(c2) - 0.5 * std::sqrt(std::max(k, 0.0));
}

double CoveredFluxFraction(const LimbDarkeningLaw& law, double radius, double occulter_radius,
                           double separation, int nodes) {
    const double d = std::abs(separation);
    if (d >= radius + occulter_radius) return 0.0;
    if (d + radius <= occulter_radius) return 1.0;
    // Total flux: 2 pi R^2 integral_0^1 I(mu) x dx = 2 pi R^2 sum a_k / (k + 2) (x dx = -mu dmu).
    double moments = 0.0;
    for (int k = 0; k < 6; ++k) moments += law[static_cast<std::size_t>(k)] / (k + 2.0);
    const double total = 2.0 * kPi * radius * radius * moments;

    std::array<double, 4> edges = {0.0, std::abs(d - occulter_radius), d + occulter_radius, radius};
    for (double& e : edges) e = std::clamp(e, 0.0, radius);
    std::sort(edges.begin(), edges.end());
    const GaussLegendreRule& g = Nodes(nodes);
    double covered = 0.0;
    for (std::size_t piece = 0; piece + 1 < edges.size(); ++piece) {
        const double a = edges[piece], b = edges[piece + 1];
        if (!(b > a)) continue;
        for (std::size_t i = 0; i < g.nodes.size(); ++i) {
            const double t = g.nodes[i];  // [0, pi]
            const double r = a + (b - a) * 0.5 * (1.0 - std::cos(t));
            const double dr_dt = (b - a) * 0.5 * std::sin(t);
            const double x = r / radius;
            const double mu = std::sqrt(std::max(1.0 - x * x, 0.0));
            covered +=
                g.weights[i] * dr_dt * Intensity(law, mu) * CoveredArc(r, occulter_radius, d) * r;
        }
    }
    return std::clamp(covered / total, 0.0, 1.0);
}

SolarEclipse ComputeSolarEclipse(const SkyEphemeris& e) {
    SolarEclipse s;
    s.sun_radius = 0.5 * e.sun.angular_diameter;
    s.moon_radius = 0.5 * e.moon.angular_diameter;
    s.separation = AngleBetween(e.sun.topocentric.horizontal.direction_enu,
                                e.moon.topocentric.horizontal.direction_enu);
    if (!(s.separation < s.sun_radius + s.moon_radius)) return s;  // no overlap: no cost
    s.magnitude = (s.sun_radius + s.moon_radius - s.separation) / (2.0 * s.sun_radius);
    s.obscuration = std::min(DiskOverlapArea(s.sun_radius, s.moon_radius, s.separation) /
                                 (kPi * s.sun_radius * s.sun_radius),
                             1.0);
    for (int c = 0; c < 3; ++c) {
        s.uncovered_flux[c] =
            1.0 - CoveredFluxFraction(kSunLimbDarkeningRgb[static_cast<std::size_t>(c)],
                                      s.sun_radius, s.moon_radius, s.separation);
    }
    return s;
}

LunarEclipse ComputeLunarEclipse(const SkyEphemeris& e, double shadow_radius) {
    return LunarEclipseAt(e.moon.geocentric_distance, e.moon_phase.elongation,
                          e.sun.geocentric_distance, shadow_radius);
}

LunarEclipse LunarEclipseAt(double moon_distance, double elongation, double sun_distance,
                            double shadow_radius) {
    LunarEclipse l;
    // The triangle Earth-Moon-Sun from the geocentric distances and elongation: the antisolar
    // point is pi - elongation from the Moon, and the angle at the Moon between the Earth and
    // the Sun follows (atan2: exact near 0, where an acos would lose half the digits).
    l.moon_distance = moon_distance;
    l.axis_angle = kPi - elongation;
    l.axis_distance = moon_distance * std::sin(l.axis_angle);
    const double sun_from_moon =
        std::sqrt(sun_distance * sun_distance + moon_distance * moon_distance -
                  2.0 * sun_distance * moon_distance * std::cos(elongation));
    l.separation = std::atan2(sun_distance * std::sin(elongation),
                              moon_distance - sun_distance * std::cos(elongation));
    l.sun_radius = std::asin(kSunRadius / sun_from_moon);
    l.earth_radius = std::asin(shadow_radius / moon_distance);
    if (l.separation < l.sun_radius + l.earth_radius) {  // in the penumbra: the quadrature
        for (int c = 0; c < 3; ++c) {
            l.direct_sunlight[c] =
                1.0 - CoveredFluxFraction(kSunLimbDarkeningRgb[static_cast<std::size_t>(c)],
                                          l.sun_radius, l.earth_radius, l.separation);
        }
    }
    // Shadow radii seen from the Earth's centre (Meeus, Astronomical Algorithms, ch. 54, without
    // his 1.02 for the air): umbra pi_moon - s_sun + pi_sun, penumbra pi_moon + s_sun + pi_sun.
    const double parallax_moon = l.earth_radius;
    const double parallax_sun = std::asin(shadow_radius / sun_distance);
    const double sun_semi = std::asin(kSunRadius / sun_distance);
    const double moon_semi = std::asin(kMoonRadius / moon_distance);
    const double umbra = parallax_moon - sun_semi + parallax_sun;
    const double penumbra = parallax_moon + sun_semi + parallax_sun;
    l.umbral_magnitude = (umbra + moon_semi - l.axis_angle) / (2.0 * moon_semi);
    l.penumbral_magnitude = (penumbra + moon_semi - l.axis_angle) / (2.0 * moon_semi);
    return l;
}

}  // namespace zenith::geo
