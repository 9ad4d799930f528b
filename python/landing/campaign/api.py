"""Monte Carlo campaigns: dispersions -> batched rollouts -> tables, statistics and checks;
:func:`monte_carlo` runs one (here or on a Dask cluster, into a store or not) and :func:`load`
reads a stored one back."""

from __future__ import annotations

import dataclasses
import os
import warnings
from collections.abc import Sequence
from typing import Any, Optional, Union

import numpy as np

from landing._internal.args import boolean, integer, short
from landing._internal.limits import available_memory, format_bytes, require_memory
from landing._internal.progress import ProgressBar
from landing.campaign._assembly import Assembly, assemble_campaign, finish_campaign
from landing.campaign.result import MonteCarloResult
from landing.campaign.store import (
    CampaignStore,
    default_chunk_size,
    open_campaign_store,
    read_campaign_store,
    store_chunk_size,
)
from landing.errors import DivergenceWarning, ParameterError, ParameterTypeError
from landing.results import SIGNALS, SimulationResult, describe_diverged
from landing.scenarios import Scenario

__all__ = ["campaign_bytes", "load", "monte_carlo"]


def _keep(keep: Union[str, Sequence[str]]) -> tuple[str, ...]:
    if not isinstance(keep, (str, Sequence, np.ndarray)) or not all(isinstance(k, str) for k in keep):
        raise ParameterTypeError(f"keep must be a signal's name or a sequence of them, among {SIGNALS}, "
                                 f"got {short(keep)}")
    items = (keep,) if isinstance(keep, str) else tuple(keep)
    bad = [k for k in items if k not in SIGNALS]
    if bad:
        raise ParameterError(f"keep = {keep!r}: {bad[0]!r} is not one of {SIGNALS}")
    return tuple(k for k in SIGNALS if k in items)  # canonical order, no repeats


def campaign_bytes(scenario: Scenario, n: int, record_every: int, *, chunk: int,
                   keep: Sequence[str] = SIGNALS, stored: bool = False) -> int:
    """Bytes a campaign's results take in memory: the kept recorded signals (states, commands,
    diagnostics) of the ``n`` cases plus their final states and metrics, in the output allocated
    once, plus one chunk's batch output (every signal) before it is copied in. A campaign written
    to a store (``stored``) holds no recorded signal (they are in the store, read back on demand):
    its final states and metrics, and two chunks' batch output (the one written and what the
    store's writer and reader hold of it). An estimate from above.

    Parameters
    ----------
    scenario : landing.scenarios.Scenario
        The campaign's scenario (its ``t_final`` and ``dt`` in s, plant and law).
    n : int
        The number of cases.
    record_every : int
        The decimation of the recorded signals (0: final states and metrics only).
    chunk : int
        Cases per batch.
    keep : sequence of str, default all
        The recorded signals kept, among ``"states"``, ``"controls"``, ``"diagnostics"``.
    stored : bool, default False
        Whether the campaign is written to a store.

    Returns
    -------
    int
        The estimate, in bytes.

    Examples
    --------
    >>> import landing
    >>> from landing.campaign.api import campaign_bytes
    >>> scenario = landing.scenarios.preset("mars_monte_carlo").replace(t_final=5.0)
    >>> full = campaign_bytes(scenario, 100, 50, chunk=100)
    >>> metrics_only = campaign_bytes(scenario, 100, 0, chunk=100, keep=())
    >>> metrics_only < full
    True
    """
    steps = round(scenario.t_final / scenario.dt)
    if record_every == 0:
        instants = 0
    else:
        instants = steps // record_every + 1 + (steps % record_every != 0)
    axes = scenario.plant.axes
    widths = sum(w for _, w in scenario.controller.diagnostic_layout(axes))
    sizes = {"states": scenario.plant.state_dim, "controls": axes, "diagnostics": widths}
    # final state plus about 40 metric columns, some per axis, and the dispersed parameters
    fixed = scenario.plant.state_dim + 40 * (axes + 1) + len(scenario.dispersions) * axes
    kept = (0 if stored else instants * sum(v for k, v in sizes.items() if k in keep)) + fixed
    batch = instants * sum(sizes.values()) + fixed
    if stored:
        return 8 * (n * kept + 2 * min(chunk, n) * batch)
    # one chunk holding every case and every signal is the output itself; otherwise a chunk's
    # batch lives beside the output it is copied into
    whole = chunk >= n and set(keep) >= set(SIGNALS)
    return 8 * (n * kept + (0 if whole else min(chunk, n) * batch))


def _what_fits(scenario: Scenario, n: int, every: int, chunk: int, keep: tuple[str, ...], stored: bool) -> str:
    """The options that would fit in the memory available, for the refusal's message."""
    free = available_memory() or 0
    steps = max(1, round(scenario.t_final / scenario.dt))
    options = []
    for k in sorted({every * f for f in (2, 5, 10, 100, 1000) if every} | {steps}):
        size = campaign_bytes(scenario, n, k, chunk=chunk, keep=keep, stored=stored)
        if size <= free:
            options.append(f"record_every={k} ({format_bytes(size)} in all)")
            break
    for fewer in (("states",), ()):
        if set(fewer) < set(keep) and campaign_bytes(scenario, n, every, chunk=chunk, keep=fewer,
                                                     stored=stored) <= free:
            options.append(f"keep={fewer!r}")
            break
    if campaign_bytes(scenario, n, 0, chunk=chunk, keep=(), stored=stored) <= free:
        options.append("record_every=0 (final states and metrics only)")
    if not stored:
        size = campaign_bytes(scenario, n, every, chunk=default_chunk_size(n), keep=keep, stored=True)
        if size <= free:
            options.append(f"store=DIR (the recorded signals written to disk and read back on demand: "
                           f"{format_bytes(size)} in memory)")
    return f"what fits: {'; '.join(options)}; or fewer cases" if options else "ask for fewer cases"


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
    store: Union[str, os.PathLike[str], None] = None,
    client: Any = None,
) -> MonteCarloResult:
    """Run ``n`` dispersed cases of ``scenario``.

    Case i's initial state and random disturbances depend only on (seed, i): the result is the
    same for any ``chunk_size`` (cases per batch) and thread count.

    A parameter of the plant, law, reference or disturbance given per case has one row per case
    of the campaign (``n`` rows; another number is refused, naming it); each chunk runs its own
    rows (:meth:`Scenario.cases`), so the result does not depend on the chunking. A dispersed
    parameter (:meth:`Scenario.disperse`) is drawn for each chunk's cases from a stream keyed by
    (seed, case, its path), and recorded as the metric column ``param.<path>``
    (:meth:`Scenario.simulate_cases`).

    Parameters
    ----------
    scenario : landing.scenarios.Scenario
        What each case runs (plant, law, dispersions, ``t_final`` and ``dt`` in s).
    n : int
        The number of cases.
    seed : int, default 0
        The campaign's seed (0 to 2^64 - 1).
    record_every : int, optional
        Decimation of the kept trajectories (default: the scenario's); 0 keeps final states and
        metrics only.
    chunk_size : int, optional
        Cases per batch (default: all at once, or ``max(1000, n / 50)`` with a progress bar, as
        for a store; smaller chunks leave threads idle at each chunk's end).
    threads : int, optional
        Threads of the batch (default: all cores).
    progress : bool, optional
        Show progress on stderr, a bar in terminals and notebooks and a line every 30 s in logs
        (default: when the campaign is long, more than 2e7 case-steps).
    check_bounds : bool, default True
        Check the run against the scenario's theoretical bounds, if any (needs the diagnostics
        kept).
    keep : str or sequence of str, default all
        The recorded signals kept, among ``"states"``, ``"controls"`` and ``"diagnostics"``; the
        others are dropped chunk by chunk. Metrics and final states are always kept. The output is
        allocated once and filled chunk by chunk.
    store : str or os.PathLike, optional
        A directory to write the campaign to as each chunk completes (metrics, initial states and
        draws as Parquet, trajectories as Zarr, a provenance record; see
        :mod:`landing.campaign.store`), and to resume from: completed chunks are read back, not
        re-run, and the result is the uninterrupted run's bit for bit. A store of another campaign
        (scenario, seed, n, chunk_size, record settings) is refused. Without ``chunk_size`` a new
        store is cut into ``max(1000, n / 50)``-case chunks and a resumed one keeps its own. With a
        store the recorded signals are not kept in memory: each chunk's are written and dropped,
        and the result holds the per-case metrics, initial and final states (a few hundred bytes a
        case) while its states, controls and diagnostics are read from the store on demand
        (:class:`~landing.campaign.lazy.StoredArray`: a slice of cases stays lazy, any other index
        or ``np.asarray`` reads; ``mc[i]``, ``mc.bands``, the theory's checks, ``to_xarray`` and
        the figures read slice by slice). Memory then stays bounded by a few chunks whatever ``n``
        (the up-front check counts only that), so a campaign whose trajectories exceed the memory
        runs. :func:`landing.load` reads it back the same way. Needs ``pip install "landing[io]"``.
    client : distributed.Client, optional
        Run the chunks on its Dask cluster, ``threads`` threads each on a worker (default: all the
        worker machine's cores), the store (if any) written by this process as chunks arrive. The
        result is the local run's bit for bit; a lost worker costs only its chunks, which are
        re-run; Ctrl-C cancels the outstanding chunks and keeps the completed ones in the store.
        Without ``chunk_size`` (and no store to resume) the chunks are of ``max(1000, n / 50)``
        cases. See :mod:`landing.campaign.dask` and docs/cluster.md. Needs
        ``pip install "landing[dask]"``.

    Returns
    -------
    MonteCarloResult
        The cases' recorded runs, metrics (m, m/s, s, kg...), statistics and checks.

    Examples
    --------
    >>> import landing
    >>> scenario = landing.scenarios.preset("mars_monte_carlo").replace(t_final=5.0)
    >>> mc = landing.monte_carlo(scenario, n=8, seed=1)
    >>> len(mc), mc.states.shape
    (8, (8, 101, 7))
    >>> print(f"mean fuel used {mc.summary()['fuel_used']['mean']:.2f} kg")
    mean fuel used 61.33 kg
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
    # parameters given per case must have a row for each of the n cases; a chunk takes its own
    scenario.cases(0, n, n)
    if client is not None:
        # the Dask runner, loaded for a cluster campaign only (it is the landing[dask] extra's side)
        from landing.campaign import dask as cluster  # noqa: PLC0415 - the optional extra's runner, on demand

        cluster.check_client(client)
        if chunk_size is None and store is None:
            chunk_size = default_chunk_size(n)
    work = n * scenario.t_final / scenario.dt
    if progress is None:
        # wherever stderr goes: a bar in terminals and notebooks, a line every 30 s in logs
        progress = work > 2e7
    if chunk_size is None:
        # not 2 % of a few thousand cases: 40-case chunks left a thread idle at each chunk's end
        # and ran a 2000-case campaign about 1.6x slower (BENCHMARKS.md)
        chunk_size = default_chunk_size(n) if progress else n
    every, threads = options.record_every, options.threads
    # what the campaign holds in memory (with a store: its metrics and final states, and the
    # chunk in hand, of the store's chunking): refused up front if it cannot fit
    stored = store is not None
    held = chunk_size if store is None else store_chunk_size(store, n, chunk_size if chunk_given else None)
    require_memory(
        f"monte_carlo({scenario.name!r}, n={n}): the recorded runs",
        campaign_bytes(scenario, n, every, chunk=held, keep=_keep(keep), stored=stored),
        hint=_what_fits(scenario, n, every, held, _keep(keep), stored),
    )

    keep = _keep(keep)
    x0 = scenario.initial_states(n, seed=seed)
    campaign_store = None
    if store is not None:
        campaign_store = open_campaign_store(
            store, scenario, seed=seed, n=n, x0=x0, keep=keep, record_every=every,
            chunk_size=chunk_size if chunk_given else None, threads=threads, check_bounds=check_bounds,
        )
        # the store is locked from here: released by the ``finally`` below, whatever happens
        chunk_size = campaign_store.key.chunk_size
    bar: Optional[ProgressBar] = None
    diverged_warnings = 0

    def run_chunk(start: int, stop: int, into: Optional[tuple[np.ndarray, np.ndarray, np.ndarray]]) -> SimulationResult:
        nonlocal diverged_warnings
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always", DivergenceWarning)
            part = scenario.simulate_cases(x0[start:stop], start, n, seed=seed, threads=threads,
                                           record_every=every, into=into)
        diverged_warnings += sum(issubclass(w.category, DivergenceWarning) for w in caught)
        return part

    try:
        # a resumed campaign counts the cases it computes, and says how many the store holds
        kept = 0 if campaign_store is None else campaign_store.completed_cases
        label = scenario.name if not kept else f"{scenario.name} (resumed: {kept} of {n} cases in the store)"
        bar = ProgressBar(n - kept, label=label) if progress and kept < n else None
        if client is not None:
            mc = cluster.run_campaign(client, scenario, n=n, seed=seed, x0=x0, chunk_size=chunk_size, keep=keep,
                              record_every=every, threads=threads, store=campaign_store,
                              check_bounds=check_bounds, bar=bar)
        else:
            mc = assemble_campaign(scenario, n=n, seed=seed, x0=x0, chunk_size=chunk_size, keep=keep,
                                   run_chunk=run_chunk, store=campaign_store, check_bounds=check_bounds,
                                   bar=bar)
    except KeyboardInterrupt:
        raise KeyboardInterrupt(_interrupted(campaign_store, n)) from None
    finally:
        if bar:
            bar.close()
        if campaign_store is not None:
            campaign_store.close()
    if mc.metrics["diverged"].any():
        warnings.warn(
            f"{describe_diverged(mc.metrics)}; they are flagged in metrics['diverged'] (why: "
            "metrics['diverged_reason']) and left out of the summary's statistics",
            DivergenceWarning,
            stacklevel=2,
        )
    return mc


def _interrupted(store: Optional[CampaignStore], n: int) -> str:
    """What an interrupted campaign kept, and how to go on."""
    if store is None:
        return (f"the campaign of {n} cases was interrupted; nothing is kept (with store=DIR the completed chunks "
                "are, and the same call resumes it)")
    kept = store.completed_cases
    return (f"the campaign was interrupted: {kept} of {n} cases ({len(store.completed)} of {store.n_chunks} "
            f"chunks) are kept in '{store.path}'; the same monte_carlo(..., store='{store.path}') call (or landing "
            f"mc ... --store {store.path}) resumes it, landing.load('{store.path}', partial=True) reads them")


def load(path: Union[str, os.PathLike], *, scenario: Optional[Scenario] = None,
         partial: bool = False) -> MonteCarloResult:
    """The campaign stored at ``path`` (by ``landing.monte_carlo(..., store=path)``), bit for bit
    the result of the run that wrote it.

    Every chunk is read and checked against its checksums, one at a time; the result holds the
    per-case metrics, initial and final states, and reads the recorded signals (states, controls,
    diagnostics) from the store's Zarr tree on demand, as ``monte_carlo(..., store=path)`` returns
    them (:mod:`landing.campaign.lazy`): its memory does not grow with the trajectories.

    A store whose run was interrupted is refused (re-run ``monte_carlo`` with the same ``store``
    to complete it), unless ``partial``. Needs ``pip install "landing[io]"``.

    Parameters
    ----------
    path : str or os.PathLike
        The store's directory.
    scenario : landing.scenarios.Scenario, optional
        The campaign's scenario; it is checked against the stored one. Without it the scenario is
        rebuilt from the stored text when it is a preset's.
    partial : bool, default False
        Read an interrupted store: the result then holds the completed chunks' cases only, in
        case order, ``mc.cases`` their indices in the campaign and ``mc.planned`` its size, and
        its report says so.

    Returns
    -------
    MonteCarloResult
        The stored campaign, its recorded signals read on demand.

    Examples
    --------
    >>> import tempfile, numpy as np, landing
    >>> scenario = landing.scenarios.preset("mars_monte_carlo").replace(t_final=5.0)
    >>> path = tempfile.mkdtemp() + "/campaign"
    >>> mc = landing.monte_carlo(scenario, n=8, seed=1, store=path)
    >>> back = landing.load(path)
    >>> len(back), bool(np.array_equal(back.metrics["fuel_used"], mc.metrics["fuel_used"]))
    (8, True)
    """
    partial = boolean("partial", partial)
    store, scenario, x0, check_bounds = read_campaign_store(path, scenario=scenario, partial=partial)
    key = store.key
    if len(store.completed) == store.n_chunks:
        return assemble_campaign(
            scenario, n=key.n, seed=key.seed, x0=x0, chunk_size=key.chunk_size, keep=key.keep,
            run_chunk=None, store=store, check_bounds=check_bounds,
        )
    chunks = sorted(store.completed)
    if not chunks:
        raise ParameterError(f"the campaign at '{path}' has no completed chunk yet: nothing to load")
    index = np.concatenate([np.arange(store.completed[i]["start"], store.completed[i]["stop"]) for i in chunks])
    out = Assembly(index.size, key.keep, store, rows=index)
    row = 0
    for i in chunks:
        part = store.read_chunk(i)
        out.put(row, part)
        row += part.n_cases
    mc = finish_campaign(scenario, key.seed, x0[index], out.result(), key.keep, store, check_bounds)
    return dataclasses.replace(mc, cases=index, planned=key.n)
