"""Every law runs on every three-axis plant (SPEC 5: "every one available on every compatible
plant"): from a 10 m offset each brings the plant to its target. Gains are moderate and shared,
with two physical exceptions: the super-twisting gains are in force units and so scale with the
plant's inertia, and the fuzzy-blended FTSMC drops its equivalent control (gravity cancellation
included) far from the surface (seed 000 eq. 20), so its switching gain must exceed the plant's
gravity, and near the surface the blend leaves a steady offset unless b(D) rises fast
(M = 10): 0.5 m/s^2 suffices near an asteroid, the Mars lander needs 5."""

import numpy as np
import pytest

import landing
from landing import controllers as C
from landing import plants

TARGET_SB = np.array([2000.0, 500.0, 8000.0])

PLANTS = {
    "double_integrator": (plants.DoubleIntegrator(), np.zeros(3), np.zeros(0), 1.0, 0.5),
    "small_body": (plants.SmallBody(gravity=landing.gravity.Harmonic2(), omega=1.65e-4), TARGET_SB, np.zeros(0), 1.0,
                   0.5),
    "mars_lander": (plants.MarsLander(), np.zeros(3), np.array([1905.0]), 1905.0, 5.0),
}


def laws(inertia, blend_k):
    return {
        "fixed_time_mss": C.FixedTimeMSS(**landing.scenarios.MARS_FIXED_TIME_GAINS),
        "super_twisting": C.SuperTwisting(b1=2.0 * inertia, b2=0.2 * inertia, c=0.5, variant="standard"),
        "pd_sliding_mode": C.PDSlidingMode(lambda_=0.5, k=0.5, switch="tanh", boundary_layer=1.0),
        "fast_terminal_smc": C.FastTerminalSMC(alpha=0.5, beta=0.3, p=3, q=5, k=0.5, switch="tanh", boundary_layer=1.0),
        "fuzzy_fast_terminal_smc": C.FuzzyFastTerminalSMC(alpha=0.5, beta=0.3, p=3, q=5, k=blend_k, n=1.0, m=10.0,
                                                          switch="tanh", boundary_layer=1.0),
        "integral_exponential_reaching": C.IntegralExponentialReaching(c1=0.25, c2=1.0, k=0.5, epsilon=0.01,
                                                                       switch="sat", boundary_layer=0.1),
        "fuzzy_variable_rate": C.FuzzyVariableRate(c1=0.25, c2=1.0, k=0.5, ke=10.0, kec=1.0, ku=0.003),
    }


@pytest.mark.parametrize("plant_name", list(PLANTS))
def test_every_law_lands_on_every_plant(plant_name):
    plant, target, extra, inertia, blend_k = PLANTS[plant_name]
    x0 = np.r_[target + [10.0, -10.0, 10.0], [0.5, 0.0, -0.5], extra]
    failures = []
    for name, law in laws(inertia, blend_k).items():
        res = landing.simulate(plant, law, x0, t_final=60.0, dt=0.01, record_every=0,
                               reference=landing.reference.Constant(position=target))
        m = res.metrics
        if m["diverged"] or not m["final_position_error"] < 0.5 or not m["final_velocity_error"] < 0.5:
            failures.append((name, float(m["final_position_error"]), float(m["final_velocity_error"])))
    assert not failures, failures
