"""Every bound against simulation: each check simulates the system its bound speaks about and
reports the cases that violate it.

- :func:`check_fixed_time_bound`: the scalar reaching law ``s' = -c1 sig^e1(s) - c2 sig^e2(s)``
  (the Mars fixed-time guidance paper's Lemma 2; eq. 18 with the beta gains, eq. 26 with the
  alpha gains) from any s(0).
- :func:`check_practical_bound`: the same law with a bounded disturbance (Theorem 1; eq. 38
  to 40 for s2, eq. 31 and 45 for s1).
- :func:`check_mss`: a recorded run of :class:`~landing.controllers.FixedTimeMSS` against its
  practical neighbourhoods and times (Theorem 4).
- :func:`check_fntsmc_bound` (the tethered-satellite paper's law on a double integrator, where
  its derivation holds exactly) and :func:`check_fntsmc_run` (a recorded tethered-satellite
  run).
- :func:`check_terminal_reaching_time`: the fuzzy fast-terminal asteroid paper's eq. 7
  (and eq. 5, its alpha -> 0 limit) for
  :class:`~landing.controllers.FastTerminalSMC` started on its surface.

A scalar reaching law is simulated where the library realises it: the exact variant of
FixedTimeMSS on a :class:`~landing.plants.DoubleIntegrator` makes its second sliding variable
obey ``s2' = -alpha1 sig^gamma1(s2) - alpha2 sig^gamma2(s2) + d`` (no drift, unit inertia).
With negligible first-surface gains (beta = 1e-20), s2 is the velocity itself, so each axis of
the double integrator's velocity is one run of the scalar law.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Optional

import numpy as np

from landing._internal.args import integer, real, real_array
from landing._internal.table import ArrayLike
from landing.controllers import FastTerminalSMC, FixedTimeMSS, FixedTimeNTSMC
from landing.disturbances import DisturbanceLike, Sinusoid
from landing.errors import ParameterError, ParameterTypeError
from landing.plants import DoubleIntegrator, Plant
from landing.results import SimulationResult
from landing.simulation import simulate_batch
from landing.theory._signals import entry_time, settle_time
from landing.theory.bounds import (
    FNTSMC_GAINS,
    FNTSMCBounds,
    MSSBounds,
    chattering_band,
    fast_terminal_reaching_time,
    fixed_time_bound,
    fntsmc_bounds,
    law_gains,
    law_parameter,
    practical_radius,
    practical_time_bound,
)

__all__ = [
    "BoundCheck",
    "check_fixed_time_bound",
    "check_practical_bound",
    "check_mss",
    "check_fntsmc_bound",
    "check_fntsmc_run",
    "check_terminal_reaching_time",
]


def _instance(owner: str, name: str, value: Any, cls: type, what: str) -> None:
    """Refuses a ``value`` that is not a ``cls``, naming the argument."""
    if not isinstance(value, cls):
        raise ParameterTypeError(f"{owner}: {name} must be {what}, got {type(value).__name__}")


@dataclass
class BoundCheck:
    """A bound against simulation: ``measured <= bound`` for every case and axis.

    ``measured`` is NaN where the event never happened within the horizon (a violation).

    Parameters
    ----------
    name : str
        What is checked, with the bound's value.
    bound : numpy.ndarray
        The bound per case and axis (s, or the checked quantity's unit).
    measured : numpy.ndarray
        What the simulation gave, same shape and unit (NaN: never).
    extra : dict, optional
        What else the check measured (e.g. the largest excursion afterwards).

    Examples
    --------
    >>> import numpy as np
    >>> from landing.theory import BoundCheck
    >>> c = BoundCheck("t <= 2 s", bound=np.array([2.0, 2.0]), measured=np.array([1.0, np.nan]))
    >>> c.ok, c.violations.tolist()
    (False, [1])
    """

    name: str
    bound: np.ndarray
    measured: np.ndarray
    extra: dict[str, Any] = field(default_factory=dict)

    @property
    def violations(self) -> np.ndarray:
        """Indices of the cases (first axis) with a violation on any axis."""
        bad = np.asarray(~(self.measured <= self.bound))
        if bad.ndim > 1:
            bad = np.asarray(bad.reshape(bad.shape[0], -1).any(axis=1))
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
        status = ("holds" if self.ok
                  else f"VIOLATED in {self.violations.size} of {n} cases: {self.violations[:10].tolist()}")
        return f"BoundCheck({self.name}: {status}; worst measured/bound = {self.worst_ratio:.3f})"


# With these the first surface adds less than 1e-12 to s2 = v + beta1 sig^q1(r) + ... for
# |r| < 1e8, and the exact law's cancellation terms are as small: s2 is the velocity.
_NEGLIGIBLE_S1_GAINS = dict(beta1=1e-20, q1=0.999, beta2=1e-20, q2=1.001)


def _reaching_run(c1: float, e1: float, c2: float, e2: float, s0: np.ndarray, *, disturbance: DisturbanceLike,
                  dt: float, t_final: float, seed: int = 0) -> SimulationResult:
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


def check_fixed_time_bound(
    c1: float, e1: float, c2: float, e2: float, s0: ArrayLike, *, dt: Optional[float] = None, tol: float = 1e-6
) -> BoundCheck:
    """Simulate ``s' = -c1 sig^e1(s) - c2 sig^e2(s)`` from each initial value ``s0`` ((N,), or
    (N, 3) for three axes at once) and compare the time at which |s| first reaches ``tol`` with
    :func:`fixed_time_bound`. ``dt`` defaults to a control period at which the sampled law is
    stable from the largest ``|s0|``; ``tol`` is raised to ten times the :func:`chattering_band`
    of the sampled law if that is larger.

    Parameters
    ----------
    c1, e1, c2, e2 : float
        The reaching law's gains and exponents (0 < e1 < 1 < e2).
    s0 : array_like
        The initial values of s, (N,) or (N, 3) (m/s: s is simulated as a velocity).
    dt : float, optional
        The control period (s).
    tol : float, default 1e-6
        The |s| counted as reached (m/s).

    Returns
    -------
    BoundCheck
        ``measured``: the entry times (s) against the bound (s), per case and axis.

    Examples
    --------
    >>> from landing.theory import check_fixed_time_bound
    >>> check_fixed_time_bound(1.0, 0.5, 1.0, 1.5, [1.0, 10.0])
    BoundCheck(fixed-time bound 4.0602 s for c1=1.0, e1=0.5, c2=1.0, e2=1.5: holds; worst measured/bound = 0.620)
    """
    owner = "check_fixed_time_bound"
    c1, e1, c2, e2 = (real(n, v, owner=owner) for n, v in (("c1", c1), ("e1", e1), ("c2", c2), ("e2", e2)))
    bound = float(fixed_time_bound(c1, e1, c2, e2))
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
    c1: float, e1: float, c2: float, e2: float, s0: ArrayLike, *, d_max: float, theta: float, omega: float = 1.0,
    dt: Optional[float] = None, settle_for: Optional[float] = None,
) -> BoundCheck:
    """Simulate ``s' = -c1 sig^e1(s) - c2 sig^e2(s) + d(t)`` with ``d = d_max sin(omega t)`` from
    each ``s0`` and compare with Theorem 1 of the Mars fixed-time guidance paper: |s| enters
    :func:`practical_radius` within :func:`practical_time_bound` and stays in it
    (``extra["max_after_entry"]``, checked over ``settle_for`` seconds after the bound, by default
    the bound itself).

    Parameters
    ----------
    c1, e1, c2, e2 : float
        The reaching law's gains and exponents (0 < e1 < 1 < e2).
    s0 : array_like
        The initial values of s, (N,) or (N, 3) (m/s).
    d_max : float
        The disturbance's amplitude (m/s^2).
    theta : float
        The share of the law kept to dominate it, 0 < theta < 1.
    omega : float, default 1.0
        The disturbance's angular frequency (rad/s).
    dt : float, optional
        The control period (s).
    settle_for : float, optional
        How long after the bound staying inside is checked (s).

    Returns
    -------
    BoundCheck
        ``measured``: the entry times (s; NaN where |s| leaves the neighbourhood again).

    Examples
    --------
    >>> from landing.theory import check_practical_bound
    >>> check_practical_bound(1.0, 0.5, 1.0, 1.5, [1.0, 10.0], d_max=0.1, theta=0.5)
    BoundCheck(practical bound: |s| <= 0.04 within 8.1204 s (theta=0.5, d_max=0.1): holds; worst measured/bound = 0.293)
    """
    owner = "check_practical_bound"
    c1, e1, c2, e2, d_max, theta, omega = (
        real(n, v, owner=owner) for n, v in (("c1", c1), ("e1", e1), ("c2", c2), ("e2", e2),
                                              ("d_max", d_max), ("theta", theta), ("omega", omega)))
    dt = None if dt is None else real("dt", dt, positive=True, owner=owner)
    settle_for = None if settle_for is None else real("settle_for", settle_for, nonnegative=True, owner=owner)
    radius = float(practical_radius(c1, e1, c2, e2, d_max, theta))
    bound = float(practical_time_bound(c1, e1, c2, e2, theta))
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
    """Check a recorded FixedTimeMSS run against Theorem 4 of the Mars fixed-time guidance paper:
    after ``s2_time`` every |s2_i| stays within ``s2_radius``; after ``settle_time`` every |s1_i|
    within ``s1_radius``. Where the bound time exceeds the horizon, ``extra["checkable"]`` is
    False and only the end of the run is seen.

    Parameters
    ----------
    result : landing.SimulationResult
        A recorded run of a FixedTimeMSS law (s1 in m, s2 in m/s among its diagnostics).
    bounds : MSSBounds
        The bounds to check, e.g. from :func:`mss_bounds`.

    Returns
    -------
    dict of str to BoundCheck
        Checks "s2" and "s1" whose ``measured`` is the time (s) from which the variable stays in
        its neighbourhood (NaN if it is outside at the end of the run).

    Examples
    --------
    >>> import landing
    >>> from landing.controllers import FixedTimeMSS
    >>> from landing.theory import check_mss, mss_bounds
    >>> law = FixedTimeMSS(beta1=1.0, beta2=1.0, q1=0.5, q2=1.5, alpha1=2.0, alpha2=2.0, gamma1=0.5, gamma2=1.5)
    >>> r = landing.simulate(landing.plants.DoubleIntegrator(), law, [1.0, 2.0, -1.0, 0, 0, 0], t_final=20.0, dt=0.01)
    >>> checks = check_mss(r, mss_bounds(law, ap_max=0.01))
    >>> sorted(checks), checks["s2"].bound.shape
    (['s1', 's2'], (1, 3))
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


def _axis_law(law: FixedTimeNTSMC, axis: int) -> FixedTimeNTSMC:
    """The gains of one axis of ``law`` on every axis, the network and the switching term off:
    the law of Theorem 1's nominal case."""
    names = FNTSMC_GAINS + ("rbf_scale_e1", "rbf_scale_e2", "rbf_width")
    gains = law_gains(law, names, None)
    if any(g.ndim > 1 for g in gains):
        raise ParameterError("check_fntsmc_bound takes a law with the same gains for every case")
    kw = {n: float(g[axis]) for n, g in zip(names, gains)}
    return FixedTimeNTSMC(**kw, eps_max=0.0, gamma=0.0, rbf_nodes=1)


def check_fntsmc_bound(law: FixedTimeNTSMC, pairs: Any, *, axis: int = 0, tol: float = 1e-6,
                       dt: Optional[float] = None) -> dict[str, BoundCheck]:
    """Simulate the FNTSMC with the gains of ``axis`` on a :class:`~landing.plants.DoubleIntegrator`
    (unit inertia, no drift, no saturation, network and switching term off: where the
    tethered-satellite paper's derivation holds exactly) from initial errors ``pairs`` ((M, 2):
    e1, e2) and compare with :func:`fntsmc_bounds`: ``"s"``, the first time |s| <= s_tol against
    ``ts``; ``"e1"``, the time from which |e1| <= tol against ``total``.

    The sampled law cannot bring s closer to 0 than its chattering band
    ``(k3 dt)^(1/(1 - alpha_s))`` (:func:`chattering_band`), nor e1 closer than that band over the
    inside rate: ``s_tol`` and ``tol`` are raised to ten times those if larger. ``dt`` defaults to
    a period at which the held command is stable from the largest initial s.

    Parameters
    ----------
    law : landing.controllers.FixedTimeNTSMC
        The law, its gains shared by every case.
    pairs : array_like
        Initial errors (e1 in rad, e2 in rad/s), (M, 2).
    axis : int, default 0
        Whose gains are used.
    tol : float, default 1e-6
        The |e1| counted as settled (rad).
    dt : float, optional
        The control period (s).

    Returns
    -------
    dict of str to BoundCheck
        Checks "s" and "e1", times in s.

    Examples
    --------
    >>> import landing
    >>> from landing.theory import check_fntsmc_bound
    >>> checks = check_fntsmc_bound(landing.scenarios.tether_law(), [[0.1, 0.0], [0.5, 0.1]], axis=1, tol=1e-3)
    >>> checks["e1"].ok, checks["s"].ok
    (True, True)
    """
    owner = "check_fntsmc_bound"
    _instance(owner, "law", law, FixedTimeNTSMC, "a landing.controllers.FixedTimeNTSMC law")
    e = real_array("pairs", pairs, finite=True, owner=owner)
    if e.size == 0 or e.size % 2:
        raise ParameterError(f"{owner}: pairs has shape {e.shape}; it takes (M, 2) pairs (e1, e2) with M >= 1")
    e = e.reshape(-1, 2)
    integer("pairs M", e.shape[0], cap="max_cases", owner=owner)
    tol = real("tol", tol, positive=True, owner=owner)
    dt = None if dt is None else real("dt", dt, positive=True, owner=owner)
    axes = law_gains(law, FNTSMC_GAINS, None)[0].shape[-1]
    axis = integer("axis", axis, minimum=0, maximum=axes - 1, owner=owner)
    one = _axis_law(law, axis)
    g = {n: float(getattr(one, n)) for n in FNTSMC_GAINS}
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
    assert res.states is not None  # recorded: record_every >= 1
    settle_e1 = settle_time(res.t, res.states[:, :, :3], tol).reshape(-1)[:m]
    return {
        "s": BoundCheck(name=f"|s| <= {s_tol:.3g} within T_s = {bound_s:.4g} s", bound=np.full(m, bound_s),
                        measured=reach_s, extra={"tolerance": np.asarray(s_tol), "dt": np.asarray(dt)}),
        "e1": BoundCheck(name=f"|e1| <= {tol:.3g} from T_s + T_d + T_inside = {bound_total:.4g} s on",
                         bound=np.full(m, bound_total), measured=settle_e1,
                         extra={"tolerance": np.asarray(tol), "bounds": b}),
    }


def check_fntsmc_run(result: SimulationResult, plant: Any, bounds: FNTSMCBounds) -> BoundCheck:
    """A recorded run of a plant (e.g. the tethered satellite) under the FNTSMC against ``bounds``:
    per case and axis, the time from which |q_i - 0| stays within ``bounds.tol`` (NaN if it is
    outside at the end) against ``bounds.total``. The reference must be the origin (the
    tethered-satellite paper's q_d = 0).

    Parameters
    ----------
    result : landing.SimulationResult
        The recorded run.
    plant : landing.plants.Plant
        The plant it ran, whose ``coordinates`` give q (rad).
    bounds : FNTSMCBounds
        The bounds, from :func:`fntsmc_bounds` (``tol`` in rad, times in s).

    Returns
    -------
    BoundCheck
        ``measured``: the settling times (s) per case and axis; ``extra["checkable"]`` where the
        bound lies within the run.

    Examples
    --------
    >>> import landing
    >>> from landing.theory import check_fntsmc_run, fntsmc_bounds
    >>> sc = landing.scenarios.preset("tether_fntsmc_simplified")
    >>> r = sc.simulate(t_final=1.0)
    >>> c = check_fntsmc_run(r, sc.plant, fntsmc_bounds(sc.controller, tol=0.01))
    >>> c.bound.shape, bool(c.extra["checkable"].any())
    ((1, 2), False)
    """
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


# The fuzzy fast-terminal asteroid paper: the fast terminal surface's reaching time (eq. 7).

def check_terminal_reaching_time(law: FastTerminalSMC, e0: ArrayLike, *, tol: float = 1e-3,
                                 dt: Optional[float] = None) -> BoundCheck:
    """Simulate ``law`` (its gains shared by every case; each axis its own) on a
    :class:`~landing.plants.DoubleIntegrator` (unit inertia, no drift, no saturation) from initial
    errors ``e0`` ((N,) or (N, 3)) started on the sliding surface,
    ``e'(0) = -alpha e0 - beta sig^(p/q)(e0)``, and compare the first time |e| <= tol with the
    fuzzy fast-terminal asteroid paper's eq. 7 time to reach 0,
    :func:`~landing.theory.fast_terminal_reaching_time`.

    On the surface the error obeys ``e' = -alpha e - beta sig^(p/q)(e)``, so the time to come down
    to ``tol`` is eq. 7 at e0 less eq. 7 at tol: that prediction is ``extra["predicted"]``, and
    ``extra["difference"]`` what the sampled law measures against it (a few control periods when
    eq. 7 holds). ``tol`` is raised to ten times the law's ``e_floor`` (below which the equivalent
    control is guarded, not the surface's) if smaller. ``dt`` defaults to a period a hundred times
    shorter than the fastest time constant of the surface. Eq. 5 is eq. 7's limit as alpha tends
    to 0: a law with a small alpha checks it.

    Parameters
    ----------
    law : landing.controllers.FastTerminalSMC
        The law, its gains shared by every case.
    e0 : array_like
        Non-zero initial errors (m), (N,) or (N, 3).
    tol : float, default 1e-3
        The |e| counted as reached (m).
    dt : float, optional
        The control period (s).

    Returns
    -------
    BoundCheck
        ``measured``: the entry times (s) against eq. 7's times (s).

    Examples
    --------
    >>> from landing.controllers import FastTerminalSMC
    >>> from landing.theory import check_terminal_reaching_time
    >>> law = FastTerminalSMC(alpha=1.0, beta=1.0, p=3, q=5, k=1.0)
    >>> check_terminal_reaching_time(law, [1.0, 2.0])
    BoundCheck(|e| <= 0.01 within eq. 7's time to reach 0: holds; worst measured/bound = 0.825)
    """
    owner = "check_terminal_reaching_time"
    _instance(owner, "law", law, FastTerminalSMC, "a landing.controllers.FastTerminalSMC law")
    e = _as_cases(owner, e0).astype(float)
    if np.any(e == 0):
        raise ParameterError(f"{owner}: e0 has a zero; it takes non-zero initial errors (at 0 the time is 0)")
    gains = [law_parameter(law, n, 3) for n in ("alpha", "beta", "p", "q")]
    if any(g.ndim > 1 for g in gains):
        raise ParameterError(f"{owner} takes a law with the same gains for every case")
    alpha, beta, p, q = gains
    e_floor = float(np.max(law_parameter(law, "e_floor", 3)))
    tol = max(real("tol", tol, positive=True, owner=owner), 10.0 * e_floor)
    r = p / q
    if dt is None:
        e_max = np.abs(e).max(axis=0)
        # the surface's local rate at e: alpha + beta r |e|^(r - 1), largest at the smallest
        # |e| the check reads (tol)
        rate = float(np.max(alpha + beta * r * np.minimum(e_max, tol) ** (r - 1.0)))
        dt = float(min(1e-2, 0.01 / rate))
    else:
        dt = real("dt", dt, positive=True, owner=owner)
    de0 = -alpha * e - beta * np.sign(e) * np.abs(e) ** r
    bound = np.asarray(fast_terminal_reaching_time(np.abs(e), alpha, beta, p, q), dtype=float)
    predicted = bound - np.asarray(fast_terminal_reaching_time(np.full_like(e, tol), alpha, beta, p, q), dtype=float)
    predicted = np.where(np.abs(e) <= tol, 0.0, predicted)
    res = simulate_batch(DoubleIntegrator(), law, np.concatenate([e, de0], axis=1),
                         t_final=_horizon(dt, 1.2 * float(bound.max()) + 10 * dt), dt=dt, record_every=1)
    assert res.states is not None  # recorded: record_every = 1
    measured = entry_time(res.t, res.states[:, :, :3], tol)
    return BoundCheck(name=f"|e| <= {tol:.3g} within eq. 7's time to reach 0", bound=bound, measured=measured,
                      extra={"predicted": predicted, "difference": measured - predicted,
                             "tolerance": np.asarray(tol), "dt": np.asarray(dt)})
