"""landing.tune (the package landing.tuning): a known optimum found, constraints honoured, determinism, the grammar."""

from __future__ import annotations

import math

import numpy as np
import pytest

import landing
from landing.errors import ParameterError

pytest.importorskip("cma")

pytestmark = pytest.mark.tune

# The test problem: a double integrator q'' = u under PD sliding mode with a wide boundary
# layer (sat switch, phi = 1), started at rest at e0 on the x axis only. In the layer the law is
# linear: s = e' + lam e, u = -lam e' - k s (u_eq = -lam e' from s' = 0), so s' = -k s and
# e' = -lam e + s with s(0) = lam e0. Then
#     e(t) = e0 exp(-lam t) + lam e0 (exp(-lam t) - exp(-k t)) / (k - lam) >= 0,
# and the integrated absolute error (metric "iae") is
#     IAE = int e dt = e0/lam + lam e0 (1/lam - 1/k)/(k - lam) = e0 (1/lam + 1/k).
# The first command is u(0) = -k s(0) = -k lam e0, and with lam = k it is the largest |u|:
# u = lam^2 e - 2 lam s, e' <= 0 (w = s - lam e starts at 0 and w' = -k lam e < 0 at w = 0),
# so lam^2 e - 2 lam s < lam^2 e0. Minimising IAE subject to k lam e0 <= U (the peak
# command) gives, by symmetry and AM-GM (1/lam + 1/k >= 2/sqrt(lam k) >= 2 sqrt(e0/U)),
#     lam* = k* = sqrt(U / e0),  IAE* = 2 e0 sqrt(e0 / U).
# With e0 = 0.1 and U = 0.4: lam* = k* = 2, IAE* = 0.1. s stays within the layer:
# |s| <= lam e0 <= 0.8 < 1 over the box below.
E0 = 0.1
U = 0.4
LAM_STAR = math.sqrt(U / E0)
IAE_STAR = 2 * E0 * math.sqrt(E0 / U)


def _scenario(**overrides):
    s = landing.scenarios.Scenario(
        name="di_pd",
        plant=landing.plants.DoubleIntegrator(),
        controller=landing.controllers.PDSlidingMode(lambda_=1.0, k=1.0, switch="sat", boundary_layer=1.0),
        x0=np.array([E0, 0.0, 0.0, 0.0, 0.0, 0.0]),
        t_final=20.0,
        dt=0.005,
    )
    return s.replace(**overrides)


GAINS = {"lambda_": (0.2, 8.0, "log"), "k": (0.2, 8.0, "log")}


def test_closed_form_of_the_test_problem():
    """The analytic IAE and first command against a run (checks the derivation, not tune)."""
    s = _scenario(controller={"lambda_": 1.5, "k": 3.0})
    m = s.simulate().metrics
    assert m["iae"] == pytest.approx(E0 * (1 / 1.5 + 1 / 3.0), rel=5e-3)
    assert m["peak_command"] == pytest.approx(3.0 * 1.5 * E0, rel=1e-9)


@pytest.fixture(scope="module")
def constrained():
    return landing.tune(_scenario(), GAINS, "mean(iae)", ["max(peak_command) <= 0.4"],
                        budget=240, seed=3, threads=1)


def test_finds_the_constrained_optimum(constrained):
    r = constrained
    assert r.best_feasible
    assert r.best_gains["lambda_"] == pytest.approx(LAM_STAR, rel=0.05)
    assert r.best_gains["k"] == pytest.approx(LAM_STAR, rel=0.05)
    assert r.best_objectives["mean(iae)"] == pytest.approx(IAE_STAR, rel=0.01)


def test_finds_a_one_gain_optimum():
    """k = 4 fixed, J = IAE + peak/16 = e0/lam + e0/4 + 4 lam e0/16 (the first command is the
    peak for lam <= k: lam^2 e <= lam^2 e0 <= k lam e0), minimal at lam* = 2, J* = 0.125."""
    r = landing.tune(_scenario(controller={"k": 4.0}), {"lambda_": (0.2, 8.0, "log")},
                     "mean(iae) + max(peak_command)/16", budget=80, seed=3, threads=1)
    assert r.best_gains["lambda_"] == pytest.approx(2.0, rel=0.03)
    assert r.objective_values[r.best, 0] == pytest.approx(0.125, rel=5e-3)


def test_the_start_is_evaluated_first():
    r = landing.tune(_scenario(), GAINS, "mean(iae)", budget=12, seed=3, threads=1, popsize=6,
                     start={"lambda_": 1.5, "k": 1.2})
    np.testing.assert_allclose(r.x[0], [1.5, 1.2], rtol=1e-12)
    assert r.objective_values[0, 0] == pytest.approx(E0 * (1 / 1.5 + 1 / 1.2), rel=5e-3)


def test_constraints_are_honoured(constrained):
    r = constrained
    lam, k = r.x[:, 0], r.x[:, 1]
    peak = k * lam * E0  # the first command, exact in the sampled loop
    # every evaluation marked feasible meets the constraint by the closed form, every one
    # marked infeasible breaks it
    assert np.all(peak[r.feasible] <= U * (1 + 1e-9))
    assert np.all(peak[~r.feasible] > U * (1 - 1e-9))
    assert r.feasible.any() and (~r.feasible).any()
    b = r.best_gains
    assert b["k"] * b["lambda_"] * E0 <= U * (1 + 1e-9)
    # the tuned scenario carries the best gains
    assert r.scenario().controller.lambda_ == b["lambda_"]
    assert r.scenario().controller.k == b["k"]
    # the search moved into the feasible region: most of the last generation is feasible
    last = r.generation == r.generation.max()
    assert r.feasible[last].mean() >= 0.5


def test_no_feasible_point_gives_the_least_violation():
    r = landing.tune(_scenario(), GAINS, "mean(iae)", ["max(peak_command) <= 0.001"],
                     budget=60, seed=1, threads=1)
    # k lam e0 >= 0.2 * 0.2 * 0.1 = 0.004 > 0.001 everywhere in the box
    assert not r.feasible.any()
    assert not r.best_feasible
    assert r.unmet() == ["max(peak_command) <= 0.001"]
    assert r.violation[r.best] == r.violation.min()


def test_same_seed_same_result_whatever_the_threads():
    s = _scenario(
        dispersion=landing.dispersions.Normal(mean=[E0, 0, 0, 0, 0, 0], std=[0.02, 0.02, 0.02, 0.01, 0.01, 0.01]),
        disturbance=landing.disturbances.UniformNoise(0.05),
        t_final=5.0, dt=0.01,
    )
    kw = dict(cases=4, budget=24, seed=11)
    a = landing.tune(s, GAINS, "mean(iae)", ["max(peak_command) <= 0.6"], threads=1, **kw)
    b = landing.tune(s, GAINS, "mean(iae)", ["max(peak_command) <= 0.6"], threads=2, **kw)
    assert np.array_equal(a.x, b.x)
    assert np.array_equal(a.objective_values, b.objective_values)
    assert np.array_equal(a.constraint_values, b.constraint_values)
    assert a.best == b.best and a.best_gains == b.best_gains
    c = landing.tune(s, GAINS, "mean(iae)", ["max(peak_command) <= 0.6"], threads=2, cases=4, budget=24, seed=12)
    assert not np.array_equal(a.x, c.x)
    # without the noise a generation is one batch of popsize x K cases: the same again
    quiet = s.replace(disturbance=None)
    a = landing.tune(quiet, GAINS, "mean(iae)", ["max(peak_command) <= 0.6"], threads=1, **kw)
    b = landing.tune(quiet, GAINS, "mean(iae)", ["max(peak_command) <= 0.6"], threads=2, **kw)
    assert np.array_equal(a.x, b.x)
    assert np.array_equal(a.objective_values, b.objective_values)
    assert a.best_gains == b.best_gains


def test_common_random_numbers_in_one_batch_and_per_candidate():
    """Without random disturbances a generation is one batch; every candidate sees the same
    K initial states: a candidate re-run alone on those states gives the same metrics."""
    s = _scenario(dispersion=landing.dispersions.Normal(mean=[E0, 0, 0, 0, 0, 0], std=[0.02] * 3 + [0.01] * 3),
                  t_final=5.0, dt=0.01)
    r = landing.tune(s, GAINS, "mean(iae)", budget=12, cases=3, seed=5, threads=1)
    x0 = s.initial_states(3, seed=5)
    for i in (0, 7):
        alone = s.replace(controller=r.gains_of(i)).simulate_batch(x0, seed=5, record_every=0)
        assert r.objective_values[i, 0] == np.mean(alone.metrics["iae"])


def test_pareto_front_is_the_non_dominated_feasible_set():
    r = landing.tune(_scenario(), GAINS, ["mean(iae)", "max(peak_command)"], budget=120, seed=2, threads=1)
    F = np.flatnonzero(r.feasible)
    front = set(r.front.tolist())
    assert front and front <= set(F.tolist())
    v = r.objective_values
    for i in F:
        dominated = any(np.all(v[j] <= v[i]) and np.any(v[j] < v[i]) for j in F)
        assert (i in front) == (not dominated)
    # the trade-off is bounded below by the closed form: P >= k lam e0 (the first command), so
    # IAE = e0 (1/lam + 1/k) >= 2 e0 / sqrt(lam k) >= 2 e0 sqrt(e0 / P); checked where the 20 s
    # horizon holds the whole integral (lam, k >= 0.5: exp(-10) left), to the rectangle rule's
    # error
    long = np.min(r.x, axis=1) >= 0.5
    assert long[r.front].sum() >= 3
    for i in r.front[long[r.front]]:
        assert v[i, 0] >= 2 * E0 * math.sqrt(E0 / v[i, 1]) * (1 - 5e-3)


def test_interrupt_returns_the_best_so_far():
    calls = {"n": 0}

    def objective(metrics, bounds):
        calls["n"] += 1
        if calls["n"] > 20:
            raise KeyboardInterrupt
        return float(np.mean(metrics["iae"]))

    r = landing.tune(_scenario(t_final=5.0, dt=0.01), GAINS, objective, budget=200, seed=0, threads=1, popsize=6)
    assert r.interrupted
    assert r.n_evaluations == 18  # three whole generations of 6
    assert r.best_feasible


def test_several_setups():
    """Two set-ups share the searched gains; expressions name their metrics by label. The
    second set-up starts at 2 e0, so its IAE is twice the first's (linear loop)."""
    s1 = _scenario()
    s2 = _scenario(x0=np.array([2 * E0, 0.0, 0.0, 0.0, 0.0, 0.0]))
    r = landing.tune({"near": s1, "far": s2}, GAINS, "mean(near.iae) + mean(far.iae)",
                     ["max(far.peak_command) <= 0.8"], budget=240, seed=3, threads=1)
    # IAE_near + IAE_far = 3 e0 (1/lam + 1/k) with k lam 2 e0 <= 0.8: the same optimum as above
    assert r.best_gains["lambda_"] == pytest.approx(LAM_STAR, rel=0.05)
    assert r.best_gains["k"] == pytest.approx(LAM_STAR, rel=0.05)
    assert r.objective_values[r.best, 0] == pytest.approx(3 * IAE_STAR, rel=0.01)
    assert r.scenario(setup="far").x0[0] == 2 * E0


def test_bounds_in_expressions():
    s = landing.scenarios.mars_nominal(t_final=1.0, dt=0.01)
    r = landing.tune(s, {"beta1": (0.5, 2.0), "q1": (0.5, 0.9)}, "abs(t1 - 100)", budget=8, seed=0, threads=1)
    t1 = landing.theory.fixed_time_bound(r.x[:, 0], r.x[:, 1], s.controller.beta2, s.controller.q2)
    np.testing.assert_allclose(r.objective_values[:, 0], np.abs(t1 - 100), rtol=1e-12)


@pytest.mark.parametrize("expr, kind, fragment", [
    ("mean(fule_used)", "objective", "unknown name 'fule_used'"),
    ("__import__('os')", "objective", "unknown function '__import__'"),
    ("mean(iae).real", "objective", "only NAME or SETUP.NAME"),
    ("nominal.iae", "objective", "unknown name 'nominal.iae'"),
    ("fuel_used", "objective", "one number per candidate"),
    ("mean(iae) + t1", "objective", "FixedTimeMSS"),
    ("percentile(iae, 120)", "objective", "[0, 100]"),
    ("mean(iae) == 1", "constraint", "one comparison"),
    ("mean(iae)", "constraint", "one comparison"),
    ("[1, 2]", "objective", "List"),
    ("mean(iae", "objective", "not a valid expression"),
    ("'a'", "objective", "numbers"),
    ("mean(x=iae)", "objective", "positional"),
])
def test_the_grammar_refuses(expr, kind, fragment):
    with pytest.raises(ParameterError) as err:
        if kind == "objective":
            landing.tune(_scenario(), GAINS, expr, budget=4)
        else:
            landing.tune(_scenario(), GAINS, "mean(iae)", [expr], budget=4)
    assert fragment in str(err.value)
    assert repr(expr) in str(err.value)


@pytest.mark.parametrize("gains, fragment", [
    ({"lam": (0.1, 1.0)}, "not a parameter"),
    ({"k": (1.0, 0.5)}, "low < high"),
    ({"k": (0.0, 1.0, "log")}, "low > 0"),
    ({"k": (0.1, 1.0, "ln")}, "scale"),
])
def test_bad_gains(gains, fragment):
    with pytest.raises(ParameterError, match="gains") as err:
        landing.tune(_scenario(), gains, "mean(iae)", budget=4)
    assert fragment in str(err.value)


def test_write_and_plots(constrained, tmp_path):
    files = constrained.write(tmp_path)
    names = {p.name for p in files}
    assert "tuned.toml" in names
    back = landing.scenarios.Scenario.load(tmp_path / "tuned.toml")
    assert back.controller.k == constrained.best_gains["k"]
    import matplotlib

    matplotlib.use("Agg")
    fig = landing.plots.tuning_convergence(constrained)
    assert fig.axes
    fig = landing.plots.tuning_front(constrained)
    assert fig.axes


def test_command_line(tmp_path, capsys):
    from landing.cli import main

    config = tmp_path / "di.toml"
    config.write_text(_scenario().to_toml() + """
[tune]
objective = "mean(iae)"
constraints = ["max(peak_command) <= 0.4"]
cases = 1
budget = 120
seed = 3

[tune.gains]
lambda_ = [0.2, 8.0, "log"]
k = [0.2, 8.0, "log"]
""")
    out = tmp_path / "out"
    assert main(["tune", str(config), "--out", str(out), "--no-progress", "--threads", "1"]) == 0
    text = capsys.readouterr().out
    assert "best gains: lambda_=" in text
    tuned = landing.scenarios.Scenario.load(out / "tuned.toml")
    assert tuned.controller.lambda_ * tuned.controller.k * E0 <= U * (1 + 1e-9)
    assert tuned.controller.lambda_ == pytest.approx(LAM_STAR, rel=0.1)
    assert any(out.glob("evaluations.*"))
    # a bad [tune] key is refused as bad input (exit code 2) naming the file and the key
    config.write_text(config.read_text().replace("budget = 120", "budgt = 120"))
    assert main(["tune", str(config), "--no-progress"]) == 2
    assert "tune.budgt" in capsys.readouterr().err


def test_write_csv_without_pyarrow(constrained, tmp_path, monkeypatch):
    import sys

    monkeypatch.setitem(sys.modules, "pyarrow", None)  # import pyarrow raises ImportError
    files = constrained.write(tmp_path)
    csv = tmp_path / "evaluations.csv"
    assert csv in files
    rows = np.loadtxt(csv, delimiter=",", skiprows=1)
    # generation, two gains, one objective, one constraint, diverged, violation, feasible
    assert rows.shape == (constrained.n_evaluations, 8)
    header = csv.read_text().splitlines()[0].split(",")
    np.testing.assert_array_equal(rows[:, header.index("lambda_")], constrained.x[:, 0])


def test_the_function_and_the_package_are_both_reachable() -> None:
    # `landing.tune` is the search function; its package is `landing.tuning`, whose modules import
    # by their dotted names (they could not while the package shared the function's name).
    import importlib

    import landing.tuning.pareto as pareto

    assert callable(landing.tune) and landing.tune is landing.tuning.tune
    assert landing.tuning.pareto_front is pareto.pareto_front
    assert importlib.import_module("landing.tuning.search").tune is landing.tune
    assert landing.TuneResult is landing.tuning.TuneResult
