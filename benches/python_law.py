"""A law written in Python against the same law built in (BENCHMARKS.md, "Python laws").

The law: seed 001's fixed-time multiple-sliding-surface guidance, eq. 25 as printed, with the
gains of W1 (beta1 0.8, beta2 0.4, q1 0.95, q2 1.05, alpha1 0.9, alpha2 0.5, gamma1 0.9, gamma2
1.1), written in numpy over the cases as ``landing.controllers.PythonLaw``, on the Mars lander
with W1's plant (drag, mass depletion, 50 kN per axis, RK4), no disturbance, 2 s at dt = 1 ms,
final states only. Before any time is taken the Python law's final states must agree with the
built-in law's to a relative 1e-9.

Three tables:

1. The same campaign, built-in against Python, on ``--cases`` cases (10^4 by default) at each
   ``--threads``: the ratio is the cost of writing the law in Python (the law at its default
   ``cases_per_call``).
2. The same at each ``--threads`` for ``cases_per_call`` from 256 to the whole batch
   (``None``): what running a slice of cases at a time buys (``--sweep careful zeros``: for
   the careful function and the zeros law of table 4 too).
3. Where the time of the default goes, at each ``--threads``: the function alone (timed
   inside the run), the built-in open-loop law on the same cases (the plant's periods without
   a law), and the rest (the engine's round trip). On one thread the function and the open
   loop against the built-in law bound the ratio any engine could reach with this function;
   on more, the function alone does (its calls hold the interpreter, so they run one at a
   time; table 5).
4. The per-call overhead of a Python law: a law that returns zeros (``np.zeros_like(e)``), so
   that what is timed is the engine's round trip (gathering the inputs of every case, the call
   into Python, the checks of the return, handing the commands back), per control instant,
   from 10^2 to 10^5 cases, against the built-in open-loop law on the same cases, at each
   ``--threads``.
5. Whether two threads calling the function at once would run it faster than one thread
   calling it twice, outside the engine: numpy lets go of the interpreter inside its loops on
   large arrays, so the loops of two calls could overlap while each call's interpreted part
   waits its turn. The function alone on two slices' arrays (2048 and 4096 cases), the two
   calls in turn on one thread against one call on each of two threads at once: the speed-up
   a driver calling the law from both threads could at most expect.
6. What the form of the parameters costs: the careful function with its eight gains given as
   scalars, per axis ``(3,)`` and per case ``(N,)`` (the same values, so the same bits), whole
   runs at each ``--threads``; and the function alone on 4096 cases with the gains as the
   run hands them (a scalar as a view with zero strides, any other value as a contiguous
   ``(n, 3)`` array) against per-axis and per-case gains handed as views with one zero
   stride, which numpy cannot iterate as one run of values; and one multiply with a gain in
   each of these forms and as a ``(3,)`` vector, which numpy broadcasts the same way.

The timed runs go round-robin over the rows; the tables give the median of ``--repeat`` runs.

    python benches/python_law.py [--cases 10000] [--repeat 5] [--threads 1 2] [--json FILE]

``--json`` writes tables 1, 3, 4 and 6 (those that ran).
"""

from __future__ import annotations

import argparse
import datetime
import os
import platform
import statistics
import threading
import time
import types

import numpy as np
from _harness import json_option, write_json

import landing
from landing import controllers as C
from landing import plants as P

GAINS = dict(beta1=0.8, beta2=0.4, q1=0.95, q2=1.05, alpha1=0.9, alpha2=0.5, gamma1=0.9, gamma2=1.1)
NOMINAL = np.array([-2000.0, 1000.0, 1500.0, 100.0, -15.0, -75.0, 1905.0])


def mss_printed(t, e, de, ref, drift, inertia, params, memory):
    """Eq. 21-25 as printed, over the cases, the powers of |s1| shared as the core shares them."""
    b1, b2, q1, q2 = params["beta1"], params["beta2"], params["q1"], params["q2"]
    a1, a2, g1, g2 = params["alpha1"], params["alpha2"], params["gamma1"], params["gamma2"]
    abs1 = np.abs(e)
    with np.errstate(divide="ignore", invalid="ignore"):
        log1 = np.log(abs1)
        p1, p2 = np.exp(q1 * log1), np.exp(q2 * log1)
        sign1 = np.sign(e)
        s2 = de + sign1 * (b1 * p1 + b2 * p2)
        inv = 1.0 / abs1
        # 2 q1 - 1 = 0.9 >= 0: no singularity guard is needed at these gains
        cancel = np.where(abs1 > 0, sign1 * ((b1 * b1 * q1) * (p1 * p1 * inv)
                                             + (p2 * inv) * ((b2 * b2 * q2) * p2 + (b1 * b2 * (q1 + q2)) * p1)), 0.0)
        log2 = np.log(np.abs(s2))
        reach = -np.sign(s2) * (a1 * np.exp(g1 * log2) + a2 * np.exp(g2 * log2))
    return ref.acceleration - drift + (cancel + reach)


def mss_lean(t, e, de, ref, drift, inertia, params, memory):
    """``mss_printed`` as a careful numpy user writes it: the same operations in the same order
    (so the same bits), each result written into an array the function already holds (``out=``
    and in-place operators) instead of a fresh temporary."""
    b1, b2, q1, q2 = params["beta1"], params["beta2"], params["q1"], params["q2"]
    a1, a2, g1, g2 = params["alpha1"], params["alpha2"], params["gamma1"], params["gamma2"]
    abs1 = np.abs(e)
    with np.errstate(divide="ignore", invalid="ignore"):
        log1 = np.log(abs1)
        p1 = np.multiply(q1, log1)
        np.exp(p1, out=p1)
        p2 = np.multiply(q2, log1, out=log1)
        np.exp(p2, out=p2)
        sign1 = np.sign(e)
        s2 = np.multiply(b1, p1)
        s2 += np.multiply(b2, p2)
        s2 *= sign1
        s2 += de
        inv = np.divide(1.0, abs1)
        c1 = np.multiply(b1, b1)
        c1 *= q1
        t1 = np.multiply(p1, p1)
        t1 *= inv
        c1 *= t1
        c2 = np.multiply(b2, b2, out=t1)
        c2 *= q2
        c2 *= p2
        c3 = np.multiply(b1, b2)
        c3 *= np.add(q1, q2)
        c3 *= p1
        c2 += c3
        p2 *= inv
        c2 *= p2
        c1 += c2
        c1 *= sign1
        cancel = np.where(abs1 > 0, c1, 0.0)
        log2 = np.abs(s2, out=c3)
        np.log(log2, out=log2)
        r1 = np.multiply(g1, log2, out=p1)
        np.exp(r1, out=r1)
        r1 *= a1
        r2 = np.multiply(g2, log2, out=log2)
        np.exp(r2, out=r2)
        r2 *= a2
        r1 += r2
        r1 *= np.sign(s2)
    cancel -= r1
    out = np.subtract(ref.acceleration, drift, out=c2)
    out += cancel
    return out


def zeros(t, e, de, ref, drift, inertia, params, memory):
    return np.zeros_like(e)


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


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cases", type=int, default=10_000)
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--threads", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--t-final", type=float, default=2.0)
    ap.add_argument("--tables", type=int, nargs="+", default=[1, 2, 3, 4, 5, 6], help="which tables to print")
    ap.add_argument("--sweep", nargs="+", choices=["printed", "careful", "zeros"], default=["printed"],
                    help="table 2's functions (zeros: the engine's own cost)")
    json_option(ap)
    args = ap.parse_args()
    plant = P.MarsLander(thrust_limit=50_000.0)
    dt, t_final = 1e-3, args.t_final
    steps = round(t_final / dt)
    builtin = C.FixedTimeMSS(**GAINS)
    python = C.PythonLaw(mss_printed, params=GAINS)
    careful = C.PythonLaw(mss_lean, params=GAINS)
    x0 = dispersed(args.cases)
    kw = dict(t_final=t_final, dt=dt, record_every=0)

    # accuracy first
    a = landing.simulate_batch(plant, builtin, x0, **kw)
    b = landing.simulate_batch(plant, python, x0, **kw)
    err = np.max(np.abs(b.final_state - a.final_state) / np.maximum(np.abs(a.final_state), 1e-300))
    assert err < 1e-9, f"the Python law's final states differ from the built-in law's by {err:.3g}"
    c = landing.simulate_batch(plant, careful, x0, **kw)
    assert np.array_equal(c.final_state, b.final_state), "the careful numpy law gives other bits"

    print(f"# {datetime.date.today()}  {platform.processor() or platform.machine()}  "
          f"{os.cpu_count()} cores  landing {landing.__version__}  numpy {np.__version__}")
    print(f"# accuracy: max relative difference of the final states {err:.2g}")
    numbers: dict = {"cases": args.cases}
    if 1 in args.tables:
        numbers["table1"] = table1(args, plant, builtin, python, careful, x0, kw, steps)
    if 2 in args.tables:
        table2(args, plant, builtin, python, x0, kw, steps)
    if 3 in args.tables:
        numbers["table3"] = table3(args, plant, builtin, python, x0, kw, steps)
    if 4 in args.tables:
        numbers["table4"] = table4(args, plant, kw, steps)
    if 5 in args.tables:
        table5(args)
    if 6 in args.tables:
        numbers["table6"] = table6(args, plant, x0, kw, steps)
    write_json(args.json, numbers)


def table1(args, plant, builtin, python, careful, x0, kw, steps) -> list[dict]:
    t_final, dt = kw["t_final"], kw["dt"]
    print(f"\n1. fixed-time MSS, {args.cases} Mars cases, {t_final} s at dt = {dt} s ({steps} control instants); "
          f"median of {args.repeat}, ns per case-step")
    rows = {}
    for threads in args.threads:
        rows[f"built-in, {threads} thread(s)"] = lambda t=threads: landing.simulate_batch(plant, builtin, x0,
                                                                                           threads=t, **kw)
        rows[f"PythonLaw, {threads} thread(s)"] = lambda t=threads: landing.simulate_batch(plant, python, x0,
                                                                                            threads=t, **kw)
        rows[f"careful, {threads} thread(s)"] = lambda t=threads: landing.simulate_batch(plant, careful, x0,
                                                                                          threads=t, **kw)
    times = {name: [] for name in rows}
    for r in range(args.repeat):
        names = list(rows)
        for name in names[r % len(names):] + names[:r % len(names)]:
            times[name].append(timed(rows[name]))
    per = {name: statistics.median(v) / (args.cases * steps) * 1e9 for name, v in times.items()}
    rows = []
    for threads in args.threads:
        bi, py = per[f"built-in, {threads} thread(s)"], per[f"PythonLaw, {threads} thread(s)"]
        ca = per[f"careful, {threads} thread(s)"]
        print(f"   {threads} thread(s): built-in {bi:8.1f}   PythonLaw {py:8.1f}   ratio {py / bi:5.2f}   "
              f"careful numpy {ca:8.1f}   ratio {ca / bi:5.2f}")
        rows.append({"threads": threads, "builtin_ns": bi, "printed_ns": py, "careful_ns": ca})
    return rows


def table2(args, plant, builtin, python, x0, kw, steps) -> None:
    for threads in args.threads:
        print(f"\n2. cases per call, {args.cases} Mars cases, {threads} thread(s); median of {args.repeat}, "
              "ns per case-step")
        sweep = {"built-in": builtin}
        functions = {"printed": python, "careful": python.replace(function=mss_lean),
                     "zeros": python.replace(function=zeros)}
        for label in args.sweep:
            for per_call in (256, 512, 1024, 2048, 4096, None):
                name = f"cases_per_call={per_call}" + (f", {label}" if args.sweep != ["printed"] else "")
                sweep[name] = functions[label].replace(cases_per_call=per_call)
        times = {name: [] for name in sweep}
        for r in range(args.repeat):
            names = list(sweep)
            for name in names[r % len(names):] + names[:r % len(names)]:
                times[name].append(timed(lambda law=sweep[name], t=threads: landing.simulate_batch(
                    plant, law, x0, threads=t, **kw)))
        base = statistics.median(times["built-in"])
        for name, v in times.items():
            print(f"   {name:>22}: {statistics.median(v) / (args.cases * steps) * 1e9:8.1f}   "
                  f"ratio {statistics.median(v) / base:5.2f}")


def table3(args, plant, builtin, python, x0, kw, steps) -> list[dict]:
    inside = [0.0]
    table = []
    for threads in args.threads:
        print(f"\n3. where the time goes, cases_per_call={python.cases_per_call}, {threads} thread(s); median of "
              f"{args.repeat}, ns per case-step")
        for label, function in (("printed", mss_printed), ("careful", mss_lean)):

            def timed_law(*a, function=function):
                start = time.perf_counter()
                out = function(*a)
                inside[0] += time.perf_counter() - start
                return out

            spy = python.replace(function=timed_law)
            parts: dict[str, list[float]] = {"function": [], "total": [], "open loop": [], "built-in": []}
            for _ in range(args.repeat):
                inside[0] = 0.0
                parts["total"].append(timed(lambda spy=spy, t=threads: landing.simulate_batch(
                    plant, spy, x0, threads=t, **kw)))
                parts["function"].append(inside[0])
                parts["open loop"].append(timed(lambda t=threads: landing.simulate_batch(
                    plant, C.OpenLoop(), x0, threads=t, **kw)))
                parts["built-in"].append(timed(lambda t=threads: landing.simulate_batch(
                    plant, builtin, x0, threads=t, **kw)))
            med = {k: statistics.median(v) / (args.cases * steps) * 1e9 for k, v in parts.items()}
            print(f"   {label}: PythonLaw {med['total']:.1f} = function {med['function']:.1f} + the rest "
                  f"{med['total'] - med['function']:.1f}; open loop built-in {med['open loop']:.1f}; "
                  f"built-in law {med['built-in']:.1f}; ratio {med['total'] / med['built-in']:.2f}")
            if threads == 1:
                bound = (med["function"] + med["open loop"]) / med["built-in"]
                print(f"   {label}: bound on the ratio with no engine overhead: (function + open loop) / built-in "
                      f"= {bound:.2f}")
            else:
                # the calls hold the interpreter, so they run one at a time whatever the engine
                # overlaps with them (table 5: two calls at once are not faster than in turn)
                bound = med["function"] / med["built-in"]
                print(f"   {label}: bound on the ratio with the plant fully overlapped and no engine overhead: "
                      f"function / built-in = {bound:.2f}")
            table.append({"threads": threads, "function": label, "total_ns": med["total"],
                          "function_ns": med["function"], "open_loop_ns": med["open loop"],
                          "builtin_ns": med["built-in"], "bound": bound})
    return table


def table4(args, plant, kw, steps) -> list[dict]:
    t_final, dt = kw["t_final"], kw["dt"]
    zero = C.PythonLaw(zeros)
    table = []
    for threads in args.threads:
        print(f"\n4. per-call overhead: a law returning zeros against the built-in OpenLoop, {t_final} s at dt = "
              f"{dt} s, {threads} thread(s); median of {args.repeat}, microseconds per control instant")
        for n in (100, 1_000, 10_000, 100_000):
            x = dispersed(n)
            rows = {"open": lambda x=x, t=threads: landing.simulate_batch(plant, C.OpenLoop(), x, threads=t, **kw),
                    "python": lambda x=x, t=threads: landing.simulate_batch(plant, zero, x, threads=t, **kw)}
            t = {k: [] for k in rows}
            for r in range(args.repeat):
                for k in (["open", "python"] if r % 2 == 0 else ["python", "open"]):
                    t[k].append(timed(rows[k]))
            o, p = (statistics.median(t[k]) / (steps + 1) * 1e6 for k in ("open", "python"))
            print(f"   {n:>7} cases: OpenLoop {o:9.1f}   PythonLaw {p:9.1f}   overhead {p - o:9.1f} "
                  f"({(p - o) / n * 1e3:6.1f} ns per case)")
            table.append({"threads": threads, "cases": n, "open_loop_us": o, "python_us": p})
    return table


def table5(args) -> None:
    print(f"\n5. the function alone, two calls in turn on one thread against one on each of two threads at once; "
          f"median of {args.repeat}, ns per case per call")
    for label, function in (("printed", mss_printed), ("careful", mss_lean)):
        for n in (2048, 4096):
            a, b = two_calls(function, n, args.repeat)
            print(f"   {label}, {n} cases: in turn {a:6.1f}   at once {b:6.1f}   speed-up {a / b:5.2f}")


def gain_forms(n: int) -> dict[str, dict[str, object]]:
    """``GAINS`` given as scalars, per axis and per case: the same values in three forms."""
    return {"scalars": dict(GAINS), "per axis": {k: np.full(3, v) for k, v in GAINS.items()},
            "per case": {k: np.full(n, v) for k, v in GAINS.items()}}


def table6(args, plant, x0, kw, steps) -> list[dict]:
    from landing._internal.user_law import per_axis

    n = len(x0)
    table = []
    laws = {form: C.PythonLaw(mss_lean, params=p) for form, p in gain_forms(n).items()}
    ref = landing.simulate_batch(plant, laws["scalars"], x0, threads=1, **kw).final_state
    for form, law in laws.items():
        same = np.array_equal(landing.simulate_batch(plant, law, x0, threads=1, **kw).final_state, ref)
        assert same, f"the gains given {form} give other bits"
    for threads in args.threads:
        print(f"\n6. the careful function's gains given in three forms, {n} Mars cases, {threads} thread(s); "
              f"median of {args.repeat}, ns per case-step")
        times: dict[str, list[float]] = {form: [] for form in laws}
        for r in range(args.repeat):
            names = list(laws)
            for form in names[r % len(names):] + names[:r % len(names)]:
                times[form].append(timed(lambda law=laws[form], t=threads: landing.simulate_batch(
                    plant, law, x0, threads=t, **kw)))
        per = {form: statistics.median(v) / (n * steps) * 1e9 for form, v in times.items()}
        print("   " + "   ".join(f"{form} {ns:6.1f}" for form, ns in per.items()))
        table.append({"threads": threads, **{form.replace(" ", "_") + "_ns": ns for form, ns in per.items()}})

    m, calls = 4096, 200
    rng = np.random.default_rng(6)
    e, de, drift = rng.normal(0.0, 100.0, (m, 3)), rng.normal(0.0, 5.0, (m, 3)), rng.normal(0.0, 1.0, (m, 3))
    ref = types.SimpleNamespace(position=np.zeros((m, 3)), velocity=np.zeros((m, 3)), acceleration=np.zeros((m, 3)))
    handed = {form: {k: per_axis("bench", k, v, m, 3) for k, v in p.items()}
              for form, p in gain_forms(m).items()}
    handed["per axis, as views"] = {k: np.broadcast_to(np.full(3, v), (m, 3)) for k, v in GAINS.items()}
    handed["per case, as views"] = {k: np.broadcast_to(np.full(m, v)[:, None], (m, 3)) for k, v in GAINS.items()}
    print(f"\n6. the careful function alone, {m} cases, its gains as handed to it; median of {args.repeat} rounds of "
          f"{calls} calls, ns per case")
    alone: dict[str, list[float]] = {form: [] for form in handed}
    for _ in range(args.repeat):
        for form, p in handed.items():
            start = time.perf_counter()
            for _ in range(calls):
                mss_lean(0.0, e, de, ref, drift, np.ones((m, 3)), p, None)
            alone[form].append(time.perf_counter() - start)
    for form, v in alone.items():
        strides = handed[form]["beta1"].strides
        print(f"   {form:>26} (strides {strides}): {statistics.median(v) / (calls * m) * 1e9:6.1f}")
    table.append({"alone_ns_per_case": {form: statistics.median(v) / (calls * m) * 1e9 for form, v in alone.items()}})

    # one operation: a (4096, 3) array times a gain in each form, into an array held
    out, ops = np.empty((m, 3)), 2000
    print(f"\n6. one multiply, np.multiply(e, gain, out=out), {m} cases; median of {args.repeat} rounds of {ops}, "
          "ns per case")
    gains = {form: p["beta1"] for form, p in handed.items()}
    # what numpy does with a (3,) vector itself: the same loop over rows as a (0, 8) view
    gains["per axis, as a (3,) vector"] = np.full(3, GAINS["beta1"])
    one: dict[str, list[float]] = {form: [] for form in gains}
    for _ in range(args.repeat):
        for form, gain in gains.items():
            start = time.perf_counter()
            for _ in range(ops):
                np.multiply(e, gain, out=out)
            one[form].append(time.perf_counter() - start)
    for form, v in one.items():
        print(f"   {form:>26}: {statistics.median(v) / (ops * m) * 1e9:6.2f}")
    table.append({"multiply_ns_per_case": {form: statistics.median(v) / (ops * m) * 1e9 for form, v in one.items()}})
    return table


def two_calls(function, n: int, repeat: int, calls: int = 200) -> tuple[float, float]:
    """The median time per case per call of ``calls`` calls on each of two arrays of ``n``
    cases: the two in turn on this thread, and each on a thread of its own at once."""
    rng = np.random.default_rng(5)

    def arguments():
        e, de = rng.normal(0.0, 100.0, (n, 3)), rng.normal(0.0, 5.0, (n, 3))
        ref = types.SimpleNamespace(position=np.zeros((n, 3)), velocity=np.zeros((n, 3)),
                                    acceleration=np.zeros((n, 3)))
        return (0.0, e, de, ref, rng.normal(0.0, 1.0, (n, 3)), np.ones((n, 3)), GAINS, None)

    pair = (arguments(), arguments())

    def loop(a):
        for _ in range(calls):
            function(*a)

    def in_turn():
        start = time.perf_counter()
        loop(pair[0])
        loop(pair[1])
        return time.perf_counter() - start

    def at_once():
        threads = [threading.Thread(target=loop, args=(a,)) for a in pair]
        start = time.perf_counter()
        for th in threads:
            th.start()
        for th in threads:
            th.join()
        return time.perf_counter() - start

    in_turn(), at_once()
    runs: dict[str, list[float]] = {"in turn": [], "at once": []}
    for _ in range(repeat):
        runs["in turn"].append(in_turn())
        runs["at once"].append(at_once())
    in_turn_ns, at_once_ns = (statistics.median(v) / (2 * calls * n) * 1e9 for v in runs.values())
    return in_turn_ns, at_once_ns


if __name__ == "__main__":
    main()
