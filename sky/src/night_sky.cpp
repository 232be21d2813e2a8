#include "zenith/sky/night_sky.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "night_sky_map.h"
#include "reference/atmosphere_functions.h"
#include "reference/lut_texture.h"
#include "shader_parameters.h"
#include "zenith/geo/stars.h"
#include "zenith/sky/sky_state.h"

namespace zenith::sky {
namespace {

constexpr double kDeg = 0.017453292519943295;
constexpr double kArcsec2 = 2.3504430539097885e-11;  // sr in one square arcsecond

// Rotation from ICRS to galactic coordinates (rows: the galactic x, y, z axes in ICRS), the
// Hipparcos definition (ESA 1997, vol. 1, §1.5.3, Eq. 1.5.11).
const glm::dmat3& GalacticFromIcrs() {
    static const glm::dmat3 m =
        glm::transpose(glm::dmat3(-0.0548755604162154, -0.8734370902348850, -0.4838350155487132,  //
                                  0.4941094278755837, -0.4448296299600112, 0.7469822444972189,    //
                                  -0.8676661490190047, -0.1980763734312015, 0.4559837761750669));
    return m;
}

// Integrated light of the stars fainter than V = 8 at galactic latitude b, in S10 (night_sky.h).
double FaintStarlightS10(double galactic_latitude) {
    return 20.0 + 130.0 * std::exp(-std::abs(galactic_latitude) / (10.0 * kDeg));
}

// Leinert et al. (1998) Table 17; -1 marks the entries the table leaves empty near the Sun.
constexpr std::array<double, 19> kZodiacalLongitudes = {0,  5,  10, 15,  20,  25,  30,  35,  40, 45,
                                                        60, 75, 90, 105, 120, 135, 150, 165, 180};
constexpr std::array<double, 11> kZodiacalLatitudes = {0, 5, 10, 15, 20, 25, 30, 45, 60, 75, 90};
constexpr double kEclipticPole = 77.0;
constexpr std::array<std::array<double, 10>, 19> kZodiacal = {{
    {-1, -1, -1, 3140, 1610, 985, 640, 275, 150, 100},
    {-1, -1, -1, 2940, 1540, 945, 625, 271, 150, 100},
    {-1, -1, 4740, 2470, 1370, 865, 590, 264, 148, 100},
    {11500, 6780, 3440, 1860, 1110, 755, 525, 251, 146, 100},
    {6400, 4480, 2410, 1410, 910, 635, 454, 237, 141, 99},
    {3840, 2830, 1730, 1100, 749, 545, 410, 223, 136, 97},
    {2480, 1870, 1220, 845, 615, 467, 365, 207, 131, 95},
    {1650, 1270, 910, 680, 510, 397, 320, 193, 125, 93},
    {1180, 940, 700, 530, 416, 338, 282, 179, 120, 92},
    {910, 730, 555, 442, 356, 292, 250, 166, 116, 90},
    {505, 442, 352, 292, 243, 209, 183, 134, 104, 86},
    {338, 317, 269, 227, 196, 172, 151, 116, 93, 82},
    {259, 251, 225, 193, 166, 147, 132, 104, 86, 79},
    {212, 210, 197, 170, 150, 133, 119, 96, 82, 77},
    {188, 186, 177, 154, 138, 125, 113, 90, 77, 74},
    {179, 178, 166, 147, 134, 122, 110, 90, 77, 73},
    {179, 178, 165, 148, 137, 127, 116, 96, 79, 72},
    {196, 192, 179, 165, 151, 141, 131, 104, 82, 72},
    {230, 212, 195, 178, 163, 148, 134, 105, 83, 72},
}};

double ZodiacalEntry(std::size_t row, std::size_t column) {
    if (column == kZodiacalLatitudes.size() - 1) return kEclipticPole;
    for (std::size_t c = column; c < kZodiacal[row].size(); ++c) {
        if (kZodiacal[row][c] > 0.0) return kZodiacal[row][c];  // nearest filled entry
    }
    return kEclipticPole;
}

// Index i and weight of x in a sorted grid (clamped to its ends).
template <std::size_t N>
std::pair<std::size_t, double> GridCell(const std::array<double, N>& grid, double x) {
    x = std::clamp(x, grid.front(), grid.back());
    std::size_t i = 0;
    while (i + 2 < N && x > grid[i + 1]) ++i;
    return {i, (x - grid[i]) / (grid[i + 1] - grid[i])};
}

// Mean colour of the integrated starlight: B-V = 0.8 (a G8 star's), about what the summed
// spectra of the solar neighbourhood give in the visible.
constexpr double kStarlightBMinusV = 0.8;

// Length of {t in [t0, t1] : |p + t v| <= radius} for a ray from radius r with zenith cosine mu.
double InsideLength(double r, double mu, double radius, double t0, double t1) {
    const double b = r * mu;
    const double discriminant = b * b - (r * r - radius * radius);
    if (discriminant <= 0.0) return 0.0;
    const double s = std::sqrt(discriminant);
    return std::max(0.0, std::min(t1, -b + s) - std::max(t0, -b - s));
}

// Distance to the ground along the ray, or +inf when it misses.
double GroundDistance(double r, double mu, double ground_radius) {
    const double b = r * mu;
    const double discriminant = b * b - (r * r - ground_radius * ground_radius);
    if (mu >= 0.0 || discriminant < 0.0) return std::numeric_limits<double>::infinity();
    return -b - std::sqrt(discriminant);
}

glm::dvec3 Zodiacal(const NightSky& night, const glm::dvec3& direction) {
    if (!night.settings.zodiacal_light) return glm::dvec3(0.0);
    const glm::dvec3 e = night.ecliptic_from_world * direction;
    const double longitude = std::atan2(e.y, e.x);
    const double latitude = std::asin(std::clamp(e.z, -1.0, 1.0));
    const double z =
        ZodiacalTable((longitude - night.sun_ecliptic_longitude) / kDeg, latitude / kDeg);
    return LuminanceFromSurfaceBrightness(ZodiacalSurfaceBrightness(z)) * ZodiacalColour();
}

glm::dvec3 Starlight(const NightSky& night, const glm::dvec3& direction) {
    if (!night.settings.starlight || !night.starlight) return glm::dvec3(0.0);
    return night.starlight->Sample(night.icrs_from_world * direction);
}

}  // namespace

double LuminanceFromSurfaceBrightness(double mag_per_arcsec2) {
    return kSurfaceBrightnessZeroPoint * std::pow(10.0, -0.4 * mag_per_arcsec2);
}

double SurfaceBrightnessFromLuminance(double luminance) {
    if (!(luminance > 0.0)) return std::numeric_limits<double>::infinity();
    return -2.5 * std::log10(luminance / kSurfaceBrightnessZeroPoint);
}

double BortleZenithBrightness(int bortle_class) {
    // Middles of the sky-quality-meter ranges (night_sky.h).
    constexpr std::array<double, 9> kMiddle = {21.88,  21.675, 21.45, 21.05, 19.775,
                                               18.875, 18.25,  17.50, 17.00};
    if (bortle_class < 1 || bortle_class > 9) {
        throw ArgumentError("bortle_class", "bortle_class = " + std::to_string(bortle_class) +
                                                " is out of range (expected 1..9)");
    }
    return kMiddle[static_cast<std::size_t>(bortle_class - 1)];
}

double ArtificialZenithBrightness(double total_zenith_mag) {
    return SurfaceBrightnessFromLuminance(LuminanceFromSurfaceBrightness(total_zenith_mag) -
                                          LuminanceFromSurfaceBrightness(kNaturalZenithBrightness));
}

void NightSkySettings::Validate() const {
    Require("airglow_zenith_brightness", airglow_zenith_brightness, "mag/arcsec^2",
            Range::Closed(10.0, 30.0));
    Require("airglow_height", airglow_height, "m", Range::Open(0.0, 1e6));
    Require("airglow_thickness", airglow_thickness, "m", Range::Open(0.0, 2.0 * airglow_height));
    if (artificial_zenith_brightness) {
        Require("artificial_zenith_brightness", *artificial_zenith_brightness, "mag/arcsec^2",
                Range::Closed(10.0, 30.0));
    }
}

glm::dvec3 AirglowColour() {
    // 557.7 nm in CIE 1931 (x, y, z bar = 0.5566, 0.9973, 0.0047, the 5 nm table interpolated)
    // to linear sRGB (IEC 61966-2-1): (0.268, 1.332, -0.167); the blue clipped to 0 and scaled
    // to Y = 1, then half of the luminance as white.
    const glm::dvec3 line(0.2659, 1.3191, 0.0);  // Y = 0.2126 R + 0.7152 G = 1
    return 0.5 * line + 0.5 * glm::dvec3(1.0);
}

glm::dvec3 ZodiacalColour() { return StarColour(0.65); }
glm::dvec3 LightPollutionColour() { return StarColour(2.2); }

double ZodiacalTable(double delta_longitude_deg, double latitude_deg) {
    double dl = std::fmod(std::abs(delta_longitude_deg), 360.0);
    if (dl > 180.0) dl = 360.0 - dl;
    const double beta = std::min(std::abs(latitude_deg), 90.0);
    const auto [i, u] = GridCell(kZodiacalLongitudes, dl);
    const auto [j, v] = GridCell(kZodiacalLatitudes, beta);
    return (1.0 - u) * ((1.0 - v) * ZodiacalEntry(i, j) + v * ZodiacalEntry(i, j + 1)) +
           u * ((1.0 - v) * ZodiacalEntry(i + 1, j) + v * ZodiacalEntry(i + 1, j + 1));
}

double ZodiacalSurfaceBrightness(double table_value) {
    // 1e-8 W m^-2 sr^-1 um^-1 = 1e-11 W m^-2 nm^-1 sr^-1, times the sr of an arcsec^2, against
    // V = 0 at 3.63e-11 W m^-2 nm^-1.
    return -2.5 * std::log10(table_value * 1e-11 * kArcsec2 / 3.63e-11);
}

double ShellChord(double r, double mu, double radius_low, double radius_high,
                  double ground_radius) {
    const double t_max = GroundDistance(r, mu, ground_radius);
    return InsideLength(r, mu, radius_high, 0.0, t_max) -
           InsideLength(r, mu, radius_low, 0.0, t_max);
}

StarlightMap StarlightMap::ModelOnly(int width, int height) {
    Require("starlight map width", width, "texels", Range::Closed(4, 4096));
    Require("starlight map height", height, "texels", Range::Closed(2, 2048));
    StarlightMap map;
    map.width = width;
    map.height = height;
    map.texels.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
    const glm::dvec3 colour = StarColour(kStarlightBMinusV);
    const double s10 = LuminanceFromSurfaceBrightness(kS10Magnitude);
    for (int j = 0; j < height; ++j) {
        const double dec = (-90.0 + (j + 0.5) * 180.0 / height) * kDeg;
        for (int i = 0; i < width; ++i) {
            const double ra = (i + 0.5) * 360.0 / width * kDeg;
            const glm::dvec3 icrs(std::cos(dec) * std::cos(ra), std::cos(dec) * std::sin(ra),
                                  std::sin(dec));
            const double b = std::asin(std::clamp((GalacticFromIcrs() * icrs).z, -1.0, 1.0));
            map.texels[static_cast<std::size_t>(j) * static_cast<std::size_t>(width) +
                       static_cast<std::size_t>(i)] = FaintStarlightS10(b) * s10 * colour;
        }
    }
    return map;
}

StarlightMap StarlightMap::FromCatalog(const geo::StarCatalog& catalog, double drawn_limit,
                                       int width, int height) {
    StarlightMap map = ModelOnly(width, height);
    for (const geo::Star& star : catalog.stars()) {
        if (!(star.magnitude_v > drawn_limit)) continue;
        const int i =
            std::clamp(static_cast<int>(star.ra_j2000 / (2.0 * ref::kPi) * width), 0, width - 1);
        const int j = std::clamp(static_cast<int>((star.dec_j2000 / kDeg + 90.0) / 180.0 * height),
                                 0, height - 1);
        const double dec_low = (-90.0 + j * 180.0 / height) * kDeg;
        const double dec_high = (-90.0 + (j + 1) * 180.0 / height) * kDeg;
        const double solid_angle =
            2.0 * ref::kPi / width * (std::sin(dec_high) - std::sin(dec_low));
        map.texels[static_cast<std::size_t>(j) * static_cast<std::size_t>(width) +
                   static_cast<std::size_t>(i)] += geo::IlluminanceFromMagnitude(star.magnitude_v) *
                                                   StarColour(star.b_minus_v) / solid_angle;
    }
    return map;
}

glm::dvec3 StarlightMap::Sample(const glm::dvec3& icrs) const {
    if (texels.empty()) return glm::dvec3(0.0);
    double ra = std::atan2(icrs.y, icrs.x);
    if (ra < 0.0) ra += 2.0 * ref::kPi;
    const double dec = std::asin(std::clamp(icrs.z, -1.0, 1.0));
    const double x = ra / (2.0 * ref::kPi) * width - 0.5;
    const double y = std::clamp((dec / kDeg + 90.0) / 180.0 * height - 0.5, 0.0, height - 1.0);
    const int x0 = static_cast<int>(std::floor(x));
    const int y0 = std::min(static_cast<int>(y), height - 2 < 0 ? 0 : height - 2);
    const double u = x - x0, v = std::clamp(y - y0, 0.0, 1.0);
    const auto at = [&](int i, int j) {
        i = ((i % width) + width) % width;
        j = std::clamp(j, 0, height - 1);
        return texels[static_cast<std::size_t>(j) * static_cast<std::size_t>(width) +
                      static_cast<std::size_t>(i)];
    };
    return (1.0 - v) * ((1.0 - u) * at(x0, y0) + u * at(x0 + 1, y0)) +
           v * ((1.0 - u) * at(x0, y0 + 1) + u * at(x0 + 1, y0 + 1));
}

NightSkyComponents NightSkySources(const NightSky& night, double bottom_radius,
                                   const glm::dvec3& camera_m, const glm::dvec3& direction) {
    NightSkyComponents c;
    const NightSkySettings& s = night.settings;
    const double r = glm::length(camera_m);
    const double mu = glm::dot(camera_m, direction) / r;
    c.airglow_slant =
        ShellChord(r, mu, bottom_radius + s.airglow_height - 0.5 * s.airglow_thickness,
                   bottom_radius + s.airglow_height + 0.5 * s.airglow_thickness, bottom_radius) /
        s.airglow_thickness;
    c.airglow = LuminanceFromSurfaceBrightness(s.airglow_zenith_brightness) * c.airglow_slant *
                AirglowColour();
    c.zodiacal = Zodiacal(night, direction);
    c.starlight = Starlight(night, direction);
    return c;
}

double StarThresholdIlluminance(double background) {
    return ref::StarThresholdIlluminance(background);
}

double StarVisibility(double illuminance, double background) {
    return ref::StarVisibility(illuminance, background);
}

namespace {

// The natural night light (airglow, zodiacal light, starlight) that the air scatters toward the
// camera. The air at altitude h sees around it a mean radiance J(h): the sources over its sky
// through the air's transmittance, and below it the Lambertian ground lit by them, seen through
// the air between; and the air's own glow lights the air in turn, a share
// f = omega(h) (1 / 4 pi) int (1 - T) of J coming back, so J = J_direct / (1 - f) (the geometric
// series of H20 Eq. 9 for this light). Scattering it isotropically (Rayleigh's phase is within
// 25 % of that everywhere; the aerosols' forward peak is not followed), a ray gathers
// int sigma_s(h(t)) J(h(t)) T(t) dt, marched once per frame for kScatteredRows view zenith
// angles (the sources are averaged over azimuth in J, and the air is layered, so the light
// depends on the zenith angle alone), read between them. Against the path tracer under a uniform
// sky: BENCHMARKS.md, tests/sky/night_sky_scattering_test.cpp. Rays that meet the ground get none
// (the ground's own shading draws them).
constexpr int kScatteredRows = 64;
constexpr std::array<double, 7> kMeanRadianceAltitudes = {0.0, 1.0, 2.5, 5.0, 10.0, 20.0, 50.0};

struct ScatteredNightLight {
    double mu_horizon = 0.0;  // zenith cosine of the ground's tangent from the camera
    std::array<glm::dvec3, kScatteredRows> rows{};  // at mu = RowMu(i)
    double RowMu(double x) const { return mu_horizon + (1.0 - mu_horizon) * x * x; }
    glm::dvec3 At(double mu) const {
        if (!(mu > mu_horizon)) return glm::dvec3(0.0);
        const double x =
            std::sqrt(std::min((mu - mu_horizon) / (1.0 - mu_horizon), 1.0)) * (kScatteredRows - 1);
        const int i = std::min(static_cast<int>(x), kScatteredRows - 2);
        return glm::mix(rows[static_cast<std::size_t>(i)], rows[static_cast<std::size_t>(i) + 1],
                        x - i);
    }
};

struct NightRadiance {
    // J(h) at kMeanRadianceAltitudes above the ground point.
    std::array<glm::dvec3, kMeanRadianceAltitudes.size()> mean{};
    glm::dvec3 ground_irradiance{0.0};   // lux on it, the air's glow included
    glm::dvec3 ground_direct{0.0};       // the same from the sources alone (through the air)
    glm::dvec3 ground_haze_cosine{0.0};  // sum over the sky of (1 - T) mu, per direction of n
    double directions = 0.0;             // n, over the sphere
};

// The mean radiance at kMeanRadianceAltitudes above the ground point under `up` (unit,
// planet-centred), and the ground's irradiance there.
NightRadiance MeanNightRadiance(const NightSky& night, const ref::AtmosphereParameters& atmosphere,
                                const ref::TransmittanceTexture& transmittance,
                                const glm::dvec3& up) {
    const NightSkySettings& s = night.settings;
    const glm::dvec3 east = glm::normalize(glm::cross(
        std::abs(up.z) < 0.9 ? glm::dvec3(0.0, 0.0, 1.0) : glm::dvec3(1.0, 0.0, 0.0), up));
    const glm::dvec3 north = glm::cross(up, east);
    const glm::dvec3 airglow =
        LuminanceFromSurfaceBrightness(s.airglow_zenith_brightness) * AirglowColour();
    const double low =
        atmosphere.bottom_radius + (s.airglow_height - 0.5 * s.airglow_thickness) / 1000.0;
    const double high = low + s.airglow_thickness / 1000.0;
    // The sphere in equal-solid-angle rings (cos of the zenith angle uniform), kAzimuths each;
    // the ground's radiance from the sky's irradiance on it, found first (altitude 0).
    constexpr int kRings = 32, kAzimuths = 8;
    glm::dvec3 ground_radiance(0.0);
    NightRadiance result;
    result.directions = static_cast<double>(kRings) * kAzimuths;
    auto& mean = result.mean;
    for (std::size_t a = 0; a < kMeanRadianceAltitudes.size(); ++a) {
        const double h = kMeanRadianceAltitudes[a];
        const double r = atmosphere.bottom_radius + h;
        const glm::dvec3 point = up * r;
        glm::dvec3 incoming(0.0), irradiance(0.0), haze(0.0), haze_cosine(0.0);
        for (int i = 0; i < kRings; ++i) {
            const double mu = -1.0 + 2.0 * (i + 0.5) / kRings;
            const double sin_theta = std::sqrt(1.0 - mu * mu);
            const double ground = GroundDistance(r, mu, atmosphere.bottom_radius);
            const double slant = ShellChord(r, mu, low, high, atmosphere.bottom_radius) /
                                 (s.airglow_thickness / 1000.0);
            for (int k = 0; k < kAzimuths; ++k) {
                const double phi = 2.0 * ref::kPi * (k + 0.5) / kAzimuths;
                const glm::dvec3 direction =
                    mu * up + sin_theta * (std::cos(phi) * east + std::sin(phi) * north);
                if (std::isfinite(ground)) {
                    const glm::dvec3 t = ref::TransmittanceToGround(atmosphere, transmittance,
                                                                    point, h, direction, ground);
                    incoming += ground_radiance * t;
                    haze += glm::dvec3(1.0) - t;
                    continue;
                }
                const glm::dvec3 t =
                    ref::TransmittanceToSpace(atmosphere, transmittance, point, h, direction);
                const glm::dvec3 l =
                    (airglow * slant + Zodiacal(night, direction) + Starlight(night, direction)) *
                    t;
                incoming += l;
                irradiance += l * std::max(mu, 0.0);
                haze += glm::dvec3(1.0) - t;
                haze_cosine += (glm::dvec3(1.0) - t) * std::max(mu, 0.0);
            }
        }
        const double n = static_cast<double>(kRings) * kAzimuths;
        const ref::MediumSample medium = ref::SampleMedium(atmosphere, h);
        const glm::dvec3 albedo =
            medium.scattering / glm::max(medium.extinction, glm::dvec3(1e-30));
        const glm::dvec3 returned = glm::min(albedo * haze / n, glm::dvec3(0.999));
        if (a == 0) {
            // On the ground, the lower half of the sphere is the Lambertian ground of radiance
            // albedo E / pi, E = sum of L mu d omega (4 pi / n each) from the sources and from
            // the air's glow, omega J (1 - T) the sky over: J n (1 - f) = incoming + n/2 radiance
            // is linear in J, solved per channel.
            const glm::dvec3 reflect = 2.0 * atmosphere.ground_albedo;
            mean[a] = (incoming + reflect * irradiance) /
                      glm::max(n * (glm::dvec3(1.0) - returned) - reflect * albedo * haze_cosine,
                               glm::dvec3(1e-30));
            const glm::dvec3 glow = s.scattered ? albedo * mean[a] * haze_cosine : glm::dvec3(0.0);
            result.ground_irradiance = 4.0 * ref::kPi * (irradiance + glow) / n;
            result.ground_direct = 4.0 * ref::kPi * irradiance / n;
            result.ground_haze_cosine = haze_cosine;
            ground_radiance = atmosphere.ground_albedo * result.ground_irradiance / ref::kPi;
            continue;
        }
        mean[a] = incoming / n / (glm::dvec3(1.0) - returned);
    }
    return result;
}

// The scattered light's table for a camera above the ground point `radiance` was made for.
ScatteredNightLight MakeScatteredNightLight(const NightRadiance& radiance,
                                            const ref::AtmosphereParameters& atmosphere,
                                            double camera_altitude_km) {
    const auto& mean = radiance.mean;
    const auto mean_at = [&](double h) {
        const auto& z = kMeanRadianceAltitudes;
        if (h >= z.back()) return mean.back();
        std::size_t i = 0;
        while (i + 2 < z.size() && h > z[i + 1]) ++i;
        return glm::mix(mean[i], mean[i + 1], std::clamp((h - z[i]) / (z[i + 1] - z[i]), 0.0, 1.0));
    };
    ScatteredNightLight light;
    const double r = atmosphere.bottom_radius + camera_altitude_km;
    light.mu_horizon = -std::sqrt(
        std::max(0.0, 1.0 - (atmosphere.bottom_radius * atmosphere.bottom_radius) / (r * r)));
    const double shell = atmosphere.top_radius - atmosphere.bottom_radius;
    constexpr int kSteps = 48;
    for (int row = 0; row < kScatteredRows; ++row) {
        const double mu =
            std::min(light.RowMu(static_cast<double>(row) / (kScatteredRows - 1)), 1.0);
        // From the camera, or where the ray enters the atmosphere, to where it leaves it.
        double t0 = 0.0;
        if (camera_altitude_km > shell) {
            t0 = ref::RaySphereDistance(r, mu, camera_altitude_km - shell, atmosphere.top_radius);
            if (t0 < 0.0) continue;  // misses the atmosphere
        }
        const double r0 = std::sqrt(r * r + t0 * t0 + 2.0 * r * mu * t0);
        const double mu0 = (r * mu + t0) / r0;
        const double length = ref::RaySphereDistance(r0, mu0, r0 - atmosphere.top_radius - 1e-9,
                                                     atmosphere.top_radius);
        if (!(length > 0.0)) continue;
        // Steps finer near the camera (quadratic in the distance), where the light is gathered.
        glm::dvec3 gathered(0.0), optical_depth(0.0);
        double previous = 0.0;
        for (int k = 1; k <= kSteps; ++k) {
            const double t =
                length * (static_cast<double>(k) / kSteps) * (static_cast<double>(k) / kSteps);
            const double mid = 0.5 * (previous + t), dt = t - previous;
            previous = t;
            const double h =
                std::sqrt(r0 * r0 + mid * mid + 2.0 * r0 * mu0 * mid) - atmosphere.bottom_radius;
            const ref::MediumSample m = ref::SampleMedium(atmosphere, std::max(h, 0.0));
            const glm::dvec3 step_depth = m.extinction * dt;
            // The step's share of the light: sigma_s J int T over it, T from the step's start.
            const glm::dvec3 share = glm::exp(-optical_depth) *
                                     (glm::dvec3(1.0) - glm::exp(-step_depth)) /
                                     glm::max(m.extinction, glm::dvec3(1e-30));
            gathered += m.scattering * mean_at(std::max(h, 0.0)) * share;
            optical_depth += step_depth;
        }
        light.rows[static_cast<std::size_t>(row)] = gathered;
    }
    return light;
}

// What is the same for every direction of a frame.
struct FrameConstants {
    glm::dvec3 airglow{0.0};          // cd/m^2 per unit slant path, coloured
    glm::dvec3 light_pollution{0.0};  // cd/m^2 per unit 1 - T, coloured
    ScatteredNightLight scattered;    // zero without NightSkySettings::scattered
};

// Light pollution's luminance per unit 1 - T along a ray, coloured (0 without it).
glm::dvec3 LightPollutionPerHaze(const NightSkySettings& s,
                                 const ref::AtmosphereParameters& atmosphere,
                                 const ref::TransmittanceTexture& transmittance) {
    if (!s.artificial_zenith_brightness) return glm::dvec3(0.0);
    const glm::dvec3 zenith = ref::GetTransmittanceToTopAtmosphereBoundary(
        atmosphere, transmittance, atmosphere.bottom_radius, 1.0);
    return LuminanceFromSurfaceBrightness(*s.artificial_zenith_brightness) *
           LightPollutionColour() / (glm::dvec3(1.0) - zenith);
}

FrameConstants MakeFrameConstants(const NightSky& night,
                                  const ref::AtmosphereParameters& atmosphere,
                                  const ref::TransmittanceTexture& transmittance,
                                  const glm::dvec3& camera_km, double camera_altitude_km) {
    FrameConstants f;
    const NightSkySettings& s = night.settings;
    f.airglow = LuminanceFromSurfaceBrightness(s.airglow_zenith_brightness) * AirglowColour();
    f.light_pollution = LightPollutionPerHaze(s, atmosphere, transmittance);
    if (night.enabled && s.enabled && s.scattered) {
        f.scattered = MakeScatteredNightLight(
            MeanNightRadiance(night, atmosphere, transmittance, glm::normalize(camera_km)),
            atmosphere, camera_altitude_km);
    }
    return f;
}

glm::dvec3 NightSkyLuminanceKm(const NightSky& night, const FrameConstants& frame,
                               const ref::AtmosphereParameters& atmosphere,
                               const ref::TransmittanceTexture& transmittance,
                               const glm::dvec3& camera_km, double camera_altitude_km,
                               const glm::dvec3& direction) {
    if (!night.enabled || !night.settings.enabled) return glm::dvec3(0.0);
    const NightSkySettings& s = night.settings;
    const double r = glm::length(camera_km);
    const double mu = glm::dot(camera_km, direction) / r;
    const double ground = atmosphere.bottom_radius;
    const glm::dvec3 t = ref::TransmittanceToSpace(atmosphere, transmittance, camera_km,
                                                   camera_altitude_km, direction);
    // The airglow shell, split at the ray's lowest point: the part before it (the ray going
    // down, from a camera at or above the layer) is seen through the thin air above the layer
    // (transmittance 1); the part after it through the ray's transmittance to space.
    const double low = ground + (s.airglow_height - 0.5 * s.airglow_thickness) / 1000.0;
    const double high = ground + (s.airglow_height + 0.5 * s.airglow_thickness) / 1000.0;
    const double t_ground = GroundDistance(r, mu, ground);
    const double t_lowest = std::min(std::max(-r * mu, 0.0), t_ground);
    const auto shell = [&](double t0, double t1) {
        return InsideLength(r, mu, high, t0, t1) - InsideLength(r, mu, low, t0, t1);
    };
    const double thickness = s.airglow_thickness / 1000.0;
    const double near = shell(0.0, t_lowest) / thickness;
    const double far = shell(t_lowest, t_ground) / thickness;
    glm::dvec3 l = frame.airglow * (glm::dvec3(near) + far * t);
    if (t == glm::dvec3(0.0)) return l;  // the ground is in the way of the rest
    l += (Zodiacal(night, direction) + Starlight(night, direction)) * t;
    // Light pollution: the city light scattered along the line of sight grows with the air's
    // optical depth along it, 1 - T, normalised at the ground's zenith (a Garstang-like horizon
    // brightening from the renderer's own transmittance: ~1 / (1 - T_zenith) at the horizon,
    // and less air, so less glow, above the ground).
    l += frame.light_pollution * (glm::dvec3(1.0) - t) + frame.scattered.At(mu);
    return l;
}

}  // namespace

glm::dvec3 NightSkyLuminance(const NightSky& night, const Atmosphere& atmosphere,
                             const ref::TransmittanceTexture& transmittance,
                             const glm::dvec3& camera_km, double camera_altitude_km,
                             const glm::dvec3& direction) {
    const auto parameters = MakeShaderParameters<ref::AtmosphereParameters>(atmosphere);
    return NightSkyLuminanceKm(
        night, MakeFrameConstants(night, parameters, transmittance, camera_km, camera_altitude_km),
        parameters, transmittance, camera_km, camera_altitude_km, direction);
}

glm::dvec3 NightSkyGroundIrradiance(const NightSky& night, const Atmosphere& atmosphere,
                                    const LutImage& transmittance, const glm::dvec3& position) {
    return NightSkyGroundIrradiance(night, atmosphere, ref::FromImage(transmittance), position);
}

glm::dvec3 NightSkyGroundIrradiance(const NightSky& night, const Atmosphere& atmosphere_si,
                                    const ref::TransmittanceTexture& transmittance,
                                    const glm::dvec3& position) {
    if (!night.enabled || !night.settings.enabled) return glm::dvec3(0.0);
    const auto atmosphere = MakeShaderParameters<ref::AtmosphereParameters>(atmosphere_si);
    const NightRadiance r =
        MeanNightRadiance(night, atmosphere, transmittance, glm::normalize(position));
    // The glows over the sky, E = 2 pi int L mu dmu: light pollution's, L = light_pollution
    // (1 - T), from the same quadrature as the direct light; the natural light's from the
    // scattered light's table seen from the ground, as the sky draws it (J at the ground alone
    // left blue 6 % short).
    const glm::dvec3 pollution = LightPollutionPerHaze(night.settings, atmosphere, transmittance) *
                                 4.0 * ref::kPi * r.ground_haze_cosine / r.directions;
    glm::dvec3 glow(0.0);
    if (night.settings.scattered) {
        const ScatteredNightLight scattered = MakeScatteredNightLight(r, atmosphere, 0.0);
        constexpr int kRings = 64;
        for (int i = 0; i < kRings; ++i) {
            const double mu = (i + 0.5) / kRings;
            glow += scattered.At(mu) * mu * (2.0 * ref::kPi / kRings);
        }
    }
    return r.ground_direct + glow + pollution;
}

void FillNightSkyMap(const NightSky& night, const Atmosphere& atmosphere_si,
                     const ref::TransmittanceTexture& transmittance, const glm::dvec3& camera_km,
                     double camera_altitude_km, const glm::dvec3& sun_direction, glm::ivec2 size,
                     std::vector<glm::vec4>& texels) {
    const auto atmosphere = MakeShaderParameters<ref::AtmosphereParameters>(atmosphere_si);
    texels.assign(static_cast<std::size_t>(size.x) * static_cast<std::size_t>(size.y),
                  glm::vec4(0.0f));
    const glm::dvec3 up = glm::normalize(camera_km);
    const glm::dvec3 frame_x = ref::SkyViewFrameX(up, glm::normalize(sun_direction));
    const FrameConstants frame =
        MakeFrameConstants(night, atmosphere, transmittance, camera_km, camera_altitude_km);
    for (int y = 0; y < size.y; ++y) {
        for (int x = 0; x < size.x; ++x) {
            const glm::dvec2 uv((x + 0.5) / size.x, (y + 0.5) / size.y);
            double view_zenith = 0.0, azimuth = 0.0;
            ref::GetViewFromSkyViewTextureUv(atmosphere, camera_altitude_km, uv, size, view_zenith,
                                             azimuth);
            const glm::dvec3 direction = ref::SkyViewDirection(up, frame_x, view_zenith, azimuth);
            texels[static_cast<std::size_t>(y) * static_cast<std::size_t>(size.x) +
                   static_cast<std::size_t>(x)] =
                glm::vec4(glm::vec3(NightSkyLuminanceKm(night, frame, atmosphere, transmittance,
                                                        camera_km, camera_altitude_km, direction)),
                          1.0f);
        }
    }
}

}  // namespace zenith::sky
