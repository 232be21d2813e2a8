#!/usr/bin/env bash
# The README's first command: install what is missing, configure and build (Release) into
# ./build, then run the main job on built-in defaults: replay a sample flight into
# build/replay/frame_*.png (and build/replay.mp4 when ffmpeg is installed), render the built-in
# scene to build/zenith.png (exposed, tone mapped) and build/zenith.exr (linear cd/m^2), and
# print where the Sun, Moon and stars are now.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)"

echo
echo "== zenith replay (sample flight: a sunset approach into San Francisco) =="
build/sim/zenith replay data/flights/sunset_approach_sfo.kml --out build/replay --fps 0.2 \
    --video build/replay.mp4
echo
echo "== zenith render (built-in scene: sunset over Zurich from 10 km) =="
build/sim/zenith render --out build/zenith.png
build/sim/zenith render --out build/zenith.exr
echo
echo "== zenith ephemeris (now, Royal Observatory Greenwich) =="
build/sim/zenith ephemeris
