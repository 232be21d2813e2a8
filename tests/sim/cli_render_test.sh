#!/usr/bin/env bash
# `zenith render` end to end: files written, clear errors and no partial output for bad input.
# Usage: cli_render_test.sh path/to/zenith
set -uo pipefail
zenith=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
source "$(dirname "$0")/check.sh"

(cd "$work" && "$zenith" render --size 64x36 >/dev/null 2>&1)
check "no options renders the built-in scene to zenith.png" test -s "$work/zenith.png"
"$zenith" render --size 64x36 --utc 2024-06-21T12:00:00Z --lat 0 --lon 0 --height 2 \
    --out "$work/noon.exr" >/dev/null 2>&1
check "EXR written" test -s "$work/noon.exr"
"$zenith" render --size 64x36 --height 1000000 --pitch -60 --preset mars --out "$work/mars.png" \
    >/dev/null 2>&1
check "Mars preset from orbit" test -s "$work/mars.png"

err=$("$zenith" render --size 64x36 --out "$work/frame.jpg" 2>&1); rc=$?
check "unknown extension exits 2" test $rc -eq 2
check "message names --out and the allowed extensions" grep -q "\-\-out.*\.exr.*\.png" <<<"$err"
err=$("$zenith" render --pitch 100 --out "$work/p.png" 2>&1); rc=$?
check "pitch 100 names --pitch, the value and its range" \
    bash -c "test $rc -eq 2 && grep -q -- '--pitch: pitch_deg = 100 deg is out of range (expected \\[-90, 90\\] deg)' <<<'$err'"
err=$("$zenith" render --size 0x10 --out "$work/s.png" 2>&1)
check "size 0x10 names --size" grep -q -- "--size" <<<"$err"
err=$("$zenith" render --preset nowhere --out "$work/n.png" 2>&1)
check "unknown preset names it" grep -qi "nowhere" <<<"$err"
err=$("$zenith" render --exposure bright --out "$work/e.png" 2>&1)
check "bad exposure names --exposure" grep -q -- "--exposure" <<<"$err"
check "no output for any failed run" bash -c "! ls '$work' | grep -qE '^(frame|p|s|n|e)\.|partial'"

report
