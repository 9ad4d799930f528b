"""The Mars lander's figures (the Mars fixed-time guidance paper's): trajectories, touchdown
sites, final velocities, sliding variables against their bounds, thrust, positions and mass; and
the fuel-optimal comparison's position, thrust and mass."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any, Callable, Optional

import numpy as np

from landing.plants import MarsLander
from landing.plots._common import (
    AXES,
    BAND_ABOVE,
    Labelled,
    Result,
    batched,
    draw_cases,
    figure_of,
    first_cases,
    labelled,
    mars_limits,
    need_records,
    new_figure,
    recorded,
    result_and_bounds,
    say_why,
    several_axes,
    single_axes,
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


def trajectories_3d(result: Result, max_cases: int = 300, *, highlight: int = 0, ax: Optional[Any] = None) -> Figure:
    """3D trajectories, m (the Mars fixed-time guidance paper's Fig. 7(a)): the cases thin, the
    nominal (case ``highlight``) bold, the target marked and the ground (z = 0) outlined.

    Parameters
    ----------
    result : landing.SimulationResult or landing.MonteCarloResult
        A run, a batch or a campaign (a campaign's bounds and thrust limits are drawn).
    max_cases : int, default 300
        The most cases drawn (the first ones).
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
    >>> scenario = landing.scenarios.preset("mars_monte_carlo").replace(t_final=5.0)
    >>> mc = landing.monte_carlo(scenario, n=8, seed=1)
    >>> fig = landing.plots.trajectories_3d(mc)
    >>> type(fig).__name__, len(fig.axes)
    ('Figure', 1)
    """
    res, _ = result_and_bounds(result)
    need_records(res)
    s = batched(recorded(res, "states"), 3)[:max_cases]
    if ax is None:
        fig = new_figure(figsize=(7, 6))
        ax = fig.add_subplot(projection="3d")
    else:
        fig = figure_of(ax)
    k = int(highlight) % s.shape[0]
    lw = 0.4 if s.shape[0] > BAND_ABOVE else 0.6
    first = 1 if k == 0 else 0
    for i, case in enumerate(s):
        if i != k:
            ax.plot(case[:, 0], case[:, 1], case[:, 2], label=f"cases ({s.shape[0]})" if i == first else None,
                    lw=lw, alpha=0.4, color="tab:blue")
    ax.plot(s[k, :, 0], s[k, :, 1], s[k, :, 2], lw=1.8, color="k",
            label=("nominal" if k == 0 else f"case {k}") if s.shape[0] > 1 else "trajectory")
    lo = np.minimum(np.nanmin(s[:, :, :2], axis=(0, 1)), 0.0)
    hi = np.maximum(np.nanmax(s[:, :, :2], axis=(0, 1)), 0.0)
    ax.plot([lo[0], hi[0], hi[0], lo[0], lo[0]], [lo[1], lo[1], hi[1], hi[1], lo[1]], [0.0] * 5, color="0.5",
            lw=0.8, label="ground (z = 0)")
    ax.scatter([0], [0], [0], color="tab:red", marker="x", s=60, label="target")
    ax.set_xlabel("crossrange x (m)")
    ax.set_ylabel("downrange y (m)")
    ax.set_zlabel("altitude z (m)")
    ax.set_title(f"Trajectories ({s.shape[0]} cases)")
    ax.legend(fontsize="small")
    return fig


def _radius_box(ax: Axes, r: Optional[float]) -> None:
    from matplotlib.patches import Rectangle

    if r is not None and np.isfinite(r):
        ax.add_patch(Rectangle((-r, -r), 2 * r, 2 * r, fill=False, ls="--", color="tab:red",
                               label=f"theory: |s1| <= {r:.4g} m"))


def dispersion_ellipse(points: np.ndarray, k: float, samples: int = 181) -> np.ndarray:
    """The k-sigma ellipse of 2-D ``points`` (n, 2): the curve at Mahalanobis distance k from their
    mean under their sample covariance, (samples, 2). For a 2-D normal it holds 1 - exp(-k^2 / 2)
    of the cases (39.3, 86.5 and 98.9 % at k = 1, 2, 3).

    Parameters
    ----------
    points : numpy.ndarray
        (n, 2) points (m for touchdown sites).
    k : float
        The Mahalanobis distance.
    samples : int, default 181
        The points of the curve.

    Returns
    -------
    numpy.ndarray
        (samples, 2), in the points' unit.

    Examples
    --------
    >>> import numpy as np
    >>> from landing.plots.mars import dispersion_ellipse
    >>> points = np.array([[1.0, 0.0], [-1.0, 0.0], [0.0, 2.0], [0.0, -2.0]])
    >>> e = dispersion_ellipse(points, 1.0, samples=5)
    >>> e.shape, bool(np.allclose(np.abs(e).max(axis=0), np.sqrt(np.diag(np.cov(points, rowvar=False)))))
    ((5, 2), True)
    """
    mean = points.mean(axis=0)
    w, v = np.linalg.eigh(np.cov(points, rowvar=False))
    a = np.linspace(0.0, 2.0 * np.pi, samples)
    circle = np.stack([np.cos(a), np.sin(a)], axis=1)
    return mean + k * (circle * np.sqrt(np.maximum(w, 0.0))) @ v.T


def landing_sites(result: Result, requirement_radius: Optional[float] = None, *, highlight: int = 0,
                  axes: Optional[Sequence[Axes]] = None) -> Figure:
    """Touchdown sites, m: where each case first crosses rz = 0 from above (the
    ``touchdown_position`` metric, interpolated within the integrator step), on the XOY plane,
    with their 1, 2 and 3 sigma dispersion ellipses (of the sites' 2-D covariance), the
    requirement's circle about the target when ``requirement_radius`` is given, and the
    theoretical s1 neighbourhood when the result carries bounds; and the touchdown speeds, m/s
    (the Mars fixed-time guidance paper's Fig. 8(a), (c) read at touchdown). Cases that never
    touch the ground are counted in the title; the nominal's site (case ``highlight``) is marked.

    Parameters
    ----------
    result : landing.SimulationResult or landing.MonteCarloResult
        A run, a batch or a campaign (a campaign's bounds and thrust limits are drawn).
    requirement_radius : float, optional
        The touchdown requirement's radius about the target (m).
    highlight : int, default 0
        The case drawn bold (the nominal).
    axes : sequence of matplotlib.axes.Axes, optional
        Exactly 2 Axes to draw into (sites, speeds); by default a Figure of its own.

    Returns
    -------
    matplotlib.figure.Figure
        The figure drawn (that of ``ax`` or ``axes`` when given).

    Examples
    --------
    >>> import landing
    >>> scenario = landing.scenarios.preset("mars_monte_carlo").replace(t_final=5.0)
    >>> mc = landing.monte_carlo(scenario, n=8, seed=1)
    >>> fig = landing.plots.landing_sites(mc, requirement_radius=50.0)
    >>> len(fig.axes)
    2
    """
    res, bounds = result_and_bounds(result)
    m = res.metrics
    r = np.atleast_2d(np.asarray(m["touchdown_position"], dtype=float))[:, :3]
    speed = np.atleast_1d(np.asarray(m["touchdown_speed"], dtype=float))
    touched = np.all(np.isfinite(r), axis=1)
    radius = None if bounds is None else float(np.max(bounds.s1_radius))
    fig, (ax, ax_speed) = several_axes(axes, 2, (1, 2), figsize=(11, 5), layout="constrained")
    if touched.any():
        ax.scatter(r[touched, 0], r[touched, 1], s=8, color="tab:blue", label="touchdown sites")
    k = int(highlight) % touched.size
    if touched.size > 1 and touched[k]:
        ax.scatter(r[k:k + 1, 0], r[k:k + 1, 1], s=60, marker="D", facecolors="none", edgecolors="k", lw=1.5,
                   label="nominal" if k == 0 else f"case {k}")
    if touched.any():
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
    else:
        say_why(ax, f"no case touched down (rz did not cross 0 by t = {res.t[-1]:.4g} s):\nno site to draw"
                if res.t.size else "no case touched down (rz did not cross 0):\nno site to draw")
    ax.set_aspect("equal", adjustable="datalim")
    ax = ax_speed
    if np.isfinite(speed).any():
        ax.hist(speed[np.isfinite(speed)], bins=30, color="tab:green")
    else:
        say_why(ax, "no case touched down:\nno touchdown speed to draw")
    ax.set_xlabel("speed at touchdown (m/s)")
    ax.set_ylabel("cases")
    ax.set_title("Speed at the first rz = 0 crossing")
    return fig


def final_velocities(result: Result, *, highlight: int = 0, axes: Optional[Sequence[Axes]] = None) -> Figure:
    """Velocities at touchdown, m/s (the ``touchdown_velocity`` metric, at the first rz = 0
    crossing) on the XOZ and XOY planes (the Mars fixed-time guidance paper's Fig. 8(c), (d));
    the final states' velocities only for the cases that never touch down (a case that hovers at
    its target until t_final would show one dot at zero). The nominal (case ``highlight``) is
    marked.

    Parameters
    ----------
    result : landing.SimulationResult or landing.MonteCarloResult
        A run, a batch or a campaign (a campaign's bounds and thrust limits are drawn).
    highlight : int, default 0
        The case drawn bold (the nominal).
    axes : sequence of matplotlib.axes.Axes, optional
        Exactly 2 Axes to draw into (XOZ, XOY); by default a Figure of its own.

    Returns
    -------
    matplotlib.figure.Figure
        The figure drawn (that of ``ax`` or ``axes`` when given).

    Examples
    --------
    >>> import landing
    >>> scenario = landing.scenarios.preset("mars_monte_carlo").replace(t_final=5.0)
    >>> mc = landing.monte_carlo(scenario, n=8, seed=1)
    >>> len(landing.plots.final_velocities(mc).axes)
    2
    """
    res, _ = result_and_bounds(result)
    v_end = batched(res.final_state, 2)[:, 3:6]
    v_td = np.atleast_2d(np.asarray(res.metrics["touchdown_velocity"], dtype=float))[:, :3]
    touched = np.all(np.isfinite(v_td), axis=1)
    fig, panels = several_axes(axes, 2, (1, 2), figsize=(11, 5), layout="constrained")
    for ax, (j, name) in zip(panels, ((2, "z"), (1, "y"))):
        if touched.any():
            ax.scatter(v_td[touched, 0], v_td[touched, j], s=8, color="tab:green",
                       label=f"at touchdown ({int(touched.sum())} cases)")
        if (~touched).any():
            ax.scatter(v_end[~touched, 0], v_end[~touched, j], s=8, marker="x", color="tab:gray",
                       label=f"at t_final, never touched down ({int((~touched).sum())})")
        k = int(highlight) % touched.size
        if touched.size > 1:
            v = v_td if touched[k] else v_end
            ax.scatter(v[k:k + 1, 0], v[k:k + 1, j], s=60, marker="D", facecolors="none", edgecolors="k", lw=1.5,
                       label="nominal" if k == 0 else f"case {k}")
        ax.axhline(0, color="0.7", lw=0.5)
        ax.axvline(0, color="0.7", lw=0.5)
        ax.set_xlabel("vx (m/s)")
        ax.set_ylabel(f"v{name} (m/s)")
        ax.ticklabel_format(style="sci", scilimits=(-3, 4))  # tiny velocities: no long, overlapping ticks
        ax.set_title(f"Velocities at touchdown, XO{name.upper()} plane")
        ax.legend(loc="best", fontsize="small")
    return fig


def sliding_variables(result: Result, bounds: Optional[MSSBounds] = None, max_cases: int = 300, *,
                      highlight: int = 0, axes: Optional[Sequence[Axes]] = None) -> Figure:
    """s1 (m) and s2 (m/s) per axis against time, s (the Mars fixed-time guidance paper's Fig. 9,
    10), with the theoretical neighbourhoods (dashed) and the times from which they hold
    (dotted), when known; a bound off the plot or beyond the run is said in the panel's title.
    The cases thin, the nominal (case ``highlight``) bold.

    Parameters
    ----------
    result : landing.SimulationResult or landing.MonteCarloResult
        A run, a batch or a campaign (a campaign's bounds and thrust limits are drawn).
    bounds : landing.theory.MSSBounds, optional
        The bounds drawn (default: the campaign's).
    max_cases : int, default 300
        The most cases drawn (the first ones).
    highlight : int, default 0
        The case drawn bold (the nominal).
    axes : sequence of matplotlib.axes.Axes, optional
        Exactly 6 Axes to draw into (s1 x, y, z; s2 x, y, z); by default a Figure of its own.

    Returns
    -------
    matplotlib.figure.Figure
        The figure drawn (that of ``ax`` or ``axes`` when given).

    Examples
    --------
    >>> import landing
    >>> scenario = landing.scenarios.preset("mars_monte_carlo").replace(t_final=5.0)
    >>> mc = landing.monte_carlo(scenario, n=8, seed=1)
    >>> len(landing.plots.sliding_variables(mc).axes)
    6
    """
    res, b = result_and_bounds(result)
    need_records(res)
    b = bounds if bounds is not None else b
    fig, panels = several_axes(axes, 6, (2, 3), figsize=(12, 7.5), layout="constrained")
    for row, (name, unit) in enumerate((("s1", "m"), ("s2", "m/s"))):
        if name not in res.diagnostics:
            for ax in panels[3 * row:3 * row + 3]:
                say_why(ax, f"{name} was not recorded (the law records s1 and s2 as diagnostics)")
            continue
        sig = batched(res.diagnostics[name], 3)[:max_cases]
        for j in range(3):
            ax = panels[3 * row + j]
            draw_cases(ax, res.t, sig[:, :, j], highlight)
            notes = []
            ax.set_xlabel("t (s)")
            ax.set_ylabel(f"{name} ({unit})")
            if b is not None:
                radius = float(np.ravel(b.s1_radius if name == "s1" else b.s2_radius)[j])
                when = float(np.ravel(b.settle_time if name == "s1" else b.s2_time)[j])
                span = float(np.nanmax(np.abs(sig[:, :, j]))) or 1.0
                if radius < 5 * span:
                    for sgn in (-1, 1):
                        ax.axhline(sgn * radius, ls="--", color="tab:red", lw=1,
                                   label=f"bound |{name}| <= {radius:.4g} {unit}" if sgn > 0 else None)
                else:
                    notes.append(f"bound |{name}| <= {radius:.4g} {unit}: off the plot")
                if when <= res.t[-1]:
                    ax.axvline(when, ls=":", color="tab:red", lw=1, label=f"bound time {when:.4g} s")
                else:
                    notes.append(f"bound time {when:.4g} s: beyond the run")
            ax.set_title("\n".join([f"{name}, {AXES[j]} axis", *notes]), fontsize="medium")
            if j == 0 and ax.get_legend_handles_labels()[0]:
                ax.legend(fontsize="x-small", loc="best")
    return fig


def _per_axis(result: Result, signal: Callable[[SimulationResult], np.ndarray], ylabel: str, title: str,
              max_cases: int, highlight: int, axes: Optional[Sequence[Axes]], scale: float = 1.0
              ) -> tuple[Figure, list[Axes]]:
    res, _ = result_and_bounds(result)
    need_records(res)
    res = first_cases(res, max_cases)
    fig, panels = several_axes(axes, 3, (1, 3), figsize=(12, 3.8), layout="constrained")
    data = batched(signal(res), 3)
    for j, ax in enumerate(panels):
        draw_cases(ax, res.t, data[:, :, j], highlight, scale)
        ax.set_title(f"{title}, {AXES[j]} axis")
        ax.set_xlabel("t (s)")
        ax.set_ylabel(ylabel)
    return fig, panels


def thrust(result: Result, max_cases: int = 300, *, plant: Optional[MarsLander] = None, highlight: int = 0,
           axes: Optional[Sequence[Axes]] = None) -> Figure:
    """Applied thrust per axis against time, kN (the Mars fixed-time guidance paper's Fig. 2(c),
    12), with the lander's per-axis limit and its thrust magnitude limit (which bounds every
    component) when it has them: of ``plant``, else of the campaign's scenario. The cases thin,
    the nominal (case ``highlight``) bold.

    Parameters
    ----------
    result : landing.SimulationResult or landing.MonteCarloResult
        A run, a batch or a campaign (a campaign's bounds and thrust limits are drawn).
    max_cases : int, default 300
        The most cases drawn (the first ones).
    plant : landing.plants.MarsLander, optional
        The lander whose thrust limits (N, drawn in kN) are drawn.
    highlight : int, default 0
        The case drawn bold (the nominal).
    axes : sequence of matplotlib.axes.Axes, optional
        Exactly 3 Axes to draw into (x, y, z); by default a Figure of its own.

    Returns
    -------
    matplotlib.figure.Figure
        The figure drawn (that of ``ax`` or ``axes`` when given).

    Examples
    --------
    >>> import landing
    >>> scenario = landing.scenarios.preset("mars_monte_carlo").replace(t_final=5.0)
    >>> mc = landing.monte_carlo(scenario, n=8, seed=1)
    >>> fig = landing.plots.thrust(mc)
    >>> len(fig.axes), fig.axes[0].get_ylabel()
    (3, 'thrust (kN)')
    """
    fig, panels = _per_axis(result, lambda r: recorded(r, "controls"), "thrust (kN)", "Thrust", max_cases,
                            highlight, axes, scale=1e-3)
    per_axis, magnitude = mars_limits(result, plant)
    for j, ax in enumerate(panels):
        draw_thrust_limits(ax, None if per_axis is None else float(per_axis[j]), magnitude)
        if j == 0 and ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize="x-small", loc="best")
    return fig


def draw_thrust_limits(ax: Axes, per_axis: Optional[float], magnitude: Optional[float]) -> None:
    """The per-axis thrust limit (dashed red) and the thrust magnitude limit (dash-dotted), in kN,
    drawn at plus and minus each, where finite.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The panel.
    per_axis : float or None
        The per-axis limit (N).
    magnitude : float or None
        The magnitude limit (N).
    """
    for value, style, label in ((per_axis, "--", "axis limit"), (magnitude, "-.", "|F| limit")):
        if value is not None and np.isfinite(value):
            for sgn in (1, -1):
                ax.axhline(sgn * value / 1e3, ls=style, color="tab:red", lw=1,
                           label=f"{label} {value / 1e3:.4g} kN" if sgn > 0 else None)


def positions(result: Result, max_cases: int = 300, *, highlight: int = 0,
              axes: Optional[Sequence[Axes]] = None) -> Figure:
    """Position per axis against time, m (the Mars fixed-time guidance paper's Fig. 2(a), 11), the
    ground (rz = 0) drawn on the altitude. The cases thin, the nominal (case ``highlight``) bold.

    Parameters
    ----------
    result : landing.SimulationResult or landing.MonteCarloResult
        A run, a batch or a campaign (a campaign's bounds and thrust limits are drawn).
    max_cases : int, default 300
        The most cases drawn (the first ones).
    highlight : int, default 0
        The case drawn bold (the nominal).
    axes : sequence of matplotlib.axes.Axes, optional
        Exactly 3 Axes to draw into (x, y, z); by default a Figure of its own.

    Returns
    -------
    matplotlib.figure.Figure
        The figure drawn (that of ``ax`` or ``axes`` when given).

    Examples
    --------
    >>> import landing
    >>> scenario = landing.scenarios.preset("mars_monte_carlo").replace(t_final=5.0)
    >>> mc = landing.monte_carlo(scenario, n=8, seed=1)
    >>> fig = landing.plots.positions(mc)
    >>> len(fig.axes), fig.axes[2].get_ylabel()
    (3, 'position (m)')
    """
    fig, panels = _per_axis(result, lambda r: batched(recorded(r, "states"), 3)[:, :, :3], "position (m)",
                            "Position", max_cases, highlight, axes)
    panels[2].axhline(0.0, color="tab:brown", lw=1.2, label="ground (rz = 0)")
    panels[2].legend(fontsize="x-small", loc="best")
    return fig


def mass(result: Result, max_cases: int = 300, *, highlight: int = 0, ax: Optional[Axes] = None) -> Figure:
    """Lander mass against time, kg (the Mars fixed-time guidance paper's Fig. 4): the cases thin,
    the nominal (case ``highlight``) bold.

    Parameters
    ----------
    result : landing.SimulationResult or landing.MonteCarloResult
        A run, a batch or a campaign (a campaign's bounds and thrust limits are drawn).
    max_cases : int, default 300
        The most cases drawn (the first ones).
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
    >>> scenario = landing.scenarios.preset("mars_monte_carlo").replace(t_final=5.0)
    >>> mc = landing.monte_carlo(scenario, n=8, seed=1)
    >>> fig = landing.plots.mass(mc)
    >>> len(fig.axes), fig.axes[0].get_ylabel()
    (1, 'mass (kg)')
    """
    res, _ = result_and_bounds(result)
    need_records(res)
    m = batched(recorded(res, "states"), 3)[:max_cases, :, res.state_names.index("m")]
    fig, ax = single_axes(ax, figsize=(6, 4), layout="constrained")
    draw_cases(ax, res.t, m, highlight)
    ax.set_xlabel("t (s)")
    ax.set_ylabel("mass (kg)")
    ax.set_title("Mass")
    if m.shape[0] > 1:
        ax.legend(fontsize="x-small", loc="best")
    return fig


def position_and_thrust(results: Labelled, ground: bool = True, *, plant: Optional[MarsLander] = None,
                        axes: Optional[Sequence[Axes]] = None) -> Figure:
    """One row per labelled single-case run: position per axis, m (left) and thrust per axis, kN
    (right) against time (the Mars fixed-time guidance paper's Fig. 3: the optimum flown open loop
    without and with the disturbance). The altitude's first crossing of zero is marked, the ground
    (rz = 0) drawn when ``ground``, and the thrust limits of ``plant`` when given.

    Parameters
    ----------
    results : landing.SimulationResult or dict of str to landing.SimulationResult
        Single-case runs by label (one run: no label).
    ground : bool, default True
        Whether the ground is drawn.
    plant : landing.plants.MarsLander, optional
        The lander whose thrust limits are drawn.
    axes : sequence of matplotlib.axes.Axes, optional
        Two Axes per run to draw into (position, thrust, row by row); by default a Figure of its
        own.

    Returns
    -------
    matplotlib.figure.Figure
        The figure drawn (that of ``ax`` or ``axes`` when given).

    Examples
    --------
    >>> import landing
    >>> scenario = landing.scenarios.preset("mars_monte_carlo").replace(t_final=5.0)
    >>> mc = landing.monte_carlo(scenario, n=8, seed=1)
    >>> fig = landing.plots.position_and_thrust({"case 0": mc[0], "case 1": mc[1]})
    >>> len(fig.axes)
    4
    """
    runs = labelled(results)
    fig, panels = several_axes(axes, 2 * len(runs), (len(runs), 2), figsize=(12, 3.3 * len(runs)),
                               layout="constrained")
    per_axis, magnitude = mars_limits(next(iter(runs.values())), plant)
    for row, (label, res) in enumerate(runs.items()):
        ax = panels[2 * row]
        for j in range(3):
            ax.plot(res.t, recorded(res, "states")[:, j], label=f"r{AXES[j]}")
        if ground:
            ax.axhline(0, color="tab:brown", lw=1.0, label="ground")
        td = float(np.asarray(res.metrics["touchdown_time"]))
        if np.isfinite(td):
            ax.axvline(td, ls=":", color="tab:red", lw=1)
            ax.text(td, ax.get_ylim()[1], f" rz = 0 at {td:.2f} s", color="tab:red", fontsize=8, va="top")
        ax.set_xlabel("t (s)")
        ax.set_ylabel("position (m)")
        ax.set_title(f"Position{': ' + label if label else ''}")
        ax.legend(fontsize=8)
        ax = panels[2 * row + 1]
        for j in range(3):
            ax.step(res.t, recorded(res, "controls")[:, j] / 1e3, where="post", label=f"F{AXES[j]}")
        draw_thrust_limits(ax, None if per_axis is None else float(np.max(per_axis)), magnitude)
        ax.set_xlabel("t (s)")
        ax.set_ylabel("thrust (kN)")
        ax.set_title(f"Thrust{': ' + label if label else ''}")
        ax.legend(fontsize=8)
    return fig


def masses(results: Labelled, read_at: Optional[Mapping[str, float]] = None, *, ax: Optional[Axes] = None) -> Figure:
    """Mass against time, kg, for labelled single-case runs (the Mars fixed-time guidance paper's
    Fig. 4), each labelled with the fuel spent (kg) by ``read_at[label]`` (a time, e.g. the
    landing time; the end of the run if not given).

    Parameters
    ----------
    results : landing.SimulationResult or dict of str to landing.SimulationResult
        Single-case runs by label.
    read_at : mapping of str to float, optional
        The time (s) each run's fuel is read at, by label.
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
    >>> fig = landing.plots.masses({"case 0": mc[0], "case 1": mc[1]}, read_at={"case 0": 4.0})
    >>> len(fig.axes)
    1
    """
    runs = labelled(results)
    fig, ax = single_axes(ax, figsize=(7, 4.5), layout="constrained")
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
