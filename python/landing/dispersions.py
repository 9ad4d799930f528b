"""Dispersions of initial states for Monte Carlo campaigns ("dispersions as types").

Case i's sample depends only on (seed, i), drawn in the core from the counter-based
generator's dispersion stream: a campaign's cases are the same whatever the batch size, the
chunking or the thread count.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from landing import _core
from landing._internal.args import integer
from landing._internal.limits import require_memory
from landing._internal.table import ArrayLike, Table

__all__ = ["Dispersion", "Normal", "Uniform"]


class Dispersion(Table):
    """Independent distributions of the state components."""

    family: ClassVar[str] = "dispersion"

    @staticmethod
    def _compiler(owner: str, table: dict) -> _core.DispersionHandle:
        return _core.DispersionHandle(table)

    @property
    def dim(self) -> int:
        """Number of state components."""
        return int(self._core.dim)

    def sample(self, n: int, seed: int = 0, first_case: int = 0) -> np.ndarray:
        """Cases ``first_case .. first_case + n``, shape ``(n, dim)``. The memory the draws
        need is checked first: a MemoryError states it if it cannot fit."""
        owner = type(self).__name__
        n = integer("n", n, minimum=0, cap="max_cases", owner=owner)
        seed = integer("seed", seed, minimum=0, maximum=2**64 - 1, owner=owner)
        first_case = integer("first_case", first_case, minimum=0, maximum=2**64 - 1 - n, owner=owner)
        require_memory(f"{owner}.sample(n={n}): {n} x {self.dim} draws", 8 * n * self.dim)
        return self._core.sample(seed, first_case, n)


@dataclass(frozen=True, eq=False)
class Normal(Dispersion):
    """Normal per component (seed 001 Table II). A zero standard deviation fixes the value."""

    mean: ArrayLike
    std: ArrayLike

    kind: ClassVar[str] = "normal"


@dataclass(frozen=True, eq=False)
class Uniform(Dispersion):
    """Uniform on ``[low, high]`` per component (seed 001 Table III). ``low == high`` fixes
    the value."""

    low: ArrayLike
    high: ArrayLike

    kind: ClassVar[str] = "uniform"
