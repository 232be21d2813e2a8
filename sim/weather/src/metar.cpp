// METAR decoder; the forms are in metar.h. Each group kind has a small hand-written matcher
// (no std::regex); codes (weather, cover, units) are looked up in the tables below.
#include "zenith/weather/metar.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <functional>

#include "zenith/base/units.h"

namespace zenith::weather {

namespace {

// --- tables -----------------------------------------------------------------------------------

template <class T>
struct Code {
    std::string_view code;
    T value;
    std::string_view name;
};

constexpr std::array<Code<Descriptor>, 8> kDescriptors{{
    {"MI", Descriptor::kShallow, "shallow"},
    {"BC", Descriptor::kPatches, "patches of"},
    {"PR", Descriptor::kPartial, "partial"},
    {"DR", Descriptor::kLowDrifting, "low drifting"},
    {"BL", Descriptor::kBlowing, "blowing"},
    {"SH", Descriptor::kShowers, "showers of"},
    {"TS", Descriptor::kThunderstorm, "thunderstorm"},
    {"FZ", Descriptor::kFreezing, "freezing"},
}};

struct PhenomenonCodeEntry {
    std::string_view code;
    Phenomenon value;
    std::string_view name;
    bool precipitation;
};

constexpr std::array<PhenomenonCodeEntry, 22> kPhenomena{{
    {"DZ", Phenomenon::kDrizzle, "drizzle", true},
    {"RA", Phenomenon::kRain, "rain", true},
    {"SN", Phenomenon::kSnow, "snow", true},
    {"SG", Phenomenon::kSnowGrains, "snow grains", true},
    {"IC", Phenomenon::kIceCrystals, "ice crystals", true},
    {"PL", Phenomenon::kIcePellets, "ice pellets", true},
    {"GR", Phenomenon::kHail, "hail", true},
    {"GS", Phenomenon::kSmallHail, "small hail or snow pellets", true},
    {"UP", Phenomenon::kUnknownPrecipitation, "unknown precipitation", true},
    {"BR", Phenomenon::kMist, "mist", false},
    {"FG", Phenomenon::kFog, "fog", false},
    {"FU", Phenomenon::kSmoke, "smoke", false},
    {"VA", Phenomenon::kVolcanicAsh, "volcanic ash", false},
    {"DU", Phenomenon::kDust, "widespread dust", false},
    {"SA", Phenomenon::kSand, "sand", false},
    {"HZ", Phenomenon::kHaze, "haze", false},
    {"PY", Phenomenon::kSpray, "spray", false},
    {"PO", Phenomenon::kDustWhirls, "dust or sand whirls", false},
    {"SQ", Phenomenon::kSqualls, "squalls", false},
    {"FC", Phenomenon::kFunnelCloud, "funnel cloud", false},
    {"SS", Phenomenon::kSandstorm, "sandstorm", false},
    {"DS", Phenomenon::kDuststorm, "duststorm", false},
}};

constexpr std::array<Code<Cover>, 4> kCovers{{
    {"FEW", Cover::kFew, "few"},
    {"SCT", Cover::kScattered, "scattered"},
    {"BKN", Cover::kBroken, "broken"},
    {"OVC", Cover::kOvercast, "overcast"},
}};

constexpr std::array<Code<ClearSky>, 4> kClearSkies{{
    {"SKC", ClearSky::kSkc, "sky clear"},
    {"CLR", ClearSky::kClr, "no cloud below 12000 ft (automatic)"},
    {"NSC", ClearSky::kNsc, "no significant cloud"},
    {"NCD", ClearSky::kNcd, "no cloud detected (automatic)"},
}};

struct SpeedUnitEntry {
    std::string_view code;
    SpeedUnit unit;
    double m_s_per_unit;
};
constexpr std::array<SpeedUnitEntry, 3> kSpeedUnits{{
    {"KT", SpeedUnit::kKnot, kMetresPerSecondPerKnot},
    {"MPS", SpeedUnit::kMetrePerSecond, 1.0},
    {"KMH", SpeedUnit::kKilometrePerHour, 1.0 / 3.6},
}};

constexpr std::array<Code<CompassPoint>, 8> kCompassPoints{{
    {"NE", CompassPoint::kNE, "north-east"},
    {"SE", CompassPoint::kSE, "south-east"},
    {"SW", CompassPoint::kSW, "south-west"},
    {"NW", CompassPoint::kNW, "north-west"},
    {"N", CompassPoint::kN, "north"},
    {"E", CompassPoint::kE, "east"},
    {"S", CompassPoint::kS, "south"},
    {"W", CompassPoint::kW, "west"},
}};

constexpr std::array<Code<TrendKind>, 3> kTrends{{
    {"NOSIG", TrendKind::kNosig, "no significant change"},
    {"BECMG", TrendKind::kBecmg, "becoming"},
    {"TEMPO", TrendKind::kTempo, "temporarily"},
}};

template <class Table>
auto Find(const Table& table, std::string_view code) -> const typename Table::value_type* {
    for (const auto& entry : table) {
        if (entry.code == code) return &entry;
    }
    return nullptr;
}

template <class Table, class T>
auto FindValue(const Table& table, T value) -> const typename Table::value_type* {
    for (const auto& entry : table) {
        if (entry.value == value) return &entry;
    }
    return nullptr;
}

// --- small text helpers -----------------------------------------------------------------------

bool IsDigit(char c) { return c >= '0' && c <= '9'; }
bool IsUpper(char c) { return c >= 'A' && c <= 'Z'; }
bool AllDigits(std::string_view s) {
    return !s.empty() && std::all_of(s.begin(), s.end(), IsDigit);
}
bool AllSlashes(std::string_view s) {
    return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) { return c == '/'; });
}
bool StartsWith(std::string_view s, std::string_view prefix) {
    return s.substr(0, prefix.size()) == prefix;
}
bool EndsWith(std::string_view s, std::string_view suffix) {
    return s.size() >= suffix.size() && s.substr(s.size() - suffix.size()) == suffix;
}
bool IsSpace(char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}

// A run of at most 9 digits as an int (so no overflow); nullopt otherwise.
std::optional<int> ToInt(std::string_view s) {
    if (!AllDigits(s) || s.size() > 9) return std::nullopt;
    int value = 0;
    std::from_chars(s.data(), s.data() + s.size(), value);
    return value;
}

// Takes a run of digits of length in [min, max] from the front of s.
std::optional<int> TakeInt(std::string_view& s, std::size_t min, std::size_t max) {
    std::size_t n = 0;
    while (n < s.size() && n < max && IsDigit(s[n])) ++n;
    if (n < min) return std::nullopt;
    const auto value = ToInt(s.substr(0, n));
    s.remove_prefix(n);
    return value;
}

bool Take(std::string_view& s, std::string_view prefix) {
    if (!StartsWith(s, prefix)) return false;
    s.remove_prefix(prefix.size());
    return true;
}

std::string Clip(std::string_view s) {
    constexpr std::size_t kMaxShown = 40;
    if (s.size() <= kMaxShown) return std::string(s);
    return std::string(s.substr(0, kMaxShown)) + "...";
}

struct Group {
    std::string_view text;
    GroupPosition position;
};

std::vector<Group> Split(std::string_view text) {
    std::vector<Group> groups;
    std::size_t i = 0;
    while (i < text.size()) {
        while (i < text.size() && IsSpace(text[i])) ++i;
        const std::size_t start = i;
        while (i < text.size() && !IsSpace(text[i])) ++i;
        if (i > start) groups.push_back({text.substr(start, i - start), {groups.size(), start}});
    }
    // The end-of-message '=' (WMO bulletins) is not part of the last group.
    if (!groups.empty()) {
        Group& last = groups.back();
        while (!last.text.empty() && last.text.back() == '=') last.text.remove_suffix(1);
        if (last.text.empty()) groups.pop_back();
    }
    return groups;
}

// --- group decoders ---------------------------------------------------------------------------
// Each returns nullopt when the group is not of its kind at all; a group of the kind with a bad
// value is reported through `warn` and still counts as recognised.

using Warn = std::function<void(std::string)>;

std::optional<double> SpeedNumber(std::string_view& s, bool& more_than) {
    more_than = Take(s, "P");
    if (Take(s, "//")) return std::nullopt;
    const auto v = TakeInt(s, 2, 3);
    if (!v) return std::nullopt;
    return static_cast<double>(*v);
}

// dddff(f)(Gfmfm(fm))KT|MPS|KMH, VRBffKT, 00000KT, /////KT.
std::optional<Wind> DecodeWind(std::string_view s, const Warn& warn) {
    const SpeedUnitEntry* unit = nullptr;
    for (const auto& u : kSpeedUnits) {
        if (EndsWith(s, u.code)) unit = &u;
    }
    if (!unit || s.size() < 5 + unit->code.size()) return std::nullopt;
    s.remove_suffix(unit->code.size());
    Wind wind;
    wind.unit = unit->unit;
    std::optional<int> direction;
    if (Take(s, "VRB")) {
        wind.variable = true;
    } else if (!Take(s, "///")) {
        direction = TakeInt(s, 3, 3);
        if (!direction) return std::nullopt;
    }
    if (AllSlashes(s)) {
        wind.direction_deg = direction;
        return wind;  // speed missing
    }
    bool more_than = false;
    const auto speed = SpeedNumber(s, more_than);
    if (!speed && !s.empty() && s.front() != 'G') return std::nullopt;
    wind.speed_in_unit = speed;
    wind.speed_more_than = more_than;
    if (Take(s, "G")) {
        bool gust_more = false;
        const auto gust = SpeedNumber(s, gust_more);
        if (!gust) return std::nullopt;
        wind.gust_in_unit = gust;
    }
    if (!s.empty()) return std::nullopt;
    if (direction) {
        if (*direction > 360) {
            warn(fmt::format("wind direction {} deg is out of range (expected [0, 360] deg)",
                             *direction));
        } else {
            wind.direction_deg = *direction;
        }
    }
    if (wind.speed_in_unit) wind.speed_m_s = *wind.speed_in_unit * unit->m_s_per_unit;
    if (wind.gust_in_unit) wind.gust_m_s = *wind.gust_in_unit * unit->m_s_per_unit;
    return wind;
}

// dndndnVdxdxdx
bool DecodeWindVariation(std::string_view s, Wind& wind, const Warn& warn) {
    if (s.size() != 7 || s[3] != 'V') return false;
    const auto from = ToInt(s.substr(0, 3));
    const auto to = ToInt(s.substr(4, 3));
    if (!from || !to) return false;
    if (*from > 360 || *to > 360) {
        warn("wind direction variation out of range (expected [0, 360] deg)");
        return true;
    }
    wind.variable_from_deg = *from;
    wind.variable_to_deg = *to;
    return true;
}

CompassPoint TakeCompassPoint(std::string_view& s) {
    for (const auto& p : kCompassPoints) {
        if (s == p.code) {
            s.remove_prefix(p.code.size());
            return p.value;
        }
    }
    return CompassPoint::kNone;
}

// VVVV, VVVVNDV, VVVVDv (metres); 9999 is 10 km or more, 0000 less than 50 m.
struct MetricVisibility {
    int metres;
    CompassPoint direction = CompassPoint::kNone;
    bool ndv = false;
};
std::optional<MetricVisibility> DecodeMetricVisibility(std::string_view s) {
    if (s.size() < 4) return std::nullopt;
    const auto v = ToInt(s.substr(0, 4));
    if (!v) return std::nullopt;
    s.remove_prefix(4);
    MetricVisibility out{*v};
    if (s == "NDV") {
        out.ndv = true;
        return out;
    }
    if (!s.empty()) {
        out.direction = TakeCompassPoint(s);
        if (out.direction == CompassPoint::kNone || !s.empty()) return std::nullopt;
    }
    return out;
}

Visibility VisibilityFromMetres(int metres) {
    Visibility v;
    v.reported = metres;
    v.visibility_m = metres;
    if (metres >= 9999) {
        v.visibility_m = 10000.0;
        v.bound = Bound::kMoreThan;
    } else if (metres == 0) {
        v.visibility_m = 50.0;  // FM 15 reg. 15.6.3: 0000 is "less than 50 m"
        v.bound = Bound::kLessThan;
    }
    return v;
}

// [P|M](n|n/d|nn/dd)SM; `whole` is a preceding whole-miles group ("1 1/2SM").
std::optional<Visibility> DecodeMilesVisibility(std::string_view s, std::optional<int> whole,
                                                const Warn& warn) {
    if (!EndsWith(s, "SM")) return std::nullopt;
    s.remove_suffix(2);
    Visibility v;
    v.statute_miles = true;
    if (Take(s, "P")) {
        v.bound = Bound::kMoreThan;
    } else if (Take(s, "M")) {
        v.bound = Bound::kLessThan;
    }
    const auto a = TakeInt(s, 1, 3);
    if (!a) return std::nullopt;
    double miles = *a;
    if (Take(s, "/")) {
        const auto b = TakeInt(s, 1, 3);
        if (!b || !s.empty()) return std::nullopt;
        if (*b == 0) {
            warn("zero denominator in a statute-mile fraction");
            return Visibility{};
        }
        miles = static_cast<double>(*a) / *b;
    }
    if (!s.empty()) return std::nullopt;
    if (whole) miles += *whole;
    v.reported = miles;
    v.visibility_m = miles * kMetresPerStatuteMile;
    return v;
}

// R24/P2000, R06L/1200V1800FT/U, R24/M0050N.
enum class RunwayGroup { kNone, kRvr, kState, kMissing };
RunwayGroup DecodeRunway(std::string_view s, RunwayVisualRange& rvr) {
    if (!Take(s, "R")) return RunwayGroup::kNone;
    const auto runway_number = TakeInt(s, 2, 2);
    if (!runway_number) return RunwayGroup::kNone;
    std::string runway = fmt::format("{:02d}", *runway_number);
    if (!s.empty() && (s[0] == 'L' || s[0] == 'C' || s[0] == 'R')) {
        runway += s[0];
        s.remove_prefix(1);
    }
    if (!Take(s, "/")) return RunwayGroup::kNone;
    // Runway state (FM 15 reg. 15.13.6.1): deposit, extent, depth and braking, E C eeBB, each
    // element '/' where not reported (R24L/590350, R14/9///95); CLRD and SNOCLO in their place.
    const bool state_digits =
        s.size() == 6 && !AllSlashes(s) &&
        std::all_of(s.begin(), s.end(), [](char c) { return IsDigit(c) || c == '/'; });
    if (state_digits || StartsWith(s, "CLRD") || s == "SNOCLO") return RunwayGroup::kState;
    if (AllSlashes(s)) return RunwayGroup::kMissing;
    rvr.runway = std::move(runway);
    auto take_value = [&s](Bound& bound) -> std::optional<double> {
        bound = Take(s, "P") ? Bound::kMoreThan : Take(s, "M") ? Bound::kLessThan : Bound::kExact;
        const auto v = TakeInt(s, 4, 4);
        if (!v) return std::nullopt;
        return static_cast<double>(*v);
    };
    const auto value = take_value(rvr.bound);
    if (!value) return RunwayGroup::kNone;
    std::optional<double> max;
    if (Take(s, "V")) {
        max = take_value(rvr.max_bound);
        if (!max) return RunwayGroup::kNone;
    }
    rvr.feet = Take(s, "FT");
    Take(s, "/");
    if (s.size() == 1 && (s[0] == 'U' || s[0] == 'D' || s[0] == 'N')) {
        rvr.tendency = s[0];
        s.remove_prefix(1);
    }
    if (!s.empty()) return RunwayGroup::kNone;
    const double scale = rvr.feet ? kMetresPerFoot : 1.0;
    rvr.rvr_m = *value * scale;
    if (max) rvr.max_rvr_m = *max * scale;
    return RunwayGroup::kRvr;
}

// [-|+|VC][descriptor][phenomena...]
std::optional<PresentWeather> DecodeWeather(std::string_view s) {
    if (s.empty() || s.size() > 12) return std::nullopt;
    PresentWeather w;
    w.code = std::string(s);
    if (Take(s, "-")) {
        w.intensity = Intensity::kLight;
    } else if (Take(s, "+")) {
        w.intensity = Intensity::kHeavy;
    } else if (Take(s, "VC")) {
        w.intensity = Intensity::kVicinity;
    }
    if (s.size() >= 2) {
        if (const auto* d = Find(kDescriptors, s.substr(0, 2))) {
            w.descriptor = d->value;
            s.remove_prefix(2);
        }
    }
    while (s.size() >= 2) {
        const auto* p = Find(kPhenomena, s.substr(0, 2));
        if (!p) return std::nullopt;
        w.phenomena.push_back(p->value);
        s.remove_prefix(2);
    }
    if (!s.empty()) return std::nullopt;
    // A descriptor alone is a group only for TS (thunderstorm) and, in the vicinity, SH.
    if (w.phenomena.empty()) {
        const bool alone_ok =
            w.descriptor == Descriptor::kThunderstorm ||
            (w.descriptor == Descriptor::kShowers && w.intensity == Intensity::kVicinity);
        if (!alone_ok) return std::nullopt;
    }
    return w;
}

// NsNsNshshshs[CB|TCU|///] or ///hshshs...; VVhshshs.
std::optional<SkyLayer> DecodeSkyLayer(std::string_view s) {
    SkyLayer layer;
    if (s.size() < 6) return std::nullopt;
    if (const auto* c = Find(kCovers, s.substr(0, 3))) {
        layer.cover = c->value;
    } else if (s.substr(0, 3) == "///") {
        layer.cover = Cover::kUnknown;
    } else {
        return std::nullopt;
    }
    s.remove_prefix(3);
    if (!Take(s, "///")) {
        const auto h = TakeInt(s, 3, 3);
        if (!h) return std::nullopt;
        layer.base_ft = *h * 100.0;
    }
    if (s == "CB") {
        layer.convective = ConvectiveCloud::kCumulonimbus;
    } else if (s == "TCU") {
        layer.convective = ConvectiveCloud::kToweringCumulus;
    } else if (s == "///") {
        layer.convective = ConvectiveCloud::kUnknown;
    } else if (!s.empty()) {
        return std::nullopt;
    }
    return layer;
}

// M?dd or // -> value; returns false if neither.
bool TakeTemperature(std::string_view& s, std::optional<double>& value) {
    if (Take(s, "//")) {
        value.reset();
        return true;
    }
    const bool negative = Take(s, "M");
    const auto v = TakeInt(s, 2, 2);
    if (!v) return false;
    value = negative ? -*v : *v;
    return true;
}

// US remark T-group: T snTTT snTdTdTd, tenths of degC, sn 1 = negative.
bool DecodeTenthsGroup(std::string_view s, double& t, std::optional<double>& td) {
    if ((s.size() != 5 && s.size() != 9) || s[0] != 'T' || !AllDigits(s.substr(1))) return false;
    auto tenths = [](std::string_view g) -> std::optional<double> {
        if (g[0] != '0' && g[0] != '1') return std::nullopt;
        const double v = *ToInt(g.substr(1)) / 10.0;
        return g[0] == '1' ? -v : v;
    };
    const auto a = tenths(s.substr(1, 4));
    if (!a) return false;
    t = *a;
    if (s.size() == 9) {
        td = tenths(s.substr(5, 4));
        if (!td) return false;
    }
    return true;
}

// --- the report -------------------------------------------------------------------------------

// The order of FM 15 groups: a group is looked for from the current stage on, then, if not
// found, in the stages before (and decoded with an "out of order" warning).
enum Stage {
    kModifier,
    kWind,
    kWindVariation,
    kVisibility,
    kMinimumVisibility,
    kRvr,
    kWeather,
    kSky,
    kTemperature,
    kPressure,
    kSupplementary,
    kStageCount,
};

class Decoder {
  public:
    explicit Decoder(std::string_view text) : groups_(Split(text)) {}

    Metar Run() {
        if (groups_.empty()) throw MetarError("empty METAR report (no groups)");
        std::size_t i = 0;
        if (groups_[i].text == "METAR" || groups_[i].text == "SPECI") {
            m_.type = groups_[i].text == "SPECI" ? ReportType::kSpeci : ReportType::kMetar;
            ++i;
        }
        if (i < groups_.size() && groups_[i].text == "COR") {
            m_.corrected = true;
            ++i;
        }
        if (i >= groups_.size())
            throw MetarError("METAR report has no station (ends after its type)");
        const std::string_view station = groups_[i].text;
        if (!IsStation(station)) {
            throw MetarError(fmt::format(
                "{}: expected the station (4 letters or digits, starting with a letter)",
                Where(groups_[i])));
        }
        m_.station = std::string(station);
        ++i;
        if (i < groups_.size() && DecodeTime(groups_[i])) ++i;
        if (!m_.time) {
            if (i < groups_.size()) {
                Warning(groups_[i], "expected the time of the report (DDHHMMZ)");
            } else {
                m_.warnings.push_back(
                    {"", {groups_.size(), 0}, "report ends without a time (DDHHMMZ)"});
            }
        }
        for (; i < groups_.size(); ++i) {
            const Group& g = groups_[i];
            if (g.text == "RMK") {
                Remarks(i + 1);
                break;
            }
            const bool bare_time = IsTrendTime(g.text);
            if (bare_time) {
                Warning(g,
                        "a trend's time group without BECMG or TEMPO before it: the groups "
                        "from here on are taken as the trend (forecast), not the observation");
            }
            if (bare_time || Find(kTrends, g.text)) {
                i = Trend(i);
                if (i < groups_.size()) {
                    Remarks(i + 1);
                }
                break;
            }
            if (m_.nil) {
                Warning(g, "group after NIL (a missing report has no body)");
                continue;
            }
            i = Body(i);
        }
        return std::move(m_);
    }

  private:
    static bool IsStation(std::string_view s) {
        return s.size() == 4 && IsUpper(s[0]) &&
               std::all_of(s.begin(), s.end(), [](char c) { return IsUpper(c) || IsDigit(c); });
    }

    static std::string Where(const Group& g) {
        return fmt::format("group {} '{}' at character {}", g.position.index, Clip(g.text),
                           g.position.offset);
    }

    void Warning(const Group& g, std::string message) {
        if (m_.warnings.size() >= kMaxMetarWarnings) {
            ++m_.warnings_suppressed;
            return;
        }
        m_.warnings.push_back({Clip(g.text), g.position, std::move(message)});
    }

    bool DecodeTime(const Group& g) {
        const std::string_view s = g.text;
        if (s.size() != 7 || s[6] != 'Z' || !AllDigits(s.substr(0, 6))) return false;
        const ReportTime t{*ToInt(s.substr(0, 2)), *ToInt(s.substr(2, 2)), *ToInt(s.substr(4, 2))};
        if (t.day < 1 || t.day > 31 || t.hour > 23 || t.minute > 59) {
            Warning(g, "time out of range (expected day 01-31, hour 00-23, minute 00-59)");
            return true;
        }
        m_.time = t;
        return true;
    }

    // Decodes group i (and a following group it needs, "1 1/2SM"); returns the last index used.
    std::size_t Body(std::size_t i) {
        const Group& g = groups_[i];
        for (int pass = 0; pass < 2; ++pass) {
            const int from = pass == 0 ? stage_ : 0;
            const int to = pass == 0 ? kStageCount : stage_;
            for (int s = from; s < to; ++s) {
                std::size_t used = i;
                if (!TryStage(static_cast<Stage>(s), i, used)) continue;
                if (pass == 1) {
                    Warning(g, "group out of the FM 15 order (decoded anyway)");
                } else {
                    stage_ = s;
                }
                return used;
            }
        }
        Warning(g, "unknown group");
        return i;
    }

    bool TryStage(Stage stage, std::size_t i, std::size_t& used) {
        const Group& g = groups_[i];
        const std::string_view s = g.text;
        const Warn warn = [this, &g](std::string message) { Warning(g, std::move(message)); };
        switch (stage) {
            case kModifier:
                if (s == "AUTO") {
                    m_.automatic = true;
                } else if (s == "COR" || s == "CCA" || s == "CCB") {
                    m_.corrected = true;
                } else if (s == "NIL") {
                    m_.nil = true;
                } else {
                    return false;
                }
                return true;
            case kWind: {
                auto wind = DecodeWind(s, warn);
                if (!wind) return false;
                if (m_.wind) {
                    Warning(g, "second wind group (ignored)");
                } else {
                    m_.wind = std::move(wind);
                }
                return true;
            }
            case kWindVariation: {
                if (!m_.wind) return false;
                return DecodeWindVariation(s, *m_.wind, warn);
            }
            case kVisibility:
                return TryVisibility(i, used, warn);
            case kMinimumVisibility: {
                if (!m_.visibility || m_.minimum_visibility) return false;
                const auto v = DecodeMetricVisibility(s);
                if (!v || v->direction == CompassPoint::kNone) return false;
                m_.minimum_visibility =
                    DirectionalVisibility{static_cast<double>(v->metres), v->direction};
                return true;
            }
            case kRvr: {
                RunwayVisualRange rvr;
                switch (DecodeRunway(s, rvr)) {
                    case RunwayGroup::kNone:
                        return false;
                    case RunwayGroup::kRvr:
                        if (m_.rvr.size() < 16) m_.rvr.push_back(std::move(rvr));
                        return true;
                    case RunwayGroup::kState:  // supplementary, after QNH
                        return false;
                    case RunwayGroup::kMissing:
                        return true;
                }
                return false;
            }
            case kWeather: {
                if (s == "//") {
                    m_.weather_not_observed = true;
                    return true;
                }
                if (s == "NSW") {
                    m_.no_significant_weather = true;
                    return true;
                }
                auto w = DecodeWeather(s);
                if (!w) return false;
                if (m_.weather.size() < 16) m_.weather.push_back(std::move(*w));
                return true;
            }
            case kSky:
                return TrySky(g, warn);
            case kTemperature: {
                if (s == "/////") return true;  // both missing (automatic stations)
                std::string_view rest = s;
                std::optional<double> t, td;
                if (!TakeTemperature(rest, t) || !Take(rest, "/")) return false;
                if (!rest.empty() && !TakeTemperature(rest, td)) return false;
                if (!rest.empty()) return false;
                if (m_.temperature_c || m_.dew_point_c) {
                    Warning(g, "second temperature group (ignored)");
                    return true;
                }
                if (t && td && *td > *t) {
                    Warning(g, "dew point above the temperature (kept as reported)");
                }
                m_.temperature_c = t;
                m_.dew_point_c = td;
                return true;
            }
            case kPressure:
                return TryPressure(g, warn);
            case kSupplementary:
                return TrySupplementary(i, used);
            case kStageCount:
                break;
        }
        return false;
    }

    bool TryVisibility(std::size_t i, std::size_t& used, const Warn& warn) {
        const std::string_view s = groups_[i].text;
        std::optional<Visibility> v;
        if (s == "CAVOK") {
            m_.cavok = true;
            v = VisibilityFromMetres(9999);
        } else if (s == "////" || s == "////SM") {
            return true;  // not observed
        } else if (const auto metric = DecodeMetricVisibility(s)) {
            if (m_.visibility) return false;  // a minimum visibility, or a second group
            v = VisibilityFromMetres(metric->metres);
            v->no_directional_variation = metric->ndv;
            v->direction = metric->direction;
        } else if (s.size() <= 2 && AllDigits(s) && i + 1 < groups_.size() &&
                   EndsWith(groups_[i + 1].text, "SM") &&
                   groups_[i + 1].text.find('/') != std::string_view::npos &&
                   IsDigit(groups_[i + 1].text[0])) {
            // "1 1/2SM": whole miles and a fraction in two groups.
            v = DecodeMilesVisibility(groups_[i + 1].text, ToInt(s), warn);
            if (!v) return false;
            used = i + 1;
        } else {
            v = DecodeMilesVisibility(s, std::nullopt, warn);
            if (!v) return false;
        }
        if (m_.visibility) {
            Warning(groups_[i], "second visibility group (ignored)");
            return true;
        }
        m_.visibility = v;
        return true;
    }

    bool TrySky(const Group& g, const Warn& warn) {
        const std::string_view s = g.text;
        if (const auto* c = Find(kClearSkies, s)) {
            m_.clear = c->value;
            return true;
        }
        if (s == "//////") {
            m_.sky_not_observed = true;
            return true;
        }
        if (StartsWith(s, "VV") && s.size() == 5) {
            std::string_view rest = s.substr(2);
            m_.vertical_visibility_reported = true;
            if (rest == "///") return true;
            const auto h = ToInt(rest);
            if (!h) {
                m_.vertical_visibility_reported = false;
                return false;
            }
            m_.vertical_visibility_ft = *h * 100.0;
            return true;
        }
        auto layer = DecodeSkyLayer(s);
        if (!layer) return false;
        if (m_.sky.size() >= 8) {
            warn("more than 8 cloud layers (ignored)");
            return true;
        }
        if (!m_.sky.empty() && layer->base_ft && m_.sky.back().base_ft &&
            *layer->base_ft < *m_.sky.back().base_ft) {
            warn("cloud layer below the one before it (kept as reported)");
        }
        m_.sky.push_back(*layer);
        return true;
    }

    bool TryPressure(const Group& g, const Warn& warn) {
        std::string_view s = g.text;
        const bool q = StartsWith(s, "Q");
        const bool a = StartsWith(s, "A");
        if ((!q && !a) || s.size() != 5) return false;
        s.remove_prefix(1);
        if (s == "////") return true;
        const auto v = ToInt(s);
        if (!v) return false;
        double hpa = *v;
        if (a) {
            m_.altimeter_inhg = *v / 100.0;
            hpa = *m_.altimeter_inhg * kHectopascalsPerInchOfMercury;
        }
        if (!(hpa >= 850.0 && hpa <= 1090.0)) {
            warn(fmt::format("QNH {:.1f} hPa is out of range (expected [850, 1090] hPa)", hpa));
            m_.altimeter_inhg.reset();
            return true;
        }
        if (m_.qnh_hpa) {
            warn("second pressure group (ignored)");
            return true;
        }
        m_.qnh_hpa = hpa;
        return true;
    }

    // Recent weather (REw'w'), wind shear (WS RWY24, WS R24, WS ALL RWY), sea (W15/S4, W15/H12),
    // runway state (R24L/590350, R/SNOCLO).
    bool TrySupplementary(std::size_t i, std::size_t& used) {
        const std::string_view s = groups_[i].text;
        RunwayVisualRange unused;
        if (s == "R/SNOCLO" || DecodeRunway(s, unused) == RunwayGroup::kState) {
            NotDecoded(s);
            return true;
        }
        if (StartsWith(s, "RE") && s.size() > 2) {
            auto w = DecodeWeather(s.substr(2));
            if (!w) return false;
            if (m_.recent_weather.size() < 16) m_.recent_weather.push_back(std::move(*w));
            return true;
        }
        if (s == "WS") {
            std::string text(s);
            used = i;
            while (used + 1 < groups_.size() &&
                   (groups_[used + 1].text == "ALL" || groups_[used + 1].text == "RWY" ||
                    (StartsWith(groups_[used + 1].text, "R") && groups_[used + 1].text != "RMK"))) {
                ++used;
                text += ' ';
                text += groups_[used].text;
                if (groups_[used].text != "ALL") break;
            }
            NotDecoded(text);
            return true;
        }
        if (s.size() >= 5 && s[0] == 'W' && (IsDigit(s[1]) || s[1] == 'M' || s[1] == '/') &&
            (s.find("/S") != std::string_view::npos || s.find("/H") != std::string_view::npos)) {
            NotDecoded(s);
            return true;
        }
        return false;
    }

    void NotDecoded(std::string_view s) {
        if (m_.not_decoded.size() < 16) m_.not_decoded.emplace_back(Clip(s));
    }

    // A trend's time group (FM 15 reg. 15.14): FM, TL or AT and the time HHMM. No group of the
    // body has this form.
    static bool IsTrendTime(std::string_view s) {
        return s.size() == 6 &&
               (StartsWith(s, "FM") || StartsWith(s, "TL") || StartsWith(s, "AT")) &&
               AllDigits(s.substr(2));
    }

    // From the trend indicator (or a trend's time group without one) at i to RMK (or the end);
    // returns RMK's index or the end.
    std::size_t Trend(std::size_t i) {
        if (const auto* kind = Find(kTrends, groups_[i].text)) m_.trend_kind = kind->value;
        std::size_t j = i;
        while (j < groups_.size() && groups_[j].text != "RMK") ++j;
        m_.trend = Join(i, j);
        return j;
    }

    void Remarks(std::size_t from) {
        m_.remarks = Join(from, groups_.size());
        for (std::size_t j = from; j < groups_.size(); ++j) {
            double t = 0.0;
            std::optional<double> td;
            if (!DecodeTenthsGroup(groups_[j].text, t, td)) continue;
            if (m_.temperature_c && std::abs(*m_.temperature_c - t) > 1.0) {
                Warning(groups_[j],
                        "remark temperature differs from the body's by more than 1 degC");
                continue;
            }
            m_.temperature_c = t;
            if (td) m_.dew_point_c = td;
            m_.temperature_from_remarks = true;
            break;
        }
    }

    std::string Join(std::size_t from, std::size_t to) const {
        std::string out;
        for (std::size_t j = from; j < to && j < groups_.size(); ++j) {
            if (!out.empty()) out += ' ';
            out += groups_[j].text;
        }
        return out;
    }

    std::vector<Group> groups_;
    Metar m_;
    int stage_ = kModifier;
};

std::string FormatNumber(double v) {
    if (v == std::floor(v) && std::abs(v) < 1e9) return fmt::format("{:.0f}", v);
    return fmt::format("{:.2f}", v);
}

std::string_view BoundText(Bound b) {
    switch (b) {
        case Bound::kMoreThan:
            return "more than ";
        case Bound::kLessThan:
            return "less than ";
        case Bound::kExact:
            break;
    }
    return "";
}

}  // namespace

std::string MetarWarning::ToString() const {
    return fmt::format("group {} '{}' at character {}: {}", position.index, group, position.offset,
                       message);
}

std::string_view SpeedUnitCode(SpeedUnit unit) {
    for (const auto& u : kSpeedUnits) {
        if (u.unit == unit) return u.code;
    }
    return "?";
}

std::string_view CompassPointCode(CompassPoint point) {
    const auto* p = FindValue(kCompassPoints, point);
    return p ? p->code : "";
}

std::string_view DescriptorCode(Descriptor descriptor) {
    const auto* d = FindValue(kDescriptors, descriptor);
    return d ? d->code : "";
}
std::string_view DescriptorName(Descriptor descriptor) {
    const auto* d = FindValue(kDescriptors, descriptor);
    return d ? d->name : "";
}
std::string_view PhenomenonCode(Phenomenon phenomenon) {
    const auto* p = FindValue(kPhenomena, phenomenon);
    return p ? p->code : "";
}
std::string_view PhenomenonName(Phenomenon phenomenon) {
    const auto* p = FindValue(kPhenomena, phenomenon);
    return p ? p->name : "";
}
bool IsPrecipitation(Phenomenon phenomenon) {
    const auto* p = FindValue(kPhenomena, phenomenon);
    return p && p->precipitation;
}

bool PresentWeather::Has(Phenomenon phenomenon) const {
    return std::find(phenomena.begin(), phenomena.end(), phenomenon) != phenomena.end();
}
bool PresentWeather::HasPrecipitation() const {
    return std::any_of(phenomena.begin(), phenomena.end(), IsPrecipitation);
}

std::string PresentWeather::Describe() const {
    std::string out;
    switch (intensity) {
        case Intensity::kLight:
            out = "light ";
            break;
        case Intensity::kHeavy:
            out = "heavy ";
            break;
        case Intensity::kModerate:
        case Intensity::kVicinity:
            break;
    }
    if (descriptor != Descriptor::kNone) {
        out += DescriptorName(descriptor);
        if (descriptor == Descriptor::kThunderstorm && !phenomena.empty()) out += " with";
    }
    for (std::size_t i = 0; i < phenomena.size(); ++i) {
        if (!out.empty() && out.back() != ' ') out += i == 0 ? " " : " and ";
        out += PhenomenonName(phenomena[i]);
    }
    if (phenomena.empty() && descriptor == Descriptor::kShowers) out = "showers";
    if (intensity == Intensity::kVicinity) out += " in the vicinity";
    return out;
}

std::string_view CoverCode(Cover cover) {
    const auto* c = FindValue(kCovers, cover);
    return c ? c->code : "///";
}
int MinOktas(Cover cover) {
    switch (cover) {
        case Cover::kFew:
            return 1;
        case Cover::kScattered:
            return 3;
        case Cover::kBroken:
            return 5;
        case Cover::kOvercast:
            return 8;
        case Cover::kUnknown:
            break;
    }
    return 1;
}
int MaxOktas(Cover cover) {
    switch (cover) {
        case Cover::kFew:
            return 2;
        case Cover::kScattered:
            return 4;
        case Cover::kBroken:
            return 7;
        case Cover::kOvercast:
        case Cover::kUnknown:
            break;
    }
    return 8;
}

std::optional<double> SkyLayer::base_m() const {
    if (!base_ft) return std::nullopt;
    return *base_ft * kMetresPerFoot;
}

std::string_view ClearSkyCode(ClearSky clear) {
    const auto* c = FindValue(kClearSkies, clear);
    return c ? c->code : "";
}

std::optional<double> Metar::ceiling_ft() const {
    for (const SkyLayer& l : sky) {
        if ((l.cover == Cover::kBroken || l.cover == Cover::kOvercast) && l.base_ft) {
            return l.base_ft;
        }
    }
    return vertical_visibility_ft;
}

std::string Metar::Describe() const {
    std::string out = fmt::format("{} {}", type == ReportType::kSpeci ? "SPECI" : "METAR", station);
    if (time) {
        out += fmt::format(", day {} {:02d}:{:02d} UTC", time->day, time->hour, time->minute);
    }
    if (automatic) out += ", automatic";
    if (corrected) out += ", corrected";
    if (nil) out += ", NIL (missing report)";
    out += '\n';
    if (wind) {
        const std::string_view unit = SpeedUnitCode(wind->unit);
        out += "wind: ";
        if (wind->calm()) {
            out += "calm";
        } else {
            out += wind->variable        ? std::string("variable")
                   : wind->direction_deg ? fmt::format("from {:.0f} deg", *wind->direction_deg)
                                         : std::string("direction missing");
            if (wind->speed_m_s) {
                out +=
                    fmt::format(", {}{:.0f} {} ({:.1f} m/s)", wind->speed_more_than ? "above " : "",
                                *wind->speed_in_unit, unit, *wind->speed_m_s);
            } else {
                out += ", speed missing";
            }
            if (wind->gust_m_s) {
                out += fmt::format(", gusts {:.0f} {} ({:.1f} m/s)", *wind->gust_in_unit, unit,
                                   *wind->gust_m_s);
            }
        }
        if (wind->variable_from_deg) {
            out += fmt::format(", varying between {:.0f} and {:.0f} deg", *wind->variable_from_deg,
                               *wind->variable_to_deg);
        }
        out += '\n';
    }
    if (cavok) {
        out += "CAVOK: visibility 10 km or more, no cloud below 5000 ft, no significant weather\n";
    } else if (visibility) {
        out += fmt::format(
            "visibility: {}{}", BoundText(visibility->bound),
            FormatNumber(visibility->visibility_m >= 1000.0 ? std::round(visibility->visibility_m)
                                                            : visibility->visibility_m));
        out += " m";
        if (visibility->statute_miles) {
            out += fmt::format(" ({} SM)", FormatNumber(visibility->reported));
        }
        if (visibility->no_directional_variation) out += ", no directional variation";
        out += '\n';
    }
    if (minimum_visibility) {
        out += fmt::format("minimum visibility: {:.0f} m towards {}\n",
                           minimum_visibility->visibility_m,
                           CompassPointCode(minimum_visibility->direction));
    }
    for (const RunwayVisualRange& r : rvr) {
        out += fmt::format("RVR runway {}: {}{:.0f} m", r.runway, BoundText(r.bound), r.rvr_m);
        if (r.max_rvr_m) {
            out += fmt::format(" to {}{:.0f} m", BoundText(r.max_bound), *r.max_rvr_m);
        }
        if (r.feet) {
            out += fmt::format(" ({}{:.0f} ft", BoundText(r.bound), r.rvr_m / kMetresPerFoot);
            if (r.max_rvr_m) {
                out += fmt::format(" to {}{:.0f} ft", BoundText(r.max_bound),
                                   *r.max_rvr_m / kMetresPerFoot);
            }
            out += ')';
        }
        if (r.tendency == 'U') out += ", increasing";
        if (r.tendency == 'D') out += ", decreasing";
        if (r.tendency == 'N') out += ", no change";
        out += '\n';
    }
    if (!weather.empty()) {
        out += "weather:";
        for (std::size_t i = 0; i < weather.size(); ++i) {
            out += (i == 0 ? " " : "; ") + weather[i].Describe();
        }
        out += '\n';
    }
    if (weather_not_observed) out += "weather: not observed\n";
    if (no_significant_weather) out += "weather: nil significant weather\n";
    if (!recent_weather.empty()) {
        out += "recent weather:";
        for (std::size_t i = 0; i < recent_weather.size(); ++i) {
            out += (i == 0 ? " " : "; ") + recent_weather[i].Describe();
        }
        out += '\n';
    }
    if (clear != ClearSky::kNone) {
        out += fmt::format("sky: {}\n", FindValue(kClearSkies, clear)->name);
    }
    for (const SkyLayer& l : sky) {
        out += "cloud: ";
        out +=
            l.cover == Cover::kUnknown ? std::string("amount not observed")
            : MinOktas(l.cover) == MaxOktas(l.cover)
                ? fmt::format("{} ({} oktas)", FindValue(kCovers, l.cover)->name, MinOktas(l.cover))
                : fmt::format("{} ({}-{} oktas)", FindValue(kCovers, l.cover)->name,
                              MinOktas(l.cover), MaxOktas(l.cover));
        out += l.base_ft ? fmt::format(" at {:.0f} ft ({:.0f} m)", *l.base_ft, *l.base_m())
                         : std::string(", base not observed");
        if (l.convective == ConvectiveCloud::kCumulonimbus) out += ", cumulonimbus";
        if (l.convective == ConvectiveCloud::kToweringCumulus) out += ", towering cumulus";
        out += '\n';
    }
    if (vertical_visibility_reported) {
        out += vertical_visibility_ft
                   ? fmt::format("sky obscured, vertical visibility {:.0f} ft\n",
                                 *vertical_visibility_ft)
                   : std::string("sky obscured, vertical visibility not observed\n");
    }
    if (sky_not_observed) out += "sky: not observed\n";
    if (temperature_c || dew_point_c) {
        auto t = [this](const std::optional<double>& v) {
            if (!v) return std::string("missing");
            return temperature_from_remarks ? fmt::format("{:.1f} degC", *v)
                                            : fmt::format("{:.0f} degC", *v);
        };
        out += fmt::format("temperature: {}, dew point {}\n", t(temperature_c), t(dew_point_c));
    }
    if (qnh_hpa) {
        out += fmt::format("QNH: {:.1f} hPa", *qnh_hpa);
        if (altimeter_inhg) out += fmt::format(" (altimeter {:.2f} inHg)", *altimeter_inhg);
        out += '\n';
    }
    if (!trend.empty()) out += "trend: " + trend + '\n';
    if (!remarks.empty()) out += "remarks: " + remarks + '\n';
    for (const std::string& s : not_decoded) out += "not decoded: " + s + '\n';
    for (const MetarWarning& w : warnings) out += "warning: " + w.ToString() + '\n';
    if (warnings_suppressed > 0)
        out += fmt::format("... and {} more warnings\n", warnings_suppressed);
    return out;
}

Metar DecodeMetar(std::string_view text) {
    if (text.size() > kMaxMetarBytes) {
        throw MetarError(
            fmt::format("METAR report of {} characters (at most {})", text.size(), kMaxMetarBytes));
    }
    return Decoder(text).Run();
}

}  // namespace zenith::weather
