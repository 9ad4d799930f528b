"""What recording costs a campaign (issue 27): the part-2 Mars preset (60 s at 1 ms), metrics only
against recording every 50 ms (the preset's), through simulate_batch and through monte_carlo
(in memory: one chunk, 20 chunks, 50 chunks (2 % of the cases each: the progress bar's chunks
before 2026-12-06) and the progress bar's default chunks, and these chunks as before
2026-12-07: each chunk's recording in arrays of its own, copied into the campaign's output,
instead of written into it), medians of alternated repeats in one run.

    python benches/recording_cost.py [--cases 2000] [--repeat 3] [--threads 2] [--paths NAME ...] [--json FILE]

Accuracy first: every path's final states equal simulate_batch's bit for bit.
"""

from __future__ import annotations

import argparse
import statistics
import time

import numpy as np
from _harness import json_option, write_json

import landing
from landing.campaign._assembly import Assembly


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cases", type=int, default=2000)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--threads", type=int, default=2)
    json_option(ap)
    ap.add_argument("--paths", nargs="+", help="only these paths (names as printed, e.g. 'monte_carlo, progress bar')")
    args = ap.parse_args()
    s = landing.scenarios.preset("mars_monte_carlo")
    n, threads = args.cases, args.threads
    steps = round(s.options.t_final / s.options.dt)
    x0 = s.initial_states(n, seed=1)

    def batch(every: int) -> landing.SimulationResult:
        return s.simulate_batch(x0, seed=1, record_every=every, threads=threads)

    def mc(every: int, chunk: int) -> landing.SimulationResult:
        return landing.monte_carlo(s, n, seed=1, record_every=every, chunk_size=chunk, threads=threads,
                                   progress=False, check_bounds=False).result

    def copied(every: int) -> landing.SimulationResult:
        # every chunk records into arrays of its own, copied into the output (before 2026-12-07)
        lend = Assembly.destination
        Assembly.destination = lambda self, start, stop: None  # type: ignore[method-assign]
        try:
            return landing.monte_carlo(s, n, seed=1, record_every=every, threads=threads, progress=True,
                                       check_bounds=False).result
        finally:
            Assembly.destination = lend  # type: ignore[method-assign]

    runs = {
        "simulate_batch": batch,
        "monte_carlo, one chunk": lambda e: mc(e, n),
        "monte_carlo, 20 chunks": lambda e: mc(e, -(-n // 20)),
        "monte_carlo, 50 chunks": lambda e: mc(e, -(-n // 50)),
        "monte_carlo, progress bar": lambda e: landing.monte_carlo(
            s, n, seed=1, record_every=e, threads=threads, progress=True, check_bounds=False).result,
        "progress bar, chunks copied": copied,
    }
    if args.paths:
        unknown = set(args.paths) - set(runs)
        assert not unknown, f"no path {sorted(unknown)}; the paths: {list(runs)}"
        runs = {k: v for k, v in runs.items() if k in args.paths}
    reference = batch(0).final_state
    for name, f in runs.items():
        for every in (0, 50):
            assert np.array_equal(f(every).final_state, reference), (name, every)
    times: dict[tuple[str, int], list[float]] = {(k, e): [] for k in runs for e in (0, 50)}
    for _ in range(args.repeat):
        for (name, every), out in times.items():
            t0 = time.perf_counter()
            runs[name](every)
            out.append(time.perf_counter() - t0)
    print(f"{n} cases x {steps} steps, {threads} threads; ns of wall time per case-step, median of {args.repeat}")
    print(f"{'path':<30} {'metrics only':>13} {'every 50 ms':>12} {'cost':>7}")
    rows = []
    for name in runs:
        a = statistics.median(times[(name, 0)]) / (n * steps) * 1e9
        b = statistics.median(times[(name, 50)]) / (n * steps) * 1e9
        print(f"{name:<30} {a:>13.2f} {b:>12.2f} {100 * (b / a - 1):>6.1f}%")
        rows.append({"path": name, "metrics_only_ns": a, "every_50ms_ns": b, "cost": b / a - 1})
    write_json(args.json, {"cases": n, "threads": threads, "repeat": args.repeat, "rows": rows})


if __name__ == "__main__":
    main()
