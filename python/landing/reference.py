"""Reference trajectories the laws track."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, ClassVar, Literal

import numpy as np

from landing import _core
from landing._internal.args import integer, real, real_array
from landing._internal.table import ArrayLike, Table, as_float_array
from landing.errors import ParameterError

__all__ = ["Reference", "Constant", "Cubic"]


class Reference(Table):
    """Base class of the references: the trajectory, in the plant's coordinate q, that a law
    tracks.

    Parameters
    ----------
    **fields : ArrayLike
        The subclass's fields (see each one); the base class takes none of its own.

    Examples
    --------
    >>> from landing.reference import Constant
    >>> p, v, a = Constant(position=[1.0, 2.0, 3.0]).evaluate(0.5)
    >>> print(p, v)
    [1. 2. 3.] [0. 0. 0.]
    """

    family: ClassVar[str] = "reference"

    _compiler = _core.Reference

    def evaluate(self, t: ArrayLike, axes: int = 3) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Position, velocity and acceleration of the reference at times ``t``, computed by the
        core.

        Parameters
        ----------
        t : ArrayLike
            Time, s: a scalar or a 1-D array.
        axes : int
            Number of axes of the plant, 2 or 3 (default 3).

        Returns
        -------
        tuple of numpy.ndarray
            ``(position, velocity, acceleration)`` in q, q/s and q/s^2, each of shape
            ``(len(t), axes)``, or ``(axes,)`` for a scalar ``t``.

        Raises
        ------
        ParameterError
            If ``t`` is not finite or ``axes`` is not 2 or 3.

        Examples
        --------
        >>> ref = Cubic.from_boundary([10.0, 0.0], [0.0, 0.0], [0.0, 0.0], [0.0, 0.0], T=10.0)
        >>> p, v, a = ref.evaluate([0.0, 5.0, 20.0], axes=2)
        >>> print(p[:, 0], v[:, 0])
        [10.  5.  0.] [ 0.  -1.5  0. ]
        """
        owner = type(self).__name__
        tt = real_array("t", t, finite=True, owner=owner)
        axes = integer("axes", axes, owner=owner)
        if axes not in (2, 3):
            raise ParameterError(f"{owner}: axes = {axes} violates axes in (2, 3)")
        out = self._core.evaluate(axes, tt.ravel().tolist())
        p, v, a = (out[k] for k in ("position", "velocity", "acceleration"))
        if tt.ndim == 0:
            return p[0], v[0], a[0]
        return p, v, a


@dataclass(frozen=True, eq=False)
class Constant(Reference):
    """A fixed target state: position (default the origin) and velocity (default zero).

    Parameters
    ----------
    position : ArrayLike
        The target position, q, per axis (a scalar is the same on every axis). Default 0.
    velocity : ArrayLike
        The target velocity, q/s, per axis. Default 0.

    Examples
    --------
    >>> p, v, a = Constant(position=[0.0, 0.0, 5.0]).evaluate([0.0, 1.0])
    >>> print(p.shape, p[1])
    (2, 3) [0. 0. 5.]
    """

    position: ArrayLike = 0.0
    velocity: ArrayLike = 0.0

    kind: ClassVar[str] = "constant"


@dataclass(frozen=True, eq=False)
class Cubic(Reference):
    """``p(t) = c0 + c1 t + c2 t^2 + c3 t^3`` per axis on ``[0, t_end]``; then, by ``after``, the
    end point held at rest (``"hold"``, the asteroid papers' references) or extended at the end velocity,
    ``p(t) = p(t_end) + p'(t_end) (t - t_end)`` (``"extend"``: a constant-velocity phase, such
    as a lander's terminal descent).

    ``coefficients`` has shape ``(axes, 4)`` (columns c0..c3), or ``(N, axes, 4)`` per case.

    Parameters
    ----------
    coefficients : ArrayLike
        The coefficients c0, c1, c2, c3 in q, q/s, q/s^2, q/s^3: shape ``(axes, 4)``, or
        ``(N, axes, 4)`` per case.
    t_end : ArrayLike
        End of the cubic, s, scalar; t_end > 0.
    after : {"hold", "extend"}
        Past ``t_end``: hold the end point at rest (default) or extend it at the end velocity.

    Raises
    ------
    ParameterError
        When compiled, if ``coefficients`` is not of shape ``(axes, 4)`` or ``(N, axes, 4)``.

    Examples
    --------
    >>> ref = Cubic(coefficients=[[10.0, 0.0, -0.3, 0.02], [0.0, 0.0, 0.0, 0.0]], t_end=10.0,
    ...             after="extend")
    >>> p, v, a = ref.evaluate(12.0, axes=2)
    >>> print(f"{p[0]:.3f} {v[0]:.3f}")
    0.000 0.000
    """

    coefficients: ArrayLike
    t_end: ArrayLike
    after: Literal["hold", "extend"] = "hold"

    kind: ClassVar[str] = "cubic"

    @classmethod
    def from_boundary(
        cls, p0: ArrayLike, v0: ArrayLike, pT: ArrayLike, vT: ArrayLike, T: float,
        after: Literal["hold", "extend"] = "hold",
    ) -> Cubic:
        """The cubic through position and velocity ``p0, v0`` at 0 and ``pT, vT`` at ``T``,
        then ``after`` it (see the class).

        Parameters
        ----------
        p0, v0 : ArrayLike
            Position (q) and velocity (q/s) at t = 0, one value per axis.
        pT, vT : ArrayLike
            Position (q) and velocity (q/s) at t = ``T``, one value per axis.
        T : float
            Duration of the cubic, s.
        after : {"hold", "extend"}
            Past ``T``: hold the end point (default) or extend it at ``vT``.

        Returns
        -------
        Cubic
            The reference, with ``coefficients`` of shape ``(axes, 4)``.

        Examples
        --------
        >>> ref = Cubic.from_boundary([10.0, 0.0, 5.0], [0.0] * 3, [0.0] * 3, [0.0] * 3, T=10.0)
        >>> print(ref.coefficients[0])
        [10.    0.   -0.3   0.02]
        """
        p0l, v0l, pTl, vTl = [real_array(n, v, finite=True, owner=cls.__name__).ravel().tolist() for n, v in
                              (("p0", p0), ("v0", v0), ("pT", pT), ("vT", vT))]
        t_end = real("T", T, owner=cls.__name__)
        c = _core.cubic_from_boundary(p0l, v0l, pTl, vTl, t_end)
        return cls(coefficients=np.array(c).T, t_end=t_end, after=after)

    def _table(self) -> dict[str, Any]:
        c = as_float_array(type(self).__name__, "coefficients", self.coefficients)
        if c.ndim not in (2, 3) or c.shape[-1] != 4:
            raise ParameterError(
                f"Cubic: coefficients has shape {c.shape}; it takes (axes, 4) or (N, axes, 4)"
            )
        bad = np.argwhere(~np.isfinite(c))
        if bad.size:
            # the core reads the columns as c0..c3: refused here, the message names the argument
            where = tuple(int(i) for i in bad[0])
            value = "NaN" if np.isnan(c[where]) else f"{c[where]:g}"
            raise ParameterError(f"Cubic: coefficients = {value} violates finite values (entry {list(where)})")
        table: dict[str, Any] = {"kind": self.kind, "t_end": as_float_array("Cubic", "t_end", self.t_end),
                                 "after": self.after}
        for j in range(4):
            table[f"c{j}"] = np.ascontiguousarray(c[..., j])
        return table
