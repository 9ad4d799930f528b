"""Part 2 of the Mars fixed-time guidance paper (Table II, a_p = 20 sin t) read at touchdown, and
how alike its cases are.

The campaign of examples/mars_monte_carlo.py (preset gains, seed 1), each case ending at its
touchdown (``stop_at="touchdown"``: the first rz = 0 crossing, where the paper's Fig. 8 reads its
landing sites and speeds). Then the same 300 cases run to 60 s without the event, to show how
the deterministic disturbance draws them together: the spread over the cases (largest over the
axes of max - min) of the position at several times. The neighbourhood of Theorem 4 is reported
as "not informative" when its time bound lies beyond the instant checked or its radius is 100
times the largest error or more.

    python examples/studies/mars_part2_touchdown.py      (about 8 s)
"""

from __future__ import annotations

import numpy as np

import landing

SEED_R = 23.8472  # the Mars paper's final position error per axis and its Fig. 8 sites
SEED_V = 1.5  # the Mars paper's largest touchdown speed (Fig. 8 c, d)


def verdict(radius: float, time_bound: float, horizon: float, errors: np.ndarray) -> str:
    """Inside-the-neighbourhood count, or why it says nothing."""
    worst = float(np.max(errors))
    if time_bound > horizon:
        return f"not informative: its time bound {time_bound:.0f} s lies beyond {horizon:.1f} s"
    if radius >= 100 * worst:
        return f"not informative: its radius {radius:.0f} m is {radius / worst:.0f} times the largest error"
    return f"{int(np.sum(np.all(errors <= radius, axis=1)))} of {len(errors)} inside {radius:.2f} m"


def main() -> None:
    scenario = landing.scenarios.mars_monte_carlo(stop_at="touchdown")
    mc = landing.monte_carlo(scenario, 300, seed=1)
    m = mc.metrics
    n = len(m["touchdown_time"])
    td = np.isfinite(m["touchdown_time"])
    site = np.abs(m["touchdown_position"][td, :2])
    vel = m["touchdown_velocity"][td]
    speed = m["touchdown_speed"][td]
    print(f"Part 2 at touchdown (stop_at=\"touchdown\"), {n} cases, seed 1; Fig. 8 of the Mars fixed-time "
          "guidance paper")
    print(f"  cases touching down                 {int(td.sum())} of {n}, at {np.min(m['touchdown_time'][td]):.2f} "
          f"to {np.max(m['touchdown_time'][td]):.2f} s")
    print(f"  sites: max abs(x), max abs(y)       {site[:, 0].max():.2f} m, {site[:, 1].max():.2f} m   "
          f"paper: within {SEED_R} m")
    print(f"  sites within {SEED_R} m on x and y   {int(np.sum(np.all(site <= SEED_R, axis=1)))} of {int(td.sum())}")
    print(f"  touchdown speed min / median / max  {speed.min():.2f} / {np.median(speed):.2f} / {speed.max():.2f} m/s   "
          f"paper: at most {SEED_V} m/s")
    print(f"  vz at touchdown min / max           {vel[:, 2].min():.2f} / {vel[:, 2].max():.2f} m/s")
    print(f"  abs(vx), abs(vy) at touchdown, max  {np.abs(vel[:, 0]).max():.2f}, {np.abs(vel[:, 1]).max():.2f} m/s")
    print(f"  cases within {SEED_V} m/s               {int(np.sum(speed <= SEED_V))} of {int(td.sum())}")
    b = scenario.bounds()
    err = np.abs(m["touchdown_position"][td])
    print(f"  inside the s1 neighbourhood (eq. 31) at touchdown: "
          f"{verdict(float(np.max(b.s1_radius)), float(np.max(b.settle_time)), float(np.max(m['touchdown_time'][td])), err)}")

    full = landing.monte_carlo(scenario.replace(stop_at=None), 300, seed=1)
    t = full.result.t
    print("\nThe same 300 cases to 60 s (no touchdown event): spread of the position over the cases")
    for when in (0.0, 10.0, 20.0, 30.0, 40.0, 50.0, 60.0):
        k = int(np.argmin(np.abs(t - when)))
        spread = float(np.max(np.ptp(full.result.states[:, k, :3], axis=0)))
        print(f"  t = {t[k]:4.1f} s   {spread:10.4f} m")
    err = np.abs(full.metrics["final_error"])
    print(f"  at 60 s every case is within {float(np.max(np.ptp(full.result.final_state[:, :3], axis=0))) * 1e3:.1f} mm "
          f"of every other: the {SEED_R} m check at 60 s ({int(np.sum(np.all(err <= SEED_R, axis=1)))} of 300) "
          "is one trajectory's")
    print(f"  inside the s1 neighbourhood (eq. 31) at 60 s: "
          f"{verdict(float(np.max(b.s1_radius)), float(np.max(b.settle_time)), 60.0, err)}")

    print("\nThe tuned preset mars_monte_carlo_tuned (no thrust limit) at touchdown, two draws of 300 cases")
    tuned = landing.scenarios.preset("mars_monte_carlo_tuned").replace(stop_at="touchdown")
    for seed in (1, 2):
        tm = landing.monte_carlo(tuned, 300, seed=seed).metrics
        hit = np.isfinite(tm["touchdown_time"])
        print(f"  seed {seed}: {int(hit.sum())} of 300 touch down at {np.min(tm['touchdown_time'][hit]):.2f} to "
              f"{np.max(tm['touchdown_time'][hit]):.2f} s; sites within {np.abs(tm['touchdown_position'][hit, :2]).max():.3f} m; "
              f"speed at most {np.max(tm['touchdown_speed'][hit]):.2f} m/s; peak {np.max(tm['peak_command_axis']) / 1e3:.1f} kN per axis")


if __name__ == "__main__":
    main()
