"""settle.sweep(..., executor=...) and settle.vary(..., executor=...): the grid split into shards,
each run by an executor (a process pool, Dask's local cluster, submitit on the local Slurm of
scripts/slurm_local.sh), merged in the caller: every table equal to the serial call's, cell for
cell (wall times aside), the same charts and lines. A scenario travels as its to_toml() text,
also through pickle. Dask, distributed and submitit are installed by scripts/test_python.sh and
the Slurm is started by scripts/test.sh: without them these tests FAIL, saying so (never skip)."""

from __future__ import annotations

import concurrent.futures
import csv
import io
import multiprocessing
import pickle
import shutil
import subprocess
from pathlib import Path
from typing import Any, Dict, Iterator, List, Tuple

import pandas as pd
import pytest

import settle

ROOT = Path(__file__).resolve().parents[2]
STOKES = ROOT / "scenarios" / "stokes_single.toml"
VALENTIK = ROOT / "scenarios" / "valentik_susp1.toml"
WALL = "wall_time_s"
# Valentik & Whitmore's suspension 1 (27 spheres from a CSV table) with overrides, coarse dt.
VALENTIK_SET = {"time.dt_s": 0.01, "fluid.yield_stress_pa": 25.0}
SWEEP = dict(dt=[1e-3, 1e-4, 1e-5], integrators=["explicit", "exponential"])
GRID = {"fluid.viscosity_pa_s": [1e-3, 2e-3, 5e-3], "drag.law": ["stokes", "dallavalle"]}


def without_wall(data: bytes) -> bytes:
    """CSV bytes with every wall_time_s cell emptied (wall times measure the machine)."""
    rows = list(csv.reader(io.StringIO(data.decode())))
    k = rows[0].index(WALL) if rows and WALL in rows[0] else None
    out = io.StringIO()
    w = csv.writer(out, lineterminator="\n")
    for i, r in enumerate(rows):
        if k is not None and i > 0:
            r[k] = ""
        w.writerow(r)
    return out.getvalue().encode()


def wall_free(line: str) -> str:
    """A console line of a dt sweep without its wall-time column (a case line's 4th word)."""
    w = line.split()
    if len(w) > 3 and w[0] in ("explicit", "implicit", "exponential"):
        w[3] = ""
    return " ".join(w)


def assert_same(got: Any, want: Any) -> None:
    """Every table of `got` equals that of `want` (CSV bytes and DataFrame, exact; wall times
    aside), with the same charts, warnings and lines; the charts that do not draw wall times
    are equal byte for byte."""
    assert got.name == want.name
    assert sorted(got.tables) == sorted(want.tables)
    for name, frame in want.tables.items():
        assert without_wall(got.csv(name)) == without_wall(want.csv(name)), name
        drop = [WALL] if WALL in frame.columns else []
        pd.testing.assert_frame_equal(
            got.tables[name].drop(columns=drop), frame.drop(columns=drop), check_exact=True
        )
    assert sorted(got.files) == sorted(want.files)
    for name, data in want.files.items():
        if name.endswith(".svg") and name != "speed_accuracy.svg":  # its x axis: wall time
            assert got.files[name] == data, name
    assert got.warnings == want.warnings
    assert [wall_free(x) for x in got.lines] == [wall_free(x) for x in want.lines]


@pytest.fixture(scope="module")
def pool() -> Iterator[concurrent.futures.ProcessPoolExecutor]:
    """Two worker processes, started by spawn (nothing inherited from this process)."""
    ctx = multiprocessing.get_context("spawn")
    with concurrent.futures.ProcessPoolExecutor(max_workers=2, mp_context=ctx) as ex:
        yield ex


def test_a_scenario_round_trips_through_its_toml_and_pickle() -> None:
    """A scenario with overrides and a CSV table of spheres, made again from its to_toml()
    text (as an executor's task makes it) or unpickled, runs to the same tables."""
    s = settle.load(VALENTIK)
    for k, v in VALENTIK_SET.items():
        s = s.set(k, v)
    want = settle.run(s)
    for again in (settle.Scenario.from_toml(s.to_toml(), s.path), pickle.loads(pickle.dumps(s))):
        assert again.name == s.name and again.path == s.path
        assert again.to_toml() == s.to_toml()
        got = settle.run(again)
        for name in want.tables:
            assert without_wall(got.csv(name)) == without_wall(want.csv(name)), name


def test_a_dt_sweep_on_a_process_pool_equals_the_serial_sweep(
    pool: concurrent.futures.ProcessPoolExecutor,
) -> None:
    want = settle.sweep(STOKES, **SWEEP)
    for parts in (None, 4):  # one part per case (6), and shards of 2, 2, 1, 1 cases
        assert_same(settle.sweep(STOKES, **SWEEP, executor=pool, parts=parts), want)
    # overrides and a CSV table of spheres: the workers read it from its absolute path
    opts: Dict[str, Any] = dict(dt=[0.02, 0.01], integrators="exponential", overrides=VALENTIK_SET)
    assert_same(settle.sweep(VALENTIK, **opts, executor=pool), settle.sweep(VALENTIK, **opts))


def test_a_parameter_sweep_on_a_process_pool_equals_the_serial_sweep(
    pool: concurrent.futures.ProcessPoolExecutor,
) -> None:
    calls: List[Tuple[str, int, Any, str, str]] = []
    progress = lambda *a: calls.append(a)  # noqa: E731
    got = settle.vary(STOKES, GRID, executor=pool, parts=4, progress=progress)
    assert_same(got, settle.vary(STOKES, GRID))
    # the bar: over the 4 parts, to the last
    assert calls and calls[-1] == ("stokes_single", 4, 4, "parts", "")
    grid = {"fluid.yield_stress_pa": [20, 30]}
    want = settle.vary(VALENTIK, grid, overrides=VALENTIK_SET)
    assert_same(settle.vary(VALENTIK, grid, overrides=VALENTIK_SET, executor=pool), want)


class Recorder:
    """An executor that records what is submitted and runs nothing; its futures never end and
    record their cancellation."""

    def __init__(self) -> None:
        self.futures: List["Recorder.Never"] = []

    class Never:
        cancelled = False

        def done(self) -> bool:
            return False

        def result(self) -> Any:  # pragma: no cover
            raise AssertionError("never done")

        def cancel(self) -> bool:
            self.cancelled = True
            return True

    def submit(self, fn: Any, *args: Any) -> "Recorder.Never":
        self.futures.append(Recorder.Never())
        return self.futures[-1]


def test_errors_are_the_serial_calls_and_ctrl_c_cancels_the_parts(
    pool: concurrent.futures.ProcessPoolExecutor, tmp_path: Path
) -> None:
    # A bad option: the serial call's ScenarioError, before anything is submitted.
    rec = Recorder()
    for call in (
        lambda **kw: settle.sweep(STOKES, dt=[1e-3, -1.0], **kw),
        lambda **kw: settle.vary(STOKES, {"fluid.viscosity_pa_s": [1e-3, -1.0]}, **kw),
    ):
        with pytest.raises(settle.ScenarioError) as serial:
            call()
        with pytest.raises(settle.ScenarioError) as spread:
            call(executor=rec)
        assert str(spread.value) == str(serial.value)
        assert rec.futures == []
    # An error in a task (the spheres' CSV gone before the workers read it): a ScenarioError
    # naming the file and the key, raised in the caller.
    for d in ("s", "data"):
        (tmp_path / d).mkdir()
    shutil.copy(VALENTIK, tmp_path / "s" / "v.toml")  # its table: ../data/<name>.csv
    table = tmp_path / "data" / "valentik_whitmore_1965_spheres.csv"
    shutil.copy(ROOT / "data" / table.name, table)
    s = settle.load(tmp_path / "s" / "v.toml").set("time.dt_s", 0.01)
    table.unlink()
    with pytest.raises(settle.ScenarioError) as e:
        settle.sweep(s, dt=[0.02, 0.01], executor=pool)
    with pytest.raises(settle.ScenarioError) as loading:
        settle.load(tmp_path / "s" / "v.toml")
    assert str(e.value) == str(loading.value)
    assert (e.value.file, e.value.key) == (str(tmp_path / "s" / "v.toml"), "spheres_csv.path")
    # Ctrl-C while waiting: every part not done is cancelled, and KeyboardInterrupt raised.
    rec = Recorder()

    def interrupt(*_: Any) -> None:
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        settle.sweep(STOKES, **SWEEP, executor=rec, parts=3, progress=interrupt)
    assert len(rec.futures) == 3 and all(f.cancelled for f in rec.futures)
    # Bad arguments.
    with pytest.raises(ValueError, match="parts: only with an executor"):
        settle.sweep(STOKES, **SWEEP, parts=2)
    with pytest.raises(ValueError, match="an int >= 1"):
        settle.sweep(STOKES, **SWEEP, executor=rec, parts=0)
    with pytest.raises(TypeError, match="submit"):
        settle.vary(STOKES, GRID, executor=object())  # type: ignore[arg-type]


def test_dask_local_cluster_spreads_a_sweep_and_a_parameter_sweep() -> None:
    """Dask's executor on a local cluster of 2 worker processes."""
    import distributed  # installed by scripts/test_python.sh: missing, the test fails

    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        ex = client.get_executor()
        assert_same(settle.sweep(STOKES, **SWEEP, executor=ex), settle.sweep(STOKES, **SWEEP))
        assert_same(settle.vary(STOKES, GRID, executor=ex, parts=3), settle.vary(STOKES, GRID))


def require_slurm() -> None:
    """Fails (never skips) with how to start Slurm unless a controller answers."""
    try:
        p = subprocess.run(["sinfo", "-h", "-o", "%T"], capture_output=True, text=True)
        up = p.returncode == 0 and any(
            s.strip() in ("idle", "mixed", "allocated", "completing") for s in p.stdout.splitlines()
        )
        why = p.stderr.strip()
    except FileNotFoundError as e:
        up, why = False, str(e)
    if not up:
        pytest.fail(
            f"no Slurm answers here (sinfo: {why!r}): the submitit test needs one; install "
            "Debian's slurm-wlm and munge and run `scripts/slurm_local.sh start` as root "
            "(scripts/test.sh does the second, .ci/run the first)"
        )


def test_submitit_on_slurm_spreads_a_sweep(tmp_path: Path) -> None:
    """submitit's Slurm executor: each part a Slurm job running this venv's python (the folder
    on this machine's disk, which the local slurmd reads)."""
    require_slurm()
    import submitit

    ex = submitit.AutoExecutor(folder=tmp_path / "submitit", cluster="slurm")
    ex.update_parameters(timeout_min=10, cpus_per_task=1, slurm_job_name="settle-executor-test")
    jobs: List[Any] = []

    class Recording:
        def submit(self, fn: Any, *args: Any) -> Any:
            jobs.append(ex.submit(fn, *args))
            return jobs[-1]

    got = settle.sweep(STOKES, **SWEEP, executor=Recording(), parts=2)
    assert_same(got, settle.sweep(STOKES, **SWEEP))
    # two Slurm jobs ran them, each with its log
    assert len(jobs) == 2 and all(j.job_id.isdigit() for j in jobs), [j.job_id for j in jobs]
    assert all(j.paths.stdout.exists() for j in jobs)
