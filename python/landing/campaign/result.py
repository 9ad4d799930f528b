"""A Monte Carlo campaign's result: the runs, the statistics of their metrics, per-instant
bands of their signals and the theory's bounds with their checks."""

from __future__ import annotations

import warnings
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Optional

import numpy as np

from landing._internal.args import integer
from landing.campaign.lazy import stored_dataset
from landing.campaign.sensitivity import RankCorrelations, dispersed_quantities, flat_columns, rank_correlations
from landing.campaign.verify import Verification, tolerance_bound, verify
from landing.errors import ParameterError, ParameterTypeError
from landing.results import SIGNALS, Metrics, SimulationResult, describe_diverged, diverged_cases
from landing.scenarios import Scenario
from landing.theory import BoundCheck, MSSBounds

if TYPE_CHECKING:  # pragma: no cover
    import xarray

__all__ = ["Bands", "MonteCarloResult", "Summary", "summarize", "SUMMARY_COLUMNS"]

#: The most bytes of a signal :meth:`MonteCarloResult.bands` reads at a time (a block of instants).
BANDS_BLOCK_BYTES = 2**27

#: The per-case columns the summary describes.
SUMMARY_COLUMNS = (
    "final_position_error",
    "final_velocity_error",
    "fuel_used",
    "fuel_to_settle",
    "peak_command",
    "control_effort",
    "settle_time",
    "touchdown_time",
    "touchdown_speed",
)


class Summary(dict):
    """Statistics of the per-case metrics: ``summary[column]`` is a dict with ``n`` (cases with a
    finite value), ``mean``, ``std``, ``min``, ``p50``, ``p95`` and ``max``, in the metric's unit
    (m, m/s, s, kg, N...).

    Diverged cases have NaN metrics and are left out of every statistic; ``diverged`` names them
    by reason (``{reason: case indices}``), and the printed table says so first. Made by
    :func:`summarize` (``MonteCarloResult.summary()``).

    Parameters
    ----------
    *args, **kwargs
        As :class:`dict` takes them: ``{column: statistics}``.
    diverged : dict of str to numpy.ndarray, optional
        The diverged cases' indices by reason.

    Examples
    --------
    >>> from landing.campaign.result import Summary
    >>> s = Summary({"fuel_used": {"n": 0}})
    >>> s.diverged, s["fuel_used"]["n"]
    ({}, 0)
    """

    diverged: dict[str, np.ndarray]

    def __init__(self, *args: Any, diverged: Optional[dict[str, np.ndarray]] = None, **kwargs: Any):
        super().__init__(*args, **kwargs)
        self.diverged = diverged or {}

    def __str__(self) -> str:
        head = f"  {'metric':<22} {'n':>5} {'mean':>11} {'std':>11} {'min':>11} {'p50':>11} {'p95':>11} {'max':>11}"
        rows = []
        if self.diverged:
            k = sum(v.size for v in self.diverged.values())
            rows.append(
                f"  left out of the statistics: {k} diverged case{'s' if k != 1 else ''} ("
                + "; ".join(f"{name}: {v.size}" for name, v in self.diverged.items()) + ")"
            )
        rows.append(head)
        for k, s in self.items():
            if s["n"] == 0:
                rows.append(f"  {k:<22} {0:>5}")
                continue
            rows.append(
                f"  {k:<22} {s['n']:>5} "
                + " ".join(f"{s[x]:>11.5g}" for x in ("mean", "std", "min", "p50", "p95", "max"))
            )
        return "\n".join(rows)


def summarize(metrics: Metrics, columns: tuple[str, ...] = SUMMARY_COLUMNS) -> Summary:
    """Statistics over the cases with a finite value (a diverged case has NaN metrics and is named in
    ``Summary.diverged``).

    Parameters
    ----------
    metrics : landing.Metrics
        The per-case metrics.
    columns : tuple of str, default SUMMARY_COLUMNS
        The scalar metrics described.

    Returns
    -------
    Summary
        ``{column: {"n", "mean", "std", "min", "p50", "p95", "max"}}`` in each metric's unit.

    Examples
    --------
    >>> import landing
    >>> scenario = landing.scenarios.preset("mars_monte_carlo").replace(t_final=5.0)
    >>> mc = landing.monte_carlo(scenario, n=8, seed=1)
    >>> from landing.campaign.result import summarize
    >>> s = summarize(mc.metrics, ("fuel_used",))
    >>> s["fuel_used"]["n"], f"{s['fuel_used']['max']:.2f} kg"
    (8, '67.46 kg')
    """
    out = Summary(diverged=diverged_cases(metrics))
    for k in columns:
        v = np.asarray(metrics[k], dtype=float)
        v = v[np.isfinite(v)]
        if v.size == 0:
            out[k] = {"n": 0}
            continue
        out[k] = {
            "n": int(v.size),
            "mean": float(v.mean()),
            "std": float(v.std(ddof=1)) if v.size > 1 else 0.0,
            "min": float(v.min()),
            "p50": float(np.percentile(v, 50)),
            "p95": float(np.percentile(v, 95)),
            "max": float(v.max()),
        }
    return out


@dataclass(frozen=True, eq=False)
class Bands:
    """Percentiles of a recorded signal over the cases, at every recorded instant. Made by
    :meth:`MonteCarloResult.bands`.

    ``values[k]`` is the ``percentiles[k]``-th percentile, shape (T,) or (T, D) for a per-axis
    signal; ``n`` (T,) counts the cases with a finite value at each instant (diverged cases are
    NaN from their divergence on and left out). ``bands[50]`` is the median.

    Parameters
    ----------
    signal : str
        The signal's name (e.g. ``"rz"``, ``"Fz"``, ``"s1"``).
    t : numpy.ndarray
        The recorded instants (s), (T,).
    percentiles : tuple of float
        The percentiles, 0 to 100.
    values : numpy.ndarray
        The percentiles' values in the signal's unit (m, m/s, N...), (P, T) or (P, T, D).
    n : numpy.ndarray
        The cases counted at each instant, (T,).

    Examples
    --------
    >>> import landing
    >>> scenario = landing.scenarios.preset("mars_monte_carlo").replace(t_final=5.0)
    >>> mc = landing.monte_carlo(scenario, n=8, seed=1)
    >>> b = mc.bands("rz")
    >>> b.percentiles, b[50].shape, int(b.n[0])
    ((5.0, 50.0, 95.0), (101,), 8)
    """

    signal: str
    t: np.ndarray
    percentiles: tuple[float, ...]
    values: np.ndarray
    n: np.ndarray

    def __getitem__(self, percentile: float) -> np.ndarray:
        try:
            return self.values[self.percentiles.index(percentile)]
        except ValueError:
            raise KeyError(f"percentile {percentile!r} not among {self.percentiles}") from None


@dataclass(frozen=True, eq=False)
class MonteCarloResult:
    """A campaign: the scenario, the sampled initial states, the recorded runs (decimated), the
    per-case metrics, their statistics and the theory's bounds with their checks. Made by
    :func:`landing.monte_carlo` and :func:`landing.load`.

    A stored campaign's (``monte_carlo(..., store=...)``, ``landing.load``) recorded signals stay
    in its store: ``result`` is a :class:`~landing.campaign.lazy.StoredResult` whose states,
    controls and diagnostics are read-only :class:`~landing.campaign.lazy.StoredArray` views,
    read on demand (``np.asarray(mc.states)`` reads them all).

    Parameters
    ----------
    scenario : landing.scenarios.Scenario
        The campaign's scenario.
    seed : int
        The campaign's seed.
    x0 : numpy.ndarray
        The sampled initial states, (N, state_dim) (m, m/s, kg as the plant has them).
    result : landing.SimulationResult
        The runs, the case axis first.
    bounds : landing.theory.MSSBounds, optional
        The scenario's theoretical bounds (s, m/s, m).
    checks : dict of str to landing.theory.BoundCheck, optional
        The runs checked against them.
    keep : tuple of str, default all
        The recorded signals kept (``monte_carlo(..., keep=...)``).
    store : str, optional
        The directory the campaign is stored in, if any.
    cases : numpy.ndarray, optional
        The campaign's case index of each row, when this is part of a campaign (a partial store's
        completed cases, ``landing.load(path, partial=True)``); None when the rows are cases
        0..n-1.
    planned : int, optional
        The number of cases the campaign was planned with, when this is part of it.

    Examples
    --------
    >>> import landing
    >>> scenario = landing.scenarios.preset("mars_monte_carlo").replace(t_final=5.0)
    >>> mc = landing.monte_carlo(scenario, n=8, seed=1)
    >>> len(mc), float(mc.t[-1]), mc.metrics["fuel_used"].shape
    (8, 5.0, (8,))
    >>> print(mc)  # doctest: +ELLIPSIS
    <landing.MonteCarloResult: mars_monte_carlo, 8 cases, seed 1>
      recorded: states, controls, diagnostics at 101 instants, 0 .. 5 s
      dispersed: initial states
    ...
    """

    scenario: Scenario
    seed: int
    x0: np.ndarray
    result: SimulationResult
    bounds: Optional[MSSBounds] = None
    checks: Optional[dict[str, BoundCheck]] = None
    #: The recorded signals kept (``monte_carlo(..., keep=...)``).
    keep: tuple[str, ...] = SIGNALS
    #: The directory the campaign is stored in, if any.
    store: Optional[str] = None
    #: The campaign's case index of each row, when this is part of a campaign (a partial store's
    #: completed cases, ``landing.load(path, partial=True)``); None when the rows are cases 0..n-1.
    cases: Optional[np.ndarray] = None
    #: The number of cases the campaign was planned with, when this is part of it.
    planned: Optional[int] = None

    @property
    def partial(self) -> bool:
        """Whether this holds only some of the campaign's cases (an interrupted store's)."""
        return self.cases is not None

    def case_index(self, row: int) -> int:
        """The campaign's index of row ``row`` (the same unless :attr:`partial`).

        Parameters
        ----------
        row : int
            A row of this result (negative counts from the end).

        Returns
        -------
        int
            The case's index in the campaign.
        """
        row = integer("case", row, minimum=-self.n_cases, maximum=self.n_cases - 1)
        row %= self.n_cases
        return int(self.cases[row]) if self.cases is not None else row

    def __len__(self) -> int:
        return self.n_cases

    def __repr__(self) -> str:
        """A short description (the scenario, the sizes, what was kept and dispersed, the
        summary table), not the arrays: ``print(mc)``, ``mc`` in a notebook; ``mc.report()``
        says more."""
        res = self.result
        of = f" of {self.planned} planned (partial)" if self.partial else ""
        where = f", stored in '{self.store}'" if self.store else ""
        lines = [f"<landing.MonteCarloResult: {self.scenario.name}, {self.n_cases} cases{of}, seed {self.seed}{where}>"]
        if res.t.size:
            kept = ", ".join(self.keep) if self.keep else "nothing"
            lines.append(f"  recorded: {kept} at {res.t.size} instants, {res.t[0]:.6g} .. {res.t[-1]:.6g} s")
        else:
            lines.append("  recorded: final states and metrics only")
        draws = [k[len("param."):] for k in self.metrics if k.startswith("param.")]
        dispersed = ["initial states"] * (self.scenario.dispersion is not None) + draws
        lines.append(f"  dispersed: {', '.join(dispersed) if dispersed else 'nothing'}")
        lines += str(self.summary()).splitlines()
        return "\n".join(lines)

    def __getitem__(self, case: int) -> SimulationResult:
        """Row ``case`` (case ``case`` of the campaign unless :attr:`partial`) alone, its
        recorded signals and metrics, the case axis dropped."""
        if isinstance(case, (bool, np.bool_)) or not isinstance(case, (int, np.integer)):
            raise ParameterTypeError(f"a campaign is indexed by a case number, got {type(case).__name__} "
                                     "(several cases: mc.result.cases(a, b))")
        self.case_index(int(case))  # the range check
        return self.result[int(case)]

    def worst(self, metric: str, k: int = 5, *, largest: bool = True) -> np.ndarray:
        """The rows of the ``k`` worst cases by the scalar ``metric``, worst first: the largest values
        (``largest=False``: the smallest), a case whose value is NaN (diverged, no event) before any
        finite one. Index the campaign with them (``mc[i]``) or re-run them (:meth:`rerun`).

        Parameters
        ----------
        metric : str
            A scalar metric's name (e.g. ``"touchdown_speed"``, m/s; ``"fuel_used"``, kg).
        k : int, default 5
            How many cases.
        largest : bool, default True
            Whether the largest values are the worst.

        Returns
        -------
        numpy.ndarray
            The rows, (k,) (fewer when the campaign has fewer cases).

        Examples
        --------
        >>> import landing
        >>> scenario = landing.scenarios.preset("mars_monte_carlo").replace(t_final=5.0)
        >>> mc = landing.monte_carlo(scenario, n=8, seed=1)
        >>> mc.worst("fuel_used", 3)
        array([5, 3, 0])
        """
        if metric not in self.metrics:
            raise ParameterError(f"metric = {metric!r} is not one of the campaign's metrics ({sorted(self.metrics)})")
        v = np.asarray(self.metrics[metric], dtype=float)
        if v.ndim != 1:
            raise ParameterError(f"metric = {metric!r} is per axis; rank the cases by a scalar metric")
        k = integer("k", k, minimum=0)
        key = np.where(np.isnan(v), -np.inf, -v if largest else v)  # NaN first, then worst first
        return np.argsort(key, kind="stable")[:k]

    def rerun(self, case: int, **overrides: Any) -> SimulationResult:
        """Row ``case`` simulated again, alone, as the campaign ran it (its initial state, its rows of
        the parameters given per case, its draws of the dispersed ones and of the random
        disturbances): bit for bit the campaign's case, with other run options if given, such as
        ``record_every=1`` to record every instant of a failed case.

        Parameters
        ----------
        case : int
            The row to re-run.
        **overrides
            Run options (``record_every``, ``threads``...), as :meth:`Scenario.simulate_cases`
            takes them.

        Returns
        -------
        landing.SimulationResult
            The case's run, a batch of one.

        Examples
        --------
        >>> import landing
        >>> scenario = landing.scenarios.preset("mars_monte_carlo").replace(t_final=5.0)
        >>> mc = landing.monte_carlo(scenario, n=8, seed=1)
        >>> r = mc.rerun(0)
        >>> bool(r.metrics["fuel_used"][0] == mc.metrics["fuel_used"][0])
        True
        """
        i = self.case_index(case)
        row = int(case) % self.n_cases
        n = self.planned if self.planned is not None else self.n_cases
        return self.scenario.simulate_cases(self.x0[row:row + 1], i, n, seed=self.seed, **overrides)

    @property
    def n_cases(self) -> int:
        """The number of cases (rows) this result holds."""
        return self.x0.shape[0]

    @property
    def metrics(self) -> Metrics:
        """Per-case metrics (m, m/s, s, kg...); ``.to_pandas()`` adds the seed and the initial states."""
        return self.result.metrics._with_context(seed=self.seed, x0=self.x0)

    @property
    def t(self) -> np.ndarray:
        """The recorded instants (s), (T,)."""
        return self.result.t

    @property
    def states(self) -> Optional[np.ndarray]:
        """The recorded states, (N, T, state_dim) (m, m/s, kg; None when not kept)."""
        return self.result.states

    @property
    def controls(self) -> Optional[np.ndarray]:
        """The recorded commands, (N, T, axes) (N; None when not kept)."""
        return self.result.controls

    @property
    def diagnostics(self) -> dict[str, np.ndarray]:
        """The law's recorded diagnostics by name (e.g. s1 in m, s2 in m/s), each (N, T, ...)."""
        return self.result.diagnostics

    def summary(self) -> Summary:
        """Statistics of the per-case metrics (:func:`summarize`).

        Returns
        -------
        Summary
            ``{column: {"n", "mean", "std", "min", "p50", "p95", "max"}}`` in each metric's unit.
        """
        return summarize(self.metrics)

    def sensitivity(self, metrics: Optional[Sequence[str]] = None) -> RankCorrelations:
        """Spearman's and the partial rank correlation of each metric (default: every one that varies,
        per axis split) with each dispersed quantity (the initial-state components that vary, the
        dispersed parameters): :func:`landing.campaign.sensitivity.rank_correlations`;
        ``landing.plots.tornado(mc, metric)`` draws one metric's.

        Parameters
        ----------
        metrics : sequence of str, optional
            The metric columns (per-axis ones split, e.g. ``"touchdown_position_x"``).

        Returns
        -------
        RankCorrelations
            The correlations (dimensionless, -1 to 1) and their p-values.
        """
        return rank_correlations(self.result, self.x0, metrics)

    def verify(self, requirement: str, p: float = 0.9973, confidence: float = 0.9) -> Verification:
        """The requirement checked case by case, and whether the campaign shows it met for at least
        ``p`` of cases with ``confidence`` (Clopper-Pearson; :mod:`landing.campaign.verify`):
        ``mc.verify("touchdown_speed <= 1 and max(abs(touchdown_position)) <= 5")`` (m/s, m) in the
        grammar of the tuner's expressions, each case's pass or fail (``and``, ``or``, ``not``; an
        aggregate reduces the case's own axes). A case with a NaN metric (diverged, never touched
        down) fails.

        Parameters
        ----------
        requirement : str
            The requirement, in the metrics' units (m, m/s, s, kg).
        p : float, default 0.9973
            The share of cases it must hold for (0 < p < 1).
        confidence : float, default 0.9
            The confidence of the statement (0 < confidence < 1).

        Returns
        -------
        Verification
            Each case's pass or fail, the lower confidence bound and whether ``p`` is shown.

        Examples
        --------
        >>> import landing
        >>> scenario = landing.scenarios.preset("mars_monte_carlo").replace(t_final=5.0)
        >>> mc = landing.monte_carlo(scenario, n=8, seed=1)
        >>> v = mc.verify("final_position_error <= 3000")
        >>> print(v)
        requirement 'final_position_error <= 3000': 8 of 8 cases pass (100 %);
        at 90 % confidence at least 74.99 % of cases meet it
        (Clopper-Pearson)
          not shown: at least 99.73 % with 90 % confidence (852 cases without a failure would show it)
        """
        return verify(self.metrics, requirement, p, confidence)

    def tolerance_bound(self, metric: str, p: float = 0.9973, confidence: float = 0.9,
                        side: str = "upper") -> float:
        """A value of ``metric`` that at least ``p`` of cases stay below (``side="upper"``) or above
        (``"lower"``) with ``confidence``: the order statistic of Wilks' distribution-free bound
        (:func:`landing.campaign.verify.tolerance_bound`). A per-axis metric is refused: give a scalar
        one.

        Parameters
        ----------
        metric : str
            A scalar metric's name.
        p : float, default 0.9973
            The share of cases (0 < p < 1).
        confidence : float, default 0.9
            The confidence (0 < confidence < 1).
        side : {"upper", "lower"}, default "upper"
            Which bound.

        Returns
        -------
        float
            The bound, in the metric's unit (NaN when the campaign has too few cases for it).

        Examples
        --------
        >>> import landing
        >>> scenario = landing.scenarios.preset("mars_monte_carlo").replace(t_final=5.0)
        >>> mc = landing.monte_carlo(scenario, n=8, seed=1)
        >>> print(f"{mc.tolerance_bound('fuel_used', p=0.5, confidence=0.5):.2f} kg")
        62.08 kg
        """
        if metric not in self.metrics:
            raise ParameterError(f"metric = {metric!r} is not one of the campaign's metrics ({sorted(self.metrics)})")
        values = np.asarray(self.metrics[metric], dtype=float)
        if values.ndim != 1:
            raise ParameterError(f"metric = {metric!r} is per axis; a tolerance bound takes a scalar metric")
        return tolerance_bound(values, p, confidence, side)

    def bands(self, signal: str, percentiles: Sequence[float] = (5, 50, 95)) -> Bands:
        """Per-instant percentiles over the cases of a recorded signal: a state or control component by
        name (``"rz"``, ``"Fz"``) or a diagnostic (``"s1"``, per axis). NaN-aware: a diverged case
        counts until it diverges. Computed over blocks of instants of at most
        :data:`BANDS_BLOCK_BYTES` of the signal (a stored campaign's read from its store block by
        block).

        Parameters
        ----------
        signal : str
            The signal's name.
        percentiles : sequence of float, default (5, 50, 95)
            The percentiles, 0 to 100.

        Returns
        -------
        Bands
            The percentiles at each recorded instant, in the signal's unit (m, m/s, kg, N...).
        """
        pct = tuple(float(p) for p in percentiles)
        if not pct or not all(0.0 <= p <= 100.0 for p in pct):
            raise ParameterError(f"percentiles = {percentiles!r} violates 0 <= p <= 100 (at least one)")
        res = self.result
        signal_array: Any
        component: tuple[int, ...] = ()
        if res.states is not None and signal in res.state_names:
            signal_array, component = res.states, (res.state_names.index(signal),)
        elif res.controls is not None and signal in res.control_names:
            signal_array, component = res.controls, (res.control_names.index(signal),)
        elif signal in res.diagnostics:
            signal_array = res.diagnostics[signal]
        else:
            known = [*(res.state_names if res.states is not None else ()),
                     *(res.control_names if res.controls is not None else ()), *res.diagnostics]
            raise ParameterError(
                f"signal = {signal!r} is not a recorded signal of this campaign (kept: {self.keep}); "
                f"one of {known}"
            )
        # over blocks of instants, each read whole (of a stored campaign: from its store), at most
        # BANDS_BLOCK_BYTES of the signal at a time; each instant's percentiles are its own
        cases, instants = signal_array.shape[:2]
        width = 1 if component else int(np.prod(signal_array.shape[2:], dtype=np.int64))
        step = max(1, BANDS_BLOCK_BYTES // max(1, 8 * cases * width))
        values = np.empty((len(pct), instants) + (() if component else signal_array.shape[2:]))
        n = np.empty(instants, dtype=np.int64)
        for a in range(0, instants, step):
            b = min(instants, a + step)
            x = np.asarray(signal_array[(slice(None), slice(a, b)) + component])
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", RuntimeWarning)  # all-NaN instants give NaN
                values[:, a:b] = np.nanpercentile(x, pct, axis=0)
            finite = np.isfinite(x)
            n[a:b] = finite.reshape(finite.shape[0], finite.shape[1], -1).all(axis=2).sum(axis=0)
        return Bands(signal=signal, t=res.t, percentiles=pct, values=values, n=n)

    def to_xarray(self) -> xarray.Dataset:
        """An xarray Dataset of the campaign: the kept signals (case, time, component), the final and
        initial states, every metric, with names, time (s) and units (see
        :meth:`SimulationResult.to_xarray`). Needs ``pip install "landing[io]"``.

        Returns
        -------
        xarray.Dataset
            The campaign's data, with units in each variable's attributes.

        Examples
        --------
        >>> import landing
        >>> scenario = landing.scenarios.preset("mars_monte_carlo").replace(t_final=5.0)
        >>> mc = landing.monte_carlo(scenario, n=8, seed=1)
        >>> ds = mc.to_xarray()
        >>> ds.sizes["case"], ds["time"].attrs["units"]
        (8, 's')
        """
        return stored_dataset(self.result, x0=self.x0, seed=self.seed,
                              attrs={"scenario": self.scenario.name, "keep": list(self.keep)})

    def within_bounds(self) -> Optional[np.ndarray]:
        """Per case: s1 and s2 stay in their theoretical neighbourhoods from the bound times on.

        Returns
        -------
        numpy.ndarray or None
            (N,) booleans; None when the scenario has no bounds or nothing was recorded.
        """
        if not self.checks:
            return None
        ok = np.ones(self.n_cases, dtype=bool)
        for check in self.checks.values():
            ok[check.violations] = False
        return ok

    def within_radius_at_end(self) -> Optional[np.ndarray]:
        """Per case: |s1_i(t_final)| (the position error, m) within the s1 neighbourhood.

        Returns
        -------
        numpy.ndarray or None
            (N,) booleans; None when the scenario has no bounds.
        """
        if self.bounds is None:
            return None
        err = np.abs(self.metrics["final_error"])
        return np.all(err <= np.asarray(self.bounds.s1_radius), axis=-1)

    @staticmethod
    def _informative(radius: np.ndarray, errors: np.ndarray) -> str:
        """A note for a check that cannot fail: a radius ten times (or more) the largest error
        it is checked against, on every axis, says nothing about the errors."""
        largest = np.nanmax(errors, axis=0) if errors.size else np.zeros(1)
        ratio = float(np.min(np.asarray(radius) / np.maximum(largest, 1e-300)))
        if ratio < 10:
            return ""
        return (f" (not informative: the radius is {ratio:.0f} times the largest error, "
                f"{float(np.max(largest)):.4g} m)")

    def _driver_lines(self) -> list[str]:
        """The summary metrics' three strongest drivers among the dispersed quantities (partial
        rank correlations), when the campaign has enough cases to tell."""
        if self.n_cases < 30:
            return []
        cols = flat_columns(self.metrics, self.result.axis_names)
        shown = [m for m, v in cols.items() if (m in SUMMARY_COLUMNS or m.startswith("touchdown_position_"))
                 and np.isfinite(v).sum() > 2 and np.nanstd(v) > 0]
        if not shown or not dispersed_quantities(self.result, self.x0):
            return []
        corr = self.sensitivity(shown)
        lines = ["  what drives the metrics (partial rank correlation with the dispersed quantities; "
                 "mc.sensitivity()):"]
        for m in shown:
            lines.append(f"    {m:<24} " + ", ".join(f"{name} {p:+.2f}" for name, p, _ in corr.drivers(m, 3)))
        return lines

    def _dispersed_lines(self) -> list[str]:
        """The dispersed parameters: each one's dispersion and the statistics of its draws
        (the metric columns ``param.<path>``; per axis, each axis)."""
        if not self.scenario.dispersions:
            return []
        lines = ["  dispersed parameters (their draws: mean, std, min, max):"]
        for name, d in self.scenario.dispersions.items():
            v = np.asarray(self.metrics[f"param.{name}"], dtype=float)
            cols = v.reshape(len(v), -1).T
            stats = "; ".join(f"{c.mean():.6g}, {c.std(ddof=1) if c.size > 1 else 0.0:.6g}, {c.min():.6g}, "
                              f"{c.max():.6g}" for c in cols)
            lines.append(f"    {name} ~ {d!r}: {stats}")
        return lines

    def report(self, requirement: Optional[str] = None, p: float = 0.9973, confidence: float = 0.9) -> str:
        """The campaign in words: its statistics, landings, dispersed parameters, the theory's checks,
        and with ``requirement`` its verification (:meth:`verify`). A statistic of no undiverged case
        reads nan, without numpy's warnings about empty slices.

        Parameters
        ----------
        requirement : str, optional
            A requirement to verify, as :meth:`verify` takes it.
        p, confidence : float
            As :meth:`verify` takes them.

        Returns
        -------
        str
            The report, several lines.

        Examples
        --------
        >>> import landing
        >>> scenario = landing.scenarios.preset("mars_monte_carlo").replace(t_final=5.0)
        >>> mc = landing.monte_carlo(scenario, n=8, seed=1)
        >>> print(mc.report().splitlines()[0])
        mars_monte_carlo: 8 cases, seed 1, 5 s at dt = 0.001 s (rk4)
        """
        with warnings.catch_warnings():
            warnings.filterwarnings("ignore", "All-NaN slice|Mean of empty slice|invalid value encountered",
                                    RuntimeWarning)
            return self._report(requirement, p, confidence)

    def _report(self, requirement: Optional[str], p: float, confidence: float) -> str:
        m = self.metrics
        n = self.n_cases
        lines = [
            f"{self.scenario.name}: {n} cases, seed {self.seed}, {self.scenario.t_final:g} s at dt = "
            f"{self.scenario.dt:g} s ({self.scenario.integrator})",
            *([f"  partial: {n} of the campaign's {self.planned} cases (its completed chunks; resume it with "
               f"monte_carlo(..., store={self.store!r}))"] if self.partial else []),
            f"  diverged: {describe_diverged(m)}",
            str(self.summary()),
        ]
        fe = np.abs(m["final_error"])
        lines.append(
            "  final |error| per axis: max " + np.array2string(np.nanmax(fe, axis=0), precision=4)
            + ", mean " + np.array2string(np.nanmean(fe, axis=0), precision=4)
        )
        touched = np.isfinite(m["touchdown_time"])
        lines.append(f"  touched down (rz crossed 0): {int(touched.sum())} of {n}")
        lines.extend(self._dispersed_lines())
        lines.extend(self._driver_lines())
        if requirement is not None:
            lines.extend("  " + row for row in str(self.verify(requirement, p, confidence)).splitlines())
        if self.bounds is not None:
            b = self.bounds
            lines.append("  theory (the Mars fixed-time guidance paper's Theorem 4), per axis:")
            lines.extend("    " + row for row in str(b).splitlines()[1:])
            end = self.within_radius_at_end()
            assert end is not None  # the bounds are known
            lines.append(f"  final position error within the s1 radius: {int(end.sum())} of {n}"
                         + self._informative(np.asarray(b.s1_radius, dtype=float),
                                             np.abs(np.asarray(self.metrics["final_error"], dtype=float))))
            if self.checks:
                for name, c in self.checks.items():
                    what = f"  {name} stays in its neighbourhood from its bound time on: "
                    if bool(np.all(c.extra["checkable"])):
                        lines.append(f"{what}{n - c.violations.size} of {n}")
                    else:
                        # a bound time beyond the run leaves nothing to check: no count that
                        # reads as a pass
                        lines.append(f"{what}not informative (the bound time, {float(np.nanmax(c.bound)):.4g} s, "
                                     f"is beyond the run's {float(self.scenario.t_final):.4g} s)")
        return "\n".join(lines)
