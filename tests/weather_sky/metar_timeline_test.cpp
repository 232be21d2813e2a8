// Weather along a replay (metar_timeline.h): report times, interpolation in time, the nearest
// station and the blend across a change of station. Pure functions, no GL.
#include "zenith/weather/metar_timeline.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "zenith/geo/time.h"

namespace zenith::weather {
namespace {

double Unix(const char* iso) { return geo::UnixSecondsFromCivil(geo::ParseIso8601(iso)); }

const double kNoon = Unix("2024-07-14T12:00:00Z");

// One station, two reports an hour apart: 2000 m and SCT035 at 12:00, 8000 m and BKN035 at 13:00.
MetarTimeline TwoReports(double flight_start_s, double flight_end_s) {
    return MetarTimeline(ParseMetarCsv("station,valid,lon,lat,metar\n"
                                       "AAA,2024-07-14 12:00,5.0,44.0,LFAA 141200Z 27005KT 2000 "
                                       "SCT035 20/10 Q1015\n"
                                       "AAA,2024-07-14 13:00,5.0,44.0,LFAA 141300Z 27005KT 8000 "
                                       "BKN035 20/10 Q1015\n",
                                       "two.csv"),
                         {}, flight_start_s, flight_end_s);
}

TEST(MetarTimeline, MidwayVisibilityIsTheGeometricMean) {
    const MetarTimeline t = TwoReports(kNoon, kNoon + 3600);
    const TimelineSample s = t.At(kNoon + 1800, 44.0, 5.0);
    ASSERT_TRUE(s.weather.visibility_m);
    // log-linear: exp((ln 2000 + ln 8000) / 2) = 4000 m.
    EXPECT_NEAR(*s.weather.visibility_m, 4000.0, 1e-6);
    EXPECT_NEAR(*s.weather.ground_extinction_per_m, std::log(20.0) / 4000.0, 1e-12);
    // A quarter of the way: 2000 * 4^0.25.
    EXPECT_NEAR(*t.At(kNoon + 900, 44.0, 5.0).weather.visibility_m, 2000.0 * std::sqrt(2.0), 1e-6);
}

TEST(MetarTimeline, MidwayCoverageIsTheMeanAndTheBaseStays) {
    const MetarTimeline t = TwoReports(kNoon, kNoon + 3600);
    const TimelineSample s = t.At(kNoon + 1800, 44.0, 5.0);
    ASSERT_EQ(s.weather.clouds.layers.size(), 1u);
    const auto layer = [&](double time_s) {
        return t.At(time_s, 44.0, 5.0).weather.clouds.layers[0];
    };
    EXPECT_NEAR(s.weather.clouds.layers[0].coverage,
                (layer(kNoon).coverage + layer(kNoon + 3600).coverage) / 2, 1e-12);
    EXPECT_NEAR(s.weather.clouds.layers[0].base_altitude,
                (layer(kNoon).base_altitude + layer(kNoon + 3600).base_altitude) / 2, 1e-9);
    EXPECT_GT(s.weather.clouds.layers[0].base_altitude, 0.9 * 3500 * 0.3048);
}

TEST(MetarTimeline, HoldsTheNearestReportOutsideTheirSpan) {
    const MetarTimeline t = TwoReports(kNoon - 7200, kNoon + 7200);
    const MetarWeather first = CloudWeatherFromMetar(t.file().records[0].metar, 0.0);
    const MetarWeather last = CloudWeatherFromMetar(t.file().records[1].metar, 0.0);
    for (const double dt : {-7200.0, -1.0, 0.0}) {
        const TimelineSample s = t.At(kNoon + dt, 44.0, 5.0);
        EXPECT_EQ(s.weather.clouds, first.clouds) << dt;
        EXPECT_EQ(s.weather.visibility_m, first.visibility_m) << dt;
    }
    for (const double dt : {3600.0, 3601.0, 7200.0}) {
        const TimelineSample s = t.At(kNoon + dt, 44.0, 5.0);
        EXPECT_EQ(s.weather.clouds, last.clouds) << dt;
        EXPECT_EQ(s.weather.visibility_m, last.visibility_m) << dt;
    }
}

TEST(MetarTimeline, LongGapsAreNoted) {
    const MetarTimeline near = TwoReports(kNoon, kNoon + 3600);
    EXPECT_TRUE(near.notes().empty()) << near.notes().front();
    const MetarTimeline far = TwoReports(kNoon - 5 * 3600, kNoon + 3600);
    ASSERT_EQ(far.notes().size(), 1u);
    EXPECT_NE(far.notes()[0].find("5.0 h before its first report"), std::string::npos)
        << far.notes()[0];
}

// Steps of 1/kBlendSteps: the coverage moves by less than 1 % between distinct weathers, and
// times within a step give the same weather (so the renderer's weather is not set again).
TEST(MetarTimeline, QuantisedStepsMoveCoverageByLessThanOnePercent) {
    const MetarTimeline t = TwoReports(kNoon, kNoon + 3600);
    double previous = t.At(kNoon, 44.0, 5.0).weather.clouds.layers[0].coverage;
    int changes = 0;
    for (int s = 1; s <= 3600; ++s) {
        const double c = t.At(kNoon + s, 44.0, 5.0).weather.clouds.layers[0].coverage;
        EXPECT_LT(std::abs(c - previous), 0.01) << s;
        if (c != previous) ++changes;
        previous = c;
    }
    EXPECT_EQ(changes, kBlendSteps);
    EXPECT_EQ(t.At(kNoon + 1800, 44.0, 5.0).weather.clouds,
              t.At(kNoon + 1801, 44.0, 5.0).weather.clouds);
}

TEST(MetarTimeline, ReportWithoutVisibilityBlendsTowardsTheClearAir) {
    TimelineOptions options;
    options.clear_visibility_m = 50000.0;
    const MetarTimeline t(ParseMetarCsv("station,valid,metar\n"
                                        "A,2024-07-14 12:00,LFAA 141200Z 27005KT 5000 BR\n"
                                        "A,2024-07-14 13:00,LFAA 141300Z 27005KT 9999 NSC\n",
                                        "clear.csv"),
                          options, kNoon, kNoon + 3600);
    EXPECT_NEAR(*t.At(kNoon + 1800, 0, 0).weather.visibility_m, std::sqrt(5000.0 * 50000.0), 1e-6);
    EXPECT_FALSE(t.At(kNoon + 3600, 0, 0).weather.visibility_m);
    EXPECT_FALSE(t.At(kNoon + 3599, 0, 0).weather.visibility_m);  // within 0.5 % of clear
}

// Different layer sets: matched by order from the bottom, the extra layer fades.
TEST(BlendMetarWeather, ExtraLayerFadesAndFogMatchesFog) {
    const MetarWeather a =
        CloudWeatherFromMetar(DecodeMetar("LFAA 141200Z 00000KT 0300 FG VV002 12/12 Q1020"), 0);
    const MetarWeather b = CloudWeatherFromMetar(
        DecodeMetar("LFAA 141300Z 00000KT 9999 FEW020 SCT100 20/10 Q1020"), 0);
    ASSERT_EQ(a.clouds.layers.size(), 1u);
    ASSERT_EQ(b.clouds.layers.size(), 2u);
    const MetarWeather m = BlendMetarWeather(a, b, 0.25, 1e5);
    // The fog (a's only) at 3/4 of its coverage; FEW020 and SCT100 (b's) at 1/4 of theirs.
    ASSERT_EQ(m.clouds.layers.size(), 3u);
    EXPECT_EQ(m.clouds.layers[0].name, "fog");
    EXPECT_NEAR(m.clouds.layers[0].coverage, 0.75, 1e-12);
    EXPECT_NEAR(m.clouds.layers[1].coverage, 0.25 * b.clouds.layers[0].coverage, 1e-12);
    EXPECT_NEAR(m.clouds.layers[2].coverage, 0.25 * b.clouds.layers[1].coverage, 1e-12);
    EXPECT_TRUE(m.fog);
    EXPECT_EQ(BlendMetarWeather(a, b, 0.0, 1e5).clouds, a.clouds);
    EXPECT_EQ(BlendMetarWeather(a, b, 1.0, 1e5).clouds, b.clouds);
    // Matched by order: FEW020 -> SCT035's base moves linearly.
    const MetarWeather c =
        CloudWeatherFromMetar(DecodeMetar("LFAA 141400Z 00000KT 9999 SCT040 20/10 Q1020"), 0);
    const MetarWeather bc = BlendMetarWeather(b, c, 0.5, 1e5);
    ASSERT_EQ(bc.clouds.layers.size(), 2u);
    EXPECT_NEAR(bc.clouds.layers[0].base_altitude,
                (b.clouds.layers[0].base_altitude + c.clouds.layers[0].base_altitude) / 2, 1e-9);
}

TEST(ResolveReportTime, PicksTheMonthClosestToTheFlight) {
    const ReportTime late{30, 23, 50};
    // A flight just after midnight on 1 July: the report of the 30th is June's.
    EXPECT_EQ(ResolveReportTime(late, Unix("2024-07-01T00:30:00Z"), Unix("2024-07-01T01:30:00Z")),
              Unix("2024-06-30T23:50:00Z"));
    // The same day.
    EXPECT_EQ(ResolveReportTime({14, 11, 50}, kNoon, kNoon + 1800), Unix("2024-07-14T11:50:00Z"));
    // Day 1 seen from a flight on 31 January: February's.
    EXPECT_EQ(
        ResolveReportTime({1, 0, 20}, Unix("2024-01-31T23:00:00Z"), Unix("2024-01-31T23:50:00Z")),
        Unix("2024-02-01T00:20:00Z"));
    // Day 31 seen from a flight in February 2024 (no 31st): January's, not March's.
    EXPECT_EQ(
        ResolveReportTime({31, 12, 0}, Unix("2024-02-10T12:00:00Z"), Unix("2024-02-10T13:00:00Z")),
        Unix("2024-01-31T12:00:00Z"));
}

TEST(MetarTimeline, LinesFileTimesFromTheReportGroup) {
    const MetarTimeline t(ParseMetarLines("LFAA 141200Z 27005KT 2000 SCT035 20/10 Q1015\n"
                                          "LFAA 141300Z 27005KT 8000 BKN035 20/10 Q1015\n",
                                          "lines.txt"),
                          {}, kNoon, kNoon + 3600);
    ASSERT_EQ(t.stations().size(), 1u);
    EXPECT_EQ(t.stations()[0].times_s[0], kNoon);
    EXPECT_EQ(t.stations()[0].times_s[1], kNoon + 3600);
    EXPECT_NEAR(*t.At(kNoon + 1800, 0, 0).weather.visibility_m, 4000.0, 1e-6);
}

TEST(MetarTimeline, NoPositionsMeansOneStation) {
    const MetarTimeline t(ParseMetarLines("LFAA 141200Z 27005KT 2000 SCT035 20/10 Q1015\n"
                                          "LFBB 141230Z 27005KT 8000 BKN035 20/10 Q1015\n",
                                          "lines.txt"),
                          {}, kNoon, kNoon + 3600);
    ASSERT_EQ(t.stations().size(), 1u);
    EXPECT_EQ(t.stations()[0].reports.size(), 2u);
    ASSERT_EQ(t.notes().size(), 2u);
    EXPECT_NE(t.notes()[1].find("one station"), std::string::npos) << t.notes()[1];
}

TEST(MetarTimeline, NoUsableTimeNamesTheFileAndLine) {
    try {
        MetarTimeline(ParseMetarLines("# header\nLFAA 27005KT 2000 SCT035 20/10 Q1015\n", "x.txt"),
                      {}, kNoon, kNoon + 60);
        FAIL() << "no error";
    } catch (const MetarError& e) {
        EXPECT_NE(std::string(e.what()).find("x.txt:2"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("usable time"), std::string::npos) << e.what();
    }
}

// Two stations on the 44th parallel, 1 degree of longitude apart: the nearest changes where
// their great-circle distances cross (the meridian half-way), and the weather there is half of
// each, so it changes in steps of at most 1/kBlendSteps of the difference.
TEST(MetarTimeline, NearestStationSwitchesWhereTheDistancesCross) {
    const MetarTimeline t(ParseMetarCsv("station,valid,lon,lat,metar\n"
                                        "W,2024-07-14 12:00,5.0,44.0,LFWW 141200Z 00000KT 1000 "
                                        "OVC010 20/10 Q1015\n"
                                        "E,2024-07-14 12:00,6.0,44.0,LFEE 141200Z 00000KT 8000 "
                                        "FEW040 20/10 Q1015\n",
                                        "two_stations.csv"),
                          {}, kNoon, kNoon + 3600);
    ASSERT_EQ(t.stations().size(), 2u);
    std::optional<double> switched_at;
    std::string previous;
    double previous_v = 0.0;
    for (int i = 0; i <= 2000; ++i) {
        const double lon = 5.0 + i * 0.0005;
        const TimelineSample s = t.At(kNoon, 44.0, lon);
        const std::string nearest = s.description.substr(0, s.description.find(' '));
        ASSERT_TRUE(s.weather.visibility_m);
        const double v = *s.weather.visibility_m;
        if (i > 0) {
            // log V moves by at most one step of ln(8000 / 1000).
            EXPECT_LE(std::abs(std::log(v / previous_v)), std::log(8.0) / kBlendSteps + 1e-9)
                << lon;
            if (nearest != previous) {
                EXPECT_FALSE(switched_at) << "switched twice";
                switched_at = lon;
            }
        }
        previous = nearest;
        previous_v = v;
    }
    ASSERT_TRUE(switched_at);
    EXPECT_NEAR(*switched_at, 5.5, 0.001);
    EXPECT_LT(GreatCircleDistance(44.0, *switched_at, 44.0, 6.0),
              GreatCircleDistance(44.0, *switched_at, 44.0, 5.0));
    // On the line: half of each; far from it: only the nearest.
    EXPECT_NEAR(*t.At(kNoon, 44.0, 5.5).weather.visibility_m, std::sqrt(1000.0 * 8000.0), 1e-6);
    EXPECT_EQ(*t.At(kNoon, 44.0, 5.3).weather.visibility_m, 1000.0);
    EXPECT_EQ(*t.At(kNoon, 44.0, 5.7).weather.visibility_m, 8000.0);
}

// The air for altimetry: QNH and temperature linear in time between the reports that give
// them (a report without QNH is skipped, not read as 1013.25), blended across stations as the
// weather is, at the stations' elevation.
TEST(MetarTimeline, AirForAltimetryFollowsTheReports) {
    TimelineOptions options;
    options.station_elevation_m = 150.0;
    const MetarTimeline t(ParseMetarCsv("station,valid,lon,lat,metar\n"
                                        "W,2024-07-14 12:00,5.0,44.0,LFWW 141200Z 00000KT 9999 "
                                        "FEW040 10/05 Q1000\n"
                                        "W,2024-07-14 12:30,5.0,44.0,LFWW 141230Z 00000KT 9999 "
                                        "FEW040 16/05\n"
                                        "W,2024-07-14 13:00,5.0,44.0,LFWW 141300Z 00000KT 9999 "
                                        "FEW040 20/05 Q1020\n"
                                        "E,2024-07-14 12:00,6.0,44.0,LFEE 141200Z 00000KT 9999 "
                                        "FEW040 Q1030\n",
                                        "air.csv"),
                          options, kNoon, kNoon + 3600);
    const StationAir quarter = t.AirAt(kNoon + 900, 44.0, 5.0);
    EXPECT_NEAR(quarter.qnh_hpa, 1005.0, 1e-9);       // 1000 -> 1020 over the hour
    EXPECT_NEAR(*quarter.temperature_c, 13.0, 1e-9);  // 10 -> 16 over half an hour
    EXPECT_DOUBLE_EQ(quarter.elevation_m, 150.0);
    EXPECT_NEAR(t.AirAt(kNoon + 2700, 44.0, 5.0).temperature_c.value(), 18.0, 1e-9);
    EXPECT_DOUBLE_EQ(t.AirAt(kNoon - 600, 44.0, 5.0).qnh_hpa, 1000.0);  // held
    // The east station gives no temperature: the west's is kept on the line between them, and
    // the pressure is half of each.
    const StationAir between = t.AirAt(kNoon, 44.0, 5.5);
    EXPECT_NEAR(between.qnh_hpa, 1015.0, 1e-6);
    EXPECT_NEAR(*between.temperature_c, 10.0, 1e-9);
    const StationAir east = t.AirAt(kNoon, 44.0, 5.9);
    EXPECT_DOUBLE_EQ(east.qnh_hpa, 1030.0);
    EXPECT_FALSE(east.temperature_c);
}

TEST(GreatCircleDistance, KnownArcs) {
    // A quarter of a meridian, and a degree of the equator.
    EXPECT_NEAR(GreatCircleDistance(0, 0, 90, 0), kEarthRadius * M_PI / 2, 1e-6);
    EXPECT_NEAR(GreatCircleDistance(0, 10, 0, 11), kEarthRadius * M_PI / 180, 1e-6);
    EXPECT_NEAR(GreatCircleDistance(10, 179.5, 10, -179.5), GreatCircleDistance(10, 0, 10, 1),
                1e-6);
}

TEST(MetarTimeline, WindIsTheNearestReportsAndOverridesEveryLayer) {
    const MetarTimeline t = TwoReports(kNoon, kNoon + 3600);
    const LayerWind w = t.WindAt(kNoon + 100, 44.0, 5.0);
    EXPECT_NEAR(w.speed_m_s, 5 * 0.514444, 1e-3);
    EXPECT_NEAR(w.from_rad, 270.0 * M_PI / 180.0, 1e-12);
    const LayerWind calm{0.0, 0.0};
    for (const auto& l : t.At(kNoon + 1800, 44.0, 5.0, calm).weather.clouds.layers) {
        EXPECT_EQ(l.wind_speed, 0.0);
    }
}

}  // namespace
}  // namespace zenith::weather
