"""What the fuel optimum of the Mars fixed-time guidance paper (212.9067 kg) could have been:
which unprinted choice fits it.

The paper prints neither the thrust bounds of its GPOPS problem nor whether its engine may shut
down. Our optimum with 40 kN per axis and free throttling spends 178.5 kg (burn, coast, burn),
4 kg above the drag-free impulsive bound. Two unprinted choices each fit the paper's number, so
the paper does not identify which (if either) it made:

1. a minimum throttle `low` (an engine that cannot coast): swept, and the `low` that gives the
   paper's fuel found. At that floor the optimum burns a constant |F| (the paper's fuel over
   30 s is exactly that average thrust), so this fit holds for any fuel above the floor-free
   optimum: it is an identity, not evidence;
2. a lower specific impulse: the Isp that gives the paper's fuel, free throttling.

And the engine of the paper's reference [1] (Acikmese and Ploen 2007, where the Table I lander
comes from: |F| between 4.97 and 13.26 kN): the most it can burn in 30 s is below the paper's
212.9 kg, so that engine cannot be the paper's.

    python examples/studies/mars_optimal_throttle.py     (about 2 min on 2 cores)
"""

from __future__ import annotations

from scipy.optimize import brentq

from landing import optimal, plants, scenarios

SEED_FUEL = 212.9067


#: The engine of the paper's reference [1], |F| in N (Acikmese and Ploen 2007).
REFERENCE_ENGINE = (4.97e3, 13.26e3)


def fuel(low: float, nodes: int = 150, isp: float = 225.0, high: float = 80e3) -> float:
    res = optimal.fuel_optimal(plants.MarsLander(thrust_limit=40e3, isp=isp), scenarios.MARS_NOMINAL_STATE, 30.0,
                               nodes=nodes, thrust_magnitude=None if low == 0 and high == 80e3 else (low, high))
    assert res.success, res.status
    return res.fuel


def main() -> None:
    print("t_f = 30 s, 40 kN per axis, |F| >= low throughout (150 intervals of 0.2 s)")
    for low in (0.0, 5e3, 10e3, 12e3, 14e3, 15e3, 16e3):
        print(f"  low = {low / 1e3:5.1f} kN: fuel {fuel(low):7.2f} kg")
    low = brentq(lambda x: fuel(x) - SEED_FUEL, 14e3, 16e3, xtol=10.0)
    print(f"the Mars paper's {SEED_FUEL} kg needs low = {low / 1e3:.2f} kN "
          f"({low / 1905.0 / 3.7114:.2f} times the initial weight on Mars); the paper's fuel over 30 s is "
          f"an average |F| of {SEED_FUEL * 225.0 * 9.807 / 30.0 / 1e3:.2f} kN")

    isp = brentq(lambda x: fuel(0.0, isp=x) - SEED_FUEL, 170.0, 225.0, xtol=0.05)
    print(f"free throttling, the Mars paper's {SEED_FUEL} kg needs Isp = {isp:.1f} s (ours, from reference [1]: 225 s)")

    lo, hi = REFERENCE_ENGINE
    # arithmetic, no optimiser: the propellant flow is |F| / (Isp g0), at most its largest |F|
    print(f"the reference's engine, {lo / 1e3:.2f} kN <= |F| <= {hi / 1e3:.2f} kN, burns at most "
          f"{hi * 30.0 / (225.0 * 9.807):.2f} kg in 30 s (|F| = {hi / 1e3:.2f} kN throughout): below the Mars paper's "
          f"{SEED_FUEL} kg, which that engine cannot spend in 30 s")


if __name__ == "__main__":
    main()
