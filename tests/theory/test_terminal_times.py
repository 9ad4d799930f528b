"""Seed 000's reaching times on the terminal (eq. 5) and fast terminal (eq. 6, 7) surfaces:
the closed forms against an independent integration of the surface's dynamics, the printed
forms against the seed's formulas, and the law on its surface against eq. 7."""

import numpy as np
import pytest
from scipy.integrate import quad

from _cases import RECONSTRUCTED_GAINS
from landing import theory
from landing.controllers import FastTerminalSMC, FixedTimeMSS
from landing.errors import ParameterError, ParameterTypeError
from landing.scenarios import SEED000_GAINS, seed000_tracking


def time_down_to(eps: float, e0: float, alpha: float, beta: float, r: float) -> float:
    """The time e' = -alpha e - beta e^r takes from e0 > 0 down to eps: the integral of
    de / |e'| by adaptive quadrature (in u = ln e, where the integrand is smooth)."""
    t, err = quad(lambda u: np.exp(u) / (alpha * np.exp(u) + beta * np.exp(r * u)), np.log(eps), np.log(e0),
                  epsabs=0.0, epsrel=1e-13, limit=200)
    assert err < 1e-12 * t
    return float(t)


@pytest.mark.parametrize("e0, alpha, beta, p, q", [
    (10.0, 1.0, 0.4, 1.0, 5.0),    # the seed-000 preset's gains and offset
    (1e-2, 1.0, 0.4, 1.0, 5.0),
    (300.0, 0.05, 2.0, 3.0, 5.0),
    (2.0, 4.0, 0.1, 7.0, 9.0),
])
def test_the_closed_forms_against_the_integrated_surface(e0, alpha, beta, p, q):
    # the time from e0 down to eps is t(e0) - t(eps) if t is the time to reach 0; t(eps) itself
    # tends to 0 with eps (the reaching is finite)
    r, eps = p / q, 1e-6 * e0
    t7 = lambda e: theory.fast_terminal_reaching_time(e, alpha, beta, p, q)  # noqa: E731
    t5 = lambda e: theory.terminal_reaching_time(e, beta, p, q)  # noqa: E731
    assert t7(e0) - t7(eps) == pytest.approx(time_down_to(eps, e0, alpha, beta, r), rel=1e-12)
    assert t5(e0) - t5(eps) == pytest.approx(time_down_to(eps, e0, 0.0, beta, r), rel=1e-12)
    assert t7(1e-300) < 1e-20 and t5(1e-300) < 1e-20
    # the sign of e0 does not matter (sig keeps the dynamics odd)
    assert theory.fast_terminal_reaching_time(-e0, alpha, beta, p, q) == theory.fast_terminal_reaching_time(
        e0, alpha, beta, p, q)


def test_eq7_tends_to_eq5_and_is_faster():
    e0, beta, p, q = 10.0, 0.4, 1.0, 5.0
    t5 = theory.terminal_reaching_time(e0, beta, p, q)
    assert theory.fast_terminal_reaching_time(e0, 1e-9, beta, p, q) == pytest.approx(t5, rel=1e-7)
    t7 = theory.fast_terminal_reaching_time(e0, np.array([0.1, 1.0, 10.0]), beta, p, q)
    assert np.all(np.diff(t7) < 0) and np.all(t7 < t5)


def test_the_printed_forms_are_the_seeds_formulas_with_p_and_q_swapped():
    e0, alpha, beta, p, q = 10.0, 1.0, 0.4, 1.0, 5.0
    # eq. 5 and 7 as the seed prints them, written out here
    eq5 = p / (beta * (p - q)) * e0 ** ((p - q) / p)
    eq7 = p / (alpha * (p - q)) * (np.log(alpha * e0 ** ((p - q) / p) + beta) - np.log(beta))
    assert theory.terminal_reaching_time_printed(e0, beta, p, q) == pytest.approx(eq5, rel=1e-14)
    assert theory.fast_terminal_reaching_time_printed(e0, alpha, beta, p, q) == pytest.approx(eq7, rel=1e-14)
    # for the seed's own p < q both are negative: not a time
    assert eq5 < 0 and eq7 < 0
    # the derived forms are the standard ones: swapping p and q back in the printed formula
    # gives q / (beta (q - p)) |e0|^((q - p)/q)
    assert theory.terminal_reaching_time(e0, beta, p, q) == pytest.approx(
        q / (beta * (q - p)) * e0 ** ((q - p) / q), rel=1e-14)


@pytest.mark.parametrize("alpha", [1.0, 1e-6])
def test_the_fast_terminal_law_on_its_surface_follows_eq7(alpha):
    """The seed-000 FTSMC, started on its surface on a double integrator, brings each axis's
    error to the tolerance when eq. 7 says (within three control periods), before eq. 7's time
    to 0; with alpha near 0 the same law checks eq. 5."""
    g = SEED000_GAINS
    law = seed000_tracking("ftsmc", "sat").controller.replace(alpha=alpha)
    e0 = np.array([[10.0, -3.0, 0.5], [-40.0, 1.0, 2.0]])
    check = theory.check_terminal_reaching_time(law, e0)
    assert check.ok, check
    dt = float(check.extra["dt"])
    assert np.abs(check.extra["difference"]).max() <= 3 * dt, check.extra["difference"]
    if alpha < 1e-3:
        np.testing.assert_allclose(check.bound, theory.terminal_reaching_time(e0, g["beta"], g["p"], g["q"]),
                                   rtol=1e-4)


def test_a_wrong_time_is_seen():
    """The check can fail: against a law whose surface is slower than the one the bound is
    computed for (beta halved on one axis), the measured time exceeds eq. 7's."""
    law = FastTerminalSMC(alpha=1.0, beta=0.4, p=1.0, q=5.0, k=2.5, switch="sat", boundary_layer=0.3)
    check = theory.check_terminal_reaching_time(law, [10.0])
    assert check.ok
    slow = law.replace(beta=[0.2, 0.4, 0.4])
    # the start is on the slow surface, the bound the fast one's: compare by hand
    fast_bound = theory.fast_terminal_reaching_time(10.0, 1.0, 0.4, 1.0, 5.0)
    measured = theory.check_terminal_reaching_time(slow, [10.0]).measured[0]
    assert measured[0] > fast_bound and measured[1] <= fast_bound


def test_bad_input_is_refused_naming_the_argument():
    with pytest.raises(ParameterError, match="q > p"):
        theory.terminal_reaching_time(1.0, 0.4, 5.0, 1.0)
    with pytest.raises(ParameterError, match="alpha"):
        theory.fast_terminal_reaching_time(1.0, -1.0, 0.4, 1.0, 5.0)
    # alpha = 0 is eq. 5 exactly
    t5 = theory.terminal_reaching_time(1.0, 0.4, 1.0, 5.0)
    assert theory.fast_terminal_reaching_time(1.0, 0.0, 0.4, 1.0, 5.0) == t5
    with pytest.raises(ParameterError, match="e0"):
        theory.terminal_reaching_time(np.inf, 0.4, 1.0, 5.0)
    law = FastTerminalSMC(alpha=1.0, beta=0.4, p=1.0, q=5.0, k=2.5)
    with pytest.raises(ParameterError, match="e0 has a zero"):
        theory.check_terminal_reaching_time(law, [0.0, 1.0])
    with pytest.raises(ParameterTypeError, match="FastTerminalSMC"):
        theory.check_terminal_reaching_time(FixedTimeMSS(**RECONSTRUCTED_GAINS), [1.0])
