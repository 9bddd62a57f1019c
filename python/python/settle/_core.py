"""The core of the package: scenarios, runs, results and the tables of any command (the
extension settle._settle wrapped for Python users)."""

from __future__ import annotations

import os
import sys
from typing import TYPE_CHECKING, Any, Dict, List, Mapping, Optional, Sequence, Union

from . import _progress, _settle
from ._settle import ScenarioError, UnstableError

if TYPE_CHECKING:  # pragma: no cover
    import pandas

PathLike = Union[str, "os.PathLike[str]"]


def _toml_text(value: Any) -> str:
    """The TOML text of a Python value (number, str, bool, list, dict) as ``--set`` reads it."""
    return _settle.toml_text(value)


class Scenario:
    """A scenario ready to run: read, its overrides applied, validated, its input files read.

    Every bad input raises :class:`ScenarioError` when the scenario is made, with the message
    of ``settle run``. Scenarios are immutable: :meth:`set` returns a new one.
    """

    __slots__ = ("_inner",)

    def __init__(self, inner: _settle.Scenario) -> None:
        if not isinstance(inner, _settle.Scenario):
            raise TypeError(
                "make a Scenario with settle.load(path), Scenario.from_toml(text) "
                "or Scenario.from_dict(d)"
            )
        self._inner = inner

    @classmethod
    def load(cls, path: PathLike) -> "Scenario":
        """Reads the scenario file ``path`` (or a run record ``OUT/NAME/run.toml``)."""
        return cls(_settle.Scenario.load(os.fspath(path)))

    @classmethod
    def from_toml(cls, text: str, origin: Optional[PathLike] = None) -> "Scenario":
        """A scenario from the text of a scenario file. Errors name ``origin`` (default
        ``<scenario text>``); relative input files are found from its folder (default: the
        current folder)."""
        return cls(
            _settle.Scenario.from_toml(text, None if origin is None else os.fspath(origin))
        )

    @classmethod
    def from_dict(cls, d: Mapping[str, Any]) -> "Scenario":
        """A scenario from a dict of the tables and keys of a scenario file (``None`` values
        are left out)."""
        return cls(_settle.Scenario.from_dict(dict(d)))

    def set(self, key: str, value: Any) -> "Scenario":
        """A new scenario with ``key = value`` applied exactly as ``settle run --set KEY=VALUE``
        applies it (same keys, same validation). ``value``: a number, str, bool, list or dict,
        written as TOML."""
        return Scenario(self._inner.set(key, _toml_text(value)))

    def with_dt(self, dt_s: float) -> "Scenario":
        """A new scenario with the time step ``dt_s``, s (as ``settle run --dt``)."""
        return Scenario(self._inner.with_dt(float(dt_s)))

    def to_toml(self) -> str:
        """The effective scenario (overrides applied, defaults filled in, input files as
        absolute paths) as the text of a scenario file."""
        return self._inner.to_toml()

    def to_dict(self) -> Dict[str, Any]:
        """The effective scenario as a dict (:meth:`to_toml` parsed)."""
        return _toml_loads(self.to_toml())

    def run(self, **kwargs: Any) -> "Result":
        """Runs the scenario (:func:`settle.run`)."""
        return run(self, **kwargs)

    @property
    def name(self) -> str:
        """The scenario's name (its output folder is ``OUT/<name>/``)."""
        return self._inner.name

    @property
    def kind(self) -> str:
        """The scenario's kind as written in scenario files (``free_settling``, ...)."""
        return self._inner.kind

    @property
    def path(self) -> str:
        """The file the scenario came from (``<scenario text>`` for text)."""
        return os.fspath(self._inner.path)

    @property
    def overrides(self) -> List[str]:
        """The overrides applied, in order, as ``KEY=VALUE``."""
        return self._inner.overrides

    @property
    def dt_s(self) -> float:
        """The time step, s."""
        return self._inner.dt_s

    def __repr__(self) -> str:
        return f"<settle.Scenario {self.name!r} kind={self.kind!r} from {self.path!r}>"

    def __reduce__(self) -> Any:
        """Pickles as the effective scenario (:meth:`to_toml`) and its path: unpickled, it runs
        as this one does (its overrides applied, not listed); its input files are read again
        where it is unpickled, from their absolute paths."""
        return (_scenario_from_toml, (self.to_toml(), self.path))


def _scenario_from_toml(text: str, origin: str) -> Scenario:
    """The scenario of a pickle (:meth:`Scenario.__reduce__`)."""
    return Scenario.from_toml(text, origin)


def _toml_loads(text: str) -> Dict[str, Any]:
    if sys.version_info >= (3, 11):
        import tomllib
    else:  # pragma: no cover
        import tomli as tomllib
    return tomllib.loads(text)


# The cells pandas.read_csv reads as booleans by default.
_BOOLS: Dict[Optional[str], Optional[bool]] = {
    "true": True, "True": True, "TRUE": True,
    "false": False, "False": False, "FALSE": False,
    None: None,
}


def _frame(header: List[str], columns: List[Any], preamble: List[str]) -> "pandas.DataFrame":
    """A DataFrame of a table: numeric columns float64, true/false columns bool, other text
    columns as pandas infers them from str cells (empty cells NaN), as ``pandas.read_csv`` of
    the file reads them. The comment lines before the header (``# instrument = pipette``), if
    any, are in ``df.attrs["preamble"]``."""
    import numpy as np
    import pandas as pd

    data: Dict[str, Any] = {}
    for name, col in zip(header, columns):
        if isinstance(col, (bytes, bytearray)):
            # a writable view of the bytearray the extension filled: no copy
            data[name] = np.frombuffer(col, dtype=np.float64)
        elif col and _BOOLS.keys() >= set(col) and not all(c is None for c in col):
            # true/false cells: bool, as read_csv reads them (object with NaN when some are empty)
            if None in col:
                data[name] = [np.nan if c is None else _BOOLS[c] for c in col]
            else:
                data[name] = np.array([_BOOLS[c] for c in col], dtype=bool)
        elif None in col:
            data[name] = [np.nan if c is None else c for c in col]
        else:
            data[name] = col
    # copy=False: the numeric columns stay the arrays above (one copy of the numbers in Python)
    df = pd.DataFrame(data, columns=header, copy=False)
    if preamble:
        df.attrs["preamble"] = list(preamble)
    return df


class _Tables:
    """What a run and a command have in common: tables as DataFrames, CSV bytes, charts."""

    __slots__ = ("_inner", "_tables")

    _inner: Union[_settle.RunResult, _settle.Output]

    def __init__(self, inner: Union[_settle.RunResult, _settle.Output]) -> None:
        self._inner = inner
        self._tables: Optional[Dict[str, "pandas.DataFrame"]] = None

    @property
    def tables(self) -> Dict[str, "pandas.DataFrame"]:
        """Every table, keyed by the stem of its CSV file (``summary``, ``timeseries``,
        ``pictures/t_10s``): equal, cell for cell, to ``pandas.read_csv`` of the file the
        command line writes (numeric columns float64, true/false columns bool; the comment
        lines a readings file has before its header in ``df.attrs["preamble"]``)."""
        if self._tables is None:
            self._tables = {
                stem: _frame(header, cols, pre) for stem, header, cols, pre in self._inner.raw_tables()
            }
        return self._tables

    def csv(self, name: str) -> bytes:
        """The bytes of the CSV file ``name`` (stem or file name) as the command line writes it."""
        b = self._inner.csv(name)
        if b is None:
            raise KeyError(name)
        return b

    @property
    def charts(self) -> List[str]:
        """The charts :meth:`plot` can draw (file names: ``velocity.svg``, ...), in the order
        they were made."""
        return self._inner.figure_names()

    @property
    def warnings(self) -> List[str]:
        """The validity warnings (a law used outside its range, ...)."""
        return self._inner.warnings

    @property
    def lines(self) -> List[str]:
        """The lines the command line prints."""
        return self._inner.lines

    def _plot(self, name: str) -> Any:
        data = self._inner.figure(name)
        if data is None:
            raise KeyError(f"no chart {name!r}: the charts with data are {self.charts}")
        from ._plot import figure

        return figure(data)


class Result(_Tables):
    """The outcome of a run, in memory: its tables, warnings, record and status; ``write``
    writes the files ``settle run`` writes."""

    __slots__ = ("_record",)

    _inner: _settle.RunResult

    def __init__(self, inner: _settle.RunResult) -> None:
        super().__init__(inner)
        self._record: Optional[Dict[str, Any]] = None

    @property
    def status(self) -> str:
        """``complete`` or ``interrupted``, as ``run.toml`` says."""
        return self._inner.status

    @property
    def record(self) -> Dict[str, Any]:
        """What ``run.toml`` holds (the run's record and its effective scenario), as a dict."""
        if self._record is None:
            self._record = _toml_loads(self._inner.record)
        return self._record

    @property
    def record_toml(self) -> str:
        """The text of ``run.toml``."""
        return self._inner.record

    @property
    def scenario(self) -> Scenario:
        """The scenario that ran."""
        return Scenario(self._inner.scenario)

    @property
    def wall_time_s(self) -> float:
        """Wall time of the run, s."""
        return self._inner.wall_time_s

    @property
    def steps(self) -> int:
        """Total steps over all worlds."""
        return self._inner.steps

    @property
    def main_chart(self) -> str:
        """The file name of the kind's main chart (``velocity.svg``, ``granulometry.svg``, ...)."""
        return self._inner.main_chart

    def plot(self, name: Optional[str] = None) -> Any:
        """The chart ``name`` (a file name or stem of :attr:`charts`; default the kind's main
        chart) as a ``matplotlib.figure.Figure``: the data of the SVG file ``settle run``
        writes, drawn with matplotlib (an optional dependency)."""
        return self._plot(name or self.main_chart)

    def write(self, folder: PathLike) -> str:
        """Writes the run's files to ``folder/<name>/`` as ``settle run --out folder`` does
        (byte for byte except wall times); returns that folder. Refused (ScenarioError) when
        it exists and was not made by settle; nothing is ever half-written."""
        return os.fspath(self._inner.write(os.fspath(folder)))

    def __repr__(self) -> str:
        return f"<settle.Result {self._inner.scenario.name!r} {self.status}>"


def load(path: PathLike) -> Scenario:
    """Reads the scenario file ``path`` (or a run record ``OUT/NAME/run.toml``)."""
    return Scenario.load(path)


Overrides = Union[Mapping[str, Any], Sequence[str], None]


def _scenario(scenario: Union[Scenario, PathLike], overrides: Overrides) -> Scenario:
    """The scenario (a Scenario or the path of a file) with ``overrides`` (``{key: value}`` or
    ``["KEY=VALUE"]``) applied in order, as ``--set`` applies them; every command takes its
    scenario through here."""
    s = scenario if isinstance(scenario, Scenario) else load(scenario)
    if not overrides:
        return s
    if isinstance(overrides, Mapping):
        for k, v in overrides.items():
            s = s.set(k, v)
        return s
    for kv in overrides:
        if not isinstance(kv, str) or "=" not in kv:
            raise TypeError(f"an override is KEY=VALUE, not {kv!r}")
        k, v = kv.split("=", 1)
        s = Scenario(s._inner.set(k, v))
    return s


def run(
    scenario: Union[Scenario, PathLike],
    *,
    dt: Optional[float] = None,
    overrides: Overrides = None,
    out: Optional[PathLike] = None,
    progress: _progress.Progress = None,
    force: bool = False,
    threads: Optional[int] = None,
) -> Result:
    """Runs a scenario (a :class:`Scenario` or the path of a scenario file) in memory, with the
    GIL released.

    ``dt``: the time step, s (``--dt``). ``overrides``: ``{key: value}`` or ``["KEY=VALUE"]``,
    applied in order as ``--set`` does. ``out``: also write the run's files to
    ``out/<name>/`` (``--out``). ``progress``: a progress bar (True, False, or a callable
    ``f(name, pos, len, unit, message)``; default: in a terminal or a Jupyter notebook, shown
    after half a second). ``force``: run even when the cost estimate exceeds the limits.
    ``threads``: threads of the run's own parallel loops (default: every core); ``threads=1``
    when running many small scenarios in parallel Python threads, so that they do not compete
    for the same cores.

    Ctrl-C (``KeyboardInterrupt``) stops the run within about half a second, and
    nothing is written to ``out``. A run that goes unstable raises :class:`UnstableError`.
    """
    s = _scenario(scenario, overrides)
    if dt is not None:
        s = s.with_dt(dt)
    with _progress.bar(progress) as cb:
        r = Result(s._inner.run(progress=cb, force=bool(force), threads=threads))
    if out is not None:
        r.write(out)
    return r


class Output(_Tables):
    """What a command other than ``run`` made (``sweep``, ``vary``, ``reduce``, ``invert``,
    ``laws``, ``fit``), in memory: its tables as DataFrames equal to the CSV files the command
    line writes, its other files (charts) as bytes, its warnings and console lines; ``write``
    writes the folder the command line writes."""

    __slots__ = ()

    _inner: _settle.Output

    @property
    def name(self) -> str:
        """The results folder's name (``valentik_susp1_sweep``, ``soil_a_reduced``, ``laws``)."""
        return self._inner.name

    @property
    def files(self) -> Dict[str, bytes]:
        """The files that are not tables (charts as SVG, records as TOML), by name."""
        out: Dict[str, bytes] = {}
        for n in self._inner.file_names():
            b = self._inner.file(n)
            if b is not None:
                out[n] = b
        return out

    def plot(self, name: Optional[str] = None) -> Any:
        """The chart ``name`` (a file name or stem of :attr:`charts`; default the first) as a
        ``matplotlib.figure.Figure``, drawn from the data of the SVG file the command writes."""
        names = self.charts
        if name is None:
            if not names:
                raise KeyError(f"{self.name} has no chart")
            name = names[0]
        return self._plot(name)

    def write(self, folder: PathLike) -> str:
        """Writes ``folder/<name>/`` as the command line does with ``--out folder``; returns
        that folder. Refused (ScenarioError) when it exists and was not made by settle."""
        return os.fspath(self._inner.write(os.fspath(folder)))

    def __repr__(self) -> str:
        return f"<settle.Output {self.name!r}: {', '.join(self.tables)}>"
