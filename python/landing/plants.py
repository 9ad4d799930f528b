"""Plants: the dynamics a batch integrates.

A plant holds physical parameters only; any numeric parameter may be given per case (an array
with one entry per case of the batch, or ``(N, 3)`` for per-axis ones).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Any, ClassVar, Literal, Optional

import numpy as np

from landing import _core
from landing._internal.args import real, real_array
from landing._internal.limits import require_memory
from landing._internal.table import ArrayLike, Parameter, Table
from landing._internal.user_law import qualified_name, source_hash
from landing._internal.user_params import frozen_params, params_taking_cases, replace_with_params
from landing._internal.user_plant import PlantStep, per_case
from landing.errors import ParameterError, ParameterTypeError
from landing.gravity import Gravity, TwoPointMass
from landing.sensors import Filter, Sensor

__all__ = ["Plant", "MarsLander", "DoubleIntegrator", "SmallBody", "TetheredSatellite", "PythonPlant"]


class Plant(Table):
    """Base class of the plants: the dynamics a law controls, with generalized coordinates q
    (one per axis) and their rates q' read from the state.

    Parameters
    ----------
    **fields : Any
        The subclass's fields (see each one); the base class takes none of its own.

    Examples
    --------
    >>> import landing
    >>> plant = landing.plants.DoubleIntegrator()
    >>> plant.axes, plant.state_dim, plant.state_names
    (3, 6, ('x', 'y', 'z', 'vx', 'vy', 'vz'))
    """

    family: ClassVar[str] = "plant"

    _compiler = _core.Plant

    def _info(self) -> dict[str, Any]:
        return self._core.info()

    @property
    def state_names(self) -> tuple[str, ...]:
        return tuple(self._info()["state_names"])

    @property
    def control_names(self) -> tuple[str, ...]:
        return tuple(self._info()["control_names"])

    @property
    def axes(self) -> int:
        """Number of generalized coordinates (and of command components)."""
        return int(self._info()["axes"])

    @property
    def state_dim(self) -> int:
        return len(self.state_names)

    def coordinates(self, states: Any) -> tuple[np.ndarray, np.ndarray]:
        """The generalized coordinates q and rates q' the laws read, computed by the core from
        states ``(..., n_state)`` (e.g. ``result.states``): two arrays ``(..., axes)``."""
        x = real_array("states", states, owner=type(self).__name__)
        if x.ndim == 0 or x.shape[-1] != self.state_dim:
            raise ParameterError(f"states have shape {x.shape}; this plant's have {self.state_dim} components")
        q, qd = self._core.coordinates(x.reshape(-1, x.shape[-1]))
        lead = x.shape[:-1]
        return q.reshape(lead + (q.shape[-1],)), qd.reshape(lead + (qd.shape[-1],))

    def states_from_draws(self, draws: np.ndarray) -> np.ndarray:
        """Initial states from what a dispersion draws; the draws are the states themselves
        unless the plant says otherwise (the flexible tether draws its angles and rates)."""
        return draws


@dataclass(frozen=True, eq=False)
class MarsLander(Plant):
    """Mars powered descent (the Mars fixed-time guidance paper).

    State ``[rx, ry, rz, vx, vy, vz, m]`` in an inertial frame at the target, z up; the
    command is the engine force ``F = m a`` (N), clipped per axis to ``thrust_limit``, or, for
    an engine with ``thrust_magnitude_limit`` or ``pointing_limit``, projected onto what the
    engine can give: onto the cone within ``pointing_limit`` of +z (the Euclidean projection),
    then its magnitude clamped into ``[min_throttle, 1] * thrust_magnitude_limit`` along its
    direction (the engine is always on: a zero command gives the least thrust straight up).
    Between the law and those limits, the command may be delayed by ``control_delay`` whole
    control periods and lagged by the engine, ``F' = (F_c - F) / engine_time_constant``, solved
    exactly over each period; the limits are imposed again on the lag's output, so the applied
    force meets them at every instant (docs/parameters.md, "actuator").

    ``r' = v``, ``v' = F/m + g + a_drag + a_p(t)``, ``m' = -|F| / (isp g0)``, with
    ``a_drag_i = -drag_coefficient v_i |v_i| exp(-density_decay rz) / (area_i m)``.

    Parameters
    ----------
    isp : ArrayLike
        Specific impulse, s, scalar; isp > 0 (225 s, Acikmese and Ploen 2007, the paper's
        reference [1]).
    area : ArrayLike
        Effective cross-sections perpendicular to x, y, z, m^2, per axis; area > 0 (the
        paper's Table I).
    gravity : ArrayLike
        Mars surface gravity, m/s^2, scalar, >= 0 (acts along -z).
    drag : bool
        Whether the plant has drag (the guidance then models it).
    thrust_limit : ArrayLike or None
        Per-axis limit on |F_i|, N, > 0; ``None`` for unlimited (the paper's part 3: 50 kN).
        Not combined with the engine's limits below.
    thrust_magnitude_limit : ArrayLike or None
        Limit on |F|, N, > 0 (the engine's full thrust); ``None`` for none.
    min_throttle : ArrayLike or None
        The least |F| as a fraction of ``thrust_magnitude_limit``, in [0, 1); ``None`` for 0.
    pointing_limit : ArrayLike or None
        Largest angle of F from +z, rad, in (0, pi/2]; ``None`` for any direction.
    control_delay : ArrayLike or None
        The command's transport delay in whole control periods, an integer in [0, 1000];
        ``None`` for none. Before the first command arrives, the limits applied to a zero
        command (Simulink's Transport Delay default of an initial output 0).
    engine_time_constant : ArrayLike or None
        The engine's first-order lag time constant, s, >= 0; ``None`` or 0 for none. The lag
        starts in steady state, at the first command that reaches it.
    drag_coefficient : ArrayLike
        k_d of the paper's eq. 12, kg/m, >= 0.
    density_decay : ArrayLike
        h_d of the paper's eq. 12, 1/m, >= 0 (the paper's 0.0009; the Mars-atmosphere model it
        cites uses 0.00009).
    g0 : ArrayLike
        Standard gravity in the rocket equation, m/s^2, > 0.
    sensor : Sensor or None
        What the law reads the position and velocity through (:class:`landing.sensors.Noise`);
        ``None`` for the true state. The mass is known to the law.
    filter : Filter or None
        The estimator between the sensor and the law (:class:`landing.sensors.KalmanFilter`);
        ``None`` for none (the law reads the measurement). Needs a sensor.

    Each numeric parameter may be given per case.

    Examples
    --------
    >>> plant = MarsLander(thrust_limit=50e3)
    >>> plant.state_names
    ('rx', 'ry', 'rz', 'vx', 'vy', 'vz', 'm')
    >>> MarsLander.initial_state([200.0, 100.0, 1500.0], [-10.0, 5.0, -75.0], 1905.0)
    array([ 200.,  100., 1500.,  -10.,    5.,  -75., 1905.])
    """

    isp: ArrayLike = 225.0
    area: ArrayLike = (6.0, 7.5, 8.7)
    gravity: ArrayLike = 3.7114
    drag: bool = True
    thrust_limit: Optional[ArrayLike] = None
    thrust_magnitude_limit: Optional[ArrayLike] = None
    min_throttle: Optional[ArrayLike] = None
    pointing_limit: Optional[ArrayLike] = None
    control_delay: Optional[ArrayLike] = None
    engine_time_constant: Optional[ArrayLike] = None
    drag_coefficient: ArrayLike = 0.699
    density_decay: ArrayLike = 0.0009
    g0: ArrayLike = 9.807
    sensor: Optional[Sensor] = None
    filter: Optional[Filter] = None

    kind: ClassVar[str] = "mars_lander"

    @staticmethod
    def initial_state(position: ArrayLike, velocity: ArrayLike, mass: ArrayLike) -> np.ndarray:
        """Stack positions ``(..., 3)``, velocities ``(..., 3)`` and masses ``(...)`` into states ``(..., 7)``.

        Parameters
        ----------
        position : ArrayLike
            Positions, m, shape (..., 3).
        velocity : ArrayLike
            Velocities, m/s, shape (..., 3).
        mass : ArrayLike
            Masses, kg, shape (...).

        Returns
        -------
        numpy.ndarray
            The states ``[rx, ry, rz, vx, vy, vz, m]``, shape (..., 7).
        """
        r = real_array("position", position, owner="MarsLander.initial_state")
        v = real_array("velocity", velocity, owner="MarsLander.initial_state")
        m = real_array("mass", mass, owner="MarsLander.initial_state")
        for name, a in (("position", r), ("velocity", v)):
            if a.ndim == 0 or a.shape[-1] != 3:
                raise ParameterError(f"MarsLander.initial_state: {name} has shape {a.shape}; it takes (..., 3)")
        try:
            shape = np.broadcast_shapes(r.shape[:-1], v.shape[:-1], m.shape)
        except ValueError:
            raise ParameterError(
                f"MarsLander.initial_state: position {r.shape}, velocity {v.shape} and mass {m.shape} "
                "violate shapes that broadcast"
            ) from None
        require_memory(f"MarsLander.initial_state: states of shape {shape + (7,)}", 8 * 7 * math.prod(shape))
        return np.concatenate(
            [np.broadcast_to(r, shape + (3,)), np.broadcast_to(v, shape + (3,)), np.broadcast_to(m, shape)[..., None]],
            axis=-1,
        )


@dataclass(frozen=True, eq=False)
class DoubleIntegrator(Plant):
    """``q'' = u + d`` on three axes: no drift, unit inertia.

    The plant on which a law's reaching law holds exactly, used to check the theory's bounds
    against simulation, and the simplest test bed for any law. State ``[x, y, z, vx, vy, vz]``;
    the command is the acceleration, clipped per axis to ``acceleration_limit`` (None: none).
    ``sensor`` and ``filter`` (:mod:`landing.sensors`) put a measurement and an estimator
    between the plant and the law (``None``: the law reads the true state).

    Parameters
    ----------
    acceleration_limit : ArrayLike or None
        Per-axis limit on |u_i|, q/s^2 (m/s^2 as the core's table writes it), > 0; None for
        none. May be given per case.
    sensor : Sensor or None
        The sensor between the plant and the law (:class:`landing.sensors.Noise`).
    filter : Filter or None
        The estimator between the sensor and the law (:class:`landing.sensors.KalmanFilter`);
        needs a sensor.

    Examples
    --------
    >>> import numpy as np, landing
    >>> from landing.controllers import PDSlidingMode
    >>> law = PDSlidingMode(lambda_=1.0, k=0.5, switch="sat", boundary_layer=0.1)
    >>> r = landing.simulate(DoubleIntegrator(acceleration_limit=0.2), law, [10.0, 0, 0, 0, 0, 0],
    ...                      t_final=5.0, dt=0.01)
    >>> print(f"{r.metrics['peak_command']:.3f}")
    0.200
    """

    acceleration_limit: Optional[ArrayLike] = None
    sensor: Optional[Sensor] = None
    filter: Optional[Filter] = None

    kind: ClassVar[str] = "double_integrator"


@dataclass(frozen=True, eq=False)
class SmallBody(Plant):
    """A probe near a small body, in the body's frame rotating at ``omega`` about z (the fuzzy
    fast-terminal and the fuzzy variable-rate asteroid papers). State ``[x, y, z, vx, vy, vz]``;
    the command is a control acceleration (m/s^2), clipped per axis to ``acceleration_limit``
    (None: none), then scaled into
    ``|u| <= acceleration_magnitude_limit`` (None: none; the scaling keeps the per-axis bounds).
    Between the law and those limits, the command may be delayed by ``control_delay`` whole
    control periods and lagged by the thrusters, ``u' = (u_c - u) / engine_time_constant``,
    solved exactly over each period, the limits imposed on the lag's output, as on the Mars
    lander (docs/parameters.md, "actuator"). Each of the four per case.

    ``x'' - 2 omega y' - omega^2 x = g_x + u_x + d_x``, ``y'' + 2 omega x' - omega^2 y = g_y + u_y + d_y``,
    ``z'' = g_z + u_z + d_z``, with g from a :mod:`landing.gravity` field. Defaults: the fuzzy
    fast-terminal asteroid paper's (433 Eros as two mass points, omega = 3.3118e-4 rad/s).
    ``sensor`` and ``filter`` (:mod:`landing.sensors`) put a measurement and an estimator
    between the plant and the law (``None``: the law reads the true state).

    Parameters
    ----------
    gravity : Gravity
        The body's gravity field (a :mod:`landing.gravity` field); default
        :class:`~landing.gravity.TwoPointMass` (433 Eros).
    omega : ArrayLike
        The body's rotation rate about z, rad/s, scalar.
    acceleration_limit : ArrayLike or None
        Per-axis limit on |u_i|, m/s^2, > 0; None for none.
    acceleration_magnitude_limit : ArrayLike or None
        Limit on |u| after the per-axis one, m/s^2, > 0; None for none.
    control_delay : ArrayLike or None
        The command's transport delay in whole control periods, an integer in [0, 1000];
        None for none.
    engine_time_constant : ArrayLike or None
        The thrusters' first-order lag time constant, s, >= 0; None (or 0) for none.
    sensor : Sensor or None
        The sensor between the plant and the law (:class:`landing.sensors.Noise`).
    filter : Filter or None
        The estimator between the sensor and the law (:class:`landing.sensors.KalmanFilter`);
        needs a sensor.

    Raises
    ------
    ParameterTypeError
        If ``gravity`` is not a :mod:`landing.gravity` field.

    Examples
    --------
    >>> from landing.gravity import Harmonic2
    >>> plant = SmallBody(gravity=Harmonic2(), omega=3.3118e-4, acceleration_limit=0.01)
    >>> plant.state_names, plant.control_names
    (('x', 'y', 'z', 'vx', 'vy', 'vz'), ('ux', 'uy', 'uz'))
    """

    gravity: Gravity = field(default_factory=TwoPointMass)
    omega: ArrayLike = 3.3118e-4
    acceleration_limit: Optional[ArrayLike] = None
    acceleration_magnitude_limit: Optional[ArrayLike] = None
    control_delay: Optional[ArrayLike] = None
    engine_time_constant: Optional[ArrayLike] = None
    sensor: Optional[Sensor] = None
    filter: Optional[Filter] = None

    kind: ClassVar[str] = "small_body"

    def __post_init__(self) -> None:
        if not isinstance(self.gravity, Gravity):
            raise ParameterTypeError(
                f"SmallBody: gravity must be a landing.gravity field, got {self.gravity!r}"
            )
        super().__post_init__()


@dataclass(frozen=True, eq=False)
class TetheredSatellite(Plant):
    """The space-tethered satellite in its orbital plane (the tethered-satellite paper).

    Generalized coordinates ``q = (phi, theta)``: the in-plane angle of the line from the main
    satellite to the sub-satellite's centre (from nadir) and the sub-satellite's attitude, both
    in the orbital (Hill) frame, rad. Commands: the in-plane thrust (N, on the sub-satellite,
    perpendicular to that line) and the attitude torque (N m), each saturated. The controller
    sees the paper's inertia ``M = diag(mu L0, m_s a^2/6)`` (eq. 17 in the actuators' units,
    mu the reduced mass) and no other model term.

    Two fidelities share that interface:

    - ``"simplified"``: the rigid dumbbell of the paper's eq. 17 with its unknown terms written out
      (gravity gradient, tension torque); state ``[phi, theta, phi_dot, theta_dot]``.
    - ``"flexible"``: the validation plant: the tether as ``nodes`` lumped masses joined by
      tension-only Kelvin-Voigt spring-dampers, gravity gradient and Coriolis terms of the Hill
      frame on every node, a rigid cube sub-satellite pulled at its attachment point a/2 from
      its centre; state ``[xs, ys, theta, vxs, vys, omega, x1, y1, vx1, vy1, ...]`` (m, m/s).
      Use :meth:`initial_state` to build states from angles and :meth:`coordinates` to read
      the angles back. Its tether modes are stiff: integrate with ``substeps`` of at least
      :meth:`substeps_for` (the presets do); fewer make the cases diverge (flagged, with a
      warning).

    Parameters
    ----------
    fidelity : {"simplified", "flexible"}
        The model (default ``"flexible"``).
    main_mass, sub_mass : ArrayLike
        m_m and m_s, kg, > 0 (the paper's Table 1: 1000, 10).
    tether_length : ArrayLike
        L0, the unstretched length, m, > 0 (the paper: 100).
    side : ArrayLike
        a, the sub-satellite cube's side, m, 0 < side < tether_length (the paper: 1); the
        tether is attached a/2 from its centre.
    orbit_altitude : ArrayLike
        Altitude of the main satellite's circular Earth orbit, m (the paper: 500 km).
    thrust_limit : ArrayLike or None
        Limit on the in-plane thrust, N, > 0 (the paper: 0.1); None for none.
    torque_limit : ArrayLike or None
        Limit on the attitude torque, N m, > 0; None for ``thrust_limit * side / 2``.
    nodes : int
        Tether nodes of the flexible model, one of 2, 4, 8, 16 (each is its own compiled
        state size); 8 is within 0.01 s of 16 on the paper's comparison (docs/parameters.md).
    tether_density : ArrayLike
        The tether's linear density, kg/m, > 0.
    axial_stiffness : ArrayLike
        EA, N, > 0.
    axial_damping : ArrayLike
        Kelvin-Voigt damping c_A, N s, >= 0 (with the two above: a YES2-class 0.5 mm Dyneema
        line, docs/parameters.md).

    Any numeric parameter but ``nodes`` may be given per case.

    Examples
    --------
    >>> rigid = TetheredSatellite(fidelity="simplified")
    >>> rigid.state_names
    ('phi', 'theta', 'phi_dot', 'theta_dot')
    >>> print(" ".join(f"{m:.3f}" for m in rigid.inertia), f"{rigid.orbital_rate:.6f} rad/s")
    990.099 1.667 0.001107 rad/s
    >>> flexible = TetheredSatellite()
    >>> q, dq = flexible.coordinates(flexible.initial_state(0.1, 0.05))
    >>> print(" ".join(f"{v:.3f}" for v in q), flexible.state_dim)
    0.100 0.050 38
    """

    fidelity: Literal["simplified", "flexible"] = "flexible"
    main_mass: ArrayLike = 1000.0
    sub_mass: ArrayLike = 10.0
    tether_length: ArrayLike = 100.0
    side: ArrayLike = 1.0
    orbit_altitude: ArrayLike = 500e3
    thrust_limit: Optional[ArrayLike] = 0.1
    torque_limit: Optional[ArrayLike] = None
    nodes: int = 8
    tether_density: ArrayLike = 1.9e-4
    axial_stiffness: ArrayLike = 1.0e4
    axial_damping: ArrayLike = 5.0

    kind: ClassVar[str] = "tethered_satellite"

    @property
    def inertia(self) -> np.ndarray:
        """The controller's M = (mu L0, m_s a^2 / 6) (of the first case)."""
        return np.asarray(self._info()["inertia"])

    @property
    def orbital_rate(self) -> float:
        """Mean motion n of the orbit, rad/s (of the first case)."""
        return float(self._info()["orbital_rate"])

    @property
    def max_step(self) -> float:
        """Largest stable RK4 step of the tether's fastest mode over the cases, s (infinite for
        the simplified model)."""
        return float(self._info()["max_step"])

    def substeps_for(self, dt: float) -> int:
        """The fewest RK4 substeps per control period ``dt`` that keep the tether stable."""
        dt = real("dt", dt, positive=True, owner="TetheredSatellite.substeps_for")
        step = self.max_step
        return 1 if math.isinf(step) else max(1, math.ceil(dt / step))

    def initial_state(self, phi: ArrayLike, theta: ArrayLike, phi_dot: ArrayLike = 0.0,
                      theta_dot: ArrayLike = 0.0) -> np.ndarray:
        """States at the given angles (rad) and rates (rad/s), broadcast together: ``(n_state,)``
        for scalars, ``(..., n_state)`` otherwise. The flexible tether is laid straight and
        stretched by the rigid dumbbell's tension, every point turning with the line."""
        owner = "TetheredSatellite.initial_state"
        args = [real_array(n, v, finite=True, owner=owner) for n, v in
                (("phi", phi), ("theta", theta), ("phi_dot", phi_dot), ("theta_dot", theta_dot))]
        try:
            a = np.broadcast_arrays(*args)
        except ValueError:
            raise ParameterError(
                f"{owner}: phi, theta, phi_dot, theta_dot have shapes {[x.shape for x in args]}; "
                "they must broadcast together"
            ) from None
        shape = a[0].shape
        # the rows of angles, then the states
        require_memory(f"{owner}: states of shape {shape + (self.state_dim,)}",
                       8 * (4 + self.state_dim) * math.prod(shape))
        if a[0].size == 0:
            return np.empty(shape + (self.state_dim,))
        rows = np.ascontiguousarray(np.stack([v.reshape(-1) for v in a], axis=1))
        x = self._core.state_at(rows)
        return x.reshape(shape + (x.shape[-1],))

    def states_from_draws(self, draws: np.ndarray) -> np.ndarray:
        """A dispersion of a tethered satellite draws ``(phi, theta, phi_dot, theta_dot)``."""
        d = np.asarray(draws, dtype=np.float64)
        if d.shape[-1] == 4:
            return self.initial_state(d[..., 0], d[..., 1], d[..., 2], d[..., 3])
        return d


#: Most state components a plant written in Python may have.
MAX_PYTHON_STATE: int = 32


@dataclass(frozen=True, eq=False)
class PythonPlant(Plant):
    """A plant written in Python: the core integrates ``derivative`` with its RK4 or Euler
    step, calling it once per integrator stage for every case of the batch at once, and runs
    every law on it, built in or written in Python, with the metrics, events and stops of a
    built-in plant.

    ``derivative(t, x, u, params)`` returns ``x'`` (n, n_state) for the states ``x`` (n,
    n_state) and the applied commands ``u`` (n, D), without the disturbance: the core adds a
    disturbance (a generalized acceleration, see :mod:`landing.disturbances`) to the
    derivative of each velocity component. The arrays are read-only; ``params`` is a dict of
    the plant's parameters, one row per case (see ``params`` below).

    The law reads ``q = x[:, positions]`` and ``q' = x[:, velocities]``, and from ``model(t, x,
    params) -> (drift, inertia)`` (each (n, D)) the modelled acceleration it may cancel and the
    inertia its command is scaled by; without a model, drift 0 and inertia 1. The applied
    command is ``actuate(t, x, a, params)`` (n, D) for the law's commanded acceleration ``a``
    (saturation goes here); without one, ``inertia * a``. ``in_domain(t, x, params)`` returns
    booleans (n,): a case whose state leaves the domain is stopped and flagged
    ``out_of_domain``, as a non-finite state is ``non_finite_state``. Each hook is one call per
    control period for every case (the domain: per integrator step).

    Parameters
    ----------
    derivative : Callable
        ``derivative(t, x, u, params) -> x'``, shapes above; t in s.
    n_state : int
        The number of state components (at most 32).
    positions, velocities : Sequence[int]
        The components holding q and q' (one per axis, 2 or 3 axes, 2 D distinct components).
    model, actuate, in_domain : Callable or None
        The optional hooks above.
    params : Mapping[str, ArrayLike]
        The plant's parameters by name: a scalar (the functions see (n,)), a vector (k,)
        shared by every case (seen as (n, k)), or a value per case (N,) or (N, k); read-only
        copies, a scalar as a broadcast view of one value (stride 0), any other C-contiguous.
    state_names, control_names : tuple of str
        Names for tables and plots (default x0, x1, ... and u0, ...).
    mass, altitude : int or None
        The components holding the mass (fuel metrics) and the height above the ground
        (touchdown metrics and ``stop_at="touchdown"``), if any. An altitude that is one of
        ``positions`` has its crossing located on the step's interpolant, as the built-in
        landers do; another component, on the chord between the step's ends.
    name : str or None
        How the plant is named in messages (default: the derivative's ``module:qualname``).

    The cases run one after the other between the calls, on the calling thread, with the
    baseline kernel (``threads`` and ``kernel`` do not apply): the functions' time dominates.

    Examples
    --------
    >>> import numpy as np, landing
    >>> def falling(t, x, u, params):  # a point mass in 1 g, commanded in force
    ...     m = params["mass"][:, None]
    ...     return np.concatenate([x[:, 3:], u / m - [0.0, 0.0, 9.81]], axis=1)
    >>> plant = landing.plants.PythonPlant(falling, 6, positions=(0, 1, 2), velocities=(3, 4, 5),
    ...     model=lambda t, x, p: (np.tile([0.0, 0.0, -9.81], (len(x), 1)), np.repeat(p["mass"][:, None], 3, 1)),
    ...     params={"mass": 2.0})
    >>> r = landing.simulate(plant, landing.controllers.OpenLoop(), np.zeros(6), t_final=1.0, dt=0.1)
    >>> print(f"{r.final_state[2]:.3f} m")
    -4.905 m
    """

    derivative: Callable[..., Any]
    n_state: int
    positions: Sequence[int]
    velocities: Sequence[int]
    model: Optional[Callable[..., Any]] = None
    actuate: Optional[Callable[..., Any]] = None
    in_domain: Optional[Callable[..., Any]] = None
    params: Mapping[str, ArrayLike] = field(default_factory=dict)
    state_names: tuple[str, ...] = ()
    control_names: tuple[str, ...] = ()
    mass: Optional[int] = None
    altitude: Optional[int] = None
    name: Optional[str] = None

    kind: ClassVar[str] = "python"
    _in_core: ClassVar[bool] = False

    def __post_init__(self) -> None:
        owner = "PythonPlant"
        for key in ("derivative", "model", "actuate", "in_domain"):
            f = getattr(self, key)
            if (f is not None or key == "derivative") and not callable(f):
                raise ParameterTypeError(f"{owner}: {key} must be callable, got {type(f).__name__}")
        n_state = self.n_state
        whole = isinstance(n_state, (int, np.integer)) and not isinstance(n_state, bool)
        if not whole or not 1 <= n_state <= MAX_PYTHON_STATE:
            raise ParameterError(f"{owner}: n_state = {n_state!r} violates 1 <= n_state <= {MAX_PYTHON_STATE}")
        indices = {}
        for key in ("positions", "velocities"):
            v = getattr(self, key)
            if isinstance(v, (str, bytes)) or not isinstance(v, Sequence) and not isinstance(v, np.ndarray):
                raise ParameterTypeError(f"{owner}: {key} must be a sequence of component indices")
            indices[key] = tuple(int(i) for i in v)
        axes = len(indices["positions"])
        if axes not in (2, 3) or len(indices["velocities"]) != axes:
            raise ParameterError(f"{owner}: positions {indices['positions']} and velocities {indices['velocities']} "
                                 "violate one index per axis, 2 or 3 axes")
        every = indices["positions"] + indices["velocities"]
        if len(set(every)) != 2 * axes or not all(0 <= i < n_state for i in every):
            raise ParameterError(f"{owner}: positions and velocities {every} violate {2 * axes} distinct components "
                                 f"of 0..{n_state - 1}")
        for key in ("mass", "altitude"):
            i = getattr(self, key)
            if i is not None and not (isinstance(i, (int, np.integer)) and 0 <= i < n_state):
                raise ParameterError(f"{owner}: {key} = {i!r} violates a component of 0..{n_state - 1} or None")
        object.__setattr__(self, "n_state", int(n_state))
        object.__setattr__(self, "positions", indices["positions"])
        object.__setattr__(self, "velocities", indices["velocities"])
        object.__setattr__(self, "params", frozen_params(owner, self.params, "a scalar, (k,), (N,) or (N, k)"))
        for key, count, prefix in (("state_names", n_state, "x"), ("control_names", axes, "u")):
            names = tuple(str(s) for s in getattr(self, key)) or tuple(f"{prefix}{i}" for i in range(count))
            if len(names) != count:
                raise ParameterError(f"{owner}: {key} has {len(names)} names; the plant has {count}")
            object.__setattr__(self, key, names)
        if self.name is None:
            object.__setattr__(self, "name", qualified_name(self.derivative))
        self._compile()

    def _compile(self) -> None:
        """Nothing for the core to compile: the dynamics run in Python."""
        object.__setattr__(self, "_core", None)

    def _info(self) -> dict[str, Any]:
        return {"state_names": self.state_names, "control_names": self.control_names, "axes": self.axes}

    @property
    def axes(self) -> int:
        return len(self.positions)

    @property
    def parameters(self) -> Mapping[str, Parameter]:  # type: ignore[override]
        """The plant's parameters (scalars, shared vectors or values per case)."""
        return MappingProxyType({
            k: Parameter(name=k, shape="scalar", unit="", rule="", required=True, doc="a parameter of the plant")
            for k in self.params
        })

    @property
    def source_hash(self) -> str:
        """SHA-256 of the derivative's source (what a campaign's provenance records)."""
        return source_hash(self.derivative)

    def coordinates(self, states: Any) -> tuple[np.ndarray, np.ndarray]:
        """q and q' from states ``(..., n_state)``: the components ``positions`` and ``velocities``."""
        x = real_array("states", states, owner="PythonPlant")
        if x.ndim == 0 or x.shape[-1] != self.n_state:
            raise ParameterError(f"states have shape {x.shape}; this plant's have {self.n_state} components")
        return x[..., list(self.positions)], x[..., list(self.velocities)]

    def replace(self, **changes: Any) -> PythonPlant:
        """A copy with some fields or parameters changed: ``plant.replace(isp=300.0)`` changes
        ``params["isp"]``; ``plant.replace(params={...})`` replaces them all."""
        return replace_with_params(self, "PythonPlant", changes)

    @staticmethod
    def _rows(value: np.ndarray, n: int) -> Optional[int]:
        # as the functions see it (per_case): a vector of n values is one per case, another
        # vector is shared; a matrix has a row per case
        return value.shape[0] if value.ndim == 2 or (value.ndim == 1 and value.shape[0] == n) else None

    def case_rows(self, n: int, axes: int) -> dict[str, int]:
        return {k: r for k, v in self.params.items() if (r := self._rows(np.asarray(v), n)) is not None}

    def take_cases(self, start: int, stop: int, n: int, axes: int) -> PythonPlant:
        return params_taking_cases(self, lambda v: self._rows(v, n), start, stop)

    def _step(self, n: int, first_case: int) -> PlantStep:
        """The hooks the core calls for a batch of n cases numbered from ``first_case``."""
        name = self.name or ""
        params = {k: per_case(f"PythonPlant {name}", k, v, n) for k, v in self.params.items()}
        layout = (self.n_state, list(self.positions), list(self.velocities), self.mass, self.altitude)
        return PlantStep(name=name, derivative=self.derivative, model=self.model, actuate=self.actuate,
                         in_domain=self.in_domain, params=params, n_state=self.n_state, axes=self.axes,
                         layout=layout, n=n, first_case=first_case)
