"""Your own control law, written in Python (docs/own-law.md).

Two laws on the Mars lander of the Monte Carlo of the Mars fixed-time guidance paper (Table II
dispersions, the paper's disturbance), each run as a 100-case campaign beside the preset's built-in law, and the first
tuned:

1. a PD law with model cancellation, ``a = q_ref'' - drift - kp e - kd e'``;
2. a sliding-mode law with an internal state: the integral sliding surface
   ``s = e' + 2 lam e + lam^2 z``, ``z' = e`` (the integral of the error, the law's memory,
   advanced by forward Euler over each control period), the equivalent control of s' = 0 and a
   boundary-layer switch ``-k tanh(s / phi)``.

    python examples/own_law.py [--cases 100] [--budget 60]
"""

from __future__ import annotations

import argparse

import numpy as np

import landing
from landing import controllers as C


def pd(t, e, de, ref, drift, inertia, params, memory):
    """PD with model cancellation: e'' = -kp e - kd e'."""
    return ref.acceleration - drift - params["kp"] * e - params["kd"] * de


def integral_smc(t, e, de, ref, drift, inertia, params, memory):
    """Integral sliding mode: s = e' + 2 lam e + lam^2 z with z' = e."""
    lam, k, phi, dt = params["lam"], params["k"], params["phi"], params["dt"]
    z = memory["z"]
    s = de + 2 * lam * e + lam**2 * z
    # s' = e'' + 2 lam e' + lam^2 e = 0 with e'' = drift + a - q_ref''
    a = ref.acceleration - drift - 2 * lam * de - lam**2 * e - k * np.tanh(s / phi)
    return a, {"z": z + dt * e}, {"s": s}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cases", type=int, default=100)
    ap.add_argument("--budget", type=int, default=60)
    args = ap.parse_args()

    base = landing.scenarios.mars_monte_carlo()
    dt = base.dt
    laws = {
        "the preset's fixed-time MSS law (built in)": base.controller,
        "PD": C.PythonLaw(pd, params={"kp": 0.04, "kd": 0.4}),
        "integral SMC": C.PythonLaw(integral_smc, params={"lam": 0.15, "k": 0.5, "phi": 1.0, "dt": dt},
                                    memory={"z": np.zeros(3)}, diagnostics=("s",)),
    }
    for name, law in laws.items():
        scenario = base.replace(controller=law, record_every=0)
        mc = landing.monte_carlo(scenario, args.cases, seed=1, progress=False, check_bounds=False)
        m = mc.metrics
        print(f"{name}: {args.cases} cases, 60 s: final position error median {np.median(m['final_position_error']):.3g} m, "
              f"max {m['final_position_error'].max():.3g} m; fuel used median {np.median(m['fuel_used']):.1f} kg")

    # tune the PD law's gains: least fuel with every case within 25 m of the target at 60 s
    scenario = base.replace(controller=laws["PD"], record_every=0)
    result = landing.tune(scenario, {"kp": (1e-3, 0.2, "log"), "kd": (0.02, 2.0, "log")},
                          "mean(fuel_used)", ["max(final_position_error) <= 25.0"],
                          cases=8, budget=args.budget, seed=2, progress=False)
    g = result.best_gains
    print(f"PD tuned ({result.n_evaluations} evaluations on 8 cases): kp = {g['kp']:.4g}, kd = {g['kd']:.4g}, "
          f"mean fuel {result.best_objectives['mean(fuel_used)']:.1f} kg, feasible {result.best_feasible}")


if __name__ == "__main__":
    main()
