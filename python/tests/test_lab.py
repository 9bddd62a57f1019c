"""settle.reduce, settle.invert and settle.laws against `settle reduce`, `settle invert` and
`settle laws`: the same tables (each DataFrame equals pandas.read_csv of the command line's
file, the CSV bytes are the file's), the same files written, the same error messages; readings
from a file or from a DataFrame."""

from __future__ import annotations

import itertools
import os
import subprocess
from pathlib import Path
from typing import List

import pandas as pd
import pytest

import settle
from frames import READ_CSV, assert_frame_is_read_csv

ROOT = Path(__file__).resolve().parents[2]
LAB = ROOT / "data" / "lab"
SAMPLE2 = [
    ROOT / "data" / "invert" / "sample2_full" / f
    for f in ("readings.csv", "readings_d7928.csv", "readings_pipette.csv", "readings_sphere.csv")
]
BINARY = Path(os.environ.get("SETTLE_BIN", ROOT / "target" / "release" / "settle"))


def cli(*args: str, cwd: Path | None = None, check: bool = True) -> subprocess.CompletedProcess:
    """Runs the settle binary; fails the test when it exits non-zero and `check`."""
    if not BINARY.exists():
        pytest.fail(f"{BINARY} is missing: build it with `cargo build --release`")
    p = subprocess.run([str(BINARY), *args], capture_output=True, text=True, cwd=cwd)
    if check:
        assert p.returncode == 0, p.stderr
    return p


def cli_error(*args: str, cwd: Path | None = None) -> str:
    """The message of a command line refused as bad input (exit 2), without `error: `."""
    p = cli(*args, cwd=cwd, check=False)
    assert p.returncode == 2, (p.returncode, p.stdout, p.stderr)
    err = p.stderr.strip()
    assert err.startswith("error: "), err
    return err[len("error: "):]


def files(folder: Path) -> List[str]:
    """The files of a results folder (settle's marker left out), relative, sorted."""
    return sorted(
        p.relative_to(folder).as_posix()
        for p in folder.rglob("*")
        if p.is_file() and not p.name.startswith(".settle")
    )


def without_wall_time(b: bytes) -> List[str]:
    """The lines of a text file but its wall time; a binary file (the .xlsx) as its bytes."""
    try:
        text = b.decode()
    except UnicodeDecodeError:
        return [b.hex()]
    return [line for line in text.splitlines() if not line.startswith("wall_time_s")]


def assert_same_as_folder(r: settle.Output, folder: Path) -> None:
    """Every CSV file of `folder` is a table of `r` (the same bytes; the DataFrame equal to
    pandas.read_csv of it) and `r` has no other; every other file the same bytes (wall times
    aside)."""
    names = files(folder)
    csvs = {n[: -len(".csv")]: folder / n for n in names if n.endswith(".csv")}
    assert csvs, folder
    assert sorted(r.tables) == sorted(csvs)
    for stem, path in csvs.items():
        assert r.csv(stem) == path.read_bytes(), stem
        got = r.tables[stem]
        lines = path.read_text().splitlines()
        preamble = list(itertools.takewhile(lambda line: line.startswith("#"), lines))
        expected = pd.read_csv(path, skiprows=len(preamble), **READ_CSV)
        assert_frame_is_read_csv(got, expected, stem)
    others = [n for n in names if not n.endswith(".csv")]
    assert sorted(r.files) == others
    for n in others:
        assert without_wall_time(r.files[n]) == without_wall_time((folder / n).read_bytes()), n


def assert_writes_the_same(r: settle.Output, cli_folder: Path, tmp: Path) -> None:
    """`r.write(tmp)` writes the folder the command line wrote: the same files, the same bytes
    (wall times aside)."""
    written = Path(r.write(tmp))
    assert written == tmp / cli_folder.name
    assert files(written) == files(cli_folder)
    for n in files(written):
        assert without_wall_time((written / n).read_bytes()) == without_wall_time(
            (cli_folder / n).read_bytes()
        ), n


def readings_frame(path: Path, drop: tuple = ()) -> pd.DataFrame:
    """A readings file as a DataFrame: its table, its `#` lines in attrs["preamble"] (those of
    the keys `drop` left out)."""
    lines = path.read_text().splitlines()
    preamble = [
        line
        for line in itertools.takewhile(lambda line: line.startswith("#"), lines)
        if line[1:].split("=", 1)[0].strip() not in drop
    ]
    df = pd.read_csv(path, comment="#", **READ_CSV)
    df.attrs["preamble"] = preamble
    return df


# --- reduce ---------------------------------------------------------------------------------


def test_reduce_of_a_file_equals_settle_reduce(tmp_path: Path) -> None:
    f = LAB / "soiltestr_protocol8_d7928.csv"
    cli("reduce", str(f), "--standard", "d7928", "--out", str(tmp_path / "cli"))
    folder = tmp_path / "cli" / "soiltestr_protocol8_d7928_reduced"
    r = settle.reduce(f, standard="d7928")
    assert r.name == "soiltestr_protocol8_d7928_reduced"
    assert_same_as_folder(r, folder)
    assert_writes_the_same(r, folder, tmp_path / "lib")
    assert r.lines[0].startswith(f"{f} (ASTM D7928, 152H,")


def test_reduce_of_a_dataframe_equals_settle_reduce(tmp_path: Path) -> None:
    f = LAB / "envalysis_clayloam_d422.csv"
    cli("reduce", str(f), "--out", str(tmp_path / "cli"))
    folder = tmp_path / "cli" / "envalysis_clayloam_d422_reduced"
    df = readings_frame(f)
    r = settle.reduce(df, name="envalysis_clayloam_d422")
    assert r.name == "envalysis_clayloam_d422_reduced"
    for stem in ("percent_finer",):
        assert r.csv(stem) == (folder / f"{stem}.csv").read_bytes()
    assert r.files["percent_finer.svg"] == (folder / "percent_finer.svg").read_bytes()
    # the figures as keywords instead of the preamble's lines: the same table
    k = settle.reduce(
        readings_frame(f, drop=("dry_mass_g", "specific_gravity")),
        name="envalysis_clayloam_d422",
        dry_mass_g=50,
        specific_gravity=2.65,
    )
    assert k.csv("percent_finer") == (folder / "percent_finer.csv").read_bytes()
    pd.testing.assert_frame_equal(k.tables["percent_finer"], r.tables["percent_finer"])
    # a keyword replaces the preamble's line: another dry mass, another percent finer
    m = settle.reduce(df, name="envalysis_clayloam_d422", dry_mass_g=40)
    ratio = m.tables["percent_finer"]["percent_finer"] / r.tables["percent_finer"]["percent_finer"]
    assert ratio.round(12).eq(1.25).all()
    written = Path(r.write(tmp_path / "lib"))
    assert (written / "percent_finer.csv").read_bytes() == (folder / "percent_finer.csv").read_bytes()


def test_reduce_missing_figure_is_the_command_lines_error(tmp_path: Path) -> None:
    f = LAB / "envalysis_clayloam_d422.csv"
    text = "\n".join(
        line for line in f.read_text().splitlines() if not line.startswith("# dry_mass_g")
    )
    (tmp_path / "readings.csv").write_text(text + "\n")
    msg = cli_error("reduce", "readings.csv", cwd=tmp_path)
    assert "dry_mass_g" in msg
    with pytest.raises(settle.ScenarioError) as e:
        settle.reduce(readings_frame(f, drop=("dry_mass_g",)), name="readings.csv")
    assert str(e.value) == msg
    assert e.value.key == "dry_mass_g"
    # the file itself, through settle.reduce: the same message
    msg = cli_error("reduce", str(tmp_path / "readings.csv"))
    with pytest.raises(settle.ScenarioError) as e:
        settle.reduce(tmp_path / "readings.csv")
    assert str(e.value) == msg


def test_reduce_unknown_standard_is_the_command_lines_error() -> None:
    f = LAB / "envalysis_clayloam_d422.csv"
    msg = cli_error("reduce", str(f), "--standard", "d999")
    with pytest.raises(settle.ScenarioError) as e:
        settle.reduce(f, standard="d999")
    assert str(e.value) == msg
    assert e.value.key == "standard"
    assert "allowed: d422, d7928" in msg


def test_reduce_refuses_figure_keywords_with_a_file() -> None:
    with pytest.raises(TypeError, match="DataFrame"):
        settle.reduce(LAB / "envalysis_clayloam_d422.csv", dry_mass_g=50)


# --- invert ---------------------------------------------------------------------------------


def test_invert_equals_settle_invert(tmp_path: Path) -> None:
    cli("invert", *map(str, SAMPLE2), "--model", "full", "--out", str(tmp_path / "cli"))
    folder = tmp_path / "cli" / "readings_inverted"
    r = settle.invert(SAMPLE2, model="full")
    assert r.name == "readings_inverted"
    assert_same_as_folder(r, folder)
    assert_writes_the_same(r, folder, tmp_path / "lib")
    assert sorted(r.tables) == ["inverted", "misfit", "standard"]


def test_invert_of_a_dataframe_equals_settle_invert(tmp_path: Path) -> None:
    f = LAB / "envalysis_clayloam_d422.csv"
    cli("invert", str(f), "--bounds", "--repeats", "20", "--out", str(tmp_path / "cli"))
    folder = tmp_path / "cli" / "envalysis_clayloam_d422_inverted"
    df = readings_frame(f)
    df.attrs["name"] = str(f)  # what misfit.csv and standard.csv name
    r = settle.invert(df, bounds=True, repeats=20)
    assert_same_as_folder(r, folder)


def test_invert_bounds_at_a_confidence_equals_settle_invert(tmp_path: Path) -> None:
    f = LAB / "envalysis_clayloam_d422.csv"
    cli("invert", str(f), "--bounds=0.99", "--repeats", "0", "--out", str(tmp_path / "cli"))
    folder = tmp_path / "cli" / "envalysis_clayloam_d422_inverted"
    r = settle.invert(f, bounds=0.99, repeats=0)
    assert_same_as_folder(r, folder)
    assert "bounds_confidence = 0.99" in (folder / "invert.toml").read_text()
    msg = cli_error("invert", str(f), "--bounds=1.5")
    with pytest.raises(settle.ScenarioError) as e:
        settle.invert(f, bounds=1.5)
    assert str(e.value) == msg
    assert e.value.key == "--bounds"


def test_invert_bad_option_is_the_command_lines_error() -> None:
    f = LAB / "envalysis_clayloam_d422.csv"
    for option, value, kw in [
        ("--model", "hindered", {"model": "hindered"}),
        ("--lambda", "-1", {"lambda_": -1}),
        ("--bins", "1", {"bins": 1}),
        ("--diameters-um", "75:2", {"diameters_um": (75, 2)}),
    ]:
        msg = cli_error("invert", str(f), option, value)
        with pytest.raises(settle.ScenarioError) as e:
            settle.invert(f, **kw)  # type: ignore[arg-type]
        assert str(e.value) == msg, option
        assert e.value.key == option


# --- laws -----------------------------------------------------------------------------------


def test_laws_equals_settle_laws(tmp_path: Path) -> None:
    cli("laws", "--out", str(tmp_path / "cli"))
    folder = tmp_path / "cli" / "laws"
    r = settle.laws()
    assert r.name == "laws"
    assert_same_as_folder(r, folder)
    assert_writes_the_same(r, folder, tmp_path / "lib")
    assert r.lines[0].startswith("settle laws: 121 spheres")
    # out=: written as the command line writes it
    o = settle.laws(out=tmp_path / "out")
    assert files(tmp_path / "out" / "laws") == files(folder)
    assert o.lines[-1] == f"-> {tmp_path / 'out' / 'laws'}"


def test_laws_spheres_without_fluids_is_refused() -> None:
    spheres = ROOT / "data" / "valentik_whitmore_1965_spheres.csv"
    with pytest.raises(settle.ScenarioError) as e:
        settle.laws(spheres)
    assert e.value.key == "--fluids"
    # both files: the built-in spheres' tables
    r = settle.laws(spheres, ROOT / "data" / "valentik_whitmore_1965_suspensions.csv")
    assert r.csv("laws") == settle.laws().csv("laws")


# --- lab files as labs keep them (issue 26) -------------------------------------------------

LAB_FORMATS = ROOT / "tests" / "data" / "lab"


def test_reduce_reads_xlsx_ods_and_latin1_csv_as_the_utf8_csv() -> None:
    """The same readings sheet as UTF-8 CSV, Latin-1 semicolon CSV with decimal commas, .xlsx
    and .ods: identical DataFrames, and the record says how each was read."""
    base = settle.reduce(LAB_FORMATS / "utf8" / "soil_b3.csv")
    frame = base.tables["percent_finer"]
    assert len(frame) == 8
    for path, said in [
        (LAB_FORMATS / "latin1" / "soil_b3.csv", 'encoding = "Windows-1252"'),
        (LAB_FORMATS / "xlsx" / "soil_b3.xlsx", 'format = "excel"'),
        (LAB_FORMATS / "kv" / "soil_b3.xlsx", 'sheet = "Sheet1"'),
        (LAB_FORMATS / "ods" / "soil_b3.ods", 'format = "ods"'),
    ]:
        r = settle.reduce(path)
        pd.testing.assert_frame_equal(r.tables["percent_finer"], frame)
        assert r.csv("percent_finer") == base.csv("percent_finer")
        record = r.files["reduce.toml"].decode()
        assert said in record.split("[input]")[1], record
        assert r.lines[1].startswith("  read as: "), r.lines


def test_reduce_refuses_minutes_under_time_s_with_the_fix(tmp_path: Path) -> None:
    f = tmp_path / "m.csv"
    f.write_text((LAB_FORMATS / "utf8" / "soil_b3.csv").read_text().replace("time_min,", "time_s,"))
    msg = cli_error("reduce", str(f), "--out", str(tmp_path / "out"))
    with pytest.raises(settle.ScenarioError) as e:
        settle.reduce(f)
    assert str(e.value) == msg
    assert "look like minutes" in msg and "time_min" in msg
    assert not (tmp_path / "out").exists()
