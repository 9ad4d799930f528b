"""The tethered satellite's figures (the tethered-satellite paper's Fig. 3 to 7): angles,
rates and commands against time, and the worst settle time against the initial spread with the
fixed-time bound."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Callable, Optional, Union

import numpy as np

from landing._internal.table import ArrayLike
from landing.plants import TetheredSatellite
from landing.plots._common import (
    Runs,
    batched,
    draw_cases,
    first_cases,
    named_runs,
    need_records,
    recorded,
    say_why,
    several_axes,
)
from landing.results import SimulationResult
from landing.theory import FNTSMCBounds

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = ["tether_angles", "tether_rates", "tether_commands", "tether_fixed_time"]

_TETHER_AXES = (("in-plane angle", "phi"), ("attitude angle", "theta"))


def _tether_coordinates(res: SimulationResult,
                        plant: Optional[TetheredSatellite] = None) -> tuple[np.ndarray, np.ndarray]:
    """(q, q') of a tethered-satellite result, (N, T, 2) each. The flexible model's state holds
    positions; its angles come from the core (they do not depend on the physical parameters,
    so a default plant with the result's node count serves when none is given)."""
    states = batched(recorded(res, "states"), 3)
    if res.state_names[:2] == ("phi", "theta"):
        return states[..., :2], states[..., 2:4]
    if plant is None:
        plant = TetheredSatellite(fidelity="flexible", nodes=(len(res.state_names) - 6) // 4)
    return plant.coordinates(states)


def _tether_pair(results: Runs, pick: Callable[[SimulationResult, Optional[TetheredSatellite]], np.ndarray],
                 ylabels: tuple[str, str], title: tuple[str, str], plant: Optional[TetheredSatellite], scale: float,
                 max_cases: int, highlight: int, axes: Optional[Sequence[Axes]]) -> tuple[Figure, list[Axes]]:
    """Two panels; one run per label: a single case as one line, a batch as thin case lines
    (a percentile band when many) with case ``highlight`` bold."""
    runs = named_runs(results)
    fig, panels = several_axes(axes, 2, (1, 2), figsize=(11, 4), layout="constrained")
    for label, res in runs.items():
        need_records(res)
        data = pick(first_cases(res, max_cases), plant)
        for j, ax in enumerate(panels):
            if len(runs) == 1 and data.shape[0] > 1:
                draw_cases(ax, res.t, data[:, :, j], highlight, scale)
                continue
            lines = ax.plot(res.t, data[:, :, j].T * scale, lw=0.9)
            if label:
                lines[0].set_label(label)
    for j, ax in enumerate(panels):
        ax.set_title(f"{title[j]}")
        ax.set_xlabel("t (s)")
        ax.set_ylabel(ylabels[j])
        ax.axhline(0.0, color="0.7", lw=0.5)
    return fig, panels


def _legends(panels: list[Axes]) -> None:
    for ax in panels:
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize="small")


def tether_angles(results: Runs, plant: Optional[TetheredSatellite] = None, max_cases: int = 50, *,
                  highlight: int = 0, axes: Optional[Sequence[Axes]] = None) -> Figure:
    """In-plane and attitude angles against time, deg and s (the tethered-satellite paper's Fig. 3
    and 5). A batch's cases thin with case ``highlight`` bold.

    Parameters
    ----------
    results : landing.SimulationResult or mapping of str to landing.SimulationResult
        A run or batch, or several by label (e.g. ``{"FNTSMC": ..., "NTSMC": ...}``).
    plant : landing.plants.TetheredSatellite, optional
        The plant the runs are of (the flexible model's angles are computed from its state).
    max_cases : int, default 50
        The most cases of a batch drawn (the first ones).
    highlight : int, default 0
        The case drawn bold (the nominal).
    axes : sequence of matplotlib.axes.Axes, optional
        Exactly 2 Axes to draw into (phi, theta); by default a Figure of its own.

    Returns
    -------
    matplotlib.figure.Figure
        The figure drawn (that of ``ax`` or ``axes`` when given).

    Examples
    --------
    >>> import landing
    >>> scenario = landing.scenarios.preset("tether_fntsmc_simplified").replace(t_final=5.0)
    >>> run = scenario.simulate()
    >>> fig = landing.plots.tether_angles(run, scenario.plant)
    >>> len(fig.axes), fig.axes[0].get_ylabel()
    (2, 'phi (deg)')
    """
    fig, panels = _tether_pair(results, lambda r, p: _tether_coordinates(r, p)[0], ("phi (deg)", "theta (deg)"),
                               ("In-plane angle", "Attitude angle"), plant, 180.0 / np.pi, max_cases, highlight,
                               axes)
    _legends(panels)
    return fig


def tether_rates(results: Runs, plant: Optional[TetheredSatellite] = None, max_cases: int = 50, *,
                 highlight: int = 0, axes: Optional[Sequence[Axes]] = None) -> Figure:
    """In-plane and attitude angular rates against time, deg/s and s (the tethered-satellite paper's
    Fig. 4 and 6).

    Parameters
    ----------
    results : landing.SimulationResult or mapping of str to landing.SimulationResult
        A run or batch, or several by label (e.g. ``{"FNTSMC": ..., "NTSMC": ...}``).
    plant : landing.plants.TetheredSatellite, optional
        The plant the runs are of (the flexible model's angles are computed from its state).
    max_cases : int, default 50
        The most cases of a batch drawn (the first ones).
    highlight : int, default 0
        The case drawn bold (the nominal).
    axes : sequence of matplotlib.axes.Axes, optional
        Exactly 2 Axes to draw into (phi', theta'); by default a Figure of its own.

    Returns
    -------
    matplotlib.figure.Figure
        The figure drawn (that of ``ax`` or ``axes`` when given).

    Examples
    --------
    >>> import landing
    >>> scenario = landing.scenarios.preset("tether_fntsmc_simplified").replace(t_final=5.0)
    >>> run = scenario.simulate()
    >>> len(landing.plots.tether_rates(run, scenario.plant).axes)
    2
    """
    fig, panels = _tether_pair(results, lambda r, p: _tether_coordinates(r, p)[1],
                               ("phi' (deg/s)", "theta' (deg/s)"), ("In-plane angular rate", "Attitude angular rate"),
                               plant, 180.0 / np.pi, max_cases, highlight, axes)
    _legends(panels)
    return fig


def tether_commands(results: Runs, max_cases: int = 50, *, plant: Optional[TetheredSatellite] = None,
                    highlight: int = 0, axes: Optional[Sequence[Axes]] = None) -> Figure:
    """Applied thrust (N) and torque (N m) against time, s (the tethered-satellite paper's Fig. 7
    (a), (b)), with the plant's thrust and torque limits when ``plant`` is given.

    Parameters
    ----------
    results : landing.SimulationResult or mapping of str to landing.SimulationResult
        A run or batch, or several by label (e.g. ``{"FNTSMC": ..., "NTSMC": ...}``).
    max_cases : int, default 50
        The most cases of a batch drawn (the first ones).
    plant : landing.plants.TetheredSatellite, optional
        The plant whose limits are drawn.
    highlight : int, default 0
        The case drawn bold (the nominal).
    axes : sequence of matplotlib.axes.Axes, optional
        Exactly 2 Axes to draw into (thrust, torque); by default a Figure of its own.

    Returns
    -------
    matplotlib.figure.Figure
        The figure drawn (that of ``ax`` or ``axes`` when given).

    Examples
    --------
    >>> import landing
    >>> scenario = landing.scenarios.preset("tether_fntsmc_simplified").replace(t_final=5.0)
    >>> run = scenario.simulate()
    >>> len(landing.plots.tether_commands(run, plant=scenario.plant).axes)
    2
    """
    fig, panels = _tether_pair(results, lambda r, p: batched(recorded(r, "controls"), 3),
                               ("thrust (N)", "torque (N m)"),
                               ("(a) Thrust of the sub-satellite", "(b) Torque of the sub-satellite"), None, 1.0,
                               max_cases, highlight, axes)
    if plant is not None:
        for ax, limit, unit in zip(panels, tether_limits(plant), ("N", "N m")):
            if limit is not None and np.isfinite(limit):
                for sgn in (1, -1):
                    ax.axhline(sgn * limit, ls="--", color="tab:red", lw=1,
                               label=f"limit {limit:.4g} {unit}" if sgn > 0 else None)
    _legends(panels)
    return fig


def tether_limits(plant: TetheredSatellite) -> tuple[Optional[float], Optional[float]]:
    """The tethered satellite's thrust limit (N) and torque limit (N m; by default
    ``thrust_limit * side / 2``), None where it has none.

    Parameters
    ----------
    plant : landing.plants.TetheredSatellite
        The plant.

    Returns
    -------
    tuple of (float or None, float or None)
        ``(thrust limit in N, torque limit in N m)``.
    """
    thrust = None if plant.thrust_limit is None else float(np.max(np.asarray(plant.thrust_limit, dtype=float)))
    if plant.torque_limit is not None:
        torque: Optional[float] = float(np.max(np.asarray(plant.torque_limit, dtype=float)))
    elif thrust is not None:
        torque = thrust * float(np.max(np.asarray(plant.side, dtype=float))) / 2.0
    else:
        torque = None
    return thrust, torque


def tether_fixed_time(worst: Mapping[str, Mapping[float, np.ndarray]],
                      bound: Union[FNTSMCBounds, ArrayLike], *, axes: Optional[Sequence[Axes]] = None) -> Figure:
    """Worst settle time of each angle, s, against the initial-error spread of a campaign, deg, per
    law, with the fixed-time bound (dashed).

    Parameters
    ----------
    worst : mapping of str to mapping of float to numpy.ndarray
        ``worst[law][spread_deg]``: the (2,) worst settle times (phi, theta), s.
    bound : landing.theory.FNTSMCBounds or array_like
        The (2,) bound (s) of :func:`landing.theory.fntsmc_bounds` (its ``.total``).
    axes : sequence of matplotlib.axes.Axes, optional
        Exactly 2 Axes to draw into (phi, theta); by default a Figure of its own.

    Returns
    -------
    matplotlib.figure.Figure
        The figure drawn (that of ``ax`` or ``axes`` when given).

    Examples
    --------
    >>> import numpy as np, landing
    >>> worst = {"FNTSMC": {1.0: np.array([20.0, 10.0]), 5.0: np.array([25.0, 12.0])}}
    >>> len(landing.plots.tether_fixed_time(worst, bound=[60.0, 30.0]).axes)
    2
    """
    fig, panels = several_axes(axes, 2, (1, 2), figsize=(11, 4), layout="constrained")
    total = np.ravel(bound.total if isinstance(bound, FNTSMCBounds) else bound)
    for j, ((name, sym), ax) in enumerate(zip(_TETHER_AXES, panels)):
        if not worst:
            say_why(ax, "no campaign given: no settle time to draw")
            continue
        for law, by_spread in worst.items():
            spreads = sorted(by_spread)
            ax.plot(spreads, [by_spread[k][j] for k in spreads], marker="o", label=law)
        ax.axhline(total[j], ls="--", color="tab:red", label=f"bound {total[j]:.4g} s")
        ax.set_yscale("log")
        ax.set_xlabel("initial spread (deg)")
        ax.set_ylabel(f"worst settle time of {sym} (s)")
        ax.set_title(f"Fixed-time property, {name}")
        ax.legend()
    return fig
