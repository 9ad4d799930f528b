"""The Mars lander's actuator: the command's delay and the engine's lag, against their
definitions (the shift by whole periods, the exponential step response) and the limits."""

import numpy as np
import pytest

import landing
from _cases import G_MARS, RECONSTRUCTED_GAINS, assert_within_engine_limits, dispersed

C, P = landing.controllers, landing.plants
X0 = np.array([0.0, 0.0, 5000.0, 0.0, 0.0, 0.0, 1905.0])


def commanded(t):
    """A command that differs at every instant: acceleration (n, 3) at times t (n,)."""
    t = np.asarray(t, dtype=float)
    return np.stack([np.sin(t), 0.5 * np.cos(3 * t), G_MARS + 0.2 * t], axis=-1)


def by_time(t, e, de, ref, drift, inertia, params, memory):
    return commanded(np.full(e.shape[0], t))


LAW = C.PythonLaw(by_time, name="by_time")


@pytest.mark.parametrize("delay", [1, 3, 7])
def test_a_delay_applies_the_command_of_exactly_k_periods_before(delay):
    plant = P.MarsLander(drag=False, control_delay=delay)
    res = landing.simulate(plant, LAW, X0, t_final=2.0, dt=0.05, record_every=1)
    t, u, m = res.t, res.controls, res.states[:, 6]
    # the force the engine was asked for at instant j is m_j a(t_j) (no limits): applied k later
    asked = m[:, None] * commanded(t)
    np.testing.assert_array_equal(u[delay:], asked[:-delay])
    # before the first command arrives: a zero command (no limits here)
    np.testing.assert_array_equal(u[:delay], 0.0)
    undelayed = landing.simulate(P.MarsLander(drag=False), LAW, X0, t_final=2.0, dt=0.05, record_every=1)
    np.testing.assert_array_equal(undelayed.controls, undelayed.states[:, 6, None] * commanded(undelayed.t))


def test_before_the_first_command_an_always_on_engine_gives_its_least_thrust():
    plant = P.MarsLander(drag=False, control_delay=2, thrust_magnitude_limit=40_000.0, min_throttle=0.3)
    res = landing.simulate(plant, LAW, X0, t_final=0.5, dt=0.05, record_every=1)
    np.testing.assert_allclose(res.controls[:2], [[0.0, 0.0, 12_000.0]] * 2, rtol=1e-15)


def step(t, e, de, ref, drift, inertia, params, memory):
    a = np.where(t < 1.0, 1.0, 3.0)
    return np.tile([0.5 * a, 0.0, a], (e.shape[0], 1))


@pytest.mark.parametrize("tau", [0.2, 0.7])
def test_the_lag_follows_the_exponential_step_response(tau):
    # an engine that burns no propellant (isp 1e30: m' rounds to 0), so F = m a is a true step
    plant = P.MarsLander(drag=False, gravity=0.0, isp=1e30, engine_time_constant=tau)
    m = 1905.0
    dt = 1e-3
    res = landing.simulate(plant, C.PythonLaw(step), X0, t_final=3.0, dt=dt, record_every=1)
    assert np.all(res.states[:, 6] == m)
    t = res.t
    s = np.clip(t - 1.0, 0.0, None)
    # F(t) = F2 + (F1 - F2) exp(-(t - 1) / tau) after the step at t = 1, F1 before (steady state)
    fz = np.where(t < 1.0, m * 1.0, m * (3.0 + (1.0 - 3.0) * np.exp(-s / tau)))
    np.testing.assert_allclose(res.controls[:, 2], fz, rtol=1e-13)
    np.testing.assert_allclose(res.controls[:, 0], 0.5 * fz, rtol=1e-13)
    # and the velocity integrates it: vz = int F/m = t before, 1 + 3 s - 2 tau (1 - exp(-s / tau)) after
    vz = np.where(t < 1.0, t, 1.0 + 3.0 * s - 2.0 * tau * (1.0 - np.exp(-s / tau)))
    # RK4 on the exact exponential: the global error is O((dt / tau)^4) tau
    np.testing.assert_allclose(res.states[:, 5], vz, atol=1e-9)


def test_lag_and_delay_compose_and_the_limits_hold_at_every_instant_of_a_dispersed_campaign():
    n = 48
    rng = np.random.default_rng(11)
    t_max = rng.uniform(25_000.0, 45_000.0, n)
    throttle = rng.uniform(0.1, 0.4, n)
    pointing = rng.uniform(0.2, 1.2, n)
    tau = rng.uniform(0.0, 0.5, n)
    delay = rng.integers(0, 4, n).astype(float)
    plant = P.MarsLander(thrust_magnitude_limit=t_max, min_throttle=throttle, pointing_limit=pointing,
                         engine_time_constant=tau, control_delay=delay)
    law = C.FixedTimeMSS(**RECONSTRUCTED_GAINS)
    x0 = dispersed(n)
    res = landing.simulate_batch(plant, law, x0, t_final=15.0, dt=0.01, record_every=1)
    u = res.controls
    live = assert_within_engine_limits(u, t_max, throttle, pointing, cone_binds=False)
    assert live.sum() > n * 100
    # every case equals the same case run alone, at one thread and at two (lanes mix delays)
    two = landing.simulate_batch(plant, law, x0, t_final=15.0, dt=0.01, record_every=1, threads=2)
    np.testing.assert_array_equal(two.controls, u)
    for i in (0, 5, 17, n - 1):
        solo = landing.simulate(
            P.MarsLander(thrust_magnitude_limit=t_max[i], min_throttle=throttle[i], pointing_limit=pointing[i],
                         engine_time_constant=tau[i], control_delay=delay[i]),
            law, x0[i], t_final=15.0, dt=0.01, record_every=1)
        np.testing.assert_array_equal(solo.controls, u[i])


def test_a_python_law_is_delayed_and_lagged_as_a_built_in_one_is():
    # the built-in open-loop command and the same command from Python: one actuator, same bits
    plant = P.MarsLander(thrust_magnitude_limit=40_000.0, min_throttle=0.2, pointing_limit=0.5,
                         engine_time_constant=np.array([0.0, 0.3, 0.8]), control_delay=np.array([2.0, 0.0, 5.0]))
    a = (1.0, -2.0, 30.0)

    def constant(t, e, de, ref, drift, inertia, params, memory):
        return np.tile(a, (e.shape[0], 1))

    x0 = np.tile(X0, (3, 1))
    kw = dict(t_final=3.0, dt=0.02, record_every=1)
    built_in = landing.simulate_batch(plant, C.OpenLoop(acceleration=a), x0, **kw)
    python = landing.simulate_batch(plant, C.PythonLaw(constant), x0, **kw)
    np.testing.assert_array_equal(python.controls, built_in.controls)
    np.testing.assert_array_equal(python.states, built_in.states)
    # the three cases differ: the actuator acts per case
    assert not np.array_equal(built_in.controls[0], built_in.controls[1])
    assert not np.array_equal(built_in.controls[1], built_in.controls[2])


def test_the_actuator_is_checked_naming_the_rule():
    for kwargs, message in [
        (dict(control_delay=1.5), r"control_delay an integer in \[0, 1000\]"),
        (dict(control_delay=-1), r"control_delay an integer in \[0, 1000\]"),
        (dict(control_delay=2000), r"control_delay an integer in \[0, 1000\]"),
        (dict(engine_time_constant=-0.1), "engine_time_constant >= 0"),
        (dict(engine_time_constant=np.inf), "engine_time_constant = inf violates finite values"),
        (dict(engine_time_constant=np.nan), "engine_time_constant = NaN violates finite values"),
    ]:
        with pytest.raises(landing.ParameterError, match=message):
            P.MarsLander(**kwargs)
