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
    return t ? detail::Trim(t) : std::string_view();
}

int LineAt(std::string_view text, std::size_t offset) {
    return 1 + static_cast<int>(
                   std::count(text.begin(), text.begin() + static_cast<long>(offset), '\n'));
}

// Parses text; when it is not well-formed, retries with the text cut after the last complete
// sample element (last_sample_end, e.g. "</trkpt>") and closed by one of the given tails.
void ParseWithRecovery(tinyxml2::XMLDocument& doc, std::string_view text,
                       std::string_view last_sample_end, const std::vector<std::string>& tails,
                       LogBuilder& out) {
    if (doc.Parse(text.data(), text.size()) == tinyxml2::XML_SUCCESS) return;
    const int error_line = doc.ErrorLineNum();
    const std::string error = doc.ErrorStr();
    const auto cut = text.rfind(last_sample_end);
    if (cut != std::string_view::npos) {
        const std::size_t end = cut + last_sample_end.size();
        for (const std::string& tail : tails) {
            std::string repaired(text.substr(0, end));
            repaired += tail;
            if (doc.Parse(repaired.data(), repaired.size()) == tinyxml2::XML_SUCCESS) {
                out.Skip(error_line,
                         fmt::format("XML not well-formed ({}); read up to line {}, the last "
                                     "complete {}",
                                     error, LineAt(text, end), last_sample_end));
                return;
            }
        }
    }
    throw FlightLogError(
        fmt::format("{}:{}: XML not well-formed: {}", out.source(), error_line, error));
}

}  // namespace

FlightLog ParseGpx(std::string_view text, std::string source) {
    LogBuilder out(std::move(source), LogFormat::kGpx);
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
                s.lat_deg = *detail::ParseDouble(lat);
                s.lon_deg = *detail::ParseDouble(lon);
            } catch (const std::exception& e) {
                out.Skip(line, fmt::format("trkpt lat/lon: {}", e.what()));
                continue;
            }
            if (!(std::abs(s.lat_deg) <= 90.0) || !(std::abs(s.lon_deg) <= 180.0)) {
                out.Skip(line, fmt::format("position out of range: lat {}, lon {} deg (allowed "
                                           "[-90, 90], [-180, 180])",
                                           s.lat_deg, s.lon_deg));
                continue;
            }
            if (s.lon_deg >= 180.0) s.lon_deg -= 360.0;
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

FlightLog ParseKml(std::string_view text, std::string source) {
    LogBuilder out(std::move(source), LogFormat::kKml);
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
        std::string mode = "clampToGround";
        int mode_line = track->GetLineNum();
        for (const XMLElement* c = track->FirstChildElement(); c; c = c->NextSiblingElement()) {
            const std::string_view name = LocalName(*c);
            if (name == "when") {
                whens.push_back(c);
            } else if (name == "coord") {
                coords.push_back(c);
            } else if (name == "angles") {
                angles.push_back(c);
            } else if (name == "altitudeMode") {
                mode = std::string(TextOf(*c));
                mode_line = c->GetLineNum();
            }
        }
        const bool absolute = mode == "absolute";
        if (!absolute) {
            out.Note(
                fmt::format("{}altitudeMode {}: altitudes are relative to terrain zenith "
                            "does not know (or clamped to it) and are not used",
                            detail::Where(out.source(), mode_line), mode));
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
            if (!(std::abs(s.lat_deg) <= 90.0) || !(std::abs(s.lon_deg) <= 180.0)) {
                out.Skip(s.line, fmt::format("position out of range: lon {}, lat {} deg", s.lon_deg,
                                             s.lat_deg));
                continue;
            }
            if (s.lon_deg >= 180.0) s.lon_deg -= 360.0;
            if (absolute && v.size() == 3) s.msl_altitude = v[2];
            if (use_angles && i < angles.size()) {
                std::istringstream a{std::string(TextOf(*angles[i]))};
                std::array<double, 3> hpr{};
                try {
                    for (double& x : hpr) {
                        if (!(a >> field)) throw std::invalid_argument("needs 3 values");
                        x = *detail::ParseDouble(field);
                    }
                    if (a >> field) throw std::invalid_argument("more than 3 values");
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
