// Atmosphere parameters (SI units, public API) and presets.
//
// The model is that of Hillaire (2020) and Bruneton & Neyret (2008): a spherical planet of radius
// bottom_radius with an atmosphere up to top_radius, made of
//   - Rayleigh scatterers, density exp(-h / rayleigh_scale_height),
//   - Mie scatterers (aerosols), density exp(-h / mie_scale_height), phase Cornette-Shanks(mie_g),
//   - an absorbing layer (ozone on Earth), density max(0, 1 - |h - absorption_center| /
//     (absorption_width / 2)), a tent,
// and a Lambertian ground of albedo ground_albedo. RGB channels are the linear Rec.709 primaries;
// luminance is Y = 0.2126 R + 0.7152 G + 0.0722 B. Coefficients are per metre at density 1.
#pragma once

#include <filesystem>
#include <glm/glm.hpp>
#include <stdexcept>
#include <string>
#include <string_view>

#include "zenith/base/error.h"

namespace zenith::sky {

// Thrown for an invalid parameter or preset file; the message names the file (and line where
// the JSON parser knows it), the field, its value, its unit and the allowed range.
class AtmosphereError : public InputError {
  public:
    using InputError::InputError;
};

struct Atmosphere {
    std::string name = "earth";
    double bottom_radius = 6360e3;                                 // m
    double top_radius = 6460e3;                                    // m
    glm::dvec3 rayleigh_scattering{5.802e-6, 13.558e-6, 33.1e-6};  // 1/m (Hillaire 2020, Table 1)
    double rayleigh_scale_height = 8000.0;                         // m
    glm::dvec3 mie_scattering{3.996e-6};                           // 1/m
    // 0.444e-6, not Hillaire 2020 Table 1's "4.40": the table's value is a slip. Hillaire's own
    // demo (UnrealEngineSkyAtmosphere) and Bruneton's (precomputed_atmospheric_scattering) use
    // extinction 4.44e-6 = scattering / 0.9, a single-scattering albedo of 0.9; 4.40e-6 would
    // make it 0.48, dark haze. Sources: data/presets/README.md.
    glm::dvec3 mie_absorption{0.444e-6};  // 1/m
    double mie_scale_height = 1200.0;     // m
    double mie_g = 0.8;                   // Cornette-Shanks asymmetry, (-1, 1)
    glm::dvec3 absorption_extinction{0.650e-6, 1.881e-6, 0.085e-6};  // 1/m (ozone)
    double absorption_center = 25000.0;                              // m above the ground
    double absorption_width = 30000.0;                               // m, full width of the tent
    glm::dvec3 ground_albedo{0.3};                                   // [0, 1]
    // Solar illuminance at the top of the atmosphere, lux, per channel (white: equal channels).
    glm::dvec3 solar_illuminance{127000.0};
    double sun_angular_radius = 0.004675;  // rad (0.2679 deg at 1 au)

    // Extinction = scattering + absorption of each component, 1/m.
    glm::dvec3 MieExtinction() const { return mie_scattering + mie_absorption; }

    // Exact, member by member (NaN is unequal to itself): for round-trip tests and for noticing
    // that parameters changed and the LUTs must be recomputed.
    bool operator==(const Atmosphere&) const = default;
};

// Throws AtmosphereError naming the first invalid field (member name, value in SI, unit, allowed
// range). Ranges, with the reason where it is not obvious:
//   bottom_radius > 0; bottom_radius < top_radius <= bottom_radius + 1000 km (the LUT
//     parameterisations spread their texels over the thickness; 1000 km is ten Earth atmospheres);
//   every scattering/absorption/extinction channel finite, >= 0 and < 1 /m (a mean free path
//     under a metre is fog, not an atmosphere, and a unit slip of 1000 lands there);
//   scale heights > 0 and finite;
//   -1 < mie_g < 1, strictly: at |g| = 1 the Cornette-Shanks phase function is a Dirac delta
//     (infinite at theta = 0 or pi), which the LUTs cannot sample;
//   0 <= absorption_center <= top_radius - bottom_radius; absorption_width > 0;
//   ground_albedo in [0, 1] per channel (a Lambertian surface cannot reflect more than it gets);
//   solar_illuminance > 0 and finite per channel; 0 < sun_angular_radius <= 45 deg;
//   name non-empty.
void Validate(const Atmosphere& atmosphere);

// Reads a preset: a built-in name ("earth", "mars", "thick") resolved in PresetDirectory(), or a
// path to a JSON file (anything with a '/' or ending in ".json"). Unknown keys are an error (a
// typo must not silently keep a default). The result is validated.
//
// The file format (data/presets/README.md has the sources of the shipped values). Units are in
// the key names, those of the atmosphere literature (km, 1/km); each RGB value may also be one
// number for three equal channels:
//   {
//     "name": "earth",                       optional, default: the file's stem
//     "description": "...",                  optional, ignored
//     "bottom_radius_km": 6360,
//     "top_radius_km": 6460,
//     "rayleigh": {"scattering_per_km": [0.005802, 0.013558, 0.0331], "scale_height_km": 8},
//     "mie": {"scattering_per_km": 0.003996, "absorption_per_km": 0.000444,
//             "scale_height_km": 1.2, "g": 0.8},
//     "absorption": {"extinction_per_km": [0.00065, 0.001881, 0.000085],
//                    "center_km": 25, "width_km": 30},       optional, default: none
//     "ground_albedo": 0.3,
//     "solar_illuminance_lux": 127000,
//     "sun_angular_radius_deg": 0.26786
//   }
// All other keys are required. Powers of ten are converted by shifting the decimal exponent, so
// "0.005802" per km becomes exactly the double nearest to 5.802e-6 per m.
Atmosphere LoadAtmosphere(std::string_view name_or_path);
// As LoadAtmosphere, from text; source_name is used in messages and as the default name.
Atmosphere ParseAtmosphereJson(std::string_view json_text, std::string_view source_name);
// The format above; ParseAtmosphereJson(AtmosphereToJson(a), ...) == a for a valid a.
std::string AtmosphereToJson(const Atmosphere& atmosphere);

// Where built-in presets live: $ZENITH_DATA_DIR/presets if that variable is set (even if the
// directory is missing, so a wrong setting is reported rather than masked), else the installed
// data directory if it exists, else the source tree's data/presets.
std::filesystem::path PresetDirectory();

}  // namespace zenith::sky
