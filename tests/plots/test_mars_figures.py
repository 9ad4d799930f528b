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
