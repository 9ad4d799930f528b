"""Monte Carlo campaigns: dispersions -> batched rollouts -> tables, statistics and checks."""

from __future__ import annotations

import sys
import warnings
from dataclasses import dataclass
from typing import Any, Optional

import numpy as np

from landing._progress import ProgressBar
from landing._args import boolean, integer
from landing._limits import require_memory
from landing.errors import DivergenceWarning, ParameterError
from landing.scenarios import Scenario
from landing.simulation import Metrics, SimulationResult

__all__ = ["MonteCarloResult", "Summary", "monte_carlo"]

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
    with a finite value), ``mean``, ``std``, ``min``, ``p50``, ``p95`` and ``max``."""

    def __str__(self) -> str:
        head = f"  {'metric':<22} {'n':>5} {'mean':>11} {'std':>11} {'min':>11} {'p50':>11} {'p95':>11} {'max':>11}"
        rows = [head]
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
    """Statistics over the cases with a finite value (a diverged case has NaN metrics)."""
    out = Summary()
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
class MonteCarloResult:
    """A campaign: the scenario, the sampled initial states, the recorded runs (decimated),
    the per-case metrics, their statistics and the theory's bounds with their checks."""

    scenario: Scenario
    seed: int
    x0: np.ndarray
    result: SimulationResult
    bounds: Any = None
    checks: Optional[dict] = None

    @property
    def n_cases(self) -> int:
        return self.x0.shape[0]

    @property
    def metrics(self) -> Metrics:
        return self.result.metrics

    @property
    def t(self) -> np.ndarray:
        return self.result.t

    @property
    def states(self) -> np.ndarray:
        return self.result.states

    @property
    def controls(self) -> np.ndarray:
        return self.result.controls

    @property
    def diagnostics(self) -> dict[str, np.ndarray]:
        return self.result.diagnostics

    def summary(self) -> Summary:
        return summarize(self.metrics)

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
            f"  diverged: {int(np.sum(m['diverged']))} of {n}",
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


def _concat(parts: list[SimulationResult]) -> SimulationResult:
    if len(parts) == 1:
        return parts[0]
    first = parts[0]
    return SimulationResult(
        t=first.t,
        states=np.concatenate([p.states for p in parts]),
        controls=np.concatenate([p.controls for p in parts]),
        final_state=np.concatenate([p.final_state for p in parts]),
        diagnostics={k: np.concatenate([p.diagnostics[k] for p in parts]) for k in first.diagnostics},
        metrics=Metrics({k: np.concatenate([p.metrics[k] for p in parts]) for k in first.metrics}),
        state_names=first.state_names,
        control_names=first.control_names,
    )


def campaign_bytes(scenario: Scenario, n: int, record_every: int, *, chunked: bool) -> int:
    """Bytes a campaign's results take: the recorded states, commands and diagnostics of the
    ``n`` cases plus their final states and metrics (twice when chunked: the chunks, then
    their concatenation). An estimate from above of what the batches allocate."""
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
    return 8 * n * per_case * (2 if chunked else 1)


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
    progress : show a progress bar (default: when stderr is a terminal and the campaign is
        long).
    check_bounds : check the run against the scenario's theoretical bounds, if any.
    """
    if not isinstance(scenario, Scenario):
        raise ParameterError(f"scenario must be a landing.scenarios.Scenario, got {type(scenario).__name__}")
    n = integer("n", n, minimum=1, cap="max_cases")
    seed = integer("seed", seed, minimum=0, maximum=2**64 - 1)
    if record_every is not None:
        record_every = integer("record_every", record_every, minimum=0, maximum=2**63 - 1)
    if chunk_size is not None:
        chunk_size = integer("chunk_size", chunk_size, minimum=1, cap="max_cases")
    if threads is not None:
        threads = integer("threads", threads, minimum=1, cap="max_threads")
    if progress is not None:
        progress = boolean("progress", progress)
    check_bounds = boolean("check_bounds", check_bounds)
    work = n * scenario.t_final / scenario.dt
    if progress is None:
        progress = sys.stderr.isatty() and work > 2e7
    if chunk_size is None:
        chunk_size = max(1, -(-n // 50)) if progress else n
    every = scenario.record_every if record_every is None else record_every
    # the chunks' recordings, then their concatenation: refused up front if they cannot fit
    require_memory(
        f"monte_carlo({scenario.name!r}, n={n}): the recorded runs",
        campaign_bytes(scenario, n, every, chunked=chunk_size < n),
    )

    x0 = scenario.initial_states(n, seed=seed)
    opts = scenario.run_options()
    if record_every is not None:
        opts["record_every"] = record_every
    bar = ProgressBar(n, label=scenario.name) if progress else None
    parts = []
    diverged_warnings = 0
    try:
        for start in range(0, n, chunk_size):
            stop = min(n, start + chunk_size)
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always", DivergenceWarning)
                parts.append(
                    scenario.simulate_batch(x0[start:stop], seed=seed, first_case=start, threads=threads, **opts)
                )
            diverged_warnings += sum(issubclass(w.category, DivergenceWarning) for w in caught)
            if bar:
                bar.update(stop - start)
    finally:
        if bar:
            bar.close()
    result = _concat(parts)
    diverged = np.flatnonzero(result.metrics["diverged"])
    if diverged.size:
        warnings.warn(
            f"{diverged.size} of {n} cases diverged (cases {diverged[:10].tolist()}); they are flagged in "
            "metrics['diverged']",
            DivergenceWarning,
            stacklevel=2,
        )
    bounds = scenario.bounds()
    checks = None
    if check_bounds and bounds is not None and result.t.size:
        from landing.theory import check_mss

        checks = check_mss(result, bounds)
    return MonteCarloResult(scenario=scenario, seed=seed, x0=x0, result=result, bounds=bounds, checks=checks)
