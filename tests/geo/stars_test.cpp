// Bright-star catalogue: the KStars binary reader (on synthetic files of both byte orders and on
// the installed kstars-data), photometry and colour laws, and the apparent place against ERFA.
#include "zenith/geo/stars.h"

#include <erfa.h>
#include <erfam.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

#include "zenith/geo/angles.h"

namespace zg = zenith::geo;
namespace fs = std::filesystem;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kArcsec = kPi / (180.0 * 3600.0);
constexpr double kHipparcosEpochJd = 2448349.0625;  // J1991.25
constexpr double kJ2000 = 2451545.0;

// ---------------------------------------------------------------------------------------------
// Synthetic KStars files, written field by field in either byte order.

struct SyntheticStar {
    double ra_hours = 0.0;
    double dec_deg = 0.0;
    double pm_ra_mas_per_yr = 0.0;  // includes cos(dec)
    double pm_dec_mas_per_yr = 0.0;
    double parallax_mas = 0.0;
    std::int32_t hd = 0;
    double magnitude_v = 0.0;
    double b_minus_v = 0.0;
    std::string spectral_type = "A0";
    int trixel = 0;  // 0..7 (HTM level 0)
};

class ByteWriter {
  public:
    explicit ByteWriter(bool big_endian) : big_endian_(big_endian) {}
    void Int(std::uint32_t value, int size) {
        for (int i = 0; i < size; ++i) {
            const int shift = 8 * (big_endian_ ? size - 1 - i : i);
            bytes_.push_back(static_cast<char>((value >> shift) & 0xFF));
        }
    }
    void Text(const std::string& text, std::size_t size) {
        std::string padded = text.substr(0, size);
        padded.resize(size, '\0');
        bytes_ += padded;
    }
    void Bom() { bytes_ += big_endian_ ? std::string("KS") : std::string("SK"); }
    std::string& bytes() { return bytes_; }

  private:
    bool big_endian_;
    std::string bytes_;
};

struct Field {
    std::string name;
    int size;
};
const std::vector<Field> kStarFields = {
    {"RA", 4},  {"Dec", 4},      {"dRA", 4},       {"dDec", 4},  {"parallax", 4}, {"HD", 4},
    {"mag", 2}, {"bv_index", 2}, {"spec_type", 2}, {"flags", 1}, {"unused", 1}};
const std::vector<Field> kNameFields = {{"bayerName", 8}, {"longName", 32}};

void WriteHeader(ByteWriter& w, const std::vector<Field>& fields) {
    w.Text("KStars Star Data v1.0. Synthetic test file.", 124);
    w.Bom();
    w.Int(1, 1);
    w.Int(static_cast<std::uint32_t>(fields.size()), 2);
    for (const Field& f : fields) {
        w.Text(f.name, 10);
        w.Int(static_cast<std::uint32_t>(f.size), 1);
        w.Int(0, 1);  // type code, not read
        w.Int(1, 4);  // scale, not read
    }
}

std::string StarFile(std::vector<SyntheticStar> stars, bool big_endian) {
    std::stable_sort(stars.begin(), stars.end(),
                     [](const auto& a, const auto& b) { return a.trixel < b.trixel; });
    ByteWriter w(big_endian);
    WriteHeader(w, kStarFields);
    constexpr int kTrixels = 8;
    w.Int(kTrixels, 4);
    const std::size_t index_start = w.bytes().size();
    const std::size_t data_start = index_start + kTrixels * 12 + 5;
    std::size_t offset = data_start;
    for (int t = 0; t < kTrixels; ++t) {
        const auto count = static_cast<std::uint32_t>(std::count_if(
            stars.begin(), stars.end(), [t](const auto& s) { return s.trixel == t; }));
        w.Int(static_cast<std::uint32_t>(t), 4);
        w.Int(static_cast<std::uint32_t>(offset), 4);
        w.Int(count, 4);
        offset += count * 32;
    }
    w.Int(800, 2);  // faint limit x 100
    w.Int(0, 1);    // HTM level 0: 8 trixels
    w.Int(10, 2);   // max stars per trixel
    for (const SyntheticStar& s : stars) {
        w.Int(static_cast<std::uint32_t>(std::lround(s.ra_hours * 1e6)), 4);
        w.Int(static_cast<std::uint32_t>(std::lround(s.dec_deg * 1e5)), 4);
        w.Int(static_cast<std::uint32_t>(std::lround(s.pm_ra_mas_per_yr * 10)), 4);
        w.Int(static_cast<std::uint32_t>(std::lround(s.pm_dec_mas_per_yr * 10)), 4);
        w.Int(static_cast<std::uint32_t>(std::lround(s.parallax_mas * 10)), 4);
        w.Int(static_cast<std::uint32_t>(s.hd), 4);
        w.Int(static_cast<std::uint32_t>(std::lround(s.magnitude_v * 100)), 2);
        w.Int(static_cast<std::uint32_t>(std::lround(s.b_minus_v * 100)), 2);
        w.Text(s.spectral_type, 2);
        w.Int(0, 1);
        w.Int(0, 1);
    }
    return w.bytes();
}

std::string NameFile(const std::vector<std::pair<std::string, std::string>>& names,
                     bool big_endian) {
    ByteWriter w(big_endian);
    WriteHeader(w, kNameFields);
    w.Int(1, 4);
    w.Int(0, 4);
    w.Int(static_cast<std::uint32_t>(w.bytes().size() + 8), 4);
    w.Int(static_cast<std::uint32_t>(names.size()), 4);
    for (const auto& [bayer, name] : names) {
        w.Text(bayer, 8);
        w.Text(name, 32);
    }
    return w.bytes();
}

void WriteFile(const fs::path& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    ASSERT_TRUE(out.good()) << path;
}

fs::path ScratchDir(const std::string& name) {
    const fs::path dir = fs::path(ZENITH_BINARY_DIR) / "stars_test_scratch" / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

// Named stars sorted brightest first within each trixel, as KStars writes them; file order is
// trixel 0: A, B; trixel 5: C. The names pair with that order.
std::vector<SyntheticStar> NamedStars() {
    SyntheticStar a{.ra_hours = 6.752569,
                    .dec_deg = -16.71314,
                    .pm_ra_mas_per_yr = -546.0,
                    .pm_dec_mas_per_yr = -1223.1,
                    .parallax_mas = 379.0,
                    .hd = 48915,
                    .magnitude_v = -1.44,
                    .b_minus_v = 0.0,
                    .spectral_type = "A0",
                    .trixel = 0};
    SyntheticStar b{.ra_hours = 1.0,
                    .dec_deg = 10.0,
                    .hd = 2,
                    .magnitude_v = 3.0,
                    .b_minus_v = 1.2,
                    .spectral_type = "K0",
                    .trixel = 0};
    SyntheticStar c{.ra_hours = 23.5,
                    .dec_deg = -70.0,
                    .hd = 3,
                    .magnitude_v = 2.0,
                    .b_minus_v = -0.2,
                    .spectral_type = "B2",
                    .trixel = 5};
    return {a, b, c};
}
const std::vector<std::pair<std::string, std::string>> kNames = {
    {"alp CMa", "Sirius"}, {"bet Tst", ""}, {"gam Tst", "Testar"}};

std::vector<SyntheticStar> UnnamedStars() {
    std::vector<SyntheticStar> stars;
    // Trixel 2: 4.0, 7.0 (fainter than the test limit), 7.5; trixel 7: 5.0, 6.0.
    for (double m : {4.0, 7.0, 7.5}) {
        stars.push_back(
            {.ra_hours = 12.0, .dec_deg = 45.0, .hd = 100, .magnitude_v = m, .trixel = 2});
    }
    for (double m : {5.0, 6.0}) {
        stars.push_back({.ra_hours = 0.0, .dec_deg = 90.0, .hd = 0, .magnitude_v = m, .trixel = 7});
    }
    return stars;
}

fs::path WriteSyntheticCatalogue(const std::string& name, bool big_endian) {
    const fs::path dir = ScratchDir(name);
    WriteFile(dir / "namedstars.dat", StarFile(NamedStars(), big_endian));
    WriteFile(dir / "starnames.dat", NameFile(kNames, big_endian));
    WriteFile(dir / "unnamedstars.dat", StarFile(UnnamedStars(), big_endian));
    return dir;
}

std::string LoadError(double limit, const fs::path& dir) {
    try {
        zg::StarCatalog::Load(limit, dir);
    } catch (const zg::CatalogError& e) {
        return e.what();
    }
    return "(no CatalogError thrown)";
}

const zg::Star* FindByName(const zg::StarCatalog& catalog, const std::string& name) {
    for (const zg::Star& s : catalog.stars()) {
        if (s.name == name) return &s;
    }
    return nullptr;
}

// ---------------------------------------------------------------------------------------------
// Reader on synthetic files.

class StarCatalogSyntheticTest : public ::testing::TestWithParam<bool> {};

TEST_P(StarCatalogSyntheticTest, DecodesRecordsNamesAndLimit) {
    const bool big_endian = GetParam();
    const fs::path dir = WriteSyntheticCatalogue(big_endian ? "big" : "little", big_endian);
    const zg::StarCatalog catalog = zg::StarCatalog::Load(6.5, dir);
    EXPECT_EQ(catalog.magnitude_limit(), 6.5);

    // 3 named + unnamed 4.0, 5.0, 6.0 (7.0 and 7.5 beyond the limit).
    const auto& stars = catalog.stars();
    ASSERT_EQ(stars.size(), 6u);
    const std::vector<float> expected_magnitudes = {-1.44f, 2.0f, 3.0f, 4.0f, 5.0f, 6.0f};
    for (std::size_t i = 0; i < stars.size(); ++i) {
        EXPECT_NEAR(stars[i].magnitude_v, expected_magnitudes[i], 1e-6) << i;
    }
    EXPECT_EQ(stars[0].name, "Sirius");
    EXPECT_EQ(stars[0].designation, "alp CMa");
    EXPECT_EQ(stars[1].name, "Testar");  // trixel 5 record takes the third name
    EXPECT_EQ(stars[1].designation, "gam Tst");
    EXPECT_EQ(stars[2].name, "");
    EXPECT_EQ(stars[2].designation, "bet Tst");
    EXPECT_EQ(stars[3].name, "");
    EXPECT_EQ(stars[3].designation, "");

    // A star without proper motion keeps its place exactly (to the file's 1e-6 h, 1e-5 deg).
    const zg::Star& b = stars[2];
    EXPECT_NEAR(b.ra_j2000, 15.0 * kPi / 180.0, 1e-12);
    EXPECT_NEAR(b.dec_j2000, 10.0 * kPi / 180.0, 1e-12);
    EXPECT_NEAR(b.b_minus_v, 1.2f, 1e-6);
    EXPECT_EQ(b.spectral_type, "K0");
    EXPECT_EQ(b.hd, 2u);
    // RA 23.5 h at dec -70.
    EXPECT_NEAR(stars[1].ra_j2000, 23.5 * kPi / 12.0, 1e-12);
    EXPECT_NEAR(stars[1].b_minus_v, -0.2f, 1e-6);
    // The pole (RA 0, Dec +90) decodes without NaN.
    EXPECT_NEAR(stars[4].dec_j2000, kPi / 2, 1e-12);
    EXPECT_TRUE(std::isfinite(stars[4].ra_j2000));

    // Sirius: moved from J1991.25 to J2000.0 along its proper motion; compare with ERFA's
    // eraPmpx (same linear model, zero parallax, observer at the barycentre).
    const zg::Star& sirius = stars[0];
    const double ra0 = 6.752569 * kPi / 12.0;
    const double dec0 = -16.71314 * kPi / 180.0;
    const double pmr = -546.0 / 1000.0 * kArcsec / std::cos(dec0);
    const double pmd = -1223.1 / 1000.0 * kArcsec;
    double pob[3] = {0.0, 0.0, 0.0};
    double pco[3];
    eraPmpx(ra0, dec0, pmr, pmd, 0.0, 0.0, (kJ2000 - kHipparcosEpochJd) / 365.25, pob, pco);
    double ra_ref = 0.0;
    double dec_ref = 0.0;
    eraC2s(pco, &ra_ref, &dec_ref);
    constexpr double kEpochTolerance = 1e-6 * kArcsec;  // same model: round-off only
    EXPECT_NEAR(sirius.ra_j2000, eraAnp(ra_ref), kEpochTolerance / std::cos(dec_ref));
    EXPECT_NEAR(sirius.dec_j2000, dec_ref, kEpochTolerance);
    EXPECT_NEAR(sirius.pm_ra_mas_per_yr, -546.0, 0.01);
    EXPECT_NEAR(sirius.pm_dec_mas_per_yr, -1223.1, 0.01);
    EXPECT_NEAR(sirius.parallax_mas, 379.0, 1e-9);
    EXPECT_EQ(sirius.hd, 48915u);
}

std::string ByteOrderName(const ::testing::TestParamInfo<bool>& param_info) {
    return param_info.param ? "BigEndian" : "LittleEndian";
}
INSTANTIATE_TEST_SUITE_P(ByteOrder, StarCatalogSyntheticTest, ::testing::Bool(), ByteOrderName);

TEST(StarCatalogErrors, MissingDirectoryNamesPathAndPackage) {
    const fs::path dir = fs::path(ZENITH_BINARY_DIR) / "no_such_star_directory";
    const std::string message = LoadError(6.5, dir);
    EXPECT_NE(message.find(dir.string()), std::string::npos) << message;
    EXPECT_NE(message.find("apt-get install kstars-data"), std::string::npos) << message;
    EXPECT_NE(message.find("ZENITH_STAR_DIR"), std::string::npos) << message;
}

TEST(StarCatalogErrors, MissingOneFileNamesIt) {
    const fs::path dir = WriteSyntheticCatalogue("missing_unnamed", false);
    fs::remove(dir / "unnamedstars.dat");
    const std::string message = LoadError(6.5, dir);
    EXPECT_NE(message.find((dir / "unnamedstars.dat").string()), std::string::npos) << message;
}

TEST(StarCatalogErrors, TruncatedFilesNameFileOffsetAndExpectation) {
    const std::string full = StarFile(UnnamedStars(), false);
    // Cut inside the preamble, the field table, the index, the trailer and the last record.
    for (std::size_t cut : {std::size_t{50}, std::size_t{140}, std::size_t{320}, std::size_t{407},
                            full.size() - 10}) {
        const fs::path dir = WriteSyntheticCatalogue("truncated", false);
        WriteFile(dir / "unnamedstars.dat", full.substr(0, cut));
        const std::string message = LoadError(99.0, dir);
        SCOPED_TRACE("cut at " + std::to_string(cut) + ": " + message);
        EXPECT_NE(message.find((dir / "unnamedstars.dat").string()), std::string::npos);
        EXPECT_NE(message.find("offset"), std::string::npos);
        EXPECT_NE(message.find("expected"), std::string::npos);
    }
    // Empty file.
    const fs::path dir = WriteSyntheticCatalogue("empty", false);
    WriteFile(dir / "namedstars.dat", "");
    EXPECT_NE(LoadError(6.5, dir).find("truncated"), std::string::npos);
}

TEST(StarCatalogErrors, CorruptHeadersAreReported) {
    const std::string good = StarFile(UnnamedStars(), false);
    struct Case {
        std::size_t offset;
        char value;
        const char* expect;
    };
    const std::vector<Case> cases = {
        {124, 'X', "byte-order mark"},               // BOM
        {126, 2, "version"},                         // format version
        {129, 'Q', "field 0"},                       // first field name
        {129 + 11 * 16 + 4, 9, "index entry id 0"},  // first index entry id
    };
    for (const Case& c : cases) {
        std::string bad = good;
        bad[c.offset] = c.value;
        const fs::path dir = WriteSyntheticCatalogue("corrupt", false);
        WriteFile(dir / "unnamedstars.dat", bad);
        const std::string message = LoadError(6.5, dir);
        EXPECT_NE(message.find(c.expect), std::string::npos) << message;
        EXPECT_NE(message.find("offset " + std::to_string(c.offset)), std::string::npos) << message;
    }
    // A record whose Dec is out of range.
    std::string bad = good;
    const std::size_t first_record = good.size() - 5 * 32;
    bad[first_record + 4 + 3] = 0x7F;  // Dec high byte (little endian)
    const fs::path dir = WriteSyntheticCatalogue("corrupt_record", false);
    WriteFile(dir / "unnamedstars.dat", bad);
    const std::string message = LoadError(99.0, dir);
    EXPECT_NE(message.find("Dec in [-90, 90]"), std::string::npos) << message;
}

// Every truncation and every single-byte corruption of each file either loads or throws
// CatalogError: no crash, no other exception (the sanitizer build checks memory safety too).
TEST(StarCatalogErrors, NoCrashOnAnyTruncationOrByteCorruption) {
    const fs::path dir = WriteSyntheticCatalogue("fuzz", false);
    for (const char* file : {"namedstars.dat", "starnames.dat", "unnamedstars.dat"}) {
        std::ifstream in(dir / file, std::ios::binary);
        const std::string good((std::istreambuf_iterator<char>(in)),
                               std::istreambuf_iterator<char>());
        std::vector<std::string> variants;
        for (std::size_t n = 0; n < good.size(); ++n) variants.push_back(good.substr(0, n));
        for (std::size_t i = 0; i < good.size(); ++i) {
            for (char value : {'\x00', '\x7F', '\xFF'}) {
                std::string bad = good;
                bad[i] = value;
                variants.push_back(bad);
            }
        }
        for (const std::string& variant : variants) {
            WriteFile(dir / file, variant);
            try {
                zg::StarCatalog::Load(99.0, dir);
            } catch (const zg::CatalogError&) {
            }
        }
        WriteFile(dir / file, good);
    }
}

TEST(StarCatalogErrors, NameCountMustMatchNamedStars) {
    const fs::path dir = WriteSyntheticCatalogue("name_count", false);
    WriteFile(dir / "starnames.dat", NameFile({{"alp CMa", "Sirius"}}, false));
    const std::string message = LoadError(6.5, dir);
    EXPECT_NE(message.find("starnames.dat"), std::string::npos) << message;
    EXPECT_NE(message.find("expected 3 name records"), std::string::npos) << message;
}

TEST(StarCatalogErrors, NanLimitIsRejected) {
    const fs::path dir = WriteSyntheticCatalogue("nan_limit", false);
    EXPECT_NE(LoadError(std::nan(""), dir).find("magnitude_limit"), std::string::npos);
}

TEST(StarCatalogDirectory, FromEnvironment) {
    const fs::path dir = WriteSyntheticCatalogue("environment", false);
    const char* previous = std::getenv("ZENITH_STAR_DIR");
    const std::optional<std::string> saved =
        previous ? std::optional<std::string>(previous) : std::nullopt;
    ASSERT_EQ(setenv("ZENITH_STAR_DIR", dir.c_str(), 1), 0);
    EXPECT_EQ(zg::DefaultStarDirectory(), dir);
    EXPECT_EQ(zg::StarCatalog::Load(99.0).stars().size(), 8u);
    ASSERT_EQ(setenv("ZENITH_STAR_DIR", "", 1), 0);
    EXPECT_EQ(zg::DefaultStarDirectory(), fs::path("/usr/share/kstars"));
    if (saved) {
        setenv("ZENITH_STAR_DIR", saved->c_str(), 1);
    } else {
        unsetenv("ZENITH_STAR_DIR");
    }
}

// ---------------------------------------------------------------------------------------------
// Reader on the installed kstars-data (CI installs it; skipped only where it is absent).

std::optional<fs::path> InstalledCatalogue() {
    const fs::path dir = zg::DefaultStarDirectory();
    for (const char* file : {"namedstars.dat", "unnamedstars.dat", "starnames.dat"}) {
        if (!fs::exists(dir / file)) return std::nullopt;
    }
    return dir;
}

#define REQUIRE_INSTALLED_CATALOGUE(dir)                                                      \
    const std::optional<fs::path> dir = InstalledCatalogue();                                 \
    if (!dir) {                                                                               \
        GTEST_SKIP() << "kstars-data star files not found in " << zg::DefaultStarDirectory()  \
                     << "; apt-get install kstars-data (or set ZENITH_STAR_DIR) to run this"; \
    }

struct KnownStar {
    const char* name;
    // J2000.0 ICRS place, epoch J2000 (SIMBAD, from the Hipparcos new reduction).
    double ra_h, ra_m, ra_s;
    double dec_sign, dec_d, dec_m, dec_s;
    double pm_ra_mas_per_yr, pm_dec_mas_per_yr;  // SIMBAD
    double magnitude_v, b_minus_v;               // values this catalogue holds
};

// Position within the file's quantisation (1e-6 h = 54 mas, 1e-5 deg = 36 mas) plus the
// difference between the original Hipparcos and the new reduction carried to J2000.
constexpr double kKnownPositionTolerance = 0.1 * kArcsec;
// The catalogue's proper motions differ from SIMBAD's by up to 5.2 mas/yr (Canopus: 17.5, 28.4
// against 19.93, 23.24); an error of scale or a missing cos(dec) would be far larger (Polaris:
// 45.5 mas/yr in RA * cos(dec) would be 3500 mas/yr in RA).
constexpr double kKnownPmToleranceMasPerYr = 6.0;
constexpr double kKnownPhotometryTolerance = 0.011;  // values stored to 0.01

const KnownStar kKnownStars[] = {
    {"Sirius", 6, 45, 8.91728, -1, 16, 42, 58.0171, -546.01, -1223.07, -1.44, 0.00},
    {"Vega", 18, 36, 56.33635, +1, 38, 47, 1.2802, 200.94, 286.23, 0.03, 0.00},
    {"Arcturus", 14, 15, 39.67207, +1, 19, 10, 56.6730, -1093.39, -2000.06, 0.16, 1.14},
    {"Betelgeuse", 5, 55, 10.30536, +1, 7, 24, 25.4304, 27.54, 11.30, 0.57, 1.74},
    {"Polaris", 2, 31, 49.09456, +1, 89, 15, 50.7923, 44.48, -11.85, 2.00, 0.62},
    {"Canopus", 6, 23, 57.10988, -1, 52, 41, 44.3810, 19.93, 23.24, -0.63, 0.17},
    {"Rigel", 5, 14, 32.27210, -1, 8, 12, 5.8981, 1.31, 0.50, 0.28, 0.02},
};

TEST(StarCatalogInstalled, KnownStarsMatchReferencePlaces) {
    REQUIRE_INSTALLED_CATALOGUE(dir);
    const zg::StarCatalog catalog = zg::StarCatalog::Load(6.5, *dir);
    for (const KnownStar& k : kKnownStars) {
        SCOPED_TRACE(k.name);
        const zg::Star* s = FindByName(catalog, k.name);
        ASSERT_NE(s, nullptr);
        const double ra = (k.ra_h + k.ra_m / 60.0 + k.ra_s / 3600.0) * kPi / 12.0;
        const double dec = k.dec_sign * (k.dec_d + k.dec_m / 60.0 + k.dec_s / 3600.0) * kPi / 180.0;
        EXPECT_NEAR(eraAnpm(s->ra_j2000 - ra) * std::cos(dec), 0.0, kKnownPositionTolerance);
        EXPECT_NEAR(s->dec_j2000, dec, kKnownPositionTolerance);
        EXPECT_NEAR(s->pm_ra_mas_per_yr, k.pm_ra_mas_per_yr, kKnownPmToleranceMasPerYr);
        EXPECT_NEAR(s->pm_dec_mas_per_yr, k.pm_dec_mas_per_yr, kKnownPmToleranceMasPerYr);
        EXPECT_NEAR(s->magnitude_v, k.magnitude_v, kKnownPhotometryTolerance);
        EXPECT_NEAR(s->b_minus_v, k.b_minus_v, kKnownPhotometryTolerance);
    }
    // Against the usual Johnson values: Sirius V = -1.46, B-V = 0.00; Betelgeuse (variable)
    // is listed with B-V 1.85 in the Bright Star Catalogue.
    const zg::Star* sirius = FindByName(catalog, "Sirius");
    EXPECT_NEAR(sirius->magnitude_v, -1.46, 0.05);
    EXPECT_EQ(sirius->hd, 48915u);
    EXPECT_EQ(sirius->designation, "alp CMa");
    EXPECT_EQ(sirius->spectral_type, "A0");
    EXPECT_GT(FindByName(catalog, "Betelgeuse")->b_minus_v, 1.5f);
    EXPECT_GT(sirius->parallax_mas, 370.0);
}

TEST(StarCatalogInstalled, CountsSortingAndRanges) {
    REQUIRE_INSTALLED_CATALOGUE(dir);
    const auto start = std::chrono::steady_clock::now();
    const zg::StarCatalog catalog = zg::StarCatalog::Load(6.5, *dir);
    const double load_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    const zg::StarCatalog all = zg::StarCatalog::Load(99.0, *dir);
    std::cout << "[ INFO     ] " << catalog.stars().size() << " stars to V = 6.5 of "
              << all.stars().size() << "; load to 6.5 took " << load_ms << " ms\n";
    ::testing::Test::RecordProperty("stars_to_6_5", static_cast<int>(catalog.stars().size()));
    ::testing::Test::RecordProperty("load_ms", std::to_string(load_ms));

    // About 9,000 stars brighter than 6.5 in the whole sky (Bright Star Catalogue: 9,110
    // objects to ~6.5); this catalogue has 8,411.
    EXPECT_GT(catalog.stars().size(), 8000u);
    EXPECT_LT(catalog.stars().size(), 9500u);
    EXPECT_GT(all.stars().size(), 40000u);  // complete to V = 8.0
    EXPECT_LE(all.stars().back().magnitude_v, 8.2f);

    const auto& stars = catalog.stars();
    EXPECT_TRUE(std::is_sorted(stars.begin(), stars.end(), [](const auto& a, const auto& b) {
        return a.magnitude_v < b.magnitude_v;
    }));
    EXPECT_EQ(stars.front().name, "Sirius");
    EXPECT_LE(stars.back().magnitude_v, 6.5f);
    for (const zg::Star& s : all.stars()) {
        ASSERT_GE(s.ra_j2000, 0.0);
        ASSERT_LT(s.ra_j2000, 2.0 * kPi);
        ASSERT_LE(std::abs(s.dec_j2000), kPi / 2);
        ASSERT_LT(std::hypot(s.pm_ra_mas_per_yr, s.pm_dec_mas_per_yr), 11000.0);
        ASSERT_GE(s.b_minus_v, -0.5f);
        ASSERT_LE(s.b_minus_v, 6.0f);
    }
    std::size_t named = 0;
    for (const zg::Star& s : stars) named += s.name.empty() ? 0u : 1u;
    EXPECT_GT(named, 200u);  // 223 proper names to 6.5
}

// ---------------------------------------------------------------------------------------------
// Apparent place against ERFA.

// ERFA reference at one date: eraPmpx (linear space motion, zero parallax, at the
// barycentre) -> eraAb with the Earth's barycentric velocity from eraEpv00 -> eraPnm06a
// (bias-precession-nutation matrix, IAU 2006/2000A). No light deflection, as in ApparentTod.
// Differences expected: heliocentric vs barycentric Earth velocity (Sun's motion about the
// barycentre, <= 15 m/s: 10 mas), IAU 2000B vs 2000A nutation (1 mas), the ephemeris.
class ErfaApparentTod {
  public:
    explicit ErfaApparentTod(double jd_tt) : jd_tt_(jd_tt) {
        double pvh[2][3];
        double pvb[2][3];
        eraEpv00(jd_tt, 0.0, pvh, pvb);
        for (int i = 0; i < 3; ++i) v_[i] = pvb[1][i] * ERFA_AULT / ERFA_DAYSEC;  // au/d -> c
        sun_distance_au_ = eraPm(pvh[0]);
        bm1_ = std::sqrt(1.0 - eraPdp(v_, v_));
        eraPnm06a(jd_tt, 0.0, rnpb_);
    }

    glm::dvec3 operator()(const zg::Star& s) const {
        const double pmr = s.pm_ra_mas_per_yr / 1000.0 * kArcsec / std::cos(s.dec_j2000);
        const double pmd = s.pm_dec_mas_per_yr / 1000.0 * kArcsec;
        double pob[3] = {0.0, 0.0, 0.0};
        double pco[3];
        eraPmpx(s.ra_j2000, s.dec_j2000, pmr, pmd, 0.0, 0.0, (jd_tt_ - kJ2000) / 365.25, pob, pco);
        double ppr[3];
        eraAb(pco, v_, sun_distance_au_, bm1_, ppr);
        double tod[3];
        eraRxp(rnpb_, ppr, tod);
        return {tod[0], tod[1], tod[2]};
    }

  private:
    double jd_tt_;
    // ERFA's C API takes non-const pointers even for inputs.
    mutable double v_[3];
    double sun_distance_au_;
    double bm1_;
    mutable double rnpb_[3][3];
};

// Required accuracy of the apparent place; measured worst case is reported by the test.
constexpr double kApparentTolerance = 0.1 * kArcsec;

TEST(StarApparentTod, MatchesErfaOnSyntheticStars) {
    const fs::path dir = WriteSyntheticCatalogue("apparent", false);
    const zg::StarCatalog catalog = zg::StarCatalog::Load(99.0, dir);
    double worst = 0.0;
    // Calendar dates as TT (the time scale does not matter for this comparison).
    const int dates[][3] = {{1950, 1, 1}, {1987, 9, 23}, {2000, 1, 1},
                            {2024, 4, 8}, {2061, 7, 28}, {2100, 12, 31}};
    for (const auto& date : dates) {
        double jd0 = 0.0;
        double mjd = 0.0;
        ASSERT_EQ(eraCal2jd(date[0], date[1], date[2], &jd0, &mjd), 0);
        const double jd_tt = jd0 + mjd + 0.3;
        const std::vector<glm::dvec3> apparent = catalog.ApparentTod(jd_tt);
        ASSERT_EQ(apparent.size(), catalog.stars().size());
        const ErfaApparentTod reference(jd_tt);
        for (std::size_t i = 0; i < apparent.size(); ++i) {
            const double error = zg::AngleBetween(apparent[i], reference(catalog.stars()[i]));
            worst = std::max(worst, error);
            EXPECT_LT(error, kApparentTolerance) << date[0] << " star " << i;
            EXPECT_NEAR(glm::length(apparent[i]), 1.0, 1e-15);
        }
    }
    std::cout << "[ INFO     ] worst apparent-place difference from ERFA: " << worst / kArcsec
              << " arcsec\n";
}

TEST(StarApparentTod, MatchesErfaOnInstalledCatalogue) {
    REQUIRE_INSTALLED_CATALOGUE(dir);
    const zg::StarCatalog catalog = zg::StarCatalog::Load(6.5, *dir);
    double worst = 0.0;
    double slowest_ms = 0.0;
    for (double year : {1950.0, 1975.5, 2000.0, 2025.25, 2050.0, 2075.75, 2100.0}) {
        const double jd_tt = kJ2000 + (year - 2000.0) * 365.25;
        const auto start = std::chrono::steady_clock::now();
        const std::vector<glm::dvec3> apparent = catalog.ApparentTod(jd_tt);
        const std::chrono::duration<double, std::milli> took =
            std::chrono::steady_clock::now() - start;
        slowest_ms = std::max(slowest_ms, took.count());
        ASSERT_EQ(apparent.size(), catalog.stars().size());
        const ErfaApparentTod reference(jd_tt);
        for (std::size_t i = 0; i < apparent.size(); ++i) {
            const zg::Star& star = catalog.stars()[i];
            const double error = zg::AngleBetween(apparent[i], reference(star));
            worst = std::max(worst, error);
            ASSERT_LT(error, kApparentTolerance) << year << " HD " << star.hd << " " << star.name;
        }
    }
    std::cout << "[ INFO     ] worst apparent-place difference from ERFA over "
              << catalog.stars().size() << " stars, 1950-2100: " << worst / kArcsec
              << " arcsec; one ApparentTod call took up to " << slowest_ms << " ms\n";
}

// ---------------------------------------------------------------------------------------------
// Photometry and colour.

TEST(StarIlluminance, ZeroPointAndPogsonRatio) {
    EXPECT_DOUBLE_EQ(zg::IlluminanceFromMagnitude(0.0), zg::kZeroMagnitudeIlluminance);
    EXPECT_NEAR(zg::kZeroMagnitudeIlluminance, std::pow(10.0, -14.18 / 2.5), 1e-18);
    for (double m : {-26.74, -1.46, 0.0, 3.3, 6.5}) {
        EXPECT_NEAR(zg::IlluminanceFromMagnitude(m) / zg::IlluminanceFromMagnitude(m + 5.0), 100.0,
                    1e-12);
    }
    // The Sun: ~1.06e5 lux with this zero point (see stars.h).
    EXPECT_NEAR(zg::IlluminanceFromMagnitude(-26.74), 1.057e5, 0.005e5);
}

TEST(StarColour, TemperatureFormulaAndClamp) {
    EXPECT_NEAR(zg::TemperatureFromBMinusV(0.65), 5778.4, 0.1);  // Sun: 5772 K nominal
    EXPECT_NEAR(zg::TemperatureFromBMinusV(0.0), 10125.2, 0.1);
    EXPECT_EQ(zg::TemperatureFromBMinusV(-2.0), zg::TemperatureFromBMinusV(zg::kMinBMinusV));
    EXPECT_EQ(zg::TemperatureFromBMinusV(9.0), zg::TemperatureFromBMinusV(zg::kMaxBMinusV));
    EXPECT_TRUE(std::isnan(zg::TemperatureFromBMinusV(std::nan(""))));
    for (double bv = -0.4; bv < 4.0; bv += 0.05) {
        EXPECT_GT(zg::TemperatureFromBMinusV(bv), zg::TemperatureFromBMinusV(bv + 0.05));
    }
}

// Linear Rec. 709 luminance (the Y row of the sRGB -> XYZ matrix, IEC 61966-2-1).
double Luminance(const glm::dvec3& rgb) {
    return 0.2126729 * rgb.r + 0.7151522 * rgb.g + 0.0721750 * rgb.b;
}

TEST(StarColour, UnitLuminanceAndHueOrder) {
    double previous_red_over_blue = 0.0;
    for (double bv = -0.4; bv <= 4.0; bv += 0.1) {
        const glm::dvec3 c = zg::ColourFromBMinusV(bv);
        SCOPED_TRACE(bv);
        EXPECT_NEAR(Luminance(c), 1.0, 1e-12);
        EXPECT_GE(c.r, 0.0);
        EXPECT_GE(c.g, 0.0);
        EXPECT_GE(c.b, 0.0);
        const double red_over_blue = c.r / std::max(c.b, 1e-300);
        EXPECT_GT(red_over_blue, previous_red_over_blue);  // redder with B-V
        previous_red_over_blue = red_over_blue;
    }
    const glm::dvec3 sun = zg::ColourFromBMinusV(0.65);
    EXPECT_LT(std::max({sun.r, sun.g, sun.b}) / std::min({sun.r, sun.g, sun.b}), 1.3);
    const glm::dvec3 betelgeuse = zg::ColourFromBMinusV(1.85);
    EXPECT_GT(betelgeuse.r, 2.0 * betelgeuse.b);
    const glm::dvec3 rigel = zg::ColourFromBMinusV(-0.03);
    EXPECT_GT(rigel.b, 1.2 * rigel.r);
    EXPECT_TRUE(std::isnan(zg::ColourFromBMinusV(std::nan("")).g));
}

// Chromaticity of the black body against the Planckian locus approximation of Kim et al.
// (2002, US patent 7,024,034; the cubic splines quoted on Wikipedia, "Planckian locus"), which
// is independent of the integration and colour matching functions used here.
TEST(StarColour, BlackBodyOnPlanckianLocus) {
    const glm::dmat3 xyz_from_rgb(0.4124564, 0.2126729, 0.0193339,  //
                                  0.3575761, 0.7151522, 0.1191920,  //
                                  0.1804375, 0.0721750, 0.9503041);
    for (double temperature : {3000.0, 4000.0, 5000.0, 6500.0, 10000.0, 15000.0}) {
        // Invert TemperatureFromBMinusV (monotonic) by bisection.
        double lo = zg::kMinBMinusV;
        double hi = zg::kMaxBMinusV;
        for (int i = 0; i < 100; ++i) {
            const double mid = 0.5 * (lo + hi);
            (zg::TemperatureFromBMinusV(mid) > temperature ? lo : hi) = mid;
        }
        const glm::dvec3 xyz = xyz_from_rgb * zg::ColourFromBMinusV(0.5 * (lo + hi));
        const double x = xyz.x / (xyz.x + xyz.y + xyz.z);
        const double y = xyz.y / (xyz.x + xyz.y + xyz.z);
        const double t = temperature;
        const double x_ref =
            t < 4000.0
                ? -0.2661239e9 / (t * t * t) - 0.2343589e6 / (t * t) + 0.8776956e3 / t + 0.179910
                : -3.0258469e9 / (t * t * t) + 2.1070379e6 / (t * t) + 0.2226347e3 / t + 0.240390;
        const double y_ref = t < 4000.0
                                 ? -0.9549476 * x_ref * x_ref * x_ref - 1.37418593 * x_ref * x_ref +
                                       2.09137015 * x_ref - 0.16748867
                                 : 3.0817580 * x_ref * x_ref * x_ref - 5.87338670 * x_ref * x_ref +
                                       3.75112997 * x_ref - 0.37001483;
        // Wyman et al.'s fit moves chromaticity by up to ~1e-3 here (5e-3 below 2,000 K).
        constexpr double kChromaticityTolerance = 0.002;
        EXPECT_NEAR(x, x_ref, kChromaticityTolerance) << temperature;
        EXPECT_NEAR(y, y_ref, kChromaticityTolerance) << temperature;
    }
}

}  // namespace
