#!/usr/bin/env bash
# zenith live's frame time (live.csv's render_s: interpolate, Update, RenderOffscreen, PNG) while
# the recorded FlightGear stream (tests/data/live) is sent into it, against zenith replay's frame
# loop at the same size in the same session, alternated twice (BENCHMARKS.md).
# Usage, from the source root after a build: bash tests/bench/live_frame_time.sh
set -u
z=build/sim/zenith; w=$(mktemp -d)
for round in ${ROUNDS:-1 2}; do
  rm -rf $w/live $w/replay
  $z live --fg-native 0 --out $w/live --every "${EVERY:-0.5}" --size 640x360 --duration 300 2>$w/live.log &
  pid=$!
  until grep -q listening $w/live.log; do sleep 0.2; done
  port=$(sed -n 's/.*:\([0-9]*\)$/\1/p' $w/live.log)
  build/tests/udp_stream send tests/data/live/fgfs_native.udprec 127.0.0.1 $port 2>/dev/null
  kill -INT $pid; wait $pid
  python3 -c "
import csv,statistics
r=[float(x['render_s']) for x in csv.DictReader(open('$w/live/live.csv'))]
print('live   round $round: %d frames, mean %.4f s, median %.4f s'%(len(r),statistics.mean(r),statistics.median(r)))"
  # The same poses and times as a flight log (CSV, data/flights/README.md), replayed at the same
  # size: replay's own rate, frames rendered / seconds of its frame loop (start-up excluded).
  python3 -c "
import csv, datetime
rows = list(csv.DictReader(open('$w/live/live.csv')))
seen = set()
with open('$w/flight.csv', 'w') as out:
    out.write('time,lat_deg,lon_deg,alt_wgs84_m,heading_deg,pitch_deg,roll_deg\\n')
    for r in rows:
        if r['utc_s'] in seen: continue
        seen.add(r['utc_s'])
        t = datetime.datetime.fromtimestamp(float(r['utc_s']), datetime.timezone.utc)
        out.write('%s,%s,%s,%s,%s,%s,%s\\n' % (t.strftime('%Y-%m-%dT%H:%M:%S.%fZ'), r['lat_deg'],
                  r['lon_deg'], r['height_m'], r['heading_deg'], r['pitch_deg'], r['roll_deg']))"
  fps=$($z replay $w/flight.csv --out $w/replay --fps 2 --size 640x360 2>&1 |
        sed -n 's/.* \([0-9.]*\) fps.*/\1/p' | tail -1)
  python3 -c "print('replay round $round: the same poses, %.4f s per frame'%(1/$fps))"
done
rm -rf $w
