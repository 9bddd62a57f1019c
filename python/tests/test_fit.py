"""settle.fit against `settle fit`: the same tables (each DataFrame equals pandas.read_csv of the
command line's file; the CSV bytes are the file's), the same chart and record, the same folder
written, the same error messages; settle.slump against `settle fit slump`."""

from __future__ import annotations

import os
import subprocess
from pathlib import Path
from typing import List, Optional, Tuple

import pandas as pd
import pytest

import settle
from frames import READ_CSV, assert_frame_is_read_csv

ROOT = Path(__file__).resolve().parents[2]
SCENARIOS = ROOT / "scenarios"
BINARY = Path(os.environ.get("SETTLE_BIN", ROOT / "target" / "release" / "settle"))

# docs/commands/fit.md's worked cases: η_B of paste from a settling distance (one fall height),
# and a constant restitution from f-EDEM Table A2 (at dt = 1e-4 s, as
# scripts/regress_outputs.py runs it, to stay short).
PASTE = SCENARIOS / "paste_single_ball.toml"
PASTE_M = (
    "file,column,row,value,sigma\n"
    "summary.csv,settling_distance_m,id=d12.6mm-H255mm,0.05063,5e-4\n"
)
ONE_HEIGHT = "release.fall_heights_m=[0.255]"
ETA = ("fluid.plastic_viscosity_pa_s", 0.1, 3.0)
DROP = SCENARIOS / "restitution_drop.toml"
REBOUND = pd.DataFrame(
    {
        "file": ["summary.csv"] * 5,
        "column": ["rebound_height_m"] * 5,
        "row": [f"drop_height_m={h}" for h in ("0.095", "0.188", "0.252", "0.318", "0.398")],
        "value": [0.0370, 0.0720, 0.0909, 0.1180, 0.1469],
    }
)
DROP_SET = ["time.dt_s=1e-4", "contacts.restitution_exponent=0"]


def cli(*args: str) -> subprocess.CompletedProcess:
    if not BINARY.exists():
        pytest.fail(f"{BINARY} is missing: build it with `cargo build --release`")
    return subprocess.run([str(BINARY), *args], capture_output=True, text=True)


def cli_fit(
    file: Path, sets: List[str], fits: List[Tuple[str, float, float]], m: Path, out: Path
) -> subprocess.CompletedProcess:
    args = ["fit", str(file), "--measured", str(m), "--out", str(out), "-q"]
    for s in sets:
        args += ["--set", s]
    for k, lo, hi in fits:
        args += ["--fit", f"{k}={lo:g}:{hi:g}"]
    return cli(*args)


def assert_output_equals_folder(o: settle.Output, folder: Path, same_record: bool = True) -> None:
    """Every CSV file of `folder` is a table of `o` (bytes; DataFrame as read_csv reads it),
    every other file one of `o.files` with the same bytes, and `o` has nothing else."""
    files = sorted(p.name for p in folder.iterdir() if not p.name.startswith("."))
    csvs = [f for f in files if f.endswith(".csv")]
    assert sorted(o.tables) == sorted(f[: -len(".csv")] for f in csvs)
    assert sorted(o.files) == sorted(f for f in files if not f.endswith(".csv"))
    for f in csvs:
        stem = f[: -len(".csv")]
        assert o.csv(stem) == (folder / f).read_bytes(), f
        expected = pd.read_csv(folder / f, **READ_CSV)
        assert_frame_is_read_csv(o.tables[stem], expected, stem)
    for name, data in o.files.items():
        if name != "fit.toml" or same_record:
            assert data == (folder / name).read_bytes(), name


def test_tables_equal_the_files_of_settle_fit(tmp_path: Path) -> None:
    m = tmp_path / "m.csv"
    m.write_text(PASTE_M)
    p = cli_fit(PASTE, [ONE_HEIGHT], [ETA], m, tmp_path / "cli")
    assert p.returncode == 0, p.stderr
    folder = tmp_path / "cli" / "paste_single_ball_fit"

    calls: List[Tuple[str, int, Optional[int], str, str]] = []
    o = settle.fit(
        os.fspath(PASTE),
        fit={ETA[0]: (ETA[1], ETA[2])},
        measured=m,
        overrides={"release.fall_heights_m": [0.255]},
        progress=lambda *a: calls.append(a),
    )
    assert o.name == "paste_single_ball_fit"
    assert_output_equals_folder(o, folder)
    assert set(o.tables) == {"fitted", "residuals", "objective"}
    eta = float(o.tables["fitted"]["value"].iloc[0])
    assert abs(eta / 0.7 - 1) < 0.01, eta
    assert o.lines[0].startswith("fit (brent, ")
    assert isinstance(o.warnings, list)
    # The progress callback saw the fit's runs, and ended full.
    assert calls, "no progress reported"
    name, pos, length, unit, _ = calls[-1]
    assert (name, unit) == ("paste_single_ball", "runs")
    assert pos == length and pos > 13, calls[-1]
    # write() writes the command line's folder, byte for byte.
    written = Path(o.write(tmp_path / "lib"))
    assert written == tmp_path / "lib" / "paste_single_ball_fit"
    for f in folder.iterdir():
        assert (written / f.name).read_bytes() == f.read_bytes(), f.name


def test_measurements_as_a_dataframe(tmp_path: Path) -> None:
    m = tmp_path / "rebound.csv"
    REBOUND.to_csv(m, index=False)
    fits = [("contacts.restitution", 0.4, 0.8)]
    p = cli_fit(DROP, DROP_SET, fits, m, tmp_path / "cli")
    assert p.returncode == 0, p.stderr
    o = settle.fit(
        settle.load(DROP),
        fit={"contacts.restitution": (0.4, 0.8)},
        measured=REBOUND,
        overrides=DROP_SET,
        out=tmp_path / "lib",
        progress=False,
    )
    folder = tmp_path / "cli" / "restitution_drop_fit"
    assert_output_equals_folder(o, folder, same_record=False)
    assert 'measured_file = "<measured table>"' in o.files["fit.toml"].decode()
    for stem in o.tables:
        written = tmp_path / "lib" / "restitution_drop_fit" / f"{stem}.csv"
        assert written.read_bytes() == (folder / f"{stem}.csv").read_bytes()


def cli_error(args: List[str]) -> str:
    p = cli(*args)
    assert p.returncode == 2, p.stderr
    return p.stderr.splitlines()[0].removeprefix("error: ")


def test_bad_input_raises_the_command_lines_message(tmp_path: Path) -> None:
    m = tmp_path / "m.csv"
    m.write_text(PASTE_M)
    base = ["fit", os.fspath(PASTE), "--set", ONE_HEIGHT, "--measured", os.fspath(m), "--out", os.fspath(tmp_path / "o")]
    s = settle.load(os.fspath(PASTE)).set("release.fall_heights_m", [0.255])
    # A bound outside the key's range (η_B > 0): the whole message, naming the key.
    with pytest.raises(settle.ScenarioError) as e:
        settle.fit(s, fit={ETA[0]: (-1, 3)}, measured=m, progress=False)
    assert str(e.value) == cli_error(base + ["--fit", f"{ETA[0]}=-1:3"])
    assert e.value.key == ETA[0]
    # A key that is not a real number.
    with pytest.raises(settle.ScenarioError) as e:
        settle.fit(s, fit={"name": (0, 1)}, measured=m, progress=False)
    assert str(e.value) == cli_error(base + ["--fit", "name=0:1"])
    # Reversed bounds: clap words the command line's, the message after it is the same.
    with pytest.raises(settle.ScenarioError) as e:
        settle.fit(s, fit={ETA[0]: (3, 0.1)}, measured=m, progress=False)
    assert e.value.key == "--fit"
    msg = str(e.value).split(": key `--fit`: ")[1]
    assert msg.startswith("bounds 3:0.1 are reversed or empty")
    assert cli_error(base + ["--fit", f"{ETA[0]}=3:0.1"]).endswith(msg)
    # A column the run does not write, found at the first run.
    bad = tmp_path / "bad.csv"
    bad.write_text("file,column,row,value\nsummary.csv,nope_m,0,1\n")
    with pytest.raises(settle.ScenarioError) as e:
        settle.fit(s, fit={ETA[0]: (0.1, 3)}, measured=bad, progress=False)
    args = ["fit", os.fspath(PASTE), "--set", ONE_HEIGHT, "--measured", os.fspath(bad),
            "--out", os.fspath(tmp_path / "o"), "--fit", f"{ETA[0]}=0.1:3"]
    assert str(e.value) == cli_error(args)
    assert "no column `nope_m`" in str(e.value)
    assert not (tmp_path / "o").exists()
    # Not a pair of numbers: a TypeError before anything runs.
    with pytest.raises(TypeError):
        settle.fit(s, fit={ETA[0]: 3}, measured=m)  # type: ignore[dict-item]


def test_slump_equals_settle_fit_slump() -> None:
    r = settle.slump(152, [102, 103, 100], density=1843)
    p = cli("fit", "slump", "--height-mm", "152", "--slump-mm", "102,103,100", "--density", "1843")
    assert p.returncode == 0, p.stderr
    assert r.lines == p.stdout.splitlines()
    assert [round(t, 1) for t in r.yield_stress_pa] == [136.6, 132.7, 144.6]
    assert r.mean_yield_stress_pa == pytest.approx(sum(r.yield_stress_pa) / 3, rel=1e-15)
    assert r.relative_slump[0] == pytest.approx(102 / 152, rel=1e-15)
    one = settle.slump(152, 102, 1843, g=9.81)
    assert one.yield_stress_pa == r.yield_stress_pa[:1]
    with pytest.raises(settle.ScenarioError) as e:
        settle.slump(152, [100, 152], 1843)
    assert str(e.value) == cli_error(
        ["fit", "slump", "--height-mm", "152", "--slump-mm", "100,152", "--density", "1843"]
    )
