"""W3 and W5 side by side (BENCHMARKS.md): landing against the numba peer a GNC user would write
instead, same workload, same starts, same machine, same thread counts, one run.

W3: the fuzzy fast-terminal asteroid paper's law (fuzzy-blended fast terminal SMC, eq. 20-22:
alpha 1, beta 0.4, p/q = 1/5, k 2.5, N = M = 10, sign switching, |e| floored at 1e-3 in
|e|^(p/q - 1)) on 433 Eros as two mass points (6.687e15 kg in two halves at (+-17200/sqrt 5,
0, 0) m, G 6.6743e-11) in the body frame rotating at 3.3118e-4 rad/s, tracking the paper's
cubic from (3200, 1300, 9000) m, (-1.2, 0.2, -1) m/s to (2837, 928.1, 5708) m at rest at 8000 s;
300 starts dispersed by 10 m (1 sigma) per axis about the cubic's start, at its velocity; 15 s at
dt = 0.01 s, RK4 with the command held over each control period, final states only. This is
``eros_w3`` of the core's workloads, timed by criterion in the core's rollout bench.

W5: the fuzzy variable-rate asteroid paper's law (integral surface s = -sigma' - I,
I' = c1 sigma + c2 sigma', c1 = 0.017^2, c2 = 2 x 0.017, k 0.1; the switching term
ku F(ke s, kec s') with ke 3.162e4, kec 10, ku 2.813e-4, s' the backward difference of s over
the period, 0 at the first instant; F the paper's 5x5-rule Mamdani system, min/max inference,
centroid over the output universe sampled at 401 points) on 433 Eros with the C20/C22
harmonics (mu 4.842e5, R0 1138.5 m, C20 -0.043, C22 0.058) rotating at 1.65e-4 rad/s,
tracking the paper's cubic from (550, 500, 8200) m, (-1.7, 0.7, -1.5) m/s to (20, 80, 2000) m
at rest at 4000 s; 300 starts at the documented 50 m offset per axis, dispersed by 10 m (1
sigma), at the cubic's initial velocity; 100 s at dt = 0.1 s, RK4 (one step per period), final
states only. This is ``eros_w5``.

The starts are drawn here once with numpy and the same array goes to both sides (the core's
workloads draw theirs from its own counter-based streams: the numbers differ, the distribution
and the work do not).

The peer is numba, one case per ``prange`` iteration, ``@njit(parallel=True, fastmath=False,
cache=False)``, written in landing's semantics (docs/guide/semantics.md): the law reads the
state at t_k, the command is held over [t_k, t_k + dt), RK4's stages at t, t + h/2, t + h/2,
t + h, the gravity and frame terms evaluated at each stage, the reference cubic evaluated at
the control instants, and every floating-point operation in landing's order. What cannot
agree bit for bit is the elementary functions: landing evaluates exp, log and pow with its own
vectorised kernels (crates/landing_core/src/lanes/exp_log.rs: within an ulp or so, not
correctly rounded, the same bits at every instruction-set level), numba calls the platform's
libm; the tolerance below says how far that carries (see TOLERANCE_W3).

Both sides must agree on every final state before any time is taken. Compilation is excluded:
every row runs once untimed first. The timed runs go round-robin over the rows (a different
row first in each round), and the table gives the best and the median of --repeat runs, ns
per case-step, and the ratio landing/numba at the same thread count (above 1: landing is
slower). CPU/wall is the process's CPU time (all its threads) over the wall time of a run.
Every timed run starts 50 ms after the last (SETTLE_S): numba's OpenMP workers spin after a
parallel region and, unpaused, took 8 ms of CPU from a 19 ms landing run that followed.

    pip install -r benches/requirements.txt   # numba
    python benches/peers_small_body.py [--cases 300] [--repeat 5] [--threads 1 2] [--only W3,W5]
"""

from __future__ import annotations

import argparse
import datetime
import os
import platform
import shlex
import statistics
import sys
import time
from importlib import metadata

import numpy as np

# --- W3 ------------------------------------------------------------------------------------------

W3_T_FINAL, W3_DT = 15.0, 0.01
W3_STEPS = int(round(W3_T_FINAL / W3_DT))
W3_OMEGA = 3.3118e-4
W3_G, W3_MASS_HALF = 6.6743e-11, 6.687e15 / 2.0
W3_D = 17_200.0 / np.sqrt(5.0)  # the core's TwoPointMass::eros (the Python default rounds it)
W3_P0 = np.array([3200.0, 1300.0, 9000.0])
W3_V0 = np.array([-1.2, 0.2, -1.0])
W3_PT = np.array([2837.0, 928.1, 5708.0])
W3_T_END = 8000.0
W3_ALPHA, W3_BETA, W3_P, W3_Q, W3_K, W3_N, W3_M, W3_E_FLOOR = 1.0, 0.4, 1.0, 5.0, 2.5, 10.0, 10.0, 1e-3
W3_SPREAD = 10.0
# Largest relative difference |x - x_landing| / max(|x_landing|, 1) allowed on any final state.
TOLERANCE_W3 = 1e-9


def cubic_coefficients(p0, v0, pt, vt, t):
    """c0..c3 as the core computes them (reference.rs, cubic_coefficients), operation for
    operation: shape (3, 4)."""
    c2 = (pt - p0) * (3.0 / (t * t)) - (v0 * 2.0 + vt) / t
    c3 = (p0 - pt) * (2.0 / (t * t * t)) + (v0 + vt) / (t * t)
    return np.stack([p0, v0, c2, c3], axis=1)


def w3_initial_states(n: int, seed: int = 2024) -> np.ndarray:
    z = np.random.default_rng(seed).standard_normal((n, 3))
    return np.concatenate([W3_P0 + W3_SPREAD * z, np.broadcast_to(W3_V0, (n, 3))], axis=1)


def w3_landing_setup():
    import landing

    gravity = landing.gravity.TwoPointMass(m1=W3_MASS_HALF, m2=W3_MASS_HALF, position1=[W3_D, 0.0, 0.0],
                                           position2=[-W3_D, 0.0, 0.0], G=W3_G)
    plant = landing.plants.SmallBody(gravity=gravity, omega=W3_OMEGA)
    law = landing.controllers.FuzzyFastTerminalSMC(alpha=W3_ALPHA, beta=W3_BETA, p=W3_P, q=W3_Q, k=W3_K, n=W3_N,
                                                   m=W3_M, switch="sign", e_floor=W3_E_FLOOR)
    reference = landing.reference.Cubic.from_boundary(W3_P0, W3_V0, W3_PT, np.zeros(3), T=W3_T_END)
    coefficients = np.asarray(reference.coefficients, dtype=float)
    mine = cubic_coefficients(W3_P0, W3_V0, W3_PT, np.zeros(3), W3_T_END)
    if not np.array_equal(coefficients, mine):
        raise RuntimeError(f"landing's cubic {coefficients} differs from the peer's {mine}")
    return landing, plant, law, reference


def w3_run_landing(setup, x0: np.ndarray, threads: int | None) -> np.ndarray:
    landing, plant, law, reference = setup
    res = landing.simulate_batch(plant, law, x0, t_final=W3_T_FINAL, dt=W3_DT, reference=reference,
                                 record_every=0, threads=threads)
    return np.asarray(res.final_state)


def make_numba_w3():
    """The W3 peer: one case per prange iteration, every operation in landing's order."""
    import numba

    coef = cubic_coefficients(W3_P0, W3_V0, W3_PT, np.zeros(3), W3_T_END)
    C0, C1, C2, C3 = (np.ascontiguousarray(coef[:, j]) for j in range(4))
    mu = W3_G * W3_MASS_HALF
    w, w2 = W3_OMEGA, W3_OMEGA * W3_OMEGA
    d = W3_D
    r_exp = W3_P / W3_Q
    floor_slope = W3_E_FLOOR ** (r_exp - 1.0)  # as landing: floor.powf(r - 1), one value
    scale_d = np.sqrt(1.0 + W3_ALPHA * W3_ALPHA)
    alpha, beta, beta_r, k_sw, n_b, m_b, e_floor = W3_ALPHA, W3_BETA, W3_BETA * r_exp, W3_K, W3_N, W3_M, W3_E_FLOOR
    t_end, dt, steps = W3_T_END, W3_DT, W3_STEPS

    @numba.njit(inline="always")
    def sgn(x):
        return 1.0 if x > 0.0 else (-1.0 if x < 0.0 else 0.0)

    @numba.njit(inline="always")
    def drift(x, out):
        """Frame (Coriolis, centrifugal) and two-point-mass gravity at x."""
        r0, r1, r2 = x[0], x[1], x[2]
        # first mass point at (+d, 0, 0)
        a0 = r0 - d
        q = a0 * a0 + r1 * r1 + r2 * r2
        s = mu / (q * np.sqrt(q))
        g0, g1, g2 = -(a0 * s), -(r1 * s), -(r2 * s)
        # second mass point at (-d, 0, 0)
        b0 = r0 + d
        q = b0 * b0 + r1 * r1 + r2 * r2
        s = mu / (q * np.sqrt(q))
        out[0] = (w * 2.0 * x[4] + w2 * r0) + (g0 - b0 * s)
        out[1] = (-w * 2.0 * x[3] + w2 * r1) + (g1 - r1 * s)
        out[2] = g2 - r2 * s

    @numba.njit(inline="always")
    def rhs(y, u, dr, out, fresh):
        """x' at y under the held command u; the drift recomputed at y unless fresh is False
        (the step's first stage, where the law's drift is the drift at the state)."""
        if fresh:
            drift(y, dr)
        for i in range(3):
            out[i] = y[3 + i]
            out[3 + i] = dr[i] + u[i]

    @numba.njit(inline="always")
    def command(t, x, dr, u, s, eq):
        """The fuzzy fast-terminal law at (t, x); dr is the drift at x."""
        tt = t if t <= t_end else t_end
        before = t <= t_end
        for i in range(3):
            pos = C0[i] + (C1[i] + (C2[i] + C3[i] * tt) * tt) * tt
            vel = C1[i] + (C2[i] * 2.0 + C3[i] * (3.0 * tt)) * tt if before else 0.0
            acc = C2[i] * 2.0 + C3[i] * (6.0 * tt) if before else 0.0
            e = x[i] - pos
            de = x[3 + i] - vel
            ae = abs(e)
            p = ae ** r_exp
            s[i] = (de + alpha * e) + (beta * sgn(e)) * p
            slope = p / ae if ae >= e_floor else floor_slope
            eq[i] = (acc - dr[i]) - (alpha + beta_r * slope) * de
        d0, d1, d2 = s[0] / scale_d, s[1] / scale_d, s[2] / scale_d
        dist = np.sqrt(d0 * d0 + d1 * d1 + d2 * d2)
        a = np.exp(-n_b * dist)
        b = 1.0 - np.exp(-m_b * dist)
        for i in range(3):
            u[i] = a * eq[i] - b * k_sw * sgn(s[i])

    @numba.njit(parallel=True, fastmath=False, cache=False)
    def run(x0):
        n = x0.shape[0]
        out = np.empty_like(x0)
        for c in numba.prange(n):
            x = x0[c].copy()
            y = np.empty(6)
            acc = np.empty(6)
            k = np.empty(6)
            u, dr, s, eq = np.empty(3), np.empty(3), np.empty(3), np.empty(3)
            for step in range(steps):
                t = step * dt
                drift(x, dr)
                command(t, x, dr, u, s, eq)
                # RK4, the command held; landing's weighted sum ((k1 + 2 k2) + 2 k3) + k4
                rhs(x, u, dr, k, False)
                for j in range(6):
                    acc[j] = k[j]
                    y[j] = x[j] + k[j] * (0.5 * dt)
                rhs(y, u, dr, k, True)
                for j in range(6):
                    acc[j] += k[j] * 2.0
                    y[j] = x[j] + k[j] * (0.5 * dt)
                rhs(y, u, dr, k, True)
                for j in range(6):
                    acc[j] += k[j] * 2.0
                    y[j] = x[j] + k[j] * (1.0 * dt)
                rhs(y, u, dr, k, True)
                for j in range(6):
                    acc[j] += k[j]
                    x[j] = x[j] + acc[j] * (dt / 6.0)
            out[c] = x
        return out

    return numba, run


# --- measuring -----------------------------------------------------------------------------------


# numba's OpenMP workers spin for a while after a parallel region (libgomp's default wait
# policy): measured here, 8 ms of CPU taken from a 19 ms landing run that followed a two-thread
# numba run at once. Every timed run starts after this pause, when they have gone to sleep.
SETTLE_S = 0.05


def measure(fn) -> dict:
    """Wall time and CPU time of this process (all its threads) over one run, after SETTLE_S."""
    time.sleep(SETTLE_S)
    c0, t0 = time.process_time(), time.perf_counter()
    fn()
    return {"wall": time.perf_counter() - t0, "cpu": time.process_time() - c0}


def machine() -> str:
    model = platform.processor() or platform.machine()
    try:
        with open("/proc/cpuinfo") as fh:
            model = next(line.split(":", 1)[1].strip() for line in fh if line.startswith("model name"))
    except (OSError, StopIteration):
        pass
    return f"{model}, {len(os.sched_getaffinity(0))} cores, Linux {platform.release()}"


def version(name: str) -> str:
    try:
        return metadata.version(name)
    except metadata.PackageNotFoundError:
        return "not installed"


def agreement(final: np.ndarray, reference: np.ndarray) -> tuple[float, float]:
    """Largest |x - x_ref| / max(|x_ref|, 1) over all final states, and the share of the
    final-state components that agree bit for bit."""
    err = float(np.max(np.abs(final - reference) / np.maximum(np.abs(reference), 1.0)))
    return err, float(np.mean(final == reference))


WORKLOADS = ("W3",)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--cases", type=int, default=300)
    ap.add_argument("--repeat", type=int, default=5, help="timed runs per row (best and median of these)")
    ap.add_argument("--threads", type=int, nargs="+", default=None,
                    help="thread counts (default: 1 and the number of cores)")
    ap.add_argument("--only", default=",".join(WORKLOADS), help="comma-separated subset of " + ",".join(WORKLOADS))
    args = ap.parse_args()

    cores = len(os.sched_getaffinity(0))
    thread_counts = args.threads or sorted({1, cores})
    only = [s.strip() for s in args.only.split(",") if s.strip()]
    unknown = set(only) - set(WORKLOADS)
    if unknown:
        ap.error(f"unknown workload(s) {sorted(unknown)}; choose from {','.join(WORKLOADS)}")

    print(f"W3/W5 peers, {datetime.datetime.now().astimezone().isoformat(timespec='seconds')}")
    print(f"command: {shlex.join([os.path.basename(sys.executable)] + sys.argv)}")
    print(f"machine: {machine()}")
    print(f"python {platform.python_version()}, landing {version('landing')}, numpy {np.__version__}, "
          f"numba {version('numba')}, llvmlite {version('llvmlite')}")

    # Per workload: steps per case, x0, the landing runner, the numba runner, the tolerance.
    notes = []
    specs = {}
    numba = None
    if "W3" in only:
        setup = w3_landing_setup()
        x0 = w3_initial_states(args.cases)
        t0 = time.perf_counter()
        numba, run = make_numba_w3()
        first = run(x0)  # compiles on the first call
        notes.append(f"W3 numba: first call (compilation and one run) {time.perf_counter() - t0:.2f} s")
        specs["W3"] = dict(steps=W3_STEPS, x0=x0, tolerance=TOLERANCE_W3, numba_final=first,
                           landing=lambda n, s=setup, x0=x0: w3_run_landing(s, x0, n),
                           numba=lambda x0=x0, run=run: run(x0))
    if "W5" in only:
        setup = w5_landing_setup()
        x0 = w5_initial_states(args.cases)
        t0 = time.perf_counter()
        numba, run = make_numba_w5(setup)
        first = run(x0)
        notes.append(f"W5 numba: first call (compilation and one run) {time.perf_counter() - t0:.2f} s")
        specs["W5"] = dict(steps=W5_STEPS, x0=x0, tolerance=TOLERANCE_W5, numba_final=first,
                           landing=lambda n, s=setup, x0=x0: w5_run_landing(s, x0, n),
                           numba=lambda x0=x0, run=run: run(x0))
    notes.append(f"numba threading layer: {numba.threading_layer()}")
    for name, spec in specs.items():
        print(f"{name}: {args.cases} cases x {spec['steps']} steps = {args.cases * spec['steps']:.3g} case-steps "
              f"per run; thread counts {thread_counts}")

    # Agreement before any timing: landing's final states (at every thread count) against the
    # peer's, and landing against itself across thread counts (bit for bit).
    print("\nAgreement (largest |x - x_landing| / max(|x_landing|, 1) over all final states; share of "
          "components equal bit for bit):")
    failed = False
    for name, spec in specs.items():
        finals = {n: spec["landing"](n) for n in thread_counts}
        reference = finals[thread_counts[0]]
        for n, final in finals.items():
            if not np.array_equal(final, reference):
                failed = True
                print(f"  {name} landing, {n} threads: differs from {thread_counts[0]} thread(s)  DISAGREES")
        numba.set_num_threads(thread_counts[0])
        err, same = agreement(spec["numba_final"], reference)
        ok = err <= spec["tolerance"] and np.isfinite(spec["numba_final"]).all()
        failed |= not ok
        print(f"  {name} numba vs landing: {err:.1e} ({same:.1%} bit-equal)"
              f"{'' if ok else '  DISAGREES'} (tolerance {spec['tolerance']:g})")
    if failed:
        sys.exit("the peer disagrees with landing; no timings taken")

    rows = []  # (workload, implementation, threads, callable returning a measurement)
    for name, spec in specs.items():
        for n in thread_counts:
            rows.append((name, "landing", n, lambda n=n, f=spec["landing"]: measure(lambda: f(n))))

            def numba_row(n=n, f=spec["numba"]):
                numba.set_num_threads(n)
                return measure(f)

            rows.append((name, "numba", n, numba_row))

    # One untimed run of every row (thread pools, caches), then round-robin timing.
    for row in rows:
        row[3]()
    results = {i: [] for i in range(len(rows))}
    for rnd in range(args.repeat):
        order = list(range(len(rows)))
        order = order[rnd % len(order):] + order[:rnd % len(order)]
        for i in order:
            results[i].append(rows[i][3]())

    def stats(i):
        walls = [m["wall"] for m in results[i]]
        return min(walls), statistics.median(walls)

    index = {(w, impl, n): i for i, (w, impl, n, _) in enumerate(rows)}
    print(f"\n{args.repeat} timed runs per row, round-robin; ns/cs = ns per case-step; landing/numba = landing's "
          f"time over numba's at the same thread count (best; median); CPU/wall = median over the runs")
    head = (f"| {'workload':<8} | {'implementation':<26} | {'thr':>3} | {'best s':>7} | {'median s':>8} | "
            f"{'ns/cs best':>10} | {'ns/cs med':>9} | {'landing/numba best':>18} | {'landing/numba med':>17} | "
            f"{'CPU/wall':>8} |")
    print(head)
    print("|" + "|".join("-" * len(c) for c in head.split("|")[1:-1]) + "|")
    for name, spec in specs.items():
        case_steps = args.cases * spec["steps"]
        for n in thread_counts:
            lb, lm = stats(index[(name, "landing", n)])
            nb, nm = stats(index[(name, "numba", n)])
            for impl, label in (("landing", "landing (simulate_batch)"), ("numba", "numba (prange over cases)")):
                i = index[(name, impl, n)]
                best, med = stats(i)
                cpu = statistics.median(m["cpu"] / m["wall"] for m in results[i])
                ratio_b = f"{lb / nb:.2f}" if impl == "landing" else ""
                ratio_m = f"{lm / nm:.2f}" if impl == "landing" else ""
                print(f"| {name:<8} | {label:<26} | {n:>3} | {best:7.4f} | {med:8.4f} | "
                      f"{best * 1e9 / case_steps:10.1f} | {med * 1e9 / case_steps:9.1f} | {ratio_b:>18} | "
                      f"{ratio_m:>17} | {cpu:8.2f} |")
    print("\nEvery timed run, in the order of the rounds (wall s, CPU/wall; a multi-threaded row far below its")
    print("thread count in CPU/wall had cores taken by other load on the machine):")
    for i, (name, impl, n, _) in enumerate(rows):
        runs = "  ".join(f"{m['wall']:.4f} {m['cpu'] / m['wall']:.2f}" for m in results[i])
        print(f"  {name} {impl + ', ' + str(n) + ' thr':<16} {runs}")
    print("\nNotes:")
    for note in notes:
        print(f"  {note}")


if __name__ == "__main__":
    main()
