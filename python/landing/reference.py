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
    """Base class of the references."""

    family: ClassVar[str] = "reference"

    _compiler = _core.Reference

    def evaluate(self, t: ArrayLike, axes: int = 3) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Position, velocity and acceleration at times ``t``, each ``(len(t), axes)``
        (``(axes,)`` for a scalar t), computed by the core."""
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
    """A fixed target state: position (default the origin) and velocity (default zero)."""

    position: ArrayLike = 0.0
    velocity: ArrayLike = 0.0

    kind: ClassVar[str] = "constant"


@dataclass(frozen=True, eq=False)
class Cubic(Reference):
    """``p(t) = c0 + c1 t + c2 t^2 + c3 t^3`` per axis on ``[0, t_end]``; then, by ``after``, the
    end point held at rest (``"hold"``, the seeds' references) or extended at the end velocity,
    ``p(t) = p(t_end) + p'(t_end) (t - t_end)`` (``"extend"``: a constant-velocity phase, such
    as a lander's terminal descent).

    ``coefficients`` has shape ``(axes, 4)`` (columns c0..c3), or ``(N, axes, 4)`` per case.
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
        then ``after`` it (see the class)."""
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
        table: dict[str, Any] = {"kind": self.kind, "t_end": as_float_array("Cubic", "t_end", self.t_end),
                                 "after": self.after}
        for j in range(4):
            table[f"c{j}"] = np.ascontiguousarray(c[..., j])
        return table
