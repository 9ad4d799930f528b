"""Verifying a requirement from a campaign's cases, with a stated confidence (Hanson and Beard,
"Applying Monte Carlo simulation to launch vehicle design and requirements verification",
J. Spacecraft and Rockets 49(1), 2012).

Each case passes or fails the requirement; the cases are independent draws, so the number of
passes is binomial in the unknown probability of success P. "The requirement is met for at least
p of cases with confidence c" is shown when the Clopper-Pearson lower bound on P at level c is at
least p: when, were P only p, seeing as many passes as were seen would have probability at most
1 - c. A metric's one-sided tolerance bound (Wilks) is the order statistic that at least p of
the population lies below (or above) with confidence c.

The binomial tails are summed term by term (in logarithms, from :func:`math.lgamma`), and the
lower bound is found by bisection on them: no SciPy needed (the tests compare with scipy.stats).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Optional

import numpy as np

from landing._internal.args import integer, real
from landing._internal.expression import Expression
from landing.errors import ParameterError

__all__ = ["Verification", "clopper_pearson_lower", "samples_needed", "tolerance_bound", "verify"]


def _probability(name: str, value: Any) -> float:
    v = real(name, value)
    if not 0 < v < 1:
        raise ParameterError(f"{name} = {v!r} violates 0 < {name} < 1")
    return v


def _tail_at_least(k: int, n: int, p: float) -> float:
    """P(X >= k) for X ~ Binomial(n, p), summed exactly term by term (in logarithms)."""
    if k <= 0:
        return 1.0
    if k > n:
        return 0.0
    if p <= 0.0:
        return 0.0
    if p >= 1.0:
        return 1.0
    # log C(n, i) for i = k .. n by the recurrence C(n, i + 1) = C(n, i) (n - i) / (i + 1)
    i = np.arange(k, n + 1, dtype=float)
    log_c = math.lgamma(n + 1) - math.lgamma(k + 1) - math.lgamma(n - k + 1) + np.concatenate(
        ([0.0], np.cumsum(np.log((n - i[:-1]) / (i[:-1] + 1)))))
    terms = log_c + i * math.log(p) + (n - i) * math.log1p(-p)
    top = float(terms.max())
    return min(1.0, math.exp(top) * math.fsum(np.exp(terms - top)))


def clopper_pearson_lower(successes: int, n: int, confidence: float) -> float:
    """The one-sided Clopper-Pearson lower bound on the success probability at ``confidence``,
    after ``successes`` of ``n``: the P at which seeing at least that many successes has
    probability 1 - confidence (0 for no success). The beta quantile
    ``beta.ppf(1 - confidence, successes, n - successes + 1)``, found by bisection.

    Parameters
    ----------
    successes : int
        The cases that passed, 0 to n.
    n : int
        The cases, >= 1.
    confidence : float
        The confidence, 0 < confidence < 1.

    Returns
    -------
    float
        The lower bound on the probability of passing (dimensionless, 0 to 1).

    Examples
    --------
    >>> from landing.campaign.verify import clopper_pearson_lower
    >>> print(f"{clopper_pearson_lower(95, 100, 0.9):.4f}")
    0.9092
    >>> print(f"{clopper_pearson_lower(10, 10, 0.9):.4f}")  # 0.1 ** (1 / 10)
    0.7943
    """
    n = integer("n", n, minimum=1)
    successes = integer("successes", successes, minimum=0, maximum=n)
    alpha = 1.0 - _probability("confidence", confidence)
    if successes == 0:
        return 0.0
    if successes == n:
        return alpha ** (1.0 / n)  # the closed form: P^n = alpha
    lo, hi = 0.0, 1.0
    for _ in range(200):  # the tail rises with P: bisect to the last bit
        mid = 0.5 * (lo + hi)
        if mid in (lo, hi):
            break
        if _tail_at_least(successes, n, mid) < alpha:
            lo = mid
        else:
            hi = mid
    return lo


def samples_needed(p: float, confidence: float, failures: int = 0) -> int:
    """The fewest cases that can show "met for at least ``p`` with ``confidence``" when ``failures``
    of them fail: 852 for p = 0.9973, 90 % and no failure (the closed form
    ceil(ln(1 - confidence) / ln p) for none).

    Parameters
    ----------
    p : float
        The share of cases the requirement must hold for, 0 < p < 1.
    confidence : float
        The confidence, 0 < confidence < 1.
    failures : int, default 0
        The failing cases allowed.

    Returns
    -------
    int
        The number of cases.

    Examples
    --------
    >>> from landing.campaign import samples_needed
    >>> samples_needed(0.9973, 0.9), samples_needed(0.99, 0.9, failures=1)
    (852, 388)
    """
    p = _probability("p", p)
    c = _probability("confidence", confidence)
    failures = integer("failures", failures, minimum=0)
    alpha = 1.0 - c
    n = max(failures + 1, math.ceil(math.log(alpha) / math.log(p)))
    while _tail_at_least(n - failures, n, p) > alpha:
        n += 1
    return n


def _order_index(n: int, p: float, confidence: float) -> Optional[int]:
    """The smallest j (1-based) whose order statistic X_(j) of n bounds at least p of the
    population from above with ``confidence`` (P(Binomial(n, p) >= j) <= 1 - confidence), or
    None when even the largest does not."""
    alpha = 1.0 - confidence
    if _tail_at_least(n, n, p) > alpha:
        return None
    lo, hi = 1, n  # the tail falls as j grows: the first j below alpha
    while lo < hi:
        mid = (lo + hi) // 2
        if _tail_at_least(mid, n, p) <= alpha:
            hi = mid
        else:
            lo = mid + 1
    return lo


def tolerance_bound(values: Any, p: float, confidence: float, side: str = "upper") -> float:
    """The one-sided distribution-free tolerance bound (Wilks): a value that at least ``p`` of the
    population lies below (``side="upper"``) or above (``"lower"``) with ``confidence``, the order
    statistic of the finite ``values`` the binomial gives. A NaN value (a diverged case) is
    refused, as are too few cases for the pair (p, confidence), saying how many are needed.

    Parameters
    ----------
    values : array_like
        One value per case, in the metric's unit (m, m/s, s, kg...).
    p : float
        The share of the population bounded, 0 < p < 1.
    confidence : float
        The confidence, 0 < confidence < 1.
    side : {"upper", "lower"}, default "upper"
        Which bound.

    Returns
    -------
    float
        The bound, in the values' unit.

    Examples
    --------
    >>> import numpy as np
    >>> from landing.campaign.verify import tolerance_bound
    >>> speeds = np.arange(1.0, 101.0) / 100  # m/s
    >>> print(f"{tolerance_bound(speeds, p=0.9, confidence=0.9):.2f} m/s")
    0.95 m/s
    """
    x = np.asarray(values, dtype=float).reshape(-1)
    p = _probability("p", p)
    c = _probability("confidence", confidence)
    if side not in ("upper", "lower"):
        raise ParameterError(f"side = {side!r} is not one of ('upper', 'lower')")
    n = x.size
    if not np.all(np.isfinite(x)):
        raise ParameterError(f"{int(np.sum(~np.isfinite(x)))} of the {n} values are not finite (diverged cases or "
                             "no event): a tolerance bound needs every case's value")
    j = _order_index(n, p, c) if n else None
    if j is None:
        raise ParameterError(f"{n} cases cannot bound {p:g} of the population with {c:g} confidence: at least "
                             f"{samples_needed(p, c)} are needed (the largest of them is then the bound)")
    ordered = np.sort(x)
    return float(ordered[j - 1] if side == "upper" else ordered[n - j])


@dataclass(frozen=True)
class Verification:
    """A requirement checked on a campaign: ``passed`` of ``n`` cases, the point estimate
    ``passed / n``, the Clopper-Pearson ``lower_bound`` on the probability of passing at
    ``confidence``, and whether that shows the requirement ``met`` for at least ``p`` of cases.
    Made by :func:`verify` (:meth:`MonteCarloResult.verify`).

    Parameters
    ----------
    requirement : str
        The requirement's text, in the metrics' units (m, m/s, s, kg).
    p : float
        The share of cases it must hold for.
    confidence : float
        The confidence of the statement.
    n : int
        The cases checked.
    passed : int
        The cases that pass.
    lower_bound : float
        The Clopper-Pearson lower bound on the probability of passing.
    needed : int
        How many cases with no failure would show it.
    failed : numpy.ndarray
        The failing cases' indices.

    Examples
    --------
    >>> import numpy as np
    >>> from landing.campaign.verify import verify
    >>> metrics = {"touchdown_speed": np.array([0.5, 0.8, 1.2, 0.3]), "diverged": np.zeros(4, bool)}
    >>> v = verify(metrics, "touchdown_speed <= 1", p=0.5, confidence=0.9)
    >>> v.passed, v.failed, v.met
    (3, array([2]), False)
    """

    requirement: str
    p: float
    confidence: float
    n: int
    passed: int
    lower_bound: float
    needed: int
    failed: np.ndarray = field(repr=False)

    @property
    def estimate(self) -> float:
        """The share of cases that pass, ``passed / n`` (dimensionless)."""
        return self.passed / self.n

    @property
    def met(self) -> bool:
        """Whether the campaign shows the requirement met: ``lower_bound >= p``."""
        return self.lower_bound >= self.p

    def __str__(self) -> str:
        head = (f"requirement {self.requirement!r}: {self.passed} of {self.n} cases pass "
                f"({100 * self.estimate:.4g} %); at {100 * self.confidence:.4g} % confidence at least "
                f"{100 * self.lower_bound:.4g} % of cases meet it (Clopper-Pearson)")
        if self.met:
            return (f"{head}\n  shown: the requirement is met for at least {100 * self.p:.4g} % of cases with "
                    f"{100 * self.confidence:.4g} % confidence")
        more = (f"{self.needed} cases without a failure would show it" if self.passed == self.n
                else f"the failing cases: {', '.join(map(str, self.failed[:10]))}"
                     f"{' ...' if self.failed.size > 10 else ''}")
        return (f"{head}\n  not shown: at least {100 * self.p:.4g} % with {100 * self.confidence:.4g} % "
                f"confidence ({more})")


def requirement(text: str, metric_names: Any) -> Expression:
    """A requirement parsed (the grammar of ``landing._internal.expression``)."""
    return Expression(text, list(metric_names), kind="requirement")


def verify(metrics: Any, text: str, p: float = 0.9973, confidence: float = 0.9) -> Verification:
    """The requirement ``text`` checked case by case on the metric columns ``metrics``, and whether
    it is shown met for at least ``p`` of cases with ``confidence`` (see :class:`Verification`).
    A case with a NaN metric (diverged, never touched down) fails.

    Parameters
    ----------
    metrics : landing.Metrics or mapping of str to numpy.ndarray
        The per-case metric columns (with ``"diverged"``), in their units (m, m/s, s, kg).
    text : str
        The requirement, in the grammar of the tuner's expressions
        (e.g. ``"touchdown_speed <= 1 and max(abs(touchdown_position)) <= 5"``, m/s and m).
    p : float, default 0.9973
        The share of cases it must hold for, 0 < p < 1.
    confidence : float, default 0.9
        The confidence, 0 < confidence < 1.

    Returns
    -------
    Verification
        The cases' passes and the statistical statement.

    Examples
    --------
    >>> import numpy as np
    >>> from landing.campaign.verify import verify
    >>> metrics = {"touchdown_speed": np.array([0.5, 0.8, 1.2, 0.3]), "diverged": np.zeros(4, bool)}
    >>> print(verify(metrics, "touchdown_speed <= 1", p=0.5, confidence=0.9))
    requirement 'touchdown_speed <= 1': 3 of 4 cases pass (75 %);
        at 90 % confidence at least 32.05 % of cases meet it (Clopper-Pearson)
      not shown: at least 50 % with 90 % confidence (the failing cases: 2)
    """
    p = _probability("p", p)
    confidence = _probability("confidence", confidence)
    passes = requirement(text, metrics).holds(metrics)
    n = passes.size
    k = int(passes.sum())
    return Verification(requirement=text, p=p, confidence=confidence, n=n, passed=k,
                        lower_bound=clopper_pearson_lower(k, n, confidence), needed=samples_needed(p, confidence),
                        failed=np.flatnonzero(~passes))
