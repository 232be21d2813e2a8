// Where the twilight sky's error comes from (issue 18 §2), against the path tracer on the rays
// where H20's form failed the twilight grid (accuracy_report --grid twilight):
//
//   order <= 2     the renderer's Psi = order 2 alone against the path tracer's paths of at most
//                  two scattering vertices: what the second order's own treatment costs;
//   H20            order 2, then H20's series L_2 f_ms / (1 - f_ms) (Eq. 9-10), against
//                  unbounded paths;
//   iterated       orders 2 .. K, each integrated from the one before through the LUT, then the
//                  series and the plane-parallel column's correction of it (the renderer's LUT,
//                  LutSettings::multiple_scattering_orders = K), against unbounded paths.
//
// The three share one LUT resolution and sampling (kLutSize, kDirectionsSqrt, kSteps) and the
// renderer's shared GLSL. Since 484c981 every order carries the second moments of its light and
// the air scatters them with Rayleigh's phase (functions.glsl, MultipleScatteringSample); the
// table in BENCHMARKS.md ("before the fix") was made at ea3e6ee, when they were isotropic.
//
//   twilight_orders_report [--paths N] [--orders K] [--threads T]

#include <CLI/CLI.hpp>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <string>

#include "reference/atmosphere_functions.h"
#include "reference/lut_texture.h"
#include "shader_parameters.h"
#include "zenith/base/error.h"
#include "zenith/sky/atmosphere.h"
#include "zenith/sky/reference/accuracy.h"
#include "zenith/sky/reference/atmosphere_reference.h"
#include "zenith/sky/reference/path_tracer.h"

namespace {

namespace sky = zenith::sky;
namespace ref = zenith::sky::ref;

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr glm::ivec2 kLutSize{128, 64};
constexpr int kDirectionsSqrt = 16;
constexpr int kSteps = 40;
constexpr int kViewSteps = 100;

// The report's LUT resolution and sampling (LutSettings::Pc()'s, finer): `orders` orders.
sky::LutSettings Settings(int orders) {
    sky::LutSettings settings = sky::LutSettings::Pc();
    settings.multiple_scattering_size = kLutSize;
    settings.multiple_scattering_directions_sqrt = kDirectionsSqrt;
    settings.multiple_scattering_steps = kSteps;
    settings.multiple_scattering_orders = orders;
    return settings;
}

// A multiple-scattering LUT of the report's size, all zero.
ref::Texture2D EmptyMultipleScatteringTexture() {
    const glm::ivec2 size = Settings(2).multiple_scattering_texture_size();
    return ref::Texture2D(size.x, size.y);
}

// Order 2 alone and H20's series after it (AccumulateScatteringOrder with K = 2), from the
// renderer's shared GLSL at the report's resolution. The iterated LUT is AtmosphereReference's.
struct SecondOrderLuts {
    ref::Texture2D alone = EmptyMultipleScatteringTexture();
    ref::Texture2D h20 = EmptyMultipleScatteringTexture();
};

SecondOrderLuts BuildSecondOrder(const ref::AtmosphereParameters& atmosphere,
                                 const ref::Texture2D& transmittance) {
    SecondOrderLuts luts;
    const ref::Texture2D no_order(1, 1);  // order 2 reads no order before it
    for (int y = 0; y < kLutSize.y; ++y) {
        for (int x = 0; x < kLutSize.x; ++x) {
            const ref::vec2 uv((x + 0.5) / kLutSize.x, (y + 0.5) / kLutSize.y);
            const ref::ScatteringOrder o =
                ref::ComputeScatteringOrderTexel(atmosphere, transmittance, no_order, 2, uv,
                                                 kLutSize, kDirectionsSqrt, kSteps, 0, 1);
            const ref::MultipleScatteringSample h20 =
                ref::AccumulateScatteringOrder(o.light, o, 2, 2, ref::vec3(0.0));
            for (int tile = 0; tile < sky::kMultipleScatteringTiles; ++tile) {
                luts.alone.at(x + tile * kLutSize.x, y) =
                    ref::MultipleScatteringTexel(o.light, tile);
                luts.h20.at(x + tile * kLutSize.x, y) = ref::MultipleScatteringTexel(h20, tile);
            }
        }
    }
    return luts;
}

}  // namespace

int main(int argc, char** argv) {
    long paths = 262144;
    int orders = 6;
    int threads = 2;
    CLI::App app{"The twilight sky's error by scattering order (BENCHMARKS.md)"};
    app.add_option("--paths", paths, "path tracer's paths per ray")
        ->check(CLI::Range(2L, 1L << 26));
    app.add_option("--orders", orders, "K, the orders iterated through the LUT");
    app.add_option("--threads", threads, "0: every core")->check(CLI::Range(0, 1024));
    CLI11_PARSE(app, argc, argv);
    try {
        Settings(orders).Validate();  // LutSettings' own range for --orders
    } catch (const zenith::ArgumentError& e) {
        std::fprintf(stderr, "twilight_orders_report: %s\n", e.what());
        return 2;
    }

    sky::Atmosphere earth = sky::LoadAtmosphere("earth");
    earth.ground_albedo = glm::dvec3(0.0);
    const sky::reference::AtmosphereReference iterated(earth, Settings(orders));
    const auto atmosphere = sky::MakeShaderParameters<ref::AtmosphereParameters>(earth);
    const ref::Texture2D transmittance = ref::FromImage(iterated.transmittance());
    const SecondOrderLuts second_order = BuildSecondOrder(atmosphere, transmittance);
    const ref::Texture2D iterated_lut = ref::FromImage(iterated.multiple_scattering());
    const ref::Texture2D unused(1, 1);

    std::printf(
        "Earth preset, black ground; multiple-scattering LUT %dx%d, %d directions, %d steps, "
        "orders 2..%d then f_ms's tail; views marched in %d steps; path tracer %ld paths per "
        "ray, seed per ray. renderer / path tracer - 1, %% (R, G, B) ± the path tracer's "
        "standard error\n\n",
        kLutSize.x, kLutSize.y, kDirectionsSqrt * kDirectionsSqrt, kSteps, orders, kViewSteps,
        paths);
    std::printf(
        "| sun zenith | altitude | view | order <= 2 | H20 (all orders) | iterated (all orders) "
        "|\n|---|---|---|---|---|---|\n");
    const struct {
        const char* name;
        double elevation, azimuth;  // deg; azimuth from the sun's
    } views[] = {{"horizon, sun side", 1, 0},
                 {"horizon, 90 deg off", 1, 90},
                 {"horizon, anti-solar", 1, 180},
                 {"zenith", 90, 0}};
    std::uint64_t seed = 1;
    for (const double sun_zenith : {90.0, 95.0, 96.0}) {
        sky::Lights lights;
        lights.sun_direction = sky::reference::LocalDirection((90.0 - sun_zenith) * kDeg, 0.0);
        lights.sun_illuminance = earth.solar_illuminance;
        for (const double altitude : {1.0, 1e3, 5e3}) {  // m; "0 km" is 1 m
            const glm::dvec3 camera(0.0, earth.bottom_radius + altitude, 0.0);
            const auto light_set = sky::MakeLightSet<ref::LightSet>(lights, camera);
            for (const auto& view : views) {
                const glm::dvec3 direction =
                    sky::reference::LocalDirection(view.elevation * kDeg, view.azimuth * kDeg);
                const auto march = [&](const ref::Texture2D& multiple_scattering) {
                    return ref::IntegrateScatteredLuminance(atmosphere, transmittance,
                                                            multiple_scattering, unused, light_set,
                                                            camera / 1000.0, altitude / 1000.0,
                                                            direction, 0.0, 1e9, kViewSteps, true)
                        .luminance;
                };
                const auto trace = [&](int max_bounces) {
                    sky::reference::PathTraceOptions o;
                    o.samples = paths;
                    o.ground = false;
                    o.threads = threads;
                    o.max_bounces = max_bounces;
                    o.seed = seed++;
                    return sky::reference::PathTrace(earth, camera, direction, lights.sun_direction,
                                                     o);
                };
                const auto cell = [](const glm::dvec3& renderer,
                                     const sky::reference::PathTraceResult& pt) {
                    char text[128];
                    const glm::dvec3 e = 100.0 * (renderer / pt.luminance - 1.0);
                    const glm::dvec3 se =
                        100.0 * renderer / pt.luminance * (pt.standard_error / pt.luminance);
                    std::snprintf(text, sizeof(text), "%+.1f ± %.1f, %+.1f ± %.1f, %+.1f ± %.1f",
                                  e.x, se.x, e.y, se.y, e.z, se.z);
                    return std::string(text);
                };
                const sky::reference::PathTraceResult two = trace(2);
                const sky::reference::PathTraceResult all = trace(0);
                std::printf("| %.0f° | %.0f km | %s | %s | %s | %s |\n", sun_zenith,
                            altitude < 100.0 ? 0.0 : altitude / 1e3, view.name,
                            cell(march(second_order.alone), two).c_str(),
                            cell(march(second_order.h20), all).c_str(),
                            cell(march(iterated_lut), all).c_str());
                std::fflush(stdout);
            }
        }
    }
    return 0;
}
