"""Your own plant, written in Python (docs/own-law.md, "A plant of your own").

A lunar lander the library does not ship: a point mass under lunar gravity with a throttleable
engine whose thrust is limited in magnitude (not per axis, as the built-in Mars lander's) and
points up only, burning propellant by the rocket equation. It is written as a
``landing.plants.PythonPlant`` (its dynamics, its model for the law, its actuator and its
domain) and flown by the built-in fixed-time MSS guidance and by a PD law written in Python,
each as a 100-case campaign from a dispersed approach, then the PD law is tuned on it.

    python examples/own_plant.py [--cases 100] [--budget 60]
"""

from __future__ import annotations

import argparse

import numpy as np

import landing
from landing import controllers as C
from landing import dispersions, plants

G_MOON = 1.62  # m/s^2
G0 = 9.807  # m/s^2, the rocket equation's standard gravity


def lunar_derivative(t, x, u, params):
    """r' = v, v' = F / m + g, m' = -|F| / (isp g0): the state is [r (3), v (3), m]."""
    m = x[:, 6:7]
    a = u / m + np.array([0.0, 0.0, -G_MOON])
    mdot = -np.linalg.norm(u, axis=1, keepdims=True) / (params["isp"][:, None] * G0)
    return np.concatenate([x[:, 3:6], a, mdot], axis=1)


def lunar_model(t, x, params):
    """What the law may cancel (gravity) and the inertia its command is scaled by (the mass)."""
    n = len(x)
    return np.tile([0.0, 0.0, -G_MOON], (n, 1)), np.repeat(x[:, 6:7], 3, axis=1)


def lunar_engine(t, x, a, params):
    """The thrust for the commanded acceleration: F = m a, pointing up only (F_z >= 0) and
    scaled down to the engine's limit in magnitude, keeping its direction."""
    f = a * x[:, 6:7]
    f[:, 2] = np.maximum(f[:, 2], 0.0)
    limit = params["max_thrust"][:, None]
    norm = np.linalg.norm(f, axis=1, keepdims=True)
    return f * np.minimum(1.0, limit / np.maximum(norm, 1e-300))


def lunar_domain(t, x, params):
    """Propellant left: the mass above the dry mass."""
    return x[:, 6] > params["dry_mass"]


LUNAR_LANDER = plants.PythonPlant(
    lunar_derivative, 7, positions=(0, 1, 2), velocities=(3, 4, 5),
    model=lunar_model, actuate=lunar_engine, in_domain=lunar_domain,
    params={"isp": 311.0, "max_thrust": 45_000.0, "dry_mass": 6_800.0},
    state_names=("rx", "ry", "rz", "vx", "vy", "vz", "m"), control_names=("Fx", "Fy", "Fz"),
    mass=6, altitude=2, name="lunar lander",
)

#: Approach: 40 m off the site, 400 m up, coming down at 15 m/s; dispersed per component.
APPROACH = np.array([40.0, -30.0, 400.0, -2.0, 1.0, -15.0, 15_000.0])
SPREAD = np.array([10.0, 10.0, 20.0, 1.0, 1.0, 1.0, 50.0])


def pd(t, e, de, ref, drift, inertia, params, memory):
    """PD with gravity cancelled: e'' = -kp e - kd e'."""
    return ref.acceleration - drift - params["kp"] * e - params["kd"] * de


def summary(name: str, mc: landing.MonteCarloResult) -> str:
    m = mc.metrics
    return (f"{name}: {mc.n_cases} cases, 60 s: final position error median {np.median(m['final_position_error']):.3g} m, "
            f"max {m['final_position_error'].max():.3g} m; final velocity error max {m['final_velocity_error'].max():.3g} m/s; "
            f"fuel used median {np.median(m['fuel_used']):.1f} kg")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cases", type=int, default=100)
    ap.add_argument("--budget", type=int, default=60)
    args = ap.parse_args()

    base = landing.scenarios.Scenario(
        name="lunar_landing", description="a lunar lander written in Python (examples/own_plant.py)",
        plant=LUNAR_LANDER, controller=C.PythonLaw(pd, params={"kp": 0.05, "kd": 0.5}),
        x0=APPROACH, dispersion=dispersions.Normal(mean=APPROACH, std=SPREAD),
        t_final=60.0, dt=0.05, record_every=0, settle_tolerance=1.0,
    )
    laws = {
        "fixed-time MSS (built in)": C.FixedTimeMSS(beta1=1.3, q1=0.589, beta2=0.0242, q2=1.18, alpha1=4.89,
                                                   gamma1=0.319, alpha2=0.0129, gamma2=1.42),
        "PD (Python)": base.controller,
    }
    for name, law in laws.items():
        mc = landing.monte_carlo(base.replace(controller=law), args.cases, seed=1, progress=False, check_bounds=False)
        print(summary(name, mc))

    result = landing.tune(base, {"kp": (0.005, 0.5, "log"), "kd": (0.05, 5.0, "log")},
                          "mean(fuel_used)", ["max(final_position_error) <= 1.0", "max(final_velocity_error) <= 0.5"],
                          cases=8, budget=args.budget, seed=2, progress=False)
    g = result.best_gains
    print(f"PD tuned ({result.n_evaluations} evaluations on 8 cases): kp = {g['kp']:.4g}, kd = {g['kd']:.4g}, "
          f"mean fuel {result.best_objectives['mean(fuel_used)']:.1f} kg, feasible {result.best_feasible}")
    tuned = landing.monte_carlo(base.replace(controller=base.controller.replace(**g)), args.cases, seed=1,
                                progress=False, check_bounds=False)
    print(summary("PD tuned", tuned))


if __name__ == "__main__":
    main()
