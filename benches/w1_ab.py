"""W1 on one thread under several builds of the core, alternated (BENCHMARKS.md: the realistic
loop's cost with its features off, fat against thin LTO).

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
"""

from __future__ import annotations

import argparse
import statistics
import subprocess


def run(binary: str, level: str) -> tuple[float, str]:
    out = subprocess.run([binary, "300", level], capture_output=True, text=True, check=True).stdout
    words = out.split()
    return float(words[0]), out[out.index("checksum"):].strip(" )\n")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("binaries", nargs="+", help="name=path of a profile_w1 binary; the first is the reference")
    ap.add_argument("--rounds", type=int, default=30)
    ap.add_argument("--level", default="avx512")
    args = ap.parse_args()
    named = dict(b.split("=", 1) for b in args.binaries)
    sums = {name: run(path, args.level)[1] for name, path in named.items()}
    assert len(set(sums.values())) == 1, f"the binaries give other bits: {sums}"
    times: dict[str, list[float]] = {name: [] for name in named}
    names = list(named)
    for r in range(args.rounds):
        # each round starts at another binary, so that no binary always runs first
        for name in names[r % len(names):] + names[:r % len(names)]:
            times[name].append(run(named[name], args.level)[0])
    first = next(iter(named))
    print(f"W1, 300 cases, 10 s at 1 ms, one thread, {args.level}; {args.rounds} rounds; {sums[first]}")
    for name, v in times.items():
        ratio = statistics.median(a / b for a, b in zip(v, times[first]))
        print(f"  {name:>12}: median {statistics.median(v):6.2f}  min {min(v):6.1f}  max {max(v):6.1f}  "
              f"paired ratio to {first} {ratio:.4f}")


if __name__ == "__main__":
    main()
