"""W1 side by side (BENCHMARKS.md): landing against the peers a user would write instead, same
workload, same machine, same thread counts, one run.

W1: seed-001 fixed-time multiple-sliding-surface guidance, eq. 25 as printed (variant "printed"),
gains beta1 0.8, beta2 0.4, q1 0.95, q2 1.05, alpha1 0.9, alpha2 0.5, gamma1 0.9, gamma2 1.1, on
300 Table II dispersed Mars cases, 10 s at dt = 1 ms, RK4 with the thrust held over each control
period, drag (k_d 0.699, h_d 0.0009, areas 6, 7.5, 8.7 m^2), mass depletion (Isp 225 s, g0
9.807), Mars gravity 3.7114, 50 kN per axis, a_p = 20 sin t on every axis at each RK4 stage's
time, final states only.

The peers:

- landing itself with the AVX2 kernel forced (``simulate_batch(..., kernel="avx2")``, one thread),
  where the CPU has AVX2: the level a CPU without AVX-512 runs.
- numpy, vectorised over cases (one thread); it is the accuracy reference.
- numba, one case per ``prange`` iteration, written two ways: the law as printed, seven
  ``abs(x)**a`` per axis, and with the powers shared as landing shares them (one ``log`` and two
  ``exp`` per sliding variable; the other powers of |s1| as products and quotients of those).
- JAX in float64, ``vmap`` over cases, ``lax.fori_loop`` over steps, ``jit``, powers shared the
  same way, sgn(0) = 0 through ``where``, the drag exponential once per stage. XLA's CPU threads
  are fixed when the process starts, so every JAX row runs in a child interpreter of its own,
  pinned with ``os.sched_setaffinity`` to as many cores as the row's thread count (one thread:
  also ``XLA_FLAGS=--xla_cpu_multi_thread_eigen=false``). vmap alone does not spread the cases
  over cores, so a second JAX row at two or more threads shards the cases over that many XLA
  CPU devices (``--xla_force_host_platform_device_count``), as a JAX user after more cores would.

Every implementation must agree with numpy to a relative 1e-9 on every final state before any
time is taken. Compilation (numba, XLA) is excluded: every row runs once untimed first. The
timed runs go round-robin over the rows (a different row first in each round), and the table
gives the best and the median of --repeat runs, ns per case-step and ratios against landing on
one thread and on the same thread count. CPU/wall is the process's CPU time (all its threads)
over the wall time of a run: it shows whether a row used the cores it was given.

    pip install -r benches/requirements.txt   # numba, jax (CPU)
    python benches/peers_w1.py [--cases 300] [--repeat 5] [--threads 1 2] [--only landing,jax] [--json FILE]
"""

from __future__ import annotations

import argparse
import datetime
import json
import os
import platform
import shlex
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np
from _harness import json_option, machine, version, write_json

G_MARS, G0, ISP, KD, HD, FMAX = 3.7114, 9.807, 225.0, 0.699, 0.0009, 50_000.0
AREA = np.array([6.0, 7.5, 8.7])
B1, B2, Q1, Q2, A1, A2, G1, G2 = 0.8, 0.4, 0.95, 1.05, 0.9, 0.5, 0.9, 1.1
T_FINAL, DT = 10.0, 1e-3
STEPS = int(round(T_FINAL / DT))
TOLERANCE = 1e-9  # largest relative difference from the numpy peer on any final state
IMPLEMENTATIONS = ("landing", "landing-avx2", "numpy", "numba-printed", "numba-shared", "jax", "jax-sharded")


def initial_states(n: int) -> np.ndarray:
    import landing

    mean = landing.scenarios.MARS_NOMINAL_STATE
    sd = np.array([100, 100, 100, 10, 10, 10, 20.0])
    return landing.dispersions.Normal(mean=mean, std=sd).sample(n, seed=2024)


def run_landing(x0: np.ndarray, threads: int | None, kernel: str | None = None) -> np.ndarray:
    import landing

    law = landing.controllers.FixedTimeMSS(beta1=B1, beta2=B2, q1=Q1, q2=Q2, alpha1=A1, alpha2=A2, gamma1=G1,
                                           gamma2=G2)
    res = landing.simulate_batch(landing.plants.MarsLander(thrust_limit=FMAX), law, x0, t_final=T_FINAL, dt=DT,
                                 disturbance=landing.disturbances.Sinusoid(amplitude=20.0, omega=1.0),
                                 record_every=0, threads=threads, kernel=kernel)
    return res.final_state


# --- numpy: all cases at once (the accuracy reference) --------------------------------------


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
    """Two numba peers that differ only in the law: as printed (seven abs(x)**a per axis) and
    with the powers shared (one log and two exp per sliding variable and axis)."""
    import numba

    @numba.njit(inline="always")
    def sig(x, a):
        return 0.0 if x == 0.0 else np.sign(x) * abs(x) ** a

    @numba.njit(inline="always")
    def command_printed(r, v, m, e, i):
        drift = -KD * v * abs(v) * e / (AREA[i] * m) - (G_MARS if i == 2 else 0.0)
        s2 = v + B1 * sig(r, Q1) + B2 * sig(r, Q2)
        a = (-drift + B1 * B1 * Q1 * sig(r, 2 * Q1 - 1) + B2 * B2 * Q2 * sig(r, 2 * Q2 - 1)
             + B1 * B2 * (Q1 + Q2) * sig(r, Q1 + Q2 - 1) - A1 * sig(s2, G1) - A2 * sig(s2, G2))
        return min(max(m * a, -FMAX), FMAX)

    @numba.njit(inline="always")
    def command_shared(r, v, m, e, i):
        drift = -KD * v * abs(v) * e / (AREA[i] * m) - (G_MARS if i == 2 else 0.0)
        # |s1|^q1, |s1|^q2 from one log; |s1|^(2q1-1), |s1|^(2q2-1), |s1|^(q1+q2-1) from those.
        a1 = abs(r)
        if a1 == 0.0:
            u1 = u2 = 0.0
            w = 0.0
        else:
            l1 = np.log(a1)
            sg1 = 1.0 if r > 0.0 else -1.0
            p1, p2 = np.exp(Q1 * l1), np.exp(Q2 * l1)
            u1, u2 = sg1 * p1, sg1 * p2
            inv = 1.0 / a1
            w = (B1 * B1 * Q1 * u1 * p1 + B2 * B2 * Q2 * u2 * p2 + B1 * B2 * (Q1 + Q2) * u1 * p2) * inv
        s2 = v + B1 * u1 + B2 * u2
        a2 = abs(s2)
        if a2 == 0.0:
            z = 0.0
        else:
            l2 = np.log(a2)
            z = (1.0 if s2 > 0.0 else -1.0) * (A1 * np.exp(G1 * l2) + A2 * np.exp(G2 * l2))
        a = -drift + w - z
        return min(max(m * a, -FMAX), FMAX)

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

    def make_run(command):
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
                        f[i] = command(x[i], x[3 + i], m, e, i)
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

        return run

    return numba, make_run(command_printed), make_run(command_shared)


# --- JAX: vmap over cases, fori_loop over steps, jit -----------------------------------------


def make_jax():
    import jax
    import jax.numpy as jnp
    from jax import lax

    jax.config.update("jax_enable_x64", True)
    area = jnp.asarray(AREA)
    gravity = jnp.asarray([0.0, 0.0, G_MARS])

    def signed_powers(s, p, q):
        """sgn(s)|s|^p and sgn(s)|s|^q from one log and two exps, with sgn(0) = 0; also 1/|s|
        (1 where s = 0, where every term it multiplies is 0)."""
        a = jnp.abs(s)
        nonzero = a > 0.0
        safe = jnp.where(nonzero, a, 1.0)
        ln = jnp.log(safe)
        sg = jnp.where(nonzero, jnp.where(s > 0.0, 1.0, -1.0), 0.0)
        return sg * jnp.exp(p * ln), sg * jnp.exp(q * ln), 1.0 / safe

    def command(r, v, m):
        drift = -KD * v * jnp.abs(v) * jnp.exp(-HD * r[2]) / (area * m) - gravity
        u1, u2, inv = signed_powers(r, Q1, Q2)  # sgn(r)|r|^q1, sgn(r)|r|^q2
        s2 = v + B1 * u1 + B2 * u2
        w1, w2, _ = signed_powers(s2, G1, G2)
        # sgn(r)|r|^(2q1-1) = u1 |r|^q1 / |r|, and so on; sgn(r)|r|^q = |u|.
        p1, p2 = jnp.abs(u1), jnp.abs(u2)
        a = (-drift + (B1 * B1 * Q1 * u1 * p1 + B2 * B2 * Q2 * u2 * p2 + B1 * B2 * (Q1 + Q2) * u1 * p2) * inv
             - A1 * w1 - A2 * w2)
        return jnp.clip(m * a, -FMAX, FMAX)

    def deriv(t, r, v, m, f, mdot):
        e = jnp.exp(-HD * r[2])  # once per stage, shared by the three axes
        return v, f / m - KD * v * jnp.abs(v) * e / (area * m) + 20.0 * jnp.sin(t) - gravity, mdot

    def step(k, x):
        r, v, m = x
        t = k * DT
        f = command(r, v, m)
        mdot = -jnp.sqrt(jnp.sum(f * f)) / (ISP * G0)  # the thrust is held over the period
        k1 = deriv(t, r, v, m, f, mdot)
        k2 = deriv(t + DT / 2, *(xi + DT / 2 * ki for xi, ki in zip(x, k1)), f, mdot)
        k3 = deriv(t + DT / 2, *(xi + DT / 2 * ki for xi, ki in zip(x, k2)), f, mdot)
        k4 = deriv(t + DT, *(xi + DT * ki for xi, ki in zip(x, k3)), f, mdot)
        return tuple(xi + DT / 6 * (a + 2 * b + 2 * c + d) for xi, a, b, c, d in zip(x, k1, k2, k3, k4))

    def simulate(x0):
        r, v, m = lax.fori_loop(0, STEPS, step, (x0[:3], x0[3:6], x0[6]))
        return jnp.concatenate([r, v, m[None]])

    return jax, jax.vmap(simulate)


# --- measuring ---------------------------------------------------------------------------------


def measure(fn) -> dict:
    """Wall time and CPU time of this process (all its threads, ended ones included) over one run."""
    c0, t0 = time.process_time(), time.perf_counter()
    fn()
    return {"wall": time.perf_counter() - t0, "cpu": time.process_time() - c0}


def jax_child(mode: str, threads: int, x0_path: str, out_path: str) -> None:
    """One JAX row in a fresh interpreter: pin, compile, write the final states, then time one
    run for each 'run' line on stdin, answering with one JSON line."""
    cores = sorted(os.sched_getaffinity(0))[:threads]
    os.sched_setaffinity(0, cores)
    jax, batched = make_jax()
    import jaxlib

    x0 = np.load(x0_path)
    if mode == "jax-sharded":
        from jax.sharding import Mesh, NamedSharding, PartitionSpec

        sharding = NamedSharding(Mesh(np.array(jax.devices()), ("cases",)), PartitionSpec("cases", None))
        fn = jax.jit(batched, in_shardings=sharding, out_shardings=sharding)
        x = jax.device_put(x0, sharding)
    else:
        fn = jax.jit(batched)
        x = jax.device_put(x0)
    t0 = time.perf_counter()
    compiled = fn.lower(x).compile()
    compile_s = time.perf_counter() - t0
    first = measure(lambda: np.save(out_path, np.asarray(compiled(x))))
    ready = {"compile_s": compile_s, "first_run_s": first["wall"], "devices": len(jax.devices()),
             "affinity": sorted(os.sched_getaffinity(0)), "threads_in_process": len(os.listdir("/proc/self/task")),
             "xla_flags": os.environ.get("XLA_FLAGS", ""), "jax": jax.__version__, "jaxlib": jaxlib.__version__}
    print("@@" + json.dumps(ready), flush=True)
    for line in sys.stdin:
        if line.strip() != "run":
            break
        print("@@" + json.dumps(measure(lambda: np.asarray(compiled(x)))), flush=True)


class JaxRow:
    """The parent's end of a JAX child: idle (blocked on stdin) while the other rows run."""

    def __init__(self, mode: str, threads: int, x0_path: str, out_path: str):
        # XLA sizes its CPU thread pools from the affinity mask the child sets before importing
        # jax. intra_op_parallelism_threads, often seen beside the eigen flag, is a TensorFlow
        # setting: XLA_FLAGS ignores a bare word after a --flag, so it is left out.
        flags = [f for f in os.environ.get("XLA_FLAGS", "").split() if f]
        if threads == 1:
            flags.append("--xla_cpu_multi_thread_eigen=false")
        if mode == "jax-sharded":
            flags.append(f"--xla_force_host_platform_device_count={threads}")
        env = dict(os.environ, XLA_FLAGS=" ".join(flags), JAX_PLATFORMS="cpu")
        cmd = [sys.executable, os.path.abspath(__file__), "--jax-child", mode, "--threads", str(threads),
               "--x0", x0_path, "--out", out_path]
        self.proc = subprocess.Popen(cmd, stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True, env=env)
        self.ready = self._answer()
        self.final_state = np.load(out_path)

    def _answer(self) -> dict:
        for line in self.proc.stdout:
            if line.startswith("@@"):
                return json.loads(line[2:])
        raise RuntimeError(f"JAX child exited with {self.proc.wait()}")

    def cpu_ticks(self) -> int:
        with open(f"/proc/{self.proc.pid}/stat") as fh:
            fields = fh.read().rsplit(")", 1)[1].split()
        return int(fields[11]) + int(fields[12])

    def __call__(self) -> dict:
        self.proc.stdin.write("run\n")
        self.proc.stdin.flush()
        return self._answer()

    def close(self) -> None:
        self.proc.stdin.close()
        self.proc.wait()


def threads_label(n: int) -> str:
    return f"{n} thread{'s' if n != 1 else ''}"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--cases", type=int, default=300)
    ap.add_argument("--repeat", type=int, default=5, help="timed runs per row (best and median of these)")
    ap.add_argument("--threads", type=int, nargs="+", default=None,
                    help="thread counts for the threaded rows (default: 1 and the number of cores)")
    ap.add_argument("--only", default=",".join(IMPLEMENTATIONS),
                    help="comma-separated subset of " + ",".join(IMPLEMENTATIONS))
    json_option(ap)
    ap.add_argument("--jax-child", choices=("jax", "jax-sharded"), help=argparse.SUPPRESS)
    ap.add_argument("--x0", help=argparse.SUPPRESS)
    ap.add_argument("--out", help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.jax_child:
        jax_child(args.jax_child, args.threads[0], args.x0, args.out)
        return

    cores = len(os.sched_getaffinity(0))
    thread_counts = args.threads or sorted({1, cores})
    only = [s.strip() for s in args.only.split(",") if s.strip()]
    unknown = set(only) - set(IMPLEMENTATIONS)
    if unknown:
        ap.error(f"unknown implementation(s) {sorted(unknown)}; choose from {','.join(IMPLEMENTATIONS)}")
    steps = args.cases * STEPS
    x0 = initial_states(args.cases)

    print(f"W1 peers, {datetime.datetime.now().astimezone().isoformat(timespec='seconds')}")
    print(f"command: {shlex.join([os.path.basename(sys.executable)] + sys.argv)}")
    print(f"machine: {machine()}")
    print(f"python {platform.python_version()}, landing {version('landing')}, numpy {np.__version__}, "
          f"numba {version('numba')}, jax {version('jax')}, jaxlib {version('jaxlib')}")
    print(f"W1: {args.cases} cases x {STEPS} steps = {steps:.3g} case-steps per run; thread counts {thread_counts}")

    # Rows: (label, implementation, threads, callable returning a measurement).
    rows = []
    finals = {}
    notes = []
    t0 = time.perf_counter()
    reference = run_numpy(x0)
    notes.append(f"numpy reference run: {time.perf_counter() - t0:.2f} s")
    if "numpy" in only:
        rows.append(("numpy (vectorised over cases)", "numpy", 1, lambda: measure(lambda: run_numpy(x0))))
    if "landing" in only:
        finals["landing"] = run_landing(x0, None)
        for n in thread_counts:
            rows.append(("landing (simulate_batch)", "landing", n, lambda n=n: measure(lambda: run_landing(x0, n))))
    if "landing-avx2" in only:
        import landing

        if "avx2" in landing.kernel_levels():
            finals["landing-avx2"] = run_landing(x0, 1, "avx2")
            rows.append(("landing, AVX2 kernel forced", "landing-avx2", 1,
                         lambda: measure(lambda: run_landing(x0, 1, "avx2"))))
        else:
            notes.append("landing-avx2: skipped, this CPU has no AVX2")
    numba = None
    for key in ("numba-printed", "numba-shared"):
        if key in only:
            if numba is None:
                numba, run_printed, run_shared = make_numba()
            fn = run_printed if key == "numba-printed" else run_shared
            t0 = time.perf_counter()
            finals[key] = fn(x0)  # compiles this variant on its first call
            notes.append(f"{key}: first call (compilation and one run) {time.perf_counter() - t0:.2f} s")

            def numba_row(fn=fn, n=1, numba=numba):
                numba.set_num_threads(n)
                return measure(lambda: fn(x0))

            label = ("numba, law as printed (7 abs(x)**a per axis)" if key == "numba-printed"
                     else "numba, powers shared (1 log + 2 exp per variable)")
            for n in thread_counts:
                rows.append((label, key, n, lambda fn=fn, n=n: numba_row(fn, n)))
    if numba is not None:
        notes.append(f"numba threading layer: {numba.threading_layer()}")

    children = []
    with tempfile.TemporaryDirectory() as tmp:
        x0_path = os.path.join(tmp, "x0.npy")
        np.save(x0_path, x0)
        for key in ("jax", "jax-sharded"):
            if key not in only:
                continue
            for n in thread_counts:
                if key == "jax-sharded" and n == 1:
                    continue  # one device: the same as the jax row
                if key == "jax-sharded" and args.cases % n:
                    notes.append(f"jax-sharded, {n} threads: skipped, {args.cases} cases do not split over {n} devices")
                    continue
                child = JaxRow(key, n, x0_path, os.path.join(tmp, f"{key}-{n}.npy"))
                children.append(child)
                finals[f"{key}, {threads_label(n)}"] = child.final_state
                r = child.ready
                notes.append(f"{key}, {threads_label(n)}: lower + compile {r['compile_s']:.2f} s, first run "
                             f"{r['first_run_s']:.3f} s; cores {r['affinity']}, {r['devices']} XLA device(s), "
                             f"{r['threads_in_process']} threads in the process, XLA_FLAGS='{r['xla_flags']}'")
                label = ("JAX, vmap + fori_loop + jit" if key == "jax"
                         else f"JAX, cases sharded over {n} CPU devices")
                rows.append((label, key, n, child))

        # Agreement before any timing.
        print("\nAgreement with the numpy peer (largest |x - x_numpy| / max(|x_numpy|, 1) over all final states):")
        failed = False
        for name, final in finals.items():
            err = float(np.max(np.abs(final - reference) / np.maximum(np.abs(reference), 1.0)))
            ok = err < TOLERANCE and np.isfinite(final).all()
            failed |= not ok
            print(f"  {name:<28} {err:.1e}{'' if ok else f'  DISAGREES (tolerance {TOLERANCE:g})'}")
        if failed:
            for child in children:
                child.close()
            sys.exit("an implementation disagrees with the numpy peer; no timings taken")

        # One untimed run of every row (compilation, thread pools), then round-robin timing.
        for _, key, _, fn in rows:
            if key != "numpy":  # the reference run above warmed numpy
                fn()
        child_ticks = {id(c): c.cpu_ticks() for c in children}
        results = {i: [] for i in range(len(rows))}
        for rnd in range(args.repeat):
            order = list(range(len(rows)))
            order = order[rnd % len(order):] + order[:rnd % len(order)]
            for i in order:
                results[i].append(rows[i][3]())
        hz = os.sysconf("SC_CLK_TCK")
        for child in children:
            own = sum(m["cpu"] for i, m_list in results.items() if rows[i][3] is child for m in m_list)
            idle = (child.cpu_ticks() - child_ticks[id(child)]) / hz - own
            notes.append(f"JAX child {child.proc.pid}: CPU outside its own timed runs {idle:+.2f} s "
                         f"(clock-tick resolution)")
            child.close()

    def stats(i):
        walls = [m["wall"] for m in results[i]]
        return min(walls), statistics.median(walls)

    def ratio(a, b):
        return f"{a / b:.2f}x" if b else "-"

    base_best, base_med = None, None
    same = {}
    for i, (_label, key, n, _) in enumerate(rows):
        if key == "landing":
            same[n] = stats(i)
            if n == 1:
                base_best, base_med = stats(i)

    print(f"\nW1, {args.repeat} timed runs per row, round-robin; ns/cs = ns per case-step; /landing = this row's "
          f"time over landing's (on 1 thread, or on the same thread count); CPU/wall = median over the runs")
    head = (f"| {'implementation':<50} | {'thr':>3} | {'best s':>7} | {'median s':>8} | {'ns/cs best':>10} | "
            f"{'ns/cs med':>9} | {'/landing 1t, best':>17} | {'/landing 1t, med':>16} | {'/landing same thr, med':>22} | "
            f"{'CPU/wall':>8} |")
    print(head)
    print("|" + "|".join("-" * (len(c)) for c in head.split("|")[1:-1]) + "|")
    for i, (label, _key, n, _) in sorted(enumerate(rows), key=lambda r: (r[1][2], IMPLEMENTATIONS.index(r[1][1]))):
        best, med = stats(i)
        same_med = same.get(n, (None, None))[1]
        cpu = statistics.median(m["cpu"] / m["wall"] for m in results[i])
        print(f"| {label:<50} | {n:>3} | {best:7.3f} | {med:8.3f} | {best * 1e9 / steps:10.1f} | "
              f"{med * 1e9 / steps:9.1f} | {ratio(best, base_best):>17} | {ratio(med, base_med):>16} | "
              f"{ratio(med, same_med):>22} | {cpu:8.2f} |")
    print("\nEvery timed run, in the order of the rounds (wall s, CPU/wall; a multi-threaded row far below its")
    print("thread count in CPU/wall had cores taken by other load on the machine):")
    for i, (_label, key, n, _) in enumerate(rows):
        runs = "  ".join(f"{m['wall']:.3f} {m['cpu'] / m['wall']:.2f}" for m in results[i])
        print(f"  {key + ', ' + threads_label(n):<26} {runs}")
    print("\nNotes:")
    for note in notes:
        print(f"  {note}")
    write_json(args.json, {"cases": args.cases, "steps": STEPS, "rows": [
        {"implementation": key, "threads": n, "best_ns": stats(i)[0] * 1e9 / steps,
         "median_ns": stats(i)[1] * 1e9 / steps} for i, (_label, key, n, _) in enumerate(rows)]})


if __name__ == "__main__":
    main()
