"""The fuzzy fast-terminal asteroid paper: PD sliding mode, fast terminal SMC and fuzzy-blended
FTSMC, each with sign and tanh switching, tracking the Table 1 cubic on 433 Eros (two mass
points) for 15 s at dt = 0.01 s; then the full 8000 s landing. Prints the comparison of
docs/reproduction-asteroid.md and writes the paper's figures.

    python examples/asteroid_seed000.py [--out figures/seed000]
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

import landing
from landing import theory
from landing.scenarios import (
    SEED000_GAINS,
    SEED000_LAWS,
    SEED000_OFFSET,
    seed000_landing,
    seed000_reference,
    seed000_tracking,
)

SEED = {"pd": (8.0, 244.0), "ftsmc": (5.0, 139.0), "fuzzy_ftsmc": (4.0, 113.0)}
NAMES = {"pd": "PD-SMC", "ftsmc": "FTSMC", "fuzzy_ftsmc": "fuzzy FTSMC"}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="figures/seed000")
    args = ap.parse_args()

    runs = {}
    print(f"{'law':<22} {'tracked in':>11} {'IAE':>10} {'IAE / PD':>9} {'variation':>11} {'HF share':>10}   paper: time, error")
    for switch in ("sign", "tanh"):
        base = None
        for law in SEED000_LAWS:
            res = seed000_tracking(law, switch).simulate()
            runs[(law, switch)] = res
            m = res.metrics
            base = base or float(m["iae"])
            t, e = SEED[law]
            print(f"{NAMES[law] + ' (' + switch + ')':<22} {m['settle_time']:9.2f} s {m['iae']:8.2f} m s "
                  f"{m['iae'] / base:9.2f} {m['chattering_variation']:9.1f}   {m['chattering_hf_share']:10.2e}   "
                  f"{t:.0f} s, {e:.0f} ({e / SEED['pd'][1]:.2f})")
    print("\n(tracked: |r - r_ref| within 0.1 m from then on; IAE: integral of |e_x| + |e_y| + |e_z|; variation:"
          " total variation of the command per second, m/s^3; HF share: energy above 5 Hz)")

    # eq. 5 and 7: the time to reach e = 0 once on the surface, for the preset's FTSMC gains
    # and the 10 m initial offset; the paper prints p and q swapped
    g, e0 = SEED000_GAINS, float(SEED000_OFFSET[0])
    alpha, beta, p, q = g["lam"], g["beta"], g["p"], g["q"]
    print(f"\nReaching times on the surface from e0 = {e0:g} m (alpha {alpha:g}, beta {beta:g}, p/q = {p:g}/{q:g}):")
    print(f"  eq. 7 (fast terminal):  {theory.fast_terminal_reaching_time(e0, alpha, beta, p, q):.4f} s"
          f"   as printed (p, q swapped): {theory.fast_terminal_reaching_time_printed(e0, alpha, beta, p, q):.3g} s")
    print(f"  eq. 5 (terminal):       {theory.terminal_reaching_time(e0, beta, p, q):.4f} s"
          f"   as printed (p, q swapped): {theory.terminal_reaching_time_printed(e0, beta, p, q):.3g} s")
    law = seed000_tracking("ftsmc", "sat").controller
    check = theory.check_terminal_reaching_time(law, [e0, -e0, 1.0])
    print(f"  the FTSMC started on its surface (double integrator, dt {float(check.extra['dt']):.3g} s): |e| <= "
          f"{float(check.extra['tolerance']):g} m after {check.measured[0, 0]:.4f} s, eq. 7 predicts "
          f"{check.extra['predicted'][0, 0]:.4f} s; largest difference over e0 = +-{e0:g}, 1 m: "
          f"{np.abs(check.extra['difference']).max():.2g} s")

    print("\nFull landing, 8000 s (tanh switching):")
    for law in SEED000_LAWS:
        m = seed000_landing(law).simulate().metrics
        print(f"  {NAMES[law]:<12} final |r - r_target| {m['final_position_error']:.2e} m, |v| {m['final_velocity_error']:.2e} m/s, "
              f"delta-v {m['control_effort']:.1f} m/s")

    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    ref = seed000_reference()
    for switch in ("sign", "tanh"):
        group = {NAMES[law]: runs[(law, switch)] for law in SEED000_LAWS}
        figures = {
            f"tracking_{switch}": landing.plots.tracking_errors(group, ref),
            f"velocity_{switch}": landing.plots.tracking_errors(group, ref, velocity=True),
            f"command_{switch}": landing.plots.commands(group, "u (m/s^2)"),
            f"sliding_{switch}": landing.plots.diagnostic(group, "s"),
        }
        for name, fig in figures.items():
            fig.savefig(out / f"{name}.png", dpi=110)
    landing.plots.blend_coefficients(runs[("fuzzy_ftsmc", "sign")]).savefig(out / "fuzzy_coefficients.png", dpi=110)
    full = seed000_landing("fuzzy_ftsmc").simulate()
    landing.plots.trajectory_with_reference({"fuzzy FTSMC": full}, ref).savefig(out / "trajectory_3d.png", dpi=110)
    print(f"\nfigures written to {out}/")


if __name__ == "__main__":
    main()
