"""Batches: shapes, per-case parameters, determinism, divergence."""

import numpy as np
import pytest

import landing
from _cases import RECONSTRUCTED_GAINS, dispersed

MC = dict(t_final=3.0, dt=0.001, record_every=100)


def storm():
    return [landing.disturbances.Sinusoid(amplitude=20.0, omega=1.0),
            landing.disturbances.UniformNoise(bound=0.5)]


def limited():
    return landing.plants.MarsLander(thrust_limit=50_000.0)


def test_shapes_and_names(ftmss):
    x0 = dispersed(5)
    res = landing.simulate_batch(limited(), ftmss, x0, t_final=1.0, dt=0.01, record_every=10)
    assert res.t.shape == (11,) and res.t[-1] == pytest.approx(1.0)
    assert res.states.shape == (5, 11, 7)
    assert res.controls.shape == (5, 11, 3)
    assert res.final_state.shape == (5, 7)
    assert set(res.diagnostics) == {"s1", "s2"} and res.diagnostics["s2"].shape == (5, 11, 3)
    np.testing.assert_array_equal(res.states[:, 0], x0)
    np.testing.assert_array_equal(res.states[:, -1], res.final_state)
    np.testing.assert_array_equal(res.diagnostics["s1"][:, 0], x0[:, :3])  # s1 = r - r_d
    assert res.state_names == ("rx", "ry", "rz", "vx", "vy", "vz", "m")
    assert res.control_names == ("Fx", "Fy", "Fz")
    for name in ("final_position_error", "fuel_used", "peak_command", "touchdown_time", "diverged"):
        assert res.metrics[name].shape == (5,)
    assert res.metrics.final_error.shape == (5, 3)
    one = res[2]
    assert one.states.shape == (11, 7) and one.metrics["fuel_used"].shape == ()
    np.testing.assert_array_equal(res.state("rz"), res.states[:, :, 2])


def test_record_every_zero_keeps_final_states_only(ftmss):
    x0 = dispersed(4)
    full = landing.simulate_batch(limited(), ftmss, x0, t_final=1.0, dt=0.01)
    bare = landing.simulate_batch(limited(), ftmss, x0, t_final=1.0, dt=0.01, record_every=0)
    assert bare.states.shape == (4, 0, 7) and bare.t.shape == (0,)
    np.testing.assert_array_equal(bare.final_state, full.final_state)
    for k in full.metrics:
        np.testing.assert_array_equal(bare.metrics[k], full.metrics[k])


def test_thread_count_does_not_change_a_bit(ftmss):
    x0 = dispersed(24)
    runs = [landing.simulate_batch(limited(), ftmss, x0, disturbance=storm(), seed=7, threads=k, **MC)
            for k in (1, 2)]
    assert runs[0].states.tobytes() == runs[1].states.tobytes()
    assert runs[0].controls.tobytes() == runs[1].controls.tobytes()
    assert runs[0].final_state.tobytes() == runs[1].final_state.tobytes()


def test_seed_changes_the_noise_and_only_the_noise(ftmss):
    x0 = dispersed(3)
    a = landing.simulate_batch(limited(), ftmss, x0, disturbance=storm(), seed=1, **MC)
    b = landing.simulate_batch(limited(), ftmss, x0, disturbance=storm(), seed=2, **MC)
    assert not np.array_equal(a.final_state, b.final_state)
    quiet = [landing.disturbances.Sinusoid(amplitude=20.0, omega=1.0)]
    c = landing.simulate_batch(limited(), ftmss, x0, disturbance=quiet, seed=1, **MC)
    d = landing.simulate_batch(limited(), ftmss, x0, disturbance=quiet, seed=2, **MC)
    np.testing.assert_array_equal(c.final_state, d.final_state)


def test_per_case_gains_equal_separate_runs():
    x0 = dispersed(4)
    alpha2 = np.array([0.3, 0.5, 0.7, 0.9])
    gains = dict(RECONSTRUCTED_GAINS, alpha2=alpha2)
    isp = np.array([200.0, 225.0, 250.0, 300.0])
    plant = landing.plants.MarsLander(thrust_limit=50_000.0, isp=isp)
    batch = landing.simulate_batch(plant, landing.controllers.FixedTimeMSS(**gains), x0,
                                   disturbance=storm(), seed=3, **MC)
    for i in range(4):
        law = landing.controllers.FixedTimeMSS(**dict(RECONSTRUCTED_GAINS, alpha2=alpha2[i]))
        alone = landing.simulate(landing.plants.MarsLander(thrust_limit=50_000.0, isp=isp[i]), law, x0[i],
                                 disturbance=storm(), seed=3, first_case=i, **MC)
        assert alone.states.tobytes() == batch.states[i].tobytes()
        assert alone.metrics["fuel_used"] == batch.metrics["fuel_used"][i]
    assert len(set(batch.metrics["fuel_used"])) == 4


def test_per_axis_gains_per_case():
    x0 = dispersed(2)
    beta1 = np.array([[0.8, 0.8, 0.8], [0.7, 0.8, 0.9]])
    law = landing.controllers.FixedTimeMSS(**dict(RECONSTRUCTED_GAINS, beta1=beta1))
    batch = landing.simulate_batch(limited(), law, x0, **MC)
    alone = landing.simulate(limited(),
                             landing.controllers.FixedTimeMSS(**dict(RECONSTRUCTED_GAINS, beta1=(0.7, 0.8, 0.9))),
                             x0[1], first_case=1, **MC)
    assert alone.final_state.tobytes() == batch.final_state[1].tobytes()


def test_a_diverging_case_is_flagged_and_isolated(ftmss):
    x0 = dispersed(5)
    x0[3, 0] = 1e200
    # case 3 starts 1e200 m away with a practically unlimited engine: its command overflows
    limit = np.full((5, 3), 5e4)
    limit[3] = 1e300
    plant = landing.plants.MarsLander(thrust_limit=limit)
    with pytest.warns(landing.DivergenceWarning, match="1 of 5 cases diverged"):
        res = landing.simulate_batch(plant, ftmss, x0, **MC)
    np.testing.assert_array_equal(res.metrics["diverged"], [False, False, False, True, False])
    assert np.isfinite(res.metrics["diverged_time"][3])
    assert np.all(np.isnan(res.final_state[3])) and np.isnan(res.metrics["fuel_used"][3])
    healthy = [0, 1, 2, 4]
    assert np.all(np.isfinite(res.final_state[healthy]))
    clean = landing.simulate_batch(landing.plants.MarsLander(thrust_limit=5e4), ftmss, x0[healthy], **MC)
    np.testing.assert_array_equal(res.final_state[healthy], clean.final_state)


def test_simulate_is_one_case_of_a_batch(ftmss, nominal):
    one = landing.simulate(limited(), ftmss, nominal, **MC)
    batch = landing.simulate_batch(limited(), ftmss, nominal[None, :], **MC)
    assert one.states.tobytes() == batch.states[0].tobytes()


def test_tracks_a_constant_target(ftmss, nominal):
    target = landing.reference.Constant(position=(10.0, -5.0, 2.0))
    res = landing.simulate(landing.plants.MarsLander(), ftmss, nominal, t_final=60.0, dt=0.01,
                           reference=target, record_every=0)
    np.testing.assert_allclose(res.final_state[:3], [10.0, -5.0, 2.0], atol=1e-3)
    assert res.metrics["final_position_error"] < 1e-3


def test_super_twisting_variants_run(nominal):
    for variant in ("printed", "standard"):
        law = landing.controllers.SuperTwisting(variant=variant)
        res = landing.simulate(landing.plants.MarsLander(), law, nominal, t_final=5.0, dt=0.01)
        assert not res.metrics["diverged"]
        assert set(res.diagnostics) == {"sigma", "w"}
    # the standard variant's integral state obeys w' = -b2 sgn(sigma), per axis
    res = landing.simulate(landing.plants.MarsLander(), landing.controllers.SuperTwisting(variant="standard"),
                           nominal, t_final=1.0, dt=0.01)
    w, sigma = res.diagnostics["w"], res.diagnostics["sigma"]
    np.testing.assert_allclose(np.diff(w, axis=0), -0.01 * np.array([5500.0, 5000, 5000]) * np.sign(sigma[:-1]))
