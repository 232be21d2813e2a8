// Weather map images (PNG and OpenEXR, through libpng and OpenEXR): a map or WeatherError. The
// first byte picks the extension; the rest is the file.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "zenith/sky/clouds/weather.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size < 1) return 0;
    const std::string extension = (data[0] & 1) ? ".exr" : ".png";
    const std::filesystem::path path =
        std::filesystem::temp_directory_path() /
        ("zenith_weather_map_fuzz_" + std::to_string(::getpid()) + extension);
    {
        std::ofstream file(path, std::ios::binary | std::ios::trunc);
        file.write(reinterpret_cast<const char*>(data + 1), static_cast<std::streamsize>(size - 1));
    }
    try {
        (void)zenith::sky::clouds::LoadWeatherMapImage(path);
    } catch (const zenith::sky::clouds::WeatherError&) {
    }
    std::filesystem::remove(path);
    return 0;
}
