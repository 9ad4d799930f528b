"""Study behind the super-twisting comparison (docs/parameters.md, docs/reproduction-mars.md).

The Mars fixed-time guidance paper's baseline (eq. 46, B1 = (1200, 1000, 1000),
B2 = (5500, 5000, 5000)) "lands in 30 s with 277.1 kg". With the gains as printed (divided by the mass, as eq. 46 writes them):

1. the printed variant is run for 300 s to see when it lands;
2. the standard variant's slope c (not in the paper) is swept in one batch, per-case c, to
   find the value that best reproduces 30 s / 277.1 kg: the shortest landing that never
   crosses the ground before settling, then the least fuel.

    python examples/studies/mars_super_twisting.py
"""

from __future__ import annotations

import warnings

import numpy as np

import landing
from landing.scenarios import MARS_NOMINAL_STATE

KEYS = ("settle_time", "fuel_to_settle", "peak_command", "final_position_error", "touchdown_time")


def main() -> None:
    plant = landing.plants.MarsLander()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", landing.DivergenceWarning)
        printed = landing.simulate(plant, landing.controllers.SuperTwisting(variant="printed"), MARS_NOMINAL_STATE,
                                   t_final=300.0, dt=1e-3, record_every=0, settle_tolerance=1.0)
        c = np.round(np.logspace(-2, 0.5, 26), 4)
        x0 = np.tile(MARS_NOMINAL_STATE, (c.size, 1))
        standard = landing.simulate_batch(plant, landing.controllers.SuperTwisting(variant="standard", c=c), x0,
                                          t_final=300.0, dt=1e-3, record_every=0, settle_tolerance=1.0)
    m = printed.metrics
    print("printed eq. 46 (s_floor 1 mm), 300 s:")
    print("  " + ", ".join(f"{k} {float(m[k]):.4g}" for k in KEYS))
    print("\nstandard variant, slope c swept (settle = |r| within 1 m for good):")
    print(f"  {'c':>8} {'settle s':>9} {'fuel kg':>9} {'peak kN':>9} {'|r(tf)| m':>10} {'touchdown s':>12}")
    m = standard.metrics
    for i in range(c.size):
        print(f"  {c[i]:8.4g} {m['settle_time'][i]:9.2f} {m['fuel_to_settle'][i]:9.1f} {m['peak_command'][i] / 1e3:9.1f} "
              f"{m['final_position_error'][i]:10.3g} {m['touchdown_time'][i]:12.2f}")
    clean = np.isfinite(m["settle_time"]) & ~(m["touchdown_time"] < m["settle_time"])
    best = np.flatnonzero(clean)[np.argmin(m["settle_time"][clean])]
    print(f"\nshortest landing without crossing the ground first: c = {c[best]:g} "
          f"({m['settle_time'][best]:.2f} s, {m['fuel_to_settle'][best]:.1f} kg); paper: 30 s, 277.1 kg")


if __name__ == "__main__":
    main()
