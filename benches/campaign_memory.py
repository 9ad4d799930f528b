"""Memory of a stored campaign (BENCHMARKS.md, "A stored campaign's memory"; issue 25, item 2).

The main job's Monte Carlo (the ``mars_monte_carlo`` preset: seed 001 part 2, Table II
dispersions, a_p = 20 sin t, 60 s at dt = 1 ms) over ``--cases`` cases, recording every second
(``record_every`` = 1 s / dt = 1000: 61 instants of the states, thrust, s1 and s2, 7 808 bytes
a case), written to a store (``store=``, chunks of ``max(1000, n / 50)`` cases): the campaign
keeps its metrics, initial and final states in memory and leaves the recorded signals in the
store. Prints the wall time of the campaign and this process's peak resident set (VmHWM)
after the import, after the campaign and after reading the signals back (``mc.bands("rz")``
over blocks of instants, ``report()``); then, with ``--load``, the same for ``landing.load``
in a fresh process.

    python benches/campaign_memory.py --cases 100000 [--threads 2] [--store DIR] [--load] [--in-memory] [--json FILE]

``--in-memory`` runs the same campaign without a store (the trajectories in memory), for
comparison.

The store goes to a temporary directory (deleted at the end) unless ``--store`` names one.
"""

from __future__ import annotations

import argparse
import os
import platform
import resource
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from _harness import json_option, write_json


def peak_mib() -> float:
    """This process's peak resident set so far, MiB: VmHWM of /proc/self/status (Linux), which
    starts afresh at exec (ru_maxrss carries over the parent's peak into a forked child), else
    ru_maxrss (KiB on Linux)."""
    try:
        with open("/proc/self/status") as f:
            return next(int(line.split()[1]) for line in f if line.startswith("VmHWM:")) / 1024
    except (OSError, StopIteration):
        return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def cpu_name() -> str:
    try:
        with open("/proc/cpuinfo") as f:
            return next(line.split(":", 1)[1].strip() for line in f if line.startswith("model name"))
    except (OSError, StopIteration):
        return platform.processor()


def load_only(store: str) -> None:
    """The child of ``--load``: the stored campaign opened and read as the parent read it."""
    import landing

    base = peak_mib()
    t0 = time.perf_counter()
    mc = landing.load(store)
    loaded = time.perf_counter() - t0
    after_load = peak_mib()
    t0 = time.perf_counter()
    mc.bands("rz")
    mc.report()
    read = time.perf_counter() - t0
    print(f"load: {loaded:.1f} s (every chunk read and checked), peak RSS {after_load:.0f} MiB "
          f"(after import {base:.0f} MiB); bands + report {read:.1f} s, peak RSS {peak_mib():.0f} MiB")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cases", type=int, default=100_000)
    ap.add_argument("--threads", type=int, default=None)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--store", default=None, help="the store's directory (default: a temporary one, deleted)")
    ap.add_argument("--load", action="store_true", help="then landing.load the store in a fresh process")
    ap.add_argument("--in-memory", action="store_true", help="the same campaign without a store, for comparison")
    json_option(ap)
    ap.add_argument("--load-only", default=None, help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.load_only:
        load_only(args.load_only)
        return

    import landing

    scenario = landing.scenarios.mars_monte_carlo()
    every = round(1.0 / scenario.dt)  # one record per second
    n = args.cases
    instants = round(scenario.t_final / scenario.dt) // every + 1
    per_case = 8 * instants * (7 + 3 + 3 + 3)  # states, thrust, s1, s2
    base = peak_mib()
    print(f"{scenario.name}: {n} cases, {scenario.t_final:g} s at dt = {scenario.dt:g} s, record_every = {every} "
          f"({instants} instants: {per_case} bytes a case, {per_case * n / 2**30:.2f} GiB recorded in all); "
          f"{cpu_name()}, {os.cpu_count()} cores, Python {platform.python_version()}")
    folder = Path(args.store) if args.store else Path(tempfile.mkdtemp(prefix="campaign_memory_")) / "store"
    try:
        t0 = time.perf_counter()
        mc = landing.monte_carlo(scenario, n, seed=args.seed, record_every=every, threads=args.threads,
                                 store=None if args.in_memory else folder, progress=False)
        wall = time.perf_counter() - t0
        after_run = peak_mib()
        size = sum(p.stat().st_size for p in folder.rglob("*") if p.is_file())
        where = "in memory" if args.in_memory else f"store {size / 2**30:.2f} GiB on disk, states read on demand"
        print(f"campaign: {wall:.1f} s ({wall / n * 1e3:.3f} ms a case), peak RSS {after_run:.0f} MiB "
              f"(after import {base:.0f} MiB); {where}")
        write_json(args.json, {"cases": n, "threads": args.threads, "stored": not args.in_memory,
                               "case_steps": n * round(scenario.t_final / scenario.dt), "wall_s": wall,
                               "peak_rss_mib": after_run, "bytes_on_disk": size})
        t0 = time.perf_counter()
        bands = mc.bands("rz")
        mc.report()
        read = time.perf_counter() - t0
        print(f"bands('rz') + report(): {read:.1f} s, peak RSS {peak_mib():.0f} MiB "
              f"(median rz at 60 s: {bands[50][-1]:.4g} m)")
        del mc, bands
        if args.load and not args.in_memory:
            subprocess.run([sys.executable, __file__, "--load-only", str(folder)], check=True)
    finally:
        if not args.store:
            shutil.rmtree(folder.parent, ignore_errors=True)


if __name__ == "__main__":
    main()
