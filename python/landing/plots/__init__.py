"""Figures: each function takes a result and returns a matplotlib Figure.

They accept a :class:`~landing.SimulationResult` (one case or a batch) or a
:class:`~landing.MonteCarloResult`; a campaign's theoretical bounds, if any, are drawn.
``save_all`` writes the standard set for a campaign. The families: :mod:`~landing.plots.mars`
(the Mars fixed-time guidance paper), :mod:`~landing.plots.comparison` (single-case
comparisons: the fuzzy fast-terminal asteroid paper and the fuzzy variable-rate asteroid
paper), :mod:`~landing.plots.tether` (the tethered-satellite paper), :mod:`~landing.plots.tuning`
(``landing.tune``).
matplotlib is imported when the first figure is drawn.

The conventions every figure function keeps: given ``ax=`` (one panel) or ``axes=`` (a sequence
of exactly as many Axes as it has panels; another count is refused naming ``axes``) it draws
there and returns that Axes' Figure, so that several compose into one figure of the user's;
given neither it makes a Figure of its own (not pyplot's: it is freed with the result). Thrust
is in kN (the tether's commands in N and N m) and every axis states its unit; the plant's thrust
limits (of ``plant=``, else of a campaign's scenario) and the ground (rz = 0) are drawn; a
batch's cases are thin light lines (their 5-95 % band above 50 cases) about the nominal (the
first case, or ``highlight=``) drawn bold; a panel with nothing to draw says why.
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
