#!/usr/bin/env python3
"""Check that a restructuring changed no result.

    scripts/regress_outputs.py run BINARY OUTDIR      # run every scenario with BINARY
    scripts/regress_outputs.py compare OLD NEW        # compare two such folders

`run` runs every file in scenarios/ one at a time (sedimentation at
--set sample.particles=20000, the funnel at --set repeats.count=2) into OUTDIR/<file stem>/.
`compare` reads every CSV present in both trees and compares every column both files have:
numbers within 1e-9 relative (absolute 1e-300 floor; NaN equals NaN), text exactly. Files
and columns present on one side only are listed, not failed. Exit 1 on any difference.
Wall-time columns (`wall_time_s`, `*_wall_s`) are skipped: they measure the machine.
"""
import csv
import math
import os
import subprocess
import sys

OVERRIDES = {
    "sedimentation": ["--set", "sample.particles=20000"],
    "paste_68_balls": ["--set", "repeats.count=2"],
}
SKIP_COLUMNS = ("wall_time_s", "wall_s", "elapsed_s")


def run(binary, outdir):
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    scen = os.path.join(root, "scenarios")
    for name in sorted(os.listdir(scen)):
        if not name.endswith(".toml"):
            continue
        stem = name[:-5]
        extra = []
        for key, ov in OVERRIDES.items():
            if stem.startswith(key):
                extra = ov
        dest = os.path.join(outdir, stem)
        cmd = [binary, "run", os.path.join(scen, name), "--out", dest, "-q"] + extra
        print(" ".join(cmd), flush=True)
        r = subprocess.run(cmd)
        if r.returncode != 0:
            print(f"  exit {r.returncode}", flush=True)


def number(s):
    try:
        return float(s)
    except ValueError:
        return None


def same(a, b):
    x, y = number(a), number(b)
    if x is None or y is None:
        return a.strip() == b.strip()
    if math.isnan(x) or math.isnan(y):
        return math.isnan(x) and math.isnan(y)
    if x == y:
        return True
    return abs(x - y) <= 1e-9 * max(abs(x), abs(y), 1e-300)


def csvs(top):
    out = {}
    for d, _, files in os.walk(top):
        for f in files:
            if f.endswith(".csv"):
                p = os.path.join(d, f)
                out[os.path.relpath(p, top)] = p
    return out


def compare(old, new):
    a, b = csvs(old), csvs(new)
    bad = 0
    for rel in sorted(set(a) - set(b)):
        print(f"only in {old}: {rel}")
    for rel in sorted(set(b) - set(a)):
        print(f"only in {new}: {rel}")
    checked = 0
    for rel in sorted(set(a) & set(b)):
        with open(a[rel]) as fa, open(b[rel]) as fb:
            ra, rb = list(csv.reader(fa)), list(csv.reader(fb))
        if not ra or not rb:
            if bool(ra) != bool(rb):
                print(f"{rel}: one side empty")
                bad += 1
            continue
        ha, hb = ra[0], rb[0]
        if len(ra) != len(rb):
            print(f"{rel}: {len(ra) - 1} rows vs {len(rb) - 1}")
            bad += 1
            continue
        common = [c for c in ha if c in hb and not c.endswith(SKIP_COLUMNS)]
        for c in sorted(set(ha) ^ set(hb)):
            print(f"{rel}: column {c} on one side only")
        ia = {c: ha.index(c) for c in common}
        ib = {c: hb.index(c) for c in common}
        diffs = 0
        for i, (x, y) in enumerate(zip(ra[1:], rb[1:]), start=2):
            for c in common:
                u = x[ia[c]] if ia[c] < len(x) else ""
                v = y[ib[c]] if ib[c] < len(y) else ""
                if not same(u, v):
                    if diffs < 5:
                        print(f"{rel}: row {i} column {c}: {u} vs {v}")
                    diffs += 1
        if diffs:
            print(f"{rel}: {diffs} differing values")
            bad += 1
        checked += 1
    print(f"{checked} files compared, {bad} differ")
    return 1 if bad else 0


if __name__ == "__main__":
    if len(sys.argv) != 4 or sys.argv[1] not in ("run", "compare"):
        print(__doc__)
        sys.exit(2)
    if sys.argv[1] == "run":
        run(os.path.abspath(sys.argv[2]), os.path.abspath(sys.argv[3]))
    else:
        sys.exit(compare(sys.argv[2], sys.argv[3]))
