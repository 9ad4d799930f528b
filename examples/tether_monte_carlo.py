"""The fixed-time property of the tethered-satellite paper's FNTSMC in Monte Carlo
(docs/reproduction-tether.md): the worst settle time of each angle over campaigns whose initial
angles and rates grow, against the computed bound, with the NTSMC baseline beside it, and the
sub-satellite's largest speed in the orbital (Hill) frame over each campaign's recorded states
(every 0.1 s). Writes figures/tether/fixed_time.png.

    python examples/tether_monte_carlo.py [--cases 40] [--out figures/tether]   (under 1 min on 2 cores)
"""

from __future__ import annotations

import argparse
import warnings
from pathlib import Path

import numpy as np

import landing
from landing import plots, scenarios, theory
from landing.controllers import FixedTimeNTSMC

SPREADS = (1.0, 2.0, 5.0, 10.0, 15.0, 20.0, 25.0, 30.0)
#: The FNTSMC without its network, from where the actuators start to saturate for long.
NETWORK_OFF_FROM = 20.0


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cases", type=int, default=40, help="cases per campaign")
    ap.add_argument("--out", default="figures/tether", help="folder for the figure")
    args = ap.parse_args()
    plant = scenarios.tether_plant()
    bounds = theory.fntsmc_bounds(FixedTimeNTSMC(), scenarios.TETHER_SETTLE_TOLERANCE)
    print(f"bound on the settle time (|angle| within 0.02 deg), Theorem 1 with Table 2: "
          f"phi {bounds.total[0]:.1f} s, theta {bounds.total[1]:.2f} s")
    print(f"{args.cases} cases per campaign, angles uniform within +-spread, rates within +-spread x "
          f"{scenarios.TETHER_RATE_SPREAD} rad/s per degree; seed 1\n")
    print(f"  {'spread':>7} {'law':>10} {'horizon':>8} {'worst phi':>10} {'worst theta':>12} {'within bound':>13} "
          f"{'unsettled':>10} {'peak speed':>11}")
    vx, vy = (plant.state_names.index(n) for n in ("vxs", "vys"))
    worst: dict[str, dict[float, np.ndarray]] = {"FNTSMC": {}, "NTSMC": {}, "no network": {}}
    for spread in SPREADS:
        laws = [("FNTSMC", "fntsmc", {}), ("NTSMC", "ntsmc", {})]
        if spread >= NETWORK_OFF_FROM:
            laws.append(("no network", "fntsmc", {"controller": FixedTimeNTSMC(gamma=0.0)}))
        for name, law, override in laws:
            sc = scenarios.tether_monte_carlo(spread, law, **override)
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", landing.DivergenceWarning)
                mc = landing.monte_carlo(sc, args.cases, seed=1)
            check = theory.check_fntsmc_run(mc.result, plant, bounds)
            w = np.where(np.isnan(check.measured), np.inf, check.measured).max(axis=0)
            worst[name][spread] = w
            unsettled = int(np.isnan(check.measured).any(axis=1).sum())
            inside = args.cases - check.violations.size
            states = np.asarray(mc.states)
            speed = float(np.nanmax(np.hypot(states[..., vx], states[..., vy])))
            print(f"  {spread:>6g}° {name:>10} {sc.t_final:>7.0f}s {w[0]:>9.1f}s {w[1]:>11.2f}s "
                  f"{inside:>6} of {args.cases:<4} {unsettled:>6} {speed:>7.2f} m/s")
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    finite = {k: {s: np.minimum(v, 1e4) for s, v in d.items()} for k, d in worst.items() if k != "no network"}
    plots.tether_fixed_time(finite, bounds).savefig(out / "fixed_time.png", dpi=120)
    print(f"\nfigure: {out}/fixed_time.png")


if __name__ == "__main__":
    main()
