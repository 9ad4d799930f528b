"""When the 300-case Monte Carlo's sliding variables enter their neighbourhoods, against Fig. 9
and 10 of the Mars fixed-time guidance paper (s2 within 26.5257 by 7.89 s, s1 within
23.8472 m by 9.76 s).

The campaign of examples/mars_monte_carlo.py (Table II, a_p = 20 sin t, preset gains, seed 1)
records s1 = r and s2 every 50 ms. The entry time of a band is the first recorded instant from
which every case's every axis stays inside it to the end of the 60 s run. The bands: the paper's
printed radii (26.5257 for s2, 23.8472 m for s1), and the radii eq. 39 and 31 give for the
preset gains (`landing.theory.mss_bounds`, theta1 = 0.2, theta2 = 0.1). Also the first instant
each case is inside (the median over cases), for the paper's figures read that way; and where
the cases first touch the ground (the landing-sites figure of examples/mars_monte_carlo.py).

    python examples/studies/mars_entry_times.py [--cases 300] [--seed 1]   (about 20 s on 2 cores)
"""

from __future__ import annotations

import argparse

import numpy as np

import landing

SEED_S2, SEED_S1 = 26.5257, 23.8472
SEED_S2_TIME, SEED_S1_TIME = 7.89, 9.76


def stays_inside_from(t: np.ndarray, sig: np.ndarray, radius: float) -> float:
    """First recorded time from which abs(sig) <= radius for every case and axis (inf if never)."""
    inside = np.all(np.abs(sig) <= radius, axis=(0, 2))  # (T,)
    if not inside[-1]:
        return float("inf")
    outside = np.flatnonzero(~inside)
    return float(t[0] if outside.size == 0 else t[outside[-1] + 1])


def first_inside(t: np.ndarray, sig: np.ndarray, radius: float) -> np.ndarray:
    """Per case, the first recorded time with every axis inside (inf if never)."""
    inside = np.all(np.abs(sig) <= radius, axis=2)  # (N, T)
    return np.where(inside.any(axis=1), t[np.argmax(inside, axis=1)], np.inf)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--cases", type=int, default=300)
    ap.add_argument("--seed", type=int, default=1)
    args = ap.parse_args()
    scenario = landing.scenarios.mars_monte_carlo()
    mc = landing.monte_carlo(scenario, args.cases, seed=args.seed)
    res = mc.result
    b = scenario.bounds()
    ours = {"s2": float(np.max(b.s2_radius)), "s1": float(np.max(b.s1_radius))}
    print(f"{args.cases} cases, seed {args.seed}, records every {res.t[1] - res.t[0]:.3g} s")
    print(f"{'band':<44} {'all cases stay inside from':>27} {'first inside, median / max':>28}   paper")
    for name, radius, unit, seed_time in (("s2", SEED_S2, "m/s", SEED_S2_TIME), ("s1", SEED_S1, "m", SEED_S1_TIME),
                                           ("s2", ours["s2"], "m/s", None), ("s1", ours["s1"], "m", None)):
        sig = res.diagnostics[name]
        stay = stays_inside_from(res.t, sig, radius)
        first = first_inside(res.t, sig, radius)
        label = f"{name} within {radius:.6g} {unit}" + (" (paper's radius)" if seed_time else " (eq. 39/31, preset)")
        print(f"{label:<44} {stay:25.2f} s {np.median(first):12.2f} / {np.max(first):6.2f} s   "
              + (f"{seed_time} s" if seed_time else "-"))
    td = np.asarray(mc.metrics["touchdown_position"])[:, :2]
    touched = np.all(np.isfinite(td), axis=1)
    miss = np.abs(td[touched])
    print(f"touchdown sites (first rz = 0 crossing, landing_sites.png): {touched.sum()} of {args.cases} cases; "
          f"max abs(x) {miss[:, 0].max():.2f} m, max abs(y) {miss[:, 1].max():.2f} m, "
          f"{int(np.sum(np.all(miss <= SEED_S1, axis=1)))} within the paper's {SEED_S1} m on both axes")


if __name__ == "__main__":
    main()
