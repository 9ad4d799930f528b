"""The tethered satellite's figures (seed 003, figures 3 to 7)."""

import numpy as np
import pytest

from _cases import tether_comparison_runs
from landing import plots, scenarios


@pytest.fixture(scope="module")
def comparison():
    return tether_comparison_runs()


def test_figures(comparison):
    plant = scenarios.tether_plant()
    runs = {"FNTSMC": comparison["fntsmc"], "NTSMC": comparison["ntsmc"]}
    for fig in (plots.tether_angles(runs, plant), plots.tether_rates(runs), plots.tether_commands(runs)):
        assert len(fig.axes) == 2
        assert len(fig.axes[0].lines) >= 2
    fig = plots.tether_fixed_time({"FNTSMC": {1.0: np.array([30.0, 2.0]), 5.0: np.array([80.0, 5.0])}},
                                  np.array([1600.0, 28.0]))
    assert len(fig.axes) == 2
