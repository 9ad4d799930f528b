"""Every law runs on every plant ("every one available on every compatible plant").

Three-axis plants: from a 10 m offset each law brings the plant to its target. Gains are
moderate and shared, with two physical exceptions: the super-twisting gains are in force units
and so scale with the plant's inertia, and the fuzzy-blended FTSMC drops its equivalent control (gravity cancellation
included) far from the surface (seed 000 eq. 20), so its switching gain must exceed the plant's
gravity, and near the surface the blend leaves a steady offset unless b(D) rises fast
(M = 10): 0.5 m/s^2 suffices near an asteroid, the Mars lander needs 5.

The tethered satellite (two axes, rad): from seed 003's 1 degree on both angles each law settles
both within 0.02 degree under the 0.1 N limit. Its command authority is tiny (about 1e-4 rad/s^2
in-plane), so the gains are in rad and rad/s^2: switching gains below that authority, the
fuzzy blend's D scaled by M = 1e4 to act at milliradian distances, the singularity floors below
the tolerance."""

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
        "ntsmc": C.NTSMC(alpha=1.0, beta=[0.5] * 3, gamma=[1.5] * 3, k=[0.5] * 3),
        "fixed_time_ntsmc": C.FixedTimeNTSMC(k1=0.5, k2=0.5, k3=0.5, eps_max=0.0, p1=1.1, p2=0.6, alpha_s=0.7,
                                             beta_s=1.5, sigma_phi=0.01, gamma=0.0, rbf_scale_e1=10.0,
                                             rbf_scale_e2=1.0, rbf_width=1.0),
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


def tether_laws(inertia):
    layer = dict(switch="sat", boundary_layer=1e-3)
    terminal = dict(alpha=[0.1, 0.5], beta=[1e-3, 0.05], p=1, q=5, k=[2e-5, 1e-3], e_floor=1e-4, **layer)
    surface = dict(c1=[0.0025, 0.0625], c2=[0.1, 0.5], k=0.1)
    return {
        "fixed_time_mss": C.FixedTimeMSS(beta1=[0.05, 0.5], q1=0.6, beta2=[0.01, 0.1], q2=1.2, alpha1=[0.1, 1.0],
                                         gamma1=0.6, alpha2=[0.01, 0.1], gamma2=1.2, s1_floor=1e-6),
        "super_twisting": C.SuperTwisting(b1=list(2e-3 * inertia), b2=list(2e-5 * inertia), c=[0.05, 0.5],
                                          variant="standard"),
        "pd_sliding_mode": C.PDSlidingMode(lambda_=[0.1, 0.5], k=[2e-5, 1e-3], **layer),
        "fast_terminal_smc": C.FastTerminalSMC(**terminal),
        "fuzzy_fast_terminal_smc": C.FuzzyFastTerminalSMC(**terminal, n=1.0, m=1e4),
        "integral_exponential_reaching": C.IntegralExponentialReaching(**surface, epsilon=[2e-5, 1e-3], **layer),
        "fuzzy_variable_rate": C.FuzzyVariableRate(**surface, ke=[1e4, 1e3], kec=[1e5, 1e4], ku=[4e-6, 2e-4]),
        "ntsmc": C.NTSMC(),
        "fixed_time_ntsmc": C.FixedTimeNTSMC(),
    }


def test_every_law_settles_the_tethered_satellite():
    plant = plants.TetheredSatellite(fidelity="simplified")
    x0 = plant.initial_state(np.radians(1.0), np.radians(1.0))
    tol = np.radians(0.02)
    failures = []
    for name, law in tether_laws(plant.inertia).items():
        res = landing.simulate(plant, law, x0, t_final=300.0, dt=0.01, record_every=0, settle_tolerance=tol)
        q, _ = plant.coordinates(res.final_state)
        if res.metrics["diverged"] or not res.metrics["settle_time"] < 300.0 or not np.all(np.abs(q) < tol):
            failures.append((name, float(res.metrics["settle_time"]), np.degrees(q).tolist()))
    assert not failures, failures
