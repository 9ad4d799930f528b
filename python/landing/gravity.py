"""Gravity fields of small bodies. Sign convention: the potential U is positive for a
point mass (U = +mu/r) and the field is its gradient, g = grad U, so gravity always attracts.

Each field evaluates in the Rust core: ``field.acceleration(r)`` and ``field.potential(r)``
take ``r`` of shape (3,) or (N, 3).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np

from landing import _core
from landing._internal.args import real_array
from landing._internal.table import ArrayLike, Table
from landing.errors import ParameterError

__all__ = ["Gravity", "PointMass", "TwoPointMass", "Harmonic2", "G", "EROS_MASS"]

#: Newton's constant used by the core, m^3 / (kg s^2).
G = float(_core.GRAVITATIONAL_CONSTANT)
#: Mass of 433 Eros, kg (the seed-000 "6.69e5 kg" is a typo for 6.69e15).
EROS_MASS = 6.687e15
_EROS_D = 17_200.0 / np.sqrt(5.0)


class Gravity(Table):
    """Base class of the gravity fields."""

    family: ClassVar[str] = "gravity"

    _compiler = _core.Gravity

    def _evaluate(self, r: ArrayLike, potential: bool) -> np.ndarray:
        x = real_array("r", r, finite=True, owner=type(self).__name__)
        if x.shape[-1:] != (3,) or x.ndim > 2:
            raise ParameterError(f"{type(self).__name__}: r has shape {x.shape}; it takes (3,) or (N, 3)")
        out = self._core.evaluate(np.ascontiguousarray(x.reshape(-1, 3)), potential)
        return out[0] if x.ndim == 1 else out

    def acceleration(self, r: ArrayLike) -> np.ndarray:
        """The field g = grad U at r, m/s^2: shape (3,) or (N, 3) like r."""
        return self._evaluate(r, potential=False)

    def potential(self, r: ArrayLike) -> np.ndarray:
        """The potential U at r, m^2/s^2: a scalar or (N,)."""
        return self._evaluate(r, potential=True)


@dataclass(frozen=True, eq=False)
class PointMass(Gravity):
    """U = mu / r."""

    mu: ArrayLike

    kind: ClassVar[str] = "point_mass"


@dataclass(frozen=True, eq=False)
class TwoPointMass(Gravity):
    """Two mass points, U = sum_i G M_i / |r - r_i| (seed 000 eq. 2, sign fixed).

    Defaults: 433 Eros as a dumbbell, M = 6.687e15 kg in two halves at (+-a/sqrt(5), 0, 0)
    with a = 17.2 km, the second moment M a^2 / 5 of a homogeneous ellipsoid of semi-axis a
    along x (docs/parameters.md).
    """

    m1: ArrayLike = EROS_MASS / 2
    m2: ArrayLike = EROS_MASS / 2
    position1: ArrayLike = field(default_factory=lambda: np.array([_EROS_D, 0.0, 0.0]))
    position2: ArrayLike = field(default_factory=lambda: np.array([-_EROS_D, 0.0, 0.0]))
    G: ArrayLike = G

    kind: ClassVar[str] = "two_point_mass"


@dataclass(frozen=True, eq=False)
class Harmonic2(Gravity):
    """Second-degree harmonics (seed 002):
    U = (mu/r) [1 + (R0/r)^2 (C20 (3 z^2/r^2 - 1)/2 + 3 C22 (x^2 - y^2)/r^2)].

    Defaults: seed 002 Table 2 (433 Eros).
    """

    mu: ArrayLike = 4.842e5
    r0: ArrayLike = 1138.5
    c20: ArrayLike = -0.043
    c22: ArrayLike = 0.058

    kind: ClassVar[str] = "harmonic2"
