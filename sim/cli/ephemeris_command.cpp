// `zenith ephemeris`: Sun, Moon and stars for one instant, or a JSON-lines batch.
#include <fmt/format.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "commands.h"
#include "zenith/geo/ephemeris.h"
#include "zenith/sim/ephemeris_report.h"

namespace zenith::cli {
namespace {

namespace fs = std::filesystem;

// Built-in default observer: the Royal Observatory, Greenwich (WGS84).
constexpr double kDefaultLatDeg = 51.476852;
constexpr double kDefaultLonDeg = -0.000500;
constexpr double kDefaultHeightM = 46.0;

struct EphemerisArgs {
    std::optional<std::string> utc;
    double lat_deg = kDefaultLatDeg;
    double lon_deg = kDefaultLonDeg;
    double height_m = kDefaultHeightM;
    std::optional<double> dut1_s;
    std::optional<double> delta_t_s;
    bool refraction = false;
    double pressure_hpa = 1010.0;
    double temperature_c = 10.0;
    bool json = false;
    std::size_t stars = 10;
    double mag_limit = 6.5;
    std::string batch_in;
    std::string batch_out;
};

int RunBatch(const EphemerisArgs& a) {
    std::ifstream in(a.batch_in);
    if (!in) {
        fmt::print(stderr, "zenith ephemeris: cannot open --batch file '{}'\n", a.batch_in);
        return 2;
    }
    // Written under a temporary name and renamed when complete, so OUT is never half-written.
    const fs::path out_path = a.batch_out;
    const fs::path tmp_path = out_path.string() + ".partial";
    std::ofstream out(tmp_path, std::ios::trunc);
    if (!out) {
        fmt::print(stderr, "zenith ephemeris: cannot write --out file '{}'\n", a.batch_out);
        return 2;
    }
    const sim::BatchSummary summary = sim::RunEphemerisBatch(in, out);
    out.close();
    if (!out) {
        fmt::print(stderr, "zenith ephemeris: write error on '{}'\n", tmp_path.string());
        return 2;
    }
    fs::rename(tmp_path, out_path);
    if (summary.failed > 0) {
        fmt::print(stderr,
                   "zenith ephemeris: {} of {} lines failed (first: {}); their output lines hold "
                   "{{\"line\": N, \"error\": ...}}\n",
                   summary.failed, summary.lines, summary.first_error);
        return 1;
    }
    fmt::print(stderr, "zenith ephemeris: {} lines written to {}\n", summary.lines, a.batch_out);
    return 0;
}

int RunSingle(const EphemerisArgs& a) {
    geo::TimeOptions time_options{a.dut1_s, a.delta_t_s};
    const geo::Time t =
        a.utc ? geo::TimeFromIso8601(*a.utc, time_options) : geo::TimeNow(time_options);
    const geo::Observer observer(a.lat_deg, a.lon_deg, a.height_m);
    geo::EphemerisOptions options;
    if (a.refraction) options.refraction = geo::RefractionOptions{a.pressure_hpa, a.temperature_c};

    std::optional<geo::StarCatalog> catalog;
    if (a.stars > 0) {
        try {
            catalog = geo::StarCatalog::Load(a.mag_limit);
        } catch (const geo::CatalogError& e) {
            fmt::print(stderr, "zenith ephemeris: stars not shown: {}\n", e.what());
        }
    }
    const geo::Ephemeris ephemeris(catalog ? &*catalog : nullptr);
    const geo::SkyEphemeris e = ephemeris.Compute(t, observer, options);
    if (a.json) {
        nlohmann::json j = sim::EphemerisRecord(e);
        j["utc"] = geo::FormatIso8601(geo::CivilFromJulianDate(t.jd_utc));
        j["lat_deg"] = observer.lat_deg();
        j["lon_deg"] = observer.lon_deg();
        j["height_m"] = observer.height_m();
        j["tt_minus_ut1_s"] = t.DeltaT();
        j["refraction"] = a.refraction;
        if (a.refraction) {
            j["sun_el_deg"] = e.sun.elevation * 57.29577951308232;
            j["moon_el_deg"] = e.moon.elevation * 57.29577951308232;
        }
        j["moon_waxing"] = e.moon_phase.waxing;
        j["moon_bright_limb_from_zenith_deg"] =
            e.moon_phase.bright_limb_from_zenith * 57.29577951308232;
        nlohmann::json stars = nlohmann::json::array();
        for (std::size_t i = 0; i < e.stars.size() && i < a.stars; ++i) {
            const auto& s = e.stars[i];
            stars.push_back({{"name", s.star->name},
                             {"hd", s.star->hd},
                             {"mag_v", s.star->magnitude_v},
                             {"b_minus_v", s.star->b_minus_v},
                             {"az_deg", s.horizontal.azimuth * 57.29577951308232},
                             {"el_deg", s.horizontal.elevation * 57.29577951308232},
                             {"illuminance_lux", s.illuminance_lux}});
        }
        j["stars"] = stars;
        std::cout << j.dump(2) << '\n';
    } else {
        std::cout << sim::EphemerisTable(e, observer, a.stars);
    }
    return 0;
}

}  // namespace

Command AddEphemerisCommand(CLI::App& app) {
    const auto eph_ptr = std::make_shared<EphemerisArgs>();
    EphemerisArgs& eph = *eph_ptr;
    CLI::App* ephemeris = app.add_subcommand(
        "ephemeris", "Sun, Moon and star positions for a UTC instant and a WGS84 position");
    ephemeris->add_option("--utc", eph.utc,
                          "UTC instant, ISO 8601 (2024-04-08T18:18:00Z, offsets allowed); "
                          "default: now");
    ephemeris->add_option("--lat", eph.lat_deg, "geodetic latitude, degrees (north +)")
        ->capture_default_str();
    ephemeris->add_option("--lon", eph.lon_deg, "longitude, degrees (east +)")
        ->capture_default_str();
    ephemeris->add_option("--height", eph.height_m, "height above the WGS84 ellipsoid, metres")
        ->capture_default_str();
    ephemeris->add_option("--dut1", eph.dut1_s, "UT1 - UTC, seconds (default 0)");
    ephemeris->add_option("--delta-t", eph.delta_t_s,
                          "override TT - UT1, seconds (default: leap seconds + 32.184 s)");
    ephemeris->add_flag("--refraction", eph.refraction,
                        "apply atmospheric refraction to elevations (default: geometric)");
    ephemeris->add_option("--pressure", eph.pressure_hpa, "pressure for refraction, hPa")
        ->capture_default_str();
    ephemeris
        ->add_option("--temperature", eph.temperature_c, "temperature for refraction, degrees C")
        ->capture_default_str();
    ephemeris->add_option("--stars", eph.stars, "how many of the brightest stars to list")
        ->capture_default_str();
    ephemeris->add_option("--mag-limit", eph.mag_limit, "faintest star magnitude loaded")
        ->capture_default_str();
    ephemeris->add_flag("--json", eph.json, "print JSON instead of a table");
    auto* batch = ephemeris->add_option(
        "--batch", eph.batch_in,
        "JSON-lines input: {utc, lat_deg, lon_deg, height_m} per line (needs --out)");
    auto* batch_out =
        ephemeris->add_option("--out", eph.batch_out, "JSON-lines output for --batch");
    batch->needs(batch_out);
    batch_out->needs(batch);
    batch->check(CLI::ExistingFile);
    return {ephemeris, [eph_ptr] {
                return eph_ptr->batch_in.empty() ? RunSingle(*eph_ptr) : RunBatch(*eph_ptr);
            }};
}

}  // namespace zenith::cli
