"""The convergence bounds of the fixed-time laws, computed by the Rust core
(``landing_core::theory``) and broadcast here over arrays: the Mars fixed-time guidance
paper's fixed-time and practical bounds (Lemma 2, Theorems 1-4, Remark 1) and the
tethered-satellite paper's FNTSMC bounds (Theorem 1, made sound), with the printed eq. 42 and
47 for the record."""

from __future__ import annotations

import math
import sys
from dataclasses import dataclass
from typing import Any, Callable, Optional, Union

import numpy as np

from landing import _core
from landing._internal.args import integer, real, real_array
from landing._internal.limits import require_memory
from landing._internal.table import ArrayLike
from landing.controllers import Controller, FixedTimeMSS, FixedTimeNTSMC
from landing.disturbances import DisturbanceLike, compiled
from landing.errors import LandingError, ParameterError, ParameterTypeError
from landing.scenarios import Scenario

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
    "FNTSMCBounds",
    "fntsmc_bounds",
    "terminal_reaching_time",
    "fast_terminal_reaching_time",
    "terminal_reaching_time_printed",
    "fast_terminal_reaching_time_printed",
    "fntsmc_ts_printed",
    "fntsmc_td_printed",
    "FNTSMC_GAINS",
    "law_gains",
]

#: What a broadcasting bound returns: a number for numbers, an array for arrays.
Real = Union[float, np.ndarray]


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


def _vectorized(fn: Callable[..., float], owner: str, **args: Any) -> Real:
    out = np.vectorize(fn, otypes=[float])(*_reals(owner, **args))
    return float(out) if out.ndim == 0 else out


def fixed_time_bound(c1: ArrayLike, e1: ArrayLike, c2: ArrayLike, e2: ArrayLike) -> Real:
    """The Mars fixed-time guidance paper's Lemma 2 with k = 1 on V = s^2/2 for
    ``s' = -c1 sig^e1(s) - c2 sig^e2(s)``:
    ``T <= 1/(c1 (1-e1) 2^((e1-1)/2)) + 1/(c2 (e2-1) 2^((e2-1)/2))``, whatever s(0).

    Eq. 18 is this with (beta1, q1, beta2, q2), eq. 26 with (alpha1, gamma1, alpha2, gamma2).
    Arrays broadcast.

    Parameters
    ----------
    c1, c2 : float or array_like
        The gains of the two terms (1/s times the unit of s to the power 1 - e).
    e1, e2 : float or array_like
        The exponents, 0 < e1 < 1 < e2 (dimensionless).

    Returns
    -------
    float or numpy.ndarray
        The bound on the time s takes to reach 0 (s): a float for scalars, else the broadcast shape.

    Examples
    --------
    >>> from landing.theory import fixed_time_bound
    >>> print(f"{fixed_time_bound(1.0, 0.5, 1.0, 1.5):.4f} s")
    4.0602 s
    >>> fixed_time_bound([1.0, 2.0], 0.5, 1.0, 1.5).shape
    (2,)
    """
    return _vectorized(_core.fixed_time_bound, "fixed_time_bound", c1=c1, e1=e1, c2=c2, e2=e2)


def practical_time_bound(c1: ArrayLike, e1: ArrayLike, c2: ArrayLike, e2: ArrayLike, theta: ArrayLike) -> Real:
    """Theorem 1 of the Mars fixed-time guidance paper (k = 1): the time to reach the practical
    neighbourhood, the fixed-time bound (:func:`fixed_time_bound`) divided by theta.

    Parameters
    ----------
    c1, e1, c2, e2 : float or array_like
        The reaching law's gains and exponents, as :func:`fixed_time_bound` takes them.
    theta : float or array_like
        The share of the law kept to dominate the disturbance, 0 < theta < 1 (dimensionless).

    Returns
    -------
    float or numpy.ndarray
        The bound (s); arrays broadcast.

    Examples
    --------
    >>> from landing.theory import practical_time_bound
    >>> print(f"{practical_time_bound(1.0, 0.5, 1.0, 1.5, 0.5):.4f} s")
    8.1204 s
    """
    return _vectorized(_core.practical_time_bound, "practical_time_bound", c1=c1, e1=e1, c2=c2, e2=e2,
                       theta=theta)


def practical_radius(c1: ArrayLike, e1: ArrayLike, c2: ArrayLike, e2: ArrayLike, d_max: ArrayLike,
                     theta: ArrayLike) -> Real:
    """Eq. 38-39 of the Mars fixed-time guidance paper:
    ``min{(d_max/((1-theta) c1))^(1/e1), (d_max/((1-theta) c2))^(1/e2)}``, the
    neighbourhood that ``s' = -c1 sig^e1(s) - c2 sig^e2(s) + d``, |d| <= d_max, reaches.

    Parameters
    ----------
    c1, e1, c2, e2 : float or array_like
        The reaching law's gains and exponents, as :func:`fixed_time_bound` takes them.
    d_max : float or array_like
        The bound on |d| (the unit of s per second: m/s^2 for s2, m/s for s1).
    theta : float or array_like
        As :func:`practical_time_bound` takes it, 0 < theta < 1.

    Returns
    -------
    float or numpy.ndarray
        The radius, in the unit of s (m/s for s2, m for s1); arrays broadcast.

    Examples
    --------
    >>> from landing.theory import practical_radius
    >>> print(f"{practical_radius(1.0, 0.5, 1.0, 1.5, d_max=0.1, theta=0.5):.4f}")
    0.0400
    """
    return _vectorized(_core.practical_radius, "practical_radius", c1=c1, e1=e1, c2=c2, e2=e2, d_max=d_max,
                       theta=theta)


@dataclass(frozen=True)
class MSSBounds:
    """The Mars fixed-time guidance paper's bounds for FixedTimeMSS, per axis (shape (3,), or
    (N, 3) for per-case gains). Made by :func:`mss_bounds`; the arguments are its fields.

    Parameters
    ----------
    t1, t2 : numpy.ndarray
        Eq. 18 and 26, without disturbance (s).
    s2_radius, s2_time : numpy.ndarray
        Eq. 39 and 40, the neighbourhood of s2 (m/s) under |a_p| <= ap_max, and when it is
        reached (s).
    s1_radius, s1_time : numpy.ndarray
        Eq. 31 and 45, that of s1 = r - r_d (m) once s2 is in its own, and the time it takes then
        (s).
    printed_time : numpy.ndarray
        Eq. 32 as printed, max(s2_time, s1_time) (s).
    settle_time : numpy.ndarray
        s2_time + s1_time (s), the sound bound: s1 obeys its perturbed reaching law only once s2
        is in its neighbourhood.
    ap_max : numpy.ndarray
        The disturbance bound per axis (m/s^2).
    theta1, theta2 : float
        The shares of the two laws kept to dominate the disturbance (dimensionless).

    Examples
    --------
    >>> import landing
    >>> from landing.theory import mss_bounds
    >>> b = mss_bounds(landing.scenarios.preset("mars_nominal").controller, ap_max=0.01)
    >>> type(b).__name__, b.settle_time.shape
    ('MSSBounds', (3,))
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
        fmt = _fmt_cases
        return (
            f"MSSBounds(theta1={self.theta1}, theta2={self.theta2}, ap_max={fmt(self.ap_max)})\n"
            f"  T1 (eq. 18)            {fmt(self.t1)} s\n"
            f"  T2 (eq. 26)            {fmt(self.t2)} s\n"
            f"  |s2| radius (eq. 39)   {fmt(self.s2_radius)} m/s, reached by {fmt(self.s2_time)} s (eq. 40)\n"
            f"  |s1| radius (eq. 31)   {fmt(self.s1_radius)} m, {fmt(self.s1_time)} s later (eq. 45)\n"
            f"  eq. 32 as printed      {fmt(self.printed_time)} s; sound total {fmt(self.settle_time)} s"
        )


def _fmt(a: Any) -> str:
    """A bound as the printed tables show it."""
    return np.array2string(np.asarray(a), precision=4, floatmode="maxprec")


def _fmt_cases(a: Any) -> str:
    """A bound as :func:`_fmt` shows it, per-case bounds (N, D) as their range over the cases."""
    a = np.asarray(a)
    if a.ndim == 2:
        return f"{_fmt(a.min(axis=0))} to {_fmt(a.max(axis=0))} over {a.shape[0]} cases"
    return _fmt(a)


def law_parameter(law: Controller, name: str, axes: int) -> np.ndarray:
    """The numeric parameter ``name`` of ``law`` as the core reads it for ``axes`` axes:
    ``(axes,)`` when shared by every case, ``(N, axes)`` per case."""
    values = np.asarray(law._core.parameter(name, axes), dtype=float)
    if values.ndim == 1:  # a scalar parameter: (cases,)
        values = np.repeat(values[:, None], axes, axis=1)
    return values[0] if values.shape[0] == 1 else values


def mss_bounds(law: FixedTimeMSS, ap_max: Any = 0.0, theta1: float = 0.5, theta2: float = 0.5) -> MSSBounds:
    """The bounds of the Mars fixed-time guidance paper's Theorems 2-4 for a FixedTimeMSS law
    (per axis), under a disturbance bounded by ``ap_max`` per axis (see :func:`disturbance_bound`).

    Parameters
    ----------
    law : landing.controllers.FixedTimeMSS
        The law whose gains are read (shared by every case, or per case).
    ap_max : float or array_like, default 0.0
        The disturbance acceleration's bound per axis (m/s^2): a scalar, (3,) or (N, 3).
    theta1, theta2 : float, default 0.5
        The shares of the s1 and s2 laws kept to dominate the disturbance, 0 < theta < 1.

    Returns
    -------
    MSSBounds
        Times in s, the s2 radius in m/s, the s1 radius in m, per axis.

    Examples
    --------
    >>> import landing
    >>> from landing.theory import mss_bounds
    >>> b = mss_bounds(landing.scenarios.preset("mars_nominal").controller, ap_max=0.01)
    >>> print(f"{b.settle_time[0]:.1f} s")
    755.6 s
    """
    if not isinstance(law, FixedTimeMSS):
        raise ParameterTypeError(f"mss_bounds takes a FixedTimeMSS law, got {type(law).__name__}")
    names = ("beta1", "q1", "beta2", "q2", "alpha1", "gamma1", "alpha2", "gamma2")
    gains = [law_parameter(law, n, 3) for n in names]
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
        b1, q1, b2, q2, a1, g1, a2, g2, ap_i = (float(a[idx]) for a in args)
        b = _core.mss_bounds(b1, q1, b2, q2, a1, g1, a2, g2, ap_i, float(theta1), float(theta2))
        for k in keys:
            out[k][idx] = b[k]
    return MSSBounds(**out, ap_max=args[-1], theta1=float(theta1), theta2=float(theta2))


def scenario_bounds(scenario: Scenario) -> Optional[MSSBounds]:
    """The Mars fixed-time guidance paper's practical fixed-time bounds for a scenario's law and
    disturbance (what :meth:`Scenario.bounds` returns): None unless the law is FixedTimeMSS and
    the scenario's ``theta`` is set, and None for a disturbance given per case (its bound is one
    number per axis, shared by every case).

    Parameters
    ----------
    scenario : landing.scenarios.Scenario
        The scenario whose controller, disturbance and ``theta`` are read.

    Returns
    -------
    MSSBounds or None
        The bounds (s, m/s, m), or None as above.

    Examples
    --------
    >>> import landing
    >>> from landing.theory import scenario_bounds
    >>> print(scenario_bounds(landing.scenarios.preset("mars_nominal")))  # no theta set
    None
    """
    if scenario.theta is None or not isinstance(scenario.controller, FixedTimeMSS):
        return None
    if any(name.startswith("disturbance") for name in scenario.case_rows(1)):
        return None
    ap_max = disturbance_bound(scenario.disturbance, scenario.plant.axes)
    return mss_bounds(scenario.controller, ap_max, *scenario.theta)


def disturbance_bound(disturbance: DisturbanceLike, axes: int = 3) -> np.ndarray:
    """Per-axis bound on |d_i(t)|: |constant| + sum of |amplitudes| + noise bound.

    Parameters
    ----------
    disturbance : landing.disturbances.Disturbance, sequence of them, or None
        The disturbance acceleration (m/s^2).
    axes : int, default 3
        The plant's axes, 2 or 3.

    Returns
    -------
    numpy.ndarray
        The bound per axis (m/s^2), shape (axes,); zeros for no disturbance.

    Examples
    --------
    >>> from landing.theory import disturbance_bound
    >>> disturbance_bound(None)
    array([0., 0., 0.])
    """
    axes = integer("axes", axes, owner="disturbance_bound")
    if axes not in (2, 3):
        raise ParameterError(f"disturbance_bound: axes = {axes} violates axes in (2, 3)")
    handle = compiled(disturbance)
    if handle is None:
        return np.zeros(axes)
    return np.asarray(handle.bound(axes))


def min_final_time(r0: ArrayLike, v0: ArrayLike, a_max: ArrayLike, g: ArrayLike = 0.0) -> tuple[Real, Real]:
    """The Mars fixed-time guidance paper's Remark 1, sign-consistent, per axis: ``(tf1, tf2)`` with
    tf1 the first time the position can reach 0 at full thrust towards the target (with gravity g
    on that axis, negative for z up) and tf2 the time to null the velocity at full thrust. A soft
    landing needs ``t_f >= max(tf1, tf2)`` over the axes. Arrays broadcast.

    Parameters
    ----------
    r0 : float or array_like
        Initial position on the axis (m).
    v0 : float or array_like
        Initial velocity on the axis (m/s).
    a_max : float or array_like
        The thrust acceleration available (m/s^2).
    g : float or array_like, default 0.0
        Gravity on the axis (m/s^2, negative for z up).

    Returns
    -------
    tuple of numpy.ndarray
        ``(tf1, tf2)`` (s), each of the broadcast shape (0-d for scalars).

    Examples
    --------
    >>> from landing.theory import min_final_time
    >>> tf1, tf2 = min_final_time(100.0, -10.0, 5.0, g=-3.71)
    >>> print(f"tf1 = {float(tf1):.2f} s, tf2 = {float(tf2):.2f} s")
    tf1 = 3.78 s, tf2 = 7.75 s
    """
    f = np.vectorize(lambda *a: _core.min_final_time(*a), otypes=[float, float])
    tf1, tf2 = f(*_reals("min_final_time", r0=r0, v0=v0, a_max=a_max, g=g))
    return tf1, tf2


def min_time_to_rest(r0: ArrayLike, v0: ArrayLike, a_max: ArrayLike, g: ArrayLike = 0.0) -> Real:
    """The shortest time to bring one axis from (r0, v0) to rest at 0 with thrust up to ``a_max``
    either way plus gravity ``g`` (time-optimal bang-bang, one switch): a lower bound on any
    landing time on that axis. Infinite when the thrust cannot overcome gravity. Arrays broadcast.

    Parameters
    ----------
    r0 : float or array_like
        Initial position on the axis (m).
    v0 : float or array_like
        Initial velocity on the axis (m/s).
    a_max : float or array_like
        The thrust acceleration available either way (m/s^2).
    g : float or array_like, default 0.0
        Gravity on the axis (m/s^2, negative for z up).

    Returns
    -------
    float or numpy.ndarray
        The time (s).

    Examples
    --------
    >>> from landing.theory import min_time_to_rest
    >>> print(f"{min_time_to_rest(100.0, -10.0, 5.0, g=-3.71):.2f} s")
    12.57 s
    """
    return _vectorized(_core.min_time_to_rest, "min_time_to_rest", r0=r0, v0=v0, a_max=a_max, g=g)


def chattering_band(c1: float, e1: float, dt: float) -> float:
    """Half-width of the band a sampled ``s' = -c1 sig^e1(s)`` (e1 < 1) chatters in: where one held
    step ``c1 |s|^e1 dt`` equals ``|s|``, ``(c1 dt)^(1/(1-e1))``. Continuous time reaches 0; the
    sampled law cannot get further.

    Parameters
    ----------
    c1 : float
        The gain, > 0.
    e1 : float
        The exponent, 0 < e1 < 1.
    dt : float
        The control period (s), > 0.

    Returns
    -------
    float
        The band's half-width, in the unit of s.

    Examples
    --------
    >>> from landing.theory import chattering_band
    >>> print(f"{chattering_band(1.0, 0.5, dt=0.01):.1e}")
    1.0e-04
    """
    c1 = real("c1", c1, positive=True, owner="chattering_band")
    e1 = real("e1", e1, owner="chattering_band")
    if not 0 < e1 < 1:
        raise ParameterError(f"chattering_band: e1 = {e1:g} violates 0 < e1 < 1")
    dt = real("dt", dt, positive=True, owner="chattering_band")
    log_band = math.log(c1) + math.log(dt)
    if log_band / (1.0 - e1) > math.log(sys.float_info.max):
        raise ParameterError(f"chattering_band: (c1 dt)^(1/(1 - e1)) with c1 = {c1:g}, dt = {dt:g}, e1 = {e1:g} "
                             "exceeds the largest double: no band to speak of (a smaller c1 dt)")
    return float((c1 * dt) ** (1.0 / (1.0 - e1)))


# The fuzzy fast-terminal asteroid paper: the terminal and fast terminal surfaces' reaching times (eq. 5 and 7).


def terminal_reaching_time(e0: ArrayLike, beta: ArrayLike, p: ArrayLike, q: ArrayLike) -> Real:
    """The fuzzy fast-terminal asteroid paper's eq. 5: the time the error takes to reach 0 from
    ``e0`` on the terminal sliding surface ``s = e' + beta sig^(p/q)(e) = 0`` (0 < p < q),
    ``t_s = q / (beta (q - p)) |e0|^((q - p)/q)``. The paper prints p and q swapped
    (:func:`terminal_reaching_time_printed`), which is negative for its own p < q. Arrays
    broadcast; checked against simulation by :func:`check_terminal_reaching_time`.

    Parameters
    ----------
    e0 : float or array_like
        The initial error (m).
    beta : float or array_like
        The surface's gain, > 0.
    p, q : float or array_like
        The exponent p/q, 0 < p < q.

    Returns
    -------
    float or numpy.ndarray
        The time (s).

    Examples
    --------
    >>> from landing.theory import terminal_reaching_time
    >>> print(f"{terminal_reaching_time(1.0, beta=1.0, p=3, q=5):.2f} s")
    2.50 s
    """
    return _vectorized(_core.terminal_reaching_time, "terminal_reaching_time", e0=e0, alpha=0.0, beta=beta, p=p,
                       q=q)


def fast_terminal_reaching_time(e0: ArrayLike, alpha: ArrayLike, beta: ArrayLike, p: ArrayLike,
                                q: ArrayLike) -> Real:
    """The fuzzy fast-terminal asteroid paper's eq. 7: the time the error takes to reach 0 from
    ``e0`` on the fast terminal surface ``s = e' + alpha e + beta sig^(p/q)(e) = 0`` (eq. 6,
    0 < p < q, alpha >= 0), ``t_s = q / (alpha (q - p)) ln((alpha |e0|^((q - p)/q) + beta) / beta)``;
    at alpha = 0 its limit, eq. 5 (:func:`terminal_reaching_time`). The paper prints p and q
    swapped (:func:`fast_terminal_reaching_time_printed`). Arrays broadcast; checked against
    simulation by :func:`check_terminal_reaching_time`.

    Parameters
    ----------
    e0 : float or array_like
        The initial error (m).
    alpha : float or array_like
        The surface's linear gain (1/s), >= 0.
    beta : float or array_like
        The surface's terminal gain, > 0.
    p, q : float or array_like
        The exponent p/q, 0 < p < q.

    Returns
    -------
    float or numpy.ndarray
        The time (s).

    Examples
    --------
    >>> from landing.theory import fast_terminal_reaching_time
    >>> print(f"{fast_terminal_reaching_time(1.0, alpha=1.0, beta=1.0, p=3, q=5):.4f} s")
    1.7329 s
    """
    return _vectorized(_core.terminal_reaching_time, "fast_terminal_reaching_time", e0=e0, alpha=alpha, beta=beta,
                       p=p, q=q)


def terminal_reaching_time_printed(e0: ArrayLike, beta: ArrayLike, p: ArrayLike, q: ArrayLike) -> Real:
    """The fuzzy fast-terminal asteroid paper's eq. 5 as printed,
    ``p / (beta (p - q)) |e0|^((p - q)/p)``: negative for the paper's p < q. Returned as printed,
    whatever its sign. Arrays broadcast.

    Parameters
    ----------
    e0 : float or array_like
        The initial error (m).
    beta : float or array_like
        The surface's gain.
    p, q : float or array_like
        The exponent p/q as the surface has it.

    Returns
    -------
    float or numpy.ndarray
        The printed formula's value (s).

    Examples
    --------
    >>> from landing.theory import terminal_reaching_time_printed
    >>> print(f"{terminal_reaching_time_printed(1.0, beta=1.0, p=3, q=5):.2f} s")
    -1.50 s
    """
    return _vectorized(_core.terminal_reaching_time_printed, "terminal_reaching_time_printed", e0=e0, alpha=0.0,
                       beta=beta, p=p, q=q)


def fast_terminal_reaching_time_printed(e0: ArrayLike, alpha: ArrayLike, beta: ArrayLike, p: ArrayLike,
                                        q: ArrayLike) -> Real:
    """The fuzzy fast-terminal asteroid paper's eq. 7 as printed,
    ``p / (alpha (p - q)) (ln(alpha |e0|^((p - q)/p) + beta) - ln beta)`` (|e0| for the paper's
    e0). Returned as printed, whatever its sign. Arrays broadcast.

    Parameters
    ----------
    e0 : float or array_like
        The initial error (m).
    alpha : float or array_like
        The surface's linear gain (1/s).
    beta : float or array_like
        The surface's terminal gain.
    p, q : float or array_like
        The exponent p/q as the surface has it.

    Returns
    -------
    float or numpy.ndarray
        The printed formula's value (s).

    Examples
    --------
    >>> from landing.theory import fast_terminal_reaching_time_printed
    >>> print(f"{fast_terminal_reaching_time_printed(1.0, alpha=1.0, beta=1.0, p=3, q=5):.4f} s")
    -1.0397 s
    """
    return _vectorized(_core.terminal_reaching_time_printed, "fast_terminal_reaching_time_printed", e0=e0,
                       alpha=alpha, beta=beta, p=p, q=q)


# The tethered-satellite paper: the fixed-time NTSMC with RBF compensation (law 9).

#: The FixedTimeNTSMC gains its bounds read, in the core's order.
FNTSMC_GAINS = ("k1", "p1", "k2", "p2", "k3", "alpha_s", "beta_s", "sigma_phi")


def fntsmc_ts_printed(c_v: ArrayLike, alpha_s: ArrayLike, beta_s: ArrayLike) -> Real:
    """The tethered-satellite paper's eq. 42 as printed,
    ``2/(c_v (z4 - 1)) + 2/(c_v (1 - z3))`` with ``z3 = (3 alpha_s - 1)/(2 alpha_s)``,
    ``z4 = (3 beta_s - 1)/(2 beta_s)`` (the paper's degrees). The paper never gives Lemma 2's
    ``c_v``, so this is a function of it. Arrays broadcast.

    Parameters
    ----------
    c_v : float or array_like
        Lemma 2's constant (1/s).
    alpha_s, beta_s : float or array_like
        The reaching law's exponents (dimensionless).

    Returns
    -------
    float or numpy.ndarray
        The printed formula's value (s).

    Examples
    --------
    >>> from landing.theory import fntsmc_ts_printed
    >>> print(f"{fntsmc_ts_printed(1.0, alpha_s=0.9, beta_s=1.1):.1f} s")
    80.0 s
    """
    return _vectorized(_core.fntsmc_ts_printed, "fntsmc_ts_printed", c_v=c_v, alpha_s=alpha_s, beta_s=beta_s)


def fntsmc_td_printed(k1: ArrayLike, p1: ArrayLike, k2: ArrayLike, p2: ArrayLike, d: ArrayLike = 0.5) -> Real:
    """The tethered-satellite paper's eq. 47 as printed, ``2/(d g1 (1 - p1)) + 2/(d g2 (p2 - 1))``
    with ``g1 = 2^((p1+1)/2) k1``, ``g2 = 2^((p2+1)/2) (k2 - 1/(p2+1))``. Not a bound for the law:
    Lemma 4 needs p1 < 1 < p2 and g2 > 0, eq. 21 and Table 2 have p1 > 1 > p2 and g2 < 0 (see
    :func:`fntsmc_bounds`). Returned as printed, whatever its sign. Arrays broadcast.

    Parameters
    ----------
    k1, p1, k2, p2 : float or array_like
        The sliding surface's gains and exponents (dimensionless).
    d : float or array_like, default 0.5
        The constant of Lemma 4 (dimensionless).

    Returns
    -------
    float or numpy.ndarray
        The printed formula's value (s).

    Examples
    --------
    >>> from landing.theory import fntsmc_td_printed
    >>> print(f"{fntsmc_td_printed(1.0, 1.2, 1.0, 0.8):.2f} s")
    -33.45 s
    """
    return _vectorized(_core.fntsmc_td_printed, "fntsmc_td_printed", k1=k1, p1=p1, k2=k2, p2=p2, d=d)


@dataclass(frozen=True)
class FNTSMCBounds:
    """The tethered-satellite paper's Theorem 1 made sound, per axis (shape (D,), or (N, D) for
    per-case gains). Made by :func:`fntsmc_bounds`; the arguments are its fields.

    With ``d_max = 0`` (no disturbance of the s dynamics) the radii are 0 and the times are the
    nominal fixed-time bounds; with ``d_max > 0`` they are the practical ones (times divided by
    ``theta``). The law's derivation assumes an unsaturated actuator.

    Parameters
    ----------
    ts : numpy.ndarray
        Time for s to reach its neighbourhood s_radius (eq. 42's role), from any state (s).
    s_radius : numpy.ndarray
        That neighbourhood (rad/s).
    td : numpy.ndarray
        Then, time for |e1| to reach max(sigma_phi, e1_radius) (eq. 47's role) (s).
    e1_radius : numpy.ndarray
        The neighbourhood of e1 the disturbance allows (rad).
    inside_rate : numpy.ndarray
        The rate at which e1 decays at least inside sigma_phi (1/s).
    t_inside : numpy.ndarray
        Then, time to reach ``tol`` inside sigma_phi (s; the fixed-time part of the law ends at
        sigma_phi by design).
    total : numpy.ndarray
        ts + td + t_inside (s): from then on |e1| <= tol, whatever the initial state.
    printed_td : numpy.ndarray
        Eq. 47 as printed with ``d`` (s; not a bound, kept for the record).
    tol : numpy.ndarray
        The tolerance on |e1| (rad).
    d_max : numpy.ndarray
        The bound on the disturbance of the s dynamics (rad/s^2).
    theta, d : float
        The share of the law kept to dominate the disturbance, and eq. 47's constant.

    Examples
    --------
    >>> import landing
    >>> from landing.theory import fntsmc_bounds
    >>> b = fntsmc_bounds(landing.scenarios.tether_law(), tol=0.01)
    >>> type(b).__name__, b.total.shape
    ('FNTSMCBounds', (2,))
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
        fmt = _fmt
        return (
            f"FNTSMCBounds(tol={fmt(self.tol)}, d_max={fmt(self.d_max)}, theta={self.theta})\n"
            f"  T_s, s reaches {fmt(self.s_radius)}         {fmt(self.ts)} s\n"
            f"  T_d, |e1| reaches max(sigma_phi, {fmt(self.e1_radius)})  {fmt(self.td)} s\n"
            f"  then |e1| reaches tol at rate {fmt(self.inside_rate)} 1/s  {fmt(self.t_inside)} s\n"
            f"  total                                 {fmt(self.total)} s\n"
            f"  eq. 47 as printed (d = {self.d}, not a bound)  {fmt(self.printed_td)} s"
        )


def law_gains(law: FixedTimeNTSMC, names: tuple[str, ...], axes: Optional[int]) -> list[np.ndarray]:
    """The gains ``names`` of ``law`` per axis, ``(axes,)`` (or ``(N, axes)`` per case), as the core
    reads them; ``axes`` defaults to the gains' own length (2, the tethered satellite's, when they
    are scalars).

    Parameters
    ----------
    law : landing.controllers.FixedTimeNTSMC
        The law whose gains are read.
    names : tuple of str
        The gains' names, e.g. :data:`FNTSMC_GAINS`.
    axes : int or None
        The number of axes, or None for the gains' own length.

    Returns
    -------
    list of numpy.ndarray
        One array per name, in the order of ``names``, in the gain's own unit.

    Examples
    --------
    >>> import landing
    >>> from landing.theory.bounds import law_gains
    >>> [g.shape for g in law_gains(landing.scenarios.tether_law(), ("k1", "p1"), None)]
    [(2,), (2,)]
    """
    if axes is None:
        sizes = {np.shape(getattr(law, n))[-1] for n in names if np.ndim(getattr(law, n)) >= 1}
        sizes.discard(1)
        axes = sizes.pop() if len(sizes) == 1 else 2
    return [law_parameter(law, n, axes) for n in names]


def fntsmc_bounds(law: FixedTimeNTSMC, tol: Any, *, d_max: Any = 0.0, theta: float = 0.5, d: float = 0.5,
                  axes: Optional[int] = None) -> FNTSMCBounds:
    """Sound fixed-time bounds of a :class:`~landing.controllers.FixedTimeNTSMC` per axis (the
    tethered-satellite paper's Theorem 1): after ``total`` seconds ``|e1_i| <= tol_i`` from any
    initial state, when the lumped disturbance of the s dynamics,
    ``M^-1 (f - W^T Phi - eps_max sign s)``, is bounded by ``d_max`` (0: the theorem's nominal
    case) and the actuator does not saturate.

    Parameters
    ----------
    law : landing.controllers.FixedTimeNTSMC
        The law whose gains are read.
    tol : float or array_like
        The tolerance on |e1| per axis (rad for the tethered satellite).
    d_max : float or array_like, default 0.0
        The bound on the lumped disturbance of the s dynamics (rad/s^2 for the tethered satellite).
    theta : float, default 0.5
        The share of the law kept to dominate the disturbance, 0 < theta < 1.
    d : float, default 0.5
        Eq. 47's constant, for ``printed_td``.
    axes : int or None, default None
        The number of axes (1 to 3); by default the gains' length (2 for the tethered satellite's
        defaults).

    Returns
    -------
    FNTSMCBounds
        The times (s) and neighbourhoods per axis.

    Examples
    --------
    >>> import landing
    >>> from landing.theory import fntsmc_bounds
    >>> b = fntsmc_bounds(landing.scenarios.tether_law(), tol=0.01)
    >>> print(" ".join(f"{t:.1f}" for t in b.total), "s")
    1587.3 27.6 s
    """
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
        gains = law_gains(law, FNTSMC_GAINS, axes)
    except LandingError as e:
        raise ParameterError(f"{owner}: axes = {axes} violates the law's gains having 1 or axes values ({e})") from None
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


