#!/usr/bin/env bash
# End-to-end checks of the `zenith` binary: exit codes, messages, batch file handling.
# Usage: cli_test.sh path/to/zenith
set -uo pipefail
zenith=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
source "$(dirname "$0")/check.sh"

# Single instant, table and JSON.
out=$("$zenith" ephemeris --utc 2024-04-08T18:18:00Z --lat 31.0 --lon -104.0 --height 1000 --stars 0)
check "table has Sun and Moon rows" grep -q "^Moon " <<<"$out"
json=$("$zenith" ephemeris --utc 2024-04-08T18:18:00Z --lat 31.0 --lon -104.0 --height 1000 --json --stars 3)
check "--json is valid JSON with the batch keys" \
    /usr/bin/python3 -c 'import json,sys; d=json.load(sys.stdin); assert "moon_bright_limb_deg" in d and "sun_el_deg" in d' <<<"$json"
check "table reports the partial solar eclipse at 31 N" grep -q "^Solar eclipse: partial" <<<"$out"
# 2024-04-08 at greatest eclipse (NASA: 18:17:16 UT, 25.29 N 104.12 W): total.
out=$("$zenith" ephemeris --utc 2024-04-08T18:17:16Z --lat 25.2917 --lon -104.12 --stars 0)
check "table reports the total solar eclipse" grep -q "^Solar eclipse: total" <<<"$out"
json=$("$zenith" ephemeris --utc 2024-04-08T18:17:16Z --lat 25.2917 --lon -104.12 --json --stars 0)
check "--json has sun_obscuration 1" \
    /usr/bin/python3 -c 'import json,sys; d=json.load(sys.stdin); assert d["sun_obscuration"] == 1.0 and d["sun_uncovered_flux"] == 0.0' <<<"$json"

# Bad arguments: clear message naming the parameter, non-zero exit, nothing on stdout.
err=$("$zenith" ephemeris --utc 2024-02-30T00:00:00Z 2>&1 >/dev/null); rc=$?
check "impossible date exits 2" test $rc -eq 2
check "impossible date names the field" grep -q "day = 30" <<<"$err"
err=$("$zenith" ephemeris --utc 2024-01-01T00:00:00Z --lat 95 2>&1 >/dev/null); rc=$?
check "latitude 95 exits 2 and names lat_deg" exited_saying 2 'lat_deg = 95'
"$zenith" ephemeris --batch "$work/missing.jsonl" --out "$work/o.jsonl" >/dev/null 2>&1
check "missing batch file is an error" test $? -ne 0

# Batch: order kept, bad line in place, summary on stderr, exit 1, no temporary left behind.
cat >"$work/in.jsonl" <<'JSONL'
{"utc": "2024-04-08T18:18:00Z", "lat_deg": 31.0, "lon_deg": -104.0, "height_m": 1000}
{"utc": "2024-04-08T18:18:00Z", "lat_deg": 31.0, "lon_deg": -104.0}
{"utc": "1950-01-01T00:00:00Z", "lat_deg": -90, "lon_deg": 180, "height_m": 100000}
JSONL
"$zenith" ephemeris --batch "$work/in.jsonl" --out "$work/out.jsonl" 2>"$work/err"; rc=$?
check "batch with a bad line exits 1" test $rc -eq 1
check "batch writes one line per input line" test "$(wc -l <"$work/out.jsonl")" -eq 3
check "bad line reported in place" grep -q '"line":2' <(sed -n 2p "$work/out.jsonl")
check "stderr summary names the line and key" grep -q "1 of 3 lines failed.*line 2.*height_m" "$work/err"
check "no partial file left" test ! -e "$work/out.jsonl.partial"

report
