// The simulators' UDP datagrams (zenith/track/live_packets.h) built here byte by byte from the
// published layouts (FlightGear's net_fdm.hxx version 24 in network order; X-Plane's DATA and
// RPOS, little-endian), and the clock rebuilt from whole seconds.
#include "zenith/track/live_packets.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace zenith::track {
namespace {

using ::testing::HasSubstr;

// Writes `value`'s bytes at `offset`, most significant first (big) or last (little).
template <class T>
void Put(std::vector<std::byte>& bytes, std::size_t offset, T value, bool big) {
    unsigned char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));  // this machine is little-endian (x86-64, aarch64)
    for (std::size_t i = 0; i < sizeof(T); ++i) {
        bytes.at(offset + i) = std::byte{raw[big ? sizeof(T) - 1 - i : i]};
    }
}

// An FGNetFDM v24 as FlightGear's FGProps2NetFDM fills it (the fields read, and a few more).
struct Fdm {
    std::uint32_t version = 24;
    double lon_rad = -2.1366;  // KSFO
    double lat_rad = 0.65859;
    double alt_m = 914.4;
    float phi = 0.1f, theta = 0.05f, psi = 4.88f;
    std::uint32_t engines = 1, tanks = 2, wheels = 3;
    std::uint32_t cur_time = 1718940600u;  // 2024-06-21T03:30:00Z
    std::int32_t warp = -12345;

    std::vector<std::byte> Bytes(std::size_t size = 408) const {
        std::vector<std::byte> b(std::max<std::size_t>(size, 408));
        Put(b, 0, version, true);
        Put(b, 8, lon_rad, true);
        Put(b, 16, lat_rad, true);
        Put(b, 24, alt_m, true);
        Put(b, 32, 12.5f, true);  // agl
        Put(b, 36, phi, true);
        Put(b, 40, theta, true);
        Put(b, 44, psi, true);
        Put(b, 68, 100.0f, true);  // vcas
        Put(b, 120, engines, true);
        Put(b, 140, 2400.0f, true);  // rpm[0]
        Put(b, 284, tanks, true);
        Put(b, 304, wheels, true);
        Put(b, 356, cur_time, true);
        Put(b, 360, warp, true);
        Put(b, 364, 20000.0f, true);  // visibility
        b.resize(size);
        return b;
    }
};

std::string KindOf(const std::vector<std::byte>& packet,
                   LiveFix (*parse)(std::span<const std::byte>)) {
    try {
        parse(packet);
    } catch (const PacketError& e) {
        return e.kind();
    }
    return "(no error)";
}

std::string MessageOf(const std::vector<std::byte>& packet,
                      LiveFix (*parse)(std::span<const std::byte>)) {
    try {
        parse(packet);
    } catch (const PacketError& e) {
        return e.what();
    }
    return "(no error)";
}

TEST(FlightGearNative, ReadsTheFieldsOfAVersion24Packet) {
    const Fdm fdm;
    const LiveFix fix = ParseFlightGearNative(fdm.Bytes());
    ASSERT_TRUE(fix.has_position());
    EXPECT_DOUBLE_EQ(*fix.lat_deg, fdm.lat_rad * 180.0 / M_PI);
    EXPECT_DOUBLE_EQ(*fix.lon_deg, fdm.lon_rad * 180.0 / M_PI);
    EXPECT_DOUBLE_EQ(*fix.height_m, 914.4);
    EXPECT_EQ(fix.altitude_kind, AltitudeKind::kEllipsoid);
    ASSERT_TRUE(fix.attitude);
    EXPECT_NEAR(fix.attitude->roll_rad, 0.1, 1e-7);
    EXPECT_NEAR(fix.attitude->pitch_rad, 0.05, 1e-7);
    EXPECT_NEAR(fix.attitude->heading_rad, 4.88, 1e-6);
    ASSERT_TRUE(fix.utc_whole_s);
    EXPECT_EQ(*fix.utc_whole_s, 1718940600.0);
}

TEST(FlightGearNative, RefusesWrongSizesNamingThem) {
    const Fdm fdm;
    EXPECT_THAT(MessageOf(fdm.Bytes(407), ParseFlightGearNative), HasSubstr("size 407 bytes"));
    EXPECT_THAT(MessageOf(fdm.Bytes(409), ParseFlightGearNative), HasSubstr("size 409 bytes"));
    EXPECT_THAT(MessageOf(fdm.Bytes(3), ParseFlightGearNative), HasSubstr("size 3 bytes"));
    EXPECT_THAT(MessageOf({}, ParseFlightGearNative), HasSubstr("size 0 bytes"));
    EXPECT_EQ(KindOf(fdm.Bytes(407), ParseFlightGearNative), "size");
}

TEST(FlightGearNative, RefusesOtherVersionsAndLittleEndianPackets) {
    Fdm old;
    old.version = 23;
    EXPECT_THAT(MessageOf(old.Bytes(), ParseFlightGearNative), HasSubstr("version 23"));
    // A packet written in host order on a little-endian machine.
    std::vector<std::byte> swapped = Fdm{}.Bytes();
    Put(swapped, 0, std::uint32_t{24}, false);
    EXPECT_THAT(MessageOf(swapped, ParseFlightGearNative), HasSubstr("little-endian"));
    EXPECT_EQ(KindOf(swapped, ParseFlightGearNative), "version");
}

TEST(FlightGearNative, RefusesNanAndOutOfRangeValues) {
    Fdm nan_lat;
    nan_lat.lat_rad = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THAT(MessageOf(nan_lat.Bytes(), ParseFlightGearNative), HasSubstr("latitude = nan rad"));
    Fdm far_lon;
    far_lon.lon_rad = 3.5;
    EXPECT_THAT(MessageOf(far_lon.Bytes(), ParseFlightGearNative),
                HasSubstr("longitude = 3.5 rad"));
    Fdm deep;
    deep.alt_m = -5000.0;
    EXPECT_THAT(MessageOf(deep.Bytes(), ParseFlightGearNative), HasSubstr("altitude = -5000 m"));
    Fdm inf_roll;
    inf_roll.phi = std::numeric_limits<float>::infinity();
    EXPECT_THAT(MessageOf(inf_roll.Bytes(), ParseFlightGearNative), HasSubstr("phi (roll)"));
    Fdm engines;
    engines.engines = 7;
    EXPECT_THAT(MessageOf(engines.Bytes(), ParseFlightGearNative),
                HasSubstr("num_engines = 7 (expected 0 to 4)"));
    Fdm wheels;
    wheels.wheels = 0xffffffffu;
    EXPECT_THAT(MessageOf(wheels.Bytes(), ParseFlightGearNative), HasSubstr("num_wheels"));
}

TEST(FlightGearNative, ClockNotSetGivesNoTime) {
    Fdm fdm;
    fdm.cur_time = 0;
    EXPECT_FALSE(ParseFlightGearNative(fdm.Bytes()).utc_whole_s);
}

std::vector<std::byte> Text(const std::string& s) {
    std::vector<std::byte> b;
    for (const char c : s) b.push_back(static_cast<std::byte>(c));
    return b;
}

TEST(FlightGearGeneric, ReadsALineOfZenithXml) {
    const LiveFix fix = ParseFlightGearGeneric(
        Text("2024-06-21T03:30:07,37.618805695,-122.375416667,3000.000,280.5000,2.2500,-"
             "15.7500\n"));
    EXPECT_DOUBLE_EQ(*fix.lat_deg, 37.618805695);
    EXPECT_DOUBLE_EQ(*fix.lon_deg, -122.375416667);
    EXPECT_DOUBLE_EQ(*fix.height_m, 3000.0 * 0.3048);
    EXPECT_NEAR(fix.attitude->heading_rad, 280.5 * M_PI / 180.0, 1e-12);
    EXPECT_NEAR(fix.attitude->pitch_rad, 2.25 * M_PI / 180.0, 1e-12);
    EXPECT_NEAR(fix.attitude->roll_rad, -15.75 * M_PI / 180.0, 1e-12);
    EXPECT_EQ(*fix.utc_whole_s, 1718940607.0);  // date -u -d 2024-06-21T03:30:07Z +%s
}

TEST(FlightGearGeneric, RefusesMalformedLinesNamingTheField) {
    auto message = [](const std::string& line) {
        return MessageOf(Text(line), ParseFlightGearGeneric);
    };
    EXPECT_THAT(message("2024-06-21T03:30:07,37.6,-122.3,3000,280,2"), HasSubstr("6 fields"));
    EXPECT_THAT(message("2024-06-21T03:30:07,37.6,-122.3,3000,280,2,1,9"),
                HasSubstr("more than 7 fields"));
    EXPECT_THAT(message(""), HasSubstr("1 fields"));
    EXPECT_THAT(message("2024-13-21T03:30:07,37.6,-122.3,3000,280,2,1"), HasSubstr("gmt"));
    EXPECT_THAT(message("yesterday,37.6,-122.3,3000,280,2,1"), HasSubstr("gmt = 'yesterday'"));
    EXPECT_THAT(message("2024-06-21T03:30:07,nan,-122.3,3000,280,2,1"),
                HasSubstr("latitude = nan deg"));
    EXPECT_THAT(message("2024-06-21T03:30:07,91,-122.3,3000,280,2,1"),
                HasSubstr("latitude = 91 deg"));
    EXPECT_THAT(message("2024-06-21T03:30:07,37.6,-122.3,3000,280,95,1"),
                HasSubstr("pitch = 95 deg"));
    EXPECT_THAT(message("2024-06-21T03:30:07,37.6,west,3000,280,2,1"),
                HasSubstr("longitude = 'west' is not a number"));
    EXPECT_THAT(message("2024-06-21T03:30:07,37.6,-122.3,1e9,280,2,1"),
                HasSubstr("altitude = 1000000000 ft"));
    EXPECT_THAT(message("2024-06-21T03:30:07,37.6,-122.3,3000,280,2,1\n2024-06-21T03:30:07"),
                HasSubstr("more than one line"));
}

// X-Plane: "DATA" + one byte, then (int32 index, 8 x float32) records, little-endian.
std::vector<std::byte> XPlaneData(
    const std::vector<std::pair<std::int32_t, std::vector<float>>>& records) {
    std::vector<std::byte> b = Text("DATA*");
    for (const auto& [index, values] : records) {
        const std::size_t at = b.size();
        b.resize(at + 36);
        Put(b, at, index, false);
        for (std::size_t i = 0; i < 8; ++i) {
            Put(b, at + 4 + 4 * i, i < values.size() ? values[i] : 0.0f, false);
        }
    }
    return b;
}

TEST(XPlane, ReadsDataIndices17And20AndSkipsOthers) {
    const auto packet = XPlaneData({{3, {120, 118, 121, 122}},
                                    {17, {2.5f, -10.0f, 275.25f, 289.0f}},
                                    {20, {47.4582f, 8.5555f, 1416.0f, 0.0f, 1, 1416, 47, 8}}});
    const LiveFix fix = ParseXPlane(packet);
    EXPECT_FLOAT_EQ(static_cast<float>(*fix.lat_deg), 47.4582f);
    EXPECT_FLOAT_EQ(static_cast<float>(*fix.lon_deg), 8.5555f);
    EXPECT_DOUBLE_EQ(*fix.height_m, 1416.0 * 0.3048);
    EXPECT_EQ(fix.altitude_kind, AltitudeKind::kMsl);
    EXPECT_NEAR(fix.attitude->pitch_rad, 2.5 * M_PI / 180.0, 1e-7);
    EXPECT_NEAR(fix.attitude->roll_rad, -10.0 * M_PI / 180.0, 1e-7);
    EXPECT_NEAR(fix.attitude->heading_rad, 275.25 * M_PI / 180.0, 1e-7);
    EXPECT_FALSE(fix.utc_whole_s);
    // Attitude only: no position.
    const LiveFix attitude_only = ParseXPlane(XPlaneData({{17, {1, 2, 3, 4}}}));
    EXPECT_FALSE(attitude_only.has_position());
    EXPECT_TRUE(attitude_only.attitude);
}

TEST(XPlane, ReadsRpos) {
    std::vector<std::byte> b = Text("RPOS4");
    b.resize(69);
    Put(b, 5, 8.5555, false);    // longitude
    Put(b, 13, 47.4582, false);  // latitude
    Put(b, 21, 431.6, false);    // elevation, m MSL
    Put(b, 29, 2.0f, false);     // AGL
    Put(b, 33, 3.0f, false);     // pitch
    Put(b, 37, 271.0f, false);   // true heading
    Put(b, 41, -20.0f, false);   // roll
    const LiveFix fix = ParseXPlane(b);
    EXPECT_DOUBLE_EQ(*fix.lon_deg, 8.5555);
    EXPECT_DOUBLE_EQ(*fix.lat_deg, 47.4582);
    EXPECT_DOUBLE_EQ(*fix.height_m, 431.6);
    EXPECT_NEAR(fix.attitude->pitch_rad, 3.0 * M_PI / 180.0, 1e-7);
    EXPECT_NEAR(fix.attitude->heading_rad, 271.0 * M_PI / 180.0, 1e-7);
    EXPECT_NEAR(fix.attitude->roll_rad, -20.0 * M_PI / 180.0, 1e-7);
    b.pop_back();
    EXPECT_THAT(MessageOf(b, ParseXPlane), HasSubstr("RPOS size 68 bytes (expected 69)"));
}

TEST(XPlane, RefusesMalformedPackets) {
    auto packet = XPlaneData({{20, {47.0f, 8.0f, 1000.0f}}});
    auto truncated = packet;
    truncated.pop_back();
    EXPECT_THAT(MessageOf(truncated, ParseXPlane), HasSubstr("DATA size 40 bytes"));
    EXPECT_THAT(MessageOf(Text("DATA*"), ParseXPlane), HasSubstr("DATA size 5 bytes"));
    EXPECT_THAT(MessageOf(Text("XYZ"), ParseXPlane), HasSubstr("size 3 bytes"));
    EXPECT_THAT(MessageOf(Text(std::string("BECN\0xxxxxxxxxx", 15)), ParseXPlane),
                HasSubstr("header 'BECN'"));
    EXPECT_THAT(MessageOf(XPlaneData({{3, {1, 2, 3}}}), ParseXPlane),
                HasSubstr("without index 17 or 20"));
    EXPECT_THAT(MessageOf(XPlaneData({{20, {-999.0f, 8.0f, 1000.0f}}}), ParseXPlane),
                HasSubstr("latitude is unset"));
    EXPECT_THAT(MessageOf(XPlaneData({{20, {std::nanf(""), 8.0f, 1000.0f}}}), ParseXPlane),
                HasSubstr("latitude = nan deg"));
    EXPECT_THAT(MessageOf(XPlaneData({{17, {0.0f, 200.0f, 10.0f}}}), ParseXPlane),
                HasSubstr("roll = 200 deg"));
    std::vector<std::byte> huge(kMaxPacketBytes + 1, std::byte{'D'});
    EXPECT_THAT(MessageOf(huge, ParseXPlane), HasSubstr("size 8193 bytes"));
}

// A simulator whose UTC is receiver time + offset sends floor(UTC) at 20 Hz with up to 8 ms of
// latency; the rebuilt clock converges to the offset from below and never runs backwards.
TEST(WholeSecondClock, ConvergesFromBelowAndIsMonotonic) {
    const double offset = 1718940600.0 + 0.3712;
    std::mt19937 random(7);
    std::uniform_real_distribution<double> latency(0.0, 0.008);
    WholeSecondClock clock;
    double previous = -1e300;
    for (int i = 0; i < 400; ++i) {
        const double sent = 0.05 * i;
        const double arrival = sent + latency(random);
        clock.Observe(std::floor(sent + offset), arrival);
        const double now = clock.UtcAt(arrival);
        EXPECT_GE(now, previous);
        previous = now;
        EXPECT_LE(now, arrival + offset + 1e-9);  // a lower bound of the offset, latency aside
        if (sent > 1.0) {
            EXPECT_NEAR(clock.UtcAt(arrival), arrival + offset, 0.05 + 0.008);
        }
    }
    EXPECT_EQ(clock.resets(), 0);
    EXPECT_LT(clock.uncertainty_s(), 0.06);
}

TEST(WholeSecondClock, JumpsForwardAtOnceWhenTheTimeIsSetForward) {
    WholeSecondClock clock;
    for (int i = 0; i < 40; ++i) clock.Observe(std::floor(1000.25 + 0.05 * i), 0.05 * i);
    EXPECT_FALSE(clock.Observe(1002.0, 2.0));
    EXPECT_TRUE(clock.Observe(4602.0, 2.05));  // an hour later: the time was set
    EXPECT_EQ(clock.resets(), 1);
    EXPECT_EQ(clock.UtcAt(2.05), 4602.0);
}

// FlightGear stalled for 1.67 s between stamping a packet and sending it (seen in a real run):
// the packet is set aside, the clock neither resets nor moves.
TEST(WholeSecondClock, ALatePacketIsSetAside) {
    WholeSecondClock clock;
    for (int i = 0; i < 40; ++i) clock.Observe(std::floor(1000.25 + 0.05 * i), 0.05 * i);
    const double before = clock.UtcAt(2.0);
    EXPECT_FALSE(clock.Observe(1001.0, 2.1));  // sent at 1.70 (UTC 1001.95), 0.4 s late
    EXPECT_FALSE(clock.Observe(1001.0, 3.6));  // 1.9 s late
    EXPECT_EQ(clock.UtcAt(2.0), before);
    EXPECT_EQ(clock.late_packets(), 1);
    EXPECT_EQ(clock.resets(), 0);
    // The stream goes on as before.
    EXPECT_FALSE(clock.Observe(1003.0, 3.65));
    EXPECT_EQ(clock.UtcAt(2.0), before);
}

// The real run's stall: two late packets 4 s apart (1.7 and 2.4 s late), then on time again.
TEST(WholeSecondClock, TwoLatePacketsOverAStallAreSetAside) {
    WholeSecondClock clock;
    for (int i = 0; i < 40; ++i) {
        const double t = 45.0 + 0.05 * i;
        clock.Observe(std::floor(596.80 + t), t);
    }
    const double before = clock.UtcAt(0.0);
    EXPECT_FALSE(clock.Observe(650.0, 54.871));  // the arrivals and stamps of the real run
    EXPECT_FALSE(clock.Observe(653.0, 58.867));
    EXPECT_FALSE(clock.Observe(657.0, 60.632));
    EXPECT_EQ(clock.resets(), 0);
    EXPECT_EQ(clock.late_packets(), 2);
    EXPECT_EQ(clock.UtcAt(0.0), before);
}

// The time set back by a minute: earlier packets that keep coming for kLateResetSeconds.
TEST(WholeSecondClock, StartsOverWhenEarlierPacketsLast) {
    WholeSecondClock clock;
    double t = 0.0;
    for (; t < 2.0; t += 0.05) clock.Observe(std::floor(1000.25 + t), t);
    int resets_at = -1;
    for (int i = 0; t < 6.0; t += 0.05, ++i) {
        if (clock.Observe(std::floor(940.25 + t), t) && resets_at < 0) resets_at = i;
    }
    EXPECT_EQ(clock.resets(), 1);
    EXPECT_GE(resets_at, 40);  // 2 s of packets 50 ms apart (41: 40 x 0.05 rounds under 2)
    EXPECT_LE(resets_at, 41);
    EXPECT_NEAR(clock.UtcAt(t), 940.25 + t, 0.05);
}

}  // namespace
}  // namespace zenith::track
