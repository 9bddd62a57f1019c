"""Progress bars of long computations, in a terminal and in a Jupyter notebook.

The extension calls a callback ``f(name, pos, len, unit, message)`` about ten times a second
while a run's progress bar moves (``settle._settle`` watches the Rust bar; nothing is drawn on
the process's stderr). :func:`bar` makes that callback from the ``progress`` argument:

- ``False``: none;
- ``None`` (the default): a bar when the session is interactive (stderr a terminal, or a
  Jupyter kernel), shown only once the computation has taken :data:`DELAY_S`;
- ``True``: a bar, even when not interactive (to a log, one line per 10 %);
- a callable: called as is.

In Jupyter the bar is ``tqdm.auto``'s widget when tqdm is installed, else an HTML
``<progress>`` element updated in place; in a terminal, one line on stderr redrawn with ``\\r``.
"""

from __future__ import annotations

import contextlib
import sys
import time
from typing import Any, Callable, Iterator, Optional, Union

Callback = Callable[[str, int, Optional[int], str, str], None]
Progress = Union[bool, None, Callback]

#: Wall time before a bar appears, s (short runs show none).
DELAY_S = 0.5


def in_jupyter() -> bool:
    """True inside a Jupyter (IPython) kernel."""
    ip = sys.modules.get("IPython")
    if ip is None or "ipykernel" not in sys.modules:
        return False
    try:
        shell = ip.get_ipython()
    except Exception:  # pragma: no cover
        return False
    return shell is not None and getattr(shell, "kernel", None) is not None


def _tty() -> bool:
    return bool(getattr(sys.stderr, "isatty", lambda: False)())


class _Bar:
    """The default bar: tqdm.auto if installed, else HTML in Jupyter or a line on stderr."""

    def __init__(self) -> None:
        self.start = time.monotonic()
        self.jupyter = in_jupyter()
        self.tty = _tty()
        self.tqdm: Any = None
        self.handle: Any = None
        self.last_decile = -1
        self.drawn = False

    def __call__(self, name: str, pos: int, length: Optional[int], unit: str, message: str) -> None:
        if not self.drawn and time.monotonic() - self.start < DELAY_S:
            return
        self.drawn = True
        total = length or 0
        if self.tqdm is None and (self.jupyter or self.tty):
            try:
                from tqdm.auto import tqdm  # type: ignore[import-untyped,unused-ignore]  # optional

                self.tqdm = tqdm(total=total, desc=name, unit=unit or "it", leave=False)
            except ImportError:
                self.tqdm = False
        if self.tqdm:
            self.tqdm.total = total
            self.tqdm.n = pos
            self.tqdm.set_postfix_str(message, refresh=False)
            self.tqdm.refresh()
        elif self.jupyter:
            self._html(name, pos, total, unit, message)
        else:
            self._line(name, pos, total, unit, message)

    def _html(self, name: str, pos: int, total: int, unit: str, message: str) -> None:
        ipd = _ipython_display()
        html = ipd.HTML(
            f"<div><code>{name}</code> <progress value='{pos}' max='{max(total, 1)}' "
            f"style='width:40%'></progress> {pos}/{total} {unit} <small>{message}</small></div>"
        )
        if self.handle is None:
            self.handle = ipd.display(html, display_id=True)
        else:
            self.handle.update(html)

    def _line(self, name: str, pos: int, total: int, unit: str, message: str) -> None:
        frac = pos / total if total else 0.0
        if self.tty:
            filled = int(30 * min(frac, 1.0))
            bar = "=" * filled + (">" if filled < 30 else "") + " " * max(29 - filled, 0)
            sys.stderr.write(f"\r{name} [{bar}] {pos}/{total} {unit} {message}\x1b[K")
            sys.stderr.flush()
        elif int(10 * frac) > self.last_decile:
            # not a terminal (a log): one line per tenth
            self.last_decile = int(10 * frac)
            sys.stderr.write(f"{name}: {pos}/{total} {unit} {message}\n")
            sys.stderr.flush()

    def close(self) -> None:
        if self.tqdm:
            self.tqdm.close()
        elif self.handle is not None:
            self.handle.update(_ipython_display().HTML(""))
        elif self.drawn and self.tty:
            sys.stderr.write("\r\x1b[K")
            sys.stderr.flush()


def _ipython_display() -> Any:
    """IPython.display (untyped to mypy: its functions are called through Any)."""
    import importlib

    return importlib.import_module("IPython.display")


@contextlib.contextmanager
def bar(progress: Progress) -> Iterator[Optional[Callback]]:
    """The callback for ``progress`` (see the module), closed when the block ends."""
    if progress is False:
        yield None
        return
    if not isinstance(progress, bool) and progress is not None:
        yield progress
        return
    if progress is None and not (_tty() or in_jupyter()):
        yield None
        return
    b = _Bar()
    try:
        yield b
    finally:
        b.close()
