"""Can the super-twisting baseline land in 30 s with 277.1288 kg, as Fig. 5 of the Mars fixed-time
guidance paper shows?

With the printed B1 = (1200, 1000, 1000), B2 = (5500, 5000, 5000) neither reading of eq. 46
does (examples/studies/mars_super_twisting.py). This study scales both gains by a common
factor k and, for the standard variant, sweeps its slope c, all in one batch per variant
(per-case gains): k over [0.1, 100] (61 values, log), c over [0.01, 3.16] (51 values, log), the
nominal Table I case for 100 s at dt = 1 ms. A case "lands in 30 s" when abs(r) settles within
1 m by 30 s without crossing rz = 0 before. Of those, the one closest to 277.1288 kg of fuel to
landing is printed.

    python examples/studies/mars_super_twisting_30s.py      (about 5 s on 2 cores)
"""

from __future__ import annotations

import warnings

import numpy as np

import landing
from landing.scenarios import MARS_NOMINAL_STATE

B1 = np.array([1200.0, 1000.0, 1000.0])
B2 = np.array([5500.0, 5000.0, 5000.0])
SEED_FUEL = 277.1288


def sweep(variant: str, k: np.ndarray, c: np.ndarray) -> None:
    kk, cc = (a.ravel() for a in np.meshgrid(k, c, indexing="ij"))
    law = landing.controllers.SuperTwisting(variant=variant, b1=kk[:, None] * B1, b2=kk[:, None] * B2,
                                            c=cc[:, None])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", landing.DivergenceWarning)
        res = landing.simulate_batch(landing.plants.MarsLander(), law, np.tile(MARS_NOMINAL_STATE, (kk.size, 1)),
                                     t_final=100.0, dt=1e-3, record_every=0, settle_tolerance=1.0)
    m = res.metrics
    settle, fuel, td = m["settle_time"], m["fuel_to_settle"], m["touchdown_time"]
    clean = np.isfinite(settle) & ~(td < settle) & ~m["diverged"]
    in30 = clean & (settle <= 30.0)
    print(f"{variant} variant: {kk.size} (k, c) pairs, {clean.sum()} land without crossing the ground first, "
          f"{in30.sum()} of them within 30 s")
    if clean.any():
        i = np.flatnonzero(clean)[np.argmin(settle[clean])]
        print(f"  fastest clean landing: k = {kk[i]:.3g}, c = {cc[i]:.3g}: {settle[i]:.2f} s, {fuel[i]:.1f} kg, "
              f"peak abs(F) {m['peak_command'][i] / 1e3:.1f} kN")
    if in30.any():
        i = np.flatnonzero(in30)[np.argmin(np.abs(fuel[in30] - SEED_FUEL))]
        j = np.flatnonzero(in30)[np.argmin(fuel[in30])]
        print(f"  within 30 s, closest to the paper's {SEED_FUEL} kg: k = {kk[i]:.3g}, c = {cc[i]:.3g}: "
              f"{settle[i]:.2f} s, {fuel[i]:.1f} kg, peak abs(F) {m['peak_command'][i] / 1e3:.1f} kN")
        print(f"  within 30 s, least fuel: k = {kk[j]:.3g}, c = {cc[j]:.3g}: {settle[j]:.2f} s, {fuel[j]:.1f} kg, "
              f"peak abs(F) {m['peak_command'][j] / 1e3:.1f} kN")


def derivative_reading() -> None:
    """Eq. 46 read as the thrust's time derivative, F = -B1 sig^(1/2)(s) + w, w' = -B2 sgn(s), with
    s = r_x (the textbook super-twisting on the position itself), gravity and drag left out:
    a scalar check with scipy, outside the package's laws."""
    from scipy.integrate import solve_ivp

    m, b1, b2 = MARS_NOMINAL_STATE[6], B1[0], B2[0]

    def f(_t: float, y: np.ndarray) -> list[float]:
        x, v, w = y
        return [v, (-b1 * np.sign(x) * np.sqrt(abs(x)) + w) / m, -b2 * np.sign(x)]

    sol = solve_ivp(f, (0.0, 100.0), [MARS_NOMINAL_STATE[0], MARS_NOMINAL_STATE[3], 0.0], max_step=0.01,
                    dense_output=True)
    print("eq. 46 as the thrust's derivative, x axis, the paper's B1, B2: r_x = "
          + ", ".join(f"{sol.sol(t)[0]:.0f} m at {t:g} s" for t in (10.0, 30.0, 60.0, 100.0)))


def main() -> None:
    derivative_reading()
    k = np.logspace(-1, 2, 61)
    sweep("standard", k, np.logspace(-2, 0.5, 51))
    sweep("printed", k, np.array([1.0]))  # c is not read by the printed variant


if __name__ == "__main__":
    main()
