"""What every test of the package compares: a DataFrame of settle against pandas.read_csv of
the command line's file, to the last digit, with the dtypes read_csv gives (numeric columns
float64 here, true/false columns bool, text as read_csv infers it)."""

from __future__ import annotations

import pandas as pd

# pandas < 3 reads floats to the last digit only with float_precision="round_trip" (pandas 3
# does by default and deprecates the argument).
READ_CSV = {"float_precision": "round_trip"} if int(pd.__version__.split(".")[0]) < 3 else {}


def assert_frame_is_read_csv(got: pd.DataFrame, expected: pd.DataFrame, stem: str) -> None:
    """`got` equals `expected` (read_csv of the file `stem`) cell for cell and column for column."""
    assert list(got.columns) == list(expected.columns), stem
    # numbers to the last digit; integer columns of read_csv are float64 here
    pd.testing.assert_frame_equal(got, expected, check_dtype=False, check_exact=True)
    for name in got.columns:
        if pd.api.types.is_bool_dtype(expected[name]):
            assert got[name].dtype == bool, (stem, name)
        elif pd.api.types.is_numeric_dtype(expected[name]):
            assert got[name].dtype == "float64", (stem, name)
        else:
            assert got[name].dtype == expected[name].dtype, (stem, name)
