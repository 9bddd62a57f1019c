"""`settle reduce` writes the reduced curve in the laboratory's formats (issue 26, item 4):
`percent_finer.ags`, an AGS4 file that the `python-ags4` validator (PyPI) passes with no rule
broken, whose GRAT rows are the curve of `percent_finer.csv`; and `percent_finer.xlsx`, which
reads back (pandas + openpyxl) equal to `percent_finer.csv`, cell for cell."""

from __future__ import annotations

import os
import subprocess
from pathlib import Path

import pandas as pd
import pytest
from python_ags4 import AGS4

from frames import READ_CSV

ROOT = Path(__file__).resolve().parents[2]
BINARY = Path(os.environ.get("SETTLE_BIN", ROOT / "target" / "release" / "settle"))
READINGS = [
    ROOT / "data" / "lab" / "soiltestr_protocol8_d7928.csv",
    ROOT / "data" / "lab" / "envalysis_clayloam_d422.csv",
    ROOT / "data" / "invert" / "sample2_full" / "readings_pipette.csv",
    ROOT / "data" / "invert" / "sample2_full" / "readings_sphere.csv",
]
# What check_file reports besides the rules broken.
NOT_ERRORS = {"Summary of data", "Metadata"}


def reduce(readings: Path, out: Path) -> Path:
    """Runs `settle reduce READINGS --out OUT`; returns the results folder."""
    if not BINARY.exists():
        pytest.fail(f"{BINARY} is missing: build it with `cargo build --release`")
    p = subprocess.run(
        [str(BINARY), "reduce", str(readings), "--out", str(out)], capture_output=True, text=True
    )
    assert p.returncode == 0, p.stderr
    return out / f"{readings.stem}_reduced"


@pytest.mark.parametrize("readings", READINGS, ids=lambda p: p.stem)
def test_ags_passes_the_validator_and_holds_the_curve(readings: Path, tmp_path: Path) -> None:
    res = reduce(readings, tmp_path)
    ags = res / "percent_finer.ags"
    errors = AGS4.check_file(str(ags), standard_AGS4_dictionary="4.1.1")
    broken = {k: v for k, v in errors.items() if k not in NOT_ERRORS}
    assert broken == {}, broken
    tables, _ = AGS4.AGS4_to_dataframe(str(ags))
    assert {"PROJ", "TRAN", "UNIT", "TYPE", "ABBR", "LOCA", "SAMP", "GRAG", "GRAT"} <= set(tables)
    grat = tables["GRAT"]
    grat = grat[grat["HEADING"] == "DATA"]
    csv = pd.read_csv(res / "percent_finer.csv", **READ_CSV)
    assert len(grat) == len(csv)
    size_mm = grat["GRAT_SIZE"].astype(float).to_numpy()
    finer = grat["GRAT_PERP"].astype(float).to_numpy()
    # GRAT_SIZE to 3 significant figures (or more, to keep the sizes apart), GRAT_PERP to 0.1 %.
    assert abs(size_mm / (csv["diameter_m"].to_numpy() * 1e3) - 1).max() <= 5e-3
    assert abs(finer - csv["percent_finer"].to_numpy()).max() <= 0.05 + 1e-9
    assert set(grat["GRAT_TYPE"]) <= {"HYD", "PIP", "BSPH"}


@pytest.mark.parametrize("readings", READINGS, ids=lambda p: p.stem)
def test_xlsx_reads_back_as_the_csv(readings: Path, tmp_path: Path) -> None:
    res = reduce(readings, tmp_path)
    csv = pd.read_csv(res / "percent_finer.csv", **READ_CSV)
    xlsx = pd.read_excel(res / "percent_finer.xlsx", sheet_name="percent_finer", engine="openpyxl")
    assert list(xlsx.columns) == list(csv.columns)
    pd.testing.assert_frame_equal(xlsx, csv, check_dtype=False, check_exact=True)


def test_a_broken_ags_file_is_caught(tmp_path: Path) -> None:
    """The check can fail: the same file with a GRAT row's size off its 3SF type and a
    heading renamed breaks rules 8 and 9."""
    res = reduce(READINGS[0], tmp_path)
    text = (res / "percent_finer.ags").read_bytes().decode("ascii")
    bad = text.replace('"GRAT_PERP"', '"GRAT_PERC"', 1)
    lines = bad.split("\r\n")
    i = next(k for k, l in enumerate(lines) if l.startswith('"DATA"') and '"HYD"' in l)
    fields = lines[i].split('","')
    fields[8] = fields[8] + "123"
    lines[i] = '","'.join(fields)
    broken = tmp_path / "broken.ags"
    broken.write_text("\r\n".join(lines), newline="")
    errors = AGS4.check_file(str(broken), standard_AGS4_dictionary="4.1.1")
    assert {"AGS Format Rule 8", "AGS Format Rule 9"} <= set(errors), errors.keys()
