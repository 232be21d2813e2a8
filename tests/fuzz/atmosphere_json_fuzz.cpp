// The atmosphere preset reader: a valid Atmosphere or AtmosphereError, nothing else.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "zenith/sky/atmosphere.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    try {
        (void)zenith::sky::ParseAtmosphereJson(text, "<fuzz>.json");
    } catch (const zenith::sky::AtmosphereError&) {
    }
    return 0;
}
