# Hand-written stubs of the Rust extension module (crates/landing_py). The public API is the
# Python package; these functions take the parameter tables its classes build.
from typing import Any, Optional

import numpy as np
import numpy.typing as npt

__version__: str
INTEGRATORS: list[str]
PLANT_KINDS: list[str]
CONTROLLER_KINDS: list[str]

Table = dict[str, Any]

def simulate_batch(
    plant: Table,
    controller: Table,
    x0: npt.NDArray[np.float64],
    *,
    t_final: float,
    dt: float,
    integrator: str,
    substeps: int,
    reference: Optional[Table],
    disturbance: Optional[Table],
    record_every: int,
    seed: int,
    first_case: int,
    threads: Optional[int],
) -> dict[str, Any]:
    """Run a batch. Returns t, states, controls, diagnostics, final_state, metrics (a dict of
    arrays), state_names, control_names, diagnostic_names and axes."""

def check_plant(owner: str, table: Table) -> int:
    """Validate a plant table; returns its number of axes."""

def check_controller(owner: str, table: Table) -> None:
    """Validate a controller table."""

def check_signal(owner: str, what: str, table: Table) -> None:
    """Validate a reference (what="reference") or disturbance (what="disturbance") table."""

def evaluate_reference(table: Table, axes: int, t: list[float]) -> dict[str, npt.NDArray[np.float64]]:
    """Position, velocity and acceleration of a reference at times t, each (len(t), axes)."""

def cubic_from_boundary(
    p0: list[float], v0: list[float], pt: list[float], vt: list[float], t_end: float
) -> list[list[float]]:
    """Coefficients c0..c3 (each a list over axes) of the cubic through the boundary states."""

def plant_info(kind: str) -> dict[str, Any]:
    """state_names, control_names and axes of a plant kind."""

def philox4x64(counter: tuple[int, int, int, int], key: tuple[int, int]) -> list[int]:
    """One Philox4x64-10 block (the generator behind every random draw)."""
