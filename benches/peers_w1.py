"""W1 side by side (SPEC section 10): landing against a numpy implementation vectorised over
cases and a numba one (one case per prange iteration), same workload, same machine, one run.

Seed-001 fixed-time MSS guidance (eq. 25 as printed, the SPEC section 6 gains) on 300 Table II
dispersed Mars cases, 10 s at dt = 1 ms, RK4 with the thrust held over each period, drag, 50 kN
per axis, a_p = 20 sin t evaluated at the stage times, final states only. The three
implementations must agree on the final states before any time is reported.

    pip install numba   # benches/requirements.txt
    python benches/peers_w1.py [--cases 300] [--repeat 3]
"""

from __future__ import annotations

import argparse
import os
import platform
import time

import numpy as np

import landing

G_MARS, G0, ISP, KD, HD, FMAX = 3.7114, 9.807, 225.0, 0.699, 0.0009, 50_000.0
AREA = np.array([6.0, 7.5, 8.7])
B1, B2, Q1, Q2, A1, A2, G1, G2 = 0.8, 0.4, 0.95, 1.05, 0.9, 0.5, 0.9, 1.1
T_FINAL, DT = 10.0, 1e-3
STEPS = int(round(T_FINAL / DT))


def initial_states(n: int) -> np.ndarray:
    mean = landing.scenarios.MARS_NOMINAL_STATE
    sd = np.array([100, 100, 100, 10, 10, 10, 20.0])
    return landing.dispersions.Normal(mean=mean, std=sd).sample(n, seed=2024)


def run_landing(x0: np.ndarray, threads: int | None) -> np.ndarray:
    law = landing.controllers.FixedTimeMSS(beta1=B1, beta2=B2, q1=Q1, q2=Q2, alpha1=A1, alpha2=A2, gamma1=G1,
                                           gamma2=G2)
    res = landing.simulate_batch(landing.plants.MarsLander(thrust_limit=FMAX), law, x0, t_final=T_FINAL, dt=DT,
                                 disturbance=landing.disturbances.Sinusoid(amplitude=20.0, omega=1.0),
                                 record_every=0, threads=threads)
    return res.final_state


# --- numpy: all cases at once --------------------------------------------------------------


def np_sig(x, a):
    return np.sign(x) * np.abs(x) ** a


def np_drag(r, v, m):
    return -KD * v * np.abs(v) * np.exp(-HD * r[:, 2:3]) / (AREA * m[:, None])


def np_rhs(t, x, force):
    r, v, m = x[:, :3], x[:, 3:6], x[:, 6]
    a = force / m[:, None] + np_drag(r, v, m) + 20.0 * np.sin(t)
    a[:, 2] -= G_MARS
    mdot = -np.linalg.norm(force, axis=1) / (ISP * G0)
    return np.concatenate([v, a, mdot[:, None]], axis=1)


def np_command(x):
    r, v, m = x[:, :3], x[:, 3:6], x[:, 6]
    drift = np_drag(r, v, m)
    drift[:, 2] -= G_MARS
    s2 = v + B1 * np_sig(r, Q1) + B2 * np_sig(r, Q2)
    a = (-drift + B1**2 * Q1 * np_sig(r, 2 * Q1 - 1) + B2**2 * Q2 * np_sig(r, 2 * Q2 - 1)
         + B1 * B2 * (Q1 + Q2) * np_sig(r, Q1 + Q2 - 1) - A1 * np_sig(s2, G1) - A2 * np_sig(s2, G2))
    return np.clip(m[:, None] * a, -FMAX, FMAX)


def run_numpy(x0: np.ndarray) -> np.ndarray:
    x = x0.copy()
    for k in range(STEPS):
        t = k * DT
        f = np_command(x)
        k1 = np_rhs(t, x, f)
        k2 = np_rhs(t + DT / 2, x + DT / 2 * k1, f)
        k3 = np_rhs(t + DT / 2, x + DT / 2 * k2, f)
        k4 = np_rhs(t + DT, x + DT * k3, f)
        x = x + DT / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
    return x


# --- numba: one case per prange iteration ---------------------------------------------------


def make_numba():
    import numba

    @numba.njit(inline="always")
    def sig(x, a):
        return 0.0 if x == 0.0 else np.sign(x) * abs(x) ** a

    @numba.njit(inline="always")
    def rhs(t, x, f, out):
        m = x[6]
        e = np.exp(-HD * x[2])
        d = 20.0 * np.sin(t)
        nf = np.sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2])
        for i in range(3):
            out[i] = x[3 + i]
            drag = -KD * x[3 + i] * abs(x[3 + i]) * e / (AREA[i] * m)
            out[3 + i] = f[i] / m + drag + d
        out[5] -= G_MARS
        out[6] = -nf / (ISP * G0)

    @numba.njit(parallel=True, fastmath=False)
    def run(x0):
        n = x0.shape[0]
        out = np.empty_like(x0)
        for c in numba.prange(n):
            x = x0[c].copy()
            f = np.empty(3)
            k1, k2, k3, k4, tmp = np.empty(7), np.empty(7), np.empty(7), np.empty(7), np.empty(7)
            for k in range(STEPS):
                t = k * DT
                m = x[6]
                e = np.exp(-HD * x[2])
                for i in range(3):
                    r, v = x[i], x[3 + i]
                    drift = -KD * v * abs(v) * e / (AREA[i] * m) - (G_MARS if i == 2 else 0.0)
                    s2 = v + B1 * sig(r, Q1) + B2 * sig(r, Q2)
                    a = (-drift + B1 * B1 * Q1 * sig(r, 2 * Q1 - 1) + B2 * B2 * Q2 * sig(r, 2 * Q2 - 1)
                         + B1 * B2 * (Q1 + Q2) * sig(r, Q1 + Q2 - 1) - A1 * sig(s2, G1) - A2 * sig(s2, G2))
                    f[i] = min(max(m * a, -FMAX), FMAX)
                rhs(t, x, f, k1)
                for j in range(7):
                    tmp[j] = x[j] + DT / 2 * k1[j]
                rhs(t + DT / 2, tmp, f, k2)
                for j in range(7):
                    tmp[j] = x[j] + DT / 2 * k2[j]
                rhs(t + DT / 2, tmp, f, k3)
                for j in range(7):
                    tmp[j] = x[j] + DT * k3[j]
                rhs(t + DT, tmp, f, k4)
                for j in range(7):
                    x[j] += DT / 6 * (k1[j] + 2 * k2[j] + 2 * k3[j] + k4[j])
            out[c] = x
        return out

    return numba, run


def best_of(fn, repeat: int) -> float:
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--cases", type=int, default=300)
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    x0 = initial_states(args.cases)
    cores = os.cpu_count() or 1

    ours = run_landing(x0, None)
    ref_np = run_numpy(x0)
    numba, run_numba = make_numba()
    ref_nb = run_numba(x0)
    for name, other in (("numpy", ref_np), ("numba", ref_nb)):
        err = np.max(np.abs(other - ours) / np.maximum(np.abs(ours), 1.0))
        assert err < 1e-6, f"{name} disagrees with landing: {err:.2e}"
        print(f"{name:<6} agrees with landing: largest relative difference {err:.1e}")

    steps = args.cases * STEPS
    rows = [("landing, 1 thread", lambda: run_landing(x0, 1)),
            (f"landing, {cores} threads", lambda: run_landing(x0, None)),
            ("numpy (vectorised over cases)", lambda: run_numpy(x0))]
    numba.set_num_threads(1)
    rows.append(("numba, 1 thread", lambda: run_numba(x0)))
    timings = [(name, best_of(fn, args.repeat)) for name, fn in rows]
    numba.set_num_threads(cores)
    timings.append((f"numba, {cores} threads", best_of(lambda: run_numba(x0), args.repeat)))

    base = timings[0][1]
    print(f"\nW1: {args.cases} cases x {STEPS} steps = {steps:.3g} case-steps, best of {args.repeat}; "
          f"{platform.processor() or platform.machine()}, {cores} cores, numba {numba.__version__}, numpy {np.__version__}")
    print(f"{'implementation':<32} {'time (s)':>9} {'ns/case-step':>13} {'vs landing 1 thread':>20}")
    for name, t in timings:
        print(f"{name:<32} {t:9.3f} {t * 1e9 / steps:13.1f} {t / base:19.2f}x")


if __name__ == "__main__":
    main()
