"""settle.sweep, settle.vary: see python/src/sweep.rs."""

from __future__ import annotations

from typing import Any

from ._core import Output



def sweep(*args: Any, **kwargs: Any) -> Output:
    """Not yet bound (issue 25)."""
    raise NotImplementedError("settle.sweep: not yet available from Python")


def vary(*args: Any, **kwargs: Any) -> Output:
    """Not yet bound (issue 25)."""
    raise NotImplementedError("settle.vary: not yet available from Python")
