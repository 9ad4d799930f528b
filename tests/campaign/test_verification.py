"""Verifying requirements with a confidence: the Clopper-Pearson bound and the sample sizes
against scipy.stats' beta and binomial distributions, Wilks' tolerance bound against the
binomial and against its coverage in repeated sampling, the requirement grammar against numpy
written by hand, and the campaign, report and command-line entry points."""

from __future__ import annotations

import numpy as np
import pytest

import landing
from _cases import small_campaign
from landing.campaign import samples_needed
from landing.campaign.verify import clopper_pearson_lower, tolerance_bound
from landing.errors import ParameterError

stats = pytest.importorskip("scipy.stats")


def test_852_cases_without_a_failure_show_99_73_percent_with_90_percent_confidence():
    # Hanson and Beard's example; the closed form ceil(ln(1 - c) / ln p) for no failure
    assert samples_needed(0.9973, 0.9) == 852
    for p in (0.9, 0.99, 0.999, 0.9973):
        for c in (0.5, 0.9, 0.95, 0.99):
            assert samples_needed(p, c) == int(np.ceil(np.log(1 - c) / np.log(p)))


@pytest.mark.parametrize("p, c, failures", [(0.9973, 0.9, 1), (0.9973, 0.9, 2), (0.99, 0.95, 3), (0.9, 0.5, 5)])
def test_samples_needed_with_failures_is_the_least_n_whose_beta_bound_reaches_p(p, c, failures):
    n = samples_needed(p, c, failures)
    bound = lambda m: stats.beta.ppf(1 - c, m - failures, failures + 1)  # noqa: E731
    assert bound(n) >= p > bound(n - 1)


@pytest.mark.parametrize("k, n", [(1, 1), (3, 10), (9, 10), (851, 852), (990, 1000), (4990, 5000), (5, 10_000)])
@pytest.mark.parametrize("c", [0.5, 0.9, 0.99])
def test_the_lower_bound_is_scipys_beta_quantile(k, n, c):
    expected = stats.beta.ppf(1 - c, k, n - k + 1) if k < n else (1 - c) ** (1 / n)
    assert clopper_pearson_lower(k, n, c) == pytest.approx(expected, rel=1e-11, abs=1e-14)
    assert clopper_pearson_lower(0, n, c) == 0.0


@pytest.mark.parametrize("n, p, c", [(852, 0.9973, 0.9), (100, 0.9, 0.9), (1000, 0.99, 0.95), (59, 0.95, 0.95)])
def test_the_tolerance_bound_is_the_order_statistic_the_binomial_gives(n, p, c):
    x = np.random.default_rng(n).normal(size=n)
    # the smallest j with P(Binomial(n, p) >= j) <= 1 - c, from scipy's survival function
    j = next(j for j in range(1, n + 1) if stats.binom.sf(j - 1, n, p) <= 1 - c)
    assert tolerance_bound(x, p, c) == np.sort(x)[j - 1]
    assert tolerance_bound(x, p, c, side="lower") == np.sort(x)[n - j]
    if (n, p, c) in ((852, 0.9973, 0.9), (59, 0.95, 0.95)):
        assert tolerance_bound(x, p, c) == x.max()  # Wilks' classic cases: the largest value


def test_the_tolerance_bound_covers_p_of_the_population_in_at_least_c_of_campaigns():
    # repeated sampling from U(0, 1), whose p-quantile is p: the bound lies above it in at least
    # c of the trials (the order statistic's coverage is exactly binomial, so about c)
    rng = np.random.default_rng(0)
    p, c, n, trials = 0.9, 0.9, 100, 4000
    covered = np.mean([tolerance_bound(rng.uniform(size=n), p, c) >= p for _ in range(trials)])
    exact = 1 - stats.binom.sf(tolerance_index(n, p, c) - 1, n, p)
    assert covered >= c - 3 * np.sqrt(c * (1 - c) / trials)
    assert abs(covered - exact) < 4 * np.sqrt(exact * (1 - exact) / trials)


def tolerance_index(n: int, p: float, c: float) -> int:
    return next(j for j in range(1, n + 1) if stats.binom.sf(j - 1, n, p) <= 1 - c)


def test_too_few_cases_for_a_tolerance_bound_is_refused_naming_the_need():
    with pytest.raises(ParameterError, match="at least 852 are needed"):
        tolerance_bound(np.arange(851.0), 0.9973, 0.9)
    with pytest.raises(ParameterError, match="not finite"):
        tolerance_bound([1.0, np.nan] * 500, 0.9, 0.9)


def metrics(n: int = 40) -> dict[str, np.ndarray]:
    rng = np.random.default_rng(1)
    speed = rng.uniform(0, 2, n)
    speed[3] = np.nan  # a case that never touched down
    return {"diverged": np.zeros(n, bool), "touchdown_speed": speed,
            "touchdown_position": rng.normal(0, 4, (n, 3)), "fuel_used": rng.uniform(200, 300, n)}


def test_a_requirement_is_each_cases_pass_or_fail():
    from landing._internal.expression import Expression

    m = metrics()
    names = list(m)
    req = lambda text: Expression(text, names, kind="requirement").holds(m)  # noqa: E731
    speed, pos, fuel = m["touchdown_speed"], m["touchdown_position"], m["fuel_used"]
    with np.errstate(invalid="ignore"):
        np.testing.assert_array_equal(req("touchdown_speed <= 1"), speed <= 1)
        np.testing.assert_array_equal(req("touchdown_speed <= 1 and max(abs(touchdown_position)) <= 5"),
                                      (speed <= 1) & (np.abs(pos).max(axis=1) <= 5))
        np.testing.assert_array_equal(req("not touchdown_speed > 1 or fuel_used < 250"),
                                      ~(speed > 1) | (fuel < 250))
        np.testing.assert_array_equal(req("sqrt(sum(touchdown_position ** 2)) <= 6"),
                                      np.sqrt((pos**2).sum(axis=1)) <= 6)
    assert not req("touchdown_speed <= 100")[3]  # NaN fails
    for bad, rule in [("touchdown_speed", "comparisons"), ("mean(touchdown_speed)", "comparisons"),
                      ("touchdown_sped <= 1", "unknown name"), ("touchdown_speed == 1", "comparison")]:
        with pytest.raises(ParameterError, match=rule):
            Expression(bad, names, kind="requirement")


def test_a_campaign_verifies_reports_and_bounds():
    mc = landing.monte_carlo(small_campaign(), 60, seed=2, progress=False, check_bounds=False)
    ok = mc.verify("fuel_used <= 1e9", p=0.95, confidence=0.9)
    assert (ok.passed, ok.n) == (60, 60) and ok.met == (0.1 ** (1 / 60) >= 0.95)
    assert ok.lower_bound == pytest.approx(0.1 ** (1 / 60))
    fuel = mc.metrics["fuel_used"]
    v = mc.verify(f"fuel_used < {np.median(fuel)}", p=0.9, confidence=0.9)
    assert v.passed == int(np.sum(fuel < np.median(fuel))) and not v.met
    np.testing.assert_array_equal(v.failed, np.flatnonzero(~(fuel < np.median(fuel))))
    assert "not shown" in str(v) and "shown: the requirement is met" in str(mc.verify("fuel_used > 0", 0.9, 0.9))
    report = mc.report(requirement="fuel_used > 0", p=0.9, confidence=0.9)
    assert "requirement 'fuel_used > 0': 60 of 60 cases pass" in report
    assert mc.tolerance_bound("fuel_used", 0.9, 0.9) == np.sort(fuel)[tolerance_index(60, 0.9, 0.9) - 1]
    with pytest.raises(ParameterError, match="per axis"):
        mc.tolerance_bound("final_error")


@pytest.mark.io
def test_landing_verify_reads_a_store_and_exits_1_when_not_shown(tmp_path, capsys):
    pytest.importorskip("pyarrow")
    from landing.cli import main

    path = str(tmp_path / "c")
    landing.monte_carlo(small_campaign(), 30, seed=2, store=path, progress=False, check_bounds=False)
    assert main(["verify", path, "fuel_used > 0", "--p", "0.9", "--confidence", "0.9"]) == 0
    assert "shown: the requirement is met for at least 90 %" in capsys.readouterr().out
    assert main(["verify", path, "fuel_used > 0"]) == 1  # 30 cases cannot show 99.73 %
    assert "852 cases without a failure would show it" in capsys.readouterr().out
    assert main(["verify", path, "fuel_usd > 0"]) == 2
    assert "unknown name 'fuel_usd'" in capsys.readouterr().err
