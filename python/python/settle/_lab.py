"""settle.reduce, settle.invert, settle.laws: see python/src/lab.rs.

Readings are a readings file (the format of ``settle reduce``, docs/commands/reduce.md) or a
pandas DataFrame of its table (``time_min`` or ``time_s``, ``reading`` (or ``drawn_mass_g``,
``apparent_mass_g``), ``temperature_c`` [, ``blank_reading``]) whose figures, the file's
``# key = value`` lines, are in ``df.attrs["preamble"]`` and/or given as keyword arguments
(``dry_mass_g=50``; a keyword replaces the preamble's line of the same key).
"""

from __future__ import annotations

import math
import numbers
import os
from typing import TYPE_CHECKING, Any, Dict, List, Optional, Sequence, Tuple, Union, cast

from . import _settle
from ._core import Output, PathLike

if TYPE_CHECKING:  # pragma: no cover
    import pandas

#: Readings: a file, or a DataFrame of a readings file's table.
ReadingsLike = Union[PathLike, "pandas.DataFrame"]
#: A figure given as a keyword (``dry_mass_g=50``, ``standard="d422"``).
Figure = Union[float, int, str]

_RawReadings = Union[str, Tuple[str, List[str], List[List[str]], List[Tuple[str, str]]]]


def _text(v: Any) -> str:
    """A cell or figure as the text of a readings file: numbers written to read back to the
    same value, an empty cell for None or NaN."""
    if v is None:
        return ""
    if isinstance(v, str):
        return v
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, numbers.Integral):
        return str(int(v))
    if isinstance(v, numbers.Real):
        x = float(v)
        if math.isnan(x):
            return ""
        return repr(x)
    return str(v)


def _figures(preamble: Sequence[str], figures: Dict[str, Optional[Figure]]) -> List[Tuple[str, str]]:
    """The ``# key = value`` lines of ``preamble`` as (key, value), then ``figures`` (a keyword
    replaces the line of its key; None leaves a figure out)."""
    out: List[Tuple[str, str]] = []
    for line in preamble:
        body = line.strip()
        if not body.startswith("#") or "=" not in body:
            continue
        k, v = body[1:].split("=", 1)
        out.append((k.strip(), v.strip()))
    for k, fig in figures.items():
        out = [(kk, vv) for kk, vv in out if kk != k]
        if fig is not None:
            out.append((k, _text(fig)))
    return out


def _raw(readings: ReadingsLike, name: str, figures: Dict[str, Optional[Figure]]) -> _RawReadings:
    """Readings as the extension takes them: a path, or (name, header, rows, figures)."""
    if isinstance(readings, (str, os.PathLike)):
        if figures:
            raise TypeError(
                f"figures as keywords ({', '.join(figures)}) apply to readings given as a "
                "DataFrame; a readings file gives them as `# key = value` lines"
            )
        return os.fspath(readings)
    if not (hasattr(readings, "columns") and hasattr(readings, "itertuples")):
        raise TypeError(
            "readings are the path of a readings file or a pandas DataFrame of its table, "
            f"not {type(readings).__name__}"
        )
    attrs = getattr(readings, "attrs", {}) or {}
    preamble = attrs.get("preamble", [])
    if isinstance(preamble, str):
        preamble = preamble.splitlines()
    header = [str(c) for c in readings.columns]
    rows = [[_text(v) for v in row] for row in readings.itertuples(index=False, name=None)]
    return (str(attrs.get("name", name)), header, rows, _figures(preamble, figures))


def reduce(
    readings: ReadingsLike,
    *,
    standard: Optional[str] = None,
    hydrometer: Optional[str] = None,
    name: str = "readings",
    out: Optional[PathLike] = None,
    **figures: Optional[Figure],
) -> Output:
    """``settle reduce``: the standard reduction of hydrometer readings (ASTM D422 or D7928),
    or of pipette and buoyancy-sphere readings, in memory.

    ``readings``: a readings file, or a DataFrame of its table with its figures in
    ``df.attrs["preamble"]`` (the file's ``# key = value`` lines) and/or as keywords
    (``dry_mass_g=50, specific_gravity=2.65``). ``standard`` (``d422``, ``d7928``) and
    ``hydrometer`` (``152H``, ``151H``) override the readings' own, as ``--standard`` and
    ``--hydrometer`` do. ``name``: what a DataFrame stands for (``df.attrs["name"]`` if set):
    it names the results (``<name>_reduced``) and the errors. ``out``: also write
    ``out/<stem>_reduced/`` (``--out``).

    Returns an :class:`Output` whose ``tables["percent_finer"]`` is ``percent_finer.csv``.
    Bad input raises :class:`ScenarioError` with the command line's message.
    """
    raw = _raw(readings, name, figures)
    return Output(
        _settle.reduce(
            raw, standard, hydrometer, None if out is None else os.fspath(out)
        )
    )


def _bounds(bounds: Union[bool, float]) -> Optional[float]:
    """``bounds=`` of :func:`invert` as ``--bounds[=P]`` takes it: None (off), 0.95 or P."""
    if isinstance(bounds, bool):
        return 0.95 if bounds else None
    return float(bounds)


def invert(
    readings: Union[ReadingsLike, Sequence[ReadingsLike]],
    *,
    model: str = "ideal-stokes",
    bins: Optional[int] = None,
    diameters_um: Union[str, Tuple[float, float], None] = None,
    lambda_: Union[str, float] = "discrepancy",
    resolution: Union[float, Sequence[float], None] = None,
    repeats: int = 100,
    seed: int = 1,
    bounds: Union[bool, float] = False,
    out: Optional[PathLike] = None,
) -> Output:
    """``settle invert``: the grain-size distribution that explains one or several
    instruments' readings of the same soil, in memory.

    ``readings``: one readings file or DataFrame (as :func:`reduce` takes them, figures in
    ``df.attrs["preamble"]``), or a list of them. The options are the command line's, with its
    defaults: ``model`` (``ideal-stokes``, ``full``), ``bins`` (2–200; default twice the
    readings, 8–30), ``diameters_um`` (``"LO:HI"`` or ``(lo, hi)``, µm), ``lambda_``
    (``--lambda``: ``discrepancy``, ``gcv`` or a number ≥ 0), ``resolution`` (one for every
    file or one per file), ``repeats``, ``seed``, ``bounds`` (``--bounds[=P]``: ``True`` for
    the strict bounds at confidence 0.95, a number 0 < P < 1 for another). ``out``: also write
    ``out/<stem>_inverted/``.

    Returns an :class:`Output` with the tables ``inverted``, ``misfit`` and ``standard``.
    Bad input raises :class:`ScenarioError` naming the option or file.
    """
    items: List[ReadingsLike]
    if isinstance(readings, (str, os.PathLike)) or hasattr(readings, "columns"):
        items = [cast(ReadingsLike, readings)]
    else:
        items = list(readings)
    raw = [
        _raw(r, "readings" if k == 0 else f"readings_{k + 1}", {}) for k, r in enumerate(items)
    ]
    if isinstance(diameters_um, tuple):
        lo, hi = diameters_um
        diameters_um = f"{_text(lo)}:{_text(hi)}"
    if resolution is None:
        res: List[float] = []
    elif isinstance(resolution, (int, float, numbers.Real)):
        res = [float(resolution)]
    else:
        res = [float(x) for x in resolution]
    return Output(
        _settle.invert(
            raw,
            model=model,
            bins=bins,
            diameters_um=diameters_um,
            lambda_=_text(lambda_),
            resolution=res,
            repeats=repeats,
            seed=seed,
            bounds=_bounds(bounds),
            out=None if out is None else os.fspath(out),
        )
    )


def laws(
    spheres: Optional[PathLike] = None,
    fluids: Optional[PathLike] = None,
    *,
    out: Optional[PathLike] = None,
) -> Output:
    """``settle laws``: every drag law of a yield-stress fluid on spheres with measured
    terminal velocities, in memory.

    By default the built-in spheres of Valentik & Whitmore (1965); else ``spheres`` (a spheres
    CSV) and ``fluids`` (its fluids CSV), both. ``out``: also write ``out/laws/``.

    Returns an :class:`Output` with the tables ``laws`` and ``predictions``.
    """
    return Output(
        _settle.laws(
            None if spheres is None else os.fspath(spheres),
            None if fluids is None else os.fspath(fluids),
            out=None if out is None else os.fspath(out),
        )
    )
