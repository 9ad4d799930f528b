"""The Mars lander and the integrators against closed forms and hand computations."""

import numpy as np
import pytest

import landing
from _cases import G_MARS, RECONSTRUCTED_GAINS, assert_within_engine_limits, dispersed

ISP, G0 = 225.0, 9.807


def coast(plant, x0, t_final, dt, **kw):
    return landing.simulate(plant, landing.controllers.OpenLoop(), x0, t_final=t_final, dt=dt, **kw)


def test_free_fall_is_a_parabola():
    x0 = np.array([10.0, -20.0, 1500.0, 3.0, 4.0, -75.0, 1905.0])
    res = coast(landing.plants.MarsLander(drag=False), x0, 12.0, 0.05)
    t = res.t
    np.testing.assert_allclose(res.states[:, 0], 10 + 3 * t, atol=1e-9)
    np.testing.assert_allclose(res.states[:, 2], 1500 - 75 * t - 0.5 * G_MARS * t**2, atol=1e-8)
    np.testing.assert_allclose(res.states[:, 5], -75 - G_MARS * t, atol=1e-10)
    assert np.all(res.states[:, 6] == 1905.0)
    assert res.metrics["fuel_used"] == 0.0


def rocket(t, m0, v0, fmax):
    """Closed form of constant thrust along x: m = m0 - b t, v = v0 + c ln(m0/m)."""
    c = ISP * G0
    b = fmax / c
    m = m0 - b * t
    v = v0 + c * np.log(m0 / m)
    x = v0 * t + c * (t + (m / b) * np.log(m / m0))
    return x, v, m


def burn(dt, integrator, t_final=60.0, fmax=50_000.0):
    plant = landing.plants.MarsLander(drag=False, thrust_limit=fmax)
    law = landing.controllers.OpenLoop(acceleration=(1e6, 0.0, 0.0))  # saturates: constant force
    x0 = np.array([0, 0, 1e4, 5.0, 0, 0, 1905.0])
    return landing.simulate(plant, law, x0, t_final=t_final, dt=dt, integrator=integrator, record_every=0)


def test_constant_thrust_follows_the_rocket_equation():
    res = burn(0.01, "rk4")
    x, v, m = rocket(60.0, 1905.0, 5.0, 50_000.0)
    assert res.final_state[6] == pytest.approx(m, rel=1e-12)
    assert res.final_state[3] == pytest.approx(v, rel=1e-10)
    assert res.final_state[0] == pytest.approx(x, rel=1e-10)
    assert res.metrics["fuel_used"] == pytest.approx(1905.0 - m, rel=1e-12)
    assert res.metrics["peak_command"] == pytest.approx(50_000.0)


@pytest.mark.parametrize("integrator, order, steps", [("rk4", 4, (2.0, 1.0, 0.5)), ("euler", 1, (0.02, 0.01, 0.005))])
def test_global_error_order(integrator, order, steps):
    """The velocity error of the burn falls as dt^order (ln m is not polynomial in t)."""
    _, v, _ = rocket(60.0, 1905.0, 5.0, 50_000.0)
    err = [abs(burn(dt, integrator).final_state[3] - v) for dt in steps]
    observed = np.log2(np.array(err[:-1]) / np.array(err[1:]))
    assert np.all(np.abs(observed - order) < 0.15 * order), (err, observed)


def test_drag_opposes_motion_and_matches_eq_12():
    """One Euler period of a coasting lander without gravity isolates the drag."""
    plant = landing.plants.MarsLander(gravity=0.0)
    v0 = np.array([100.0, -15.0, -75.0])
    x0 = np.r_[-2000, 1000, 1500, v0, 1905.0]
    dt = 1e-3
    res = coast(plant, x0, dt, dt, integrator="euler")
    accel = (res.final_state[3:6] - v0) / dt
    assert np.all(np.sign(accel) == -np.sign(v0))
    expect = -0.699 * v0 * np.abs(v0) * np.exp(-0.0009 * 1500) / (np.array([6.0, 7.5, 8.7]) * 1905.0)
    np.testing.assert_allclose(accel, expect, rtol=1e-8)  # (v1 - v0) / dt loses ~6 digits


def test_touchdown_time_and_velocity():
    x0 = np.array([0, 0, 100.0, 2.0, 0, -10.0, 1000.0])
    res = coast(landing.plants.MarsLander(drag=False), x0, 10.0, 0.01, record_every=0)
    t_star = (-10 + np.sqrt(100 + 2 * G_MARS * 100)) / G_MARS
    assert res.metrics["touchdown_time"] == pytest.approx(t_star, abs=1e-5)
    np.testing.assert_allclose(res.metrics["touchdown_velocity"], [2.0, 0, -10 - G_MARS * t_star], atol=1e-3)
    np.testing.assert_allclose(res.metrics["touchdown_position"][:2], [2.0 * t_star, 0], atol=1e-3)
    assert res.metrics["touchdown_speed"] == pytest.approx(np.hypot(2.0, 10 + G_MARS * t_star), abs=1e-3)


def test_thrust_is_clipped_per_axis_and_recorded_after_saturation(nominal, ftmss):
    plant = landing.plants.MarsLander(thrust_limit=(50_000.0, 40_000.0, 30_000.0))
    res = landing.simulate(plant, ftmss, nominal, t_final=5.0, dt=0.01)
    peak = np.abs(res.controls).max(axis=0)
    np.testing.assert_allclose(peak, [50_000.0, 40_000.0, 30_000.0])
    np.testing.assert_allclose(res.metrics["peak_command_axis"], peak)


def test_an_engine_with_throttle_and_pointing_limits_meets_them_over_a_dispersed_campaign():
    # per-case limits (a dispersion of the engine), under a law that asks for far more than it
    # can give: every applied thrust is within the throttle range and the pointing cone
    n = 64
    rng = np.random.default_rng(7)
    t_max = rng.uniform(20_000.0, 45_000.0, n)
    throttle = rng.uniform(0.1, 0.4, n)
    pointing = rng.uniform(0.2, 1.2, n)
    plant = landing.plants.MarsLander(thrust_magnitude_limit=t_max, min_throttle=throttle, pointing_limit=pointing)
    law = landing.controllers.FixedTimeMSS(**RECONSTRUCTED_GAINS)
    x0 = dispersed(n)
    res = landing.simulate_batch(plant, law, x0, t_final=20.0, dt=0.01, record_every=1)
    u = res.controls  # (n, instants, 3): the applied force
    live = assert_within_engine_limits(u, t_max, throttle, pointing)
    assert live.sum() > n * 100
    mag = np.linalg.norm(u, axis=2)
    # the mass burns the applied thrust: m' = -|F| / (isp g0) over each held period
    dm = res.states[:, 1:, 6] - res.states[:, :-1, 6]
    expect = -mag[:, :-1] * 0.01 / (225.0 * 9.807)
    ok = live[:, :-1] & live[:, 1:]
    np.testing.assert_allclose(dm[ok], expect[ok], rtol=1e-9)


def test_the_engine_limits_are_checked_naming_the_rule():
    P = landing.plants.MarsLander
    for kwargs, message in [
        (dict(min_throttle=0.2), "min_throttle > 0 needs a thrust_magnitude_limit"),
        (dict(thrust_magnitude_limit=4e4, min_throttle=1.0), "0 <= min_throttle < 1"),
        (dict(pointing_limit=2.0), "0 < pointing_limit <= pi/2"),
        (dict(thrust_magnitude_limit=-1.0), "thrust_magnitude_limit > 0"),
        (dict(thrust_magnitude_limit=4e4, thrust_limit=5e4), "not combined with thrust_magnitude_limit"),
    ]:
        with pytest.raises(landing.ParameterError, match=message):
            P(**kwargs)
