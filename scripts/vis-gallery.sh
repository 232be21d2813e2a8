#!/usr/bin/env bash
# Regenerates docs/gallery (README "zenith-plot") with BUILD_DIR/vis/zenith-plot.
set -euo pipefail
build=${1:?usage: vis-gallery.sh BUILD_DIR}
root=$(cd "$(dirname "$0")/.." && pwd)
plot=$build/vis/zenith-plot
out=$root/docs/gallery
mkdir -p "$out"
for preset in earth mars; do
    "$plot" transmittance --preset "$preset" --reference --out "$out/transmittance_$preset.png"
    "$plot" lut --preset "$preset" --lut transmittance --channel g \
        --out "$out/lut_transmittance_$preset.png"
    "$plot" lut --preset "$preset" --lut multiple-scattering --channel g \
        --out "$out/lut_multiple_scattering_$preset.png"
    "$plot" lut --preset "$preset" --lut irradiance --out "$out/lut_irradiance_$preset.png"
    "$plot" lut --preset "$preset" --lut sky-view --scale log --out "$out/lut_sky_view_$preset.png"
    "$plot" lut --preset "$preset" --lut aerial-perspective --slice 8 \
        --out "$out/lut_aerial_perspective_$preset.png"
done
"$plot" overview --flight "$root/data/flights/sunset_approach_sfo.kml" --out "$out/overview_sfo.png"
du -ch "$out"/*.png | tail -1
