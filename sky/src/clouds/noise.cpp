// Tileable cloud noise (noise.h): generation, and the on-disk cache.
#include "zenith/sky/clouds/noise.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <stdexcept>
#include <system_error>
#include <thread>

#include "zenith/base/error.h"

namespace zenith::sky::clouds {
namespace {

// --- hashing: every random number is a pure function of (seed, salt, lattice point) ----------

// Wellons' lowbias32: a full-avalanche 32-bit integer hash.
std::uint32_t Hash(std::uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    x ^= x >> 16;
    return x;
}

std::uint32_t Hash(const glm::ivec3& c, std::uint32_t seed) {
    std::uint32_t h = Hash(seed);
    h = Hash(h ^ static_cast<std::uint32_t>(c.x));
    h = Hash(h ^ static_cast<std::uint32_t>(c.y));
    return Hash(h ^ static_cast<std::uint32_t>(c.z));
}

// A uniform number in [0, 1) from 24 bits of a hash.
double Unit(std::uint32_t h) { return static_cast<double>(h >> 8) * (1.0 / 16777216.0); }

// Independent streams for each channel and octave of one seed.
std::uint32_t Salted(std::uint32_t seed, std::uint32_t salt) {
    return Hash(seed ^ Hash(salt * 0x9E3779B9U + 0x632BE5ABU));
}

int Mod(int a, int n) { return ((a % n) + n) % n; }

glm::ivec3 Mod(const glm::ivec3& a, const glm::ivec3& n) {
    return {Mod(a.x, n.x), Mod(a.y, n.y), Mod(a.z, n.z)};
}

double Fade(double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }

// Perlin 2002: the 12 cube-edge gradients (the 16 hash values repeat four of them).
double Gradient(std::uint32_t h, const glm::dvec3& d) {
    switch (h & 15U) {
        case 0:
            return d.x + d.y;
        case 1:
            return -d.x + d.y;
        case 2:
            return d.x - d.y;
        case 3:
            return -d.x - d.y;
        case 4:
            return d.x + d.z;
        case 5:
            return -d.x + d.z;
        case 6:
            return d.x - d.z;
        case 7:
            return -d.x - d.z;
        case 8:
            return d.y + d.z;
        case 9:
            return -d.y + d.z;
        case 10:
            return d.y - d.z;
        case 11:
            return -d.y - d.z;
        case 12:
            return d.x + d.y;
        case 13:
            return -d.y + d.z;
        case 14:
            return -d.x + d.y;
        default:
            return -d.y - d.z;
    }
}

// --- volumes ----------------------------------------------------------------------------------

// Cells along each axis for a noise with `cells_x` cells along x: proportional to the axis size,
// so cells are cubes in texels. Throws when an axis cannot hold a whole number of them.
glm::ivec3 CellsFor(int cells_x, const glm::ivec3& size, const char* what) {
    glm::ivec3 cells;
    for (int a = 0; a < 3; ++a) {
        const long long product = static_cast<long long>(cells_x) * size[a];
        if (product % size.x != 0 || product / size.x < 1) {
            throw ArgumentError(std::string(what) + " noise of size " + std::to_string(size.x) +
                                "x" + std::to_string(size.y) + "x" + std::to_string(size.z) +
                                ": axis " + "xyz"[a] + " cannot hold a whole number of its " +
                                std::to_string(cells_x) +
                                " cells along x; expected every axis to be a multiple of x / " +
                                std::to_string(cells_x) + " (e.g. 128x32x128)");
        }
        cells[a] = static_cast<int>(product / size.x);
    }
    return cells;
}

void CheckSize(const glm::ivec3& size, int minimum, const char* what) {
    if (!(size.x >= minimum && size.y >= 1 && size.z >= 1 && size.x <= 4096 && size.y <= 4096 &&
          size.z <= 4096)) {
        throw ArgumentError(
            std::string(what) + " noise size " + std::to_string(size.x) + "x" +
            std::to_string(size.y) + "x" + std::to_string(size.z) +
            ": expected each axis in [1, 4096] and x >= " + std::to_string(minimum));
    }
}

// Runs texel(x, y, z, out) over the volume, slices of z interleaved over `threads` threads. The
// result is independent of the thread count: each texel is a pure function of its position.
NoiseVolume Fill(const glm::ivec3& size, int channels, int threads,
                 const std::function<void(const glm::dvec3&, std::uint8_t*)>& texel) {
    NoiseVolume volume;
    volume.size = size;
    volume.channels = channels;
    volume.texels.resize(static_cast<std::size_t>(size.x) * static_cast<std::size_t>(size.y) *
                         static_cast<std::size_t>(size.z) * static_cast<std::size_t>(channels));
    const auto work = [&](int first) {
        for (int z = first; z < size.z; z += std::max(threads, 1)) {
            for (int y = 0; y < size.y; ++y) {
                for (int x = 0; x < size.x; ++x) {
                    // Texel centres in units of the volume: [0, 1) on every axis.
                    const glm::dvec3 u((x + 0.5) / size.x, (y + 0.5) / size.y, (z + 0.5) / size.z);
                    texel(u, &volume.texels[volume.Index(x, y, z, 0)]);
                }
            }
        }
    };
    threads = std::clamp(threads, 1, size.z);
    std::vector<std::thread> pool;
    for (int t = 1; t < threads; ++t) pool.emplace_back(work, t);
    work(0);
    for (std::thread& thread : pool) thread.join();
    return volume;
}

std::uint8_t Byte(double v) {
    return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255.0));
}

// Perlin FBM over `octaves` octaves from `cells` (doubling, amplitude halving), normalised by
// the amplitude sum; about [-1, 1], mostly within +-0.5.
double PerlinFbm(const glm::dvec3& u, const glm::ivec3& cells, int octaves, std::uint32_t seed) {
    double sum = 0.0, amplitude = 1.0, total = 0.0;
    glm::ivec3 period = cells;
    for (int o = 0; o < octaves; ++o) {
        sum += amplitude * TileablePerlin(u * glm::dvec3(period), period,
                                          Salted(seed, 100U + static_cast<std::uint32_t>(o)));
        total += amplitude;
        amplitude *= 0.5;
        period *= 2;
    }
    return sum / total;
}

// Inverted Worley FBM over three octaves from `cells` (S15's weights 0.625, 0.25, 0.125), in
// [0, 1].
double WorleyFbm(const glm::dvec3& u, const glm::ivec3& cells, std::uint32_t seed) {
    constexpr std::array<double, 3> kWeights = {0.625, 0.25, 0.125};
    double sum = 0.0;
    glm::ivec3 octave_cells = cells;
    for (int o = 0; o < 3; ++o) {
        const double f1 = TileableWorley(u * glm::dvec3(octave_cells), octave_cells,
                                         Salted(seed, 200U + static_cast<std::uint32_t>(o)));
        sum += kWeights[static_cast<std::size_t>(o)] * (1.0 - std::min(f1, 1.0));
        octave_cells *= 2;
    }
    return sum;
}

// --- cache file -------------------------------------------------------------------------------

constexpr char kMagic[8] = {'Z', 'C', 'N', 'O', 'I', 'S', 'E', '\n'};
// Written in the machine's byte order; a file from the other order fails this check.
constexpr std::uint32_t kByteOrderMark = 0x01020304U;

struct Header {
    char magic[8];
    std::uint32_t byte_order;
    std::uint32_t version;
    std::uint32_t seed;
    std::int32_t shape_size[3];
    std::int32_t detail_size;
    std::int32_t curl_size;
    std::uint64_t payload_bytes;
    std::uint64_t checksum;  // FNV-1a 64 of the payload
};
static_assert(sizeof(Header) == 56, "the cache header has no implicit padding");

std::uint64_t Fnv1a(const std::vector<std::uint8_t>& bytes, std::uint64_t h) {
    for (const std::uint8_t b : bytes) {
        h ^= b;
        h *= 1099511628211ULL;
    }
    return h;
}

std::uint64_t Checksum(const CloudNoise& noise) {
    std::uint64_t h = 14695981039346656037ULL;
    h = Fnv1a(noise.shape.texels, h);
    h = Fnv1a(noise.detail.texels, h);
    return Fnv1a(noise.curl.texels, h);
}

Header MakeHeader(const CloudNoiseSettings& settings) {
    Header header{};
    std::memcpy(header.magic, kMagic, sizeof kMagic);
    header.byte_order = kByteOrderMark;
    header.version = kCloudNoiseFormatVersion;
    header.seed = settings.seed;
    for (int a = 0; a < 3; ++a) header.shape_size[a] = settings.shape_size[a];
    header.detail_size = settings.detail_size;
    header.curl_size = settings.curl_size;
    return header;
}

std::size_t Bytes(const glm::ivec3& size, int channels) {
    return static_cast<std::size_t>(size.x) * static_cast<std::size_t>(size.y) *
           static_cast<std::size_t>(size.z) * static_cast<std::size_t>(channels);
}

// The volumes these settings produce, sized and empty.
CloudNoise EmptyNoise(const CloudNoiseSettings& s) {
    CloudNoise noise;
    noise.shape = {s.shape_size, 4, std::vector<std::uint8_t>(Bytes(s.shape_size, 4))};
    const glm::ivec3 detail(s.detail_size);
    noise.detail = {detail, 3, std::vector<std::uint8_t>(Bytes(detail, 3))};
    const glm::ivec3 curl(s.curl_size, s.curl_size, 1);
    noise.curl = {curl, 2, std::vector<std::uint8_t>(Bytes(curl, 2))};
    return noise;
}

// Built by appending: "'" + std::string + "'" trips GCC 12's false -Wrestrict (bug 105329).
std::string Quoted(const std::filesystem::path& path) {
    std::string quoted(1, '\'');
    quoted.append(path.string());
    quoted.push_back('\'');
    return quoted;
}

void WriteAll(int fd, const void* data, std::size_t size, const std::filesystem::path& path) {
    const auto* bytes = static_cast<const char*>(data);
    while (size > 0) {
        const ssize_t written = ::write(fd, bytes, size);
        if (written < 0) {
            if (errno == EINTR) continue;
            throw Error("cannot write noise cache " + Quoted(path) + ": " + std::strerror(errno));
        }
        bytes += written;
        size -= static_cast<std::size_t>(written);
    }
}

}  // namespace

double TileablePerlin(const glm::dvec3& p, const glm::ivec3& period, std::uint32_t seed) {
    const glm::dvec3 cell = glm::floor(p);
    const glm::dvec3 f = p - cell;
    const glm::ivec3 i(cell);
    const glm::dvec3 w(Fade(f.x), Fade(f.y), Fade(f.z));
    double corners[8];
    for (int c = 0; c < 8; ++c) {
        const glm::ivec3 o(c & 1, (c >> 1) & 1, (c >> 2) & 1);
        corners[c] = Gradient(Hash(Mod(i + o, period), seed), f - glm::dvec3(o));
    }
    const double x00 = corners[0] + w.x * (corners[1] - corners[0]);
    const double x10 = corners[2] + w.x * (corners[3] - corners[2]);
    const double x01 = corners[4] + w.x * (corners[5] - corners[4]);
    const double x11 = corners[6] + w.x * (corners[7] - corners[6]);
    const double y0 = x00 + w.y * (x10 - x00);
    const double y1 = x01 + w.y * (x11 - x01);
    return y0 + w.z * (y1 - y0);
}

double TileableWorley(const glm::dvec3& p, const glm::ivec3& cells, std::uint32_t seed) {
    const glm::dvec3 cell = glm::floor(p);
    const glm::ivec3 i(cell);
    double nearest2 = 1e300;
    for (int dz = -1; dz <= 1; ++dz) {
        for (int dy = -1; dy <= 1; ++dy) {
            for (int dx = -1; dx <= 1; ++dx) {
                const glm::ivec3 n = i + glm::ivec3(dx, dy, dz);
                // The feature point of the wrapped cell, placed in the unwrapped one: the
                // pattern repeats every `cells` (H16 §4.2.2 step 3).
                std::uint32_t h = Hash(Mod(n, cells), seed);
                glm::dvec3 feature(n);
                feature.x += Unit(h);
                h = Hash(h);
                feature.y += Unit(h);
                h = Hash(h);
                feature.z += Unit(h);
                const glm::dvec3 d = feature - p;
                nearest2 = std::min(nearest2, glm::dot(d, d));
            }
        }
    }
    return std::sqrt(nearest2);
}

NoiseVolume GenerateShapeNoise(std::uint32_t seed, glm::ivec3 size, int threads) {
    CheckSize(size, 4, "shape");
    // Perlin FBM from 8 cells (3 octaves) and the Worley FBM that dilates it from 4 cells, as in
    // Hillaire's TileableVolumeNoise (F16 App. D); G, B, A: Worley FBM from 4, 8 and 16 cells.
    const glm::ivec3 perlin_cells = CellsFor(8, size, "shape");
    const std::array<glm::ivec3, 3> worley_cells = {
        CellsFor(4, size, "shape"), CellsFor(8, size, "shape"), CellsFor(16, size, "shape")};
    const std::uint32_t perlin_seed = Salted(seed, 1);
    const std::array<std::uint32_t, 3> worley_seeds = {Salted(seed, 2), Salted(seed, 3),
                                                       Salted(seed, 4)};
    return Fill(size, 4, threads, [&](const glm::dvec3& u, std::uint8_t* out) {
        std::array<double, 3> worley;
        for (std::size_t k = 0; k < 3; ++k)
            worley[k] = WorleyFbm(u, worley_cells[k], worley_seeds[k]);
        // The FBM keeps mostly within +-0.5: 0.5 + fbm spans [0, 1].
        const double perlin =
            std::clamp(0.5 + PerlinFbm(u, perlin_cells, 3, perlin_seed), 0.0, 1.0);
        // S15 / TileableVolumeNoise: Remap(perlin, 0, 1, worley, 1), Perlin puffed up by Worley.
        out[0] = Byte(worley[0] + perlin * (1.0 - worley[0]));
        out[1] = Byte(worley[0]);
        out[2] = Byte(worley[1]);
        out[3] = Byte(worley[2]);
    });
}

NoiseVolume GenerateDetailNoise(std::uint32_t seed, int size, int threads) {
    const glm::ivec3 dims(size);
    CheckSize(dims, 2, "detail");
    const std::array<glm::ivec3, 3> cells = {glm::ivec3(2), glm::ivec3(4), glm::ivec3(8)};
    const std::array<std::uint32_t, 3> seeds = {Salted(seed, 11), Salted(seed, 12),
                                                Salted(seed, 13)};
    return Fill(dims, 3, threads, [&](const glm::dvec3& u, std::uint8_t* out) {
        for (std::size_t k = 0; k < 3; ++k) out[k] = Byte(WorleyFbm(u, cells[k], seeds[k]));
    });
}

NoiseVolume GenerateCurlNoise(std::uint32_t seed, int size, int threads) {
    const glm::ivec3 dims(size, size, 1);
    CheckSize(dims, 2, "curl");
    // Potential psi: a 2-D Perlin FBM from 4 cells (z held at 0, period 1 in z).
    const std::uint32_t psi_seed = Salted(seed, 21);
    std::vector<double> psi(static_cast<std::size_t>(size) * static_cast<std::size_t>(size));
    for (int y = 0; y < size; ++y) {
        for (int x = 0; x < size; ++x) {
            const glm::dvec3 u((x + 0.5) / size, (y + 0.5) / size, 0.0);
            psi[static_cast<std::size_t>(y * size + x)] =
                PerlinFbm(u, glm::ivec3(4, 4, 1), 3, psi_seed);
        }
    }
    // v = (d psi / dy, -d psi / dx) by central differences with wrap: divergence-free.
    const auto at = [&](int x, int y) {
        return psi[static_cast<std::size_t>(Mod(y, size) * size + Mod(x, size))];
    };
    std::vector<glm::dvec2> v(psi.size());
    double largest = 0.0;
    for (int y = 0; y < size; ++y) {
        for (int x = 0; x < size; ++x) {
            const glm::dvec2 c(0.5 * (at(x, y + 1) - at(x, y - 1)),
                               -0.5 * (at(x + 1, y) - at(x - 1, y)));
            v[static_cast<std::size_t>(y * size + x)] = c;
            largest = std::max(largest, glm::length(c));
        }
    }
    const double scale = largest > 0.0 ? 1.0 / largest : 0.0;
    (void)threads;  // 128^2 takes a few milliseconds
    NoiseVolume volume{dims, 2, std::vector<std::uint8_t>(Bytes(dims, 2))};
    for (int y = 0; y < size; ++y) {
        for (int x = 0; x < size; ++x) {
            const glm::dvec2 c = v[static_cast<std::size_t>(y * size + x)] * scale;
            volume.texels[volume.Index(x, y, 0, 0)] = Byte(0.5 + 0.5 * c.x);
            volume.texels[volume.Index(x, y, 0, 1)] = Byte(0.5 + 0.5 * c.y);
        }
    }
    return volume;
}

CloudNoise GenerateCloudNoise(const CloudNoiseSettings& settings) {
    CloudNoise noise;
    noise.shape = GenerateShapeNoise(settings.seed, settings.shape_size, settings.threads);
    noise.detail = GenerateDetailNoise(settings.seed, settings.detail_size, settings.threads);
    noise.curl = GenerateCurlNoise(settings.seed, settings.curl_size, settings.threads);
    return noise;
}

std::filesystem::path DefaultNoiseCacheDirectory() {
    const auto env = [](const char* name) -> const char* {
        const char* value = std::getenv(name);
        return value != nullptr && value[0] != '\0' ? value : nullptr;
    };
    if (const char* dir = env("ZENITH_CACHE_DIR")) return dir;
    if (const char* dir = env("XDG_CACHE_HOME")) return std::filesystem::path(dir) / "zenith";
    if (const char* home = env("HOME")) return std::filesystem::path(home) / ".cache" / "zenith";
    return std::filesystem::temp_directory_path() / "zenith";
}

std::string NoiseCacheFileName(const CloudNoiseSettings& s) {
    return "cloud-noise-v" + std::to_string(kCloudNoiseFormatVersion) + "-seed" +
           std::to_string(s.seed) + "-shape" + std::to_string(s.shape_size.x) + "x" +
           std::to_string(s.shape_size.y) + "x" + std::to_string(s.shape_size.z) + "-detail" +
           std::to_string(s.detail_size) + "-curl" + std::to_string(s.curl_size) + ".bin";
}

void WriteNoiseCache(const std::filesystem::path& file, const CloudNoiseSettings& settings,
                     const CloudNoise& noise) {
    std::error_code error;
    if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path(), error);
    if (error) {
        throw Error("cannot create noise cache directory " + Quoted(file.parent_path()) + ": " +
                    error.message());
    }
    Header header = MakeHeader(settings);
    header.payload_bytes =
        noise.shape.texels.size() + noise.detail.texels.size() + noise.curl.texels.size();
    header.checksum = Checksum(noise);
    // Unique per process and thread, so concurrent writers never share a temporary file.
    const std::filesystem::path temporary =
        file.string() + ".partial-" + std::to_string(::getpid()) + "-" +
        std::to_string(std::hash<std::thread::id>{}(std::this_thread::get_id()));
    const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) {
        throw Error("cannot write noise cache " + Quoted(temporary) + ": " + std::strerror(errno));
    }
    try {
        WriteAll(fd, &header, sizeof header, temporary);
        WriteAll(fd, noise.shape.texels.data(), noise.shape.texels.size(), temporary);
        WriteAll(fd, noise.detail.texels.data(), noise.detail.texels.size(), temporary);
        WriteAll(fd, noise.curl.texels.data(), noise.curl.texels.size(), temporary);
        if (::fsync(fd) != 0) {
            throw Error("cannot flush noise cache " + Quoted(temporary) + ": " +
                        std::strerror(errno));
        }
    } catch (...) {
        ::close(fd);
        std::filesystem::remove(temporary, error);
        throw;
    }
    ::close(fd);
    std::filesystem::rename(temporary, file, error);
    if (error) {
        std::filesystem::remove(temporary, error);
        throw Error("cannot rename noise cache into " + Quoted(file) + ": " + error.message());
    }
}

std::optional<CloudNoise> ReadNoiseCache(const std::filesystem::path& file,
                                         const CloudNoiseSettings& settings, std::string* problem) {
    const auto fail = [&](const std::string& why) -> std::optional<CloudNoise> {
        if (problem != nullptr) *problem = "noise cache " + Quoted(file) + ": " + why;
        return std::nullopt;
    };
    std::ifstream in(file, std::ios::binary);
    if (!in) return fail("cannot open (" + std::string(std::strerror(errno)) + ")");
    Header header{};
    if (!in.read(reinterpret_cast<char*>(&header), sizeof header)) return fail("truncated header");
    const Header expected = MakeHeader(settings);
    if (std::memcmp(header.magic, kMagic, sizeof kMagic) != 0) return fail("not a noise cache");
    if (header.byte_order != kByteOrderMark) return fail("written with another byte order");
    if (header.version != expected.version) {
        return fail("format version " + std::to_string(header.version) + ", expected " +
                    std::to_string(expected.version));
    }
    if (header.seed != expected.seed ||
        std::memcmp(header.shape_size, expected.shape_size, sizeof header.shape_size) != 0 ||
        header.detail_size != expected.detail_size || header.curl_size != expected.curl_size) {
        return fail("made for other settings (seed or sizes)");
    }
    CloudNoise noise = EmptyNoise(settings);
    const std::uint64_t payload =
        noise.shape.texels.size() + noise.detail.texels.size() + noise.curl.texels.size();
    if (header.payload_bytes != payload) return fail("payload size does not match the sizes");
    for (NoiseVolume* volume : {&noise.shape, &noise.detail, &noise.curl}) {
        if (!in.read(reinterpret_cast<char*>(volume->texels.data()),
                     static_cast<std::streamsize>(volume->texels.size()))) {
            return fail("truncated payload");
        }
    }
    if (in.peek() != std::char_traits<char>::eof()) return fail("trailing bytes after payload");
    if (Checksum(noise) != header.checksum) return fail("checksum mismatch (corrupt)");
    return noise;
}

CloudNoiseLoad LoadOrGenerateCloudNoise(const CloudNoiseSettings& settings,
                                        const std::filesystem::path& cache_directory) {
    const auto start = std::chrono::steady_clock::now();
    CloudNoiseLoad load;
    load.cache_file = cache_directory / NoiseCacheFileName(settings);
    std::error_code error;
    if (std::filesystem::exists(load.cache_file, error)) {
        if (auto cached = ReadNoiseCache(load.cache_file, settings, &load.cache_problem)) {
            load.noise = std::move(*cached);
            load.from_cache = true;
        }
    }
    if (!load.from_cache) {
        load.noise = GenerateCloudNoise(settings);
        try {
            WriteNoiseCache(load.cache_file, settings, load.noise);
        } catch (const std::exception& e) {
            load.cache_problem += (load.cache_problem.empty() ? "" : "; ") + std::string(e.what());
        }
    }
    load.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return load;
}

}  // namespace zenith::sky::clouds
