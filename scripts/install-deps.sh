#!/usr/bin/env bash
# Installs the Debian 12 packages zenith needs to build, test and run. Installs only what is
# missing, so it is quick on a machine that has them. Needs root (or sudo).
set -euo pipefail

packages=(
    # toolchain
    build-essential cmake ninja-build ccache pkg-config python3
    # geo: geodesy, math, CLI, JSON, formatting; ERFA is the independent reference in tests
    libgeographiclib-dev libglm-dev libcli11-dev nlohmann-json3-dev libfmt-dev liberfa-dev
    # star catalogue (Hipparcos-based, with B-V and proper motions; GPL, read at run time)
    kstars-data
    # sky: headless OpenGL 4.5 (OSMesa, EGL surfaceless), glad2 loader generator
    libosmesa6-dev libegl-dev libegl-mesa0 libgl1-mesa-dri mesa-common-dev python3-glad
    # sky: linear algebra (the multiple scattering's plane-parallel column)
    libeigen3-dev
    # sky: frame output (HDR OpenEXR, tone-mapped PNG)
    libopenexr-dev libpng-dev
    # sim: flight logs (GPX/KML XML), EGM96 geoid grid for MSL -> WGS84 heights (egm96_15.gtx)
    libtinyxml2-dev proj-data
    # sim: replay's manifest hashes the log (xxHash); replay --video spawns ffmpeg
    libxxhash-dev ffmpeg
    # vis: zenith-plot (Debian's VTK 9 is X11-only: Xvfb + xauth for headless plots, xvfb-run)
    libvtk9-dev xvfb xauth
    # tests and benchmarks
    libgtest-dev libgmock-dev libbenchmark-dev
    # fuzzing the readers (ZENITH_FUZZ=ON, .ci/run's fuzz stage): clang's libFuzzer
    clang libclang-rt-14-dev
    # .ci/run checks the formatting
    clang-format
)

missing=()
for p in "${packages[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
        missing+=("$p")
    fi
done

if ((${#missing[@]} == 0)); then
    echo "install-deps: all ${#packages[@]} packages present"
    exit 0
fi

sudo=""
if [[ $(id -u) -ne 0 ]]; then
    command -v sudo >/dev/null || { echo "install-deps: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
    sudo="sudo"
fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
