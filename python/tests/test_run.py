"""settle.run against `settle run`: the same tables (each DataFrame equals pandas.read_csv of the
command line's file; the CSV bytes are the file's), overrides equal to --set, the same error
messages, the same files written."""

from __future__ import annotations

import itertools
import os
import subprocess
from pathlib import Path

import pandas as pd
import pytest

import settle
from frames import READ_CSV, assert_frame_is_read_csv

ROOT = Path(__file__).resolve().parents[2]
SCENARIOS = ROOT / "scenarios"
BINARY = Path(os.environ.get("SETTLE_BIN", ROOT / "target" / "release" / "settle"))




def cli(*args: str, check: bool = True) -> subprocess.CompletedProcess:
    """Runs the settle binary; fails the test when it exits non-zero and `check`."""
    if not BINARY.exists():
        pytest.fail(f"{BINARY} is missing: build it with `cargo build --release`")
    p = subprocess.run([str(BINARY), *args], capture_output=True, text=True)
    if check:
        assert p.returncode == 0, p.stderr
    return p


def cli_run(file: Path, out: Path, *sets: str) -> Path:
    """`settle run FILE --set ... --out OUT -q`; returns the run's folder."""
    args = ["run", str(file), "--out", str(out), "-q"]
    for s in sets:
        args += ["--set", s]
    cli(*args)
    (run_dir,) = [p for p in out.iterdir() if p.is_dir() and not p.name.startswith(".")]
    return run_dir


def csv_files(run_dir: Path) -> dict:
    """Every CSV file of a run folder, keyed by its stem relative to the folder."""
    return {
        p.relative_to(run_dir).as_posix()[: -len(".csv")]: p
        for p in sorted(run_dir.rglob("*.csv"))
    }


def assert_tables_equal_files(r: settle.Result, run_dir: Path) -> None:
    files = csv_files(run_dir)
    assert sorted(r.tables) == sorted(files)
    for stem, path in files.items():
        assert r.csv(stem) == path.read_bytes(), stem
        got = r.tables[stem]
        lines = path.read_text().splitlines()
        preamble = list(itertools.takewhile(lambda line: line.startswith("#"), lines))
        assert preamble == got.attrs.get("preamble", []), stem
        expected = pd.read_csv(path, skiprows=len(preamble), **READ_CSV)
        assert_frame_is_read_csv(got, expected, stem)


# One scenario of every kind (the long ones shortened by overrides, as in tests/api/run.rs).
EVERY_KIND = [
    ("stokes_single.toml", "free_settling", ()),
    ("valentik_susp1.toml", "free_settling", ()),
    ("paste_single_ball.toml", "drop", ()),
    ("restitution_drop.toml", "restitution_drop", ()),
    ("tilt_friction.toml", "tilt_friction", ()),
    (
        "paste_68_balls.toml",
        "funnel_pour",
        ("repeats.count=1", "time.dt_s=1e-4", "funnel.count_time_s=0.15", "time.end_s=0.2"),
    ),
    ("sedimentation_sample1.toml", "sedimentation", ("sample.particles=2000",)),
]


@pytest.mark.parametrize("file,kind,sets", EVERY_KIND)
def test_tables_equal_the_files_of_settle_run(
    tmp_path: Path, file: str, kind: str, sets: tuple
) -> None:
    s = settle.load(SCENARIOS / file)
    assert s.kind == kind
    r = settle.run(s, overrides=list(sets), progress=False)
    assert r.status == "complete"
    assert r.record["run"]["status"] == "complete"
    assert isinstance(r.warnings, list)
    assert_tables_equal_files(r, cli_run(SCENARIOS / file, tmp_path, *sets))


def test_empty_cells_are_nan_as_read_csv_reads_them(tmp_path: Path) -> None:
    """Some table of the runs above has empty cells; they are NaN in both."""
    seen = 0
    for file, _, sets in EVERY_KIND[:5]:
        r = settle.run(SCENARIOS / file, overrides=list(sets), progress=False)
        for stem, df in r.tables.items():
            empty = sum(
                1 for row in r.csv(stem).decode().splitlines()[1:] for c in row.split(",") if c == ""
            )
            assert int(df.isna().sum().sum()) >= empty, stem
            seen += empty
    assert seen > 0, "no table with an empty cell: pick a scenario that has one"


def test_set_equals_cli_set(tmp_path: Path) -> None:
    file = SCENARIOS / "stokes_single.toml"
    s = settle.load(file).set("fluid.viscosity_pa_s", 0.002).set("drag.law", "dallavalle")
    assert s.overrides == ['fluid.viscosity_pa_s=0.002', 'drag.law="dallavalle"']
    r = settle.run(s, progress=False)
    run_dir = cli_run(file, tmp_path, "fluid.viscosity_pa_s=0.002", "drag.law=dallavalle")
    assert_tables_equal_files(r, run_dir)
    # the overrides argument of run() is the same as set()
    r2 = settle.run(
        file,
        overrides={"fluid.viscosity_pa_s": 0.002, "drag.law": "dallavalle"},
        progress=False,
    )
    for stem in r.tables:
        assert r2.csv(stem) == r.csv(stem)
    baseline = settle.run(file, progress=False)
    assert baseline.csv("summary") != r.csv("summary")


def test_bad_input_raises_the_cli_message(tmp_path: Path) -> None:
    file = SCENARIOS / "stokes_single.toml"
    p = cli("run", str(file), "--set", "fluid.viscosity_pa_s=-1", "--out", str(tmp_path), check=False)
    assert p.returncode == 2
    with pytest.raises(settle.ScenarioError) as e:
        settle.load(file).set("fluid.viscosity_pa_s", -1)
    assert isinstance(e.value, ValueError)
    assert e.value.key == "fluid.viscosity_pa_s"
    assert p.stderr.strip() == f"error: {e.value}"


def test_unknown_key_and_bad_text() -> None:
    with pytest.raises(settle.ScenarioError) as e:
        settle.load(SCENARIOS / "stokes_single.toml").set("fluid.no_such_key_m", 1.0)
    assert "no_such_key_m" in str(e.value)
    with pytest.raises(settle.ScenarioError) as e:
        settle.Scenario.from_toml("kind = 3")
    assert str(e.value).startswith("<scenario text>")


def test_missing_file_is_an_error_naming_it(tmp_path: Path) -> None:
    missing = tmp_path / "nope.toml"
    p = cli("run", str(missing), "--out", str(tmp_path / "out"), check=False)
    with pytest.raises((settle.ScenarioError, OSError)) as e:
        settle.load(missing)
    assert p.stderr.strip() == f"error: {e.value}"


def test_from_toml_and_from_dict_equal_load() -> None:
    file = SCENARIOS / "stokes_single.toml"
    s = settle.load(file)
    t = settle.Scenario.from_toml(file.read_text(), origin=file)
    assert t.to_toml() == s.to_toml()
    d = settle.Scenario.from_dict(s.to_dict())
    assert (d.name, d.kind) == (s.name, s.kind)
    assert d.to_toml() == s.to_toml()
    assert settle.run(d, progress=False).csv("summary") == settle.run(s, progress=False).csv(
        "summary"
    )


def test_dt_equals_cli_dt(tmp_path: Path) -> None:
    file = SCENARIOS / "stokes_single.toml"
    r = settle.run(file, dt=2e-4, progress=False)
    assert r.scenario.dt_s == 2e-4
    cli("run", str(file), "--dt", "2e-4", "--out", str(tmp_path), "-q")
    assert_tables_equal_files(r, tmp_path / "stokes_single")


def test_run_with_out_writes_the_folder(tmp_path: Path) -> None:
    file = SCENARIOS / "stokes_single.toml"
    r = settle.run(file, out=tmp_path / "py", progress=False)
    cli_dir = cli_run(file, tmp_path / "cli")
    py_dir = tmp_path / "py" / "stokes_single"
    names = lambda d: sorted(p.relative_to(d).as_posix() for p in d.rglob("*") if p.is_file())
    assert names(py_dir) == names(cli_dir)
    for stem, path in csv_files(cli_dir).items():
        assert (py_dir / f"{stem}.csv").read_bytes() == path.read_bytes()
    # record: what run.toml holds, as a dict (the written file's, but for its wall time)
    written = settle._core._toml_loads((py_dir / "run.toml").read_text())
    for rec in (written, r.record):
        rec["run"].pop("wall_time_s")
    assert written == r.record
    assert r.record["scenario"]["name"] == "stokes_single"
    # a second write into the same folder replaces the run settle made
    assert r.write(tmp_path / "py") == os.fspath(py_dir)


def test_write_refuses_a_folder_settle_did_not_make(tmp_path: Path) -> None:
    foreign = tmp_path / "stokes_single"
    foreign.mkdir()
    (foreign / "mine.txt").write_text("not settle's")
    r = settle.run(SCENARIOS / "stokes_single.toml", progress=False)
    with pytest.raises(settle.ScenarioError):
        r.write(tmp_path)
    assert (foreign / "mine.txt").read_text() == "not settle's"


def test_unstable_run_raises_unstable_error_with_the_cli_message(tmp_path: Path) -> None:
    file = SCENARIOS / "stokes_single.toml"
    p = cli(
        "run", str(file), "--dt", "5e-3", "--set", "time.integrator=explicit",
        "--out", str(tmp_path / "cli"), check=False,
    )
    assert p.returncode == 3
    with pytest.raises(settle.UnstableError) as e:
        settle.run(file, dt=5e-3, overrides=["time.integrator=explicit"],
                   out=tmp_path / "py", progress=False)
    assert p.stderr.strip() == f"error: {e.value}"
    assert not (tmp_path / "py").exists()
