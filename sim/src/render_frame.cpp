#include "zenith/sim/render_frame.h"

#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "zenith/base/error.h"
#include "zenith/base/units.h"
#include "zenith/geo/ephemeris.h"
#include "zenith/geo/observer.h"
#include "zenith/sim/sky_system.h"
#include "zenith/sky/atmosphere_renderer.h"
#include "zenith/sky/gl/context.h"
#include "zenith/sky/inspection.h"
#include "zenith/weather/altimetry.h"
#include "zenith/weather/cloud_weather.h"
#include "zenith/weather/metar.h"

namespace zenith::sim {

glm::ivec2 ParseFrameSize(const std::string& text) {
    int w = 0, h = 0;
    char x = 0, extra = 0;
    if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X') ||
        !(w >= 1 && w <= kMaxFrameSide && h >= 1 && h <= kMaxFrameSide)) {
        throw ArgumentError("size", fmt::format("size = {} is not a frame size (expected WxH with "
                                                "1 <= W, H <= {}, e.g. 1280x720)",
                                                text, kMaxFrameSide));
    }
    return {w, h};
}

void ValidateFrameRequest(const FrameRequest& r) {
    Require("heading_deg", r.heading_deg, "deg", Range::Closed(-1e6, 1e6));
    Require("pitch_deg", r.pitch_deg, "deg", Range::Closed(-90.0, 90.0));
    Require("roll_deg", r.roll_deg, "deg", Range::Closed(-180.0, 180.0));
    ParseFrameSize(fmt::format("{}x{}", r.size.x, r.size.y));
    sky::ValidateProjection(Radians(r.fov_deg), static_cast<double>(r.size.x) / r.size.y);
    r.night_sky.Validate();
    const std::string extension = r.out.extension().string();
    if (extension != ".exr" && extension != ".png" && extension != ".EXR" && extension != ".PNG") {
        throw ArgumentError("out", fmt::format("out = {} has no image extension (expected a file "
                                               "name ending in .exr (linear cd/m^2) or .png)",
                                               r.out.string()));
    }
    // Position and time are validated by geo (Observer, TimeFromIso8601) with the same style.
    geo::Observer(r.lat_deg, r.lon_deg, r.height_m);
    geo::TimeFromIso8601(r.utc);
    r.lut_settings.Validate();
    r.clouds.Validate();
    Require("cloud_passes", r.cloud_passes, "", Range::Closed(1, 64));
}

FrameResult RenderFrame(const FrameRequest& request, std::string* warning) {
    ValidateFrameRequest(request);
    sky::Atmosphere atmosphere = sky::LoadAtmosphere(request.preset);
    sky::clouds::Weather weather;
    std::vector<std::string> notes;
    if (request.metar) {
        if (request.weather != "clear") {
            throw ArgumentError("weather", "weather = " + request.weather +
                                               " and a METAR report: give one of them");
        }
        const weather::Metar& metar = *request.metar;
        for (const weather::MetarWarning& w : metar.warnings) {
            notes.push_back("METAR: " + w.ToString());
        }
        double station = 0.0;
        if (request.station_elevation_m) {
            station = *request.station_elevation_m;
        } else {
            notes.push_back(
                "METAR heights are taken above the ground under the observer (0 m, "
                "zenith's ground); give the station's elevation to place them");
        }
        weather::MetarWeather from_report = weather::CloudWeatherFromMetar(metar, station);
        notes.insert(notes.end(), from_report.notes.begin(), from_report.notes.end());
        weather = std::move(from_report.clouds);
        if (from_report.visibility_m) {
            atmosphere = weather::AtmosphereForVisibility(atmosphere, *from_report.visibility_m,
                                                          from_report.fog, &notes);
        }
    } else {
        weather = sky::clouds::LoadWeather(request.weather);
    }
    std::optional<geo::StarCatalog> catalog;
    try {
        catalog = geo::StarCatalog::Load(request.star_magnitude_limit);
    } catch (const geo::CatalogError& e) {
        notes.push_back(std::string("stars not drawn: ") + e.what());
    }
    sky::FrameSetup setup;
    setup.time = geo::TimeFromIso8601(request.utc);
    setup.observer = geo::Observer(request.lat_deg, request.lon_deg, request.height_m);
    setup.attitude =
        geo::Attitude::FromDegrees(request.heading_deg, request.pitch_deg, request.roll_deg);
    setup.vertical_fov = Radians(request.fov_deg);
    setup.aspect = static_cast<double>(request.size.x) / request.size.y;
    setup.refraction = request.refraction ? PresetRefraction(request.preset) : std::nullopt;
    if (setup.refraction && request.metar) {
        setup.refraction = weather::RefractionAirOf(
            weather::StationAirOf(*request.metar, request.station_elevation_m.value_or(0.0)));
    }
    sky::SkyFrame frame =
        sky::BuildSkyFrame(geo::Ephemeris(catalog ? &*catalog : nullptr), setup, atmosphere);
    frame.view.force_ray_march = request.force_ray_march;

    const auto context = sky::gl::CreateHeadlessContextFromEnvironment();
    sky::AtmosphereRenderer renderer(atmosphere, request.lut_settings);
    renderer.SetWeather(weather, request.clouds);
    frame.scene.night_sky.settings = request.night_sky;
    try {
        // The catalogue down to its own end (V = 8) for the stars not drawn one by one.
        frame.scene.night_sky.starlight =
            std::make_shared<const sky::StarlightMap>(sky::StarlightMap::FromCatalog(
                geo::StarCatalog::Load(std::max(8.0, request.star_magnitude_limit)),
                request.star_magnitude_limit));
    } catch (const geo::CatalogError&) {
        frame.scene.night_sky.starlight =
            std::make_shared<const sky::StarlightMap>(sky::StarlightMap::ModelOnly());
    }
    renderer.Update(frame.scene, frame.view);
    const int passes = weather.layers.empty() ? 1 : request.cloud_passes;
    for (int i = 0; i < passes; ++i) renderer.Render(sky::RenderTarget::Offscreen(request.size));

    FrameResult result;
    result.image = sky::ImageFromFrame(sky::Inspect(renderer).ReadFrame());
    result.ev100 = sky::ResolveEV100(request.exposure, result.image);
    result.sun_elevation_deg = Degrees(frame.sun_elevation);
    result.stars_drawn = frame.scene.stars.size();
    result.gl_description = context->description();
    sky::ImageWriteOptions write_options;
    write_options.exposure = sky::Exposure{false, result.ev100};
    sky::WriteImage(request.out, result.image, write_options);
    if (warning != nullptr) {
        warning->clear();
        for (const std::string& note : notes) *warning += (warning->empty() ? "" : "\n") + note;
    }
    return result;
}

}  // namespace zenith::sim
