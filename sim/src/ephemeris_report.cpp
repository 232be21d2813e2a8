#include "zenith/sim/ephemeris_report.h"

#include <fmt/format.h>

#include <cmath>
#include <istream>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>

#include "zenith/base/error.h"
#include "zenith/base/json_text.h"
#include "zenith/base/json_value.h"
#include "zenith/geo/eclipse.h"
#include "zenith/geo/planets.h"

namespace zenith::sim {
namespace {

constexpr double kRadToDeg = 57.295779513082320876798;

double Deg(double radians) { return radians * kRadToDeg; }

// Rec. 709 luminance weights, as the renderer's (sky/atmosphere.h).
double Luminance(const glm::dvec3& rgb) { return 0.2126 * rgb.x + 0.7152 * rgb.y + 0.0722 * rgb.z; }

std::string FormatLatLon(double lat_deg, double lon_deg) {
    return fmt::format("{:.5f}°{} {:.5f}°{}", std::abs(lat_deg), lat_deg >= 0 ? 'N' : 'S',
                       std::abs(lon_deg), lon_deg >= 0 ? 'E' : 'W');
}

constexpr std::size_t kMaxBatchLineBytes = 1u << 16;
constexpr int kMaxBatchDepth = 8;

// Reads one line (up to '\n', which is dropped) keeping at most kMaxBatchLineBytes of it; a
// longer line is read to its end all the same and reported by its length. False at the end.
bool ReadLine(std::istream& in, std::string& text, std::size_t& length) {
    text.clear();
    length = 0;
    std::streambuf& buffer = *in.rdbuf();
    for (int c = buffer.sbumpc(); c != std::char_traits<char>::eof(); c = buffer.sbumpc()) {
        if (c == '\n') return true;
        if (length++ < kMaxBatchLineBytes) text += static_cast<char>(c);
    }
    in.setstate(std::ios::eofbit);
    return length > 0;
}

// Reads a required finite number; the message names the key and what was found.
double RequireNumber(const nlohmann::json& j, const char* key, const char* unit) {
    const auto it = j.find(key);
    if (it == j.end()) {
        throw ArgumentError(fmt::format("missing key \"{}\" ({})", key, unit));
    }
    if (!it->is_number()) {
        throw ArgumentError(
            fmt::format("\"{}\" must be a number ({}), got {}", key, unit, DescribeJsonValue(*it)));
    }
    return it->get<double>();
}

geo::TimeOptions TimeOptionsFrom(const nlohmann::json& j) {
    geo::TimeOptions options;
    if (j.contains("dut1_s")) options.dut1_s = RequireNumber(j, "dut1_s", "seconds");
    if (j.contains("delta_t_s")) options.delta_t_s = RequireNumber(j, "delta_t_s", "seconds");
    return options;
}

}  // namespace

nlohmann::json EphemerisRecord(const geo::SkyEphemeris& e) {
    const auto& sun = e.sun.topocentric.horizontal;
    const auto& moon = e.moon.topocentric.horizontal;
    nlohmann::json record = {
        {"sun_az_deg", Deg(sun.azimuth)},
        {"sun_el_deg", Deg(sun.elevation)},
        {"sun_dist_km", sun.distance / 1000.0},
        {"sun_diameter_deg", Deg(e.sun.angular_diameter)},
        {"moon_az_deg", Deg(moon.azimuth)},
        {"moon_el_deg", Deg(moon.elevation)},
        {"moon_dist_km", moon.distance / 1000.0},
        {"moon_diameter_deg", Deg(e.moon.angular_diameter)},
        {"moon_illum_fraction", e.moon_phase.illuminated_fraction},
        {"moon_phase_angle_deg", Deg(e.moon_phase.phase_angle)},
        {"moon_bright_limb_deg", Deg(e.moon_phase.bright_limb_angle)},
    };
    // Eclipses (geo/eclipse.h): the Sun's disk area the Moon covers for this observer and the
    // share of its light (luminance Y of the limb-darkened RGB) left; the sunlight reaching the
    // Moon's centre past the solid Earth and the umbral magnitude of its place.
    const geo::SolarEclipse solar = geo::ComputeSolarEclipse(e);
    record["sun_obscuration"] = solar.obscuration;
    record["sun_eclipse_magnitude"] = solar.magnitude;
    record["sun_uncovered_flux"] = Luminance(solar.uncovered_flux);
    const geo::LunarEclipse lunar = geo::ComputeLunarEclipse(e);
    record["moon_direct_sunlight"] = Luminance(lunar.direct_sunlight);
    record["moon_umbral_magnitude"] = lunar.umbral_magnitude;
    // Planets: <name>_az_deg, _el_deg, _dist_au, _mag, _illum_fraction ("venus_mag").
    for (const geo::PlanetPosition& planet : e.planets) {
        const std::string key(geo::PlanetName(planet.planet));
        const auto& h = planet.topocentric.horizontal;
        record[key + "_az_deg"] = Deg(h.azimuth);
        record[key + "_el_deg"] = Deg(planet.elevation);
        record[key + "_dist_au"] = planet.distance_au;
        record[key + "_mag"] = planet.magnitude_v;
        record[key + "_illum_fraction"] = planet.illuminated_fraction;
    }
    return record;
}

std::string EphemerisTable(const geo::SkyEphemeris& e, const geo::Observer& observer,
                           std::size_t max_stars) {
    std::string out;
    auto line = [&out](const std::string& s) { out += s + '\n'; };
    line(fmt::format("UTC {}   TT-UT1 {:.3f} s",
                     geo::FormatIso8601(geo::CivilFromJulianDate(e.time.jd_utc)), e.time.DeltaT()));
    line(fmt::format("observer {}   height {:.1f} m above the WGS84 ellipsoid",
                     FormatLatLon(observer.lat_deg(), observer.lon_deg()), observer.height_m()));
    line("");
    line(fmt::format("{:<6} {:>12} {:>12} {:>16} {:>11}", "body", "azimuth °", "elevation °",
                     "distance km", "diameter °"));
    auto body = [&](const char* name, const geo::BodyState& b) {
        line(fmt::format("{:<6} {:>12.5f} {:>12.5f} {:>16.1f} {:>11.5f}", name,
                         Deg(b.topocentric.horizontal.azimuth), Deg(b.elevation),
                         b.topocentric.horizontal.distance / 1000.0, Deg(b.angular_diameter)));
    };
    body("Sun", e.sun);
    body("Moon", e.moon);
    line("");
    const auto& p = e.moon_phase;
    line(
        fmt::format("Moon: {:.1f}% illuminated ({}), phase angle {:.2f}°, bright limb at "
                    "position angle {:.2f}° (from north), {:.2f}° from the zenith direction",
                    100.0 * p.illuminated_fraction, p.waxing ? "waxing" : "waning",
                    Deg(p.phase_angle), Deg(p.bright_limb_angle), Deg(p.bright_limb_from_zenith)));
    const geo::SolarEclipse solar = geo::ComputeSolarEclipse(e);
    if (solar.partial()) {
        line(
            fmt::format("Solar eclipse: {} magnitude {:.4f}, {:.2f}% of the Sun's disk covered, "
                        "{:.2f}% of its light left (limb-darkened)",
                        solar.total() ? "total," : "partial,", solar.magnitude,
                        100.0 * solar.obscuration, 100.0 * Luminance(solar.uncovered_flux)));
    }
    const geo::LunarEclipse lunar = geo::ComputeLunarEclipse(e);
    if (lunar.penumbral_magnitude > 0.0) {
        line(
            fmt::format("Lunar eclipse: umbral magnitude {:.4f}, penumbral {:.4f}; {:.2f}% of "
                        "the Sun's light reaches the Moon's centre directly",
                        lunar.umbral_magnitude, lunar.penumbral_magnitude,
                        100.0 * Luminance(lunar.direct_sunlight)));
    }
    if (!e.planets.empty()) {
        line("");
        line(fmt::format("  {:<8} {:>10} {:>10} {:>11} {:>6} {:>8} {:>9}", "planet", "azimuth °",
                         "elev. °", "distance au", "V", "lit %", "diam. \""));
        for (const geo::PlanetPosition& planet : e.planets) {
            line(fmt::format("  {:<8} {:>10.4f} {:>10.4f} {:>11.6f} {:>6.2f} {:>8.1f} {:>9.2f}",
                             geo::PlanetName(planet.planet),
                             Deg(planet.topocentric.horizontal.azimuth), Deg(planet.elevation),
                             planet.distance_au, planet.magnitude_v,
                             100.0 * planet.illuminated_fraction, planet.angular_diameter_arcsec));
        }
    }
    if (max_stars > 0 && !e.stars.empty()) {
        line("");
        // Civil twilight ends at -6 deg: before that the eye sees at most the brightest planets.
        const bool daylit = e.sun.elevation > -0.10471975511965977;
        line(fmt::format("Brightest stars above the horizon ({} of {} shown){}:",
                         std::min(max_stars, e.stars.size()), e.stars.size(),
                         daylit ? "; the Sun is above -6 deg, so the sky hides them" : ""));
        line(fmt::format("  {:<14} {:>6} {:>6} {:>10} {:>10} {:>12}", "name", "V", "B-V",
                         "azimuth °", "elev. °", "E lux"));
        for (std::size_t i = 0; i < e.stars.size() && i < max_stars; ++i) {
            const auto& s = e.stars[i];
            const std::string name =
                s.star->name.empty() ? fmt::format("HD {}", s.star->hd) : s.star->name;
            line(fmt::format("  {:<14} {:>6.2f} {:>6.2f} {:>10.3f} {:>10.3f} {:>12.3e}", name,
                             s.star->magnitude_v, s.star->b_minus_v, Deg(s.horizontal.azimuth),
                             Deg(s.horizontal.elevation), s.illuminance_lux));
        }
    }
    return out;
}

BatchSummary RunEphemerisBatch(std::istream& in, std::ostream& out) {
    BatchSummary summary;
    const geo::Ephemeris ephemeris;
    std::string text;
    std::size_t length = 0;
    while (ReadLine(in, text, length)) {
        ++summary.lines;
        nlohmann::json record;
        try {
            // A line is one small object: bound what it may cost before parsing it.
            if (length > kMaxBatchLineBytes) {
                throw ArgumentError(
                    fmt::format("line of {} bytes (at most {})", length, kMaxBatchLineBytes));
            }
            if (const auto at = FindJsonNestingBeyond(text, kMaxBatchDepth)) {
                throw ArgumentError(
                    fmt::format("JSON nested deeper than {} levels at "
                                "byte {}",
                                kMaxBatchDepth, *at + 1));
            }
            const nlohmann::json j = nlohmann::json::parse(text);
            if (!j.is_object()) throw ArgumentError("expected a JSON object");
            const auto utc = j.find("utc");
            if (utc == j.end() || !utc->is_string()) {
                throw ArgumentError("missing string key \"utc\" (ISO 8601 UTC)");
            }
            const geo::Time t = geo::TimeFromIso8601(utc->get<std::string>(), TimeOptionsFrom(j));
            const geo::Observer observer(RequireNumber(j, "lat_deg", "degrees"),
                                         RequireNumber(j, "lon_deg", "degrees"),
                                         RequireNumber(j, "height_m", "metres"));
            record = EphemerisRecord(ephemeris.Compute(t, observer));
        } catch (const std::exception& ex) {
            ++summary.failed;
            std::string message = ex.what();
            if (const auto* pe = dynamic_cast<const nlohmann::json::parse_error*>(&ex)) {
                message = fmt::format("not valid JSON (byte {})", pe->byte);
            }
            if (summary.first_error.empty()) {
                summary.first_error = fmt::format("line {}: {}", summary.lines, message);
            }
            record = {{"line", summary.lines}, {"error", message}};
        }
        out << record.dump() << '\n';
    }
    return summary;
}

}  // namespace zenith::sim
