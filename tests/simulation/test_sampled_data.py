"""The zero-order-hold semantics (docs/guide/semantics.md), against a hand computation in numpy."""

import numpy as np
import pytest

import landing
from _cases import G_MARS, RECONSTRUCTED_GAINS

AREA = np.array([6.0, 7.5, 8.7])


def sig(x, a):
    return np.sign(x) * np.abs(x) ** a


def eq25(r, v, drift, g=RECONSTRUCTED_GAINS):
    """Seed 001 eq. 25 as printed, written independently of the core."""
    b1, b2, q1, q2 = g["beta1"], g["beta2"], g["q1"], g["q2"]
    s2 = v + b1 * sig(r, q1) + b2 * sig(r, q2)
    return (-drift + b1**2 * q1 * sig(r, 2 * q1 - 1) + b2**2 * q2 * sig(r, 2 * q2 - 1)
            + b1 * b2 * (q1 + q2) * sig(r, q1 + q2 - 1)
            - g["alpha1"] * sig(s2, g["gamma1"]) - g["alpha2"] * sig(s2, g["gamma2"]))


def mars_rhs(x, force):
    r, v, m = x[:3], x[3:6], x[6]
    drag = -0.699 * v * np.abs(v) * np.exp(-0.0009 * r[2]) / (AREA * m)
    a = force / m + np.array([0, 0, -G_MARS]) + drag
    return np.r_[v, a, -np.linalg.norm(force) / (225.0 * 9.807)]


def drift(x):
    return mars_rhs(x, np.zeros(3))[3:6]


@pytest.mark.parametrize("integrator", ["euler", "rk4"])
def test_one_period_by_hand(nominal, ftmss, integrator):
    dt = 0.05
    force = nominal[6] * eq25(nominal[:3], nominal[3:6], drift(nominal))
    if integrator == "euler":
        expect = nominal + dt * mars_rhs(nominal, force)
    else:  # the force is held over all four stages
        k1 = mars_rhs(nominal, force)
        k2 = mars_rhs(nominal + dt / 2 * k1, force)
        k3 = mars_rhs(nominal + dt / 2 * k2, force)
        k4 = mars_rhs(nominal + dt * k3, force)
        expect = nominal + dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
    res = landing.simulate(landing.plants.MarsLander(), ftmss, nominal, t_final=dt, dt=dt, integrator=integrator)
    np.testing.assert_allclose(res.controls[0], force, rtol=1e-11)
    np.testing.assert_allclose(res.final_state, expect, rtol=1e-11)
    # the second recorded command is computed from the new state
    x1 = res.final_state
    np.testing.assert_allclose(res.controls[1], x1[6] * eq25(x1[:3], x1[3:6], drift(x1)), rtol=1e-10)


def test_substeps_hold_the_command(nominal, ftmss):
    """With substeps the command is still computed once per period."""
    dt, n = 0.05, 5
    force = nominal[6] * eq25(nominal[:3], nominal[3:6], drift(nominal))
    x = nominal.copy()
    for _ in range(n):
        x = x + dt / n * mars_rhs(x, force)
    res = landing.simulate(landing.plants.MarsLander(), ftmss, nominal, t_final=dt, dt=dt,
                           integrator="euler", substeps=n)
    np.testing.assert_allclose(res.final_state, x, rtol=1e-11)


def test_sinusoid_is_evaluated_at_stage_times():
    """Coasting without gravity under 20 sin(t): with the disturbance at each stage's time RK4
    is 4th-order accurate (errors ~1e-6 at dt = 0.1); a disturbance held over the period
    would be off by ~A dt / 2 = 1 m/s."""
    plant = landing.plants.MarsLander(drag=False, gravity=0.0)
    x0 = np.array([0, 0, 100.0, 0, 0, 0, 1000.0])
    dist = landing.disturbances.Sinusoid(amplitude=20.0, omega=1.0)
    res = landing.simulate(plant, landing.controllers.OpenLoop(), x0, t_final=6.0, dt=0.1, disturbance=dist)
    np.testing.assert_allclose(res.states[:, 3], 20 * (1 - np.cos(res.t)), atol=2e-5)
    np.testing.assert_allclose(res.states[:, 0], 20 * (res.t - np.sin(res.t)), atol=2e-5)
