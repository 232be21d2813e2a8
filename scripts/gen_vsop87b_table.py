#!/usr/bin/env python3
"""Generate geo/src/vsop87b_<body>.inc: a VSOP87B heliocentric planet series, truncated.

VSOP87 (Bretagnon & Francou 1988, A&A 202, 309; CDS catalogue VI/81) gives each planet's
heliocentric spherical coordinates as Poisson series
    X = sum_i tau^i sum_k A_k cos(B_k + C_k tau),   X in {L, B (radians), R (au)},
tau = Julian millennia of TT since J2000. The input is the full series as packaged by Debian's
kstars-data (/usr/share/kstars, one file per coordinate and power: <body>.L0.vsop ..
<body>.R5.vsop, columns A B C; a power with no terms has no file, e.g. uranus.B4/B5).

Those files are version B of VSOP87, referred to the fixed dynamical ecliptic and equinox of
J2000 (not version D, ecliptic of date): the Earth's leading L1 term is 6283.0758
rad/millennium, the sidereal mean motion without the 5029"/millennium of general precession,
and B1 carries the 0.00228 rad ecliptic-motion term (VSOP87B_L1 holds every body's). check_version() below refuses anything else, since the C++
side precesses from J2000 to date itself (geo/src/sun.cpp, geo/src/planets.cpp).

A term is kept when its amplitude at the edge of the validity window, A * |tau_max|^i, is at
least the threshold. The truncation error is then *measured*, not estimated: the dropped terms
are summed over a dense grid of instants 1950-2100 and the maximum angular (L, B) and radial
(R) errors are printed and written into the .inc header.

Usage: gen_vsop87b_table.py [--body NAME] [--src DIR] [--out FILE] [--threshold RAD]
  Earth (the default) is what geo/src/vsop87b_earth.inc was made with; the other planets were
  made with --body mercury .. neptune --threshold 3e-8 --grid-days 0.5 (each .inc
  header says how it was made and what it measured).
stdlib only, so CI and developers can rerun it without a virtual environment.
"""

import argparse
import math
import os
import random
import sys

COORDS = ("L", "B", "R")
MAX_POWER = 5
J2000 = 2451545.0
DAYS_PER_MILLENNIUM = 365250.0
ARCSEC_PER_RAD = 180.0 * 3600.0 / math.pi
AU_M = 149597870700.0

# Validity window the truncation is tuned and measured for (TT Julian dates).
JD_1950 = 2433282.5
JD_2100 = 2488069.5


def read_series(src, body, coord, power):
    path = os.path.join(src, f"{body}.{coord}{power}.vsop")
    terms = []
    if not os.path.exists(path) and power > 0:
        return terms  # kstars-data leaves out powers that have no terms
    with open(path, encoding="ascii") as f:
        for line_no, line in enumerate(f, 1):
            fields = line.split()
            if not fields:
                continue
            if len(fields) != 3:
                sys.exit(f"{path}:{line_no}: expected 3 columns A B C, got {len(fields)}")
            # Keep the text as published so the table carries the source's exact digits.
            float(fields[0]), float(fields[1]), float(fields[2])
            terms.append(tuple(fields))
    return terms


# Leading L1 term (sidereal mean motion, rad per Julian millennium) of each body in VSOP87B;
# VSOP87D's is larger by the general precession, 0.02438 rad per millennium.
VSOP87B_L1 = {"mercury": 26087.90314, "venus": 10213.28555, "earth": 6283.07585,
              "mars": 3340.61243, "jupiter": 529.69097, "saturn": 213.29910,
              "uranus": 74.78160, "neptune": 38.13304}


def check_version(body, full):
    """Refuse input that is not VSOP87B: the runtime precession would then be applied twice."""
    l1_rate = float(full["L"][1][0][0])
    if not abs(l1_rate - VSOP87B_L1[body]) < 1e-3:
        sys.exit(f"{body}.L1 leading term {l1_rate} is not VSOP87B's {VSOP87B_L1[body]} "
                 "(VSOP87D adds 0.02438 of precession); the tables and the C++ assume VSOP87B")


def eval_terms(terms, tau):
    return sum(a * math.cos(b + c * tau) for a, b, c in terms)


def eval_coord(series, tau):
    """series: list over powers of term lists."""
    return sum(eval_terms(terms, tau) * tau**i for i, terms in enumerate(series))


def sample_taus(grid_days, n_random):
    # A 0.25-day grid resolves the shortest period in the Earth series (7.0 days, C up to
    # 327575 rad/millennium), plus random instants so the grid cannot alias with any period.
    # The other planets were run on a 0.5-day grid, for run time: a maximum between grid points
    # is then under-sampled by at most the curvature of the dropped terms over 0.25 d, and the
    # random instants would show an alias.
    rng = random.Random(87)
    jds = [JD_1950 + grid_days * k for k in range(int((JD_2100 - JD_1950) / grid_days) + 1)]
    jds += [rng.uniform(JD_1950, JD_2100) for _ in range(n_random)]
    return [(jd - J2000) / DAYS_PER_MILLENNIUM for jd in jds]


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--body", default="earth", choices=sorted(VSOP87B_L1))
    parser.add_argument("--src", default="/usr/share/kstars")
    parser.add_argument("--out", default=None, help="default geo/src/vsop87b_<body>.inc")
    parser.add_argument("--grid-days", type=float, default=0.25)
    parser.add_argument("--random", type=int, default=20000, help="random instants added")
    parser.add_argument("--threshold", type=float, default=3e-9,
                        help="keep terms with A*|tau_max|^i >= this (rad, or au for R)")
    parser.add_argument("--stride", type=int, default=1,
                        help="evaluate every n-th sample (faster, for exploring thresholds)")
    args = parser.parse_args()
    body = args.body
    name = body.capitalize()
    if args.out is None:
        args.out = os.path.join(here, "..", "geo", "src", f"vsop87b_{body}.inc")

    full = {c: [read_series(args.src, body, c, i) for i in range(MAX_POWER + 1)] for c in COORDS}
    check_version(body, full)
    tau_max = max(abs(JD_1950 - J2000), abs(JD_2100 - J2000)) / DAYS_PER_MILLENNIUM
    kept, dropped = {}, {}
    for c in COORDS:
        kept[c], dropped[c] = [], []
        for i, terms in enumerate(full[c]):
            k = [t for t in terms if float(t[0]) * tau_max**i >= args.threshold]
            d = [t for t in terms if float(t[0]) * tau_max**i < args.threshold]
            kept[c].append(k)
            dropped[c].append(d)

    # Truncation error = the dropped part of the series, evaluated directly (numbers parsed once;
    # the kept terms stay text so the table carries the source's digits).
    dropped = {c: [[tuple(map(float, t)) for t in terms] for terms in dropped[c]] for c in COORDS}
    taus = sample_taus(args.grid_days, args.random)[:: args.stride]
    max_ang = max_l = max_b = max_r = 0.0
    worst_jd = J2000
    for tau in taus:
        dl = eval_coord(dropped["L"], tau)
        db = eval_coord(dropped["B"], tau)
        dr = eval_coord(dropped["R"], tau)
        # Direction error: dL is foreshortened by cos B (B < 7.1 deg for Mercury, the most
        # inclined), so hypot(dL, dB) is a bound, tight for the Earth (B < 1e-5 rad).
        ang = math.hypot(dl, db)
        if ang > max_ang:
            max_ang, worst_jd = ang, J2000 + tau * DAYS_PER_MILLENNIUM
        max_l, max_b, max_r = max(max_l, abs(dl)), max(max_b, abs(db)), max(max_r, abs(dr))

    n_full = sum(len(t) for c in COORDS for t in full[c])
    n_kept = sum(len(t) for c in COORDS for t in kept[c])
    counts = {c: [len(t) for t in kept[c]] for c in COORDS}
    full_counts = {c: [len(t) for t in full[c]] for c in COORDS}
    summary = [
        f"threshold: A * |tau|^i >= {args.threshold:g} (rad for L and B, au for R), "
        f"|tau| <= {tau_max:.4f} (1950-2100)",
        f"terms kept: {n_kept} of {n_full}",
    ] + [f"  {c}0..{c}5 kept {counts[c]} of {full_counts[c]}" for c in COORDS] + [
        f"measured truncation error over 1950-2100 ({len(taus)} instants, {args.grid_days:g} d grid "
        "+ random):",
        f"  max |dL| = {max_l * ARCSEC_PER_RAD:.4f} arcsec, max |dB| = "
        f"{max_b * ARCSEC_PER_RAD:.4f} arcsec, max direction = "
        f"{max_ang * ARCSEC_PER_RAD:.4f} arcsec",
        f"  (worst at JD {worst_jd:.2f})",
        f"  max |dR| = {max_r:.3e} au = {max_r * AU_M / 1000:.2f} km",
    ]
    for s in summary:
        print(s)

    out = []
    out.append("// Generated by scripts/gen_vsop87b_table.py. Do not edit; rerun the script.")
    out.append("//")
    desc = "the Earth" if body == "earth" else name
    out.append(f"// VSOP87B heliocentric spherical coordinates of {desc}, dynamical ecliptic and")
    out.append("// equinox of J2000 (Bretagnon & Francou 1988, A&A 202, 309; CDS catalogue VI/81),")
    out.append(f"// from the full series as packaged by Debian kstars-data ({body}.[LBR][0-5].vsop).")
    out.append("// Term = A cos(B + C tau),")
    out.append("// tau = Julian millennia of TT since J2000; L, B in radians, R in au;")
    out.append("// coordinate = sum_i tau^i S_i.")
    out.append("//")
    for s in summary:
        out.append("// " + s)
    out.append("//")
    out.append("// Expects in scope: struct VsopTerm { double a, b, c; }; and <span>.")
    out.append("")
    for c in COORDS:
        for i, terms in enumerate(kept[c]):
            if not terms:
                continue
            out.append(f"constexpr VsopTerm k{name}{c}{i}[] = {{")
            for a, b, cc in terms:
                out.append(f"    {{{a}, {b}, {cc}}},")
            out.append("};")
        # Powers of tau left empty at the top are dropped (Horner's rule needs no zero
        # coefficients there); an empty power in between stays as an empty span.
        powers = [i for i, t in enumerate(kept[c]) if t]
        out.append(f"constexpr std::span<const VsopTerm> k{name}{c}[] = {{")
        for i in range(powers[-1] + 1):
            entry = f"k{name}{c}{i}" if kept[c][i] else "std::span<const VsopTerm>{}"
            out.append(f"    {entry},")
        out.append("};")
        out.append("")
    with open(args.out, "w", encoding="ascii") as f:
        f.write("\n".join(out))
    print(f"wrote {os.path.normpath(args.out)}")


if __name__ == "__main__":
    main()
