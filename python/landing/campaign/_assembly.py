"""How a campaign's chunks become its result, whoever runs them (this process or a Dask
cluster): the output allocated once and filled chunk by chunk, chunks read back from a store
or run and written to it, then the theory's bounds and their checks."""

from __future__ import annotations

import dataclasses
from collections.abc import Iterable
from typing import Callable, Optional

import numpy as np

from landing._internal.progress import ProgressBar
from landing.campaign.lazy import in_memory
from landing.campaign.result import MonteCarloResult
from landing.campaign.store import CampaignStore
from landing.errors import ParameterError
from landing.results import SimulationResult
from landing.scenarios import Scenario
from landing.theory import BoundCheck, MSSBounds, check_mss

__all__ = ["Assembly", "assemble_campaign", "check_in_slices", "finish_campaign", "write_chunk"]


class Assembly:
    """A campaign's output, allocated once (from the first chunk's shapes) and filled chunk
    by chunk: no list of parts, no concatenation of the whole at the end. Signals not kept are
    never allocated; with a store, no recorded signal is: each chunk's are in the store once
    written, and the result reads them from there on demand (:meth:`CampaignStore.signals`),
    so the campaign holds its final states and metrics only (``rows``: the campaign's cases
    the output holds, default all)."""

    def __init__(self, n: int, keep: tuple[str, ...], store: Optional[CampaignStore] = None,
                 rows: Optional[np.ndarray] = None):
        self.n = n
        self.keep = keep
        self.store = store
        self.rows = rows
        self.out: Optional[SimulationResult] = None

    def put(self, start: int, part: SimulationResult) -> None:
        part = part.keeping(self.keep if self.store is None else ())
        if self.out is None and start == 0 and part.n_cases == self.n:
            # one chunk is the whole campaign: its arrays are the output (copying them into a
            # fresh one touched every page of it again: 19 % of a 1000-case campaign recording
            # every 50 ms, BENCHMARKS.md)
            self.out = part
            return
        if self.out is None:
            self.out = SimulationResult.empty(self.n, like=part)
        self.out.put(start, part)

    def result(self) -> SimulationResult:
        assert self.out is not None
        return self.out if self.store is None else self.store.signals(self.out, self.rows)


def check_in_slices(result: SimulationResult, bounds: MSSBounds, step: int = 256) -> dict[str, BoundCheck]:
    """``theory.check_mss`` a slice of cases at a time (its temporaries are as large as the
    signals it reads: a slice keeps them small), the per-case arrays put back together."""
    n = result.n_cases
    sliding = result.keeping(("diagnostics",))  # what the check reads (a stored result's, read slice by slice)
    parts = [check_mss(in_memory(sliding.cases(a, min(n, a + step))), bounds) for a in range(0, n, step)]
    if len(parts) == 1:
        return parts[0]

    def cat(arrays: Iterable[np.ndarray]) -> np.ndarray:
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


def assemble_campaign(
    scenario: Scenario,
    *,
    n: int,
    seed: int,
    x0: np.ndarray,
    chunk_size: int,
    keep: tuple[str, ...],
    run_chunk: Optional[Callable[[int, int], SimulationResult]],
    store: Optional[CampaignStore],
    check_bounds: bool,
    bar: Optional[ProgressBar] = None,
) -> MonteCarloResult:
    """Chunk by chunk into the preallocated output: a chunk the store holds is read (and
    checked), any other is run (``run_chunk(start, stop)``) and, with a store, written to it
    as it completes; with a store each chunk's recorded signals are then dropped (the result
    reads them back from the store on demand)."""
    out = Assembly(n, keep, store)
    for index, start in enumerate(range(0, n, chunk_size)):
        stop = min(n, start + chunk_size)
        part: Optional[SimulationResult]
        if store is not None and run_chunk is None:
            part = store.read_chunk(index)  # load(): a damaged chunk is named, never filled
        else:
            part = None if store is None else store.resume_chunk(index)
        if part is None:
            if run_chunk is None:  # pragma: no cover - load() checks completeness first
                raise ParameterError(f"chunk {index} (cases {start}..{stop - 1}) is missing from the store")
            part = run_chunk(start, stop)
            if store is not None:
                write_chunk(store, scenario, seed, x0, index, start, stop, part)
            if bar:  # the cases computed now (a resumed campaign's bar counts only those)
                bar.update(stop - start)
        out.put(start, part)
        del part
    return finish_campaign(scenario, seed, x0, out.result(), keep, store, check_bounds)


def write_chunk(store: CampaignStore, scenario: Scenario, seed: int, x0: np.ndarray, index: int, start: int,
                stop: int, part: SimulationResult) -> None:
    """Chunk ``index`` (cases start..stop) into the store, with its initial states and the
    dispersion's draws behind them."""
    draws = None if scenario.dispersion is None else scenario.dispersion.sample(stop - start, seed=seed,
                                                                                 first_case=start)
    store.write_chunk(index, start, stop, part, x0[start:stop], draws)


def finish_campaign(scenario: Scenario, seed: int, x0: np.ndarray, result: SimulationResult,
                    keep: tuple[str, ...], store: Optional[CampaignStore], check_bounds: bool) -> MonteCarloResult:
    """The campaign's result from its assembled runs: the scenario's bounds and, when asked and
    the sliding variables were kept, the checks against them (the local and cluster paths)."""
    bounds = scenario.bounds()
    checks = None
    if check_bounds and bounds is not None and result.t.size and {"s1", "s2"} <= set(result.diagnostics):
        checks = check_in_slices(result, bounds)
    return MonteCarloResult(scenario=scenario, seed=seed, x0=x0, result=result, bounds=bounds, checks=checks,
                            keep=keep, store=None if store is None else str(store.path))
