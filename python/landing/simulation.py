"""Batched rollouts: :func:`simulate_batch` and :func:`simulate`."""

from __future__ import annotations

import dataclasses
import warnings
from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType
from typing import Any, ClassVar, Optional

import numpy as np

from landing import _core
from landing._internal.args import choice, integer, real, real_array
from landing._internal.limits import LIMITS
from landing._internal.user_law import LawStep, per_axis
from landing.controllers import Controller, PythonLaw
from landing.disturbances import DisturbanceLike, compiled
from landing.errors import DivergenceWarning, ParameterError, ParameterTypeError
from landing.plants import Plant, PythonPlant
from landing.reference import Reference
from landing.results import Metrics, SimulationResult, describe_diverged

__all__ = ["MAX_COMMAND", "RunOptions", "kernel_levels", "simulate_batch", "simulate"]

MAX_COMMAND: float = _core.MAX_COMMAND
#: The diagnostics a run records for a plant with a sensor (landing.sensors): the position and
#: velocity the law read (the measurement, or the filter's estimate), per axis.
ESTIMATES: tuple[str, ...] = ("estimated_position", "estimated_velocity")
"""Largest magnitude of a command component a case may apply before it is stopped."""


def kernel_levels() -> list[str]:
    """The instruction-set levels of the compiled kernel this CPU runs, lowest first (every
    level gives the same bits; ``simulate_batch(..., kernel=...)`` forces one).

    Returns
    -------
    list of str
        The levels, such as ``["baseline", "avx2", "avx512"]`` on x86-64.

    Examples
    --------
    >>> kernel_levels()[0]
    'baseline'
    """
    return list(_core.kernel_levels())


@dataclass(frozen=True)
class RunOptions:
    """How a batch runs: its horizon and step, the integrator, what is recorded and how the
    settle and chattering metrics are measured, and the machine's share of it (threads, the
    kernel level). The keywords of :func:`simulate_batch` of the same names, which builds one;
    a :class:`~landing.scenarios.Scenario` holds one for its settings.

    Checked when made, each field by the rule the messages name (``t_final = 0 violates
    t_final > 0``), and the step count t_final / dt against the core's cap; what else relates
    them (t_final a whole number of steps, the cut-off below the Nyquist frequency) the core
    checks when it runs them. ``options.replace(dt=1e-2)`` is a
    copy, checked again.

    Parameters
    ----------
    t_final : float
        Horizon, s; > 0, a whole number of control periods.
    dt : float
        Control period, s; > 0.
    integrator : str
        ``"rk4"`` (default) or ``"euler"``.
    substeps : int
        Integrator steps per control period, >= 1.
    record_every : int
        Keep every k-th control instant, >= 0 (0: only the final states and the metrics).
    settle_tolerance : float or None
        Tolerance on the tracking-error norm behind ``settle_time``, units of q (None: 2 % of
        the initial error norm).
    chatter_cutoff : float or None
        Cut-off frequency of the chattering metric's high-pass filter, Hz (None: 1 / (20 dt)).
    threads : int or None
        Worker threads, >= 1 (None: all cores).
    kernel : str or None
        One of :func:`kernel_levels` (None: ``LANDING_KERNEL``, else the best).
    stop_at : str or None
        ``"touchdown"`` to end each case at its touchdown, or None.

    Raises
    ------
    ParameterError
        If a field breaks its rule, or t_final / dt exceeds the core's step cap.
    ParameterTypeError
        If a field has the wrong type.

    Examples
    --------
    >>> RunOptions(t_final=10.0, dt=0.01).replace(dt=0.02).dt
    0.02
    >>> RunOptions(t_final=0.0, dt=0.01)
    Traceback (most recent call last):
        ...
    landing.errors.ParameterError: t_final = 0 violates t_final > 0
    """

    t_final: float
    dt: float
    integrator: str = "rk4"
    substeps: int = 1
    record_every: int = 1
    settle_tolerance: Optional[float] = None
    chatter_cutoff: Optional[float] = None
    threads: Optional[int] = None
    kernel: Optional[str] = None
    stop_at: Optional[str] = None

    #: The least value of each count (a scenario file's reader names it when a count is not
    #: written as an integer).
    MINIMUM: ClassVar[Mapping[str, int]] = MappingProxyType({"substeps": 1, "record_every": 0, "threads": 1})

    def __post_init__(self) -> None:
        least = self.MINIMUM
        checked: dict[str, Any] = {
            "t_final": real("t_final", self.t_final, positive=True),
            "dt": real("dt", self.dt, positive=True),
            "integrator": choice("integrator", self.integrator, tuple(_core.INTEGRATORS)),
            "substeps": integer("substeps", self.substeps, minimum=least["substeps"], cap="max_substeps"),
            "record_every": integer("record_every", self.record_every, minimum=least["record_every"],
                                    maximum=2**63 - 1),
        }
        steps = checked["t_final"] / checked["dt"]
        if steps > LIMITS["max_steps"]:
            # the core's cap, checked here too so that a campaign's memory estimate never sees it
            raise ParameterError(
                f"t_final = {checked['t_final']:g} violates t_final / dt <= 2^{LIMITS['max_steps'].bit_length() - 1} "
                f"(max_steps; dt = {checked['dt']:g}: {steps:.3g} steps); see landing._core.LIMITS")
        if self.settle_tolerance is not None:
            # 0 is a tolerance too (settled means exactly on the reference); None is relative
            checked["settle_tolerance"] = real("settle_tolerance", self.settle_tolerance, nonnegative=True)
        if self.chatter_cutoff is not None:
            checked["chatter_cutoff"] = real("chatter_cutoff", self.chatter_cutoff, positive=True)
        if self.threads is not None:
            checked["threads"] = integer("threads", self.threads, minimum=least["threads"], cap="max_threads")
        if self.kernel is not None:
            if not isinstance(self.kernel, str):
                raise ParameterTypeError(f"kernel must be a string or None, got {self.kernel!r}")
            choice("kernel", self.kernel, tuple(_core.KERNEL_LEVELS))
        if self.stop_at is not None:
            if not isinstance(self.stop_at, str):
                raise ParameterTypeError(f"stop_at must be a string or None, got {self.stop_at!r}")
            choice("stop_at", self.stop_at, tuple(_core.EVENTS))
        # the checked Python values (a numpy integer becomes an int): what the core is given
        for name, value in checked.items():
            object.__setattr__(self, name, value)

    @property
    def settle_relative(self) -> bool:
        """Whether the settle tolerance is relative: 2 % of the initial error norm, the
        default (``settle_tolerance`` None)."""
        return self.settle_tolerance is None

    def replace(self, **changes: Any) -> RunOptions:
        """A copy with some options changed, checked like a new one."""
        return dataclasses.replace(self, **changes)

    def keywords(self) -> dict[str, Any]:
        """These options as the keyword arguments of :func:`simulate_batch`."""
        return {f.name: getattr(self, f.name) for f in dataclasses.fields(self)}

    def _core_arguments(self) -> dict[str, Any]:
        return dict(
            t_final=self.t_final, dt=self.dt, integrator=self.integrator, substeps=self.substeps,
            record_every=self.record_every,
            settle_tolerance=0.02 if self.settle_tolerance is None else self.settle_tolerance,
            settle_relative=self.settle_relative, chatter_cutoff=self.chatter_cutoff, threads=self.threads,
            kernel=self.kernel, stop_at=self.stop_at,
        )


def simulate_batch(
    plant: Plant,
    controller: Controller,
    x0: Any,
    *,
    t_final: float,
    dt: float,
    integrator: str = "rk4",
    substeps: int = 1,
    reference: Optional[Reference] = None,
    disturbance: DisturbanceLike = None,
    record_every: int = 1,
    seed: int = 0,
    first_case: int = 0,
    settle_tolerance: Optional[float] = None,
    chatter_cutoff: Optional[float] = None,
    threads: Optional[int] = None,
    kernel: Optional[str] = None,
    stop_at: Optional[str] = None,
) -> SimulationResult:
    """Simulate N cases of ``plant`` under ``controller`` in parallel (the semantics: docs/guide/semantics.md).

    Parameters
    ----------
    plant : Plant
        A :mod:`landing.plants` plant; its numeric parameters may be per case.
    controller : Controller
        A :mod:`landing.controllers` law; its gains may be per case.
    x0 : ArrayLike
        Shape (N, n_state): initial states, one row per case, in the plant's units (q, q/s,
        and kg for a lander's mass).
    t_final : float
        Horizon, s; a whole number of control periods.
    dt : float
        Control period, s. The command is computed from the state at t_k, saturated, and held
        over ``[t_k, t_k + dt)``.
    integrator : str
        ``"rk4"`` or ``"euler"``.
    substeps : int
        Integrator steps per control period.
    reference : Reference or None
        Target the law tracks (default: the origin at rest).
    disturbance : Disturbance, list of Disturbance or None
        Unknown disturbance (a component, a sum or a list of components).
    record_every : int
        Keep every k-th control instant (always the first and the last); 0 keeps only the
        final states and the metrics.
    seed : int
        Seed of the counter-based random streams; case i's numbers depend only on
        (seed, first_case + i), never on the thread count or the batch size.
    first_case : int
        Global index of the first case, so that a slice of a campaign run alone (or in
        chunks) draws the same random numbers as in the whole batch.
    settle_tolerance : float or None
        The tolerance on the tracking-error norm |q - q_ref| behind ``metrics["settle_time"]``
        (the first control instant from which the error stays within it), in units of q; None
        for 2 % of the initial error norm.
    chatter_cutoff : float or None
        Cut-off frequency (Hz) of the high-pass filter behind
        ``metrics["chattering_hf_share"]``; None for a tenth of the Nyquist frequency,
        1 / (20 dt).
    threads : int or None
        Worker threads (default: all cores).
    kernel : str or None
        The instruction-set level of the compiled kernel, one of
        ``landing.kernel_levels()`` (``"baseline"``, ``"avx2"``, ``"avx512"`` on x86-64); the
        default is the ``LANDING_KERNEL`` environment variable, else the best this CPU has. Every
        level gives the same bits; forcing one is for testing and benchmarking.
    stop_at : str or None
        An event that ends each case, or None to run every case to ``t_final``.
        ``"touchdown"`` (a plant with an altitude: the landers) ends a case at its first
        crossing of the ground, ``rz = 0``, located inside the integrator step (on the step's
        cubic Hermite interpolant, to 1e-12 of the step): the case is then frozen in its state
        there (its final state), no fuel is burnt and no metric accumulates after the control
        period of the event, and its recorded signals are NaN from the next recorded instant.
        ``metrics["touchdown_time"]``, ``touchdown_position`` and ``touchdown_velocity`` are
        the event's.

    Returns
    -------
    SimulationResult
        ``t`` (T,) in s, ``states`` (N, T, n_state), ``controls`` and the ``metrics`` by name,
        one value (or row) per case. Cases whose state leaves the model's domain are stopped,
        flagged in ``metrics["diverged"]`` and reported with a
        :class:`~landing.errors.DivergenceWarning`.

    Raises
    ------
    ParameterError
        If an argument breaks its rule (``x0`` not of shape (N, n_state), ``t_final`` not a
        whole number of periods, a per-case parameter with the wrong number of rows...).
    ParameterTypeError
        If an argument has the wrong type.
    UserFunctionError
        If a function given in Python (a :class:`~landing.controllers.PythonLaw`'s) fails.

    Examples
    --------
    >>> import numpy as np, landing
    >>> from landing.controllers import PDSlidingMode
    >>> law = PDSlidingMode(lambda_=1.0, k=0.5, switch="sat", boundary_layer=0.1)
    >>> x0 = np.zeros((4, 6))
    >>> x0[:, 0] = [1.0, 2.0, 5.0, 10.0]
    >>> r = simulate_batch(landing.plants.DoubleIntegrator(), law, x0, t_final=10.0, dt=0.01,
    ...                    record_every=10)
    >>> r.t.shape, r.states.shape
    ((101,), (4, 101, 6))
    >>> print(" ".join(f"{e:.3f}" for e in r.metrics["final_position_error"]))
    0.000 0.001 0.500 5.497
    """
    return simulate_batch_into(
        None, plant, controller, x0,
        t_final=t_final, dt=dt, integrator=integrator, substeps=substeps, reference=reference,
        disturbance=disturbance, record_every=record_every, seed=seed, first_case=first_case,
        settle_tolerance=settle_tolerance, chatter_cutoff=chatter_cutoff, threads=threads, kernel=kernel,
        stop_at=stop_at,
    )


def simulate_batch_into(
    into: Optional[tuple[np.ndarray, np.ndarray, np.ndarray]],
    plant: Plant,
    controller: Controller,
    x0: Any,
    *,
    t_final: float,
    dt: float,
    integrator: str = "rk4",
    substeps: int = 1,
    reference: Optional[Reference] = None,
    disturbance: DisturbanceLike = None,
    record_every: int = 1,
    seed: int = 0,
    first_case: int = 0,
    settle_tolerance: Optional[float] = None,
    chatter_cutoff: Optional[float] = None,
    threads: Optional[int] = None,
    kernel: Optional[str] = None,
    stop_at: Optional[str] = None,
) -> SimulationResult:
    """:func:`simulate_batch` with its recording written into ``into`` when given: float64
    C-contiguous arrays (N, T, n_state), (N, T, axes) and (N, T, the diagnostics' widths side
    by side), which become the result's states, controls and diagnostics (views of the third);
    a campaign lends each chunk its rows of the campaign's output this way
    (``landing.campaign``). Arrays of another shape raise ParameterError before anything runs."""
    x = _as_states(x0)
    if x.ndim != 2:
        raise ParameterError(
            f"x0 has shape {x.shape}; simulate_batch takes (N, n_state) "
            f"(use landing.simulate for one case)"
        )
    if not isinstance(plant, Plant):
        raise ParameterTypeError(f"plant must be a landing.plants plant, got {type(plant).__name__}")
    if not isinstance(controller, Controller):
        raise ParameterTypeError(
            f"controller must be a landing.controllers law, got {type(controller).__name__}"
        )
    if reference is not None and not isinstance(reference, Reference):
        raise ParameterTypeError(
            f"reference must be a landing.reference reference or None, got {type(reference).__name__}"
        )
    options = RunOptions(t_final=t_final, dt=dt, integrator=integrator, substeps=substeps, record_every=record_every,
                         settle_tolerance=settle_tolerance, chatter_cutoff=chatter_cutoff, threads=threads,
                         kernel=kernel, stop_at=stop_at)
    seed_i = integer("seed", seed, minimum=0, maximum=2**64 - 1)
    first = integer("first_case", first_case, minimum=0, maximum=2**63 - 1)
    integer("x0 cases N", x.shape[0], cap="max_cases")
    arguments = dict(
        reference=None if reference is None else reference._core,
        disturbance=compiled(disturbance),
        seed=seed_i,
        first_case=first,
        # a campaign's rows of its output, which the recording is written into (Assembly)
        into=into,
        **options._core_arguments(),
    )
    # a plant written in Python is handed over as its hooks for this batch
    core_plant = plant._step(x.shape[0], first) if isinstance(plant, PythonPlant) else plant._core
    if isinstance(controller, PythonLaw):
        step, layout = _python_step(controller, plant, x.shape[0], first)
        out = _core.simulate_batch(core_plant, step, x, diagnostic_layout=layout, **arguments)
    else:
        out = _core.simulate_batch(core_plant, controller._core, x, **arguments)
    if isinstance(plant, PythonPlant):
        out["state_names"], out["control_names"] = plant.state_names, plant.control_names
    diag = out["diagnostics"]
    diagnostics = {}
    offset = 0
    layout = list(out["diagnostic_layout"])
    if getattr(plant, "sensor", None) is not None:
        # the core records the estimate the law read after the law's own signals
        layout += [(name, out["axes"]) for name in ESTIMATES]
    for name, width in layout:
        # per-axis signals keep their axis, scalar ones (blending coefficients...) drop it
        diagnostics[name] = diag[:, :, offset:offset + width] if width == out["axes"] else diag[:, :, offset]
        offset += width
    metrics = Metrics(out["metrics"])
    if metrics["diverged"].any():
        warnings.warn(
            f"{describe_diverged(metrics)}; they are stopped, flagged in metrics['diverged'] "
            "(when: metrics['diverged_time'], why: metrics['diverged_reason']) and NaN from the "
            "divergence on",
            DivergenceWarning,
            stacklevel=3,  # the caller of simulate_batch
        )
    return SimulationResult(
        t=out["t"],
        states=out["states"],
        controls=out["controls"],
        final_state=out["final_state"],
        diagnostics=diagnostics,
        metrics=metrics,
        state_names=tuple(out["state_names"]),
        control_names=tuple(out["control_names"]),
        kernel=str(out["kernel"]),
    )


def _python_step(law: PythonLaw, plant: Plant, n: int, first_case: int) -> tuple[LawStep, list[tuple[str, int]]]:
    """What the core calls for a law written in Python, for n cases of ``plant``, and the
    layout of its diagnostics."""
    axes = plant.axes
    name = law.name or ""
    params = {k: per_axis(f"PythonLaw {name}", k, v, n, axes) for k, v in law.params.items()}
    layout = law.diagnostic_layout(axes)
    step = LawStep(law.function, name=name, params=params, memory=law.memory, layout=layout, n=n, axes=axes,
                   first_case=first_case, cases_per_call=law.cases_per_call or max(n, 1))
    return step, layout


def _as_states(x0: Any) -> np.ndarray:
    return real_array("x0", x0, expected="an array of real numbers")


def simulate(
    plant: Plant,
    controller: Controller,
    x0: Any,
    **kwargs: Any,
) -> SimulationResult:
    """One case: :func:`simulate_batch` with ``x0`` of shape ``(n_state,)``; the result has no
    case axis (``states`` is (T, n_state), metrics are scalars).

    Parameters
    ----------
    plant : Plant
        A :mod:`landing.plants` plant (scalar parameters).
    controller : Controller
        A :mod:`landing.controllers` law.
    x0 : ArrayLike
        Shape (n_state,): the initial state, in the plant's units.
    **kwargs : Any
        The keywords of :func:`simulate_batch` (``t_final`` and ``dt``, s, are required).

    Returns
    -------
    SimulationResult
        ``t`` (T,) in s, ``states`` (T, n_state), and the metrics as scalars.

    Raises
    ------
    ParameterError
        As :func:`simulate_batch`, and if ``x0`` is not one state.

    Examples
    --------
    >>> import landing
    >>> from landing.controllers import PDSlidingMode
    >>> law = PDSlidingMode(lambda_=1.0, k=0.5, switch="sat", boundary_layer=0.1)
    >>> r = simulate(landing.plants.DoubleIntegrator(), law, [1.0, 0, 0, 0, 0, 0], t_final=10.0, dt=0.01)
    >>> r.states.shape, f"{r.metrics['settle_time']:.2f} s"
    ((1001, 6), '5.10 s')
    """
    x = _as_states(x0)
    if x.ndim != 1:
        raise ParameterError(
            f"x0 has shape {x.shape}; simulate takes one state (n_state,) (use simulate_batch for many)"
        )
    # warnings raised for the batch of one are re-raised here, pointing at the caller
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        res = simulate_batch(plant, controller, x[None, :], **kwargs)
    for w in caught:
        warnings.warn(w.message, w.category, stacklevel=2)
    return res[0]
