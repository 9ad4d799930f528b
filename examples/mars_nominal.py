"""The Mars fixed-time guidance paper, nominal case (Table I): the fixed-time
multiple-sliding-surface guidance lands the Mars lander. Prints fuel, landing state and peak
thrust beside the paper's printed figures, for the preset gains (docs/parameters.md) and for
the reconstruction from the printed bounds, which reproduces the paper's bounds T1 = 74.578 s and T2 = 30.822 s but not its other figures.

    python examples/mars_nominal.py
"""

from __future__ import annotations

import numpy as np

import landing

SEED_FUEL_KG = 238.2907  # the Mars paper, Fig. 4
SEED_PEAK_THRUST_N = 4e4  # the Mars paper, Fig. 2(c): "less than 4 x 10^4 N"
RECONSTRUCTION = dict(beta1=0.8, beta2=0.4, q1=0.95, q2=1.05, alpha1=0.9, alpha2=0.5, gamma1=0.9, gamma2=1.1)


def report(title: str, scenario: landing.scenarios.Scenario) -> None:
    res = scenario.simulate()
    m = res.metrics
    print(title)
    print(f"  gains: {scenario.controller}")
    print(f"  fuel to landing   {m['fuel_to_settle']:10.2f} kg   (paper: {SEED_FUEL_KG} kg; landing = |r| within 1 m)")
    print(f"  landing time      {m['settle_time']:10.2f} s")
    print(f"  peak thrust       {np.max(m['peak_command_axis']):10.4g} N per axis (paper: below {SEED_PEAK_THRUST_N:.0e} N)")
    if np.isfinite(m["touchdown_time"]):
        print(f"  touchdown         t = {m['touchdown_time']:.3f} s, velocity "
              f"{np.array2string(m['touchdown_velocity'], precision=3)} m/s")
    else:
        print("  touchdown         none: the altitude comes to 0 from above without crossing it")
    print(f"  state at {scenario.t_final:g} s     r = {np.array2string(res.final_state[:3], precision=3)} m, "
          f"v = {np.array2string(res.final_state[3:6], precision=3)} m/s, m = {res.final_state[6]:.2f} kg")
    b = landing.theory.mss_bounds(scenario.controller)
    print(f"  bounds            T1 = {b.t1[0]:.4f} s, T2 = {b.t2[0]:.4f} s (paper: 74.5780 s, 30.8217 s)\n")


def main() -> None:
    report("Preset gains (tuning study)", landing.scenarios.mars_nominal())
    law = landing.controllers.FixedTimeMSS(**RECONSTRUCTION)
    report("reconstruction from the printed bounds", landing.scenarios.mars_nominal(controller=law))


if __name__ == "__main__":
    main()
