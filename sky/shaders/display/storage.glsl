// The display pass's storage (zenith/sky/display.h): the meter's histogram and the exposure,
// which stays on the GPU from frame to frame (no read-back unless the host asks for it).
layout(std430, binding = kDisplayStorageBinding) buffer DisplayStorage {
    float display_ev100;         // the exposure the display pass applies (adapted)
    float display_target_ev100;  // this frame's metered exposure, before adaptation
    float display_log2_average;  // log2 of the metered log-average luminance (cd/m^2)
    uint display_valid;          // 0 until the first metered frame: no adaptation from nothing
    uint display_histogram[kDisplayHistogramBins];
};

// The bin of a pixel of luminance y, or -1 for a pixel the meter skips (not finite).
int DisplayHistogramBin(float y) {
    if (isnan(y) || isinf(y)) return -1;
    float l = log2(max(y, float(kDisplayMinMeteredLuminance)));
    float width = float(kDisplayHistogramMaxLog2 - kDisplayHistogramMinLog2) /
                  float(kDisplayHistogramBins);
    return clamp(int(floor((l - float(kDisplayHistogramMinLog2)) / width)), 0,
                 kDisplayHistogramBins - 1);
}
