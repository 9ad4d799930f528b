"""Which dispersed quantity drives a metric: rank correlations of a campaign's metrics with its
draws (Spearman's and the partial rank correlation, PRCC, which holds the other draws fixed),
and variance-based Sobol indices through SALib (the ``landing[sensitivity]`` extra) with its
sampling design run as one batch.

The dispersed quantities of a campaign are the components of its initial-state dispersion that
vary and its dispersed parameters (the metric columns ``param.<path>``, per component). A
per-axis metric or parameter counts per axis (``final_error_x``). Cases whose value is not finite (diverged,
no touchdown) are left out of each metric's correlations.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any, Optional

import numpy as np

from landing._internal.args import integer
from landing.dispersions import LogNormal, Normal, TruncatedNormal, Uniform
from landing.errors import ParameterError
from landing.results import SimulationResult
from landing.results import flat_columns as result_columns
from landing.scenarios import Scenario

__all__ = ["RankCorrelations", "SobolIndices", "flat_columns", "rank_correlations", "ranks", "sobol"]


def ranks(x: np.ndarray) -> np.ndarray:
    """Ranks 1..n of the values, ties given their average rank (as Spearman's coefficient takes
    them).

    Parameters
    ----------
    x : array_like
        The values, (n,), in any unit.

    Returns
    -------
    numpy.ndarray
        The ranks, (n,) floats.

    Examples
    --------
    >>> import numpy as np
    >>> from landing.campaign.sensitivity import ranks
    >>> ranks(np.array([3.0, 1.0, 3.0, 2.0]))
    array([3.5, 1. , 3.5, 2. ])
    """
    x = np.asarray(x, dtype=float)
    order = np.argsort(x, kind="stable")
    r = np.empty(x.size)
    r[order] = np.arange(1, x.size + 1)
    values, inverse, counts = np.unique(x, return_inverse=True, return_counts=True)
    if values.size < x.size:  # ties: the mean rank of each group
        sums = np.bincount(inverse, weights=r)
        r = (sums / counts)[inverse]
    return r


def flat_columns(columns: Mapping[str, Any], axis_names: Sequence[str]) -> dict[str, np.ndarray]:
    """The real-valued per-case columns, a per-axis one split into ``name_<axis>`` as the store
    writes them (:func:`landing.results.flat_columns`); the flag and the divergence reason's code
    are left out.

    Parameters
    ----------
    columns : mapping of str to array_like
        Per-case columns, (N,) or (N, axes), in their units.
    axis_names : sequence of str
        The axes' names (``("x", "y", "z")``).

    Returns
    -------
    dict of str to numpy.ndarray
        The float columns, each (N,), units unchanged.

    Examples
    --------
    >>> import numpy as np
    >>> from landing.campaign.sensitivity import flat_columns
    >>> cols = {"final_error": np.zeros((2, 3)), "fuel_used": np.ones(2), "diverged": np.zeros(2, bool)}
    >>> sorted(flat_columns(cols, ("x", "y", "z")))
    ['final_error_x', 'final_error_y', 'final_error_z', 'fuel_used']
    """
    return {k: v for k, v in result_columns(columns, axis_names).items() if v.dtype.kind == "f"}


@dataclass(frozen=True)
class RankCorrelations:
    """Rank correlations of each metric (rows, ``outputs``) with each dispersed quantity (columns,
    ``inputs``): ``spearman`` and ``prcc`` (partial rank correlation), ``n`` the cases each
    metric's row used. Made by :func:`rank_correlations` (:meth:`MonteCarloResult.sensitivity`).

    Parameters
    ----------
    inputs : tuple of str
        The dispersed quantities (``x0_<state>``, ``param.<path>``).
    outputs : tuple of str
        The metrics.
    spearman, prcc : numpy.ndarray
        The correlations, (outputs, inputs), dimensionless, -1 to 1 (NaN: too few cases).
    n : numpy.ndarray
        The cases each metric's row used, (outputs,).

    Examples
    --------
    >>> import landing
    >>> from landing.dispersions import Normal
    >>> scenario = landing.scenarios.preset("mars_monte_carlo").replace(t_final=5.0)
    >>> mc = landing.monte_carlo(scenario.disperse({"plant.isp": Normal(225.0, 5.0)}), n=40, seed=1)
    >>> corr = mc.sensitivity(["fuel_used"])
    >>> corr.prcc.shape, corr.inputs[-1]
    ((1, 8), 'param.plant.isp')
    >>> print(corr)
      fuel_used                x0_vy +0.96, x0_ry +0.78, param.plant.isp -0.72
    """

    inputs: tuple[str, ...]
    outputs: tuple[str, ...]
    spearman: np.ndarray
    prcc: np.ndarray
    n: np.ndarray

    def drivers(self, metric: str, k: int = 3) -> list[tuple[str, float, float]]:
        """The ``k`` quantities with the largest |PRCC| for ``metric``: (name, PRCC, Spearman).

        Parameters
        ----------
        metric : str
            One of :attr:`outputs`.
        k : int, default 3
            How many.

        Returns
        -------
        list of tuple
            ``(name, prcc, spearman)``, the strongest first.
        """
        if metric not in self.outputs:
            raise ParameterError(f"metric = {metric!r} is not one of {self.outputs}")
        i = self.outputs.index(metric)
        order = np.argsort(-np.nan_to_num(np.abs(self.prcc[i]), nan=-1.0), kind="stable")[:k]
        return [(self.inputs[j], float(self.prcc[i, j]), float(self.spearman[i, j])) for j in order]

    def to_pandas(self) -> Any:
        """Both tables as one pandas DataFrame (metric, quantity) x (spearman, prcc).

        Returns
        -------
        pandas.DataFrame
            One row per (metric, quantity).
        """
        import pandas as pd  # noqa: PLC0415 - the io extra, on demand

        idx = pd.MultiIndex.from_product([self.outputs, self.inputs], names=["metric", "quantity"])
        return pd.DataFrame({"spearman": self.spearman.reshape(-1), "prcc": self.prcc.reshape(-1)}, index=idx)

    def __str__(self) -> str:
        lines = []
        for m in self.outputs:
            top = ", ".join(f"{name} {p:+.2f}" for name, p, _ in self.drivers(m, 3))
            lines.append(f"  {m:<24} {top}")
        return "\n".join(lines)


def _partial_rank(R: np.ndarray, y: np.ndarray) -> np.ndarray:
    """PRCC of ranked output ``y`` with each ranked input column of ``R``: the correlation of
    the residuals of both after a linear fit on the other inputs (and a constant)."""
    n, p = R.shape
    out = np.full(p, np.nan)
    ones = np.ones((n, 1))
    for j in range(p):
        others = np.hstack([ones, np.delete(R, j, axis=1)])
        rx = R[:, j] - others @ np.linalg.lstsq(others, R[:, j], rcond=None)[0]
        ry = y - others @ np.linalg.lstsq(others, y, rcond=None)[0]
        d = np.sqrt((rx @ rx) * (ry @ ry))
        out[j] = (rx @ ry) / d if d > 0 else np.nan
    return out


def _pearson(a: np.ndarray, b: np.ndarray) -> float:
    a, b = a - a.mean(), b - b.mean()
    d = np.sqrt((a @ a) * (b @ b))
    return float(a @ b / d) if d > 0 else float("nan")


def dispersed_quantities(result: SimulationResult, x0: np.ndarray) -> dict[str, np.ndarray]:
    """A campaign's dispersed quantities per case, from its runs and initial states ``x0``: the
    initial-state components that vary (``x0_<state>``) and the dispersed parameters' draws
    (``param.<path>``, per component)."""
    out = {f"x0_{name}": x0[:, j] for j, name in enumerate(result.state_names) if np.ptp(x0[:, j]) > 0}
    params = {k: v for k, v in result.metrics.items() if k.startswith("param.")}
    out.update(flat_columns(params, result.axis_names))
    return out


def rank_correlations(result: SimulationResult, x0: np.ndarray,
                      metrics: Optional[Sequence[str]] = None) -> RankCorrelations:
    """Spearman's and the partial rank correlation of each metric of a campaign's runs ``result``
    (default: every numeric metric that varies, per axis split; ``param.*`` columns are inputs,
    not metrics) with each of its dispersed quantities (its initial states ``x0`` and its
    parameters' draws): what :meth:`MonteCarloResult.sensitivity
    <landing.MonteCarloResult.sensitivity>` gives.

    Parameters
    ----------
    result : landing.SimulationResult
        The campaign's runs (their metrics and draws).
    x0 : numpy.ndarray
        The campaign's initial states, (N, state_dim) (m, m/s, kg).
    metrics : sequence of str, optional
        The metric columns (per-axis ones split).

    Returns
    -------
    RankCorrelations
        The correlations, dimensionless.

    Examples
    --------
    >>> import landing
    >>> from landing.dispersions import Normal
    >>> scenario = landing.scenarios.preset("mars_monte_carlo").replace(t_final=5.0)
    >>> mc = landing.monte_carlo(scenario.disperse({"plant.isp": Normal(225.0, 5.0)}), n=40, seed=1)
    >>> from landing.campaign.sensitivity import rank_correlations
    >>> corr = rank_correlations(mc.result, mc.x0, ["fuel_used"])
    >>> name, prcc, spearman = corr.drivers("fuel_used", 1)[0]
    >>> name, round(prcc, 2)
    ('x0_vy', 0.96)
    """
    inputs = dispersed_quantities(result, np.asarray(x0, dtype=float))
    if not inputs:
        raise ParameterError("the campaign disperses nothing: no quantity to correlate the metrics with")
    cols = flat_columns({k: v for k, v in result.metrics.items() if not k.startswith("param.")},
                        result.axis_names)
    names = list(metrics) if metrics is not None else [
        k for k, v in cols.items() if np.isfinite(v).sum() > 2 and np.nanstd(v) > 0]
    unknown = [m for m in names if m not in cols]
    if unknown:
        raise ParameterError(f"metrics: {unknown[0]!r} is not one of {sorted(cols)}")
    X = np.column_stack(list(inputs.values()))
    sp = np.full((len(names), X.shape[1]), np.nan)
    pr = np.full_like(sp, np.nan)
    counts = np.zeros(len(names), dtype=int)
    for i, m in enumerate(names):
        ok = np.isfinite(cols[m])
        counts[i] = int(ok.sum())
        if counts[i] <= X.shape[1] + 1:
            continue  # fewer cases than the fit needs
        R = np.column_stack([ranks(c) for c in X[ok].T])
        y = ranks(cols[m][ok])
        sp[i] = [_pearson(R[:, j], y) for j in range(R.shape[1])]
        pr[i] = _partial_rank(R, y)
    return RankCorrelations(tuple(inputs), tuple(names), sp, pr, counts)


# --- Sobol indices ---------------------------------------------------------------------------


def _salib_variable(d: Any, j: int) -> tuple[str, list[float]]:
    """SALib's distribution and its parameters for component ``j`` of a dispersion."""
    def pick(v: Any) -> float:
        a = np.atleast_1d(np.asarray(v, dtype=float))
        return float(a[j if a.size > 1 else 0])

    if isinstance(d, Uniform):
        return "unif", [pick(d.low), pick(d.high)]
    if isinstance(d, TruncatedNormal):
        return "truncnorm", [pick(d.low), pick(d.high), pick(d.mean), pick(d.std)]
    if isinstance(d, Normal):
        return "norm", [pick(d.mean), pick(d.std)]
    if isinstance(d, LogNormal):
        return "lognorm", [pick(d.mu), pick(d.sigma)]
    raise ParameterError(f"{type(d).__name__} has no SALib counterpart")  # pragma: no cover


@dataclass(frozen=True)
class SobolIndices:
    """First-order (``S1``) and total (``ST``) Sobol indices of ``metric`` for each variable (a
    dispersed parameter's component), with SALib's confidence half-widths, from ``n`` model runs.
    Made by :func:`sobol`.

    Parameters
    ----------
    metric : str
        The metric analysed.
    names : tuple of str
        The variables (``path`` or ``path[j]``).
    S1, S1_conf, ST, ST_conf : numpy.ndarray
        The indices and their confidence half-widths (dimensionless), one per variable.
    n : int
        The model runs.

    Examples
    --------
    >>> import numpy as np
    >>> from landing.campaign import SobolIndices
    >>> s = SobolIndices("fuel_used", ("plant.isp",), np.array([0.9]), np.array([0.1]), np.array([1.0]),
    ...                  np.array([0.1]), 48)
    >>> print(s)
      Sobol indices of fuel_used (48 runs):  S1 (+-), ST (+-)
        plant.isp                         0.900 (0.100)   1.000 (0.100)
    """

    metric: str
    names: tuple[str, ...]
    S1: np.ndarray
    S1_conf: np.ndarray
    ST: np.ndarray
    ST_conf: np.ndarray
    n: int

    def __str__(self) -> str:
        rows = [f"  Sobol indices of {self.metric} ({self.n} runs):  S1 (+-), ST (+-)"]
        rows += [f"    {name:<32} {s1:6.3f} ({c1:.3f})  {st:6.3f} ({ct:.3f})"
                 for name, s1, c1, st, ct in zip(self.names, self.S1, self.S1_conf, self.ST, self.ST_conf)]
        return "\n".join(rows)


def sobol(scenario: Scenario, metric: str, n: int = 512, *, seed: int = 0, threads: Optional[int] = None,
          calc_second_order: bool = False) -> SobolIndices:
    """Sobol indices of ``metric`` for the scenario's dispersed parameters
    (:meth:`Scenario.disperse`), each component one variable of SALib's Saltelli-Sobol design of
    ``n`` base samples (a power of 2): the design's rows are run as one batch from the nominal
    initial state, each row's parameters given per case, then analysed by SALib. The random
    disturbances, if any, differ from row to row (their stream is keyed by the row) and add their
    variance to what no variable explains. Needs ``pip install "landing[sensitivity]"``.

    Parameters
    ----------
    scenario : landing.scenarios.Scenario
        A scenario with dispersed parameters.
    metric : str
        The metric column (per-axis ones split, e.g. ``"final_error_x"``).
    n : int, default 512
        The design's base samples (a power of 2).
    seed : int, default 0
        The design's and the runs' seed.
    threads : int, optional
        Threads of the batch.
    calc_second_order : bool, default False
        Whether SALib computes second-order indices too (more runs).

    Returns
    -------
    SobolIndices
        The indices (dimensionless) per variable.

    Examples
    --------
    >>> import landing
    >>> from landing.dispersions import Normal
    >>> from landing.campaign import sobol
    >>> scenario = landing.scenarios.preset("mars_monte_carlo").replace(t_final=2.0)
    >>> s = sobol(scenario.disperse({"plant.isp": Normal(225.0, 5.0)}), "fuel_used", n=16)
    >>> s.names, s.n
    (('plant.isp',), 48)
    """
    try:
        from SALib.analyze import sobol as analyze  # noqa: PLC0415 - the sensitivity extra, on demand
        from SALib.sample import sobol as sample  # noqa: PLC0415
    except ImportError:  # pragma: no cover - depends on the installation
        raise ImportError('landing.campaign.sobol needs SALib: pip install "landing[sensitivity]"') from None
    n = integer("n", n, minimum=2)
    if not scenario.dispersions:
        raise ParameterError(f"scenario {scenario.name!r} disperses no parameter (Scenario.disperse)")
    variables = []  # (path, component, dists, bounds)
    for path, d in scenario.dispersions.items():
        for j in range(d.dim):
            dist, bounds = _salib_variable(d, j)
            variables.append((path, j, dist, bounds, f"{path}[{j}]" if d.dim > 1 else path))
    names = [v[4] for v in variables]
    problem = {"num_vars": len(variables), "names": names,
               "bounds": [v[3] for v in variables], "dists": [v[2] for v in variables]}
    design = sample.sample(problem, n, calc_second_order=calc_second_order, seed=seed)
    draws: dict[str, np.ndarray] = {}
    for col, (path, j, *_rest) in enumerate(variables):
        k = scenario.dispersions[path].dim
        draws.setdefault(path, np.zeros((design.shape[0], k)))[:, j] = design[:, col]
    runs = design.shape[0]
    x0 = np.tile(np.asarray(scenario.x0, dtype=float), (runs, 1))
    result = scenario.with_draws(draws).simulate_batch(x0, seed=seed, threads=threads, record_every=0)
    cols = flat_columns(result.metrics, result.axis_names)
    if metric not in cols:
        raise ParameterError(f"metric = {metric!r} is not one of {sorted(cols)}")
    y = cols[metric]
    if not np.all(np.isfinite(y)):
        raise ParameterError(f"{int(np.sum(~np.isfinite(y)))} of the {runs} design runs give no finite {metric}: "
                             "Sobol indices need every run's value")
    s = analyze.analyze(problem, y, calc_second_order=calc_second_order, seed=seed)
    return SobolIndices(metric, tuple(names), np.asarray(s["S1"]), np.asarray(s["S1_conf"]),
                        np.asarray(s["ST"]), np.asarray(s["ST_conf"]), runs)
