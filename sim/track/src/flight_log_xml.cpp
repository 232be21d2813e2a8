// GPX 1.1 and KML 2.2 (gx:Track) readers, on tinyxml2.
//
// GPX: every trk/trkseg/trkpt in document order: lat/lon attributes, <time> (ISO 8601, needed),
// <ele> (metres; GPX 1.1 does not name its datum, and GNSS receivers write height above mean sea
// level, so it is read as kMsl). Waypoints and routes have no times and are not read.
//
// KML: every gx:Track (also inside gx:MultiTrack) in document order; its i-th <when> pairs with
// its i-th <gx:coord> ("lon lat [alt]") and, when present, its i-th <gx:angles> ("heading tilt
// roll", degrees). Angles follow the KML <Orientation> convention read as: heading clockwise
// from true north, tilt = nose up, roll = right wing down (Attitude's convention); a writer that
// uses the opposite roll sign will show mirrored banks. <altitudeMode> absolute means above sea
// level (kMsl); the other modes are relative to terrain that zenith does not know, so their
// altitudes are not used (and clampToGround is KML's default when the mode is missing).
//
// XML has no record lines, so messages carry the line of the element. A document cut short (a
// logger that lost power) fails to parse; it is then read up to its last complete sample, with
// the parse error and its line in the summary.
#include <fmt/format.h>
#include <tinyxml2.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <sstream>

#include "flight_log_internal.h"
#include "zenith/base/error.h"

namespace zenith::track {

namespace {

using detail::LogBuilder;
using tinyxml2::XMLElement;

constexpr double kRadPerDeg = std::numbers::pi / 180.0;

std::string_view LocalName(const XMLElement& e) {
    std::string_view name = e.Name();
    const auto colon = name.find(':');
    return colon == std::string_view::npos ? name : name.substr(colon + 1);
}

void CollectByLocalName(const XMLElement& parent, std::string_view name,
                        std::vector<const XMLElement*>& out) {
    for (const XMLElement* c = parent.FirstChildElement(); c; c = c->NextSiblingElement()) {
        if (LocalName(*c) == name) {
            out.push_back(c);
        } else {
            CollectByLocalName(*c, name, out);
        }
    }
}

const XMLElement* ChildByLocalName(const XMLElement& parent, std::string_view name) {
    for (const XMLElement* c = parent.FirstChildElement(); c; c = c->NextSiblingElement()) {
        if (LocalName(*c) == name) return c;
    }
    return nullptr;
}

std::string_view TextOf(const XMLElement& e) {
    const char* t = e.GetText();
    return t ? Trim(t) : std::string_view();
}

int LineAt(std::string_view text, std::size_t offset) {
    return 1 + static_cast<int>(
                   std::count(text.begin(), text.begin() + static_cast<long>(offset), '\n'));
}

// tinyxml2's error, in words, with the line when it has one.
std::string XmlError(const tinyxml2::XMLDocument& doc, std::string_view source) {
    std::string what;
    switch (doc.ErrorID()) {
        case tinyxml2::XML_ERROR_EMPTY_DOCUMENT:
            what = "the document is empty";
            break;
        case tinyxml2::XML_ERROR_MISMATCHED_ELEMENT:
            what = "an element is closed by another's tag";
            break;
        case tinyxml2::XML_ERROR_PARSING_ELEMENT:
            what = "an element is malformed or not closed";
            break;
        case tinyxml2::XML_ERROR_PARSING_ATTRIBUTE:
            what = "an attribute is malformed";
            break;
        case tinyxml2::XML_ERROR_PARSING_TEXT:
            what = "text is malformed";
            break;
        case tinyxml2::XML_ERROR_PARSING_COMMENT:
            what = "a comment is not closed";
            break;
        case tinyxml2::XML_ERROR_PARSING_DECLARATION:
            what = "a declaration is malformed";
            break;
        case tinyxml2::XML_ERROR_PARSING_CDATA:
            what = "a CDATA section is not closed";
            break;
        case tinyxml2::XML_ELEMENT_DEPTH_EXCEEDED:
            what = "elements are nested too deeply";
            break;
        default:
            what = doc.ErrorName();
            break;
    }
    const int line = doc.ErrorLineNum();
    return line > 0 ? fmt::format("{}:{}: XML not well-formed: {}", source, line, what)
                    : fmt::format("{}: XML not well-formed: {}", source, what);
}

// XML that declares itself UTF-16 by its byte-order mark (Windows tools write it), as UTF-8;
// tinyxml2 reads UTF-8 only. Unpaired surrogates become U+FFFD. Other text is returned as it is.
std::string_view AsUtf8(std::string_view text, std::string& storage) {
    if (text.size() < 2) return text;
    const auto b0 = static_cast<unsigned char>(text[0]), b1 = static_cast<unsigned char>(text[1]);
    const bool little = b0 == 0xFF && b1 == 0xFE, big = b0 == 0xFE && b1 == 0xFF;
    if (!little && !big) return text;
    storage.clear();
    storage.reserve(text.size());
    const auto unit = [&](std::size_t i) -> std::uint32_t {
        const auto lo = static_cast<unsigned char>(text[i + (little ? 0 : 1)]);
        const auto hi = static_cast<unsigned char>(text[i + (little ? 1 : 0)]);
        return static_cast<std::uint32_t>(hi << 8 | lo);
    };
    const auto put = [&](std::uint32_t c) {
        if (c < 0x80) {
            storage += static_cast<char>(c);
        } else if (c < 0x800) {
            storage += static_cast<char>(0xC0 | c >> 6);
            storage += static_cast<char>(0x80 | (c & 0x3F));
        } else if (c < 0x10000) {
            storage += static_cast<char>(0xE0 | c >> 12);
            storage += static_cast<char>(0x80 | (c >> 6 & 0x3F));
            storage += static_cast<char>(0x80 | (c & 0x3F));
        } else {
            storage += static_cast<char>(0xF0 | c >> 18);
            storage += static_cast<char>(0x80 | (c >> 12 & 0x3F));
            storage += static_cast<char>(0x80 | (c >> 6 & 0x3F));
            storage += static_cast<char>(0x80 | (c & 0x3F));
        }
    };
    for (std::size_t i = 2; i + 1 < text.size(); i += 2) {
        const std::uint32_t u = unit(i);
        if (u >= 0xD800 && u < 0xDC00 && i + 3 < text.size()) {
            const std::uint32_t v = unit(i + 2);
            if (v >= 0xDC00 && v < 0xE000) {
                put(0x10000 + ((u - 0xD800) << 10) + (v - 0xDC00));
                i += 2;
                continue;
            }
        }
        put(u >= 0xD800 && u < 0xE000 ? 0xFFFD : u);
    }
    // The declaration may still say encoding="UTF-16"; tinyxml2 ignores it.
    return storage;
}

// Parses text; when it is not well-formed, retries with the text cut after the last complete
// sample element (last_sample_end, e.g. "</trkpt>") and closed by one of the given tails.
void ParseWithRecovery(tinyxml2::XMLDocument& doc, std::string_view text,
                       std::string_view last_sample_end, const std::vector<std::string>& tails,
                       LogBuilder& out) {
    if (doc.Parse(text.data(), text.size()) == tinyxml2::XML_SUCCESS) return;
    const int error_line = doc.ErrorLineNum();
    const std::string error = XmlError(doc, out.source());
    const auto cut = text.rfind(last_sample_end);
    if (cut != std::string_view::npos) {
        const std::size_t end = cut + last_sample_end.size();
        for (const std::string& tail : tails) {
            std::string repaired(text.substr(0, end));
            repaired += tail;
            if (doc.Parse(repaired.data(), repaired.size()) == tinyxml2::XML_SUCCESS) {
                out.Skip(error_line, fmt::format("{}; read up to line {}, the last complete {}",
                                                 error, LineAt(text, end), last_sample_end));
                return;
            }
        }
    }
    throw FlightLogError(error);
}

// How a gx:Track's altitudes are meant (KML 2.2 §9.1.2 and the gx extensions): its own
// altitudeMode or gx:altitudeMode, else that of the gx:MultiTrack holding it, else KML's default,
// clampToGround.
struct AltitudeMode {
    enum Kind { kAbsolute, kRelative, kClamped } kind = kClamped;
    std::string name = "clampToGround";
    std::string where = "KML's default when none is given";
    int line = 0;
};

std::optional<AltitudeMode> OwnAltitudeMode(const XMLElement& element, const char* where) {
    for (const XMLElement* c = element.FirstChildElement(); c; c = c->NextSiblingElement()) {
        if (LocalName(*c) != "altitudeMode") continue;  // altitudeMode and gx:altitudeMode
        AltitudeMode mode;
        mode.name = std::string(TextOf(*c));
        mode.where = where;
        mode.line = c->GetLineNum();
        if (mode.name == "absolute") {
            mode.kind = AltitudeMode::kAbsolute;
        } else if (mode.name == "relativeToGround" || mode.name == "relativeToSeaFloor") {
            mode.kind = AltitudeMode::kRelative;
        } else {
            mode.kind = AltitudeMode::kClamped;  // clampToGround, clampToSeaFloor, unknown
        }
        return mode;
    }
    return std::nullopt;
}

AltitudeMode TrackAltitudeMode(const XMLElement& track) {
    if (auto own = OwnAltitudeMode(track, "given by the gx:Track")) return *own;
    const tinyxml2::XMLNode* parent = track.Parent();
    const XMLElement* multi = parent ? parent->ToElement() : nullptr;
    if (multi && LocalName(*multi) == "MultiTrack") {
        if (auto inherited = OwnAltitudeMode(*multi, "inherited from its gx:MultiTrack")) {
            return *inherited;
        }
    }
    AltitudeMode mode;
    mode.line = track.GetLineNum();
    return mode;
}

}  // namespace

FlightLog ParseGpx(std::string_view text, std::string source, const ReadOptions& options) {
    LogBuilder out(std::move(source), LogFormat::kGpx, options);
    std::string utf8;
    text = AsUtf8(text, utf8);
    tinyxml2::XMLDocument doc;
    ParseWithRecovery(doc, text, "</trkpt>", {"</trkseg></trk></gpx>"}, out);
    const XMLElement* root = doc.RootElement();
    if (!root || LocalName(*root) != "gpx") {
        throw FlightLogError(fmt::format("{}: not a GPX document (root element '{}')", out.source(),
                                         root ? root->Name() : ""));
    }
    std::vector<const XMLElement*> segments;
    CollectByLocalName(*root, "trkseg", segments);
    if (segments.size() > 1) {
        out.Note(fmt::format("{} track segments, joined in document order", segments.size()));
    }
    if (const XMLElement* name = ChildByLocalName(*root, "trk")) {
        if (const XMLElement* n = ChildByLocalName(*name, "name")) {
            out.SetDescription(std::string(TextOf(*n)));
        }
    }
    int without_ele = 0;
    for (const XMLElement* seg : segments) {
        for (const XMLElement* p = seg->FirstChildElement(); p; p = p->NextSiblingElement()) {
            if (LocalName(*p) != "trkpt") continue;
            out.CountRecord();
            const int line = p->GetLineNum();
            FlightSample s;
            s.line = line;
            try {
                const char* lat = p->Attribute("lat");
                const char* lon = p->Attribute("lon");
                if (!lat || !lon) {
                    out.Skip(line, "trkpt without lat/lon attributes");
                    continue;
                }
                const std::optional<double> lat_deg = detail::ParseDouble(lat);
                const std::optional<double> lon_deg = detail::ParseDouble(lon);
                if (!lat_deg || !lon_deg) {
                    out.Skip(line, "trkpt with an empty lat or lon attribute");
                    continue;
                }
                s.lat_deg = *lat_deg;
                s.lon_deg = *lon_deg;
            } catch (const std::exception& e) {
                out.Skip(line, fmt::format("trkpt lat/lon: {}", e.what()));
                continue;
            }
            const XMLElement* time = ChildByLocalName(*p, "time");
            if (!time) {
                out.Skip(line, "trkpt without <time>");
                continue;
            }
            try {
                s.time_s = detail::UnixSecondsFromIso8601(TextOf(*time));
            } catch (const std::exception& e) {
                out.Skip(time->GetLineNum(), fmt::format("bad <time>: {}", e.what()));
                continue;
            }
            if (const XMLElement* ele = ChildByLocalName(*p, "ele")) {
                try {
                    s.msl_altitude = detail::ParseDouble(TextOf(*ele));
                } catch (const std::exception& e) {
                    out.Skip(ele->GetLineNum(), fmt::format("bad <ele>: {}", e.what()));
                    continue;
                }
            }
            if (!s.msl_altitude) ++without_ele;
            out.Add(std::move(s));
        }
    }
    if (without_ele > 0) out.Note(fmt::format("{} trkpt have no <ele>", without_ele));
    return out.Finish();
}

FlightLog ParseKml(std::string_view text, std::string source, const ReadOptions& options) {
    LogBuilder out(std::move(source), LogFormat::kKml, options);
    std::string utf8;
    text = AsUtf8(text, utf8);
    tinyxml2::XMLDocument doc;
    // gx:Track lists all <when> first, then the coordinates, then the angles.
    const std::string_view last_end = text.rfind("</gx:angles>") != std::string_view::npos &&
                                              text.rfind("</gx:angles>") > text.rfind("</gx:coord>")
                                          ? "</gx:angles>"
                                          : "</gx:coord>";
    ParseWithRecovery(doc, text, last_end,
                      {"</gx:Track></Placemark></Document></kml>", "</gx:Track></Placemark></kml>",
                       "</gx:Track></gx:MultiTrack></Placemark></Document></kml>",
                       "</gx:Track></Placemark></Folder></Document></kml>"},
                      out);
    const XMLElement* root = doc.RootElement();
    if (!root || LocalName(*root) != "kml") {
        throw FlightLogError(fmt::format("{}: not a KML document (root element '{}')", out.source(),
                                         root ? root->Name() : ""));
    }
    std::vector<const XMLElement*> tracks;
    CollectByLocalName(*root, "Track", tracks);
    if (tracks.empty()) {
        throw FlightLogError(
            fmt::format("{}: no gx:Track element (LineString has no times and "
                        "cannot be replayed)",
                        out.source()));
    }
    std::vector<const XMLElement*> names;
    CollectByLocalName(*root, "name", names);
    if (!names.empty()) out.SetDescription(std::string(TextOf(*names.front())));

    for (const XMLElement* track : tracks) {
        std::vector<const XMLElement*> whens, coords, angles;
        for (const XMLElement* c = track->FirstChildElement(); c; c = c->NextSiblingElement()) {
            const std::string_view name = LocalName(*c);
            if (name == "when") {
                whens.push_back(c);
            } else if (name == "coord") {
                coords.push_back(c);
            } else if (name == "angles") {
                angles.push_back(c);
            }
        }
        const AltitudeMode mode = TrackAltitudeMode(*track);
        if (mode.kind != AltitudeMode::kAbsolute) {
            out.Note(fmt::format("{}altitudeMode {} ({}): {}",
                                 detail::Where(out.source(), mode.line), mode.name, mode.where,
                                 mode.kind == AltitudeMode::kClamped
                                     ? "the track is on the terrain, which zenith does not know: "
                                       "heights are taken as 0 m above sea level"
                                     : "heights are above the terrain, which zenith does not "
                                       "know: they are taken as above sea level"));
        }
        const std::size_t n = std::max(whens.size(), coords.size());
        if (whens.size() != coords.size()) {
            out.Note(fmt::format(
                "{}gx:Track has {} <when> and {} <gx:coord>: the unpaired ones "
                "are skipped",
                detail::Where(out.source(), track->GetLineNum()), whens.size(), coords.size()));
        }
        const bool use_angles = !angles.empty();
        if (use_angles && angles.size() != whens.size()) {
            out.Note(fmt::format("{}gx:Track has {} <gx:angles> for {} <when>",
                                 detail::Where(out.source(), track->GetLineNum()), angles.size(),
                                 whens.size()));
        }
        for (std::size_t i = 0; i < n; ++i) {
            out.CountRecord();
            if (i >= whens.size() || i >= coords.size()) {
                const XMLElement* lone = i < whens.size() ? whens[i] : coords[i];
                out.Skip(lone->GetLineNum(),
                         fmt::format("<{}> #{} has no matching <{}>", lone->Name(), i + 1,
                                     i < whens.size() ? "gx:coord" : "when"));
                continue;
            }
            FlightSample s;
            s.line = coords[i]->GetLineNum();
            try {
                s.time_s = detail::UnixSecondsFromIso8601(TextOf(*whens[i]));
            } catch (const std::exception& e) {
                out.Skip(whens[i]->GetLineNum(), fmt::format("bad <when>: {}", e.what()));
                continue;
            }
            std::istringstream coord{std::string(TextOf(*coords[i]))};
            std::string field;
            std::vector<double> v;
            try {
                while (coord >> field) v.push_back(*detail::ParseDouble(field));
            } catch (const std::exception& e) {
                out.Skip(s.line, fmt::format("bad <gx:coord>: {}", e.what()));
                continue;
            }
            if (v.size() < 2 || v.size() > 3) {
                out.Skip(s.line,
                         fmt::format("<gx:coord> '{}' is not 'lon lat [alt]'", TextOf(*coords[i])));
                continue;
            }
            s.lon_deg = v[0];
            s.lat_deg = v[1];
            if (mode.kind == AltitudeMode::kClamped) {
                s.msl_altitude = 0.0;
            } else if (v.size() == 3) {
                s.msl_altitude = v[2];
            }
            if (use_angles && i < angles.size()) {
                std::istringstream a{std::string(TextOf(*angles[i]))};
                std::array<double, 3> hpr{};
                try {
                    for (double& x : hpr) {
                        if (!(a >> field)) throw ArgumentError("needs 3 values");
                        x = *detail::ParseDouble(field);
                    }
                    if (a >> field) throw ArgumentError("more than 3 values");
                } catch (const std::exception& e) {
                    out.Skip(angles[i]->GetLineNum(),
                             fmt::format("bad <gx:angles> '{}' (heading tilt roll): {}",
                                         TextOf(*angles[i]), e.what()));
                    continue;
                }
                s.attitude =
                    geo::Attitude{hpr[0] * kRadPerDeg, hpr[1] * kRadPerDeg, hpr[2] * kRadPerDeg};
            }
            out.Add(std::move(s));
        }
    }
    return out.Finish();
}

}  // namespace zenith::track
