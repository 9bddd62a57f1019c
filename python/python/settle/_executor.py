"""Sweeps spread over an executor: ``settle.sweep(..., executor=ex)`` and ``settle.vary(...,
executor=ex)`` split the grid into shards (``settle sweep --shard I/N``), submit each to ``ex``
(``ex.submit(task, ...)``: a ``concurrent.futures`` executor such as a process pool or Dask's
``Client.get_executor()``, or submitit's Slurm executor), and merge the parts in the caller
(``settle sweep --merge``) into what the serial call returns.

A task is a module-level function of plain values only (the scenario as the text of
:meth:`Scenario.to_toml` and its path, the options, the shard), so that any executor can pickle
it; it returns the text of the shard's part file (``sweep_part_I_of_N.csv``). A settle error in
a task is returned, not raised, and raised again in the caller: the same
:class:`ScenarioError` as the serial call whatever the executor does with exceptions (submitit
wraps them in its own).
"""

from __future__ import annotations

import time
from typing import Any, Callable, List, Optional, Protocol, Sequence, Tuple, Union

from . import _progress, _settle
from ._core import Scenario

#: The default number of parts: one per case, at most this many (each part is a task of the
#: executor: a process, a Dask task, a Slurm job).
MAX_DEFAULT_PARTS = 64

#: The errors of settle a task hands back to the caller (raised there again).
_SETTLE_ERRORS = (_settle.ScenarioError, _settle.UnstableError, OSError)

# The options of a dt sweep as the extension takes them: dt, dt_range, per_decade,
# integrators, tol.
SweepArgs = Tuple[
    Optional[List[float]],
    Optional[Tuple[float, float]],
    Optional[int],
    Optional[List[str]],
    Optional[float],
]
# The axes of a parameter sweep as the extension takes them: (key, grid text or values).
Axes = List[Tuple[str, Union[str, List[str]]]]
# What a task returns: the part's text, or the settle error that stopped it.
Outcome = Tuple[Optional[str], Optional[BaseException]]


class Executor(Protocol):
    """What ``executor`` must have: ``submit(fn, *args)`` returning a future with ``done()``,
    ``result()`` and ``cancel()`` (``concurrent.futures.Executor``, Dask's
    ``Client.get_executor()``, submitit's executors)."""

    def submit(self, fn: Callable[..., Any], /, *args: Any) -> Any: ...


def _scenario_of(text: str, origin: str) -> _settle.Scenario:
    return _settle.Scenario.from_toml(text, origin)


def _sweep_part_task(text: str, origin: str, args: SweepArgs, index: int, count: int) -> Outcome:
    """Shard ``index`` of ``count`` of a dt sweep, run where the executor runs it."""
    try:
        s = _scenario_of(text, origin)
        return _settle.sweep_part(s, *args, index, count), None
    except _SETTLE_ERRORS as e:
        return None, e


def _vary_part_task(text: str, origin: str, axes: Axes, index: int, count: int) -> Outcome:
    """Shard ``index`` of ``count`` of a parameter sweep, run where the executor runs it."""
    try:
        s = _scenario_of(text, origin)
        return _settle.vary_part(s, axes, index, count), None
    except _SETTLE_ERRORS as e:
        return None, e


def _how_many(parts: Optional[int], cases: int) -> int:
    """The number of parts: ``parts`` (an int >= 1), or one per case up to
    :data:`MAX_DEFAULT_PARTS`; never more than the cases."""
    if parts is None:
        return max(1, min(cases, MAX_DEFAULT_PARTS))
    if isinstance(parts, bool) or not isinstance(parts, int) or parts < 1:
        raise ValueError(f"parts: the number of shards to submit, an int >= 1, not {parts!r}")
    return max(1, min(parts, cases))


def _gather(
    futures: Sequence[Any], name: str, progress: _progress.Progress
) -> List[Tuple[int, int, str]]:
    """Waits for every part (polling ``done()``, which every executor's futures have), with a
    bar over the parts done; returns ``(index, count, text)`` of each. A settle error of a part
    is raised as is; on any error or Ctrl-C the parts not yet done are cancelled."""
    n = len(futures)
    texts: List[Optional[str]] = [None] * n
    pending = list(range(n))
    try:
        with _progress.bar(progress) as cb:
            delay, shown, shown_at = 0.01, -1, 0.0
            while pending:
                still = []
                for k in pending:
                    if futures[k].done():
                        text, err = futures[k].result()
                        if err is not None:
                            raise err
                        texts[k] = text
                    else:
                        still.append(k)
                now = time.monotonic()
                # on each change, else about ten times a second (the bar appears after a delay)
                if cb is not None and (n - len(still) != shown or now - shown_at >= 0.1):
                    shown, shown_at = n - len(still), now
                    cb(name, shown, n, "parts", "")
                if still:
                    time.sleep(delay)
                    delay = min(delay * 1.5, 0.2)
                pending = still
    except BaseException:
        _cancel(futures[k] for k in pending)
        raise
    return [(k + 1, n, t) for k, t in enumerate(texts) if t is not None]


def _cancel(futures: Any) -> None:
    for f in futures:
        try:
            f.cancel()
        except Exception:  # pragma: no cover  (a scheduler that refuses: nothing more to do)
            pass


def _spread(
    executor: Executor, task: Callable[..., Outcome], s: Scenario, what: Any, n: int,
    progress: _progress.Progress,
) -> List[Tuple[int, int, str]]:
    """Submits shards 1..=n of ``what`` (the options or the axes) on ``s`` to ``executor`` and
    gathers their texts (:func:`_gather`); if a submission fails, those made are cancelled."""
    text, origin = s.to_toml(), s.path
    futures: List[Any] = []
    try:
        for i in range(1, n + 1):
            futures.append(executor.submit(task, text, origin, what, i, n))
    except BaseException:
        _cancel(futures)
        raise
    return _gather(futures, s.name, progress)


def sweep(
    executor: Executor, s: Scenario, args: SweepArgs, parts: Optional[int],
    progress: _progress.Progress,
) -> _settle.Output:
    """The dt sweep of ``s`` with ``args`` in ``parts`` shards on ``executor``, merged; the
    options are checked before anything is submitted."""
    n = _how_many(parts, _settle.sweep_cases(s._inner, *args))
    texts = _spread(executor, _sweep_part_task, s, args, n, progress)
    return _settle.sweep_merge(s._inner, *args, texts)


def vary(
    executor: Executor, s: Scenario, axes: Axes, parts: Optional[int],
    progress: _progress.Progress,
) -> _settle.Output:
    """The parameter sweep of ``s`` over ``axes`` in ``parts`` shards on ``executor``, merged;
    every point is validated before anything is submitted."""
    n = _how_many(parts, _settle.vary_cases(s._inner, axes))
    texts = _spread(executor, _vary_part_task, s, axes, n, progress)
    return _settle.vary_merge(s._inner, axes, texts)
