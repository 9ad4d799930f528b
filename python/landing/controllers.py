"""Control laws (SPEC section 5).

Every law runs in the Rust core and works on any plant with the right number of axes: gains
are per axis (a scalar applies to every axis) and may be given per case to sweep them in one
batch. A law returns a commanded generalized acceleration; the plant's actuator turns it into
thrust or torque and saturates it.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

from landing import _core
from landing._table import ArrayLike, Table

__all__ = ["Controller", "FixedTimeMSS", "SuperTwisting", "OpenLoop"]


class Controller(Table):
    """Base class of the control laws."""

    def __post_init__(self) -> None:
        _core.check_controller(type(self).__name__, self._table())


@dataclass(eq=False)
class FixedTimeMSS(Controller):
    """Fixed-time multiple-sliding-surface guidance (seed 001 eq. 15-25).

    ``s1 = r - r_d``, ``s2 = s1' + beta1 sig^q1(s1) + beta2 sig^q2(s1)``; the law drives
    ``s2' = -alpha1 sig^gamma1(s2) - alpha2 sig^gamma2(s2)``, after which s1 reaches zero in a
    fixed time (``landing.theory`` gives the bounds).

    Parameters (each a scalar, a per-axis triple, or per case)
    ----------
    beta1, beta2 : gains of the first reaching law (> 0).
    q1, q2 : its exponents, 0 < q1 < 1 < q2.
    alpha1, alpha2 : gains of the second reaching law (> 0).
    gamma1, gamma2 : its exponents (the seed's g1, g2), 0 < gamma1 < 1 < gamma2.
    variant : ``"printed"`` is eq. 25 as printed (drops the s2-coupling terms of the exact
        derivative of s2); ``"exact"`` uses the exact derivative, so the second reaching law
        holds everywhere, not only on s2 = 0.
    s1_floor : singularity guard, m: floor on |s1| wherever it is raised to a negative power
        (``|s1|^(q1-1)`` in the exact variant; ``|s1|^(2 q1 - 1)`` when q1 < 1/2).
    """

    beta1: ArrayLike
    beta2: ArrayLike
    q1: ArrayLike
    q2: ArrayLike
    alpha1: ArrayLike
    alpha2: ArrayLike
    gamma1: ArrayLike
    gamma2: ArrayLike
    variant: Literal["printed", "exact"] = "printed"
    s1_floor: ArrayLike = 1e-3

    kind = "fixed_time_mss"


@dataclass(eq=False)
class SuperTwisting(Controller):
    """Super-twisting guidance, the seed-001 baseline (eq. 46).

    Parameters
    ----------
    b1, b2 : gains in force units, divided by the plant's inertia (the lander's mass), as in
        eq. 46. Defaults: the seed's B1 = (1200, 1000, 1000), B2 = (5500, 5000, 5000).
    variant : ``"printed"``: eq. 46, ``a = -(1/m)((b1/2)|s|^(-1/2) s' + b2 sgn(s)) - g`` with
        s the position error (singular at s = 0, guarded by ``s_floor``). ``"standard"``: the
        textbook algorithm on ``sigma = s' + c s`` with its integral state,
        ``a = -c s' + (1/m)(-b1 sig^(1/2)(sigma) + w)``, ``w' = -b2 sgn(sigma)``.
    c : slope of sigma in the standard variant, 1/s.
    s_floor : floor on |s| in ``|s|^(-1/2)`` of the printed variant, m.
    """

    b1: ArrayLike = (1200.0, 1000.0, 1000.0)
    b2: ArrayLike = (5500.0, 5000.0, 5000.0)
    variant: Literal["printed", "standard"] = "printed"
    c: ArrayLike = 1.0
    s_floor: ArrayLike = 1e-3

    kind = "super_twisting"


@dataclass(eq=False)
class OpenLoop(Controller):
    """A constant commanded acceleration (free flight, ballistic baselines, closed-form checks).

    The plant's actuator applies it as usual: a lander's thrust is ``m a``, clipped to its limit.
    """

    acceleration: ArrayLike = 0.0

    kind = "open_loop"
