"""The tethered-satellite paper's comparison, FNTSMC against NTSMC on the flexible tethered
satellite: every number of docs/reproduction-tether.md, and the paper's figures 3 to 7 in
figures/tether/.

    python examples/tether_comparison.py [--out figures/tether]
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

import landing
from landing import plots, scenarios, theory
from landing.controllers import FixedTimeNTSMC

DEG = np.pi / 180.0
LAWS = {"FNTSMC": "fntsmc", "NTSMC": "ntsmc"}


def line(label: str, ours: str, paper: str = "") -> None:
    print(f"  {label:<50} {ours:<34} {('paper: ' + paper) if paper else ''}")


def runs(fidelity: str = "flexible") -> dict[str, landing.SimulationResult]:
    return {name: scenarios.tether_comparison(law, fidelity).simulate() for name, law in LAWS.items()}


def settle(res: landing.SimulationResult, plant, tol: float, rates: bool = False) -> np.ndarray:
    q, qd = plant.coordinates(res.states)
    if rates:
        return theory.settle_time(res.t, qd[None], tol * np.abs(qd).max(axis=0))[0]
    return theory.settle_time(res.t, q[None], tol)[0]


def comparison() -> dict[str, landing.SimulationResult]:
    plant = scenarios.tether_plant()
    print(f"The tethered-satellite paper, section 4: 1 degree on both angles to 0, 0.1 N thrust ({plant.substeps_for(0.01)} RK4 "
          f"substeps per 10 ms), flexible plant with {plant.nodes} tether nodes")
    res = runs()
    f, n = res["FNTSMC"], res["NTSMC"]
    tol = scenarios.TETHER_SETTLE_TOLERANCE
    sf, sn = settle(f, plant, tol), settle(n, plant, tol)
    line("in-plane settle (2 % of 1 deg), FNTSMC / NTSMC", f"{sf[0]:.2f} / {sn[0]:.2f} s", "about 30 / 50 s")
    line("attitude settle (2 % of 1 deg), FNTSMC / NTSMC", f"{sf[1]:.2f} / {sn[1]:.2f} s", "12 / 15 s")
    rf, rn = settle(f, plant, 0.02, rates=True), settle(n, plant, 0.02, rates=True)
    line("in-plane rate settle (2 % of its peak)", f"{rf[0]:.2f} / {rn[0]:.2f} s", "about 35 / 50 s")
    line("attitude rate settle (2 % of its peak)", f"{rf[1]:.2f} / {rn[1]:.2f} s", "13 / 15 s")
    for label, tl in (("5 %", 0.05), ("1 %", 0.01), ("0.1 %", 0.001)):
        a, b = settle(f, plant, tl * DEG), settle(n, plant, tl * DEG)
        line(f"settle at {label} of 1 deg (phi, theta), FNTSMC / NTSMC",
             f"({a[0]:.1f}, {a[1]:.2f}) / ({b[0]:.1f}, {b[1]:.2f}) s")
    mf, mn = f.metrics, n.metrics
    v_f, v_n = mf["chattering_variation_axis"], mn["chattering_variation_axis"]
    h_f, h_n = mf["chattering_hf_share_axis"], mn["chattering_hf_share_axis"]
    line("thrust variation (N/s), FNTSMC / NTSMC", f"{v_f[0]:.3g} / {v_n[0]:.3g}", "FNTSMC smoother")
    line("torque variation (N m/s), FNTSMC / NTSMC", f"{v_f[1]:.3g} / {v_n[1]:.3g}", "FNTSMC smoother")
    line("thrust energy above 5 Hz, FNTSMC / NTSMC", f"{h_f[0]:.2g} / {h_n[0]:.2g}", "NTSMC chatters")
    line("torque energy above 5 Hz, FNTSMC / NTSMC", f"{h_f[1]:.2g} / {h_n[1]:.2g}", "NTSMC chatters")
    line("peak thrust, FNTSMC / NTSMC", f"{mf['peak_command_axis'][0]:.3g} / {mn['peak_command_axis'][0]:.3g} N",
         "saturated at 0.1 N at first")
    line("peak torque, FNTSMC / NTSMC", f"{mf['peak_command_axis'][1]:.3g} / {mn['peak_command_axis'][1]:.3g} N m",
         "FNTSMC lower (Fig. 7(b))")
    qf, _ = plant.coordinates(f.states)
    qn, _ = plant.coordinates(n.states)
    tail = f.t >= 80.0
    line("largest |angle| over 80-100 s (phi, theta), FNTSMC",
         f"({np.abs(qf[tail, 0]).max() / DEG:.1e}, {np.abs(qf[tail, 1]).max() / DEG:.1e}) deg")
    line("largest |angle| over 80-100 s (phi, theta), NTSMC",
         f"({np.abs(qn[tail, 0]).max() / DEG:.1e}, {np.abs(qn[tail, 1]).max() / DEG:.1e}) deg",
         "NTSMC chatters at steady state")
    off = scenarios.tether_comparison("fntsmc", controller=FixedTimeNTSMC(gamma=0.0)).simulate()
    s_off = settle(off, plant, tol)
    line("FNTSMC without its network (gamma = 0): settle", f"{s_off[0]:.2f}, {s_off[1]:.2f} s")
    simple = runs("simplified")
    simple_plant = scenarios.tether_plant("simplified")
    a, b = settle(simple["FNTSMC"], simple_plant, tol), settle(simple["NTSMC"], simple_plant, tol)
    line("simplified plant: settle (phi, theta), FNTSMC / NTSMC",
         f"({a[0]:.2f}, {a[1]:.2f}) / ({b[0]:.2f}, {b[1]:.2f}) s")
    return res


def bounds() -> None:
    law = FixedTimeNTSMC()
    tol = scenarios.TETHER_SETTLE_TOLERANCE
    b = theory.fntsmc_bounds(law, tol)
    print("\nThe tether paper's Theorem 1 with Table 2 (no disturbance; axes phi, theta)")
    line("T_s (s reaches 0, Lemma 2 on V = s^2/2)", f"{b.ts[0]:.1f}, {b.ts[1]:.2f} s", "eq. 42: needs c_v (not given)")
    line("T_d (|e1| reaches sigma_phi)", f"{b.td[0]:.1f}, {b.td[1]:.2f} s", "eq. 47")
    line("then |e1| within 0.02 deg", f"{b.t_inside[0]:.1f}, {b.t_inside[1]:.2f} s")
    line("total bound", f"{b.total[0]:.1f}, {b.total[1]:.2f} s", "independent of the initial state")
    line("eq. 47 as printed, d = 0.5 (not a bound)", f"{b.printed_td[0]:.1f}, {b.printed_td[1]:.2f} s")
    g2 = [2 ** ((p2 + 1) / 2) * (k2 - 1 / (p2 + 1)) for k2, p2 in ((0.08, 0.99), (0.5, 0.6))]
    line("eq. 45's gamma2 with Table 2 (must be > 0)", f"{g2[0]:.3f}, {g2[1]:.3f}")
    for c_v in (0.1, 1.0):
        ts = theory.fntsmc_ts_printed(c_v, np.array([0.89, 0.7]), np.array([1.1, 1.8]))
        line(f"eq. 42 as printed with c_v = {c_v}", f"{ts[0]:.1f}, {ts[1]:.1f} s")
    pairs = np.array([[1e-3, 0.0], [DEG, 0.0], [-0.3, 0.1], [1.0, -0.5], [3.0, 1.0], [-5.0, 0.0]])
    for axis in (0, 1):
        c = theory.check_fntsmc_bound(law, pairs, axis=axis)
        line(f"double integrator, axis {axis}, e1(0) up to 5 rad: worst s / T_s",
             f"{np.nanmax(c['s'].measured):.2f} / {c['s'].bound[0]:.2f} s ({'holds' if c['s'].ok else 'VIOLATED'})")
        line(f"double integrator, axis {axis}: worst settle / total",
             f"{np.nanmax(c['e1'].measured):.2f} / {c['e1'].bound[0]:.1f} s ({'holds' if c['e1'].ok else 'VIOLATED'})")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="figures/tether", help="folder for the figures")
    out = Path(ap.parse_args().out)
    res = comparison()
    bounds()
    out.mkdir(parents=True, exist_ok=True)
    plant = scenarios.tether_plant()
    # the baseline first, so that its chattering does not hide the FNTSMC's curves
    ordered = {"NTSMC": res["NTSMC"], "FNTSMC": res["FNTSMC"]}
    for name, fig in (("angles", plots.tether_angles(ordered, plant)), ("rates", plots.tether_rates(ordered, plant)),
                      ("commands", plots.tether_commands(ordered))):
        fig.savefig(out / f"{name}.png", dpi=120)
    print(f"\nfigures: {out}/angles.png (the paper's Fig. 3, 5), rates.png (Fig. 4, 6), commands.png (Fig. 7)")


if __name__ == "__main__":
    main()
