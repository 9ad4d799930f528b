"""Comparisons of single-case runs, one line per labelled run (the figures of the fuzzy
fast-terminal asteroid paper and the fuzzy variable-rate asteroid paper): tracking errors,
commands, a law's diagnostics, the fuzzy blend and the trajectory against its reference."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any, Optional

import numpy as np

from landing.errors import ParameterError
from landing.plants import DoubleIntegrator, Plant, SmallBody
from landing.plots._common import (
    AXES,
    Labelled,
    batched,
    draw_cases,
    figure_of,
    first_cases,
    labelled,
    need_records,
    new_figure,
    recorded,
    say_why,
    several_axes,
    single_axes,
)
from landing.reference import Reference
from landing.results import SimulationResult

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = ["tracking_errors", "commands", "diagnostic", "blend_coefficients", "trajectory_with_reference"]

#: The most cases of a lone batch drawn (its first).
MAX_CASES = 300


def _runs(results: Labelled) -> dict[str, SimulationResult]:
    """Labelled single-case runs, or a lone run or batch (its first :data:`MAX_CASES` cases)."""
    runs = labelled(results)
    if isinstance(results, SimulationResult):
        need_records(results)
        runs = {"": first_cases(results, MAX_CASES)}
    return runs


def _draw(ax: Axes, label: str, t: np.ndarray, data: np.ndarray, highlight: int, lw: float = 1.0,
          colors: tuple[str, str] = ("tab:blue", "k")) -> None:
    """One run's signal (cases, T): a single case as one line (labelled), a batch as thin cases
    about its bold nominal."""
    if data.shape[0] == 1:
        ax.plot(t, data[0], lw=lw, label=label or None)
    else:
        draw_cases(ax, t, data, highlight, what=label or "cases", colors=colors)


def tracking_errors(results: Labelled, reference: Optional[Reference] = None, velocity: bool = False, *,
                    highlight: int = 0, axes: Optional[Sequence[Axes]] = None) -> Figure:
    """Position (m) or velocity (m/s) tracking error per axis against time, s, one line per labelled
    run (the fuzzy fast-terminal asteroid paper's Fig. 11, the fuzzy variable-rate asteroid
    paper's Fig. 7). A batch's cases thin, the nominal (case ``highlight``) bold.

    Parameters
    ----------
    results : landing.SimulationResult or dict of str to landing.SimulationResult
        Single-case runs by label (one line each), or a lone run or batch (its first 300 cases).
    reference : landing.reference.Reference, optional
        The target tracked (default the origin).
    velocity : bool, default False
        Whether the velocity error is drawn instead of the position error.
    highlight : int, default 0
        The case drawn bold (the nominal).
    axes : sequence of matplotlib.axes.Axes, optional
        One Axes per axis of the plant to draw into; by default a Figure of its own.

    Returns
    -------
    matplotlib.figure.Figure
        The figure drawn (that of ``ax`` or ``axes`` when given).

    Examples
    --------
    >>> import landing
    >>> scenario = landing.scenarios.preset("seed000_fuzzy_ftsmc_tanh").replace(t_final=2.0)
    >>> run = scenario.simulate()
    >>> fig = landing.plots.tracking_errors({"fuzzy FTSMC": run}, scenario.reference)
    >>> type(fig).__name__, len(fig.axes)
    ('Figure', 3)
    """
    runs = _runs(results)
    first = next(iter(runs.values()))
    n = recorded(first, "controls").shape[-1]
    fig, panels = several_axes(axes, n, (1, n), figsize=(12, 3.8), layout="constrained")
    for label, res in runs.items():
        states = batched(recorded(res, "states"), 3)
        q = states[:, :, n:2 * n] if velocity else states[:, :, :n]
        if reference is not None:
            p, v, _ = reference.evaluate(res.t, axes=n)
            q = q - (v if velocity else p)
        for j, ax in enumerate(panels):
            _draw(ax, label, res.t, q[:, :, j], highlight, lw=0.9)
    for j, ax in enumerate(panels):
        ax.set_title(f"{'velocity' if velocity else 'position'} error, {AXES[j] if n == 3 else j}")
        ax.set_xlabel("t (s)")
        ax.set_ylabel("velocity error (m/s)" if velocity else "position error (m)")
        ax.axhline(0, color="0.7", lw=0.5)
    if panels[0].get_legend_handles_labels()[0]:
        panels[0].legend()
    return fig


def commands(results: Labelled, ylabel: Optional[str] = None, *, plant: Optional[Plant] = None,
             highlight: int = 0, axes: Optional[Sequence[Axes]] = None) -> Figure:
    """Applied command per axis against time, s, one line per labelled run (the fuzzy fast-terminal
    asteroid paper's Fig. 5, 10; the fuzzy variable-rate asteroid paper's Fig. 9, 10). The
    acceleration limits (m/s^2) of a small body's or a double integrator's ``plant`` are drawn. A
    batch's cases thin, the nominal (case ``highlight``) bold.

    Parameters
    ----------
    results : landing.SimulationResult or dict of str to landing.SimulationResult
        Single-case runs by label (one line each), or a lone run or batch (its first 300 cases).
    ylabel : str, optional
        The command and its unit, e.g. "u (m/s^2)" (by default that of ``plant``'s command when
        known).
    plant : landing.plants.Plant, optional
        The plant whose command limits are drawn.
    highlight : int, default 0
        The case drawn bold (the nominal).
    axes : sequence of matplotlib.axes.Axes, optional
        One Axes per command to draw into; by default a Figure of its own.

    Returns
    -------
    matplotlib.figure.Figure
        The figure drawn (that of ``ax`` or ``axes`` when given).

    Examples
    --------
    >>> import landing
    >>> scenario = landing.scenarios.preset("seed000_fuzzy_ftsmc_tanh").replace(t_final=2.0)
    >>> run = scenario.simulate()
    >>> fig = landing.plots.commands({"fuzzy FTSMC": run}, plant=scenario.plant)
    >>> len(fig.axes)
    3
    """
    runs = _runs(results)
    n = recorded(next(iter(runs.values())), "controls").shape[-1]
    fig, panels = several_axes(axes, n, (1, n), figsize=(12, 3.8), layout="constrained")
    accelerating = isinstance(plant, (DoubleIntegrator, SmallBody))
    if ylabel is None:
        ylabel = "u (m/s^2)" if accelerating else "command (the plant's units)"
    for label, res in runs.items():
        u = batched(recorded(res, "controls"), 3)
        for j, ax in enumerate(panels):
            _draw(ax, label, res.t, u[:, :, j], highlight, lw=0.7)
    limits = []
    if accelerating:
        per_axis = getattr(plant, "acceleration_limit", None)
        magnitude = getattr(plant, "acceleration_magnitude_limit", None)
        limits = [(np.broadcast_to(np.asarray(v, dtype=float), (n,)), style, what)
                  for v, style, what in ((per_axis, "--", "axis limit"), (magnitude, "-.", "|u| limit"))
                  if v is not None]
    for j, ax in enumerate(panels):
        ax.set_title(f"{res.control_names[j]}")
        ax.set_xlabel("t (s)")
        ax.set_ylabel(ylabel)
        for value, style, what in limits:
            if np.isfinite(value[j]):
                for sgn in (1, -1):
                    ax.axhline(sgn * value[j], ls=style, color="tab:red", lw=1,
                               label=f"{what} {value[j]:.4g} m/s^2" if sgn > 0 else None)
    if panels[0].get_legend_handles_labels()[0]:
        panels[0].legend()
    return fig


def diagnostic(results: Labelled, name: str = "s", unit: str = "", *, highlight: int = 0,
               axes: Optional[Sequence[Axes]] = None) -> Figure:
    """A law's recorded signal (a sliding variable, the fuzzy term...) per axis against time, s, one
    line per labelled run that has it (the fuzzy fast-terminal asteroid paper's Fig. 6, the fuzzy
    variable-rate asteroid paper's Fig. 8).

    Parameters
    ----------
    results : landing.SimulationResult or dict of str to landing.SimulationResult
        Single-case runs by label (one line each), or a lone run or batch (its first 300 cases).
    name : str, default "s"
        The diagnostic's name.
    unit : str, default ""
        Its unit for the axis label (none: the law's own units, e.g. m/s for a sliding variable
        on velocity).
    highlight : int, default 0
        The case drawn bold (the nominal).
    axes : sequence of matplotlib.axes.Axes, optional
        One Axes per component to draw into; by default a Figure of its own.

    Returns
    -------
    matplotlib.figure.Figure
        The figure drawn (that of ``ax`` or ``axes`` when given).

    Examples
    --------
    >>> import landing
    >>> scenario = landing.scenarios.preset("seed000_fuzzy_ftsmc_tanh").replace(t_final=2.0)
    >>> run = scenario.simulate()
    >>> len(landing.plots.diagnostic({"fuzzy FTSMC": run}, "s", "m/s").axes)
    3
    """
    runs = {k: v for k, v in _runs(results).items() if name in v.diagnostics}
    if not runs:
        raise ParameterError(f"no run recorded the diagnostic {name!r}")
    some = next(iter(runs.values()))
    first = np.asarray(some.diagnostics[name])
    n = 1 if first.shape[-1] == some.t.size else first.shape[-1]
    fig, panels = several_axes(axes, n, (1, n), figsize=(12 if n > 1 else 6, 3.8), layout="constrained")
    for label, res in runs.items():
        sig = np.asarray(res.diagnostics[name]).reshape(-1, res.t.size, n)
        for j, ax in enumerate(panels):
            _draw(ax, label, res.t, sig[:, :, j], highlight, lw=0.8)
    for j, ax in enumerate(panels):
        ax.set_title(name if n == 1 else f"{name}, {AXES[j] if n == 3 else j}")
        ax.set_xlabel("t (s)")
        ax.set_ylabel(f"{name} ({unit})" if unit else f"{name} (the law's units)")
    if panels[0].get_legend_handles_labels()[0]:
        panels[0].legend()
    return fig


def blend_coefficients(result: SimulationResult, *, highlight: int = 0, ax: Optional[Axes] = None) -> Figure:
    """The fuzzy blend a(D), b(D) (dimensionless) of FuzzyFastTerminalSMC against time, s (the fuzzy
    fast-terminal asteroid paper's Fig. 7).

    Parameters
    ----------
    result : landing.SimulationResult
        A run of FuzzyFastTerminalSMC (its diagnostics ``a`` and ``b``).
    highlight : int, default 0
        The case drawn bold (the nominal).
    ax : matplotlib.axes.Axes, optional
        An Axes to draw into; by default a Figure of its own.

    Returns
    -------
    matplotlib.figure.Figure
        The figure drawn (that of ``ax`` or ``axes`` when given).

    Examples
    --------
    >>> import landing
    >>> scenario = landing.scenarios.preset("seed000_fuzzy_ftsmc_tanh").replace(t_final=2.0)
    >>> run = scenario.simulate()
    >>> len(landing.plots.blend_coefficients(run).axes)
    1
    """
    need_records(result)
    fig, ax = single_axes(ax, figsize=(6, 4), layout="constrained")
    missing = [name for name in ("a", "b") if name not in result.diagnostics]
    if missing:
        say_why(ax, f"the run did not record {' and '.join(missing)} (a FuzzyFastTerminalSMC diagnostic)")
        return fig
    batch = first_cases(result, MAX_CASES)
    for name, colors in (("a", ("tab:blue", "navy")), ("b", ("tab:orange", "saddlebrown"))):
        _draw(ax, name, batch.t, np.asarray(batch.diagnostics[name]).reshape(-1, batch.t.size), highlight,
              lw=1.5, colors=colors)
    ax.set_xlabel("t (s)")
    ax.set_ylabel("coefficient (1)")
    ax.set_ylim(-0.05, 1.05)
    ax.legend()
    ax.set_title("Fuzzy blending coefficients")
    return fig


def trajectory_with_reference(results: Labelled, reference: Optional[Reference] = None, *, highlight: int = 0,
                              ax: Optional[Any] = None) -> Figure:
    """3D trajectories, m, of labelled runs with the reference they track (the fuzzy fast-terminal
    asteroid paper's Fig. 12, the fuzzy variable-rate asteroid paper's Fig. 6).

    Parameters
    ----------
    results : landing.SimulationResult or dict of str to landing.SimulationResult
        Single-case runs by label (one line each), or a lone run or batch (its first 300 cases).
    reference : landing.reference.Reference, optional
        The reference drawn.
    highlight : int, default 0
        The case drawn bold (the nominal).
    ax : mpl_toolkits.mplot3d.axes3d.Axes3D, optional
        A 3D Axes to draw into; by default a Figure of its own.

    Returns
    -------
    matplotlib.figure.Figure
        The figure drawn (that of ``ax`` or ``axes`` when given).

    Examples
    --------
    >>> import landing
    >>> scenario = landing.scenarios.preset("seed000_fuzzy_ftsmc_tanh").replace(t_final=2.0)
    >>> run = scenario.simulate()
    >>> len(landing.plots.trajectory_with_reference({"fuzzy FTSMC": run}, scenario.reference).axes)
    1
    """
    runs = _runs(results)
    if ax is None:
        fig = new_figure(figsize=(7, 6))
        ax = fig.add_subplot(projection="3d")
    else:
        fig = figure_of(ax)
    for label, res in runs.items():
        states = batched(recorded(res, "states"), 3)
        k = int(highlight) % states.shape[0]
        for i in range(states.shape[0]):
            if i != k:
                ax.plot(states[i, :, 0], states[i, :, 1], states[i, :, 2], lw=0.5, alpha=0.35, color="tab:blue",
                        label=f"cases ({states.shape[0]})" if i == (1 if k == 0 else 0) else None)
        ax.plot(states[k, :, 0], states[k, :, 1], states[k, :, 2], lw=1.8 if states.shape[0] > 1 else 1.0,
                color="k" if states.shape[0] > 1 else None,
                label=label or ("trajectory" if states.shape[0] == 1 else "nominal" if k == 0 else f"case {k}"))
    if reference is not None:
        t = next(iter(runs.values())).t
        p, _, _ = reference.evaluate(t)
        ax.plot(p[:, 0], p[:, 1], p[:, 2], "k--", lw=0.8, label="reference")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_zlabel("z (m)")
    ax.legend()
    return fig
