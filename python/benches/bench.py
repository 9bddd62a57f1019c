#!/usr/bin/env python3
"""Benchmarks of the Python package (issue 25's acceptance figures), measured in one run:

    target/py-venv/bin/python python/benches/bench.py [--quick]

- `import settle`: wall time of a fresh interpreter's import (median of 7);
- overhead: `settle.run("scenarios/stokes_single.toml")` from Python against the Rust run's own
  wall time (`Result.wall_time_s`), median of 200 (and with the tables as DataFrames);
- threads: the six Valentik scenarios run serially and by a pool of two Python threads
  (`ThreadPoolExecutor.map` over the files in order), with the runs' own parallel loops on
  every core (default) and on one thread each (`threads=1`); median of 5;
- memory: peak RSS of a 1e5-grain cylinder (sedimentation_sample5) run from Python with every
  table as a DataFrame, against `settle run` of the same scenario (the command line writes
  its CSV files) and against the size of the largest table as float64 columns.
Speeds are machine figures: compare ratios measured in one run, not figures across machines.
"""
from __future__ import annotations

import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SCEN = ROOT / "scenarios"
BIN = Path(os.environ.get("SETTLE_BIN", ROOT / "target" / "release" / "settle"))
QUICK = "--quick" in sys.argv


def import_time() -> float:
    times = []
    for _ in range(3 if QUICK else 7):
        out = subprocess.run(
            [sys.executable, "-c", "import time; t=time.perf_counter(); import settle; "
             "print(time.perf_counter()-t)"],
            capture_output=True, text=True, check=True,
        )
        times.append(float(out.stdout))
    return statistics.median(times)


def overhead() -> tuple[float, float, float]:
    import settle

    s = settle.load(SCEN / "stokes_single.toml")
    settle.run(s, progress=False)  # warm
    py, rust, frames = [], [], []
    for _ in range(50 if QUICK else 200):
        t = time.perf_counter()
        r = settle.run(s, progress=False)
        py.append(time.perf_counter() - t)
        rust.append(r.wall_time_s)
        t = time.perf_counter()
        r = settle.run(s, progress=False)
        _ = r.tables
        frames.append(time.perf_counter() - t)
    return statistics.median(py), statistics.median(rust), statistics.median(frames)


def threads(per_run_threads: int | None) -> tuple[float, float]:
    import settle

    files = [settle.load(SCEN / f"valentik_susp{i}.toml") for i in range(1, 7)]
    for s in files:
        settle.run(s, progress=False, threads=per_run_threads)  # warm

    def serial() -> float:
        t = time.perf_counter()
        for s in files:
            settle.run(s, progress=False, threads=per_run_threads)
        return time.perf_counter() - t

    def two() -> float:
        # as a user would: a pool of two threads mapping settle.run over the files in order
        from concurrent.futures import ThreadPoolExecutor

        t = time.perf_counter()
        with ThreadPoolExecutor(max_workers=2) as ex:
            list(ex.map(lambda s: settle.run(s, progress=False, threads=per_run_threads), files))
        return time.perf_counter() - t

    n = 3 if QUICK else 5
    ser = statistics.median(serial() for _ in range(n))
    par = statistics.median(two() for _ in range(n))
    return ser, par


MEM_CHILD = """
import resource, sys, settle
r = settle.run(sys.argv[1], overrides={"sample.particles": 100000}, progress=False)
tables = r.tables
big = max(tables, key=lambda k: tables[k].memory_usage(deep=False).sum())
print(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024,
      big, int(tables[big].memory_usage(deep=False).sum()), len(tables[big]))
"""


def memory() -> tuple[int, int, str, int, int]:
    file = str(SCEN / "sedimentation_sample5.toml")
    out = subprocess.run([sys.executable, "-c", MEM_CHILD, file], capture_output=True,
                         text=True, check=True).stdout.split()
    py_rss, big, big_bytes, big_rows = int(out[0]), out[1], int(out[2]), int(out[3])
    import tempfile

    with tempfile.TemporaryDirectory() as d:
        p = subprocess.run(["/usr/bin/time", "-f", "%M", str(BIN), "run", file, "--set",
                            "sample.particles=100000", "--out", d, "-q"],
                           capture_output=True, text=True, check=True)
        cli_rss = int(p.stderr.strip().splitlines()[-1]) * 1024
    return py_rss, cli_rss, big, big_bytes, big_rows


def main() -> None:
    print(f"import settle: {import_time() * 1e3:.0f} ms (median)")
    py, rust, frames = overhead()
    print(f"stokes_single: settle.run {py * 1e3:.2f} ms median, the Rust run {rust * 1e3:.2f} ms, "
          f"binding overhead {(py - rust) * 1e3:.2f} ms; with the tables as DataFrames "
          f"{frames * 1e3:.2f} ms")
    for per in (None, 1):
        ser, par = threads(per)
        label = "every core per run" if per is None else "threads=1 per run"
        print(f"six Valentik scenarios ({label}): serial {ser:.3f} s, two Python threads "
              f"{par:.3f} s, ratio {par / ser:.2f}")
    py_rss, cli_rss, big, big_bytes, big_rows = memory()
    print(f"1e5-grain cylinder (sample 5): peak RSS from Python with every table as a DataFrame "
          f"{py_rss / 1e6:.0f} MB, settle run {cli_rss / 1e6:.0f} MB; largest table {big} "
          f"({big_rows} rows, {big_bytes / 1e6:.1f} MB as DataFrame)")


if __name__ == "__main__":
    main()
