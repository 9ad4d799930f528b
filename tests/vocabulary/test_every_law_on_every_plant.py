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
from _cases import laws, tether_laws
from landing import plants

TARGET_SB = np.array([2000.0, 500.0, 8000.0])


def double_integrator(t, x, u, params):
    """The double integrator written in Python: the engine integrates it stage by stage."""
    return np.concatenate([x[:, 3:], u], axis=1)


PLANTS = {
    "double_integrator": (plants.DoubleIntegrator(), np.zeros(3), np.zeros(0), 1.0, 0.5),
    "small_body": (plants.SmallBody(gravity=landing.gravity.Harmonic2(), omega=1.65e-4), TARGET_SB, np.zeros(0), 1.0,
                   0.5),
    "mars_lander": (plants.MarsLander(), np.zeros(3), np.array([1905.0]), 1905.0, 5.0),
    "python_plant": (plants.PythonPlant(double_integrator, 6, positions=(0, 1, 2), velocities=(3, 4, 5)),
                     np.zeros(3), np.zeros(0), 1.0, 0.5),
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
