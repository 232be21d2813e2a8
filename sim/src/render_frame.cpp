#include "zenith/sim/render_frame.h"

#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "zenith/geo/ephemeris.h"
#include "zenith/geo/observer.h"
#include "zenith/sky/atmosphere_renderer.h"
#include "zenith/sky/gl/context.h"

namespace zenith::sim {
namespace {

constexpr double kDegToRad = 0.017453292519943295;

void Require(bool ok, const std::string& parameter, const std::string& value,
             const std::string& expected) {
    if (!ok) {
        throw std::invalid_argument(fmt::format("{} = {} is out of range (expected {})", parameter,
                                                value, expected));
    }
}

}  // namespace

void ValidateFrameRequest(const FrameRequest& r) {
    Require(std::isfinite(r.heading_deg), "--heading", fmt::format("{}", r.heading_deg),
            "a finite angle in degrees");
    Require(r.pitch_deg >= -90.0 && r.pitch_deg <= 90.0, "--pitch",
            fmt::format("{}", r.pitch_deg), "-90..90 degrees");
    Require(r.roll_deg >= -180.0 && r.roll_deg <= 180.0, "--roll", fmt::format("{}", r.roll_deg),
            "-180..180 degrees");
    Require(r.fov_deg > 0.0 && r.fov_deg < 180.0, "--fov", fmt::format("{}", r.fov_deg),
            "0 < vertical field of view < 180 degrees");
    Require(r.size.x >= 1 && r.size.y >= 1 && r.size.x <= 16384 && r.size.y <= 16384, "--size",
            fmt::format("{}x{}", r.size.x, r.size.y), "WxH with 1..16384 pixels per axis");
    const std::string extension = r.out.extension().string();
    Require(extension == ".exr" || extension == ".png" || extension == ".EXR" ||
                extension == ".PNG",
            "--out", r.out.string(), "a file name ending in .exr (linear cd/m^2) or .png");
    // Position and time are validated by geo (Observer, TimeFromIso8601) with the same style.
    geo::Observer(r.lat_deg, r.lon_deg, r.height_m);
    geo::TimeFromIso8601(r.utc);
    r.lut_settings.Validate();
    r.clouds.Validate();
    Require(r.cloud_passes >= 1 && r.cloud_passes <= 64, "cloud_passes",
            fmt::format("{}", r.cloud_passes), "1..64");
}

FrameResult RenderFrame(const FrameRequest& request, std::string* warning) {
    ValidateFrameRequest(request);
    const sky::Atmosphere atmosphere = sky::LoadAtmosphere(request.preset);
    const sky::clouds::Weather weather = sky::clouds::LoadWeather(request.weather);
    const geo::Time time = geo::TimeFromIso8601(request.utc);
    const geo::Observer observer(request.lat_deg, request.lon_deg, request.height_m);

    std::optional<geo::StarCatalog> catalog;
    try {
        catalog = geo::StarCatalog::Load(request.star_magnitude_limit);
    } catch (const geo::CatalogError& e) {
        if (warning != nullptr) *warning = std::string("stars not drawn: ") + e.what();
    }
    const geo::Ephemeris ephemeris(catalog ? &*catalog : nullptr);
    geo::EphemerisOptions ephemeris_options;
    ephemeris_options.star_min_elevation = -0.1;  // below the horizon the planet hides them
    const geo::SkyEphemeris sky_ephemeris = ephemeris.Compute(time, observer, ephemeris_options);

    const double aspect = static_cast<double>(request.size.x) / request.size.y;
    const geo::Attitude attitude{request.heading_deg * kDegToRad, request.pitch_deg * kDegToRad,
                                 request.roll_deg * kDegToRad};
    sky::SkyState state = sky::MakeSkyState(sky_ephemeris, observer, atmosphere, attitude,
                                            request.fov_deg * kDegToRad, aspect);

    const auto context = sky::gl::CreateHeadlessContextFromEnvironment();
    sky::AtmosphereRenderer renderer(atmosphere, request.lut_settings);
    renderer.SetWeather(weather, request.clouds);
    sky::RenderOptions options;
    options.size = request.size;
    options.force_ray_march = request.force_ray_march;
    options.moon = state.moon;
    options.stars = std::move(state.stars);
    renderer.UpdateFrameLuts(state.camera, state.lights, options.clouds);
    const int passes = weather.layers.empty() ? 1 : request.cloud_passes;
    for (int i = 0; i < passes; ++i) renderer.Render(state.camera, state.lights, options);
    const sky::LutImage frame = renderer.ReadFrame();

    FrameResult result;
    result.image = sky::Image(request.size.x, request.size.y);
    for (int y = 0; y < request.size.y; ++y) {  // GL rows run bottom-up; images top-down
        for (int x = 0; x < request.size.x; ++x) {
            result.image.pixels[result.image.Index(x, y)] = frame.at(x, request.size.y - 1 - y);
        }
    }
    result.ev100 = sky::ResolveEV100(request.exposure, result.image);
    result.sun_elevation_deg = state.sun_elevation / kDegToRad;
    result.stars_drawn = options.stars.size();
    result.gl_description = context->description();
    sky::ImageWriteOptions write_options;
    write_options.exposure = sky::Exposure{false, result.ev100};
    sky::WriteImage(request.out, result.image, write_options);
    return result;
}

}  // namespace zenith::sim
