// zenith-plot: VTK views of the atmosphere's LUTs, computed by the real renderer (read back from
// GL), in physical units. Subcommands: transmittance, lut, export, overview. Headless with
// --out FILE.png (starting a private Xvfb if there is no display), interactive otherwise.
#include <fmt/format.h>
#include <vtkAbstractContextItem.h>
#include <vtkChartMatrix.h>
#include <vtkImageData.h>
#include <vtkPolyData.h>
#include <vtkRenderer.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "display.h"
#include "luts.h"
#include "plots.h"
#include "zenith/base/error.h"
#include "zenith/sky/gl/error.h"

namespace {

namespace fs = std::filesystem;
using namespace zenith;

glm::ivec2 ParseSize(const std::string& text, const char* option = "--size", int min = 64) {
    int w = 0, h = 0;
    char x = 0;
    if (std::sscanf(text.c_str(), "%d%c%d", &w, &x, &h) != 3 || x != 'x' || w < min || h < min ||
        w > 8192 || h > 8192) {
        throw ArgumentError(
            fmt::format("{} = '{}' is not a size (expected WxH with "
                        "{}..8192 per axis)",
                        option, text, min));
    }
    return {w, h};
}

void AddSceneOptions(CLI::App* app, vis::Scene& scene, bool frame_luts) {
    app->add_option("--preset", scene.preset, "atmosphere: earth, mars, thick or a JSON file")
        ->capture_default_str();
    app->add_option("--quality", scene.quality, "LUT sizes and steps: pc or mobile")
        ->capture_default_str();
    if (!frame_luts) return;
    const std::string group = "Scene (Sky-View and aerial perspective; as `zenith render`)";
    app->add_option("--utc", scene.utc, "UTC instant, ISO 8601")
        ->capture_default_str()
        ->group(group);
    app->add_option("--lat", scene.lat_deg, "geodetic latitude, degrees")
        ->capture_default_str()
        ->group(group);
    app->add_option("--lon", scene.lon_deg, "longitude, degrees")
        ->capture_default_str()
        ->group(group);
    app->add_option("--height", scene.height_m, "height above the WGS84 ellipsoid, metres")
        ->capture_default_str()
        ->group(group);
    app->add_option("--heading", scene.heading_deg, "degrees from true north, clockwise")
        ->capture_default_str()
        ->group(group);
    app->add_option("--pitch", scene.pitch_deg, "degrees, nose up positive")
        ->capture_default_str()
        ->group(group);
    app->add_option("--fov", scene.fov_deg, "vertical field of view, degrees")
        ->capture_default_str()
        ->group(group);
}

// A display before any VTK window: an interactive window needs a real one; a PNG can use Xvfb.
std::optional<vis::DisplayGuard> Display(const std::string& out) {
    if (out.empty()) {
        std::string why;
        if (!vis::CanOpenDisplay(nullptr, &why)) {
            throw vis::DisplayError(
                "an interactive window needs an X display (" + why +
                "); give --out FILE.png to draw headless (zenith-plot then starts Xvfb itself "
                "when there is no display)");
        }
        return std::nullopt;
    }
    return vis::EnsureDisplay(true);
}

void CheckPng(const std::string& out) {
    if (!out.empty() && fs::path(out).extension() != ".png") {
        throw ArgumentError(
            fmt::format("--out = '{}' must end in .png (or leave it out for a window)", out));
    }
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{
        "zenith-plot: transmittance curves, LUT slices, .vti/.vtp export and a 3-D overview, from "
        "the LUTs the GL renderer computes (headless GL: ZENITH_GL=osmesa|egl). Plots open a "
        "window, or with --out FILE.png draw headless (an X display is needed: Xvfb is started "
        "when there is none)."};
    app.require_subcommand(1);

    vis::Scene scene;
    std::string out, size_text = "800x500";

    vis::TransmittancePlotOptions transmittance;
    CLI::App* transmittance_cmd =
        app.add_subcommand("transmittance",
                           "Transmittance (R, G, B) to space versus view zenith angle for chosen "
                           "altitudes, and versus altitude for chosen angles");
    AddSceneOptions(transmittance_cmd, scene, false);
    transmittance_cmd
        ->add_option("--altitudes", transmittance.altitudes_km, "altitudes of the left chart, km")
        ->delimiter(',')
        ->capture_default_str();
    transmittance_cmd
        ->add_option("--zeniths", transmittance.zeniths_deg,
                     "view zenith angles of the right chart, degrees")
        ->delimiter(',')
        ->capture_default_str();
    transmittance_cmd->add_flag("--reference", transmittance.reference,
                                "overlay the independent CPU reference (path tracer quadrature)");
    transmittance_cmd->add_flag("--log", transmittance.log, "logarithmic transmittance axis");
    transmittance_cmd->add_option("--out", out, "write this PNG instead of opening a window");
    transmittance_cmd->add_option("--size", size_text, "image size WxH")->capture_default_str();

    std::string lut_name = "transmittance", channel_name = "luminance", scale = "linear",
                samples_text = "400x200";
    int slice = 8;
    CLI::App* lut_cmd = app.add_subcommand(
        "lut", "A slice of one LUT as an image with a colour bar, axes in physical units");
    lut_cmd
        ->add_option("--lut", lut_name,
                     "transmittance, multiple-scattering, irradiance, sky-view or "
                     "aerial-perspective")
        ->capture_default_str();
    lut_cmd->add_option("--channel", channel_name, "r, g, b or luminance")->capture_default_str();
    lut_cmd->add_option("--scale", scale, "linear or log")->capture_default_str();
    lut_cmd->add_option("--slice", slice, "aerial-perspective depth slice k")
        ->capture_default_str();
    lut_cmd
        ->add_option("--samples", samples_text,
                     "WxH samples of the physical grid the LUT is sampled on (GL_LINEAR)")
        ->capture_default_str();
    AddSceneOptions(lut_cmd, scene, true);
    lut_cmd->add_option("--out", out, "write this PNG instead of opening a window");
    lut_cmd->add_option("--size", size_text, "image size WxH")->capture_default_str();

    std::string export_dir = ".", flight, vtp_name = "flight_path.vtp";
    double step_s = 10.0;
    CLI::App* export_cmd = app.add_subcommand(
        "export", "Every LUT as <preset>_<lut>.vti for ParaView, and a flight path as .vtp");
    export_cmd->add_option("--dir", export_dir, "output directory (created)")
        ->capture_default_str();
    export_cmd->add_option("--flight", flight, "flight log (.igc .gpx .kml .csv) to export")
        ->check(CLI::ExistingFile);
    export_cmd->add_option("--vtp", vtp_name, "file name of the flight path in --dir")
        ->capture_default_str();
    export_cmd->add_option("--step", step_s, "seconds between flight-path points")
        ->capture_default_str();
    AddSceneOptions(export_cmd, scene, true);

    CLI::App* overview_cmd = app.add_subcommand(
        "overview", "3-D scene: planet, atmosphere shell, Sun and Moon directions, flight path");
    overview_cmd->add_option("--flight", flight, "flight log to draw (and take time/place from)")
        ->check(CLI::ExistingFile);
    overview_cmd->add_option("--step", step_s, "seconds between flight-path points")
        ->capture_default_str();
    AddSceneOptions(overview_cmd, scene, true);
    overview_cmd->add_option("--out", out, "write this PNG instead of opening a window");
    overview_cmd->add_option("--size", size_text, "image size WxH")->capture_default_str();

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    }

    try {
        const glm::ivec2 size = ParseSize(size_text);
        if (*export_cmd) {
            const vis::Luts luts = vis::ComputeLuts(scene);
            fs::create_directories(export_dir);
            for (vis::LutKind kind : vis::kAllLuts) {
                const fs::path path =
                    fs::path(export_dir) /
                    fmt::format("{}_{}.vti", luts.atmosphere.name, vis::LutName(kind));
                vis::WriteVti(vis::LutImageData(luts, kind), path);
                fmt::print("{}\n", path.string());
            }
            if (!flight.empty()) {
                const fs::path path = fs::path(export_dir) / vtp_name;
                vis::WriteVtp(vis::FlightPath(flight, step_s), path);
                fmt::print("{}\n", path.string());
            }
            return 0;
        }
        CheckPng(out);
        if (*transmittance_cmd) {
            const auto display = Display(out);  // first: fail before the GL work
            const vis::Luts luts = vis::ComputeLuts(scene);
            vis::ShowChart(vis::MakeTransmittanceCharts(luts, transmittance), size, out);
        } else if (*lut_cmd) {
            const vis::LutKind kind = vis::ParseLutKind(lut_name);
            const vis::Channel channel = vis::ParseChannel(channel_name);
            if (scale != "linear" && scale != "log") {
                throw ArgumentError(
                    fmt::format("--scale = '{}' is not a scale (expected linear or log)", scale));
            }
            const glm::ivec2 samples = ParseSize(samples_text, "--samples", 2);
            const auto display = Display(out);
            const vis::Luts luts = vis::ComputeLuts(scene);
            const vis::Slice s = vis::MakeSlice(luts, kind, channel, slice, samples.x, samples.y);
            vis::ShowChart(vis::MakeSliceChart(s, scale == "log"), size, out);
        } else if (*overview_cmd) {
            const sky::Atmosphere atmosphere = sky::LoadAtmosphere(scene.preset);
            const auto display = Display(out);
            vtkSmartPointer<vtkPolyData> path;
            if (!flight.empty()) path = vis::FlightPath(flight, step_s);
            vis::ShowScene(vis::MakeOverview(atmosphere, scene, path), size, out);
        }
        if (!out.empty()) fmt::print("{}\n", out);
    } catch (const vis::DisplayError& e) {
        fmt::print(stderr, "zenith-plot: no display: {}\n", e.what());
        return 3;
    } catch (const ArgumentError& e) {
        // The library names its fields (the frame builder's "fov_deg"); say which option it was.
        fmt::print(stderr, "zenith-plot: error: {}{}\n", e.field() == "fov_deg" ? "--fov: " : "",
                   e.what());
        return 2;
    } catch (const std::exception& e) {
        fmt::print(stderr, "zenith-plot: error: {}\n", e.what());
        return 2;
    }
    return 0;
}
