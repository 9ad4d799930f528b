"""A plant written in Python against the same plant built in (BENCHMARKS.md, "A plant written
in Python").

Two tables:

1. The Mars lander of W1 (drag, mass depletion, 50 kN per axis, RK4) written in numpy as a
   ``landing.plants.PythonPlant`` (its derivative, its model, its actuator and its domain)
   against the built-in plant, both under the built-in fixed-time MSS law with W1's gains, on
   ``--cases`` cases, 0.5 s at dt = 1 ms, final states only. Before any time is taken the two
   must agree to a relative 1e-11.
2. The per-stage overhead of a Python plant: the double integrator written in numpy (one
   ``concatenate`` per stage) against the built-in double integrator, both under the
   open-loop law (zero command) with forward Euler (one stage per step), from 10^2 to 10^5
   cases: what is timed is the engine's round trip per stage (handing the stage points of every
   case to Python, the call, the checks of the return, the cases' integrator and bookkeeping).

The timed runs alternate; the tables give the median of ``--repeat`` runs.

    python benches/python_plant.py [--cases 10000] [--repeat 3]
"""

from __future__ import annotations

import argparse
import datetime
import os
import platform
import statistics
import time

import numpy as np

import landing
from landing import controllers as C
from landing import plants as P

GAINS = dict(beta1=0.8, beta2=0.4, q1=0.95, q2=1.05, alpha1=0.9, alpha2=0.5, gamma1=0.9, gamma2=1.1)
NOMINAL = np.array([-2000.0, 1000.0, 1500.0, 100.0, -15.0, -75.0, 1905.0])
AREA = np.array([6.0, 7.5, 8.7])
GRAVITY = np.array([0.0, 0.0, -3.7114])


def mars_model(t, x, params):
    v, m = x[:, 3:6], x[:, 6:7]
    drag = -((0.699 * np.exp(-0.0009 * x[:, 2:3])) * (v * np.abs(v))) * (1.0 / m) / AREA
    return GRAVITY + drag, np.repeat(m, 3, axis=1)


def mars_derivative(t, x, u, params):
    drift, _ = mars_model(t, x, params)
    a = u * (1.0 / x[:, 6:7]) + drift
    mdot = -np.sqrt((u * u).sum(axis=1, keepdims=True)) * (1.0 / (225.0 * 9.807))
    return np.concatenate([x[:, 3:6], a, mdot], axis=1)


def mars_actuate(t, x, a, params):
    return np.clip(a * x[:, 6:7], -50_000.0, 50_000.0)


def mars_domain(t, x, params):
    return (x[:, 6] > 0.0) & ((x[:, :3] ** 2).sum(axis=1) <= 1e16)


def double_integrator(t, x, u, params):
    return np.concatenate([x[:, 3:], u], axis=1)


def dispersed(n: int) -> np.ndarray:
    rng = np.random.default_rng(42)
    x = np.tile(NOMINAL, (n, 1))
    x[:, :3] += rng.normal(0.0, 50.0, (n, 3))
    x[:, 3:6] += rng.normal(0.0, 2.0, (n, 3))
    return x


def timed(run) -> float:
    start = time.perf_counter()
    run()
    return time.perf_counter() - start


def median_pair(a, b, repeat: int) -> tuple[float, float]:
    ta, tb = [], []
    for r in range(repeat):
        for which in ((a, ta), (b, tb)) if r % 2 == 0 else ((b, tb), (a, ta)):
            which[1].append(timed(which[0]))
    return statistics.median(ta), statistics.median(tb)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cases", type=int, default=10_000)
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    mars = P.PythonPlant(mars_derivative, 7, positions=(0, 1, 2), velocities=(3, 4, 5), model=mars_model,
                         actuate=mars_actuate, in_domain=mars_domain, mass=6, altitude=2)
    builtin = P.MarsLander(thrust_limit=50_000.0)
    law = C.FixedTimeMSS(**GAINS)
    dt, t_final = 1e-3, 0.5
    steps = round(t_final / dt)
    x0 = dispersed(args.cases)
    kw = dict(t_final=t_final, dt=dt, record_every=0, threads=1)

    a = landing.simulate_batch(builtin, law, x0, **kw)
    b = landing.simulate_batch(mars, law, x0, **kw)
    err = np.max(np.abs(b.final_state - a.final_state) / np.maximum(np.abs(a.final_state), 1e-300))
    assert err < 1e-11, f"the Python plant's final states differ from the built-in plant's by {err:.3g}"

    print(f"# {datetime.date.today()}  {platform.processor() or platform.machine()}  "
          f"{os.cpu_count()} cores  landing {landing.__version__}  numpy {np.__version__}")
    print(f"# accuracy: max relative difference of the final states {err:.2g}")
    print(f"\n1. Mars lander, fixed-time MSS, {args.cases} cases, {t_final} s at dt = {dt} s, RK4, 1 thread; "
          f"median of {args.repeat}, ns per case-step")
    tb, tp = median_pair(lambda: landing.simulate_batch(builtin, law, x0, **kw),
                         lambda: landing.simulate_batch(mars, law, x0, **kw), args.repeat)
    per = args.cases * steps
    print(f"   built-in {tb / per * 1e9:8.1f}   PythonPlant {tp / per * 1e9:8.1f}   ratio {tp / tb:6.2f}")

    print(f"\n2. per-stage overhead: the double integrator in numpy against the built-in one, OpenLoop, Euler, "
          f"{t_final} s at dt = {dt} s; median of {args.repeat}, microseconds per stage")
    di = P.PythonPlant(double_integrator, 6, positions=(0, 1, 2), velocities=(3, 4, 5))
    kw_di = dict(t_final=t_final, dt=dt, record_every=0, integrator="euler", threads=1)
    for n in (100, 1_000, 10_000, 100_000):
        x = np.random.default_rng(1).normal(size=(n, 6))
        tb, tp = median_pair(lambda x=x: landing.simulate_batch(P.DoubleIntegrator(), C.OpenLoop(), x, **kw_di),
                             lambda x=x: landing.simulate_batch(di, C.OpenLoop(), x, **kw_di), args.repeat)
        b, p = tb / steps * 1e6, tp / steps * 1e6
        print(f"   {n:>7} cases: built-in {b:9.1f}   PythonPlant {p:9.1f}   overhead {p - b:9.1f} "
              f"({(p - b) / n * 1e3:6.1f} ns per case)")


if __name__ == "__main__":
    main()
