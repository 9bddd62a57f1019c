#!/usr/bin/env python3
"""Summary of scripts/peer/liggghts_bench.sh: OUT/runs.csv -> markdown on stdout.

Per N: LIGGGHTS particle-steps/s (N x M / loop time) per number of ranks, settle's suspended
grain-steps/s of the full-physics free update and of the whole run, N x steps/s, each as the
median and the best (the least disturbed) of the rounds; the ratio settle / LIGGGHTS (median
to median and best to best); and the wall time of the full 1440 min, settle's measured and
LIGGGHTS's projected as (86400 s / dt) x N / (particle-steps/s) at the drag-limited step and at
the step LIGGGHTS's floor E = 5e6 Pa would impose (OUT/logs/params_N.txt).

Usage: liggghts_summary.py OUT
"""
import csv
import glob
import os
import re
import statistics
import sys

END_S = 86400.0


def params(out, n):
    p = {}
    with open(os.path.join(out, "logs", f"params_{n}.txt")) as f:
        for line in f:
            k, v = line.split("=", 1)
            p[k.strip()] = float(v)
    return p


def breakdown(out):
    """{(atoms, ranks, round): {"loop": s, "Pair": s, "Neigh": s, ..., "builds": n}} of the
    timed (last) loop of every LIGGGHTS log."""
    res = {}
    for path in glob.glob(os.path.join(out, "logs", "liggghts_*_np*_r*.log")):
        text = open(path).read()
        loops = list(re.finditer(r"Loop time of (\S+) on (\d+) procs for (\d+) steps with (\d+) atoms", text))
        if not loops:
            continue
        last = loops[-1]
        tail = text[last.end():]
        parts = {"loop": float(last.group(1))}
        for name, secs in re.findall(r"^(\w+)\s+time \(%\) = (\S+)", tail, re.M)[:5]:
            parts[name] = float(secs)
        m = re.search(r"Neighbor list builds = (\d+)", tail)
        parts["builds"] = int(m.group(1)) if m else 0
        rnd = int(re.search(r"_r(\d+)\.log$", path).group(1))
        res[(int(last.group(4)), last.group(2), rnd)] = parts
    return res


def fmt(x):
    return f"{x:.3g}"


def duration(s):
    for unit, size in (("years", 365.25 * 86400), ("days", 86400), ("h", 3600), ("min", 60)):
        if s >= size:
            return f"{s / size:.3g} {unit}"
    return f"{s:.3g} s"


def main():
    out = sys.argv[1]
    rows = list(csv.DictReader(open(os.path.join(out, "runs.csv"))))
    by = {}
    for r in rows:
        key = (r["tool"], int(r["grains"]), r["ranks"])
        by.setdefault(key, []).append(r)
    loads = [float(r["load1_before"]) for r in rows]
    print("# LIGGGHTS against settle: summary\n")
    print(open(os.path.join(out, "machine.txt")).read().replace("\n", "  \n"))
    print(f"Load average (1 min) before the runs: median {statistics.median(loads):.2f}, "
          f"range {min(loads):.2f}–{max(loads):.2f}.\n")
    print("Median [best] of the rounds; rates in grain-steps (particle-steps) per second of wall.\n")
    print("| N | LIGGGHTS ranks | LIGGGHTS particle-steps/s | settle full, free update, suspended grain-steps/s "
          "| ratio settle / LIGGGHTS | settle full, whole run | ratio (run) | settle full, N × steps/s "
          "| settle ideal Stokes, free update |")
    print("|---|---|---|---|---|---|---|---|---|")
    proj = []
    parts = breakdown(out)
    notes = []
    for (tool, n, ranks), lg in sorted(by.items(), key=lambda kv: (kv[0][1], kv[0][2])):
        if tool != "liggghts":
            continue
        full = next(v for (t, m, _), v in by.items() if t == "settle-full-nocontacts" and m == n)
        ideal = next(v for (t, m, _), v in by.items() if t == "settle-ideal-stokes" and m == n)

        def col(rs, k):
            xs = [float(r[k]) for r in rs]
            return statistics.median(xs), max(xs)

        lg_med, lg_best = col(lg, "grain_steps_per_s")
        fu_med, fu_best = col(full, "grain_steps_per_s")
        run_med, run_best = col(full, "run_grain_steps_per_s")
        nt_med, nt_best = col(full, "n_times_steps_per_s")
        id_med, id_best = col(ideal, "grain_steps_per_s")
        print(f"| {n} | {ranks} | {fmt(lg_med)} [{fmt(lg_best)}] | {fmt(fu_med)} [{fmt(fu_best)}] | "
              f"**{fu_med / lg_med:.2f}** [{fu_best / lg_best:.2f}] | {fmt(run_med)} [{fmt(run_best)}] | "
              f"{run_med / lg_med:.2f} [{run_best / lg_best:.2f}] | {fmt(nt_med)} [{fmt(nt_best)}] | "
              f"{fmt(id_med)} [{fmt(id_best)}] |")
        p = params(out, n)
        bd = [parts[(n, ranks, int(r["round"]))] for r in lg if (n, ranks, int(r["round"])) in parts]
        if bd:
            share = lambda k: statistics.median(b.get(k, 0.0) / b["loop"] for b in bd)  # noqa: E731
            no_neigh = statistics.median(
                float(r["grain_steps_per_s"]) * parts[key]["loop"] / (parts[key]["loop"] - parts[key].get("Neigh", 0.0))
                for r in lg if (key := (n, ranks, int(r["round"]))) in parts)
            notes.append(f"| {n} | {ranks} | {share('Pair'):.0%} | {share('Neigh'):.0%} | {share('Comm'):.0%} | "
                         f"{share('Other'):.0%} | {statistics.median(b['builds'] for b in bd):.0f} | "
                         f"{fmt(no_neigh)} | {fu_med / no_neigh:.2f} |")
        walls = [float(r["wall_1440min_s"]) for r in full]
        iwalls = [float(r["wall_1440min_s"]) for r in ideal]
        proj.append((n, ranks, p, lg_med, lg_best, statistics.median(walls), min(walls),
                     statistics.median(iwalls)))
    print("\nLIGGGHTS's loop time by part (median share over the rounds; Other: the fixes: "
          "integration, gravity, drag, walls), its neighbour-list builds in the timed run, and its "
          "rate with the neighbour time taken out (an upper bound for a state without rebuilds):\n")
    print("| N | ranks | Pair | Neigh | Comm | Other | builds | particle-steps/s without Neigh "
          "| ratio settle free update / that |")
    print("|---|---|---|---|---|---|---|---|---|")
    print("\n".join(notes))
    print("\nWall time of the full 1440 min (settle: measured, median [best]; LIGGGHTS: projected "
          "from its median [best] rate):\n")
    print("| N | LIGGGHTS ranks | LIGGGHTS at the drag-limited dt | LIGGGHTS at dt for E = 5e6 Pa "
          "| settle full physics | settle ideal Stokes |")
    print("|---|---|---|---|---|---|")
    for n, ranks, p, lg_med, lg_best, w_med, w_best, iw in proj:
        def lw(dt, rate):
            return END_S / dt * n / rate
        print(f"| {n} | {ranks} | {duration(lw(p['dt_s'], lg_med))} [{duration(lw(p['dt_s'], lg_best))}] "
              f"(dt = {p['dt_s']:.3g} s) | {duration(lw(p['dt_at_e_5e6_pa_s'], lg_med))} "
              f"(dt = {p['dt_at_e_5e6_pa_s']:.3g} s) | {duration(w_med)} [{duration(w_best)}] | "
              f"{duration(iw)} |")


if __name__ == "__main__":
    main()
