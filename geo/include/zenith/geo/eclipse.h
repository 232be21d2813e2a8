// Solar and lunar eclipses from the ephemeris: how much of the Sun's disk and light the Moon
// hides from an observer, and how much of the Sun's light reaches the Moon past the Earth.
//
// Both are one disk hiding another: the Moon's over the Sun's seen from the observer, the
// Earth's over the Sun's seen from the Moon. The hidden light is integrated over the Sun's
// limb-darkened disk (a converged quadrature over rings about its centre, checked against closed
// forms in tests/geo/eclipse_test.cpp), per RGB channel, since the limb is redder than the centre.
#pragma once

#include <array>
#include <glm/glm.hpp>

#include "zenith/geo/ephemeris.h"

namespace zenith::geo {

// Solar limb darkening I(mu) / I(centre) = sum a_k mu^k, mu the cosine of the angle between the
// line of sight and the surface normal (mu = sqrt(1 - (r / R)^2) across the disk): Hestroffer &
// Magnan (1998, A&A 333, 338) fifth-order polynomials at 680, 550 and 440 nm, as Hillaire (2016,
// Appendix B) gives them for R, G and B. The same numbers as the renderer's disk
// (sky/shaders/atmosphere/render.frag, SunLimbDarkening), so what is reported is what is drawn.
using LimbDarkeningLaw = std::array<double, 6>;
inline constexpr std::array<LimbDarkeningLaw, 3> kSunLimbDarkeningRgb = {{
    {0.34685, 1.37539, -2.04425, 2.70493, -1.94290, 0.55999},
    {0.26073, 1.27428, -1.30352, 1.47085, -0.96618, 0.26384},
    {0.15248, 1.38517, -1.49615, 1.99886, -1.48155, 0.44119},
}};
// Uniform brightness (no limb darkening): the covered flux is the covered area.
inline constexpr LimbDarkeningLaw kUniformDisk = {1.0, 0.0, 0.0, 0.0, 0.0, 0.0};

// Area common to two disks of radii r1 and r2 whose centres are `separation` apart (closed form;
// any consistent unit, angles in radians for the small disks of the sky).
double DiskOverlapArea(double r1, double r2, double separation);

// Fraction of the flux of a disk of `radius` with limb-darkening `law` that an opaque disk of
// `occulter_radius`, its centre `separation` from the disk's, hides. Gauss-Legendre quadrature of
// the covered arc over rings of the disk, `nodes` per piece between the rings where the arc's
// form changes, each piece mapped r = a + (b - a)(1 - cos t) / 2 so the square-root ends of the
// arc and of mu cost no accuracy (48 nodes: < 1e-9 against closed forms). Radii > 0.
double CoveredFluxFraction(const LimbDarkeningLaw& law, double radius, double occulter_radius,
                           double separation, int nodes = 48);

// The Sun seen from one observer (topocentric, from SkyEphemeris::sun and ::moon).
struct SolarEclipse {
    double separation = 0.0;   // rad, between the Sun's and the Moon's centres
    double sun_radius = 0.0;   // rad, apparent
    double moon_radius = 0.0;  // rad, apparent
    // Fraction of the Sun's diameter covered, (r_sun + r_moon - separation) / (2 r_sun) while the
    // disks overlap, else 0 (the eclipse circulars' "magnitude"; > 1 in a total eclipse).
    double magnitude = 0.0;
    double obscuration = 0.0;  // fraction of the Sun's disk area covered (0..1)
    // Fraction of the Sun's light still reaching the observer, per channel (limb-darkened): what
    // the Sun's illuminance is multiplied by. 1 without an eclipse, 0 in totality.
    glm::dvec3 uncovered_flux{1.0};
    bool partial() const { return obscuration > 0.0; }
    bool total() const { return obscuration >= 1.0 && moon_radius >= sun_radius; }
};
SolarEclipse ComputeSolarEclipse(const SkyEphemeris& e);

// Mean radius of the Earth's solid disk for the shadow, m (IAU 2015 nominal equatorial and
// polar radii, their mean weighted 2:1). The air above it is not opaque: its light in the umbra
// is sky::UmbraRefractedLight's.
inline constexpr double kEarthShadowRadius = 6371000.0;

// The Moon's centre in the Earth's shadow: geocentric geometry (the same for every observer).
struct LunarEclipse {
    // Angle at the Earth's centre between the Moon and the antisolar point, rad.
    double axis_angle = 0.0;
    // The Moon's centre's distance from the shadow's axis (the Earth-Sun line), m.
    double axis_distance = 0.0;
    double moon_distance = 0.0;  // m, geocentric
    // Seen from the Moon's centre: the Sun's radius, the Earth's (shadow_radius) and their
    // centres' separation, rad.
    double sun_radius = 0.0;
    double earth_radius = 0.0;
    double separation = 0.0;
    // Fraction of the Sun's light reaching the Moon's centre in a straight line, per channel
    // (limb-darkened): 1 outside the penumbra, 0 in the umbra.
    glm::dvec3 direct_sunlight{1.0};
    // Umbral and penumbral magnitudes of the Moon's centre's position (how far into each shadow
    // the Moon's disk reaches, in Moon diameters; negative outside), with the solid Earth only
    // (almanacs enlarge the shadow by ~2 % for the air: here only by what shadow_radius adds).
    double umbral_magnitude = 0.0;
    double penumbral_magnitude = 0.0;
};
// From the ephemeris's geocentric distances and elongation (the Earth-Moon-Sun triangle); the
// limb-darkened quadrature runs only while the Moon's centre is in the penumbra.
// `shadow_radius`: the opaque Earth's radius, m. The renderer passes the solid Earth plus its
// air's thickness, since it adds the light through the air itself, refracted and filtered
// (sky::UmbraRefractedLight); so the straight rays count only above the air.
LunarEclipse ComputeLunarEclipse(const SkyEphemeris& e, double shadow_radius = kEarthShadowRadius);
// The same for a point `moon_distance` m from the Earth's centre at `elongation` rad from the Sun
// (seen from the Earth's centre), the Sun `sun_distance` m away: a point of the Moon's surface
// as well as its centre (the Earth's shadow's edge across the Moon's disk).
LunarEclipse LunarEclipseAt(double moon_distance, double elongation, double sun_distance,
                            double shadow_radius = kEarthShadowRadius);

}  // namespace zenith::geo
