"""Figures: each function takes a result and returns a matplotlib Figure.

They accept a :class:`~landing.SimulationResult` (one case or a batch) or a
:class:`~landing.MonteCarloResult`; a campaign's theoretical bounds, if any, are drawn.
``save_all`` writes the standard set for a campaign.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, Mapping, Optional, Union

import numpy as np

from landing.campaign import MonteCarloResult
from landing.results import SimulationResult

__all__ = [
    "trajectories_3d",
    "landing_sites",
    "final_velocities",
    "sliding_variables",
    "thrust",
    "mass",
    "positions",
    "save_all",
    "tracking_errors",
    "commands",
    "diagnostic",
    "blend_coefficients",
    "trajectory_with_reference",
    "tether_angles",
    "tether_rates",
    "tether_commands",
    "tether_fixed_time",
    "position_and_thrust",
    "masses",
    "tuning_convergence",
    "tuning_front",
]

AXES = ("x", "y", "z")
Result = Union[SimulationResult, MonteCarloResult]


def _figure(**kw: Any):
    # pyplot keeps figures alive until closed; building Figure objects directly does not,
    # so a campaign's figures are freed with their result
    from matplotlib.figure import Figure

    return Figure(**kw)


def _parts(result: Result) -> tuple[SimulationResult, Any]:
    if isinstance(result, MonteCarloResult):
        return result.result, result.bounds
    return result, None


def _batched(a: np.ndarray, ndim: int) -> np.ndarray:
    """Add the case axis to a single case's array."""
    return a[None] if a.ndim == ndim - 1 else a


def _need_records(res: SimulationResult) -> None:
    if res.t.size == 0:
        from landing.errors import ParameterError

        raise ParameterError("this figure needs recorded trajectories: run with record_every >= 1")


def trajectories_3d(result: Result, max_cases: int = 300):
    """3D trajectories (seed 001 Fig. 7(a)), the target marked."""
    res, _ = _parts(result)
    _need_records(res)
    s = _batched(res.states, 3)[:max_cases]
    fig = _figure(figsize=(7, 6))
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


def _radius_box(ax, r: Optional[float]) -> None:
    if r is not None and np.isfinite(r):
        ax.add_patch(__import__("matplotlib.patches", fromlist=["Rectangle"]).Rectangle(
            (-r, -r), 2 * r, 2 * r, fill=False, ls="--", color="tab:red", label=f"theory: |s1| <= {r:.4g} m"))


def landing_sites(result: Result):
    """Touchdown sites: where each case first crosses rz = 0 from above (the ``touchdown_position``
    metric, interpolated within the integrator step), on the XOY plane, with the theoretical s1
    neighbourhood when the result carries bounds; and the touchdown speeds (seed 001 Fig. 8(a),
    (c) read at touchdown). Cases that never touch the ground are counted in the title; the state
    at t_final is not drawn (the lander flies on after touchdown, the simulator does not stop)."""
    res, bounds = _parts(result)
    m = res.metrics
    r = np.atleast_2d(np.asarray(m["touchdown_position"], dtype=float))[:, :3]
    speed = np.atleast_1d(np.asarray(m["touchdown_speed"], dtype=float))
    touched = np.all(np.isfinite(r), axis=1)
    radius = None if bounds is None else float(np.max(bounds.s1_radius))
    fig = _figure(figsize=(11, 5), layout="constrained")
    ax = fig.add_subplot(1, 2, 1)
    ax.scatter(r[touched, 0], r[touched, 1], s=8)
    ax.axhline(0, color="0.7", lw=0.5)
    ax.axvline(0, color="0.7", lw=0.5)
    ax.set_xlabel("x at touchdown (m)")
    ax.set_ylabel("y at touchdown (m)")
    ax.set_title(f"Touchdown sites (first rz = 0 crossing), XOY plane\n"
                 f"{int(touched.sum())} of {touched.size} cases touched down")
    if touched.any():
        span = max(float(np.nanmax(np.abs(r[touched][:, :2]))), 1e-6) * 1.3
        if radius is not None and radius < 20 * span:
            _radius_box(ax, radius)
            ax.legend(loc="upper right")
        elif radius is not None:
            ax.text(0.02, 0.02, f"theory: |s1| <= {radius:.4g} m (off the plot)", transform=ax.transAxes, fontsize=8)
    ax.set_aspect("equal", adjustable="datalim")
    ax = fig.add_subplot(1, 2, 2)
    if np.isfinite(speed).any():
        ax.hist(speed[np.isfinite(speed)], bins=30, color="tab:green")
    ax.set_xlabel("speed at touchdown (m/s)")
    ax.set_ylabel("cases")
    ax.set_title("Speed at the first rz = 0 crossing")
    return fig


def final_velocities(result: Result):
    """Final velocities on the XOZ and XOY planes (seed 001 Fig. 8(c), (d))."""
    res, _ = _parts(result)
    v = _batched(res.final_state, 2)[:, 3:6]
    fig = _figure(figsize=(11, 5))
    for k, (j, name) in enumerate(((2, "z"), (1, "y"))):
        ax = fig.add_subplot(1, 2, k + 1)
        ax.scatter(v[:, 0], v[:, j], s=8, color="tab:green")
        ax.axhline(0, color="0.7", lw=0.5)
        ax.axvline(0, color="0.7", lw=0.5)
        ax.set_xlabel("vx (m/s)")
        ax.set_ylabel(f"v{name} (m/s)")
        ax.set_title(f"Final velocities, XO{name.upper()} plane")
    return fig


def sliding_variables(result: Result, bounds: Any = None, max_cases: int = 300):
    """s1 and s2 per axis against time (seed 001 Fig. 9, 10), with the theoretical
    neighbourhoods (dashed) and the times from which they hold (dotted), when known."""
    res, b = _parts(result)
    _need_records(res)
    b = bounds if bounds is not None else b
    fig = _figure(figsize=(12, 7), layout="constrained")
    for row, (name, unit) in enumerate((("s1", "m"), ("s2", "m/s"))):
        sig = _batched(res.diagnostics[name], 3)[:max_cases]
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
                    ax.text(0.02, 0.95, f"radius {radius:.4g} {unit} (off the plot)", transform=ax.transAxes, fontsize=8, va="top")
                if when <= res.t[-1]:
                    ax.axvline(when, ls=":", color="tab:red", lw=1)
                else:
                    ax.text(0.02, 0.85, f"bound time {when:.4g} s (beyond the run)", transform=ax.transAxes, fontsize=8, va="top")
    return fig


def _per_axis(result: Result, index: Any, ylabel: str, title: str, max_cases: int):
    res, _ = _parts(result)
    _need_records(res)
    fig = _figure(figsize=(12, 3.8), layout="constrained")
    for j in range(3):
        ax = fig.add_subplot(1, 3, j + 1)
        data = index(res)[:max_cases, :, j]
        ax.plot(res.t, data.T, lw=0.5, alpha=0.6)
        ax.set_title(f"{title}, {AXES[j]} axis")
        ax.set_xlabel("t (s)")
        ax.set_ylabel(ylabel)
    return fig


def thrust(result: Result, max_cases: int = 300):
    """Applied thrust per axis against time (seed 001 Fig. 2(c), 12)."""
    return _per_axis(result, lambda r: _batched(r.controls, 3), "thrust (N)", "Thrust", max_cases)


def positions(result: Result, max_cases: int = 300):
    """Position per axis against time (seed 001 Fig. 2(a), 11)."""
    return _per_axis(result, lambda r: _batched(r.states, 3)[:, :, :3], "position (m)", "Position", max_cases)


def mass(result: Result, max_cases: int = 300):
    """Lander mass against time (seed 001 Fig. 4)."""
    res, _ = _parts(result)
    _need_records(res)
    m = _batched(res.states, 3)[:max_cases, :, res.state_names.index("m")]
    fig = _figure(figsize=(6, 4), layout="constrained")
    ax = fig.add_subplot()
    ax.plot(res.t, m.T, lw=0.6, alpha=0.7)
    ax.set_xlabel("t (s)")
    ax.set_ylabel("mass (kg)")
    ax.set_title("Mass")
    return fig


def save_all(result: Result, folder: Union[str, Path], dpi: int = 120) -> list[Path]:
    """Write the standard figures of a Mars campaign as PNG files into ``folder``."""
    return save_figures(standard_figures(result), folder, dpi=dpi)


def standard_figures(result: Result, plant: Any = None, reference: Any = None) -> dict[str, Any]:
    """The usual figures of a run or campaign for its plant, by name (what ``landing run``,
    ``landing mc`` and ``landing report`` write): the Mars figures of :func:`save_all` for the
    lander, tracking errors and commands for the small body and the double integrator, angles,
    rates and commands for the tethered satellite. Nothing for a run that recorded nothing."""
    from landing import plants

    res, _ = _parts(result)
    if res.t.size == 0:
        return {}
    if plant is None or isinstance(plant, plants.MarsLander):
        makers: dict[str, Any] = {
            "trajectories_3d": trajectories_3d,
            "landing_sites": landing_sites,
            "final_velocities": final_velocities,
            "positions": positions,
            "thrust": thrust,
            "mass": mass,
        }
        if {"s1", "s2"} <= set(res.diagnostics):
            makers["sliding_variables"] = sliding_variables
        return {name: make(result) for name, make in makers.items()}
    if isinstance(plant, plants.TetheredSatellite):
        return {
            "tether_angles": tether_angles(res, plant),
            "tether_rates": tether_rates(res, plant),
            "tether_commands": tether_commands(res),
        }
    figs = {"tracking_errors": tracking_errors(res, reference), "commands": commands(res)}
    if reference is not None and res.states.shape[-1] >= 6:
        figs["trajectory"] = trajectory_with_reference(res, reference)
    return figs


def save_figures(figures: Mapping[str, Any], folder: Union[str, Path], dpi: int = 120) -> list[Path]:
    """Writes figures (name -> Figure) as ``folder/name.png`` and closes them."""
    import matplotlib.pyplot as plt

    out = Path(folder)
    out.mkdir(parents=True, exist_ok=True)
    written = []
    for name, fig in figures.items():
        path = out / f"{name}.png"
        fig.savefig(path, dpi=dpi)
        plt.close(fig)
        written.append(path)
    return written


# --- Comparisons of single-case runs (the asteroid and tether papers' figures) ---------------

Labelled = Union[SimulationResult, "dict[str, SimulationResult]"]


def _labelled(results: Labelled) -> dict[str, SimulationResult]:
    if isinstance(results, SimulationResult):
        return {"": results}
    out = dict(results)
    for res in out.values():
        _need_records(res)
        if res.states.ndim != 2:
            from landing.errors import ParameterError

            raise ParameterError("comparison figures take single cases: pass result[i] for case i")
    return out


def _axis_grid(fig, n: int):
    return [fig.add_subplot(1, n, j + 1) for j in range(n)]


def tracking_errors(results: Labelled, reference: Any = None, velocity: bool = False):
    """Position (or velocity) tracking error per axis against time, one line per labelled run
    (seed 000 Fig. 11, seed 002 Fig. 7). ``reference``: the target tracked (default the
    origin)."""
    runs = _labelled(results)
    fig = _figure(figsize=(12, 3.8), layout="constrained")
    first = next(iter(runs.values()))
    n = first.controls.shape[-1]
    axes = _axis_grid(fig, n)
    for label, res in runs.items():
        q = res.states[:, n:2 * n] if velocity else res.states[:, :n]
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


def commands(results: Labelled, ylabel: str = "command"):
    """Applied command per axis against time, one line per labelled run (seed 000 Fig. 5, 10;
    seed 002 Fig. 9, 10)."""
    runs = _labelled(results)
    n = next(iter(runs.values())).controls.shape[-1]
    fig = _figure(figsize=(12, 3.8), layout="constrained")
    axes = _axis_grid(fig, n)
    for label, res in runs.items():
        for j, ax in enumerate(axes):
            ax.plot(res.t, res.controls[:, j], lw=0.7, label=label or None)
    for j, ax in enumerate(axes):
        ax.set_title(f"{res.control_names[j]}")
        ax.set_xlabel("t (s)")
        ax.set_ylabel(ylabel)
    if len(runs) > 1:
        axes[0].legend()
    return fig


def diagnostic(results: Labelled, name: str = "s"):
    """A law's recorded signal (a sliding variable, the fuzzy term...) per axis against time,
    one line per labelled run that has it (seed 000 Fig. 6, seed 002 Fig. 8)."""
    runs = {k: v for k, v in _labelled(results).items() if name in v.diagnostics}
    if not runs:
        from landing.errors import ParameterError

        raise ParameterError(f"no run recorded the diagnostic {name!r}")
    first = next(iter(runs.values())).diagnostics[name]
    n = first.shape[-1] if first.ndim == 2 else 1
    fig = _figure(figsize=(12 if n > 1 else 6, 3.8), layout="constrained")
    axes = _axis_grid(fig, n)
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


def blend_coefficients(result: SimulationResult):
    """The fuzzy blend a(D), b(D) of FuzzyFastTerminalSMC against time (seed 000 Fig. 7)."""
    _need_records(result)
    fig = _figure(figsize=(6, 4), layout="constrained")
    ax = fig.add_subplot()
    for name in ("a", "b"):
        ax.plot(result.t, result.diagnostics[name], label=name)
    ax.set_xlabel("t (s)")
    ax.set_ylim(-0.05, 1.05)
    ax.legend()
    ax.set_title("Fuzzy blending coefficients")
    return fig


def trajectory_with_reference(results: Labelled, reference: Any = None):
    """3D trajectories of labelled runs with the reference they track (seed 000 Fig. 12, seed 002
    Fig. 6)."""
    runs = _labelled(results)
    fig = _figure(figsize=(7, 6))
    ax = fig.add_subplot(projection="3d")
    for label, res in runs.items():
        ax.plot(res.states[:, 0], res.states[:, 1], res.states[:, 2], lw=1.0, label=label or "trajectory")
    if reference is not None:
        t = next(iter(runs.values())).t
        p, _, _ = reference.evaluate(t)
        ax.plot(p[:, 0], p[:, 1], p[:, 2], "k--", lw=0.8, label="reference")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_zlabel("z (m)")
    ax.legend()
    return fig


# Seed 003: the tethered satellite (figures 3 to 7).

Runs = Union[SimulationResult, Mapping[str, SimulationResult]]
_TETHER_AXES = (("in-plane angle", "phi"), ("attitude angle", "theta"))


def _tether_coordinates(res: SimulationResult, plant: Any = None) -> tuple[np.ndarray, np.ndarray]:
    """(q, q') of a tethered-satellite result, (N, T, 2) each. The flexible model's state holds
    positions; its angles come from the core (they do not depend on the physical parameters,
    so a default plant with the result's node count serves when none is given)."""
    states = _batched(res.states, 3)
    if res.state_names[:2] == ("phi", "theta"):
        return states[..., :2], states[..., 2:4]
    if plant is None:
        from landing.plants import TetheredSatellite

        plant = TetheredSatellite(fidelity="flexible", nodes=(len(res.state_names) - 6) // 4)
    return plant.coordinates(states)


def _runs(results: Runs) -> dict[str, SimulationResult]:
    if isinstance(results, SimulationResult):
        return {"": results}
    return dict(results)


def _tether_pair(results: Runs, pick, ylabels: tuple[str, str], title: str, plant: Any, scale: float,
                 max_cases: int):
    runs = _runs(results)
    fig = _figure(figsize=(11, 4), layout="constrained")
    axes = [fig.add_subplot(1, 2, j + 1) for j in range(2)]
    for label, res in runs.items():
        _need_records(res)
        data = pick(res, plant)[:max_cases]
        for j, ax in enumerate(axes):
            lines = ax.plot(res.t, data[:, :, j].T * scale, lw=0.9)
            if label:
                lines[0].set_label(label)
    for j, ax in enumerate(axes):
        ax.set_title(f"{title[j]}")
        ax.set_xlabel("t (s)")
        ax.set_ylabel(ylabels[j])
        ax.axhline(0.0, color="0.7", lw=0.5)
        if any(runs):
            ax.legend()
    return fig


def tether_angles(results: Runs, plant: Any = None, max_cases: int = 50):
    """In-plane and attitude angles against time, degrees (seed 003 Fig. 3 and 5). ``results``
    is a result or a mapping label -> result (e.g. {"FNTSMC": ..., "NTSMC": ...})."""
    return _tether_pair(results, lambda r, p: _tether_coordinates(r, p)[0], ("phi (deg)", "theta (deg)"),
                        ("In-plane angle", "Attitude angle"), plant, 180.0 / np.pi, max_cases)


def tether_rates(results: Runs, plant: Any = None, max_cases: int = 50):
    """In-plane and attitude angular rates against time, deg/s (seed 003 Fig. 4 and 6)."""
    return _tether_pair(results, lambda r, p: _tether_coordinates(r, p)[1], ("phi' (deg/s)", "theta' (deg/s)"),
                        ("In-plane angular rate", "Attitude angular rate"), plant, 180.0 / np.pi, max_cases)


def tether_commands(results: Runs, max_cases: int = 50):
    """Applied thrust (N) and torque (N m) against time (seed 003 Fig. 7 (a), (b))."""
    return _tether_pair(results, lambda r, p: _batched(r.controls, 3), ("thrust (N)", "torque (N m)"),
                        ("(a) Thrust of the sub-satellite", "(b) Torque of the sub-satellite"), None, 1.0, max_cases)


def tether_fixed_time(worst: Mapping[str, Mapping[float, np.ndarray]], bound: Any):
    """Worst settle time of each angle against the initial-error spread of a campaign, per law,
    with the fixed-time bound (dashed): ``worst[law][spread_deg]`` is a (2,) array (phi, theta);
    ``bound`` the (2,) bound of :func:`landing.theory.fntsmc_bounds` (``.total``)."""
    fig = _figure(figsize=(11, 4), layout="constrained")
    total = np.ravel(getattr(bound, "total", bound))
    for j, (name, sym) in enumerate(_TETHER_AXES):
        ax = fig.add_subplot(1, 2, j + 1)
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


# --- The fuel-optimal comparison (seed 001 Fig. 3 and 4) ----------------------------------------


def position_and_thrust(results: Labelled, ground: bool = True):
    """One row per labelled single-case run: position per axis (left) and thrust per axis
    (right) against time (seed 001 Fig. 3: the optimum flown open loop without and with the
    disturbance). The altitude's first crossing of zero is marked."""
    runs = _labelled(results)
    fig = _figure(figsize=(12, 3.3 * len(runs)), layout="constrained")
    for row, (label, res) in enumerate(runs.items()):
        ax = fig.add_subplot(len(runs), 2, 2 * row + 1)
        for j in range(3):
            ax.plot(res.t, res.states[:, j], label=f"r{AXES[j]}")
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
            ax.step(res.t, res.controls[:, j] / 1e3, where="post", label=f"F{AXES[j]}")
        ax.set_xlabel("t (s)")
        ax.set_ylabel("thrust (kN)")
        ax.set_title(f"Thrust{': ' + label if label else ''}")
        ax.legend(fontsize=8)
    return fig


def masses(results: Labelled, read_at: Optional[Mapping[str, float]] = None):
    """Mass against time for labelled single-case runs (seed 001 Fig. 4), each labelled with
    the fuel spent by ``read_at[label]`` (a time, e.g. the landing time; the end of the run if
    not given)."""
    runs = _labelled(results)
    fig = _figure(figsize=(7, 4.5), layout="constrained")
    ax = fig.add_subplot()
    for label, res in runs.items():
        m = res.states[:, res.state_names.index("m")]
        t_read = res.t[-1] if read_at is None or label not in read_at else float(read_at[label])
        m_read = float(np.interp(t_read, res.t, m))
        (line,) = ax.plot(res.t, m, label=f"{label}: {m[0] - m_read:.2f} kg by {t_read:.2f} s")
        ax.plot([t_read], [m_read], "o", color=line.get_color())
    ax.set_xlabel("t (s)")
    ax.set_ylabel("mass (kg)")
    ax.set_title("Mass, fuel spent to landing")
    ax.legend(fontsize=8)
    return fig


# --- Gain tuning (landing.tune) ----------------------------------------------------------------


def tuning_convergence(result: Any):
    """A :class:`landing.tune.TuneResult`'s search: every evaluation's first objective against
    its generation (feasible filled, infeasible hollow) and the best feasible so far (line);
    below, the share of each generation that is feasible."""
    fig = _figure(figsize=(8, 6), layout="constrained")
    ax = fig.add_subplot(2, 1, 1)
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
    ax2 = fig.add_subplot(2, 1, 2, sharex=ax)
    gens = np.arange(int(g.max()) + 1 if g.size else 0)
    share = [float(f[g == k].mean()) for k in gens]
    ax2.bar(gens, share, color="tab:green")
    ax2.set_ylim(0, 1)
    ax2.set_xlabel("generation")
    ax2.set_ylabel("feasible share")
    return fig


def tuning_front(result: Any, objectives: tuple[int, int] = (0, 1)):
    """The Pareto front of a several-objective tuning (the front of the feasible evaluations):
    every evaluation in objective space, the front highlighted. With one objective, the first
    objective against the total constraint violation (0: feasible), the best marked."""
    fig = _figure(figsize=(7, 5), layout="constrained")
    ax = fig.add_subplot(1, 1, 1)
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
