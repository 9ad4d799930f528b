"""Events that end a case: ``stop_at="touchdown"`` ends each lander case at its first crossing
of the ground, located inside the step, and freezes it there. Checked against the closed form
of a drag-free free fall (a parabola), and for what must not change: bits across threads,
levels and chunks, the same law written in Python, the same plant written in Python."""

from __future__ import annotations

import numpy as np
import pytest

import landing
from _cases import LEVELS, write_file
from landing import controllers as C
from landing import plants as P
from landing.errors import ParameterError

G = 3.7114
ISP, G0 = 225.0, 9.807
#: a constant commanded acceleration (the thrust is m a at each control instant)
A = np.array([0.3, -0.2, 1.5])
PLANT = P.MarsLander(drag=False, gravity=G, isp=ISP)
LAW = C.OpenLoop(acceleration=A)


def states(n: int, seed: int = 0) -> np.ndarray:
    rng = np.random.default_rng(seed)
    x = np.empty((n, 7))
    x[:, 0:2] = rng.uniform(-50, 50, (n, 2))
    x[:, 2] = rng.uniform(100, 400, n)
    x[:, 3:5] = rng.uniform(-3, 3, (n, 2))
    x[:, 5] = rng.uniform(-30, -5, n)
    x[:, 6] = rng.uniform(1500, 1900, n)
    return x


def closed_form(x0: np.ndarray) -> dict[str, np.ndarray]:
    """The touchdown of a free fall, r'' = g, from x0: the first root of z0 + vz0 t - g t^2 / 2,
    and the position and velocity there."""
    z0, vz0 = x0[:, 2], x0[:, 5]
    t = (vz0 + np.sqrt(vz0 ** 2 + 2 * G * z0)) / G
    acc = np.array([0.0, 0.0, -G])
    r = x0[:, 0:3] + x0[:, 3:6] * t[:, None] + 0.5 * acc * t[:, None] ** 2
    v = x0[:, 3:6] + acc * t[:, None]
    return {"t": t, "r": r, "v": v}


def run(x0, **kw):
    kw = {"t_final": 30.0, "dt": 1e-2, "stop_at": "touchdown", **kw}
    return landing.simulate_batch(PLANT, kw.pop("law", LAW), x0, **kw)


def test_a_free_fall_touches_down_at_the_closed_form_to_1e_9():
    x0 = states(40)
    exact = closed_form(x0)
    assert exact["t"].max() < 30.0
    res = run(x0, law=C.OpenLoop())
    m = res.metrics
    np.testing.assert_allclose(m["touchdown_time"], exact["t"], rtol=0, atol=1e-9)
    np.testing.assert_allclose(m["touchdown_position"][:, :2], exact["r"][:, :2], rtol=0, atol=1e-9)
    np.testing.assert_allclose(m["touchdown_velocity"], exact["v"], rtol=0, atol=1e-9)
    np.testing.assert_allclose(m["touchdown_speed"], np.linalg.norm(exact["v"], axis=1), rtol=0, atol=1e-9)
    # frozen at the event: on the ground, with the event's velocity, no fuel burnt
    np.testing.assert_allclose(res.final_state[:, 2], 0.0, atol=1e-9)
    np.testing.assert_allclose(res.final_state[:, 3:6], exact["v"], rtol=0, atol=1e-9)
    np.testing.assert_array_equal(res.final_state[:, 6], x0[:, 6])
    assert not m["diverged"].any()


def test_under_thrust_the_frozen_mass_is_the_burn_until_the_event():
    # a thrust held per period burns m' = -|T| / (Isp g0) until the event, and nothing after
    x0 = states(20)
    res = run(x0)
    t_event = res.metrics["touchdown_time"]
    assert np.isfinite(t_event).all()
    long = run(x0, dt=1e-3, t_final=30.0)
    # the event's mass against a ten times finer run of the same law (O(dt) apart: the hold)
    np.testing.assert_allclose(long.final_state[:, 6], res.final_state[:, 6], rtol=1e-4)
    np.testing.assert_allclose(res.metrics["fuel_used"], x0[:, 6] - res.final_state[:, 6], rtol=1e-12)


def test_without_the_event_the_case_flies_on_and_touchdown_is_still_located():
    x0 = states(10)
    exact = closed_form(x0)
    res = run(x0, law=C.OpenLoop(), stop_at=None)
    np.testing.assert_allclose(res.metrics["touchdown_time"], exact["t"], rtol=0, atol=1e-9)
    assert (res.final_state[:, 2] < -100).all()  # below the ground at t_final


def test_nothing_accumulates_after_the_event():
    x0 = states(12)
    short, long = run(x0, t_final=30.0), run(x0, t_final=60.0)
    np.testing.assert_array_equal(long.final_state, short.final_state)
    for name in short.metrics:
        if name == "settle_time":
            continue
        np.testing.assert_array_equal(np.asarray(long.metrics[name]), np.asarray(short.metrics[name]), err_msg=name)
    # the recording ends at the event: NaN from the first recorded instant after it
    t_event = short.metrics["touchdown_time"]
    after = short.t[None, :] > t_event[:, None] + short.t[1]
    assert np.isnan(short.states[after]).all()
    assert np.isfinite(short.states[short.t[None, :] < t_event[:, None]]).all()


def test_a_frozen_case_keeps_its_error_at_the_event_whatever_its_block_does():
    # under a moving reference the law's input goes on changing after a case lands, for the
    # block's lanes that still fly: the landed case's final errors are those at its event's step
    ref = landing.reference.Cubic.from_boundary([0.0, 0.0, 300.0], [0.0, 0.0, -10.0], [0.0, 0.0, -50.0],
                                                [0.0, 0.0, -2.0], 20.0, after="extend")
    x0 = states(16)
    x0[1, 2] = 5_000.0  # a case that never lands keeps its block running to t_final
    together = run(x0, reference=ref)
    landed = np.flatnonzero(np.isfinite(together.metrics["touchdown_time"]))
    assert landed.size >= 12 and 1 not in landed
    for i in landed[:4]:
        alone = run(x0[i:i + 1], reference=ref)
        for name in ("final_error", "final_rate_error", "final_position_error", "settle_time"):
            np.testing.assert_array_equal(alone.metrics[name][0], together.metrics[name][i], err_msg=name)
    # and the error is the frozen state against the reference at the end of the event's step
    i = landed[0]
    step = np.ceil(together.metrics["touchdown_time"][i] / 1e-2) * 1e-2
    p, v, _ = ref.evaluate(np.array([step]))
    np.testing.assert_allclose(together.metrics["final_error"][i], together.final_state[i, :3] - p[0], atol=1e-9)
    np.testing.assert_allclose(together.metrics["final_rate_error"][i], together.final_state[i, 3:6] - v[0],
                               atol=1e-9)


@pytest.mark.parametrize("level", LEVELS)
def test_the_same_bits_at_every_level_thread_count_and_chunk(level):
    x0 = states(37)
    ref = run(x0, threads=1, kernel="baseline")
    for threads in (1, 2):
        res = run(x0, threads=threads, kernel=level)
        np.testing.assert_array_equal(res.final_state, ref.final_state)
        np.testing.assert_array_equal(res.metrics["touchdown_time"], ref.metrics["touchdown_time"])
    parts = [run(x0[a:b], kernel=level) for a, b in ((0, 5), (5, 21), (21, 37))]
    np.testing.assert_array_equal(np.concatenate([p.final_state for p in parts]), ref.final_state)


def test_a_python_law_and_a_python_plant_stop_at_the_same_event():
    x0 = states(9)
    ref = run(x0)
    python_law = C.PythonLaw(lambda t, e, de, r, drift, inertia, params, memory: np.broadcast_to(A, e.shape).copy())
    np.testing.assert_array_equal(run(x0, law=python_law).final_state, ref.final_state)

    def derivative(t, x, u, params):
        m = x[:, 6:7]
        return np.concatenate([x[:, 3:6], u / m + np.array([0.0, 0.0, -G]),
                               -np.linalg.norm(u, axis=1, keepdims=True) / (ISP * G0)], axis=1)

    plant = P.PythonPlant(derivative, 7, positions=(0, 1, 2), velocities=(3, 4, 5), mass=6, altitude=2,
                          model=lambda t, x, params: (np.tile([0.0, 0.0, -G], (len(x), 1)), np.repeat(x[:, 6:7], 3, 1)))
    res = landing.simulate_batch(plant, LAW, x0, t_final=30.0, dt=1e-2, stop_at="touchdown")
    np.testing.assert_allclose(res.final_state, ref.final_state, rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(res.metrics["touchdown_time"], ref.metrics["touchdown_time"], rtol=0, atol=1e-12)


def test_a_plant_without_an_altitude_or_an_unknown_event_is_refused():
    with pytest.raises(ParameterError, match="stop_at = 'touchdown' needs a plant with an altitude"):
        landing.simulate(P.DoubleIntegrator(), C.OpenLoop(), np.zeros(6), t_final=1.0, dt=0.1, stop_at="touchdown")
    with pytest.raises(ParameterError, match="stop_at"):
        run(states(2), stop_at="landing")


def test_scenarios_files_and_campaigns_take_the_event(tmp_path):
    s = landing.scenarios.mars_monte_carlo(t_final=60.0, dt=1e-2, record_every=10).replace(stop_at="touchdown")
    text = s.to_toml()
    assert 'stop_at = "touchdown"' in text
    back = landing.scenarios.Scenario.load(str(write_file(tmp_path, text)))
    assert back.stop_at == "touchdown"
    whole = landing.monte_carlo(s, 8, seed=2, progress=False, check_bounds=False)
    chunked = landing.monte_carlo(back, 8, seed=2, chunk_size=3, progress=False, check_bounds=False)
    np.testing.assert_array_equal(chunked.result.final_state, whole.result.final_state)
    # the seed's guidance arrives fast: each case is frozen on the ground at its touchdown
    m = whole.metrics
    landed = np.isfinite(m["touchdown_time"])
    assert landed.any()
    np.testing.assert_allclose(whole.result.final_state[landed, 2], 0.0, atol=1e-9)
