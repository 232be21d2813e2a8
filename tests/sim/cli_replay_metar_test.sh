#!/usr/bin/env bash
# `zenith replay --metar-file` end to end: the weather changes along the flight, the manifest
# records the METAR file, a resume with another file (or other station elevation) is refused
# naming it, shards write the same bytes as a whole run, and bad METAR input names the file or
# the flag. Fixtures: tests/sim/metar (synthetic; see its README).
# Usage: cli_replay_metar_test.sh path/to/zenith path/to/source
set -uo pipefail
zenith=$(realpath "$1")
source_dir=$(realpath "$2")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
source "$(dirname "$0")/check.sh"
log=$source_dir/data/flights/glider_sisteron.igc
metar=$source_dir/tests/sim/metar
# 7 frames, 10 s apart, over the first minute: station ZZSW goes from its 12:00 report to its
# 12:01 one.
common=(--fps 0.1 --start 0 --end 60 --size 64x36)

err=$("$zenith" replay "$log" "${common[@]}" --metar-file "$metar/reports_a.csv" \
    --out "$work/a" 2>&1); rc=$?
check "a replay with a METAR CSV exits 0" test $rc -eq 0
check "and writes 7 frames" test "$(ls "$work/a" | grep -c '^frame_.*\.png$')" -eq 7
check "the manifest records the METAR file" grep -q '"file": "reports_a.csv"' "$work/a/replay.json"
check "with its hash" bash -c "grep -A8 '\"metar\"' '$work/a/replay.json' | grep -q xxh3_128"
check "and where its heights are measured from" \
    grep -q '"station_elevation_m": "ground under the station (0 m)"' "$work/a/replay.json"
check "the notices say which station elevation" grep -q "ground zenith draws under them" <<<"$err"
check "the weather changed between frames (set more than once)" \
    grep -Eq "METAR weather set ([2-9]|[1-9][0-9]+) times" <<<"$err"
check "the first and last frames differ (12:00 and 12:01 reports)" \
    bash -c "! cmp -s '$work/a/frame_000000.png' '$work/a/frame_000006.png'"

# The same run again: everything skipped, nothing set.
err=$("$zenith" replay "$log" "${common[@]}" --metar-file "$metar/reports_a.csv" \
    --out "$work/a" 2>&1); rc=$?
check "a rerun with the same file resumes (exit 0, all skipped)" \
    exited_saying 0 "rendered 0, skipped 7"

# Another METAR file (one report differs) into the same folder: refused, naming it.
before=$(ls -l "$work/a" | md5sum)
err=$("$zenith" replay "$log" "${common[@]}" --metar-file "$metar/reports_b.csv" \
    --out "$work/a" 2>&1); rc=$?
check "a resume with another METAR file exits 2" test $rc -eq 2
check "and names the METAR file" grep -q 'metar.file: "reports_a.csv" in the folder' <<<"$err"
check "and its hash" grep -q 'metar.xxh3_128' <<<"$err"
check "and touches nothing" test "$(ls -l "$work/a" | md5sum)" = "$before"
# The same name with other bytes is refused too (the hash, not the name).
mkdir -p "$work/same_name" && cp "$metar/reports_b.csv" "$work/same_name/reports_a.csv"
err=$("$zenith" replay "$log" "${common[@]}" --metar-file "$work/same_name/reports_a.csv" \
    --out "$work/a" 2>&1); rc=$?
check "a file of the same name with other reports is refused by its hash" \
    exited_saying 2 "metar.xxh3_128"
err=$("$zenith" replay "$log" "${common[@]}" --metar-file "$metar/reports_a.csv" \
    --station-elevation 500 --out "$work/a" 2>&1); rc=$?
check "a resume with another --station-elevation is refused" \
    exited_saying 2 "metar.station_elevation_m"
err=$("$zenith" replay "$log" "${common[@]}" --out "$work/a" 2>&1); rc=$?
check "a resume without the METAR file is refused, naming it" \
    exited_saying 2 'metar: {.*reports_a.csv.*} in the folder, (none) now'

# Shards: the same bytes as the whole run (each frame's weather depends only on its time).
for k in 0 1 2; do
    "$zenith" replay "$log" "${common[@]}" --metar-file "$metar/reports_a.csv" --shard "$k/3" \
        --out "$work/shards" >/dev/null 2>&1
done
check "three shards equal the whole run" diff -r -x replay.json "$work/a" "$work/shards"

# A lines file without positions or times: one station, times from the report groups.
err=$("$zenith" replay "$log" "${common[@]}" --metar-file "$metar/reports_lines.txt" \
    --out "$work/lines" 2>&1); rc=$?
check "a lines file without times or positions works (exit 0)" test $rc -eq 0
check "and says all reports are one station's" grep -q "one station" <<<"$err"
check "and that the times came from the report groups" grep -q "ddhhmmZ group" <<<"$err"
check "the lines file's ZZSW matches the CSV's ZZSW frame at the start" \
    cmp -s "$work/a/frame_000000.png" "$work/lines/frame_000000.png"

# Bad input: named, exit 2, no folder.
printf '# no times\nZZSW 27006KT 6000 SCT030 24/12 Q1016\n' >"$work/untimed.txt"
err=$("$zenith" replay "$log" "${common[@]}" --metar-file "$work/untimed.txt" \
    --out "$work/bad" 2>&1); rc=$?
check "reports without a usable time: exit 2 naming file:line" \
    exited_saying 2 "untimed.txt:2" "usable time"
err=$("$zenith" replay "$log" "${common[@]}" --metar-file "$work/missing.csv" \
    --out "$work/bad" 2>&1); rc=$?
check "a missing METAR file: exit 2 naming it" exited_saying 2 "missing.csv"
err=$("$zenith" replay "$log" "${common[@]}" --metar-file "$metar/reports_a.csv" \
    --weather broken --out "$work/bad" 2>&1); rc=$?
check "--weather with --metar-file: exit 2 naming --weather" exited_saying 2 "--weather"
# A log with pressure altitudes only (every fix made a 'V' fix, no GNSS height): their heights
# come from the reports' QNH and temperature (tests/weather/altimetry_test.cpp has the numbers).
sed -E 's/^(B[0-9]{6}[0-9]{7}[NS][0-9]{8}[EW])A/\1V/' "$log" > "$work/pressure_only.igc"
pressure=(--fps 0.1 --start 0 --end 0 --size 64x36)
err=$("$zenith" replay "$work/pressure_only.igc" "${pressure[@]}" \
    --metar-file "$metar/reports_a.csv" --out "$work/p" 2>&1); rc=$?
check "a pressure-only log with METAR reports exits 0" test $rc -eq 0
check "its heights come from the reports' QNH and temperature" \
    grep -q "pressure altitude -> height through the reports' QNH and temperature" <<<"$err"

err=$("$zenith" replay "$log" "${common[@]}" --metar-file "$metar/reports_a.csv" \
    --station-elevation 20000 --out "$work/bad" 2>&1); rc=$?
check "--station-elevation 20000: exit 2 naming the flag and the range" \
    exited_saying 2 "--station-elevation" "9000"
check "no folder for any refused run" test ! -e "$work/bad"

report
