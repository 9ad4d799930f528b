"""The Mars gains study (examples/studies/mars_gains.py) as a landing.tune call.

The same eight gains of FixedTimeMSS (printed variant), the same box (log10 for the gains, the
exponents as is), the same requirements on the nominal Table I case, at the same search step
(dt = 5 ms), then the best rounded to three digits and checked at the shipped 1 ms:

  R1  peak thrust below 40 kN                     max(peak_command) < 40e3
  R2  precise soft landing at 60 s                max(final_position_error) < 0.1, max(final_velocity_error) < 0.1
  R3  fuel to landing within 2 % of 238.29 kg     abs(mean(fuel_to_settle) - 238.2907) <= 4.7658
  R4' under a_p = 20 sin t, |r| within          max(storm.settle_time) <= 40
      sqrt(3) x 23.85 m from 40 s on
  R5  T1 <= 745.78 s, T2 <= 308.22 s              t1 <= 745.78, t2 <= 308.22
  objective: the shortest landing                 mean(nominal.settle_time)

Two set-ups share the gains: "nominal" (Table I, no disturbance, 1 m settle tolerance) and
"storm" (the same case under a_p = 20 sin t with a sqrt(3) x 23.8472 m settle tolerance, so that
its settle_time is when |r| enters that ball for good). The study's R4 (each |r_i| within
23.85 m over the last 20 s) reads the trajectory, which no metric holds; R4' (the norm within
sqrt(3) x 23.85 m) is implied by it, so the search keeps every gain set R4 allows. Then, as
the hand-written study's stage 3 does, the 200 best feasible evaluations are rounded to three
digits and checked against R1-R5 exactly (R4 on the recorded trajectory) at the shipped 1 ms
step, with the hand-written study's own checks (mars_gains.evaluate, mars_gains.feasible), and
the one with the shortest landing that meets them all is chosen.

    python examples/studies/tune_mars.py [--budget 3000] [--seed 1]
"""

from __future__ import annotations

import argparse
import math
import sys
import time
import warnings
from pathlib import Path

import numpy as np

import landing
from landing.scenarios import MARS_FIXED_TIME_GAINS

sys.path.insert(0, str(Path(__file__).parent))
import mars_gains  # noqa: E402 - the hand-written study's exact checks

SEED_FUEL = 238.2907
SEED_BOUND = 23.8472
GAINS = {
    "beta1": (10**-1.5, 10.0, "log"), "q1": (0.2, 0.95),
    "beta2": (1e-7, 0.1, "log"), "q2": (1.01, 2.0),
    "alpha1": (0.1, 100.0, "log"), "gamma1": (0.05, 0.95),
    "alpha2": (1e-7, 1.0, "log"), "gamma2": (1.01, 2.0),
}
OBJECTIVE = "mean(nominal.settle_time)"
CONSTRAINTS = [
    "max(nominal.peak_command) < 40e3",
    "max(nominal.final_position_error) < 0.1",
    "max(nominal.final_velocity_error) < 0.1",
    f"abs(mean(nominal.fuel_to_settle) - {SEED_FUEL}) <= {0.02 * SEED_FUEL:.4f}",
    "max(storm.settle_time) <= 40",
    "t1 <= 745.78",
    "t2 <= 308.22",
]


def storm_amplitude(scenario: landing.scenarios.Scenario) -> float:
    """R4: the largest |r_i| over the last 20 s of the nominal case under a_p = 20 sin t."""
    s = scenario.replace(disturbance=landing.disturbances.Sinusoid(amplitude=20.0, omega=1.0), record_every=500)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", landing.DivergenceWarning)
        res = s.simulate()
    tail = res.t >= 40.0
    return float(np.abs(res.states[tail, :3]).max())


def report(label: str, scenario: landing.scenarios.Scenario) -> None:
    m = scenario.simulate(record_every=0).metrics
    law = scenario.controller
    t1 = landing.theory.fixed_time_bound(law.beta1, law.q1, law.beta2, law.q2)
    t2 = landing.theory.fixed_time_bound(law.alpha1, law.gamma1, law.alpha2, law.gamma2)
    print(f"{label}: settle {m['settle_time']:.2f} s, fuel to landing {m['fuel_to_settle']:.2f} kg, "
          f"peak {m['peak_command'] / 1e3:.2f} kN, |r| {m['final_position_error']:.2e} m, "
          f"|v| {m['final_velocity_error']:.2e} m/s, T1 {t1:.2f} s, T2 {t2:.2f} s, "
          f"storm {storm_amplitude(scenario):.2f} m (R4 asks <= {SEED_BOUND})")


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--budget", type=int, default=6000)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--popsize", type=int, default=60)
    ap.add_argument("--threads", type=int, default=None)
    args = ap.parse_args()
    base = landing.scenarios.mars_nominal(dt=5e-3, record_every=0)
    storm = base.replace(name="mars_nominal_storm", settle_tolerance=math.sqrt(3) * SEED_BOUND,
                         disturbance=landing.disturbances.Sinusoid(amplitude=20.0, omega=1.0))
    t0 = time.perf_counter()
    result = landing.tune({"nominal": base, "storm": storm}, GAINS, OBJECTIVE, CONSTRAINTS, cases=1, budget=args.budget, seed=args.seed,
                          popsize=args.popsize, threads=args.threads)
    print(f"landing.tune, dt = 5 ms [{time.perf_counter() - t0:.0f} s]:")
    print(result)
    feasible = np.flatnonzero(result.feasible)
    top = feasible[np.argsort(result.objective_values[feasible, 0], kind="stable")][:200]
    names = result.gain_names
    cand = {n: np.array([float(f"{result.x[i, j]:.3g}") for i in top]) for j, n in enumerate(names)}
    check = mars_gains.evaluate(cand, 1e-3)
    ok = mars_gains.feasible(check)
    print(f"stage 3: the {top.size} best feasible evaluations, rounded to three digits, at dt = 1 ms: "
          f"{int(ok.sum())} meet R1-R5 (R4 exactly)")
    if not ok.any():
        print("none meets R1-R5 exactly; the best of the search is reported")
        pick = 0
    else:
        pick = int(np.flatnonzero(ok)[np.argmin(np.nan_to_num(check["settle"][ok], nan=1e9))])
    rounded = {n: float(cand[n][pick]) for n in names}
    print("chosen gains: " + ", ".join(f"{k}={v:.3g}" for k, v in rounded.items()))
    report("tuned, at dt = 1 ms", landing.scenarios.mars_nominal(controller=rounded))
    report("preset (hand-written study), at dt = 1 ms",
           landing.scenarios.mars_nominal(controller=dict(MARS_FIXED_TIME_GAINS)))
    report("preset mars_fast (an earlier seed-1 search's choice), at dt = 1 ms", landing.scenarios.mars_fast())
    print(f"total {time.perf_counter() - t0:.0f} s")


if __name__ == "__main__":
    main()
