"""The main job: the 300-case Mars Monte Carlo (part 2) of the Mars fixed-time guidance paper.

Table II dispersions of position, velocity and mass, the dust storm a_p = 20 sin t on every
axis, the fixed-time MSS guidance (printed eq. 25) with the preset gains, and the practical
fixed-time bounds of Theorem 4 (theta1 = 0.2, theta2 = 0.1). Prints a summary and writes the
figures into a folder. Then, beside the paper's idealised loop, the same lander in a realistic
one (the ``mars_realistic`` preset: engine limits, lag, delay, a noisy sensor and a filter, each
case ending at touchdown), whose 1000 cases land softly (examples/mars_realistic.py, its figures
in a sibling folder).

    python examples/mars_monte_carlo.py [--cases 300] [--seed 1] [--out figures/mars_monte_carlo]
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import mars_realistic  # the sibling example: the realistic loop's campaign and summary
import numpy as np
from studies.mars_entry_times import SEED_S1, SEED_S1_TIME, SEED_S2, SEED_S2_TIME, stays_inside_from

import landing

#: Where docs/reproduction-mars.md discusses each row.
DOC = "docs/reproduction-mars.md, Part 2"


def claims(mc: landing.MonteCarloResult, scenario: landing.Scenario) -> str:
    """The Mars paper's part-2 claims beside this campaign's numbers, each marked reproduced, gap or
    not informative, with where the docs explain it."""
    m, res = mc.metrics, mc.result
    n = len(m["final_error"])
    err = np.abs(np.asarray(m["final_error"]))
    within = int(np.sum(np.all(err <= SEED_S1, axis=1)))
    # how far apart the cases end: the deterministic a_p = 20 sin t drives them all alike
    spread = float(np.max(np.ptp(np.asarray(res.final_state)[:, :3], axis=0)))
    speed = np.asarray(m["touchdown_speed"])
    sites = np.abs(np.asarray(m["touchdown_position"])[:, :2])
    touched = np.all(np.isfinite(sites), axis=1)
    on_site = int(np.sum(np.all(sites[touched] <= SEED_S1, axis=1)))
    s2_in = stays_inside_from(res.t, res.diagnostics["s2"], SEED_S2)
    s1_in = stays_inside_from(res.t, res.diagnostics["s1"], SEED_S1)
    radius = float(np.max(scenario.bounds().s1_radius))
    rows = [
        ("final |r_i| per axis at 60 s", f"<= {SEED_S1} m", f"max {np.max(err):.2f} m, {within} of {n}",
         f"reproduced; the cases end within {spread * 1e3:.1f} mm of one another (a_p = 20 sin t drives "
         "them alike: one trajectory, not 300)"),
        (f"s2 inside {SEED_S2} m/s from", f"{SEED_S2_TIME} s", f"{s2_in:.2f} s",
         f"gap ({DOC}, \"Gap: the entry times\")"),
        (f"s1 inside {SEED_S1} m from", f"{SEED_S1_TIME} s", f"{s1_in:.2f} s",
         f"gap ({DOC}, \"Gap: the entry times\")"),
        ("touchdown speed", "<= 1.5 m/s", f"{np.nanmin(speed):.1f} .. {np.nanmax(speed):.1f} m/s",
         f"gap: the storm (5.4 Mars gravities) leaves a {np.max(err):.0f} m oscillation, met at speed ({DOC}, "
         "\"Gap: the touchdown speed\")"),
        (f"touchdown sites within {SEED_S1} m", "all (Fig. 8)", f"{on_site} of {int(touched.sum())}",
         f"gap ({DOC}, \"Gap: where the cases touch down\")"),
        ("inside the s1 neighbourhood (eq. 31)", "all", f"{int(np.sum(np.all(err <= radius, axis=1)))} of {n}",
         f"not informative: its radius, {radius:.0f} m, is {radius / np.max(err):.0f} times the largest error"),
    ]
    widths = [max(len(r[i]) for r in rows) for i in range(3)]
    head = ("claim", "paper", "ours")
    lines = [f"The Mars fixed-time guidance paper's part 2, claim by claim ({n} cases; the realistic loop below lands softly)",
             "  " + "  ".join(h.ljust(w) for h, w in zip(head, widths)) + "  verdict"]
    lines += ["  " + "  ".join(c.ljust(w) for c, w in zip(r[:3], widths)) + "  " + r[3] for r in rows]
    return "\n".join(lines)


def main() -> None:
    ap = argparse.ArgumentParser(description="the Mars fixed-time guidance paper, part 2: the 300-case Monte Carlo")
    ap.add_argument("--cases", type=int, default=300)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--out", default="figures/mars_monte_carlo", help="folder for the figures")
    ap.add_argument("--threads", type=int, default=None)
    ap.add_argument("--realistic-cases", type=int, default=1000,
                    help="cases of the realistic loop's campaign (0: leave it out)")
    args = ap.parse_args()

    scenario = landing.scenarios.mars_monte_carlo()
    print(scenario)
    start = time.perf_counter()
    mc = landing.monte_carlo(scenario, args.cases, seed=args.seed, threads=args.threads)
    elapsed = time.perf_counter() - start
    print(f"\n{args.cases} cases of {scenario.t_final:g} s at dt = {scenario.dt:g} s in {elapsed:.2f} s\n")
    print(mc.report())

    print()
    print(claims(mc, scenario))

    written = landing.plots.save_all(mc, args.out)
    print(f"\nfigures written to {args.out}/: " + ", ".join(p.name for p in written))

    if args.realistic_cases > 0:
        realistic = landing.scenarios.mars_realistic()
        print(f"\nThe same lander in a realistic loop ({realistic.name}: {realistic.description}; "
              "docs/mars-realistic.md)")
        mc = mars_realistic.run(realistic, args.realistic_cases, args.seed, args.threads)
        mars_realistic.summary(mc)
        out = Path(args.out).parent / "mars_realistic"
        written = mars_realistic.figures(mc, out)
        print(f"\nfigures written to {out}/: " + ", ".join(p.name for p in written))


if __name__ == "__main__":
    main()
