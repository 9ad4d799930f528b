"""W1 from one thread to two: the engine's threads against two processes (BENCHMARKS.md, issue 27's
1 -> 2 threads).

Three ways of running W1's work, alternated round after round so a machine's drift reaches each
alike, each printed as the wall time per case-step of the whole work:

- ``1 thread``: one process, ``cases`` cases on one thread;
- ``2 threads``: one process, ``2 cases`` cases on two threads (the engine's own scaling);
- ``2 processes``: two processes at once, ``cases`` cases on one thread each (what the machine
  gives two independent single-threaded runs: no shared pool, no shared memory).

The speed-up of two threads is ``1 thread / 2 threads``; that of two processes bounds what any
threading of the engine could reach on this machine (two cores' shared caches, memory, clock
and the host's scheduling of the virtual machine's two CPUs are in it; the engine's pool,
scheduling and division of the blocks are not). Each run is ``profile_w1`` (W1's cases, 10 s at
1 ms, timing its batch itself: the processes' start is not counted; two processes count the
slower's time), built with::

    cargo build --release -p landing_core --example profile_w1
    python benches/w1_scaling.py [--binary target/release/examples/profile_w1] [--cases 1200] [--rounds 10]

Every run of the same case count must print the same checksum of the final states whatever the
threads (the same bits) before any time is read.
"""

from __future__ import annotations

import argparse
import statistics
import subprocess


def start(binary: str, cases: int, level: str, threads: int) -> subprocess.Popen[str]:
    return subprocess.Popen([binary, str(cases), level, str(threads)], stdout=subprocess.PIPE, text=True)


def finish(p: subprocess.Popen[str]) -> tuple[float, str]:
    """The ns per case-step the run printed (its own timing of the batch, without the process's
    start) and its checksum."""
    out, _ = p.communicate()
    if p.returncode != 0:
        raise RuntimeError(f"{p.args} exited with {p.returncode}")
    return float(out.split()[0]), out[out.index("checksum"):].strip(" )\n")


def timed(binary: str, cases: int, level: str, threads: int, processes: int) -> tuple[float, list[str]]:
    """Wall ns per case-step of the work of `processes` runs at once, `cases` cases each: the
    slowest run's time over all their cases."""
    runs = [start(binary, cases, level, threads) for _ in range(processes)]
    done = [finish(p) for p in runs]
    return max(t for t, _ in done) / processes, [s for _, s in done]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--binary", default="target/release/examples/profile_w1")
    ap.add_argument("--cases", type=int, default=1200, help="cases per thread")
    ap.add_argument("--rounds", type=int, default=10)
    ap.add_argument("--level", default="avx512")
    args = ap.parse_args()
    n = args.cases
    ways = {
        "1 thread": (n, 1, 1),
        "2 threads": (2 * n, 2, 1),
        "2 processes": (n, 1, 2),
    }
    # the same bits: a run of 2n cases on one thread against two, and n cases on one against two
    one = timed(args.binary, 2 * n, args.level, 1, 1)[1]
    two = timed(args.binary, 2 * n, args.level, 2, 1)[1]
    assert one == two, f"two threads give other bits: {one} against {two}"
    times: dict[str, list[float]] = {w: [] for w in ways}
    names = list(ways)
    for r in range(args.rounds):
        for name in names[r % len(names):] + names[:r % len(names)]:
            cases, threads, processes = ways[name]
            times[name].append(timed(args.binary, cases, args.level, threads, processes)[0])
    print(f"W1, 10 s at 1 ms, {args.level}, {n} cases per thread; {args.rounds} rounds; wall ns per case-step, "
          "medians (min, max)")
    for name, v in times.items():
        print(f"  {name:>12}: {statistics.median(v):6.2f}  ({min(v):.2f}, {max(v):.2f})")
    base = times["1 thread"]
    for name in ("2 threads", "2 processes"):
        ratio = statistics.median(a / b for a, b in zip(base, times[name]))
        print(f"  speed-up of {name} over 1 thread (median of the rounds' ratios): {ratio:.3f}")


if __name__ == "__main__":
    main()
