#!/usr/bin/env python3
"""Generate geo/src/vsop87b_earth.inc: the VSOP87B heliocentric Earth series, truncated.

VSOP87 (Bretagnon & Francou 1988, A&A 202, 309; CDS catalogue VI/81) gives the Earth's
heliocentric spherical coordinates as Poisson series
    X = sum_i tau^i sum_k A_k cos(B_k + C_k tau),   X in {L, B (radians), R (au)},
tau = Julian millennia of TT since J2000. The input is the full series as packaged by Debian's
kstars-data (one file per coordinate and power: earth.L0.vsop .. earth.R5.vsop, columns A B C).

Those files are version B of VSOP87, referred to the fixed dynamical ecliptic and equinox of
J2000 (not version D, ecliptic of date): the leading L1 term is 6283.0758 rad/millennium, the
sidereal mean motion without the 5029"/millennium of general precession, and B1 carries the
0.00228 rad ecliptic-motion term. check_version() below refuses anything else, since the C++
side precesses from J2000 to date itself (geo/src/sun.cpp).

A term is kept when its amplitude at the edge of the validity window, A * |tau_max|^i, is at
least the threshold. The truncation error is then *measured*, not estimated: the dropped terms
are summed over a dense grid of instants 1950-2100 and the maximum angular (L, B) and radial
(R) errors are printed and written into the .inc header.

Usage: gen_vsop87b_table.py [--src DIR] [--out FILE] [--threshold RAD]
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


def read_series(src, coord, power):
    path = os.path.join(src, f"earth.{coord}{power}.vsop")
    terms = []
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


def check_version(full):
    """Refuse input that is not VSOP87B: the runtime precession would then be applied twice."""
    l1_rate = float(full["L"][1][0][0])
    if not abs(l1_rate - 6283.07585) < 1e-3:
        sys.exit(f"earth.L1 leading term {l1_rate} is not VSOP87B's 6283.07585 (VSOP87D has "
                 "6283.31967, precession included); the table and sun.cpp assume VSOP87B")


def eval_terms(terms, tau):
    return sum(float(a) * math.cos(float(b) + float(c) * tau) for a, b, c in terms)


def eval_coord(series, tau):
    """series: list over powers of term lists."""
    return sum(eval_terms(terms, tau) * tau**i for i, terms in enumerate(series))


def sample_taus():
    # A 0.25-day grid resolves the shortest period in the Earth series (7.0 days, C up to
    # 327575 rad/millennium), plus random instants so the grid cannot alias with any period.
    rng = random.Random(87)
    jds = [JD_1950 + 0.25 * k for k in range(int((JD_2100 - JD_1950) / 0.25) + 1)]
    jds += [rng.uniform(JD_1950, JD_2100) for _ in range(20000)]
    return [(jd - J2000) / DAYS_PER_MILLENNIUM for jd in jds]


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--src", default="/tmp/ks/usr/share/kstars")
    parser.add_argument("--out", default=os.path.join(here, "..", "geo", "src",
                                                      "vsop87b_earth.inc"))
    parser.add_argument("--threshold", type=float, default=3e-9,
                        help="keep terms with A*|tau_max|^i >= this (rad, or au for R)")
    parser.add_argument("--stride", type=int, default=1,
                        help="evaluate every n-th sample (faster, for exploring thresholds)")
    args = parser.parse_args()

    full = {c: [read_series(args.src, c, i) for i in range(MAX_POWER + 1)] for c in COORDS}
    check_version(full)
    tau_max = max(abs(JD_1950 - J2000), abs(JD_2100 - J2000)) / DAYS_PER_MILLENNIUM
    kept, dropped = {}, {}
    for c in COORDS:
        kept[c], dropped[c] = [], []
        for i, terms in enumerate(full[c]):
            k = [t for t in terms if float(t[0]) * tau_max**i >= args.threshold]
            d = [t for t in terms if float(t[0]) * tau_max**i < args.threshold]
            kept[c].append(k)
            dropped[c].append(d)

    # Truncation error = the dropped part of the series, evaluated directly.
    taus = sample_taus()[:: args.stride]
    max_ang = max_l = max_b = max_r = 0.0
    worst_jd = J2000
    for tau in taus:
        dl = eval_coord(dropped["L"], tau)
        db = eval_coord(dropped["B"], tau)
        dr = eval_coord(dropped["R"], tau)
        ang = math.hypot(dl, db)  # |cos B| <= 1 and B < 1e-5 rad: cos B = 1 to 1e-10
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
        f"measured truncation error over 1950-2100 ({len(taus)} instants, 0.25 d grid + random):",
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
    out.append("// VSOP87B heliocentric spherical coordinates of the Earth, dynamical ecliptic and")
    out.append("// equinox of J2000 (Bretagnon & Francou 1988, A&A 202, 309; CDS catalogue VI/81),")
    out.append("// from the full series as packaged by Debian kstars-data.")
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
            out.append(f"constexpr VsopTerm kEarth{c}{i}[] = {{")
            for a, b, cc in terms:
                out.append(f"    {{{a}, {b}, {cc}}},")
            out.append("};")
        # Powers of tau left empty at the top are dropped (Horner's rule needs no zero
        # coefficients there); an empty power in between stays as an empty span.
        powers = [i for i, t in enumerate(kept[c]) if t]
        out.append(f"constexpr std::span<const VsopTerm> kEarth{c}[] = {{")
        for i in range(powers[-1] + 1):
            entry = f"kEarth{c}{i}" if kept[c][i] else "std::span<const VsopTerm>{}"
            out.append(f"    {entry},")
        out.append("};")
        out.append("")
    with open(args.out, "w", encoding="ascii") as f:
        f.write("\n".join(out))
    print(f"wrote {os.path.normpath(args.out)}")


if __name__ == "__main__":
    main()
