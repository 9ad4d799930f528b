"""Comparisons of single-case runs, one line per labelled run (the asteroid papers' figures,
seeds 000 and 002): tracking errors, commands, a law's diagnostics, the fuzzy blend and the
trajectory against its reference."""

from __future__ import annotations

from typing import TYPE_CHECKING, Optional

from landing.errors import ParameterError
from landing.plots._common import AXES, Labelled, axis_grid, labelled, need_records, new_figure, recorded
from landing.reference import Reference
from landing.results import SimulationResult

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.figure import Figure

__all__ = ["tracking_errors", "commands", "diagnostic", "blend_coefficients", "trajectory_with_reference"]


def tracking_errors(results: Labelled, reference: Optional[Reference] = None, velocity: bool = False) -> Figure:
    """Position (or velocity) tracking error per axis against time, one line per labelled run
    (seed 000 Fig. 11, seed 002 Fig. 7). ``reference``: the target tracked (default the
    origin)."""
    runs = labelled(results)
    fig = new_figure(figsize=(12, 3.8), layout="constrained")
    first = next(iter(runs.values()))
    n = recorded(first, "controls").shape[-1]
    axes = axis_grid(fig, n)
    for label, res in runs.items():
        q = recorded(res, "states")[:, n:2 * n] if velocity else recorded(res, "states")[:, :n]
        if reference is not None:
            p, v, _ = reference.evaluate(res.t, axes=n)
            q = q - (v if velocity else p)
        for j, ax in enumerate(axes):
            ax.plot(res.t, q[:, j], lw=0.9, label=label or None)
    for j, ax in enumerate(axes):
        ax.set_title(f"{'velocity' if velocity else 'position'} error, {AXES[j] if n == 3 else j}")
        ax.set_xlabel("t (s)")
        ax.axhline(0, color="0.7", lw=0.5)
    if len(runs) > 1:
        axes[0].legend()
    return fig


def commands(results: Labelled, ylabel: str = "command") -> Figure:
    """Applied command per axis against time, one line per labelled run (seed 000 Fig. 5, 10;
    seed 002 Fig. 9, 10)."""
    runs = labelled(results)
    n = recorded(next(iter(runs.values())), "controls").shape[-1]
    fig = new_figure(figsize=(12, 3.8), layout="constrained")
    axes = axis_grid(fig, n)
    for label, res in runs.items():
        for j, ax in enumerate(axes):
            ax.plot(res.t, recorded(res, "controls")[:, j], lw=0.7, label=label or None)
    for j, ax in enumerate(axes):
        ax.set_title(f"{res.control_names[j]}")
        ax.set_xlabel("t (s)")
        ax.set_ylabel(ylabel)
    if len(runs) > 1:
        axes[0].legend()
    return fig


def diagnostic(results: Labelled, name: str = "s") -> Figure:
    """A law's recorded signal (a sliding variable, the fuzzy term...) per axis against time,
    one line per labelled run that has it (seed 000 Fig. 6, seed 002 Fig. 8)."""
    runs = {k: v for k, v in labelled(results).items() if name in v.diagnostics}
    if not runs:
        raise ParameterError(f"no run recorded the diagnostic {name!r}")
    first = next(iter(runs.values())).diagnostics[name]
    n = first.shape[-1] if first.ndim == 2 else 1
    fig = new_figure(figsize=(12 if n > 1 else 6, 3.8), layout="constrained")
    axes = axis_grid(fig, n)
    for label, res in runs.items():
        sig = res.diagnostics[name].reshape(res.t.size, n)
        for j, ax in enumerate(axes):
            ax.plot(res.t, sig[:, j], lw=0.8, label=label or None)
    for j, ax in enumerate(axes):
        ax.set_title(name if n == 1 else f"{name}, {AXES[j] if n == 3 else j}")
        ax.set_xlabel("t (s)")
    if len(runs) > 1:
        axes[0].legend()
    return fig


def blend_coefficients(result: SimulationResult) -> Figure:
    """The fuzzy blend a(D), b(D) of FuzzyFastTerminalSMC against time (seed 000 Fig. 7)."""
    need_records(result)
    fig = new_figure(figsize=(6, 4), layout="constrained")
    ax = fig.add_subplot()
    for name in ("a", "b"):
        ax.plot(result.t, result.diagnostics[name], label=name)
    ax.set_xlabel("t (s)")
    ax.set_ylim(-0.05, 1.05)
    ax.legend()
    ax.set_title("Fuzzy blending coefficients")
    return fig


def trajectory_with_reference(results: Labelled, reference: Optional[Reference] = None) -> Figure:
    """3D trajectories of labelled runs with the reference they track (seed 000 Fig. 12, seed 002
    Fig. 6)."""
    runs = labelled(results)
    fig = new_figure(figsize=(7, 6))
    ax = fig.add_subplot(projection="3d")
    for label, res in runs.items():
        states = recorded(res, "states")
        ax.plot(states[:, 0], states[:, 1], states[:, 2], lw=1.0, label=label or "trajectory")
    if reference is not None:
        t = next(iter(runs.values())).t
        p, _, _ = reference.evaluate(t)
        ax.plot(p[:, 0], p[:, 1], p[:, 2], "k--", lw=0.8, label="reference")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_zlabel("z (m)")
    ax.legend()
    return fig
