"""The main job's campaign path against W1's kernel, per case-step, on the same threads (issue 27,
item 2: "the campaign path with metrics only within 1.1x of W1 per thread").

Alternated in each round: ``profile_w1 CASES avx512 THREADS`` (W1's kernel: 10 s at 1 ms, final
states only) and ``landing.monte_carlo`` of the ``mars_monte_carlo`` preset (60 s at 1 ms,
Table II dispersions, a_p = 20 sin t, metrics only, the progress bar off) on ``--campaign-cases``
cases; both in wall time per case-step on ``--threads`` threads. Short runs, many rounds: on a
shared machine the load moves between minutes, and the median of the rounds' paired ratios is
what this prints.

    cargo build --release -p landing_core --example profile_w1
    python benches/campaign_vs_w1.py [--rounds 16] [--threads 2] [--w1-cases 2400] [--campaign-cases 1600] [--json FILE]
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import time
from pathlib import Path

from _harness import json_option, write_json

import landing

ROOT = Path(__file__).resolve().parents[1]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rounds", type=int, default=16)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--w1-cases", type=int, default=2400)
    ap.add_argument("--campaign-cases", type=int, default=1600)
    json_option(ap)
    ap.add_argument("--profile", type=Path, default=ROOT / "target" / "release" / "examples" / "profile_w1")
    args = ap.parse_args()
    scenario = landing.scenarios.preset("mars_monte_carlo")
    steps = round(scenario.options.t_final / scenario.options.dt)
    n = args.campaign_cases
    w1: list[float] = []
    campaign: list[float] = []
    for r in range(args.rounds):
        out = subprocess.run(
            [str(args.profile), str(args.w1_cases), "avx512", str(args.threads)],
            capture_output=True,
            text=True,
            check=True,
        ).stdout
        w1.append(float(out.split()[0]))
        start = time.perf_counter()
        landing.monte_carlo(scenario, n, seed=1, record_every=0, progress=False, threads=args.threads)
        campaign.append((time.perf_counter() - start) / (n * steps) * 1e9)
        print(f"round {r:2d}: W1 {w1[-1]:6.2f}   campaign {campaign[-1]:6.2f}   ns of wall time per case-step")
    ratio = statistics.median(c / w for c, w in zip(campaign, w1))
    print(
        f"{args.threads} thread(s), medians: W1 {statistics.median(w1):.2f}, campaign {statistics.median(campaign):.2f}; "
        f"campaign / W1 {ratio:.3f} (median of the rounds' ratios)"
    )
    write_json(args.json, {"threads": args.threads, "rounds": args.rounds, "w1_ns": statistics.median(w1),
                           "campaign_ns": statistics.median(campaign), "ratio": ratio})


if __name__ == "__main__":
    main()
