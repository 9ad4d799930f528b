"""Study behind the default singularity guards (docs/parameters.md).

FixedTimeMSS(variant="exact") raises |s1| to q1 - 1 < 0 and the printed SuperTwisting raises
|s| to -1/2: both are floored at a named guard (s1_floor, s_floor). One batch per law sweeps the
floor per case on the nominal landing of the Mars fixed-time guidance paper and reports what the guard changes.

    python examples/studies/singularity_guards.py
"""

from __future__ import annotations

import numpy as np

import landing

FLOORS = np.logspace(-9, 0, 10)
X0 = np.array([-2000.0, 1000.0, 1500.0, 100.0, -15.0, -75.0, 1905.0])
GAINS = dict(beta1=0.8, beta2=0.4, q1=0.95, q2=1.05, alpha1=0.9, alpha2=0.5, gamma1=0.9, gamma2=1.1)


def tail_variation(res: landing.SimulationResult, t_from: float) -> np.ndarray:
    """Total variation of the thrust per second after t_from (chattering near the target)."""
    k = res.t >= t_from
    u = res.controls[:, k, :]
    return np.abs(np.diff(u, axis=1)).sum(axis=(1, 2)) / (res.t[k][-1] - res.t[k][0])


def report(name: str, res: landing.SimulationResult, t_from: float) -> None:
    m = res.metrics
    tv = tail_variation(res, t_from)
    print(f"\n{name}")
    print(f"  {'floor':>8} {'|r(tf)| m':>11} {'|v(tf)| m/s':>12} {'fuel kg':>9} {'peak N':>10} {'TV/s after ' + str(t_from) + ' s':>18}")
    for i, f in enumerate(FLOORS):
        print(f"  {f:8.0e} {m['final_position_error'][i]:11.3e} {m['final_velocity_error'][i]:12.3e} "
              f"{m['fuel_used'][i]:9.3f} {m['peak_command'][i]:10.4g} {tv[i]:18.4g}")


def main() -> None:
    plant = landing.plants.MarsLander()
    x0 = np.tile(X0, (FLOORS.size, 1))
    exact = landing.controllers.FixedTimeMSS(**GAINS, variant="exact", s1_floor=FLOORS)
    res = landing.simulate_batch(plant, exact, x0, t_final=60.0, dt=1e-3, record_every=10)
    report("FixedTimeMSS, exact variant, s1_floor swept (nominal case, 60 s, dt 1 ms)", res, 50.0)

    st = landing.controllers.SuperTwisting(variant="printed", s_floor=FLOORS)
    res = landing.simulate_batch(plant, st, x0, t_final=60.0, dt=1e-3, record_every=10)
    report("SuperTwisting, printed variant, s_floor swept (nominal case, 60 s, dt 1 ms)", res, 50.0)


if __name__ == "__main__":
    main()
