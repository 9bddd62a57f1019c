"""settle.sweep and settle.vary against `settle sweep` and `settle sweep --vary`: the same tables
(each DataFrame equals pandas.read_csv of the command line's file; the CSV bytes are the file's,
wall times aside), the same charts and console lines, the same files written, the command
line's error messages."""

from __future__ import annotations

import csv
import io
import os
import subprocess
from pathlib import Path
from typing import List, Optional, Tuple

import pandas as pd
import pytest

import settle
from frames import READ_CSV, assert_frame_is_read_csv

ROOT = Path(__file__).resolve().parents[2]
STOKES = ROOT / "scenarios" / "stokes_single.toml"
BINARY = Path(os.environ.get("SETTLE_BIN", ROOT / "target" / "release" / "settle"))
WALL = "wall_time_s"


def cli(*args: str, check: bool = True) -> subprocess.CompletedProcess:
    """Runs `settle sweep ARGS`; fails the test when it exits non-zero and `check`."""
    if not BINARY.exists():
        pytest.fail(f"{BINARY} is missing: build it with `cargo build --release`")
    p = subprocess.run([str(BINARY), "sweep", *args], capture_output=True, text=True)
    if check:
        assert p.returncode == 0, p.stderr
    return p


def without_wall(data: bytes) -> bytes:
    """CSV bytes with every wall_time_s cell emptied (wall times measure the machine); the
    other cells, and their quoting, as they are."""
    rows = list(csv.reader(io.StringIO(data.decode())))
    k = rows[0].index(WALL) if WALL in rows[0] else None
    out = io.StringIO()
    w = csv.writer(out, lineterminator="\n")
    for i, r in enumerate(rows):
        if k is not None and i > 0:
            r[k] = ""
        w.writerow(r)
    return out.getvalue().encode()


def files(folder: Path) -> List[str]:
    """The files of a results folder but settle's marker, relative, sorted."""
    return sorted(
        p.relative_to(folder).as_posix()
        for p in folder.rglob("*")
        if p.is_file() and p.name != ".settle-run"
    )


def assert_output_is_the_folder(r: settle.Output, folder: Path, charts_equal: List[str]) -> None:
    """Every CSV file of the folder is a table of `r` with its bytes and as read_csv reads it
    (wall times aside); every other file is a file of `r`; the charts named are equal."""
    on_disk = files(folder)
    assert sorted([s + ".csv" for s in r.tables] + list(r.files)) == on_disk
    for name in [n for n in on_disk if n.endswith(".csv")]:
        stem = name[: -len(".csv")]
        path = folder / name
        assert without_wall(r.csv(stem)) == without_wall(path.read_bytes()), stem
        got = r.tables[stem].drop(columns=[WALL], errors="ignore")
        expected = pd.read_csv(path, **READ_CSV).drop(columns=[WALL], errors="ignore")
        assert_frame_is_read_csv(got, expected, stem)
    for name in charts_equal:
        assert r.files[name] == (folder / name).read_bytes(), name


def masked(line: str) -> str:
    """A console line of a dt sweep with its wall-time column left out."""
    w = line.split()
    if len(w) > 3 and w[0] in ("explicit", "implicit", "exponential"):
        w[3] = ""
    return " ".join(w)


def test_a_dt_sweep_equals_settle_sweep(tmp_path: Path) -> None:
    calls: List[Tuple[str, int, Optional[int], str, str]] = []
    r = settle.sweep(
        STOKES,
        dt=[1e-3, 1e-4, 1e-5],
        integrators=["explicit", "exponential"],
        overrides={"fluid.viscosity_pa_s": 0.002},
        progress=lambda *a: calls.append(a),
    )
    assert r.name == "stokes_single_sweep"
    assert sorted(r.tables) == ["recommended_dt", "sweep"]
    assert len(r.tables["sweep"]) == 2 * 3 * 3
    # The progress callback counted the 6 cases.
    assert calls and calls[-1][:4] == ("stokes_single", 6, 6, "cases")
    p = cli(str(STOKES), "--dt", "1e-3,1e-4,1e-5", "--integrator", "explicit,exponential",
            "--set", "fluid.viscosity_pa_s=0.002", "--out", str(tmp_path))
    folder = tmp_path / "stokes_single_sweep"
    assert_output_is_the_folder(r, folder, ["quantity_vs_dt.svg"])
    assert set(r.files) == {"quantity_vs_dt.svg", "speed_accuracy.svg", "report.html"}
    out = p.stdout.splitlines()
    assert out[-1] == f"  -> {folder}"
    assert [masked(x) for x in r.lines] == [masked(x) for x in out[:-1]]
    # The explicit scheme's recommendation is its finest dt: unverified.
    assert len(r.warnings) == 1 and r.warnings[0].startswith("explicit: the recommended dt 1e-5 s")
    # write(): the command line's files, each table's bytes.
    written = Path(r.write(tmp_path / "again"))
    assert written == tmp_path / "again" / "stokes_single_sweep"
    assert files(written) == files(folder)
    for stem in r.tables:
        assert (written / f"{stem}.csv").read_bytes() == r.csv(stem)


def test_the_same_sweep_as_text_options(tmp_path: Path) -> None:
    """integrators as the command line's comma list, one dt as a number; `out=` writes."""
    s = settle.load(STOKES)
    a = settle.sweep(s, dt=[1e-3, 1e-4], integrators="explicit,exponential", progress=False,
                     out=tmp_path)
    b = settle.sweep(s, dt=[1e-4, 1e-3], integrators=["explicit", "exponential"], progress=False)
    assert without_wall(a.csv("sweep")) == without_wall(b.csv("sweep"))
    assert a.csv("recommended_dt") == b.csv("recommended_dt")
    assert (tmp_path / "stokes_single_sweep" / "recommended_dt.csv").read_bytes() == a.csv(
        "recommended_dt"
    )
    one = settle.sweep(s, dt=1e-3, integrators="exponential", tol=0.5, progress=False)
    assert list(one.tables["sweep"]["dt_s"].unique()) == [1e-3]
    assert list(one.tables["recommended_dt"]["tol"]) == [0.5]


def test_a_parameter_sweep_equals_settle_sweep_vary(tmp_path: Path) -> None:
    """Two keys: a log grid as its text, a categorical key as a list; the first key outermost."""
    grid = {"fluid.viscosity_pa_s": "log:1e-3:1e-2:3", "drag.law": ["stokes", "dallavalle"]}
    r = settle.vary(settle.load(STOKES), grid, progress=False)
    assert r.name == "stokes_single_vary"
    assert list(r.tables) == ["vary"]
    assert len(r.tables["vary"]) == 6
    assert r.warnings == []
    p = cli(str(STOKES), "--vary", "fluid.viscosity_pa_s=log:1e-3:1e-2:3",
            "--vary", "drag.law=stokes,dallavalle", "--out", str(tmp_path))
    folder = tmp_path / "stokes_single_vary"
    charts = [n for n in files(folder) if n.endswith(".svg")]
    assert len(charts) == 3
    assert_output_is_the_folder(r, folder, charts)
    assert r.lines + [f"  -> {folder}"] == p.stdout.splitlines()
    written = Path(r.write(tmp_path / "again"))
    assert files(written) == files(folder)
    assert (written / "vary.csv").read_bytes() == r.csv("vary")


def test_vary_values_as_numbers_equal_the_command_lines_list(tmp_path: Path) -> None:
    r = settle.vary(STOKES, {"fluid.viscosity_pa_s": [0.005, 0.001, 0.002]},
                    overrides=["drag.law=dallavalle"], progress=False)
    cli(str(STOKES), "--vary", "fluid.viscosity_pa_s=0.001,0.002,0.005",
        "--set", "drag.law=dallavalle", "-q", "--out", str(tmp_path))
    folder = tmp_path / "stokes_single_vary"
    charts = [n for n in files(folder) if n.endswith(".svg")]
    assert_output_is_the_folder(r, folder, charts)
    assert list(r.tables["vary"]["fluid.viscosity_pa_s"]) == [0.001, 0.002, 0.005]


def cli_message(*args: str) -> str:
    """The command line's error message (stderr's first line without `error: `); exit 2."""
    p = cli(*args, "--out", "/nonexistent/never-written", check=False)
    assert p.returncode == 2, p.stderr
    first = p.stderr.splitlines()[0]
    assert first.startswith("error: ")
    return first[len("error: "):]


def allowed(message: str) -> str:
    """What clap's message says is allowed (after the option and value)."""
    return message.split("': ", 1)[1]


def test_bad_sweep_options_raise_the_command_lines_message() -> None:
    f = str(STOKES)
    with pytest.raises(settle.ScenarioError) as e:
        settle.sweep(STOKES, dt=[1e-3, -1e-3], progress=False)
    assert e.value.key == "--dt"
    assert str(e.value).endswith(allowed(cli_message(f, "--dt", "-1e-3")))
    with pytest.raises(settle.ScenarioError) as e:
        settle.sweep(STOKES, dt=1e-3, integrators=["rk4"], progress=False)
    assert e.value.key == "--integrator" and "rk4" in str(e.value)
    assert "explicit, implicit, exponential" in str(e.value)
    assert "rk4" in cli_message(f, "--dt", "1e-3", "--integrator", "rk4")
    with pytest.raises(settle.ScenarioError) as e:
        settle.sweep(STOKES, dt=1e-3, tol=0.0, progress=False)
    assert str(e.value).endswith(allowed(cli_message(f, "--dt", "1e-3", "--tol", "0")))
    with pytest.raises(settle.ScenarioError) as e:
        settle.sweep(STOKES, dt_range=(1e-3, 1e-5), progress=False)
    assert str(e.value).endswith(allowed(cli_message(f, "--dt-range", "1e-3:1e-5")))
    # No time steps: stokes_single.toml has no [sweep] table. The same message, word for word.
    with pytest.raises(settle.ScenarioError) as e:
        settle.sweep(STOKES, progress=False)
    assert str(e.value) == cli_message(f)
    assert e.value.key == "sweep.dt_s"
    # A kind that cannot be swept.
    tilt = ROOT / "scenarios" / "tilt_friction.toml"
    with pytest.raises(settle.ScenarioError) as e:
        settle.sweep(tilt, dt=1e-3, progress=False)
    assert str(e.value) == cli_message(str(tilt), "--dt", "1e-3")


def test_bad_vary_axes_raise_the_command_lines_message() -> None:
    f = str(STOKES)
    for key, values in [("fluid.no_such_m", "1,2"), ("fluid.viscosity_pa_s", "-1,1e-3")]:
        with pytest.raises(settle.ScenarioError) as e:
            settle.vary(STOKES, {key: values}, progress=False)
        assert str(e.value) == cli_message(f, "--vary", f"{key}={values}")
        assert e.value.key == key
    with pytest.raises(settle.ScenarioError) as e:
        settle.vary(STOKES, {"fluid.viscosity_pa_s": "1:2"}, progress=False)
    assert e.value.key == "--vary"
    assert str(e.value).endswith(allowed(cli_message(f, "--vary", "fluid.viscosity_pa_s=1:2")))
    with pytest.raises(settle.ScenarioError):
        settle.vary(STOKES, {"fluid.viscosity_pa_s": [float("nan"), 1.0]}, progress=False)
    with pytest.raises(settle.ScenarioError) as e:
        settle.vary(STOKES, {}, progress=False)
    assert e.value.key == "--vary"
    with pytest.raises(TypeError):
        settle.vary(STOKES, {"fluid.viscosity_pa_s": [None]}, progress=False)



def test_typed_usage_of_sweep_and_vary_runs() -> None:
    """The typed examples of typed_usage.py (checked by mypy --strict) run and say what a sweep
    says: the exponential scheme is exact at 1e-3 s, and Stokes' law is v ∝ 1/μ."""
    import sys

    here = str(Path(__file__).resolve().parent)
    sys.path.insert(0, here)
    try:
        import typed_usage
    finally:
        sys.path.remove(here)
    assert typed_usage.recommended_dts(STOKES) == {"exponential": 1e-3}
    v = typed_usage.terminal_velocities(STOKES)
    assert len(v) == 4
    # rows: (1e-3, dallavalle), (1e-3, stokes), (2e-3, dallavalle), (2e-3, stokes)
    assert v[1] / v[3] == pytest.approx(2.0, rel=1e-6)
