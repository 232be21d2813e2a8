// `zenith render`: one frame offscreen to EXR or PNG.
#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <optional>
#include <string>

#include "commands.h"
#include "zenith/base/error.h"
#include "zenith/sim/render_frame.h"
#include "zenith/weather/metar_file.h"

namespace zenith::cli {
namespace {

int RunRender(sim::FrameRequest request, const std::string& size, const std::string& exposure,
              const std::string& quality) {
    request.size = sim::ParseFrameSize(size);
    request.exposure = sky::ExposureFromString(exposure);
    if (quality == "mobile") {
        request.lut_settings = sky::LutSettings::Mobile();
    } else if (quality != "pc") {
        throw ArgumentError("quality",
                            "quality = " + quality + " is not known (expected pc or mobile)");
    }
    std::string warning;
    const sim::FrameResult result = sim::RenderFrame(request, &warning);
    if (!warning.empty()) fmt::print(stderr, "zenith render: {}\n", warning);
    fmt::print(stderr,
               "zenith render: {} ({}x{}, sun elevation {:.2f} deg, {} stars, EV100 {:.2f}) "
               "on {}\n",
               request.out.string(), request.size.x, request.size.y, result.sun_elevation_deg,
               result.stars_drawn, result.ev100, result.gl_description);
    return 0;
}

}  // namespace

Command AddRenderCommand(CLI::App& app) {
    struct Args {
        sim::FrameRequest frame;
        std::string size = "1280x720", exposure = "auto", quality = "pc", out = "zenith.png";
        std::string metar, metar_file;
        std::optional<int> bortle;
        std::optional<double> light_pollution;
    };
    const auto args = std::make_shared<Args>();
    sim::FrameRequest& frame = args->frame;
    CLI::App* render = app.add_subcommand(
        "render",
        "Render one frame of sky offscreen to EXR (linear cd/m^2) or PNG (exposed, tone mapped); "
        "with no options, a built-in scene: sunset over Zurich at 10 km");
    render->add_option("--utc", frame.utc, "UTC instant, ISO 8601")->capture_default_str();
    render->add_option("--lat", frame.lat_deg, "geodetic latitude, degrees")->capture_default_str();
    render->add_option("--lon", frame.lon_deg, "longitude, degrees")->capture_default_str();
    render->add_option("--height", frame.height_m, "height above the WGS84 ellipsoid, metres")
        ->capture_default_str();
    render->add_option("--heading", frame.heading_deg, "degrees from true north, clockwise")
        ->capture_default_str();
    render->add_option("--pitch", frame.pitch_deg, "degrees, nose up positive")
        ->capture_default_str();
    render->add_option("--roll", frame.roll_deg, "degrees, right wing down positive")
        ->capture_default_str();
    render->add_option("--fov", frame.fov_deg, "vertical field of view, degrees")
        ->capture_default_str();
    render->add_option("--size", args->size, "image size WxH")->capture_default_str();
    render
        ->add_option("--weather", frame.weather,
                     "clouds: clear, scattered_cumulus, broken, overcast_stratus, "
                     "cumulonimbus, cirrus or a weather JSON file")
        ->capture_default_str();
    render->add_option("--preset", frame.preset, "atmosphere: earth, mars, thick or a JSON file")
        ->capture_default_str();
    render->add_option("--exposure", args->exposure, "EV100 for PNG output, or auto")
        ->capture_default_str();
    render
        ->add_option("--quality", args->quality,
                     "LUT sizes and steps: pc or mobile (Hillaire 2020 "
                     "Table 2)")
        ->capture_default_str();
    render->add_flag("--ray-march", frame.force_ray_march,
                     "ray march every pixel instead of using the Sky-View LUT");
    render->add_option("--out", args->out, "output file, .exr or .png")->capture_default_str();
    auto* metar = render->add_option(
        "--metar", args->metar,
        "the weather of a METAR report (\"EGLL 211750Z 24012KT 9999 FEW035 18/09 Q1018\"): its "
        "clouds over the observer and its visibility");
    render
        ->add_option("--metar-file", args->metar_file,
                     "the first report of a METAR file (one per line, # comments)")
        ->excludes(metar);
    render->add_option("--station-elevation", frame.station_elevation_m,
                       "the METAR station's elevation above mean sea level, metres (default: "
                       "the ground under the observer)");
    auto* bortle = render->add_option(
        "--bortle", args->bortle,
        "light pollution as a Bortle class 1..9: the zenith's total brightness is the middle of "
        "the class's sky-quality-meter range (zenith/sky/night_sky.h)");
    render
        ->add_option("--light-pollution", args->light_pollution,
                     "artificial zenith sky brightness, V mag/arcsec^2 (e.g. 20 for a suburb)")
        ->excludes(bortle);
    render->add_flag("!--no-refraction", frame.refraction,
                     "the Sun, Moon, planets and stars at their geometric places (default: seen "
                     "through the air's refraction, ISA's or the METAR's QNH and temperature)");
    render->add_flag("!--no-night-sky", frame.night_sky.enabled,
                     "no airglow, zodiacal light or starlight (the atmosphere's scattering only)");
    return {render, [args] {
                sim::FrameRequest request = args->frame;
                if (args->bortle) {
                    request.night_sky.artificial_zenith_brightness =
                        sky::ArtificialZenithBrightness(sky::BortleZenithBrightness(*args->bortle));
                    if (std::isinf(*request.night_sky.artificial_zenith_brightness)) {
                        request.night_sky.artificial_zenith_brightness.reset();  // class 1
                    }
                }
                if (args->light_pollution) {
                    request.night_sky.artificial_zenith_brightness = *args->light_pollution;
                }
                if (!args->metar.empty()) request.metar = weather::DecodeMetar(args->metar);
                if (!args->metar_file.empty()) {
                    const weather::MetarFile file = weather::ReadMetarLines(args->metar_file);
                    if (file.records.empty()) {
                        throw ArgumentError("metar_file", file.Summary());
                    }
                    request.metar = file.records.front().metar;
                }
                request.out = args->out;
                return RunRender(request, args->size, args->exposure, args->quality);
            }};
}

}  // namespace zenith::cli
