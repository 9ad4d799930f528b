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
centroid of the aggregated membership sampled at 401 points on the output universe) on 433
Eros with the C20/C22 harmonics (mu 4.842e5, R0 1138.5 m, C20 -0.043, C22 0.058) rotating at
1.65e-4 rad/s, tracking the paper's cubic from (550, 500, 8200) m, (-1.7, 0.7, -1.5) m/s to
(20, 80, 2000) m at rest at 4000 s; 300 starts at the documented 50 m offset per axis,
dispersed by 10 m (1 sigma), at the cubic's initial velocity; a model uncertainty of up to 1 %
of the command per axis, drawn once per control period (``CommandNoise(0.01)``, seed 2024);
100 s at dt = 0.1 s, RK4 (one step per period), final states only. This is ``eros_w5``.

The starts are drawn here once with numpy (W3 from seed 2024, W5 from 2025) and the same array
goes to both sides (the core's workloads draw theirs from its own counter-based streams: the
numbers differ, the distribution and the work do not).

The peer is numba, one case per ``prange`` iteration, ``@njit(parallel=True, fastmath=False,
cache=False)``, written in landing's semantics (docs/guide/semantics.md): the law reads the
state at t_k, the command (and W5's noise) is held over [t_k, t_k + dt), RK4's stages at t,
t + h/2, t + h/2, t + h with the gravity and frame terms evaluated at each stage, the reference
cubic evaluated at the control instants, the law's memory (W5's integral and previous s)
advanced by forward Euler after the command, and every floating-point operation in landing's
order. W5's command noise comes from landing's own generator, reproduced in the peer: Philox4x64-10
with the key (seed, 2) and the counter (control period, case, 0, 0), the top 53 bits of the
first three words as uniforms on [0, 1), mapped to [-1, 1) (crates/landing_core/src/rng.rs),
drawn inside the loop as landing draws it. The Mamdani system is the same computation: the
output sets tabulated once on the 401-point grid, per call the 25 rule strengths (min), one
strength per output set (max), the aggregated membership (max of the clipped sets) summed over
the fired sets' support, the centroid of its piecewise-linear interpolant in closed form.

Accuracy. W5 has no exp, log or pow: every operation is IEEE-exact on both sides, and the peer
must agree with landing bit for bit (TOLERANCE_W5 = 0; it does). W3 has three |e|^(1/5) and
two exp per case-step; landing evaluates them with its own vectorised kernels
(crates/landing_core/src/lanes/exp_log.rs: within an ulp or so, not correctly rounded, the same
bits at every instruction-set level), numba calls the platform's libm. Checked on landing's
recorded diagnostics at t = 0 for the 300 starts: libm's pow gives a surface value s one ulp
from landing's in 0.8 % of the components, libm's exp a blend weight a = exp(-N D) one ulp off
in 4 % of the cases, and everything computed from equal inputs is equal. Carried over 1500
steps, about 9 % of W3's final-state components differ from landing's, by at most 1 ulp
(2.2e-16 relative); TOLERANCE_W3 = 1e-9 is the brief's bound, with six orders of magnitude to
spare.

Both sides must agree on every final state before any time is taken. Compilation is excluded:
every row runs once untimed first. The timed runs go round-robin over the rows (a different
row first in each round), and the table gives the best and the median of --repeat runs, ns
per case-step, and the ratio landing/numba at the same thread count (above 1: landing is
slower). CPU/wall is the process's CPU time (all its threads) over the wall time of a run.
Every timed run starts 50 ms after the last (SETTLE_S): numba's OpenMP workers spin after a
parallel region and, unpaused, took 8 ms of CPU from a 19 ms landing run that followed.

    pip install -r benches/requirements.txt   # numba
    python benches/peers_small_body.py [--cases 300] [--repeat 5] [--threads 1 2] [--only W3,W5] [--json FILE]
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

import numpy as np
from _harness import json_option, machine, measure, numba_fma, version, write_json

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

    fma = numba_fma()

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
                    y[j] = fma(k[j], 0.5 * dt, x[j])
                rhs(y, u, dr, k, True)
                for j in range(6):
                    acc[j] = fma(k[j], 2.0, acc[j])
                    y[j] = fma(k[j], 0.5 * dt, x[j])
                rhs(y, u, dr, k, True)
                for j in range(6):
                    acc[j] = fma(k[j], 2.0, acc[j])
                    y[j] = fma(k[j], 1.0 * dt, x[j])
                rhs(y, u, dr, k, True)
                for j in range(6):
                    acc[j] += k[j]
                    x[j] = fma(acc[j], dt / 6.0, x[j])
            out[c] = x
        return out

    return numba, run


# --- W5 ------------------------------------------------------------------------------------------

W5_T_FINAL, W5_DT = 100.0, 0.1
W5_STEPS = int(round(W5_T_FINAL / W5_DT))
W5_OMEGA = 1.65e-4
W5_MU, W5_R0, W5_C20, W5_C22 = 4.842e5, 1138.5, -0.043, 0.058
W5_P0 = np.array([550.0, 500.0, 8200.0])
W5_V0 = np.array([-1.7, 0.7, -1.5])
W5_PT = np.array([20.0, 80.0, 2000.0])
W5_T_END = 4000.0
W5_OFFSET, W5_SPREAD = 50.0, 10.0
W5_C1, W5_C2, W5_K = 0.017 * 0.017, 2.0 * 0.017, 0.1
W5_KE, W5_KEC, W5_KU = 3.162e4, 10.0, 2.813e-4
W5_RESOLUTION = 401
W5_NOISE = 0.01  # model uncertainty: up to 1 % of the command, per axis and control period
W5_SEED = 2024  # the seed of the command noise's streams (the core's rollout bench's)
# The paper's Table 1: rows s in NB..PB, columns s' in NB..PB; entries NB NM NS ZR PS PM PB = 0..6.
W5_RULES = np.array([[0, 1, 1, 4, 3], [1, 2, 2, 3, 5], [2, 2, 3, 4, 4], [5, 3, 4, 5, 5], [3, 5, 5, 5, 6]])
# W5 has no exp, log or pow: every operation is IEEE-exact on both sides, so they must agree
# bit for bit.
TOLERANCE_W5 = 0.0


def w5_initial_states(n: int, seed: int = 2025) -> np.ndarray:
    z = np.random.default_rng(seed).standard_normal((n, 3))
    return np.concatenate([(W5_P0 + W5_OFFSET) + W5_SPREAD * z, np.broadcast_to(W5_V0, (n, 3))], axis=1)


def w5_landing_setup():
    import landing

    gravity = landing.gravity.Harmonic2(mu=W5_MU, r0=W5_R0, c20=W5_C20, c22=W5_C22)
    plant = landing.plants.SmallBody(gravity=gravity, omega=W5_OMEGA)
    law = landing.controllers.FuzzyVariableRate(c1=W5_C1, c2=W5_C2, k=W5_K, ke=W5_KE, kec=W5_KEC, ku=W5_KU,
                                                system=landing.fuzzy.variable_rate_system(W5_RESOLUTION))
    reference = landing.reference.Cubic.from_boundary(W5_P0, W5_V0, W5_PT, np.zeros(3), T=W5_T_END)
    coefficients = np.asarray(reference.coefficients, dtype=float)
    mine = cubic_coefficients(W5_P0, W5_V0, W5_PT, np.zeros(3), W5_T_END)
    if not np.array_equal(coefficients, mine):
        raise RuntimeError(f"landing's cubic {coefficients} differs from the peer's {mine}")
    noise = landing.disturbances.CommandNoise(W5_NOISE)
    return landing, plant, law, reference, noise


def w5_run_landing(setup, x0: np.ndarray, threads: int | None) -> np.ndarray:
    landing, plant, law, reference, noise = setup
    res = landing.simulate_batch(plant, law, x0, t_final=W5_T_FINAL, dt=W5_DT, reference=reference,
                                 disturbance=noise, seed=W5_SEED, record_every=0, threads=threads)
    return np.asarray(res.final_state)


def even_triangles(lo: float, hi: float, count: int) -> np.ndarray:
    """count triangles (a, b, c) evenly over [lo, hi], shoulders at the ends (the core's
    even_triangles, operation for operation)."""
    step = (hi - lo) / (count - 1)
    out = []
    for i in range(count):
        b = lo + step * i
        out.append((max(b - step, lo), b, min(b + step, hi)))
    return np.array(out)


def triangle(x: float, a: float, b: float, c: float) -> float:
    up = 0.0 if x < a else (1.0 if x >= b else (x - a) / (b - a))
    down = 0.0 if x > c else (1.0 if x <= b else (c - x) / (c - b))
    return min(up, down)


def make_numba_w5(setup=None):
    """The W5 peer: one case per prange iteration, every operation in landing's order; the
    command noise from the same counter-based generator (Philox4x64-10, key (seed, 2), counter
    (control period, case, 0, 0): the core's rng.rs), drawn inside the loop as landing draws it."""
    import numba

    fma = numba_fma()

    coef = cubic_coefficients(W5_P0, W5_V0, W5_PT, np.zeros(3), W5_T_END)
    C0, C1, C2, C3 = (np.ascontiguousarray(coef[:, j]) for j in range(4))
    w, w2 = W5_OMEGA, W5_OMEGA * W5_OMEGA
    mu, c20, c22 = W5_MU, W5_C20, W5_C22
    kq = W5_MU * W5_R0 * W5_R0
    gx, gy, gz = c22 * 6.0 - c20, -(c20 + c22 * 6.0), c20 * 2.0
    c1, c2, k_r, ke, kec, ku = W5_C1, W5_C2, W5_K, W5_KE, W5_KEC, W5_KU
    t_end, dt, steps, noise = W5_T_END, W5_DT, W5_STEPS, W5_NOISE

    # The Mamdani system: 5 triangles per input on [-5, 5], 7 on [-4, 4] for the output, sampled
    # at W5_RESOLUTION points; min for AND, max for aggregation, centroid of the piecewise-linear
    # interpolant (landing's fuzzy/mamdani.rs, the scikit-fuzzy conventions).
    in_lo, in_hi, out_lo, out_hi, n = -5.0, 5.0, -4.0, 4.0, W5_RESOLUTION
    in_sets = even_triangles(in_lo, in_hi, 5)
    out_sets = even_triangles(out_lo, out_hi, 7)
    step = (out_hi - out_lo) / (n - 1)
    grid = [out_lo + step * j for j in range(n)]
    table = np.array([[triangle(y, *abc) for y in grid] for abc in out_sets])
    support = np.array([(np.flatnonzero(row > 0.0)[0], np.flatnonzero(row > 0.0)[-1]) for row in table])
    rules = W5_RULES.copy()
    n_out = out_sets.shape[0]
    h_out = (out_hi - out_lo) / (n - 1)
    half_span = 0.5 * (n - 1)

    @numba.njit(inline="always")
    def membership(x, a, b, c):
        up = 0.0 if x < a else (1.0 if x >= b else (x - a) / (b - a))
        down = 0.0 if x > c else (1.0 if x <= b else (c - x) / (c - b))
        return up if up < down else down

    @numba.njit
    def fuzzy(x0, x1, fire, active):
        """F(x0, x1): the crisp output of the Mamdani system, 0 where no rule fires."""
        x0 = min(max(x0, in_lo), in_hi)
        x1 = min(max(x1, in_lo), in_hi)
        for kk in range(n_out):
            fire[kk] = 0.0
        for i in range(5):
            m0 = membership(x0, in_sets[i, 0], in_sets[i, 1], in_sets[i, 2])
            for j in range(5):
                m1 = membership(x1, in_sets[j, 0], in_sets[j, 1], in_sets[j, 2])
                wgt = min(min(1.0, m0), m1)
                c = rules[i, j]
                if wgt > fire[c]:
                    fire[c] = wgt
        n_active = 0
        first, last = n, 0
        for kk in range(n_out):
            if fire[kk] > 0.0:
                active[n_active] = kk
                n_active += 1
                first = min(first, support[kk, 0])
                last = max(last, support[kk, 1])
        if first > last:
            return 0.0
        s0 = 0.0
        s1 = 0.0
        m_first = 0.0
        m_last = 0.0
        for j in range(first, last + 1):
            m = 0.0
            for a in range(n_active):
                kk = active[a]
                v = min(fire[kk], table[kk, j])
                if v > m:
                    m = v
            s0 += m
            s1 += m * j
            if j == 0:
                m_first = m
            if j == n - 1:
                m_last = m
        area = s0 - (m_first + m_last) * 0.5
        moment = s1 - m_last * half_span + (m_first - m_last) / 6.0
        return out_lo + moment * h_out / area if area > 0.0 else 0.0

    M0, M1 = np.uint64(0xD2E7470EE14C6C93), np.uint64(0xCA5A826395121157)
    W0, W1 = np.uint64(0x9E3779B97F4A7C15), np.uint64(0xBB67AE8584CAA73B)
    LOW32, S32, S11 = np.uint64(0xFFFFFFFF), np.uint64(32), np.uint64(11)
    key0, key1 = np.uint64(W5_SEED), np.uint64(2)  # the command noise's stream
    two_m53 = 1.0 / float(1 << 53)

    @numba.njit(inline="always")
    def mulhilo(a, b):
        al, ah, bl, bh = a & LOW32, a >> S32, b & LOW32, b >> S32
        p0, p1, p2, p3 = al * bl, al * bh, ah * bl, ah * bh
        mid = (p0 >> S32) + (p1 & LOW32) + (p2 & LOW32)
        return p3 + (p1 >> S32) + (p2 >> S32) + (mid >> S32), a * b

    @numba.njit
    def uniforms3(counter, case, out):
        """Three uniforms on [-1, 1) from Philox4x64-10 at (counter, case, 0, 0), key (seed, 2)."""
        c0, c1_, c2_, c3 = np.uint64(counter), np.uint64(case), np.uint64(0), np.uint64(0)
        k0, k1 = key0, key1
        for rnd in range(10):
            if rnd > 0:
                k0 += W0
                k1 += W1
            hi0, lo0 = mulhilo(M0, c0)
            hi1, lo1 = mulhilo(M1, c2_)
            c0, c1_, c2_, c3 = hi1 ^ c1_ ^ k0, lo1, hi0 ^ c3 ^ k1, lo0
        out[0] = float(c0 >> S11) * two_m53 * 2.0 - 1.0
        out[1] = float(c1_ >> S11) * two_m53 * 2.0 - 1.0
        out[2] = float(c2_ >> S11) * two_m53 * 2.0 - 1.0

    @numba.njit(inline="always")
    def drift(x, out):
        """Frame (Coriolis, centrifugal) and C20/C22 gravity at x."""
        r0, r1, r2 = x[0], x[1], x[2]
        x2, y2, z2 = r0 * r0, r1 * r1, r2 * r2
        inv = 1.0 / np.sqrt(x2 + y2 + z2)
        inv2 = inv * inv
        inv5 = inv2 * inv2 * inv
        mono = -mu * inv2 * inv
        form = 0.5 * c20 * (z2 * 2.0 - x2 - y2) + 3.0 * c22 * (x2 - y2)
        radial = 5.0 * form * inv5 * inv2
        out[0] = (w * 2.0 * x[4] + w2 * r0) + (r0 * mono + (gx * r0 * inv5 - r0 * radial) * kq)
        out[1] = (-w * 2.0 * x[3] + w2 * r1) + (r1 * mono + (gy * r1 * inv5 - r1 * radial) * kq)
        out[2] = 0.0 + (r2 * mono + (gz * r2 * inv5 - r2 * radial) * kq)

    @numba.njit(inline="always")
    def rhs(y, u, d, dr, out, fresh):
        if fresh:
            drift(y, dr)
        for i in range(3):
            out[i] = y[3 + i]
            out[3 + i] = (dr[i] + u[i]) + d[i]

    @numba.njit(parallel=True, fastmath=False, cache=False)
    def run(x0):
        ncase = x0.shape[0]
        out = np.empty_like(x0)
        for c in numba.prange(ncase):
            x = x0[c].copy()
            y, acc, kd = np.empty(6), np.empty(6), np.empty(6)
            u, d, dr, uni = np.empty(3), np.empty(3), np.empty(3), np.empty(3)
            integral, prev_s = np.zeros(3), np.zeros(3)
            fire, active = np.empty(n_out), np.empty(n_out, dtype=np.int64)
            for step in range(steps):
                t = step * dt
                drift(x, dr)
                tt = t if t <= t_end else t_end
                before = t <= t_end
                for i in range(3):
                    pos = C0[i] + (C1[i] + (C2[i] + C3[i] * tt) * tt) * tt
                    vel = C1[i] + (C2[i] * 2.0 + C3[i] * (3.0 * tt)) * tt if before else 0.0
                    ref_acc = C2[i] * 2.0 + C3[i] * (6.0 * tt) if before else 0.0
                    e = x[i] - pos
                    de = x[3 + i] - vel
                    s = -de - integral[i]
                    ds = (s - prev_s[i]) / dt if step > 0 else 0.0
                    smooth = (((ref_acc - dr[i]) - c1 * e) - c2 * de) + k_r * s
                    u[i] = smooth + ku * fuzzy(ke * s, kec * ds, fire, active)
                    # the law's memory over the period (forward Euler), after the command
                    prev_s[i] = s
                    integral[i] = integral[i] + (c1 * e + c2 * de) * dt
                # the command noise, drawn for the period from the case's stream
                uniforms3(step, c, uni)
                for i in range(3):
                    d[i] = noise * uni[i] * u[i]
                # RK4, the command and the noise held; landing's weighted sum
                rhs(x, u, d, dr, kd, False)
                for j in range(6):
                    acc[j] = kd[j]
                    y[j] = fma(kd[j], 0.5 * dt, x[j])
                rhs(y, u, d, dr, kd, True)
                for j in range(6):
                    acc[j] = fma(kd[j], 2.0, acc[j])
                    y[j] = fma(kd[j], 0.5 * dt, x[j])
                rhs(y, u, d, dr, kd, True)
                for j in range(6):
                    acc[j] = fma(kd[j], 2.0, acc[j])
                    y[j] = fma(kd[j], 1.0 * dt, x[j])
                rhs(y, u, d, dr, kd, True)
                for j in range(6):
                    acc[j] += kd[j]
                    x[j] = fma(acc[j], dt / 6.0, x[j])
            out[c] = x
        return out

    return numba, run


# --- measuring -----------------------------------------------------------------------------------


def agreement(final: np.ndarray, reference: np.ndarray) -> tuple[float, float]:
    """Largest |x - x_ref| / max(|x_ref|, 1) over all final states, and the share of the
    final-state components that agree bit for bit."""
    err = float(np.max(np.abs(final - reference) / np.maximum(np.abs(reference), 1.0)))
    return err, float(np.mean(final == reference))


WORKLOADS = ("W3", "W5")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--cases", type=int, default=300)
    ap.add_argument("--repeat", type=int, default=5, help="timed runs per row (best and median of these)")
    json_option(ap)
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
    write_json(args.json, {"cases": args.cases, "rows": [
        {"workload": w, "implementation": impl, "threads": n,
         "best_ns": stats(i)[0] * 1e9 / (args.cases * specs[w]["steps"]),
         "median_ns": stats(i)[1] * 1e9 / (args.cases * specs[w]["steps"])}
        for i, (w, impl, n, _) in enumerate(rows)]})


if __name__ == "__main__":
    main()
