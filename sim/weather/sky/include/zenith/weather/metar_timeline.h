// Weather that changes along a replay: a file of METAR reports (metar_file.h) as the weather at
// any time and place of a flight. Pure functions, no GL; `zenith replay --metar-file` draws what
// MetarTimeline::At gives for each frame's time and the aircraft's position.
//
// Time of a report: the file's (a CSV `valid` column, or a NOAA time line before the report in a
// lines file); else the report's own day/hour/minute group, placed in the month before, of, or
// after the flight's first and last fix, whichever puts it closest to the flight (0 inside it;
// a tie takes the earlier). Reports with no usable time are left out with a note; none usable is
// a MetarError naming the file and the first such line. Two reports of a station at the same
// time: the later in the file (a COR) is kept.
//
// Station: the METAR's station (ICAO), placed by the file's lat/lon columns (the first record of
// the station that has both). The station of a frame is the nearest to the aircraft
// (great-circle distance on a sphere of kEarthRadius). Without any position, all reports are one
// station (with a note); stations without a position, when others have one, are left out (with a
// note). At most kMaxTimelineStations stations.
//
// Between two reports of a station the weather is blended (BlendMetarWeather) with
// u = (t - t0) / (t1 - t0) rounded to a multiple of 1 / kBlendSteps; before the first report and
// after the last the nearest report is held (a note when the flight is more than kLongGap from
// it, and for each gap between reports longer than that inside the flight).
//
// Changing station does not pop: where the nearest station A and the second nearest B are
// within kStationTransition of each other (d_B - d_A < kStationTransition), the weather is
// BlendMetarWeather(W_A, W_B, w) with w = 0.5 (1 - (d_B - d_A) / kStationTransition), rounded
// like u, so it is half of each on the line of equal distance and all of A 10 km of difference
// away from it (a band about 10 km wide each side for stations 50+ km apart).
//
// Wind: the clouds drift by wind speed x time since the replay's start, so a wind that changed
// along the flight would move the whole deck at once; every layer keeps the wind of the weather
// at the flight's first fix (MetarTimeline::WindAt there, passed to At).
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "zenith/weather/altimetry.h"
#include "zenith/weather/cloud_weather.h"
#include "zenith/weather/metar_file.h"

namespace zenith::weather {

inline constexpr int kBlendSteps = 128;                // coverage moves < 1 % per step
inline constexpr double kStationTransition = 20000.0;  // m of distance difference
inline constexpr double kLongGap = 3.0 * 3600.0;       // s
inline constexpr std::size_t kMaxTimelineStations = 4096;
inline constexpr double kEarthRadius = 6371008.8;  // m, the IUGG mean radius
inline constexpr std::size_t kMaxTimelineNotes = 12;

// Great-circle distance, metres (haversine on a sphere of kEarthRadius).
double GreatCircleDistance(double lat1_deg, double lon1_deg, double lat2_deg, double lon2_deg);

// The POSIX time of a report's day/hour/minute in the month before, of or after the months of
// `flight_start_s` and `flight_end_s`, closest to [flight_start_s, flight_end_s]; nullopt when
// the day exists in none of those months.
std::optional<double> ResolveReportTime(const ReportTime& time, double flight_start_s,
                                        double flight_end_s);

// u rounded to the nearest multiple of 1 / kBlendSteps, in [0, 1].
double QuantiseBlend(double u);

// The weather a share u in [0, 1] of the way from `a` to `b` (u = 0: exactly a; u = 1: exactly
// b):
//   - visibility: log-linear, V = Va^(1-u) Vb^u (the extinction coefficient geometric); a report
//     without visibility (10 km or more) counts as `clear_visibility_m` (the preset's own air:
//     ln 20 / GroundExtinctionGreen), and a blend within 0.5 % of it is "none";
//   - fog (the air set for >= 1 km under a fog layer): a's or b's for u in (0, 1);
//   - layers: fog layers (name "fog") are matched with each other, the other layers by order
//     from the lowest; a matched pair blends base, top, coverage, cloud type and precipitation
//     linearly and takes the map (kind, seed, size, period) and name of the nearer report
//     (u < 0.5: a); a layer without a partner fades, its coverage times (1 - u) (a's) or u (b's),
//     and goes at coverage 0. Overlaps are cut at the next base; a layer left thinner than 50 m
//     goes (the one of the two with less coverage).
// The result is validated (sky::clouds::Validate).
MetarWeather BlendMetarWeather(const MetarWeather& a, const MetarWeather& b, double u,
                               double clear_visibility_m);

struct TimelineOptions {
    // The stations' elevation above mean sea level for heights in the reports; nullopt: the
    // ground zenith draws under them (0 m), as `zenith render` does.
    std::optional<double> station_elevation_m;
    double clear_visibility_m = 1e5;  // see BlendMetarWeather
};

struct TimelineStation {
    std::string name;
    std::optional<double> lat_deg, lon_deg;
    std::vector<std::size_t> reports;  // indices into MetarFile::records, by time
    std::vector<double> times_s;
};

struct LayerWind {
    double speed_m_s = 0.0;
    double from_rad = 0.0;  // meteorological, as CloudLayer::wind_from
    bool operator==(const LayerWind&) const = default;
};

struct TimelineSample {
    MetarWeather weather;
    std::string description;  // "LFMX 14 12:00 -> 12:30 u 0.5" (what was blended)
};

class MetarTimeline {
  public:
    // Throws MetarError naming the file (and line) when no report has a usable time, or there are
    // more than kMaxTimelineStations stations.
    MetarTimeline(MetarFile file, const TimelineOptions& options, double flight_start_s,
                  double flight_end_s);

    // The weather at time_s (POSIX) at the aircraft's position; every layer gets `wind` when
    // given (see the file comment). Depends only on its arguments.
    TimelineSample At(double time_s, double lat_deg, double lon_deg,
                      const std::optional<LayerWind>& wind = std::nullopt) const;
    // The reported surface wind (as CloudWeatherFromMetar gives the layers) of the nearest
    // station's report nearest in time; calm when the report has none.
    LayerWind WindAt(double time_s, double lat_deg, double lon_deg) const;
    // The air for altimetry (altimetry.h) at time_s at the aircraft's position: QNH and
    // temperature each linear in time between the station's reports that give them (held
    // before the first and after the last; ISA's QNH and no temperature at a station that never
    // gives them), the nearest station blended with the second as At blends the weather, at
    // TimelineOptions::station_elevation_m (0 m without it).
    StationAir AirAt(double time_s, double lat_deg, double lon_deg) const;

    const std::vector<TimelineStation>& stations() const { return stations_; }
    const std::vector<std::string>& notes() const { return notes_; }
    const MetarFile& file() const { return file_; }

  private:
    std::pair<std::size_t, std::optional<std::size_t>> Nearest(double lat_deg, double lon_deg,
                                                               double* d_nearest,
                                                               double* d_second) const;
    MetarWeather StationWeather(const TimelineStation& s, double time_s,
                                std::string* description) const;
    StationAir StationAirAt(const TimelineStation& s, double time_s) const;
    MetarFile file_;
    TimelineOptions options_;
    std::vector<TimelineStation> stations_;
    std::vector<std::string> notes_;
};

}  // namespace zenith::weather
