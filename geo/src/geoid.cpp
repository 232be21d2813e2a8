#include "zenith/geo/geoid.h"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <optional>

namespace zenith::geo {
namespace {

constexpr std::size_t kGtxHeaderBytes = 40;
// GTX no-data value (NOAA VDatum).
constexpr float kGtxNoData = -88.8888f;
// A world grid at 1' spacing is 10801 x 21601 values (933 MB); nothing finer is in use.
constexpr std::uintmax_t kMaxGtxBytes = 1'000'000'000;

std::uint64_t BigEndian(const unsigned char* p, int bytes) {
    std::uint64_t u = 0;
    for (int i = 0; i < bytes; ++i) u = (u << 8) | p[i];
    return u;
}

double ReadBigEndianDouble(const unsigned char* p) {
    return std::bit_cast<double>(BigEndian(p, 8));
}

std::int32_t ReadBigEndianInt32(const unsigned char* p) {
    return std::bit_cast<std::int32_t>(static_cast<std::uint32_t>(BigEndian(p, 4)));
}

float ReadBigEndianFloat(const unsigned char* p) {
    return std::bit_cast<float>(static_cast<std::uint32_t>(BigEndian(p, 4)));
}

}  // namespace

GeoidGrid GeoidGrid::LoadGtx(const std::filesystem::path& path) {
    std::error_code error;
    const std::uintmax_t size = std::filesystem::file_size(path, error);
    if (error) {
        throw GeoidError(
            fmt::format("{}: cannot open geoid grid: {}", path.string(), error.message()));
    }
    if (size < kGtxHeaderBytes || size > kMaxGtxBytes) {
        throw GeoidError(
            fmt::format("{}: {} bytes is not the size of a GTX grid (expected {} to "
                        "{} bytes)",
                        path.string(), size, kGtxHeaderBytes, kMaxGtxBytes));
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) throw GeoidError(fmt::format("{}: cannot open geoid grid", path.string()));
    std::vector<unsigned char> bytes(static_cast<std::size_t>(size));
    in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size));
    if (!in) throw GeoidError(fmt::format("{}: read error", path.string()));
    GeoidGrid g;
    g.source_ = path.string();
    g.lat0_deg_ = ReadBigEndianDouble(&bytes[0]);
    g.lon0_deg_ = ReadBigEndianDouble(&bytes[8]);
    g.dlat_deg_ = ReadBigEndianDouble(&bytes[16]);
    g.dlon_deg_ = ReadBigEndianDouble(&bytes[24]);
    g.rows_ = ReadBigEndianInt32(&bytes[32]);
    g.cols_ = ReadBigEndianInt32(&bytes[36]);
    if (!(g.dlat_deg_ > 0.0) || !(g.dlon_deg_ > 0.0) || !(g.rows_ > 1) || !(g.cols_ > 1) ||
        !(std::abs(g.lat0_deg_) <= 90.0) || !std::isfinite(g.lon0_deg_) ||
        bytes.size() != kGtxHeaderBytes + std::size_t{4} * static_cast<std::size_t>(g.rows_) *
                                              static_cast<std::size_t>(g.cols_)) {
        throw GeoidError(fmt::format(
            "{}: not a GTX grid (header: lat0 {}, lon0 {}, spacing {} x {} deg, {} x {} values, "
            "file {} bytes)",
            path.string(), g.lat0_deg_, g.lon0_deg_, g.dlat_deg_, g.dlon_deg_, g.rows_, g.cols_,
            bytes.size()));
    }
    g.wraps_ = g.cols_ * g.dlon_deg_ >= 360.0 - 1e-9;
    g.values_.resize(static_cast<std::size_t>(g.rows_) * static_cast<std::size_t>(g.cols_));
    for (std::size_t i = 0; i < g.values_.size(); ++i) {
        g.values_[i] = ReadBigEndianFloat(&bytes[kGtxHeaderBytes + 4 * i]);
    }
    return g;
}

const GeoidGrid* GeoidGrid::Default() {
    static const std::optional<GeoidGrid> grid = []() -> std::optional<GeoidGrid> {
        const char* env = std::getenv("ZENITH_GEOID_GTX");
        const std::filesystem::path path =
            env && *env ? std::filesystem::path(env) : "/usr/share/proj/egm96_15.gtx";
        try {
            return LoadGtx(path);
        } catch (const GeoidError&) {
            return std::nullopt;
        }
    }();
    return grid ? &*grid : nullptr;
}

double GeoidGrid::UndulationAt(double lat_deg, double lon_deg) const {
    if (!std::isfinite(lat_deg) || !std::isfinite(lon_deg)) return 0.0;
    const double r = std::clamp((lat_deg - lat0_deg_) / dlat_deg_, 0.0, rows_ - 1.0);
    double c = (lon_deg - lon0_deg_) / dlon_deg_;
    if (wraps_) {
        c = std::fmod(c, static_cast<double>(cols_));
        if (c < 0.0) c += cols_;
    } else {
        c = std::clamp(c, 0.0, cols_ - 1.0);
    }
    const int r0 = std::min(static_cast<int>(r), rows_ - 2);
    const int c0 = std::min(static_cast<int>(c), wraps_ ? cols_ - 1 : cols_ - 2);
    const int c1 = wraps_ ? (c0 + 1) % cols_ : c0 + 1;
    const double fr = r - r0, fc = c - c0;
    auto v = [&](int row, int col) {
        const float x = values_[static_cast<std::size_t>(row) * static_cast<std::size_t>(cols_) +
                                static_cast<std::size_t>(col)];
        return x == kGtxNoData ? 0.0 : static_cast<double>(x);
    };
    return (1 - fr) * ((1 - fc) * v(r0, c0) + fc * v(r0, c1)) +
           fr * ((1 - fc) * v(r0 + 1, c0) + fc * v(r0 + 1, c1));
}

}  // namespace zenith::geo
