"""Caps on the sizes a request may ask for, and the memory check made before allocating.

The caps are defined once, in the core (``landing_core::limits``), and read here from
``landing._core.LIMITS``; docs/parameters.md ("Limits") says why each has its value. The
memory check is the one every Python-side allocation whose size the caller controls goes
through: it computes the bytes first and refuses with a :class:`MemoryError` stating them
(and what is available) instead of letting numpy or the allocator abort the interpreter.
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from types import MappingProxyType
from typing import Optional

from landing import _core

__all__ = ["LIMITS", "available_memory", "format_bytes", "require_memory"]

#: The caps by name: max_cases, max_steps, max_substeps, max_threads, max_fuzzy_resolution.
LIMITS: Mapping[str, int] = MappingProxyType({str(k): int(v) for k, v in dict(_core.LIMITS).items()})


def available_memory() -> Optional[int]:
    """Bytes a new allocation can count on, as the core measures it for its own batches
    (``landing_core::memory``: ``MemAvailable`` on Linux, or less where the cgroup's memory
    limit or the address-space limit, ``ulimit -v``, leaves less room), else the total
    physical memory (``os.sysconf``); None when unknown."""
    measured = _core.available_memory()
    if measured is not None:
        return int(measured)
    try:
        pages = os.sysconf("SC_PHYS_PAGES")
        page_size = os.sysconf("SC_PAGE_SIZE")
    except (AttributeError, ValueError, OSError):
        return None
    if pages > 0 and page_size > 0:
        return int(pages) * int(page_size)
    return None


def format_bytes(n: float) -> str:
    """``n`` bytes in the largest binary unit that keeps it >= 1 (e.g. ``"7.5 GiB"``)."""
    for unit in ("B", "KiB", "MiB", "GiB", "TiB", "PiB"):
        if abs(n) < 1024.0 or unit == "PiB":
            return f"{n:.0f} {unit}" if unit == "B" else f"{n:.3g} {unit}"
        n /= 1024.0
    raise AssertionError("unreachable")  # pragma: no cover


def require_memory(what: str, nbytes: int, *, available: Optional[int] = None,
                   hint: str = "ask for fewer cases or components") -> None:
    """Refuses, before anything is allocated, a request for ``nbytes`` that cannot fit in the
    memory available (``available`` overrides the measurement, for tests): a MemoryError that
    names what needed it, its size, the memory available and ``hint``, what would fit."""
    if nbytes < 0:
        raise ValueError(f"nbytes = {nbytes} violates nbytes >= 0")
    free = available_memory() if available is None else available
    if free is not None and nbytes > free:
        raise MemoryError(
            f"{what} needs {format_bytes(nbytes)} ({nbytes if nbytes < 10**20 else f'{nbytes:.3g}'} bytes) but "
            f"only {format_bytes(free)} "
            f"of memory is available; {hint}"
        )
