"""Type stubs of persson_check (the Rust extension persson_check._native and its wrappers)."""

import os
from collections.abc import Callable, Iterator, Sequence
from typing import Any, Literal, Optional, Union

import numpy as np
import numpy.typing as npt

__version__: str
SOLVERS: tuple[str, ...]
# The defaults of solve and sweep, and check_surface's, read from the library: the stubs
# below write them as `...` (a test checks that the runtime signatures take these values).
DEFAULT_SOLVER: str
DEFAULT_TOL: float
DEFAULT_MAX_ITER: int

Array2 = npt.NDArray[np.float64]
Progress = Callable[[int, float], object]
# The names of SOLVERS, in its order (a test keeps the two in step).
SolverName = Literal["gfmd", "cg", "fire"]
SolverNames = Union[SolverName, Sequence[SolverName], None]
Names = Union[str, Sequence[str], None]
Path = Union[str, os.PathLike[str]]

class SolveError(RuntimeError):
    """A solve that stopped before its tolerance, or a load search that found no load."""

class Solution:
    """The result of :func:`solve`: fields as arrays and summary.json's values."""

    pressure: Array2
    displacement: Array2
    gap: Array2
    heights: Array2
    n: int
    contact_area: float
    p0: float
    elastic_energy: float
    mean_gap: float
    iterations: int
    residual: float
    termination: str
    solver: str
    wall_s: float
    zeta: float
    rms_gradient: float
    reduced_pressure: float
    e_star: float
    tol: float
    load_solves: int
    source: str
    residual_components: dict[str, float]
    tamaas_error: float
    def summary(self) -> dict[str, Any]:
        """The summary values as a dict with summary.json's keys and values."""

class SweepStep:
    """One magnification step of :func:`sweep`."""

    step: int
    zeta: float
    p0: float
    contact_area: float
    elastic_energy: float
    mean_gap: float
    rms_gradient: float
    iterations: int
    residual: float
    wall_s: float
    pressure: Optional[Array2]
    gap: Optional[Array2]

class Sweep(Iterator[SweepStep]):
    """A magnification sweep, one warm-started solve per step; ``len()`` is its step count."""

    @property
    def zetas(self) -> npt.NDArray[np.float64]: ...
    def __iter__(self) -> Sweep: ...
    def __next__(self) -> SweepStep: ...
    def __len__(self) -> int: ...
    def close(self) -> None:
        """Stops the sweep; the iterator is then exhausted."""

class Theory:
    """Persson's theory at one load on one surface's spectrum."""

    @property
    def p0(self) -> float: ...
    @property
    def variant(self) -> str: ...
    @property
    def zeta_max(self) -> float: ...
    def contact_area(self, zeta: Optional[float] = None) -> float: ...
    def non_contact_area(self, zeta: Optional[float] = None) -> float: ...
    def total_broadening(self, zeta: Optional[float] = None) -> float: ...
    def correction_factor(self, zeta: Optional[float] = None) -> float: ...
    def elastic_energy(self, zeta: Optional[float] = None) -> float: ...
    def pressure_density(
        self, p: Sequence[float] | npt.ArrayLike, zeta: Optional[float] = None
    ) -> npt.NDArray[np.float64]: ...
    def pressure_cdf(
        self, p: Sequence[float] | npt.ArrayLike, zeta: Optional[float] = None
    ) -> npt.NDArray[np.float64]: ...
    def shells(self) -> dict[str, npt.NDArray[np.float64]]: ...

def surface(
    n: int,
    hurst: float,
    lambda_l: float,
    lambda_s: float,
    seed: int,
    zeta: Optional[float] = None,
) -> Array2:
    """An n x n self-affine surface, the command line's realization bit for bit."""

def solve(
    heights: npt.ArrayLike,
    p0: Optional[float] = None,
    contact_area: Optional[float] = None,
    solver: SolverName = ...,
    tol: float = ...,
    lambda_l: Optional[float] = None,
    threads: Optional[int] = None,
    zeta: Optional[float] = None,
    max_iter: int = ...,
    progress: Optional[Progress] = None,
) -> Solution:
    """Hard-wall contact on a square height array at p0 or at a target contact area."""

def sweep(
    heights: npt.ArrayLike,
    p0: Optional[float] = None,
    contact_area: Optional[float] = None,
    zeta_from: float = 1.0,
    zeta_to: Optional[float] = None,
    zetas: Optional[Sequence[float]] = None,
    solver: SolverName = ...,
    tol: float = ...,
    lambda_l: Optional[float] = None,
    threads: Optional[int] = None,
    fields: bool = False,
    max_iter: int = ...,
    progress: Optional[Progress] = None,
) -> Sweep:
    """A magnification sweep as an iterator of SweepStep."""

def theory(
    heights: npt.ArrayLike,
    p0: float,
    variant: Literal["original", "yang_persson", "corrected", "wang_mueser"] = "original",
    lambda_l: Optional[float] = None,
    e_star: float = 1.0,
) -> Theory:
    """Persson's theory at p0 on the spectrum of heights."""

def contact_area_law(p_reduced: float) -> float:
    """The paper's empirical contact-area law at reduced pressure p0 / (E* g_bar)."""

def validate(
    names: Names = None,
    out: Path = "out",
    full: bool = False,
    solver: SolverNames = None,
    resume: bool = False,
    dir: Optional[Path] = None,
    threads: Optional[int] = None,
) -> list[dict[str, Any]]:
    """Runs validations; returns their outcomes (the keys of <name>.json)."""

def plan(
    names: Names = None,
    shards: Optional[int] = None,
    full: bool = False,
    solver: SolverNames = None,
    out: Optional[Path] = None,
    dir: Optional[Path] = None,
) -> dict[str, Any]:
    """The jobs of validations with their estimated costs (and shares)."""

def merge(
    names: Names = None,
    out: Path = "out",
    full: bool = False,
    solver: SolverNames = None,
    accept_other_commit: bool = False,
    dir: Optional[Path] = None,
    partial: bool = False,
) -> list[dict[str, Any]]:
    """The outcomes from the job results that shares stored under out/jobs/ (with
    partial, without the optional parts of a scene whose jobs are not all in)."""

def report(
    source: Path = "out",
    out: Path = "scorecard.md",
    golden: Optional[Path] = None,
) -> dict[str, Any]:
    """Writes the Markdown scorecard of the outcomes in source (which it only reads)."""

def check_surface(
    heights: Union[npt.ArrayLike, Any, Sequence[Union[npt.ArrayLike, Any]]],
    pixel_size: Optional[Union[float, tuple[float, float]]] = None,
    periodic: bool = False,
    loads: Optional[Sequence[float]] = None,
    solver: SolverName = ...,
    cross_check: bool = True,
    tol: float = ...,
    out: Optional[Path] = None,
    threads: Optional[int] = None,
    progress: Optional[Progress] = None,
    unit: Optional[str] = None,
    modulus: Optional[float] = None,
    fill: Literal["none", "interpolate"] = "none",
    reentry: bool = True,
    verbose: bool = True,
    cross_check_all: bool = False,
    line: bool = False,
    line_side: int = ...,
    line_seeds: int = ...,
    max_iterations: int = ...,
    despike: Optional[float] = None,
    extrapolate: bool = True,
    cutoff: bool = True,
    tip_radius: Optional[float] = None,
    scales: bool = False,
) -> dict[str, Any]:
    """Persson's theory checked on measured height maps or line scans (surface.json as a
    dict); with scales=True, one surface measured at several scales (scales.json)."""
