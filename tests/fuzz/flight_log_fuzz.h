// One libFuzzer harness per flight-log format: the reader must either return a log whose samples
// are finite and strictly increasing in time, or throw FlightLogError. Anything else (a crash,
// a sanitizer report, another exception type, a broken invariant) is a finding.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "zenith/track/flight_log.h"

namespace zenith::fuzz {

inline void CheckFlightLog(const std::uint8_t* data, std::size_t size, track::LogFormat format) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    track::ReadOptions options;
    options.max_samples = 4096;  // thinning is exercised by long inputs
    try {
        const track::FlightLog log = track::ParseFlightLog(text, format, "<fuzz>", options);
        for (std::size_t i = 0; i < log.samples.size(); ++i) {
            const track::FlightSample& s = log.samples[i];
            if (!std::isfinite(s.time_s) || !std::isfinite(s.lat_deg) ||
                !std::isfinite(s.lon_deg)) {
                std::abort();
            }
            if (i > 0 && !(log.samples[i - 1].time_s < s.time_s)) std::abort();
        }
        (void)log.summary.ToString();
    } catch (const track::FlightLogError&) {
    }
}

}  // namespace zenith::fuzz
