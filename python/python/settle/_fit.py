"""settle.fit: see python/src/fit.rs."""

from __future__ import annotations

from typing import Any

from ._core import Output



def fit(*args: Any, **kwargs: Any) -> Output:
    """Not yet bound (issue 25)."""
    raise NotImplementedError("settle.fit: not yet available from Python")
