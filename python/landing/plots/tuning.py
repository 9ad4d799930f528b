"""A tuning's figures: the search's convergence and the Pareto front (:func:`landing.tune`)."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Optional

import numpy as np

from landing.plots._common import say_why, several_axes, single_axes
from landing.tuning import TuneResult

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = ["tuning_convergence", "tuning_front"]


def tuning_convergence(result: TuneResult, *, axes: Optional[Sequence[Axes]] = None) -> Figure:
    """A :class:`landing.tuning.TuneResult`'s search: every evaluation's first objective (in its own
    unit) against its generation (feasible filled, infeasible hollow) and the best feasible so far
    (line); below, the share of each generation that is feasible.

    Parameters
    ----------
    result : landing.tuning.TuneResult
        The tuning.
    axes : sequence of matplotlib.axes.Axes, optional
        Exactly 2 Axes to draw into (objective, feasible share); by default a Figure of its own.

    Returns
    -------
    matplotlib.figure.Figure
        The figure drawn (that of ``ax`` or ``axes`` when given).

    Examples
    --------
    >>> import landing
    >>> from landing.controllers import PDSlidingMode
    >>> from landing.scenarios import Scenario
    >>> from landing.tuning import tune
    >>> s = Scenario("pd", landing.plants.DoubleIntegrator(),
    ...              PDSlidingMode(lambda_=1.0, k=0.5, switch="sat", boundary_layer=0.1),
    ...              x0=[10.0, 0, 5, 0, 0, 0], t_final=10.0, dt=0.05)
    >>> r = tune(s, {"lambda_": (0.2, 2.0), "k": (0.1, 2.0, "log")}, "mean(iae)",
    ...          ["max(peak_command) <= 5"], budget=12, seed=1, progress=False)
    >>> len(landing.plots.tuning_convergence(r).axes)
    2
    """
    fig, (ax, ax2) = several_axes(axes, 2, (2, 1), figsize=(8, 6), layout="constrained")
    if axes is None:
        ax2.sharex(ax)
    g = result.generation
    obj = result.objective_values[:, 0]
    f = result.feasible
    ax.scatter(g[f], obj[f], s=10, color="tab:blue", label="feasible")
    ax.scatter(g[~f], obj[~f], s=10, facecolors="none", edgecolors="tab:gray", label="infeasible")
    best = result.best_so_far()
    ax.plot(np.arange(best.size), best, color="tab:red", label="best feasible so far")
    finite = obj[np.isfinite(obj)]
    if finite.size and finite.min() > 0 and finite.max() / finite.min() > 100:
        ax.set_yscale("log")
    ax.set_ylabel(result.objectives[0])
    ax.set_title(f"Tuning {result.base.name}: {result.n_evaluations} evaluations, seed {result.seed}")
    ax.legend()
    gens = np.arange(int(g.max()) + 1 if g.size else 0)
    share = [float(f[g == k].mean()) for k in gens]
    ax2.bar(gens, share, color="tab:green")
    ax2.set_ylim(0, 1)
    ax2.set_xlabel("generation")
    ax2.set_ylabel("feasible share (1)")
    if not gens.size:
        say_why(ax2, "no evaluation: no generation to draw")
    return fig


def tuning_front(result: TuneResult, objectives: tuple[int, int] = (0, 1), *, ax: Optional[Axes] = None) -> Figure:
    """The Pareto front of a several-objective tuning (the front of the feasible evaluations): every
    evaluation in objective space (each objective in its own unit), the front highlighted. With one
    objective, the first objective against the total constraint violation (0: feasible), the best
    marked.

    Parameters
    ----------
    result : landing.tuning.TuneResult
        The tuning.
    objectives : tuple of (int, int), default (0, 1)
        The two objectives drawn (indices), with several.
    ax : matplotlib.axes.Axes, optional
        An Axes to draw into; by default a Figure of its own.

    Returns
    -------
    matplotlib.figure.Figure
        The figure drawn (that of ``ax`` or ``axes`` when given).

    Examples
    --------
    >>> import landing
    >>> from landing.controllers import PDSlidingMode
    >>> from landing.scenarios import Scenario
    >>> from landing.tuning import tune
    >>> s = Scenario("pd", landing.plants.DoubleIntegrator(),
    ...              PDSlidingMode(lambda_=1.0, k=0.5, switch="sat", boundary_layer=0.1),
    ...              x0=[10.0, 0, 5, 0, 0, 0], t_final=10.0, dt=0.05)
    >>> r = tune(s, {"lambda_": (0.2, 2.0), "k": (0.1, 2.0, "log")}, "mean(iae)",
    ...          ["max(peak_command) <= 5"], budget=12, seed=1, progress=False)
    >>> fig = landing.plots.tuning_front(r)
    >>> len(fig.axes), fig.axes[0].get_ylabel()
    (1, 'total constraint violation')
    """
    fig, ax = single_axes(ax, figsize=(7, 5), layout="constrained")
    v = result.objective_values
    f = result.feasible
    if v.shape[1] >= 2:
        i, j = objectives
        ax.scatter(v[~f, i], v[~f, j], s=8, facecolors="none", edgecolors="tab:gray", label="infeasible")
        ax.scatter(v[f, i], v[f, j], s=8, color="tab:blue", label="feasible")
        fr = result.front[np.argsort(v[result.front, i])]
        ax.plot(v[fr, i], v[fr, j], marker="o", color="tab:red", label="Pareto front of the evaluations")
        ax.set_xlabel(result.objectives[i])
        ax.set_ylabel(result.objectives[j])
    else:
        viol = result.violation
        ax.scatter(v[:, 0], viol, s=8, c=result.generation, cmap="viridis")
        b = result.best
        ax.scatter([v[b, 0]], [viol[b]], s=80, marker="*", color="tab:red", label="best")
        ax.set_xlabel(result.objectives[0])
        ax.set_ylabel("total constraint violation")
        if np.any(viol > 0):
            ax.set_yscale("symlog", linthresh=1e-3)
    ax.set_title(f"Tuning {result.base.name}")
    ax.legend()
    return fig
