"""Stage B of the gains study of the fuzzy variable-rate asteroid paper
(examples/studies/asteroid_gains_seed002.py) as a landing.tune call.

The fuzzy variable-rate law keeps the shipped c1, c2, k and ku (the same switching authority as
the exponential law's epsilon) and searches the input scalings ke and kec (log scale, 10 to
1e6, the hand-written grid's range) under the paper's 1 % command noise, on K = 4 draws of it
(the same four for every candidate: each candidate runs as its own batch of the four cases,
since the noise is keyed by the case's index). The rule is the hand-written one:

  minimise max(chattering_variation)                       the least chattering, worst draw
  subject to max(iae) <= 1.01 x the exponential law's      as accurate: integrated error
             max(final_position_error) <= the exponential law's   and landing error

with the exponential law's figures measured on the same four draws (the hand-written study
measured them on eight). Stage A (the exponential law) searches w with c1 = w^2, c2 = 2 w tied
together (critically damped): landing.tune searches law parameters, not functions of one, so it
stays hand-written.

    python examples/studies/tune_seed002.py [--budget 120] [--seed 2]
"""

from __future__ import annotations

import argparse
import time
import warnings

import numpy as np

import landing


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--budget", type=int, default=120)
    ap.add_argument("--seed", type=int, default=2)
    ap.add_argument("--threads", type=int, default=None)
    args = ap.parse_args()
    t0 = time.perf_counter()
    K = 4
    expo = landing.scenarios.seed002_landing("exponential", record_every=0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", landing.DivergenceWarning)
        m = expo.simulate_batch(expo.initial_states(K, seed=args.seed), seed=args.seed).metrics
    iae0 = float(np.max(m["iae"]))
    land0 = float(np.max(m["final_position_error"]))
    print(f"exponential law (shipped gains), worst of {K} noise draws: IAE {iae0:.2f} m s, landing error "
          f"{land0:.3e} m, variation {np.max(m['chattering_variation']):.3e} m/s^3")

    fuzzy = landing.scenarios.seed002_landing("fuzzy_variable_rate", record_every=0)
    r = landing.tune(fuzzy, {"ke": (10.0, 1e6, "log"), "kec": (10.0, 1e6, "log")}, "max(chattering_variation)",
                     [f"max(iae) <= {1.01 * iae0:.6g}", f"max(final_position_error) <= {land0:.6g}"],
                     cases=K, budget=args.budget, seed=args.seed, popsize=12, threads=args.threads)
    print(f"\nlanding.tune [{time.perf_counter() - t0:.0f} s]:")
    print(r)
    shipped = fuzzy.controller
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", landing.DivergenceWarning)
        m = fuzzy.simulate_batch(fuzzy.initial_states(K, seed=args.seed), seed=args.seed).metrics
    print(f"\nshipped (hand-written study): ke = {shipped.ke:.4g}, kec = {shipped.kec:g}: worst of the same {K} draws: "
          f"variation {np.max(m['chattering_variation']):.3e} m/s^3, IAE {np.max(m['iae']):.2f} m s, "
          f"landing error {np.max(m['final_position_error']):.3e} m")
    print(f"total {time.perf_counter() - t0:.0f} s")


if __name__ == "__main__":
    main()
