#!/usr/bin/env bash
# The long fuzz runs recorded in README.md (RELIABILITY): every harness of a ZENITH_FUZZ build
# for RUNS executions (default 1,000,000), one after another, each from its seeds plus what
# earlier runs found (build-fuzz/long-corpus/<name>). Prints one line per harness; a crash stops
# that harness, leaves its reproducer (crash-*, leak-*, timeout-*) in the current folder and makes
# the script exit non-zero.
# Usage: scripts/fuzz-long.sh [build-fuzz] [runs]
set -uo pipefail
build=${1:-build-fuzz}
runs=${2:-1000000}
source_dir=$(cd "$(dirname "$0")/.." && pwd)
status=0
for harness in "$build"/tests/fuzz/*_fuzz; do
    name=$(basename "$harness" _fuzz)
    corpus=$build/long-corpus/$name
    mkdir -p "$corpus"
    seeds=()
    case $name in
        igc | gpx | kml | csv) seeds=("$source_dir/data/flights") ;;
        atmosphere_json) seeds=("$source_dir/data/presets") ;;
        weather_json) seeds=("$source_dir/data/weather") ;;
    esac
    [[ -d $source_dir/tests/fuzz/corpus/$name ]] && seeds+=("$source_dir/tests/fuzz/corpus/$name")
    dict=()
    [[ -f $source_dir/tests/fuzz/$name.dict ]] && dict=("-dict=$source_dir/tests/fuzz/$name.dict")
    start=$(date +%s)
    log=$build/long-corpus/$name.log
    "$harness" -runs="$runs" -max_len=4096 -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
        "${dict[@]}" "$corpus" "${seeds[@]}" >"$log" 2>&1
    rc=$?
    executed=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$')
    peak=$(grep -o 'stat::peak_rss_mb: *[0-9]*' "$log" | grep -o '[0-9]*$')
    echo "$name: exit $rc, ${executed:-?} executions in $(($(date +%s) - start)) s, peak RSS ${peak:-?} MB, corpus $(ls "$corpus" | wc -l) inputs"
    ((rc == 0)) || status=1
done
exit $status
