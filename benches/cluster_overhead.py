"""Scheduling overhead of a Dask cluster (BENCHMARKS.md, "Campaigns on a Dask cluster").

The same campaign run in this process (``landing.monte_carlo``, one batch on all the cores,
and the same cut in chunks) and on a ``distributed.LocalCluster`` of local worker processes
(one per core, one thread each, ``threads=1`` per chunk) for several chunk sizes: the
cluster's extra time over the in-process run is what scheduling, sending the tasks and
gathering the chunks cost (and, for small chunks, the per-batch cost of the core itself, which
the in-process chunked rows show alone). The campaign: the Mars Monte Carlo
preset over 10 s at dt = 1 ms (10^4 steps per case), final states and metrics only
(record_every = 0), so that what is measured is the scheduling, not the transfer of
trajectories.

The runs are interleaved (every configuration once per round, the rounds repeated) and the
medians reported, since the machine may be shared. The cluster's start is not timed; a warm-up
round is run and discarded.

    python benches/cluster_overhead.py [--cases 2000] [--chunks 10 25 50 100 250 1000] [--repeats 5]
"""

from __future__ import annotations

import argparse
import os
import platform
import statistics
import time
from typing import Any, Optional

T_FINAL, DT = 10.0, 1e-3


def run(scenario: Any, n: int, chunk: Optional[int], client: Any, threads: int) -> float:
    import landing

    t0 = time.perf_counter()
    landing.monte_carlo(scenario, n, seed=7, record_every=0, chunk_size=chunk, client=client, threads=threads,
                        progress=False, check_bounds=False)
    return time.perf_counter() - t0


def fixed_cost(client: Any, cores: int, repeats: int) -> None:
    """What a chunk costs whatever its work: 2000 cases of 10 steps each, in chunks of 10 cases
    (200 chunks), in process and on the cluster; the time per chunk is almost all fixed cost."""
    import landing

    tiny = landing.scenarios.mars_monte_carlo(t_final=10 * DT, dt=DT)
    n, chunk = 2000, 10
    rows: dict[str, list[float]] = {"in-process": [], "cluster": []}
    for rnd in range(repeats + 1):
        a = run(tiny, n, chunk, None, cores)
        b = run(tiny, n, chunk, client, 1)
        if rnd:
            rows["in-process"].append(a)
            rows["cluster"].append(b)
    print(f"\nfixed cost per chunk ({n} cases of 10 steps in chunks of {chunk}, medians of {repeats}):")
    for kind, t in rows.items():
        med = statistics.median(t)
        print(f"  {kind}: {med:.2f} s for {n // chunk} chunks, {1e3 * med / (n // chunk):.1f} ms per chunk "
              f"(all: {', '.join(f'{x:.2f}' for x in t)})")


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--cases", type=int, default=2000)
    ap.add_argument("--chunks", type=int, nargs="+", default=[10, 25, 50, 100, 250, 1000])
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--workers", type=int, default=os.cpu_count())
    ap.add_argument("--fixed-cost-only", action="store_true", help="only the per-chunk fixed cost")
    args = ap.parse_args()

    import distributed

    import landing

    scenario = landing.scenarios.mars_monte_carlo(t_final=T_FINAL, dt=DT)
    cores = os.cpu_count() or 1
    print(f"{platform.platform()}, {cores} cores, landing {landing.__version__}, distributed "
          f"{distributed.__version__}")
    print(f"campaign: mars_monte_carlo, {args.cases} cases x {int(round(T_FINAL / DT))} steps, record_every=0")
    configs: list[tuple[str, Optional[int]]] = [("in-process", None)]
    for c in args.chunks:
        configs += [("in-process", c), ("cluster", c)]
    times: dict[tuple[str, Optional[int]], list[float]] = {c: [] for c in configs}
    with distributed.LocalCluster(n_workers=args.workers, threads_per_worker=1, processes=True, host="127.0.0.1",
                                  dashboard_address=":0") as cluster, distributed.Client(cluster) as client:
        fixed_cost(client, cores, args.repeats)
        if args.fixed_cost_only:
            return
        for rnd in range(args.repeats + 1):
            for kind, chunk in configs:
                if kind == "in-process":
                    seconds = run(scenario, args.cases, chunk, None, cores)
                else:
                    seconds = run(scenario, args.cases, chunk, client, 1)
                if rnd:  # round 0 warms up
                    times[(kind, chunk)].append(seconds)
            print(f"round {rnd}: " + ", ".join(f"{k}{'' if c is None else f' {c}'} {t[-1]:.2f} s"
                                              for (k, c), t in times.items() if t and rnd))
    base = statistics.median(times[("in-process", None)])  # one batch
    print()
    print("| run | cases per chunk | chunks | median (s) | cases/s | overhead vs in-process |")
    print("|---|---:|---:|---:|---:|---:|")
    for (kind, chunk), t in times.items():
        med = statistics.median(t)
        n_chunks = 1 if chunk is None else -(-args.cases // chunk)
        print(f"| {kind} | {args.cases if chunk is None else chunk} | {n_chunks} | {med:.2f} | "
              f"{args.cases / med:,.0f} | {'' if chunk is None else f'{100 * (med / base - 1):+.1f} %'} |")
    print(f"\nsteps per case: {int(round(T_FINAL / DT))}; the overhead is against the in-process run in one batch")
    print("\nall times (s): " + "; ".join(f"{k}{'' if c is None else f' {c}'}: "
                                          + ", ".join(f"{x:.2f}" for x in t) for (k, c), t in times.items()))


if __name__ == "__main__":
    main()
