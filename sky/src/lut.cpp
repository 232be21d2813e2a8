#include "zenith/sky/lut.h"

#include <stdexcept>
#include <string>

#include "zenith/base/error.h"

namespace zenith::sky {
namespace {

void Require(bool ok, const char* field, const std::string& value, const char* expected) {
    if (!ok) {
        throw ArgumentError(std::string("LUT setting ") + field + " = " + value +
                            " is out of range (expected " + expected + ")");
    }
}

std::string Str(glm::ivec2 v) { return std::to_string(v.x) + "x" + std::to_string(v.y); }
std::string Str(glm::ivec3 v) {
    return std::to_string(v.x) + "x" + std::to_string(v.y) + "x" + std::to_string(v.z);
}

bool InRange(glm::ivec2 v, int lo, int hi) {
    return v.x >= lo && v.y >= lo && v.x <= hi && v.y <= hi;
}

}  // namespace

LutSettings LutSettings::Mobile() {
    // Hillaire 2020, Table 2, iPhone 6s column.
    LutSettings s;
    s.sky_view_size = {96, 50};
    s.sky_view_steps = 8;
    s.aerial_perspective_size = {32, 32, 16};
    s.aerial_perspective_steps = 8;
    return s;
}

void LutSettings::Validate() const {
    Require(InRange(transmittance_size, 2, 4096), "transmittance_size", Str(transmittance_size),
            "2..4096 per axis");
    Require(transmittance_steps >= 1 && transmittance_steps <= 10000, "transmittance_steps",
            std::to_string(transmittance_steps), "1..10000");
    Require(InRange(multiple_scattering_size, 2, 1024), "multiple_scattering_size",
            Str(multiple_scattering_size), "2..1024 per axis");
    Require(multiple_scattering_directions_sqrt >= 1 && multiple_scattering_directions_sqrt <= 64,
            "multiple_scattering_directions_sqrt",
            std::to_string(multiple_scattering_directions_sqrt), "1..64");
    Require(multiple_scattering_steps >= 1 && multiple_scattering_steps <= 10000,
            "multiple_scattering_steps", std::to_string(multiple_scattering_steps), "1..10000");
    Require(irradiance_size.x >= 2 && irradiance_size.x <= 4096 && irradiance_size.y >= 1 &&
                irradiance_size.y <= 4096,
            "irradiance_size", Str(irradiance_size), "2..4096 x 1..4096");
    Require(irradiance_directions_sqrt >= 1 && irradiance_directions_sqrt <= 64,
            "irradiance_directions_sqrt", std::to_string(irradiance_directions_sqrt), "1..64");
    Require(irradiance_steps >= 1 && irradiance_steps <= 10000, "irradiance_steps",
            std::to_string(irradiance_steps), "1..10000");
    Require(InRange(sky_view_size, 2, 4096), "sky_view_size", Str(sky_view_size),
            "2..4096 per axis");
    Require(sky_view_steps >= 1 && sky_view_steps <= 10000, "sky_view_steps",
            std::to_string(sky_view_steps), "1..10000");
    const glm::ivec3 ap = aerial_perspective_size;
    Require(ap.x >= 2 && ap.y >= 2 && ap.z >= 2 && ap.x <= 512 && ap.y <= 512 && ap.z <= 512,
            "aerial_perspective_size", Str(ap), "2..512 per axis");
    Require(aerial_perspective_range > 0.0 && aerial_perspective_range <= 1e7,
            "aerial_perspective_range", std::to_string(aerial_perspective_range) + " m",
            "0 < range <= 1e7 m");
    Require(aerial_perspective_steps >= 2 && aerial_perspective_steps <= 10000,
            "aerial_perspective_steps", std::to_string(aerial_perspective_steps), "2..10000");
}

}  // namespace zenith::sky
