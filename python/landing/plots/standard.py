"""The usual figures of a run or campaign for its plant (what ``landing run``, ``landing mc``
and ``landing report`` write)."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Callable, Optional, Union

from landing.plants import MarsLander, Plant, TetheredSatellite
from landing.plots._common import Result, result_and_bounds, save_figures
from landing.plots.comparison import commands, tracking_errors, trajectory_with_reference
from landing.plots.mars import (
    final_velocities,
    landing_sites,
    mass,
    positions,
    sliding_variables,
    thrust,
    trajectories_3d,
)
from landing.plots.tether import tether_angles, tether_commands, tether_rates
from landing.reference import Reference

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.figure import Figure

__all__ = ["save_all", "standard_figures"]


def save_all(result: Result, folder: Union[str, Path], dpi: int = 120) -> list[Path]:
    """Write the standard figures of a Mars campaign (:func:`standard_figures`) as PNG files into
    ``folder``, and close them.

    Parameters
    ----------
    result : landing.SimulationResult or landing.MonteCarloResult
        A run, a batch or a campaign (a campaign's bounds and thrust limits are drawn).
    folder : str or pathlib.Path
        The folder (made if missing).
    dpi : int, default 120
        The images' resolution (dots per inch).

    Returns
    -------
    list of pathlib.Path
        The files written, ``folder/<name>.png``.

    Examples
    --------
    >>> import tempfile, matplotlib
    >>> matplotlib.use("Agg")
    >>> import landing
    >>> scenario = landing.scenarios.preset("mars_monte_carlo").replace(t_final=5.0)
    >>> mc = landing.monte_carlo(scenario, n=8, seed=1)
    >>> [p.name for p in landing.plots.save_all(mc, tempfile.mkdtemp())][:3]
    ['trajectories_3d.png', 'landing_sites.png', 'final_velocities.png']
    """
    return save_figures(standard_figures(result), folder, dpi=dpi)


def standard_figures(result: Result, plant: Optional[Plant] = None,
                     reference: Optional[Reference] = None) -> dict[str, Figure]:
    """The usual figures of a run or campaign for its plant, by name (what ``landing run``,
    ``landing mc`` and ``landing report`` write): the Mars figures of :func:`save_all` for the
    lander, tracking errors and commands for the small body and the double integrator, angles,
    rates and commands for the tethered satellite. Nothing for a run that recorded nothing; none
    of a Mars campaign's figures drawn from a signal it did not keep.

    Parameters
    ----------
    result : landing.SimulationResult or landing.MonteCarloResult
        A run, a batch or a campaign (a campaign's bounds and thrust limits are drawn).
    plant : landing.plants.Plant, optional
        The plant the result is of (default: the Mars lander).
    reference : landing.reference.Reference, optional
        The reference tracked (for the small body's and the double integrator's figures).

    Returns
    -------
    dict of str to matplotlib.figure.Figure
        The figures by name.

    Examples
    --------
    >>> import landing
    >>> scenario = landing.scenarios.preset("mars_monte_carlo").replace(t_final=5.0)
    >>> mc = landing.monte_carlo(scenario, n=8, seed=1)
    >>> sorted(landing.plots.standard_figures(mc))
    ['final_velocities', 'landing_sites', 'mass', 'positions', 'sliding_variables', 'thrust', 'trajectories_3d']
    """
    res, _ = result_and_bounds(result)
    if res.t.size == 0:
        return {}
    if plant is None or isinstance(plant, MarsLander):
        makers: dict[str, Callable[[Result], Figure]] = {
            "trajectories_3d": trajectories_3d,
            "landing_sites": landing_sites,
            "final_velocities": final_velocities,
            "positions": positions,
            # the given plant's thrust limits (else a campaign's scenario's)
            "thrust": lambda r: thrust(r, plant=plant),
            "mass": mass,
        }
        if {"s1", "s2"} <= set(res.diagnostics):
            makers["sliding_variables"] = sliding_variables
        # a campaign that did not keep a signal (keep=...) has none of the figures drawn from it
        needs = {"trajectories_3d": "states", "positions": "states", "mass": "states", "thrust": "controls"}
        return {name: make(result) for name, make in makers.items()
                if name not in needs or getattr(res, needs[name]) is not None}
    if isinstance(plant, TetheredSatellite):
        return {
            "tether_angles": tether_angles(res, plant),
            "tether_rates": tether_rates(res, plant),
            "tether_commands": tether_commands(res, plant=plant),
        }
    figs = {"tracking_errors": tracking_errors(res, reference), "commands": commands(res, plant=plant)}
    if reference is not None and res.states is not None and res.states.shape[-1] >= 6:
        figs["trajectory"] = trajectory_with_reference(res, reference)
    return figs
