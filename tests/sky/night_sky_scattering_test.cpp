// The night sky's light scattered by the air (night_sky.cpp, ScatteredNightLight) against the
// path tracer under the same light: a uniform radiance above the atmosphere, from the ground.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>

#include "luminance.h"
#include "night_sky_map.h"
#include "reference/lut_texture.h"
#include "zenith/sky/night_sky.h"
#include "zenith/sky/reference/atmosphere_reference.h"
#include "zenith/sky/reference/path_tracer.h"

namespace zenith::sky {
namespace {

using zenith::test::Luminance;

TEST(NightSkyScattering, AgainstThePathTracerUnderAUniformSky) {
    // 1 cd/m^2 of white light above the air from every direction (the starlight map made
    // uniform; no airglow, zodiacal light or light pollution). The renderer's night light, with
    // and without what the air scatters, against the path tracer's scattered light plus the
    // direct light through its own optical depth. The uniform-source model was within 0.1-6.2 %
    // of the scattered light at 65536 paths (BENCHMARKS.md); the path tracer's SE here is ~1 %.
    const Atmosphere earth;
    const reference::AtmosphereReference renderer(earth);
    const ref::TransmittanceTexture transmittance = ref::FromImage(renderer.transmittance());
    NightSky night;
    night.enabled = true;
    night.settings.airglow_zenith_brightness = 30.0;  // 1e-7 cd/m^2: none
    night.settings.zodiacal_light = false;
    auto uniform = std::make_shared<StarlightMap>();
    uniform->width = 4;
    uniform->height = 2;
    uniform->texels.assign(8, glm::dvec3(1.0));
    night.starlight = uniform;
    NightSky direct_only = night;
    direct_only.settings.scattered = false;
    const glm::dvec3 position(0.0, earth.bottom_radius + 1.0, 0.0);
    for (const double elevation_deg : {90.0, 20.0, 5.0, 1.0}) {
        const double e = elevation_deg * M_PI / 180.0;
        const glm::dvec3 view(std::cos(e), std::sin(e), 0.0);
        reference::PathTraceOptions trace;
        trace.samples = 16384;
        trace.threads = 2;
        const reference::PathTraceResult scattered =
            reference::PathTraceUniformSky(earth, position, view, trace);
        const auto top = reference::IntersectSphere(position, view, earth.top_radius);
        ASSERT_TRUE(top.has_value());
        const double direct =
            Luminance(glm::exp(-reference::OpticalDepth(earth, position, view, top->t_far)));
        const double reference_total = direct + Luminance(scattered.luminance);
        const auto model = [&](const NightSky& n) {
            return NightSkyLuminance(n, earth, transmittance, position / 1000.0, 1e-3, view);
        };
        // Its colour too: R, G and B each (the light reddens through the air it crosses first).
        const glm::dvec3 scattered_rgb = model(night) - model(direct_only);
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(scattered_rgb[c] / scattered.luminance[c], 1.0, 0.10)
                << "channel " << c << " at " << elevation_deg << " deg";
        }
        const double total = Luminance(model(night)), without = Luminance(model(direct_only));
        std::printf(
            "elevation %4.1f deg: scattered %.3f (path tracer %.3f +- %.3f), total %.3f (%.3f), "
            "without the scattered light %.3f\n",
            elevation_deg, total - without, Luminance(scattered.luminance),
            Luminance(scattered.standard_error), total, reference_total, without);
        EXPECT_NEAR((total - without) / Luminance(scattered.luminance), 1.0, 0.10);
        EXPECT_NEAR(total / reference_total, 1.0, 0.06);
    }
}

}  // namespace
}  // namespace zenith::sky
