"""Figures: each function takes a result and returns a matplotlib Figure.

They accept a :class:`~landing.SimulationResult` (one case or a batch) or a
:class:`~landing.MonteCarloResult`; a campaign's theoretical bounds, if any, are drawn.
``save_all`` writes the standard set for a campaign. The families: :mod:`~landing.plots.mars`
(seed 001), :mod:`~landing.plots.comparison` (single-case comparisons, seeds 000 and 002),
:mod:`~landing.plots.tether` (seed 003), :mod:`~landing.plots.tuning` (``landing.tune``).
matplotlib is imported when the first figure is drawn.
"""

from landing.plots._common import save_figures
from landing.plots.comparison import (
    blend_coefficients,
    commands,
    diagnostic,
    tracking_errors,
    trajectory_with_reference,
)
from landing.plots.mars import (
    final_velocities,
    landing_sites,
    mass,
    masses,
    position_and_thrust,
    positions,
    sliding_variables,
    thrust,
    trajectories_3d,
)
from landing.plots.sensitivity import tornado
from landing.plots.standard import save_all, standard_figures
from landing.plots.tether import tether_angles, tether_commands, tether_fixed_time, tether_rates
from landing.plots.tuning import tuning_convergence, tuning_front

__all__ = [
    "tornado",
    "trajectories_3d",
    "landing_sites",
    "final_velocities",
    "sliding_variables",
    "thrust",
    "mass",
    "positions",
    "save_all",
    "tracking_errors",
    "commands",
    "diagnostic",
    "blend_coefficients",
    "trajectory_with_reference",
    "tether_angles",
    "tether_rates",
    "tether_commands",
    "tether_fixed_time",
    "position_and_thrust",
    "masses",
    "tuning_convergence",
    "tuning_front",
    "standard_figures",
    "save_figures",
]
