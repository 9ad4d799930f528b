"""Monte Carlo campaigns: dispersions -> batched rollouts -> tables, statistics and checks."""

from __future__ import annotations

import dataclasses
import os
import warnings
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Callable, Optional, Sequence, Union

import numpy as np

from landing._internal.progress import ProgressBar
from landing._internal.args import boolean, integer
from landing._internal.limits import require_memory
from landing.errors import DivergenceWarning, ParameterError
from landing.scenarios import Scenario
from landing.results import Metrics, SimulationResult, describe_diverged, diverged_cases, result_dataset

if TYPE_CHECKING:  # pragma: no cover
    import xarray

    from landing.store import CampaignStore

__all__ = ["Bands", "MonteCarloResult", "Summary", "monte_carlo"]

#: What ``monte_carlo(..., keep=...)`` may keep (metrics and final states are always kept).
SIGNALS: tuple[str, ...] = ("states", "controls", "diagnostics")

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
    """Statistics of the per-case metrics: ``summary[column]`` is a dict with ``n`` (cases
    with a finite value), ``mean``, ``std``, ``min``, ``p50``, ``p95`` and ``max``.

    Diverged cases have NaN metrics and are left out of every statistic; ``diverged`` names
    them by reason (``{reason: case indices}``), and the printed table says so first."""

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
    """Statistics over the cases with a finite value (a diverged case has NaN metrics and is
    named in ``Summary.diverged``)."""
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
    """Percentiles of a recorded signal over the cases, at every recorded instant.

    ``values[k]`` is the ``percentiles[k]``-th percentile, shape (T,) or (T, D) for a per-axis
    signal; ``n`` (T,) counts the cases with a finite value at each instant (diverged cases are
    NaN from their divergence on and left out). ``bands[50]`` is the median."""

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
    """A campaign: the scenario, the sampled initial states, the recorded runs (decimated),
    the per-case metrics, their statistics and the theory's bounds with their checks."""

    scenario: Scenario
    seed: int
    x0: np.ndarray
    result: SimulationResult
    bounds: Any = None
    checks: Optional[dict] = None
    #: The recorded signals kept (``monte_carlo(..., keep=...)``).
    keep: tuple[str, ...] = SIGNALS
    #: The directory the campaign is stored in, if any.
    store: Optional[str] = None

    @property
    def n_cases(self) -> int:
        return self.x0.shape[0]

    @property
    def metrics(self) -> Metrics:
        """Per-case metrics; ``.to_pandas()`` adds the seed and the initial states."""
        return self.result.metrics._with_context(seed=self.seed, x0=self.x0)

    @property
    def t(self) -> np.ndarray:
        return self.result.t

    @property
    def states(self) -> Optional[np.ndarray]:
        return self.result.states

    @property
    def controls(self) -> Optional[np.ndarray]:
        return self.result.controls

    @property
    def diagnostics(self) -> dict[str, np.ndarray]:
        return self.result.diagnostics

    def summary(self) -> Summary:
        return summarize(self.metrics)

    def bands(self, signal: str, percentiles: Sequence[float] = (5, 50, 95)) -> Bands:
        """Per-instant percentiles over the cases of a recorded signal: a state or control
        component by name (``"rz"``, ``"Fz"``) or a diagnostic (``"s1"``, per axis). NaN-aware:
        a diverged case counts until it diverges."""
        pct = tuple(float(p) for p in percentiles)
        if not pct or not all(0.0 <= p <= 100.0 for p in pct):
            raise ParameterError(f"percentiles = {percentiles!r} violates 0 <= p <= 100 (at least one)")
        res = self.result
        if res.states is not None and signal in res.state_names:
            x = res.states[..., res.state_names.index(signal)]
        elif res.controls is not None and signal in res.control_names:
            x = res.controls[..., res.control_names.index(signal)]
        elif signal in res.diagnostics:
            x = res.diagnostics[signal]
        else:
            known = [*(res.state_names if res.states is not None else ()),
                     *(res.control_names if res.controls is not None else ()), *res.diagnostics]
            raise ParameterError(
                f"signal = {signal!r} is not a recorded signal of this campaign (kept: {self.keep}); "
                f"one of {known}"
            )
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)  # all-NaN instants give NaN
            values = np.nanpercentile(x, pct, axis=0)
        finite = np.isfinite(x)
        n = finite.reshape(finite.shape[0], finite.shape[1], -1).all(axis=2).sum(axis=0)
        return Bands(signal=signal, t=res.t, percentiles=pct, values=values, n=n)

    def to_xarray(self) -> "xarray.Dataset":
        """An xarray Dataset of the campaign: the kept signals (case, time, component), the
        final and initial states, every metric, with names, time (s) and units (see
        :meth:`SimulationResult.to_xarray`). Needs ``pip install "landing[io]"``."""
        return result_dataset(self.result, x0=self.x0, seed=self.seed,
                              attrs={"scenario": self.scenario.name, "keep": list(self.keep)})

    def within_bounds(self) -> Optional[np.ndarray]:
        """Per case: s1 and s2 stay in their theoretical neighbourhoods from the bound times
        on (None when the scenario has no bounds or nothing was recorded)."""
        if not self.checks:
            return None
        ok = np.ones(self.n_cases, dtype=bool)
        for check in self.checks.values():
            ok[check.violations] = False
        return ok

    def within_radius_at_end(self) -> Optional[np.ndarray]:
        """Per case: |s1_i(t_final)| (the position error) within the s1 neighbourhood."""
        if self.bounds is None:
            return None
        err = np.abs(self.metrics["final_error"])
        return np.all(err <= np.asarray(self.bounds.s1_radius), axis=-1)

    def report(self) -> str:
        m = self.metrics
        n = self.n_cases
        lines = [
            f"{self.scenario.name}: {n} cases, seed {self.seed}, {self.scenario.t_final:g} s at dt = "
            f"{self.scenario.dt:g} s ({self.scenario.integrator})",
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
        if self.bounds is not None:
            b = self.bounds
            lines.append("  theory (seed 001 Theorem 4), per axis:")
            lines.extend("    " + row for row in str(b).splitlines()[1:])
            end = self.within_radius_at_end()
            lines.append(f"  final position error within the s1 radius: {int(end.sum())} of {n}")
            if self.checks:
                for name, c in self.checks.items():
                    checkable = bool(np.all(c.extra["checkable"]))
                    stays = n - c.violations.size
                    note = "" if checkable else " (bound time beyond the horizon: only the end of the run is seen)"
                    lines.append(f"  {name} stays in its neighbourhood from its bound time on: {stays} of {n}{note}")
        return "\n".join(lines)


class _Assembly:
    """A campaign's output, allocated once (from the first chunk's shapes) and filled chunk
    by chunk: no list of parts, no concatenation of the whole at the end. Signals not kept are
    never allocated."""

    def __init__(self, n: int, keep: tuple[str, ...]):
        self.n = n
        self.keep = keep
        self.out: Optional[SimulationResult] = None

    def put(self, start: int, part: SimulationResult) -> None:
        part = part.keeping(self.keep)
        if self.out is None:
            self.out = SimulationResult.empty(self.n, like=part)
        self.out.put(start, part)

    def result(self) -> SimulationResult:
        assert self.out is not None
        return self.out


def _check_in_slices(result: SimulationResult, bounds: Any, step: int = 256) -> dict:
    """``theory.check_mss`` a slice of cases at a time (its temporaries are as large as the
    signals it reads: a slice keeps them small), the per-case arrays put back together."""
    from landing.theory import check_mss

    n = result.n_cases
    parts = [check_mss(result.cases(a, min(n, a + step)), bounds) for a in range(0, n, step)]
    if len(parts) == 1:
        return parts[0]

    def cat(arrays: Any) -> np.ndarray:
        return np.concatenate([np.asarray(x) for x in arrays])

    return {
        name: dataclasses.replace(
            first,
            bound=cat(p[name].bound for p in parts),
            measured=cat(p[name].measured for p in parts),
            extra={k: cat(p[name].extra[k] for p in parts) for k in first.extra},
        )
        for name, first in parts[0].items()
    }


def _keep(keep: Union[str, Sequence[str]]) -> tuple[str, ...]:
    items = (keep,) if isinstance(keep, str) else tuple(keep)
    bad = [k for k in items if k not in SIGNALS]
    if bad:
        raise ParameterError(f"keep = {keep!r}: {bad[0]!r} is not one of {SIGNALS}")
    return tuple(k for k in SIGNALS if k in items)  # canonical order, no repeats


def assemble_campaign(
    scenario: Scenario,
    *,
    n: int,
    seed: int,
    x0: np.ndarray,
    chunk_size: int,
    keep: tuple[str, ...],
    run_chunk: Optional[Callable[[int, int], SimulationResult]],
    store: Optional["CampaignStore"],
    check_bounds: bool,
    bar: Optional[ProgressBar] = None,
) -> MonteCarloResult:
    """Chunk by chunk into the preallocated output: a chunk the store holds is read, any other
    is run (``run_chunk(start, stop)``) and, with a store, written to it as it completes."""
    out = _Assembly(n, keep)
    for index, start in enumerate(range(0, n, chunk_size)):
        stop = min(n, start + chunk_size)
        if store is not None and store.is_complete(index):
            part = store.read_chunk(index)
        else:
            if run_chunk is None:  # pragma: no cover - load() checks completeness first
                raise ParameterError(f"chunk {index} (cases {start}..{stop - 1}) is missing from the store")
            part = run_chunk(start, stop)
            if store is not None:
                draws = (None if scenario.dispersion is None
                         else scenario.dispersion.sample(stop - start, seed=seed, first_case=start))
                store.write_chunk(index, start, stop, part, x0[start:stop], draws)
        out.put(start, part)
        del part
        if bar:
            bar.update(stop - start)
    return finish_campaign(scenario, seed, x0, out.result(), keep, store, check_bounds)


def finish_campaign(scenario: Scenario, seed: int, x0: np.ndarray, result: SimulationResult, keep: Any,
                    store: Any, check_bounds: bool) -> MonteCarloResult:
    """The campaign's result from its assembled runs: the scenario's bounds and, when asked and
    the sliding variables were kept, the checks against them (the local and cluster paths)."""
    bounds = scenario.bounds()
    checks = None
    if check_bounds and bounds is not None and result.t.size and {"s1", "s2"} <= set(result.diagnostics):
        checks = _check_in_slices(result, bounds)
    return MonteCarloResult(scenario=scenario, seed=seed, x0=x0, result=result, bounds=bounds, checks=checks,
                            keep=keep, store=None if store is None else str(store.path))


def campaign_bytes(scenario: Scenario, n: int, record_every: int, *, chunk: int) -> int:
    """Bytes a campaign's results take: the recorded states, commands and diagnostics of the
    ``n`` cases plus their final states and metrics, in the output allocated once, plus one
    chunk's batch output before it is copied in. An estimate from above."""
    steps = round(scenario.t_final / scenario.dt)
    if record_every == 0:
        instants = 0
    else:
        instants = steps // record_every + 1 + (steps % record_every != 0)
    axes = scenario.plant.axes
    widths = sum(w for _, w in scenario.controller._core.diagnostic_layout(axes))  # type: ignore[attr-defined]
    per_instant = scenario.plant.state_dim + axes + widths
    # final state plus about 40 metric columns, some per axis
    per_case = instants * per_instant + scenario.plant.state_dim + 40 * (axes + 1)
    return 8 * (n + (min(chunk, n) if chunk < n else 0)) * per_case


def monte_carlo(
    scenario: Scenario,
    n: int,
    *,
    seed: int = 0,
    record_every: Optional[int] = None,
    chunk_size: Optional[int] = None,
    threads: Optional[int] = None,
    progress: Optional[bool] = None,
    check_bounds: bool = True,
    keep: Union[str, Sequence[str]] = SIGNALS,
    store: Union[str, "os.PathLike[str]", None] = None,
    client: Any = None,
) -> MonteCarloResult:
    """Run ``n`` dispersed cases of ``scenario``.

    Case i's initial state and random disturbances depend only on (seed, i): the result is
    the same for any ``chunk_size`` (cases per batch) and thread count.

    Parameters
    ----------
    record_every : decimation of the kept trajectories (default: the scenario's); 0 keeps
        final states and metrics only.
    chunk_size : cases per batch (default: all at once, or about 2 % of them with a progress
        bar).
    progress : show progress on stderr, a bar in terminals and notebooks and a line every 30 s
        in logs (default: when the campaign is long, more than 2e7 case-steps).
    check_bounds : check the run against the scenario's theoretical bounds, if any (needs the
        diagnostics kept).
    keep : the recorded signals kept, among ``"states"``, ``"controls"`` and ``"diagnostics"``
        (default all); the others are dropped chunk by chunk. Metrics and final states are
        always kept. The output is allocated once and filled chunk by chunk.
    store : a directory to write the campaign to as each chunk completes (metrics, initial
        states and draws as Parquet, trajectories as Zarr, a provenance record; see
        :mod:`landing.store`), and to resume from: completed chunks are read back, not re-run,
        and the result is the uninterrupted run's bit for bit. A store of another campaign
        (scenario, seed, n, chunk_size, record settings) is refused. Without ``chunk_size`` a
        new store is cut into ``max(1000, n / 50)``-case chunks and a resumed one keeps its own.
        :func:`landing.load` reads it back. Needs ``pip install "landing[io]"``.
    client : a ``distributed.Client``: run the chunks on its Dask cluster, ``threads`` threads
        each on a worker (default: all the worker machine's cores), the store (if any) written
        by this process as chunks arrive. The result is the local run's bit for bit; a lost
        worker costs only its chunks, which are re-run; Ctrl-C cancels the outstanding chunks
        and keeps the completed ones in the store. Without ``chunk_size`` (and no store to
        resume) the chunks are of ``max(1000, n / 50)`` cases. See :mod:`landing.cluster` and
        docs/cluster.md. Needs ``pip install "landing[dask]"``.
    """
    chunk_given = chunk_size is not None
    if not isinstance(scenario, Scenario):
        raise ParameterError(f"scenario must be a landing.scenarios.Scenario, got {type(scenario).__name__}")
    n = integer("n", n, minimum=1, cap="max_cases")
    seed = integer("seed", seed, minimum=0, maximum=2**64 - 1)
    # the scenario's run options with this campaign's decimation and threads, checked once
    options = scenario.options.replace(
        threads=threads, **({} if record_every is None else {"record_every": record_every}))
    if chunk_size is not None:
        chunk_size = integer("chunk_size", chunk_size, minimum=1, cap="max_cases")
    if progress is not None:
        progress = boolean("progress", progress)
    check_bounds = boolean("check_bounds", check_bounds)
    if client is not None:
        from landing.cluster import check_client, default_chunk_size

        check_client(client)
        if chunk_size is None and store is None:
            chunk_size = default_chunk_size(n)
    work = n * scenario.t_final / scenario.dt
    if progress is None:
        # wherever stderr goes: a bar in terminals and notebooks, a line every 30 s in logs
        progress = work > 2e7
    if chunk_size is None:
        chunk_size = max(1, -(-n // 50)) if progress else n
    every, threads = options.record_every, options.threads
    # the campaign's output and one chunk's batch: refused up front if they cannot fit
    require_memory(
        f"monte_carlo({scenario.name!r}, n={n}): the recorded runs",
        campaign_bytes(scenario, n, every, chunk=chunk_size),
    )

    keep = _keep(keep)
    x0 = scenario.initial_states(n, seed=seed)
    campaign_store = None
    if store is not None:
        from landing.store import open_campaign_store

        campaign_store = open_campaign_store(
            store, scenario, seed=seed, n=n, x0=x0, keep=keep, record_every=every,
            chunk_size=chunk_size if chunk_given else None, threads=threads, check_bounds=check_bounds,
        )
        chunk_size = campaign_store.key.chunk_size
    bar = ProgressBar(n, label=scenario.name) if progress else None
    diverged_warnings = 0

    def run_chunk(start: int, stop: int) -> SimulationResult:
        nonlocal diverged_warnings
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always", DivergenceWarning)
            part = scenario.simulate_batch(x0[start:stop], seed=seed, first_case=start, threads=threads,
                                           record_every=every)
        diverged_warnings += sum(issubclass(w.category, DivergenceWarning) for w in caught)
        return part

    try:
        if client is not None:
            from landing.cluster import run_campaign

            mc = run_campaign(client, scenario, n=n, seed=seed, x0=x0, chunk_size=chunk_size, keep=keep,
                              record_every=every, threads=threads, store=campaign_store,
                              check_bounds=check_bounds, bar=bar)
        else:
            mc = assemble_campaign(scenario, n=n, seed=seed, x0=x0, chunk_size=chunk_size, keep=keep,
                                   run_chunk=run_chunk, store=campaign_store, check_bounds=check_bounds,
                                   bar=bar)
    finally:
        if bar:
            bar.close()
    if mc.metrics["diverged"].any():
        warnings.warn(
            f"{describe_diverged(mc.metrics)}; they are flagged in metrics['diverged'] (why: "
            "metrics['diverged_reason']) and left out of the summary's statistics",
            DivergenceWarning,
            stacklevel=2,
        )
    return mc
