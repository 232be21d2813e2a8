#!/usr/bin/env bash
# zenith-plot end to end: every subcommand writes a non-empty PNG / .vti / .vtp headless, and
# without a display or Xvfb the tool exits with a message that says what to install (never a
# crash). Run as: plot_cli_test.sh ZENITH_PLOT SOURCE_DIR WORK_DIR (under xvfb-run -a in CTest;
# the "own Xvfb" case unsets DISPLAY to make the tool start one itself).
set -uo pipefail
plot=$1
source_dir=$2
work=$3
rm -rf "$work" && mkdir -p "$work"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

nonempty() {  # file, what
    if [[ ! -s $1 ]]; then fail "$2: $1 missing or empty"; return; fi
    if [[ $1 == *.png ]] && ! head -c 8 "$1" | od -An -tx1 | grep -q "89 50 4e 47"; then
        fail "$2: $1 is not a PNG"
    fi
}

run() {  # expected-rc what command...
    local expected=$1 what=$2; shift 2
    "$@" >"$work/out.txt" 2>"$work/err.txt"
    local rc=$?
    if [[ $rc -ne $expected ]]; then
        fail "$what: exit $rc, expected $expected"; sed 's/^/  | /' "$work/err.txt"
    fi
    return 0
}

# --- each subcommand, on the display xvfb-run gives -----------------------------------------
run 0 "transmittance" "$plot" transmittance --reference --out "$work/t.png" --size 640x400
nonempty "$work/t.png" transmittance
run 0 "transmittance mars log" "$plot" transmittance --preset mars --log --out "$work/tm.png"
nonempty "$work/tm.png" "transmittance mars"
for lut in transmittance multiple-scattering irradiance sky-view aerial-perspective; do
    run 0 "lut $lut" "$plot" lut --lut "$lut" --scale log --channel g --samples 120x60 \
        --out "$work/lut_$lut.png" --size 400x300
    nonempty "$work/lut_$lut.png" "lut $lut"
done
run 0 "export" "$plot" export --dir "$work/vti" --preset mars \
    --flight "$source_dir/data/flights/glider_sisteron.igc" --step 60
for lut in transmittance multiple-scattering irradiance sky-view aerial-perspective; do
    nonempty "$work/vti/mars_$lut.vti" "export $lut"
done
nonempty "$work/vti/flight_path.vtp" "export flight path"
grep -q 'Name="sun_elevation_deg"' "$work/vti/flight_path.vtp" || fail "vtp lacks sun_elevation_deg"
run 0 "overview" "$plot" overview --flight "$source_dir/data/flights/glider_sisteron.igc" \
    --step 120 --out "$work/overview.png" --size 400x300
nonempty "$work/overview.png" overview

# --- no DISPLAY: the tool starts its own Xvfb and stops it ----------------------------------
if command -v Xvfb >/dev/null; then
    before=$(pgrep -c -x Xvfb || true)
    run 0 "own Xvfb" env -u DISPLAY "$plot" lut --lut sky-view --out "$work/own.png" --size 320x200
    nonempty "$work/own.png" "own Xvfb"
    grep -q "started .*Xvfb" "$work/err.txt" || fail "own Xvfb: no note that Xvfb was started"
    sleep 0.5
    after=$(pgrep -c -x Xvfb || true)
    [[ $after -le $before ]] || fail "own Xvfb: left an Xvfb running ($before before, $after after)"
fi

# --- no display and no Xvfb: a clear message, exit 3, no crash -------------------------------
run 3 "no display" env -u DISPLAY PATH=/nonexistent "$plot" transmittance --out "$work/no.png"
grep -q "apt-get install xvfb" "$work/err.txt" || fail "no display: message does not say what to install"
[[ ! -e $work/no.png ]] || fail "no display: a PNG was written"
run 3 "bad display" env DISPLAY=:9999 PATH=/nonexistent "$plot" lut --out "$work/no.png"
grep -q "cannot open X display ':9999'" "$work/err.txt" || fail "bad display: message lacks the display"

# --- input errors name the parameter ---------------------------------------------------------
run 2 "bad lut" "$plot" lut --lut nonsense --out "$work/x.png"
grep -q -- "--lut = 'nonsense'" "$work/err.txt" || fail "bad lut: message"
run 2 "bad slice" "$plot" lut --lut aerial-perspective --slice 99 --out "$work/x.png"
grep -q -- "--slice = 99" "$work/err.txt" || fail "bad slice: message"
run 2 "bad out" "$plot" lut --out "$work/x.jpg"
run 2 "bad preset" "$plot" transmittance --preset nowhere.json --out "$work/x.png"

if [[ $failures -gt 0 ]]; then echo "$failures failure(s)"; exit 1; fi
echo "all zenith-plot checks passed"
