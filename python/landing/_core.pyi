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
    settle_tolerance: float,
    settle_relative: bool,
    chatter_cutoff: Optional[float],
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

def plant_info(kind: str, table: Optional[Table] = None) -> dict[str, Any]:
    """state_names, control_names and axes of a plant kind; with its table (required for a
    tethered_satellite, whose layout depends on its node count) also, for the tethered
    satellite, inertia, orbital_rate, thrust_limit, torque_limit, max_step and, for the flexible
    model, nodes and segment_length."""

def plant_coordinates(
    table: Table, states: npt.NDArray[np.float64]
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """Generalized coordinates q and rates q' (each (M, axes)) of states (M, state dim)."""

def tether_initial_state(table: Table, angles: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
    """States (M, state dim) of a tethered satellite from rows (phi, theta, phi_dot, theta_dot)."""

def philox4x64(counter: tuple[int, int, int, int], key: tuple[int, int]) -> list[int]:
    """One Philox4x64-10 block (the generator behind every random draw)."""

def fixed_time_bound(c1: float, e1: float, c2: float, e2: float) -> float:
    """Seed 001 Lemma 2 (k = 1) for s' = -c1 sig^e1(s) - c2 sig^e2(s)."""

def practical_time_bound(c1: float, e1: float, c2: float, e2: float, theta: float) -> float:
    """Seed 001 Theorem 1 (k = 1): time to reach the practical neighbourhood."""

def practical_radius(c1: float, e1: float, c2: float, e2: float, d_max: float, theta: float) -> float:
    """Seed 001 eq. 38-39: radius of the practical neighbourhood."""

def mss_bounds(
    beta1: float, q1: float, beta2: float, q2: float,
    alpha1: float, gamma1: float, alpha2: float, gamma2: float,
    ap_max: float, theta1: float, theta2: float,
) -> dict[str, float]:
    """Seed 001 Theorems 2-4 on one axis: t1, t2, s2_radius, s2_time, s1_radius, s1_time,
    printed_time, settle_time."""

def min_final_time(r0: float, v0: float, a_max: float, g: float) -> tuple[float, float]:
    """Seed 001 Remark 1 (sign-consistent): (tf1, tf2) on one axis."""

def min_time_to_rest(r0: float, v0: float, a_max: float, g: float) -> float:
    """Shortest time to rest at 0 on one axis (time-optimal bang-bang)."""

def sample_dispersion(table: Table, seed: int, first_case: int, n: int) -> npt.NDArray[np.float64]:
    """Cases first_case .. first_case + n of a dispersion, shape (n, components)."""

def check_dispersion(table: Table) -> int:
    """Validate a dispersion table; returns its number of components."""

def disturbance_bound(table: Table, axes: int) -> list[float]:
    """Per-axis bound on |d_i(t)| of a disturbance table."""

GRAVITATIONAL_CONSTANT: float
GRAVITY_KINDS: list[str]

def evaluate_gravity(table: Table, positions: npt.NDArray[np.float64], potential: bool) -> npt.NDArray[np.float64]:
    """Acceleration (N, 3) or potential (N,) of a gravity table at positions (N, 3)."""

def check_gravity(owner: str, table: Table) -> None:
    """Validate a gravity table."""

def evaluate_fuzzy(table: Table, inputs: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
    """Crisp outputs (N,) of a Mamdani table for inputs (N, number of inputs)."""

def check_fuzzy(table: Table) -> None:
    """Validate a Mamdani table."""

def variable_rate_system_table(resolution: int) -> Table:
    """The seed-002 variable-rate system as a Mamdani table."""
def fntsmc_ts_printed(c_v: float, alpha_s: float, beta_s: float) -> float:
    """Seed 003 eq. 42 as printed, as a function of Lemma 2's constant c_v."""

def fntsmc_td_printed(k1: float, p1: float, k2: float, p2: float, d: float) -> float:
    """Seed 003 eq. 47 as printed (not a bound for eq. 21's exponents)."""

def fntsmc_bounds(
    k1: float, p1: float, k2: float, p2: float, k3: float, alpha_s: float, beta_s: float,
    sigma_phi: float, tol: float, d_max: float, theta: float,
) -> dict[str, float]:
    """Sound fixed-time bounds of the seed-003 FNTSMC on one axis: ts, s_radius, td, e1_radius,
    inside_rate, t_inside, total."""
