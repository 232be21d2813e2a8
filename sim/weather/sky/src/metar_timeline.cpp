// Weather along a replay from a METAR file; the rules are in metar_timeline.h.
#include "zenith/weather/metar_timeline.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <utility>

#include "zenith/base/units.h"
#include "zenith/geo/time.h"

namespace zenith::weather {

namespace {

using sky::clouds::CloudLayer;

constexpr double kMinThickness = 50.0;  // sky::clouds::Validate
constexpr double kClearTolerance = 0.005;

bool IsFog(const CloudLayer& l) { return l.name == "fog"; }

double Lerp(double a, double b, double u) { return a + (b - a) * u; }

CloudLayer BlendLayer(const CloudLayer& a, const CloudLayer& b, double u) {
    CloudLayer l = u < 0.5 ? a : b;  // name, map, period, wind, ground fog, snow
    l.base_altitude = Lerp(a.base_altitude, b.base_altitude, u);
    l.top_altitude = Lerp(a.top_altitude, b.top_altitude, u);
    l.coverage = std::clamp(Lerp(a.coverage, b.coverage, u), 0.0, 1.0);
    l.cloud_type = std::clamp(Lerp(a.cloud_type, b.cloud_type, u), 0.0, 1.0);
    l.precipitation = std::clamp(Lerp(a.precipitation, b.precipitation, u), 0.0, 1.0);
    // The material by its logarithm: fog thinning from 100 m to 400 m of visibility, or water
    // turning to ice, changes evenly in optical depth.
    l.extinction_scale =
        std::exp(Lerp(std::log(a.extinction_scale), std::log(b.extinction_scale), u));
    return l;
}

// Blends two lists by order; a layer without a partner fades.
void BlendLists(const std::vector<CloudLayer>& a, const std::vector<CloudLayer>& b, double u,
                std::vector<CloudLayer>* out) {
    const std::size_t n = std::max(a.size(), b.size());
    for (std::size_t i = 0; i < n; ++i) {
        if (i < a.size() && i < b.size()) {
            out->push_back(BlendLayer(a[i], b[i], u));
        } else {
            CloudLayer l = i < a.size() ? a[i] : b[i];
            l.coverage *= i < a.size() ? 1.0 - u : u;
            if (l.coverage > 0.0) out->push_back(std::move(l));
        }
    }
}

double ClearOr(const std::optional<double>& v, double clear) { return v ? *v : clear; }

std::string FormatTime(double unix_s) {
    const geo::CivilTime c = geo::CivilFromUnixSeconds(unix_s);
    return fmt::format("{:04d}-{:02d}-{:02d} {:02d}:{:02d}", c.year, c.month, c.day, c.hour,
                       c.minute);
}

}  // namespace

double GreatCircleDistance(double lat1_deg, double lon1_deg, double lat2_deg, double lon2_deg) {
    const double p1 = Radians(lat1_deg), p2 = Radians(lat2_deg);
    const double dp = p2 - p1, dl = Radians(lon2_deg - lon1_deg);
    const double h = std::sin(dp / 2) * std::sin(dp / 2) +
                     std::cos(p1) * std::cos(p2) * std::sin(dl / 2) * std::sin(dl / 2);
    return 2.0 * kEarthRadius * std::asin(std::min(1.0, std::sqrt(h)));
}

std::optional<double> ResolveReportTime(const ReportTime& time, double flight_start_s,
                                        double flight_end_s) {
    std::optional<double> best;
    double best_distance = 0.0;
    for (const double anchor : {flight_start_s, flight_end_s}) {
        const geo::CivilTime c = geo::CivilFromUnixSeconds(anchor);
        for (int shift = -1; shift <= 1; ++shift) {
            geo::CivilTime t;
            const int months = c.year * 12 + (c.month - 1) + shift;
            t.year = months / 12;
            t.month = months % 12 + 1;
            t.day = time.day;
            t.hour = time.hour;
            t.minute = time.minute;
            t.second = 0.0;
            try {
                geo::ValidateCivilTime(t);
            } catch (const std::exception&) {
                continue;  // no such day in that month
            }
            const double s = geo::UnixSecondsFromCivil(t);
            const double distance = s < flight_start_s ? flight_start_s - s
                                    : s > flight_end_s ? s - flight_end_s
                                                       : 0.0;
            if (!best || distance < best_distance || (distance == best_distance && s < *best)) {
                best = s;
                best_distance = distance;
            }
        }
    }
    return best;
}

double QuantiseBlend(double u) {
    return std::clamp(std::round(u * kBlendSteps) / kBlendSteps, 0.0, 1.0);
}

MetarWeather BlendMetarWeather(const MetarWeather& a, const MetarWeather& b, double u,
                               double clear_visibility_m) {
    if (u <= 0.0) return a;
    if (u >= 1.0) return b;
    MetarWeather out = u < 0.5 ? a : b;
    out.notes.clear();
    if (a.visibility_m || b.visibility_m) {
        const double va = ClearOr(a.visibility_m, clear_visibility_m);
        const double vb = ClearOr(b.visibility_m, clear_visibility_m);
        const double v = std::exp(Lerp(std::log(va), std::log(vb), u));
        if (std::abs(v / clear_visibility_m - 1.0) <= kClearTolerance) {
            out.visibility_m.reset();
            out.ground_extinction_per_m.reset();
        } else {
            out.visibility_m = v;
            out.ground_extinction_per_m = ExtinctionForVisibility(v);
        }
    }
    out.fog = a.fog || b.fog;
    out.haze = a.haze || b.haze;
    out.precipitation = Lerp(a.precipitation, b.precipitation, u);

    std::vector<CloudLayer> fog_a, fog_b, rest_a, rest_b;
    for (const CloudLayer& l : a.clouds.layers) (IsFog(l) ? fog_a : rest_a).push_back(l);
    for (const CloudLayer& l : b.clouds.layers) (IsFog(l) ? fog_b : rest_b).push_back(l);
    std::vector<CloudLayer> layers;
    BlendLists(fog_a, fog_b, u, &layers);
    BlendLists(rest_a, rest_b, u, &layers);
    std::stable_sort(layers.begin(), layers.end(), [](const CloudLayer& x, const CloudLayer& y) {
        return x.base_altitude < y.base_altitude;
    });
    // Bottom to top without overlap: cut at the next base; a layer too thin goes (the one of
    // the two with less coverage).
    std::vector<CloudLayer> kept;
    for (CloudLayer& l : layers) {
        while (!kept.empty() && kept.back().top_altitude > l.base_altitude) {
            CloudLayer& below = kept.back();
            if (l.base_altitude - below.base_altitude >= kMinThickness) {
                below.top_altitude = l.base_altitude;
                break;
            }
            if (below.coverage >= l.coverage) {
                l.coverage = 0.0;  // this one goes
                break;
            }
            kept.pop_back();
        }
        if (l.coverage > 0.0) kept.push_back(std::move(l));
    }
    out.clouds.layers = std::move(kept);
    out.clouds.name = u < 0.5 ? a.clouds.name : b.clouds.name;
    out.clouds.description =
        fmt::format("{} -> {} at {:.4f}", a.clouds.description, b.clouds.description, u);
    sky::clouds::Validate(out.clouds);
    return out;
}

MetarTimeline::MetarTimeline(MetarFile file, const TimelineOptions& options, double flight_start_s,
                             double flight_end_s)
    : file_(std::move(file)), options_(options) {
    const auto note = [this](std::string text) {
        if (notes_.size() < kMaxTimelineNotes) {
            notes_.push_back(std::move(text));
        } else if (notes_.size() == kMaxTimelineNotes) {
            notes_.push_back("... (more notes left out)");
        }
    };
    // Times.
    std::vector<std::optional<double>> times(file_.records.size());
    std::size_t untimed = 0, from_group = 0;
    std::optional<std::size_t> first_untimed_line;
    for (std::size_t i = 0; i < file_.records.size(); ++i) {
        const MetarRecord& r = file_.records[i];
        if (r.time_s) {
            times[i] = r.time_s;
        } else if (r.metar.time) {
            times[i] = ResolveReportTime(*r.metar.time, flight_start_s, flight_end_s);
            if (times[i]) ++from_group;
        }
        if (!times[i]) {
            ++untimed;
            if (!first_untimed_line) first_untimed_line = r.line;
        }
    }
    if (untimed == file_.records.size()) {
        throw MetarError(AtLocation(file_.source, first_untimed_line,
                                    "no report has a usable time (expected a CSV 'valid' column, "
                                    "a 'YYYY/MM/DD hh:mm' line before each report, or the "
                                    "report's ddhhmmZ group)"));
    }
    if (untimed > 0) {
        note(fmt::format("{} reports without a usable time left out (the first at {})", untimed,
                         AtLocation(file_.source, first_untimed_line, "")));
    }
    if (from_group > 0) {
        note(fmt::format(
            "{} report times from their ddhhmmZ group, in the month that puts them closest to "
            "the flight",
            from_group));
    }

    // Stations, by their ICAO name, in the order of the file.
    std::map<std::string, std::size_t> index;
    bool any_position = false;
    for (std::size_t i = 0; i < file_.records.size(); ++i) {
        if (!times[i]) continue;
        const MetarRecord& r = file_.records[i];
        if (r.lat_deg && r.lon_deg) any_position = true;
    }
    for (std::size_t i = 0; i < file_.records.size(); ++i) {
        if (!times[i]) continue;
        const MetarRecord& r = file_.records[i];
        const std::string key = any_position ? r.metar.station : std::string("all");
        auto [it, inserted] = index.try_emplace(key, stations_.size());
        if (inserted) {
            if (stations_.size() >= kMaxTimelineStations) {
                throw MetarError(AtLocation(
                    file_.source, r.line,
                    fmt::format("more than {} stations in one file", kMaxTimelineStations)));
            }
            stations_.push_back({key, std::nullopt, std::nullopt, {}, {}});
        }
        TimelineStation& s = stations_[it->second];
        if (!s.lat_deg && r.lat_deg && r.lon_deg) {
            s.lat_deg = r.lat_deg;
            s.lon_deg = r.lon_deg;
        }
        s.reports.push_back(i);
    }
    if (!any_position) {
        note(
            "no station positions in the file (CSV lat/lon columns): all reports are taken as one "
            "station's");
    } else {
        std::size_t dropped = 0;
        std::string names;
        std::erase_if(stations_, [&](const TimelineStation& s) {
            if (s.lat_deg) return false;
            ++dropped;
            if (dropped <= 5) names += (names.empty() ? "" : ", ") + s.name;
            return true;
        });
        if (dropped > 0) {
            note(fmt::format("{} stations without a position left out ({})", dropped, names));
        }
    }

    // Each station's reports by time; the later of two at the same time (a COR) is kept.
    std::size_t duplicates = 0;
    for (TimelineStation& s : stations_) {
        std::stable_sort(s.reports.begin(), s.reports.end(),
                         [&](std::size_t x, std::size_t y) { return *times[x] < *times[y]; });
        std::vector<std::size_t> unique;
        for (const std::size_t r : s.reports) {
            if (!unique.empty() && *times[unique.back()] == *times[r]) {
                unique.back() = r;
                ++duplicates;
            } else {
                unique.push_back(r);
            }
        }
        s.reports = std::move(unique);
        for (const std::size_t r : s.reports) s.times_s.push_back(*times[r]);

        const double first = s.times_s.front(), last = s.times_s.back();
        if (flight_start_s < first - kLongGap) {
            note(
                fmt::format("{}: the flight starts {:.1f} h before its first report ({}): that "
                            "report is held",
                            s.name, (first - flight_start_s) / 3600.0, FormatTime(first)));
        }
        if (flight_end_s > last + kLongGap) {
            note(
                fmt::format("{}: the flight ends {:.1f} h after its last report ({}): that "
                            "report is held",
                            s.name, (flight_end_s - last) / 3600.0, FormatTime(last)));
        }
        for (std::size_t k = 1; k < s.times_s.size(); ++k) {
            const double t0 = s.times_s[k - 1], t1 = s.times_s[k];
            if (t1 - t0 > kLongGap && t1 > flight_start_s && t0 < flight_end_s) {
                note(fmt::format("{}: {:.1f} h between reports ({} to {}), blended across it",
                                 s.name, (t1 - t0) / 3600.0, FormatTime(t0), FormatTime(t1)));
            }
        }
    }
    if (duplicates > 0) {
        note(
            fmt::format("{} reports at the same time as another of their station: the later "
                        "line kept",
                        duplicates));
    }
}

MetarWeather MetarTimeline::StationWeather(const TimelineStation& s, double time_s,
                                           std::string* description) const {
    const double elevation = options_.station_elevation_m.value_or(0.0);
    const auto weather_of = [&](std::size_t k) {
        return CloudWeatherFromMetar(file_.records[s.reports[k]].metar, elevation);
    };
    const auto it = std::upper_bound(s.times_s.begin(), s.times_s.end(), time_s);
    const std::size_t next = static_cast<std::size_t>(it - s.times_s.begin());
    if (next == 0 || next == s.times_s.size()) {
        const std::size_t k = next == 0 ? 0 : next - 1;
        *description = fmt::format("{} {} (held)", s.name, FormatTime(s.times_s[k]));
        return weather_of(k);
    }
    const double t0 = s.times_s[next - 1], t1 = s.times_s[next];
    const double u = QuantiseBlend((time_s - t0) / (t1 - t0));
    *description = fmt::format("{} {} -> {} u {:.4f}", s.name, FormatTime(t0), FormatTime(t1), u);
    if (u == 0.0) return weather_of(next - 1);
    if (u == 1.0) return weather_of(next);
    return BlendMetarWeather(weather_of(next - 1), weather_of(next), u,
                             options_.clear_visibility_m);
}

std::pair<std::size_t, std::optional<std::size_t>> MetarTimeline::Nearest(double lat_deg,
                                                                          double lon_deg,
                                                                          double* d_nearest,
                                                                          double* d_second) const {
    std::size_t nearest = 0;
    std::optional<std::size_t> second;
    *d_nearest = *d_second = 0.0;
    if (stations_.size() < 2) return {nearest, second};
    for (std::size_t i = 0; i < stations_.size(); ++i) {
        const double d =
            GreatCircleDistance(lat_deg, lon_deg, *stations_[i].lat_deg, *stations_[i].lon_deg);
        if (i == 0 || d < *d_nearest) {
            if (i > 0) {
                second = nearest;
                *d_second = *d_nearest;
            }
            nearest = i;
            *d_nearest = d;
        } else if (!second || d < *d_second) {
            second = i;
            *d_second = d;
        }
    }
    return {nearest, second};
}

LayerWind MetarTimeline::WindAt(double time_s, double lat_deg, double lon_deg) const {
    double d1 = 0.0, d2 = 0.0;
    const TimelineStation& s = stations_[Nearest(lat_deg, lon_deg, &d1, &d2).first];
    const auto it = std::lower_bound(s.times_s.begin(), s.times_s.end(), time_s);
    std::size_t k = static_cast<std::size_t>(it - s.times_s.begin());
    if (k == s.times_s.size() || (k > 0 && time_s - s.times_s[k - 1] <= s.times_s[k] - time_s)) {
        --k;
    }
    const Metar& m = file_.records[s.reports[k]].metar;
    LayerWind w;
    if (m.wind && m.wind->speed_m_s) w.speed_m_s = std::min(*m.wind->speed_m_s, 150.0);
    if (m.wind && m.wind->direction_deg) w.from_rad = Radians(*m.wind->direction_deg);
    return w;
}

namespace {

// A station's reports' value at time_s: linear between the nearest two that give it, held
// beyond them; nullopt when none gives it.
template <class Value>
std::optional<double> ReportedAt(const MetarFile& file, const TimelineStation& s, double time_s,
                                 Value value) {
    std::optional<double> before, after;
    double t_before = 0.0, t_after = 0.0;
    for (std::size_t k = 0; k < s.reports.size(); ++k) {
        const std::optional<double> v = value(file.records[s.reports[k]].metar);
        if (!v) continue;
        if (s.times_s[k] <= time_s) {
            before = v;
            t_before = s.times_s[k];
        } else {
            after = v;
            t_after = s.times_s[k];
            break;
        }
    }
    if (before && after) {
        return *before + (*after - *before) * (time_s - t_before) / (t_after - t_before);
    }
    return before ? before : after;
}

}  // namespace

StationAir MetarTimeline::StationAirAt(const TimelineStation& s, double time_s) const {
    StationAir air;
    air.elevation_m = options_.station_elevation_m.value_or(0.0);
    air.qnh_hpa = ReportedAt(file_, s, time_s, [](const Metar& m) {
                      return m.qnh_hpa;
                  }).value_or(kIsaPressureHpa);
    air.temperature_c =
        ReportedAt(file_, s, time_s, [](const Metar& m) { return m.temperature_c; });
    return air;
}

StationAir MetarTimeline::AirAt(double time_s, double lat_deg, double lon_deg) const {
    double d_nearest = 0.0, d_second = 0.0;
    const auto [nearest, second] = Nearest(lat_deg, lon_deg, &d_nearest, &d_second);
    StationAir air = StationAirAt(stations_[nearest], time_s);
    if (second && d_second - d_nearest < kStationTransition) {
        const double w = 0.5 * (1.0 - (d_second - d_nearest) / kStationTransition);
        const StationAir b = StationAirAt(stations_[*second], time_s);
        air.qnh_hpa += w * (b.qnh_hpa - air.qnh_hpa);
        if (air.temperature_c && b.temperature_c) {
            *air.temperature_c += w * (*b.temperature_c - *air.temperature_c);
        } else if (!air.temperature_c) {
            air.temperature_c = b.temperature_c;
        }
    }
    return air;
}

TimelineSample MetarTimeline::At(double time_s, double lat_deg, double lon_deg,
                                 const std::optional<LayerWind>& wind) const {
    TimelineSample sample;
    double d_nearest = 0.0, d_second = 0.0;
    const auto [nearest, second] = Nearest(lat_deg, lon_deg, &d_nearest, &d_second);
    sample.weather = StationWeather(stations_[nearest], time_s, &sample.description);
    if (second && d_second - d_nearest < kStationTransition) {
        const double w = QuantiseBlend(0.5 * (1.0 - (d_second - d_nearest) / kStationTransition));
        if (w > 0.0) {
            std::string other;
            const MetarWeather b = StationWeather(stations_[*second], time_s, &other);
            sample.weather = BlendMetarWeather(sample.weather, b, w, options_.clear_visibility_m);
            sample.description += fmt::format("; {:.4f} of {}", w, other);
        }
    }
    if (wind) {
        for (CloudLayer& l : sample.weather.clouds.layers) {
            l.wind_speed = wind->speed_m_s;
            l.wind_from = wind->from_rad;
        }
    }
    return sample;
}

}  // namespace zenith::weather
