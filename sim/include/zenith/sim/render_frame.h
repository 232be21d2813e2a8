// One frame, offscreen: UTC + position + attitude -> ephemeris -> sky state -> GL render ->
// image file. Used by `zenith render`; replay (issue 5) renders many of these.
#pragma once

#include <filesystem>
#include <glm/glm.hpp>
#include <optional>
#include <string>

#include "zenith/base/error.h"
#include "zenith/geo/time.h"
#include "zenith/sky/atmosphere.h"
#include "zenith/sky/atmosphere_renderer.h"
#include "zenith/sky/image_io.h"
#include "zenith/sky/lut.h"
#include "zenith/sky/sky_state.h"
#include "zenith/weather/metar.h"

namespace zenith::sim {

inline constexpr int kMaxFrameSide = 16384;

// "WxH" with 1 <= W, H <= kMaxFrameSide; throws ArgumentError (field "size").
glm::ivec2 ParseFrameSize(const std::string& text);

struct FrameRequest {
    std::string utc = "2024-06-21T19:00:00Z";  // ISO 8601
    double lat_deg = 47.45;                    // the built-in scene: over Zurich at FL330,
    double lon_deg = 8.56;                     // looking west-north-west into the sunset
    double height_m = 10000.0;                 // above the WGS84 ellipsoid
    double heading_deg = 300.0;
    double pitch_deg = 0.0;
    double roll_deg = 0.0;
    double fov_deg = 60.0;  // vertical
    glm::ivec2 size{1280, 720};
    std::string preset = "earth";  // built-in preset name or JSON file
    sky::Exposure exposure;        // "auto" unless given (PNG only)
    std::filesystem::path out = "zenith.png";
    double star_magnitude_limit = 6.5;
    // Airglow, zodiacal light, starlight beyond the drawn stars, light pollution
    // (zenith/sky/night_sky.h).
    sky::NightSkySettings night_sky;
    bool force_ray_march = false;
    // The Sun, Moon, planets and stars seen through the air's refraction (PresetRefraction's
    // air, with the METAR's QNH and temperature when there is one); false: geometric places.
    bool refraction = true;
    sky::LutSettings lut_settings;
    // Clouds: a built-in weather preset (clear, scattered_cumulus, broken, overcast_stratus,
    // cumulonimbus, cirrus) or a weather JSON file. A single frame has no history to reproject, so
    // every pixel is traced (block 1), cloud_passes times with the jitter moved each time, averaged
    // by the renderer's history (grain instead of banding from the equal steps).
    std::string weather = "clear";
    // Or the weather of a METAR report (zenith::weather::CloudWeatherFromMetar): its clouds, and
    // its visibility as the aerosols near the ground (AtmosphereForVisibility). The report's
    // heights are above the station: station_elevation_m (above mean sea level), else the ground
    // under the observer (zenith's ground is the ellipsoid: 0 m), which the warning then says.
    std::optional<weather::Metar> metar;  // weather::DecodeMetar
    std::optional<double> station_elevation_m;
    sky::CloudSettings clouds = SingleFrameCloudSettings();
    int cloud_passes = 4;

    static sky::CloudSettings SingleFrameCloudSettings() {
        sky::CloudSettings s;
        s.block = 1;
        return s;
    }
};

// Throws zenith::ArgumentError naming the parameter, value and allowed range for anything out of
// range (before any rendering, so nothing is written).
void ValidateFrameRequest(const FrameRequest& request);

struct FrameResult {
    sky::Image image;    // linear luminance, cd/m^2, row 0 = top
    double ev100 = 0.0;  // exposure used for a PNG (resolved from "auto" if so)
    double sun_elevation_deg = 0.0;
    std::size_t stars_drawn = 0;
    std::string gl_description;
};

// Renders (creating a headless GL context: $ZENITH_GL = osmesa|egl) and writes request.out
// atomically. Stars are drawn when the catalogue is installed; without it, a warning goes to
// `warning` (if given: one line per note; also the METAR's warnings and the choices its
// mapping made) and the frame is still rendered.
FrameResult RenderFrame(const FrameRequest& request, std::string* warning = nullptr);

}  // namespace zenith::sim
