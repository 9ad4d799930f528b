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
    ``beta.ppf(1 - confidence, successes, n - successes + 1)``, found by bisection."""
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
    """The fewest cases that can show "met for at least ``p`` with ``confidence``" when
    ``failures`` of them fail: 852 for p = 0.9973, 90 % and no failure (the closed form
    ceil(ln(1 - confidence) / ln p) for none)."""
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
    """The one-sided distribution-free tolerance bound (Wilks): a value that at least ``p`` of
    the population lies below (``side="upper"``) or above (``"lower"``) with ``confidence``, the
    order statistic of the finite ``values`` the binomial gives. NaN values (diverged cases)
    count against the bound: an upper bound is then that of the cases that did not diverge,
    which with those cases unbounded is refused. Too few cases for the pair (p, confidence) is
    refused, saying how many are needed."""
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
    ``failed`` lists the failing cases; ``needed`` is how many cases with no failure would show
    it."""

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
        return self.passed / self.n

    @property
    def met(self) -> bool:
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
    """The requirement ``text`` checked on the metric columns ``metrics`` (see
    :class:`Verification`)."""
    p = _probability("p", p)
    confidence = _probability("confidence", confidence)
    passes = requirement(text, metrics).holds(metrics)
    n = passes.size
    k = int(passes.sum())
    return Verification(requirement=text, p=p, confidence=confidence, n=n, passed=k,
                        lower_bound=clopper_pearson_lower(k, n, confidence), needed=samples_needed(p, confidence),
                        failed=np.flatnonzero(~passes))
