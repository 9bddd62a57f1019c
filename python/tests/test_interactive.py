"""What a notebook user meets beyond the tables: charts as matplotlib figures (the data of the
SVG files, for every kind), progress, Ctrl-C, runs in parallel threads, and the example
notebook executed."""

from __future__ import annotations

import os
import re
import signal
import subprocess
import sys
import textwrap
import threading
import time
from pathlib import Path
from typing import Any, List, Optional, Tuple

import numpy as np
import pytest

import settle

ROOT = Path(__file__).resolve().parents[2]
SCENARIOS = ROOT / "scenarios"

# One scenario of every kind, kept short.
KINDS = {
    "free_settling": ("stokes_single.toml", {}),
    "drop": ("paste_single_ball.toml", {}),
    "restitution_drop": ("restitution_drop.toml", {}),
    "tilt_friction": ("tilt_friction.toml", {}),
    "funnel_pour": (
        "paste_68_balls.toml",
        {"repeats.count": 1, "time.dt_s": 1e-4, "funnel.count_time_s": 0.15, "time.end_s": 0.2},
    ),
    "sedimentation": ("sedimentation_sample5.toml", {"sample.particles": 5000}),
}


def svg_texts(svg: str) -> List[str]:
    """The texts of an SVG file (plotters writes each as one <text> element)."""
    out = []
    for m in re.finditer(r"<text[^>]*>(.*?)</text>", svg, re.S):
        t = re.sub(r"<[^>]+>", "", m.group(1))
        t = t.replace("&lt;", "<").replace("&gt;", ">").replace("&amp;", "&")
        t = " ".join(t.split())
        if t:
            out.append(t)
    return out


@pytest.mark.parametrize("kind", sorted(KINDS))
def test_plot_draws_the_main_chart_of_every_kind(kind: str, tmp_path: Path) -> None:
    pytest.importorskip("matplotlib")
    file, sets = KINDS[kind]
    r = settle.run(SCENARIOS / file, overrides=sets, progress=False)
    assert r.scenario.kind == kind
    assert r.main_chart in r.charts
    fig = r.plot()
    ax = fig.axes[0]
    # The figure says what the SVG file says: its title, axis labels and legend entries.
    svg = (Path(r.write(tmp_path)) / r.main_chart).read_text()
    texts = svg_texts(svg)
    joined = " ".join(texts)  # the SVG wraps long titles and labels over several lines
    assert ax.get_title() in joined
    assert ax.get_xlabel() in texts and ax.get_ylabel() in texts
    legend = ax.get_legend()
    if legend is not None:
        for t in legend.get_texts():
            assert t.get_text() in joined, t.get_text()
    # Every series is drawn with every point of the chart's data.
    data = r._inner.figure(r.main_chart)
    assert data is not None
    drawn = [it for it in data["panels"][0]["items"] if it["type"] != "band"]
    lines = ax.get_lines()
    assert len(lines) == len(drawn)
    for line, it in zip(lines, drawn):
        np.testing.assert_array_equal(np.asarray(line.get_ydata()), np.frombuffer(it["y"]))


def test_plot_of_the_free_settling_chart_is_the_timeseries() -> None:
    pytest.importorskip("matplotlib")
    r = settle.run(SCENARIOS / "stokes_single.toml", progress=False)
    ts = r.tables["timeseries"]
    simulated = r.plot("velocity").axes[0].get_lines()[0]
    np.testing.assert_array_equal(simulated.get_xdata(), ts["time_s"].to_numpy())
    np.testing.assert_array_equal(simulated.get_ydata(), ts["velocity_m_s"].to_numpy())
    with pytest.raises(KeyError, match="no chart 'nonsense'"):
        r.plot("nonsense")


def test_progress_callback_follows_a_long_run() -> None:
    calls: List[Tuple[str, int, Optional[int], str, str]] = []
    settle.run(
        SCENARIOS / "sedimentation_sample5.toml",
        overrides={"sample.particles": 20000},
        progress=lambda *a: calls.append(a),
    )
    assert calls, "the callback was never called"
    names = {c[0] for c in calls}
    assert names == {"sedimentation_sample5"}
    pos = [c[1] for c in calls]
    assert pos == sorted(pos)
    name, last, length, unit, _msg = calls[-1]
    assert unit == "s simulated"
    assert length is not None and last == length  # the final call shows the end


def test_progress_false_and_a_short_run_draw_nothing(capfd: Any) -> None:
    settle.run(SCENARIOS / "stokes_single.toml", progress=False)
    settle.run(SCENARIOS / "stokes_single.toml", progress=True)  # under DELAY_S: no bar
    assert capfd.readouterr().err == ""


def test_a_failing_progress_callback_stops_the_run_and_is_raised() -> None:
    def cb(*_a: Any) -> None:
        raise ValueError("stop here")

    with pytest.raises(ValueError, match="stop here"):
        settle.run(
            SCENARIOS / "sedimentation_sample5.toml",
            overrides={"sample.particles": 20000},
            progress=cb,
        )
    # the stop request was withdrawn: the next run completes
    assert settle.run(SCENARIOS / "stokes_single.toml", progress=False).status == "complete"


# 10⁶ grains of sample 2 (about 18 s of CPU): the signal lands mid-run even on a loaded machine.
CHILD = textwrap.dedent(
    """
    import signal, sys, time, settle
    # as in a terminal's session: a suite started in the background (`scripts/test.sh &`)
    # hands its children SIGINT ignored, and Python then leaves it so
    signal.signal(signal.SIGINT, signal.default_int_handler)
    def cb(name, pos, length, unit, msg):
        if pos > 0 and not getattr(cb, "said", False):
            cb.said = True
            print("running", flush=True)
    try:
        settle.run(sys.argv[1], overrides={"sample.particles": 1000000}, out=sys.argv[2],
                   progress=cb)
        print("finished", flush=True)
    except KeyboardInterrupt:
        print("interrupted", time.monotonic(), flush=True)
    """
)


def test_ctrl_c_stops_a_long_sedimentation_run_within_a_second(tmp_path: Path) -> None:
    out = tmp_path / "out"
    p = subprocess.Popen(
        [sys.executable, "-c", CHILD, str(SCENARIOS / "sedimentation_sample2.toml"), str(out)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        assert p.stdout is not None
        line = p.stdout.readline()  # bounded by the run itself: minutes at most
        assert line.strip() == "running", line + (p.stderr.read() if p.stderr else "")
        sent = time.monotonic()
        os.kill(p.pid, signal.SIGINT)
        rest, err = p.communicate(timeout=60)
    finally:
        if p.poll() is None:
            p.kill()
    words = rest.split()
    assert words[:1] == ["interrupted"], rest + err
    # CLOCK_MONOTONIC is one clock for every process of the machine.
    latency = float(words[1]) - sent
    assert latency < 1.0, f"KeyboardInterrupt {latency:.2f} s after SIGINT"
    # nothing was written into `out`, not even a staging folder
    assert not out.exists() or not any(out.iterdir()), list(out.iterdir())


def test_runs_in_two_threads_overlap() -> None:
    """The GIL is released while a run computes: a second thread runs a whole scenario while a
    long run is still going (with the GIL held, it could not start before the other ended)."""
    state = {"running": threading.Event(), "stop": threading.Event(), "error": None}

    def cb(name: str, pos: int, *_a: Any) -> None:
        if pos > 0:
            state["running"].set()
        if state["stop"].is_set():
            raise InterruptedError("done")

    def long_run() -> None:
        try:
            settle.run(
                SCENARIOS / "sedimentation_sample2.toml",
                overrides={"sample.particles": 300000},
                progress=cb,
                threads=1,
            )
        except InterruptedError:
            pass
        except BaseException as e:  # pragma: no cover - reported below
            state["error"] = e

    t = threading.Thread(target=long_run)
    t.start()
    try:
        while not state["running"].wait(0.1):
            assert t.is_alive(), f"the long run ended before it showed progress: {state['error']}"
        r = settle.run(SCENARIOS / "valentik_susp1.toml", progress=False, threads=1)
        assert r.status == "complete"
        assert t.is_alive(), "the long run ended before the short one: no overlap shown"
    finally:
        state["stop"].set()
        t.join(300)
    assert state["error"] is None


def test_the_example_notebook_runs(tmp_path: Path) -> None:
    nbformat = pytest.importorskip("nbformat")
    nbclient = pytest.importorskip("nbclient")
    pytest.importorskip("matplotlib")
    src = ROOT / "examples" / "yield_stress_scan.ipynb"
    nb = nbformat.read(src, as_version=4)
    client = nbclient.NotebookClient(
        nb, timeout=600, kernel_name="python3", resources={"metadata": {"path": str(src.parent)}}
    )
    client.execute()  # raises CellExecutionError on any failing cell (the notebook asserts too)
    images = [
        o
        for c in nb.cells
        if c.cell_type == "code"
        for o in c.outputs
        if "image/png" in o.get("data", {})
    ]
    assert len(images) == 2, "the run's main chart and the scan's figure, as PNG"
    last = nb.cells[-1].outputs[0]["data"]["text/plain"]
    held = {float(k): int(v) for k, v in re.findall(r"^([\d.]+)\s+(\d+)$", last, re.M)}
    # Suspension 1 at its own yield stress moves every sphere (Valentik & Whitmore measured a
    # velocity for each); at 60 Pa the yield stress holds some.
    assert held[30.5] == 0 and held[60.0] > 0, last


def test_the_jupyter_bar_updates_one_html_element(monkeypatch: pytest.MonkeyPatch) -> None:
    """In a notebook without tqdm the bar is one HTML <progress> element, updated in place."""
    import types

    from settle import _progress

    shown: List[str] = []

    class Handle:
        def update(self, html: Any) -> None:
            shown.append(html.data)

    def display(html: Any, display_id: bool = False) -> Handle:
        assert display_id
        shown.append(html.data)
        return Handle()

    class HTML:
        def __init__(self, data: str) -> None:
            self.data = data

    fake = types.ModuleType("IPython.display")
    fake.HTML = HTML  # type: ignore[attr-defined]
    fake.display = display  # type: ignore[attr-defined]
    monkeypatch.setitem(sys.modules, "IPython.display", fake)
    monkeypatch.setitem(sys.modules, "tqdm.auto", None)  # tqdm not installed
    monkeypatch.setattr(_progress, "in_jupyter", lambda: True)
    monkeypatch.setattr(_progress, "DELAY_S", 0.0)
    with _progress.bar(None) as cb:
        assert cb is not None
        cb("sedimentation_sample5", 30, 120, "s simulated", "400 steps")
        cb("sedimentation_sample5", 120, 120, "s simulated", "1600 steps")
    assert len(shown) == 3  # displayed once, updated once, cleared at the end
    assert "<progress value='30' max='120'" in shown[0]
    assert "120/120 s simulated" in shown[1]
    assert shown[2] == ""
