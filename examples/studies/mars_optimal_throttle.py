"""What seed 001's fuel optimum (212.9067 kg) could have been: a minimum-throttle sweep.

Seed 001 prints neither the thrust bounds of its GPOPS problem nor whether its engine may shut
down. Our optimum with 40 kN per axis and free throttling spends 178.5 kg (burn, coast, burn),
4 kg above the drag-free impulsive bound. An engine that cannot throttle below `low` (as in
Acikmese and Ploen 2007, the seed's reference [1]) cannot coast; this sweeps `low` and finds
the one that gives the seed's number. It explains the gap; it does not reproduce the seed.

    python examples/studies/mars_optimal_throttle.py     (about 1 min on 2 cores)
"""

from __future__ import annotations

from scipy.optimize import brentq

from landing import optimal, plants, scenarios

SEED_FUEL = 212.9067


def fuel(low: float, nodes: int = 150) -> float:
    res = optimal.fuel_optimal(plants.MarsLander(thrust_limit=40e3), scenarios.MARS_NOMINAL_STATE, 30.0,
                               nodes=nodes, thrust_magnitude=None if low == 0 else (low, 80e3))
    assert res.success, res.status
    return res.fuel


def main() -> None:
    print("t_f = 30 s, 40 kN per axis, |F| >= low throughout (150 intervals of 0.2 s)")
    for low in (0.0, 5e3, 10e3, 12e3, 14e3, 15e3, 16e3):
        print(f"  low = {low / 1e3:5.1f} kN: fuel {fuel(low):7.2f} kg")
    low = brentq(lambda x: fuel(x) - SEED_FUEL, 14e3, 16e3, xtol=10.0)
    print(f"the seed's {SEED_FUEL} kg needs low = {low / 1e3:.2f} kN "
          f"({low / 1905.0 / 3.7114:.2f} times the initial weight on Mars); the seed's fuel over 30 s is "
          f"an average |F| of {SEED_FUEL * 225.0 * 9.807 / 30.0 / 1e3:.2f} kN")


if __name__ == "__main__":
    main()
