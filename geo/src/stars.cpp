// Bright-star catalogue: reader for KStars' binary star files and reduction to apparent place.
//
// File layout (learnt from KStars' BinFileHelper and StarObject::init, checked byte by byte
// against kstars-data 3.6.2; data/stars/README.md has the details and the verification):
//   0     char[124]  free text, NUL padded
//   124   2 bytes    0x4B53 written in the writer's byte order: "SK" = little endian
//   126   uint8      format version (1)
//   127   uint16     number of fields F
//   129   F x 16     field descriptors: char name[10], int8 size, uint8 type, int32 scale
//   ...   uint32     number of index entries N (trixels of the HTM mesh)
//   ...   N x 12     index: uint32 trixel id (= entry number), uint32 byte offset of the
//                    trixel's first record, uint32 number of records
//   star files only: int16 faint magnitude x 100, uint8 HTM level, uint16 max stars per trixel
//   then the records, each trixel's sorted by magnitude, brightest first.
// Star record, 32 bytes: int32 RA (hours x 1e6), int32 Dec (degrees x 1e5), int32 pmRA*cos(dec)
// and int32 pmDec (mas/yr x 10), int32 parallax (mas x 10), int32 HD number, int16 V x 100,
// int16 B-V x 100, char[2] spectral type, uint8 flags, uint8 unused. The scales in the field
// table are not all the ones KStars applies (HD says 10 but is stored as is), so the scales
// here are KStars' fixed ones and the field table is only checked for names and sizes.
// Name record (starnames.dat), 40 bytes: char[8] Bayer designation, char[32] proper name; the
// i-th name belongs to the i-th record of namedstars.dat in index order.
#include "zenith/geo/stars.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string_view>
#include <utility>

#include "zenith/geo/earth_orientation.h"
#include "zenith/geo/sun.h"
#include "zenith/geo/time.h"

namespace zenith::geo {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kRadiansPerMas = kPi / (180.0 * 3600.0 * 1000.0);
constexpr double kDaysPerJulianYear = 365.25;
// Hipparcos catalogue epoch J1991.25 (ESA 1997, The Hipparcos and Tycho Catalogues), TT.
constexpr double kHipparcosEpochJd = 2448349.0625;
constexpr double kSpeedOfLight = 299792458.0;  // m/s

constexpr const char* kDefaultStarDirectory = "/usr/share/kstars";
constexpr const char* kNamedStarsFile = "namedstars.dat";
constexpr const char* kUnnamedStarsFile = "unnamedstars.dat";
constexpr const char* kStarNamesFile = "starnames.dat";

constexpr std::size_t kPreambleTextSize = 124;
constexpr std::size_t kFieldDescriptorSize = 16;
constexpr std::size_t kFieldNameSize = 10;
constexpr std::size_t kIndexEntrySize = 12;
constexpr std::size_t kStarRecordSize = 32;
constexpr std::size_t kNameRecordSize = 40;
constexpr std::size_t kBayerNameSize = 8;
constexpr std::size_t kLongNameSize = 32;

struct FieldSpec {
    std::string_view name;
    int size;
};
constexpr std::array<FieldSpec, 11> kStarFields = {{{"RA", 4},
                                                    {"Dec", 4},
                                                    {"dRA", 4},
                                                    {"dDec", 4},
                                                    {"parallax", 4},
                                                    {"HD", 4},
                                                    {"mag", 2},
                                                    {"bv_index", 2},
                                                    {"spec_type", 2},
                                                    {"flags", 1},
                                                    {"unused", 1}}};
constexpr std::array<FieldSpec, 2> kNameFields = {{{"bayerName", 8}, {"longName", 32}}};

std::string MissingFileMessage(const std::filesystem::path& path, const std::string& why) {
    std::ostringstream out;
    out << "star catalogue: cannot read '" << path.string() << "' (" << why
        << "); install the catalogue with `apt-get install kstars-data`, or set ZENITH_STAR_DIR "
           "to a directory holding "
        << kNamedStarsFile << ", " << kUnnamedStarsFile << " and " << kStarNamesFile;
    return out.str();
}

std::vector<unsigned char> ReadWholeFile(const std::filesystem::path& path) {
    std::error_code error;
    const auto status = std::filesystem::status(path, error);
    if (error || !std::filesystem::exists(status)) {
        throw CatalogError(MissingFileMessage(path, "no such file"));
    }
    if (!std::filesystem::is_regular_file(status)) {
        throw CatalogError(MissingFileMessage(path, "not a regular file"));
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        throw CatalogError(MissingFileMessage(path, std::strerror(errno)));
    }
    std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)),
                                     std::istreambuf_iterator<char>());
    if (in.bad()) {
        throw CatalogError(MissingFileMessage(path, "read error"));
    }
    return bytes;
}

// Bounds-checked reads in the file's byte order; every failure names file, offset and what was
// expected there.
class Cursor {
  public:
    Cursor(std::filesystem::path path, const std::vector<unsigned char>& bytes,
           bool big_endian = false)
        : path_(std::move(path)), bytes_(bytes), big_endian_(big_endian) {}

    [[noreturn]] void Fail(std::size_t offset, const std::string& what) const {
        std::ostringstream out;
        out << "star catalogue file '" << path_.string() << "' (" << bytes_.size()
            << " bytes) is corrupt at offset " << offset << ": " << what
            << "; reinstall kstars-data";
        throw CatalogError(out.str());
    }

    void Require(std::size_t offset, std::size_t count, std::string_view what) const {
        if (offset > bytes_.size() || count > bytes_.size() - offset) {
            std::ostringstream out;
            out << "truncated: expected " << what << " (" << count << " bytes)";
            Fail(offset, out.str());
        }
    }

    void set_big_endian(bool big_endian) { big_endian_ = big_endian; }

    std::uint32_t Unsigned(std::size_t offset, std::size_t size, std::string_view what) const {
        Require(offset, size, what);
        std::uint32_t value = 0;
        for (std::size_t i = 0; i < size; ++i) {
            const std::size_t byte = big_endian_ ? i : size - 1 - i;
            value = (value << 8) | bytes_[offset + byte];
        }
        return value;
    }
    std::uint8_t U8(std::size_t offset, std::string_view what) const {
        return static_cast<std::uint8_t>(Unsigned(offset, 1, what));
    }
    std::uint16_t U16(std::size_t offset, std::string_view what) const {
        return static_cast<std::uint16_t>(Unsigned(offset, 2, what));
    }
    std::uint32_t U32(std::size_t offset, std::string_view what) const {
        return Unsigned(offset, 4, what);
    }
    std::int16_t I16(std::size_t offset, std::string_view what) const {
        return static_cast<std::int16_t>(U16(offset, what));  // two's complement (C++20)
    }
    std::int32_t I32(std::size_t offset, std::string_view what) const {
        return static_cast<std::int32_t>(U32(offset, what));
    }
    // NUL-terminated (or full-width) text, trailing blanks removed.
    std::string Text(std::size_t offset, std::size_t size, std::string_view what) const {
        Require(offset, size, what);
        const auto* first = reinterpret_cast<const char*>(bytes_.data() + offset);
        std::size_t length = 0;
        while (length < size && first[length] != '\0') ++length;
        while (length > 0 && first[length - 1] == ' ') --length;
        return std::string(first, length);
    }

    std::size_t size() const { return bytes_.size(); }

  private:
    std::filesystem::path path_;
    const std::vector<unsigned char>& bytes_;
    bool big_endian_ = false;
};

struct IndexEntry {
    std::size_t offset = 0;  // bytes from the start of the file
    std::size_t count = 0;   // records
};

struct BinaryFile {
    std::vector<unsigned char> bytes;
    std::vector<IndexEntry> index;
    std::size_t header_end = 0;  // first byte after the index table
    bool big_endian = false;
};

template <std::size_t N>
void ReadHeader(Cursor& cursor, const std::array<FieldSpec, N>& expected_fields,
                std::size_t record_size, BinaryFile& file) {
    std::size_t offset = kPreambleTextSize;
    cursor.Require(0, kPreambleTextSize, "124-byte preamble text");
    cursor.Require(offset, 2, "byte-order mark 0x4B53");
    const unsigned char b0 = file.bytes[offset];
    const unsigned char b1 = file.bytes[offset + 1];
    if (b0 == 0x53 && b1 == 0x4B) {
        file.big_endian = false;
    } else if (b0 == 0x4B && b1 == 0x53) {
        file.big_endian = true;
    } else {
        cursor.Fail(offset,
                    "expected byte-order mark 0x4B53 (\"SK\" or \"KS\"), not a KStars "
                    "binary catalogue");
    }
    cursor.set_big_endian(file.big_endian);
    offset += 2;
    const std::uint8_t version = cursor.U8(offset, "format version");
    if (version != 1) {
        cursor.Fail(offset, "expected format version 1, found " + std::to_string(version));
    }
    offset += 1;
    const std::uint16_t field_count = cursor.U16(offset, "field count");
    if (field_count != N) {
        cursor.Fail(offset, "expected " + std::to_string(N) + " fields, found " +
                                std::to_string(field_count));
    }
    offset += 2;
    std::size_t total_size = 0;
    for (std::size_t i = 0; i < N; ++i) {
        const std::string name = cursor.Text(offset, kFieldNameSize, "field name");
        const std::uint8_t size = cursor.U8(offset + kFieldNameSize, "field size");
        if (name != expected_fields[i].name || size != expected_fields[i].size) {
            cursor.Fail(offset, "expected field " + std::to_string(i) + " to be '" +
                                    std::string(expected_fields[i].name) + "' of " +
                                    std::to_string(expected_fields[i].size) + " bytes, found '" +
                                    name + "' of " + std::to_string(size) + " bytes");
        }
        total_size += size;
        offset += kFieldDescriptorSize;
    }
    if (total_size != record_size) {
        cursor.Fail(offset, "fields add up to " + std::to_string(total_size) + " bytes, expected " +
                                std::to_string(record_size));
    }
    const std::uint32_t index_size = cursor.U32(offset, "index entry count");
    offset += 4;
    cursor.Require(offset, std::size_t{index_size} * kIndexEntrySize,
                   std::to_string(index_size) + " index entries");
    file.index.resize(index_size);
    for (std::uint32_t i = 0; i < index_size; ++i) {
        const std::uint32_t id = cursor.U32(offset, "index entry id");
        if (id != i) {
            cursor.Fail(offset, "expected index entry id " + std::to_string(i) + ", found " +
                                    std::to_string(id));
        }
        const std::size_t data_offset = cursor.U32(offset + 4, "index entry offset");
        const std::size_t count = cursor.U32(offset + 8, "index entry record count");
        cursor.Require(data_offset, count * record_size,
                       std::to_string(count) + " records of index entry " + std::to_string(i));
        file.index[i] = {data_offset, count};
        offset += kIndexEntrySize;
    }
    file.header_end = offset;
}

BinaryFile OpenBinary(const std::filesystem::path& path, bool star_file) {
    BinaryFile file;
    file.bytes = ReadWholeFile(path);
    Cursor cursor(path, file.bytes);
    if (star_file) {
        ReadHeader(cursor, kStarFields, kStarRecordSize, file);
    } else {
        ReadHeader(cursor, kNameFields, kNameRecordSize, file);
    }
    return file;
}

// The star files' index covers the trixels of a hierarchical triangular mesh (8 * 4^level).
void CheckStarTrailer(Cursor& cursor, const BinaryFile& file) {
    const std::size_t offset = file.header_end;
    cursor.I16(offset, "faint magnitude limit");
    const std::uint8_t level = cursor.U8(offset + 2, "HTM level");
    cursor.U16(offset + 3, "maximum stars per trixel");
    if (!(level <= 10) || file.index.size() != (std::size_t{8} << (2 * level))) {
        cursor.Fail(offset + 2, "expected HTM level matching " + std::to_string(file.index.size()) +
                                    " index entries (8 * 4^level), found level " +
                                    std::to_string(level));
    }
    for (std::size_t i = 0; i < file.index.size(); ++i) {
        if (file.index[i].count > 0 && file.index[i].offset < offset + 5) {
            cursor.Fail(file.header_end - (file.index.size() - i) * kIndexEntrySize,
                        "index entry " + std::to_string(i) + " points into the header");
        }
    }
}

Star DecodeStar(const Cursor& cursor, std::size_t offset) {
    const double ra_hours = cursor.I32(offset, "RA") / 1.0e6;
    const double dec_deg = cursor.I32(offset + 4, "Dec") / 1.0e5;
    if (!(ra_hours >= 0.0 && ra_hours <= 24.0)) {
        cursor.Fail(offset, "expected RA in [0, 24] h, found " + std::to_string(ra_hours));
    }
    if (!(dec_deg >= -90.0 && dec_deg <= 90.0)) {
        cursor.Fail(offset + 4,
                    "expected Dec in [-90, 90] degrees, found " + std::to_string(dec_deg));
    }
    Star star;
    star.ra_j2000 = ra_hours * (kPi / 12.0);  // still at J1991.25 here; see MoveToJ2000
    star.dec_j2000 = dec_deg * (kPi / 180.0);
    star.pm_ra_mas_per_yr = cursor.I32(offset + 8, "pmRA") / 10.0;
    star.pm_dec_mas_per_yr = cursor.I32(offset + 12, "pmDec") / 10.0;
    star.parallax_mas = cursor.I32(offset + 16, "parallax") / 10.0;
    const std::int32_t hd = cursor.I32(offset + 20, "HD");
    star.hd = hd > 0 ? static_cast<std::uint32_t>(hd) : 0;
    star.magnitude_v = static_cast<float>(cursor.I16(offset + 24, "magnitude") / 100.0);
    star.b_minus_v = static_cast<float>(cursor.I16(offset + 26, "B-V") / 100.0);
    star.spectral_type = cursor.Text(offset + 28, 2, "spectral type");
    return star;
}

glm::dvec3 UnitVector(double ra, double dec) {
    return {std::cos(dec) * std::cos(ra), std::cos(dec) * std::sin(ra), std::sin(dec)};
}

// Rate of change of the unit vector, rad/yr, from proper motion in RA*cos(dec) and Dec: the
// components along the local east and north directions.
glm::dvec3 MotionVector(const Star& star) {
    const double ra = star.ra_j2000;
    const double dec = star.dec_j2000;
    const glm::dvec3 east(-std::sin(ra), std::cos(ra), 0.0);
    const glm::dvec3 north(-std::sin(dec) * std::cos(ra), -std::sin(dec) * std::sin(ra),
                           std::cos(dec));
    return (star.pm_ra_mas_per_yr * east + star.pm_dec_mas_per_yr * north) * kRadiansPerMas;
}

// Linear space motion from the Hipparcos epoch to J2000.0: the direction moves along a straight
// line at constant velocity (the model of SOFA/ERFA pmpx with zero parallax); the proper motion
// is then re-expressed in the local axes at the new place.
void MoveToJ2000(Star& star) {
    const double years = (kJ2000 - kHipparcosEpochJd) / kDaysPerJulianYear;
    const glm::dvec3 p0 = UnitVector(star.ra_j2000, star.dec_j2000);
    const glm::dvec3 v = MotionVector(star);
    const glm::dvec3 p1 = p0 + years * v;
    const double length = glm::length(p1);
    const glm::dvec3 p = p1 / length;
    double ra = std::atan2(p.y, p.x);
    if (ra < 0.0) ra += 2.0 * kPi;
    if (ra >= 2.0 * kPi) ra = 0.0;
    star.ra_j2000 = ra;
    star.dec_j2000 = std::asin(std::clamp(p.z, -1.0, 1.0));
    const glm::dvec3 v_at_p = v / length;
    const glm::dvec3 east(-std::sin(ra), std::cos(ra), 0.0);
    const glm::dvec3 north(-std::sin(star.dec_j2000) * std::cos(ra),
                           -std::sin(star.dec_j2000) * std::sin(ra), std::cos(star.dec_j2000));
    star.pm_ra_mas_per_yr = glm::dot(v_at_p, east) / kRadiansPerMas;
    star.pm_dec_mas_per_yr = glm::dot(v_at_p, north) / kRadiansPerMas;
}

// Reads the records of `file` with V <= limit. Each trixel's records are sorted brightest
// first, so the rest of a trixel is skipped at the first fainter star. With `names`, the i-th
// record (counting every record in index order) takes the i-th name.
void ReadStars(const std::filesystem::path& path, const BinaryFile& file, double magnitude_limit,
               const BinaryFile* names, const std::filesystem::path& names_path,
               std::vector<Star>& out) {
    Cursor cursor(path, file.bytes, file.big_endian);
    CheckStarTrailer(cursor, file);
    std::size_t name_count = 0;
    if (names != nullptr) {
        for (const IndexEntry& entry : names->index) name_count += entry.count;
        std::size_t star_count = 0;
        for (const IndexEntry& entry : file.index) star_count += entry.count;
        if (name_count != star_count) {
            Cursor name_cursor(names_path, names->bytes, names->big_endian);
            name_cursor.Fail(names->header_end - kIndexEntrySize,
                             "expected " + std::to_string(star_count) + " name records, one for " +
                                 "each star in " + path.string() + ", found " +
                                 std::to_string(name_count));
        }
    }
    std::size_t record_number = 0;  // over all records in index order, for the names
    for (const IndexEntry& entry : file.index) {
        for (std::size_t k = 0; k < entry.count; ++k) {
            const std::size_t offset = entry.offset + k * kStarRecordSize;
            Star star = DecodeStar(cursor, offset);
            if (!(star.magnitude_v <= magnitude_limit)) break;
            if (names != nullptr) {
                Cursor name_cursor(names_path, names->bytes, names->big_endian);
                // Locate record (record_number + k) among the name file's index entries.
                std::size_t n = record_number + k;
                for (const IndexEntry& name_entry : names->index) {
                    if (n < name_entry.count) {
                        const std::size_t name_offset = name_entry.offset + n * kNameRecordSize;
                        star.designation =
                            name_cursor.Text(name_offset, kBayerNameSize, "Bayer designation");
                        star.name = name_cursor.Text(name_offset + kBayerNameSize, kLongNameSize,
                                                     "proper name");
                        break;
                    }
                    n -= name_entry.count;
                }
            }
            MoveToJ2000(star);
            out.push_back(std::move(star));
        }
        record_number += entry.count;
    }
}

// CIE 1931 colour matching functions, multi-lobe piecewise-Gaussian fit of Wyman, Sloan &
// Shirley (2013, JCGT 2(2), "Simple Analytic Approximations to the CIE XYZ Color Matching
// Functions", Listing 1); lambda in nm; the inverse widths are theirs, in 1/nm.
double Lobe(double lambda_nm, double mean_nm, double inv_width_below, double inv_width_above) {
    const double t =
        (lambda_nm - mean_nm) * (lambda_nm < mean_nm ? inv_width_below : inv_width_above);
    return std::exp(-0.5 * t * t);
}
glm::dvec3 CieXyzBar1931(double lambda_nm) {
    const double x = 1.056 * Lobe(lambda_nm, 599.8, 0.0264, 0.0323) +
                     0.362 * Lobe(lambda_nm, 442.0, 0.0624, 0.0374) -
                     0.065 * Lobe(lambda_nm, 501.1, 0.0490, 0.0382);
    const double y = 0.821 * Lobe(lambda_nm, 568.8, 0.0213, 0.0247) +
                     0.286 * Lobe(lambda_nm, 530.9, 0.0613, 0.0322);
    const double z = 1.217 * Lobe(lambda_nm, 437.0, 0.0845, 0.0278) +
                     0.681 * Lobe(lambda_nm, 459.0, 0.0385, 0.0725);
    return {x, y, z};
}

// CIE XYZ of a black body, arbitrary scale: Planck's law against the colour matching functions
// from 360 to 830 nm (the range of the CIE 1931 tables) by Simpson's rule in 5 nm steps: the
// ratios X/Y and Z/Y are within 5e-4 of the converged integral for 1,900-22,000 K, below the
// error of the fit itself (chromaticity within 0.005 of the Planckian locus, tested).
glm::dvec3 BlackBodyXyz(double temperature) {
    // Second radiation constant hc/k, m K (CODATA 2018, exact from the SI definitions).
    constexpr double kC2 = 1.438776877e-2;
    constexpr double kFirstNm = 360.0;
    constexpr int kSteps = 94;  // (830 - 360) / 5, even for Simpson's rule
    constexpr double kStepNm = 5.0;
    glm::dvec3 sum(0.0);
    for (int i = 0; i <= kSteps; ++i) {
        const double lambda_nm = kFirstNm + kStepNm * i;
        const double lambda = lambda_nm * 1e-9;
        // Planck spectral radiance up to the constant 2hc^2; lambda in micrometres keeps the
        // numbers near 1.
        const double lambda_um = lambda_nm * 1e-3;
        const double radiance = 1.0 / (lambda_um * lambda_um * lambda_um * lambda_um * lambda_um *
                                       std::expm1(kC2 / (lambda * temperature)));
        const double weight = (i == 0 || i == kSteps) ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0);
        sum += weight * radiance * CieXyzBar1931(lambda_nm);
    }
    return sum * (kStepNm / 3.0);
}

}  // namespace

double IlluminanceFromMagnitude(double magnitude_v) {
    // Pogson: 5 magnitudes are a factor of 100.
    return kZeroMagnitudeIlluminance * std::pow(10.0, -0.4 * magnitude_v);
}

double TemperatureFromBMinusV(double b_minus_v) {
    // The formula has a pole at B-V = -0.62/0.92 = -0.67; the hottest stars have B-V ~ -0.33,
    // so -0.4 (21,700 K) bounds it. Beyond B-V = 4 (2,000 K) only carbon stars remain, which
    // are far from black bodies.
    if (std::isnan(b_minus_v)) return b_minus_v;
    const double bv = std::clamp(b_minus_v, kMinBMinusV, kMaxBMinusV);
    return 4600.0 * (1.0 / (0.92 * bv + 1.7) + 1.0 / (0.92 * bv + 0.62));
}

glm::dvec3 ColourFromBMinusV(double b_minus_v) {
    if (std::isnan(b_minus_v)) return glm::dvec3(b_minus_v);
    const glm::dvec3 xyz = BlackBodyXyz(TemperatureFromBMinusV(b_minus_v));
    // XYZ -> linear sRGB (IEC 61966-2-1, D65), the inverse of the matrix whose middle row is
    // the luminance weights kLuminanceWeights below (glm is column-major: columns given).
    const glm::dmat3 rgb_from_xyz(3.2404542, -0.9692660, 0.0556434,   //
                                  -1.5371385, 1.8760108, -0.2040259,  //
                                  -0.4985314, 0.0415560, 1.0572252);  //
    const glm::dvec3 luminance_weights(0.2126729, 0.7151522, 0.0721750);
    glm::dvec3 rgb = glm::max(rgb_from_xyz * xyz, glm::dvec3(0.0));
    return rgb / glm::dot(luminance_weights, rgb);
}

std::filesystem::path DefaultStarDirectory() {
    const char* from_environment = std::getenv("ZENITH_STAR_DIR");
    if (from_environment != nullptr && from_environment[0] != '\0') {
        return std::filesystem::path(from_environment);
    }
    return std::filesystem::path(kDefaultStarDirectory);
}

StarCatalog StarCatalog::Load(double magnitude_limit, std::filesystem::path directory) {
    if (std::isnan(magnitude_limit)) {
        throw CatalogError(
            "StarCatalog::Load: magnitude_limit is NaN; expected a visual "
            "magnitude such as 6.5 (naked eye); the files go to 8.0");
    }
    if (directory.empty()) directory = DefaultStarDirectory();
    const std::filesystem::path named_path = directory / kNamedStarsFile;
    const std::filesystem::path names_path = directory / kStarNamesFile;
    const std::filesystem::path unnamed_path = directory / kUnnamedStarsFile;

    const BinaryFile named = OpenBinary(named_path, true);
    const BinaryFile names = OpenBinary(names_path, false);
    const BinaryFile unnamed = OpenBinary(unnamed_path, true);

    StarCatalog catalog;
    catalog.magnitude_limit_ = magnitude_limit;
    ReadStars(named_path, named, magnitude_limit, &names, names_path, catalog.stars_);
    ReadStars(unnamed_path, unnamed, magnitude_limit, nullptr, {}, catalog.stars_);
    std::stable_sort(catalog.stars_.begin(), catalog.stars_.end(),
                     [](const Star& a, const Star& b) { return a.magnitude_v < b.magnitude_v; });

    catalog.directions_j2000_.reserve(catalog.stars_.size());
    catalog.motions_per_yr_.reserve(catalog.stars_.size());
    for (const Star& star : catalog.stars_) {
        catalog.directions_j2000_.push_back(UnitVector(star.ra_j2000, star.dec_j2000));
        catalog.motions_per_yr_.push_back(MotionVector(star));
    }
    return catalog;
}

std::vector<glm::dvec3> StarCatalog::ApparentTod(double jd_tt) const {
    const double years = (jd_tt - kJ2000) / kDaysPerJulianYear;
    const glm::dvec3 beta = EarthVelocityGcrs(jd_tt) / kSpeedOfLight;
    const double inverse_gamma = std::sqrt(1.0 - glm::dot(beta, beta));
    const glm::dmat3 tod_from_gcrs = TodFromGcrs(jd_tt);
    std::vector<glm::dvec3> out(stars_.size());
    for (std::size_t i = 0; i < stars_.size(); ++i) {
        const glm::dvec3 p = glm::normalize(directions_j2000_[i] + years * motions_per_yr_[i]);
        // Aberration as the Lorentz transformation of the light direction (the formula of
        // SOFA/ERFA ab without its ~1e-8 rad gravitational term); the overall factor
        // 1 / (1 + p.beta) drops out on normalising.
        const double p_dot_beta = glm::dot(p, beta);
        const glm::dvec3 apparent =
            inverse_gamma * p + (1.0 + p_dot_beta / (1.0 + inverse_gamma)) * beta;
        out[i] = tod_from_gcrs * glm::normalize(apparent);
    }
    return out;
}

}  // namespace zenith::geo
