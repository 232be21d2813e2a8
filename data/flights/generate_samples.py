#!/usr/bin/env python3
"""Writes the sample flights in data/flights/ (see README.md there). Deterministic: re-running it
reproduces the committed files byte for byte.

Every flight is integrated in a local frame (east/north metres about a reference point, with the
WGS84 meridian and prime-vertical radii of curvature for the conversion to latitude/longitude),
with bank angles from the coordinated-turn law tan(bank) = V * omega / g, so the logged or
derivable attitude is consistent with the path. Times were chosen with `zenith ephemeris`:

  glider  Sisteron      2024-07-14 12:00-12:30 UTC  Sun near its highest (el ~66 deg)
  climb   Nadi -> FL390 2024-06-21 18:20-18:55 UTC  Sunrise at 18:44 UTC on the ground, earlier aloft
  sunset  SFO 28R       2024-06-22 03:22-03:30 UTC  Sun el +1.3 -> 0.0 deg at az 299 deg, dead ahead
  balloon Esrange       2024-06-24 21:30-23:40 UTC  Midnight Sun, el ~1.3 deg, to 35 km

Usage: python3 data/flights/generate_samples.py [output_dir]
"""

import math
import os
import random
import sys
from datetime import datetime, timedelta, timezone

G = 9.80665
WGS84_A = 6378137.0
WGS84_F = 1 / 298.257223563
WGS84_E2 = WGS84_F * (2 - WGS84_F)
ISA_R = 6356766.0  # geopotential Earth radius, ISO 2533


def radii(lat_deg):
    """Meridian (M) and prime-vertical (N) radii of curvature, metres."""
    s = math.sin(math.radians(lat_deg))
    w = math.sqrt(1 - WGS84_E2 * s * s)
    return WGS84_A * (1 - WGS84_E2) / w**3, WGS84_A / w


class Integrator:
    """Flies a point over the ellipsoid: heading (deg true), ground speed (m/s), vertical speed."""

    def __init__(self, lat_deg, lon_deg, height_m, heading_deg):
        self.lat, self.lon, self.h, self.heading = lat_deg, lon_deg, height_m, heading_deg

    def step(self, dt, speed, vertical_speed, turn_rate_deg_s=0.0, wind_en=(0.0, 0.0)):
        self.heading = (self.heading + turn_rate_deg_s * dt) % 360.0
        m, n = radii(self.lat)
        ve = speed * math.sin(math.radians(self.heading)) + wind_en[0]
        vn = speed * math.cos(math.radians(self.heading)) + wind_en[1]
        self.lat += math.degrees(vn * dt / (m + self.h))
        self.lon += math.degrees(ve * dt / ((n + self.h) * math.cos(math.radians(self.lat))))
        if self.lon >= 180.0:
            self.lon -= 360.0
        self.h += vertical_speed * dt


def bank_deg(speed, turn_rate_deg_s):
    return math.degrees(math.atan(speed * math.radians(turn_rate_deg_s) / G))


def geometric_from_geopotential(h):
    return ISA_R * h / (ISA_R - h)


def geopotential_from_geometric(z):
    return ISA_R * z / (ISA_R + z)


def iso(t):
    return t.strftime("%Y-%m-%dT%H:%M:%SZ")


# --- glider, IGC --------------------------------------------------------------------------------

def igc_lat(lat):
    hemi = "N" if lat >= 0 else "S"
    lat = abs(lat)
    d = int(lat)
    m = round((lat - d) * 60000)
    if m == 60000:
        d, m = d + 1, 0
    return f"{d:02d}{m:05d}{hemi}"


def igc_lon(lon):
    hemi = "E" if lon >= 0 else "W"
    lon = abs(lon)
    d = int(lon)
    m = round((lon - d) * 60000)
    if m == 60000:
        d, m = d + 1, 0
    return f"{d:03d}{m:05d}{hemi}"


def glider(path):
    rng = random.Random(1)
    start = datetime(2024, 7, 14, 12, 0, 0, tzinfo=timezone.utc)
    # Over the Durance valley near Sisteron (LFNS), 1800 m MSL, wind 3 m/s from the west.
    fly = Integrator(44.30, 5.95, 1800.0, 20.0)
    wind = (3.0, 0.0)
    # (kind, seconds, parameter): glide at 35 m/s sinking 1.0 m/s; thermal at 25 m/s, climbing,
    # turning at a constant rate (sign = direction) with 40 deg of bank.
    plan = [("glide", 150, 20.0), ("thermal", 330, +1), ("glide", 200, 75.0),
            ("thermal", 300, -1), ("glide", 220, 140.0), ("thermal", 300, +1),
            ("glide", 300, 60.0)]
    lines = [
        "AXCSZEN",
        "HFDTEDATE:140724,01",
        "HFFXA035",
        "HFPLTPILOTINCHARGE:Zenith Sample",
        "HFGTYGLIDERTYPE:ASK 21",
        "HFGIDGLIDERID:D-ZNTH",
        "HFDTM100GPSDATUM:WGS-1984",
        "HFRFWFIRMWAREVERSION:synthetic",
        "HFFTYFRTYPE:zenith,generate_samples.py",
        "HFALGALTGPS:GEO",
        "HFALPALTPRESSURE:ISA",
        "I023638FXA3940SIU",
        "LXCS synthetic flight written by data/flights/generate_samples.py",
    ]
    t = start
    # QNH 1020 hPa: pressure altitude = MSL height - 7 hPa * 8.3 m/hPa.
    qnh_offset = -58.0
    for kind, seconds, param in plan:
        if kind == "glide":
            target = param
        for _ in range(seconds):
            if kind == "glide":
                # Turn gently onto the glide heading at 3 deg/s.
                err = (target - fly.heading + 540.0) % 360.0 - 180.0
                rate = max(-3.0, min(3.0, err))
                fly.step(1.0, 35.0, -1.0, rate, wind)
            else:
                # 40 deg of bank at 25 m/s: omega = g tan(40 deg) / V.
                rate = param * math.degrees(G * math.tan(math.radians(40.0)) / 25.0)
                fly.step(1.0, 25.0, 2.4 + 0.3 * math.sin(2 * math.pi * (t.second / 19.0)), rate,
                         wind)
            t += timedelta(seconds=1)
            gnss = round(fly.h + rng.gauss(0.0, 1.0))
            pressure = round(fly.h + qnh_offset)
            lines.append(f"B{t:%H%M%S}{igc_lat(fly.lat)}{igc_lon(fly.lon)}A"
                         f"{pressure:05d}{gnss:05d}{rng.randint(3, 8):03d}{11:02d}")
    lines.append("LXCS end of flight")
    lines.append("GSYNTHETICSIGNATURENOTVALID0000000000000000000000000000000000000000000000")
    with open(path, "w", newline="\r\n") as f:  # IGC lines end in CR LF
        f.write("\n".join(lines) + "\n")


# --- airliner climb, GPX -------------------------------------------------------------------------

def airliner(path):
    start = datetime(2024, 6, 21, 18, 20, 0, tzinfo=timezone.utc)
    # Lift-off from Nadi (NFFN) runway 02, climb to FL390 on a heading of 062 toward the
    # antimeridian (crossed near 18:48 UTC). ISA day: ele = geometric height of the pressure
    # altitude. TAS by pressure altitude (ft): piecewise linear.
    fly = Integrator(-17.7655, 177.4430, 20.0, 20.0)
    tas_table = [(0, 80.0), (3000, 130.0), (10000, 150.0), (28000, 235.0), (39000, 252.0)]
    pressure_ft = 60.0
    dt = 4.0
    points = []
    t = start
    for i in range(int(35 * 60 / dt) + 1):
        if i > 0:
            if pressure_ft < 10000:
                fpm = 2500.0
            elif pressure_ft < 28000:
                fpm = 2000.0
            elif pressure_ft < 39000:
                fpm = 1000.0
            else:
                fpm = 0.0
            tas = next(v0 + (v1 - v0) * (pressure_ft - a0) / (a1 - a0)
                       for (a0, v0), (a1, v1) in zip(tas_table, tas_table[1:])
                       if pressure_ft <= a1) if pressure_ft < 39000 else 252.0
            # Right turn at 2.5 deg/s from 1500 ft until heading 062.
            rate = 2.5 if pressure_ft > 1500 and fly.heading < 62.0 else 0.0
            new_ft = min(39000.0, pressure_ft + fpm * dt / 60.0)
            h_new = geometric_from_geopotential(new_ft * 0.3048)
            fly.step(dt, tas, (h_new - fly.h) / dt, rate)
            fly.heading = min(fly.heading, 62.0) if rate else fly.heading
            pressure_ft = new_ft
            t += timedelta(seconds=dt)
        points.append((t, fly.lat, fly.lon, fly.h))
    out = ['<?xml version="1.0" encoding="UTF-8"?>',
           '<gpx version="1.1" creator="zenith data/flights/generate_samples.py" '
           'xmlns="http://www.topografix.com/GPX/1/1">',
           "  <metadata><name>Nadi to FL390 at dawn (synthetic)</name>"
           f"<time>{iso(start)}</time></metadata>",
           "  <trk>",
           "    <name>NFFN departure, climb to FL390 across 180 deg</name>",
           "    <trkseg>"]
    for t, lat, lon, h in points:
        out.append(f'      <trkpt lat="{lat:.6f}" lon="{lon:.6f}"><ele>{h:.1f}</ele>'
                   f"<time>{iso(t)}</time></trkpt>")
    out += ["    </trkseg>", "  </trk>", "</gpx>"]
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


# --- sunset approach with attitude, KML ----------------------------------------------------------

def approach(path):
    # San Francisco (KSFO) runway 28R, true course 298 deg, into the setting Sun (az 299-300 deg,
    # geometric sunset 03:29:40 UTC on the ground). Touchdown 03:30:00 UTC. Approximate threshold.
    touchdown = datetime(2024, 6, 22, 3, 30, 0, tzinfo=timezone.utc)
    course = 298.0
    threshold = (37.6136, -122.3571, 4.0)
    speed_final = 72.0  # m/s, ~140 kt
    alpha = 3.0  # deg, angle of attack: pitch = flight-path angle + alpha
    glide = 3.0
    # Fly the plan forward from an entry point: downwind (course 118) at 3000 ft, a right
    # 180-degree turn at 3 deg/s, level to the glide path, then down the 3 deg path.
    turn_rate = 3.0
    v_turn = 80.0
    radius = v_turn / math.radians(turn_rate)
    h_level = 914.0 + threshold[2]  # 3000 ft above the threshold
    final_len = (h_level - threshold[2]) / math.tan(math.radians(glide))
    level_len = 3000.0
    # Start of the final turn in local ENU about the threshold (x east, y north).
    c = math.radians(course)
    fwd = (math.sin(c), math.cos(c))
    right = (math.cos(c), -math.sin(c))  # right of the final course
    # After the right turn we are on final at distance (final_len + level_len) before the
    # threshold; the turn started 2R to the right of the final course (a right turn from the
    # reciprocal heading ends 2R to the left of where it began).
    d = final_len + level_len
    entry_x = -fwd[0] * d + right[0] * 2 * radius
    entry_y = -fwd[1] * d + right[1] * 2 * radius
    m, n = radii(threshold[0])
    lat0 = threshold[0] + math.degrees(entry_y / m)
    lon0 = threshold[1] + math.degrees(entry_x / (n * math.cos(math.radians(threshold[0]))))
    downwind_s = 120
    fly = Integrator(lat0, lon0, h_level, (course + 180.0) % 360.0)
    # Fly the downwind backwards first so that the turn starts at the entry point.
    fly.heading = course
    fly.step(downwind_s, v_turn, 0.0)
    fly.heading = (course + 180.0) % 360.0
    samples = []
    turn_s = 180.0 / turn_rate
    level_s = level_len / ((v_turn + speed_final) / 2)
    final_s = final_len / speed_final
    total = downwind_s + turn_s + level_s + final_s
    start = touchdown - timedelta(seconds=round(total))
    t = 0.0
    dt = 1.0
    roll = 0.0
    while t <= round(total):
        if t < downwind_s:
            phase, rate, v, vs = "downwind", 0.0, v_turn, 0.0
        elif t < downwind_s + turn_s:
            phase, rate, v, vs = "turn", turn_rate, v_turn, 0.0
        elif t < downwind_s + turn_s + level_s:
            frac = (t - downwind_s - turn_s) / level_s
            phase, rate, v, vs = "level", 0.0, v_turn + (speed_final - v_turn) * frac, 0.0
        else:
            phase, rate, v = "final", 0.0, speed_final
            vs = -speed_final * math.tan(math.radians(glide))
        # Roll in and out over ~3 s, as a pilot does; the path follows the bank.
        target = bank_deg(v, rate)
        roll += max(-10.0, min(10.0, target - roll)) * dt if t > 0 else target
        fpa = math.degrees(math.atan2(vs, v))
        samples.append((start + timedelta(seconds=t), fly.lat, fly.lon, fly.h, fly.heading,
                        fpa + alpha, roll))
        fly.step(dt, v, vs, rate)
        t += dt
    out = ['<?xml version="1.0" encoding="UTF-8"?>',
           '<kml xmlns="http://www.opengis.net/kml/2.2" '
           'xmlns:gx="http://www.google.com/kml/ext/2.2">',
           "<Document>",
           "  <name>Sunset approach to San Francisco 28R (synthetic)</name>",
           "  <Placemark>",
           "    <name>KSFO 28R, touchdown 2024-06-22 03:30 UTC</name>",
           "    <gx:Track>",
           "      <altitudeMode>absolute</altitudeMode>"]
    out += [f"      <when>{iso(s[0])}</when>" for s in samples]
    out += [f"      <gx:coord>{s[2]:.6f} {s[1]:.6f} {s[3]:.1f}</gx:coord>" for s in samples]
    # round(x, 2) + 0.0 writes 0.00, not -0.00, for tiny negative angles.
    out += [f"      <gx:angles>{round(s[4], 2) + 0.0:.2f} {round(s[5], 2) + 0.0:.2f} "
            f"{round(s[6], 2) + 0.0:.2f}</gx:angles>" for s in samples]
    out += ["    </gx:Track>", "  </Placemark>", "</Document>", "</kml>"]
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


# --- high-altitude balloon, CSV -------------------------------------------------------------------

def balloon(path):
    rng = random.Random(4)
    start = datetime(2024, 6, 24, 21, 30, 0, tzinfo=timezone.utc)
    # Esrange Space Center near Kiruna, 341 m MSL; geoid undulation there ~ +25 m (EGM96), so
    # the GNSS ellipsoidal height at launch is ~366 m.
    undulation = 25.0
    fly = Integrator(67.8932, 21.1069, 341.0 + undulation, 0.0)
    dt = 10.0
    rows = []
    t = 0.0
    float_height = 35000.0 + undulation
    while t <= 130 * 60:
        msl = fly.h - undulation
        # Summer Arctic winds: from the SW near the ground, westerlies at the tropopause, and
        # stratospheric easterlies above 20 km.
        if msl < 9000:
            wind = (3.0 + msl / 9000 * 9.0, 2.0)
        elif msl < 20000:
            wind = (12.0 - (msl - 9000) / 11000 * 16.0, 1.0)
        else:
            wind = (-4.0 - (msl - 20000) / 15000 * 8.0, 0.0)
        vs = 5.0 if fly.h < float_height else 0.0
        # The gondola spins slowly and swings a little under the balloon.
        heading = (t * 0.6 + 20 * math.sin(t / 97.0)) % 360.0
        pitch = 1.5 * math.sin(t / 13.0) + rng.gauss(0.0, 0.2)
        roll = 2.0 * math.sin(t / 17.0) + rng.gauss(0.0, 0.2)
        # Arctic summer stratosphere is warmer than ISA: pressure altitude ~2.5% below geometric.
        pressure = geopotential_from_geometric(msl) * (1 - 0.025 * min(1.0, msl / 20000))
        rows.append(f"{iso(start + timedelta(seconds=t))},{fly.lat:.6f},{fly.lon:.6f},"
                    f"{fly.h + rng.gauss(0.0, 2.0):.1f},{pressure:.1f},"
                    f"{heading:.1f},{pitch:.1f},{roll:.1f}")
        fly.step(dt, 0.0, min(vs, (float_height - fly.h) / dt), 0.0, wind)
        t += dt
    with open(path, "w") as f:
        f.write("# High-altitude balloon from Esrange to 35 km under the Midnight Sun (synthetic,\n"
                "# data/flights/generate_samples.py). Format: data/flights/README.md.\n")
        f.write("time,lat_deg,lon_deg,alt_wgs84_m,alt_pressure_m,heading_deg,pitch_deg,roll_deg\n")
        f.write("\n".join(rows) + "\n")


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__))
    os.makedirs(out, exist_ok=True)
    glider(os.path.join(out, "glider_sisteron.igc"))
    airliner(os.path.join(out, "airliner_nadi_climb.gpx"))
    approach(os.path.join(out, "sunset_approach_sfo.kml"))
    balloon(os.path.join(out, "balloon_esrange.csv"))


if __name__ == "__main__":
    main()
