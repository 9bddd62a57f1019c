"""Charts as matplotlib figures: the data of a chart settle draws as SVG (its series, reference
curves and bands, axes and scales), drawn again with matplotlib so that users can restyle,
annotate and combine it. matplotlib is optional: it is imported only here.

The figure is a ``matplotlib.figure.Figure`` made without pyplot, so that it is shown once in
a notebook (as a cell's value) and never opens a window by itself; ``fig.savefig(path)``
writes it.
"""

from __future__ import annotations

import math
from typing import Any, Dict, List

MARKERS = ["o", "s", "^", "D", "v", "*", "p", "h"]


def _floats(b: bytes) -> List[float]:
    import numpy as np

    return list(np.frombuffer(b, dtype=np.float64))


def figure(data: Dict[str, Any]) -> Any:
    """A matplotlib Figure of a chart's data (``_settle`` ``figure(name)``)."""
    try:
        from matplotlib.figure import Figure
    except ImportError as e:  # pragma: no cover - depends on the environment
        raise ImportError(
            "plot needs matplotlib: pip install matplotlib (or pip install 'settle[plot]')"
        ) from e
    panels = data["panels"]
    cols = max(1, min(int(data["columns"]), len(panels)))
    rows = max(1, math.ceil(len(panels) / cols))
    fig = Figure(figsize=(8.5 * cols, 4.8 * rows), layout="constrained")
    axes = fig.subplots(rows, cols, squeeze=False)
    for i, ax in enumerate(axes.flat):
        if i >= len(panels):
            ax.set_visible(False)
            continue
        _panel(ax, panels[i])
    if len(panels) > 1:
        fig.suptitle(data["title"])
    _show_in_jupyter()
    return fig


def _show_in_jupyter() -> None:
    """In a Jupyter kernel, registers the PNG formatter of matplotlib figures (what
    ``%matplotlib inline`` does), so that a figure made without pyplot shows as a cell's value."""
    from ._progress import in_jupyter

    if not in_jupyter():
        return
    try:
        import importlib

        ipython: Any = importlib.import_module("IPython")
        pylabtools: Any = importlib.import_module("IPython.core.pylabtools")
        shell = ipython.get_ipython()
        if shell is not None:
            pylabtools.select_figure_formats(shell, {"png"})
    except Exception:  # pragma: no cover - an IPython without pylabtools
        pass


def _panel(ax: Any, p: Dict[str, Any]) -> None:
    colours = [f"C{i}" for i in range(10)]
    for it in p["items"]:
        label = it["label"] or None
        x = _floats(it["x"])
        if it["type"] == "series":
            c = colours[it["colour"] % 10]
            marker = MARKERS[it["colour"] % len(MARKERS)]
            most = int(it.get("max_markers", 0))
            # as the SVG: every ceil(n / most)-th point, offset by colour
            every = max(1, -(-len(x) // most)) if most > 0 else 1
            start = it["colour"] % every if every > 1 else 0
            ax.plot(
                x,
                _floats(it["y"]),
                linestyle="-" if it["line"] else "none",
                marker=marker,
                markersize=5,
                markevery=(start, every),
                color=c,
                markerfacecolor=c if it["filled"] else "none",
                label=label,
            )
        elif it["type"] == "curve":
            c = "0.15" if it["colour"] is None else colours[it["colour"] % 10]
            ax.plot(x, _floats(it["y"]), linestyle="--" if it["dashed"] else "-", color=c, label=label)
        else:
            grey = str(max(0.0, min(1.0, 1.0 - float(it["shade"]))))
            ax.fill_between(x, _floats(it["lower"]), _floats(it["upper"]), color=grey, label=label, linewidth=0)
    if p["x_log"]:
        ax.set_xscale("log")
        _log_ticks(ax.xaxis)
    if p["y_log"]:
        ax.set_yscale("log")
        _log_ticks(ax.yaxis)
    if p["x_range"] is not None:
        ax.set_xlim(*p["x_range"])
    if p["y_range"] is not None:
        ax.set_ylim(*p["y_range"])
    cats = p["x_categories"]
    if cats:
        ax.set_xticks(range(len(cats)), cats, rotation=30, ha="right")
    ax.set_title(p["title"], fontsize="medium", wrap=True)
    ax.set_xlabel(p["x_label"])
    ax.set_ylabel(p["y_label"])
    ax.grid(True, alpha=0.3)
    labelled = sum(1 for it in p["items"] if it["label"])
    if labelled:
        # as in the SVG: the legend in a panel right of the data
        ax.legend(
            fontsize="small",
            loc="upper left",
            bbox_to_anchor=(1.02, 1.0),
            ncols=max(1, math.ceil(labelled / 18)),
            borderaxespad=0.0,
        )


def _log_ticks(axis: Any) -> None:
    """Ticks at 1, 2 and 5 of each decade, labelled as plain numbers (``2``, ``50``, ``0.01``),
    as the SVG charts label them."""
    from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

    axis.set_major_locator(LogLocator(base=10.0, subs=(1.0, 2.0, 5.0)))
    axis.set_major_formatter(FuncFormatter(lambda v, _pos: f"{v:g}"))
    axis.set_minor_formatter(NullFormatter())
