#include "clouds/cloud_parameters.h"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "zenith/base/error.h"

namespace zenith::sky {
namespace {

void Require(bool ok, const char* field, double value, const char* expected) {
    if (!ok) {
        std::ostringstream text;
        text << "CloudSettings::" << field << " = " << value << " (expected " << expected << ")";
        throw ArgumentError(text.str());
    }
}

}  // namespace

void CloudSettings::Validate() const {
    Require(std::isfinite(extinction) && extinction > 0.0 && extinction <= 10.0, "extinction",
            extinction, "0 < 1/m <= 10");
    Require(albedo >= 0.0 && albedo <= 1.0, "albedo", albedo, "[0, 1]");
    Require(forward_g > -1.0 && forward_g < 1.0, "forward_g", forward_g, "(-1, 1)");
    Require(backward_g > -1.0 && backward_g < 1.0, "backward_g", backward_g, "(-1, 1)");
    Require(lobe_weight >= 0.0 && lobe_weight <= 1.0, "lobe_weight", lobe_weight, "[0, 1]");
    Require(multiple_scattering >= 0.0 && multiple_scattering <= 1.0, "multiple_scattering",
            multiple_scattering, "[0, 1]");
    Require(ambient_scale >= 0.0 && ambient_scale <= 10.0, "ambient_scale", ambient_scale,
            "[0, 10]");
    Require(shape_period >= 100.0 && shape_period <= 1e6, "shape_period", shape_period,
            "100 m .. 1000 km");
    Require(detail_period >= 10.0 && detail_period <= 1e5, "detail_period", detail_period,
            "10 m .. 100 km");
    Require(erosion >= 0.0 && erosion <= 0.9, "erosion", erosion, "[0, 0.9]");
    Require(min_step >= 1.0 && min_step <= 10000.0, "min_step", min_step, "1 m .. 10 km");
    Require(max_steps >= 1 && max_steps <= 4096, "max_steps", max_steps, "1..4096");
    Require(shadow_steps >= 0 && shadow_steps <= 64, "shadow_steps", shadow_steps, "0..64");
    Require(shadow_first_step > 0.0 && shadow_first_step <= 10000.0, "shadow_first_step",
            shadow_first_step, "0 < m <= 10 km");
    Require(shadow_growth >= 1.0 && shadow_growth <= 4.0, "shadow_growth", shadow_growth, "[1, 4]");
    Require(thick_step_refinement >= 0 && thick_step_refinement <= 3, "thick_step_refinement",
            thick_step_refinement, "0..3");
    Require(min_transmittance >= 0.0 && min_transmittance < 1.0, "min_transmittance",
            min_transmittance, "[0, 1)");
    Require(max_distance > 0.0 && max_distance <= 1e7, "max_distance", max_distance,
            "0 < m <= 10000 km");
    Require(aerial_perspective_steps >= 1 && aerial_perspective_steps <= 256,
            "aerial_perspective_steps", aerial_perspective_steps, "1..256");
    Require(light_shaft_steps >= 0 && light_shaft_steps <= 256, "light_shaft_steps",
            light_shaft_steps, "0..256");
    Require(block >= 1 && block <= 8, "block", block, "1..8");
    Require(history_weight >= 0.0 && history_weight < 1.0, "history_weight", history_weight,
            "[0, 1)");
    Require(shadow_map_size >= 8 && shadow_map_size <= 4096, "shadow_map_size", shadow_map_size,
            "8..4096");
    Require(shadow_map_extent >= 1000.0 && shadow_map_extent <= 1e6, "shadow_map_extent",
            shadow_map_extent, "1 km .. 1000 km");
    Require(shadow_map_steps >= 1 && shadow_map_steps <= 256, "shadow_map_steps", shadow_map_steps,
            "1..256");
    Require(shadow_map_interval >= 1 && shadow_map_interval <= 1000, "shadow_map_interval",
            shadow_map_interval, "1..1000");
    const int stage = static_cast<int>(pass_stage);
    Require(stage >= static_cast<int>(CloudPassStage::kAuto) &&
                stage <= static_cast<int>(CloudPassStage::kCompute),
            "pass_stage", stage, "0 kAuto, 1 kFragment or 2 kCompute");
}

std::vector<int> CloudLayerOrder(const clouds::Weather& weather, double camera_altitude) {
    std::vector<int> order;
    const int count = static_cast<int>(weather.layers.size());
    for (int i = count - 1; i >= 0; --i) {
        if (weather.layers[static_cast<std::size_t>(i)].base_altitude <= camera_altitude) {
            order.push_back(i);
        }
    }
    for (int i = 0; i < count; ++i) {
        if (weather.layers[static_cast<std::size_t>(i)].base_altitude > camera_altitude) {
            order.push_back(i);
        }
    }
    return order;
}

}  // namespace zenith::sky
