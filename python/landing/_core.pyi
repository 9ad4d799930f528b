# Hand-written stubs of the Rust extension module (crates/landing_py). The public API is the
# Python package; its configuration classes compile their parameter tables into these handles
# once, and batches take the handles.
from collections.abc import Callable, Sequence
from typing import Any, Optional, Protocol, final

import numpy as np
import numpy.typing as npt
from typing_extensions import TypeAlias

__all__ = [
    "__version__", "Plant", "Law", "Reference", "Disturbance", "Gravity", "FuzzySystem", "simulate_batch",
    "cubic_from_boundary", "variable_rate_system_table", "kernel_levels", "default_kernel", "available_memory",
    "_panic_for_test", "fixed_time_bound", "practical_time_bound", "practical_radius", "mss_bounds",
    "min_final_time", "min_time_to_rest", "terminal_reaching_time", "terminal_reaching_time_printed",
    "fntsmc_ts_printed", "fntsmc_td_printed", "fntsmc_bounds",
    "philox4x64", "Dispersion", "DispersionHandle", "INTEGRATORS", "PLANT_KINDS", "CONTROLLER_KINDS",
    "GRAVITY_KINDS", "KERNEL_LEVELS", "EVENTS", "GRAVITATIONAL_CONSTANT", "DIVERGENCE_REASONS", "MAX_COMMAND", "LIMITS",
    "SCHEMAS", "METRICS",
]

__version__: str
INTEGRATORS: list[str]
PLANT_KINDS: list[str]
CONTROLLER_KINDS: list[str]
GRAVITY_KINDS: list[str]
KERNEL_LEVELS: list[str]
EVENTS: list[str]
GRAVITATIONAL_CONSTANT: float
#: The caps of landing_core::limits by name (docs/parameters.md, "Limits").
LIMITS: dict[str, int]
DIVERGENCE_REASONS: list[str]
MAX_COMMAND: float
#: What every kind of model declares, ``SCHEMAS[family][kind]["parameters"]``: for the
#: families "plant", "law", "gravity", "disturbance" (its component kinds, each with
#: ``"random"``: whether it draws random numbers), "reference", "dispersion" and "fuzzy" (the
#: Mamdani system's table, "mamdani", and its membership shapes). Each parameter is a dict
#: ``{"name", "shape", "unit", "rule", "required", "per_case", "doc"}``: shape one of "scalar",
#: "per_axis", "per_component", "choice", "flag", "count", "nested", "list", "fuzzy_system";
#: per_case whether it may be given one row per case (scalars, per-axis and a sensor's);
#: unit in SI ("1" dimensionless, "" not a number; "q" the plant's generalized coordinate, m or
#: rad); rule the inequality the core enforces ("" if only finiteness). A choice or a count
#: adds ``"choices"``; a nested table or a list adds ``"family"`` (the family of its kind), or
#: ``"family": None`` and ``"layout"`` (its parameters) for a fixed layout. The parameters are
#: exactly the keys of the Python class's table, in the order of its fields. In a list, an item
#: that is not a table is shorthand: a ``(kind, values)`` pair (a fuzzy set) for ``{"kind":
#: kind, "values": values}``, anything else (a fuzzy rule) for ``{"values": item}``.
SCHEMAS: dict[str, dict[str, dict[str, Any]]]
#: The per-case metric columns of a batch's output, in order: ``{"name", "unit", "per_axis",
#: "doc"}`` each (a per-axis column is (N, axes), the others (N,)).
METRICS: list[dict[str, Any]]

_Table: TypeAlias = dict[str, Any]
_Array: TypeAlias = npt.NDArray[np.float64]

@final
class Plant:
    """A compiled plant table (one case, or one per case)."""

    def __new__(cls, owner: str, table: _Table) -> Plant: ...
    @property
    def kind(self) -> str: ...
    @property
    def axes(self) -> int: ...
    @property
    def cases(self) -> int: ...
    def info(self) -> dict[str, Any]:
        """state_names, control_names, axes, max_step (the largest stable RK4 step over the
        cases, s) and the model's derived figures: for the tethered satellite inertia,
        orbital_rate, thrust_limit, torque_limit, and for the flexible model nodes and
        segment_length (of the first case)."""
    def coordinates(self, states: _Array) -> tuple[_Array, _Array]:
        """Generalized coordinates q and rates q' (each (M, axes)) of states (M, state dim)."""
    def state_at(self, rows: _Array) -> _Array:
        """States (M, state dim) from rows (q, q') of 2 axes values, for plants whose state
        they determine (the tethered satellite)."""
    def parameter(self, name: str, axes: int) -> _Array:
        """The numeric parameter ``name`` as the core reads it: (cases, axes) per axis, (cases,)
        for a scalar (cases = 1 when shared); ParameterError for another name."""

@final
class Law:
    """A compiled controller table, read for 3 and for 2 axes.

    Its ``kind`` is one of CONTROLLER_KINDS. Each kind reads the keys of its Python class's
    fields, except ``tabulated`` (``landing.controllers.Tabulated``), whose table is
    ``{"rows": [{"force": (axes,) or (N, axes)}, ...], "hold": whole number >= 1,
    "after": "hold" | "zero"}``: one table per row, every case the same number of rows.
    """

    def __new__(cls, owner: str, table: _Table) -> Law: ...
    @property
    def kind(self) -> str: ...
    @property
    def axes(self) -> list[int]:
        """The axis counts the law's parameters fit."""
    def diagnostic_layout(self, axes: int) -> list[tuple[str, int]]:
        """Names and widths of the law's recorded diagnostics for that many axes."""
    def parameter(self, name: str, axes: int) -> _Array:
        """The numeric parameter ``name`` as the law reads it for ``axes`` axes: (cases, axes)
        per axis, (cases,) for a scalar (cases = 1 when shared); ParameterError for another
        name."""

@final
class Reference:
    def __new__(cls, owner: str, table: _Table) -> Reference: ...
    def evaluate(self, axes: int, t: list[float]) -> dict[str, _Array]:
        """position, velocity and acceleration at times t, each (len(t), axes)."""
    def parameter(self, name: str, axes: int) -> _Array:
        """The numeric parameter ``name`` as the reference reads it (see Law.parameter)."""

@final
class Disturbance:
    def __new__(cls, owner: str, table: _Table) -> Disturbance:
        """From a table {"components": [component tables...]}."""
    @staticmethod
    def combine(parts: Sequence[Disturbance]) -> Disturbance:
        """The parts acting together (their components add up)."""
    def bound(self, axes: int) -> list[float]:
        """Per-axis bound on |d_i(t)|."""
    def parameter(self, name: str, axes: int) -> _Array:
        """The numeric parameter ``name`` of the one component that has it (see
        Law.parameter)."""

@final
class Gravity:
    def __new__(cls, owner: str, table: _Table) -> Gravity: ...
    @property
    def kind(self) -> str: ...
    def evaluate(self, positions: _Array, potential: bool) -> _Array:
        """Acceleration (N, 3) or potential (N,) at positions (N, 3)."""
    def parameter(self, name: str, axes: int) -> _Array:
        """The numeric parameter ``name`` as the field reads it (see Law.parameter)."""

@final
class FuzzySystem:
    def __new__(cls, table: _Table) -> FuzzySystem: ...
    def evaluate(self, inputs: _Array) -> _Array:
        """Crisp outputs (N,) for inputs (N, number of inputs)."""

@final
class Dispersion:
    def __new__(cls, table: _Table) -> Dispersion: ...
    @property
    def dim(self) -> int: ...
    def sample(self, seed: int, first_case: int, n: int, key: Optional[str] = None) -> _Array:
        """Cases first_case .. first_case + n, shape (n, components), of the initial states'
        stream or of the stream of the parameter named ``key``."""

#: The former name of :class:`Dispersion`.
DispersionHandle = Dispersion

class _PlantHooks(Protocol):
    """A plant written in Python (``landing._internal.user_plant.PlantStep``): its hooks
    ``(derivative, model, actuate, in_domain)``, None where absent, and its layout
    ``(n_state, positions, velocities, mass, altitude)``."""

    _hooks: tuple[Optional[Callable[..., _Array]], ...]
    _layout: tuple[int, list[int], list[int], Optional[int], Optional[int]]

def simulate_batch(
    plant: Plant | _PlantHooks,
    controller: Law | Callable[..., tuple[_Array, _Array]],
    x0: _Array,
    *,
    t_final: float,
    dt: float,
    integrator: str,
    substeps: int,
    reference: Optional[Reference],
    disturbance: Optional[Disturbance],
    record_every: int,
    seed: int,
    first_case: int,
    settle_tolerance: float,
    settle_relative: bool,
    chatter_cutoff: Optional[float],
    threads: Optional[int],
    kernel: Optional[str] = None,
    stop_at: Optional[str] = None,
    diagnostic_layout: Optional[list[tuple[str, int]]] = None,
    into: Optional[tuple[_Array, _Array, _Array]] = None,
) -> dict[str, Any]:
    """Run a batch. Returns t, states, controls, diagnostics, final_state, metrics (a dict of
    arrays), state_names, control_names, diagnostic_layout, axes and kernel (the level used).

    ``into``: float64 C-contiguous arrays (N, T, n_state), (N, T, axes) and (N, T, width) the
    recording is written into (and returned as states, controls and diagnostics) instead of
    fresh ones; a shape other than the batch's raises ParameterError before anything runs.

    ``controller`` is a compiled law, or a law computed in Python: a callable ``step(t, k,
    first, track, e, de, position, velocity, acceleration, drift, inertia)`` (each (m, axes) for
    the m cases from row ``first`` on, but t, k, first and track) with an int attribute
    ``cases_per_call``:
    a larger batch runs a slice of at most that many cases at a time through all its instants.
    Called once per control instant of a slice, it returns ``(command, diagnostics)``, float64
    (m, axes) and (m, width), with ``diagnostic_layout`` the names and widths of its signals.
    An exception it raises is raised as it is."""

def kernel_levels() -> list[str]:
    """The instruction-set levels this CPU supports, lowest first."""

def available_memory() -> Optional[int]:
    """Bytes of memory a new allocation can count on (None where the system does not say)."""

def default_kernel() -> str:
    """The level a batch runs at unless told otherwise."""

def cubic_from_boundary(
    p0: list[float], v0: list[float], pt: list[float], vt: list[float], t_end: float
) -> list[list[float]]:
    """Coefficients c0..c3 (each a list over axes) of the cubic through the boundary states."""

def variable_rate_system_table(resolution: int) -> _Table:
    """The variable-rate system of the fuzzy variable-rate asteroid paper as a Mamdani table."""

def philox4x64(counter: tuple[int, int, int, int], key: tuple[int, int]) -> list[int]:
    """One Philox4x64-10 block (the generator behind every random draw)."""

def fixed_time_bound(c1: float, e1: float, c2: float, e2: float) -> float:
    """The Mars fixed-time guidance paper's Lemma 2 (k = 1) for s' = -c1 sig^e1(s) - c2 sig^e2(s)."""

def practical_time_bound(c1: float, e1: float, c2: float, e2: float, theta: float) -> float:
    """The Mars paper's Theorem 1 (k = 1): time to reach the practical neighbourhood."""

def practical_radius(c1: float, e1: float, c2: float, e2: float, d_max: float, theta: float) -> float:
    """The Mars paper's eq. 38-39: radius of the practical neighbourhood."""

def mss_bounds(
    beta1: float, q1: float, beta2: float, q2: float,
    alpha1: float, gamma1: float, alpha2: float, gamma2: float,
    ap_max: float, theta1: float, theta2: float,
) -> dict[str, float]:
    """The Mars paper's Theorems 2-4 on one axis: t1, t2, s2_radius, s2_time, s1_radius, s1_time,
    printed_time, settle_time."""

def min_final_time(r0: float, v0: float, a_max: float, g: float) -> tuple[float, float]:
    """The Mars paper's Remark 1 (sign-consistent): (tf1, tf2) on one axis."""

def min_time_to_rest(r0: float, v0: float, a_max: float, g: float) -> float:
    """Shortest time to rest at 0 on one axis (time-optimal bang-bang)."""

def terminal_reaching_time(e0: float, alpha: float, beta: float, p: float, q: float) -> float:
    """The fuzzy fast-terminal asteroid paper's eq. 7 (eq. 5 at alpha = 0): time to reach e = 0 on
    the (fast) terminal surface."""

def terminal_reaching_time_printed(e0: float, alpha: float, beta: float, p: float, q: float) -> float:
    """The fast-terminal asteroid paper's eq. 7 (eq. 5 at alpha = 0) as printed: p and q swapped, negative for p < q."""

def fntsmc_ts_printed(c_v: float, alpha_s: float, beta_s: float) -> float:
    """The tethered-satellite paper's eq. 42 as printed, as a function of Lemma 2's constant c_v."""

def fntsmc_td_printed(k1: float, p1: float, k2: float, p2: float, d: float) -> float:
    """The tether paper's eq. 47 as printed (not a bound for eq. 21's exponents)."""

def fntsmc_bounds(
    k1: float, p1: float, k2: float, p2: float, k3: float, alpha_s: float, beta_s: float,
    sigma_phi: float, tol: float, d_max: float, theta: float,
) -> dict[str, float]:
    """Sound fixed-time bounds of the tether paper's FNTSMC on one axis: ts, s_radius, td, e1_radius,
    inside_rate, t_inside, total."""

def _panic_for_test() -> None:
    """Test hook: panics inside a guarded entry point (raises SimulationError)."""
