// METAR decoder and METAR files: the worked examples of the FAA's and WMO's documentation decoded
// field by field, every visibility and sky-condition form, and malformed reports, whose warnings
// must name the group and its position.
//
// Sources of the worked examples (the documents themselves are not in this repository):
//  - FAA "Key to Aerodrome Forecast (TAF) and Aviation Routine Weather Report (METAR)" reference
//    card, the example also used in AC 00-45 (Aviation Weather Services), as reproduced at
//    http://moratech.com/aviation/metar-class/quick-metar.html and
//    http://www.asiresource.com/metar.htm ("METAR KABC 121755Z AUTO 21016G24KT 180V240 1SM ...").
//    The AIM 7-1-30 text itself could not be retrieved here; its example (KGGG ...) is not used.
//  - Real US and WMO-region reports with their field-by-field key, National Weather Service
//    forms: http://www.dixwx.com/wxdecoding.htm (KLAX, KEWR, KGTF, KABQ, SVVA below).
//  - WMO No. 306 Vol. I.1, FM 15-XIV METAR, code form and regulations (15.6.2 directional
//    visibility, 15.6.3 0000/9999, 15.7 RVR, 15.8 w'w', 15.9 cloud, 15.13 supplementary), as
//    reproduced at https://docsbay.net/fm-15-xiv-metar and
//    https://docslib.org/doc/13944035/ (FM 15 XIII). The WMO-form reports below that are not from
//    the pages above are written to those regulations (marked "constructed").
#include "zenith/weather/metar.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "zenith/base/units.h"
#include "zenith/geo/time.h"
#include "zenith/weather/metar_file.h"

namespace zenith::weather {
namespace {

constexpr double kKt = kMetresPerSecondPerKnot;

bool AnyWarningContains(const Metar& m, const std::string& text) {
    return std::any_of(m.warnings.begin(), m.warnings.end(), [&](const MetarWarning& w) {
        return w.ToString().find(text) != std::string::npos;
    });
}

std::string Warnings(const Metar& m) {
    std::string out;
    for (const auto& w : m.warnings) out += w.ToString() + "\n";
    return out;
}

std::string ThrownMessage(auto&& f) {
    try {
        f();
    } catch (const MetarError& e) {
        return e.what();
    }
    return "(nothing thrown)";
}

// --- worked examples ----------------------------------------------------------------------------

// FAA key card / AC 00-45 example, field by field as the card decodes it.
TEST(MetarExamples, FaaKeyCardKabc) {
    const Metar m = DecodeMetar(
        "METAR KABC 121755Z AUTO 21016G24KT 180V240 1SM R11/P6000FT -RA BR BKN015 OVC025 06/04 "
        "A2990 RMK AO2 PK WND 20032/25 WSHFT 1715 VIS 3/4V1 1/2 VIS 3/4 RWY11 RAB07 CIG 013V017 "
        "CIG 017 RWY11 PRESFR SLP125 P0003 60009 T00640036 10066 21012 58033 TSNO $");
    EXPECT_TRUE(m.warnings.empty()) << Warnings(m);
    EXPECT_EQ(m.type, ReportType::kMetar);
    EXPECT_EQ(m.station, "KABC");
    ASSERT_TRUE(m.time);
    EXPECT_EQ(m.time->day, 12);
    EXPECT_EQ(m.time->hour, 17);
    EXPECT_EQ(m.time->minute, 55);
    EXPECT_TRUE(m.automatic);
    EXPECT_FALSE(m.corrected);
    // Wind 210 deg, 16 kt gusting 24 kt, varying 180-240.
    ASSERT_TRUE(m.wind);
    EXPECT_EQ(m.wind->direction_deg, 210.0);
    EXPECT_EQ(m.wind->unit, SpeedUnit::kKnot);
    EXPECT_EQ(m.wind->speed_in_unit, 16.0);
    EXPECT_NEAR(*m.wind->speed_m_s, 16 * kKt, 1e-12);
    EXPECT_NEAR(*m.wind->gust_m_s, 24 * kKt, 1e-12);
    EXPECT_EQ(m.wind->variable_from_deg, 180.0);
    EXPECT_EQ(m.wind->variable_to_deg, 240.0);
    // Visibility 1 statute mile.
    ASSERT_TRUE(m.visibility);
    EXPECT_TRUE(m.visibility->statute_miles);
    EXPECT_DOUBLE_EQ(m.visibility->visibility_m, kMetresPerStatuteMile);
    EXPECT_EQ(m.visibility->bound, Bound::kExact);
    // RVR runway 11 more than 6000 ft.
    ASSERT_EQ(m.rvr.size(), 1u);
    EXPECT_EQ(m.rvr[0].runway, "11");
    EXPECT_TRUE(m.rvr[0].feet);
    EXPECT_EQ(m.rvr[0].bound, Bound::kMoreThan);
    EXPECT_NEAR(m.rvr[0].rvr_m, 6000 * kMetresPerFoot, 1e-9);
    // Light rain, mist.
    ASSERT_EQ(m.weather.size(), 2u);
    EXPECT_EQ(m.weather[0].intensity, Intensity::kLight);
    EXPECT_EQ(m.weather[0].phenomena, std::vector<Phenomenon>{Phenomenon::kRain});
    EXPECT_EQ(m.weather[1].phenomena, std::vector<Phenomenon>{Phenomenon::kMist});
    // Broken at 1500 ft, overcast at 2500 ft: ceiling 1500 ft.
    ASSERT_EQ(m.sky.size(), 2u);
    EXPECT_EQ(m.sky[0].cover, Cover::kBroken);
    EXPECT_EQ(m.sky[0].base_ft, 1500.0);
    EXPECT_EQ(m.sky[1].cover, Cover::kOvercast);
    EXPECT_EQ(m.sky[1].base_ft, 2500.0);
    EXPECT_EQ(m.ceiling_ft(), 1500.0);
    // 6/4 degC in the body; the remark T00640036 gives 6.4 / 3.6 degC.
    EXPECT_TRUE(m.temperature_from_remarks);
    EXPECT_NEAR(*m.temperature_c, 6.4, 1e-12);
    EXPECT_NEAR(*m.dew_point_c, 3.6, 1e-12);
    // Altimeter 29.90 inHg = 1012.5 hPa.
    EXPECT_NEAR(*m.altimeter_inhg, 29.90, 1e-12);
    EXPECT_NEAR(*m.qnh_hpa, 1012.5, 0.05);
    EXPECT_EQ(m.remarks.substr(0, 10), "AO2 PK WND");
    EXPECT_EQ(m.trend_kind, TrendKind::kNone);
}

// dixwx.com: a corrected report with a split mile fraction and haze.
TEST(MetarExamples, KlaxCorrectedHaze) {
    const Metar m = DecodeMetar(
        "KLAX 161550Z COR 11004KT 2 1/2SM HZ BKN011 BKN015 19/16 A2993 RMK AO2 SLP134 VIS SW-NW "
        "1 1/2 FG BNK SW-NW T01890156");
    EXPECT_TRUE(m.warnings.empty()) << Warnings(m);
    EXPECT_TRUE(m.corrected);
    EXPECT_NEAR(m.visibility->visibility_m, 2.5 * kMetresPerStatuteMile, 1e-9);
    EXPECT_DOUBLE_EQ(m.visibility->reported, 2.5);
    ASSERT_EQ(m.weather.size(), 1u);
    EXPECT_TRUE(m.weather[0].Has(Phenomenon::kHaze));
    EXPECT_EQ(m.sky.size(), 2u);
    EXPECT_NEAR(*m.temperature_c, 18.9, 1e-12);
    EXPECT_NEAR(*m.dew_point_c, 15.6, 1e-12);
}

// dixwx.com: RVR varying up to more than 6000 ft; three layers.
TEST(MetarExamples, KewrVariableRvr) {
    const Metar m = DecodeMetar(
        "KEWR 160128Z 18008KT 2 1/2SM R04R/4500VP6000FT RA BR SCT008 BKN022 OVC038 22/21 A3001 "
        "RMK AO2 RAB20E51 SCT008 V BKN P0008");
    EXPECT_TRUE(m.warnings.empty()) << Warnings(m);
    ASSERT_EQ(m.rvr.size(), 1u);
    EXPECT_EQ(m.rvr[0].runway, "04R");
    EXPECT_NEAR(m.rvr[0].rvr_m, 4500 * kMetresPerFoot, 1e-9);
    EXPECT_NEAR(*m.rvr[0].max_rvr_m, 6000 * kMetresPerFoot, 1e-9);
    EXPECT_EQ(m.rvr[0].max_bound, Bound::kMoreThan);
    ASSERT_EQ(m.sky.size(), 3u);
    EXPECT_EQ(m.sky[0].cover, Cover::kScattered);
    EXPECT_EQ(m.ceiling_ft(), 2200.0);
    EXPECT_EQ(m.temperature_c, 22.0);
    EXPECT_NEAR(*m.qnh_hpa, 30.01 * kHectopascalsPerInchOfMercury, 1e-9);
}

// dixwx.com: no temperature group at all; light snow.
TEST(MetarExamples, KgtfNoTemperature) {
    const Metar m =
        DecodeMetar("KGTF 170322Z 33014KT 1 3/4SM -SN BR OVC005 A2991 RMK AO2 RAE17SNB17 P0004");
    EXPECT_TRUE(m.warnings.empty()) << Warnings(m);
    EXPECT_NEAR(m.visibility->visibility_m, 1.75 * kMetresPerStatuteMile, 1e-9);
    EXPECT_FALSE(m.temperature_c);
    EXPECT_TRUE(m.weather[0].Has(Phenomenon::kSnow));
    EXPECT_TRUE(m.weather[0].HasPrecipitation());
    EXPECT_EQ(m.weather[0].Describe(), "light snow");
}

// dixwx.com: thunderstorm without precipitation, a CB layer and negative temperatures.
TEST(MetarExamples, KabqThunderstormCb) {
    const Metar m = DecodeMetar(
        "KABQ 100156Z 32010KT 280V340 10SM TS FEW033 BKN075CB OVC100 19/14 A2999 RMK AO2 "
        "TSB09RAB09E56 SLP085 FREQ LTGCCCGIC OHD TS OHD MOV NE MTN TOP OBSCD NE P0002 T01940144");
    EXPECT_TRUE(m.warnings.empty()) << Warnings(m);
    EXPECT_EQ(m.wind->variable_from_deg, 280.0);
    ASSERT_EQ(m.weather.size(), 1u);
    EXPECT_EQ(m.weather[0].descriptor, Descriptor::kThunderstorm);
    EXPECT_TRUE(m.weather[0].phenomena.empty());
    EXPECT_EQ(m.sky[1].convective, ConvectiveCloud::kCumulonimbus);
    const Metar k = DecodeMetar(
        "KBIL 162256Z 29017G27KT 10SM FEW070 SCT085 BKN110 M02/M02 A2961 "
        "RMK AO2 PK WND 29027/2250 WSHFT 2241 SLP205 70033 T10171022");
    EXPECT_TRUE(k.warnings.empty()) << Warnings(k);
    EXPECT_NEAR(*k.temperature_c, -1.7, 1e-12);
    EXPECT_NEAR(*k.dew_point_c, -2.2, 1e-12);
}

// dixwx.com: a WMO-region report (Valencia, Venezuela): calm, 9999, Q, NOSIG.
TEST(MetarExamples, SvvaWmoForm) {
    const Metar m = DecodeMetar("SVVA 171100Z 00000KT 9999 FEW016 BKN250 21/19 Q1013 NOSIG");
    EXPECT_TRUE(m.warnings.empty()) << Warnings(m);
    EXPECT_TRUE(m.wind->calm());
    EXPECT_EQ(m.visibility->visibility_m, 10000.0);
    EXPECT_EQ(m.visibility->bound, Bound::kMoreThan);
    EXPECT_EQ(m.qnh_hpa, 1013.0);
    EXPECT_FALSE(m.altimeter_inhg);
    EXPECT_EQ(m.trend_kind, TrendKind::kNosig);
    EXPECT_EQ(m.trend, "NOSIG");
}

// WMO FM 15 (constructed to regs. 15.5-15.9 and 15.13): wind in m/s, directional minimum
// visibility, RVR with tendency, recent weather, a trend with its own groups, and '='.
TEST(MetarExamples, WmoFormsConstructed) {
    const Metar m = DecodeMetar(
        "METAR LFPG 211630Z 24004MPS 1200 0600NE R27L/0550N R09R/1200V1800U +SHRA FEW008 "
        "SCT015CB OVC030 17/16 Q1008 RERA WS R27L BECMG FM1700 9999 NSW NSC=");
    EXPECT_TRUE(m.warnings.empty()) << Warnings(m);
    EXPECT_EQ(m.wind->unit, SpeedUnit::kMetrePerSecond);
    EXPECT_EQ(m.wind->speed_m_s, 4.0);
    EXPECT_EQ(m.visibility->visibility_m, 1200.0);
    ASSERT_TRUE(m.minimum_visibility);
    EXPECT_EQ(m.minimum_visibility->visibility_m, 600.0);
    EXPECT_EQ(m.minimum_visibility->direction, CompassPoint::kNE);
    ASSERT_EQ(m.rvr.size(), 2u);
    EXPECT_EQ(m.rvr[0].runway, "27L");
    EXPECT_EQ(m.rvr[0].rvr_m, 550.0);
    EXPECT_EQ(m.rvr[0].tendency, 'N');
    EXPECT_FALSE(m.rvr[0].feet);
    EXPECT_EQ(m.rvr[1].rvr_m, 1200.0);
    EXPECT_EQ(m.rvr[1].max_rvr_m, 1800.0);
    EXPECT_EQ(m.rvr[1].tendency, 'U');
    EXPECT_EQ(m.weather[0].Describe(), "heavy showers of rain");
    ASSERT_EQ(m.recent_weather.size(), 1u);
    EXPECT_TRUE(m.recent_weather[0].Has(Phenomenon::kRain));
    EXPECT_EQ(m.not_decoded, std::vector<std::string>{"WS R27L"});
    EXPECT_EQ(m.trend_kind, TrendKind::kBecmg);
    EXPECT_EQ(m.trend, "BECMG FM1700 9999 NSW NSC");
    // The trend's NSC is the forecast's, not the observed sky.
    EXPECT_EQ(m.clear, ClearSky::kNone);
    EXPECT_EQ(m.sky.size(), 3u);
}

// A trend's time group (FM 15 reg. 15.14: FM, TL or AT and HHMM) without its change indicator
// BECMG or TEMPO before it: the groups from it on are the forecast's, not the observation's, so
// they end the body with a warning instead of being decoded into the observed sky. (Before, the
// forecast's SCT030 was taken as an observed layer.)
TEST(MetarExamples, TrendTimeGroupWithoutChangeIndicator) {
    const Metar m =
        DecodeMetar("LSZH 291950Z 24010KT 9999 FEW040 15/10 Q1015 FM2000 SCT030 RMK AO2");
    ASSERT_EQ(m.warnings.size(), 1u) << Warnings(m);
    EXPECT_TRUE(AnyWarningContains(m, "BECMG or TEMPO")) << Warnings(m);
    EXPECT_EQ(m.warnings[0].group, "FM2000");
    ASSERT_EQ(m.sky.size(), 1u);
    EXPECT_EQ(m.sky[0].base_m(), 4000 * kMetresPerFoot);
    EXPECT_EQ(m.qnh_hpa, 1015.0);
    EXPECT_EQ(m.trend_kind, TrendKind::kNone);
    EXPECT_EQ(m.trend, "FM2000 SCT030");
    EXPECT_EQ(m.remarks, "AO2");
    // TL and AT likewise; a group that only starts like one (FMS, AT12) is not a trend.
    EXPECT_EQ(DecodeMetar("LSZH 291950Z 24010KT 9999 FEW040 15/10 Q1015 TL2100 BKN020").sky.size(),
              1u);
    EXPECT_EQ(DecodeMetar("LSZH 291950Z 24010KT 9999 FEW040 15/10 Q1015 AT2030 BKN020").sky.size(),
              1u);
    EXPECT_TRUE(
        DecodeMetar("LSZH 291950Z 24010KT 9999 FEW040 15/10 Q1015 AT12 BKN020").trend.empty());
}

// Runway state groups (FM 15 reg. 15.13.6.1) come after QNH with the supplementary groups, in
// winter on most European and Russian reports: they are in order there (no warning), kept as not
// decoded, and not taken for RVR; elements not reported are '/'. (Before, they were read in
// the RVR's place, and after QNH warned as out of order.)
TEST(MetarExamples, RunwayStateAfterPressure) {
    const Metar m = DecodeMetar(
        "UUEE 271800Z 21004MPS 0800 R24L/1100D FZFG VV002 M04/M04 Q1019 R24L/590350 R06/9///95 "
        "R/SNOCLO NOSIG");
    EXPECT_TRUE(m.warnings.empty()) << Warnings(m);
    ASSERT_EQ(m.rvr.size(), 1u);
    EXPECT_EQ(m.rvr[0].runway, "24L");
    EXPECT_EQ(m.rvr[0].rvr_m, 1100.0);
    EXPECT_EQ(m.not_decoded, (std::vector<std::string>{"R24L/590350", "R06/9///95", "R/SNOCLO"}));
    EXPECT_EQ(m.qnh_hpa, 1019.0);
    EXPECT_EQ(m.trend_kind, TrendKind::kNosig);
}

// The issue's example (London Heathrow, the form of zenith render --metar).
TEST(MetarExamples, IssueExample) {
    const Metar m = DecodeMetar("EGLL 211750Z 24012KT 9999 FEW035 SCT250 18/09 Q1018");
    EXPECT_TRUE(m.warnings.empty()) << Warnings(m);
    EXPECT_EQ(m.sky[0].base_m(), 3500 * kMetresPerFoot);
    EXPECT_EQ(m.dew_point_c, 9.0);
    const std::string d = m.Describe();
    EXPECT_NE(d.find("from 240 deg, 12 KT (6.2 m/s)"), std::string::npos) << d;
    EXPECT_NE(d.find("visibility: more than 10000 m"), std::string::npos) << d;
    EXPECT_NE(d.find("few (1-2 oktas) at 3500 ft (1067 m)"), std::string::npos) << d;
    EXPECT_NE(d.find("QNH: 1018.0 hPa"), std::string::npos) << d;
}

// --- every form of each group -------------------------------------------------------------------

struct VisibilityCase {
    const char* group;
    double metres;
    Bound bound;
    bool miles;
};

TEST(MetarForms, Visibility) {
    const VisibilityCase cases[] = {
        {"9999", 10000.0, Bound::kMoreThan, false},
        {"0000", 50.0, Bound::kLessThan, false},
        {"0800", 800.0, Bound::kExact, false},
        {"1 1/2SM", 1.5 * kMetresPerStatuteMile, Bound::kExact, true},
        {"1/2SM", 0.5 * kMetresPerStatuteMile, Bound::kExact, true},
        {"3/16SM", 3.0 / 16.0 * kMetresPerStatuteMile, Bound::kExact, true},
        {"P6SM", 6 * kMetresPerStatuteMile, Bound::kMoreThan, true},
        {"M1/4SM", 0.25 * kMetresPerStatuteMile, Bound::kLessThan, true},
        {"10SM", 10 * kMetresPerStatuteMile, Bound::kExact, true},
        {"CAVOK", 10000.0, Bound::kMoreThan, false},
    };
    for (const auto& c : cases) {
        SCOPED_TRACE(c.group);
        const Metar m =
            DecodeMetar(std::string("KXYZ 010000Z 27005KT ") + c.group + " 10/05 Q1000");
        EXPECT_TRUE(m.warnings.empty()) << Warnings(m);
        ASSERT_TRUE(m.visibility);
        EXPECT_NEAR(m.visibility->visibility_m, c.metres, 1e-9);
        EXPECT_EQ(m.visibility->bound, c.bound);
        EXPECT_EQ(m.visibility->statute_miles, c.miles);
        EXPECT_EQ(m.cavok, std::string(c.group) == "CAVOK");
    }
    const Metar ndv = DecodeMetar("EDDF 010000Z AUTO 27005KT 4000NDV BR NCD 10/09 Q1000");
    EXPECT_TRUE(ndv.visibility->no_directional_variation);
    EXPECT_EQ(ndv.clear, ClearSky::kNcd);
    const Metar missing = DecodeMetar("EDDF 010000Z AUTO 27005KT //// // ////// 10/09 Q1000");
    EXPECT_TRUE(missing.warnings.empty()) << Warnings(missing);
    EXPECT_FALSE(missing.visibility);
    EXPECT_TRUE(missing.weather_not_observed);
    EXPECT_TRUE(missing.sky_not_observed);
}

TEST(MetarForms, Wind) {
    const Metar vrb = DecodeMetar("KXYZ 010000Z VRB03KT 10SM CLR 10/05 A3000");
    EXPECT_TRUE(vrb.wind->variable);
    EXPECT_FALSE(vrb.wind->direction_deg);
    const Metar kmh = DecodeMetar("UUEE 010000Z 18036G54KMH 9999 SKC M10/M15 Q1030");
    EXPECT_NEAR(*kmh.wind->speed_m_s, 10.0, 1e-12);
    EXPECT_NEAR(*kmh.wind->gust_m_s, 15.0, 1e-12);
    const Metar strong = DecodeMetar("KXYZ 010000Z 270120G150KT 10SM CLR 10/05 A3000");
    EXPECT_EQ(strong.wind->speed_in_unit, 120.0);
    EXPECT_EQ(strong.wind->gust_in_unit, 150.0);
    const Metar missing = DecodeMetar("KXYZ 010000Z AUTO /////KT 10SM CLR 10/05 A3000");
    EXPECT_TRUE(missing.warnings.empty()) << Warnings(missing);
    EXPECT_FALSE(missing.wind->speed_m_s);
}

TEST(MetarForms, PresentWeather) {
    struct Case {
        const char* group;
        Intensity intensity;
        Descriptor descriptor;
        std::vector<Phenomenon> phenomena;
    };
    const Case cases[] = {
        {"-RA", Intensity::kLight, Descriptor::kNone, {Phenomenon::kRain}},
        {"+TSRA", Intensity::kHeavy, Descriptor::kThunderstorm, {Phenomenon::kRain}},
        {"SHSN", Intensity::kModerate, Descriptor::kShowers, {Phenomenon::kSnow}},
        {"FG", Intensity::kModerate, Descriptor::kNone, {Phenomenon::kFog}},
        {"FZFG", Intensity::kModerate, Descriptor::kFreezing, {Phenomenon::kFog}},
        {"VCSH", Intensity::kVicinity, Descriptor::kShowers, {}},
        {"-SHRASN",
         Intensity::kLight,
         Descriptor::kShowers,
         {Phenomenon::kRain, Phenomenon::kSnow}},
        {"MIFG", Intensity::kModerate, Descriptor::kShallow, {Phenomenon::kFog}},
        {"BCFG", Intensity::kModerate, Descriptor::kPatches, {Phenomenon::kFog}},
        {"PRFG", Intensity::kModerate, Descriptor::kPartial, {Phenomenon::kFog}},
        {"DRSN", Intensity::kModerate, Descriptor::kLowDrifting, {Phenomenon::kSnow}},
        {"BLSA", Intensity::kModerate, Descriptor::kBlowing, {Phenomenon::kSand}},
        {"+FC", Intensity::kHeavy, Descriptor::kNone, {Phenomenon::kFunnelCloud}},
        {"UP", Intensity::kModerate, Descriptor::kNone, {Phenomenon::kUnknownPrecipitation}},
        {"GR", Intensity::kModerate, Descriptor::kNone, {Phenomenon::kHail}},
        {"GS", Intensity::kModerate, Descriptor::kNone, {Phenomenon::kSmallHail}},
        {"PL", Intensity::kModerate, Descriptor::kNone, {Phenomenon::kIcePellets}},
        {"IC", Intensity::kModerate, Descriptor::kNone, {Phenomenon::kIceCrystals}},
        {"SG", Intensity::kModerate, Descriptor::kNone, {Phenomenon::kSnowGrains}},
        {"-DZ", Intensity::kLight, Descriptor::kNone, {Phenomenon::kDrizzle}},
        {"BR", Intensity::kModerate, Descriptor::kNone, {Phenomenon::kMist}},
        {"HZ", Intensity::kModerate, Descriptor::kNone, {Phenomenon::kHaze}},
        {"FU", Intensity::kModerate, Descriptor::kNone, {Phenomenon::kSmoke}},
        {"VA", Intensity::kModerate, Descriptor::kNone, {Phenomenon::kVolcanicAsh}},
        {"DU", Intensity::kModerate, Descriptor::kNone, {Phenomenon::kDust}},
        {"SA", Intensity::kModerate, Descriptor::kNone, {Phenomenon::kSand}},
        {"PY", Intensity::kModerate, Descriptor::kNone, {Phenomenon::kSpray}},
        {"PO", Intensity::kModerate, Descriptor::kNone, {Phenomenon::kDustWhirls}},
        {"SQ", Intensity::kModerate, Descriptor::kNone, {Phenomenon::kSqualls}},
        {"+SS", Intensity::kHeavy, Descriptor::kNone, {Phenomenon::kSandstorm}},
        {"DS", Intensity::kModerate, Descriptor::kNone, {Phenomenon::kDuststorm}},
        {"FZRA", Intensity::kModerate, Descriptor::kFreezing, {Phenomenon::kRain}},
    };
    for (const auto& c : cases) {
        SCOPED_TRACE(c.group);
        const Metar m = DecodeMetar(std::string("KXYZ 010000Z 27005KT 2SM ") + c.group +
                                    " OVC010 01/M01 A2992");
        EXPECT_TRUE(m.warnings.empty()) << Warnings(m);
        ASSERT_EQ(m.weather.size(), 1u);
        EXPECT_EQ(m.weather[0].code, c.group);
        EXPECT_EQ(m.weather[0].intensity, c.intensity);
        EXPECT_EQ(m.weather[0].descriptor, c.descriptor);
        EXPECT_EQ(m.weather[0].phenomena, c.phenomena);
        EXPECT_FALSE(m.weather[0].Describe().empty());
    }
}

TEST(MetarForms, SkyCondition) {
    const Metar m = DecodeMetar(
        "KXYZ 010000Z AUTO 27005KT 10SM FEW020 SCT035TCU BKN///CB OVC100/// ///120 10/05 A3000");
    EXPECT_TRUE(m.warnings.empty()) << Warnings(m);
    ASSERT_EQ(m.sky.size(), 5u);
    EXPECT_EQ(m.sky[1].convective, ConvectiveCloud::kToweringCumulus);
    EXPECT_EQ(m.sky[2].cover, Cover::kBroken);
    EXPECT_FALSE(m.sky[2].base_ft);
    EXPECT_EQ(m.sky[2].convective, ConvectiveCloud::kCumulonimbus);
    EXPECT_EQ(m.sky[3].convective, ConvectiveCloud::kUnknown);
    EXPECT_EQ(m.sky[4].cover, Cover::kUnknown);
    EXPECT_EQ(m.sky[4].base_ft, 12000.0);
    EXPECT_EQ(m.ceiling_ft(), 10000.0);  // BKN/// has no base
    for (const char* code : {"SKC", "CLR", "NSC", "NCD"}) {
        const Metar c =
            DecodeMetar(std::string("EDDF 010000Z 27005KT 9999 ") + code + " 10/05 Q1000");
        EXPECT_TRUE(c.warnings.empty()) << Warnings(c);
        EXPECT_EQ(ClearSkyCode(c.clear), code);
        EXPECT_TRUE(c.sky.empty());
    }
    const Metar vv = DecodeMetar("EDDF 010000Z 00000KT 0100 FG VV001 05/05 Q1020");
    EXPECT_TRUE(vv.vertical_visibility_reported);
    EXPECT_EQ(vv.vertical_visibility_ft, 100.0);
    EXPECT_EQ(vv.ceiling_ft(), 100.0);
    const Metar vvu = DecodeMetar("EDDF 010000Z AUTO 00000KT 0100 FG VV/// 05/05 Q1020");
    EXPECT_TRUE(vvu.vertical_visibility_reported);
    EXPECT_FALSE(vvu.vertical_visibility_ft);
    EXPECT_EQ(MinOktas(Cover::kFew), 1);
    EXPECT_EQ(MaxOktas(Cover::kScattered), 4);
    EXPECT_EQ(MinOktas(Cover::kBroken), 5);
    EXPECT_EQ(MaxOktas(Cover::kOvercast), 8);
}

TEST(MetarForms, TemperatureAndPressure) {
    const Metar a = DecodeMetar("KXYZ 010000Z 27005KT 10SM CLR M05/M12 A2992");
    EXPECT_EQ(a.temperature_c, -5.0);
    EXPECT_EQ(a.dew_point_c, -12.0);
    EXPECT_NEAR(*a.qnh_hpa, 1013.2, 0.05);  // 29.92 inHg is the standard 1013.25 hPa
    const Metar b = DecodeMetar("EDDF 010000Z 27005KT 9999 SKC 05/ Q0998");
    EXPECT_EQ(b.temperature_c, 5.0);
    EXPECT_FALSE(b.dew_point_c);
    EXPECT_EQ(b.qnh_hpa, 998.0);
    const Metar c = DecodeMetar("EDDF 010000Z AUTO 27005KT 9999 NCD ///// Q////");
    EXPECT_TRUE(c.warnings.empty()) << Warnings(c);
    EXPECT_FALSE(c.temperature_c);
    EXPECT_FALSE(c.qnh_hpa);
}

TEST(MetarForms, SpeciNilAndRemarksOnly) {
    const Metar s = DecodeMetar("SPECI KXYZ 010012Z 27005KT 1/4SM FG VV002 10/10 A3000");
    EXPECT_EQ(s.type, ReportType::kSpeci);
    const Metar nil = DecodeMetar("METAR EDDF 010000Z NIL=");
    EXPECT_TRUE(nil.nil);
    EXPECT_TRUE(nil.warnings.empty()) << Warnings(nil);
    const Metar cor = DecodeMetar("METAR COR EDDF 010000Z 27005KT CAVOK 10/05 Q1000");
    EXPECT_TRUE(cor.corrected);
    EXPECT_TRUE(cor.cavok);
}

// --- malformed reports
// ----------------------------------------------------------------------------

TEST(MetarMalformed, FatalErrorsThrow) {
    struct Case {
        const char* text;
        const char* message;
    };
    const Case cases[] = {
        {"", "empty METAR report"},
        {"   \t  ", "empty METAR report"},
        {"METAR", "no station"},
        {"METAR 121755Z 21016KT", "group 1 '121755Z' at character 6: expected the station"},
        {"kabc 121755Z", "group 0 'kabc' at character 0"},
        {"21016KT 9999", "expected the station"},
    };
    for (const auto& c : cases) {
        SCOPED_TRACE(c.text);
        EXPECT_NE(ThrownMessage([&] { DecodeMetar(c.text); }).find(c.message), std::string::npos)
            << ThrownMessage([&] { DecodeMetar(c.text); });
    }
    const std::string huge(kMaxMetarBytes + 1, 'A');
    EXPECT_NE(ThrownMessage([&] { DecodeMetar(huge); }).find("at most 65536"), std::string::npos);
    // Every error is a zenith::Error.
    EXPECT_THROW(DecodeMetar(""), zenith::Error);
}

// Each bad group gives one warning that names it, its index and its character offset; the rest of
// the report is still decoded.
TEST(MetarMalformed, WarningsNameGroupAndPosition) {
    struct Case {
        const char* text;
        const char* warning;
    };
    const Case cases[] = {
        {"KXYZ 010000Z 27005KT 10SM XYZZY CLR 10/05 A3000",
         "group 4 'XYZZY' at character 26: unknown group"},
        {"KXYZ 01000Z 27005KT 10SM CLR 10/05 A3000",
         "group 1 '01000Z' at character 5: expected the time"},
        {"KXYZ 320000Z 27005KT 10SM CLR 10/05 A3000",
         "group 1 '320000Z' at character 5: time out of range"},
        {"KXYZ 010000Z 40005KT 10SM CLR 10/05 A3000",
         "group 2 '40005KT' at character 13: wind direction 400"},
        {"KXYZ 010000Z 27005KT 1/0SM CLR 10/05 A3000",
         "group 3 '1/0SM' at character 21: zero denominator"},
        {"KXYZ 010000Z 27005KT 10SM CLR 10/05 A1234",
         "group 6 'A1234' at character 36: QNH 417.9 hPa"},
        {"KXYZ 010000Z 27005KT 10SM CLR 10/15 A3000", "dew point above the temperature"},
        {"KXYZ 010000Z 27005KT 10SM CLR 10/05 A3000 27010KT",
         "group 7 '27010KT' at character 42: group out of the FM 15 order"},
        {"KXYZ 010000Z 27005KT 10SM 9999 CLR", "group 4 '9999' at character 26: unknown group"},
        {"KXYZ 010000Z 27005KT 10SM -XX CLR", "'-XX' at character 26: unknown group"},
        {"KXYZ 010000Z 27005KT 10SM BKN030 FEW010", "cloud layer below the one before it"},
        {"KXYZ 010000Z 27005KT 10SM FEW01 CLR", "'FEW01' at character 26: unknown group"},
        {"KXYZ 010000Z 27005KT 10SM FEW010 10/05 A3000 RMK T01831094 TX",
         "remark temperature differs"},
        {"EDDF 010000Z NIL 27005KT", "group 3 '27005KT' at character 17: group after NIL"},
        {"KXYZ", "report ends without a time"},
    };
    for (const auto& c : cases) {
        SCOPED_TRACE(c.text);
        Metar m;
        ASSERT_NO_THROW(m = DecodeMetar(c.text));
        EXPECT_TRUE(AnyWarningContains(m, c.warning)) << Warnings(m);
        EXPECT_EQ(m.station, std::string(c.text).substr(0, 4));
    }
}

TEST(MetarMalformed, WarningsAreBounded) {
    std::string text = "KXYZ 010000Z";
    for (int i = 0; i < 1000; ++i) text += " JUNK";
    const Metar m = DecodeMetar(text);
    EXPECT_EQ(m.warnings.size(), kMaxMetarWarnings);
    EXPECT_EQ(m.warnings_suppressed, 1000 - kMaxMetarWarnings);
    EXPECT_NE(m.Describe().find("more warnings"), std::string::npos);
}

// --- files ---------------------------------------------------------------------------------------

std::filesystem::path WriteTemp(const std::string& name, const std::string& text) {
    const auto path = std::filesystem::temp_directory_path() / ("zenith_metar_test_" + name);
    std::ofstream(path, std::ios::binary) << text;
    return path;
}

TEST(MetarFiles, Lines) {
    const auto path = WriteTemp("lines.txt",
                                "# Heathrow, one afternoon\r\n"
                                "EGLL 211720Z 24012KT 9999 FEW035 SCT250 18/09 Q1018\r\n"
                                "\r\n"
                                "EGLL 211750Z 24012KT 9999 FEW035 SCT250 18/09 Q1018 NOSIG\n"
                                "21016KT no station here\n"
                                "EGLL 211820Z 24010KT 9999 JUNK FEW035 17/09 Q1018");
    const MetarFile f = ReadMetarLines(path);
    ASSERT_EQ(f.records.size(), 3u) << f.Summary();
    EXPECT_EQ(f.records[0].line, 2u);
    EXPECT_EQ(f.records[1].line, 4u);
    EXPECT_EQ(f.records[2].line, 6u);
    EXPECT_EQ(f.skipped, 1u);
    ASSERT_EQ(f.first_skipped.size(), 1u);
    EXPECT_NE(f.first_skipped[0].find("lines.txt:5: group 0 '21016KT'"), std::string::npos)
        << f.first_skipped[0];
    EXPECT_EQ(f.warnings, 1u);
    EXPECT_FALSE(f.records[0].time_s);
    std::filesystem::remove(path);
}

// NOAA's station files: the time on the line before the report.
TEST(MetarFiles, NoaaTimeLines) {
    const MetarFile f = ParseMetarLines(
        "2024/07/14 12:00\nLFMY 141200Z AUTO 31010KT 9999 FEW045 29/12 Q1016\n"
        "LFMY 141230Z AUTO 31010KT 9999 FEW045 29/12 Q1016\n",
        "LFMY.TXT");
    ASSERT_EQ(f.records.size(), 2u);
    EXPECT_DOUBLE_EQ(*f.records[0].time_s,
                     geo::UnixSecondsFromCivil(geo::ParseIso8601("2024-07-14T12:00:00Z")));
    EXPECT_FALSE(f.records[1].time_s);
}

TEST(MetarFiles, IemCsv) {
    // The columns of the Iowa Environmental Mesonet's ASOS download (data=metar), reordered.
    const auto path = WriteTemp(
        "iem.csv",
        "\xEF\xBB\xBF"
        "#DEBUG: Format Typ    -> comma\n"
        "valid,station,metar,lat,lon\n"
        "2024-07-14 12:00,LFMY,LFMY 141200Z AUTO 31010KT 9999 FEW045 29/12 Q1016,43.61,5.11\n"
        "2024-07-14 12:30,LFMY,\"LFMY 141230Z AUTO 31012KT 9999 FEW048 30/11 Q1016\",M,M\n"
        "2024-07-14 13:00,LFMY,LFMY 141300Z AUTO 31012KT 9999 NCD 30/11 Q1015\n"
        "2024-07-14 25:00,LFMY,LFMY 141330Z AUTO 31012KT 9999 NCD 30/11 Q1015,43.61,5.11\n"
        "2024-07-14 14:00,LFMY,LFMY 141400Z AUTO 31012KT 9999 NCD 30/11 Q1015,91,5.11\n"
        "2024-07-14 14:30,LFMY,LFMY 141500Z AUTO 31012KT 9999 NCD 30/11 Q1015,43.61,5.11\n");
    const MetarFile f = ReadMetarCsv(path);
    ASSERT_EQ(f.records.size(), 3u) << f.Summary();
    const MetarRecord& r = f.records[0];
    EXPECT_EQ(r.line, 3u);
    EXPECT_EQ(r.archive_station, "LFMY");
    EXPECT_EQ(r.metar.station, "LFMY");
    EXPECT_DOUBLE_EQ(*r.time_s,
                     geo::UnixSecondsFromCivil(geo::ParseIso8601("2024-07-14T12:00:00Z")));
    EXPECT_DOUBLE_EQ(*r.lat_deg, 43.61);
    EXPECT_DOUBLE_EQ(*r.lon_deg, 5.11);
    EXPECT_FALSE(f.records[1].lat_deg);
    EXPECT_EQ(f.records[1].metar.wind->speed_in_unit, 12.0);
    // Skipped: wrong field count (line 5), bad hour (6), latitude 91 (7).
    EXPECT_EQ(f.skipped, 3u);
    ASSERT_EQ(f.first_skipped.size(), 3u);
    EXPECT_NE(f.first_skipped[0].find("iem.csv:5: 3 fields for 5 columns"), std::string::npos)
        << f.Summary();
    EXPECT_NE(f.first_skipped[1].find("iem.csv:6:"), std::string::npos) << f.Summary();
    EXPECT_NE(f.first_skipped[2].find("iem.csv:7: '91' is not a coordinate"), std::string::npos)
        << f.Summary();
    // Line 8's report says 15:00 where the archive says 14:30.
    EXPECT_TRUE(AnyWarningContains(f.records[2].metar, "differs from the valid time"));
    std::filesystem::remove(path);
}

TEST(MetarFiles, Errors) {
    EXPECT_NE(ThrownMessage([] {
                  ParseMetarCsv("station,valid\nLFMY,2024-07-14 12:00\n", "a.csv");
              }).find("a.csv:1: CSV header has no 'metar' column"),
              std::string::npos);
    EXPECT_NE(ThrownMessage([] {
                  ParseMetarCsv("# only a comment\n", "b.csv");
              }).find("b.csv: empty CSV"),
              std::string::npos);
    EXPECT_NE(ThrownMessage([] {
                  ParseMetarLines("\n# nothing\n", "c.txt");
              }).find("c.txt: no usable METAR"),
              std::string::npos);
    EXPECT_NE(ThrownMessage([] {
                  ReadMetarLines("/nonexistent/metar.txt");
              }).find("/nonexistent/metar.txt: cannot read"),
              std::string::npos);
    const std::string long_line(kMaxMetarLineBytes + 1, 'X');
    const MetarFile f =
        ParseMetarLines(long_line + "\nEGLL 211750Z 24012KT 9999 FEW035 18/09 Q1018\n", "d.txt");
    EXPECT_EQ(f.records.size(), 1u);
    EXPECT_NE(f.first_skipped.at(0).find("d.txt:1: line of 65537 characters"), std::string::npos);
}

// Decoding is cheap enough for a replay's archive: a year of half-hourly reports in well under a
// second.
TEST(MetarFiles, ThroughputIsReasonable) {
    std::string text;
    for (int i = 0; i < 17520; ++i) {
        text +=
            "KABC 121755Z AUTO 21016G24KT 180V240 1SM R11/P6000FT -RA BR BKN015 OVC025 06/04 "
            "A2990 RMK AO2 T00640036\n";
    }
    const auto start = std::chrono::steady_clock::now();
    const MetarFile f = ParseMetarLines(text, "year.txt");
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_EQ(f.records.size(), 17520u);
    EXPECT_LT(seconds, 5.0);  // generous: sanitizer builds on shared cores
}

}  // namespace
}  // namespace zenith::weather
