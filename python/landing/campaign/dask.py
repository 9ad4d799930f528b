"""Campaigns on a Dask cluster: ``landing.monte_carlo(..., client=CLIENT)`` and
``landing mc ... --scheduler ADDRESS``.

How a campaign runs on a cluster:

- The cases are cut into chunks (``chunk_size`` cases each); each chunk is one task,
  :func:`run_chunk`, which rebuilds the scenario on the worker and runs its cases in the Rust
  core with ``simulate_batch(x0[start:stop], seed=seed, first_case=start, threads=threads)``.
  Case i depends only on (seed, i), so the result is the local run's bit for bit whatever the
  number of workers, their order of completion or the chunk size.
- The scenario travels as its TOML text (a few kB in each task, cached on the worker; not
  scattered once, since scattered data is lost with the worker holding it), which
  reads back to the same scenario; a scenario that TOML cannot describe (a law or plant built
  in code) travels pickled. Each task also carries its slice of the initial states, computed
  once by the client.
- The client keeps a bounded number of chunks in flight (twice the cluster's threads, at least
  8), gathers each chunk as it completes, writes it to the campaign store (when ``store=`` is
  given: the store is written by the client process only, so the workers need no shared
  filesystem) and copies it into the preallocated output. Signals not kept are dropped on the
  worker, before the transfer.
- A worker lost mid-campaign costs only the chunks it was running or holding: the client still
  holds their futures, so the scheduler runs them again elsewhere (the tasks are pure: the same
  inputs give the same bits). A chunk is abandoned only when it has killed several workers
  (Dask's ``distributed.scheduler.allowed-failures``).
- Ctrl-C (or any error) cancels the outstanding chunks; the completed ones are in the store,
  and re-running the same call resumes from them.

Dask is the optional extra ``landing[dask]``: this module imports it only when a cluster
campaign starts, and a local campaign never imports this module.
"""

from __future__ import annotations

import hashlib
import importlib
import os
import pickle
import threading
import time
import uuid
import warnings
from typing import Any, Optional

import numpy as np

from landing._core import __version__
from landing._internal.progress import ProgressBar
from landing.campaign._assembly import Assembly, finish_campaign, write_chunk
from landing.campaign.result import MonteCarloResult
from landing.campaign.store import CampaignStore, default_chunk_size
from landing.errors import (
    DivergenceWarning,
    LandingError,
    ParameterError,
    ParameterTypeError,
    SimulationError,
)
from landing.results import SimulationResult
from landing.scenarios import Scenario, files

__all__ = ["require_dask", "connect", "default_chunk_size", "run_chunk", "run_campaign"]

#: Prefix of the chunks' task keys (as the Dask dashboard shows them).
KEY_PREFIX = "landing-chunk"
#: Seconds a campaign waits on a cluster with no worker before it gives up (the environment
#: variable LANDING_NO_WORKER_TIMEOUT overrides it): a cluster whose workers all died, or were
#: never started, would otherwise be waited on for ever.
NO_WORKER_TIMEOUT = 300.0


def no_worker_timeout() -> float:
    """The no-worker timeout in seconds (:data:`NO_WORKER_TIMEOUT`, or the environment's)."""
    text = os.environ.get("LANDING_NO_WORKER_TIMEOUT")
    if text is None:
        return NO_WORKER_TIMEOUT
    try:
        value = float(text)
    except ValueError:
        value = float("nan")
    if not value > 0:
        raise ParameterError(f"LANDING_NO_WORKER_TIMEOUT = {text!r} violates a number of seconds > 0")
    return value


class _Watchdog(threading.Thread):
    """Watches the cluster's workers while a campaign waits on it: after ``timeout`` seconds
    with none, it cancels the campaign's outstanding chunks (which ends the wait) and says so."""

    def __init__(self, client: Any, timeout: float, outstanding: dict[str, Any]):
        super().__init__(name="landing-dask-watchdog", daemon=True)
        self.client, self.timeout, self.outstanding = client, timeout, outstanding
        self.fired = False
        self.done = threading.Event()

    def run(self) -> None:
        since: Optional[float] = None
        while not self.done.wait(min(1.0, self.timeout / 4)):
            try:
                workers = len(self.client.scheduler_info().get("workers", {}))
            except Exception:  # noqa: BLE001 - a scheduler that does not answer has no worker for us
                workers = 0
            if workers:
                since = None
                continue
            since = time.monotonic() if since is None else since
            if time.monotonic() - since >= self.timeout:
                self.fired = True
                try:
                    self.client.cancel(list(self.outstanding.values()))
                except Exception:  # noqa: BLE001 - the campaign reports the timeout either way
                    pass
                return
#: Chunks in flight per thread of the cluster (at least MIN_IN_FLIGHT in all).
IN_FLIGHT_PER_THREAD = 2
MIN_IN_FLIGHT = 8
#: Re-runs of a chunk whose task raised (a lost worker does not count: Dask re-runs those).
RETRIES = 1


def require_dask(what: str = "monte_carlo(client=...)") -> Any:
    """The ``distributed`` module, or an ImportError saying how to install it.

    Parameters
    ----------
    what : str, default "monte_carlo(client=...)"
        What needs it, for the error's message.

    Returns
    -------
    module
        ``distributed``.

    Examples
    --------
    >>> from landing.campaign.dask import require_dask
    >>> require_dask().__name__
    'distributed'
    """
    try:
        return importlib.import_module("distributed")
    except ImportError as e:
        raise ImportError(
            f"{what} needs Dask's distributed scheduler, the optional extra landing[dask]: "
            "pip install \"landing[dask]\""
        ) from e


def connect(address: str) -> Any:
    """A ``distributed.Client`` connected to the scheduler at ``address`` (``tcp://host:8786``).

    Parameters
    ----------
    address : str
        The scheduler's address.

    Returns
    -------
    distributed.Client
        The client; ``landing.monte_carlo(..., client=client)`` runs a campaign on its cluster.

    Examples
    --------
    >>> import landing
    >>> from distributed import LocalCluster
    >>> from landing.campaign.dask import connect
    >>> cluster = LocalCluster(n_workers=1, threads_per_worker=1, processes=False, dashboard_address=None)
    >>> client = connect(cluster.scheduler_address)
    >>> type(client).__name__
    'Client'
    >>> client.close(); cluster.close()
    """
    distributed = require_dask("--scheduler")
    if not isinstance(address, str) or not address:
        raise ParameterError(f"scheduler = {address!r} must be a scheduler address such as tcp://host:8786")
    return distributed.Client(address)


def check_client(client: Any) -> Any:
    """The ``distributed`` module, once ``client`` is known to be one of its clients."""
    distributed = require_dask()
    if not isinstance(client, distributed.Client):
        raise ParameterTypeError(f"client must be a distributed.Client, got {type(client).__name__}")
    return distributed


# --- the scenario on the workers ------------------------------------------------------------------


def scenario_payload(scenario: Scenario) -> tuple[str, Any]:
    """What a task carries of the scenario: ``("toml", text)`` when the text reads back to the
    same scenario, else ``("pickle", bytes)`` (cloudpickle's, which plain pickle reads)."""
    try:
        # a plant written in Python has no text yet: it travels pickled
        text = scenario.to_toml()
        if files.scenario_from_dict(files.tomllib.loads(text)).to_toml() == text:
            return ("toml", text)
    except (files.tomllib.TOMLDecodeError, LandingError):
        pass
    # cloudpickle (distributed's own dependency) carries what pickle cannot: a law written in
    # Python as a function of the user's script, a lambda, a closure
    import cloudpickle  # type: ignore[import-untyped]  # no stubs

    try:
        return ("pickle", cloudpickle.dumps(scenario, protocol=pickle.HIGHEST_PROTOCOL))
    except Exception as e:  # noqa: BLE001 - any pickling failure means the same thing here
        raise ParameterError(
            f"scenario = {scenario.name!r} cannot be sent to the cluster's workers: its TOML text does "
            f"not read back to the same scenario and it does not pickle ({type(e).__name__}: {e}); "
            "build it from a scenario file's parts"
        ) from e


#: Scenarios rebuilt on this worker, by payload digest (a campaign's chunks share one).
_SCENARIOS: dict[str, Scenario] = {}


def _scenario_on_worker(payload: tuple[str, Any]) -> Scenario:
    kind, data = payload
    raw = data.encode() if kind == "toml" else data
    digest = kind + ":" + hashlib.sha256(raw).hexdigest()
    scenario = _SCENARIOS.get(digest)
    if scenario is None:
        if kind == "toml":
            scenario = files.scenario_from_dict(files.tomllib.loads(data), "<the campaign's scenario>")
        else:
            scenario = pickle.loads(data)
        if len(_SCENARIOS) >= 8:
            _SCENARIOS.clear()
        _SCENARIOS[digest] = scenario
    return scenario


def run_chunk(
    payload: tuple[str, Any],
    version: str,
    x0: np.ndarray,
    start: int,
    n: int,
    seed: int,
    record_every: int,
    threads: Optional[int],
    keep: tuple[str, ...],
) -> SimulationResult:
    """One chunk, on a worker: cases ``start .. start + len(x0)`` of the campaign's ``n``, with the
    signals not kept dropped (the task the client submits).

    Parameters
    ----------
    payload : tuple of (str, object)
        The scenario as :func:`scenario_payload` gives it (its TOML text, or pickled).
    version : str
        The client's package version; another than the worker's is refused.
    x0 : numpy.ndarray
        The chunk's initial states, (cases, state_dim) (m, m/s, kg).
    start : int
        The chunk's first case.
    n : int
        The campaign's cases.
    seed : int
        The campaign's seed.
    record_every : int
        The decimation.
    threads : int or None
        The worker's threads.
    keep : tuple of str
        The recorded signals kept.

    Returns
    -------
    landing.SimulationResult
        The chunk's runs, bit for bit those of the local campaign.

    Examples
    --------
    >>> import numpy as np, landing
    >>> from landing.campaign.dask import run_chunk, scenario_payload
    >>> scenario = landing.scenarios.preset("mars_monte_carlo").replace(t_final=5.0)
    >>> x0 = scenario.initial_states(8, seed=1)
    >>> part = run_chunk(scenario_payload(scenario), landing._core.__version__, x0[4:], 4, 8, 1, 50, 1, ("states",))
    >>> part.states.shape, part.controls is None
    ((4, 101, 7), True)
    >>> local = landing.monte_carlo(scenario, n=8, seed=1)
    >>> bool(np.array_equal(part.metrics["fuel_used"], local.metrics["fuel_used"][4:]))
    True
    """
    if version != __version__:
        raise RuntimeError(
            f"this worker runs landing {__version__}, the client {version}: install the same version "
            "on every worker (the same bits need the same code)"
        )
    scenario = _scenario_on_worker(payload)
    # an array received over the network may be read-only or misaligned: the core wants its own
    x0 = np.array(x0, dtype=np.float64, order="C", copy=True)
    with warnings.catch_warnings():
        # the client warns once for the whole campaign
        warnings.simplefilter("ignore", DivergenceWarning)
        # the chunk's own rows of the parameters given per case, and its draws of the dispersed ones
        part = scenario.simulate_cases(x0, start, n, seed=seed, threads=threads, record_every=record_every)
    return part.keeping(keep)


# --- the client's side -----------------------------------------------------------------------------


class _InFlight:
    """How many chunks to keep in flight: twice the cluster's threads (at least MIN_IN_FLIGHT),
    asked of the scheduler at most once a second (workers come and go)."""

    def __init__(self, client: Any):
        self.client = client
        self.asked = -float("inf")
        self.value = MIN_IN_FLIGHT

    def __call__(self) -> int:
        now = time.monotonic()
        if now - self.asked >= 1.0:
            self.asked = now
            try:
                threads = sum(self.client.nthreads().values())
            except Exception:  # noqa: BLE001 - a scheduler briefly unreachable: keep the last value
                return self.value
            self.value = max(MIN_IN_FLIGHT, IN_FLIGHT_PER_THREAD * threads)
        return self.value


def _clear_cancelled_gather(client: Any) -> None:
    """Forgets a result fetch that Ctrl-C cancelled in an earlier call on this client.

    distributed batches concurrent fetches behind one pending task (``Client._gather_future``).
    When Ctrl-C lands in ``future.result()`` after the task was made and before it ran, its
    ``sync`` cancels the task, which is left in place: every later fetch on that client awaits
    the cancelled task and fails (a ``CancelledError`` that surfaces from ``sync`` as an
    UnboundLocalError), so the re-run a user makes after Ctrl-C would fail on its first chunk.
    A pending fetch that is not cancelled is left alone.
    """
    pending = getattr(client, "_gather_future", None)
    if pending is not None and pending.done() and pending.cancelled():
        client._gather_future = None
        client._gather_keys = None


def run_campaign(
    client: Any,
    scenario: Scenario,
    *,
    n: int,
    seed: int,
    x0: np.ndarray,
    chunk_size: int,
    keep: tuple[str, ...],
    record_every: int,
    threads: Optional[int],
    store: Optional[CampaignStore],
    check_bounds: bool,
    bar: Optional[ProgressBar] = None,
) -> MonteCarloResult:
    """The campaign's chunks on the cluster behind ``client``, assembled as the local run's (see the
    module's docstring). What ``landing.monte_carlo(..., client=client)`` runs.

    Parameters
    ----------
    client : distributed.Client
        The cluster's client.
    scenario : landing.scenarios.Scenario
        The campaign's scenario.
    n, seed : int
        The campaign's cases and seed.
    x0 : numpy.ndarray
        The campaign's initial states, (n, state_dim) (m, m/s, kg).
    chunk_size : int
        Cases per chunk (one task each).
    keep : tuple of str
        The recorded signals kept.
    record_every : int
        The decimation.
    threads : int or None
        Threads per task on a worker.
    store : CampaignStore or None
        The store the chunks are written to (by this process), and resumed from.
    check_bounds : bool
        Whether the result is checked against the scenario's bounds.
    bar : ProgressBar, optional
        A progress bar, advanced chunk by chunk.

    Returns
    -------
    MonteCarloResult
        The campaign, bit for bit the local run's.

    Examples
    --------
    >>> import landing
    >>> from distributed import LocalCluster
    >>> from landing.campaign.dask import connect
    >>> cluster = LocalCluster(n_workers=1, threads_per_worker=1, processes=False, dashboard_address=None)
    >>> client = connect(cluster.scheduler_address)
    >>> import numpy as np
    >>> scenario = landing.scenarios.preset("mars_monte_carlo").replace(t_final=5.0)
    >>> on_cluster = landing.monte_carlo(scenario, n=8, seed=1, client=client, chunk_size=4)
    >>> local = landing.monte_carlo(scenario, n=8, seed=1)
    >>> bool(np.array_equal(on_cluster.metrics["fuel_used"], local.metrics["fuel_used"]))
    True
    >>> client.close(); cluster.close()
    """
    distributed = check_client(client)
    payload = scenario_payload(scenario)
    out = Assembly(n, keep, store)
    todo: list[tuple[int, int, int]] = []
    for index, start in enumerate(range(0, n, chunk_size)):
        stop = min(n, start + chunk_size)
        part = None if store is None else store.resume_chunk(index)
        if part is None:  # not in the store, or damaged there: run on the cluster
            todo.append((index, start, stop))
        else:
            out.put(start, part)
            del part

    run_id = uuid.uuid4().hex[:12]  # this call's keys: never those of a cancelled earlier call
    chunk_of: dict[str, tuple[int, int, int]] = {}
    outstanding: dict[str, Any] = {}

    def submit(chunk: tuple[int, int, int]) -> Any:
        index, start, stop = chunk
        future = client.submit(
            run_chunk, payload, __version__, x0[start:stop], start, n, seed, record_every, threads, keep,
            key=f"{KEY_PREFIX}-{run_id}-{index:06d}", pure=True, retries=RETRIES,
        )
        chunk_of[future.key] = chunk
        outstanding[future.key] = future
        return future

    in_flight = _InFlight(client)
    pending = iter(todo)
    first = [submit(c) for _, c in zip(range(in_flight()), pending)]
    completed = distributed.as_completed(first)
    del first
    timeout = no_worker_timeout()
    watchdog = _Watchdog(client, timeout, outstanding)
    watchdog.start()

    def no_worker() -> SimulationError:
        kept = "" if store is None else f"; the completed chunks are in the store '{store.path}'"
        return SimulationError(
            f"the Dask cluster has had no worker for {timeout:g} s (LANDING_NO_WORKER_TIMEOUT), so the campaign "
            f"stopped with {len(outstanding)} chunks left{kept}: start workers and run it again"
            + (" to resume" if store is not None else ""))

    try:
        for future in completed:
            if watchdog.fired:
                raise no_worker()
            index, start, stop = chunk_of.pop(future.key)
            _clear_cancelled_gather(client)
            part = future.result()  # waits if the worker holding it was lost and it is re-run
            del outstanding[future.key]
            future.release()
            if store is not None:
                write_chunk(store, scenario, seed, x0, index, start, stop, part)
            out.put(start, part)
            del part, future
            if bar:
                bar.update(stop - start)
            for _ in range(max(0, in_flight() - len(outstanding))):
                chunk = next(pending, None)
                if chunk is None:
                    break
                completed.add(submit(chunk))
    except BaseException as exc:
        if watchdog.fired and not isinstance(exc, SimulationError):
            raise no_worker() from None
        # Ctrl-C or a failed chunk: stop the rest; the completed chunks are in the store
        if outstanding:
            try:
                client.cancel(list(outstanding.values()))
            except Exception:  # noqa: BLE001 - the original error matters more
                pass
        raise
    finally:
        watchdog.done.set()
    if watchdog.fired:  # the wait ended because the watchdog cancelled what was left
        raise no_worker()
    if out.out is None:  # pragma: no cover - n >= 1 gives at least one chunk
        raise ParameterError(f"n = {n} gave no chunk")
    return finish_campaign(scenario, seed, x0, out.result(), keep, store, check_bounds)
