"""The small body's actuator: a magnitude limit on the control acceleration beside the per-axis
one, the command's delay and the thrusters' lag (the Mars lander's actuator, on a plant
commanded in acceleration), against their definitions."""

import numpy as np
import pytest

import landing

C, P, G = landing.controllers, landing.plants, landing.gravity
# far from Eros, where the field is weak: the states stay finite whatever the command
X0 = np.array([60_000.0, 0.0, 0.0, 0.0, 0.0, 0.0])


def commanded(t):
    t = np.asarray(t, dtype=float)
    return np.stack([np.sin(t), 0.5 * np.cos(3 * t), 0.2 + 0.1 * t], axis=-1)


def by_time(t, e, de, ref, drift, inertia, params, memory):
    return commanded(np.full(e.shape[0], t))


@pytest.mark.parametrize("delay", [1, 4])
def test_a_delay_applies_the_command_of_exactly_k_periods_before(delay):
    res = landing.simulate(P.SmallBody(control_delay=delay), C.PythonLaw(by_time), X0, t_final=2.0, dt=0.05,
                           record_every=1)
    np.testing.assert_array_equal(res.controls[delay:], commanded(res.t)[:-delay])
    np.testing.assert_array_equal(res.controls[:delay], 0.0)


def step(t, e, de, ref, drift, inertia, params, memory):
    a = np.where(t < 1.0, 0.01, 0.03)
    return np.tile([a, -0.5 * a, 0.0], (e.shape[0], 1))


def test_the_lag_follows_the_exponential_step_response():
    tau = 0.4
    res = landing.simulate(P.SmallBody(engine_time_constant=tau), C.PythonLaw(step), X0, t_final=3.0, dt=1e-3,
                           record_every=1)
    s = np.clip(res.t - 1.0, 0.0, None)
    ux = np.where(res.t < 1.0, 0.01, 0.03 + (0.01 - 0.03) * np.exp(-s / tau))
    np.testing.assert_allclose(res.controls[:, 0], ux, rtol=1e-13)
    np.testing.assert_allclose(res.controls[:, 1], -0.5 * ux, rtol=1e-13)


def test_the_magnitude_and_per_axis_limits_hold_together_on_every_applied_command():
    n = 32
    rng = np.random.default_rng(5)
    box = rng.uniform(0.02, 0.08, (n, 3))
    ball = rng.uniform(0.03, 0.1, n)
    tau = rng.uniform(0.0, 0.3, n)
    delay = rng.integers(0, 3, n).astype(float)
    plant = P.SmallBody(acceleration_limit=box, acceleration_magnitude_limit=ball, engine_time_constant=tau,
                        control_delay=delay)

    def wild(t, e, de, ref, drift, inertia, params, memory):
        k = int(round(t / 0.05))
        return np.random.default_rng(k).normal(0.0, 0.2, e.shape)

    res = landing.simulate_batch(plant, C.PythonLaw(wild), np.tile(X0, (n, 1)), t_final=5.0, dt=0.05, record_every=1)
    u = res.controls
    assert np.all(np.abs(u) <= box[:, None, :])
    norm = np.linalg.norm(u, axis=-1)
    assert np.all(norm <= ball[:, None])
    # both bind somewhere
    assert np.any(norm > ball[:, None] * (1 - 1e-12))
    assert np.any(np.isclose(np.abs(u), box[:, None, :], rtol=1e-12, atol=0.0))
    # without a lag or delay, a command inside both is applied as it is; one outside the ball
    # only is scaled along its own direction
    within = landing.simulate(P.SmallBody(acceleration_magnitude_limit=1.0),
                              C.OpenLoop(acceleration=[0.3, -0.4, 0.0]), X0, t_final=0.1, dt=0.05, record_every=1)
    np.testing.assert_array_equal(within.controls, [[0.3, -0.4, 0.0]] * 3)
    scaled = landing.simulate(P.SmallBody(acceleration_magnitude_limit=0.25),
                              C.OpenLoop(acceleration=[0.3, -0.4, 0.0]), X0, t_final=0.1, dt=0.05, record_every=1)
    np.testing.assert_allclose(scaled.controls, [[0.15, -0.2, 0.0]] * 3, rtol=1e-15)


def test_the_small_body_actuator_is_checked_naming_the_rule():
    for kwargs, message in [
        (dict(control_delay=0.5), r"control_delay an integer in \[0, 1000\]"),
        (dict(engine_time_constant=-1.0), "engine_time_constant >= 0"),
        (dict(acceleration_magnitude_limit=0.0), "acceleration_magnitude_limit > 0"),
    ]:
        with pytest.raises(landing.ParameterError, match=message):
            P.SmallBody(**kwargs)
