// Accuracy of the LUT renderer against the path tracer, as markdown tables (BENCHMARKS.md, "sky:
// accuracy against the path tracer"). Not a Google Benchmark: a plain main, built by
// tests/bench/CMakeLists.txt's glob.
//
//   accuracy_report [--grid paper] [--width W] [--height H] [--samples N] [--thick-samples N]
//                   [--threads T] [--seed S] [--only NAME] [--ms-* ...]
//   accuracy_report --grid twilight [--samples N] [--max-samples M] [--target-se E]
//                   [--converged-se C] [--threads T] [--seed S] [--ms-* ...]
//   accuracy_report --grid haze [--samples N] [--threads T] [--seed S] [--ms-* ...]
//                   [--haze-mie-g G] [--haze-ground-albedo A]
//   accuracy_report --grid illuminance|night [--samples N] [--threads T] [--seed S]
//
// --ms-width W, --ms-height H, --ms-directions-sqrt D, --ms-steps N, --ms-orders K rebuild the
// renderer's multiple-scattering LUT (LutSettings) for the paper, twilight and haze grids; --help
// lists every option.
//
// paper: the scenarios of Hillaire 2020 §6 as images. Defaults (96x64, 1024 paths per pixel, 256
// for the 50x atmosphere whose paths scatter hundreds of times) take several minutes on 2 cores.
//
// haze (issue 18 §2, dense atmospheres): the Earth preset's aerosols set for a METAR's
// visibility (200 m to 23 km), three views from the ground, the Sky-View LUT against the path
// tracer, with single scattering alone on both sides (N paths per ray, default 16384).
// --haze-mie-g and --haze-ground-albedo change the aerosols' asymmetry (the preset's 0.8) and the
// ground's albedo (0.3) in both, to take the error apart (BENCHMARKS.md, "Hazy air").
//
// illuminance (issue 18 §2, measured twilight): the sky's horizontal illuminance on the ground,
// sun +10 to -12 deg: the renderer's ground-irradiance LUT (as shipped and converged), the path
// tracer (N paths per direction, default 64) and Brown's (1952) measurements.
//
// twilight (issue 18 §2): single view rays on the Earth preset (black ground, no sun disk), sun
// zenith 80-102 deg x observer altitude 0 (1 m), 1, 5, 10 km x four views (horizon toward the
// sun, 90 deg off it, away from it; the zenith). The renderer is the Sky-View LUT read as
// render.frag reads it (every camera here is inside the atmosphere); the reference is PathTrace.
// Each ray gets N paths, then doubles them until the path tracer's relative standard error is
// below E in every channel or M paths are spent (defaults 16384, 1048576, 0.01); a ray that
// cannot reach C (below) within M at its rate after 65536 paths stops there. The summary
// (median and p95 of |renderer / path tracer - 1|) keeps the rays whose relative standard error
// is <= C (0.025) in every channel; past sunset the path tracer may not get there within M.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "night_sky_map.h"
#include "reference/lut_texture.h"
#include "zenith/base/error.h"
#include "zenith/sky/lighting.h"
#include "zenith/sky/night_sky.h"
#include "zenith/sky/reference/accuracy.h"
#include "zenith/sky/reference/atmosphere_reference.h"
#include "zenith/sky/reference/path_tracer.h"
#include "zenith/weather/cloud_weather.h"

namespace {

using zenith::sky::reference::AccuracyOptions;
using zenith::sky::reference::AccuracyResult;
using zenith::sky::reference::AccuracyScenario;
using zenith::sky::reference::LocalDirection;

// RGB triple as "a, b, c" scaled by `scale`, `digits` after the point.
std::string Triple(const glm::dvec3& v, double scale, int digits) {
    char text[96];
    std::snprintf(text, sizeof(text), "%.*f, %.*f, %.*f", digits, v.x * scale, digits, v.y * scale,
                  digits, v.z * scale);
    return text;
}

// --- The twilight grid ----------------------------------------------------------------------

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr glm::dvec3 kRec709{0.2126, 0.7152, 0.0722};

struct TwilightOptions {
    std::int64_t samples = 16384;        // first batch of paths per ray
    std::int64_t max_samples = 1 << 20;  // cap per ray
    double target_se = 0.01;             // relative standard error to reach in every channel
    // Rays whose relative standard error stays above this in a channel are not converged: listed,
    // but left out of the summary (their |error| would be the path tracer's noise).
    double converged_se = 0.025;
    std::uint64_t seed = 1;
    int threads = 2;
    // The renderer's LUTs. --ms-* raise the multiple-scattering LUT's resolution and sampling,
    // to tell the LUTs' discretisation from the approximation they make (H20 §5.5).
    zenith::sky::LutSettings lut = zenith::sky::LutSettings::Pc();
};

// A view from the observer, its azimuth counted from the sun's.
struct SunRelativeView {
    const char* name;
    double elevation;  // rad, above the astronomical horizon
    double azimuth;    // rad, from the sun's azimuth
};

// The horizon views look 1 deg above the astronomical horizon: a ray that stays in the air from
// every altitude of the grid (from 1 m, 0 deg would graze the ground).
const SunRelativeView kTwilightViews[] = {
    {"horizon, sun side", 1.0 * kDeg, 0.0},
    {"horizon, 90 deg off", 1.0 * kDeg, 90.0 * kDeg},
    {"horizon, anti-solar", 1.0 * kDeg, 180.0 * kDeg},
    {"zenith", 90.0 * kDeg, 0.0},
};
const double kSunZenithsDeg[] = {80.0, 85.0, 90.0, 95.0, 96.0, 100.0, 102.0};
const double kAltitudesM[] = {1.0, 1e3, 5e3, 10e3};  // "0 km" is 1 m above the ground

// Local frame of the observer: +y up, azimuth 0 along +x (the sun's azimuth).
struct TwilightRow {
    double sun_zenith_deg = 0.0;
    double altitude_m = 0.0;
    const char* view = "";
    glm::dvec4 renderer{0.0};   // R, G, B, Y, cd/m²
    glm::dvec4 reference{0.0};  // path tracer
    glm::dvec4 reference_se{0.0};
    glm::dvec4 renderer_point_sun{0.0};  // the renderer with a point sun (the path tracer's)
    std::int64_t paths = 0;
    bool converged = false;
    glm::dvec4 Error() const { return renderer / reference - 1.0; }
    // The ratio's standard error (the renderer is deterministic).
    glm::dvec4 ErrorSe() const { return renderer / reference * (reference_se / reference); }
};

glm::dvec4 WithLuminance(const glm::dvec3& rgb) { return {rgb, glm::dot(rgb, kRec709)}; }

// Path traces one ray until the target relative error or the cap, by doubling batches with
// independent seeds, merged as one sample.
zenith::sky::reference::PathTraceResult TraceRay(const zenith::sky::Atmosphere& atmosphere,
                                                 const glm::dvec3& position,
                                                 const glm::dvec3& direction, const glm::dvec3& sun,
                                                 const TwilightOptions& o, std::uint64_t seed) {
    using zenith::sky::reference::PathTraceOptions;
    using zenith::sky::reference::PathTraceResult;
    glm::dvec3 sum(0.0), sum_squares(0.0);
    std::int64_t n = 0;
    std::int64_t batch = o.samples;
    PathTraceResult total;
    for (int round = 0;; ++round) {
        PathTraceOptions trace;
        trace.samples = std::min(batch, o.max_samples - n);
        trace.seed = seed * std::uint64_t{1000003} + static_cast<std::uint64_t>(round);
        trace.ground = false;
        trace.threads = o.threads;
        const PathTraceResult r =
            zenith::sky::reference::PathTrace(atmosphere, position, direction, sun, trace);
        const double m = static_cast<double>(r.samples);
        // Back to sums: mean m, variance of the mean se² -> sample variance m se².
        sum += r.luminance * m;
        sum_squares +=
            (r.standard_error * r.standard_error * m * (m - 1.0)) + m * r.luminance * r.luminance;
        n += r.samples;
        const double count = static_cast<double>(n);
        total.samples = n;
        total.luminance = sum / count;
        const glm::dvec3 variance =
            glm::max(glm::dvec3(0.0),
                     (sum_squares - count * total.luminance * total.luminance) / (count - 1.0));
        total.standard_error = glm::sqrt(variance / count);
        const glm::dvec3 relative = total.standard_error / total.luminance;
        const bool converged = std::max({relative.x, relative.y, relative.z}) <= o.target_se;
        if (converged || n >= o.max_samples) break;
        // Hopeless within the cap (the error falls as 1/sqrt(paths)): stop once the estimate
        // has 65536 paths behind it, and spend the time on the rays that can converge.
        const double worst = std::max({relative.x, relative.y, relative.z});
        if (n >= 65536 &&
            !(worst * std::sqrt(count / static_cast<double>(o.max_samples)) <= o.converged_se)) {
            break;
        }
        batch = n;  // doubles the total
    }
    return total;
}

// Type-7 quantile (linear between order statistics) of |values|.
double AbsQuantile(std::vector<double> values, double q) {
    for (double& v : values) v = std::abs(v);
    std::sort(values.begin(), values.end());
    if (values.empty()) return 0.0;
    const double position = q * static_cast<double>(values.size() - 1);
    const auto i = static_cast<std::size_t>(position);
    const double f = position - static_cast<double>(i);
    return i + 1 < values.size() ? values[i] * (1.0 - f) + values[i + 1] * f : values[i];
}

enum class SummaryKind {
    kConverged,  // |error| over the converged rays
    kPointSun,   // the same with the point-sun renderer
    // max(0, |error| - 2 SE) over every ray with a non-zero reference: what the error is at
    // least, granting the path tracer two standard errors, converged or not
    kLowerBound,
};

// " n (left out) | median / p95 | ..." per channel (R, G, B, Y) of |error| over the rows that
// pass `keep`, in percent.
template <class Keep>
std::string Summary(const std::vector<TwilightRow>& rows, Keep keep, SummaryKind kind) {
    const auto use = [&](const TwilightRow& row) {
        if (kind != SummaryKind::kLowerBound) return row.converged;
        return row.reference.x > 0.0 && row.reference.y > 0.0 && row.reference.z > 0.0;
    };
    std::size_t count = 0, skipped = 0;
    for (const TwilightRow& row : rows) {
        if (keep(row)) ++(use(row) ? count : skipped);
    }
    char head[64];
    std::snprintf(head, sizeof(head), " %zu (%zu) |", count, skipped);
    std::string text = head;
    for (int c = 0; c < 4; ++c) {
        std::vector<double> errors;
        for (const TwilightRow& row : rows) {
            if (!keep(row) || !use(row)) continue;
            switch (kind) {
                case SummaryKind::kConverged:
                    errors.push_back(row.Error()[c]);
                    break;
                case SummaryKind::kPointSun:
                    errors.push_back(row.renderer_point_sun[c] / row.reference[c] - 1.0);
                    break;
                case SummaryKind::kLowerBound:
                    errors.push_back(
                        std::max(0.0, std::abs(row.Error()[c]) - 2.0 * row.ErrorSe()[c]));
                    break;
            }
        }
        char cell[64];
        if (errors.empty()) {
            text += " — |";
            continue;
        }
        std::snprintf(cell, sizeof(cell), " %.1f / %.1f |", 100.0 * AbsQuantile(errors, 0.5),
                      100.0 * AbsQuantile(errors, 0.95));
        text += cell;
    }
    return text;
}

int RunTwilight(const TwilightOptions& options) {
    using Clock = std::chrono::steady_clock;
    using zenith::sky::Atmosphere;
    using zenith::sky::Lights;
    using zenith::sky::reference::AtmosphereReference;
    Atmosphere earth = zenith::sky::LoadAtmosphere("earth");
    earth.ground_albedo = glm::dvec3(0.0);
    Atmosphere point_sun = earth;
    point_sun.sun_angular_radius = 1e-7;  // rad: the path tracer's point sun, for comparison
    const AtmosphereReference renderer(earth, options.lut);
    const AtmosphereReference renderer_point(point_sun, options.lut);

    const zenith::sky::LutSettings& lut = options.lut;
    std::printf(
        "Earth preset, black ground, no sun disk; renderer: Sky-View LUT (LutSettings::Pc(), "
        "multiple-scattering LUT %dx%d texels, %d directions, %d steps, orders 2..%d); "
        "reference: PathTrace, %lld paths per ray doubled until the relative standard error is "
        "<= %.3g in R, G and B or %lld paths (from 65536 on, stopped where %.3g is out of reach "
        "within that); seed %llu; horizon views 1 deg above the "
        "astronomical horizon; \"0 km\" is 1 m\n\n",
        lut.multiple_scattering_size.x, lut.multiple_scattering_size.y,
        lut.multiple_scattering_directions_sqrt * lut.multiple_scattering_directions_sqrt,
        lut.multiple_scattering_steps, lut.multiple_scattering_orders,
        static_cast<long long>(options.samples), options.target_se,
        static_cast<long long>(options.max_samples), options.converged_se,
        static_cast<unsigned long long>(options.seed));
    std::printf(
        "| sun zenith | altitude | view | path tracer Y, cd/m² | renderer / path tracer − 1 (R, "
        "G, B, Y) ± path-tracer SE | point sun, Y | paths |\n");
    std::printf("|---|---|---|---|---|---|---|\n");
    std::fflush(stdout);

    std::vector<TwilightRow> rows;
    double renderer_seconds = 0.0, reference_seconds = 0.0;
    std::uint64_t ray_index = 0;
    for (const double sun_zenith : kSunZenithsDeg) {
        Lights lights;
        lights.sun_direction = LocalDirection((90.0 - sun_zenith) * kDeg, 0.0);
        lights.sun_illuminance = earth.solar_illuminance;
        for (const double altitude : kAltitudesM) {
            const glm::dvec3 camera(0.0, earth.bottom_radius + altitude, 0.0);
            auto start = Clock::now();
            const zenith::sky::LutImage sky_view = renderer.SkyView(camera, lights);
            const zenith::sky::LutImage sky_view_point = renderer_point.SkyView(camera, lights);
            renderer_seconds += std::chrono::duration<double>(Clock::now() - start).count();
            for (const SunRelativeView& view : kTwilightViews) {
                const glm::dvec3 direction = LocalDirection(view.elevation, view.azimuth);
                TwilightRow row;
                row.sun_zenith_deg = sun_zenith;
                row.altitude_m = altitude;
                row.view = view.name;
                row.renderer = WithLuminance(
                    renderer.SampleSkyView(sky_view, camera, lights.sun_direction, direction));
                row.renderer_point_sun = WithLuminance(renderer_point.SampleSkyView(
                    sky_view_point, camera, lights.sun_direction, direction));
                start = Clock::now();
                const zenith::sky::reference::PathTraceResult r =
                    TraceRay(earth, camera, direction, lights.sun_direction, options,
                             options.seed + ray_index++);
                reference_seconds += std::chrono::duration<double>(Clock::now() - start).count();
                row.reference = WithLuminance(r.luminance);
                // Y's error as if R, G and B were fully correlated (they come from the same
                // paths): an upper bound.
                row.reference_se = {r.standard_error, glm::dot(r.standard_error, kRec709)};
                row.paths = r.samples;
                const glm::dvec3 relative_se = r.standard_error / r.luminance;
                row.converged =
                    r.luminance.x > 0.0 && r.luminance.y > 0.0 && r.luminance.z > 0.0 &&
                    std::max({relative_se.x, relative_se.y, relative_se.z}) <= options.converged_se;
                const glm::dvec4 e = 100.0 * row.Error();
                const glm::dvec4 se = 100.0 * row.ErrorSe();
                std::printf(
                    "| %.0f° | %.0f km | %s | %.3g | %+.1f ± %.1f, %+.1f ± %.1f, %+.1f ± %.1f, "
                    "%+.1f ± %.1f %% | %+.1f %% | %lld%s |\n",
                    sun_zenith, altitude < 100.0 ? 0.0 : altitude / 1e3, view.name, row.reference.w,
                    e.x, se.x, e.y, se.y, e.z, se.z, e.w, se.w,
                    100.0 * (row.renderer_point_sun.w / row.reference.w - 1.0),
                    static_cast<long long>(row.paths), row.converged ? "" : " (not converged)");
                std::fflush(stdout);
                rows.push_back(row);
            }
        }
    }

    const auto all = [](const TwilightRow&) { return true; };
    // Issue 18's goal: sun zenith 80-100 deg, civil twilight's end (96) included.
    const auto goal = [](const TwilightRow& row) { return row.sun_zenith_deg <= 100.0; };
    const auto by_sun = [&](double sun_zenith) {
        return [sun_zenith](const TwilightRow& row) { return row.sun_zenith_deg == sun_zenith; };
    };
    const auto by_altitude = [&](double altitude) {
        return [altitude](const TwilightRow& row) { return row.altitude_m == altitude; };
    };
    const auto by_view = [&](const char* name) {
        return [name](const TwilightRow& row) { return std::strcmp(row.view, name) == 0; };
    };
    const auto print_slices = [&](SummaryKind kind) {
        std::printf("| all |%s\n", Summary(rows, all, kind).c_str());
        std::printf("| sun zenith 80-100 (the goal's) |%s\n", Summary(rows, goal, kind).c_str());
        for (const double sun_zenith : kSunZenithsDeg) {
            std::printf("| sun zenith %.0f° |%s\n", sun_zenith,
                        Summary(rows, by_sun(sun_zenith), kind).c_str());
        }
        for (const double altitude : kAltitudesM) {
            std::printf("| altitude %.0f km |%s\n", altitude < 100.0 ? 0.0 : altitude / 1e3,
                        Summary(rows, by_altitude(altitude), kind).c_str());
        }
        for (const SunRelativeView& view : kTwilightViews) {
            std::printf("| %s |%s\n", view.name, Summary(rows, by_view(view.name), kind).c_str());
        }
    };
    std::printf(
        "\n|error| over the converged rays (path-tracer relative SE <= %.3g in R, G and B), median "
        "/ p95 in %% (goal, issue 18: median <= 5, p95 <= 10); n (rays left out)\n\n"
        "| rays | n | R | G | B | Y |\n|---|---|---|---|---|---|\n",
        options.converged_se);
    print_slices(SummaryKind::kConverged);
    std::printf("| all, renderer with a point sun |%s\n",
                Summary(rows, all, SummaryKind::kPointSun).c_str());
    std::printf(
        "\nLower bound, every ray with a non-zero reference: max(0, |error| - 2 SE), median / p95 "
        "in %%\n\n| rays | n | R | G | B | Y |\n|---|---|---|---|---|---|\n");
    print_slices(SummaryKind::kLowerBound);
    std::printf("\nrenderer %.1f s (two Sky-View LUTs per sun and altitude), path tracer %.0f s\n",
                renderer_seconds, reference_seconds);
    return 0;
}

// --- Twilight illuminance against measurements -------------------------------------------------

// Horizontal illuminance (lux) on the ground under an average clear sky, by the Sun's altitude
// (deg; refracted above the horizon): Brown (1952), "Natural Illumination Charts", U.S. Navy
// Bureau of Ships report 374-1, as fitted by Janiczek & DeYoung (1987), USNO Circular 171,
// evaluated at these altitudes (3 significant figures). "Average clear sky" admits up to 70 %
// scattered cloud with the Sun unobstructed.
struct MeasuredIlluminance {
    double sun_altitude_deg;
    double lux;
};
const MeasuredIlluminance kBrown1952[] = {
    {10.0, 10900.0}, {5.0, 4760.0}, {2.0, 1960.0},   {0.0, 757.0},     {-1.0, 404.0},
    {-2.0, 192.0},   {-3.0, 81.0},  {-4.0, 30.7},    {-5.0, 10.7},     {-6.0, 3.47},
    {-7.0, 1.14},    {-8.0, 0.357}, {-10.0, 0.0449}, {-12.0, 0.00843},
};

struct IlluminanceOptions {
    int directions_sqrt = 48;  // jittered cosine-weighted directions per side
    std::int64_t paths = 64;   // per direction
    std::uint64_t seed = 1;
    int threads = 2;
};

// Sky illuminance (lux per channel) on a horizontal surface on the ground, by the path tracer: E =
// pi * mean of L over cosine-distributed directions, one jittered direction per stratum of the unit
// square, `paths` paths each; standard error of the mean over directions.
std::pair<glm::dvec3, glm::dvec3> PathTracedIrradiance(const zenith::sky::Atmosphere& atmosphere,
                                                       const glm::dvec3& sun,
                                                       const IlluminanceOptions& o,
                                                       std::uint64_t seed) {
    zenith::sky::reference::Rng rng(seed);
    const int n = o.directions_sqrt;
    glm::dvec3 sum(0.0), sum_squares(0.0);
    const glm::dvec3 position(0.0, atmosphere.bottom_radius + 1.0, 0.0);
    for (int i = 0; i < n * n; ++i) {
        const double u1 = (static_cast<double>(i / n) + rng.Uniform()) / n;
        const double u2 = (static_cast<double>(i % n) + rng.Uniform()) / n;
        const double sin_theta = std::sqrt(u1);  // cosine-weighted about +y
        const double phi = 2.0 * std::numbers::pi * u2;
        const glm::dvec3 direction(sin_theta * std::cos(phi), std::sqrt(std::max(0.0, 1.0 - u1)),
                                   sin_theta * std::sin(phi));
        zenith::sky::reference::PathTraceOptions trace;
        trace.samples = o.paths;
        trace.seed = seed * std::uint64_t{1000003} + static_cast<std::uint64_t>(i);
        trace.threads = o.threads;
        const glm::dvec3 l =
            zenith::sky::reference::PathTrace(atmosphere, position, direction, sun, trace)
                .luminance *
            std::numbers::pi;
        sum += l;
        sum_squares += l * l;
    }
    const double m = static_cast<double>(n) * n;
    const glm::dvec3 mean = sum / m;
    const glm::dvec3 variance =
        glm::max(glm::dvec3(0.0), (sum_squares - m * mean * mean) / (m - 1));
    return {mean, glm::sqrt(variance / m)};
}

int RunIlluminance(const IlluminanceOptions& options) {
    using zenith::sky::Atmosphere;
    using zenith::sky::LutSettings;
    using zenith::sky::reference::AtmosphereReference;
    const Atmosphere earth = zenith::sky::LoadAtmosphere("earth");
    const AtmosphereReference shipped(earth, LutSettings::Pc());
    LutSettings fine = LutSettings::Pc();
    fine.irradiance_size = {1024, 1};
    fine.irradiance_directions_sqrt = 32;
    fine.irradiance_steps = 128;
    const AtmosphereReference converged(earth, fine);
    // The standard clear air of radiative-transfer codes (MODTRAN's and 6S's rural aerosol at 23 km
    // visibility, aerosol optical depth ~0.2-0.3 at 550 nm) against the preset's clean air (the
    // paper's aerosols, ~0.005): the same renderer, its aerosols scaled to that visibility.
    const double hazy_visibility = 23e3;
    const Atmosphere hazy_air =
        zenith::weather::AtmosphereForVisibility(earth, hazy_visibility, false, nullptr);
    const AtmosphereReference hazy(hazy_air, fine);
    std::printf(
        "Earth preset (ground albedo %.2g), observer on the ground; horizontal illuminance, lux "
        "(Rec. 709 Y of the per-channel lux); sky only below the horizon, sky + direct sun above. "
        "Renderer: the ground-irradiance LUT as SkyLighting reads it (LutSettings::Pc()) and "
        "converged (1024 texels, 32² directions, 128 steps); path tracer: %d² jittered "
        "cosine-weighted directions × %lld paths, seed %llu; measured: Brown (1952) via USNO "
        "Circular 171\n\n",
        earth.ground_albedo.y, options.directions_sqrt, static_cast<long long>(options.paths),
        static_cast<unsigned long long>(options.seed));
    std::printf(
        "| sun altitude | measured, lux | path tracer, lux | renderer (shipped LUT) | renderer "
        "(converged) | shipped / path tracer − 1 | converged / path tracer − 1 | path tracer / "
        "measured | renderer (converged), V = %.0f km / measured |\n"
        "|---|---|---|---|---|---|---|---|---|\n",
        hazy_visibility / 1e3);
    std::uint64_t index = 0;
    for (const MeasuredIlluminance& m : kBrown1952) {
        const double mu = std::sin(m.sun_altitude_deg * kDeg);
        const glm::dvec3 sun(std::sqrt(1.0 - mu * mu), mu, 0.0);
        // Per unit sun: the sky (a LUT's value) plus, above the horizon, the direct sun through
        // the renderer's own transmittance (disk included), in lux (Y).
        const auto lux = [&](const Atmosphere& air, const glm::dvec3& sky) {
            const glm::dvec3 direct = mu > 0.0 ? zenith::sky::TransmittanceToLight(
                                                     air, 0.0, mu, air.sun_angular_radius, 256) *
                                                     mu
                                               : glm::dvec3(0.0);
            return glm::dot((sky + direct) * air.solar_illuminance, kRec709);
        };
        const double lut =
            lux(earth, zenith::sky::SampleGroundIrradiance(shipped.ground_irradiance(), mu));
        const double exact =
            lux(earth, zenith::sky::SampleGroundIrradiance(converged.ground_irradiance(), mu));
        const double hazy_exact =
            lux(hazy_air, zenith::sky::SampleGroundIrradiance(hazy.ground_irradiance(), mu));
        const auto [traced, traced_se] =
            PathTracedIrradiance(earth, sun, options, options.seed + index++);
        const double reference = lux(earth, traced / earth.solar_illuminance);
        const double reference_se = glm::dot(traced_se, kRec709);
        std::printf(
            "| %+.0f° | %.3g | %.3g ± %.2g | %.3g | %.3g | %+.1f %% | %+.1f %% | %.2f | %.2f |\n",
            m.sun_altitude_deg, m.lux, reference, reference_se, lut, exact,
            100.0 * (lut / reference - 1.0), 100.0 * (exact / reference - 1.0), reference / m.lux,
            hazy_exact / m.lux);
        std::fflush(stdout);
    }
    return 0;
}

// --- Night light scattered by the air -----------------------------------------------------------

// The renderer's night sky (NightSkyLuminance, the CPU twin of the night-sky map) for a uniform
// white radiance of 1 cd/m^2 above the atmosphere (the starlight map made uniform; no airglow,
// zodiacal light or light pollution), from the ground, against the path tracer: an isotropic
// radiance L0 on the top of the atmosphere is a directional sun from every direction of the
// sphere, so the light the air scatters toward the camera is L0 / E times the path tracer's
// luminance for a sun of illuminance E, averaged over sun directions (x 4 pi). The direct part,
// L0 T, is added to both from the path tracer's own optical depth.
int RunNightScattering(const IlluminanceOptions& options) {
    using zenith::sky::Atmosphere;
    const Atmosphere earth = zenith::sky::LoadAtmosphere("earth");
    const zenith::sky::reference::AtmosphereReference renderer(earth,
                                                               zenith::sky::LutSettings::Pc());
    const zenith::sky::ref::TransmittanceTexture transmittance =
        zenith::sky::ref::FromImage(renderer.transmittance());
    zenith::sky::NightSky night;
    night.enabled = true;
    night.settings.airglow_zenith_brightness = 30.0;  // 1e-7 cd/m^2: none
    night.settings.zodiacal_light = false;
    auto uniform = std::make_shared<zenith::sky::StarlightMap>();
    uniform->width = 4;
    uniform->height = 2;
    uniform->texels.assign(8, glm::dvec3(1.0));
    night.starlight = uniform;
    const glm::dvec3 position(0.0, earth.bottom_radius + 1.0, 0.0);
    const glm::dvec3 camera_km = position / 1000.0;
    const double altitude_km = 1e-3;
    std::printf(
        "Earth preset (ground albedo %.2g), observer 1 m above the ground, a uniform white 1 cd/m² "
        "above the atmosphere; path tracer: PathTraceUniformSky, %lld paths per view (each its own "
        "sun direction, uniform over the sphere), seed %llu. Columns: Y (Rec. 709), cd/m²\n\n"
        "| elevation | transmittance to space (Y) | scattered, path tracer | scattered, renderer | "
        "renderer / path tracer − 1 (R, G, B, Y) | total, path tracer | total, renderer | without "
        "the scattered light / path tracer − 1 |\n|---|---|---|---|---|---|---|---|\n",
        earth.ground_albedo.y, static_cast<long long>(options.paths),
        static_cast<unsigned long long>(options.seed));
    std::uint64_t index = 0;
    for (const double elevation_deg : {90.0, 45.0, 20.0, 10.0, 5.0, 2.0, 1.0, 0.5}) {
        const glm::dvec3 view = LocalDirection(elevation_deg * kDeg, 0.0);
        zenith::sky::reference::PathTraceOptions trace;
        trace.samples = options.paths;
        trace.seed = options.seed + index++;
        trace.threads = options.threads;
        const zenith::sky::reference::PathTraceResult r =
            zenith::sky::reference::PathTraceUniformSky(earth, position, view, trace);
        const glm::dvec3 mean = r.luminance, se = r.standard_error;
        const auto hits = zenith::sky::reference::IntersectSphere(position, view, earth.top_radius);
        const glm::dvec3 t = glm::exp(
            -zenith::sky::reference::OpticalDepth(earth, position, view, hits ? hits->t_far : 0.0));
        const glm::dvec3 model = zenith::sky::NightSkyLuminance(night, earth, transmittance,
                                                                camera_km, altitude_km, view);
        zenith::sky::NightSky direct_only = night;
        direct_only.settings.scattered = false;
        const glm::dvec3 model_direct = zenith::sky::NightSkyLuminance(
            direct_only, earth, transmittance, camera_km, altitude_km, view);
        const double scattered_ref = glm::dot(mean, kRec709);
        const double scattered_model = glm::dot(model - model_direct, kRec709);
        const double total_ref = scattered_ref + glm::dot(t, kRec709);
        const glm::dvec3 error = 100.0 * ((model - model_direct) / mean - 1.0);
        std::printf(
            "| %.1f° | %.3f | %.3f ± %.3f | %.3f | %+.1f, %+.1f, %+.1f, %+.1f %% | %.3f | %.3f | "
            "%+.1f %% |\n",
            elevation_deg, glm::dot(t, kRec709), scattered_ref, glm::dot(se, kRec709),
            scattered_model, error.x, error.y, error.z,
            100.0 * (scattered_model / scattered_ref - 1.0), total_ref, glm::dot(model, kRec709),
            100.0 * (glm::dot(model_direct, kRec709) / total_ref - 1.0));
        std::fflush(stdout);
    }
    return 0;
}

// --- Haze: the visibility a METAR sets, against the path tracer --------------------------------

struct HazeOptions {
    std::int64_t paths = 16384;  // per ray
    std::uint64_t seed = 1;
    int threads = 2;
    zenith::sky::LutSettings lut = zenith::sky::LutSettings::Pc();
    std::optional<double> mie_g;          // the preset's when not given
    std::optional<double> ground_albedo;  // grey; the preset's when not given
};

// The Earth preset with its aerosols set for a visibility V (weather::AtmosphereForVisibility,
// as a METAR's visibility sets it without fog), observer 2 m up, the sun 40 deg high: the sky in
// three directions, the renderer's Sky-View LUT against the path tracer (ground albedo 0.3 in
// both, unless changed). Dense haze is where the multiple-scattering LUT's few orders and its
// steps, optically thick there, matter (BENCHMARKS.md, discrepancy 3).
int RunHaze(const HazeOptions& options) {
    using zenith::sky::Atmosphere;
    using zenith::sky::Lights;
    using zenith::sky::reference::AtmosphereReference;
    Atmosphere earth = zenith::sky::LoadAtmosphere("earth");
    if (options.mie_g) earth.mie_g = *options.mie_g;
    if (options.ground_albedo) earth.ground_albedo = glm::dvec3(*options.ground_albedo);
    const zenith::sky::LutSettings& lut = options.lut;
    std::printf(
        "Earth preset, aerosols for visibility V (weather::AtmosphereForVisibility, no fog), "
        "aerosol asymmetry g %.2g, ground albedo %.2g; observer 2 m up, sun 40 deg high; "
        "renderer: Sky-View LUT (multiple-scattering LUT %dx%d texels, %d directions, %d steps, "
        "orders 2..%d); "
        "reference: PathTrace, %lld paths per ray, seed %llu\n\n",
        earth.mie_g, earth.ground_albedo.y, lut.multiple_scattering_size.x,
        lut.multiple_scattering_size.y,
        lut.multiple_scattering_directions_sqrt * lut.multiple_scattering_directions_sqrt,
        lut.multiple_scattering_steps, lut.multiple_scattering_orders,
        static_cast<long long>(options.paths), static_cast<unsigned long long>(options.seed));
    std::printf(
        "| visibility | view | path tracer Y, cd/m² | renderer Y, cd/m² | renderer / path tracer "
        "− 1 (R, G, B, Y) ± path-tracer SE | view marched in 4000 steps, Y | single "
        "scattering's share (path tracer) | single scattering, renderer / path tracer − 1, Y | "
        "path tracer, s |\n|---|---|---|---|---|---|---|---|---|\n");
    const SunRelativeView views[] = {{"horizon, 90 deg off the sun", 1.0 * kDeg, 90.0 * kDeg},
                                     {"30 deg up, away from the sun", 30.0 * kDeg, 180.0 * kDeg},
                                     {"zenith", 90.0 * kDeg, 0.0}};
    std::uint64_t seed = options.seed;
    for (const double visibility : {200.0, 1000.0, 5000.0, 23000.0}) {
        const Atmosphere air =
            zenith::weather::AtmosphereForVisibility(earth, visibility, false, nullptr);
        const AtmosphereReference renderer(air, lut);
        Lights lights;
        lights.sun_direction = LocalDirection(40.0 * kDeg, 0.0);
        lights.sun_illuminance = air.solar_illuminance;
        const glm::dvec3 camera(0.0, air.bottom_radius + 2.0, 0.0);
        const zenith::sky::LutImage sky_view = renderer.SkyView(camera, lights);
        for (const SunRelativeView& view : views) {
            const glm::dvec3 direction = LocalDirection(view.elevation, view.azimuth);
            const glm::dvec4 lut_value = WithLuminance(
                renderer.SampleSkyView(sky_view, camera, lights.sun_direction, direction));
            // The same LUTs with the view ray marched in 4000 steps: the Sky-View LUT's own
            // steps and texels told from the multiple-scattering LUT's approximation.
            const glm::dvec4 marched =
                WithLuminance(renderer.RayMarch(camera, direction, lights, 4000));
            // Single scattering alone (4000 steps) against the path tracer's one-vertex paths,
            // which tells the media and the sun's light from the multiple scattering.
            const glm::dvec4 single_lut =
                WithLuminance(renderer.SingleScattering(camera, direction, lights, 4000));
            zenith::sky::reference::PathTraceOptions o;
            o.samples = options.paths;
            o.threads = options.threads;
            o.seed = seed++;
            const auto start = std::chrono::steady_clock::now();
            const zenith::sky::reference::PathTraceResult r =
                zenith::sky::reference::PathTrace(air, camera, direction, lights.sun_direction, o);
            o.max_bounces = 1;
            const glm::dvec4 single = WithLuminance(
                zenith::sky::reference::PathTrace(air, camera, direction, lights.sun_direction, o)
                    .luminance);
            const double seconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            const glm::dvec4 reference = WithLuminance(r.luminance);
            const glm::dvec4 se(r.standard_error, glm::dot(r.standard_error, kRec709));
            char cells[160] = "";
            std::size_t used = 0;
            for (int c = 0; c < 4; ++c) {
                used += static_cast<std::size_t>(std::snprintf(
                    cells + used, sizeof(cells) - used, "%s%+.1f ± %.1f", c ? ", " : "",
                    100.0 * (lut_value[c] / reference[c] - 1.0), 100.0 * se[c] / reference[c]));
            }
            std::printf(
                "| %.0f m | %s | %.4g | %.4g | %s %% | %+.1f %% | %.3g | %+.1f %% | %.0f |\n",
                visibility, view.name, reference.w, lut_value.w, cells,
                100.0 * (marched.w / reference.w - 1.0), single.w / reference.w,
                100.0 * (single_lut.w / single.w - 1.0), seconds);
            std::fflush(stdout);
        }
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    AccuracyOptions options;
    options.width = 96;
    options.height = 64;
    options.samples = 1024;
    std::int64_t thick_samples = 256;
    std::string only;
    std::string grid = "paper";
    TwilightOptions twilight;
    HazeOptions haze;
    CLI::App app{"Accuracy of the LUT renderer against the path tracer (BENCHMARKS.md)"};
    app.add_option("--grid", grid, "paper (Hillaire 2020 §6), twilight, illuminance, night or haze")
        ->check(CLI::IsMember({"paper", "twilight", "illuminance", "night", "haze"}));
    app.add_option("--width", options.width, "paper grid: image width")->check(CLI::Range(1, 4096));
    app.add_option("--height", options.height, "paper grid: image height")
        ->check(CLI::Range(1, 4096));
    const CLI::Option* samples =
        app.add_option("--samples", options.samples, "paths per pixel, ray or view")
            ->check(CLI::Range(std::int64_t{2}, std::int64_t{1} << 24));
    app.add_option("--thick-samples", thick_samples, "paper grid: paths per pixel, thick_daytime")
        ->check(CLI::Range(std::int64_t{2}, std::int64_t{1} << 24));
    app.add_option("--only", only, "paper grid: this scenario alone");
    app.add_option("--threads", options.threads, "0: every core")->check(CLI::Range(0, 1024));
    app.add_option("--seed", options.seed)
        ->check(CLI::Range(std::uint64_t{0}, std::uint64_t{1} << 62));
    app.add_option("--max-samples", twilight.max_samples, "twilight grid: paths per ray at most")
        ->check(CLI::Range(std::int64_t{2}, std::int64_t{1} << 40));
    app.add_option("--target-se", twilight.target_se,
                   "twilight grid: relative standard error to stop at")
        ->check(CLI::Range(0.0, 1.0));
    app.add_option("--converged-se", twilight.converged_se,
                   "twilight grid: relative standard error of a converged ray")
        ->check(CLI::Range(0.0, 1.0));
    app.add_option("--haze-mie-g", haze.mie_g, "haze grid: the aerosols' asymmetry g")
        ->check(CLI::Range(-0.99, 0.99));
    app.add_option("--haze-ground-albedo", haze.ground_albedo, "haze grid: the ground's albedo")
        ->check(CLI::Range(0.0, 1.0));
    CLI::Option_group* lut = app.add_option_group("the renderer's multiple-scattering LUT");
    lut->add_option("--ms-width", options.lut_settings.multiple_scattering_size.x);
    lut->add_option("--ms-height", options.lut_settings.multiple_scattering_size.y);
    lut->add_option("--ms-directions-sqrt",
                    options.lut_settings.multiple_scattering_directions_sqrt);
    lut->add_option("--ms-steps", options.lut_settings.multiple_scattering_steps);
    lut->add_option("--ms-orders", options.lut_settings.multiple_scattering_orders);
    CLI11_PARSE(app, argc, argv);
    const bool samples_given = samples->count() > 0;
    if ((grid == "illuminance" || grid == "night") && lut->count_all() > 0) {
        std::fprintf(stderr,
                     "accuracy_report: --ms-* apply to the paper, twilight and haze grids\n");
        return 2;
    }
    try {
        options.lut_settings.Validate();  // LutSettings' own ranges for --ms-*
    } catch (const zenith::ArgumentError& e) {
        std::fprintf(stderr, "accuracy_report: %s\n", e.what());
        return 2;
    }

    if (grid == "illuminance" || grid == "night") {
        IlluminanceOptions illuminance;
        if (grid == "night") illuminance.paths = 1 << 18;  // per view
        if (samples_given) illuminance.paths = options.samples;
        illuminance.seed = options.seed;
        illuminance.threads = options.threads;
        return grid == "night" ? RunNightScattering(illuminance) : RunIlluminance(illuminance);
    }
    if (grid != "haze" && (haze.mie_g || haze.ground_albedo)) {
        std::fprintf(stderr, "accuracy_report: --haze-* apply to the haze grid\n");
        return 2;
    }
    if (grid == "haze") {
        if (samples_given) haze.paths = options.samples;
        haze.seed = options.seed;
        haze.threads = options.threads;
        haze.lut = options.lut_settings;
        return RunHaze(haze);
    }
    if (grid == "twilight") {
        if (samples_given) twilight.samples = options.samples;
        twilight.max_samples = std::max(twilight.max_samples, twilight.samples);
        twilight.seed = options.seed;
        twilight.threads = options.threads;
        twilight.lut = options.lut_settings;
        return RunTwilight(twilight);
    }

    std::printf(
        "%dx%d pixels, %lld paths per pixel (%lld for thick_daytime), seed %llu, LUTs: "
        "LutSettings::Pc() (multiple scattering %dx%d texels, %d directions, %d steps, orders "
        "2..%d), %d ray-marching steps from space\n\n",
        options.width, options.height, static_cast<long long>(options.samples),
        static_cast<long long>(thick_samples), static_cast<unsigned long long>(options.seed),
        options.lut_settings.multiple_scattering_size.x,
        options.lut_settings.multiple_scattering_size.y,
        options.lut_settings.multiple_scattering_directions_sqrt *
            options.lut_settings.multiple_scattering_directions_sqrt,
        options.lut_settings.multiple_scattering_steps,
        options.lut_settings.multiple_scattering_orders, options.ray_march_steps);
    std::printf(
        "| scenario | path | relative RMSE (R, G, B) | reference noise, relative | RMSE - noise, "
        "relative | mean bias (R, G, B) | absolute RMSE ×10⁻³ /sr | paper (O) ×10⁻³ | "
        "noise ×10⁻³ /sr | time LUT / PT |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|---|\n");
    std::fflush(stdout);
    double total_seconds = 0.0;
    for (const AccuracyScenario& scenario : zenith::sky::reference::PaperScenarios()) {
        if (!only.empty() && scenario.name != only) continue;
        AccuracyOptions scenario_options = options;
        if (scenario.name == "thick_daytime") scenario_options.samples = thick_samples;
        const AccuracyResult r = MeasureAccuracy(scenario, scenario_options);
        const bool has_paper = scenario.paper_rmse != glm::dvec3(0.0);
        std::printf(
            "| %s | %s | %s | %s | %s | %s ± %s | %s | %s | %s | %.2f s / %.0f s |\n",
            scenario.name.c_str(), r.ray_marched ? "ray march" : "Sky-View",
            Triple(r.RelativeRmse(), 1.0, 4).c_str(), Triple(r.RelativeNoise(), 1.0, 4).c_str(),
            Triple(r.RelativeRmseNoiseCorrected(), 1.0, 4).c_str(),
            Triple(r.MeanBias(), 1.0, 4).c_str(), Triple(r.MeanBiasError(), 1.0, 4).c_str(),
            Triple(r.AbsoluteRmse(), 1e3, 3).c_str(),
            has_paper ? Triple(scenario.paper_rmse, 1e3, 2).c_str() : "—",
            Triple(r.AbsoluteNoise(), 1e3, 3).c_str(), r.renderer_seconds, r.reference_seconds);
        std::fflush(stdout);
        total_seconds += r.renderer_seconds + r.reference_seconds;
    }
    std::printf("\ntotal %.0f s\n", total_seconds);
    return 0;
}
