"""What every family of figures shares: the figure factory, the result and the bounds a figure
reads, the case axis, and writing figures to files."""

from __future__ import annotations

import warnings
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any, Optional, Union, cast

import numpy as np

from landing._internal.extras import import_extra
from landing.campaign import MonteCarloResult
from landing.errors import ParameterError
from landing.results import SimulationResult
from landing.theory import MSSBounds

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = ["AXES", "Labelled", "Result", "Runs", "save_figures"]

#: Above this many cases a batch is drawn as its 5-95 % percentile band, not one line per case.
BAND_ABOVE = 50

#: The axis names of the three-axis plants.
AXES = ("x", "y", "z")
#: A run, a batch or a campaign.
Result = Union[SimulationResult, MonteCarloResult]
#: A single-case run, or several by label (comparison figures).
Labelled = Union[SimulationResult, "dict[str, SimulationResult]"]
#: A run or batch, or several by label.
Runs = Union[SimulationResult, Mapping[str, SimulationResult]]


def new_figure(**kw: Any) -> Figure:
    """A figure of its own, not pyplot's: pyplot keeps figures alive until closed, a Figure
    built directly is freed with the result it shows."""
    figure = import_extra("matplotlib.figure", "pip install matplotlib")
    return figure.Figure(**kw)


def figure_of(ax: Axes) -> Figure:
    """The Figure an Axes lies in (a subfigure's: the subfigure, as ``ax.figure``)."""
    return cast("Figure", ax.figure)


def single_axes(ax: Optional[Axes], **kw: Any) -> tuple[Figure, Axes]:
    """The Figure and Axes a single-panel figure draws on: ``ax`` and its figure when given
    (the user's own figure), else a new Figure of its own (``kw``: its size and layout) with one
    subplot."""
    if ax is not None:
        return figure_of(ax), ax
    fig = new_figure(**kw)
    return fig, fig.add_subplot()


def several_axes(axes: Optional[Sequence[Axes]], n: int, grid: tuple[int, int], **kw: Any
                 ) -> tuple[Figure, list[Axes]]:
    """The Figure and the ``n`` Axes a multi-panel figure draws on: ``axes`` (a sequence of
    exactly ``n`` Axes of one figure, refused otherwise) or a new Figure (``kw``) with an
    ``grid`` = (rows, columns) of subplots."""
    if axes is not None:
        got = list(np.ravel(np.asarray(axes, dtype=object)))
        if len(got) != n:
            raise ParameterError(f"axes: this figure draws {n} panels, got a sequence of {len(got)} Axes")
        return figure_of(got[0]), got
    fig = new_figure(**kw)
    rows, cols = grid
    return fig, [fig.add_subplot(rows, cols, j + 1) for j in range(n)]


def say_why(ax: Axes, why: str) -> None:
    """An empty panel says why it is empty instead of showing bare axes."""
    ax.text(0.5, 0.5, why, transform=ax.transAxes, ha="center", va="center", wrap=True, fontsize=9, color="0.3")
    ax.set_xticks([])
    ax.set_yticks([])


def draw_cases(ax: Axes, t: np.ndarray, data: np.ndarray, highlight: int = 0, scale: float = 1.0,
               what: str = "cases", colors: tuple[str, str] = ("tab:blue", "k"), **style: Any) -> None:
    """A batch's signal (cases, T): thin light lines for the cases (their 5-95 % percentile band
    beyond :data:`BAND_ABOVE` cases) with one legend entry, and the ``highlight`` case (the
    nominal: the first) bold over them. One case: a single line. ``colors``: the cases' and the
    nominal's (several batches on one axis)."""
    data = np.asarray(data, dtype=float).reshape(-1, len(t)) * scale
    n = data.shape[0]
    if n == 1:
        ax.plot(t, data[0], lw=1.2, **style)
        return
    k = int(highlight) % n
    if n > BAND_ABOVE:
        # after every case has stopped (a touchdown event) the band is NaN: nothing is drawn
        # there, which is right, and numpy's "All-NaN slice" warning would only alarm the user
        with warnings.catch_warnings():
            warnings.filterwarnings("ignore", "All-NaN slice", RuntimeWarning)
            lo, hi = np.nanpercentile(data, [5.0, 95.0], axis=0)
        ax.fill_between(t, lo, hi, color=colors[0], alpha=0.25, lw=0, label=f"{what} 5-95 % ({n})")
    else:
        others = np.delete(data, k, axis=0)
        lines = ax.plot(t, others.T, lw=0.5, alpha=0.35, color=colors[0])
        lines[0].set_label(f"{what} ({n})")
    nominal = "nominal" if k == 0 else f"case {k}"
    ax.plot(t, data[k], lw=1.8, color=colors[1], label=nominal if what == "cases" else f"{what}: {nominal}")


def mars_limits(result: Result, plant: Optional[Any] = None) -> tuple[Optional[np.ndarray], Optional[float]]:
    """The Mars lander's per-axis thrust limit (3,) and its thrust magnitude limit, N (None where
    it has none): of ``plant`` when given, else of the campaign's scenario."""
    if plant is None and isinstance(result, MonteCarloResult):
        plant = result.scenario.plant
    per_axis = getattr(plant, "thrust_limit", None)
    magnitude = getattr(plant, "thrust_magnitude_limit", None)
    axis_limit = None if per_axis is None else np.broadcast_to(np.asarray(per_axis, dtype=float), (3,))
    mag = None if magnitude is None else float(np.max(np.asarray(magnitude, dtype=float)))
    return axis_limit, mag


def result_and_bounds(result: Result) -> tuple[SimulationResult, Optional[MSSBounds]]:
    """The runs of a result or campaign, and the campaign's bounds (None for a run)."""
    if isinstance(result, MonteCarloResult):
        return result.result, result.bounds
    return result, None


def recorded(res: SimulationResult, name: str) -> np.ndarray:
    """``res.states`` or ``res.controls``; a campaign that did not keep them is refused."""
    value: Optional[np.ndarray] = getattr(res, name)
    if value is None:
        raise ParameterError(f"this figure needs the {name}, which the campaign did not keep (keep=...)")
    return value


def batched(a: np.ndarray, ndim: int) -> np.ndarray:
    """Add the case axis to a single case's array."""
    return a[None] if a.ndim == ndim - 1 else a


def first_cases(res: SimulationResult, k: int) -> SimulationResult:
    """The first ``k`` cases of a batch, what a figure draws (of a stored campaign, the only
    ones it reads); a single case, or a batch of at most ``k``, as it is."""
    return res.cases(0, k) if res.final_state.ndim == 2 and res.n_cases > k else res


def need_records(res: SimulationResult) -> None:
    """Refuses a result that recorded nothing but its final states."""
    if res.t.size == 0:
        raise ParameterError("this figure needs recorded trajectories: run with record_every >= 1")


def save_figures(figures: Mapping[str, Figure], folder: Union[str, Path], dpi: int = 120) -> list[Path]:
    """Writes figures (name -> Figure) as ``folder/name.png`` and closes them.

    Parameters
    ----------
    figures : mapping of str to matplotlib.figure.Figure
        The figures by name.
    folder : str or pathlib.Path
        The folder (made if missing).
    dpi : int, default 120
        The images' resolution (dots per inch).

    Returns
    -------
    list of pathlib.Path
        The files written.

    Examples
    --------
    >>> import tempfile, matplotlib
    >>> matplotlib.use("Agg")
    >>> import landing
    >>> scenario = landing.scenarios.preset("mars_monte_carlo").replace(t_final=5.0)
    >>> mc = landing.monte_carlo(scenario, n=8, seed=1)
    >>> paths = landing.plots.save_figures({"mass": landing.plots.mass(mc)}, tempfile.mkdtemp())
    >>> [p.name for p in paths]
    ['mass.png']
    """
    plt = import_extra("matplotlib.pyplot", "pip install matplotlib")
    out = Path(folder)
    out.mkdir(parents=True, exist_ok=True)
    written = []
    for name, fig in figures.items():
        path = out / f"{name}.png"
        fig.savefig(path, dpi=dpi)
        plt.close(fig)
        written.append(path)
    return written


def labelled(results: Labelled) -> dict[str, SimulationResult]:
    """Single-case runs by label (one run: the empty label), each with its records."""
    if isinstance(results, SimulationResult):
        return {"": results}
    out = dict(results)
    for res in out.values():
        need_records(res)
        if res.states is None or res.states.ndim != 2:
            raise ParameterError("comparison figures take single cases: pass result[i] for case i")
    return out


def named_runs(results: Runs) -> dict[str, SimulationResult]:
    """Runs by label (one run: the empty label)."""
    if isinstance(results, SimulationResult):
        return {"": results}
    return dict(results)


