"""The package's annotations and stubs pass mypy --strict, with a typed user script."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent


def test_mypy_strict_on_the_package_and_a_typed_script() -> None:
    pytest.importorskip("mypy", reason="mypy is installed by scripts/test_python.sh")
    package = HERE.parent / "python" / "settle"
    p = subprocess.run(
        [sys.executable, "-m", "mypy", "--strict", str(package), str(HERE / "typed_usage.py")],
        capture_output=True,
        text=True,
    )
    assert p.returncode == 0, p.stdout + p.stderr


def test_typed_script_runs() -> None:
    sys.path.insert(0, str(HERE))
    try:
        import typed_usage
    finally:
        sys.path.remove(str(HERE))
    root = HERE.parents[1]
    v = typed_usage.terminal_velocity_m_s(root / "scenarios" / "stokes_single.toml", 0.002)
    assert 0.0 < v < 1.0
    assert typed_usage.error_key("kind = 3") == "kind"
