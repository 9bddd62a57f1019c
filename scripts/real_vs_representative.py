#!/usr/bin/env python3
"""How far the representative runs of a sedimentation sample are from its run at the real count.

Usage: scripts/real_vs_representative.py REAL_DIR N=DIR [N=DIR ...]

REAL_DIR and each DIR are run folders of the same scenario (`settle run`, their
`instruments.csv`); REAL_DIR ran with `--set sample.particles=real`. Per instrument
(hydrometer, buoyancy sphere, pipette) and per N, over the readings both runs have:
the largest and the RMS |percent finer(N) - percent finer(real)| in points, the mean counting
σ of the representative run's readings (`sd_percent`), and the RMS and largest |z|,
z = difference / sqrt(σ_N² + σ_real²) (readings with no grain in either run, σ = 0, have none). Prints a Markdown table, then the real run's readings.
No third-party modules (csv, math).
"""

import csv
import math
import sys
from pathlib import Path


def readings(run_dir):
    """{(instrument, time_s): (percent_finer, sd_percent)} of a run folder."""
    out = {}
    with open(Path(run_dir) / "instruments.csv", newline="") as f:
        for row in csv.DictReader(f):
            pf, sd = row["percent_finer"], row["sd_percent"]
            if pf == "" or sd == "":
                continue
            out[(row["instrument"], float(row["time_s"]))] = (float(pf), float(sd))
    return out


def compare(real, rep):
    """{instrument: (readings, max |d|, RMS d, mean σ_N, RMS z)} over the readings both have."""
    by = {}
    for key, (pf, sd) in rep.items():
        if key not in real:
            continue
        pr, sr = real[key]
        d = pf - pr
        s = math.hypot(sd, sr)
        # a reading with no grain in either run (σ = 0, both 0 %) has no z
        by.setdefault(key[0], []).append((d, sd, d / s if s > 0 else None))
    out = {}
    for inst, rows in by.items():
        n = len(rows)
        zs = [z for _, _, z in rows if z is not None]
        out[inst] = (
            n,
            max(abs(d) for d, _, _ in rows),
            math.sqrt(sum(d * d for d, _, _ in rows) / n),
            sum(s for _, s, _ in rows) / n,
            math.sqrt(sum(z * z for z in zs) / len(zs)) if zs else float("nan"),
            max((abs(z) for z in zs), default=float("nan")),
        )
    return out


def main(argv):
    if len(argv) < 3:
        sys.exit(__doc__)
    real = readings(argv[1])
    runs = []
    for a in argv[2:]:
        n, _, d = a.partition("=")
        if not d:
            sys.exit(f"{a}: expected N=DIR")
        runs.append((n, compare(real, readings(d))))
    insts = sorted({i for _, c in runs for i in c})
    print("| instrument | N | readings | max / RMS |Δ|, points | mean σ_N, points | RMS / max |z| |")
    print("|---|---|---|---|---|---|")
    for inst in insts:
        for n, c in runs:
            if inst in c:
                k, mx, rms, sd, z, zmax = c[inst]
                print(
                    f"| {inst} | {n} | {k} | {mx:.2f} / {rms:.2f} | {sd:.2f} | {z:.2f} / {zmax:.2f} |"
                )
    print()
    print("| instrument | time_s | percent finer (real count) | σ, points |")
    print("|---|---|---|---|")
    for (inst, t), (pf, sd) in sorted(real.items()):
        print(f"| {inst} | {t:g} | {pf:.3f} | {sd:.4f} |")


if __name__ == "__main__":
    main(sys.argv)
