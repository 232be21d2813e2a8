// zenith — the command-line front end: `zenith ephemeris`, `render`, `replay`, `info`, `live`. Each
// subcommand is in its own file (commands.h); this one parses and reports errors.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <map>
#include <string>

#include "commands.h"
#include "zenith/base/error.h"
#include "zenith/version.h"

namespace zenith::cli {

// The command-line option of a library field named in an ArgumentError ("" if none).
std::string FlagForField(const std::string& field) {
    static const std::map<std::string, std::string> kFlags = {
        {"size", "--size"},
        {"fps", "--fps"},
        {"fov_deg", "--fov"},
        {"time_warp", "--time-warp"},
        {"time_offset_s", "--time-offset"},
        {"start_s", "--start"},
        {"end_s", "--end"},
        {"camera", "--camera"},
        {"format", "--format"},
        {"video", "--video"},
        {"shard", "--shard"},
        {"cloud_passes", "--cloud-passes"},
        {"exposure", "--exposure"},
        {"quality", "--quality"},
        {"lat_deg", "--lat"},
        {"lon_deg", "--lon"},
        {"height_m", "--height"},
        {"heading_deg", "--heading"},
        {"pitch_deg", "--pitch"},
        {"roll_deg", "--roll"},
        {"out", "--out"},
        {"weather", "--weather"},
        {"metar_file", "--metar-file"},
        {"station_elevation", "--station-elevation"},
        {"visibility", "--metar"},
        {"protocol", "--fg-native/--fg-generic/--xplane"},
        {"port", "--fg-native/--fg-generic/--xplane"},
        {"bind_address", "--bind"},
        {"every_s", "--every"},
        {"delay_s", "--delay"},
        {"frames", "--frames"},
        {"duration_s", "--duration"},
        {"bortle_class", "--bortle"},
        {"artificial_zenith_brightness", "--light-pollution"},
    };
    const auto it = kFlags.find(field);
    return it == kFlags.end() ? std::string() : it->second;
}

}  // namespace zenith::cli

int main(int argc, char** argv) {
    using namespace zenith;
    CLI::App app{"zenith — flight-simulator sky: ephemeris, atmosphere, clouds"};
    app.require_subcommand(1);
    app.set_version_flag("--version", std::string("zenith ") + kVersion);
    const cli::Command commands[] = {cli::AddEphemerisCommand(app), cli::AddRenderCommand(app),
                                     cli::AddReplayCommand(app), cli::AddInfoCommand(app),
                                     cli::AddLiveCommand(app)};
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    }
    try {
        for (const cli::Command& command : commands) {
            if (*command.app) return command.run();
        }
    } catch (const ArgumentError& e) {
        // The library names its fields; say which option it was.
        const std::string flag = cli::FlagForField(e.field());
        fmt::print(stderr, "zenith: error: {}{}\n", flag.empty() ? "" : flag + ": ", e.what());
        return 2;
    } catch (const std::exception& e) {
        fmt::print(stderr, "zenith: error: {}\n", e.what());
        return 2;
    }
    return 0;
}
