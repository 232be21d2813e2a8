// The weather preset reader: a valid Weather or WeatherError, nothing else. Map files named by
// the input resolve against a directory that does not exist, so they fail as missing files.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "zenith/sky/clouds/weather.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    try {
        (void)zenith::sky::clouds::ParseWeatherJson(text, "/nonexistent-fuzz-dir/fuzz.json");
    } catch (const zenith::sky::clouds::WeatherError&) {
    }
    return 0;
}
