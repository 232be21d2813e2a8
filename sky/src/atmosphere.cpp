// Atmosphere parameters: validation, JSON presets (format documented in atmosphere.h).
//
// One table of fields drives both directions and the checks, so the JSON reader, the writer and
// Validate() cannot disagree about names, units or ranges. The struct is SI; the file uses the
// units of the atmosphere literature (km, 1/km, degrees), converted once here.
#include "zenith/sky/atmosphere.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <span>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

#include "data_files.h"
namespace zenith::sky {
namespace {

using data_files::Quote;

using Json = nlohmann::json;

// Beyond this an atmosphere is not a thin shell any more and the LUT parameterisations (which
// spread their texels over the thickness) lose the detail near the ground: ten Earth atmospheres.
constexpr double kMaxThickness = 1000e3;  // m
// A mean free path under a metre is fog, not an atmosphere; a km/m slip of 1000 lands here.
constexpr double kMaxCoefficient = 1.0;  // 1/m
// A sun wider than this is not a disk seen from a planet.
constexpr double kMaxSunAngularRadiusDeg = 45.0;

// --- unit conversions -----------------------------------------------------------------------

enum class Unit {
    kNone,       // same number in the file and in the struct
    kKilometre,  // file km, struct m
    kPerKm,      // file 1/km, struct 1/m
    kDegree,     // file deg, struct rad
};

// Numbers are converted as decimal text, not as doubles: the file's "0.005802" per km becomes
// the double nearest to 5.802e-6 per m (a multiplication by 1e-3 can be one ulp off, and the
// Earth preset must equal Hillaire 2020 Table 1 exactly), and the writer can always emit a text
// that reads back as the same double.

// The text of a JSON number with its decimal exponent moved by `shift`: "5.802e-3" -> "5.802e-6".
std::string ShiftExponent(std::string_view text, int shift) {
    const std::size_t e = text.find_first_of("eE");
    const int exponent =
        e == std::string_view::npos ? 0 : std::atoi(std::string(text.substr(e + 1)).c_str());
    return std::string(text.substr(0, e)) + "e" + std::to_string(exponent + shift);
}

// Correctly rounded; overflow gives +-inf (which validation then reports), underflow +-0.
double ParseDouble(const std::string& text) {
    double value = 0.0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec == std::errc::result_out_of_range) {
        const bool negative = !text.empty() && text[0] == '-';
        const std::size_t e = text.find_first_of("eE");
        const bool huge = e != std::string::npos && text[e + 1] != '-';
        value = huge ? HUGE_VAL : 0.0;
        return negative ? -value : value;
    }
    return value;
}

// Shortest text that reads back as the same double; "6360", "0.8", "1e-09".
std::string Shortest(double x) {
    char buffer[64];
    const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, x);
    return ec == std::errc() ? std::string(buffer, end) : std::to_string(x);
}

constexpr long double kPiLong = 3.141592653589793238462643383279502884L;

// The struct's SI value from the decimal text of a number in the file.
double SiFromText(const std::string& text, Unit unit) {
    switch (unit) {
        case Unit::kNone:
            return ParseDouble(text);
        case Unit::kKilometre:
            return ParseDouble(ShiftExponent(text, 3));
        case Unit::kPerKm:
            return ParseDouble(ShiftExponent(text, -3));
        case Unit::kDegree:
            // In long double so that the writer's 21 digits come back exactly (see FileText).
            return static_cast<double>(std::strtold(text.c_str(), nullptr) * (kPiLong / 180.0L));
    }
    return ParseDouble(text);
}

// The file's text for an SI value: the shortest readable form when it reads back exactly (always
// for kNone, nearly always otherwise), else a longer text that does. Non-finite values have no
// JSON form; they are written as null and rejected on reading (Validate rejects them anyway).
std::string FileText(double si, Unit unit) {
    if (!std::isfinite(si)) return "null";
    switch (unit) {
        case Unit::kNone:
            return Shortest(si);
        case Unit::kKilometre:
        case Unit::kPerKm: {
            char buffer[64];
            const auto [end, ec] =
                std::to_chars(buffer, buffer + sizeof buffer, si, std::chars_format::scientific);
            const std::string exact =
                ShiftExponent(std::string_view(buffer, static_cast<std::size_t>(end - buffer)),
                              unit == Unit::kKilometre ? -3 : 3);
            const std::string pretty = Shortest(ParseDouble(exact));
            return SiFromText(pretty, unit) == si ? pretty : exact;
        }
        case Unit::kDegree: {
            const long double degrees = static_cast<long double>(si) * (180.0L / kPiLong);
            const std::string pretty = Shortest(static_cast<double>(degrees));
            if (SiFromText(pretty, unit) == si) return pretty;
            char buffer[64];
            std::snprintf(buffer, sizeof buffer, "%.21Lg", degrees);
            return buffer;
        }
    }
    return Shortest(si);
}

// A value as the reader of a message knows it: in the file's unit, or SI.
double FileValue(double si, Unit unit) {
    if (!std::isfinite(si)) return si;
    return ParseDouble(FileText(si, unit));
}

// For messages: "0.8", "6360", "nan", "-inf".
std::string FormatNumber(double x) {
    if (std::isnan(x)) return "nan";
    if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
    return Shortest(x);
}

// --- the field table ------------------------------------------------------------------------

// Where a value lives: in the file (a path of keys, unit) and in the struct (member, SI unit).
struct FieldName {
    const char* group;  // "" for top-level keys, else "rayleigh", "mie", "absorption"
    const char* key;
    const char* member;
    Unit unit;
    const char* file_unit;  // "" for dimensionless
    const char* si_unit;
};

constexpr FieldName kBottomRadius{"", "bottom_radius_km", "bottom_radius", Unit::kKilometre, "km",
                                  "m"};
constexpr FieldName kTopRadius{"", "top_radius_km", "top_radius", Unit::kKilometre, "km", "m"};
constexpr FieldName kRayleighScattering{
    "rayleigh", "scattering_per_km", "rayleigh_scattering", Unit::kPerKm, "1/km", "1/m"};
constexpr FieldName kRayleighScaleHeight{
    "rayleigh", "scale_height_km", "rayleigh_scale_height", Unit::kKilometre, "km", "m"};
constexpr FieldName kMieScattering{
    "mie", "scattering_per_km", "mie_scattering", Unit::kPerKm, "1/km", "1/m"};
constexpr FieldName kMieAbsorption{
    "mie", "absorption_per_km", "mie_absorption", Unit::kPerKm, "1/km", "1/m"};
constexpr FieldName kMieScaleHeight{
    "mie", "scale_height_km", "mie_scale_height", Unit::kKilometre, "km", "m"};
constexpr FieldName kMieG{"mie", "g", "mie_g", Unit::kNone, "", ""};
constexpr FieldName kAbsorptionExtinction{
    "absorption", "extinction_per_km", "absorption_extinction", Unit::kPerKm, "1/km", "1/m"};
constexpr FieldName kAbsorptionCenter{"absorption",     "center_km", "absorption_center",
                                      Unit::kKilometre, "km",        "m"};
constexpr FieldName kAbsorptionWidth{"absorption",     "width_km", "absorption_width",
                                     Unit::kKilometre, "km",       "m"};
constexpr FieldName kGroundAlbedo{"", "ground_albedo", "ground_albedo", Unit::kNone, "", ""};
constexpr FieldName kSolarIlluminance{
    "", "solar_illuminance_lux", "solar_illuminance", Unit::kNone, "lux", "lux"};
constexpr FieldName kSunAngularRadius{
    "", "sun_angular_radius_deg", "sun_angular_radius", Unit::kDegree, "deg", "rad"};

constexpr const char* kTopLevelKeys[] = {
    "name", "description", "bottom_radius_km", "top_radius_km",         "rayleigh",
    "mie",  "absorption",  "ground_albedo",    "solar_illuminance_lux", "sun_angular_radius_deg"};
constexpr const char* kRayleighKeys[] = {"scattering_per_km", "scale_height_km"};
constexpr const char* kMieKeys[] = {"scattering_per_km", "absorption_per_km", "scale_height_km",
                                    "g"};
constexpr const char* kAbsorptionKeys[] = {"extinction_per_km", "center_km", "width_km"};

std::string FilePath(const FieldName& field) {
    return field.group[0] == '\0' ? std::string(field.key)
                                  : std::string(field.group) + "." + field.key;
}

// Reports an invalid value either in the file's terms (key path, file units) or in the struct's
// (member, SI), so a message always matches what its reader wrote.
class Checker {
  public:
    Checker(std::string source, bool file_terms)
        : source_(std::move(source)), file_terms_(file_terms) {}

    // name[channel] = value unit: expected <what>
    [[noreturn]] void Fail(const FieldName& field, int channel, double si_value,
                           const std::string& expected) const {
        std::string name = file_terms_ ? FilePath(field) : std::string(field.member);
        if (channel >= 0) name += "[" + std::to_string(channel) + "]";
        const double shown = file_terms_ ? FileValue(si_value, field.unit) : si_value;
        const char* unit = file_terms_ ? field.file_unit : field.si_unit;
        std::string message = source_ + ": " + name + " = " + FormatNumber(shown);
        message += unit[0] != '\0' ? std::string(" ") + unit : std::string(" (dimensionless)");
        throw AtmosphereError(message + ": expected " + expected);
    }

    // A bound as the reader knows it: "6360 km" in the file, "6.36e+06 m" for the struct.
    std::string Bound(const FieldName& field, double si_value) const {
        const double shown = file_terms_ ? FileValue(si_value, field.unit) : si_value;
        const char* unit = file_terms_ ? field.file_unit : field.si_unit;
        return FormatNumber(shown) + (unit[0] != '\0' ? std::string(" ") + unit : "");
    }
    std::string Name(const FieldName& field) const {
        return file_terms_ ? FilePath(field) : std::string(field.member);
    }

    void Positive(const FieldName& field, double value, int channel = -1) const {
        if (!(value > 0.0 && std::isfinite(value))) {
            Fail(field, channel, value, "a finite value > 0");
        }
    }
    void Coefficient(const FieldName& field, const glm::dvec3& value) const {
        for (int i = 0; i < 3; ++i) {
            if (!(value[i] >= 0.0 && value[i] < kMaxCoefficient)) {
                Fail(field, i, value[i],
                     "0 <= value < " + Bound(field, kMaxCoefficient) +
                         " (finite, not negative; larger means a mean free path under 1 m)");
            }
        }
    }

  private:
    std::string source_;
    bool file_terms_;
};

void Check(const Atmosphere& a, const Checker& check) {
    if (a.name.empty()) throw AtmosphereError("atmosphere: name is empty; expected a name");
    check.Positive(kBottomRadius, a.bottom_radius);
    if (!(a.top_radius > a.bottom_radius && a.top_radius - a.bottom_radius <= kMaxThickness)) {
        check.Fail(kTopRadius, -1, a.top_radius,
                   check.Name(kBottomRadius) + " < value <= " + check.Name(kBottomRadius) + " + " +
                       check.Bound(kTopRadius, kMaxThickness) + ", with " +
                       check.Name(kBottomRadius) + " = " +
                       check.Bound(kBottomRadius, a.bottom_radius));
    }
    check.Coefficient(kRayleighScattering, a.rayleigh_scattering);
    check.Positive(kRayleighScaleHeight, a.rayleigh_scale_height);
    check.Coefficient(kMieScattering, a.mie_scattering);
    check.Coefficient(kMieAbsorption, a.mie_absorption);
    check.Positive(kMieScaleHeight, a.mie_scale_height);
    // At |g| = 1 the Cornette-Shanks phase function (Hillaire 2020, Sec. 4) is a Dirac delta:
    // infinite in one direction, zero elsewhere, which no LUT or quadrature can sample.
    if (!(a.mie_g > -1.0 && a.mie_g < 1.0)) {
        check.Fail(kMieG, -1, a.mie_g,
                   "-1 < g < 1 (the Cornette-Shanks phase function diverges at |g| = 1)");
    }
    check.Coefficient(kAbsorptionExtinction, a.absorption_extinction);
    const double thickness = a.top_radius - a.bottom_radius;
    if (!(a.absorption_center >= 0.0 && a.absorption_center <= thickness)) {
        check.Fail(kAbsorptionCenter, -1, a.absorption_center,
                   "0 <= value <= the atmosphere's thickness " +
                       check.Bound(kAbsorptionCenter, thickness));
    }
    check.Positive(kAbsorptionWidth, a.absorption_width);
    for (int i = 0; i < 3; ++i) {
        if (!(a.ground_albedo[i] >= 0.0 && a.ground_albedo[i] <= 1.0)) {
            check.Fail(kGroundAlbedo, i, a.ground_albedo[i],
                       "0 <= value <= 1 (a Lambertian ground reflects at most what it receives)");
        }
    }
    for (int i = 0; i < 3; ++i) check.Positive(kSolarIlluminance, a.solar_illuminance[i], i);
    const double max_radius = kMaxSunAngularRadiusDeg * (std::numbers::pi / 180.0);
    if (!(a.sun_angular_radius > 0.0 && a.sun_angular_radius <= max_radius)) {
        check.Fail(kSunAngularRadius, -1, a.sun_angular_radius,
                   "0 < value <= " + check.Bound(kSunAngularRadius, max_radius));
    }
}

// --- reading --------------------------------------------------------------------------------

class Reader : public data_files::JsonReader<AtmosphereError> {
  public:
    Reader(std::string source, const std::map<std::string, std::string>& number_text)
        : JsonReader(std::move(source)), number_text_(number_text) {}

    const Json& Group(const Json& root, const char* key) const {
        const Json& group = Required(root, "", key);
        if (!group.is_object()) Fail(key, "expected an object, got " + DescribeJsonValue(group));
        return group;
    }

    double Number(const Json& value, const std::string& path, Unit unit) const {
        if (!value.is_number()) Fail(path, "expected a number, got " + DescribeJsonValue(value));
        const auto text = number_text_.find(path);
        return text != number_text_.end() ? SiFromText(text->second, unit)
                                          : SiFromText(Shortest(value.get<double>()), unit);
    }

    double Scalar(const Json& object, const FieldName& field) const {
        return Number(Required(object, Prefix(field), field.key), FilePath(field), field.unit);
    }

    // One number (three equal channels) or [r, g, b].
    glm::dvec3 Rgb(const Json& object, const FieldName& field) const {
        const Json& value = Required(object, Prefix(field), field.key);
        const std::string path = FilePath(field);
        if (value.is_number()) return glm::dvec3(Number(value, path, field.unit));
        if (!value.is_array() || value.size() != 3) {
            Fail(path, "expected a number or an array of 3 numbers (R, G, B), got " +
                           DescribeJsonValue(value));
        }
        glm::dvec3 rgb;
        for (int i = 0; i < 3; ++i) {
            rgb[i] = Number(value[static_cast<std::size_t>(i)],
                            path + "[" + std::to_string(i) + "]", field.unit);
        }
        return rgb;
    }

  private:
    static std::string Prefix(const FieldName& field) {
        return field.group[0] == '\0' ? std::string() : std::string(field.group) + ".";
    }
    const std::map<std::string, std::string>& number_text_;
};

// A JSON document and the text of each of its numbers by key path ("mie.g",
// "rayleigh.scattering_per_km[1]"), so that numbers are converted in decimal (see SiFromText).
struct Document {
    Json root;
    std::map<std::string, std::string> number_text;
};

// Builds the DOM through nlohmann's SAX interface, which passes the text of float numbers, and
// rejects duplicate keys: nlohmann's own parser keeps the last silently, and a second "g" further
// down must not quietly override the first.
class DocumentBuilder final : public nlohmann::json_sax<Json> {
  public:
    DocumentBuilder(std::string_view text, const std::string& source)
        : text_(text), source_(source) {}

    Document Take() { return std::move(document_); }

    bool null() override { return Put(nullptr); }
    bool boolean(bool value) override { return Put(value); }
    bool number_integer(number_integer_t value) override {
        return PutNumber(value, std::to_string(value));
    }
    bool number_unsigned(number_unsigned_t value) override {
        return PutNumber(value, std::to_string(value));
    }
    bool number_float(number_float_t value, const string_t& text) override {
        return PutNumber(value, text);
    }
    bool string(string_t& value) override { return Put(value); }
    bool binary(binary_t& value) override { return Put(Json::binary(value)); }
    bool start_object(std::size_t /*elements*/) override { return Open(Json::object()); }
    bool key(string_t& key) override {
        Frame& frame = stack_.back();
        if (frame.value->contains(key)) {
            throw AtmosphereError(source_ + ": " + Child(frame, key) +
                                  ": duplicate key; expected each key once per object");
        }
        frame.key = key;
        return true;
    }
    bool end_object() override { return Close(); }
    bool start_array(std::size_t /*elements*/) override { return Open(Json::array()); }
    bool end_array() override { return Close(); }
    bool parse_error(std::size_t position, const std::string& /*last_token*/,
                     const Json::exception& error) override {
        // position is 1-based: the character that stopped the parser (the end of a bad token).
        throw AtmosphereError(
            data_files::JsonSyntaxMessage(source_, text_, position, error.what()));
    }

  private:
    struct Frame {
        Json* value;
        std::string path;
        std::string key;  // objects: the key of the next value
    };

    static std::string Child(const Frame& frame, const std::string& key) {
        return frame.path.empty() ? key : frame.path + "." + key;
    }

    // Inserts a value at the current place; returns where it went and its path.
    std::pair<Json*, std::string> Insert(Json value) {
        if (stack_.empty()) {
            document_.root = std::move(value);
            return {&document_.root, ""};
        }
        Frame& frame = stack_.back();
        if (frame.value->is_object()) {
            Json& slot = (*frame.value)[frame.key];
            slot = std::move(value);
            return {&slot, Child(frame, frame.key)};
        }
        const std::size_t index = frame.value->size();
        frame.value->push_back(std::move(value));
        return {&frame.value->back(), frame.path + "[" + std::to_string(index) + "]"};
    }
    bool Put(Json value) {
        Insert(std::move(value));
        return true;
    }
    bool PutNumber(Json value, const std::string& text) {
        document_.number_text[Insert(std::move(value)).second] = text;
        return true;
    }
    // A child's pointer stays valid while it is open: no sibling is added to its parent until
    // it is closed.
    bool Open(Json container) {
        auto [where, path] = Insert(std::move(container));
        stack_.push_back(Frame{where, std::move(path), {}});
        return true;
    }
    bool Close() {
        stack_.pop_back();
        return true;
    }

    std::string_view text_;
    const std::string& source_;
    Document document_;
    std::vector<Frame> stack_;
};

Document ParseStrict(std::string_view text, const std::string& source) {
    data_files::CheckJsonDepth<AtmosphereError>(source, text);
    DocumentBuilder builder(text, source);
    try {
        Json::sax_parse(text.begin(), text.end(), &builder);
    } catch (const Json::exception& e) {
        // What the SAX events cannot see: "1e309" overflows while parsing.
        throw AtmosphereError(data_files::JsonExceptionMessage(source, e.what()));
    }
    return builder.Take();
}

}  // namespace

void Validate(const Atmosphere& atmosphere) {
    Check(atmosphere, Checker("atmosphere " + Quote(atmosphere.name), false));
}

Atmosphere ParseAtmosphereJson(std::string_view json_text, std::string_view source_name) {
    const std::string source(source_name);
    const Document document = ParseStrict(json_text, source);
    const Json& root = document.root;
    const Reader read(source, document.number_text);
    if (!root.is_object())
        read.Fail("(top level)", "expected an object, got " + DescribeJsonValue(root));
    read.RejectUnknownKeys(root, "", kTopLevelKeys);

    Atmosphere a;
    // Default name: the file's stem ("earth" for ".../earth.json").
    a.name = std::filesystem::path(source).stem().string();
    if (const auto it = root.find("name"); it != root.end()) {
        if (!it->is_string() || it->get<std::string>().empty()) {
            read.Fail("name", "expected a non-empty string, got " + DescribeJsonValue(*it));
        }
        a.name = it->get<std::string>();
    }
    if (const auto it = root.find("description"); it != root.end() && !it->is_string()) {
        read.Fail("description", "expected a string, got " + DescribeJsonValue(*it));
    }
    if (a.name.empty()) a.name = "atmosphere";

    a.bottom_radius = read.Scalar(root, kBottomRadius);
    a.top_radius = read.Scalar(root, kTopRadius);

    const Json& rayleigh = read.Group(root, "rayleigh");
    read.RejectUnknownKeys(rayleigh, "rayleigh.", kRayleighKeys);
    a.rayleigh_scattering = read.Rgb(rayleigh, kRayleighScattering);
    a.rayleigh_scale_height = read.Scalar(rayleigh, kRayleighScaleHeight);

    const Json& mie = read.Group(root, "mie");
    read.RejectUnknownKeys(mie, "mie.", kMieKeys);
    a.mie_scattering = read.Rgb(mie, kMieScattering);
    a.mie_absorption = read.Rgb(mie, kMieAbsorption);
    a.mie_scale_height = read.Scalar(mie, kMieScaleHeight);
    a.mie_g = read.Scalar(mie, kMieG);

    // Optional: an atmosphere without an absorbing layer (Mars) leaves the group out.
    if (root.contains("absorption")) {
        const Json& absorption = read.Group(root, "absorption");
        read.RejectUnknownKeys(absorption, "absorption.", kAbsorptionKeys);
        a.absorption_extinction = read.Rgb(absorption, kAbsorptionExtinction);
        a.absorption_center = read.Scalar(absorption, kAbsorptionCenter);
        a.absorption_width = read.Scalar(absorption, kAbsorptionWidth);
    } else {
        a.absorption_extinction = glm::dvec3(0.0);
    }

    a.ground_albedo = read.Rgb(root, kGroundAlbedo);
    a.solar_illuminance = read.Rgb(root, kSolarIlluminance);
    a.sun_angular_radius = read.Scalar(root, kSunAngularRadius);

    Check(a, Checker(source, true));
    return a;
}

Atmosphere LoadAtmosphere(std::string_view name_or_path) {
    data_files::NamedFile file;
    std::string error;
    if (!data_files::ReadNamedJsonFile(name_or_path, PresetDirectory(), "atmosphere",
                                       "set by $ZENITH_DATA_DIR/presets", file, error)) {
        throw AtmosphereError(error);
    }
    return ParseAtmosphereJson(file.text, file.path.string());
}

// --- writing --------------------------------------------------------------------------------

namespace {

std::string Number(double si, Unit unit) { return FileText(si, unit); }

std::string Rgb(const glm::dvec3& si, Unit unit) {
    if (si.x == si.y && si.y == si.z) return Number(si.x, unit);
    return "[" + Number(si.x, unit) + ", " + Number(si.y, unit) + ", " + Number(si.z, unit) + "]";
}

}  // namespace

std::string AtmosphereToJson(const Atmosphere& a) {
    std::string out = "{\n";
    const auto line = [&](const char* indent, const char* key, const std::string& value,
                          bool last = false) {
        out += std::string(indent) + "\"" + key + "\": " + value + (last ? "\n" : ",\n");
    };
    line("    ", "name", Json(a.name).dump());
    line("    ", kBottomRadius.key, Number(a.bottom_radius, Unit::kKilometre));
    line("    ", kTopRadius.key, Number(a.top_radius, Unit::kKilometre));
    out += "    \"rayleigh\": {\n";
    line("        ", kRayleighScattering.key, Rgb(a.rayleigh_scattering, Unit::kPerKm));
    line("        ", kRayleighScaleHeight.key, Number(a.rayleigh_scale_height, Unit::kKilometre),
         true);
    out += "    },\n    \"mie\": {\n";
    line("        ", kMieScattering.key, Rgb(a.mie_scattering, Unit::kPerKm));
    line("        ", kMieAbsorption.key, Rgb(a.mie_absorption, Unit::kPerKm));
    line("        ", kMieScaleHeight.key, Number(a.mie_scale_height, Unit::kKilometre));
    line("        ", kMieG.key, Number(a.mie_g, Unit::kNone), true);
    // Always written, even at zero extinction, so that the centre and width round-trip.
    out += "    },\n    \"absorption\": {\n";
    line("        ", kAbsorptionExtinction.key, Rgb(a.absorption_extinction, Unit::kPerKm));
    line("        ", kAbsorptionCenter.key, Number(a.absorption_center, Unit::kKilometre));
    line("        ", kAbsorptionWidth.key, Number(a.absorption_width, Unit::kKilometre), true);
    out += "    },\n";
    line("    ", kGroundAlbedo.key, Rgb(a.ground_albedo, Unit::kNone));
    line("    ", kSolarIlluminance.key, Rgb(a.solar_illuminance, Unit::kNone));
    line("    ", kSunAngularRadius.key, Number(a.sun_angular_radius, Unit::kDegree), true);
    out += "}\n";
    return out;
}

std::filesystem::path PresetDirectory() {
    const char* from_environment = std::getenv("ZENITH_DATA_DIR");
    if (from_environment != nullptr && from_environment[0] != '\0') {
        return std::filesystem::path(from_environment) / "presets";
    }
    std::error_code error;
    const std::filesystem::path installed(ZENITH_PRESET_DIR_INSTALL);
    if (std::filesystem::is_directory(installed, error)) return installed;
    return std::filesystem::path(ZENITH_PRESET_DIR_SOURCE);
}

}  // namespace zenith::sky
