#!/usr/bin/env python3
"""Check that a restructuring changed no result.

    scripts/regress_outputs.py run BINARY OUTDIR      # run every scenario with BINARY
    scripts/regress_outputs.py compare OLD NEW        # compare two such folders

`run` runs every file in scenarios/ one at a time (sedimentation at
--set sample.particles=20000, the funnel at --set repeats.count=2) into OUTDIR/<file stem>/,
then the other commands on fixed inputs into OUTDIR/cmd/<case>/ (see COMMANDS): `reduce` on
each file of data/lab/, `invert` on the readings of data/invert/ (ideal Stokes and full model,
once with --bounds), `laws`, `fit` (the worked cases of docs/commands/fit.md; the restitution
fits at dt = 1e-4 s to stay short; `fit slump` prints only, so its lines go to slump.csv),
and `sweep` (a dt sweep and a --vary sweep). About a minute and a half on an idle machine
beside the scenarios.
`compare` reads every CSV present in both trees and compares every column both files have:
numbers within 1e-9 relative (absolute 1e-300 floor; NaN equals NaN), text exactly. Files
and columns present on one side only are listed, not failed. Exit 1 on any difference.
Wall-time columns (`wall_time_s`, `*_wall_s`) are skipped: they measure the machine.
Text cells holding absolute paths are compared with each side's repository root (recorded by
`run` in OUTDIR/.repo_root) replaced by `<repo>`, so that two checkouts compare equal.
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


PASTE_M = [
    "file,column,row,value,sigma",
    "summary.csv,settling_distance_m,id=d12.6mm-H255mm,0.05063,5e-4",
]
REBOUND_M = [
    "file,column,row,value",
    "summary.csv,rebound_height_m,drop_height_m=0.095,0.0370",
    "summary.csv,rebound_height_m,drop_height_m=0.188,0.0720",
    "summary.csv,rebound_height_m,drop_height_m=0.252,0.0909",
    "summary.csv,rebound_height_m,drop_height_m=0.318,0.1180",
    "summary.csv,rebound_height_m,drop_height_m=0.398,0.1469",
]
INVERT_SETS = ["sample2_full", "sample2_full_contacts", "sample4_full", "sample4_full_contacts"]
READINGS = ["readings.csv", "readings_d7928.csv", "readings_pipette.csv", "readings_sphere.csv"]


def commands(root, cmd):
    """(case, argv after the binary, stdout file or None): the command cases of `run`."""
    lab = os.path.join(root, "data", "lab")
    scen = os.path.join(root, "scenarios")
    out = []
    # reduce: each laboratory file by the standard it allows (the D422 files lack the
    # hydrometer dimensions D7928 needs; the D7928 file's readings are refused by D422).
    for name, std in [
        ("atech_d422_percent_finer", "d422"),
        ("envalysis_clayloam_d422", "d422"),
        ("soiltestr_protocol8_d7928", "d7928"),
    ]:
        case = f"reduce_{name}_{std}"
        f = os.path.join(lab, name + ".csv")
        out.append((case, ["reduce", f, "--standard", std, "--out", os.path.join(cmd, case)], None))
    # invert: the four instruments of each reference run together, both models.
    for d in INVERT_SETS:
        files = [os.path.join(root, "data", "invert", d, r) for r in READINGS]
        for model in ("ideal-stokes", "full"):
            case = f"invert_{d}_{model}"
            argv = ["invert"] + files + ["--model", model, "--out", os.path.join(cmd, case)]
            out.append((case, argv, None))
    files = [os.path.join(root, "data", "invert", "sample2_full", r) for r in READINGS]
    case = "invert_sample2_full_bounds"
    out.append((case, ["invert"] + files + ["--bounds", "--out", os.path.join(cmd, case)], None))
    out.append(("laws", ["laws", "--out", os.path.join(cmd, "laws")], None))
    # run with the history force of Mei & Adrian (its kernel is fitted by NNLS; the scenarios
    # have the history force off).
    for reyn in ("terminal", "current"):
        case = f"run_ten_cate_e4_mei_adrian_{reyn}"
        argv = ["run", os.path.join(scen, "ten_cate_e4.toml"), "--set", "transient.history=mei-adrian",
                "--set", f"transient.history_reynolds={reyn}", "--out", os.path.join(cmd, case), "-q"]
        out.append((case, argv, None))
    # fit: the worked cases of docs/commands/fit.md.
    paste = os.path.join(cmd, "paste_measured.csv")
    rebound = os.path.join(cmd, "rebound_measured.csv")
    case = "fit_slump"
    argv = ["fit", "slump", "--height-mm", "152", "--slump-mm", "102,103,100", "--density", "1843"]
    out.append((case, argv, os.path.join(cmd, case, "slump.csv")))
    case = "fit_paste_eta_b"
    argv = ["fit", os.path.join(scen, "paste_single_ball.toml"),
            "--set", "release.fall_heights_m=[0.255]",
            "--fit", "fluid.plastic_viscosity_pa_s=0.1:3", "--measured", paste,
            "--out", os.path.join(cmd, case), "-q"]
    out.append((case, argv, None))
    case = "fit_restitution_brent"
    argv = ["fit", os.path.join(scen, "restitution_drop.toml"), "--set", "time.dt_s=1e-4",
            "--set", "contacts.restitution_exponent=0", "--fit", "contacts.restitution=0.4:0.8",
            "--measured", rebound, "--out", os.path.join(cmd, case), "-q"]
    out.append((case, argv, None))
    case = "fit_restitution_nelder_mead"
    argv = ["fit", os.path.join(scen, "restitution_drop.toml"), "--set", "time.dt_s=1e-4",
            "--fit", "contacts.restitution=0.5:0.8", "--fit", "contacts.restitution_exponent=0:0.2",
            "--measured", rebound, "--out", os.path.join(cmd, case), "-q"]
    out.append((case, argv, None))
    # sweep: a dt sweep (the scenario's [sweep] table) and a parameter sweep.
    case = "sweep_valentik_susp1"
    argv = ["sweep", os.path.join(scen, "valentik_susp1.toml"), "--out", os.path.join(cmd, case), "-q"]
    out.append((case, argv, None))
    case = "sweep_stokes_single_dt"
    argv = ["sweep", os.path.join(scen, "stokes_single.toml"), "--dt-range", "1e-5:1e-3",
            "--per-decade", "2", "--out", os.path.join(cmd, case), "-q"]
    out.append((case, argv, None))
    case = "sweep_vary_stokes_single"
    argv = ["sweep", os.path.join(scen, "stokes_single.toml"),
            "--vary", "fluid.viscosity_pa_s=log:1e-3:1e-2:3", "--vary", "drag.law=stokes,dallavalle",
            "--out", os.path.join(cmd, case), "-q"]
    out.append((case, argv, None))
    case = "sweep_vary_valentik_susp1"
    argv = ["sweep", os.path.join(scen, "valentik_susp1.toml"),
            "--vary", "fluid.yield_stress_pa=20:40:3", "--out", os.path.join(cmd, case), "-q"]
    out.append((case, argv, None))
    return out, {paste: PASTE_M, rebound: REBOUND_M}


def run_commands(binary, root, outdir):
    cmd = os.path.join(outdir, "cmd")
    os.makedirs(cmd, exist_ok=True)
    cases, inputs = commands(root, cmd)
    for path, lines in inputs.items():
        with open(path, "w") as f:
            f.write("\n".join(lines) + "\n")
    for case, argv, stdout in cases:
        print(" ".join([binary] + argv), flush=True)
        if stdout is None:
            r = subprocess.run([binary] + argv)
        else:
            r = subprocess.run([binary] + argv, capture_output=True, text=True)
            os.makedirs(os.path.dirname(stdout), exist_ok=True)
            with open(stdout, "w", newline="") as f:
                w = csv.writer(f)
                w.writerow(["line"])
                for line in r.stdout.splitlines():
                    w.writerow([line])
        if r.returncode != 0:
            print(f"  exit {r.returncode}", flush=True)


ROOT_FILE = ".repo_root"


def run(binary, outdir):
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    os.makedirs(outdir, exist_ok=True)
    with open(os.path.join(outdir, ROOT_FILE), "w") as f:
        f.write(root + "\n")
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
    run_commands(binary, root, outdir)


def number(s):
    try:
        return float(s)
    except ValueError:
        return None


def repo_root(top):
    """The repository root the outputs under `top` were made from (None if not recorded)."""
    try:
        with open(os.path.join(top, ROOT_FILE)) as f:
            return f.read().strip() or None
    except OSError:
        return None


def same(a, b, roots=(None, None)):
    x, y = number(a), number(b)
    if x is None or y is None:
        ra, rb = roots
        if ra:
            a = a.replace(ra, "<repo>")
        if rb:
            b = b.replace(rb, "<repo>")
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


def relative_difference(a, b):
    """|x - y| / max(|x|, |y|) of two numeric cells that are not the same text, else None."""
    x, y = number(a), number(b)
    if x is None or y is None or a.strip() == b.strip() or math.isnan(x) or math.isnan(y):
        return None
    return abs(x - y) / max(abs(x), abs(y), 1e-300)


def compare(old, new):
    a, b = csvs(old), csvs(new)
    roots = (repo_root(old), repo_root(new))
    bad = 0
    # Values that differ at all (within the tolerance or not), and the largest difference.
    moved, largest = 0, (0.0, "")
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
                d = relative_difference(u, v)
                if d is not None and d > 0.0:
                    moved += 1
                    if d > largest[0]:
                        largest = (d, f"{rel}: row {i} column {c}: {u} vs {v}")
                if not same(u, v, roots):
                    if diffs < 5:
                        print(f"{rel}: row {i} column {c}: {u} vs {v}")
                    diffs += 1
        if diffs:
            print(f"{rel}: {diffs} differing values")
            bad += 1
        checked += 1
    print(f"{checked} files compared, {bad} differ")
    print(f"{moved} numbers not identical; largest relative difference {largest[0]:.3g}"
          + (f" ({largest[1]})" if largest[1] else ""))
    return 1 if bad else 0


if __name__ == "__main__":
    if len(sys.argv) != 4 or sys.argv[1] not in ("run", "compare"):
        print(__doc__)
        sys.exit(2)
    if sys.argv[1] == "run":
        run(os.path.abspath(sys.argv[2]), os.path.abspath(sys.argv[3]))
    else:
        sys.exit(compare(sys.argv[2], sys.argv[3]))
