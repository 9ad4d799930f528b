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
#: Mass of 433 Eros, kg (the fuzzy fast-terminal asteroid paper's "6.69e5 kg" is a typo for 6.69e15).
EROS_MASS = 6.687e15
_EROS_D = 17_200.0 / np.sqrt(5.0)


class Gravity(Table):
    """Base class of the gravity fields.

    A field is a frozen dataclass of its parameters; ``acceleration`` and ``potential``
    evaluate it in the Rust core at one position or a batch of them.

    Parameters
    ----------
    **fields : ArrayLike
        The subclass's fields (see each one); the base class takes none of its own.

    Examples
    --------
    >>> from landing.gravity import PointMass
    >>> g = PointMass(mu=4.842e5).acceleration([1000.0, 0.0, 0.0])
    >>> print(", ".join(f"{x + 0.0:.4f}" for x in g))
    -0.4842, 0.0000, 0.0000
    """

    family: ClassVar[str] = "gravity"

    _compiler = _core.Gravity

    def _evaluate(self, r: ArrayLike, potential: bool) -> np.ndarray:
        x = real_array("r", r, finite=True, owner=type(self).__name__)
        if x.shape[-1:] != (3,) or x.ndim > 2:
            raise ParameterError(f"{type(self).__name__}: r has shape {x.shape}; it takes (3,) or (N, 3)")
        out = self._core.evaluate(np.ascontiguousarray(x.reshape(-1, 3)), potential)
        return out[0] if x.ndim == 1 else out

    def acceleration(self, r: ArrayLike) -> np.ndarray:
        """The field g = grad U at r, m/s^2.

        Parameters
        ----------
        r : ArrayLike
            Position in the body frame, m: shape (3,) or (N, 3).

        Returns
        -------
        numpy.ndarray
            The acceleration, m/s^2, shape (3,) or (N, 3) like ``r``.

        Raises
        ------
        ParameterError
            If ``r`` is not finite or not of shape (3,) or (N, 3).
        """
        return self._evaluate(r, potential=False)

    def potential(self, r: ArrayLike) -> np.ndarray:
        """The potential U at r, m^2/s^2 (positive: U = +mu/r for a point mass).

        Parameters
        ----------
        r : ArrayLike
            Position in the body frame, m: shape (3,) or (N, 3).

        Returns
        -------
        numpy.ndarray
            The potential, m^2/s^2: a scalar for ``r`` of shape (3,), else shape (N,).

        Raises
        ------
        ParameterError
            If ``r`` is not finite or not of shape (3,) or (N, 3).
        """
        return self._evaluate(r, potential=True)


@dataclass(frozen=True, eq=False)
class PointMass(Gravity):
    """A point mass, U = mu / r.

    Parameters
    ----------
    mu : ArrayLike
        Gravitational parameter G M, m^3/s^2, scalar (or one per case); mu > 0.

    Examples
    --------
    >>> U = PointMass(mu=4.842e5).potential([[1000.0, 0.0, 0.0], [0.0, 2000.0, 0.0]])
    >>> print(", ".join(f"{u:.2f}" for u in U))
    484.20, 242.10
    """

    mu: ArrayLike

    kind: ClassVar[str] = "point_mass"


@dataclass(frozen=True, eq=False)
class TwoPointMass(Gravity):
    """Two mass points, U = sum_i G M_i / |r - r_i| (the fuzzy fast-terminal asteroid paper,
    eq. 2, sign fixed).

    Defaults: 433 Eros as a dumbbell, M = 6.687e15 kg in two halves at (+-a/sqrt(5), 0, 0)
    with a = 17.2 km, the second moment M a^2 / 5 of a homogeneous ellipsoid of semi-axis a
    along x (docs/parameters.md).

    Parameters
    ----------
    m1, m2 : ArrayLike
        Masses of the first and second point, kg, scalar; G m > 0. Default ``EROS_MASS / 2``.
    position1, position2 : ArrayLike
        Positions of the points in the body frame, m, per axis (3,). Default
        (+-17.2 km / sqrt(5), 0, 0) = (+-7692.07, 0, 0) m.
    G : ArrayLike
        Newton's constant, m^3/(kg s^2), scalar. Default the core's ``G``.

    Examples
    --------
    >>> g = TwoPointMass().acceleration([20_000.0, 0.0, 0.0])
    >>> print(f"{g[0]:.6f} m/s^2")
    -0.001764 m/s^2
    """

    m1: ArrayLike = EROS_MASS / 2
    m2: ArrayLike = EROS_MASS / 2
    position1: ArrayLike = field(default_factory=lambda: np.array([_EROS_D, 0.0, 0.0]))
    position2: ArrayLike = field(default_factory=lambda: np.array([-_EROS_D, 0.0, 0.0]))
    G: ArrayLike = G

    kind: ClassVar[str] = "two_point_mass"


@dataclass(frozen=True, eq=False)
class Harmonic2(Gravity):
    """Second-degree harmonics (the fuzzy variable-rate asteroid paper):
    U = (mu/r) [1 + (R0/r)^2 (C20 (3 z^2/r^2 - 1)/2 + 3 C22 (x^2 - y^2)/r^2)].

    Defaults: that paper's Table 2 (433 Eros).

    Parameters
    ----------
    mu : ArrayLike
        Gravitational parameter G M, m^3/s^2, scalar; mu > 0. Default 4.842e5.
    r0 : ArrayLike
        Reference radius R0 of the coefficients, m, scalar; r0 > 0. Default 1138.5.
    c20 : ArrayLike
        Second-degree zonal coefficient C20, dimensionless, scalar. Default -0.043.
    c22 : ArrayLike
        Second-degree sectoral coefficient C22, dimensionless, scalar. Default 0.058.

    Examples
    --------
    >>> g = Harmonic2().acceleration([2000.0, 0.0, 0.0])
    >>> print(", ".join(f"{x + 0.0:.4f}" for x in g))
    -0.1441, 0.0000, 0.0000
    """

    mu: ArrayLike = 4.842e5
    r0: ArrayLike = 1138.5
    c20: ArrayLike = -0.043
    c22: ArrayLike = 0.058

    kind: ClassVar[str] = "harmonic2"
