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
    """The ``k`` dispersed quantities with the largest partial rank correlation (PRCC) with
    ``metric``, largest on top, as horizontal bars (Spearman's coefficient marked on each):
    which dispersion drives the metric, and in which direction. Takes a campaign (its
    :meth:`~landing.MonteCarloResult.sensitivity`) or the correlations; draws into ``ax`` if
    given and returns its Figure."""
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
