#!/usr/bin/env python3
"""The cost of spreading a sweep over an executor (docs/cluster.md's figures), in one run:

    target/py-venv/bin/python python/benches/executors.py [--slurm]

The dt sweep of scenarios/valentik_susp1.toml over its `[sweep]` grid (3 integrators × 10 time
steps, 30 cases) run serially (`settle.sweep`, every core), then with `executor=`: a process
pool of 2 workers (spawn), Dask's local cluster of 2 worker processes (one thread each), and
with `--slurm` submitit on the Slurm of scripts/slurm_local.sh (4 parts, 4 jobs). Each
executor's sweep is checked equal to the serial one (sweep.csv, wall times aside). Wall times
include starting the pool, cluster or jobs. Speeds are machine figures: compare ratios
measured in one run.
"""
from __future__ import annotations

import concurrent.futures
import multiprocessing
import sys
import tempfile
import time
from pathlib import Path
from typing import Any, Callable

import settle

ROOT = Path(__file__).resolve().parents[2]
SCENARIO = ROOT / "scenarios" / "valentik_susp1.toml"


def sweep_csv(r: Any) -> Any:
    return r.tables["sweep"].drop(columns=["wall_time_s"])


def timed(label: str, run: Callable[[], Any], want: Any) -> None:
    t = time.perf_counter()
    r = run()
    dt = time.perf_counter() - t
    same = want is None or sweep_csv(r).equals(sweep_csv(want))
    print(f"{label:44s} {dt:7.2f} s   equal to serial: {same}")
    if not same:
        raise SystemExit(f"{label}: differs from the serial sweep")


def main() -> None:
    want = settle.sweep(SCENARIO)
    timed("serial (settle.sweep, every core)", lambda: settle.sweep(SCENARIO), want)

    def pool() -> Any:
        ctx = multiprocessing.get_context("spawn")
        with concurrent.futures.ProcessPoolExecutor(2, mp_context=ctx) as ex:
            return settle.sweep(SCENARIO, executor=ex)

    timed("ProcessPoolExecutor(2), 30 parts", pool, want)

    def dask() -> Any:
        import distributed

        with distributed.LocalCluster(
            n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
        ) as cluster, distributed.Client(cluster) as client:
            return settle.sweep(SCENARIO, executor=client.get_executor())

    timed("Dask LocalCluster(2 processes), 30 parts", dask, want)
    if "--slurm" in sys.argv:
        import submitit

        with tempfile.TemporaryDirectory() as folder:
            ex = submitit.AutoExecutor(folder=folder, cluster="slurm")
            ex.update_parameters(timeout_min=10, cpus_per_task=1)
            timed("submitit on Slurm, 4 parts (4 jobs)",
                  lambda: settle.sweep(SCENARIO, executor=ex, parts=4), want)


if __name__ == "__main__":
    main()
