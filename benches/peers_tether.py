"""W6 side by side (BENCHMARKS.md): landing against the numba peer a GNC user would write instead,
same workload, same starts, same machine, same thread counts, one run.

W6: the tethered-satellite paper's FNTSMC (fixed-time nonsingular terminal sliding mode with
RBF compensation, eq. 19-24) on the flexible tethered satellite (docs/parameters.md), the
``tether_fntsmc_flexible`` preset's law and plant:

- the plant: the main satellite (1000 kg) at the origin of the Hill frame of a 500 km circular
  Earth orbit (n = sqrt(mu / (R + h)^3), WGS 84), the tether (L0 = 100 m, 1.9e-4 kg/m, EA 1e4 N,
  Kelvin-Voigt damping 5 N s) as 8 lumped nodes joined by 9 tension-only spring-dampers, the
  10 kg cube sub-satellite (side 1 m, attached a/2 from its centre) pulled at its attachment
  point; Clohessy-Wiltshire gravity gradient and Coriolis terms on every point mass; the state
  ``[xs, ys, theta, vxs, vys, omega]`` then ``[x, y, vx, vy]`` per node, 38 components. The
  thrust (limit 0.1 N) acts on the cube's centre perpendicular to the main-to-centre line, the
  torque (limit 0.05 N m) on its attitude;
- the law, per axis of q = (phi, theta): s = e2 + k1 zeta1(e1) + k2 zeta2(e1) with zeta_k =
  sig^pk outside sigma_phi and the matching quadratic inside; the command
  u = -(k1 zeta1' + k2 zeta2' + k3 (sig^as(s) + sig^bs(s))) - (W^T Phi(z) + eps_max sgn(s)) / M,
  M = (mu L0, m_s a^2 / 6), saturated as thrust and torque; W' = gamma Phi N,
  N = k3 (sig^(2as - 1)(s) + sig^(2bs - 1)(s)) / M, advanced by forward Euler after the
  command; Phi the 5 x 5 Gaussian grid on (e1 / scale_e1, e2 / scale_e2) with width b. Table 2's
  gains: k1 (0.08, 0.6), k2 (0.08, 0.5), k3 (0.09, 0.8), eps_max 1e-4, p1 1.1, p2 (0.99, 0.6),
  as (0.89, 0.7), bs (1.1, 1.8), sigma_phi (0.01, 0.001), gamma (3700, 0.48), scale_e1
  (0.12, 2) degrees, scale_e2 (0.0045, 0.00036) rad/s, b (5.9, 1.4); the reference q = 0 at rest;
- 300 starts with phi and theta uniform within +-1 degree, phi' within +-2e-4 rad/s and
  theta' within +-2e-3 rad/s (the tether laid straight and stretched by the rigid dumbbell's
  tension, ``TetheredSatellite.initial_state``); 10 s at dt = 0.01 s, 6 RK4 substeps per
  control period with the command held (the tether's fastest mode needs them), final states
  only. This is ``tether_w6`` of the core's workloads, timed by criterion in the core's
  rollout bench.

The angles and rates are drawn here once with numpy (seed 2024), turned into states by
landing's ``initial_state``, and the same array goes to both sides (the core's workload draws
its own from its counter-based streams: the numbers differ, the distribution and the work do
not). ns per case-step counts control periods, as criterion's throughput does: each is 6 RK4
steps, 24 evaluations of the 38-component derivative.

The peer is numba, one case per ``prange`` iteration, ``@njit(parallel=True, fastmath=False,
cache=False)``, written in landing's semantics (docs/guide/semantics.md): at t_k the law reads
phi = atan2(-ys, -xs), phi' = (xs vys - ys vxs) / (xs^2 + ys^2), theta and omega off the state,
its command is actuated and held over [t_k, t_k + dt), the weights are advanced, then 6 RK4
steps of dt/6 (stages at y = x + k (h/2), x + k (h/2), x + k h; landing's weighted sum
((k1 + 2 k2) + 2 k3) + k4), and every floating-point operation in landing's order
(crates/landing_core/src/plant/tether/flexible.rs: the segments two at a time with their
lengths' reciprocals from one division, the pulls added node by node in segment order; the law
in crates/landing_core/src/control/fixed_time_ntsmc.rs and rbf.rs). Where landing computes a
constant of the parameters (sigma^(p - 1) of the guard's quadratic, 1/h, 1/m), the peer computes
it once in Python with the same operations.

Accuracy. The peer calls the platform's libm for sin and cos (the cube's attitude, in every
derivative), atan2 (phi, once per period), pow (the eight powers of |e1| and |s| per period) and
exp (the ten Gaussians of each axis's network per period); landing evaluates them with its own
vectorised kernels (crates/landing_core/src/lanes/: within an ulp or so, 16 log2 x kept for the
powers, not correctly rounded, the same bits at every instruction-set level). Everything else is
IEEE-exact on both sides. The check runs in two parts, both before any timing:

1. The law, the peer's evaluated on landing's recorded states, against landing's recorded
   diagnostics (s, W^T Phi) and commands. Measured (300 starts): at t = 0 libm's atan2 gives a
   phi one ulp from landing's in 25 % of the cases (phi' is bit-equal); s differs by up to 5 ulp
   in 48 % (phi) and 61 % (theta) of the cases, and where phi is equal the differences are
   libm's pow of |e1| (e1 is outside sigma_phi at the start); the commands differ in 7-10 % of
   the cases (up to 62 ulp where not saturated, 86-91 % are), also where s is equal (libm's pow
   of |s|); at t = dt the network's output (libm's exp in Phi, pow in N) is within 1.5e-15
   relative.
2. The final states over the bench's horizon and shorter ones (CHECK_HORIZONS), with
   |x - x_landing| / max_cases |x_landing| per state component (each component against its own
   scale over the cases: the angles are 1e-2, the node positions 1e2), to show how the
   difference grows. Measured: at 1 s every case within 6.2e-15 (median 8.4e-16, 80 % of the
   components bit-equal). theta's sliding variable reaches zero between 0.08 s and 1.7 s
   (median 1.27 s) in every case, and from there the discrete-time law chatters about
   s_theta = 0 (its sign flips in about 80 % of the periods): eps_max sgn(s) and k3 sig^0.7(s),
   whose slope is infinite at 0, turn a one-ulp difference in s into a different command, and
   cases leave 1e-9 one by one: 3 at 2 s, 22 at 3 s, 41 at 5 s, 125 of 300 at 10 s, the worst
   at O(1) of their component's scale (the cube's rate omega, whose scale at 10 s is small),
   1.4e-5 absolute at most (a node's velocity, m/s), while the median case stays within 1e-13.
   landing is as sensitive to itself: with every start component moved by +-1 ulp its own
   final states move by 1.7e-4 in |x - x_landing| / max(|x_landing|, 1) at 10 s, every case
   beyond 1e-9 (already 7e-9 at 1 s: an ulp of a node's position is 4e-10 of the tether's
   tension, EA being 1e4 N for a tension of 4e-3 N).

So no relative tolerance tighter than O(1) holds for every case at 10 s, for this peer or for
landing against itself. The gates: at 1 s every component of every case within
TOLERANCE_SHORT = 1e-12 (160 times the measured 6.2e-15); at 10 s the median case within
TOLERANCE_MEDIAN = 1e-12 (measured 9.4e-14), and the largest |x - x_landing| / max(|x_landing|, 1)
(1.4e-5 measured) no larger than landing's own under +-1-ulp starts in the same run (1.7e-4):
the peer is no farther from landing than landing is from itself. landing must also agree with
itself bit for bit across thread counts.

Both sides must agree before any time is taken. Compilation is excluded: every row runs once
untimed first. The timed runs go round-robin over the rows (a different row first in each
round), and the table gives the best and the median of --repeat runs, ns per case-step, and the
ratio landing/numba at the same thread count (above 1: landing is slower). CPU/wall is the
process's CPU time (all its threads) over the wall time of a run. Every timed run starts 50 ms
after the last (SETTLE_S): numba's OpenMP workers spin after a parallel region.

    pip install -r benches/requirements.txt   # numba
    python benches/peers_tether.py [--cases 300] [--repeat 5] [--threads 1 2] [--json FILE]
"""

from __future__ import annotations

import argparse
import datetime
import math
import os
import platform
import shlex
import statistics
import sys
import time

import numpy as np
from _harness import json_option, machine, measure, numba_fma, version, write_json

# --- W6 ------------------------------------------------------------------------------------------

T_FINAL, DT, SUBSTEPS = 10.0, 0.01, 6
STEPS = int(round(T_FINAL / DT))
NODES = 8
DIM = 4 * NODES + 6
DEG = math.pi / 180.0
# the plant (the preset's and the core's defaults)
MAIN_MASS, SUB_MASS, LENGTH, SIDE, ALTITUDE = 1000.0, 10.0, 100.0, 1.0, 500e3
THRUST_LIMIT = 0.1
TORQUE_LIMIT = 0.5 * SIDE * THRUST_LIMIT  # the core's default_torque_limit
DENSITY, STIFFNESS, DAMPING = 1.9e-4, 1.0e4, 5.0
MU_EARTH, EARTH_RADIUS = 3.986_004_418e14, 6_378_137.0
# the law: Table 2 and the network of the tuning study (the preset tether_fntsmc_flexible)
GAINS = dict(
    k1=(0.08, 0.6), k2=(0.08, 0.5), k3=(0.09, 0.8), eps_max=(1e-4, 1e-4), p1=(1.1, 1.1), p2=(0.99, 0.6),
    alpha_s=(0.89, 0.7), beta_s=(1.1, 1.8), sigma_phi=(0.01, 0.001), gamma=(3700.0, 0.48),
    rbf_scale_e1=(0.12 * DEG, 2.0 * DEG), rbf_scale_e2=(0.0045, 0.00036), rbf_width=(5.9, 1.4),
)
RBF_NODES = 5
# the starts: uniform within +-1 degree, +-2e-4 rad/s (phi') and +-2e-3 rad/s (theta')
SPREAD = (1.0 * DEG, 1.0 * DEG, 2e-4, 2e-3)
SEED = 2024
# Largest relative difference |x - x_landing| / max_cases |x_landing| allowed per final-state
# component at the horizon of the timed runs (set from the measured growth, see the docstring).
TOLERANCE = 1e-9


def initial_angles(n: int, seed: int = SEED) -> np.ndarray:
    """(phi, theta, phi', theta') per case, uniform within SPREAD."""
    u = np.random.default_rng(seed).uniform(-1.0, 1.0, (n, 4))
    return u * np.array(SPREAD)


def landing_setup():
    import landing

    plant = landing.plants.TetheredSatellite(
        fidelity="flexible", main_mass=MAIN_MASS, sub_mass=SUB_MASS, tether_length=LENGTH, side=SIDE,
        orbit_altitude=ALTITUDE, thrust_limit=THRUST_LIMIT, torque_limit=None, nodes=NODES,
        tether_density=DENSITY, axial_stiffness=STIFFNESS, axial_damping=DAMPING)
    law = landing.controllers.FixedTimeNTSMC(rbf_nodes=RBF_NODES, **GAINS)
    # the peer's constants against landing's figures
    if plant.orbital_rate != orbital_rate() or not np.array_equal(np.asarray(plant.inertia), inertia()):
        raise RuntimeError(f"landing's orbital rate {plant.orbital_rate!r} or inertia {plant.inertia} differs from "
                           f"the peer's {orbital_rate()!r}, {inertia()}")
    if plant.substeps_for(DT) > SUBSTEPS:
        raise RuntimeError(f"{SUBSTEPS} substeps are too few for the tether: {plant.substeps_for(DT)}")
    return landing, plant, law


def initial_states(setup, angles: np.ndarray) -> np.ndarray:
    _, plant, _ = setup
    return np.ascontiguousarray(plant.initial_state(angles[:, 0], angles[:, 1], angles[:, 2], angles[:, 3]))


def run_landing(setup, x0: np.ndarray, threads: int | None, t_final: float = T_FINAL, record: bool = False):
    landing, plant, law = setup
    res = landing.simulate_batch(plant, law, x0, t_final=t_final, dt=DT, substeps=SUBSTEPS,
                                 record_every=1 if record else 0, threads=threads)
    return res if record else np.asarray(res.final_state)


def orbital_rate() -> float:
    r = EARTH_RADIUS + ALTITUDE
    return math.sqrt(MU_EARTH / (r * r * r))


def inertia() -> np.ndarray:
    """M = (mu L0, m_s a^2 / 6) as the core computes it (TetherBody::inertia)."""
    mu = MAIN_MASS * SUB_MASS / (MAIN_MASS + SUB_MASS)
    return np.array([mu * LENGTH, SUB_MASS * SIDE * SIDE / 6.0])


def make_numba():
    """The W6 peer: one case per prange iteration, every operation in landing's order. Returns
    (numba, run, law_check): run(x0, steps) -> the final states after `steps` control periods;
    law_check(xa, xb), for the check (see there)."""
    import numba

    fma = numba_fma()

    N = NODES
    n = orbital_rate()
    n2 = n * n
    two_n, three_n2 = 2.0 * n, 3.0 * n2
    h_seg = LENGTH / float(N + 1)
    inv_h = 1.0 / h_seg
    node_mass = DENSITY * h_seg
    inv_node = 1.0 / node_mass
    end_mass = SUB_MASS + 0.5 * node_mass
    inv_end = 1.0 / end_mass
    half = 0.5 * SIDE
    inv_js = 1.0 / (SUB_MASS * SIDE * SIDE / 6.0)
    ea, ca = STIFFNESS, DAMPING
    m_in = inertia()
    lim = np.array([THRUST_LIMIT, TORQUE_LIMIT])
    g = {k: np.array(v, dtype=float) for k, v in GAINS.items()}
    K1, K2, K3, EPS = g["k1"], g["k2"], g["k3"], g["eps_max"]
    P = np.stack([g["p1"], g["p2"]], axis=1)  # P[i, k]: exponent of zeta_k on axis i
    SIGMA = g["sigma_phi"]
    # the guard's quadratic: l_k = (2 - p) sigma^(p - 1), m_k = (p - 1) (sigma^(p - 1) / sigma)
    LK, MK = np.empty((2, 2)), np.empty((2, 2))
    for i in range(2):
        for k in range(2):
            s1 = SIGMA[i] ** (P[i, k] - 1.0)
            LK[i, k] = (2.0 - P[i, k]) * s1
            MK[i, k] = (P[i, k] - 1.0) * (s1 / SIGMA[i])
    AS, BS = g["alpha_s"], g["beta_s"]
    AS2, BS2 = 2.0 * AS - 1.0, 2.0 * BS - 1.0
    STEP_GAIN = DT * g["gamma"]  # dt gamma, then times N
    SC1, SC2 = g["rbf_scale_e1"], g["rbf_scale_e2"]
    INV_W = 1.0 / (g["rbf_width"] * g["rbf_width"])
    nb = RBF_NODES
    CENTRE = np.array([-1.0 + 2.0 * a / (nb - 1) for a in range(nb)])
    nphi = nb * nb
    h = DT / float(SUBSTEPS)
    half_h, full_h, sixth_h = 0.5 * h, 1.0 * h, h / 6.0
    substeps = SUBSTEPS

    @numba.njit(inline="always")
    def sgn(x):
        return 1.0 if x > 0.0 else (-1.0 if x < 0.0 else 0.0)

    @numba.njit(inline="always")
    def point(x, j, att):
        """Point j of the chain: 0 the main satellite, 1..N the nodes, N + 1 the attachment."""
        if j == 0:
            return 0.0, 0.0, 0.0, 0.0
        if j <= N:
            k = 6 + 4 * (j - 1)
            return x[k], x[k + 1], x[k + 2], x[k + 3]
        return att[0], att[1], att[2], att[3]

    @numba.njit(inline="always")
    def segment(x, j, att):
        px0, py0, vx0, vy0 = point(x, j, att)
        px1, py1, vx1, vy1 = point(x, j + 1, att)
        dx_, dy_ = px1 - px0, py1 - py0
        return dx_, dy_, vx1 - vx0, vy1 - vy0, np.sqrt(dx_ * dx_ + dy_ * dy_)

    @numba.njit(inline="always")
    def pull(dx_, dy_, dvx, dvy, length, inv_l):
        """The segment's force vector u T (zero when slack)."""
        if not length > h_seg:
            return 0.0, 0.0
        ux, uy = dx_ * inv_l, dy_ * inv_l
        strain = (length - h_seg) * inv_h
        rate = (ux * dvx + uy * dvy) * inv_h
        t = ea * strain + ca * rate
        t = t if t > 0.0 else 0.0
        return ux * t, uy * t

    @numba.njit(inline="always")
    def apply_pull(dx, j, fx, fy, patt):
        if j >= 1:
            i = 6 + 4 * (j - 1)
            dx[i + 2] += fx * inv_node
            dx[i + 3] += fy * inv_node
        if j < N:
            i = 6 + 4 * j
            dx[i + 2] -= fx * inv_node
            dx[i + 3] -= fy * inv_node
        else:
            patt[0] = -fx
            patt[1] = -fy

    @numba.njit(inline="always")
    def derivative(x, u0, u1, dx, att, patt):
        """x' of the chain and the sub-satellite under the held thrust u0 and torque u1."""
        sn, cs = np.sin(x[2]), np.cos(x[2])
        att[0] = x[0] + half * cs
        att[1] = x[1] + half * sn
        att[2] = x[3] - half * x[5] * sn
        att[3] = x[4] + half * x[5] * cs
        for k in range(N):
            i = 6 + 4 * k
            dx[i] = x[i + 2]
            dx[i + 1] = x[i + 3]
            dx[i + 2] = two_n * x[i + 3] + three_n2 * x[i]
            dx[i + 3] = -(two_n * x[i + 2])
        patt[0] = 0.0
        patt[1] = 0.0
        j = 0
        while j < N:
            d0x, d0y, v0x, v0y, l0 = segment(x, j, att)
            d1x, d1y, v1x, v1y, l1 = segment(x, j + 1, att)
            a0 = l0 if l0 > h_seg else 1.0
            a1 = l1 if l1 > h_seg else 1.0
            inv = 1.0 / (a0 * a1)
            f0x, f0y = pull(d0x, d0y, v0x, v0y, l0, inv * a1)
            f1x, f1y = pull(d1x, d1y, v1x, v1y, l1, inv * a0)
            apply_pull(dx, j, f0x, f0y, patt)
            apply_pull(dx, j + 1, f1x, f1y, patt)
            j += 2
        if j == N:
            d0x, d0y, v0x, v0y, l0 = segment(x, j, att)
            f0x, f0y = pull(d0x, d0y, v0x, v0y, l0, 1.0 / l0)
            apply_pull(dx, j, f0x, f0y, patt)
        rho = np.sqrt(x[0] * x[0] + x[1] * x[1])
        alx, aly = -x[1] / rho, x[0] / rho
        along = u0 + end_mass * rho * 0.0  # the generalized disturbance d is zero
        fx = patt[0] + alx * along
        fy = patt[1] + aly * along
        ax = two_n * x[4] + three_n2 * x[0]
        ay = -(two_n * x[3])
        dx[0] = x[3]
        dx[1] = x[4]
        dx[2] = x[5]
        dx[3] = ax + fx * inv_end
        dx[4] = ay + fy * inv_end
        dx[5] = ((half * cs) * patt[1] - (half * sn) * patt[0] + u1) * inv_js + 0.0

    @numba.njit(inline="always")
    def law(x, w, phi, g1, g2, out, advance):
        """The command at x under the weights w; out = (s0, s1, a0, a1, u0, u1, est0, est1): the
        surfaces, the commanded accelerations, the actuated commands and the network's outputs
        W^T Phi. Advances w when asked."""
        px, py = x[0], x[1]
        q0 = np.arctan2(-py, -px)
        dq0 = (px * x[4] - py * x[3]) / (px * px + py * py)
        for i in range(2):
            e1 = q0 - 0.0 if i == 0 else x[2] - 0.0
            e2 = dq0 - 0.0 if i == 0 else x[5] - 0.0
            a = abs(e1)
            sign = sgn(e1)
            if a > SIGMA[i]:
                pw0 = a ** P[i, 0]
                pw1 = a ** P[i, 1]
                z0, z1 = sign * pw0, sign * pw1
                sl0, sl1 = P[i, 0] * pw0 / a, P[i, 1] * pw1 / a
            else:
                z0 = LK[i, 0] * e1 + MK[i, 0] * e1 * a
                z1 = LK[i, 1] * e1 + MK[i, 1] * e1 * a
                sl0 = LK[i, 0] + 2.0 * MK[i, 0] * a
                sl1 = LK[i, 1] + 2.0 * MK[i, 1] * a
            s = e2 + K1[i] * z0 + K2[i] * z1
            rate = (K1[i] * sl0 + K2[i] * sl1) * e2
            zn0, zn1 = e1 / SC1[i], e2 / SC2[i]
            for c in range(nb):
                d1 = zn0 - CENTRE[c]
                d2 = zn1 - CENTRE[c]
                g1[c] = np.exp(-d1 * d1 * INV_W[i])
                g2[c] = np.exp(-d2 * d2 * INV_W[i])
            for c in range(nb):
                for c2 in range(nb):
                    phi[c * nb + c2] = g1[c] * g2[c2]
            sa = abs(s)
            ss = sgn(s)
            reach = K3[i] * (ss * sa ** AS[i] + ss * sa ** BS[i])
            est = 0.0
            for j in range(nphi):
                est += w[i, j] * phi[j]
            comp = est + EPS[i] * ss
            acc = (0.0 - 0.0) - ((rate + reach) + comp / m_in[i])
            v = acc * m_in[i]
            out[i] = s
            out[2 + i] = acc
            out[4 + i] = -lim[i] if v < -lim[i] else (lim[i] if v > lim[i] else v)
            out[6 + i] = est
            if advance:
                big_n = K3[i] * (ss * sa ** AS2[i] + ss * sa ** BS2[i]) / m_in[i]
                step = STEP_GAIN[i] * big_n
                for j in range(nphi):
                    w[i, j] += step * phi[j]

    @numba.njit(parallel=True, fastmath=False, cache=False)
    def run(x0, steps):
        ncase = x0.shape[0]
        out = np.empty_like(x0)
        for c in numba.prange(ncase):
            x = x0[c].copy()
            y, acc, kd = np.empty(DIM), np.empty(DIM), np.empty(DIM)
            att, patt = np.empty(4), np.empty(2)
            w, phi = np.zeros((2, nphi)), np.empty(nphi)
            g1, g2, lo = np.empty(nb), np.empty(nb), np.empty(8)
            for _period in range(steps):
                law(x, w, phi, g1, g2, lo, True)
                u0, u1 = lo[4], lo[5]
                for _ in range(substeps):
                    derivative(x, u0, u1, kd, att, patt)
                    for j in range(DIM):
                        acc[j] = kd[j]
                        y[j] = fma(kd[j], half_h, x[j])
                    derivative(y, u0, u1, kd, att, patt)
                    for j in range(DIM):
                        acc[j] = fma(kd[j], 2.0, acc[j])
                        y[j] = fma(kd[j], half_h, x[j])
                    derivative(y, u0, u1, kd, att, patt)
                    for j in range(DIM):
                        acc[j] = fma(kd[j], 2.0, acc[j])
                        y[j] = fma(kd[j], full_h, x[j])
                    derivative(y, u0, u1, kd, att, patt)
                    for j in range(DIM):
                        acc[j] += kd[j]
                        x[j] = fma(acc[j], sixth_h, x[j])
            out[c] = x
        return out

    @numba.njit
    def law_check(xa, xb):
        """Per case, the law at xa (weights zero, then advanced over the period) and at xb:
        (2, 8) rows of (s0, s1, a0, a1, u0, u1, est0, est1)."""
        ncase = xa.shape[0]
        out = np.empty((ncase, 2, 8))
        phi = np.empty(nphi)
        g1, g2, lo = np.empty(nb), np.empty(nb), np.empty(8)
        for c in range(ncase):
            w = np.zeros((2, nphi))
            law(xa[c], w, phi, g1, g2, lo, True)
            out[c, 0] = lo
            law(xb[c], w, phi, g1, g2, lo, False)
            out[c, 1] = lo
        return out

    return numba, run, law_check


# --- accuracy ------------------------------------------------------------------------------------

# The horizons of the growth table (s); the first is the strict check's.
CHECK_HORIZONS = (1.0, 2.0, 3.0, 5.0, 10.0)
# At CHECK_HORIZONS[0], before the chattering has carried any difference far: every component of
# every case within this of landing, relative to the component's largest magnitude over the cases.
TOLERANCE_SHORT = 1e-12
# At T_FINAL (the timed runs): the median case within TOLERANCE_MEDIAN (same measure), and the
# largest |x - x_landing| / max(|x_landing|, 1) (the W3 measure; absolute for the components
# below 1) no larger than landing's own when its starts move by one ulp (see the docstring).
TOLERANCE_MEDIAN = 1e-12


def per_component(final: np.ndarray, reference: np.ndarray) -> np.ndarray:
    """|x - x_ref| / max_cases |x_ref| per case and component (0 where the component is 0
    everywhere)."""
    scale = np.max(np.abs(reference), axis=0)
    return np.abs(final - reference) / np.where(scale > 0.0, scale, 1.0)


def w3_measure(final: np.ndarray, reference: np.ndarray) -> float:
    return float(np.max(np.abs(final - reference) / np.maximum(np.abs(reference), 1.0)))


def ulps(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Distance in units in the last place between doubles of the same sign (0 where equal)."""
    ia, ib = a.view(np.int64), b.view(np.int64)
    return np.abs(ia - ib)


def law_trace(setup, x0: np.ndarray, law_check) -> list[str]:
    """The law at t = 0 and at the first control instant after it, the peer's (libm) against
    landing's recorded diagnostics (s, W^T Phi) and commands, the difference traced to the
    operation: atan2 through phi, pow through s and the reaching law, exp through the network."""
    _, plant, _ = setup
    res = run_landing(setup, x0, 1, t_final=2 * DT, record=True)
    states = np.asarray(res.states)
    s_l = np.asarray(res.diagnostics["s"])
    est_l = np.asarray(res.diagnostics["rbf"])
    u_l = np.asarray(res.controls)
    peer = law_check(np.ascontiguousarray(states[:, 0]), np.ascontiguousarray(states[:, 1]))
    q, dq = (np.asarray(v) for v in plant.coordinates(states[:, 0]))
    lines = []
    # atan2: the core's phi against libm's on the same states; phi' is IEEE-exact
    phi_libm = np.arctan2(-states[:, 0, 1], -states[:, 0, 0])
    dq_mine = (states[:, 0, 0] * states[:, 0, 4] - states[:, 0, 1] * states[:, 0, 3]) / (
        states[:, 0, 0] ** 2 + states[:, 0, 1] ** 2)
    d_atan = ulps(phi_libm, q[:, 0])
    lines.append(f"t = 0, atan2: libm's phi differs from landing's in {np.mean(d_atan > 0):.1%} of the cases "
                 f"(at most {d_atan.max()} ulp); phi' equal bit for bit: {np.array_equal(dq_mine, dq[:, 0])}")
    # s: the peer's at t = 0 against landing's; with landing's phi in place of libm's the
    # remaining differences are libm's pow (|e1|^p1, |e1|^p2)
    for i, name in enumerate(("phi", "theta")):
        d = ulps(peer[:, 0, i], s_l[:, 0, i])
        lines.append(f"t = 0, s_{name}: {np.mean(d > 0):.1%} of the cases differ from landing's "
                     f"(at most {d.max()} ulp)")
    same_phi = d_atan == 0
    d = ulps(peer[same_phi, 0, 0], s_l[same_phi, 0, 0])
    lines.append(f"  of the {same_phi.sum()} cases where libm's phi is landing's, s_phi differs in "
                 f"{np.mean(d > 0):.1%} (libm's pow; e1 is outside sigma_phi there)")
    # the command at t = 0: the reaching law's pow of |s| and eps_max sgn(s); W^T Phi = 0
    same_s = (peer[:, 0, 0] == s_l[:, 0, 0]) & (peer[:, 0, 1] == s_l[:, 0, 1])
    for i, name in enumerate(("thrust", "torque")):
        d = ulps(peer[:, 0, 4 + i], u_l[:, 0, i])
        d_same = ulps(peer[same_s, 0, 4 + i], u_l[same_s, 0, i])
        sat = np.mean(np.abs(u_l[:, 0, i]) >= (THRUST_LIMIT, TORQUE_LIMIT)[i])
        lines.append(f"t = 0, {name}: {np.mean(d > 0):.1%} of the cases differ (at most {d.max()} ulp; "
                     f"{np.mean(d_same > 0):.1%} of those with s equal: libm's pow of |s|; {sat:.0%} saturated)")
    # the network's output at t = dt under the weights of the first period (exp, and the pow of
    # the adaptation's N), on landing's state at t = dt
    for i, name in enumerate(("phi", "theta")):
        d = np.abs(peer[:, 1, 6 + i] - est_l[:, 1, i]) / np.maximum(np.abs(est_l[:, 1, i]), 1e-300)
        share = np.mean(peer[:, 1, 6 + i] != est_l[:, 1, i])
        lines.append(f"t = dt, W^T Phi on {name}: {share:.1%} of the cases differ, at most {d.max():.1e} relative "
                     f"(libm's exp in Phi and pow in N)")
    return lines


# --- measuring -----------------------------------------------------------------------------------


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--cases", type=int, default=300)
    ap.add_argument("--repeat", type=int, default=5, help="timed runs per row (best and median of these)")
    json_option(ap)
    ap.add_argument("--threads", type=int, nargs="+", default=None,
                    help="thread counts (default: 1 and the number of cores)")
    args = ap.parse_args()

    cores = len(os.sched_getaffinity(0))
    thread_counts = args.threads or sorted({1, cores})

    print(f"W6 peers, {datetime.datetime.now().astimezone().isoformat(timespec='seconds')}")
    print(f"command: {shlex.join([os.path.basename(sys.executable)] + sys.argv)}")
    print(f"machine: {machine()}")
    print(f"python {platform.python_version()}, landing {version('landing')}, numpy {np.__version__}, "
          f"numba {version('numba')}, llvmlite {version('llvmlite')}")

    notes = []
    setup = landing_setup()
    x0 = initial_states(setup, initial_angles(args.cases))
    t0 = time.perf_counter()
    numba, run, law_check = make_numba()
    first = run(x0, STEPS)  # compiles on the first call
    notes.append(f"numba: first call (compilation and one run) {time.perf_counter() - t0:.2f} s")
    t0 = time.perf_counter()
    law_check(x0[:1], x0[:1])
    notes.append(f"numba: the law's check compiled in {time.perf_counter() - t0:.2f} s")
    notes.append(f"numba threading layer: {numba.threading_layer()}")
    print(f"W6: {args.cases} cases x {STEPS} steps = {args.cases * STEPS:.3g} case-steps per run "
          f"({SUBSTEPS} RK4 substeps each); thread counts {thread_counts}")

    # Agreement before any timing.
    print("\nAgreement of the law (the peer on landing's recorded states against landing's diagnostics):")
    for line in law_trace(setup, x0, law_check):
        print(f"  {line}")
    print("\nAgreement of the final states (per component: |x - x_landing| / max_cases |x_landing|; "
          "W3 measure: / max(|x_landing|, 1)):")
    print(f"  {'horizon':>7} | {'worst case':>10} | {'median case':>11} | {'cases > 1e-9':>12} | "
          f"{'bit-equal':>9} | {'W3 measure':>10} | {'landing, x0 +- 1 ulp':>20} | worst component (absolute)")
    failed = False
    names = setup[1].state_names
    ulp_rng = np.random.default_rng(SEED + 1)
    x0_ulp = np.nextafter(x0, ulp_rng.choice([-np.inf, np.inf], size=x0.shape))
    for horizon in CHECK_HORIZONS:
        steps = int(round(horizon / DT))
        reference = run_landing(setup, x0, thread_counts[0], t_final=horizon)
        final = first if steps == STEPS else run(x0, steps)
        per_case = per_component(final, reference).max(axis=1)
        diff = np.abs(final - reference)
        worst = np.unravel_index(np.argmax(diff / np.maximum(np.abs(reference), 1.0)), diff.shape)
        own = w3_measure(run_landing(setup, x0_ulp, thread_counts[0], t_final=horizon), reference)
        print(f"  {horizon:6.1f}s | {per_case.max():10.1e} | {np.median(per_case):11.1e} | "
              f"{np.sum(per_case > 1e-9):12d} | {np.mean(final == reference):9.1%} | "
              f"{w3_measure(final, reference):10.1e} | {own:20.1e} | {names[worst[1]]} ({diff[worst]:.1e})")
        if not np.isfinite(final).all():
            failed = True
            print(f"  numba's final states at {horizon} s are not all finite  DISAGREES")
        if horizon == CHECK_HORIZONS[0] and per_case.max() > TOLERANCE_SHORT:
            failed = True
            print(f"  worst case at {horizon} s beyond {TOLERANCE_SHORT:g}  DISAGREES")
        if steps == STEPS:
            if np.median(per_case) > TOLERANCE_MEDIAN or w3_measure(final, reference) > own:
                failed = True
                print(f"  median case beyond {TOLERANCE_MEDIAN:g}, or W3 measure beyond landing's own under "
                      f"1-ulp starts  DISAGREES")
            finals = {n: run_landing(setup, x0, n) for n in thread_counts}
            for n, f in finals.items():
                if not np.array_equal(f, finals[thread_counts[0]]):
                    failed = True
                    print(f"  landing, {n} threads: differs from {thread_counts[0]} thread(s)  DISAGREES")
    print(f"  tolerances: {TOLERANCE_SHORT:g} on the worst case at {CHECK_HORIZONS[0]:g} s; at {T_FINAL:g} s "
          f"{TOLERANCE_MEDIAN:g} on the median case and, in the W3 measure, no more than landing's own distance "
          f"from itself under starts moved by +-1 ulp (the chattering of theta's sliding mode, see the "
          f"docstring); landing bit for bit across thread counts")
    if failed:
        sys.exit("the peer disagrees with landing; no timings taken")

    rows = []  # (implementation, threads, callable returning a measurement)
    for n in thread_counts:
        rows.append(("landing", n, lambda n=n: measure(lambda: run_landing(setup, x0, n))))

        def numba_row(n=n):
            numba.set_num_threads(n)
            return measure(lambda: run(x0, STEPS))

        rows.append(("numba", n, numba_row))

    # One untimed run of every row (thread pools, caches), then round-robin timing.
    for row in rows:
        row[2]()
    results = {i: [] for i in range(len(rows))}
    for rnd in range(args.repeat):
        order = list(range(len(rows)))
        order = order[rnd % len(order):] + order[:rnd % len(order)]
        for i in order:
            results[i].append(rows[i][2]())

    def stats(i):
        walls = [m["wall"] for m in results[i]]
        return min(walls), statistics.median(walls)

    index = {(impl, n): i for i, (impl, n, _) in enumerate(rows)}
    case_steps = args.cases * STEPS
    print(f"\n{args.repeat} timed runs per row, round-robin; ns/cs = ns per case-step (a control period, "
          f"{SUBSTEPS} RK4 steps); landing/numba = landing's time over numba's at the same thread count "
          f"(best; median); CPU/wall = median over the runs")
    head = (f"| {'workload':<8} | {'implementation':<26} | {'thr':>3} | {'best s':>7} | {'median s':>8} | "
            f"{'ns/cs best':>10} | {'ns/cs med':>9} | {'landing/numba best':>18} | {'landing/numba med':>17} | "
            f"{'CPU/wall':>8} |")
    print(head)
    print("|" + "|".join("-" * len(c) for c in head.split("|")[1:-1]) + "|")
    for n in thread_counts:
        lb, lm = stats(index[("landing", n)])
        nb, nm = stats(index[("numba", n)])
        for impl, label in (("landing", "landing (simulate_batch)"), ("numba", "numba (prange over cases)")):
            i = index[(impl, n)]
            best, med = stats(i)
            cpu = statistics.median(m["cpu"] / m["wall"] for m in results[i])
            ratio_b = f"{lb / nb:.2f}" if impl == "landing" else ""
            ratio_m = f"{lm / nm:.2f}" if impl == "landing" else ""
            print(f"| {'W6':<8} | {label:<26} | {n:>3} | {best:7.4f} | {med:8.4f} | "
                  f"{best * 1e9 / case_steps:10.1f} | {med * 1e9 / case_steps:9.1f} | {ratio_b:>18} | "
                  f"{ratio_m:>17} | {cpu:8.2f} |")
    print("\nEvery timed run, in the order of the rounds (wall s, CPU/wall; a multi-threaded row far below its")
    print("thread count in CPU/wall had cores taken by other load on the machine):")
    for i, (impl, n, _) in enumerate(rows):
        runs = "  ".join(f"{m['wall']:.4f} {m['cpu'] / m['wall']:.2f}" for m in results[i])
        print(f"  W6 {impl + ', ' + str(n) + ' thr':<16} {runs}")
    print("\nNotes:")
    for note in notes:
        print(f"  {note}")
    write_json(args.json, {"cases": args.cases, "rows": [
        {"workload": "W6", "implementation": impl, "threads": n, "best_ns": stats(i)[0] * 1e9 / case_steps,
         "median_ns": stats(i)[1] * 1e9 / case_steps} for i, (impl, n, _) in enumerate(rows)]})


if __name__ == "__main__":
    main()
