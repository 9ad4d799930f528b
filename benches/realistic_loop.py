"""What the realistic loop's parts cost: the ``mars_realistic`` preset's batch (one thread,
final states only) as it is (engine lag, control delay, sensor and Kalman filter), without the
sensor and filter, without the lag, and without either; ns per case-step, medians of rounds that
alternate the four (BENCHMARKS.md, "The realistic loop out of line").

    python benches/realistic_loop.py [cases] [rounds]
"""

import statistics
import sys
import time

from landing.scenarios import mars_realistic

n = int(sys.argv[1]) if len(sys.argv) > 1 else 1000
s = mars_realistic()
p = s.plant
variants = {
    "preset (lag, delay, sensor, filter)": s,
    "no sensor, no filter": s.replace(plant=p.replace(sensor=None, filter=None)),
    "no lag": s.replace(plant=p.replace(engine_time_constant=0.0)),
    "neither": s.replace(plant=p.replace(sensor=None, filter=None, engine_time_constant=0.0)),
}
x0 = s.initial_states(n, seed=1)
steps = round(s.options.t_final / s.options.dt)
times = {k: [] for k in variants}
for _ in range(int(sys.argv[2]) if len(sys.argv) > 2 else 3):
    for k, v in variants.items():
        t0 = time.perf_counter()
        v.simulate_batch(x0, seed=1, record_every=0, threads=1)
        times[k].append((time.perf_counter() - t0) * 1e9 / (n * steps))
for k, t in times.items():
    print(f"{k:40s} {statistics.median(t):7.1f} ns per case-step (median of {len(t)})")
