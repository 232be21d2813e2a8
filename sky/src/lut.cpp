#include "zenith/sky/lut.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "bindings.h"
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

glm::ivec2 LutSettings::multiple_scattering_texture_size() const {
    return {multiple_scattering_size.x * kMultipleScatteringTiles, multiple_scattering_size.y};
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
    Require(multiple_scattering_orders >= 2 && multiple_scattering_orders <= 32,
            "multiple_scattering_orders", std::to_string(multiple_scattering_orders), "2..32");
    Require(multiple_scattering_column_layers == 0 || (multiple_scattering_column_layers >= 16 &&
                                                       multiple_scattering_column_layers <= 512),
            "multiple_scattering_column_layers", std::to_string(multiple_scattering_column_layers),
            "0 or 16..512");
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

std::vector<StarPoint> ResolveDisks(const std::vector<StarPoint>& points, double pixel) {
    std::vector<StarPoint> out;
    out.reserve(points.size());
    for (const StarPoint& point : points) {
        if (!(point.angular_radius > 0.5 * pixel)) {
            out.push_back(point);
            continue;
        }
        // The disk in its tangent plane: e1, e2 across it, `toward` the observer's side.
        const glm::dvec3 d = glm::normalize(point.direction);
        const glm::dvec3 helper = std::abs(d.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0);
        const glm::dvec3 e1 = glm::normalize(glm::cross(helper, d));
        const glm::dvec3 e2 = glm::cross(d, e1);
        const bool lit = glm::length(point.sunward) > 0.0;
        const glm::dvec3 sun = lit ? glm::normalize(point.sunward) : glm::dvec3(0.0);
        const int n =
            std::clamp(static_cast<int>(std::ceil(4.0 * point.angular_radius / pixel)), 2, 64);
        const std::size_t first = out.size();
        double total = 0.0;
        for (int j = 0; j < n; ++j) {
            for (int i = 0; i < n; ++i) {
                const double u = -1.0 + (2.0 * i + 1.0) / n, v = -1.0 + (2.0 * j + 1.0) / n;
                const double rho2 = u * u + v * v;
                if (rho2 >= 1.0) continue;
                // The sphere's normal there, facing the observer (-d).
                const glm::dvec3 normal = u * e1 + v * e2 - std::sqrt(1.0 - rho2) * d;
                const double weight = lit ? std::max(glm::dot(normal, sun), 0.0) : 1.0;
                if (!(weight > 0.0)) continue;
                StarPoint p = point;  // its disk's radius marks it as part of one
                p.direction =
                    glm::normalize(d + std::tan(point.angular_radius) * (u * e1 + v * e2));
                p.illuminance = glm::dvec3(weight);
                out.push_back(p);
                total += weight;
            }
        }
        for (std::size_t k = first; k < out.size(); ++k) {
            out[k].illuminance = point.illuminance * (out[k].illuminance.x / total);
        }
    }
    return out;
}

}  // namespace zenith::sky
