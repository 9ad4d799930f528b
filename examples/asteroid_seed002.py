"""The fuzzy variable-rate asteroid paper: landing on 433 Eros (C20/C22 gravity) along a cubic
over 4000 s with the integral sliding surface and either the fixed exponential reaching law or
the fuzzy variable-rate one, under a model uncertainty of up to 1 % of the command. Prints the
comparison of docs/reproduction-asteroid.md and writes the paper's figures.

    python examples/asteroid_seed002.py [--out figures/seed002]
"""

from __future__ import annotations

import argparse
from pathlib import Path

import landing
from landing.scenarios import SEED002_LAWS, seed002_landing, seed002_reference

NAMES = {"exponential": "exponential", "fuzzy_variable_rate": "fuzzy variable-rate"}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="figures/seed002")
    args = ap.parse_args()

    runs = {}
    print(f"{'reaching law':<22} {'tracked in':>11} {'IAE':>11} {'landing error':>14} {'variation':>13} {'HF share':>10}")
    for law in SEED002_LAWS:
        res = seed002_landing(law).simulate()
        runs[NAMES[law]] = res
        m = res.metrics
        print(f"{NAMES[law]:<22} {m['settle_time']:9.1f} s {m['iae']:9.1f} m s {m['final_position_error']:12.2e} m "
              f"{m['chattering_variation']:9.2e} m/s^3 {m['chattering_hf_share']:9.2e}")
    print("\n(the paper: the probe is on the nominal trajectory by 400 s; the variable-rate law removes the chattering of the"
          " exponential one. Tracked: within 1 m from then on.)")

    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    ref = seed002_reference()
    figures = {
        "tracking": landing.plots.tracking_errors(runs, ref),
        "velocity": landing.plots.tracking_errors(runs, ref, velocity=True),
        "command": landing.plots.commands(runs, "u (m/s^2)"),
        "sliding": landing.plots.diagnostic(runs, "s"),
        "fuzzy_epsilon": landing.plots.diagnostic(runs, "epsilon"),
        "trajectory_3d": landing.plots.trajectory_with_reference(runs, ref),
    }
    for name, fig in figures.items():
        fig.savefig(out / f"{name}.png", dpi=110)
    print(f"\nfigures written to {out}/")


if __name__ == "__main__":
    main()
