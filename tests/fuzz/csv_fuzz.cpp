#include "flight_log_fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    zenith::fuzz::CheckFlightLog(data, size, zenith::track::LogFormat::kCsv);
    return 0;
}
