"""W1 on one thread under several builds of the core, alternated (BENCHMARKS.md: the realistic
loop's cost with its features off, fat against thin LTO); or another profile binary's workload.

Each binary is ``profile_w1`` of some commit or build setting, built in a target directory of
its own, e.g.::

    git worktree add /tmp/wt_old 7486255
    (cd /tmp/wt_old && CARGO_TARGET_DIR=/tmp/tgt_old cargo build --release -p landing_core --example profile_w1)
    CARGO_TARGET_DIR=/tmp/tgt_new cargo build --release -p landing_core --example profile_w1
    python benches/w1_ab.py old=/tmp/tgt_old/release/examples/profile_w1 \\
                            new=/tmp/tgt_new/release/examples/profile_w1 [--rounds 30]

One run of each binary in turn per round, each round starting at the next binary (W1's 300 cases, 10 s at 1 ms, one thread, AVX-512
unless ``--level``), so a machine's drift reaches every binary alike; prints each binary's
median, min and max (ns per case-step) and the median over rounds of its ratio to the first
binary's run of the same round. Every binary must print the same checksum of the final
states (the same bits) before any time is read.

``--args`` gives the binaries other arguments, e.g. ``profile_small_body`` binaries with
``--args "W5 300 avx512 3"`` (the fastest of a run's repeats counts). ``--cpu N`` runs every
binary on processor N alone: on a shared 2-core virtual machine one core can run a one-thread
workload 1.5 times slower than the other for minutes (its sibling busy with a neighbour's
work), and an unpinned run lands on either (BENCHMARKS.md, 2026-12-08).
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess


def run(binary: str, args: list[str], cpu: int | None) -> tuple[float, str]:
    pin = None if cpu is None else (lambda: os.sched_setaffinity(0, {cpu}))
    out = subprocess.run([binary, *args], capture_output=True, text=True, check=True, preexec_fn=pin).stdout
    lines = [line for line in out.splitlines() if "checksum" in line]
    sums = {line[line.index("checksum"):].strip(" )") for line in lines}
    assert len(sums) == 1, f"{binary} gives other bits between its repeats: {sums}"
    return min(float(line.split()[0]) for line in lines), sums.pop()


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("binaries", nargs="+", help="name=path of a profile_w1 binary; the first is the reference")
    ap.add_argument("--rounds", type=int, default=30)
    ap.add_argument("--level", default="avx512")
    ap.add_argument("--args", help="the binaries' arguments instead of W1's \"300 LEVEL\"")
    ap.add_argument("--cpu", type=int, help="run every binary on this processor alone")
    args = ap.parse_args()
    argv = args.args.split() if args.args else ["300", args.level]
    named = dict(b.split("=", 1) for b in args.binaries)
    sums = {name: run(path, argv, args.cpu)[1] for name, path in named.items()}
    assert len(set(sums.values())) == 1, f"the binaries give other bits: {sums}"
    times: dict[str, list[float]] = {name: [] for name in named}
    names = list(named)
    for r in range(args.rounds):
        # each round starts at another binary, so that no binary always runs first
        for name in names[r % len(names):] + names[:r % len(names)]:
            times[name].append(run(named[name], argv, args.cpu)[0])
    first = next(iter(named))
    what = f"arguments {' '.join(argv)}" if args.args else f"W1, 300 cases, 10 s at 1 ms, one thread, {args.level}"
    where = "" if args.cpu is None else f", on processor {args.cpu}"
    print(f"{what}{where}; {args.rounds} rounds; {sums[first]}")
    for name, v in times.items():
        ratio = statistics.median(a / b for a, b in zip(v, times[first]))
        print(f"  {name:>12}: median {statistics.median(v):6.2f}  min {min(v):6.1f}  max {max(v):6.1f}  "
              f"paired ratio to {first} {ratio:.4f}")


if __name__ == "__main__":
    main()
