"""docs/python.md run as a reader would: every ```python block, in order, in one namespace, in
an empty folder; what a block prints must equal the ```text block that follows it, to the last
digit (the tutorial's figures are the runs' own). A step has at most 40 lines of code."""

from __future__ import annotations

import contextlib
import io
import os
import re
from pathlib import Path
from typing import Any, Dict, List, Optional, Tuple

import pytest

ROOT = Path(__file__).resolve().parents[2]
DOC = ROOT / "docs" / "python.md"


def blocks(text: str) -> List[Tuple[int, str, Optional[str]]]:
    """(line, code, expected output or None) of every python block."""
    found = list(re.finditer(r"^```(\w*)\n(.*?)^```\s*$", text, re.M | re.S))
    out = []
    for i, m in enumerate(found):
        if m.group(1) != "python":
            continue
        expected = None
        if i + 1 < len(found) and found[i + 1].group(1) == "text":
            between = text[m.end() : found[i + 1].start()]
            if not between.strip() or between.strip().lower().startswith("prints"):
                expected = found[i + 1].group(2)
        line = text[: m.start()].count("\n") + 1
        out.append((line, m.group(2), expected))
    return out


def test_every_step_is_short() -> None:
    for line, code, _ in blocks(DOC.read_text()):
        n = len([c for c in code.splitlines() if c.strip()])
        assert n <= 40, f"docs/python.md:{line}: {n} lines of code (at most 40 per step)"


def test_docs_python_runs_as_written(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    pytest.importorskip("matplotlib")
    text = DOC.read_text()
    # the doc's paths to the repository's files are relative to a clone's root
    monkeypatch.chdir(tmp_path)
    os.symlink(ROOT / "scenarios", tmp_path / "scenarios")
    os.symlink(ROOT / "data", tmp_path / "data")
    ns: Dict[str, Any] = {"__name__": "__docs__"}
    found = blocks(text)
    assert len(found) >= 6, "the tutorial's steps"
    for line, code, expected in found:
        buf = io.StringIO()
        with contextlib.redirect_stdout(buf):
            exec(compile(code, f"docs/python.md:{line}", "exec"), ns)
        if expected is not None:
            assert buf.getvalue() == expected, f"docs/python.md:{line}: printed\n{buf.getvalue()}"
