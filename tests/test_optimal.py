"""The offline fuel-optimal baseline (landing.optimal) and the law that replays it (Tabulated).

Independent truths: the lander's equations written again here in numpy and integrated by
scipy's adaptive DOP853 (the dynamics), the closed-form free-fall-then-full-thrust landing
(the optimum of a vertical drag-free case), the rocket equation (the impulsive bound), the
package's guidance laws (the fuel ordering) and closed-form double-integrator motion (the
table's hold semantics). Coarse grids keep the file fast.
"""

from __future__ import annotations

import math
import sys

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

pytest.importorskip("casadi")

pytestmark = pytest.mark.optimal

import landing  # noqa: E402
from _cases import LEVELS, assert_same_result_bits  # noqa: E402
from landing import controllers, disturbances, optimal, plants, scenarios  # noqa: E402
from landing.errors import ParameterError, ParameterTypeError  # noqa: E402

X0 = scenarios.MARS_NOMINAL_STATE
FMAX = 40e3
G_MARS = 3.7114
C_EXH = 225.0 * 9.807
AREA = np.array([6.0, 7.5, 8.7])


def drag(x: np.ndarray) -> np.ndarray:
    """Seed 001 eq. 12 with the sign fixed, written again from docs/parameters.md."""
    return -0.699 * x[3:6] * np.abs(x[3:6]) * np.exp(-0.0009 * x[2]) / (AREA * x[6])


def rhs(x: np.ndarray, f: np.ndarray, with_drag: bool) -> np.ndarray:
    acc = f / x[6] + np.array([0.0, 0.0, -G_MARS]) + (drag(x) if with_drag else 0.0)
    return np.r_[x[3:6], acc, -np.linalg.norm(f) / C_EXH]


@pytest.fixture(scope="module")
def nominal() -> optimal.FuelOptimalResult:
    res = optimal.fuel_optimal(plants.MarsLander(thrust_limit=FMAX), X0, 30.0, nodes=30, steps_per_node=4)
    assert res.success, res.status
    return res


def test_every_constraint_holds_on_the_returned_trajectory(nominal: optimal.FuelOptimalResult) -> None:
    r = nominal
    assert r.thrust.shape == (30, 3) and r.states.shape == (31, 7) and r.states_fine.shape == (121, 7)
    assert np.all(np.abs(r.thrust) <= FMAX * (1 + 1e-7))
    assert r.states_fine[:, 2].min() >= -1e-6  # altitude at every integration step
    assert np.all(np.abs(r.states[-1, :3]) < 1e-6) and np.all(np.abs(r.states[-1, 3:6]) < 1e-6)
    np.testing.assert_array_equal(r.states[0], X0)
    assert r.fuel == pytest.approx(X0[6] - r.states[-1, 6], abs=1e-12)
    assert 0.0 <= r.slack_gap < 1e-2  # N: the fuel pays for the thrust flown, no more
    # the dynamics: each node interval re-integrated by an independent adaptive method from
    # the equations written above, with the interval's force held
    for j in range(r.nodes):
        sol = solve_ivp(lambda t, x, j=j: rhs(x, r.thrust[j], True), (r.t[j], r.t[j + 1]), r.states[j],
                        method="DOP853", rtol=1e-12, atol=1e-10)
        err = np.abs(sol.y[:, -1] - r.states[j + 1])
        # RK4 at 0.25 s against the adaptive solution: mm and mm/s over an interval
        assert np.all(err[:6] < 1e-3) and err[6] < 1e-6, (j, err)


def test_the_optimum_is_coast_between_two_burns(nominal: optimal.FuelOptimalResult) -> None:
    """The fuel-optimal structure with fixed t_f: thrust, coast, thrust (zero in between)."""
    mag = np.linalg.norm(nominal.thrust, axis=1)
    off = mag < 1.0
    assert off.sum() >= 10 and off[0] == off[-1] == False  # noqa: E712
    inner = np.flatnonzero(off)
    assert np.all(np.diff(inner) == 1)  # one coast arc


def meditch_landing(z0: float, v0: float, m0: float, thrust: float) -> tuple[float, float]:
    """Free fall, then full upward thrust to rest at z = 0 (Meditch 1964: the minimum-fuel
    vertical soft landing under a thrust bound). Returns (landing time, fuel), from the
    closed-form burn: m(t) = m1 - k t with k = T/c,
    v(t) = v1 + c ln(m1/m) - g t,
    z(t) = z1 + v1 t - g t^2/2 + c (t + (m/k) ln(m/m1))."""
    k = thrust / C_EXH

    def burn_to_rest(ts: float) -> tuple[float, float]:
        z1, v1 = z0 + v0 * ts - G_MARS * ts**2 / 2, v0 - G_MARS * ts
        tau = brentq(lambda t: v1 + C_EXH * math.log(m0 / (m0 - k * t)) - G_MARS * t, 1e-9, 0.999 * m0 / k)
        m = m0 - k * tau
        z = z1 + v1 * tau - G_MARS * tau**2 / 2 + C_EXH * (tau + (m / k) * math.log(m / m0))
        return tau, z

    ts = brentq(lambda s: burn_to_rest(s)[1], 0.0, 60.0)
    tau = burn_to_rest(ts)[0]
    return ts + tau, k * tau


@pytest.mark.parametrize("free", [False, True], ids=["fixed_tf", "free_tf"])
def test_vertical_drag_free_case_is_free_fall_then_full_thrust(free: bool) -> None:
    """Drag-free, constant gravity, vertical descent: the optimum is Meditch's free-fall /
    full-thrust landing, computed here in closed form. The same problem: with no horizontal
    state, horizontal thrust only costs fuel (|F| >= |F_z|), so the 3-axis optimum is vertical.
    With t_f fixed at Meditch's landing time the optimum of the fixed-time problem is his
    landing (it is the best over every t_f); with t_f free the solver must find that time."""
    z0, v0, m0 = 1500.0, -75.0, 1905.0
    tf_star, fuel_star = meditch_landing(z0, v0, m0, FMAX)
    plant = plants.MarsLander(drag=False, thrust_limit=FMAX)
    x0 = np.array([0.0, 0.0, z0, 0.0, 0.0, v0, m0])
    if free:
        res = optimal.fuel_optimal(plant, x0, 1.1 * tf_star, free_final_time=True, nodes=40, steps_per_node=4)
        assert res.t_final == pytest.approx(tf_star, rel=2e-2)
    else:
        res = optimal.fuel_optimal(plant, x0, tf_star, nodes=40, steps_per_node=4)
    assert res.success, res.status
    # piecewise-constant thrust is a restriction of the continuous problem: never below the
    # true optimum (up to the RK4 error), above it by the switching interval's share at most
    assert fuel_star * (1 - 1e-6) <= res.fuel <= fuel_star * (1 + 2e-3), (res.fuel, fuel_star)
    assert np.abs(res.thrust[:, :2]).max() < 1.0
    burning = res.thrust[:, 2] > 1.0
    assert burning[-1] and not burning[0]  # off, then on
    assert np.all(np.diff(burning.astype(int)) >= 0)  # one switch


def rocket_bound(m0: float, dv: np.ndarray) -> float:
    """m0 (1 - exp(-|dv|/c)): the least propellant giving the velocity change dv.

    Proof: m' = -|F|/c gives integral(|F|/m) dt = c ln(m0/m_f), and |dv| = |integral(F/m) dt|
    <= integral(|F|/m) dt (triangle inequality); so m0 - m_f >= m0 (1 - exp(-|dv|/c))."""
    return m0 * (1.0 - math.exp(-np.linalg.norm(dv) / C_EXH))


def test_fuel_is_above_the_impulsive_bound(nominal: optimal.FuelOptimalResult) -> None:
    """The engine's velocity change to land in t_f from v0 is dv = -v0 + g t_f e_z - D, D the
    drag's impulse (v(t_f) = 0 = v0 + integral(F/m) + g_vec t_f + D): the initial velocity
    plus the gravity loss of t_f, less what drag does. Drag-free, D = 0; with drag, D is
    integrated here from the returned trajectory with this file's drag formula."""
    tf = 30.0
    dv_free = -X0[3:6] + np.array([0.0, 0.0, G_MARS * tf])
    free = optimal.fuel_optimal(plants.MarsLander(drag=False, thrust_limit=FMAX), X0, tf, nodes=30)
    assert free.success
    bound_free = rocket_bound(X0[6], dv_free)
    assert bound_free < free.fuel < 1.1 * bound_free
    # the library's bound is this file's, with or without a thrust limit (it uses none)
    for plant in (plants.MarsLander(drag=False), plants.MarsLander(drag=False, thrust_limit=FMAX)):
        assert optimal.impulsive_fuel_bound(plant, X0, tf) == pytest.approx(bound_free, rel=1e-12)
    a = np.array([drag(x) for x in nominal.states_fine])
    trapezoid = np.trapezoid if hasattr(np, "trapezoid") else np.trapz
    impulse = trapezoid(a, nominal.t_fine, axis=0)
    bound = rocket_bound(X0[6], dv_free - impulse)
    assert bound - 0.01 < nominal.fuel, (bound, nominal.fuel)
    assert abs(impulse).max() > 0.5  # drag is not negligible here (m/s), so this is a second check


def test_fuel_is_below_every_guidance_law(nominal: optimal.FuelOptimalResult) -> None:
    """Against the shipped presets on the same initial state (their fuel to landing)."""
    guided = {
        "fixed_time_mss": scenarios.mars_nominal().simulate(record_every=0),
        "super_twisting_standard": scenarios.mars_super_twisting("standard").simulate(record_every=0),
        "super_twisting_printed": scenarios.mars_super_twisting("printed").simulate(record_every=0),
    }
    for name, res in guided.items():
        fuel = float(res.metrics["fuel_to_settle"])
        assert nominal.fuel < fuel, (name, nominal.fuel, fuel)
    # and the preset stays within the same 40 kN per axis, so the comparison is like for like
    mss = scenarios.mars_nominal().simulate()
    assert np.abs(mss.controls).max() < FMAX


def test_replay_through_the_simulator_reproduces_the_optimum(nominal: optimal.FuelOptimalResult) -> None:
    rep = nominal.replay()
    np.testing.assert_allclose(rep.t, nominal.t_fine, atol=1e-12)
    err = np.abs(rep.states - nominal.states_fine).max(axis=0)
    # same discrete dynamics: what is left is the solver's constraint tolerance
    assert np.all(err[:3] < 1e-4) and np.all(err[3:6] < 1e-4) and err[6] < 1e-3, err
    np.testing.assert_allclose(rep.controls[:-1], np.repeat(nominal.thrust, 4, axis=0), rtol=1e-9, atol=1e-6)
    # at 1 ms (the guidance's step) the same profile lands within centimetres
    hold = round((nominal.t[1] - nominal.t[0]) / 1e-3)
    fine = landing.simulate(nominal.plant, controllers.Tabulated(force=nominal.thrust, hold=hold), X0,
                            t_final=30.0, dt=1e-3, record_every=1000)
    assert np.linalg.norm(fine.states[-1, :3]) < 0.05 and np.linalg.norm(fine.states[-1, 3:6]) < 0.01


def test_replay_under_the_sinusoid(nominal: optimal.FuelOptimalResult) -> None:
    """Seed 001 Fig. 3(c): the optimum flown open loop under a_p = sin(t) per axis. The
    disturbance's double integral is t - sin t >= 0, so a_p = +sin t lifts the lander (it ends
    about 30 m above the target, no crash); a_p = -sin t drives it into the ground before t_f.
    The fixed-time guidance lands under both."""
    up = nominal.replay(disturbances.Sinusoid(amplitude=1.0, omega=1.0))
    assert up.states[:, 2].min() > 0 and math.isnan(float(up.metrics["touchdown_time"]))
    # 30 - sin 30 = 31.0 m, less what the faster descent loses to drag (about 1 m)
    assert up.states[-1, 2] == pytest.approx(30.0 - math.sin(30.0), abs=1.5)
    down = nominal.replay(disturbances.Sinusoid(amplitude=-1.0, omega=1.0))
    assert float(down.metrics["touchdown_time"]) < 30.0 and down.states[-1, 2] < -10.0
    for amp in (1.0, -1.0):
        res = scenarios.mars_nominal(disturbance=disturbances.Sinusoid(amplitude=amp, omega=1.0)).simulate()
        assert np.linalg.norm(res.states[-1, :3]) < 1.0, amp
        assert res.states[res.t <= float(res.metrics["settle_time"]), 2].min() > -1.0, amp


# --- the tabulated law --------------------------------------------------------------------------


def test_tabulated_holds_rows_as_forces_closed_form() -> None:
    """On the double integrator (unit inertia) a force row is an acceleration; RK4 is exact for
    piecewise-constant acceleration, so positions follow the closed form."""
    rows = np.array([[1.0, -2.0, 0.5], [-1.0, 0.0, 2.0], [0.0, 3.0, -1.0]])
    hold, dt = 3, 0.1
    for after in ("zero", "hold"):
        res = landing.simulate(plants.DoubleIntegrator(), controllers.Tabulated(force=rows, hold=hold, after=after),
                               np.zeros(6), t_final=1.5, dt=dt)
        p, v = np.zeros(3), np.zeros(3)
        for k in range(15):
            j = k // hold
            a = rows[j] if j < 3 else (rows[-1] if after == "hold" else np.zeros(3))
            np.testing.assert_allclose(res.controls[k], a, atol=1e-12)
            p, v = p + v * dt + a * dt**2 / 2, v + a * dt
            np.testing.assert_allclose(res.states[k + 1, :3], p, atol=1e-12)
            np.testing.assert_allclose(res.states[k + 1, 3:], v, atol=1e-12)


def test_tabulated_per_case_tables_match_single_runs() -> None:
    rng = np.random.default_rng(3)
    tables = rng.uniform(-3e4, 3e4, size=(11, 5, 3))
    x0 = np.tile(X0, (11, 1))
    plant = plants.MarsLander()
    batch = landing.simulate_batch(plant, controllers.Tabulated(force=tables, hold=7), x0, t_final=4.0, dt=0.1)
    for i in (0, 4, 10):
        one = landing.simulate(plant, controllers.Tabulated(force=tables[i], hold=7), X0, t_final=4.0, dt=0.1)
        np.testing.assert_array_equal(batch.states[i], one.states)


def test_tabulated_per_case_tables_give_the_same_bits_at_every_level() -> None:
    """37 cases with their own tables (several blocks at every level, the last one partly
    padding): a case's bits do not depend on the instruction-set level."""
    rng = np.random.default_rng(4)
    tables = rng.uniform(-3e4, 3e4, size=(37, 6, 3))
    x0 = np.tile(X0, (37, 1)) + rng.uniform(-10.0, 10.0, (37, 7)) * [1, 1, 1, 1, 1, 1, 0]
    law = controllers.Tabulated(force=tables, hold=3, after="hold")
    runs = {level: landing.simulate_batch(plants.MarsLander(thrust_limit=25e3), law, x0, t_final=2.5, dt=0.1,
                                          kernel=level, disturbance=disturbances.Sinusoid(amplitude=0.5, omega=1.0))
            for level in LEVELS}
    for level, res in runs.items():
        assert_same_result_bits(runs["baseline"], res, f"tabulated at {level}")


@pytest.mark.parametrize("kwargs, error, match", [
    (dict(force=[]), ParameterError, "at least one row"),
    (dict(force=[1.0, 2.0, 3.0]), ParameterError, "rows, axes"),
    (dict(force=[[1.0, 2.0, 3.0]], hold=0), ParameterError, "hold"),
    (dict(force=[[1.0, 2.0, 3.0]], hold=1.5), ParameterError, "hold"),
    (dict(force=[[1.0, np.nan, 3.0]]), ParameterError, "finite"),
    (dict(force=[[1.0, 2.0, 3.0]], after="stop"), ParameterError, "after"),
])
def test_tabulated_refuses_bad_tables(kwargs: dict, error: type, match: str) -> None:
    with pytest.raises(error, match=match):
        controllers.Tabulated(**kwargs)


# --- bad input ----------------------------------------------------------------------------------


@pytest.mark.parametrize("call, error, match", [
    (lambda: optimal.fuel_optimal(plants.MarsLander(), X0), ParameterError, "no thrust limit"),
    (lambda: optimal.fuel_optimal(plants.DoubleIntegrator(), X0), ParameterTypeError, "MarsLander"),
    (lambda: optimal.fuel_optimal(plants.MarsLander(thrust_limit=FMAX), X0[:6]), ParameterError, r"\(7,\)"),
    (lambda: optimal.fuel_optimal(plants.MarsLander(thrust_limit=FMAX), np.r_[X0[:2], -1.0, X0[3:]]),
     ParameterError, "altitude"),
    (lambda: optimal.fuel_optimal(plants.MarsLander(thrust_limit=FMAX), X0, -1.0), ParameterError, "t_final"),
    (lambda: optimal.fuel_optimal(plants.MarsLander(thrust_limit=FMAX), X0, nodes=1), ParameterError, "nodes"),
    (lambda: optimal.fuel_optimal(plants.MarsLander(thrust_limit=FMAX), X0, nodes=10.0), ParameterTypeError, "nodes"),
    (lambda: optimal.fuel_optimal(plants.MarsLander(thrust_limit=FMAX), X0, t_final_bounds=(1.0, 2.0)),
     ParameterError, "free_final_time"),
    (lambda: optimal.fuel_optimal(plants.MarsLander(thrust_limit=FMAX), X0, glide_slope=89.0),
     ParameterError, "glide slope"),
    (lambda: optimal.fuel_optimal(plants.MarsLander(thrust_limit=[FMAX, FMAX]), X0), ParameterError, "thrust_limit"),
])
def test_bad_input_is_refused_by_name(call, error: type, match: str) -> None:
    with pytest.raises(error, match=match):
        call()


def test_missing_casadi_names_the_extra(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setitem(sys.modules, "casadi", None)
    with pytest.raises(ImportError, match=r'pip install "landing\[optimal\]"'):
        optimal.fuel_optimal(plants.MarsLander(thrust_limit=FMAX), X0)


def test_glide_slope_is_honoured() -> None:
    res = optimal.fuel_optimal(plants.MarsLander(thrust_limit=FMAX), X0, 30.0, nodes=30, glide_slope=20.0)
    assert res.success, res.status
    x = res.states_fine[:-1]
    assert np.all(x[:, 2] - math.tan(math.radians(20.0)) * np.sqrt(x[:, 0] ** 2 + x[:, 1] ** 2 + 1.0) >= -1e-6)


def test_a_minimum_throttle_costs_fuel(nominal: optimal.FuelOptimalResult) -> None:
    res = optimal.fuel_optimal(plants.MarsLander(thrust_limit=FMAX), X0, 30.0, nodes=30,
                               thrust_magnitude=(10e3, 60e3))
    assert res.success, res.status
    mag = np.linalg.norm(res.thrust, axis=1)
    assert mag.min() >= 10e3 * (1 - 1e-6) and mag.max() <= 60e3 * (1 + 1e-6)
    # no coasting: at least 10 kN for 30 s, and more than the free-throttle optimum
    assert res.fuel >= 10e3 * 30.0 / C_EXH and res.fuel > nominal.fuel
