"""W4 (BENCHMARKS.md): scaling from 10^3 to 10^6 cases. Time and peak memory should grow
linearly with the case count, with no per-case Python.

The W1 set-up (seed-001 fixed-time guidance, Table II dispersions, RK4, drag, 50 kN per axis,
a_p = 20 sin t, final states only) over a shorter horizon, 0.1 s at dt = 1 ms (100 steps), so
that a million cases take seconds. Each size runs in a fresh interpreter, so the peak resident
memory it reports (ru_maxrss) is that size's alone; the baseline row (0 cases) is the
interpreter with numpy and landing imported.

    python benches/scaling_w4.py [--sizes 1000 10000 100000 1000000] [--threads N]
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import resource
import subprocess
import sys
import time

T_FINAL, DT = 0.1, 1e-3


def child(n: int, threads: int | None) -> None:
    import numpy as np

    import landing

    if n == 0:
        print(json.dumps({"n": 0, "seconds": 0.0, "maxrss_kib": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss}))
        return
    sc = landing.scenarios.mars_monte_carlo()
    x0 = sc.dispersion.sample(n, seed=2024)
    law = landing.controllers.FixedTimeMSS(**landing.scenarios.MARS_FIXED_TIME_GAINS)
    plant = landing.plants.MarsLander(thrust_limit=50e3)
    dist = landing.disturbances.Sinusoid(amplitude=20.0, omega=1.0)
    t0 = time.perf_counter()
    res = landing.simulate_batch(plant, law, x0, t_final=T_FINAL, dt=DT, disturbance=dist, record_every=0,
                                 threads=threads)
    seconds = time.perf_counter() - t0
    assert res.final_state.shape == (n, 7) and np.isfinite(res.final_state).all()
    print(json.dumps({"n": n, "seconds": seconds, "maxrss_kib": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss}))


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--sizes", type=int, nargs="+", default=[1000, 10_000, 100_000, 1_000_000])
    ap.add_argument("--threads", type=int, default=None)
    ap.add_argument("--child", type=int, default=None, help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.child is not None:
        child(args.child, args.threads)
        return
    steps = int(round(T_FINAL / DT))
    rows = []
    for n in [0] + args.sizes:
        cmd = [sys.executable, __file__, "--child", str(n)] + (["--threads", str(args.threads)] if args.threads else [])
        out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
        rows.append(json.loads(out.strip().splitlines()[-1]))
    base = rows[0]["maxrss_kib"]
    print(f"W4: {steps} steps per case, final states only; {platform.processor() or platform.machine()}, "
          f"{os.cpu_count()} cores, threads = {args.threads or 'all'}")
    print(f"{'cases':>9} {'time (s)':>9} {'ns/case-step':>13} {'peak RSS (MiB)':>15} {'above baseline, B/case':>23}")
    for r in rows:
        n = r["n"]
        ns = r["seconds"] * 1e9 / (n * steps) if n else float("nan")
        per_case = (r["maxrss_kib"] - base) * 1024 / n if n else float("nan")
        print(f"{n:>9} {r['seconds']:9.3f} {ns:13.1f} {r['maxrss_kib'] / 1024:15.1f} {per_case:23.0f}")


if __name__ == "__main__":
    main()
