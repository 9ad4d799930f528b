"""Control laws.

Every law runs in the Rust core and works on any plant with the right number of axes: gains
are per axis (a scalar applies to every axis) and may be given per case to sweep them in one
batch. A law returns a commanded generalized acceleration; the plant's actuator turns it into
thrust or torque and saturates it.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Any, ClassVar, Literal, Optional, Union

import numpy as np

from landing import _core
from landing._internal.args import integer
from landing._internal.table import ArrayLike, Parameter, Table, as_float_array, case_rows
from landing._internal.user_law import qualified_name, source_hash
from landing._internal.user_params import frozen_params, params_taking_cases, replace_with_params
from landing.errors import ParameterError, ParameterTypeError
from landing.fuzzy import variable_rate_system

__all__ = [
    "Controller",
    "FixedTimeMSS",
    "SuperTwisting",
    "OpenLoop",
    "PDSlidingMode",
    "FastTerminalSMC",
    "FuzzyFastTerminalSMC",
    "IntegralExponentialReaching",
    "FuzzyVariableRate",
    "NTSMC",
    "FixedTimeNTSMC",
    "Tabulated",
    "PythonLaw",
]


class Controller(Table):
    """Base class of the control laws: each maps the tracking errors (and the plant's model)
    to a commanded generalized acceleration, q/s^2.

    Parameters
    ----------
    **fields : ArrayLike
        The subclass's fields (see each one); the base class takes none of its own.

    Examples
    --------
    >>> PDSlidingMode(lambda_=1.0, k=0.5).diagnostic_layout(3)
    [('s', 3)]
    """

    family: ClassVar[str] = "law"

    _compiler = _core.Law

    def diagnostic_layout(self, axes: int) -> list[tuple[str, int]]:
        """Names and widths of the law's diagnostic signals on a plant of ``axes`` axes, in
        recording order.

        Parameters
        ----------
        axes : int
            The plant's number of axes, 2 or 3.

        Returns
        -------
        list of tuple of (str, int)
            ``(name, width)``: width ``axes`` for a per-axis signal, 1 for a scalar one.
        """
        return [(str(name), int(width)) for name, width in self._core.diagnostic_layout(axes)]


@dataclass(frozen=True, eq=False)
class FixedTimeMSS(Controller):
    """Fixed-time multiple-sliding-surface guidance (the Mars fixed-time guidance paper,
    eq. 15-25).

    ``s1 = r - r_d``, ``s2 = s1' + beta1 sig^q1(s1) + beta2 sig^q2(s1)``; the law drives
    ``s2' = -alpha1 sig^gamma1(s2) - alpha2 sig^gamma2(s2)``, after which s1 reaches zero in a
    fixed time (``landing.theory`` gives the bounds). Each parameter is a scalar, a per-axis
    triple, or given per case.

    Parameters
    ----------
    beta1, beta2 : ArrayLike
        Gains of the first reaching law's sig^q1 and sig^q2 terms, > 0, units m^(1 - q1)/s and
        m^(1 - q2)/s.
    q1, q2 : ArrayLike
        Its exponents, 0 < q1 < 1 < q2.
    alpha1, alpha2 : ArrayLike
        Gains of the second reaching law's sig^gamma1 and sig^gamma2 terms, > 0, units
        (m/s)^(1 - gamma1)/s and (m/s)^(1 - gamma2)/s.
    gamma1, gamma2 : ArrayLike
        Its exponents (the paper's g1, g2), 0 < gamma1 < 1 < gamma2.
    variant : {"printed", "exact"}
        ``"printed"`` is eq. 25 as printed (drops the s2-coupling terms of the exact
        derivative of s2); ``"exact"`` uses the exact derivative, so the second reaching law
        holds everywhere, not only on s2 = 0.
    s1_floor : ArrayLike
        Singularity guard, m, scalar, > 0: floor on |s1| wherever it is raised to a negative
        power (``|s1|^(q1-1)`` in the exact variant; ``|s1|^(2 q1 - 1)`` when q1 < 1/2).

    Examples
    --------
    >>> import landing
    >>> law = FixedTimeMSS(beta1=1.0, beta2=1.0, q1=0.5, q2=1.5, alpha1=1.0, alpha2=1.0,
    ...                  gamma1=0.5, gamma2=1.5)
    >>> r = landing.simulate(landing.plants.DoubleIntegrator(), law, [1.0, 0, 0, 0, 0, 0],
    ...                      t_final=10.0, dt=0.01)
    >>> print(f"{r.metrics['final_position_error']:.3f} {r.metrics['final_velocity_error']:.3f}")
    0.045 0.008
    >>> law.diagnostic_layout(3)
    [('s1', 3), ('s2', 3)]
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

    kind: ClassVar[str] = "fixed_time_mss"


@dataclass(frozen=True, eq=False)
class SuperTwisting(Controller):
    """Super-twisting guidance, the Mars fixed-time guidance paper's baseline (eq. 46).

    Parameters
    ----------
    b1, b2 : ArrayLike
        Gains in force units, N, > 0, divided by the plant's inertia (the lander's mass), as
        in eq. 46. Defaults: the paper's B1 = (1200, 1000, 1000), B2 = (5500, 5000, 5000).
    variant : {"printed", "standard"}
        ``"printed"``: eq. 46, ``a = -(1/m)((b1/2)|s|^(-1/2) s' + b2 sgn(s)) - g`` with
        s the position error (singular at s = 0, guarded by ``s_floor``). ``"standard"``: the
        textbook algorithm on ``sigma = s' + c s`` with its integral state,
        ``a = -c s' + (1/m)(-b1 sig^(1/2)(sigma) + w)``, ``w' = -b2 sgn(sigma)``.
    c : ArrayLike
        Slope of sigma in the standard variant, 1/s, > 0.
    s_floor : ArrayLike
        Floor on |s| in ``|s|^(-1/2)`` of the printed variant, m, scalar, > 0.

    Examples
    --------
    >>> import landing
    >>> law = SuperTwisting(b1=2.0, b2=1.0, variant="standard", c=1.0)
    >>> r = landing.simulate(landing.plants.DoubleIntegrator(), law, [1.0, 0, 0, 0, 0, 0],
    ...                      t_final=10.0, dt=0.01)
    >>> print(f"{r.metrics['final_position_error']:.3f} {r.metrics['final_velocity_error']:.3f}")
    0.000 0.000
    """

    b1: ArrayLike = (1200.0, 1000.0, 1000.0)
    b2: ArrayLike = (5500.0, 5000.0, 5000.0)
    variant: Literal["printed", "standard"] = "printed"
    c: ArrayLike = 1.0
    s_floor: ArrayLike = 1e-3

    kind: ClassVar[str] = "super_twisting"


@dataclass(frozen=True, eq=False)
class OpenLoop(Controller):
    """A constant commanded acceleration (free flight, ballistic baselines, closed-form checks).

    The plant's actuator applies it as usual: a lander's thrust is ``m a``, clipped to its limit.

    Parameters
    ----------
    acceleration : ArrayLike
        The commanded generalized acceleration, q/s^2, per axis (default 0).

    Examples
    --------
    x = 1 + 0.1 t^2 / 2 = 6 and v = 1 at t = 10 s:

    >>> import landing
    >>> law = OpenLoop(acceleration=[0.1, 0.0, 0.0])
    >>> r = landing.simulate(landing.plants.DoubleIntegrator(), law, [1.0, 0, 0, 0, 0, 0],
    ...                      t_final=10.0, dt=0.01)
    >>> print(f"{r.metrics['final_position_error']:.3f} {r.metrics['final_velocity_error']:.3f}")
    6.000 1.000
    """

    acceleration: ArrayLike = 0.0

    kind: ClassVar[str] = "open_loop"


@dataclass(frozen=True, eq=False)
class PDSlidingMode(Controller):
    """PD sliding mode, the fuzzy fast-terminal asteroid paper's baseline: ``s = e' + lambda e``,
    ``u = u_eq - k switch(s)``, the equivalent control from s' = 0 with the plant's model.

    Each parameter is per axis, or given per case.

    Parameters
    ----------
    lambda_ : ArrayLike
        Slope of the surface, 1/s, > 0 (``lambda`` is a Python keyword, so the field, the TOML
        key and ``PDSlidingMode.parameters`` are all ``lambda_``).
    k : ArrayLike
        Switching gain, in command units, q/s^2 (m/s^2 on a small body), > 0.
    switch : {"sign", "sat", "tanh"}
        Switching function: sign(s), sat(s / phi) = clamp(s / phi, -1, 1) or tanh(s / phi)
        (default ``"sign"``).
    boundary_layer : float
        Boundary-layer width phi of sat and tanh, units of s, > 0 (unused by sign).

    Examples
    --------
    >>> import landing
    >>> law = PDSlidingMode(lambda_=1.0, k=0.5, switch="sat", boundary_layer=0.1)
    >>> r = landing.simulate(landing.plants.DoubleIntegrator(), law, [1.0, 0, 0, 0, 0, 0],
    ...                      t_final=10.0, dt=0.01)
    >>> print(f"{r.metrics['final_position_error']:.3f} {r.metrics['final_velocity_error']:.3f}")
    0.000 0.000
    """

    lambda_: ArrayLike
    k: ArrayLike
    switch: Literal["sign", "sat", "tanh"] = "sign"
    boundary_layer: float = 1.0

    kind: ClassVar[str] = "pd_sliding_mode"


@dataclass(frozen=True, eq=False)
class FastTerminalSMC(Controller):
    """Fast terminal sliding mode (the fuzzy fast-terminal asteroid paper, eq. 6, 14, 19):
    ``s = e' + alpha e + beta sig^(p/q)(e)``, ``u = u_eq - k switch(s)``.

    Parameters
    ----------
    alpha : ArrayLike
        Gain of e in the surface, 1/s, > 0.
    beta : ArrayLike
        Gain of sig^(p/q)(e) in the surface, q^(1 - p/q)/s, > 0.
    p, q : ArrayLike
        The exponent p/q, 0 < p < q (the paper takes odd integers; with sig any ratio keeps
        the sign of e).
    k : ArrayLike
        Switching gain, in command units, q/s^2, > 0.
    switch : {"sign", "sat", "tanh"}
        Switching function: sign(s), sat(s / phi) = clamp(s / phi, -1, 1) or tanh(s / phi)
        (default ``"sign"``).
    boundary_layer : float
        Boundary-layer width phi of sat and tanh, units of s, > 0 (unused by sign).
    e_floor : ArrayLike
        Singularity guard, in units of q, scalar, > 0: |e| is floored there in |e|^(p/q - 1)
        of the equivalent control.

    Examples
    --------
    >>> import landing
    >>> law = FastTerminalSMC(alpha=1.0, beta=0.5, p=3, q=5, k=0.5, switch="sat", boundary_layer=0.1)
    >>> r = landing.simulate(landing.plants.DoubleIntegrator(), law, [1.0, 0, 0, 0, 0, 0],
    ...                      t_final=10.0, dt=0.01)
    >>> print(f"{r.metrics['final_position_error']:.3f} {r.metrics['final_velocity_error']:.3f}")
    0.000 0.000
    """

    alpha: ArrayLike
    beta: ArrayLike
    p: ArrayLike
    q: ArrayLike
    k: ArrayLike
    switch: Literal["sign", "sat", "tanh"] = "sign"
    boundary_layer: float = 1.0
    e_floor: ArrayLike = 1e-3

    kind: ClassVar[str] = "fast_terminal_smc"


@dataclass(frozen=True, eq=False)
class FuzzyFastTerminalSMC(Controller):
    """Fuzzy-blended fast terminal sliding mode (the fuzzy fast-terminal asteroid paper,
    eq. 20-22):
    ``u = a(D) u_eq + b(D) u_s`` with ``a = exp(-n D)``, ``b = 1 - exp(-m D)`` and D the
    distance of the state to the surface, ``D_i = s_i / sqrt(1 + alpha_i^2)``.
    Records the blend (a, b, D) as scalar diagnostics.

    Parameters
    ----------
    alpha, beta, p, q, k : ArrayLike
        As for :class:`FastTerminalSMC`.
    n : ArrayLike
        The paper's N: how fast the equivalent control's weight a(D) = exp(-N D) falls, s/q,
        scalar, > 0.
    m : ArrayLike
        The paper's M: how fast the switching weight b(D) = 1 - exp(-M D) rises, s/q, scalar,
        > 0.
    switch : {"sign", "sat", "tanh"}
        Switching function: sign(s), sat(s / phi) = clamp(s / phi, -1, 1) or tanh(s / phi)
        (default ``"sign"``).
    boundary_layer : float
        Boundary-layer width phi of sat and tanh, units of s, > 0 (unused by sign).
    e_floor : ArrayLike
        As for :class:`FastTerminalSMC`.

    Examples
    --------
    >>> import landing
    >>> law = FuzzyFastTerminalSMC(alpha=1.0, beta=0.5, p=3, q=5, k=0.5, n=2.0, m=2.0, switch="sat",
    ...                          boundary_layer=0.1)
    >>> r = landing.simulate(landing.plants.DoubleIntegrator(), law, [1.0, 0, 0, 0, 0, 0],
    ...                      t_final=10.0, dt=0.01)
    >>> print(f"{r.metrics['final_position_error']:.3f} {r.metrics['final_velocity_error']:.3f}")
    0.002 0.000
    >>> law.diagnostic_layout(3)
    [('s', 3), ('a', 1), ('b', 1), ('distance', 1)]
    """

    alpha: ArrayLike
    beta: ArrayLike
    p: ArrayLike
    q: ArrayLike
    k: ArrayLike
    n: ArrayLike
    m: ArrayLike
    switch: Literal["sign", "sat", "tanh"] = "sign"
    boundary_layer: float = 1.0
    e_floor: ArrayLike = 1e-3

    kind: ClassVar[str] = "fuzzy_fast_terminal_smc"


@dataclass(frozen=True, eq=False)
class IntegralExponentialReaching(Controller):
    """Integral sliding surface with the exponential reaching law (the fuzzy variable-rate
    asteroid paper, eq. 10-12) in the
    stable form ``s = -sigma' - int(c1 sigma + c2 sigma')``:
    ``u = q_ref'' - drift - c1 sigma - c2 sigma' + k s + epsilon switch(s)``, so that
    ``s' = -k s - epsilon sgn(s)`` and, on s = 0, ``sigma'' + c2 sigma' + c1 sigma = 0``.
    (The paper's printed surface gives unstable sliding dynamics.)

    Parameters
    ----------
    c1 : ArrayLike
        Gain of sigma in the integral, I' = c1 sigma + c2 sigma', 1/s^2, > 0.
    c2 : ArrayLike
        Gain of sigma' in the integral, 1/s, > 0.
    k : ArrayLike
        Rate of the exponential reaching law, 1/s, >= 0.
    epsilon : ArrayLike
        Switching gain of the reaching law, q/s^2, >= 0.
    switch : {"sign", "sat", "tanh"}
        Switching function: sign(s), sat(s / phi) = clamp(s / phi, -1, 1) or tanh(s / phi)
        (default ``"sign"``).
    boundary_layer : float
        Boundary-layer width phi of sat and tanh, units of s, > 0 (unused by sign).

    Examples
    --------
    >>> import landing
    >>> law = IntegralExponentialReaching(c1=1.0, c2=2.0, k=1.0, epsilon=0.05, switch="sat",
    ...                                 boundary_layer=0.1)
    >>> r = landing.simulate(landing.plants.DoubleIntegrator(), law, [1.0, 0, 0, 0, 0, 0],
    ...                      t_final=10.0, dt=0.01)
    >>> print(f"{r.metrics['final_position_error']:.3f} {r.metrics['final_velocity_error']:.3f}")
    0.001 0.000
    """

    c1: ArrayLike
    c2: ArrayLike
    k: ArrayLike
    epsilon: ArrayLike
    switch: Literal["sign", "sat", "tanh"] = "sign"
    boundary_layer: float = 1.0

    kind: ClassVar[str] = "integral_exponential_reaching"


@dataclass(frozen=True, eq=False)
class FuzzyVariableRate(Controller):
    """Fuzzy variable-rate reaching law (the fuzzy variable-rate asteroid paper, sec. 2.3): the
    surface of
    :class:`IntegralExponentialReaching`, with ``epsilon sgn(s)`` replaced by
    ``ku F(ke s, kec s')``, F the Mamdani system (by default the paper's 5x5 rules,
    :func:`landing.fuzzy.variable_rate_system`) and s' the backward difference of s over the
    control period. Records s, s' and the fuzzy term.

    Parameters
    ----------
    c1, c2, k : ArrayLike
        Surface and exponential-rate gains, as for :class:`IntegralExponentialReaching`
        (1/s^2, 1/s, 1/s).
    ke : ArrayLike
        Input scaling of s onto the system's universe [-5, 5], s/q, > 0.
    kec : ArrayLike
        Input scaling of s' onto the universe, s^2/q, > 0.
    ku : ArrayLike
        Output scaling factor, command units (q/s^2) per unit of the output universe, > 0.
    system : Mamdani or None
        A :class:`landing.fuzzy.Mamdani` with two inputs (s and s'); None (default) for
        :func:`landing.fuzzy.variable_rate_system`.

    Examples
    --------
    >>> import landing
    >>> law = FuzzyVariableRate(c1=1.0, c2=2.0, k=1.0, ke=5.0, kec=5.0, ku=0.02)
    >>> r = landing.simulate(landing.plants.DoubleIntegrator(), law, [1.0, 0, 0, 0, 0, 0],
    ...                      t_final=10.0, dt=0.01)
    >>> print(f"{r.metrics['final_position_error']:.3f} {r.metrics['final_velocity_error']:.3f}")
    0.001 0.000
    """

    c1: ArrayLike
    c2: ArrayLike
    k: ArrayLike
    ke: ArrayLike
    kec: ArrayLike
    ku: ArrayLike
    system: Any = None

    kind: ClassVar[str] = "fuzzy_variable_rate"

    def __post_init__(self) -> None:
        if self.system is None:
            object.__setattr__(self, "system", variable_rate_system())
        super().__post_init__()


@dataclass(frozen=True, eq=False)
class NTSMC(Controller):
    """Conventional nonsingular terminal sliding mode, the tethered-satellite paper's baseline
    (its eq. 47/48).

    ``s = e1 + (1/beta) sig^(gamma/alpha)(e2)``,
    ``u = -M (beta (alpha/gamma) sig^(2 - gamma/alpha)(e2) + k sign(s))``, with e1 = q - q_d,
    e2 = q' - q_d' and M the plant's inertia. Defaults: the paper's alpha = diag(1, 1),
    beta = diag(0.05, 0.3), gamma = diag(1.07, 1.1), K = diag(0.001, 0.001) for the tethered
    satellite's (phi, theta); give three values per gain on a 3-axis plant.

    The law is nonsingular by construction: every power is non-negative because
    ``1 < gamma/alpha < 2`` is required (that range is its singularity guard).

    Parameters
    ----------
    alpha : ArrayLike
        Denominator of the surface's exponent gamma / alpha, dimensionless, > 0.
    beta : ArrayLike
        The surface's gain, s^(gamma/alpha) q^(1 - gamma/alpha), > 0.
    gamma : ArrayLike
        Numerator of the surface's exponent, > 0, with 1 < gamma / alpha < 2.
    k : ArrayLike
        Switching gain, in command units divided by the inertia, q/s^2, > 0.

    Examples
    --------
    >>> import landing
    >>> law = NTSMC(alpha=1.0, beta=1.0, gamma=1.5, k=0.05)
    >>> r = landing.simulate(landing.plants.DoubleIntegrator(), law, [1.0, 0, 0, 0, 0, 0],
    ...                      t_final=10.0, dt=0.01)
    >>> print(f"{r.metrics['final_position_error']:.3f} {r.metrics['final_velocity_error']:.3f}")
    0.945 0.006
    """

    alpha: ArrayLike = 1.0
    beta: ArrayLike = (0.05, 0.3)
    gamma: ArrayLike = (1.07, 1.1)
    k: ArrayLike = 0.001

    kind: ClassVar[str] = "ntsmc"


@dataclass(frozen=True, eq=False)
class FixedTimeNTSMC(Controller):
    """Fixed-time nonsingular terminal sliding mode with RBF compensation (the tethered-satellite
    paper, eq. 19-24).

    ``s = e2 + k1 zeta1(e1) + k2 zeta2(e1)`` with the piecewise zeta of eq. 21 (``sig^p`` outside
    ``sigma_phi``, the quadratic matching its value and slope inside: the singularity guard);
    ``u = -M (k1 zeta1' + k2 zeta2' + k3 (sig^alpha_s(s) + sig^beta_s(s))) - W^T Phi(z)
    - eps_max sign(s)``; ``W' = gamma Phi N``, ``N = M^-1 k3 (sig^(2 alpha_s - 1)(s) +
    sig^(2 beta_s - 1)(s))``. Each axis has its own Gaussian network on its normalised errors
    ``z = (e1 / rbf_scale_e1, e2 / rbf_scale_e2)``, ``rbf_nodes``^2 centres on a grid over
    [-1, 1]^2 with width ``rbf_width``; its weights start at zero and are the law's state.

    Defaults: the paper's Table 2 for the tethered satellite's (phi, theta), with alpha_s and
    beta_s in the roles the text gives them (Table 2 prints them swapped; the law is symmetric
    in the two) and the network of the tuning study (docs/parameters.md).

    The parameters are per axis unless said.

    Parameters
    ----------
    k1, k2 : ArrayLike
        Gains of zeta1 and zeta2 in the surface, q^(1 - p1)/s and q^(1 - p2)/s, > 0.
    k3 : ArrayLike
        Gain of the reaching law, 1/s, > 0.
    eps_max : ArrayLike
        Bound of the network's error, in actuator units (N, N m), >= 0.
    p1, p2 : ArrayLike
        Exponents of zeta1, zeta2: p1 > 1, 0 < p2 < 1.
    alpha_s, beta_s : ArrayLike
        Exponents of the reaching law, 1/2 < alpha_s < 1 < beta_s.
    sigma_phi : ArrayLike
        Threshold of the piecewise zeta, in units of q, > 0.
    gamma : ArrayLike
        Adaptation gain (Gamma = gamma I), dimensionless, >= 0; 0 switches the network off.
    rbf_nodes : int
        Centres per input (1 to 7), shared by the axes and the cases.
    rbf_scale_e1, rbf_scale_e2 : ArrayLike
        The errors at the edge of the centre grid, q and q/s, > 0.
    rbf_width : ArrayLike
        Gaussian width b on the normalised inputs, > 0.

    Examples
    --------
    >>> import landing
    >>> law = FixedTimeNTSMC(k1=1.0, k2=1.0, k3=1.0, eps_max=0.0, p1=1.1, p2=0.6, alpha_s=0.8,
    ...                    beta_s=1.2, sigma_phi=0.01, gamma=0.0, rbf_scale_e1=1.0, rbf_scale_e2=1.0,
    ...                    rbf_width=1.0)
    >>> r = landing.simulate(landing.plants.DoubleIntegrator(), law, [1.0, 0, 0, 0, 0, 0],
    ...                      t_final=10.0, dt=0.01)
    >>> print(f"{r.metrics['final_position_error']:.3f} {r.metrics['final_velocity_error']:.3f}")
    0.000 0.000
    """

    k1: ArrayLike = (0.08, 0.6)
    k2: ArrayLike = (0.08, 0.5)
    k3: ArrayLike = (0.09, 0.8)
    eps_max: ArrayLike = 1e-4
    p1: ArrayLike = 1.1
    p2: ArrayLike = (0.99, 0.6)
    alpha_s: ArrayLike = (0.89, 0.7)
    beta_s: ArrayLike = (1.1, 1.8)
    sigma_phi: ArrayLike = (0.01, 0.001)
    gamma: ArrayLike = (3700.0, 0.48)
    rbf_nodes: int = 5
    rbf_scale_e1: ArrayLike = (math.radians(0.12), math.radians(2.0))
    rbf_scale_e2: ArrayLike = (0.0045, 0.00036)
    rbf_width: ArrayLike = (5.9, 1.4)

    kind: ClassVar[str] = "fixed_time_ntsmc"


@dataclass(frozen=True, eq=False)
class Tabulated(Controller):
    """A tabulated open-loop force, held: the replay of an offline thrust profile
    (:func:`landing.optimal.fuel_optimal`; the Mars fixed-time guidance paper's Fig. 3 flies its
    optimum this way).

    Row ``j`` of ``force`` is a generalized force per axis (N on the Mars lander), held for
    ``hold`` control periods: at control instant ``k`` (t = k dt) the law commands
    ``force[k // hold] / M(x)``, M the plant's inertia (the lander's current mass), and the
    actuator multiplies by the same M, so the applied force is the row (then clipped to the
    actuator's limit). After the table the law holds the last row (``after="hold"``) or
    commands zero (``after="zero"``, engine off).

    Parameters
    ----------
    force : ArrayLike
        The table of generalized forces (N on the Mars lander), shape (rows, axes), or
        (cases, rows, axes) for a table per case (every case the same number of rows).
    hold : int
        Control periods per row, a whole number >= 1 (the row period over the control period
        of the run).
    after : {"hold", "zero"}
        Past the table: hold the last row, or command zero (default).

    Raises
    ------
    ParameterError
        If ``force`` is not of shape (rows, axes) or (cases, rows, axes) with a row.
    ParameterTypeError
        If ``hold`` is not a whole number.

    Examples
    --------
    On a unit inertia, 0.1 for 1 s then -0.1 for 1 s moves the point by 0.1 and stops it:

    >>> import landing
    >>> law = Tabulated(force=[[0.1, 0.0, 0.0], [-0.1, 0.0, 0.0]], hold=100)
    >>> r = landing.simulate(landing.plants.DoubleIntegrator(), law, [1.0, 0, 0, 0, 0, 0],
    ...                      t_final=10.0, dt=0.01)
    >>> print(f"{r.metrics['final_position_error']:.3f} {r.metrics['final_velocity_error']:.3f}")
    1.100 0.000
    """

    force: ArrayLike
    hold: int = 1
    after: Literal["hold", "zero"] = "zero"

    kind: ClassVar[str] = "tabulated"

    def _table(self) -> dict[str, Any]:
        force = as_float_array("Tabulated", "force", self.force)
        if force.ndim not in (2, 3) or force.shape[-2] == 0:
            raise ParameterError(
                f"Tabulated: force has shape {force.shape}; it takes (rows, axes) or (cases, rows, axes) "
                "with at least one row"
            )
        if isinstance(self.hold, bool) or not isinstance(self.hold, (int, float)):
            raise ParameterTypeError(f"Tabulated: hold must be a whole number, got {self.hold!r}")
        rows = [{"force": np.ascontiguousarray(force[j] if force.ndim == 2 else force[:, j, :])}
                for j in range(force.shape[-2])]
        return {"kind": self.kind, "rows": rows, "hold": np.asarray(float(self.hold)), "after": self.after}

    def case_rows(self, n: int, axes: int) -> dict[str, int]:
        force = np.asarray(self.force)
        return {"force": force.shape[0]} if force.ndim == 3 else {}

    def take_cases(self, start: int, stop: int, n: int, axes: int) -> Tabulated:
        force = np.asarray(self.force)
        return self.replace(force=force[start:stop]) if force.ndim == 3 else self


def _diagnostic_kinds(diagnostics: Union[Sequence[str], Mapping[str, str]]) -> dict[str, str]:
    """Diagnostic names and kinds, from a mapping or a sequence of per-axis names."""
    return dict(diagnostics) if isinstance(diagnostics, Mapping) else {d: "axes" for d in diagnostics}


Memory = Union[Mapping[str, ArrayLike], Callable[..., Mapping[str, Any]], None]

#: A Python law's cases per call by default (``PythonLaw.cases_per_call``): measured in
#: BENCHMARKS.md ("A law written in Python"; 4096 ran the fixed-time MSS law in numpy 14 % faster
#: than 1024 on one thread and 23 % on two, on 10^4 Mars cases, 2026-12-06).
DEFAULT_CASES_PER_CALL = 4096


@dataclass(frozen=True, eq=False)
class PythonLaw(Controller):
    """A control law written in Python: ``function`` is called once per control period for a
    block of cases at once, exactly where a built-in law is (the command is then actuated by the
    plant and held over the period), and the core advances the plant between calls.

    ``function(t, e, de, ref, drift, inertia, params, memory)`` receives the control instant t
    (s), the tracking errors ``e = q - q_ref`` and ``de = q' - q_ref'``, the reference ``ref``
    (``ref.position``, ``ref.velocity``, ``ref.acceleration``), the plant's modelled
    acceleration ``drift`` and its diagonal ``inertia`` (each an (n, D) numpy array, read-only),
    the parameters (a dict of (n, D) arrays) and the memory (a dict of arrays with one row per
    case, or None). It returns the commanded generalized acceleration, an (n, D) float array
    (``q'' = drift + command + disturbance``), or ``(command, new_memory)``, or ``(command,
    new_memory, diagnostics)``. Any callable on arrays serves: numpy, a numba-jitted or a
    JAX-jitted function.

    Parameters
    ----------
    function : Callable
        The law, ``function(t, e, de, ref, drift, inertia, params, memory)`` as above.
    params : Mapping[str, ArrayLike]
        Its parameters, by name: each a scalar, a per-axis ``(D,)`` value, or per case
        ``(N,)``, ``(N, 1)``, ``(N, D)`` (N the batch's or campaign's cases; a 1-d value of length D is per
        axis, so give ``(N, 1)`` for a value per case when N equals D). The function sees each
        as a read-only (n, D) array: a scalar as a broadcast view of one copy (zero strides),
        any other value as a C-contiguous array. ``law.replace(kp=2.0)`` changes one;
        ``landing.tune`` tunes them.
    memory : Mapping, Callable or None
        The law's internal state at t = 0: a dict of initial values shared by every case
        (each broadcast to one row per case), or a function ``memory(t, e, de, ref, drift,
        inertia, params)`` returning the dict from the first inputs, or None for a law
        without one. The function returns the new memory, advanced over the period.
    diagnostics : Sequence[str] or Mapping[str, str]
        Names of signals the function returns in its diagnostics dict, recorded with
        the states: a sequence of names of per-axis signals ((n, D) each), or a mapping of
        name to ``"axes"`` or ``"scalar"`` ((n,) each).
    name : str or None
        How the law is named in messages and a campaign's provenance (default: the
        function's ``module:qualname``).
    cases_per_call : int or None
        At most this many cases per call (default 4096; None: the whole batch in
        every call). A larger batch is run a slice of cases at a time, each slice through all
        its control instants, so that the slice's arrays and the core's state of its cases
        stay in the processor's caches between calls; with the whole batch at every call they
        stream through memory, and numpy's temporaries of a few hundred kilobytes each are
        mapped and unmapped at every operation (BENCHMARKS.md, "A law written in Python"). The
        slices hold whole blocks of the kernel's lanes (4 to 16 cases, by instruction set). The
        results do not depend on it for a function that treats each case on its own, as a law
        does; each slice's memory is its own. On one thread the slices run one after another;
        on more, two at once, the function called on one while the other threads advance the
        other's plant, their calls alternating (a batch that fits in one call is cut in two from
        1024 cases on). On a plant written in Python the law sees every case at each call.

    Examples
    --------
    >>> import landing
    >>> def pd(t, e, de, ref, drift, inertia, params, memory):
    ...     return -drift - params["kp"] * e - params["kd"] * de
    >>> law = landing.controllers.PythonLaw(pd, params={"kp": 1.0, "kd": 2.0})
    >>> r = landing.simulate(landing.plants.DoubleIntegrator(), law, [1.0, 0, 0, 0, 0, 0],
    ...                      t_final=10.0, dt=0.01)
    >>> print(f"{r.metrics['final_position_error']:.3f}, settled at {r.metrics['settle_time']:.2f} s")
    0.001, settled at 5.84 s
    """

    function: Callable[..., Any]
    params: Mapping[str, ArrayLike] = field(default_factory=dict)
    memory: Memory = None
    diagnostics: Union[Sequence[str], Mapping[str, str]] = ()
    name: Optional[str] = None
    cases_per_call: Optional[int] = DEFAULT_CASES_PER_CALL

    kind: ClassVar[str] = "python"
    _in_core: ClassVar[bool] = False

    def __post_init__(self) -> None:
        owner = "PythonLaw"
        if not callable(self.function):
            raise ParameterTypeError(f"{owner}: function must be callable, got {type(self.function).__name__}")
        object.__setattr__(self, "params", frozen_params(owner, self.params, "a scalar, (D,), (N,), (N, 1) or (N, D)"))
        memory = self.memory
        if memory is not None and not callable(memory):
            if not isinstance(memory, Mapping):
                raise ParameterTypeError(f"{owner}: memory must be a dict of initial values, a function or None, "
                                         f"got {type(memory).__name__}")
            object.__setattr__(self, "memory", MappingProxyType(
                {k: as_float_array(owner, f"memory[{k!r}]", v) for k, v in memory.items()}))
        diagnostics = self.diagnostics
        if isinstance(diagnostics, str):
            raise ParameterTypeError(f"{owner}: diagnostics must be a sequence of names or a mapping, "
                                     f"got the string {diagnostics!r}")
        kinds = _diagnostic_kinds(diagnostics)
        for key, kind in kinds.items():
            if not isinstance(key, str) or kind not in ("axes", "scalar"):
                raise ParameterError(f"{owner}: diagnostics[{key!r}] = {kind!r}; each is 'axes' or 'scalar'")
        object.__setattr__(self, "diagnostics", MappingProxyType(kinds))
        if self.name is None:
            object.__setattr__(self, "name", qualified_name(self.function))
        if self.cases_per_call is not None:
            object.__setattr__(self, "cases_per_call", integer("cases_per_call", self.cases_per_call, minimum=1,
                                                               maximum=2**63 - 1, owner=owner))
        self._compile()

    def _compile(self) -> None:
        """Nothing for the core to compile: the function runs in Python."""
        object.__setattr__(self, "_core", None)

    @property
    def parameters(self) -> Mapping[str, Parameter]:  # type: ignore[override]
        """The law's parameters, each per axis (a scalar, (D,), or per case)."""
        return MappingProxyType({
            k: Parameter(name=k, shape="per_axis", unit="", rule="", required=True, doc="a parameter of the law")
            for k in self.params
        })

    @property
    def diagnostic_kinds(self) -> Mapping[str, str]:
        """The diagnostic signals' names and kinds (``"axes"`` or ``"scalar"``)."""
        return MappingProxyType(_diagnostic_kinds(self.diagnostics))

    def diagnostic_layout(self, axes: int) -> list[tuple[str, int]]:
        """Names and widths of the diagnostic signals on a plant of ``axes`` axes."""
        return [(k, axes if kind == "axes" else 1) for k, kind in _diagnostic_kinds(self.diagnostics).items()]

    @property
    def source_hash(self) -> str:
        """SHA-256 of the function's source: what a campaign's provenance records, so that a
        store is not resumed with a changed function."""
        return source_hash(self.function)

    def replace(self, **changes: Any) -> PythonLaw:
        """A copy with some fields or parameters changed: ``law.replace(kp=2.0)`` changes
        ``params["kp"]``; ``law.replace(params={...})`` replaces them all."""
        return replace_with_params(self, "PythonLaw", changes)

    def case_rows(self, n: int, axes: int) -> dict[str, int]:
        return {k: r for k, v in self.params.items() if (r := case_rows("per_axis", np.shape(v), axes)) is not None}

    def take_cases(self, start: int, stop: int, n: int, axes: int) -> PythonLaw:
        return params_taking_cases(self, lambda v: case_rows("per_axis", np.shape(v), axes), start, stop)
