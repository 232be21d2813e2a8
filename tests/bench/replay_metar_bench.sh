#!/usr/bin/env bash
# Issue 17: replay frames/s with and without --metar-file, in one run (BENCHMARKS.md). Run from
# the source tree after building into build/. Prints, per case, the frame loop's rate as
# `zenith replay` reports it (frames rendered / seconds since the loop started) and, with a
# METAR file, how often the weather was set and the seconds that took. Two rounds, interleaved.
set -uo pipefail
z=build/sim/zenith; log=data/flights/glider_sisteron.igc; m=tests/sim/metar/bench_sisteron.csv
run() { local name=$1; shift; rm -rf /tmp/bench_out; local out; out=$("$z" replay "$log" --size 160x90 --out /tmp/bench_out "$@" 2>&1)
  local fps; fps=$(grep -o '[0-9.]* fps' <<<"$out" | tail -1); local w; w=$(grep -o 'METAR weather set.*' <<<"$out")
  echo "$name: $fps $w"; }
for rep in 1 2; do
  run "A clear  fps2 60s  " --fps 2 --start 300 --end 360
  run "B broken fps2 60s  " --fps 2 --start 300 --end 360 --weather broken
  run "C metar  fps2 60s  " --fps 2 --start 300 --end 360 --metar-file "$m"
  run "D broken fps0.02   " --fps 0.02 --weather broken
  run "E metar  fps0.02   " --fps 0.02 --metar-file "$m"
done
