#!/usr/bin/env bash
# `zenith render` end to end: files written, clear errors and no partial output for bad input.
# Usage: cli_render_test.sh path/to/zenith
set -uo pipefail
zenith=$(realpath "$1")
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
    exited_saying 2 '--pitch: pitch_deg = 100 deg is out of range (expected \[-90, 90\] deg)'
"$zenith" render --size 64x36 --utc 2024-08-04T23:00:00Z --lat 28.76 --lon -17.88 --bortle 6 \
    --out "$work/bortle.exr" >/dev/null 2>&1
check "a night under Bortle 6" test -s "$work/bortle.exr"
err=$("$zenith" render --bortle 12 --out "$work/b.png" 2>&1); rc=$?
check "Bortle 12 names --bortle, the value and its range" \
    exited_saying 2 '--bortle: bortle_class = 12 is out of range (expected 1..9)'
check "nothing written for a bad Bortle class" test ! -e "$work/b.png"
err=$("$zenith" render --light-pollution 5 --out "$work/l.png" 2>&1); rc=$?
check "light pollution 5 names --light-pollution and its range" \
    exited_saying 2 '--light-pollution: artificial_zenith_brightness = 5' '\[10, 30\]'
err=$("$zenith" render --size 0x10 --out "$work/s.png" 2>&1)
check "size 0x10 names --size" grep -q -- "--size" <<<"$err"
err=$("$zenith" render --preset nowhere --out "$work/n.png" 2>&1)
check "unknown preset names it" grep -qi "nowhere" <<<"$err"
err=$("$zenith" render --exposure bright --out "$work/e.png" 2>&1)
check "bad exposure names --exposure" grep -q -- "--exposure" <<<"$err"
# Weather from a METAR report: its clouds and its visibility.
"$zenith" render --size 64x36 --metar "EGLL 211750Z 24012KT 9999 FEW035 SCT250 18/09 Q1018" \
    --station-elevation 25 --out "$work/metar.png" >/dev/null 2>&1
check "a METAR report renders" test -s "$work/metar.png"
err=$("$zenith" render --size 64x36 --metar "EGLL 211200Z 24012KT 2500 BR BKN008 12/11 Q1008" \
    --out "$work/mist.png" 2>&1)
check "without --station-elevation it says where the heights are taken from" \
    grep -q "above the ground under the observer" <<<"$err"
printf '# a comment\nEGLL 211200Z 24012KT 0300 FG VV002 10/10 Q1008\n' >"$work/reports.txt"
"$zenith" render --size 64x36 --metar-file "$work/reports.txt" --out "$work/fog.png" >/dev/null 2>&1
check "--metar-file renders its first report" test -s "$work/fog.png"
err=$("$zenith" render --size 64x36 --metar "EGLL 211200Z 9999" --weather broken \
    --out "$work/w.png" 2>&1); rc=$?
check "--metar with --weather exits 2 naming --weather" \
    exited_saying 2 --weather
err=$("$zenith" render --size 64x36 --metar "12 nonsense" --out "$work/m.png" 2>&1); rc=$?
check "a report without a station exits 2 naming the group" \
    exited_saying 2 12
check "no output for any failed run" bash -c "! ls '$work' | grep -qE '^(frame|p|s|n|e|w|m)\.|partial'"

report
