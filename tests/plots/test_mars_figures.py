"""The Mars figures (seed 001) of a campaign and of one run."""

import matplotlib
import numpy as np
import pytest

import landing
from _cases import small_campaign
from landing import scenarios

matplotlib.use("Agg")


def test_figures(tmp_path):
    mc = landing.monte_carlo(small_campaign(), 8, seed=1)
    # the touchdown positions (first rz = 0 crossing), not the state at t_final: a run long
    # enough for the cases to reach the ground
    landed = landing.monte_carlo(scenarios.mars_monte_carlo(t_final=40.0, dt=2e-3, record_every=0), 8, seed=1)
    fig = landing.plots.landing_sites(landed)
    assert len(fig.axes) == 2
    td = np.asarray(landed.metrics["touchdown_position"])[:, :2]
    touched = np.all(np.isfinite(td), axis=1)
    assert touched.sum() >= 6
    assert not np.allclose(td[touched], np.asarray(landed.result.final_state)[touched, :2])
    np.testing.assert_array_equal(np.asarray(fig.axes[0].collections[0].get_offsets()), td[touched])
    assert "touchdown" in fig.axes[0].get_title().lower()
    fig = landing.plots.sliding_variables(mc)
    assert len(fig.axes) == 6 and len(fig.axes[0].lines) >= 8
    written = landing.plots.save_all(mc, tmp_path / "figs")
    assert {p.name for p in written} >= {"trajectories_3d.png", "landing_sites.png", "thrust.png", "mass.png",
                                         "sliding_variables.png", "final_velocities.png"}
    assert all(p.stat().st_size > 1000 for p in written)
    one = scenarios.mars_nominal(t_final=2.0).simulate()
    assert len(landing.plots.thrust(one).axes) == 3
    with pytest.raises(ValueError, match="record_every"):
        landing.plots.thrust(scenarios.mars_nominal(t_final=2.0, record_every=0).simulate())


def test_the_landing_sites_carry_their_dispersion_ellipses_and_the_requirement():
    mc = landing.monte_carlo(scenarios.mars_realistic(record_every=0), 200, seed=2)
    fig = landing.plots.landing_sites(mc, requirement_radius=5.0)
    ax = fig.axes[0]
    sites = np.asarray(mc.metrics["touchdown_position"])[:, :2]
    lines = {line.get_label(): line.get_xydata() for line in ax.lines}
    # the k-sigma curve lies at Mahalanobis distance k under the sites' own covariance
    inv = np.linalg.inv(np.cov(sites, rowvar=False))
    for k in (1, 2, 3):
        (label,) = [lab for lab in lines if lab.startswith(f"{k} sigma")]
        d = lines[label] - sites.mean(axis=0)
        np.testing.assert_allclose(np.sqrt(np.einsum("ij,jk,ik->i", d, inv, d)), k, rtol=1e-12)
    # about 98.9 % of a 2-D normal's points lie inside 3 sigma: most sites do here
    d = sites - sites.mean(axis=0)
    inside = np.sqrt(np.einsum("ij,jk,ik->i", d, inv, d)) <= 3
    assert inside.mean() > 0.95
    circle = lines["requirement: within 5 m"]
    np.testing.assert_allclose(np.hypot(circle[:, 0], circle[:, 1]), 5.0)


def test_the_velocity_figure_shows_the_velocities_at_touchdown():
    mc = landing.monte_carlo(scenarios.mars_realistic(record_every=0), 40, seed=2)
    fig = landing.plots.final_velocities(mc)
    v = np.asarray(mc.metrics["touchdown_velocity"])
    np.testing.assert_array_equal(fig.axes[0].collections[0].get_offsets(), v[:, [0, 2]])
    assert len(np.unique(v[:, 2])) > 30  # one point per case, not one dot
