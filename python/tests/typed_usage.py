"""Typed use of the package, checked by mypy --strict (test_types.py): the stubs and the
annotations of settle must accept what a user writes."""

from __future__ import annotations

import concurrent.futures
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


# --- lab (settle.reduce, settle.invert, settle.laws) ---


def lab_tables(readings_file: Path, frame: pd.DataFrame, out: Path) -> list[str]:
    r: settle.Output = settle.reduce(readings_file, standard="d422", hydrometer="152H", out=out)
    finer: pd.DataFrame = r.tables["percent_finer"]
    f: settle.Output = settle.reduce(frame, name="soil_a", dry_mass_g=50, specific_gravity=2.65)
    i: settle.Output = settle.invert(
        [readings_file, frame],
        model="full",
        bins=12,
        diameters_um=(2.0, 75.0),
        lambda_=0.5,
        resolution=[0.5, 0.001],
        repeats=20,
        seed=3,
        bounds=True,
    )
    one: settle.Output = settle.invert(readings_file, lambda_="gcv", resolution=0.5)
    laws: settle.Output = settle.laws()
    mine: settle.Output = settle.laws(Path("spheres.csv"), "fluids.csv", out=out)
    csv: bytes = i.csv("inverted")
    written: str = laws.write(out)
    return [str(len(finer)), f.name, one.name, mine.name, str(len(csv)), written, *r.warnings]


# --- end of lab ---


# --- w-fit: settle.fit, settle.slump ---
def fitted_eta_b(scenario_file: Path, measured: pd.DataFrame) -> tuple[float, float]:
    o: settle.Output = settle.fit(
        scenario_file,
        fit={"fluid.plastic_viscosity_pa_s": (0.1, 3.0)},
        measured=measured,
        overrides={"release.fall_heights_m": [0.255]},
        progress=False,
    )
    fitted: pd.DataFrame = o.tables["fitted"]
    chart: bytes = o.files["objective_vs_plastic_viscosity_pa_s.svg"]
    assert chart.startswith(b"<svg")
    s: settle.Slump = settle.slump(152.0, [102.0, 103.0], density=1843.0)
    return float(fitted["value"].iloc[0]), s.mean_yield_stress_pa
# --- end of w-fit ---


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


def spread_sweep(scenario_file: Path, pool: concurrent.futures.ProcessPoolExecutor) -> settle.Output:
    """A process pool is an executor of settle.sweep (typed: the package's Executor protocol)."""
    return settle.sweep(scenario_file, dt=[1e-3, 1e-4], executor=pool, parts=2, progress=False)


# --- end of sweep ---
