"""Which dispersion drives a metric: the rank correlations against scipy.stats and a second
implementation of the partial rank correlation, a linear model whose drivers are known, the
Ishigami function's Sobol indices (closed form) through SALib, and the tornado plot."""

from __future__ import annotations

import numpy as np
import pytest

import landing
from _cases import small_campaign
from landing import controllers as C
from landing import plants as P
from landing.campaign.sensitivity import flat_columns, rank_correlations, ranks, sobol
from landing.dispersions import Normal, Uniform
from landing.errors import ParameterError
from landing.scenarios import Scenario

stats = pytest.importorskip("scipy.stats")


def one_step(f, names):
    """A plant whose first coordinate moves by f(params) in one Euler step of 1 s from 0: its
    final_error_x0 is f of the case's parameters, a model with a closed form."""
    def derivative(t, x, u, params):
        out = np.zeros_like(x)
        out[:, 0] = f(*(params[n] for n in names))
        return out

    plant = P.PythonPlant(derivative, 4, positions=(0, 1), velocities=(2, 3), params={n: 0.0 for n in names})
    return Scenario(name="model", plant=plant, controller=C.OpenLoop(), x0=np.zeros(4), t_final=1.0, dt=1.0,
                    integrator="euler", record_every=0)


def test_ranks_are_scipys_with_ties_averaged():
    x = np.array([3.0, 1.0, 2.0, 2.0, 5.0, 1.0])
    np.testing.assert_array_equal(ranks(x), stats.rankdata(x))


def test_linear_drivers_spearman_against_scipy_and_prcc_against_the_inverse_correlation_matrix():
    s = one_step(lambda a, b, c: 1.0 * a + 3.0 * b + 0.0 * c, ["a", "b", "c"]).disperse(
        {"plant.a": Uniform(-1, 1), "plant.b": Normal(0, 0.5), "plant.c": Uniform(0, 1)})
    mc = landing.monte_carlo(s, 400, seed=3, progress=False)
    corr = mc.sensitivity(["final_error_x0"])
    assert corr.inputs == ("param.plant.a", "param.plant.b", "param.plant.c")
    y = mc.metrics["final_error"][:, 0]
    X = np.column_stack([mc.metrics[f"param.plant.{n}"] for n in "abc"])
    for j in range(3):
        assert corr.spearman[0, j] == pytest.approx(stats.spearmanr(X[:, j], y).statistic, abs=1e-12)
    # a second PRCC: minus the normalised inverse of the correlation matrix of the ranks
    R = np.column_stack([stats.rankdata(c) for c in (*X.T, y)])
    P_ = np.linalg.inv(np.corrcoef(R, rowvar=False))
    expected = [-P_[j, 3] / np.sqrt(P_[j, j] * P_[3, 3]) for j in range(3)]
    np.testing.assert_allclose(corr.prcc[0], expected, atol=1e-10)
    # the known structure: b drives most, then a, c not at all
    assert corr.drivers("final_error_x0", 3)[0][0] == "param.plant.b"
    assert corr.prcc[0, 1] > corr.prcc[0, 0] > 0.5 and abs(corr.prcc[0, 2]) < 3 / np.sqrt(400)
    # the report names the summary metrics' drivers (here |y|: no monotone driver)
    assert "what drives the metrics" in mc.report() and "final_position_error     param.plant." in mc.report()


def test_initial_state_dispersions_are_quantities_too():
    mc = landing.monte_carlo(small_campaign(), 60, seed=1, progress=False, check_bounds=False)
    corr = mc.sensitivity(["fuel_used"])
    assert "x0_rx" in corr.inputs and "x0_m" in corr.inputs  # Table II disperses every component
    with pytest.raises(ParameterError, match="is not one of"):
        mc.sensitivity(["fuel"])
    nothing = landing.monte_carlo(small_campaign(dispersion=None), 40, seed=1, progress=False, check_bounds=False)
    with pytest.raises(ParameterError, match="disperses nothing"):
        rank_correlations(nothing.result, nothing.x0)


def test_per_axis_columns_split_by_axis_and_components_by_index():
    cols = flat_columns({"e": np.ones((4, 3)), "param.p": np.ones((4, 3)), "diverged": np.zeros(4, bool)},
                        ("x", "y", "z"))
    assert list(cols) == ["e_x", "e_y", "e_z", "param.p_x", "param.p_y", "param.p_z"]


@pytest.mark.slow
def test_sobol_indices_of_the_ishigami_function_are_its_closed_form():
    pytest.importorskip("SALib")
    # y = sin x1 + 7 sin^2 x2 + 0.1 x3^4 sin x1, x_i ~ U(-pi, pi) (Ishigami and Homma 1990): with
    # a = 7, b = 0.1, V = a^2/8 + b pi^4/5 + b^2 pi^8/18 + 1/2, V1 = (1 + b pi^4/5)^2 / 2,
    # V2 = a^2/8, V13 = b^2 pi^8 (1/18 - 1/50); S3 = 0
    a, b = 7.0, 0.1
    V = a**2 / 8 + b * np.pi**4 / 5 + b**2 * np.pi**8 / 18 + 0.5
    V1, V2, V13 = (1 + b * np.pi**4 / 5) ** 2 / 2, a**2 / 8, b**2 * np.pi**8 * (1 / 18 - 1 / 50)
    s = one_step(lambda x1, x2, x3: np.sin(x1) + a * np.sin(x2) ** 2 + b * x3**4 * np.sin(x1),
                 ["x1", "x2", "x3"]).disperse({f"plant.x{i}": Uniform(-np.pi, np.pi) for i in (1, 2, 3)})
    r = sobol(s, "final_error_x0", n=4096, seed=1)
    assert r.names == ("plant.x1", "plant.x2", "plant.x3") and r.n == 4096 * 5
    np.testing.assert_allclose(r.S1, [V1 / V, V2 / V, 0.0], atol=0.03)
    np.testing.assert_allclose(r.ST, [(V1 + V13) / V, V2 / V, V13 / V], atol=0.03)
    assert "Sobol indices of final_error_x0" in str(r)


def test_sobol_needs_dispersed_parameters():
    pytest.importorskip("SALib")
    with pytest.raises(ParameterError, match="disperses no parameter"):
        sobol(small_campaign(), "fuel_used", n=8)


def test_the_tornado_plot_draws_the_strongest_drivers_largest_on_top():
    pytest.importorskip("matplotlib")
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    s = one_step(lambda a, b: a + 3 * b, ["a", "b"]).disperse({"plant.a": Uniform(-1, 1), "plant.b": Uniform(-1, 1)})
    mc = landing.monte_carlo(s, 200, seed=2, progress=False)
    fig, ax = plt.subplots()
    assert landing.plots.tornado(mc, "final_error_x0", ax=ax) is fig
    labels = [t.get_text() for t in ax.get_yticklabels()]
    assert labels == ["param.plant.a", "param.plant.b"]  # b, the stronger, on top
    plt.close("all")
