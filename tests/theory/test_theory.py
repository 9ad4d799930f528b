"""Seed 001's bounds: the printed numbers, and each formula against a simulation of the law
it speaks about."""

import numpy as np
import pytest

import landing
from _cases import RECONSTRUCTED_GAINS
from landing import theory
from landing.controllers import FixedTimeMSS, OpenLoop
from landing.plants import DoubleIntegrator


def test_the_reconstructed_gains_give_the_seed_bounds():
    assert round(theory.fixed_time_bound(0.8, 0.95, 0.4, 1.05), 4) == 74.5780
    assert round(theory.fixed_time_bound(0.9, 0.9, 0.5, 1.1), 4) == 30.8217
    b = theory.mss_bounds(FixedTimeMSS(**RECONSTRUCTED_GAINS))
    np.testing.assert_allclose(b.t1, 74.578022, atol=1e-6)
    np.testing.assert_allclose(b.t2, 30.821670, atol=1e-6)


def test_practical_formulas_against_their_definitions():
    # eq. 6 / 40: the fixed-time bound divided by theta; eq. 38: the radius where
    # (1 - theta) times the weaker of the two reaching terms meets the disturbance bound
    c1, e1, c2, e2, d, th = 0.9, 0.9, 0.5, 1.1, 20.0, 0.2
    fixed = theory.fixed_time_bound(c1, e1, c2, e2)
    assert theory.practical_time_bound(c1, e1, c2, e2, th) == pytest.approx(fixed / th)
    r = theory.practical_radius(c1, e1, c2, e2, d, th)
    assert r == pytest.approx(min((d / ((1 - th) * c1)) ** (1 / e1), (d / ((1 - th) * c2)) ** (1 / e2)))
    b = theory.mss_bounds(FixedTimeMSS(**RECONSTRUCTED_GAINS), ap_max=d, theta1=th, theta2=0.1)
    np.testing.assert_allclose(b.s2_radius, r)
    np.testing.assert_allclose(b.s1_radius, theory.practical_radius(0.8, 0.95, 0.4, 1.05, r, 0.1))
    np.testing.assert_allclose(b.settle_time, b.s2_time + b.s1_time)
    np.testing.assert_allclose(b.printed_time, np.maximum(b.s2_time, b.s1_time))


def test_bounds_broadcast_over_per_case_gains():
    law = FixedTimeMSS(**dict(RECONSTRUCTED_GAINS, alpha1=[0.5, 0.9, 2.0]))
    assert theory.mss_bounds(law).t2.shape == (3,)  # read per axis
    law = FixedTimeMSS(**dict(RECONSTRUCTED_GAINS, alpha1=np.array([[0.5], [0.9], [2.0], [4.0]])))
    t2 = theory.mss_bounds(law).t2
    assert t2.shape == (4, 3) and np.all(np.diff(t2[:, 0]) < 0)


@pytest.mark.parametrize("gains", [
    (0.9, 0.9, 0.5, 1.1),     # eq. 26 with the reconstruction
    (0.8, 0.95, 0.4, 1.05),   # eq. 18 with the reconstruction
    (0.05, 0.5, 0.05, 1.5),
    (3.0, 0.2, 0.02, 2.0),
])
def test_fixed_time_bound_holds_in_simulation(gains):
    """From initial values spanning nine decades, the scalar reaching law reaches 1e-6 before
    the bound; the bound is not vacuous (the slowest case takes a sizeable share of it)."""
    s0 = np.array([[1e-3, -1.0, 30.0], [-300.0, 3e3, 1e4], [-1e5, 3e5, 1e6]])
    if gains[3] >= 2.0:
        s0 = s0 / 1e3  # a steep super-linear term needs a tiny step for large s0; keep it quick
    check = theory.check_fixed_time_bound(*gains, s0)
    assert check.ok, check
    assert check.worst_ratio > 0.15, check
    # after reaching, it stays (the sampled law chatters within its band, below the tolerance)
    assert np.all(check.extra["max_after_entry"] <= check.extra["tolerance"])


def test_a_violation_is_reported():
    check = theory.check_fixed_time_bound(0.9, 0.9, 0.5, 1.1, [100.0])
    wrong = theory.BoundCheck("too tight", bound=check.bound / 10, measured=check.measured)
    assert not wrong.ok and wrong.violations.tolist() == [0]
    assert "VIOLATED" in repr(wrong)


@pytest.mark.parametrize("theta", [0.2, 0.5, 0.8])
def test_practical_bound_holds_in_simulation(theta):
    check = theory.check_practical_bound(0.9, 0.9, 0.5, 1.1, [[0.0, 50.0, -500.0], [5e3, -2e4, 1e5]],
                                         d_max=20.0, theta=theta, omega=1.0)
    assert check.ok, check
    assert np.all(check.extra["max_after_entry"] <= check.extra["radius"])


def test_the_first_reaching_law_on_the_real_guidance():
    """Exact FixedTimeMSS on a double integrator, started on s2 = 0: s1 follows eq. 16 and
    reaches 1e-6 within T1, for any distance."""
    law = FixedTimeMSS(**RECONSTRUCTED_GAINS, variant="exact")
    r0 = np.array([[-8000.0, -6000.0, -4000.0], [-2000.0, -1000.0, 1e5]])
    sig = lambda x, a: np.sign(x) * np.abs(x) ** a  # noqa: E731
    v0 = -0.8 * sig(r0, 0.95) - 0.4 * sig(r0, 1.05)
    res = landing.simulate_batch(DoubleIntegrator(), law, np.concatenate([r0, v0], axis=1),
                                 t_final=80.0, dt=1e-3, record_every=10)
    reach = theory.entry_time(res.t, res.diagnostics["s1"], 1e-6)
    assert np.all(reach <= theory.fixed_time_bound(0.8, 0.95, 0.4, 1.05))
    # it stayed on the second surface, up to the O(dt) drift of the held command
    drift = np.abs(res.diagnostics["s2"]).max(axis=1) / np.abs(v0)
    assert np.all(drift < 1e-3), drift


def test_theorem4_on_the_real_guidance():
    """Exact FixedTimeMSS on a double integrator under a bounded disturbance: s2 and s1 stay in
    the neighbourhoods of eq. 39 and 31 from the times of eq. 40 and 40 + 45 on."""
    law = FixedTimeMSS(beta1=1.0, q1=0.7, beta2=0.5, q2=1.3, alpha1=3.0, gamma1=0.6, alpha2=1.0, gamma2=1.4,
                       variant="exact")
    d = [landing.disturbances.Sinusoid(amplitude=(3.0, 2.0, 1.0), omega=(1.0, 2.0, 0.5)),
         landing.disturbances.UniformNoise(bound=0.5)]
    b = theory.mss_bounds(law, theory.disturbance_bound(d), theta1=0.5, theta2=0.5)
    np.testing.assert_allclose(b.ap_max, [3.5, 2.5, 1.5])
    rng = np.random.default_rng(5)
    x0 = np.concatenate([rng.normal(0, 300, (12, 3)), rng.normal(0, 30, (12, 3))], axis=1)
    horizon = float(np.ceil(b.settle_time.max())) + 5
    res = landing.simulate_batch(DoubleIntegrator(), law, x0, t_final=horizon, dt=2e-3, disturbance=d,
                                 record_every=5, seed=3)
    checks = theory.check_mss(res, b)
    for name, c in checks.items():
        assert np.all(c.extra["checkable"])
        assert c.ok, (name, c)


def test_remark1_times_against_a_full_thrust_run():
    """Full thrust towards the target on a double integrator with an acceleration limit: the
    position first reaches 0 at tf1 and the velocity reaches 0 at tf2 (Remark 1, gravity on z)."""
    a, g = 5.0, -3.7114
    r0 = np.array([-200.0, 150.0, 300.0])
    v0 = np.array([10.0, -5.0, -20.0])
    tf1, tf2 = theory.min_final_time(r0, v0, a, [0.0, 0.0, g])
    # towards the target: the sign of -r0; the plant's gravity is the disturbance here
    law = OpenLoop(acceleration=-np.sign(r0) * 1e6)
    res = landing.simulate(DoubleIntegrator(acceleration_limit=a), law, np.r_[r0, v0], t_final=40.0, dt=1e-3,
                           disturbance=landing.disturbances.Constant([0.0, 0.0, g]))
    x = res.states
    for j in range(3):
        k = np.flatnonzero(np.sign(x[:, j]) != np.sign(r0[j]))[0]
        crossing = res.t[k - 1] + (res.t[k] - res.t[k - 1]) * x[k - 1, j] / (x[k - 1, j] - x[k, j])
        assert crossing == pytest.approx(tf1[j], abs=2e-3)
    # thrust against the velocity instead: it stops at tf2
    law = OpenLoop(acceleration=-np.sign(v0) * 1e6)
    res = landing.simulate(DoubleIntegrator(acceleration_limit=a), law, np.r_[r0, v0], t_final=40.0, dt=1e-3,
                           disturbance=landing.disturbances.Constant([0.0, 0.0, g]))
    for j in range(3):
        v = res.states[:, 3 + j]
        k = np.flatnonzero(np.sign(v) != np.sign(v0[j]))[0]
        assert res.t[k] == pytest.approx(tf2[j], abs=2e-3)


def test_time_to_rest_is_a_lower_bound_for_every_run():
    """No thrust-limited landing in the Table III sweep comes to rest faster than the
    time-optimal bound (computed at the lightest mass any case reaches)."""
    mc = landing.monte_carlo(landing.scenarios.mars_thrust_limited(), 20, seed=4, record_every=10)
    light = 1905.0 - np.nanmax(mc.metrics["fuel_used"])
    bound = theory.min_time_to_rest(mc.x0[:, :3], mc.x0[:, 3:6], 50e3 / light, [0, 0, -3.7114]).max(axis=1)
    rest = theory.settle_time(mc.t, mc.states[:, :, :6], 1e-3).max(axis=1)
    assert np.all(rest >= bound)
