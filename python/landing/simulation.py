"""Batched rollouts: :func:`simulate_batch` and :func:`simulate`."""

from __future__ import annotations

import warnings
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Iterator, Mapping, Optional, Sequence, Union

import numpy as np

from landing import _core
from landing._internal.args import integer, real, real_array
from landing.controllers import Controller
from landing.disturbances import DisturbanceLike, compiled
from landing.errors import DivergenceWarning, ParameterError, ParameterTypeError
from landing.plants import Plant
from landing.reference import Reference

if TYPE_CHECKING:  # pragma: no cover
    import pandas
    import xarray

__all__ = ["Metrics", "SimulationResult", "simulate_batch", "simulate"]


DIVERGENCE_REASONS: tuple[str, ...] = tuple(_core.DIVERGENCE_REASONS)
"""Names of the codes in ``metrics["diverged_reason"]`` (index 0: not diverged)."""


def diverged_cases(metrics: Mapping[str, np.ndarray]) -> dict[str, np.ndarray]:
    """The indices of the diverged cases, by reason name (only the reasons that occur)."""
    codes = np.atleast_1d(metrics["diverged_reason"])
    return {DIVERGENCE_REASONS[c]: np.flatnonzero(codes == c) for c in np.unique(codes) if c != 0}


def describe_diverged(metrics: Mapping[str, np.ndarray], shown: int = 10) -> str:
    """"k of n cases diverged (reason: cases ...; ...)", or "0 of n"."""
    n = np.atleast_1d(metrics["diverged"]).size
    groups = diverged_cases(metrics)
    k = sum(v.size for v in groups.values())
    if k == 0:
        return f"0 of {n}"
    parts = []
    for name, idx in groups.items():
        listed = ", ".join(str(i) for i in idx[:shown]) + (", ..." if idx.size > shown else "")
        parts.append(f"{name}: {idx.size} (cases {listed})")
    return f"{k} of {n} cases diverged ({'; '.join(parts)})"


class Metrics(Mapping[str, np.ndarray]):
    """Per-case figures of merit: a table of columns, one row per case.

    Columns (N cases, D axes):

    - ``final_position_error`` (N,), ``final_velocity_error`` (N,): norms of the tracking
      error and its rate at t_final; ``final_error``, ``final_rate_error`` (N, D) per axis.
    - ``fuel_used`` (N,): m(0) - m(t_final), for plants with mass (NaN otherwise).
    - ``fuel_to_settle`` (N,): m(0) - m(settle_time), the propellant spent until the error
      settles (NaN if it does not, or the plant has no mass).
    - ``peak_command`` (N,): largest |u| applied (for the Mars lander, the peak thrust in N);
      ``peak_command_axis`` (N, D): largest |u_i|.
    - ``control_effort`` (N,): integral of |u| dt.
    - ``settle_time`` (N,): first control instant from which |q - q_ref| stays within the
      settle tolerance until t_final (NaN if it is outside at t_final); seed 000's "time to
      track".
    - ``iae`` (N,), ``iae_axis`` (N, D): integral of |e_i| dt over the run (rectangle rule at
      the control instants), summed over the axes or per axis.
    - ``chattering_variation`` (N,), ``chattering_variation_axis`` (N, D): total variation of
      the applied command per unit time, sum_k |u(k+1) - u(k)| / T.
    - ``chattering_hf_share`` (N,), ``chattering_hf_share_axis`` (N, D): share of the applied
      command's energy above the chattering cut-off (2nd-order Butterworth high-pass).
    - ``touchdown_time``, ``touchdown_speed`` (N,), ``touchdown_position``,
      ``touchdown_velocity`` (N, D): first crossing of the surface, interpolated within the
      step; NaN if none (or the plant has no surface).
    - ``diverged`` (N,) bool, ``diverged_time`` (N,), ``diverged_reason`` (N,) uint8: cases
      stopped before t_final, when and why. The reason codes index
      :data:`landing.DIVERGENCE_REASONS` (0 ``none``; ``non_finite_command``: the law returned
      NaN or infinity; ``command_out_of_range``: a command component beyond
      ``landing.MAX_COMMAND`` = 1e100; ``non_finite_state``; ``out_of_domain``: the state left
      the plant's domain, listed in docs/parameters.md; ``non_finite_metric``: a statistic
      overflowed). Their final errors and fuel are NaN; no metric is infinite without the flag.
      :meth:`Metrics.diverged_cases` groups them by reason.

    Columns are also attributes: ``res.metrics.fuel_used``.
    """

    def __init__(self, columns: Mapping[str, np.ndarray]):
        self._columns = dict(columns)

    def __getitem__(self, name: str) -> np.ndarray:
        return self._columns[name]

    def __getattr__(self, name: str) -> np.ndarray:
        try:
            return self.__dict__["_columns"][name]
        except KeyError:
            raise AttributeError(name) from None

    def __iter__(self) -> Iterator[str]:
        return iter(self._columns)

    def __len__(self) -> int:
        return len(self._columns)

    def __dir__(self) -> list[str]:
        return sorted(set(super().__dir__()) | set(self._columns))

    def diverged_cases(self) -> dict[str, np.ndarray]:
        """The indices of the diverged cases, by reason name (only the reasons that occur)."""
        return diverged_cases(self._columns)

    def row(self, case: int) -> dict[str, Any]:
        """The metrics of one case."""
        return {k: v[case] for k, v in self._columns.items()}

    def to_pandas(
        self,
        *,
        axis_names: Optional[Sequence[str]] = None,
        x0: Optional[np.ndarray] = None,
        state_names: Optional[Sequence[str]] = None,
        seed: Optional[int] = None,
        first_case: int = 0,
    ) -> "pandas.DataFrame":
        """A pandas DataFrame, one row per case (index ``case``; a single case gives one row).

        Per-axis columns are split with the axis names, ``final_error_x`` ... (``_0``, ``_1``
        ... when the axes have no names). The arguments default to what the result that made
        these metrics knows (a :class:`SimulationResult` or a Monte Carlo campaign fills them):
        ``seed`` adds a ``seed`` column, ``x0`` (N, n_state) the initial states as
        ``x0_<state name>`` columns. Needs pandas (``pip install "landing[io]"``).
        """
        from landing.store import flat_columns, require_io

        pd = require_io("pandas", what="Metrics.to_pandas")
        ctx = self.__dict__.get("_context", {})
        axis_names = tuple(axis_names if axis_names is not None else ctx.get("axis_names", ()))
        x0 = x0 if x0 is not None else ctx.get("x0")
        state_names = tuple(state_names if state_names is not None else ctx.get("state_names", ()))
        seed = seed if seed is not None else ctx.get("seed")
        first_case = first_case or int(ctx.get("first_case", 0))
        flat = flat_columns(self._columns, axis_names)
        n = len(next(iter(flat.values()))) if flat else 0
        front: dict[str, np.ndarray] = {}
        if seed is not None:
            front["seed"] = np.full(n, int(seed), dtype=np.uint64)
        if x0 is not None:
            x = np.atleast_2d(np.asarray(x0))
            names = state_names if len(state_names) == x.shape[1] else tuple(str(j) for j in range(x.shape[1]))
            for j, name in enumerate(names):
                front[f"x0_{name}"] = x[:, j]
        index = pd.RangeIndex(first_case, first_case + n, name="case")
        return pd.DataFrame({**front, **flat}, index=index)

    def _with_context(self, **context: Any) -> "Metrics":
        """The same columns, knowing what :meth:`to_pandas` adds (axis names, seed, x0)."""
        out = Metrics(self._columns)
        out.__dict__["_context"] = {**self.__dict__.get("_context", {}), **context}
        return out

    def __repr__(self) -> str:
        cols = {k: np.atleast_1d(v) for k, v in self._columns.items()}
        n = len(cols["diverged"])
        lines = [f"Metrics({n} case{'s' if n != 1 else ''})"]
        for k, v in cols.items():
            if v.ndim == 1 and v.dtype != bool and (n > 1 or np.ndim(self._columns[k]) == 0):
                finite = v[np.isfinite(v)]
                if finite.size:
                    lines.append(f"  {k:<22} mean {finite.mean():.6g}  min {finite.min():.6g}  max {finite.max():.6g}")
                else:
                    lines.append(f"  {k:<22} (none)")
        lines.append(f"  {'diverged':<22} {describe_diverged(self._columns)}")
        return "\n".join(lines)


@dataclass(frozen=True, eq=False)
class SimulationResult:
    """What a batch produced.

    Attributes
    ----------
    t : (T,) recorded control instants, s (empty with ``record_every=0``).
    states : (N, T, n_state) states at the recorded instants.
    controls : (N, T, n_control) the command applied over ``[t_k, t_k + dt)``, after
        saturation (thrust in N for the Mars lander). The last entry is the command computed
        at t_final, which would be held next.
    final_state : (N, n_state) state at t_final.
    diagnostics : name -> (N, T, D) internal signals of the law (sliding variables, ...), or
        (N, T) for scalar ones (blending coefficients).
    metrics : per-case table, see :class:`Metrics`.

    ``result[i]`` is case i alone, with the case axis dropped. A Monte Carlo campaign run with
    ``keep=`` leaves out what it did not keep: ``states`` or ``controls`` are then None and
    ``diagnostics`` is empty.
    """

    t: np.ndarray
    states: Optional[np.ndarray]
    controls: Optional[np.ndarray]
    final_state: np.ndarray
    diagnostics: dict[str, np.ndarray]
    metrics: Metrics
    state_names: tuple[str, ...]
    control_names: tuple[str, ...]
    #: The instruction-set level the batch ran at (the same bits at every level).
    kernel: str = ""

    def __post_init__(self) -> None:
        # the metrics know their axis names (and the initial states, when recorded) for to_pandas
        context: dict[str, Any] = {"axis_names": self.axis_names, "state_names": self.state_names}
        if self.states is not None and self.t.size and self.t[0] == 0.0:
            context["x0"] = self.states[..., 0, :]
        object.__setattr__(self, "metrics", self.metrics._with_context(**context))

    @property
    def n_cases(self) -> int:
        return int(self.final_state.shape[0]) if self.final_state.ndim == 2 else 1

    @property
    def axis_names(self) -> tuple[str, ...]:
        """Names of the axes of the per-axis metrics and diagnostics (x, y, z for the
        three-axis plants, the generalized coordinates' names otherwise)."""
        from landing.store import axis_names

        return axis_names(self.metrics, self.state_names)

    def to_xarray(self) -> "xarray.Dataset":
        """An xarray Dataset: ``states`` (case, time, state), ``controls`` (case, time,
        control), each diagnostic (case, time[, axis]), ``final_state`` (case, state) and every
        metric (case[, axis]), with the time (s), component and axis names as coordinates and
        units where known (a single case has no ``case`` dimension). Needs xarray
        (``pip install "landing[io]"``)."""
        from landing.store import result_dataset

        return result_dataset(self)

    @property
    def diverged(self) -> np.ndarray:
        return self.metrics["diverged"]

    def __len__(self) -> int:
        return self.n_cases

    def __getitem__(self, case: int) -> "SimulationResult":
        if self.final_state.ndim != 2:
            raise TypeError("this result holds a single case")
        return SimulationResult(
            t=self.t,
            states=None if self.states is None else self.states[case],
            controls=None if self.controls is None else self.controls[case],
            final_state=self.final_state[case],
            diagnostics={k: v[case] for k, v in self.diagnostics.items()},
            metrics=Metrics({k: v[case] for k, v in self.metrics.items()}),
            state_names=self.state_names,
            control_names=self.control_names,
            kernel=self.kernel,
        )

    def state(self, name: str) -> np.ndarray:
        """One state component by name, e.g. ``res.state("rz")``: (N, T) or (T,)."""
        if self.states is None:
            raise ParameterError(f"state {name!r}: the states were not kept (keep=...)")
        return self.states[..., self.state_names.index(name)]


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
