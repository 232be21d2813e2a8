// The meter, second pass (one invocation): AutoExposureEV100's definition over the histogram
// (the log-average of the pixels between the 50th and 95th percentiles of luminance, each bin
// at its centre: within 0.025 EV of the CPU's sort), made darker at night
// (DisplayNightCompensationEV), then adapted toward over time:
// EV += (target - EV) (1 - exp(-dt / tau)).
layout(local_size_x = 1) in;
layout(location = 0) uniform float display_dt_over_tau;  // <= 0: no adaptation (snap)
layout(location = 1) uniform int display_night;          // 1: night compensation
layout(location = 2) uniform float display_compensation_ev;

void main() {
    uint n = 0u;
    for (int b = 0; b < kDisplayHistogramBins; ++b) n += display_histogram[b];
    if (n == 0u) return;  // nothing finite: keep the previous exposure
    // The same integer percentile bounds as AutoExposureEV100 (n < 4.5e7 pixels).
    uint first = n * uint(kDisplayMeteredLowPercentile) / 100u;
    uint last = max(first + 1u, n * uint(kDisplayMeteredHighPercentile) / 100u);
    float width = float(kDisplayHistogramMaxLog2 - kDisplayHistogramMinLog2) /
                  float(kDisplayHistogramBins);
    float sum = 0.0;
    uint start = 0u;
    for (int b = 0; b < kDisplayHistogramBins && start < last; ++b) {
        uint end = start + display_histogram[b];
        uint lo = max(start, first), hi = min(end, last);
        if (hi > lo) {
            float centre = float(kDisplayHistogramMinLog2) + (float(b) + 0.5) * width;
            sum += float(hi - lo) * max(centre, log2(float(kDisplayMinMeteredLuminance)));
        }
        start = end;
    }
    float log2_average = sum / float(last - first);
    float ev = float(DisplayMeteredEV100(log2_average));
    if (display_night != 0) ev += float(DisplayNightCompensationEV(exp2(log2_average)));
    ev = clamp(ev + display_compensation_ev, float(kDisplayMinEV100), float(kDisplayMaxEV100));
    display_target_ev100 = ev;
    display_log2_average = log2_average;
    if (display_valid != 0u && display_dt_over_tau > 0.0 && !isinf(display_dt_over_tau)) {
        display_ev100 += (ev - display_ev100) * (1.0 - exp(-display_dt_over_tau));
    } else {
        display_ev100 = ev;
    }
    display_valid = 1u;
}
