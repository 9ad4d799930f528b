"""The offline fuel-optimal powered descent: the baseline of the Mars fixed-time guidance
paper's fuel comparison.

The Mars fixed-time guidance paper ("Mars Powered Descent Phase Guidance Design Based on Fixed-time Stabilization
Technique", section IV, Fig. 3 and 4) compares its guidance with an offline fuel-optimal
trajectory computed with GPOPS for t_f = 30 s (212.9067 kg of fuel). :func:`fuel_optimal` solves
the same problem on the simulator's own model (docs/reproduction-mars.md, "Fuel-optimal
baseline")::

    minimise    m(0) - m(t_f)
    subject to  r' = v,  v' = F/m + g + a_drag(rz, v, m),  m' = -|F| / (Isp g0)
                |F_i| <= F_max per axis (the plant's ``thrust_limit``)
                rz >= 0 along the way, r(t_f) = 0, v(t_f) = 0
                optionally rz >= tan(glide slope) |(rx, ry)|  (the paper uses none)

with the drag of :class:`landing.plants.MarsLander` (the paper's eq. 12, sign fixed) and its
mass depletion (eq. 13). The thrust is piecewise constant on ``nodes`` intervals, each
integrated by ``steps_per_node`` RK4 steps of the control period ``dt = t_f / (nodes
steps_per_node)``: the discrete dynamics are those of :func:`landing.simulate_batch` at that
``dt`` with the force held over each control period, so :meth:`FuelOptimalResult.replay` (the
:class:`landing.controllers.Tabulated` law) flies exactly the computed trajectory. The
altitude constraint holds at every integration step, not only at the nodes.

The problem is solved by multiple shooting with CasADi and IPOPT (``pip install
"landing[optimal]"``). The thrust is written F = Gamma w with Gamma >= 0 and |w| <= 1, and
the mass rate is -Gamma / (Isp g0): smooth where the engine is off (F = 0 exactly when
Gamma = 0, unlike a slack Gamma >= |F|, which lets a force below the solver's tolerance fly
for free). Gamma >= |F| always, and the fuel pushes |w| to 1 wherever Gamma > 0
(``FuelOptimalResult.slack_gap`` reports the largest Gamma - |F|).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Any, Literal, Optional

import numpy as np

from landing.controllers import Tabulated
from landing.errors import ParameterError, ParameterTypeError
from landing.plants import MarsLander
from landing.results import SimulationResult
from landing.simulation import simulate

__all__ = ["FuelOptimalResult", "fuel_optimal", "impulsive_fuel_bound"]

_CASADI_MISSING = (
    "landing.optimal needs CasADi (with its bundled IPOPT): pip install \"landing[optimal]\" "
    "(or pip install casadi)"
)


def _casadi() -> Any:
    try:
        import casadi
    except ImportError as exc:  # pragma: no cover - exercised by monkeypatching in tests
        raise ImportError(_CASADI_MISSING) from exc
    return casadi


@dataclass(frozen=True)
class MarsModel:
    """The scalar parameters of a :class:`landing.plants.MarsLander` the optimiser uses."""

    isp: float
    g0: float
    gravity: float
    area: tuple[float, float, float]
    drag: bool
    drag_coefficient: float
    density_decay: float
    thrust_limit: tuple[float, float, float]

    @property
    def exhaust_velocity(self) -> float:
        return self.isp * self.g0


def _scalar(name: str, value: Any, who: str = "fuel_optimal") -> float:
    arr = np.asarray(value, dtype=float)
    if arr.size != 1:
        raise ParameterError(
            f"{who}: the plant's {name} has shape {arr.shape}; it takes one case (a scalar)"
        )
    return float(arr.reshape(()))


def _triple(name: str, value: Any) -> tuple[float, float, float]:
    arr = np.asarray(value, dtype=float)
    if arr.size == 1:
        return (float(arr.reshape(())),) * 3
    if arr.shape != (3,):
        raise ParameterError(
            f"fuel_optimal: the plant's {name} has shape {arr.shape}; the optimiser takes one case "
            "(a scalar or one value per axis)"
        )
    return (float(arr[0]), float(arr[1]), float(arr[2]))


def _model(plant: Any) -> MarsModel:
    if not isinstance(plant, MarsLander):
        raise ParameterTypeError(f"fuel_optimal: plant must be a landing.plants.MarsLander, got {type(plant).__name__}")
    if plant.thrust_limit is None:
        raise ParameterError(
            "fuel_optimal: the plant has no thrust limit, and without one the minimum-fuel landing "
            "is impulsive; give it one, e.g. MarsLander(thrust_limit=40e3)"
        )
    limit = _triple("thrust_limit", plant.thrust_limit)
    if not all(math.isfinite(f) and f > 0 for f in limit):
        raise ParameterError(f"fuel_optimal: thrust_limit = {limit} violates finite thrust_limit > 0")
    return MarsModel(
        isp=_scalar("isp", plant.isp),
        g0=_scalar("g0", plant.g0),
        gravity=_scalar("gravity", plant.gravity),
        area=_triple("area", plant.area),
        drag=bool(plant.drag),
        drag_coefficient=_scalar("drag_coefficient", plant.drag_coefficient),
        density_decay=_scalar("density_decay", plant.density_decay),
        thrust_limit=limit,
    )


def impulsive_fuel_bound(plant: Any, x0: Any, t_final: float) -> float:
    """A lower bound on the fuel of any landing of a drag-free lander from ``x0`` at rest at
    the target at ``t_final``, kg: ``m0 (1 - exp(-|v0 + g e_z ... | / c))`` below.

    Proof. With no drag, ``v(t_f) - v(0) = integral(F/m) dt + g_vec t_f`` with
    ``g_vec = (0, 0, -g)``, so the engine must supply ``dv = -v0 - g_vec t_f`` (it brings the
    initial velocity to rest and makes up for gravity over the whole flight: the gravity loss of
    a landing in t_f). By the triangle inequality ``integral(|F|/m) dt >= |dv|``, and since
    ``m' = -|F|/c``, ``integral(|F|/m) dt = c ln(m0 / m(t_f))``. Hence
    ``m0 - m(t_f) >= m0 (1 - exp(-|dv| / c))``, with equality only for an impulse along dv,
    which the thrust limit forbids. With drag the bound needs the drag's impulse, which depends
    on the trajectory; it is computed from the drag-free formula only.

    Parameters
    ----------
    plant : MarsLander
        The lander (one case, scalar parameters); its ``isp``, ``g0`` and ``gravity`` are used
        (the bound holds whatever its thrust limit, or none).
    x0 : ArrayLike
        Initial state ``[rx, ry, rz, vx, vy, vz, m]``: m, m/s, kg.
    t_final : float
        Flight time, s.

    Returns
    -------
    float
        The bound on the fuel, kg.

    Raises
    ------
    ParameterError
        If ``isp``, ``g0`` or ``gravity`` is not a scalar.

    Examples
    --------
    >>> import numpy as np, landing
    >>> from landing.optimal import fuel_optimal
    >>> plant = landing.plants.MarsLander(thrust_limit=[8e3, 8e3, 16e3], drag=False)
    >>> x0 = np.array([200.0, 100.0, 1500.0, -10.0, 5.0, -75.0, 1905.0])
    >>> from landing.optimal import impulsive_fuel_bound
    >>> print(f"{impulsive_fuel_bound(plant, x0, 30.0):.1f} kg")
    154.5 kg
    """
    if not isinstance(plant, MarsLander):
        raise ParameterTypeError(
            f"impulsive_fuel_bound: plant must be a landing.plants.MarsLander, got {type(plant).__name__}")
    who = "impulsive_fuel_bound"
    exhaust_velocity = _scalar("isp", plant.isp, who) * _scalar("g0", plant.g0, who)
    gravity = _scalar("gravity", plant.gravity, who)
    x = np.asarray(x0, dtype=float)
    dv = -x[3:6] - np.array([0.0, 0.0, -gravity]) * t_final
    return float(x[6] * (1.0 - math.exp(-np.linalg.norm(dv) / exhaust_velocity)))


@dataclass(frozen=True, eq=False)
class FuelOptimalResult:
    """A fuel-optimal landing (:func:`fuel_optimal`).

    Made by :func:`fuel_optimal`; its fields:

    Parameters
    ----------
    t : numpy.ndarray
        Node times, shape (nodes + 1,), s.
    states : numpy.ndarray
        States at the nodes, shape (nodes + 1, 7): [rx, ry, rz, vx, vy, vz, m] in m, m/s, kg.
    thrust : numpy.ndarray
        Force per axis on each node interval, shape (nodes, 3), N (held constant over it).
    t_fine, states_fine : numpy.ndarray
        Times (s) and states at every integration step (every control period), shapes
        (K + 1,) and (K + 1, 7).
    fuel : float
        Propellant spent, m(0) - m(t_f), kg.
    t_final : float
        The final time, s (the optimum's when ``free_final_time``).
    dt : float
        The control period, s: the integration step, and the period of the replay.
    steps_per_node : int
        Control periods per node (the replay law's ``hold``).
    status : str
        IPOPT's return status.
    success : bool
        Whether IPOPT converged.
    iterations : int
        IPOPT's iteration count.
    solve_seconds : float
        Wall time of the solve, s.
    slack_gap : float
        The largest Gamma - |F| over the nodes, N (fuel paid for no thrust; 0 at the optimum).
    plant : MarsLander
        The plant solved for (its thrust_limit is the bound).
    glide_slope : float or None
        The glide-slope angle imposed, degrees, if any.
    thrust_magnitude : tuple of float or None
        The ``(low, high)`` bounds on |F| imposed, N, if any.

    Examples
    --------
    >>> import numpy as np, landing
    >>> from landing.optimal import fuel_optimal
    >>> plant = landing.plants.MarsLander(thrust_limit=[8e3, 8e3, 16e3], drag=False)
    >>> x0 = np.array([200.0, 100.0, 1500.0, -10.0, 5.0, -75.0, 1905.0])
    >>> r = fuel_optimal(plant, x0, 30.0, nodes=15, steps_per_node=2)
    >>> r.success, r.states.shape, r.thrust.shape, r.nodes
    (True, (16, 7), (15, 3), 15)
    >>> print(f"{r.fuel:.1f} kg, dt = {r.dt:.1f} s")
    155.4 kg, dt = 1.0 s
    """

    t: np.ndarray
    states: np.ndarray
    thrust: np.ndarray
    t_fine: np.ndarray
    states_fine: np.ndarray
    fuel: float
    t_final: float
    dt: float
    steps_per_node: int
    status: str
    success: bool
    iterations: int
    solve_seconds: float
    slack_gap: float
    plant: Any = field(repr=False)
    glide_slope: Optional[float] = None
    thrust_magnitude: Optional[tuple[float, float]] = None

    @property
    def nodes(self) -> int:
        return int(self.thrust.shape[0])

    def controller(self, after: Literal["hold", "zero"] = "zero") -> Tabulated:
        """The thrust profile as a :class:`landing.controllers.Tabulated` law (each row held for
        ``steps_per_node`` control periods of ``dt``).

        Parameters
        ----------
        after : {"hold", "zero"}
            Past the last row: hold it, or command no thrust (default).

        Returns
        -------
        Tabulated
            The open-loop law, force in N.
        """
        return Tabulated(force=self.thrust, hold=self.steps_per_node, after=after)

    def replay(self, disturbance: Any = None, *, t_final: Optional[float] = None, x0: Any = None,
               **options: Any) -> SimulationResult:
        """The thrust profile flown open loop by :func:`landing.simulate` at the control period
        ``dt`` (one RK4 step each), from the optimum's initial state unless ``x0`` is given,
        with an optional disturbance; ``options`` go to :func:`landing.simulate`.

        Parameters
        ----------
        disturbance : Disturbance, list of Disturbance or None
            Added to the dynamics (default none).
        t_final : float or None
            Horizon, s (default the optimum's ``t_final``).
        x0 : ArrayLike or None
            Initial state [rx, ry, rz, vx, vy, vz, m] in m, m/s, kg (default ``states[0]``).
        **options : Any
            More keyword arguments of :func:`landing.simulate`.

        Returns
        -------
        SimulationResult
            The simulated case (no case axis).

        Examples
        --------
        >>> import numpy as np, landing
        >>> from landing.optimal import fuel_optimal
        >>> plant = landing.plants.MarsLander(thrust_limit=[8e3, 8e3, 16e3], drag=False)
        >>> x0 = np.array([200.0, 100.0, 1500.0, -10.0, 5.0, -75.0, 1905.0])
        >>> r = fuel_optimal(plant, x0, 30.0, nodes=15, steps_per_node=2)
        >>> end = r.replay().states[-1]
        >>> print(f"{np.linalg.norm(end[:3]):.3f} m, {np.linalg.norm(end[3:6]):.3f} m/s")
        0.000 m, 0.000 m/s
        """
        start = self.states[0] if x0 is None else np.asarray(x0, dtype=float)
        return simulate(
            self.plant, self.controller(), start, t_final=self.t_final if t_final is None else t_final,
            dt=self.dt, disturbance=disturbance, **options,
        )


def _positive_int(name: str, value: Any, minimum: int) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        raise ParameterTypeError(f"fuel_optimal: {name} must be a whole number, got {value!r}")
    if value < minimum:
        raise ParameterError(f"fuel_optimal: {name} = {value} violates {name} >= {minimum}")
    return int(value)


def _positive(name: str, value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.floating, np.integer)):
        raise ParameterTypeError(f"fuel_optimal: {name} must be a real number, got {value!r}")
    v = float(value)
    if not (math.isfinite(v) and v > 0):
        raise ParameterError(f"fuel_optimal: {name} = {value!r} violates finite {name} > 0")
    return v


def fuel_optimal(
    plant: Any,
    x0: Any,
    t_final: float = 30.0,
    *,
    free_final_time: bool = False,
    t_final_bounds: Optional[tuple[float, float]] = None,
    nodes: int = 150,
    steps_per_node: int = 4,
    glide_slope: Optional[float] = None,
    thrust_magnitude: Optional[tuple[float, float]] = None,
    tolerance: float = 1e-9,
    max_iterations: int = 3000,
    verbose: bool = False,
) -> FuelOptimalResult:
    """The fuel-optimal landing of a :class:`landing.plants.MarsLander` from ``x0`` at rest at
    the origin (module docstring for the problem).

    Parameters
    ----------
    plant : MarsLander
        The lander; its ``thrust_limit`` (finite, per axis, N) is the thrust bound, and its
        drag and mass depletion are modelled as in the simulator. One case (scalar parameters).
    x0 : ArrayLike
        Initial state [rx, ry, rz, vx, vy, vz, m] in m, m/s, kg (rz >= 0, m > 0).
    t_final : float
        The flight time, s (the Mars fixed-time guidance paper: 30 s); with
        ``free_final_time`` the initial guess.
    free_final_time : bool
        Also optimise t_f, within ``t_final_bounds``; the control period then scales with it.
    t_final_bounds : tuple of float or None
        ``(low, high)`` bounds on t_f, s (default ``(0.2 t_final, 3 t_final)``); only with
        ``free_final_time``.
    nodes : int
        Thrust intervals (the thrust is constant on each).
    steps_per_node : int
        RK4 steps (control periods) per interval.
    glide_slope : float or None
        If given, the angle in degrees above the horizontal the lander must stay above, as
        seen from the target: ``rz >= tan(angle) sqrt(rx^2 + ry^2 + 1 m^2)`` at every
        integration step before t_f (the softening keeps it smooth over the target).
    thrust_magnitude : tuple of float or None
        If given, ``(low, high)`` bounds on |F| in N besides the per-axis limit:
        ``low <= |F| <= high`` throughout (an engine that cannot throttle below ``low`` nor
        shut down, as in Acikmese and Ploen 2007, the paper's reference [1]; ``low = 0``
        allows coasting).
    tolerance : float
        IPOPT's ``tol``.
    max_iterations : int
        IPOPT's ``max_iter``.
    verbose : bool
        Print IPOPT's log.

    Returns
    -------
    FuelOptimalResult
        Check ``success`` (IPOPT's status is ``status``).

    Raises
    ------
    ParameterError
        If the plant has no thrust limit, ``x0`` is not one finite state with m > 0 and
        rz >= 0, or an option is out of range (a glide slope not in (0, 90) degrees or one
        ``x0`` lies below, ``t_final`` outside ``t_final_bounds``).
    ParameterTypeError
        If ``thrust_magnitude`` is not a pair of numbers.
    ImportError
        If CasADi is not installed.

    Examples
    --------
    >>> import numpy as np, landing
    >>> from landing.optimal import fuel_optimal
    >>> plant = landing.plants.MarsLander(thrust_limit=[8e3, 8e3, 16e3], drag=False)
    >>> x0 = np.array([200.0, 100.0, 1500.0, -10.0, 5.0, -75.0, 1905.0])
    >>> r = fuel_optimal(plant, x0, t_final=30.0, nodes=15, steps_per_node=2)
    >>> print(r.status, f"{r.fuel:.1f} kg", f"{r.states[-1, 6]:.1f} kg left")
    Solve_Succeeded 155.4 kg 1749.6 kg left
    """
    ca = _casadi()
    model = _model(plant)
    x0 = np.asarray(x0, dtype=float)
    if x0.shape != (7,):
        raise ParameterError(f"fuel_optimal: x0 has shape {x0.shape}; it takes one state (7,)")
    if not np.all(np.isfinite(x0)):
        raise ParameterError(f"fuel_optimal: x0 = {x0} violates finite values")
    if x0[6] <= 0:
        raise ParameterError(f"fuel_optimal: x0[6] = {x0[6]} violates mass x0[6] > 0")
    if x0[2] < 0:
        raise ParameterError(f"fuel_optimal: x0[2] = {x0[2]} violates altitude x0[2] >= 0")
    t_final = _positive("t_final", t_final)
    nodes = _positive_int("nodes", nodes, 2)
    steps_per_node = _positive_int("steps_per_node", steps_per_node, 1)
    tolerance = _positive("tolerance", tolerance)
    max_iterations = _positive_int("max_iterations", max_iterations, 1)
    if free_final_time:
        lo, hi = t_final_bounds if t_final_bounds is not None else (0.2 * t_final, 3.0 * t_final)
        lo, hi = _positive("t_final_bounds[0]", lo), _positive("t_final_bounds[1]", hi)
        if not lo <= t_final <= hi:
            raise ParameterError(f"fuel_optimal: t_final = {t_final} violates t_final_bounds[0] <= t_final <= "
                                 f"t_final_bounds[1] ({lo}, {hi})")
    elif t_final_bounds is not None:
        raise ParameterError("fuel_optimal: t_final_bounds applies only with free_final_time=True")
    tan_glide = None
    if glide_slope is not None:
        angle = float(glide_slope)
        if not 0.0 < angle < 90.0:
            raise ParameterError(f"fuel_optimal: glide_slope = {glide_slope!r} violates 0 < glide_slope < 90 (degrees)")
        tan_glide = math.tan(math.radians(angle))
        if x0[2] < tan_glide * math.sqrt(x0[0] ** 2 + x0[1] ** 2 + 1.0):
            raise ParameterError(f"fuel_optimal: x0 = {x0} lies below the glide slope of {angle} degrees")

    if thrust_magnitude is not None:
        try:
            low, high = (float(b) for b in thrust_magnitude)
        except (TypeError, ValueError) as exc:
            raise ParameterTypeError(
                f"fuel_optimal: thrust_magnitude must be (low, high) in N, got {thrust_magnitude!r}") from exc
        if not (math.isfinite(low) and math.isfinite(high) and 0.0 <= low < high):
            raise ParameterError(f"fuel_optimal: thrust_magnitude = {thrust_magnitude!r} violates 0 <= low < high")
    fmax = np.array(model.thrust_limit)
    c = model.exhaust_velocity
    m0 = float(x0[6])
    # scales: the optimiser sees O(1) numbers
    x_scale = np.array([1e3, 1e3, 1e3, 1e2, 1e2, 1e2, m0])
    f_scale = float(np.max(fmax))

    # --- the simulator's plant, in CasADi (crates/landing_core/src/plant/mars.rs) ------------
    xs = ca.SX.sym("x", 7)
    fs = ca.SX.sym("f", 3)
    gam = ca.SX.sym("gamma")
    r, v, m = xs[0:3], xs[3:6], xs[6]
    if model.drag:
        k = -model.drag_coefficient * ca.exp(-model.density_decay * r[2]) / m
        drag = ca.vertcat(*[k * v[i] * ca.fabs(v[i]) / model.area[i] for i in range(3)])
    else:
        drag = ca.SX.zeros(3)
    acc = fs / m + ca.vertcat(0, 0, -model.gravity) + drag
    xdot = ca.Function("xdot", [xs, fs, gam], [ca.vertcat(v, acc, -gam / c)])

    h = ca.SX.sym("h")  # control period

    def rk4(x: Any, f: Any, g: Any) -> Any:
        k1 = xdot(x, f, g)
        k2 = xdot(x + (h / 2) * k1, f, g)
        k3 = xdot(x + (h / 2) * k2, f, g)
        k4 = xdot(x + h * k3, f, g)
        return x + (h / 6) * (k1 + 2 * k2 + 2 * k3 + k4)

    # one node interval: steps_per_node RK4 steps; outputs every step's state
    xi = xs
    steps = []
    for _ in range(steps_per_node):
        xi = rk4(xi, fs, gam)
        steps.append(xi)
    interval = ca.Function("interval", [xs, fs, gam, h], [ca.horzcat(*steps)])

    # --- the NLP ------------------------------------------------------------------------------
    opti = ca.Opti()
    X = opti.variable(7, nodes + 1)  # scaled states
    G = opti.variable(1, nodes)  # scaled thrust magnitude
    W = opti.variable(3, nodes)  # thrust direction, |W| <= 1
    U = W * ca.repmat(G, 3, 1)  # scaled force
    T = opti.variable() if free_final_time else t_final
    xsc = ca.DM(x_scale)
    hstep = T / (nodes * steps_per_node)

    opti.subject_to(X[:, 0] == ca.DM(x0 / x_scale))
    for j in range(nodes):
        traj = interval(X[:, j] * xsc, U[:, j] * f_scale, G[j] * f_scale, hstep)  # 7 x steps
        opti.subject_to(X[:, j + 1] == traj[:, -1] / xsc)
        # altitude (and glide slope) at every integration step strictly before t_f
        inner = traj[:, :-1] if j == nodes - 1 else traj
        if inner.shape[1] > 0:
            opti.subject_to(ca.vec(inner[2, :]) / 1e3 >= 0)
            if tan_glide is not None:
                horiz = ca.sqrt(inner[0, :] ** 2 + inner[1, :] ** 2 + 1.0)
                opti.subject_to(ca.vec(inner[2, :] - tan_glide * horiz) / 1e3 >= 0)
    opti.subject_to(X[0:6, nodes] == 0)
    opti.subject_to(X[6, :] > 1e-3)
    for i in range(3):
        opti.subject_to(opti.bounded(-fmax[i] / f_scale, U[i, :], fmax[i] / f_scale))
    opti.subject_to(G >= 0)
    opti.subject_to(ca.sum1(W ** 2) <= 1)
    opti.subject_to(G <= float(np.linalg.norm(fmax)) / f_scale)
    if thrust_magnitude is not None:
        opti.subject_to(opti.bounded(low / f_scale, G, high / f_scale))
        if low > 0:  # |F| = Gamma: the direction is a unit vector
            opti.subject_to(ca.sum1(W ** 2) >= 1)
    if free_final_time:
        opti.subject_to(opti.bounded(lo, T, hi))
        opti.set_initial(T, t_final)
    opti.minimize(X[6, 0] - X[6, nodes])

    # initial guess: a straight line to the target, a hover-plus-braking force
    s = np.linspace(0.0, 1.0, nodes + 1)
    guess = np.empty((7, nodes + 1))
    guess[0:3] = x0[0:3, None] * (1 - s) ** 2
    guess[3:6] = x0[3:6, None] * (1 - s)
    guess[6] = m0 * (1 - 0.1 * s)
    f_guess = np.clip(m0 * (-x0[3:6] / t_final + np.array([0.0, 0.0, model.gravity])), -fmax, fmax)
    opti.set_initial(X, guess / x_scale[:, None])
    opti.set_initial(W, np.tile((f_guess / np.linalg.norm(f_guess))[:, None], (1, nodes)))
    opti.set_initial(G, np.full((1, nodes), np.linalg.norm(f_guess) / f_scale))

    ipopt = {"tol": tolerance, "max_iter": max_iterations, "print_level": 5 if verbose else 0,
             "constr_viol_tol": 1e-9, "acceptable_tol": 1e-7, "acceptable_iter": 15}
    opti.solver("ipopt", {"print_time": verbose, "ipopt.sb": "yes"}, ipopt)
    started = time.perf_counter()
    try:
        sol = opti.solve()
        value = sol.value
        stats = sol.stats()
    except RuntimeError:
        value = opti.debug.value
        stats = opti.stats()
    elapsed = time.perf_counter() - started

    tf = float(value(T)) if free_final_time else t_final
    Xv = np.asarray(value(X)).reshape(7, nodes + 1) * x_scale[:, None]
    Uv = np.asarray(value(W)).reshape(3, nodes) * np.asarray(value(G)).reshape(1, nodes) * f_scale
    Gv = np.asarray(value(G)).reshape(nodes) * f_scale
    dt = tf / (nodes * steps_per_node)

    # the states at every control period, from the solved nodes and forces
    fine = [Xv[:, 0]]
    for j in range(nodes):
        traj = np.asarray(interval(Xv[:, j], Uv[:, j], Gv[j], dt))
        fine.extend(traj.T)
    states_fine = np.array(fine)
    status = str(stats.get("return_status", "unknown"))
    return FuelOptimalResult(
        t=np.linspace(0.0, tf, nodes + 1),
        states=Xv.T.copy(),
        thrust=Uv.T.copy(),
        t_fine=np.arange(nodes * steps_per_node + 1) * dt,
        states_fine=states_fine,
        fuel=float(Xv[6, 0] - Xv[6, -1]),
        t_final=tf,
        dt=dt,
        steps_per_node=steps_per_node,
        status=status,
        success=bool(stats.get("success", False)),
        iterations=int(stats.get("iter_count", -1)),
        solve_seconds=elapsed,
        slack_gap=float(np.max(Gv - np.linalg.norm(Uv, axis=0))),
        plant=plant,
        glide_slope=glide_slope,
        thrust_magnitude=None if thrust_magnitude is None else (low, high),
    )
