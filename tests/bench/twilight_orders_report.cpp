// Where the twilight sky's error comes from (issue 18 §2): H20's multiple-scattering LUT makes two
// assumptions past the second order and one in it, and this report measures each against the
// path tracer on the rays where the twilight grid fails (accuracy_report --grid twilight):
//
//   order <= 2     the renderer with Psi = L_2 only (H20 Eq. 5-6: the second order, scattered
//                  isotropically at both vertices) against the path tracer's paths of at most two
//                  scattering vertices: what the isotropic second order alone costs;
//   H20            Psi = L_2 / (1 - f_ms) (Eq. 9-10, the shipped form) against unbounded paths;
//   iterated       Psi = L_2 + L_3 + ... + L_K + L_K f_ms / (1 - f_ms), each order L_(n+1)
//                  integrated from L_n through the LUT (isotropic transfer, as H20's f_ms; the
//                  LUT stays 2-D because the atmosphere is spherically symmetric), against
//                  unbounded paths: what H20's local geometric series costs.
//
// The three share one LUT resolution (converged: see BENCHMARKS.md) and the renderer's single
// scattering (IntegrateScatteredLuminance, the shared GLSL). The LUT loop below is a second
// form of ComputeMultipleScatteringTexel on purpose: it is the prototype of orders the shader
// does not have yet, and goes when the shader has them.
//
//   twilight_orders_report [--paths N] [--orders K] [--threads T]

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <numbers>
#include <string>
#include <vector>

#include "reference/atmosphere_functions.h"
#include "reference/lut_texture.h"
#include "shader_parameters.h"
#include "zenith/sky/atmosphere.h"
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

struct OrderTexel {
    ref::vec3 luminance{0.0};  // L_n per unit sun illuminance
    ref::vec3 f_ms{0.0};       // H20 Eq. 7-8
};

// One texel of order n + 1 from `previous` (order n), or of order 2 from the sun when `previous`
// is null. Black ground (the twilight grid's).
OrderTexel ComputeOrderTexel(const ref::AtmosphereParameters& atmosphere,
                             const ref::Texture2D& transmittance, const ref::Texture2D* previous,
                             ref::vec2 uv) {
    using namespace ref;
    const Number mu_s = SunCosineFromUnitRange(GetUnitRangeFromTextureCoord(uv.x, kLutSize.x));
    const Number x_h = GetUnitRangeFromTextureCoord(uv.y, kLutSize.y);
    Number r = atmosphere.bottom_radius +
               std::clamp(x_h, 0.0, 1.0) * (atmosphere.top_radius - atmosphere.bottom_radius);
    r = std::clamp(r, atmosphere.bottom_radius + 1e-4, atmosphere.top_radius - 1e-4);
    const vec3 position(0.0, 0.0, r);
    const vec3 sun_direction(SafeSqrt(1.0 - mu_s * mu_s), 0.0, mu_s);
    const int n = kDirectionsSqrt * kDirectionsSqrt;
    OrderTexel texel;
    for (int i = 0; i < n; ++i) {
        const vec3 direction = UniformSphereDirection(i, n);
        const Number mu = direction.z;
        const Number t_max = RayIntersectsGround(atmosphere, r, mu)
                                 ? DistanceToBottomAtmosphereBoundary(atmosphere, r, mu)
                                 : DistanceToTopAtmosphereBoundary(atmosphere, r, mu);
        const Number dt = t_max / Number(kSteps);
        vec3 throughput(1.0), l(0.0), l_f(0.0);
        for (int j = 0; j < kSteps; ++j) {
            const vec3 p = position + direction * ((Number(j) + 0.5) * dt);
            const Number r_p = length(p);
            const MediumSample s = SampleMedium(atmosphere, r_p - atmosphere.bottom_radius);
            const Number mu_s_p = dot(p, sun_direction) / r_p;
            const vec3 integral = StepIntegral(s.extinction, dt);
            // Orders >= 3 transfer isotropically with the aerosols' reduced scattering, as f_ms.
            const vec3 reduced = s.scattering - s.mie_scattering * atmosphere.mie_g;
            if (previous == nullptr) {
                const vec3 sun = GetTransmittanceToSun(atmosphere, transmittance, r_p, mu_s_p);
                l += throughput * s.scattering * sun * IsotropicPhase() * integral;
            } else {
                l += throughput * reduced *
                     GetMultipleScattering(atmosphere, *previous, r_p, mu_s_p) * integral;
            }
            l_f += throughput * reduced * integral;
            throughput *= exp(-s.extinction * dt);
        }
        texel.luminance += l / Number(n);
        texel.f_ms += l_f / Number(n);
    }
    return texel;
}

struct Luts {
    ref::Texture2D second_order{kLutSize.x, kLutSize.y};
    ref::Texture2D h20{kLutSize.x, kLutSize.y};
    ref::Texture2D iterated{kLutSize.x, kLutSize.y};
};

ref::vec3 GeometricTail(const ref::vec3& f_ms) {
    const ref::vec3 f = glm::min(f_ms, ref::vec3(0.999));
    return f / (ref::vec3(1.0) - f);
}

Luts BuildLuts(const ref::AtmosphereParameters& atmosphere, const ref::Texture2D& transmittance,
               int orders) {
    Luts luts;
    ref::Texture2D order(kLutSize.x, kLutSize.y), f_ms(kLutSize.x, kLutSize.y);
    const auto uv = [](int x, int y) {
        return ref::vec2((x + 0.5) / kLutSize.x, (y + 0.5) / kLutSize.y);
    };
    for (int y = 0; y < kLutSize.y; ++y) {
        for (int x = 0; x < kLutSize.x; ++x) {
            const OrderTexel t = ComputeOrderTexel(atmosphere, transmittance, nullptr, uv(x, y));
            luts.second_order.at(x, y) = ref::vec4(t.luminance, 1.0);
            luts.h20.at(x, y) =
                ref::vec4(t.luminance * (ref::vec3(1.0) + GeometricTail(t.f_ms)), 1.0);
            luts.iterated.at(x, y) = ref::vec4(t.luminance, 1.0);
            order.at(x, y) = ref::vec4(t.luminance, 1.0);
            f_ms.at(x, y) = ref::vec4(t.f_ms, 1.0);
        }
    }
    for (int k = 3; k <= orders; ++k) {
        ref::Texture2D next(kLutSize.x, kLutSize.y);
        for (int y = 0; y < kLutSize.y; ++y) {
            for (int x = 0; x < kLutSize.x; ++x) {
                const OrderTexel t = ComputeOrderTexel(atmosphere, transmittance, &order, uv(x, y));
                next.at(x, y) = ref::vec4(t.luminance, 1.0);
                luts.iterated.at(x, y) += ref::vec4(t.luminance, 0.0);
            }
        }
        order = next;
    }
    for (int y = 0; y < kLutSize.y; ++y) {
        for (int x = 0; x < kLutSize.x; ++x) {
            const ref::vec3 tail =
                ref::vec3(order.at(x, y)) * GeometricTail(ref::vec3(f_ms.at(x, y)));
            luts.iterated.at(x, y) += ref::vec4(tail, 0.0);
        }
    }
    return luts;
}

glm::dvec3 LocalDirection(double elevation, double azimuth) {
    return {std::cos(elevation) * std::cos(azimuth), std::sin(elevation),
            std::cos(elevation) * std::sin(azimuth)};
}

[[noreturn]] void Usage(const std::string& message) {
    std::fprintf(stderr,
                 "twilight_orders_report: %s\nusage: twilight_orders_report [--paths N] "
                 "[--orders K] [--threads T]\n",
                 message.c_str());
    std::exit(2);
}

long ParseCount(const char* flag, const char* text, long low, long high) {
    char* end = nullptr;
    const long value = std::strtol(text, &end, 10);
    if (end == text || *end != '\0' || value < low || value > high) {
        Usage(std::string(flag) + " " + text + " is not an integer in [" + std::to_string(low) +
              ", " + std::to_string(high) + "]");
    }
    return value;
}

}  // namespace

int main(int argc, char** argv) {
    long paths = 262144;
    int orders = 6;
    int threads = 2;
    for (int i = 1; i < argc; ++i) {
        if (i + 1 >= argc) Usage(std::string("missing value after ") + argv[i]);
        const char* flag = argv[i];
        const char* value = argv[++i];
        if (!std::strcmp(flag, "--paths")) {
            paths = ParseCount(flag, value, 2, 1L << 26);
        } else if (!std::strcmp(flag, "--orders")) {
            orders = static_cast<int>(ParseCount(flag, value, 2, 50));
        } else if (!std::strcmp(flag, "--threads")) {
            threads = static_cast<int>(ParseCount(flag, value, 0, 1024));
        } else {
            Usage(std::string("unknown option ") + flag);
        }
    }

    sky::Atmosphere earth = sky::LoadAtmosphere("earth");
    earth.ground_albedo = glm::dvec3(0.0);
    const sky::reference::AtmosphereReference shipped(earth, sky::LutSettings::Pc());
    const auto atmosphere = sky::MakeShaderParameters<ref::AtmosphereParameters>(earth);
    const ref::Texture2D transmittance = ref::FromImage(shipped.transmittance());
    const Luts luts = BuildLuts(atmosphere, transmittance, orders);
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
        lights.sun_direction = LocalDirection((90.0 - sun_zenith) * kDeg, 0.0);
        lights.sun_illuminance = earth.solar_illuminance;
        for (const double altitude : {1.0, 1e3, 5e3}) {  // m; "0 km" is 1 m
            const glm::dvec3 camera(0.0, earth.bottom_radius + altitude, 0.0);
            const auto light_set = sky::MakeLightSet<ref::LightSet>(lights, camera);
            for (const auto& view : views) {
                const glm::dvec3 direction =
                    LocalDirection(view.elevation * kDeg, view.azimuth * kDeg);
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
                            cell(march(luts.second_order), two).c_str(),
                            cell(march(luts.h20), all).c_str(),
                            cell(march(luts.iterated), all).c_str());
                std::fflush(stdout);
            }
        }
    }
    return 0;
}
