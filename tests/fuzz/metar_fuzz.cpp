// libFuzzer harness for the METAR decoder and the METAR file parsers: no input may crash, hang,
// leak or trip a sanitizer; a report either decodes (with warnings) or throws MetarError.
//
// Built by hand until CMake wires ZENITH_FUZZ (clang 14, libclang-rt-14-dev):
//   clang++-14 -std=c++20 -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all \
//     -Isim/weather/include -Igeo/include tests/fuzz/metar_fuzz.cpp sim/weather/src/*.cpp \
//     geo/src/base/error.cpp geo/src/time.cpp -lfmt -o metar_fuzz
//   ./metar_fuzz -dict=tests/fuzz/metar.dict -max_len=512 tests/fuzz/corpus/metar
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "zenith/weather/metar.h"
#include "zenith/weather/metar_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    try {
        const zenith::weather::Metar m = zenith::weather::DecodeMetar(text);
        // Exercise every accessor and the summary on whatever was decoded.
        (void)m.Describe();
        (void)m.ceiling_ft();
        for (const auto& w : m.weather) (void)w.Describe();
        for (const auto& l : m.sky) (void)l.base_m();
    } catch (const zenith::weather::MetarError&) {
    }
    // The same bytes as a file of lines and as a CSV (the first byte picks the CSV header).
    try {
        (void)zenith::weather::ParseMetarLines(text, "fuzz.txt").Summary();
    } catch (const zenith::weather::MetarError&) {
    }
    try {
        const std::string csv =
            (size > 0 && (data[0] & 1) ? "valid,station,lat,lon,metar\n" : "metar\n") +
            std::string(text);
        (void)zenith::weather::ParseMetarCsv(csv, "fuzz.csv").Summary();
    } catch (const zenith::weather::MetarError&) {
    }
    return 0;
}
