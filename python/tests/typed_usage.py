"""Typed use of the package, checked by mypy --strict (test_types.py): the stubs and the
annotations of settle must accept what a user writes."""

from __future__ import annotations

from pathlib import Path

import pandas as pd

import settle


def terminal_velocity_m_s(scenario_file: Path, viscosity_pa_s: float) -> float:
    s: settle.Scenario = settle.load(scenario_file).set("fluid.viscosity_pa_s", viscosity_pa_s)
    r: settle.Result = settle.run(s, dt=1e-4, overrides={"drag.law": "dallavalle"}, progress=False)
    summary: pd.DataFrame = r.tables["summary"]
    warnings: list[str] = r.warnings
    status: str = r.status
    assert status == "complete", warnings
    return float(summary["v_simulated_m_s"].iloc[0])


def error_key(text: str) -> str | None:
    try:
        settle.Scenario.from_toml(text)
    except settle.ScenarioError as e:
        return e.key
    return None


# --- sweep (helper w-sweep): settle.sweep, settle.vary ---


def recommended_dts(scenario_file: Path) -> dict[str, float]:
    r: settle.Output = settle.sweep(
        scenario_file, dt=[1e-3, 1e-4], integrators=["exponential"], tol=0.01, progress=False
    )
    table: pd.DataFrame = r.tables["recommended_dt"]
    lines: list[str] = r.lines
    assert lines and r.name.endswith("_sweep")
    return dict(zip(table["integrator"], table["recommended_dt_s"]))


def terminal_velocities(scenario_file: Path) -> list[float]:
    r: settle.Output = settle.vary(
        settle.load(scenario_file),
        {"fluid.viscosity_pa_s": [1e-3, 2e-3], "drag.law": "stokes,dallavalle"},
        overrides={"time.end_s": 0.05},
        progress=False,
    )
    return [float(v) for v in r.tables["vary"]["terminal_velocity_m_s"]]


# --- end of sweep ---
