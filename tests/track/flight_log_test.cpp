// Flight-log readers: the sample flights in data/flights, and malformed logs given inline, whose
// messages must name the line.
#include "zenith/track/flight_log.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

namespace zenith::track {
namespace {

const std::string kFlights = std::string(ZENITH_SOURCE_DIR) + "/data/flights/";
constexpr double kRadPerDeg = std::numbers::pi / 180.0;

double Iso(const char* text) { return geo::UnixSecondsFromCivil(geo::ParseIso8601(text)); }

bool AnySkippedContains(const FlightLog& log, const std::string& text) {
    return std::any_of(
        log.summary.first_skipped.begin(), log.summary.first_skipped.end(),
        [&](const SkippedRecord& s) { return s.reason.find(text) != std::string::npos; });
}

bool AnyNoteContains(const FlightLog& log, const std::string& text) {
    return std::any_of(log.summary.notes.begin(), log.summary.notes.end(),
                       [&](const std::string& n) { return n.find(text) != std::string::npos; });
}

std::string ThrownMessage(auto&& f) {
    try {
        f();
    } catch (const FlightLogError& e) {
        return e.what();
    }
    return "(nothing thrown)";
}

// --- sample flights ---------------------------------------------------------------------------

TEST(SampleFlights, GliderIgc) {
    const FlightLog log = ReadFlightLog(kFlights + "glider_sisteron.igc");
    EXPECT_EQ(log.format, LogFormat::kIgc);
    EXPECT_EQ(log.summary.skipped, 0) << log.summary.ToString();
    EXPECT_EQ(log.samples.size(), 1800u);
    EXPECT_DOUBLE_EQ(log.samples.front().time_s, Iso("2024-07-14T12:00:01Z"));
    EXPECT_DOUBLE_EQ(log.samples.back().time_s, Iso("2024-07-14T12:30:00Z"));
    EXPECT_NE(log.description.find("ASK 21"), std::string::npos);
    // Both altitudes, kept apart: pressure is 58 m below GNSS (QNH 1020 hPa) give or take noise.
    const auto kinds = log.AltitudeKinds();
    ASSERT_EQ(kinds.size(), 2u);
    EXPECT_EQ(kinds[0], AltitudeKind::kPressure);
    EXPECT_EQ(kinds[1], AltitudeKind::kMsl);
    const FlightSample& s = log.samples.front();
    EXPECT_NEAR(*s.msl_altitude - *s.pressure_altitude, 58.0, 5.0);
    EXPECT_FALSE(s.ellipsoid_height);
    EXPECT_FALSE(log.HasAttitude());
    EXPECT_NEAR(s.lat_deg, 44.0 + 18.018 / 60.0, 1e-9);
    EXPECT_NEAR(s.lon_deg, 5.0 + 57.011 / 60.0, 1e-9);
}

TEST(SampleFlights, AirlinerGpxCrossesAntimeridian) {
    const FlightLog log = ReadFlightLog(kFlights + "airliner_nadi_climb.gpx");
    EXPECT_EQ(log.format, LogFormat::kGpx);
    EXPECT_EQ(log.summary.skipped, 0) << log.summary.ToString();
    EXPECT_EQ(log.samples.size(), 526u);
    EXPECT_EQ(log.AltitudeKinds(), std::vector<AltitudeKind>{AltitudeKind::kMsl});
    const double top =
        std::max_element(log.samples.begin(), log.samples.end(), [](const auto& a, const auto& b) {
            return *a.msl_altitude < *b.msl_altitude;
        })->msl_altitude.value();
    EXPECT_NEAR(top, 11909.0, 5.0);  // FL390 on an ISA day, geometric
    EXPECT_TRUE(AnyNoteContains(log, "180 deg meridian")) << log.summary.ToString();
    EXPECT_GT(log.samples.front().lon_deg, 177.0);
    EXPECT_LT(log.samples.back().lon_deg, -178.5);
}

TEST(SampleFlights, SunsetApproachKmlHasAttitude) {
    const FlightLog log = ReadFlightLog(kFlights + "sunset_approach_sfo.kml");
    EXPECT_EQ(log.format, LogFormat::kKml);
    EXPECT_EQ(log.summary.skipped, 0) << log.summary.ToString();
    EXPECT_TRUE(log.HasAttitude());
    EXPECT_EQ(log.AltitudeKinds(), std::vector<AltitudeKind>{AltitudeKind::kMsl});
    EXPECT_DOUBLE_EQ(log.samples.back().time_s, Iso("2024-06-22T03:30:00Z"));
    const geo::Attitude& a = *log.samples.back().attitude;
    EXPECT_NEAR(a.heading_rad, 298.0 * kRadPerDeg, 1e-9);
    EXPECT_NEAR(a.roll_rad, 0.0, 1e-9);
    // The base turn banks right.
    const double max_roll =
        std::max_element(log.samples.begin(), log.samples.end(), [](const auto& x, const auto& y) {
            return x.attitude->roll_rad < y.attitude->roll_rad;
        })->attitude->roll_rad;
    EXPECT_NEAR(max_roll, std::atan(80.0 * 3.0 * kRadPerDeg / 9.80665), 1e-3);
}

TEST(SampleFlights, BalloonCsvTo35Km) {
    const FlightLog log = ReadFlightLog(kFlights + "balloon_esrange.csv");
    EXPECT_EQ(log.format, LogFormat::kCsv);
    EXPECT_EQ(log.summary.skipped, 0) << log.summary.ToString();
    EXPECT_TRUE(log.HasAttitude());
    const auto kinds = log.AltitudeKinds();
    ASSERT_EQ(kinds.size(), 2u);
    EXPECT_EQ(kinds[0], AltitudeKind::kPressure);
    EXPECT_EQ(kinds[1], AltitudeKind::kEllipsoid);
    EXPECT_NEAR(*log.samples.back().ellipsoid_height, 35025.0, 10.0);
    EXPECT_LT(*log.samples.back().pressure_altitude, *log.samples.back().ellipsoid_height - 500.0);
}

// --- IGC --------------------------------------------------------------------------------------

constexpr const char* kIgcHeader =
    "AXXX001\n"
    "HFDTE140724\n"
    "HFALGALTGPS:GEO\n";

TEST(IgcReader, ReadsBRecordFields) {
    const FlightLog log = ParseIgc(std::string(kIgcHeader) +
                                       "B1200004418018N00557011EA0174101800\n"
                                       "B1200014418018S00557011WA-001201800\n",
                                   "t.igc");
    ASSERT_EQ(log.samples.size(), 2u);
    EXPECT_DOUBLE_EQ(log.samples[0].time_s, Iso("2024-07-14T12:00:00Z"));
    EXPECT_EQ(*log.samples[0].pressure_altitude, 1741.0);
    EXPECT_EQ(*log.samples[0].msl_altitude, 1800.0);
    EXPECT_LT(log.samples[1].lat_deg, 0.0);
    EXPECT_LT(log.samples[1].lon_deg, 0.0);
    EXPECT_EQ(*log.samples[1].pressure_altitude, -12.0);
    EXPECT_EQ(log.samples[1].line, 5);
}

TEST(IgcReader, BothDateFormsAndEllipsoidDatum) {
    const std::string b =
        "B2359594418018N00557011EA0174101800\n"
        "B0000014418018N00557011EA0174101800\n";
    const FlightLog a = ParseIgc("HFDTEDATE:311224,02\nHFALGALTGPS:ELL\n" + b);
    ASSERT_EQ(a.samples.size(), 2u);
    EXPECT_DOUBLE_EQ(a.samples[0].time_s, Iso("2024-12-31T23:59:59Z"));
    // Past midnight UTC the date moves on.
    EXPECT_DOUBLE_EQ(a.samples[1].time_s, Iso("2025-01-01T00:00:01Z"));
    EXPECT_TRUE(a.samples[0].ellipsoid_height);
    EXPECT_FALSE(a.samples[0].msl_altitude);
    const FlightLog old = ParseIgc("HFDTE311224\n" + b);
    EXPECT_DOUBLE_EQ(old.samples[0].time_s, a.samples[0].time_s);
}

TEST(IgcReader, NoDateIsAnErrorThatSaysWhat) {
    const std::string msg = ThrownMessage(
        [] { ParseIgc("AXXX\nB1200004418018N00557011EA0174101800\n", "nodate.igc"); });
    EXPECT_NE(msg.find("nodate.igc"), std::string::npos) << msg;
    EXPECT_NE(msg.find("HFDTE"), std::string::npos) << msg;
}

TEST(IgcReader, BadRecordsAreSkippedWithLineNumbers) {
    const std::string text = std::string(kIgcHeader) +
                             "B1200004418018N00557011EA0174101800\n"   // 4 ok
                             "B1200014418018N00557011EA01741\n"        // 5 truncated
                             "B1200024461018N00557011EA0174101800\n"   // 6 minutes >= 60
                             "B1200034418018N00557011XA0174101800\n"   // 7 bad E/W
                             "B1200044418018N00557011EX0174101800\n"   // 8 bad validity
                             "B1200054418018N00557011EA01741018x0\n"   // 9 bad altitude
                             "B1200054418018N00557011EA0174101800\n"   // 10 ok
                             "B1200054418018N00557011EA0174101800\n"   // 11 duplicate time
                             "B1159594418018N00557011EA0174101800\n"   // 12 backwards
                             "B12006x4418018N00557011EA0174101800\n"   // 13 bad time
                             "B1200064418018N00557011EV0174101800\n"   // 14 V fix: no GNSS alt
                             "\x01garbage\n"                           // 15 not a record
                             "B1200074418018N00557011EA0174101800\n";  // 16 ok
    const FlightLog log = ParseIgc(text, "bad.igc");
    EXPECT_EQ(log.samples.size(), 4u) << log.summary.ToString();
    EXPECT_EQ(log.summary.skipped, 9);
    EXPECT_EQ(log.summary.records, 13);
    EXPECT_EQ(log.summary.used, 4);
    EXPECT_TRUE(AnySkippedContains(log, "bad.igc:5: B record truncated"));
    EXPECT_TRUE(AnySkippedContains(log, "bad.igc:6: bad latitude"));
    EXPECT_TRUE(AnySkippedContains(log, "bad.igc:7: bad longitude"));
    EXPECT_TRUE(AnySkippedContains(log, "bad.igc:8: bad fix validity"));
    // Only the first kMaxListed reasons are kept; the count says how many there were.
    EXPECT_EQ(log.summary.first_skipped.size(), ReadSummary::kMaxListed);
    EXPECT_FALSE(log.samples[2].msl_altitude);  // the V fix
    EXPECT_TRUE(log.samples[2].pressure_altitude);
    EXPECT_TRUE(AnyNoteContains(log, "flagged V"));
    const std::string summary = log.summary.ToString();
    EXPECT_NE(summary.find("used 4 of 13 records; skipped 9"), std::string::npos) << summary;
    EXPECT_NE(summary.find("and 1 more skipped"), std::string::npos) << summary;
}

TEST(IgcReader, DuplicateAndBackwardTimesNameTheLine) {
    const std::string text = std::string(kIgcHeader) +
                             "B1200004418018N00557011EA0174101800\n"   // 4
                             "B1200004418018N00557011EA0174101800\n"   // 5 duplicate
                             "B1159594418018N00557011EA0174101800\n"   // 6 backwards
                             "B1200014418018N00557011EA0174101800\n";  // 7
    const FlightLog log = ParseIgc(text, "t.igc");
    EXPECT_EQ(log.samples.size(), 2u);
    EXPECT_TRUE(AnySkippedContains(
        log, "t.igc:5: duplicate time 12:00:00.000 (also at line 4; the first is kept)"))
        << log.summary.ToString();
    EXPECT_TRUE(AnySkippedContains(log, "t.igc:6: time goes backwards")) << log.summary.ToString();
}

TEST(IgcReader, ATimeSpikeDropsOnlyItself) {
    const std::string text = std::string(kIgcHeader) +
                             "B1200004418018N00557011EA0174101800\n"   // 4
                             "B1300004418018N00557011EA0174101800\n"   // 5 spike
                             "B1200014418018N00557011EA0174101800\n"   // 6
                             "B1200024418018N00557011EA0174101800\n";  // 7
    const FlightLog log = ParseIgc(text, "t.igc");
    EXPECT_EQ(log.samples.size(), 3u) << log.summary.ToString();
    EXPECT_TRUE(AnySkippedContains(log, "t.igc:5: time jumps ahead")) << log.summary.ToString();
}

TEST(IgcReader, IRecordExtensionsAndGapNotes) {
    const std::string text = std::string(kIgcHeader) + "I023638FXA3940SIU\n" +
                             "B120000441801 8N00557011EA0174101800\n"  // 5: space in latitude
                             "B1200014418018N00557011EA017410180000311\n"
                             "B1200024418018N00557011EA017410180000311\n"
                             "B1200034418018N00557011EA0174101800003\n"     // short extension
                             "B1210004418018N00557011EA017410180000311\n";  // 9: 10-minute gap
    const FlightLog log = ParseIgc(text, "t.igc");
    EXPECT_EQ(log.samples.size(), 4u);
    EXPECT_TRUE(AnySkippedContains(log, "t.igc:5: bad latitude"));
    EXPECT_TRUE(AnyNoteContains(log, "shorter than the I record")) << log.summary.ToString();
    EXPECT_TRUE(AnyNoteContains(log, "t.igc:9: gap of 597 s")) << log.summary.ToString();
}

TEST(IgcReader, NothingUsableThrows) {
    const std::string msg =
        ThrownMessage([] { ParseIgc(std::string(kIgcHeader) + "B12000044\n", "short.igc"); });
    EXPECT_NE(msg.find("short.igc: no usable IGC record"), std::string::npos) << msg;
    EXPECT_NE(msg.find("short.igc:4: B record truncated"), std::string::npos) << msg;
}

// --- GPX --------------------------------------------------------------------------------------

constexpr const char* kGpx = R"(<?xml version="1.0"?>
<gpx version="1.1" creator="t" xmlns="http://www.topografix.com/GPX/1/1">
 <trk><name>T</name><trkseg>
  <trkpt lat="10.0" lon="179.999"><ele>100</ele><time>2024-01-01T00:00:00Z</time></trkpt>
  <trkpt lat="10.0" lon="-179.999"><ele>110</ele><time>2024-01-01T00:00:01Z</time></trkpt>
  <trkpt lat="95.0" lon="0"><ele>110</ele><time>2024-01-01T00:00:02Z</time></trkpt>
  <trkpt lat="10.0" lon="-179.998"><ele>x</ele><time>2024-01-01T00:00:03Z</time></trkpt>
  <trkpt lat="10.0" lon="-179.997"><ele>120</ele></trkpt>
  <trkpt lat="10.0" lon="-179.996"><time>2024-13-01T00:00:05Z</time></trkpt>
  <trkpt lat="10.0" lon="-179.995"><time>2024-01-01T00:00:06+01:00</time></trkpt>
  <trkpt lat="10.0" lon="-179.994"><time>2024-01-01T00:00:07Z</time></trkpt>
 </trkseg></trk>
</gpx>
)";

TEST(GpxReader, ReadsTrackPointsAndSkipsBadOnes) {
    const FlightLog log = ParseGpx(kGpx, "t.gpx");
    ASSERT_EQ(log.samples.size(), 3u) << log.summary.ToString();
    EXPECT_EQ(log.description, "T");
    EXPECT_EQ(*log.samples[0].msl_altitude, 100.0);
    EXPECT_EQ(log.samples[0].line, 4);
    EXPECT_FALSE(log.samples[2].msl_altitude);  // no <ele>: kept, without altitude
    EXPECT_EQ(log.summary.records, 8);
    EXPECT_TRUE(AnySkippedContains(log, "t.gpx:6: position out of range"))
        << log.summary.ToString();
    EXPECT_TRUE(AnySkippedContains(log, "t.gpx:7: bad <ele>"));
    EXPECT_TRUE(AnySkippedContains(log, "t.gpx:8: trkpt without <time>"));
    EXPECT_TRUE(AnySkippedContains(log, "t.gpx:9: bad <time>"));
    // 00:00:06+01:00 is 23:00:06 the day before: backwards.
    EXPECT_TRUE(AnySkippedContains(log, "t.gpx:10: time goes backwards"));
    EXPECT_TRUE(AnyNoteContains(log, "t.gpx:5: track crosses the 180 deg meridian"));
}

TEST(GpxReader, TruncatedFileIsReadUpToTheLastCompletePoint) {
    const std::string full = kGpx;
    const std::string cut = full.substr(0, full.find("<trkpt lat=\"95.0\"") + 30);
    const FlightLog log = ParseGpx(cut, "cut.gpx");
    EXPECT_EQ(log.samples.size(), 2u) << log.summary.ToString();
    ASSERT_FALSE(log.summary.first_skipped.empty());
    EXPECT_NE(log.summary.first_skipped[0].reason.find("cut.gpx:6: XML not well-formed"),
              std::string::npos)
        << log.summary.ToString();
    EXPECT_NE(log.summary.first_skipped[0].reason.find("read up to line 5"), std::string::npos);
}

TEST(GpxReader, NotGpxThrows) {
    EXPECT_NE(ThrownMessage([] { ParseGpx("<kml/>", "x.gpx"); }).find("not a GPX document"),
              std::string::npos);
    EXPECT_NE(ThrownMessage([] { ParseGpx("<gpx><trk>", "x.gpx"); }).find("x.gpx:1: XML"),
              std::string::npos);
}

// --- KML --------------------------------------------------------------------------------------

constexpr const char* kKml = R"(<?xml version="1.0" encoding="UTF-8"?>
<kml xmlns="http://www.opengis.net/kml/2.2" xmlns:gx="http://www.google.com/kml/ext/2.2">
<Document><Placemark><name>K</name>
<gx:Track>
  <altitudeMode>absolute</altitudeMode>
  <when>2024-06-22T03:00:00Z</when>
  <when>2024-06-22T03:00:01Z</when>
  <when>2024-06-22T03:00:02Z</when>
  <when>2024-06-22T03:00:03Z</when>
  <gx:coord>-122.0 37.0 1000</gx:coord>
  <gx:coord>-122.001 37.0 1001</gx:coord>
  <gx:coord>-122.002 nope 1002</gx:coord>
  <gx:coord>-122.003 37.0 1003</gx:coord>
  <gx:angles>270 2 -10</gx:angles>
  <gx:angles>270 2</gx:angles>
  <gx:angles>270 2 -10</gx:angles>
  <gx:angles>271 2 -10</gx:angles>
</gx:Track>
</Placemark></Document></kml>
)";

TEST(KmlReader, ReadsWhenCoordAngles) {
    const FlightLog log = ParseKml(kKml, "t.kml");
    ASSERT_EQ(log.samples.size(), 2u) << log.summary.ToString();
    EXPECT_EQ(log.description, "K");
    EXPECT_EQ(*log.samples[0].msl_altitude, 1000.0);
    EXPECT_NEAR(log.samples[0].attitude->heading_rad, 270.0 * kRadPerDeg, 1e-12);
    EXPECT_NEAR(log.samples[0].attitude->pitch_rad, 2.0 * kRadPerDeg, 1e-12);
    EXPECT_NEAR(log.samples[0].attitude->roll_rad, -10.0 * kRadPerDeg, 1e-12);
    EXPECT_EQ(log.samples[1].line, 13);
    EXPECT_TRUE(AnySkippedContains(log, "t.kml:12: bad <gx:coord>")) << log.summary.ToString();
    EXPECT_TRUE(AnySkippedContains(log, "t.kml:15: bad <gx:angles>")) << log.summary.ToString();
}

TEST(KmlReader, UnpairedWhenAndRelativeAltitudes) {
    std::string text = kKml;
    text.replace(text.find("absolute"), 8, "relativeToGround");
    text.insert(text.find("  <gx:coord>"), "  <when>2024-06-22T03:00:04Z</when>\n");
    const FlightLog log = ParseKml(text, "t.kml");
    EXPECT_TRUE(AnySkippedContains(log, "t.kml:10: <when> #5 has no matching <gx:coord>"))
        << log.summary.ToString();
    // Above terrain zenith does not know: taken as above sea level, and said so.
    EXPECT_TRUE(AnyNoteContains(log, "relativeToGround (given by the gx:Track)"));
    EXPECT_TRUE(AnyNoteContains(log, "taken as above sea level"));
    EXPECT_EQ(log.samples[0].msl_altitude, 1000.0);
}

TEST(KmlReader, TruncatedFileKeepsCompleteSamples) {
    const std::string full = kKml;
    const std::string cut = full.substr(0, full.find("<gx:angles>"));
    const FlightLog log = ParseKml(cut, "cut.kml");
    EXPECT_EQ(log.samples.size(), 3u) << log.summary.ToString();
    EXPECT_FALSE(log.HasAttitude());
    EXPECT_TRUE(AnySkippedContains(log, "XML not well-formed")) << log.summary.ToString();
}

TEST(KmlReader, NoTrackThrows) {
    const std::string msg = ThrownMessage([] {
        ParseKml("<kml><Document><Placemark><LineString/></Placemark></Document></kml>", "l.kml");
    });
    EXPECT_NE(msg.find("l.kml: no gx:Track"), std::string::npos) << msg;
}

// --- CSV --------------------------------------------------------------------------------------

TEST(CsvReader, IsoAndUnixTimesUnitsAndAttitude) {
    const FlightLog log = ParseCsv(
        "# comment\n"
        "time,lat_deg,lon_deg,alt_msl_ft,alt_pressure_ft,alt_wgs84_m,heading_deg,pitch_deg,"
        "roll_deg,note\n"
        "2024-06-22T03:00:00Z,37,-122,1000,900,320.5,90,1,2,a\n"
        "1719025201,37,-122.001,1010,910,,90,1,2,\"b, quoted\"\n",
        "t.csv");
    ASSERT_EQ(log.samples.size(), 2u) << log.summary.ToString();
    EXPECT_DOUBLE_EQ(log.samples[1].time_s - log.samples[0].time_s, 1.0);
    EXPECT_DOUBLE_EQ(*log.samples[0].msl_altitude, 304.8);
    EXPECT_DOUBLE_EQ(*log.samples[0].pressure_altitude, 900 * 0.3048);
    EXPECT_DOUBLE_EQ(*log.samples[0].ellipsoid_height, 320.5);
    EXPECT_FALSE(log.samples[1].ellipsoid_height);
    EXPECT_NEAR(log.samples[0].attitude->heading_rad, std::numbers::pi / 2, 1e-12);
    EXPECT_EQ(log.samples[0].line, 3);
    EXPECT_TRUE(AnyNoteContains(log, "columns not used: note"));
}

TEST(CsvReader, OpenSkyStateVectors) {
    const FlightLog log = ParseCsv(
        "time,icao24,lat,lon,velocity,heading,vertrate,callsign,onground,alert,spi,squawk,"
        "baroaltitude,geoaltitude,lastposupdate,lastcontact\n"
        "1719025200,4b1805,47.1,8.5,200.5,45.0,5.2,SWR123,False,False,False,1000,10000.0,"
        "10250.0,1719025199.9,1719025200.1\n"
        "1719025210,4b1805,,,200.5,45.0,5.2,SWR123,False,False,False,1000,10050.0,"
        "10300.0,1719025209.9,1719025210.1\n"
        "1719025220,4b1805,47.12,8.52,200.5,45.0,5.2,SWR123,False,False,False,1000,10100.0,"
        "10350.0,1719025219.9,1719025220.1\n",
        "opensky.csv");
    ASSERT_EQ(log.samples.size(), 2u);
    EXPECT_EQ(*log.samples[0].pressure_altitude, 10000.0);
    EXPECT_EQ(*log.samples[0].ellipsoid_height, 10250.0);
    EXPECT_FALSE(log.samples[0].attitude);
    EXPECT_TRUE(AnySkippedContains(log, "opensky.csv:3: no position"));
    EXPECT_TRUE(AnyNoteContains(log, "'heading' (OpenSky"));
}

TEST(CsvReader, BadRowsNameTheirLines) {
    const FlightLog log = ParseCsv(
        "time,lat,lon,alt_msl_m\n"
        "2024-06-22T03:00:00Z,89.9999,0,100\n"      // 2 ok, near the pole: note
        "2024-06-22T03:00:01Z,89.9999,180\n"        // 3 truncated
        "2024-06-22T03:00:02Z,89.9999,180,1e400\n"  // 4 not finite
        "2024-06-22T03:00:03Z,89.9999,180,12,13\n"  // 5 too many fields
        "2024-06-22T03:00:04Z,-91,180,12\n"         // 6 out of range
        "2024-06-22T03:00:05Z,89.9999,180,12\n"     // 7 ok, lon 180 -> -180
        "2024-06-22T03:00:06Z,\"89.9999,180,12\n"   // 8 open quote
        "yesterday,89.9999,180,12\n",               // 9 bad time
        "b.csv");
    EXPECT_EQ(log.samples.size(), 2u) << log.summary.ToString();
    EXPECT_EQ(log.samples[1].lon_deg, -180.0);
    EXPECT_TRUE(AnySkippedContains(log, "b.csv:3: 3 fields for 4 columns (truncated row?)"));
    EXPECT_TRUE(AnySkippedContains(log, "b.csv:4: bad alt_msl_m"));
    EXPECT_TRUE(AnySkippedContains(log, "b.csv:5: 5 fields for 4 columns"));
    EXPECT_TRUE(AnySkippedContains(log, "b.csv:6: position out of range"));
    EXPECT_TRUE(AnySkippedContains(log, "b.csv:8: unclosed quote"));
    EXPECT_TRUE(AnySkippedContains(log, "b.csv:9: bad time 'yesterday'"));
    EXPECT_TRUE(AnyNoteContains(log, "b.csv:2: fix at the pole"));
}

TEST(CsvReader, HeaderErrorsThrow) {
    EXPECT_NE(ThrownMessage([] {
                  ParseCsv("time,lat,lon,alt\n", "h.csv");
              }).find("h.csv:1: altitude column 'alt' does not say its datum and unit"),
              std::string::npos);
    EXPECT_NE(ThrownMessage([] {
                  ParseCsv("time,lat,alt_msl_m\n", "h.csv");
              }).find("header needs columns time, lat and lon"),
              std::string::npos);
    EXPECT_NE(ThrownMessage([] {
                  ParseCsv("time,lat,lon,heading_deg\n", "h.csv");
              }).find("attitude needs all three"),
              std::string::npos);
    EXPECT_NE(ThrownMessage([] { ReadFlightLog("/nonexistent/flight.igc"); }).find("cannot open"),
              std::string::npos);
    EXPECT_NE(ThrownMessage([] { ReadFlightLog("flight.txt"); }).find("unknown flight-log"),
              std::string::npos);
}

// --- what a careful user and the fuzzers found (issue 13) --------------------------------------
namespace robustness {

// A minimal IGC with n B records a second apart from 12:00:00, at 45 N 6 E, GNSS and pressure
// altitude 1000 m ('A' fixes).
std::string IgcWithFixes(int n, const std::string& line_end = "\n") {
    std::string text = "AXXX001" + line_end + "HFDTE010624" + line_end;
    for (int i = 0; i < n; ++i) {
        text +=
            fmt::format("B12{:02}{:02}4500000N00600000EA0100001000{}", i / 60, i % 60, line_end);
    }
    return text;
}

TEST(ReaderLimits, OutOfRangeTimesAndAltitudesAreSkippedWithTheirLine) {
    const std::string csv =
        "time,lat,lon,alt_msl_m\n"
        "1719025200,45,6,1000\n"
        "1719025201,45,6,1000\n"
        "1e18,45,6,1000\n"        // line 4: the year 3e10
        "-1e12,45,6,1000\n"       // line 5: 30,000 years ago
        "1719025202,45,6,1e12\n"  // line 6
        "1719025203,45,6,-7e6\n"  // line 7
        "1719025204,45,6,1000\n";
    const FlightLog log = ParseCsv(csv, "big.csv");
    EXPECT_EQ(log.samples.size(), 3u) << log.summary.ToString();
    EXPECT_TRUE(AnySkippedContains(log, "big.csv:4: time 1e+18 s since 1970 is out of range"))
        << log.summary.ToString();
    EXPECT_TRUE(AnySkippedContains(log, "big.csv:5: time -1000000000000 s"));
    EXPECT_TRUE(
        AnySkippedContains(log,
                           "big.csv:6: height above mean sea level (geoid) 1000000000000 m is "
                           "out of range (expected [-1000, 200000] m)"))
        << log.summary.ToString();
    EXPECT_TRUE(
        AnySkippedContains(log, "big.csv:7: height above mean sea level (geoid) -7000000 m"));
}

TEST(ReaderLimits, AColdStartFixYearsBeforeTheFlightIsDroppedAsIsolated) {
    const std::string csv =
        "time,lat,lon,alt_msl_m\n"
        "1980-01-06T00:00:00Z,45,6,1000\n"  // line 2: GPS epoch, a receiver's default
        "2024-06-22T03:00:00Z,45,6,1000\n"
        "2024-06-22T03:00:01Z,45,6.0001,1000\n"
        "2024-06-22T03:00:02Z,45,6.0002,1000\n"
        "2024-06-22T03:00:03Z,45,6.0003,1000\n";
    const FlightLog log = ParseCsv(csv, "cold.csv");
    ASSERT_EQ(log.samples.size(), 4u) << log.summary.ToString();
    EXPECT_EQ(log.samples.front().line, 3);
    EXPECT_TRUE(AnySkippedContains(log, "cold.csv:2: fix at 1980-01-06 00:00:00 is isolated"))
        << log.summary.ToString();
}

TEST(ReaderLimits, ALogLongerThanTheLimitIsRefusedNamingItsEnds) {
    std::string csv = "time,lat,lon,alt_msl_m\n";
    // Fixes every 12 h for 410 days: no isolated fix, but longer than kMaxLogSpan.
    for (int i = 0; i <= 820; ++i) {
        csv += fmt::format("{},45,6,1000\n", 1.6e9 + i * 43200.0);
    }
    const std::string message = ThrownMessage([&] { ParseCsv(csv, "long.csv"); });
    EXPECT_NE(message.find("long.csv: the log spans 410 days (line 2 at"), std::string::npos)
        << message;
    EXPECT_NE(message.find("at most 400 days"), std::string::npos) << message;
}

TEST(ReaderLimits, EmptyCoordinatesAreSkippedNotRead) {
    const std::string gpx = R"(<gpx><trk><trkseg>
<trkpt lat="" lon=" "><time>2024-06-22T03:00:00Z</time></trkpt>
<trkpt lat="45" lon="6"><ele>100</ele><time>2024-06-22T03:00:01Z</time></trkpt>
</trkseg></trk></gpx>)";
    const FlightLog log = ParseGpx(gpx, "e.gpx");
    ASSERT_EQ(log.samples.size(), 1u);
    EXPECT_TRUE(AnySkippedContains(log, "e.gpx:2: trkpt with an empty lat or lon attribute"))
        << log.summary.ToString();
}

constexpr const char* kMultiTrack = R"(<?xml version="1.0" encoding="UTF-8"?>
<kml xmlns="http://www.opengis.net/kml/2.2" xmlns:gx="http://www.google.com/kml/ext/2.2">
<Document><Placemark><gx:MultiTrack>
MODE
<gx:Track>
  <when>2024-06-22T03:00:00Z</when><when>2024-06-22T03:00:01Z</when>
  <gx:coord>6.0 45.0 1500</gx:coord><gx:coord>6.0001 45.0 1501</gx:coord>
</gx:Track>
</gx:MultiTrack></Placemark></Document></kml>)";

std::string MultiTrack(const std::string& mode) {
    std::string text = kMultiTrack;
    text.replace(text.find("MODE"), 4, mode);
    return text;
}

TEST(ReaderLimits, KmlTracksInheritTheirMultiTracksAltitudeMode) {
    const FlightLog log = ParseKml(MultiTrack("<altitudeMode>absolute</altitudeMode>"), "m.kml");
    ASSERT_EQ(log.samples.size(), 2u);
    EXPECT_EQ(log.samples[1].msl_altitude, 1501.0);
    const FlightLog gx =
        ParseKml(MultiTrack("<gx:altitudeMode>absolute</gx:altitudeMode>"), "g.kml");
    EXPECT_EQ(gx.samples[0].msl_altitude, 1500.0);
}

TEST(ReaderLimits, KmlClampToGroundPutsTheTrackOnTheGroundAndSaysSo) {
    const FlightLog log = ParseKml(MultiTrack(""), "c.kml");
    ASSERT_EQ(log.samples.size(), 2u);
    EXPECT_EQ(log.samples[0].msl_altitude, 0.0);
    EXPECT_TRUE(AnyNoteContains(log,
                                "altitudeMode clampToGround (KML's default when none is "
                                "given): the track is on the terrain"))
        << log.summary.ToString();
}

constexpr const char* kTwoAircraft =
    "time,icao24,lat,lon,velocity,heading,vertrate,callsign,onground,alert,spi,squawk,"
    "baroaltitude,geoaltitude,lastposupdate,lastcontact\n"
    "1719025200,4b1805,47.0,8.0,200,90,0,SWR123  ,false,false,false,1000,3000,3050,1,1\n"
    "1719025200,3c6444,50.0,8.5,220,10,0,DLH9U   ,false,false,false,1000,9000,9050,1,1\n"
    "1719025201,4b1805,47.0,8.003,200,90,0,SWR123  ,false,false,false,1000,3000,3050,1,1\n"
    "1719025201,3c6444,50.002,8.5,220,10,0,DLH9U   ,false,false,false,1000,9000,9050,1,1\n"
    "1719025202,4b1805,47.0,8.006,200,90,0,SWR123  ,false,false,false,1000,3000,3050,1,1\n";

TEST(ReaderLimits, SeveralAircraftAreRefusedWithAListUnlessOneIsChosen) {
    const std::string message = ThrownMessage([] { ParseCsv(kTwoAircraft, "os.csv"); });
    EXPECT_NE(message.find("os.csv: 2 aircraft in one log; choose one by icao24 or callsign"),
              std::string::npos)
        << message;
    EXPECT_NE(message.find("4b1805 swr123 (3 rows), 3c6444 dlh9u (2 rows)"), std::string::npos)
        << message;

    ReadOptions by_address;
    by_address.icao24 = "4B1805";
    const FlightLog swiss = ParseCsv(kTwoAircraft, "os.csv", by_address);
    EXPECT_EQ(swiss.samples.size(), 3u);
    EXPECT_EQ(swiss.summary.records, 3);
    ReadOptions by_callsign;
    by_callsign.callsign = "dlh9u";
    const FlightLog lufthansa = ParseCsv(kTwoAircraft, "os.csv", by_callsign);
    ASSERT_EQ(lufthansa.samples.size(), 2u);
    EXPECT_EQ(lufthansa.samples[0].lat_deg, 50.0);

    ReadOptions absent;
    absent.icao24 = "abcdef";
    EXPECT_NE(ThrownMessage([&] {
                  ParseCsv(kTwoAircraft, "os.csv", absent);
              }).find("no row of icao24 abcdef"),
              std::string::npos);
}

TEST(ReaderLimits, ImpossibleJumpsAreDroppedOrBreakTheTrack) {
    // Line 4 is 563 km away for one second (spoofing); from line 7 on the track goes on 500 km
    // east and stays there.
    const std::string csv =
        "time,lat,lon,alt_msl_m\n"
        "1719025200,45,6.000,1000\n"
        "1719025201,45,6.001,1000\n"
        "1719025202,45,13.15,1000\n"
        "1719025203,45,6.003,1000\n"
        "1719025204,45,6.004,1000\n"
        "1719025205,45,12.400,1000\n"
        "1719025206,45,12.401,1000\n";
    const FlightLog log = ParseCsv(csv, "jump.csv");
    ASSERT_EQ(log.samples.size(), 6u) << log.summary.ToString();
    EXPECT_TRUE(AnySkippedContains(log, "jump.csv:4: position jumps 56")) << log.summary.ToString();
    EXPECT_TRUE(AnySkippedContains(log, "and comes back at the next fix: dropped"));
    EXPECT_TRUE(log.samples[4].discontinuity);
    EXPECT_EQ(log.samples[4].line, 7);
    EXPECT_TRUE(AnyNoteContains(log, "jump.csv:7: position jumps")) << log.summary.ToString();
}

TEST(ReaderLimits, EqualTimesKeepTheFirstFixUnderItsOwnMessage) {
    const std::string csv =
        "time,lat,lon,alt_msl_m\n"
        "1719025200,45,6.000,1000\n"
        "1719025201,45,6.001,1000\n"
        "1719025201,45,6.002,1000\n"
        "1719025202,45,6.003,1000\n";
    const FlightLog log = ParseCsv(csv, "eq.csv");
    ASSERT_EQ(log.samples.size(), 3u);
    EXPECT_EQ(log.samples[1].line, 3);
    EXPECT_TRUE(AnySkippedContains(log, "eq.csv:4: duplicate time")) << log.summary.ToString();
    EXPECT_FALSE(AnySkippedContains(log, "jumps ahead"));
}

TEST(ReaderLimits, Utf8ByteOrderMarkIsNotPartOfTheFirstColumn) {
    const FlightLog log =
        ParseCsv("\xEF\xBB\xBFtime,lat,lon,alt_msl_m\n1719025200,45,6,1000\n", "bom.csv");
    EXPECT_EQ(log.samples.size(), 1u);
}

// The GPX text as UTF-16 with a byte-order mark, as Windows tools write it.
std::string Utf16(const std::string& ascii, bool little_endian) {
    std::string out = little_endian ? "\xFF\xFE" : "\xFE\xFF";
    for (const char c : ascii) {
        out += little_endian ? std::string{c, '\0'} : std::string{'\0', c};
    }
    return out;
}

TEST(ReaderLimits, Utf16GpxIsRead) {
    const std::string gpx = R"(<?xml version="1.0" encoding="UTF-16"?>
<gpx><trk><name>W</name><trkseg>
<trkpt lat="45" lon="6"><ele>100</ele><time>2024-06-22T03:00:00Z</time></trkpt>
</trkseg></trk></gpx>)";
    for (const bool little : {true, false}) {
        const FlightLog log = ParseGpx(Utf16(gpx, little), "w.gpx");
        ASSERT_EQ(log.samples.size(), 1u) << little;
        EXPECT_EQ(log.description, "W");
        EXPECT_EQ(log.samples[0].msl_altitude, 100.0);
    }
}

TEST(ReaderLimits, XmlErrorsNameALineOrNone) {
    const std::string empty = ThrownMessage([] { ParseGpx("", "empty.gpx"); });
    EXPECT_EQ(empty, "empty.gpx: XML not well-formed: the document is empty");
    const std::string broken =
        ThrownMessage([] { ParseKml("<kml>\n<Document>\n<x></y></Document></kml>", "b.kml"); });
    EXPECT_EQ(broken.rfind("b.kml:3: XML not well-formed: ", 0), 0u) << broken;
    EXPECT_EQ(broken.find("line 0"), std::string::npos) << broken;
}

TEST(ReaderLimits, AnIgcOfOnlyVFixesSaysSo) {
    std::string text = IgcWithFixes(3);
    for (std::size_t at = text.find("EA"); at != std::string::npos; at = text.find("EA", at)) {
        text[at + 1] = 'V';
    }
    const FlightLog log = ParseIgc(text, "v.igc");
    EXPECT_TRUE(AnyNoteContains(log,
                                "all 3 fixes are flagged V (2-D or no GNSS fix): no GNSS "
                                "altitude"))
        << log.summary.ToString();
    EXPECT_FALSE(AnyNoteContains(log, "GNSS altitude is 0"));
    EXPECT_FALSE(log.samples[0].msl_altitude);
    EXPECT_EQ(log.samples[0].pressure_altitude, 1000.0);
}

TEST(ReaderLimits, CarriageReturnLineEndingsAreLineEndings) {
    for (const char* end : {"\r", "\r\n", "\n"}) {
        const FlightLog log = ParseIgc(IgcWithFixes(4, end), "cr.igc");
        EXPECT_EQ(log.samples.size(), 4u) << log.summary.ToString();
        EXPECT_EQ(log.samples[3].line, 6);
    }
}

TEST(ReaderLimits, LongLogsAreThinnedEvenly) {
    ReadOptions options;
    options.max_samples = 100;
    const FlightLog log = ParseIgc(IgcWithFixes(1000), "long.igc", options);
    // 1000 fixes, at most 100 kept: 1 in 16 (63 kept: every 16th second from 12:00:00).
    ASSERT_EQ(log.samples.size(), 63u) << log.summary.ToString();
    for (std::size_t i = 1; i < log.samples.size(); ++i) {
        EXPECT_EQ(log.samples[i].time_s - log.samples[i - 1].time_s, 16.0);
    }
    EXPECT_TRUE(AnyNoteContains(log,
                                "1000 valid fixes: 1 in 16 kept, evenly (at most 100 are "
                                "read)"))
        << log.summary.ToString();
    options.max_samples = 1;
    EXPECT_THROW(ParseIgc(IgcWithFixes(3), "x.igc", options), ArgumentError);
}

TEST(ReaderLimits, OverlongLinesAreSkipped) {
    std::string csv = "time,lat,lon\n1719025200,45,6\n";
    csv += "1719025201,45," + std::string(kMaxLineBytes, '6') + "\n";
    const FlightLog log = ParseCsv(csv, "wide.csv");
    EXPECT_EQ(log.samples.size(), 1u);
    EXPECT_TRUE(AnySkippedContains(log, "wide.csv:3: row of 65550 characters (at most 65536)"))
        << log.summary.ToString();
}

}  // namespace robustness
}  // namespace
}  // namespace zenith::track
