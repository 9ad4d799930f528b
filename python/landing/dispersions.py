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
    one per axis: independent draws). A scalar field serves every component.

    Parameters
    ----------
    **fields : ArrayLike
        The subclass's fields (see each one), each a scalar or one value per component, in
        the units of the component.

    Examples
    --------
    >>> from landing.dispersions import Normal
    >>> x = Normal(mean=[0.0, 1.0], std=[1.0, 0.0]).sample(2, seed=1)
    >>> for row in x:
    ...     print(" ".join(f"{v:.3f}" for v in row))
    -0.439 1.000
    -0.786 1.000
    """

    family: ClassVar[str] = "dispersion"

    @staticmethod
    def _compiler(owner: str, table: dict) -> _core.DispersionHandle:
        return _core.DispersionHandle(table)

    @property
    def dim(self) -> int:
        """Number of components drawn per case (1 when every field is a scalar)."""
        return int(self._core.dim)

    def sample(self, n: int, seed: int = 0, first_case: int = 0, key: Optional[str] = None) -> np.ndarray:
        """Cases ``first_case .. first_case + n``, shape ``(n, dim)``: of the initial states'
        stream, or with ``key`` of the stream of the parameter of that name (``"plant.isp"``).
        The memory the draws need is checked first: a MemoryError states it if it cannot fit.

        The draws depend only on ``seed``, the case index and ``key``.

        Parameters
        ----------
        n : int
            Number of cases, >= 0.
        seed : int
            Seed of the campaign, 0 to 2^64 - 1 (default 0).
        first_case : int
            Index of the first case (default 0).
        key : str or None
            Name of the dispersed parameter whose stream to draw from, such as
            ``"plant.isp"``; None (default) for the initial states' stream.

        Returns
        -------
        numpy.ndarray
            The draws, shape ``(n, dim)``, in the units of the components.

        Raises
        ------
        ParameterError
            If ``n``, ``seed`` or ``first_case`` is out of range.
        ParameterTypeError
            If ``key`` is neither a string nor None.
        MemoryError
            If the draws cannot fit in memory.

        Examples
        --------
        >>> d = Uniform(low=[0.0, 0.0, 0.0], high=[1.0, 2.0, 3.0])
        >>> x = d.sample(2, seed=7)
        >>> x.shape
        (2, 3)
        >>> bool((d.sample(1, seed=7, first_case=1) == x[1:]).all())
        True
        """
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
    """Normal per component (the Mars fixed-time guidance paper, Table II). A zero standard
    deviation fixes the value.

    Parameters
    ----------
    mean : ArrayLike
        Mean of each component (a scalar for all), in its units.
    std : ArrayLike
        Standard deviation of each component, in its units; std >= 0 (0 fixes the value).

    Examples
    --------
    >>> x = Normal(mean=[0.0, 1.0], std=[1.0, 0.0]).sample(2, seed=1)
    >>> print(" ".join(f"{v:.3f}" for v in x[:, 0]), x[0, 1])
    -0.439 -0.786 1.0
    """

    mean: ArrayLike
    std: ArrayLike

    kind: ClassVar[str] = "normal"


@dataclass(frozen=True, eq=False)
class Uniform(Dispersion):
    """Uniform on ``[low, high]`` per component (the Mars fixed-time guidance paper,
    Table III). ``low == high`` fixes the value.

    Parameters
    ----------
    low : ArrayLike
        Lower end of each component's range, in its units.
    high : ArrayLike
        Upper end of each component's range, in its units; high >= low.

    Examples
    --------
    >>> x = Uniform(low=[0.0, 0.0, 0.0], high=[1.0, 2.0, 3.0]).sample(2, seed=7)
    >>> print(" ".join(f"{v:.3f}" for v in x[0]))
    0.901 1.555 2.894
    """

    low: ArrayLike
    high: ArrayLike

    kind: ClassVar[str] = "uniform"


@dataclass(frozen=True, eq=False)
class TruncatedNormal(Dispersion):
    """Normal(``mean``, ``std``) conditioned on ``[low, high]`` per component, drawn by inverting
    its distribution function (exact far in the tails). One-sided: give the other end far away
    (``high=1e300``). ``std = 0`` fixes the value at ``mean``, which must lie in the window.

    Parameters
    ----------
    mean : ArrayLike
        Mean of the untruncated normal of each component, in its units.
    std : ArrayLike
        Its standard deviation, in the units of the component; std >= 0.
    low : ArrayLike
        Lower end of each component's range, in its units.
    high : ArrayLike
        Upper end of each component's range, in its units; high >= low.

    Examples
    --------
    >>> x = TruncatedNormal(mean=0.0, std=1.0, low=-0.5, high=0.5).sample(3, seed=2)
    >>> print(" ".join(f"{v:.3f}" for v in x[:, 0]))
    0.371 0.475 -0.085
    """

    mean: ArrayLike
    std: ArrayLike
    low: ArrayLike
    high: ArrayLike

    kind: ClassVar[str] = "truncated_normal"


@dataclass(frozen=True, eq=False)
class LogNormal(Dispersion):
    """``exp(N(mu, sigma))`` per component: positive, for a quantity dispersed by a factor
    (median ``exp(mu)``; numpy's ``lognormal(mu, sigma)`` and scipy's ``lognorm(s=sigma,
    scale=exp(mu))``).

    Parameters
    ----------
    mu : ArrayLike
        Mean of the logarithm of each component (in the log of its units).
    sigma : ArrayLike
        Standard deviation of the logarithm, dimensionless; sigma >= 0 (0 fixes the value at
        ``exp(mu)``).

    Examples
    --------
    >>> x = LogNormal(mu=0.0, sigma=0.1).sample(3, seed=1, key="plant.isp")
    >>> print(" ".join(f"{v:.3f}" for v in x[:, 0]))
    1.104 1.008 1.014
    """

    mu: ArrayLike
    sigma: ArrayLike

    kind: ClassVar[str] = "lognormal"
