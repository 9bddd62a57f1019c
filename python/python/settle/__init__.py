"""settle: solid particles settling in Newtonian and Bingham fluids, from Python.

The same steps as ``settle run``, as functions; every table of a run is a pandas DataFrame
equal to the CSV file the command line writes::

    import settle
    s = settle.load("scenarios/stokes_single.toml").set("fluid.viscosity_pa_s", 0.002)
    r = settle.run(s)
    r.tables["summary"]          # DataFrame: summary.csv of `settle run`
    r.write("out")               # out/stokes_single/: the files `settle run` writes

pandas and numpy are imported on the first use of ``Result.tables``, not by ``import settle``.
"""

from __future__ import annotations

from ._core import Output, Result, Scenario, load, run
from ._fit import Slump, fit, slump
from ._lab import invert, laws, reduce
from ._settle import ScenarioError, UnstableError
from ._sweep import sweep, vary

__all__ = [
    "Output",
    "Result",
    "Scenario",
    "ScenarioError",
    "Slump",
    "UnstableError",
    "fit",
    "invert",
    "laws",
    "load",
    "reduce",
    "run",
    "slump",
    "sweep",
    "vary",
]

__version__ = "0.1.0"
