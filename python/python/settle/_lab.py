"""settle.reduce, settle.invert, settle.laws: see python/src/lab.rs."""

from __future__ import annotations

from typing import Any

from ._core import Output



def reduce(*args: Any, **kwargs: Any) -> Output:
    """Not yet bound (issue 25)."""
    raise NotImplementedError("settle.reduce: not yet available from Python")


def invert(*args: Any, **kwargs: Any) -> Output:
    """Not yet bound (issue 25)."""
    raise NotImplementedError("settle.invert: not yet available from Python")


def laws(*args: Any, **kwargs: Any) -> Output:
    """Not yet bound (issue 25)."""
    raise NotImplementedError("settle.laws: not yet available from Python")
