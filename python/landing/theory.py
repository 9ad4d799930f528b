"""Convergence bounds of the fixed-time laws, and their checks against simulation.

The formulas are computed by the Rust core (``landing_core::theory``) and broadcast here over
arrays. Every bound comes with a check that simulates the system it speaks about and reports
each case that violates it:

- :func:`check_fixed_time_bound`: the scalar reaching law ``s' = -c1 sig^e1(s) - c2 sig^e2(s)``
  (seed 001 Lemma 2; eq. 18 with the beta gains, eq. 26 with the alpha gains) from any s(0).
- :func:`check_practical_bound`: the same law with a bounded disturbance (Theorem 1; eq. 38
  to 40 for s2, eq. 31 and 45 for s1).
- :func:`check_mss`: a recorded run of :class:`~landing.controllers.FixedTimeMSS` against its
  practical neighbourhoods and times (Theorem 4).
- :func:`min_final_time`: seed Remark 1.
- :func:`fntsmc_bounds` (seed 003 Theorem 1, made sound) with :func:`check_fntsmc_bound` (the
  law on a double integrator, where its derivation holds exactly) and
  :func:`check_fntsmc_run` (a recorded tethered-satellite run); the printed eq. 42 and 47 are
  :func:`fntsmc_ts_printed` and :func:`fntsmc_td_printed`.

A scalar reaching law is simulated where the library realises it: the exact variant of
FixedTimeMSS on a :class:`~landing.plants.DoubleIntegrator` makes its second sliding variable
obey ``s2' = -alpha1 sig^gamma1(s2) - alpha2 sig^gamma2(s2) + d`` (no drift, unit inertia).
With negligible first-surface gains (beta = 1e-20), s2 is the velocity itself, so each axis of
the double integrator's velocity is one run of the scalar law.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Optional

import numpy as np

from landing import _core
from landing.controllers import FixedTimeMSS, FixedTimeNTSMC
from landing.disturbances import DisturbanceLike, Sinusoid, compiled
from landing._internal.args import integer, real, real_array
from landing._internal.limits import require_memory
from landing.errors import ParameterError, ParameterTypeError
from landing.plants import DoubleIntegrator, Plant
from landing.results import SimulationResult
from landing.scenarios import Scenario
from landing.simulation import simulate_batch

__all__ = [
    "fixed_time_bound",
    "practical_time_bound",
    "practical_radius",
    "MSSBounds",
    "mss_bounds",
    "disturbance_bound",
    "scenario_bounds",
    "min_final_time",
    "min_time_to_rest",
    "chattering_band",
    "entry_time",
    "settle_time",
    "BoundCheck",
    "check_fixed_time_bound",
    "check_practical_bound",
    "check_mss",
    "FNTSMCBounds",
    "fntsmc_bounds",
    "fntsmc_ts_printed",
    "fntsmc_td_printed",
    "check_fntsmc_bound",
    "check_fntsmc_run",
]


def _reals(owner: str, **args: Any) -> list[np.ndarray]:
    """Each argument as a finite float64 array (named in the error), checked to broadcast."""
    arrays = [real_array(name, value, finite=True, owner=owner) for name, value in args.items()]
    try:
        shape = np.broadcast_shapes(*[a.shape for a in arrays])
    except ValueError:
        shapes = ", ".join(f"{n} {a.shape}" for n, a in zip(args, arrays))
        raise ParameterError(f"{owner}: the shapes {shapes} violate shapes that broadcast together") from None
    # the broadcast inputs and the results
    require_memory(f"{owner} over arrays of shape {shape}", 8 * (len(arrays) + 2) * math.prod(shape))
    return arrays


def _vectorized(fn, owner: str, **args: Any):
    out = np.vectorize(fn, otypes=[float])(*_reals(owner, **args))
    return float(out) if out.ndim == 0 else out


def _instance(owner: str, name: str, value: Any, cls: type, what: str) -> None:
    if not isinstance(value, cls):
        raise ParameterTypeError(f"{owner}: {name} must be {what}, got {type(value).__name__}")


def _time_signal(owner: str, t: Any, signal: Any, tol: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Recorded times (T,), a signal (..., T, D) and a tolerance (scalar or (..., D)), checked."""
    tt = real_array("t", t, owner=owner)
    sig = real_array("signal", signal, owner=owner)
    tl = real_array("tol", tol, owner=owner)
    if tt.ndim != 1 or tt.size == 0:
        raise ParameterError(f"{owner}: t has shape {tt.shape}; it takes (T,) with T >= 1")
    if sig.ndim < 2 or sig.shape[-2] != tt.size:
        raise ParameterError(
            f"{owner}: signal has shape {sig.shape}; it takes (..., T, D) with T = len(t) = {tt.size}"
        )
    if tl.ndim:
        try:
            np.broadcast_shapes(tl[..., None, :].shape, sig.shape)
        except (ValueError, IndexError):
            raise ParameterError(
                f"{owner}: tol has shape {tl.shape}; it takes a scalar or (..., D) matching signal {sig.shape}"
            ) from None
    return tt, sig, tl


def fixed_time_bound(c1, e1, c2, e2):
    """Seed 001 Lemma 2 with k = 1 on V = s^2/2 for ``s' = -c1 sig^e1(s) - c2 sig^e2(s)``:
    ``T <= 1/(c1 (1-e1) 2^((e1-1)/2)) + 1/(c2 (e2-1) 2^((e2-1)/2))``, whatever s(0).

    Eq. 18 is this with (beta1, q1, beta2, q2), eq. 26 with (alpha1, gamma1, alpha2, gamma2).
    Arrays broadcast."""
    return _vectorized(_core.fixed_time_bound, "fixed_time_bound", c1=c1, e1=e1, c2=c2, e2=e2)


def practical_time_bound(c1, e1, c2, e2, theta):
    """Theorem 1 (k = 1): time to reach the practical neighbourhood, the fixed-time bound / theta."""
    return _vectorized(_core.practical_time_bound, "practical_time_bound", c1=c1, e1=e1, c2=c2, e2=e2,
                       theta=theta)


def practical_radius(c1, e1, c2, e2, d_max, theta):
    """Eq. 38-39: ``min{(d_max/((1-theta) c1))^(1/e1), (d_max/((1-theta) c2))^(1/e2)}``, the
    neighbourhood that ``s' = -c1 sig^e1(s) - c2 sig^e2(s) + d``, |d| <= d_max, reaches."""
    return _vectorized(_core.practical_radius, "practical_radius", c1=c1, e1=e1, c2=c2, e2=e2, d_max=d_max,
                       theta=theta)


@dataclass(frozen=True)
class MSSBounds:
    """Seed 001's bounds for FixedTimeMSS, per axis (shape (3,), or (N, 3) for per-case gains).

    t1, t2 : eq. 18 and 26, without disturbance (s).
    s2_radius, s2_time : eq. 39 and 40, the neighbourhood of s2 under |a_p| <= ap_max.
    s1_radius, s1_time : eq. 31 and 45, that of s1 = r - r_d once s2 is in its own.
    printed_time : eq. 32 as printed, max(s2_time, s1_time).
    settle_time : s2_time + s1_time, the sound bound: s1 obeys its perturbed reaching law
        only once s2 is in its neighbourhood.
    """

    t1: np.ndarray
    t2: np.ndarray
    s2_radius: np.ndarray
    s2_time: np.ndarray
    s1_radius: np.ndarray
    s1_time: np.ndarray
    printed_time: np.ndarray
    settle_time: np.ndarray
    ap_max: np.ndarray
    theta1: float
    theta2: float

    def __str__(self) -> str:
        def fmt(a: np.ndarray) -> str:
            a = np.asarray(a)
            if a.ndim == 2:  # per case: the range over the cases, per axis
                lo = np.array2string(a.min(axis=0), precision=4, floatmode="maxprec")
                hi = np.array2string(a.max(axis=0), precision=4, floatmode="maxprec")
                return f"{lo} to {hi} over {a.shape[0]} cases"
            return np.array2string(a, precision=4, floatmode="maxprec")

        return (
            f"MSSBounds(theta1={self.theta1}, theta2={self.theta2}, ap_max={fmt(self.ap_max)})\n"
            f"  T1 (eq. 18)            {fmt(self.t1)} s\n"
            f"  T2 (eq. 26)            {fmt(self.t2)} s\n"
            f"  |s2| radius (eq. 39)   {fmt(self.s2_radius)} m/s, reached by {fmt(self.s2_time)} s (eq. 40)\n"
            f"  |s1| radius (eq. 31)   {fmt(self.s1_radius)} m, {fmt(self.s1_time)} s later (eq. 45)\n"
            f"  eq. 32 as printed      {fmt(self.printed_time)} s; sound total {fmt(self.settle_time)} s"
        )


def _axes_or_cases(value: Any, axes: int) -> np.ndarray:
    """A law parameter as the core reads it: a scalar for every axis, ``(axes,)`` per axis,
    ``(N,)`` or ``(N, 1)`` per case (a 1-D array of length ``axes`` is per axis), ``(N, axes)``
    per case and axis. Returns ``(axes,)`` or ``(N, axes)``."""
    g = np.asarray(value, dtype=float)
    if g.ndim == 0:
        return np.full(axes, float(g))
    if g.ndim == 1:
        return g if g.size == axes else np.repeat(g[:, None], axes, axis=1)
    return np.broadcast_to(g, (g.shape[0], axes))


def mss_bounds(law: FixedTimeMSS, ap_max: Any = 0.0, theta1: float = 0.5, theta2: float = 0.5) -> MSSBounds:
    """The bounds of seed 001 Theorems 2-4 for a FixedTimeMSS law (per axis), under a
    disturbance bounded by ``ap_max`` per axis (see :func:`disturbance_bound`)."""
    if not isinstance(law, FixedTimeMSS):
        raise ParameterTypeError(f"mss_bounds takes a FixedTimeMSS law, got {type(law).__name__}")
    names = ("beta1", "q1", "beta2", "q2", "alpha1", "gamma1", "alpha2", "gamma2")
    gains = [_axes_or_cases(getattr(law, n), 3) for n in names]
    ap = real_array("ap_max", ap_max, finite=True, owner="mss_bounds")
    theta1 = real("theta1", theta1, owner="mss_bounds")
    theta2 = real("theta2", theta2, owner="mss_bounds")
    try:
        args = np.broadcast_arrays(*gains, ap)
    except ValueError:
        raise ParameterError(
            f"mss_bounds: ap_max has shape {ap.shape}; it takes a scalar, (3,) or the gains' (N, 3)"
        ) from None
    shape = args[0].shape
    keys = ("t1", "t2", "s2_radius", "s2_time", "s1_radius", "s1_time", "printed_time", "settle_time")
    out = {k: np.empty(shape) for k in keys}
    for idx in np.ndindex(shape):
        b = _core.mss_bounds(*[float(a[idx]) for a in args], float(theta1), float(theta2))
        for k in keys:
            out[k][idx] = b[k]
    return MSSBounds(**out, ap_max=args[-1], theta1=float(theta1), theta2=float(theta2))


def scenario_bounds(scenario: Scenario) -> Optional[MSSBounds]:
    """Seed 001's practical fixed-time bounds for a scenario's law and disturbance (what
    :meth:`Scenario.bounds` returns): None unless the law is FixedTimeMSS and the scenario's
    ``theta`` is set."""
    if scenario.theta is None or not isinstance(scenario.controller, FixedTimeMSS):
        return None
    ap_max = disturbance_bound(scenario.disturbance, scenario.plant.axes)
    return mss_bounds(scenario.controller, ap_max, *scenario.theta)


def disturbance_bound(disturbance: DisturbanceLike, axes: int = 3) -> np.ndarray:
    """Per-axis bound on |d_i(t)|: |constant| + sum of |amplitudes| + noise bound."""
    axes = integer("axes", axes, owner="disturbance_bound")
    if axes not in (2, 3):
        raise ParameterError(f"disturbance_bound: axes = {axes} violates axes in (2, 3)")
    handle = compiled(disturbance)
    if handle is None:
        return np.zeros(axes)
    return np.asarray(handle.bound(axes))


def min_final_time(r0, v0, a_max, g=0.0) -> tuple[np.ndarray, np.ndarray]:
    """Seed 001 Remark 1, sign-consistent, per axis: ``(tf1, tf2)`` with tf1 the first time the
    position can reach 0 at full thrust towards the target (with gravity g on that axis,
    negative for z up) and tf2 the time to null the velocity at full thrust. A soft landing
    needs ``t_f >= max(tf1, tf2)`` over the axes. Arrays broadcast."""
    f = np.vectorize(lambda *a: _core.min_final_time(*a), otypes=[float, float])
    tf1, tf2 = f(*_reals("min_final_time", r0=r0, v0=v0, a_max=a_max, g=g))
    return tf1, tf2


def min_time_to_rest(r0, v0, a_max, g=0.0):
    """The shortest time to bring one axis from (r0, v0) to rest at 0 with thrust up to
    ``a_max`` either way plus gravity ``g`` (time-optimal bang-bang, one switch): a lower bound
    on any landing time on that axis. Infinite when the thrust cannot overcome gravity. Arrays
    broadcast."""
    return _vectorized(_core.min_time_to_rest, "min_time_to_rest", r0=r0, v0=v0, a_max=a_max, g=g)


def entry_time(t: np.ndarray, signal: np.ndarray, tol: Any) -> np.ndarray:
    """First recorded time at which ``|signal| <= tol``; ``signal`` has time on axis -2
    (``(..., T, D)``), the result drops it. NaN where never."""
    t, signal, tol = _time_signal("entry_time", t, signal, tol)
    inside = np.abs(signal) <= np.asarray(tol)[..., None, :] if np.ndim(tol) else np.abs(signal) <= tol
    first = np.argmax(inside, axis=-2)
    out = np.asarray(t)[first].astype(float)
    out[~inside.any(axis=-2)] = np.nan
    return out


def settle_time(t: np.ndarray, signal: np.ndarray, tol: Any) -> np.ndarray:
    """First recorded time from which ``|signal| <= tol`` holds to the end (NaN if it does not
    hold at the end); layout as :func:`entry_time`."""
    t, signal, tol = _time_signal("settle_time", t, signal, tol)
    inside = np.abs(signal) <= np.asarray(tol)[..., None, :] if np.ndim(tol) else np.abs(signal) <= tol
    tail = np.flip(np.logical_and.accumulate(np.flip(inside, axis=-2), axis=-2), axis=-2)
    first = np.argmax(tail, axis=-2)
    out = np.asarray(t)[first].astype(float)
    out[~tail.any(axis=-2)] = np.nan
    return out


@dataclass
class BoundCheck:
    """A bound against simulation: ``measured <= bound`` for every case and axis.

    ``measured`` is NaN where the event never happened within the horizon (a violation).
    ``extra`` holds what else the check measured (e.g. the largest excursion afterwards).
    """

    name: str
    bound: np.ndarray
    measured: np.ndarray
    extra: dict[str, np.ndarray] = field(default_factory=dict)

    @property
    def violations(self) -> np.ndarray:
        """Indices of the cases (first axis) with a violation on any axis."""
        bad = ~(self.measured <= self.bound)
        if bad.ndim > 1:
            bad = bad.reshape(bad.shape[0], -1).any(axis=1)
        return np.flatnonzero(bad)

    @property
    def ok(self) -> bool:
        return self.violations.size == 0

    @property
    def worst_ratio(self) -> float:
        """Largest measured / bound (below 1 when the bound holds)."""
        return float(np.nanmax(self.measured / self.bound))

    def __repr__(self) -> str:
        n = self.measured.shape[0] if self.measured.ndim else 1
        status = "holds" if self.ok else f"VIOLATED in {self.violations.size} of {n} cases: {self.violations[:10].tolist()}"
        return f"BoundCheck({self.name}: {status}; worst measured/bound = {self.worst_ratio:.3f})"


# With these the first surface adds less than 1e-12 to s2 = v + beta1 sig^q1(r) + ... for
# |r| < 1e8, and the exact law's cancellation terms are as small: s2 is the velocity.
_NEGLIGIBLE_S1_GAINS = dict(beta1=1e-20, q1=0.999, beta2=1e-20, q2=1.001)


def _reaching_run(c1, e1, c2, e2, s0, *, disturbance, dt, t_final, seed=0) -> SimulationResult:
    """The velocity of a double integrator under the exact FixedTimeMSS with negligible
    first-surface gains obeys the scalar reaching law with gains (c1, e1, c2, e2). s0 (the
    initial velocities) has shape (N, 3)."""
    law = FixedTimeMSS(**_NEGLIGIBLE_S1_GAINS, alpha1=c1, gamma1=e1, alpha2=c2, gamma2=e2, variant="exact")
    x0 = np.concatenate([np.zeros_like(s0), s0], axis=1)
    return simulate_batch(DoubleIntegrator(), law, x0, t_final=t_final, dt=dt,
                          disturbance=disturbance, seed=seed)


def _as_cases(owner: str, s0: Any) -> np.ndarray:
    s = real_array("s0", s0, finite=True, owner=owner)
    if s.ndim == 0:
        s = s.reshape(1, 1)
    if s.ndim == 1:
        s = s[:, None]
    if s.ndim != 2 or s.shape[0] == 0 or s.shape[1] not in (1, 3):
        raise ParameterError(f"{owner}: s0 has shape {s.shape}; it takes a scalar, (N,), (N, 1) or (N, 3) with N >= 1")
    integer("s0 cases N", s.shape[0], cap="max_cases", owner=owner)
    return np.broadcast_to(s, (s.shape[0], 3)) if s.shape[1] == 1 else s


def _sampling_step(c2: float, e2: float, s_max: float, dt: Optional[float]) -> float:
    """A control period at which the sampled law is stable up to |s| = s_max: the held
    command acts like an explicit step, stable while dt times the local rate
    c2 e2 |s|^(e2-1) stays well below 2."""
    if dt is not None:
        return float(dt)
    rate = c2 * e2 * max(s_max, 1.0) ** (e2 - 1.0)
    return float(min(1e-3, 0.1 / rate))


def _horizon(dt: float, seconds: float) -> float:
    steps = np.ceil(seconds / dt)
    if steps > 5e7:
        raise ParameterError(
            f"checking this bound needs {steps:.3g} control periods of {dt:.3g} s; "
            "lower the initial values or give a larger dt"
        )
    return float(dt * steps)


def chattering_band(c1: float, e1: float, dt: float) -> float:
    """Half-width of the band a sampled ``s' = -c1 sig^e1(s)`` (e1 < 1) chatters in: where
    one held step ``c1 |s|^e1 dt`` equals ``|s|``, ``(c1 dt)^(1/(1-e1))``. Continuous time
    reaches 0; the sampled law cannot get further."""
    c1 = real("c1", c1, positive=True, owner="chattering_band")
    e1 = real("e1", e1, owner="chattering_band")
    if not 0 < e1 < 1:
        raise ParameterError(f"chattering_band: e1 = {e1:g} violates 0 < e1 < 1")
    dt = real("dt", dt, positive=True, owner="chattering_band")
    return float((c1 * dt) ** (1.0 / (1.0 - e1)))


def check_fixed_time_bound(
    c1, e1, c2, e2, s0, *, dt: Optional[float] = None, tol: float = 1e-6
) -> BoundCheck:
    """Simulate ``s' = -c1 sig^e1(s) - c2 sig^e2(s)`` from each initial value ``s0`` ((N,),
    or (N, 3) for three axes at once) and compare the time at which |s| first reaches ``tol``
    with :func:`fixed_time_bound`. ``dt`` defaults to a control period at which the sampled law
    is stable from the largest ``|s0|``; ``tol`` is raised to ten times the
    :func:`chattering_band` of the sampled law if that is larger."""
    owner = "check_fixed_time_bound"
    c1, e1, c2, e2 = (real(n, v, owner=owner) for n, v in (("c1", c1), ("e1", e1), ("c2", c2), ("e2", e2)))
    bound = fixed_time_bound(c1, e1, c2, e2)
    s = _as_cases(owner, s0)
    dt = None if dt is None else real("dt", dt, positive=True, owner=owner)
    tol = real("tol", tol, positive=True, owner=owner)
    dt = _sampling_step(c2, e2, float(np.abs(s).max()), dt)
    tol = max(tol, 10.0 * chattering_band(c1, e1, dt))
    horizon = _horizon(dt, 1.2 * bound)
    res = _reaching_run(c1, e1, c2, e2, s, disturbance=None, dt=dt, t_final=horizon)
    s2 = res.diagnostics["s2"]
    measured = entry_time(res.t, s2, tol)
    return BoundCheck(
        name=f"fixed-time bound {bound:.4f} s for c1={c1}, e1={e1}, c2={c2}, e2={e2}",
        bound=np.full(measured.shape, bound),
        measured=measured,
        extra={"max_after_entry": _max_after(res.t, s2, measured), "tolerance": np.asarray(tol)},
    )


def _max_after(t: np.ndarray, signal: np.ndarray, start: np.ndarray) -> np.ndarray:
    """Largest |signal| at or after ``start`` (per case and axis)."""
    after = np.asarray(t)[None, :, None] >= np.where(np.isnan(start), np.inf, start)[:, None, :]
    return np.where(after, np.abs(signal), 0.0).max(axis=1)


def check_practical_bound(
    c1, e1, c2, e2, s0, *, d_max: float, theta: float, omega: float = 1.0,
    dt: Optional[float] = None, settle_for: Optional[float] = None,
) -> BoundCheck:
    """Simulate ``s' = -c1 sig^e1(s) - c2 sig^e2(s) + d(t)`` with ``d = d_max sin(omega t)`` from
    each ``s0`` and compare with Theorem 1: |s| enters :func:`practical_radius` within
    :func:`practical_time_bound` and stays in it (``extra["max_after_entry"]``, checked over
    ``settle_for`` seconds after the bound, by default the bound itself)."""
    owner = "check_practical_bound"
    c1, e1, c2, e2, d_max, theta, omega = (
        real(n, v, owner=owner) for n, v in (("c1", c1), ("e1", e1), ("c2", c2), ("e2", e2),
                                              ("d_max", d_max), ("theta", theta), ("omega", omega)))
    dt = None if dt is None else real("dt", dt, positive=True, owner=owner)
    settle_for = None if settle_for is None else real("settle_for", settle_for, nonnegative=True, owner=owner)
    radius = practical_radius(c1, e1, c2, e2, d_max, theta)
    bound = practical_time_bound(c1, e1, c2, e2, theta)
    s = _as_cases(owner, s0)
    dt = _sampling_step(c2, e2, max(float(np.abs(s).max()), radius), dt)
    horizon = _horizon(dt, bound + (bound if settle_for is None else settle_for))
    res = _reaching_run(c1, e1, c2, e2, s, disturbance=Sinusoid(amplitude=d_max, omega=omega),
                        dt=dt, t_final=horizon)
    s2 = res.diagnostics["s2"]
    measured = entry_time(res.t, s2, radius)
    after = _max_after(res.t, s2, measured)
    # staying in the neighbourhood is part of the claim: a later excursion is a violation
    measured = np.where(after <= radius * (1 + 1e-9), measured, np.nan)
    return BoundCheck(
        name=f"practical bound: |s| <= {radius:.4g} within {bound:.4f} s (theta={theta}, d_max={d_max})",
        bound=np.full(measured.shape, bound),
        measured=measured,
        extra={"max_after_entry": after, "radius": np.asarray(radius)},
    )


def check_mss(result: SimulationResult, bounds: MSSBounds) -> dict[str, BoundCheck]:
    """Check a recorded FixedTimeMSS run against Theorem 4: after ``s2_time`` every |s2_i|
    stays within ``s2_radius``; after ``settle_time`` every |s1_i| within ``s1_radius``.

    Returns checks "s2" and "s1" whose ``measured`` is the time from which the variable stays
    in its neighbourhood (NaN if it is outside at the end of the run). Where the bound time
    exceeds the horizon, ``extra["checkable"]`` is False and only the end of the run is seen.
    """
    _instance("check_mss", "result", result, SimulationResult, "a landing.SimulationResult")
    _instance("check_mss", "bounds", bounds, MSSBounds, "a landing.theory.MSSBounds")
    if result.t.size == 0:
        raise ParameterError("check_mss needs a recorded run (record_every >= 1)")
    if "s1" not in result.diagnostics or "s2" not in result.diagnostics:
        raise ParameterError("check_mss needs a FixedTimeMSS result with recorded s1 and s2")
    t = result.t
    out = {}
    for name, radius, time in (("s2", bounds.s2_radius, bounds.s2_time), ("s1", bounds.s1_radius, bounds.settle_time)):
        sig = result.diagnostics[name]
        if sig.ndim == 2:
            sig = sig[None]
        measured = settle_time(t, sig, radius)
        bound = np.broadcast_to(time, measured.shape)
        out[name] = BoundCheck(
            name=f"{name} stays within {np.array2string(np.asarray(radius), precision=4)} after "
                 f"{np.array2string(np.asarray(time), precision=4)} s",
            bound=bound,
            measured=measured,
            extra={"checkable": np.asarray(bound <= t[-1]), "final": np.abs(sig[:, -1, :])},
        )
    return out


# Seed 003: the fixed-time NTSMC with RBF compensation (law 9).

_FNTSMC_GAINS = ("k1", "p1", "k2", "p2", "k3", "alpha_s", "beta_s", "sigma_phi")


def fntsmc_ts_printed(c_v, alpha_s, beta_s):
    """Seed 003 eq. 42 as printed, ``2/(c_v (z4 - 1)) + 2/(c_v (1 - z3))`` with
    ``z3 = (3 alpha_s - 1)/(2 alpha_s)``, ``z4 = (3 beta_s - 1)/(2 beta_s)`` (the seed's
    degrees). The seed never gives Lemma 2's ``c_v``, so this is a function of it. Arrays
    broadcast."""
    return _vectorized(_core.fntsmc_ts_printed, "fntsmc_ts_printed", c_v=c_v, alpha_s=alpha_s, beta_s=beta_s)


def fntsmc_td_printed(k1, p1, k2, p2, d=0.5):
    """Seed 003 eq. 47 as printed, ``2/(d g1 (1 - p1)) + 2/(d g2 (p2 - 1))`` with
    ``g1 = 2^((p1+1)/2) k1``, ``g2 = 2^((p2+1)/2) (k2 - 1/(p2+1))``. Not a bound for the law:
    Lemma 4 needs p1 < 1 < p2 and g2 > 0, eq. 21 and Table 2 have p1 > 1 > p2 and g2 < 0 (see
    :func:`fntsmc_bounds`). Returned as printed, whatever its sign. Arrays broadcast."""
    return _vectorized(_core.fntsmc_td_printed, "fntsmc_td_printed", k1=k1, p1=p1, k2=k2, p2=p2, d=d)


@dataclass(frozen=True)
class FNTSMCBounds:
    """Seed 003 Theorem 1 made sound, per axis (shape (D,), or (N, D) for per-case gains).

    ts : time for s to reach its neighbourhood s_radius (eq. 42's role), from any state.
    td : then, time for |e1| to reach max(sigma_phi, e1_radius) (eq. 47's role).
    t_inside : then, time to reach ``tol`` inside sigma_phi, where e1 decays at least at
        ``inside_rate`` (the fixed-time part of the law ends at sigma_phi by design).
    total : ts + td + t_inside: from then on |e1| <= tol, whatever the initial state.
    printed_td : eq. 47 as printed with ``d`` (not a bound; kept for the record).
    With ``d_max = 0`` (no disturbance of the s dynamics) the radii are 0 and the times are
    the nominal fixed-time bounds; with ``d_max > 0`` they are the practical ones (times
    divided by ``theta``). The law's derivation assumes an unsaturated actuator.
    """

    ts: np.ndarray
    s_radius: np.ndarray
    td: np.ndarray
    e1_radius: np.ndarray
    inside_rate: np.ndarray
    t_inside: np.ndarray
    total: np.ndarray
    printed_td: np.ndarray
    tol: np.ndarray
    d_max: np.ndarray
    theta: float
    d: float

    def __str__(self) -> str:
        def fmt(a) -> str:
            return np.array2string(np.asarray(a), precision=4, floatmode="maxprec")

        return (
            f"FNTSMCBounds(tol={fmt(self.tol)}, d_max={fmt(self.d_max)}, theta={self.theta})\n"
            f"  T_s, s reaches {fmt(self.s_radius)}         {fmt(self.ts)} s\n"
            f"  T_d, |e1| reaches max(sigma_phi, {fmt(self.e1_radius)})  {fmt(self.td)} s\n"
            f"  then |e1| reaches tol at rate {fmt(self.inside_rate)} 1/s  {fmt(self.t_inside)} s\n"
            f"  total                                 {fmt(self.total)} s\n"
            f"  eq. 47 as printed (d = {self.d}, not a bound)  {fmt(self.printed_td)} s"
        )


def _law_gains(law: FixedTimeNTSMC, names: tuple[str, ...], axes: Optional[int]) -> list[np.ndarray]:
    gains = [np.asarray(getattr(law, n), dtype=float) for n in names]
    if axes is None:
        sizes = {g.shape[-1] for g in gains if g.ndim >= 1 and g.shape[-1] > 1}
        axes = sizes.pop() if len(sizes) == 1 else 2
    return [np.broadcast_to(g, np.broadcast_shapes(g.shape, (axes,))) if g.ndim <= 1 else g for g in gains]


def fntsmc_bounds(law: FixedTimeNTSMC, tol: Any, *, d_max: Any = 0.0, theta: float = 0.5, d: float = 0.5,
                  axes: Optional[int] = None) -> FNTSMCBounds:
    """Sound fixed-time bounds of a :class:`~landing.controllers.FixedTimeNTSMC` per axis
    (seed 003 Theorem 1): after ``total`` seconds ``|e1_i| <= tol_i`` from any initial state,
    when the lumped disturbance of the s dynamics, ``M^-1 (f - W^T Phi - eps_max sign s)``, is
    bounded by ``d_max`` (0: the theorem's nominal case) and the actuator does not saturate.

    ``axes`` defaults to the gains' length (2 for the tethered satellite's defaults)."""
    if not isinstance(law, FixedTimeNTSMC):
        raise ParameterTypeError(f"fntsmc_bounds takes a FixedTimeNTSMC law, got {type(law).__name__}")
    owner = "fntsmc_bounds"
    if axes is not None:
        axes = integer("axes", axes, minimum=1, maximum=3, owner=owner)
    tol_a = real_array("tol", tol, finite=True, owner=owner)
    d_max_a = real_array("d_max", d_max, finite=True, owner=owner)
    theta = real("theta", theta, owner=owner)
    d = real("d", d, owner=owner)
    try:
        gains = _law_gains(law, _FNTSMC_GAINS, axes)
    except ValueError:
        raise ParameterError(f"{owner}: axes = {axes} violates the law's gains having 1 or axes values") from None
    try:
        args = np.broadcast_arrays(*gains, tol_a, d_max_a)
    except ValueError:
        raise ParameterError(
            f"{owner}: tol {tol_a.shape} and d_max {d_max_a.shape} violate shapes that broadcast with the "
            f"gains' {gains[0].shape}"
        ) from None
    shape = args[0].shape
    keys = ("ts", "s_radius", "td", "e1_radius", "inside_rate", "t_inside", "total")
    out = {k: np.empty(shape) for k in keys}
    printed = np.empty(shape)
    for idx in np.ndindex(shape):
        k1, p1, k2, p2, k3, a_s, b_s, sg, tl, dm = (float(a[idx]) for a in args)
        b = _core.fntsmc_bounds(k1, p1, k2, p2, k3, a_s, b_s, sg, tl, dm, float(theta))
        for k in keys:
            out[k][idx] = b[k]
        printed[idx] = _core.fntsmc_td_printed(k1, p1, k2, p2, float(d))
    return FNTSMCBounds(**out, printed_td=printed, tol=args[-2], d_max=args[-1], theta=float(theta), d=float(d))


def _axis_law(law: FixedTimeNTSMC, axis: int) -> FixedTimeNTSMC:
    """The gains of one axis of ``law`` on every axis, the network and the switching term off:
    the law of Theorem 1's nominal case."""
    names = _FNTSMC_GAINS + ("rbf_scale_e1", "rbf_scale_e2", "rbf_width")
    gains = _law_gains(law, names, None)
    if any(g.ndim > 1 for g in gains):
        raise ParameterError("check_fntsmc_bound takes a law with the same gains for every case")
    kw = {n: float(g[axis]) for n, g in zip(names, gains)}
    return FixedTimeNTSMC(**kw, eps_max=0.0, gamma=0.0, rbf_nodes=1)


def check_fntsmc_bound(law: FixedTimeNTSMC, pairs: Any, *, axis: int = 0, tol: float = 1e-6,
                       dt: Optional[float] = None) -> dict[str, BoundCheck]:
    """Simulate the FNTSMC with the gains of ``axis`` on a :class:`~landing.plants.DoubleIntegrator`
    (unit inertia, no drift, no saturation, network and switching term off: where the seed's
    derivation holds exactly) from initial errors ``pairs`` ((M, 2): e1, e2) and compare with
    :func:`fntsmc_bounds`:

    - ``"s"``: the first time |s| <= s_tol against ``ts``;
    - ``"e1"``: the time from which |e1| <= tol against ``total``.

    The sampled law cannot bring s closer to 0 than its chattering band
    ``(k3 dt)^(1/(1 - alpha_s))`` (:func:`chattering_band`), nor e1 closer than that band over
    the inside rate: ``s_tol`` and ``tol`` are raised to ten times those if larger. ``dt``
    defaults to a period at which the held command is stable from the largest initial s."""
    owner = "check_fntsmc_bound"
    _instance(owner, "law", law, FixedTimeNTSMC, "a landing.controllers.FixedTimeNTSMC law")
    e = real_array("pairs", pairs, finite=True, owner=owner)
    if e.size == 0 or e.size % 2:
        raise ParameterError(f"{owner}: pairs has shape {e.shape}; it takes (M, 2) pairs (e1, e2) with M >= 1")
    e = e.reshape(-1, 2)
    integer("pairs M", e.shape[0], cap="max_cases", owner=owner)
    tol = real("tol", tol, positive=True, owner=owner)
    dt = None if dt is None else real("dt", dt, positive=True, owner=owner)
    axes = _law_gains(law, _FNTSMC_GAINS, None)[0].shape[-1]
    axis = integer("axis", axis, minimum=0, maximum=axes - 1, owner=owner)
    one = _axis_law(law, axis)
    g = {n: float(getattr(one, n)) for n in _FNTSMC_GAINS}
    zeta = lambda x, p: np.sign(x) * np.abs(x) ** p  # noqa: E731 (outside sigma, the bound's regime)
    s0 = e[:, 1] + g["k1"] * zeta(e[:, 0], g["p1"]) + g["k2"] * zeta(e[:, 0], g["p2"])
    if dt is None:
        rate = g["k3"] * g["beta_s"] * max(float(np.abs(s0).max()), 1.0) ** (g["beta_s"] - 1.0)
        rate += g["k1"] * g["p1"] * max(float(np.abs(e[:, 0]).max()), 1.0) ** (g["p1"] - 1.0)
        dt = float(min(1e-3, 0.1 / rate))
    band = chattering_band(g["k3"], g["alpha_s"], dt)
    s_tol = max(1e-6, 10.0 * band)
    nominal = fntsmc_bounds(one, 1.0, axes=1)
    tol = max(tol, 10.0 * band / float(nominal.inside_rate[0]))
    b = fntsmc_bounds(one, tol, axes=1)
    bound_total, bound_s = float(b.total[0]), float(b.ts[0])
    # three pairs per double-integrator case, the last one repeated to fill the axes
    m = e.shape[0]
    cases = -(-m // 3)
    padded = np.concatenate([e, np.repeat(e[-1:], 3 * cases - m, axis=0)])
    x0 = np.concatenate([padded[:, 0].reshape(cases, 3), padded[:, 1].reshape(cases, 3)], axis=1)
    res = simulate_batch(DoubleIntegrator(), one, x0, t_final=_horizon(dt, 1.2 * bound_total), dt=dt,
                         record_every=max(1, int(round(0.01 / dt))))
    s = res.diagnostics["s"]
    reach_s = entry_time(res.t, s, s_tol).reshape(-1)[:m]
    settle_e1 = settle_time(res.t, res.states[:, :, :3], tol).reshape(-1)[:m]
    return {
        "s": BoundCheck(name=f"|s| <= {s_tol:.3g} within T_s = {bound_s:.4g} s", bound=np.full(m, bound_s),
                        measured=reach_s, extra={"tolerance": np.asarray(s_tol), "dt": np.asarray(dt)}),
        "e1": BoundCheck(name=f"|e1| <= {tol:.3g} from T_s + T_d + T_inside = {bound_total:.4g} s on",
                         bound=np.full(m, bound_total), measured=settle_e1,
                         extra={"tolerance": np.asarray(tol), "bounds": b}),
    }


def check_fntsmc_run(result: SimulationResult, plant: Any, bounds: FNTSMCBounds) -> BoundCheck:
    """A recorded run of a plant (e.g. the tethered satellite) under the FNTSMC against
    ``bounds``: per case and axis, the time from which |q_i - 0| stays within ``bounds.tol``
    (NaN if it is outside at the end) against ``bounds.total``. The reference must be the
    origin (the seed's q_d = 0)."""
    _instance("check_fntsmc_run", "result", result, SimulationResult, "a landing.SimulationResult")
    _instance("check_fntsmc_run", "plant", plant, Plant, "a landing.plants plant")
    _instance("check_fntsmc_run", "bounds", bounds, FNTSMCBounds, "a landing.theory.FNTSMCBounds")
    if result.t.size == 0:
        raise ParameterError("check_fntsmc_run needs a recorded run (record_every >= 1)")
    q, _ = plant.coordinates(result.states)
    if q.ndim == 2:
        q = q[None]
    measured = settle_time(result.t, q, np.asarray(bounds.tol))
    bound = np.broadcast_to(bounds.total, measured.shape)
    return BoundCheck(
        name=f"|q_i| <= {np.array2string(np.asarray(bounds.tol), precision=4)} from "
             f"{np.array2string(np.asarray(bounds.total), precision=4)} s on",
        bound=bound,
        measured=measured,
        extra={"checkable": np.asarray(bound <= result.t[-1])},
    )
