"""What the benches share: a timed run after numba's workers have gone to sleep, the machine and
package versions for the header, and the ``--json`` file through which `targets.py` reads the
numbers a bench printed."""

from __future__ import annotations

import argparse
import json
import os
import platform
import time
from collections.abc import Callable
from importlib import metadata
from pathlib import Path

# numba's OpenMP workers spin for a while after a parallel region (libgomp's default wait
# policy): measured, 8 ms of CPU taken from a 19 ms landing run that followed a two-thread
# numba run at once. Every timed run starts after this pause, when they have gone to sleep.
SETTLE_S = 0.05

# Cases in one block of the three-axis plants (Mars, small body, double integrator) at each
# instruction-set level on x86-64 (`Blocks for Wide` in crates/landing_core/src/kernel.rs). A
# block costs the same whether its lanes are all used or not.
WIDE_LANES = {"baseline": 4, "avx2": 8, "avx512": 16}


def measure(fn: Callable[[], object]) -> dict:
    """Wall time and CPU time of this process (all its threads) over one run, after SETTLE_S."""
    time.sleep(SETTLE_S)
    c0, t0 = time.process_time(), time.perf_counter()
    fn()
    return {"wall": time.perf_counter() - t0, "cpu": time.process_time() - c0}


def machine() -> str:
    model = platform.processor() or platform.machine()
    try:
        with open("/proc/cpuinfo") as fh:
            model = next(line.split(":", 1)[1].strip() for line in fh if line.startswith("model name"))
    except (OSError, StopIteration):
        pass
    return f"{model}, {len(os.sched_getaffinity(0))} cores, Linux {platform.release()}"


def version(name: str) -> str:
    try:
        return metadata.version(name)
    except metadata.PackageNotFoundError:
        return "not installed"


def numba_fma() -> Callable[[float, float, float], float]:
    """`fma(a, b, c)`: `a b + c` rounded once, for numba-compiled peers (LLVM's `llvm.fma`, one
    instruction where the processor has it). The core fuses the integrators' updates
    (`Real::mul_add`), so a peer written in the core's semantics fuses them too. Imported
    lazily: numba is only needed by the peers."""
    from numba import njit, types
    from numba.extending import intrinsic

    @intrinsic
    def _fma(typingctx, a, b, c):  # type: ignore[no-untyped-def]
        sig = types.float64(types.float64, types.float64, types.float64)

        def codegen(context, builder, signature, args):  # type: ignore[no-untyped-def]
            return builder.fma(*args)

        return sig, codegen

    @njit(inline="always")
    def fma(a: float, b: float, c: float) -> float:
        return _fma(a, b, c)

    return fma


def json_option(ap: argparse.ArgumentParser) -> None:
    """``--json FILE``: also write the numbers the bench prints to FILE (`targets.py` reads them)."""
    ap.add_argument("--json", type=Path, default=None, help="also write the printed numbers to this JSON file")


def write_json(path: Path | None, numbers: dict) -> None:
    """The bench's numbers, with the machine they were measured on, to ``path`` (if given)."""
    if path is not None:
        path.write_text(json.dumps({"machine": machine(), **numbers}, indent=1))
