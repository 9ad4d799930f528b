"""The figures' conventions: each draws into given axes (``ax=`` / ``axes=``) and returns the
Figure it drew on, thrust in kN with the plant's limits, the ground on altitudes, a batch's cases
thin with the nominal bold, empty panels saying why. The image tests compare a figure drawn by
the function with one drawn by hand from the same data with plain matplotlib calls
(``check_figures_equal``): they check what is drawn, not a stored baseline's pixels."""

import inspect
import os
import tempfile

import matplotlib
import numpy as np
import pytest

matplotlib.use("Agg")

from matplotlib.patches import Rectangle  # noqa: E402
from matplotlib.testing.decorators import check_figures_equal  # noqa: E402

import landing  # noqa: E402
from _cases import small_campaign  # noqa: E402
from landing import plots, scenarios  # noqa: E402
from landing.errors import ParameterError  # noqa: E402

XYZ = ("x", "y", "z")


def figures_equal(test):
    """``check_figures_equal`` (PNG), its images written under a temporary directory's
    result_images/ (it takes the working directory's when the test is defined), not the
    checkout's."""
    here = os.getcwd()
    os.chdir(tempfile.mkdtemp(prefix="landing-figures-"))
    try:
        return check_figures_equal(extensions=["png"])(test)
    finally:
        os.chdir(here)


@pytest.fixture(scope="module")
def mc():
    """Eight Mars cases over 5 s, recorded (s1 and s2 among the diagnostics)."""
    return landing.monte_carlo(small_campaign(), 8, seed=1, progress=False)


@pytest.fixture(scope="module")
def many():
    """Sixty cases: more than a figure draws one line each for."""
    return landing.monte_carlo(small_campaign(), 60, seed=3, progress=False)


@pytest.fixture(scope="module")
def landed():
    """Eight cases long enough to touch the ground."""
    return landing.monte_carlo(scenarios.mars_monte_carlo(t_final=40.0, dt=2e-3, record_every=0), 8, seed=1,
                               progress=False)


@pytest.fixture(scope="module")
def one():
    return scenarios.mars_nominal(t_final=2.0).simulate()


def thin_and_bold(ax, t, data, k=0):
    """A batch by hand: every case but k thin and light, one legend entry; case k bold."""
    n = data.shape[0]
    others = [i for i in range(n) if i != k]
    for m, i in enumerate(others):
        ax.plot(t, data[i], lw=0.5, alpha=0.35, color="tab:blue", label=f"cases ({n})" if m == 0 else None)
    ax.plot(t, data[k], lw=1.8, color="k", label="nominal" if k == 0 else f"case {k}")


# --- image tests: the function's figure against one drawn by hand ---------------------------


@figures_equal
def test_positions_draw_the_cases_thin_the_nominal_bold_and_the_ground(fig_test, fig_ref, mc):
    assert plots.positions(mc, axes=fig_test.subplots(1, 3)) is fig_test
    t, s = mc.result.t, np.asarray(mc.result.states)
    for j, ax in enumerate(fig_ref.subplots(1, 3)):
        thin_and_bold(ax, t, s[:, :, j])
        ax.set_title(f"Position, {XYZ[j]} axis")
        ax.set_xlabel("t (s)")
        ax.set_ylabel("position (m)")
    ax.axhline(0.0, color="tab:brown", lw=1.2, label="ground (rz = 0)")
    ax.legend(fontsize="x-small", loc="best")


@figures_equal
def test_thrust_is_in_kn_with_the_plants_per_axis_limit(fig_test, fig_ref, one):
    plant = landing.plants.MarsLander(thrust_limit=5e4)
    assert plots.thrust(one, plant=plant, axes=fig_test.subplots(1, 3)) is fig_test
    u = np.asarray(one.controls)
    for j, ax in enumerate(fig_ref.subplots(1, 3)):
        ax.plot(one.t, u[:, j] / 1e3, lw=1.2)
        ax.set_title(f"Thrust, {XYZ[j]} axis")
        ax.set_xlabel("t (s)")
        ax.set_ylabel("thrust (kN)")
        ax.axhline(50.0, ls="--", color="tab:red", lw=1, label="axis limit 50 kN")
        ax.axhline(-50.0, ls="--", color="tab:red", lw=1)
        if j == 0:
            ax.legend(fontsize="x-small", loc="best")


@figures_equal
def test_a_campaigns_mass_highlights_the_chosen_case(fig_test, fig_ref, mc):
    assert plots.mass(mc, highlight=3, ax=fig_test.subplots()) is fig_test
    ax = fig_ref.subplots()
    thin_and_bold(ax, mc.result.t, np.asarray(mc.result.states)[:, :, 6], k=3)
    ax.set_xlabel("t (s)")
    ax.set_ylabel("mass (kg)")
    ax.set_title("Mass")
    ax.legend(fontsize="x-small", loc="best")


@figures_equal
def test_many_cases_are_a_percentile_band_about_the_nominal(fig_test, fig_ref, many):
    plots.mass(many, ax=fig_test.subplots())
    ax = fig_ref.subplots()
    m = np.asarray(many.result.states)[:, :, 6]
    lo, hi = np.percentile(m, [5, 95], axis=0)
    ax.fill_between(many.result.t, lo, hi, color="tab:blue", alpha=0.25, lw=0, label="cases 5-95 % (60)")
    ax.plot(many.result.t, m[0], lw=1.8, color="k", label="nominal")
    ax.set_xlabel("t (s)")
    ax.set_ylabel("mass (kg)")
    ax.set_title("Mass")
    ax.legend(fontsize="x-small", loc="best")


@figures_equal
def test_landing_sites(fig_test, fig_ref, landed):
    assert plots.landing_sites(landed, requirement_radius=5.0, axes=fig_test.subplots(1, 2)) is fig_test
    r = np.asarray(landed.metrics["touchdown_position"])[:, :2]
    speed = np.asarray(landed.metrics["touchdown_speed"])
    ok = np.all(np.isfinite(r), axis=1)
    sites = r[ok]
    ax, ax2 = fig_ref.subplots(1, 2)
    ax.scatter(sites[:, 0], sites[:, 1], s=8, color="tab:blue", label="touchdown sites")
    ax.scatter(r[:1, 0], r[:1, 1], s=60, marker="D", facecolors="none", edgecolors="k", lw=1.5, label="nominal")
    ax.axhline(0, color="0.7", lw=0.5)
    ax.axvline(0, color="0.7", lw=0.5)
    ax.set_xlabel("x at touchdown (m)")
    ax.set_ylabel("y at touchdown (m)")
    ax.set_title(f"Touchdown sites (first rz = 0 crossing), XOY plane\n{ok.sum()} of {ok.size} cases touched down")
    # the k-sigma ellipses: the unit circle through the covariance's square root, about the mean
    w, v = np.linalg.eigh(np.cov(sites, rowvar=False))
    a = np.linspace(0.0, 2.0 * np.pi, 181)
    extent = [np.abs(sites)]
    for k, style in ((1, "-"), (2, "--"), (3, ":")):
        e = sites.mean(axis=0) + k * (np.stack([np.cos(a), np.sin(a)], axis=1) * np.sqrt(w)) @ v.T
        ax.plot(e[:, 0], e[:, 1], style, color="tab:orange", lw=1.2,
                label=f"{k} sigma ({100 * (1 - np.exp(-k * k / 2)):.1f} % of a 2-D normal)")
        extent.append(np.abs(e))
    c = np.linspace(0.0, 2.0 * np.pi, 361)
    ax.plot(5.0 * np.cos(c), 5.0 * np.sin(c), color="tab:red", lw=1.5, label="requirement: within 5 m")
    span = max(float(np.max(np.concatenate(extent))), 5.0) * 1.3
    radius = float(np.max(landed.bounds.s1_radius))
    if radius < 10 * span:
        ax.add_patch(Rectangle((-radius, -radius), 2 * radius, 2 * radius, fill=False, ls="--", color="tab:red",
                               label=f"theory: |s1| <= {radius:.4g} m"))
    else:
        ax.text(0.02, 0.02, f"theory: |s1| <= {radius:.4g} m, {radius / span:.0f} times the sites' extent: "
                "not informative here (not drawn)", transform=ax.transAxes, fontsize=8)
    ax.legend(loc="upper right", fontsize="small")
    ax.set_aspect("equal", adjustable="datalim")
    ax2.hist(speed[np.isfinite(speed)], bins=30, color="tab:green")
    ax2.set_xlabel("speed at touchdown (m/s)")
    ax2.set_ylabel("cases")
    ax2.set_title("Speed at the first rz = 0 crossing")


@figures_equal
def test_two_figures_compose_into_one_user_figure(fig_test, fig_ref, mc, one):
    left, right = fig_test.subplots(1, 2)
    assert plots.mass(mc, ax=left) is fig_test
    assert plots.masses({"nominal run": one}, ax=right) is fig_test
    left, right = fig_ref.subplots(1, 2)
    thin_and_bold(left, mc.result.t, np.asarray(mc.result.states)[:, :, 6])
    left.set_xlabel("t (s)")
    left.set_ylabel("mass (kg)")
    left.set_title("Mass")
    left.legend(fontsize="x-small", loc="best")
    m = np.asarray(one.states)[:, 6]
    right.plot(one.t, m, label=f"nominal run: {m[0] - m[-1]:.2f} kg by {one.t[-1]:.2f} s")
    right.plot([one.t[-1]], [m[-1]], "o", color="C0")
    right.set_xlabel("t (s)")
    right.set_ylabel("mass (kg)")
    right.set_title("Mass, fuel spent to landing")
    right.legend(fontsize=8)


@pytest.fixture(scope="module")
def tracking_batch():
    """Four small-body cases about seed 000's tracking start."""
    s = scenarios.seed000_tracking(t_final=50.0)
    x0 = np.asarray(s.x0) + np.zeros((4, 1))
    x0[:, 0] += 10.0 * np.arange(4)
    return s, s.simulate_batch(x0)


@figures_equal
def test_a_small_body_batchs_tracking_errors(fig_test, fig_ref, tracking_batch):
    s, batch = tracking_batch
    plots.tracking_errors(batch, s.reference, axes=fig_test.subplots(1, 3))
    p, _, _ = s.reference.evaluate(batch.t, axes=3)
    e = np.asarray(batch.states)[:, :, :3] - p
    axes = fig_ref.subplots(1, 3)
    for j, ax in enumerate(axes):
        thin_and_bold(ax, batch.t, e[:, :, j])
        ax.set_title(f"position error, {XYZ[j]}")
        ax.set_xlabel("t (s)")
        ax.set_ylabel("position error (m)")
        ax.axhline(0, color="0.7", lw=0.5)
    axes[0].legend()


def test_the_standard_figures_of_a_small_body_batch(tracking_batch):
    s, batch = tracking_batch
    figs = plots.standard_figures(batch, plant=s.plant, reference=s.reference)
    assert set(figs) == {"tracking_errors", "commands", "trajectory"}
    assert figs["commands"].axes[0].get_ylabel() == "u (m/s^2)"
    bold = [line for line in figs["commands"].axes[0].lines if line.get_linewidth() == 1.8]
    np.testing.assert_array_equal(bold[0].get_ydata(), np.asarray(batch.controls)[0, :, 0])


# --- every public figure function: given axes, it draws there and returns their Figure ------


def _tether_runs():
    return {law: scenarios.tether_comparison(law, t_final=5.0).simulate() for law in ("fntsmc", "ntsmc")}


@pytest.fixture(scope="module")
def inputs(mc, one):
    """What each public figure function is called with: (args, kwargs, panels, 3D)."""
    track = scenarios.seed000_tracking(t_final=50.0).simulate()
    ref = scenarios.seed000_reference()
    tether = _tether_runs()
    calls = {
        "trajectories_3d": ((mc,), {}, 1, True),
        "landing_sites": ((mc,), {}, 2, False),
        "final_velocities": ((mc,), {}, 2, False),
        "sliding_variables": ((mc,), {}, 6, False),
        "thrust": ((mc,), {}, 3, False),
        "positions": ((mc,), {}, 3, False),
        "mass": ((mc,), {}, 1, False),
        "position_and_thrust": (({"a": one, "b": one},), {}, 4, False),
        "masses": (({"a": one},), {}, 1, False),
        "tracking_errors": (({"run": track},), {"reference": ref}, 3, False),
        "commands": (({"run": track}, "u (m/s^2)"), {}, 3, False),
        "diagnostic": (({"run": track}, "s"), {}, 3, False),
        "blend_coefficients": ((track,), {}, 1, False),
        "trajectory_with_reference": (({"run": track}, ref), {}, 1, True),
        "tether_angles": ((tether,), {}, 2, False),
        "tether_rates": ((tether,), {}, 2, False),
        "tether_commands": ((tether,), {"plant": scenarios.tether_plant()}, 2, False),
        "tether_fixed_time": (({"FNTSMC": {1.0: np.array([30.0, 2.0]), 5.0: np.array([80.0, 5.0])}},
                               np.array([1600.0, 28.0])), {}, 2, False),
        "tornado": ((mc.sensitivity(["fuel_used"]), "fuel_used"), {"k": 3}, 1, False),
    }
    if _has_cma():
        tuned = landing.tune(scenarios.Scenario(
            name="di", plant=landing.plants.DoubleIntegrator(),
            controller=landing.controllers.PDSlidingMode(lambda_=1.0, k=1.0, switch="sat", boundary_layer=1.0),
            x0=np.array([0.1, 0, 0, 0, 0, 0.0]), t_final=2.0, dt=0.01), {"k": (0.2, 8.0)}, "mean(iae)",
            budget=8, seed=0, threads=1, popsize=4)
        calls["tuning_convergence"] = ((tuned,), {}, 2, False)
        calls["tuning_front"] = ((tuned,), {}, 1, False)
    return calls


def _has_cma():
    try:
        import cma  # noqa: F401
    except ImportError:
        return False
    return True


COUNTS = {"cases", "generation", "dispersed quantity"}
NOT_FIGURES = {"save_all", "save_figures", "standard_figures"}  # they write or collect figures
FIGURES = sorted(set(plots.__all__) - NOT_FIGURES)


@pytest.mark.parametrize("name", FIGURES)
def test_every_figure_takes_its_axes_and_returns_their_figure(name, inputs):
    from matplotlib.figure import Figure

    function = getattr(plots, name)
    params = inspect.signature(function).parameters
    assert ("ax" in params) != ("axes" in params), name
    if name not in inputs:
        pytest.skip("needs the tune extra (cma)")
    args, kwargs, n, three_d = inputs[name]
    user = Figure()
    if "ax" in params:
        ax = user.add_subplot(1, 2, 2, projection="3d" if three_d else None)
        assert function(*args, ax=ax, **kwargs) is user
        drawn = [ax]
    else:
        drawn = [user.add_subplot(n, 1, j + 1) for j in range(n)]
        assert function(*args, axes=drawn, **kwargs) is user
        with pytest.raises(ParameterError, match="axes"):
            function(*args, axes=drawn[:-1] or [user.add_subplot(), user.add_subplot()], **kwargs)
    # no empty panel: each holds data or says why it has none
    for ax in drawn:
        assert ax.lines or ax.collections or ax.patches or ax.texts, (name, ax.get_title())
    for ax in drawn:
        if three_d or not (ax.lines or ax.collections or ax.patches):
            continue
        for label in (ax.get_xlabel(), ax.get_ylabel()):
            # a unit in parentheses, but on counts, categories and a tuning's own objectives
            assert "(" in label or label in COUNTS or name.startswith("tuning_"), (name, label)
    # without axes it makes a Figure of its own, not pyplot's
    own = function(*args, **kwargs)
    assert isinstance(own, Figure) and own is not user
    assert own.canvas.manager is None  # pyplot's figures have a manager that keeps them alive


def test_thrust_axes_are_in_kn_and_the_tethers_commands_in_n_and_n_m(mc, one):
    for fig in (plots.thrust(mc), plots.position_and_thrust({"a": one})):
        labels = [ax.get_ylabel() for ax in fig.axes if "hrust" in ax.get_title()]
        assert labels and all(lab == "thrust (kN)" for lab in labels)
    np.testing.assert_allclose(plots.thrust(mc).axes[0].lines[0].get_ydata(),
                               np.asarray(mc.result.controls)[1, :, 0] / 1e3)
    fig = plots.tether_commands(_tether_runs(), plant=scenarios.tether_plant())
    assert [ax.get_ylabel() for ax in fig.axes] == ["thrust (N)", "torque (N m)"]
    limits = {ax.get_ylabel(): sorted(line.get_ydata()[0] for line in ax.lines if line.get_linestyle() == "--")
              for ax in fig.axes}
    assert limits == {"thrust (N)": [-0.1, 0.1], "torque (N m)": [-0.05, 0.05]}


def test_a_small_bodys_commands_are_accelerations_with_their_limits():
    run = scenarios.seed000_tracking(t_final=20.0).simulate()
    plant = landing.plants.SmallBody(acceleration_limit=0.02)
    fig = plots.commands(run, plant=plant)
    for ax in fig.axes:
        assert ax.get_ylabel() == "u (m/s^2)"
        dashed = sorted(line.get_ydata()[0] for line in ax.lines if line.get_linestyle() == "--")
        assert dashed == [-0.02, 0.02]
    assert plots.commands(run, "a (km/s^2)").axes[0].get_ylabel() == "a (km/s^2)"  # the old call


def test_a_campaigns_thrust_shows_its_scenarios_magnitude_limit():
    mc = landing.monte_carlo(scenarios.mars_realistic(t_final=3.0, record_every=50), 4, seed=1, progress=False)
    limit = float(mc.scenario.plant.thrust_magnitude_limit) / 1e3
    for ax in plots.thrust(mc).axes:
        dashed = sorted(line.get_ydata()[0] for line in ax.lines if line.get_linestyle() == "-.")
        np.testing.assert_allclose(dashed, [-limit, limit])


def test_a_panel_with_nothing_to_draw_says_why(mc):
    fig = plots.landing_sites(mc)  # 5 s: no case reaches the ground
    speeds = fig.axes[1]
    assert not speeds.patches and "touched down" in speeds.texts[0].get_text()
    assert "touched down" in fig.axes[0].texts[-1].get_text()
    fig = plots.landing_sites(scenarios.mars_nominal(t_final=2.0).simulate())  # a nominal run, still flying
    for ax in fig.axes:
        assert not ax.collections and not ax.patches and "no case touched down" in ax.texts[0].get_text()
    no_s = scenarios.mars_super_twisting(t_final=2.0).simulate()
    if {"s1", "s2"} <= set(no_s.diagnostics):
        pytest.skip("this law records s1 and s2")
    fig = plots.sliding_variables(no_s)
    assert all("not recorded" in ax.texts[0].get_text() for ax in fig.axes if not ax.lines)


def test_the_standard_figures_leave_out_what_a_campaign_did_not_keep():
    mc = landing.monte_carlo(small_campaign(), 4, seed=1, progress=False, keep=("controls",))
    assert set(plots.standard_figures(mc)) == {"landing_sites", "final_velocities", "thrust"}


def test_sliding_variables_keep_their_notes_out_of_the_curves(mc):
    fig = plots.sliding_variables(mc)
    # the bounds beyond the run are said in the titles, not written over the curves
    assert all(not ax.texts for ax in fig.axes)
    assert any("beyond the run" in ax.get_title() for ax in fig.axes)
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    FigureCanvasAgg(fig).draw()  # lays the figure out (a bare Figure's canvas draws nothing)
    boxes = [t.get_window_extent() for ax in fig.axes for t in (ax.title, ax.xaxis.label, ax.yaxis.label)]
    for i, a in enumerate(boxes):
        for b in boxes[i + 1:]:
            assert not a.overlaps(b)


def test_a_band_past_every_case_s_stop_is_empty_and_silent():
    # cases that all stopped (NaN records) before the end: the band is NaN there (nothing drawn)
    # and no "All-NaN slice" RuntimeWarning reaches the user
    import warnings

    import matplotlib.pyplot as plt

    from landing.plots._common import BAND_ABOVE, draw_cases

    t = np.linspace(0.0, 1.0, 11)
    data = np.tile(t, (BAND_ABOVE + 5, 1))
    data[:, 6:] = np.nan
    fig, ax = plt.subplots()
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        draw_cases(ax, t, data)
    band = ax.collections[0].get_paths()[0].vertices
    assert np.isfinite(band).all() and band[:, 0].max() <= t[5] + 1e-12
    plt.close(fig)
