"""Type hints of the extension module (python/src): what the package re-exports and what
touchdown.sweep, trace and report call."""

import os
from typing import Any, Dict, List, Optional, Tuple, Union

import numpy as np
import numpy.typing as npt
import pyarrow as pa

#: A whole number as the command line takes one: an int, a float that is whole (1e5) or a
#: string ("1e5", "2.5e5", "1_000").
_Whole = Union[int, float, str]

ENGINE: str
DEFAULT_TOML: str

class TouchdownError(Exception): ...
class ScenarioError(ValueError): ...

class Scenario:
    @staticmethod
    def default() -> Scenario: ...
    @staticmethod
    def load(path: Union[str, os.PathLike[str]]) -> Scenario: ...
    @staticmethod
    def from_toml(text: str) -> Scenario: ...
    def to_toml(self) -> str: ...
    def keys(self) -> List[str]: ...
    def copy(self) -> Scenario: ...
    def __getitem__(self, key: str) -> Any: ...
    def __setitem__(self, key: str, value: Any) -> None: ...
    def __delitem__(self, key: str) -> None: ...
    def __contains__(self, key: str) -> bool: ...
    def __eq__(self, other: object) -> bool: ...

class Sensed:
    t_s: npt.NDArray[np.float64]
    attitude: npt.NDArray[np.float64]
    rate_rad_s: npt.NDArray[np.float64]
    velocity_m_s: npt.NDArray[np.float64]
    altitude_m: npt.NDArray[np.float64]
    contact: npt.NDArray[np.bool_]
    touching: npt.NDArray[np.bool_]
    def __len__(self) -> int: ...

class SweepRun:
    def __init__(
        self,
        scenario_toml: str,
        samples: Optional[_Whole] = None,
        seed: Optional[_Whole] = None,
        threads: Optional[_Whole] = None,
        design: Optional[str] = None,
        inputs: Optional[str] = None,
        keep_columns: bool = False,
        out: Optional[str] = None,
        format: Optional[str] = None,
        kernel: Optional[str] = None,
        keep: bool = True,
    ) -> None: ...
    def wait(self, seconds: float) -> bool: ...
    def stop(self) -> None: ...
    @property
    def done(self) -> int: ...
    @property
    def total(self) -> int: ...
    @property
    def out(self) -> Optional[str]: ...
    def result(self) -> Optional[pa.RecordBatchReader]: ...

def register_law(name: str, law: Any) -> None: ...
def registered_laws() -> List[str]: ...
def trace(
    sample: _Whole,
    every: Optional[_Whole] = None,
    scenario_toml: Optional[str] = None,
    seed: Optional[_Whole] = None,
    sweep: Optional[str] = None,
    metadata: Optional[Dict[str, str]] = None,
    inputs: Optional[str] = None,
) -> Tuple[str, pa.RecordBatchReader]: ...
def report(
    path: Optional[str] = None,
    table: Optional[pa.Table] = None,
    slope_distribution: Optional[str] = None,
    json: bool = True,
) -> str: ...
