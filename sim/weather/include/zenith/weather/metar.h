// METAR and SPECI reports (WMO No. 306 Vol. I.1 code forms FM 15 / FM 16, and the US forms of
// FAA Order JO 7900.5 / Advisory Circular 00-45) decoded into SI fields.
//
// A report is a list of whitespace-separated groups in the order of FM 15:
//   [METAR|SPECI] [COR] CCCC YYGGggZ [NIL] [AUTO|COR] wind [dndndnVdxdxdx] visibility|CAVOK
//   [RVR...] [present weather...] [sky...] T'T'/T'dT'd Q|A-pressure [RE.. WS.. W../S..]
//   [NOSIG|BECMG ...|TEMPO ...] [RMK ...][=]
// The decoder is forgiving and explicit: a group it cannot decode, or one it does not know, is
// kept out of the result and gives a MetarWarning naming the group, its index (0-based, among the
// report's groups) and its character offset (0-based, in the text given); whatever can be decoded
// is decoded. Only a report without a station (or an empty or oversized one) throws MetarError.
// The decoder never crashes on any input (fuzzed: tests/fuzz/metar_fuzz.cpp) and never uses
// std::regex (its recursion overflows the stack on long input).
//
// What is decoded and what is only kept as text:
//   - trend forecasts (NOSIG, BECMG, TEMPO and what follows) are kept as text in `trend`; a
//     trend's time group without BECMG or TEMPO (FM2000 ...) starts one too, with a warning and
//     trend_kind kNone, so that the forecast's groups are not taken for the observation's;
//   - remarks (RMK ...) are kept as text in `remarks`; only the US T-group (T01830094: tenths of
//     a degree) is decoded, and then replaces the whole-degree temperature and dew point;
//   - wind shear (WS ...), sea state (W15/S4) and runway state (R24/010060) groups are known but
//     not decoded: they are listed in `not_decoded`, without a warning.
//
// Units: every field carries its unit in its name unless it is SI (metres, m/s, degrees Celsius
// are named too, to avoid doubt). Heights of clouds stay in feet, as reported (hundreds of feet
// above the station); base_m() converts.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "zenith/base/error.h"

namespace zenith::weather {

// A report that cannot be decoded at all (no station, empty, longer than kMaxMetarBytes), or a
// METAR file that cannot be read. Messages name the group and its position, or the file and line.
class MetarError : public InputError {
  public:
    using InputError::InputError;
};

inline constexpr std::size_t kMaxMetarBytes = 1u << 16;  // one report, as a file line
inline constexpr std::size_t kMaxMetarWarnings = 32;     // kept per report; the rest counted

inline constexpr double kMetresPerSecondPerKnot = 1852.0 / 3600.0;
inline constexpr double kHectopascalsPerInchOfMercury = 33.8638866667;  // at 0 degC, g0

// Where a group is in the report text.
struct GroupPosition {
    std::size_t index = 0;   // 0-based among the report's whitespace-separated groups
    std::size_t offset = 0;  // 0-based character offset in the text given to DecodeMetar
};

struct MetarWarning {
    std::string group;  // as it appears in the report (at most 40 characters kept)
    GroupPosition position;
    std::string message;
    // "group 5 'XYZ' at character 31: unknown group"
    std::string ToString() const;
};

enum class ReportType { kMetar, kSpeci };

// A value reported as a bound: 9999 (10 km or more), P6SM (more than 6 SM), M1/4SM (less than
// 1/4 SM), RVR P2000 / M0050.
enum class Bound { kExact, kMoreThan, kLessThan };

enum class SpeedUnit { kKnot, kMetrePerSecond, kKilometrePerHour };
std::string_view SpeedUnitCode(SpeedUnit unit);  // "KT", "MPS", "KMH"

struct Wind {
    std::optional<double> direction_deg;  // where it blows from, true north; none: VRB or missing
    bool variable = false;                // VRB
    std::optional<double> speed_m_s;      // none: missing (/////KT)
    std::optional<double> gust_m_s;
    SpeedUnit unit = SpeedUnit::kKnot;  // as reported
    std::optional<double> speed_in_unit;
    std::optional<double> gust_in_unit;
    bool speed_more_than = false;  // P99KT, P49MPS
    // dndndnVdxdxdx: the direction varies between these (clockwise from `from`).
    std::optional<double> variable_from_deg;
    std::optional<double> variable_to_deg;
    bool calm() const { return speed_m_s && *speed_m_s == 0.0; }
};

enum class CompassPoint { kNone, kN, kNE, kE, kSE, kS, kSW, kW, kNW };
std::string_view CompassPointCode(CompassPoint point);

struct Visibility {
    double visibility_m = 0.0;  // prevailing (US) or the WMO horizontal visibility
    Bound bound = Bound::kExact;
    bool statute_miles = false;             // reported in statute miles (US), else metres
    double reported = 0.0;                  // the number as reported: metres or statute miles
    bool no_directional_variation = false;  // NDV (automatic stations)
    CompassPoint direction = CompassPoint::kNone;  // a direction on the prevailing group (rare)
};

// VNVNVNVNDv: the minimum visibility and its direction (4000NE).
struct DirectionalVisibility {
    double visibility_m = 0.0;
    CompassPoint direction = CompassPoint::kNone;
};

struct RunwayVisualRange {
    std::string runway;  // "24", "06L"
    double rvr_m = 0.0;
    Bound bound = Bound::kExact;
    std::optional<double> max_rvr_m;  // 1200V1800: varying between rvr_m and max_rvr_m
    Bound max_bound = Bound::kExact;
    bool feet = false;  // reported in feet (FT)
    char tendency = 0;  // 'U' up, 'D' down, 'N' no change, 0 none
};

enum class Intensity { kLight, kModerate, kHeavy, kVicinity };
enum class Descriptor {
    kNone,
    kShallow,       // MI
    kPatches,       // BC
    kPartial,       // PR
    kLowDrifting,   // DR
    kBlowing,       // BL
    kShowers,       // SH
    kThunderstorm,  // TS
    kFreezing,      // FZ
};
enum class Phenomenon {
    // precipitation
    kDrizzle,               // DZ
    kRain,                  // RA
    kSnow,                  // SN
    kSnowGrains,            // SG
    kIceCrystals,           // IC
    kIcePellets,            // PL
    kHail,                  // GR
    kSmallHail,             // GS
    kUnknownPrecipitation,  // UP
    // obscuration
    kMist,         // BR
    kFog,          // FG
    kSmoke,        // FU
    kVolcanicAsh,  // VA
    kDust,         // DU
    kSand,         // SA
    kHaze,         // HZ
    kSpray,        // PY
    // other
    kDustWhirls,   // PO
    kSqualls,      // SQ
    kFunnelCloud,  // FC
    kSandstorm,    // SS
    kDuststorm,    // DS
};
std::string_view DescriptorCode(Descriptor descriptor);
std::string_view DescriptorName(Descriptor descriptor);
std::string_view PhenomenonCode(Phenomenon phenomenon);
std::string_view PhenomenonName(Phenomenon phenomenon);
bool IsPrecipitation(Phenomenon phenomenon);

// One w'w' group: "+TSRA", "-SHRASN", "VCSH", "FZFG", "BR". An AUTO station's "//" (not
// observed) is not a group: it sets Metar::weather_not_observed.
struct PresentWeather {
    std::string code;  // the group as reported
    Intensity intensity = Intensity::kModerate;
    Descriptor descriptor = Descriptor::kNone;
    std::vector<Phenomenon> phenomena;  // may be empty: "TS", "VCSH"
    bool Has(Phenomenon phenomenon) const;
    bool HasPrecipitation() const;
    std::string Describe() const;  // "heavy thunderstorm with rain"
};

// FEW 1-2 oktas, SCT 3-4, BKN 5-7, OVC 8 (WMO No. 306 FM 15, reg. 15.9.1.3).
enum class Cover { kFew, kScattered, kBroken, kOvercast, kUnknown /* /// from AUTO stations */ };
std::string_view CoverCode(Cover cover);
int MinOktas(Cover cover);  // kUnknown: 1
int MaxOktas(Cover cover);  // kUnknown: 8

enum class ConvectiveCloud { kNone, kCumulonimbus, kToweringCumulus, kUnknown /* /// */ };

struct SkyLayer {
    Cover cover = Cover::kFew;
    std::optional<double> base_ft;  // above the station; none: /// (not measured)
    ConvectiveCloud convective = ConvectiveCloud::kNone;
    std::optional<double> base_m() const;
};

// The sky was reported clear: SKC (observer), CLR (US automatic: nothing below 12 000 ft), NSC
// (no significant cloud), NCD (automatic: no cloud detected).
enum class ClearSky { kNone, kSkc, kClr, kNsc, kNcd };
std::string_view ClearSkyCode(ClearSky clear);

enum class TrendKind { kNone, kNosig, kBecmg, kTempo };

struct ReportTime {
    int day = 1;  // of the month, UTC
    int hour = 0;
    int minute = 0;
};

struct Metar {
    ReportType type = ReportType::kMetar;
    std::string station;  // ICAO location indicator, 4 characters
    std::optional<ReportTime> time;
    bool automatic = false;  // AUTO
    bool corrected = false;  // COR
    bool nil = false;        // NIL: the report is missing

    std::optional<Wind> wind;
    bool cavok = false;  // visibility >= 10 km, no cloud below 5000 ft or the MSA, no CB/TCU,
                         // no significant weather: visibility is then set to 10 km, kMoreThan
    std::optional<Visibility> visibility;
    std::optional<DirectionalVisibility> minimum_visibility;
    std::vector<RunwayVisualRange> rvr;
    std::vector<PresentWeather> weather;
    bool weather_not_observed = false;           // "//" from an automatic station
    bool no_significant_weather = false;         // NSW
    std::vector<PresentWeather> recent_weather;  // RE groups, "RERA" -> code "RA"

    std::vector<SkyLayer> sky;  // bottom to top, as reported
    ClearSky clear = ClearSky::kNone;
    bool vertical_visibility_reported = false;     // VVhhh or VV///
    std::optional<double> vertical_visibility_ft;  // none with VV///
    bool sky_not_observed = false;                 // "//////" from an automatic station

    std::optional<double> temperature_c;
    std::optional<double> dew_point_c;
    bool temperature_from_remarks = false;  // tenths from the RMK T-group replaced whole degrees

    std::optional<double> qnh_hpa;         // from Q or A
    std::optional<double> altimeter_inhg;  // when reported as A (US)

    TrendKind trend_kind = TrendKind::kNone;
    std::string trend;                     // the trend forecast as text, from its first indicator
    std::string remarks;                   // the text after RMK
    std::vector<std::string> not_decoded;  // known groups kept as text (WS, W../S.., R../......)

    std::vector<MetarWarning> warnings;
    std::size_t warnings_suppressed = 0;  // beyond kMaxMetarWarnings

    // The lowest BKN or OVC layer's base, or the vertical visibility: the US ceiling, feet.
    std::optional<double> ceiling_ft() const;
    // A few lines of plain text: every decoded field with its unit, then the warnings.
    std::string Describe() const;
};

// Decodes one report; see the file comment. Throws MetarError when there is no station.
Metar DecodeMetar(std::string_view text);

}  // namespace zenith::weather
