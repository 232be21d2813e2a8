#!/usr/bin/env bash
# The README's first command: install what is missing, configure and build (Release) into
# ./build, then run the main job on built-in defaults: render the built-in scene to
# build/zenith.png (exposed, tone mapped) and build/zenith.exr (linear cd/m^2), and print where
# the Sun, Moon and stars are now.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)"

echo
echo "== zenith render (built-in scene: sunset over Zurich from 10 km) =="
build/sim/zenith render --out build/zenith.png
build/sim/zenith render --out build/zenith.exr
echo
echo "== zenith ephemeris (now, Royal Observatory Greenwich) =="
build/sim/zenith ephemeris
