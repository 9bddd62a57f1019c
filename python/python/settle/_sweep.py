"""settle.sweep and settle.vary: ``settle sweep`` (time-step sweeps) and ``settle sweep --vary``
(parameter sweeps) in memory, each returning an :class:`settle.Output` whose tables are the CSV
files the command line writes (see python/src/sweep.rs)."""

from __future__ import annotations

import numbers
from typing import Any, List, Mapping, Optional, Sequence, Tuple, Union

from . import _executor, _progress, _settle
from ._core import Output, Overrides, PathLike, Scenario, _scenario
from ._executor import Executor

#: The values of one ``vary`` axis: the grid text of ``--vary KEY=GRID`` after the ``=``
#: (``"10:40:13"``, ``"log:1e-3:1e-1:5"``, ``"off,basset"``) or a sequence of values.
Grid = Union[str, Sequence[Union[float, int, str, bool]]]


def _floats(name: str, x: Union[float, Sequence[float]]) -> List[float]:
    if isinstance(x, (str, bytes)):
        raise TypeError(f"{name}: a number or a sequence of numbers, not {x!r}")
    if isinstance(x, (int, float)) or isinstance(x, numbers.Real):  # numpy scalars too
        return [float(x)]
    return [float(v) for v in x]


def _value_text(key: str, v: Any) -> str:
    """One value of an axis as ``--vary KEY=V1,V2`` writes it: a number in its shortest form
    that reads back to the same float, a boolean as ``true``/``false``, a word as is."""
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, numbers.Integral):
        return str(int(v))
    if isinstance(v, numbers.Real):
        return repr(float(v))
    if isinstance(v, str):
        return v
    raise TypeError(f"{key}: a value of an axis is a number, a str or a bool, not {v!r}")


def _executor_of(executor: Optional[Executor], parts: Optional[int]) -> Optional[Executor]:
    """``executor`` if the sweep is to be spread over it (checked), else None."""
    if executor is None:
        if parts is not None:
            raise ValueError("parts: only with an executor (the number of shards it runs)")
        return None
    if not callable(getattr(executor, "submit", None)):
        raise TypeError(
            f"executor: an object with submit(fn, *args) (a concurrent.futures.Executor), "
            f"not {executor!r}"
        )
    return executor


def sweep(
    scenario: Union[Scenario, PathLike],
    *,
    dt: Union[float, Sequence[float], None] = None,
    dt_range: Optional[Tuple[float, float]] = None,
    per_decade: Optional[int] = None,
    integrators: Union[str, Sequence[str], None] = None,
    tol: Optional[float] = None,
    overrides: Overrides = None,
    out: Optional[PathLike] = None,
    progress: _progress.Progress = None,
    executor: Optional[Executor] = None,
    parts: Optional[int] = None,
) -> Output:
    """A time-step sweep, as ``settle sweep``: the scenario (a :class:`Scenario` or the path of
    a scenario file) runs at every (integrator, dt) of the grid, in parallel, with the GIL
    released; each quantity is compared with its reference and with the finest stable dt.

    ``dt``: time steps, s, each > 0 (``--dt``). ``dt_range``: ``(lo, hi)``, s, log-spaced with
    ``per_decade`` steps per decade (``--dt-range LO:HI --per-decade N``, default 3; not with
    ``dt``). ``integrators``: names (``"explicit"``, ``"implicit"``, ``"exponential"``), a list
    or a comma-separated str (``--integrator``). ``tol``: the largest relative error against
    the finest stable dt of the recommended dt, 0 < tol <= 1 (``--tol``). Left None, each takes
    the command line's default: the scenario's ``[sweep]`` table, else every integrator and
    tol = 0.01 (the time steps have no default). ``overrides``: ``{key: value}`` or
    ``["KEY=VALUE"]`` (``--set``). ``out``: also write ``out/<name>_sweep/`` (``--out``).
    ``progress``: as for :func:`settle.run` (with an executor, a bar over the parts done).

    ``executor``: spread the cases over other processes or machines: any object with
    ``submit(fn, *args)`` returning a future with ``done()``, ``result()`` and ``cancel()`` (a
    ``concurrent.futures.ProcessPoolExecutor``, Dask's ``distributed.Client(...).get_executor()``,
    submitit's ``AutoExecutor``/``SlurmExecutor``). The options are checked here first (a bad
    one raises before anything is submitted); the grid is split into ``parts`` shards (``settle
    sweep --shard I/N``; default one per case, at most 64; never more than the cases), each
    submitted as one task given the scenario as the text of :meth:`Scenario.to_toml` (its input
    files as absolute paths: the workers must see them) and returning its part as CSV text; the
    parts are merged here (``--merge``). The result equals the serial call's, cell for cell (wall times aside). A
    settle error in a task is raised here as the serial call raises it; Ctrl-C cancels the
    parts not yet done. ``parts`` without an executor is an error.

    The result's ``tables`` are ``sweep`` and ``recommended_dt`` (``sweep.csv`` and
    ``recommended_dt.csv``), its ``files`` the charts and ``report.html``, its ``lines`` what
    the command line prints, its ``warnings`` each recommended dt that no finer stable dt
    confirms. A bad option raises :class:`ScenarioError` with the command line's message::

        r = settle.sweep("scenarios/stokes_single.toml", dt=[1e-3, 1e-4, 1e-5],
                         integrators=["explicit", "exponential"])
        r.tables["recommended_dt"]   # DataFrame: recommended_dt.csv of `settle sweep`
    """
    s = _scenario(scenario, overrides)
    if isinstance(integrators, str):
        integrators = integrators.split(",")
    names = None if integrators is None else [str(i) for i in integrators]
    dts = None if dt is None else _floats("dt", dt)
    rng = None if dt_range is None else (float(dt_range[0]), float(dt_range[1]))
    per = None if per_decade is None else int(per_decade)
    tol_ = None if tol is None else float(tol)
    ex = _executor_of(executor, parts)
    if ex is not None:
        inner = _executor.sweep(ex, s, (dts, rng, per, names, tol_), parts, progress)
    else:
        with _progress.bar(progress) as cb:
            inner = _settle.sweep(s._inner, dts, rng, per, names, tol_, cb)
    r = Output(inner)
    if out is not None:
        r.write(out)
    return r


def vary(
    scenario: Union[Scenario, PathLike],
    grid: Mapping[str, Grid],
    *,
    overrides: Overrides = None,
    out: Optional[PathLike] = None,
    progress: _progress.Progress = None,
    executor: Optional[Executor] = None,
    parts: Optional[int] = None,
) -> Output:
    """A parameter sweep, as ``settle sweep --vary``: the scenario runs once per point of the
    full grid of ``grid`` (``{key: values}``, in order: the first key is outermost and the
    charts' x axis), each value applied as ``--set KEY=VALUE`` after ``overrides``, at the
    scenario's own dt and integrator, in parallel with the GIL released.

    The values of a key: the grid text of ``--vary KEY=GRID`` (``"10:40:13"``: 13 values from
    10 to 40; ``"log:1e-3:1e-1:5"``; ``"off,basset"``), or a sequence of numbers (in the key's
    unit), words or booleans. ``out``: also write ``out/<name>_vary/`` (``--out``).
    ``progress``: as for :func:`settle.run` (with an executor, a bar over the parts done).
    ``executor``, ``parts``: spread the cases over an executor, as for :func:`settle.sweep`.

    The result's ``tables["vary"]`` is ``vary.csv`` (one row per case and body), its ``files``
    one chart per result quantity and ``report.html``, its ``warnings`` the cases that went
    unstable. Every point is validated before any runs: a bad key or value raises
    :class:`ScenarioError` with the command line's message::

        r = settle.vary("scenarios/stokes_single.toml",
                        {"fluid.viscosity_pa_s": [0.001, 0.002, 0.005]})
        r.tables["vary"]["terminal_velocity_m_s"]
    """
    s = _scenario(scenario, overrides)
    if not isinstance(grid, Mapping):
        raise TypeError("grid: a mapping {key: values}, e.g. {'fluid.viscosity_pa_s': [1e-3, 2e-3]}")
    axes: List[Tuple[str, Union[str, List[str]]]] = []
    for key, values in grid.items():
        if isinstance(values, str):
            axes.append((str(key), values))
        else:
            axes.append((str(key), [_value_text(str(key), v) for v in values]))
    ex = _executor_of(executor, parts)
    if ex is not None:
        inner = _executor.vary(ex, s, axes, parts, progress)
    else:
        with _progress.bar(progress) as cb:
            inner = _settle.vary(s._inner, axes, cb)
    r = Output(inner)
    if out is not None:
        r.write(out)
    return r

