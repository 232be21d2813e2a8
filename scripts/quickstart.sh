#!/usr/bin/env bash
# The README's first command: install what is missing, configure and build (Release) into
# ./build, then run the main job on built-in defaults.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)"

echo
echo "== zenith ephemeris (now, Royal Observatory Greenwich) =="
build/sim/zenith ephemeris
