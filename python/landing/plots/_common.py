"""What every family of figures shares: the figure factory, the result and the bounds a figure
reads, the case axis, and writing figures to files."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any, Optional, Union

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
    """Writes figures (name -> Figure) as ``folder/name.png`` and closes them."""
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


def axis_grid(fig: Figure, n: int) -> list[Axes]:
    """``n`` subplots side by side."""
    return [fig.add_subplot(1, n, j + 1) for j in range(n)]


def named_runs(results: Runs) -> dict[str, SimulationResult]:
    """Runs by label (one run: the empty label)."""
    if isinstance(results, SimulationResult):
        return {"": results}
    return dict(results)


