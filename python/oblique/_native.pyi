# Type stubs of the native module `oblique._native` (python/src/lib.rs). Private: use the
# functions and classes of `oblique` (python/oblique/__init__.py), which convert, broadcast
# and check shapes before calling these. Columns are contiguous 1-D float64 arrays of length 1
# (shared by every row) or rows (3 x rows for vectors).
from pathlib import Path
from typing import Callable, List, Optional, Sequence, Tuple

import numpy as np
from numpy.typing import NDArray

_F = NDArray[np.float64]

VERSION: str
EMBEDDED_TABLE: str
REBOUND3: List[str]
REBOUND2: List[str]
GROUPS: List[str]
IMPACT: List[str]
# The axes a table may have beyond gamma and alpha: (name, the value where a table lacks it).
EXTRA_AXES: List[Tuple[str, float]]
# (name, E (Pa), nu, density (kg/m^3) or None, source), in catalogue order.
MATERIALS: List[
    Tuple[str, float, float, Optional[float], str, Optional[float], Optional[float], str]
]

class TableError(OSError): ...

class Table:
    def __init__(self, path: str) -> None: ...
    @staticmethod
    def embedded() -> Table: ...
    def p(self, gamma: float, alpha: float, clamp: bool) -> float: ...
    def p_into(
        self, gamma: _F, alpha: _F, out: _F, clamp: bool, shape: Sequence[int]
    ) -> None: ...
    def axes(self) -> List[str]: ...
    def p_axes(
        self, gamma: float, alpha: float, names: List[str], values: List[float], clamp: bool
    ) -> float: ...
    def p_axes_into(
        self,
        gamma: _F,
        alpha: _F,
        names: List[str],
        columns: List[_F],
        out: _F,
        clamp: bool,
        shape: Sequence[int],
    ) -> None: ...
    def curve(self, gamma: float, clamp: bool) -> Curve: ...
    def info(self) -> dict: ...

class Curve:
    @property
    def gamma(self) -> float: ...
    @property
    def requested_gamma(self) -> float: ...
    @property
    def nbytes(self) -> int: ...
    def p(self, alpha: float) -> float: ...
    def p_into(self, alpha: _F, out: _F, shape: Sequence[int]) -> None: ...

def regime_into(gamma: _F, alpha: _F, e_n: _F, out: _F, shape: Sequence[int]) -> None: ...
def critical_into(gamma: _F, e_n: _F, out: _F, shape: Sequence[int]) -> None: ...
def e_t_into(p: _F, kappa: _F, out: _F, shape: Sequence[int]) -> None: ...
def rebound_3d(
    table: Table,
    rows: int,
    shape: Sequence[int],
    velocity: _F,
    spin: _F,
    other_velocity: _F,
    other_spin: _F,
    normal: _F,
    sphere: Sequence[_F],
    other: Sequence[_F],
    gamma: Optional[_F],
    materials: Sequence[_F],
    friction: _F,
    e_n: _F,
    clamp: bool,
) -> _F: ...
def rebound_2d(
    table: Table,
    rows: int,
    shape: Sequence[int],
    motion: Sequence[_F],
    sphere: Sequence[_F],
    other: Sequence[_F],
    gamma: Optional[_F],
    materials: Sequence[_F],
    friction: _F,
    e_n: _F,
    clamp: bool,
) -> _F: ...
def groups(
    rows: int,
    shape: Sequence[int],
    motion: Sequence[_F],
    sphere: Sequence[_F],
    other: Sequence[_F],
    materials: Sequence[_F],
    friction: _F,
) -> _F: ...
def impact(
    gamma: _F,
    alpha: _F,
    e_n: _F,
    rows: int,
    shape: Sequence[int],
    tol: float,
    simulate: bool,
    law: Optional[str],
) -> _F: ...
def simulate(
    motion: Sequence[_F],
    sphere: Sequence[_F],
    other: Sequence[_F],
    materials: Sequence[_F],
    friction: _F,
    tol: float,
    relaxation_time: Optional[float],
    yield_pressure: Optional[float],
) -> dict: ...
def build_table(
    config_text: str,
    config_name: str,
    config_path: Optional[str],
    output: Optional[str],
    resume: bool,
    restart: bool,
    threads: Optional[int],
    # (kind, step, steps, stage, detail, done, total, message)
    progress: Optional[Callable[[str, int, int, str, str, int, Optional[int], str], object]],
) -> Path: ...
