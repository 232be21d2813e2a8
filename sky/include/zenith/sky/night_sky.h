// The diffuse light of the night sky (issue 18 §3): airglow, zodiacal light, integrated
// starlight beyond the stars that are drawn one by one, and light pollution, as luminance added
// to the sky by the renderer (SkyScene::night_sky, filled by MakeSkyState), and the
// threshold against that sky under which a star cannot be seen.
//
// Photometry. Surface brightness in V mag/arcsec^2 to luminance with Schaefer's conversion,
//   B[nL] = 34.08 exp(20.7233 - 0.92104 m)            (Schaefer 1990, PASP 102, 212, Eq. 1)
// and 1 nL = 1e-9 lambert = 1e-5 / pi cd/m^2, so L = kSurfaceBrightnessZeroPoint 10^(-0.4 m)
// with kSurfaceBrightnessZeroPoint = 34.08 e^20.7233 1e-5 / pi = 1.0849e5 cd/m^2: the
// "10.8e4 cd/m^2" of the light-pollution literature (Garstang 1986; Cinzano et al. 2001), within
// 0.4 % of a V = 0 star of 2.54e-6 lux (Allen's Astrophysical Quantities) spread over one square
// arcsecond (2.3504e-11 sr): 1.0806e5. The star catalogue's own zero point
// (geo::kZeroMagnitudeIlluminance, 2.128e-6 lux) is 0.19 mag fainter; both are kept as documented,
// and the threshold below works in illuminance and luminance, not magnitudes, so it does not mix
// them. S10 (one V = 10 star per square degree) is 27.78 V mag/arcsec^2.
#pragma once

#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <vector>

#include "zenith/base/error.h"
#include "zenith/sky/atmosphere.h"
#include "zenith/sky/lut.h"

namespace zenith::geo {
class StarCatalog;
}

namespace zenith::sky {

inline constexpr double kSurfaceBrightnessZeroPoint = 1.0849e5;  // cd/m^2 at 0 mag/arcsec^2
inline constexpr double kS10Magnitude = 27.78;                   // V mag/arcsec^2 of 1 S10

double LuminanceFromSurfaceBrightness(double mag_per_arcsec2);  // cd/m^2
double SurfaceBrightnessFromLuminance(double luminance);        // V mag/arcsec^2; +inf for 0

// Total zenith sky brightness (V mag/arcsec^2) of a Bortle class 1..9: the middle of the
// sky-quality-meter range the "Bortle scale" article of Wikipedia lists for the class
// (1: 21.76-22.00, 2: 21.60-21.75, 3: 21.30-21.60, 4: 20.80-21.30, 5: 19.25-20.30,
// 6: 18.50-19.25, 7: 18.00-18.50, 8 and 9: brighter than 18.00; class 8 is taken as 17.50 and
// 9 as 17.00, the table giving no lower end). Throws ArgumentError for other classes.
double BortleZenithBrightness(int bortle_class);

// The natural zenith brightness of a dark site the light pollution is measured against:
// 21.9 V mag/arcsec^2 (about 220 S10: Roach & Gordon 1973, "The Light of the Night Sky", as
// tabulated by Wikipedia's "Sky brightness": airglow 145, zodiacal light 60, scattered
// starlight 15 S10).
inline constexpr double kNaturalZenithBrightness = 21.9;

// The artificial part of a total zenith brightness (V mag/arcsec^2): what is left after the
// natural sky's luminance is taken off; +inf (none) when the total is not brighter than it.
double ArtificialZenithBrightness(double total_zenith_mag);

// What the user chooses; the defaults are a dark site near solar minimum.
struct NightSkySettings {
    bool enabled = true;
    // Airglow above the atmosphere, looking straight up: 145 S10 = 22.38 V mag/arcsec^2
    // (Roach & Gordon 1973 via Wikipedia's "Sky brightness"; it varies 0.8-2x with the solar
    // cycle, brighter at solar maximum). A thin emitting shell (the 557.7 nm line and the OH
    // bands peak at 85-95 km) seen through the layer's slant path: van Rhijn's law.
    double airglow_zenith_brightness = 22.38;  // V mag/arcsec^2
    double airglow_height = 90000.0;           // m, centre of the layer
    double airglow_thickness = 10000.0;        // m
    bool zodiacal_light = true;                // Leinert et al. 1998, Table 17
    bool starlight = true;                     // integrated starlight and the Milky Way
    // These three lights scattered by the air toward the camera (night_sky.cpp,
    // MakeScatteredNightLight; within 5.4 % of the path tracer under a uniform sky): what keeps
    // the horizon of a dark site from going black where extinction hides the light behind it.
    bool scattered = true;
    // Light pollution: the artificial zenith brightness in V mag/arcsec^2 (nullopt: none); see
    // BortleZenithBrightness and ArtificialZenithBrightness to set it from a Bortle class.
    std::optional<double> artificial_zenith_brightness;

    // Throws ArgumentError naming the field, its value and the expected range.
    void Validate() const;
    bool operator==(const NightSkySettings&) const = default;
};

// Integrated light of the stars that are not drawn one by one: an equirectangular map in ICRS
// (right ascension across, declination up; texel (i, j) centred on RA (i + 0.5) 360 / width deg,
// Dec -90 + (j + 0.5) 180 / height deg) of luminance, linear sRGB, cd/m^2 above the atmosphere.
// It holds the catalogue's stars fainter than the drawn limit (binned, each with its B-V
// colour), and the stars beyond the catalogue's limit as a smooth model of galactic latitude b:
//   I(b) = 20 S10 + 130 S10 exp(-|b| / 10 deg)   (V, stars fainter than V = 8)
// an approximation of the integrated starlight of Roach & Megill (1961, ApJ 133, 228) summarised
// in Leinert et al. (1998, A&AS 127, 1, §10): a few tens of S10 toward the galactic poles and
// about 150 in the galactic plane, where its mean hides the Milky Way's clouds and dust lanes
// (the catalogue's binned stars carry some of that structure). Its values were not checked
// against those tables in this session: treat them as +-50 %.
struct StarlightMap {
    int width = 0, height = 0;
    std::vector<glm::dvec3> texels;  // x fastest

    // From `catalog` (loaded to its own limit, V = 8 for the shipped one): the stars fainter than
    // drawn_limit, plus the model beyond catalog.magnitude_limit().
    static StarlightMap FromCatalog(const geo::StarCatalog& catalog, double drawn_limit,
                                    int width = 180, int height = 90);
    // The model alone (no catalogue): what lies beyond `limit` (V = 8).
    static StarlightMap ModelOnly(int width = 180, int height = 90);
    // Bilinear, wrapping in RA; `icrs` a unit vector.
    glm::dvec3 Sample(const glm::dvec3& icrs) const;
};

// The per-frame description the renderer needs, in its planet-centred frame.
struct NightSky {
    bool enabled = false;  // off: the sky is the atmosphere's scattering alone
    NightSkySettings settings;
    glm::dmat3 ecliptic_from_world{1.0};  // ecliptic and equinox of date
    double sun_ecliptic_longitude = 0.0;  // rad
    glm::dmat3 icrs_from_world{1.0};
    std::shared_ptr<const StarlightMap> starlight;  // null: no integrated starlight
};

// Linear sRGB colours (luminance Y = 1) of the components. Airglow: half of its V luminance in
// the 557.7 nm [O I] line (CIE 1931 chromaticity, clipped to the sRGB gamut), half in the
// continuum and the red lines taken as white; zodiacal light: sunlight (B-V = 0.65); light
// pollution: a 3000 K mix of high-pressure sodium and warm LEDs (B-V = 2.2).
glm::dvec3 AirglowColour();
glm::dvec3 ZodiacalColour();
glm::dvec3 LightPollutionColour();

// Leinert et al. (1998, A&AS 127, 1) Table 17: zodiacal light at 500 nm in
// 1e-8 W m^-2 sr^-1 um^-1 against |lambda - lambda_sun| and |beta| (degrees), bilinear; the
// table's empty corner within 15 deg of the Sun takes its nearest entry in the row, and
// |beta| = 90 deg is the ecliptic pole's 77 (Leinert §8). Angles outside [0, 180] x [0, 90]
// are folded in.
double ZodiacalTable(double delta_longitude_deg, double latitude_deg);
// Its V surface brightness: the table's unit at 500 nm with the solar spectrum's V / 500 nm
// ratio taken as 1 and V = 0 at 3.63e-11 W m^-2 nm^-1 (Bessell 1979): 27.97 - 2.5 log10(Z).
double ZodiacalSurfaceBrightness(double table_value);

// The diffuse night light above the atmosphere (or, for the airglow, in its shell) along world
// direction `direction` seen from `camera_m` (planet-centred): cd/m^2, linear sRGB, before the
// atmosphere's extinction. Components, for tests and tools.
struct NightSkyComponents {
    glm::dvec3 airglow{0.0};     // times the slant path through the shell
    glm::dvec3 zodiacal{0.0};    // extraterrestrial
    glm::dvec3 starlight{0.0};   // extraterrestrial
    double airglow_slant = 0.0;  // path through the shell / its thickness (van Rhijn factor)
};
NightSkyComponents NightSkySources(const NightSky& night, double bottom_radius,
                                   const glm::dvec3& camera_m, const glm::dvec3& direction);

// Illuminance (lux per channel, linear sRGB) on a horizontal surface on the ground below
// `position` (m, planet-centred) from the night sky: airglow, zodiacal light and starlight
// through the air, the air's glow from them (with NightSkySettings::scattered) and light
// pollution's (its luminance over the sky as drawn). What lights a moonless night's ground, for
// a host's ambient (SkyLighting::sky_irradiance); 0 when the night sky is off. `transmittance`
// is the renderer's transmittance LUT (RendererInspection::ReadTransmittance).
glm::dvec3 NightSkyGroundIrradiance(const NightSky& night, const Atmosphere& atmosphere,
                                    const LutImage& transmittance, const glm::dvec3& position);

// Path length through the spherical shell [radius_low, radius_high] (any units) of a ray from
// `r` with zenith cosine `mu`, stopped by the ground at `ground_radius`; divided by the shell's
// thickness it is the van Rhijn factor 1 / sqrt(1 - (r / R_layer)^2 sin^2 z) of a thin layer.
double ShellChord(double r, double mu, double radius_low, double radius_high, double ground_radius);

// Point-source visibility (issue 18 §3: a star is fully visible only where the sky is darker
// than it). Threshold illuminance of a point source against a background of luminance
// `background` (cd/m^2), in lux: Hecht (1947) as used by Schaefer (1990, Eqs. 2-3),
//   I = c1 (1 + sqrt(c2 B))^2, I in foot-candles, B in nanolamberts,
//   night (rods): c1 = 10^-9.8, c2 = 10^-1.9; day (cones): c1 = 10^-8.35, c2 = 10^-5.9,
// taking the smaller (the more sensitive system; they cross near Schaefer's 1479 nL switch).
// At 22 mag/arcsec^2 this is V = 6.6 with the 2.54e-6 lux zero point; in a 5000 cd/m^2 day sky
// V = -4.0, so Venus shows and Sirius does not. The eye's other factors (age, pupil, colour,
// seeing) are Schaefer's 1.
double StarThresholdIlluminance(double background);  // lux
// The share of a star of illuminance `illuminance` (lux, through the atmosphere) that is drawn:
// 0 at or below the threshold, 1 from one magnitude above it (2.512x), linear in magnitude
// between: the frequency-of-seeing curve of Blackwell (1946) rises from 0 to 1 over about that
// range of contrast. Shared with the composite shader (functions.glsl: StarVisibility).
double StarVisibility(double illuminance, double background);

}  // namespace zenith::sky
