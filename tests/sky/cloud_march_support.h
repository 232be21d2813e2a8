// The renderer's cloud march on the CPU in a bare sunlight, shared by the cloud tests and the
// cloud reference report: a sun of unit illuminance through a transparent atmosphere without
// sky light, so what the march returns is the clouds' share of the sunlight alone.
#pragma once

#include <cmath>

#include "clouds/cloud_parameters.h"
#include "reference/cloud_march.h"

namespace zenith::sky::ref {
namespace {  // like the shared GLSL types it uses (reference/cloud_march.h)

constexpr double kR = 6360.0;  // km

// A sun of unit illuminance normal to its rays through a transparent atmosphere with no sky
// light: what the march returns is the clouds' share of the sunlight alone.
struct Sunlight {
    AtmosphereParameters atmosphere{};
    Texture2D transmittance{1, 1}, irradiance{1, 1};
    LightSet lights{};

    explicit Sunlight(double mu0) {
        atmosphere.bottom_radius = kR;
        atmosphere.top_radius = kR + 100.0;
        atmosphere.sun_angular_radius = 0.00465;
        transmittance.at(0, 0) = vec4(1.0);
        irradiance.at(0, 0) = vec4(0.0);
        lights.light[0].direction = vec3(std::sqrt(1.0 - mu0 * mu0), 0.0, mu0);
        lights.light[0].illuminance = vec3(1.0);
        lights.count = 1;
    }
};

// The renderer's defaults (CloudSettings{}), in the shaders' units, over a grey ground.
CloudScatteringParameters DefaultScattering(double ground_albedo = 0.0) {
    return MakeCloudScatteringParameters<CloudScatteringParameters>(CloudSettings{},
                                                                    vec3(ground_albedo));
}
// Luminance of the clouds alone along `view` from `camera` (cloud frame, km), averaged over
// `jitters` sample offsets in the step as the renderer's reprojection averages them.
double CloudLuminance(const Sunlight& sun, const CloudLayerParameters& layer,
                      const RepeatTexture2D& weather, const Texture3D& shape,
                      const Texture3D& detail, const CloudScatteringParameters& scattering,
                      const CloudMarchParameters& march, vec3 camera, vec3 view, int jitters) {
    const double r = length(camera);
    const vec2 interval =
        CloudLayerInterval(layer, r, dot(camera, view) / r, r - kR, march.max_distance);
    double sum = 0.0;
    for (int j = 0; j < jitters; ++j) {
        CloudMarchState state = CloudMarchStart();
        MarchCloudLayer(sun.atmosphere, sun.transmittance, {1, 1}, sun.irradiance, {1, 1}, layer,
                        weather, shape, detail, scattering, march, sun.lights, 1, camera, view,
                        interval, (j + 0.5) / jitters, state);
        sum += state.luminance.x;
    }
    return sum / jitters;
}

}  // namespace
}  // namespace zenith::sky::ref
