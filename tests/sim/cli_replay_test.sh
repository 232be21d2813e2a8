#!/usr/bin/env bash
# `zenith replay` end to end, as a careful user and a security reviewer would try it: a run killed
# at any point resumes to the same bytes as a whole run, shards write the same pixels, no path is
# ever handed to a shell, ffmpeg's failures are reported, signals give the conventional exit code.
# Usage: cli_replay_test.sh path/to/zenith path/to/source
set -uo pipefail
zenith=$(realpath "$1")
source_dir=$(realpath "$2")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
source "$(dirname "$0")/check.sh"
log=$source_dir/data/flights/glider_sisteron.igc
# 11 frames of a glider at 64x36; the night case puts the same flight at local midnight, where
# the stars show, and the cloud case flies it under the scattered cumulus.
# Two frame folders hold the same files, byte for byte (the settings file aside; hidden files
# count); the differences are printed when not.
same_frames() { diff -r -x replay.json "$1" "$2"; }
common=(--fps 0.5 --start 0 --end 20 --size 64x36)

# Whole runs, the reference bytes.
for case in day night clouds; do
    extra=()
    [[ $case == night ]] && extra=(--time-offset 36000)
    [[ $case == clouds ]] && extra=(--weather scattered_cumulus)
    "$zenith" replay "$log" "${common[@]}" "${extra[@]}" --out "$work/$case-whole" >/dev/null 2>&1
    check "$case: whole run writes 11 frames" \
        test "$(ls "$work/$case-whole" | grep -c '^frame_.*\.png$')" -eq 11

    # Killed (SIGKILL) after a random time, then resumed: the same bytes as the whole run.
    out=$work/$case-killed
    for delay in 0.3 0.9 1.7; do
        "$zenith" replay "$log" "${common[@]}" "${extra[@]}" --out "$out" >/dev/null 2>&1 &
        pid=$!
        sleep "$delay"
        kill -KILL "$pid" 2>/dev/null
        wait "$pid" 2>/dev/null
    done
    "$zenith" replay "$log" "${common[@]}" "${extra[@]}" --out "$out" >/dev/null 2>&1
    check "$case: killed three times, then resumed, equals the whole run" \
        same_frames "$work/$case-whole" "$out"

    # Every other frame removed and drawn again, each after other frames than in the whole run
    # (not only where a kill happened to fall): the same floats (EXR; a PNG's 8 bits hide a
    # frame that owes a few ulps to the one before it).
    "$zenith" replay "$log" "${common[@]}" "${extra[@]}" --format exr --out "$work/$case-exr" \
        >/dev/null 2>&1
    out=$work/$case-exr-alone
    cp -r "$work/$case-exr" "$out"
    rm "$out"/frame_00000[13579].exr
    "$zenith" replay "$log" "${common[@]}" "${extra[@]}" --format exr --out "$out" >/dev/null 2>&1
    check "$case: frames drawn again alone equal the whole run's" \
        same_frames "$work/$case-exr" "$out"

    # Three shards into one folder: the same bytes as the whole run.
    for k in 0 1 2; do
        "$zenith" replay "$log" "${common[@]}" "${extra[@]}" --shard "$k/3" \
            --out "$work/$case-shards" >/dev/null 2>&1
    done
    check "$case: three shards equal the whole run" \
        same_frames "$work/$case-whole" "$work/$case-shards"
done
# What a run killed while claiming the folder leaves (its settings candidate) is swept by the next.
stale="$work/day-killed/.replay.$(hostname).999999999.json"
echo '{}' >"$stale"
"$zenith" replay "$log" "${common[@]}" --out "$work/day-killed" >/dev/null 2>&1
check "a killed run's settings candidate is removed on resume" test ! -e "$stale"
check "night frames differ from day frames (stars, not a copy)" \
    bash -c "! cmp -s '$work/day-whole/frame_000005.png' '$work/night-whole/frame_000005.png'"

# A truncated frame is rendered again, not skipped.
truncate -s 100 "$work/day-whole/frame_000004.png"
err=$("$zenith" replay "$log" "${common[@]}" --out "$work/day-whole" 2>&1)
check "a truncated frame is redone" cmp -s "$work/day-whole/frame_000004.png" \
    "$work/day-killed/frame_000004.png"
check "and the run says so" grep -qi "frame_000004.png" <<<"$err"

# Other settings into the same folder are refused, naming the setting, and change nothing.
before=$(ls -l "$work/day-whole" | md5sum)
err=$("$zenith" replay "$log" "${common[@]/64x36/80x40}" --out "$work/day-whole" 2>&1); rc=$?
check "another --size into the same folder exits 2" test $rc -eq 2
check "and names the size" grep -q "80x40" <<<"$err"
check "and touches nothing" test "$(ls -l "$work/day-whole" | md5sum)" = "$before"

# No shell: quotes, semicolons and % in paths are only characters.
cd "$work" || exit 1
evil="v'; touch pwned; echo '.mp4"
"$zenith" replay "$log" "${common[@]}" --out "$work/o'dd %d; dir" --video "$work/$evil" \
    >/dev/null 2>&1; rc=$?
check "quotes and % in --out and --video: exit 0" test $rc -eq 0
check "nothing ran: no pwned file" test ! -e "$work/pwned"
check "the frames are in the folder named" test -s "$work/o'dd %d; dir/frame_000010.png"
if command -v ffprobe >/dev/null; then
    frames=$(ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames \
        -of csv=p=0 "$work/$evil")
    check "the video has one frame per planned frame (11)" test "$frames" = 11
fi

# A log with a gap: the video holds the last frame across it and keeps the flight's timing (it
# stopped at the first gap).
{
    echo "time,lat_deg,lon_deg,alt_wgs84_m"
    for t in 00 01 02 03 04 05; do echo "2024-06-21T12:00:${t}Z,47.0,8.0${t},1000"; done
    for t in 00 01 02 03 04 05; do echo "2024-06-21T12:01:${t}Z,47.0,8.1${t},1000"; done
} >"$work/gap.csv"
"$zenith" replay "$work/gap.csv" --fps 1 --size 64x36 --out "$work/gap" --video "$work/gap.mp4" \
    >/dev/null 2>&1
if command -v ffprobe >/dev/null; then
    frames=$(ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames \
        -of csv=p=0 "$work/gap.mp4")
    check "a gap is held in the video: 66 frames for 65 s at 1 fps" test "$frames" = 66
fi

# A failed encode is reported and fails the run (the video's folder does not exist).
err=$("$zenith" replay "$log" "${common[@]}" --out "$work/day-whole" \
    --video "$work/no/such/dir/v.mp4" 2>&1); rc=$?
check "ffmpeg's failure fails the run" test $rc -ne 0
check "and is reported with the video's path" grep -q "no/such/dir" <<<"$err"

# Bad requests: the flag is named and no folder is created.
err=$("$zenith" replay "$log" --size 0x0 --out "$work/zero" 2>&1); rc=$?
check "--size 0x0 exits 2 naming --size" exited_saying 2 --size
check "and creates no folder" test ! -e "$work/zero"
for bad in "--end inf" "--end 1e300" "--end 1e12" "--fps 0" "--fps nan" "--time-warp -1"; do
    # shellcheck disable=SC2086
    err=$(timeout 20 "$zenith" replay "$log" $bad --out "$work/bad" 2>&1); rc=$?
    check "$bad: refused at once (exit 2) naming ${bad%% *}" \
        exited_saying 2 "${bad%% *}"
done
check "no folder for any refused run" test ! -e "$work/bad"

# SIGTERM stops the run at a frame boundary with 128 + 15, and what was written stays valid.
"$zenith" replay "$log" --fps 1 --size 64x36 --end 600 --out "$work/term" >/dev/null 2>&1 &
pid=$!
sleep 2
kill -TERM "$pid"
wait "$pid"; rc=$?
check "SIGTERM exits 143" test $rc -eq 143
check "no partial file is left" bash -c "! ls '$work/term' | grep -q partial"

report
