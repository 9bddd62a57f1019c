"""settle.fit and settle.slump: the calibration of ``settle fit`` and its slump calculator
(python/src/fit.rs)."""

from __future__ import annotations

import os
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, List, Mapping, Optional, Sequence, Tuple, Union

from . import _progress, _settle
from ._core import Output, Overrides, PathLike, Scenario, _scenario

if TYPE_CHECKING:  # pragma: no cover
    import pandas

#: The name an in-memory table of measurements goes by in error messages and ``fit.toml``.
MEASURED_TABLE = "<measured table>"


def _bounds(fit: Mapping[str, Tuple[float, float]]) -> List[Tuple[str, float, float]]:
    if not isinstance(fit, Mapping) or not fit:
        raise TypeError("fit: a dict {key: (lo, hi)} of one or more scenario keys to fit")
    out = []
    for key, pair in fit.items():
        try:
            lo, hi = pair
            out.append((str(key), float(lo), float(hi)))
        except (TypeError, ValueError):
            raise TypeError(f"fit[{key!r}]: bounds are a pair of numbers (lo, hi), not {pair!r}") from None
    return out


def fit(
    scenario: Union[Scenario, PathLike],
    fit: Mapping[str, Tuple[float, float]],
    measured: Union[PathLike, "pandas.DataFrame"],
    *,
    overrides: Overrides = None,
    out: Optional[PathLike] = None,
    progress: _progress.Progress = None,
) -> Output:
    """Fits scenario keys to measurements, as ``settle fit`` does, in memory with the GIL
    released.

    ``scenario``: a :class:`Scenario` or the path of a scenario file. ``fit``: ``{key: (lo,
    hi)}``, each a real-valued scenario key and its bounds (``--fit KEY=LO:HI``; Brent's method
    for one key, Nelder-Mead for several). ``measured``: the measurements file (M.csv) or a
    DataFrame with its columns ``file, column, row, value [, sigma]`` (an empty sigma is
    σ = 1). ``overrides``: ``{key: value}`` or ``["KEY=VALUE"]`` applied to every run
    (``--set``). ``out``: also write ``out/<name>_fit/`` (``--out``). ``progress``: a bar of
    the runs (see :func:`settle.run`).

    Returns an :class:`Output` whose ``tables`` are the CSV files ``settle fit`` writes
    (``fitted``, ``residuals``, for one key ``objective``), whose ``files`` are its chart
    and ``fit.toml``, and whose ``lines`` are what it prints. Bad input (a key that is not a
    real number, a bound outside the key's range, a measurement the run does not write, a best
    value on a bound, ...) raises :class:`ScenarioError` with the command line's message.
    """
    s = _scenario(scenario, overrides)
    bounds = _bounds(fit)
    path: Optional[str] = None
    table: Optional[Tuple[str, str]] = None
    if isinstance(measured, (str, os.PathLike)):
        path = os.fspath(measured)
    elif hasattr(measured, "to_csv"):
        table = (MEASURED_TABLE, measured.to_csv(index=False))
    else:
        raise TypeError(
            f"measured: the path of a measurements file or a DataFrame, not {type(measured).__name__}"
        )
    with _progress.bar(progress) as cb:
        o = Output(_settle.fit(s._inner, bounds, path, table, progress=cb))
    if out is not None:
        o.write(out)
    return o


@dataclass(frozen=True)
class Slump:
    """The yield stresses of slump tests of one paste (``settle fit slump``; f-EDEM Appendix I,
    eqs. A1-A3, Pashias & Boger 1996)."""

    #: The mould's height H, mm.
    height_mm: float
    #: The paste's density, kg/m³.
    density_kg_m3: float
    #: The gravitational acceleration, m/s².
    g_m_s2: float
    #: Each slump S, mm, in the order given.
    slump_mm: List[float]
    #: S' = S/H of each slump (eq. A2).
    relative_slump: List[float]
    #: τ_y of each slump, Pa.
    yield_stress_pa: List[float]
    #: Their mean, Pa.
    mean_yield_stress_pa: float
    #: The lines ``settle fit slump`` prints.
    lines: List[str]


def slump(
    height_mm: float,
    slump_mm: Union[float, Sequence[float]],
    density: float,
    g: float = 9.81,
) -> Slump:
    """The yield stress of a paste from cylinder slump tests, as ``settle fit slump
    --height-mm H --slump-mm S1,S2,... --density RHO [--g G]`` computes it: a mould
    ``height_mm`` high, the slump(s) ``slump_mm`` (0 < S < H), the paste's ``density``
    (kg/m³). A slump out of range raises :class:`ScenarioError` with the command line's
    message."""
    slumps = [float(slump_mm)] if isinstance(slump_mm, (int, float)) else [float(x) for x in slump_mm]
    d: Any = _settle.slump(float(height_mm), slumps, float(density), float(g))
    return Slump(**d)
