"""The Mars lander's figures (seed 001): trajectories, touchdown sites, final velocities,
sliding variables against their bounds, thrust, positions and mass; and the fuel-optimal
comparison's position, thrust and mass."""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING, Callable, Optional

import numpy as np

from landing.plots._common import (
    AXES,
    Labelled,
    Result,
    batched,
    first_cases,
    labelled,
    need_records,
    new_figure,
    recorded,
    result_and_bounds,
)
from landing.results import SimulationResult
from landing.theory import MSSBounds

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = [
    "trajectories_3d",
    "landing_sites",
    "final_velocities",
    "sliding_variables",
    "thrust",
    "mass",
    "positions",
    "position_and_thrust",
    "masses",
]


def trajectories_3d(result: Result, max_cases: int = 300) -> Figure:
    """3D trajectories (seed 001 Fig. 7(a)), the target marked."""
    res, _ = result_and_bounds(result)
    need_records(res)
    s = batched(recorded(res, "states"), 3)[:max_cases]
    fig = new_figure(figsize=(7, 6))
    ax = fig.add_subplot(projection="3d")
    for case in s:
        ax.plot(case[:, 0], case[:, 1], case[:, 2], lw=0.6, alpha=0.6)
    ax.scatter([0], [0], [0], color="k", marker="x", s=60, label="target")
    ax.set_xlabel("crossrange x (m)")
    ax.set_ylabel("downrange y (m)")
    ax.set_zlabel("altitude z (m)")
    ax.set_title(f"Trajectories ({s.shape[0]} cases)")
    ax.legend()
    return fig


def _radius_box(ax: Axes, r: Optional[float]) -> None:
    from matplotlib.patches import Rectangle

    if r is not None and np.isfinite(r):
        ax.add_patch(Rectangle((-r, -r), 2 * r, 2 * r, fill=False, ls="--", color="tab:red",
                               label=f"theory: |s1| <= {r:.4g} m"))


def dispersion_ellipse(points: np.ndarray, k: float, samples: int = 181) -> np.ndarray:
    """The k-sigma ellipse of 2-D ``points`` (n, 2): the curve at Mahalanobis distance k from
    their mean under their sample covariance, (samples, 2). For a 2-D normal it holds
    1 - exp(-k^2 / 2) of the cases (39.3, 86.5 and 98.9 % at k = 1, 2, 3)."""
    mean = points.mean(axis=0)
    w, v = np.linalg.eigh(np.cov(points, rowvar=False))
    a = np.linspace(0.0, 2.0 * np.pi, samples)
    circle = np.stack([np.cos(a), np.sin(a)], axis=1)
    return mean + k * (circle * np.sqrt(np.maximum(w, 0.0))) @ v.T


def landing_sites(result: Result, requirement_radius: Optional[float] = None) -> Figure:
    """Touchdown sites: where each case first crosses rz = 0 from above (the ``touchdown_position``
    metric, interpolated within the integrator step), on the XOY plane, with their 1, 2 and 3
    sigma dispersion ellipses (of the sites' 2-D covariance), the requirement's circle about the
    target when ``requirement_radius`` is given, and the theoretical s1 neighbourhood when the
    result carries bounds; and the touchdown speeds (seed 001 Fig. 8(a), (c) read at touchdown).
    Cases that never touch the ground are counted in the title."""
    res, bounds = result_and_bounds(result)
    m = res.metrics
    r = np.atleast_2d(np.asarray(m["touchdown_position"], dtype=float))[:, :3]
    speed = np.atleast_1d(np.asarray(m["touchdown_speed"], dtype=float))
    touched = np.all(np.isfinite(r), axis=1)
    radius = None if bounds is None else float(np.max(bounds.s1_radius))
    fig = new_figure(figsize=(11, 5), layout="constrained")
    ax = fig.add_subplot(1, 2, 1)
    ax.scatter(r[touched, 0], r[touched, 1], s=8, color="tab:blue", label="touchdown sites")
    ax.axhline(0, color="0.7", lw=0.5)
    ax.axvline(0, color="0.7", lw=0.5)
    ax.set_xlabel("x at touchdown (m)")
    ax.set_ylabel("y at touchdown (m)")
    ax.set_title(f"Touchdown sites (first rz = 0 crossing), XOY plane\n"
                 f"{int(touched.sum())} of {touched.size} cases touched down")
    sites = r[touched, :2]
    extent = [np.abs(sites)] if touched.any() else []
    if sites.shape[0] >= 3 and np.linalg.matrix_rank(np.cov(sites, rowvar=False)) == 2:
        for k, style in ((1, "-"), (2, "--"), (3, ":")):
            e = dispersion_ellipse(sites, k)
            ax.plot(e[:, 0], e[:, 1], style, color="tab:orange", lw=1.2,
                    label=f"{k} sigma ({100 * (1 - np.exp(-k * k / 2)):.1f} % of a 2-D normal)")
            extent.append(np.abs(e))
    if requirement_radius is not None:
        a = np.linspace(0.0, 2.0 * np.pi, 361)
        ax.plot(requirement_radius * np.cos(a), requirement_radius * np.sin(a), color="tab:red", lw=1.5,
                label=f"requirement: within {requirement_radius:g} m")
        extent.append(np.array([[requirement_radius, requirement_radius]]))
    if extent:
        span = max(float(np.max(np.concatenate(extent))), 1e-6) * 1.3
        if radius is not None and radius < 10 * span:
            _radius_box(ax, radius)
        elif radius is not None:
            # a bound ten times beyond every site says nothing about them: drawn, it would hide them
            ax.text(0.02, 0.02, f"theory: |s1| <= {radius:.4g} m, {radius / span:.0f} times the sites' extent: "
                    "not informative here (not drawn)", transform=ax.transAxes, fontsize=8)
    if touched.any():
        ax.legend(loc="upper right", fontsize="small")
    ax.set_aspect("equal", adjustable="datalim")
    ax = fig.add_subplot(1, 2, 2)
    if np.isfinite(speed).any():
        ax.hist(speed[np.isfinite(speed)], bins=30, color="tab:green")
    ax.set_xlabel("speed at touchdown (m/s)")
    ax.set_ylabel("cases")
    ax.set_title("Speed at the first rz = 0 crossing")
    return fig


def final_velocities(result: Result) -> Figure:
    """Velocities at touchdown (the ``touchdown_velocity`` metric, at the first rz = 0 crossing)
    on the XOZ and XOY planes (seed 001 Fig. 8(c), (d)); the final states' velocities only for
    the cases that never touch down (a case that hovers at its target until t_final would show
    one dot at zero)."""
    res, _ = result_and_bounds(result)
    v_end = batched(res.final_state, 2)[:, 3:6]
    v_td = np.atleast_2d(np.asarray(res.metrics["touchdown_velocity"], dtype=float))[:, :3]
    touched = np.all(np.isfinite(v_td), axis=1)
    fig = new_figure(figsize=(11, 5), layout="constrained")
    for k, (j, name) in enumerate(((2, "z"), (1, "y"))):
        ax = fig.add_subplot(1, 2, k + 1)
        if touched.any():
            ax.scatter(v_td[touched, 0], v_td[touched, j], s=8, color="tab:green",
                       label=f"at touchdown ({int(touched.sum())} cases)")
        if (~touched).any():
            ax.scatter(v_end[~touched, 0], v_end[~touched, j], s=8, marker="x", color="tab:gray",
                       label=f"at t_final, never touched down ({int((~touched).sum())})")
        ax.axhline(0, color="0.7", lw=0.5)
        ax.axvline(0, color="0.7", lw=0.5)
        ax.set_xlabel("vx (m/s)")
        ax.set_ylabel(f"v{name} (m/s)")
        ax.set_title(f"Velocities at touchdown, XO{name.upper()} plane")
        ax.legend(loc="best", fontsize="small")
    return fig


def sliding_variables(result: Result, bounds: Optional[MSSBounds] = None, max_cases: int = 300) -> Figure:
    """s1 and s2 per axis against time (seed 001 Fig. 9, 10), with the theoretical
    neighbourhoods (dashed) and the times from which they hold (dotted), when known."""
    res, b = result_and_bounds(result)
    need_records(res)
    b = bounds if bounds is not None else b
    fig = new_figure(figsize=(12, 7), layout="constrained")
    for row, (name, unit) in enumerate((("s1", "m"), ("s2", "m/s"))):
        sig = batched(res.diagnostics[name], 3)[:max_cases]
        for j in range(3):
            ax = fig.add_subplot(2, 3, 3 * row + j + 1)
            ax.plot(res.t, sig[:, :, j].T, lw=0.5, alpha=0.6)
            ax.set_title(f"{name}, {AXES[j]} axis")
            ax.set_xlabel("t (s)")
            ax.set_ylabel(f"{name} ({unit})")
            if b is not None:
                radius = float(np.ravel(b.s1_radius if name == "s1" else b.s2_radius)[j])
                when = float(np.ravel(b.settle_time if name == "s1" else b.s2_time)[j])
                span = float(np.nanmax(np.abs(sig[:, :, j]))) or 1.0
                if radius < 5 * span:
                    for sgn in (-1, 1):
                        ax.axhline(sgn * radius, ls="--", color="tab:red", lw=1)
                else:
                    ax.text(0.02, 0.95, f"radius {radius:.4g} {unit} (off the plot)", transform=ax.transAxes,
                            fontsize=8, va="top")
                if when <= res.t[-1]:
                    ax.axvline(when, ls=":", color="tab:red", lw=1)
                else:
                    ax.text(0.02, 0.85, f"bound time {when:.4g} s (beyond the run)", transform=ax.transAxes,
                            fontsize=8, va="top")
    return fig


def _per_axis(result: Result, index: Callable[[SimulationResult], np.ndarray], ylabel: str, title: str,
              max_cases: int) -> Figure:
    res, _ = result_and_bounds(result)
    need_records(res)
    res = first_cases(res, max_cases)
    fig = new_figure(figsize=(12, 3.8), layout="constrained")
    for j in range(3):
        ax = fig.add_subplot(1, 3, j + 1)
        data = index(res)[:, :, j]
        ax.plot(res.t, data.T, lw=0.5, alpha=0.6)
        ax.set_title(f"{title}, {AXES[j]} axis")
        ax.set_xlabel("t (s)")
        ax.set_ylabel(ylabel)
    return fig


def thrust(result: Result, max_cases: int = 300) -> Figure:
    """Applied thrust per axis against time (seed 001 Fig. 2(c), 12)."""
    return _per_axis(result, lambda r: batched(recorded(r, "controls"), 3), "thrust (N)", "Thrust", max_cases)


def positions(result: Result, max_cases: int = 300) -> Figure:
    """Position per axis against time (seed 001 Fig. 2(a), 11)."""
    return _per_axis(result, lambda r: batched(recorded(r, "states"), 3)[:, :, :3], "position (m)", "Position",
                     max_cases)


def mass(result: Result, max_cases: int = 300) -> Figure:
    """Lander mass against time (seed 001 Fig. 4)."""
    res, _ = result_and_bounds(result)
    need_records(res)
    m = batched(recorded(res, "states"), 3)[:max_cases, :, res.state_names.index("m")]
    fig = new_figure(figsize=(6, 4), layout="constrained")
    ax = fig.add_subplot()
    ax.plot(res.t, m.T, lw=0.6, alpha=0.7)
    ax.set_xlabel("t (s)")
    ax.set_ylabel("mass (kg)")
    ax.set_title("Mass")
    return fig


def position_and_thrust(results: Labelled, ground: bool = True) -> Figure:
    """One row per labelled single-case run: position per axis (left) and thrust per axis
    (right) against time (seed 001 Fig. 3: the optimum flown open loop without and with the
    disturbance). The altitude's first crossing of zero is marked."""
    runs = labelled(results)
    fig = new_figure(figsize=(12, 3.3 * len(runs)), layout="constrained")
    for row, (label, res) in enumerate(runs.items()):
        ax = fig.add_subplot(len(runs), 2, 2 * row + 1)
        for j in range(3):
            ax.plot(res.t, recorded(res, "states")[:, j], label=f"r{AXES[j]}")
        if ground:
            ax.axhline(0, color="0.5", lw=0.6)
        td = float(np.asarray(res.metrics["touchdown_time"]))
        if np.isfinite(td):
            ax.axvline(td, ls=":", color="tab:red", lw=1)
            ax.text(td, ax.get_ylim()[1], f" rz = 0 at {td:.2f} s", color="tab:red", fontsize=8, va="top")
        ax.set_xlabel("t (s)")
        ax.set_ylabel("position (m)")
        ax.set_title(f"Position{': ' + label if label else ''}")
        ax.legend(fontsize=8)
        ax = fig.add_subplot(len(runs), 2, 2 * row + 2)
        for j in range(3):
            ax.step(res.t, recorded(res, "controls")[:, j] / 1e3, where="post", label=f"F{AXES[j]}")
        ax.set_xlabel("t (s)")
        ax.set_ylabel("thrust (kN)")
        ax.set_title(f"Thrust{': ' + label if label else ''}")
        ax.legend(fontsize=8)
    return fig


def masses(results: Labelled, read_at: Optional[Mapping[str, float]] = None) -> Figure:
    """Mass against time for labelled single-case runs (seed 001 Fig. 4), each labelled with
    the fuel spent by ``read_at[label]`` (a time, e.g. the landing time; the end of the run if
    not given)."""
    runs = labelled(results)
    fig = new_figure(figsize=(7, 4.5), layout="constrained")
    ax = fig.add_subplot()
    for label, res in runs.items():
        m = recorded(res, "states")[:, res.state_names.index("m")]
        t_read = res.t[-1] if read_at is None or label not in read_at else float(read_at[label])
        m_read = float(np.interp(t_read, res.t, m))
        (line,) = ax.plot(res.t, m, label=f"{label}: {m[0] - m_read:.2f} kg by {t_read:.2f} s")
        ax.plot([t_read], [m_read], "o", color=line.get_color())
    ax.set_xlabel("t (s)")
    ax.set_ylabel("mass (kg)")
    ax.set_title("Mass, fuel spent to landing")
    ax.legend(fontsize=8)
    return fig
