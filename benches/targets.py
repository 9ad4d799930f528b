"""The speed targets of issue 27 and of the Python law (issue 21, item 6), measured in one run.

Runs the benches below one after another on this machine, each with ``--json``, each checking
its accuracy before it times anything, then prints one table: every target, what it asks,
what this run measured, and whether it holds here. The numbers of one run on one machine are
what to compare: on a shared machine the load moves absolute times between minutes, so the
table holds ratios taken inside one bench wherever a target is a ratio.

- ``peers_w1.py``: W1 on one thread, against numba (the law as printed, and with the powers
  shared) and JAX; one thread to all cores; the AVX2 kernel forced.
- ``peers_small_body.py``, ``peers_tether.py``: W3, W5, W6 against numba, one thread.
- ``campaign_vs_w1.py``: the main job's campaign (metrics only) against W1's kernel on the
  same threads (needs ``profile_w1``, built by the first command below; skipped without it).
- ``recording_cost.py``: the campaign recording every 50 ms against metrics only.
- ``campaign_memory.py``: the main job's campaign into a store, recording every second. The
  target is 10^6 cases in 10 minutes; by default this runs ``--campaign-cases`` (2 x 10^4) and
  projects linearly to 10^6 (the table says so); ``--million`` runs all 10^6 (about 20
  minutes on a 2-core machine).
- ``python_law.py``: tables 1 and 4, the FixedTimeMSS law written in numpy (as printed, and as
  a careful numpy user writes it) against the built-in law on 10^4 Mars cases, and the
  per-call overhead of a Python law.

The table's last column, "best here", is what this machine allows the same code or the same
function at best, where a bench measures it, so that a target that is not met can be told
apart from one that cannot be met here without other arithmetic:

- with ``--floor`` (needs gdb and gcc, and ``profile_w1``), ``w1_floor.py`` counts W1's
  instructions at ``avx512`` (where the machine has it) and ``avx2`` and times them with no
  dependency between them: W1's floor at each level, the least time this instruction mix can
  take here, and W1's time over it, as the median of alternated rounds. The times of the
  other benches, taken minutes apart on a shared machine, are scaled by that ratio: W1's
  one-thread time and the AVX2 kernel's at their floors; the ratios to numba and JAX with W1
  at its floor; and the stored campaign with W1's kernel at its floor (the campaign runs at
  W1's kernel speed per thread: "the campaign against W1" row). W3, W5 and W6 the same way at
  the default level, where ``profile_small_body`` and ``profile_w6`` are built: their ratios
  to numba with landing at its floor.
- one thread to many: a block of lanes costs the same however many of its cases are used, so
  W1's cases in blocks of the default level's width bound the speed-up of more threads (at
  ``avx512``, 300 cases are 19 blocks of 16, and two threads take at least 10 of one thread's
  19 block-times: 1.90x).
- the Python law: table 3 of ``python_law.py``, the function's own time (and, on one thread,
  the open-loop plant's) over the built-in law's, the ratio no engine could go under with this
  function on this machine.

    cargo build --release -p landing_core --example profile_w1   # and profile_small_body, profile_w6 for --floor
    pip install -r benches/requirements.txt
    python benches/targets.py [--repeat 3] [--million] [--floor] [--out DIR]
    python benches/targets.py --tabulate DIR    # the table of a kept run again, measuring nothing

About 11 minutes on the 2-core Intel machine of BENCHMARKS.md without ``--million``, and
some 5 more with ``--floor``.
"""

from __future__ import annotations

import argparse
import datetime
import json
import math
import os
import subprocess
import sys
import tempfile
from collections.abc import Callable
from pathlib import Path

from _harness import WIDE_LANES, machine

import landing

HERE = Path(__file__).resolve().parent
EXAMPLES = HERE.parent / "target" / "release" / "examples"
PROFILE_W1 = EXAMPLES / "profile_w1"
# the profile binary of each workload whose floor ``--floor`` takes
PROFILES = {"W1": PROFILE_W1, "W3": EXAMPLES / "profile_small_body", "W5": EXAMPLES / "profile_small_body",
            "W6": EXAMPLES / "profile_w6"}
MILLION = 1_000_000


def measured(name: str, args: list[str], out: Path, tag: str = "") -> dict | None:
    """``benches/NAME.py ARGS --json``, its output shown and kept in ``out/NAME[_TAG].log``; its
    numbers, or None if it failed (its accuracy check, or a missing peer)."""
    stem = f"{name}_{tag}" if tag else name
    numbers, log = out / f"{stem}.json", out / f"{stem}.log"
    command = [sys.executable, str(HERE / f"{name}.py"), *args, "--json", str(numbers)]
    print(f"\n$ {' '.join(command[1:])}", flush=True)
    with open(log, "w") as fh:
        proc = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        assert proc.stdout is not None
        for line in proc.stdout:
            print(line, end="", flush=True)
            fh.write(line)
        code = proc.wait()
    if code != 0 or not numbers.exists():
        print(f"{name}: exited with {code}; its targets are left unmeasured (log: {log})")
        return None
    return json.loads(numbers.read_text())


def best(rows: list[dict], **match: object) -> float | None:
    """The best ns per case-step of the row matching ``match``."""
    for row in rows:
        if all(row.get(k) == v for k, v in match.items()):
            return row["best_ns"]
    return None


class Table:
    """The targets: name, what it asks, the measured value, and whether it holds."""

    def __init__(self) -> None:
        self.rows: list[dict] = []

    def add(self, name: str, asks: str, value: float | None, holds: Callable[[float], bool] | None,
            shown: str, note: str = "", best: float | None = None) -> None:
        """A target; ``best``, in the unit of ``value``, is what this machine allows at best
        (see the module's documentation), shown as ``value`` is."""
        met = None if value is None or holds is None else bool(holds(value))
        self.rows.append({"target": name, "asks": asks, "measured": None if value is None else shown.format(value),
                          "value": value, "met": met, "note": note,
                          "best": None if best is None else shown.format(best), "best_value": best})

    def print(self) -> None:
        head = f"| {'target':<54} | {'asks':<12} | {'measured':<14} | {'here':<9} | {'best here':<10} |"
        print(head)
        print("|" + "|".join("-" * len(c) for c in head.split("|")[1:-1]) + "|")
        for r in self.rows:
            here = {True: "met", False: "not met", None: "-"}[r["met"]]
            measured = r["measured"] if r["measured"] is not None else "not measured"
            print(f"| {r['target']:<54} | {r['asks']:<12} | {measured:<14} | {here:<9} | {r['best'] or '-':<10} |")
        notes = [f"{r['target']}: {r['note']}" for r in self.rows if r["note"]]
        if notes:
            print("\n" + "\n".join(notes))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3, help="timed runs per row in each bench")
    ap.add_argument("--campaign-cases", type=int, default=20_000, help="the stored campaign's cases, projected to 10^6")
    ap.add_argument("--million", action="store_true", help="run the stored campaign on all 10^6 cases")
    ap.add_argument("--out", type=Path, default=None, help="keep each bench's log and numbers here")
    ap.add_argument("--floor", action="store_true", help="also run w1_floor.py (gdb, gcc): W1's floor at each level")
    ap.add_argument("--tabulate", type=Path, default=None, metavar="DIR",
                    help="measure nothing: print the table of the numbers an earlier run kept in DIR (its --out)")
    args = ap.parse_args()
    if args.tabulate and not args.tabulate.is_dir():
        ap.error(f"--tabulate: {args.tabulate} is not a directory (the --out of an earlier run)")
    out = args.tabulate or args.out or Path(tempfile.mkdtemp(prefix="targets_"))
    out.mkdir(parents=True, exist_ok=True)
    cores = len(os.sched_getaffinity(0))
    repeat = ["--repeat", str(args.repeat)]
    started = datetime.datetime.now().astimezone()
    levels = landing.kernel_levels()
    default = os.environ.get("LANDING_KERNEL") or levels[-1]
    if args.tabulate:
        kept = out / "targets.json"
        if kept.exists():
            summary = json.loads(kept.read_text())
            started = datetime.datetime.fromisoformat(summary["started"])
            default = summary.get("kernel_level", default)
        print(f"targets of the run kept in {out}, {started.isoformat(timespec='seconds')}")
    else:
        print(f"targets, {started.isoformat(timespec='seconds')}; {machine()}; logs and numbers in {out}")

    def run(name: str, bench_args: list[str], out: Path, tag: str = "") -> dict | None:
        if args.tabulate is None:
            return measured(name, bench_args, out, tag)
        numbers = out / (f"{name}_{tag}.json" if tag else f"{name}.json")
        return json.loads(numbers.read_text()) if numbers.exists() else None

    w1 = run("peers_w1", [*repeat, "--threads", *sorted({"1", str(cores)})], out)
    small = run("peers_small_body", [*repeat, "--threads", "1"], out)
    tether = run("peers_tether", [*repeat, "--threads", "1"], out)
    versus = None
    if PROFILE_W1.exists() or args.tabulate:
        versus = run("campaign_vs_w1", ["--rounds", str(4 * args.repeat), "--threads", str(cores)], out)
    else:
        print(f"\ncampaign_vs_w1: skipped, {PROFILE_W1} not built")
    recording = run("recording_cost", ["--cases", "20000", "--repeat", str(max(2, args.repeat - 1)), "--paths",
                                       "monte_carlo, progress bar"], out)
    cases = MILLION if args.million else args.campaign_cases
    stored = run("campaign_memory", ["--cases", str(cases)], out)
    python = run("python_law", [*repeat, "--tables", "1", "3", "4", "--threads", *sorted({"1", str(cores)})], out)
    floors: dict[str, dict] = {}
    if args.floor or args.tabulate:
        for level in ("avx512", "avx2"):
            if args.tabulate or (level in levels and PROFILE_W1.exists()):
                got = run("w1_floor", ["--level", level, "--rounds", str(2 * args.repeat)], out, tag=level)
                if got:
                    floors[level] = got
        for workload in ("W3", "W5", "W6"):
            if args.tabulate or (default in ("avx512", "avx2") and PROFILES[workload].exists()):
                got = run("w1_floor", ["--workload", workload, "--profile", str(PROFILES[workload]), "--level", default,
                                       "--rounds", str(2 * args.repeat)], out, tag=f"{workload}_{default}")
                if got:
                    floors[workload] = got
    # W1's time over its floor's, the median of w1_floor's alternated rounds: a ratio taken in
    # one run, so that it can scale the other benches' times, taken minutes apart
    above = floors[default]["ratio"] if default in floors else None

    t = Table()
    if stored:
        projected = stored["wall_s"] * MILLION / stored["cases"]
        how = "" if stored["cases"] == MILLION else f"projected from {stored['cases']} cases"
        if above:
            how += ("; " if how else "") + "best here: W1's kernel at its floor (the time over W1 / floor)"
        t.add("10^6 Mars cases, 60 s, stored, recording every second", "<= 600 s", projected,
              lambda v: v <= 600, "{:.0f} s", how, best=projected / above if above else None)
    else:
        t.add("10^6 Mars cases, 60 s, stored, recording every second", "<= 600 s", None, None, "")
    cost = recording["rows"][0]["cost"] if recording else None
    t.add("recording every 50 ms, over metrics only", "<= 15 %", None if cost is None else 100 * cost,
          lambda v: v <= 15, "{:.1f} %")
    rows = w1["rows"] if w1 else []
    one = best(rows, implementation="landing", threads=1)
    at_floor = one / above if one and above else None
    t.add("W1, one thread, ns per case-step", "<= 18", one, lambda v: v <= 18, "{:.1f}", best=at_floor)
    for key, label in (("numba-printed", "numba, law as printed"), ("numba-shared", "numba, powers shared")):
        peer = best(rows, implementation=key, threads=1)
        t.add(f"W1 against {label}, one thread", ">= 14x", None if not (one and peer) else peer / one,
              lambda v: v >= 14, "{:.1f}x", best=peer / at_floor if peer and at_floor else None)
    jax = best(rows, implementation="jax", threads=1)
    t.add("W1 against JAX, one thread", ">= 7x", None if not (one and jax) else jax / one, lambda v: v >= 7, "{:.1f}x",
          best=jax / at_floor if jax and at_floor else None)
    many = best(rows, implementation="landing", threads=cores)
    blocks = math.ceil(w1["cases"] / WIDE_LANES[default]) if w1 and default in WIDE_LANES else None
    t.add(f"W1, one thread to {cores}", ">= 1.9x", None if cores < 2 or not (one and many) else one / many,
          lambda v: v >= 1.9, "{:.2f}x",
          "" if cores >= 2 else "one core: not measured",
          best=blocks / math.ceil(blocks / cores) if blocks and cores >= 2 else None)
    avx2 = best(rows, implementation="landing-avx2", threads=1)
    t.add("W1, the AVX2 kernel forced, ns per case-step", "<= 40", avx2, lambda v: v <= 40, "{:.1f}",
          best=avx2 / floors["avx2"]["ratio"] if avx2 and "avx2" in floors else None)
    t.add(f"the campaign against W1, {cores} thread(s)", "<= 1.1", versus["ratio"] if versus else None,
          lambda v: v <= 1.1, "{:.3f}")
    for workload, source in (("W3", small), ("W5", small), ("W6", tether)):
        peer_rows = source["rows"] if source else []
        ours = best(peer_rows, workload=workload, implementation="landing", threads=1)
        peer = best(peer_rows, workload=workload, implementation="numba", threads=1)
        ratio = floors[workload]["ratio"] if workload in floors else None
        # the floor bounds a period whose instructions run once each; one that loops (W5's
        # centroid over 401 points) can run faster than their straight-line copy, which then
        # bounds nothing
        note = "" if ratio is None or ratio >= 1 else (
            f"its floor's loop ran slower than {workload} itself ({workload} / floor {ratio:.2f}): no bound")
        t.add(f"{workload} against numba, one thread", ">= 8x", None if not (ours and peer) else peer / ours,
              lambda v: v >= 8, "{:.1f}x", note,
              best=peer * ratio / ours if ours and peer and ratio and ratio >= 1 else None)
    n = (python or {}).get("cases")
    bounds = {(r["threads"], r["function"]): r["bound"] for r in (python or {}).get("table3", [])}
    for row in (python or {}).get("table1", []):
        for key, label, function in (("printed_ns", "as printed", "printed"), ("careful_ns", "careful", "careful")):
            t.add(f"Python law ({label}) / built-in, {n} cases, {row['threads']} thr", "<= 3x",
                  row[key] / row["builtin_ns"], lambda v: v <= 3, "{:.2f}x", best=bounds.get((row["threads"], function)))
    for row in (python or {}).get("table4", []):
        if row["cases"] in (100, 10_000):
            per_case = (row["python_us"] - row["open_loop_us"]) * 1e3 / row["cases"]
            t.add(f"Python law's call, {row['cases']} cases, {row['threads']} thr, ns a case", "(measured)",
                  per_case, None, "{:.1f}")

    # the machine the numbers were measured on (another one's, with --tabulate)
    where = next((b["machine"] for b in (w1, python, stored) if b and "machine" in b), machine())
    print(f"\nThe targets on this machine, {started.date()} ({where}; kernel level {default}):\n")
    t.print()
    summary = {"started": started.isoformat(timespec="seconds"), "machine": where, "kernel_level": default,
               "targets": t.rows}
    (out / "targets.json").write_text(json.dumps(summary, indent=1))
    print(f"\n{out / 'targets.json'}")


if __name__ == "__main__":
    main()
