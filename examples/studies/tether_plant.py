"""Study behind the flexible tether's parameters (docs/parameters.md, "Tethered satellite").

The tethered-satellite paper's finite-element model is not reproducible from its text and it prints no tether
properties. The flexible plant's tether comes from flown missions; this study shows
(1) which node count N the paper's comparison needs, and (2) how much the closed-loop figures
of both laws depend on the tether properties the missions only bracket.

Set-up: the paper's comparison (1 degree on both angles, 0.1 N thrust limit, dt = 0.01 s,
100 s), both laws with the paper's gains (the FNTSMC's network off: gamma = 0, so that the
plant alone varies). Settle time: |angle| within 2 % of 1 degree from then on.

    python examples/studies/tether_plant.py
"""

from __future__ import annotations

import time

import numpy as np

import landing
from landing import theory
from landing.controllers import NTSMC, FixedTimeNTSMC
from landing.plants import TetheredSatellite

DEG = np.pi / 180.0
TOL = 0.02 * DEG
DT = 0.01

#: Tethers that flew (public mission figures; see docs/parameters.md for the sources).
MISSIONS = {
    "SEDS-1 (1993)": "20 km Spectra 1000 braid, 0.75 mm, about 7 kg: 0.35 g/m",
    "TiPS (1996)": "4 km Spectra 1000 braid over an acrylic core, 2 mm, 5.5 kg: 1.4 g/m; end masses 37.7 and 10.8 kg",
    "YES2 (2007)": "31.7 km Dyneema, 0.5 mm: about 0.19 g/m",
}


def metrics(plant: TetheredSatellite, law) -> dict[str, np.ndarray]:
    x0 = plant.initial_state(DEG, DEG)
    res = landing.simulate(plant, law, x0, t_final=100.0, dt=DT, substeps=plant.substeps_for(DT))
    q, _ = plant.coordinates(res.states)
    settle = theory.settle_time(res.t, q[None], TOL)[0]
    m = res.metrics
    return {
        "settle": settle,
        "variation": np.asarray(m["chattering_variation_axis"]),
        "hf": np.asarray(m["chattering_hf_share_axis"]),
        "final": np.abs(q[-1]) / DEG,
    }


def row(label: str, a: dict[str, np.ndarray], b: dict[str, np.ndarray]) -> str:
    return (f"  {label:<30} FNTSMC settle {a['settle'][0]:6.2f} {a['settle'][1]:5.2f} s  var {a['variation'][0]:.2e} "
            f"{a['variation'][1]:.2e} | NTSMC settle {b['settle'][0]:6.2f} {b['settle'][1]:5.2f} s  var "
            f"{b['variation'][0]:.2e} {b['variation'][1]:.2e}")


def main() -> None:
    t0 = time.time()
    laws = (FixedTimeNTSMC(gamma=0.0), NTSMC())
    print("Tethers that flew:")
    for k, v in MISSIONS.items():
        print(f"  {k:<14} {v}")

    print("\n1. Node count (defaults otherwise): settle times (phi, theta) and thrust/torque variation")
    by_n = {}
    for n in (2, 4, 8, 16):
        p = TetheredSatellite(nodes=n)
        by_n[n] = [metrics(p, law) for law in laws]
        print(row(f"N = {n:2d} (substeps {p.substeps_for(DT)})", *by_n[n]))
    ref = by_n[16]
    for n in (2, 4, 8):
        dev = max(np.nanmax(np.abs(by_n[n][k]["settle"] - ref[k]["settle"])) for k in range(2))
        var = max(np.nanmax(np.abs(by_n[n][k]["variation"] / ref[k]["variation"] - 1)) for k in range(2))
        print(f"  N = {n}: largest settle-time difference to N = 16 {dev:.3f} s, variation {100 * var:.2f} %")
    simple = TetheredSatellite(fidelity="simplified")
    print(row("simplified (rigid dumbbell)", *[metrics(simple, law) for law in laws]))

    print("\n2. Tether properties, one at a time (N = 8)")
    cases = {
        "defaults (YES2-class)": {},
        "density 0.35 g/m (SEDS)": dict(tether_density=3.5e-4),
        "density 1.4 g/m (TiPS)": dict(tether_density=1.4e-3),
        "EA 1 kN": dict(axial_stiffness=1e3),
        "EA 100 kN": dict(axial_stiffness=1e5),
        "c_A 0.5 N s": dict(axial_damping=0.5),
        "c_A 0 (undamped)": dict(axial_damping=0.0),
    }
    for label, kw in cases.items():
        p = TetheredSatellite(nodes=8, **kw)
        print(row(label, *[metrics(p, law) for law in laws]))
    print(f"\n({time.time() - t0:.0f} s)")


if __name__ == "__main__":
    main()
