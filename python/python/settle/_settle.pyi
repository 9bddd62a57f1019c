"""Type stubs of the extension settle._settle (python/src/lib.rs)."""

from typing import Any, Callable, Dict, List, Optional, Tuple, Union

ProgressCallback = Callable[[str, int, Optional[int], str, str], None]
RawTable = Tuple[str, List[str], List[Union[bytearray, List[Optional[str]]]], List[str]]

TEXT_ORIGIN: str

class ScenarioError(ValueError):
    key: Optional[str]
    file: str

class UnstableError(RuntimeError): ...

def toml_text(value: Any) -> str: ...

class Scenario:
    @staticmethod
    def load(path: str) -> Scenario: ...
    @staticmethod
    def from_toml(text: str, origin: Optional[str] = None) -> Scenario: ...
    @staticmethod
    def from_dict(d: Dict[str, Any]) -> Scenario: ...
    def set(self, key: str, value: str) -> Scenario: ...
    def with_dt(self, dt_s: float) -> Scenario: ...
    def to_toml(self) -> str: ...
    def run(self, progress: Optional[ProgressCallback] = None, force: bool = False, threads: Optional[int] = None) -> RunResult: ...
    @property
    def name(self) -> str: ...
    @property
    def kind(self) -> str: ...
    @property
    def path(self) -> str: ...
    @property
    def overrides(self) -> List[str]: ...
    @property
    def dt_s(self) -> float: ...

class RunResult:
    def figure_names(self) -> List[str]: ...
    def figure(self, name: str) -> Optional[Dict[str, Any]]: ...
    @property
    def main_chart(self) -> str: ...
    def raw_tables(self) -> List[RawTable]: ...
    def csv(self, name: str) -> Optional[bytes]: ...
    def write(self, out_dir: str) -> str: ...
    @property
    def scenario(self) -> Scenario: ...
    @property
    def warnings(self) -> List[str]: ...
    @property
    def lines(self) -> List[str]: ...
    @property
    def status(self) -> str: ...
    @property
    def record(self) -> str: ...
    @property
    def wall_time_s(self) -> float: ...
    @property
    def steps(self) -> int: ...

class Output:
    def figure_names(self) -> List[str]: ...
    def figure(self, name: str) -> Optional[Dict[str, Any]]: ...
    def raw_tables(self) -> List[RawTable]: ...
    def csv(self, name: str) -> Optional[bytes]: ...
    def file_names(self) -> List[str]: ...
    def file(self, name: str) -> Optional[bytes]: ...
    def write(self, out_dir: str) -> str: ...
    @property
    def name(self) -> str: ...
    @property
    def warnings(self) -> List[str]: ...
    @property
    def lines(self) -> List[str]: ...

# --- sweep.rs: sweep, vary (keep this line: the sections below belong to separate files) ---

def sweep(
    scenario: Scenario,
    dt: Optional[List[float]] = None,
    dt_range: Optional[Tuple[float, float]] = None,
    per_decade: Optional[int] = None,
    integrators: Optional[List[str]] = None,
    tol: Optional[float] = None,
    progress: Optional[ProgressCallback] = None,
) -> Output: ...
def vary(
    scenario: Scenario,
    axes: List[Tuple[str, Union[str, List[str]]]],
    progress: Optional[ProgressCallback] = None,
) -> Output: ...
def sweep_cases(
    scenario: Scenario,
    dt: Optional[List[float]],
    dt_range: Optional[Tuple[float, float]],
    per_decade: Optional[int],
    integrators: Optional[List[str]],
    tol: Optional[float],
) -> int: ...
def sweep_part(
    scenario: Scenario,
    dt: Optional[List[float]],
    dt_range: Optional[Tuple[float, float]],
    per_decade: Optional[int],
    integrators: Optional[List[str]],
    tol: Optional[float],
    index: int,
    count: int,
) -> str: ...
def sweep_merge(
    scenario: Scenario,
    dt: Optional[List[float]],
    dt_range: Optional[Tuple[float, float]],
    per_decade: Optional[int],
    integrators: Optional[List[str]],
    tol: Optional[float],
    parts: List[Tuple[int, int, str]],
) -> Output: ...
def vary_cases(scenario: Scenario, axes: List[Tuple[str, Union[str, List[str]]]]) -> int: ...
def vary_part(
    scenario: Scenario,
    axes: List[Tuple[str, Union[str, List[str]]]],
    index: int,
    count: int,
) -> str: ...
def vary_merge(
    scenario: Scenario,
    axes: List[Tuple[str, Union[str, List[str]]]],
    parts: List[Tuple[int, int, str]],
) -> Output: ...

# --- end of sweep.rs ---

# --- lab.rs: reduce, invert, laws ---

# Readings: a file's path, or (name, header, rows of text cells, [(key, value)] figures).
LabReadings = Union[str, Tuple[str, List[str], List[List[str]], List[Tuple[str, str]]]]

def reduce(
    readings: LabReadings,
    standard: Optional[str] = None,
    hydrometer: Optional[str] = None,
    out: Optional[str] = None,
) -> Output: ...
def invert(
    readings: List[LabReadings],
    model: str = "ideal-stokes",
    bins: Optional[int] = None,
    diameters_um: Optional[str] = None,
    lambda_: str = "discrepancy",
    resolution: List[float] = ...,
    repeats: int = 100,
    seed: int = 1,
    bounds: Optional[float] = None,
    out: Optional[str] = None,
) -> Output: ...
def laws(
    spheres: Optional[str] = None,
    fluids: Optional[str] = None,
    out: Optional[str] = None,
) -> Output: ...

# --- end of lab.rs ---

# --- fit.rs: fit ---

def fit(
    scenario: Scenario,
    bounds: List[Tuple[str, float, float]],
    measured_path: Optional[str] = None,
    measured_csv: Optional[Tuple[str, str]] = None,
    progress: Optional[ProgressCallback] = None,
) -> Output: ...
def slump(height_mm: float, slump_mm: List[float], density: float, g: float) -> Dict[str, Any]: ...

# --- end of fit.rs ---
