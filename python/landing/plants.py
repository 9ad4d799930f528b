"""Plants: the dynamics a batch integrates (SPEC section 3).

A plant holds physical parameters only; any numeric parameter may be given per case (an array
with one entry per case of the batch, or ``(N, 3)`` for per-axis ones).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import ClassVar, Optional

import numpy as np

from landing import _core
from landing._table import ArrayLike, Table
from landing.gravity import Gravity, TwoPointMass

__all__ = ["Plant", "MarsLander", "DoubleIntegrator", "SmallBody"]


class Plant(Table):
    """Base class of the plants."""

    def __post_init__(self) -> None:
        _core.check_plant(type(self).__name__, self._table())

    @property
    def state_names(self) -> tuple[str, ...]:
        return tuple(_core.plant_info(self.kind)["state_names"])

    @property
    def control_names(self) -> tuple[str, ...]:
        return tuple(_core.plant_info(self.kind)["control_names"])

    @property
    def axes(self) -> int:
        """Number of generalized coordinates (and of command components)."""
        return int(_core.plant_info(self.kind)["axes"])

    @property
    def state_dim(self) -> int:
        return len(self.state_names)


@dataclass(eq=False)
class MarsLander(Plant):
    """Mars powered descent (seed 001, SPEC 3.1).

    State ``[rx, ry, rz, vx, vy, vz, m]`` in an inertial frame at the target, z up; the
    command is the engine force ``F = m a`` (N), clipped per axis to ``thrust_limit``.

    ``r' = v``, ``v' = F/m + g + a_drag + a_p(t)``, ``m' = -|F| / (isp g0)``, with
    ``a_drag_i = -drag_coefficient v_i |v_i| exp(-density_decay rz) / (area_i m)``.

    Parameters
    ----------
    isp : specific impulse, s (225 s, Acikmese and Ploen 2007, the seed's reference [1]).
    area : effective cross-sections perpendicular to x, y, z, m^2 (seed Table I).
    gravity : Mars surface gravity, m/s^2 (acts along -z).
    drag : whether the plant has drag (the guidance then models it).
    thrust_limit : per-axis limit on |F_i|, N; ``None`` for unlimited (seed part 3: 50 kN).
    drag_coefficient : k_d of seed eq. 12, kg/m.
    density_decay : h_d of seed eq. 12, 1/m (the seed's 0.0009; the Mars-atmosphere model it
        cites uses 0.00009).
    g0 : standard gravity in the rocket equation, m/s^2.
    """

    isp: ArrayLike = 225.0
    area: ArrayLike = (6.0, 7.5, 8.7)
    gravity: ArrayLike = 3.7114
    drag: bool = True
    thrust_limit: Optional[ArrayLike] = None
    drag_coefficient: ArrayLike = 0.699
    density_decay: ArrayLike = 0.0009
    g0: ArrayLike = 9.807

    kind: ClassVar[str] = "mars_lander"

    @staticmethod
    def initial_state(position: ArrayLike, velocity: ArrayLike, mass: ArrayLike) -> np.ndarray:
        """Stack positions ``(..., 3)``, velocities ``(..., 3)`` and masses ``(...)`` into states ``(..., 7)``."""
        r = np.asarray(position, dtype=np.float64)
        v = np.asarray(velocity, dtype=np.float64)
        m = np.asarray(mass, dtype=np.float64)
        shape = np.broadcast_shapes(r.shape[:-1], v.shape[:-1], m.shape)
        return np.concatenate(
            [np.broadcast_to(r, shape + (3,)), np.broadcast_to(v, shape + (3,)), np.broadcast_to(m, shape)[..., None]],
            axis=-1,
        )


@dataclass(eq=False)
class DoubleIntegrator(Plant):
    """``q'' = u + d`` on three axes: no drift, unit inertia.

    The plant on which a law's reaching law holds exactly, used to check the theory's bounds
    against simulation, and the simplest test bed for any law. State ``[x, y, z, vx, vy, vz]``;
    the command is the acceleration, clipped per axis to ``acceleration_limit`` (None: none).
    """

    acceleration_limit: Optional[ArrayLike] = None

    kind: ClassVar[str] = "double_integrator"


@dataclass(eq=False)
class SmallBody(Plant):
    """A probe near a small body, in the body's frame rotating at ``omega`` about z (seeds 000
    and 002, SPEC 3.2). State ``[x, y, z, vx, vy, vz]``; the command is a control acceleration
    (m/s^2), clipped per axis to ``acceleration_limit`` (None: none).

    ``x'' - 2 omega y' - omega^2 x = g_x + u_x + d_x``, ``y'' + 2 omega x' - omega^2 y = g_y + u_y + d_y``,
    ``z'' = g_z + u_z + d_z``, with g from a :mod:`landing.gravity` field. Defaults: seed 000
    (433 Eros as two mass points, omega = 3.3118e-4 rad/s).
    """

    gravity: Gravity = field(default_factory=TwoPointMass)
    omega: ArrayLike = 3.3118e-4
    acceleration_limit: Optional[ArrayLike] = None

    kind: ClassVar[str] = "small_body"
