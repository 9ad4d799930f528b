"""The gains study of the fuzzy fast-terminal asteroid paper (examples/studies/asteroid_gains_seed000.py)
as landing.tune calls.

The same set-up (433 Eros as two mass points, the Table 1 cubic, 10 m off on each axis, 15 s
at dt = 0.01 s, tracked = within 0.1 m from then on) and the same rules, with continuous
searches where the hand-written study used grids:

  A  PD-SMC (sign), lambda in [0.5, 3], k in [1, 6]:
     minimise max(peak_command) subject to abs(mean(settle_time) - 8) <= 0.25
     (the hand-written rule: tracking within 0.25 s of the paper's 8 s, then the least peak;
     it took the grid's nearest time, 7.97 s, as the centre)
  B  FTSMC with A's alpha = lambda and k, beta in [0.1, 3] (p/q = 1/5 fixed: the search is
     continuous, the odd ratios a list; the hand-written grid chose 1/5):
     minimise mean(iae) subject to max(peak_command) <= 1.25 x A's peak and a finite settle time
  C  fuzzy FTSMC with B's gains, N and M in [0.1, 100] (log scale): the same rule.

Stage D (the tanh layer, the widest whose tracking time stays within 0.05 s of the narrowest's)
maximises a parameter, not a metric, over a list of five values; it stays hand-written.

    python examples/studies/tune_seed000.py [--budget 300] [--seed 1]
"""

from __future__ import annotations

import argparse
import time

import landing
from landing.scenarios import SEED000_GAINS


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--budget", type=int, default=300)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--threads", type=int, default=None)
    args = ap.parse_args()
    kw = dict(budget=args.budget, seed=args.seed, threads=args.threads, popsize=12)
    t0 = time.perf_counter()

    pd = landing.scenarios.seed000_tracking("pd", "sign", record_every=0)
    a = landing.tune(pd, {"lambda_": (0.5, 3.0), "k": (1.0, 6.0)}, "max(peak_command)",
                     ["abs(mean(settle_time) - 8) <= 0.25"], **kw)
    print("stage A, PD-SMC:")
    print(a)
    lam0, k0 = a.best_gains["lambda_"], a.best_gains["k"]
    peak0 = a.objective_values[a.best, 0]

    ft = landing.scenarios.seed000_tracking("ftsmc", "sign", record_every=0,
                                           controller={"alpha": lam0, "k": k0, "p": 1.0, "q": 5.0})
    b = landing.tune(ft, {"beta": (0.1, 3.0)}, "mean(iae)",
                     [f"max(peak_command) <= {1.25 * peak0:.6g}", "max(settle_time) <= 15"], **kw)
    print("\nstage B, FTSMC (p/q = 1/5):")
    print(b)
    beta0 = b.best_gains["beta"]

    fz = landing.scenarios.seed000_tracking("fuzzy_ftsmc", "sign", record_every=0, controller={
        "alpha": lam0, "k": k0, "beta": beta0, "p": 1.0, "q": 5.0})
    c = landing.tune(fz, {"n": (0.1, 100.0, "log"), "m": (0.1, 100.0, "log")}, "mean(iae)",
                     [f"max(peak_command) <= {1.25 * peak0:.6g}", "max(settle_time) <= 15"], **kw)
    print("\nstage C, fuzzy FTSMC:")
    print(c)

    print("\nthe shipped gains (hand-written study), same runs:")
    g = SEED000_GAINS
    for law in ("pd", "ftsmc", "fuzzy_ftsmc"):
        m = landing.scenarios.seed000_tracking(law, "sign").simulate(record_every=0).metrics
        print(f"  {law}: tracked in {m['settle_time']:.2f} s, IAE {m['iae']:.3f} m s, peak {m['peak_command']:.3f} m/s^2")
    print(f"  (lambda = {g['lam']}, k = {g['k']}, beta = {g['beta']}, p/q = {g['p']:g}/{g['q']:g}, N = {g['n']}, M = {g['m']})")
    print("tuned, same runs:")
    for label, s in (("pd", a.scenario()), ("ftsmc", b.scenario()), ("fuzzy_ftsmc", c.scenario())):
        m = s.simulate(record_every=0).metrics
        print(f"  {label}: tracked in {m['settle_time']:.2f} s, IAE {m['iae']:.3f} m s, peak {m['peak_command']:.3f} m/s^2")
    print(f"total {time.perf_counter() - t0:.0f} s")


if __name__ == "__main__":
    main()
