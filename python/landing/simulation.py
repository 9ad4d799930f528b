"""Batched rollouts: :func:`simulate_batch` and :func:`simulate`."""

from __future__ import annotations

import warnings
from typing import Any, Optional

import numpy as np

from landing import _core
from landing._internal.args import integer, real, real_array
from landing.controllers import Controller
from landing.disturbances import DisturbanceLike, compiled
from landing.errors import DivergenceWarning, ParameterError, ParameterTypeError
from landing.plants import Plant
from landing.reference import Reference
from landing.results import Metrics, SimulationResult, describe_diverged

__all__ = ["MAX_COMMAND", "kernel_levels", "simulate_batch", "simulate"]

MAX_COMMAND: float = _core.MAX_COMMAND
"""Largest magnitude of a command component a case may apply before it is stopped."""


def kernel_levels() -> list[str]:
    """The instruction-set levels of the compiled kernel this CPU runs, lowest first (every
    level gives the same bits; ``simulate_batch(..., kernel=...)`` forces one)."""
    return list(_core.kernel_levels())


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
) -> SimulationResult:
    """Simulate N cases of ``plant`` under ``controller`` in parallel (the semantics in README.md).

    Parameters
    ----------
    plant : a :mod:`landing.plants` plant; its numeric parameters may be per case.
    controller : a :mod:`landing.controllers` law; its gains may be per case.
    x0 : (N, n_state) initial states, one row per case.
    t_final : horizon, s; a whole number of control periods.
    dt : control period, s. The command is computed from the state at t_k, saturated, and held
        over ``[t_k, t_k + dt)``.
    integrator : ``"rk4"`` or ``"euler"``.
    substeps : integrator steps per control period.
    reference : target the law tracks (default: the origin at rest).
    disturbance : unknown disturbance (a component, a sum or a list of components).
    record_every : keep every k-th control instant (always the first and the last); 0 keeps
        only the final states and the metrics.
    seed : seed of the counter-based random streams; case i's numbers depend only on
        (seed, first_case + i), never on the thread count or the batch size.
    first_case : global index of the first case, so that a slice of a campaign run alone
        (or in chunks) draws the same random numbers as in the whole batch.
    settle_tolerance : the tolerance on the tracking-error norm |q - q_ref| behind
        ``metrics["settle_time"]`` (the first control instant from which the error stays
        within it), in units of q; None for 2 % of the initial error norm.
    chatter_cutoff : cut-off frequency (Hz) of the high-pass filter behind
        ``metrics["chattering_hf_share"]``; None for a tenth of the Nyquist frequency,
        1 / (20 dt).
    threads : worker threads (default: all cores).
    kernel : the instruction-set level of the compiled kernel, one of
        ``landing.kernel_levels()`` (``"baseline"``, ``"avx2"``, ``"avx512"`` on x86-64); the
        default is the ``LANDING_KERNEL`` environment variable, else the best this CPU has. Every
        level gives the same bits; forcing one is for testing and benchmarking.

    Returns
    -------
    SimulationResult. Cases whose state leaves the model's domain are stopped, flagged in
    ``metrics["diverged"]`` and reported with a :class:`~landing.errors.DivergenceWarning`.
    """
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
    if not isinstance(integrator, str):
        raise ParameterTypeError(f"integrator must be a string, got {integrator!r}")
    seed_i = integer("seed", seed, minimum=0, maximum=2**64 - 1)
    first = integer("first_case", first_case, minimum=0, maximum=2**63 - 1)
    if kernel is not None and not isinstance(kernel, str):
        raise ParameterTypeError(f"kernel must be a string or None, got {kernel!r}")
    if kernel is not None and kernel not in _core.KERNEL_LEVELS:
        raise ParameterError(f"kernel = {kernel!r} is not one of {tuple(_core.KERNEL_LEVELS)}")
    substeps_i = integer("substeps", substeps, minimum=1, cap="max_substeps")
    record_every_i = integer("record_every", record_every, minimum=0, maximum=2**63 - 1)
    threads_i = None if threads is None else integer("threads", threads, minimum=1, cap="max_threads")
    integer("x0 cases N", x.shape[0], cap="max_cases")
    out = _core.simulate_batch(
        plant._core,  # type: ignore[attr-defined]
        controller._core,  # type: ignore[attr-defined]
        x,
        t_final=real("t_final", t_final),
        dt=real("dt", dt),
        integrator=integrator,
        substeps=substeps_i,
        reference=None if reference is None else reference._core,  # type: ignore[attr-defined]
        disturbance=compiled(disturbance),
        record_every=record_every_i,
        seed=seed_i,
        first_case=first,
        settle_tolerance=0.02 if settle_tolerance is None else real("settle_tolerance", settle_tolerance),
        settle_relative=settle_tolerance is None,
        chatter_cutoff=None if chatter_cutoff is None else real("chatter_cutoff", chatter_cutoff),
        threads=threads_i,
        kernel=kernel,
    )
    diag = out["diagnostics"]
    diagnostics = {}
    offset = 0
    for name, width in out["diagnostic_layout"]:
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
            stacklevel=2,
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


def _as_states(x0: Any) -> np.ndarray:
    return real_array("x0", x0, expected="an array of real numbers")


def simulate(
    plant: Plant,
    controller: Controller,
    x0: Any,
    **kwargs: Any,
) -> SimulationResult:
    """One case: :func:`simulate_batch` with ``x0`` of shape ``(n_state,)``; the result has no
    case axis (``states`` is (T, n_state), metrics are scalars)."""
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
