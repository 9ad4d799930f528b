"""The tethered-satellite paper's comparison under smaller attitude torque limits (docs/reproduction-tether.md,
"Gap: the attitude under the FNTSMC is much faster than the paper's 12 s").

The paper prints no torque limit; ours is the thrust limit times a/2 = 0.05 N m (docs/parameters.md).
Under it the FNTSMC brings the attitude to within 2 % of 1 degree in 1.5 s, against the paper's
12 s, while the NTSMC's 12.9 s is near the paper's 15 s. This study re-runs the comparison of
examples/tether_comparison.py (the same preset scenarios: flexible plant, 8 nodes, dt = 10 ms,
100 s, both laws with the paper's gains) with only the plant's ``torque_limit`` changed, and
prints per limit the settle times of both axes (the comparison's metric: within 2 % of 1 degree
from then on) and the peak attitude torque of each law. It then finds, by bisection on the
limit, the one at which the FNTSMC's attitude settles in the paper's 12 s: a fitted value,
since the paper prints none.

    python examples/studies/tether_torque_limit.py
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

import landing
from landing import scenarios

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from tether_comparison import LAWS, settle  # noqa: E402 - the comparison's laws and settle metric

#: Torque limits swept, N m: ours (0.05, the thrust limit times a/2) down to below the NTSMC's peak torque.
LIMITS = (0.05, 0.02, 0.01, 0.005, 0.003, 0.002, 0.001)
#: The paper's attitude settle times (Fig. 5), s.
PAPER_FNTSMC, PAPER_NTSMC = 12.0, 15.0


def run(law: str, limit: float) -> landing.SimulationResult:
    return scenarios.tether_comparison(law, plant={"torque_limit": limit}).simulate()


def measure(limit: float) -> dict[str, tuple[np.ndarray, float]]:
    """Per law: settle times (phi, theta), s, and the peak attitude torque, N m."""
    plant = scenarios.tether_plant(torque_limit=limit)
    out = {}
    for name, law in LAWS.items():
        res = run(law, limit)
        out[name] = (settle(res, plant, scenarios.TETHER_SETTLE_TOLERANCE),
                     float(res.metrics["peak_command_axis"][1]))
    return out


def row(limit: float, m: dict[str, tuple[np.ndarray, float]]) -> None:
    (sf, pf), (sn, pn) = m["FNTSMC"], m["NTSMC"]
    print(f"  {1e3 * limit:8.3g}   {sf[1]:6.2f} / {sn[1]:6.2f} s   {1e3 * pf:6.3g} / {1e3 * pn:6.3g} mN m   "
          f"{sf[0]:6.2f} / {sn[0]:6.2f} s")


def theta_fntsmc(limit: float) -> float:
    s = measure(limit)["FNTSMC"][0][1]
    return np.inf if np.isnan(s) else float(s)


def main() -> None:
    print("The tethered-satellite paper's comparison (examples/tether_comparison.py) at smaller attitude torque limits")
    print("  limit      attitude settle         peak attitude torque      in-plane settle")
    print("  (mN m)     FNTSMC / NTSMC          FNTSMC / NTSMC            FNTSMC / NTSMC")
    sweep = {limit: measure(limit) for limit in LIMITS}
    for limit, m in sweep.items():
        row(limit, m)
    if any(np.isnan(m[k][0]).any() for m in sweep.values() for k in LAWS):
        print("  (nan: not settled within the 100 s run)")

    ours = sweep[LIMITS[0]]
    theta = {limit: m["FNTSMC"][0][1] for limit, m in sweep.items()}
    slow = [limit for limit in LIMITS if not theta[limit] < PAPER_FNTSMC]
    in_plane = max(abs(m[k][0][0] - ours[k][0][0]) for m in sweep.values() for k in LAWS)
    print(f"\nIn-plane settle times over the sweep differ from those at {LIMITS[0]} N m by at most {in_plane:.2f} s.")
    if not slow:
        print(f"No limit of the sweep slows the FNTSMC's attitude to the paper's {PAPER_FNTSMC:g} s.")
        return
    lo = slow[0]  # the largest limit at which the attitude takes at least 12 s
    hi = LIMITS[LIMITS.index(lo) - 1]
    print(f"The largest limit of the sweep at which the FNTSMC's attitude settles in >= {PAPER_FNTSMC:g} s: "
          f"{1e3 * lo:g} mN m ({theta[lo]:.2f} s; at {1e3 * hi:g} mN m: {theta[hi]:.2f} s).")
    # bisection in log(limit): the settle time grows as the limit falls
    a, b = lo, hi
    while b / a > 1.005:
        c = float(np.sqrt(a * b))
        a, b = (c, b) if theta_fntsmc(c) >= PAPER_FNTSMC else (a, c)
    fit = measure(b)
    (sf, pf), (sn, pn) = fit["FNTSMC"], fit["NTSMC"]
    print(f"Fitted limit {1e3 * b:.2f} mN m (bisection to 0.5 %): FNTSMC attitude settle {sf[1]:.2f} s "
          f"(paper: {PAPER_FNTSMC:g} s), NTSMC {sn[1]:.2f} s (at {LIMITS[0]} N m: {ours['NTSMC'][0][1]:.2f} s; "
          f"paper: {PAPER_NTSMC:g} s);")
    print(f"  peak attitude torque there: FNTSMC {1e3 * pf:.3g} mN m, NTSMC {1e3 * pn:.3g} mN m; "
          f"in-plane settle {sf[0]:.2f} / {sn[0]:.2f} s.")
    # peaks equal where both laws saturate at the limit
    low = [limit for limit in LIMITS if sweep[limit]["FNTSMC"][1] <= sweep[limit]["NTSMC"][1] * (1 + 1e-9)]
    if low:
        fastest = min(np.nan_to_num(theta[limit], nan=np.inf) for limit in low)
        ntsmc = [sweep[limit]["NTSMC"][0][1] for limit in low]
        print(f"Where the FNTSMC's peak attitude torque is not above the NTSMC's (limits <= {1e3 * low[0]:g} mN m "
              f"in the sweep), its attitude settles in {fastest:.2f} s or later, the NTSMC's in "
              f"{np.nanmin(ntsmc):.2f} to {np.nanmax(ntsmc):.2f} s.")
    else:
        print("At no limit of the sweep is the FNTSMC's peak attitude torque at or below the NTSMC's.")

if __name__ == "__main__":
    main()
