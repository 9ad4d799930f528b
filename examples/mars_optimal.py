"""The Mars fixed-time guidance paper's fuel comparison: the offline fuel-optimal landing against
the guidance laws.

Solves the fuel-optimal descent of the Mars lander from the Table I state with t_f = 30 s
(drag, mass depletion, 40 kN per axis, altitude >= 0, at rest at the target), compares its fuel
with the fixed-time MSS preset and the super-twisting baseline, replays the optimal thrust open
loop through the simulator without and with a_p = +-sin t on every axis, and writes the
figures of the paper's Fig. 3 and 4. docs/reproduction-mars.md explains every number.

    python examples/mars_optimal.py [--nodes 150] [--out figures/mars_optimal]
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np

import landing
from landing import disturbances, optimal, plants, scenarios

THRUST_LIMIT = 40e3  # N per axis: the Mars paper's bound of Fig. 2(c); it prints none for its optimum


def main() -> None:
    ap = argparse.ArgumentParser(description="the Mars paper: the fuel-optimal baseline (Fig. 3, 4)")
    ap.add_argument("--nodes", type=int, default=150, help="thrust intervals over 30 s (150: 0.2 s)")
    ap.add_argument("--out", default="figures/mars_optimal", help="folder for the figures")
    args = ap.parse_args()

    x0 = scenarios.MARS_NOMINAL_STATE
    plant = plants.MarsLander(thrust_limit=THRUST_LIMIT)
    start = time.perf_counter()
    opt = optimal.fuel_optimal(plant, x0, 30.0, nodes=args.nodes, steps_per_node=4)
    print(f"fuel-optimal landing, t_f = 30 s, {opt.nodes} thrust intervals of {opt.t[1]:.3g} s, RK4 at "
          f"dt = {opt.dt:g} s, 40 kN per axis: {opt.status} in {opt.iterations} iterations, "
          f"{time.perf_counter() - start:.1f} s")
    fine = opt.states_fine
    print(f"  fuel {opt.fuel:.2f} kg (the Mars fixed-time guidance paper: 212.9067 kg); peak |F_i| {np.abs(opt.thrust).max() / 1e3:.2f} kN, "
          f"min altitude {fine[:, 2].min():.2e} m, |r(t_f)| {np.linalg.norm(fine[-1, :3]):.1e} m, "
          f"|v(t_f)| {np.linalg.norm(fine[-1, 3:6]):.1e} m/s, slack gap {opt.slack_gap:.1e} N")
    mag = np.linalg.norm(opt.thrust, axis=1)
    on = np.flatnonzero(mag > 1.0)
    gaps = np.flatnonzero(mag <= 1.0)
    if gaps.size:
        print(f"  structure: burn, coast from {opt.t[gaps[0]]:.2f} s to {opt.t[gaps[-1] + 1]:.2f} s, burn "
              f"({on.size} of {opt.nodes} intervals thrusting)")
    bound_plant = plants.MarsLander(drag=False, thrust_limit=THRUST_LIMIT)
    print(f"  impulsive lower bound (drag-free): {optimal.impulsive_fuel_bound(bound_plant, x0, 30.0):.2f} kg")
    free = optimal.fuel_optimal(plant, x0, 30.0, free_final_time=True, nodes=args.nodes // 2, steps_per_node=4)
    print(f"  with t_f free ({free.status}): t_f = {free.t_final:.2f} s, fuel {free.fuel:.2f} kg")

    # the peaks are the metric's, taken at every control period (the recorded controls are
    # sampled, and miss the super-twisting law's spikes)
    print("\nfuel to landing (settle within 1 m), nominal Table I case, no disturbance")
    mss = scenarios.mars_nominal().simulate()
    rows = [("fuel-optimal, t_f = 30 s (landing.optimal)", opt.fuel, 30.0, np.abs(opt.thrust).max(), "212.9067 kg")]
    mm = mss.metrics
    rows.append(("fixed-time MSS, preset gains", float(mm["fuel_to_settle"]), float(mm["settle_time"]),
                 float(np.max(mm["peak_command_axis"])), "238.2907 kg"))
    for variant in ("standard", "printed"):
        st = scenarios.mars_super_twisting(variant).simulate()
        sm = st.metrics
        rows.append((f"super-twisting ({variant})", float(sm["fuel_to_settle"]), float(sm["settle_time"]),
                     float(np.max(sm["peak_command_axis"])), "277.13 kg in 30 s"))
    print(f"  {'law':<44} {'fuel':>10} {'landing':>9} {'peak |F_i|':>11}   paper")
    for name, fuel, t_land, peak, printed in rows:
        print(f"  {name:<44} {fuel:8.2f} kg {t_land:7.2f} s {peak / 1e3:8.2f} kN   {printed}")

    print("\nthe optimal thrust replayed open loop (landing.controllers.Tabulated)")
    rep = opt.replay(record_every=1)
    err = np.abs(rep.states - opt.states_fine).max(axis=0)
    print(f"  at dt = {opt.dt:g} s (the optimiser's grid): max deviation from the optimum {err[:3].max():.1e} m, "
          f"{err[3:6].max():.1e} m/s, {err[6]:.1e} kg")
    hold = round(opt.t[1] / 1e-3)
    rep_ms = landing.simulate(plant, optimal.FuelOptimalResult.controller(opt).replace(hold=hold), x0,
                              t_final=30.0, dt=1e-3, record_every=50)
    print(f"  at dt = 1 ms: |r(30 s)| = {np.linalg.norm(rep_ms.states[-1, :3]):.1e} m, "
          f"|v(30 s)| = {np.linalg.norm(rep_ms.states[-1, 3:6]):.1e} m/s")

    print("\nunder a_p = A sin t on every axis (the Mars paper's Fig. 3(c), (d): A = 1)")
    replays = {"optimum, a_p = 0": rep}
    for amp in (1.0, -1.0):
        dist = disturbances.Sinusoid(amplitude=amp, omega=1.0)
        r = opt.replay(dist, record_every=1)
        replays[f"optimum, a_p = {'+' if amp > 0 else '-'}sin t"] = r
        td = float(r.metrics["touchdown_time"])
        g = scenarios.mars_nominal(disturbance=dist).simulate()
        gm = g.metrics
        g_td = float(gm["touchdown_time"])
        print(f"  A = {amp:+g}: optimum open loop: min altitude {r.states[:, 2].min():8.2f} m, "
              + (f"crosses rz = 0 at {td:.2f} s at {float(r.metrics['touchdown_speed']):.1f} m/s"
                 if np.isfinite(td) else f"no ground contact, ends at rz = {r.states[-1, 2]:.2f} m")
              + f"\n           fixed-time MSS: |r(60 s)| {np.linalg.norm(g.states[-1, :3]):.1e} m, settles at "
              f"{float(gm['settle_time']):.2f} s with {float(gm['fuel_to_settle']):.2f} kg, min altitude "
              f"{g.states[:, 2].min():.3f} m, "
              + (f"first rz = 0 at {g_td:.2f} s at {float(gm['touchdown_speed']):.3f} m/s" if np.isfinite(g_td)
                 else "no ground crossing"))

    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    fig3 = landing.plots.position_and_thrust(replays)
    fig3.savefig(out / "fig3_optimal_replay.png", dpi=110)
    fig4 = landing.plots.masses({"fixed-time MSS (preset)": mss, "fuel-optimal (replayed)": rep},
                                read_at={"fixed-time MSS (preset)": float(mm["settle_time"]),
                                         "fuel-optimal (replayed)": 30.0})
    fig4.savefig(out / "fig4_mass.png", dpi=110)
    print(f"\nfigures written to {out}/: fig3_optimal_replay.png, fig4_mass.png")


if __name__ == "__main__":
    main()
