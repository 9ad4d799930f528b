"""Dispersions for Monte Carlo campaigns ("dispersions as types"): of the initial states
(a scenario's ``dispersion``) and of any numeric parameter (:meth:`Scenario.disperse
<landing.scenarios.Scenario.disperse>`).

Case i's sample depends only on (seed, i) and, for a parameter, on its name: it is drawn in the
core from the counter-based generator, the initial states from the dispersion stream and each
parameter from a stream keyed by its name. A campaign's cases are the same whatever the batch
size, the chunking, the thread count or the other parameters dispersed.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar, Optional

import numpy as np

from landing import _core
from landing._internal.args import integer
from landing._internal.limits import require_memory
from landing._internal.table import ArrayLike, Table
from landing.errors import ParameterTypeError

__all__ = ["Dispersion", "LogNormal", "Normal", "TruncatedNormal", "Uniform"]


class Dispersion(Table):
    """Independent distributions of components: of the state (initial states), or of a
    parameter (one component: one draw per case, shared by the axes of a per-axis parameter;
    one per axis: independent draws). A scalar field serves every component."""

    family: ClassVar[str] = "dispersion"

    @staticmethod
    def _compiler(owner: str, table: dict) -> _core.DispersionHandle:
        return _core.DispersionHandle(table)

    @property
    def dim(self) -> int:
        """Number of state components."""
        return int(self._core.dim)

    def sample(self, n: int, seed: int = 0, first_case: int = 0, key: Optional[str] = None) -> np.ndarray:
        """Cases ``first_case .. first_case + n``, shape ``(n, dim)``: of the initial states'
        stream, or with ``key`` of the stream of the parameter of that name (``"plant.isp"``).
        The memory the draws need is checked first: a MemoryError states it if it cannot fit."""
        owner = type(self).__name__
        n = integer("n", n, minimum=0, cap="max_cases", owner=owner)
        seed = integer("seed", seed, minimum=0, maximum=2**64 - 1, owner=owner)
        first_case = integer("first_case", first_case, minimum=0, maximum=2**64 - 1 - n, owner=owner)
        require_memory(f"{owner}.sample(n={n}): {n} x {self.dim} draws", 8 * n * self.dim)
        if key is not None and not isinstance(key, str):
            raise ParameterTypeError(f"{owner}.sample: key must be a parameter's name (a string) or None")
        return self._core.sample(seed, first_case, n, key)


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


@dataclass(frozen=True, eq=False)
class TruncatedNormal(Dispersion):
    """Normal(``mean``, ``std``) conditioned on ``[low, high]`` per component, drawn by inverting
    its distribution function (exact far in the tails). One-sided: give the other end far away
    (``high=1e300``). ``std = 0`` fixes the value at ``mean``, which must lie in the window."""

    mean: ArrayLike
    std: ArrayLike
    low: ArrayLike
    high: ArrayLike

    kind: ClassVar[str] = "truncated_normal"


@dataclass(frozen=True, eq=False)
class LogNormal(Dispersion):
    """``exp(N(mu, sigma))`` per component: positive, for a quantity dispersed by a factor
    (median ``exp(mu)``; numpy's ``lognormal(mu, sigma)`` and scipy's ``lognorm(s=sigma,
    scale=exp(mu))``)."""

    mu: ArrayLike
    sigma: ArrayLike

    kind: ClassVar[str] = "lognormal"
