"""Which dispersed quantity drives a metric: the tornado plot of a campaign's rank correlations
(:mod:`landing.campaign.sensitivity`)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Optional, Union

import numpy as np

from landing.campaign import MonteCarloResult
from landing.campaign.sensitivity import RankCorrelations
from landing.plots._common import single_axes

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = ["tornado"]


def tornado(result: Union[MonteCarloResult, RankCorrelations], metric: str, *, k: int = 10,
            ax: Optional[Axes] = None) -> Figure:
    """The ``k`` dispersed quantities with the largest partial rank correlation (PRCC, dimensionless)
    with ``metric``, largest on top, as horizontal bars (Spearman's coefficient marked on each):
    which dispersion drives the metric, and in which direction.

    Parameters
    ----------
    result : landing.MonteCarloResult or landing.campaign.RankCorrelations
        A campaign (its :meth:`~landing.MonteCarloResult.sensitivity`) or the correlations.
    metric : str
        The metric (per-axis ones split, e.g. ``"final_error_x"``).
    k : int, default 10
        The most quantities drawn.
    ax : matplotlib.axes.Axes, optional
        An Axes to draw into; by default a Figure of its own.

    Returns
    -------
    matplotlib.figure.Figure
        The figure drawn (that of ``ax`` or ``axes`` when given).

    Examples
    --------
    >>> import landing
    >>> scenario = landing.scenarios.preset("mars_monte_carlo").replace(t_final=5.0)
    >>> mc = landing.monte_carlo(scenario, n=8, seed=1)
    >>> fig = landing.plots.tornado(mc, "fuel_used", k=3)
    >>> len(fig.axes), fig.axes[0].get_title()
    (1, 'What drives fuel_used')
    """
    corr = result.sensitivity([metric]) if isinstance(result, MonteCarloResult) else result
    top = corr.drivers(metric, k)[::-1]  # largest last: on top of the barh
    fig, ax = single_axes(ax, figsize=(7, 0.45 * len(top) + 1.5), layout="constrained")
    names = [t[0] for t in top]
    prcc = np.array([t[1] for t in top])
    spearman = np.array([t[2] for t in top])
    y = np.arange(len(top))
    ax.barh(y, prcc, color=np.where(prcc >= 0, "tab:red", "tab:blue"), label="partial rank correlation")
    ax.scatter(spearman, y, marker="|", s=200, color="black", label="Spearman", zorder=3)
    ax.set_yticks(y, names)
    ax.axvline(0.0, color="black", linewidth=0.8)
    ax.set_xlim(-1.05, 1.05)
    ax.set_xlabel(f"rank correlation with {metric} (1)")
    ax.set_ylabel("dispersed quantity")
    ax.set_title(f"What drives {metric}")
    ax.legend(loc="lower right", fontsize="small")
    return fig
