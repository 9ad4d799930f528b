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
from landing.results import SIGNALS, SimulationResult
from landing.scenarios import Scenario
from landing.theory import BoundCheck, MSSBounds, check_mss

#: Cases a campaign's first chunk runs alone (:meth:`Assembly.probe`): a few blocks of lanes.
PROBE_CASES = 64

__all__ = ["Assembly", "assemble_campaign", "check_in_slices", "finish_campaign", "write_chunk"]


class Assembly:
    """A campaign's output, allocated once (from the first chunk's shapes) and filled chunk
    by chunk: no list of parts, no concatenation of the whole at the end. Once it is allocated,
    each later chunk's recording is written by the core straight into the chunk's rows of it
    (:meth:`destination`), so that its pages are faulted in once, by the pool's threads, and
    never copied (recording every 50 ms cost a 20,000-case campaign a third of its time with
    each chunk's fresh arrays copied in, a sixth written in place: BENCHMARKS.md). Signals not kept are never allocated;
    with a store, no recorded signal is: each chunk's are in the store once written, and the
    result reads them from there on demand (:meth:`CampaignStore.signals`), so the campaign
    holds its final states and metrics only (``rows``: the campaign's cases the output holds,
    default all)."""

    def __init__(self, n: int, keep: tuple[str, ...], store: Optional[CampaignStore] = None,
                 rows: Optional[np.ndarray] = None):
        self.n = n
        self.keep = keep
        self.store = store
        self.rows = rows
        self.out: Optional[SimulationResult] = None
        # the output's recording as the core writes it (states, controls, every diagnostic
        # side by side), when the output holds all of it
        self._recording: Optional[tuple[np.ndarray, np.ndarray, np.ndarray]] = None

    def destination(self, start: int, stop: int) -> Optional[tuple[np.ndarray, np.ndarray, np.ndarray]]:
        """The arrays cases ``start .. stop``'s recording is to be written into (rows of the
        output's), or None when the chunk records into its own (the first chunk, a store,
        signals not kept)."""
        if self._recording is None:
            return None
        return (self._recording[0][start:stop], self._recording[1][start:stop], self._recording[2][start:stop])

    def probe(self, start: int, stop: int) -> int:
        """Where cases ``start .. stop`` split when the first of them are to run alone before the
        rest (``start``: no split): the first chunk of a campaign in memory that keeps every
        recorded signal runs its first :data:`PROBE_CASES` cases alone, so that the output is
        allocated from their shapes and every later case is lent its rows."""
        lends = self.out is None and self.store is None and set(SIGNALS) <= set(self.keep)
        if not lends or start != 0 or stop - start >= self.n or stop - start <= PROBE_CASES:
            return start
        return min(stop, start + PROBE_CASES)

    def put(self, start: int, part: SimulationResult) -> None:
        part = part.keeping(self.keep if self.store is None else ())
        if self.out is None and start == 0 and part.n_cases == self.n:
            # one chunk is the whole campaign: its arrays are the output (copying them into a
            # fresh one touched every page of it again: 19 % of a 1000-case campaign recording
            # every 50 ms, BENCHMARKS.md)
            self.out = part
            return
        if self.out is None:
            self.out = self._allocate(part)
        # a chunk written into its destination holds views of the output: put skips them
        self.out.put(start, part)

    def _allocate(self, like: SimulationResult) -> SimulationResult:
        """The output of ``self.n`` cases shaped like the batch ``like``: its recording laid out
        as the core writes it when every recorded signal is kept (so later chunks can be lent
        it), else :meth:`SimulationResult.empty`."""
        if like.states is None or like.controls is None or like.t.size == 0 or \
                not set(SIGNALS) <= set(self.keep) or self.store is not None:
            return SimulationResult.empty(self.n, like=like)
        out = SimulationResult.empty(self.n, like=like.keeping(()))
        widths = [v.shape[2] if v.ndim == 3 else 1 for v in like.diagnostics.values()]
        states = np.empty((self.n,) + like.states.shape[1:])
        controls = np.empty((self.n,) + like.controls.shape[1:])
        block = np.empty((self.n, like.t.size, sum(widths)))
        diagnostics = {}
        offset = 0
        for (name, v), width in zip(like.diagnostics.items(), widths):
            diagnostics[name] = block[:, :, offset:offset + width] if v.ndim == 3 else block[:, :, offset]
            offset += width
        self._recording = (states, controls, block)
        return dataclasses.replace(out, states=states, controls=controls, diagnostics=diagnostics)

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
    run_chunk: Optional[Callable[[int, int, Optional[tuple[np.ndarray, np.ndarray, np.ndarray]]], SimulationResult]],
    store: Optional[CampaignStore],
    check_bounds: bool,
    bar: Optional[ProgressBar] = None,
) -> MonteCarloResult:
    """Chunk by chunk into the preallocated output: a chunk the store holds is read (and
    checked), any other is run (``run_chunk(start, stop, into)``, ``into`` the arrays its
    recording is to be written into, or None: :meth:`Assembly.destination`) and, with a store, written to it
    as it completes; with a store each chunk's recorded signals are then dropped (the result
    reads them back from the store on demand)."""
    out = Assembly(n, keep, store)
    for index, start in enumerate(range(0, n, chunk_size)):
        stop = min(n, start + chunk_size)
        part: Optional[SimulationResult]
        start_part = start
        if store is not None and run_chunk is None:
            part = store.read_chunk(index)  # load(): a damaged chunk is named, never filled
        else:
            part = None if store is None else store.resume_chunk(index)
        if part is None:
            if run_chunk is None:  # pragma: no cover - load() checks completeness first
                raise ParameterError(f"chunk {index} (cases {start}..{stop - 1}) is missing from the store")
            head = out.probe(start, stop)
            if head > start:
                # the first cases alone, so that the output is allocated from their shapes and the
                # rest of the chunk is lent its rows too (the copy of a whole first chunk was 1.9 %
                # of a 6000-case campaign's samples, BENCHMARKS.md)
                out.put(start, run_chunk(start, head, None))
            part = run_chunk(head, stop, out.destination(head, stop))
            start_part = head
            if store is not None:
                write_chunk(store, scenario, seed, x0, index, start, stop, part)
            if bar:  # the cases computed now (a resumed campaign's bar counts only those)
                bar.update(stop - start)
        out.put(start_part, part)
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
