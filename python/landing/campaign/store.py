"""Campaigns as data: a Monte Carlo campaign as a directory a user can keep, share and reopen.

Layout of a store written by ``landing.monte_carlo(..., store=path)``::

    path/
      provenance.json         what ran: package version, the scenario as text, seed, n, chunk
                              size, record settings, and per session the machine, threads,
                              date and kernel level
      manifest.json           the completed chunks (replaced atomically after each chunk's
                              files are on disk), each with the SHA-256 of its metrics, its
                              initial states and its trajectories (of their content), the
                              layout of the metric columns and the SHA-256 of each file of the
                              Zarr tree as created (its metadata and coordinates)
      chunks/metrics/part-000000.parquet   per-case metrics of chunk 0 (index ``case``;
                              per-axis columns split with the axis names: final_error_x ...)
      chunks/initial/part-000000.parquet   the chunk's initial states (x0_<state>) and
                              dispersion draws (draw_<j>)
      writer.lock             held (an advisory lock) by the one process writing the store; released
                              when it ends, however it ends
      writer.json             who holds it: host, pid, start time (stale once the lock is free)
      trajectories.zarr/      states (case, time, state), controls (case, time, control),
                              diagnostics (case, time[, axis]) as kept, final_state (case,
                              state); coordinates case, time (s), state, control, axis and the
                              components' units; created once with the store (shaped
                              after one case), then written chunk by chunk (region writes)

``xarray.open_zarr(path / "trajectories.zarr")`` and ``pandas.read_parquet(path / "chunks" /
"metrics")`` read it without this package; :func:`read_campaign_store` opens it for the
campaign's assembly, which gives back the
:class:`~landing.campaign.MonteCarloResult` bit for bit (:func:`landing.load`): its metrics,
initial and final states in memory, its recorded signals read from the Zarr tree on demand
(:meth:`CampaignStore.signals`, :mod:`landing.campaign.lazy`), as the campaign that wrote the
store returned them.

Reading a store checks its provenance against its data: the stored initial states must be the
draws of the recorded scenario and seed, the kept arrays the recorded ``keep``, the time grid
the scenario's at the recorded ``record_every``, and the first case, run again, must end where
the stored one does; an unknown format is refused. Every chunk read back is checked against
the manifest: its Parquet parts readable and holding
its cases, its Zarr region extending over them, and each content's checksum the one written (a
deleted Zarr chunk reads as NaN fill, which its checksum tells from data). A damaged chunk is a
:class:`~landing.errors.StoreError` naming it, its file and the remedy; a resumed campaign runs
the damaged chunks again (a :class:`~landing.errors.StoreWarning` says which) and rewrites them.

Parquet, Zarr, xarray and pandas are the optional extra ``landing[io]``; nothing here imports
them until a store or a conversion is asked for.
"""

from __future__ import annotations

import dataclasses
import datetime
import errno
import hashlib
import importlib
import json
import os
import platform
import warnings
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from types import ModuleType
from typing import Any, Optional, Union, cast

import numpy as np

from landing._core import __version__
from landing._internal.args import short
from landing.campaign.lazy import StoredArray, StoredResult
from landing.errors import (
    DivergenceWarning,
    LandingError,
    ParameterError,
    ParameterTypeError,
    StoreError,
    StoreWarning,
)
from landing.results import Metrics, SimulationResult, dataset_coords, flat_columns, flat_metric_units, require_io
from landing.scenarios import Scenario, files

__all__ = ["CampaignKey", "CampaignStore", "STORE_FORMAT", "default_chunk_size", "open_campaign_store",
           "read_campaign_store", "store_chunk_size", "store_path"]

#: Version of the directory layout written here.
STORE_FORMAT = 1

PROVENANCE = "provenance.json"
MANIFEST = "manifest.json"
LOCK = "writer.lock"
HOLDER = "writer.json"
TRAJECTORIES = "trajectories.zarr"
METRICS_DIR = Path("chunks") / "metrics"
INITIAL_DIR = Path("chunks") / "initial"


# --- one writer --------------------------------------------------------------------------------------

#: The POSIX file-locking module (None elsewhere: stores are then not locked).
_FCNTL: Optional[ModuleType] = importlib.import_module("fcntl") if os.name == "posix" else None


class WriterLock:
    """The exclusive lock of a store's one writer: ``flock`` on ``writer.lock``, which the
    operating system releases when the process ends, however it ends (a kill leaves no stale
    lock). The holder writes who it is into ``writer.json``, which a refused writer reads to
    name it. POSIX only; where ``fcntl`` is missing (Windows) a store is not locked."""

    def __init__(self, path: Path):
        self.path = path
        self._fd: Optional[int] = None

    def acquire(self) -> None:
        if _FCNTL is None:  # pragma: no cover - not POSIX
            return
        try:
            fd = os.open(self.path / LOCK, os.O_RDWR | os.O_CREAT, 0o644)
        except OSError as exc:
            raise StoreError(f"store = '{self.path}': cannot open {LOCK} for writing ({exc.strerror}); "
                             "give a directory this process may write") from None
        try:
            _FCNTL.flock(fd, _FCNTL.LOCK_EX | _FCNTL.LOCK_NB)
        except BlockingIOError:
            os.close(fd)
            raise StoreError(
                f"store = '{self.path}' is being written by another process ({self._holder()}); "
                "wait for it to end or stop it, then run again to resume"
            ) from None
        except OSError as exc:
            os.close(fd)
            raise StoreError(f"store = '{self.path}': cannot lock {LOCK} ({exc.strerror}); "
                             "give a directory on a file system with locks (not every network one has)") from None
        self._fd = fd
        _write_json_atomic(self.path / HOLDER, {"host": platform.node(), "pid": os.getpid(), "started": _now()})

    def _holder(self) -> str:
        try:
            h = json.loads((self.path / HOLDER).read_text())
            return f"host {h['host']}, pid {h['pid']}, since {h['started']}"
        except (OSError, ValueError, KeyError, TypeError):
            return f"its holder unrecorded in {self.path / HOLDER}"

    def release(self) -> None:
        if self._fd is not None:
            os.close(self._fd)  # closing the descriptor releases the flock
            self._fd = None


# --- metric columns ----------------------------------------------------------------------------------


def metrics_layout(columns: Mapping[str, np.ndarray], axes: Sequence[str]) -> list[list[Any]]:
    """[name, dtype, per-axis column names or None] of each metric (how to put the flat Parquet
    columns back together)."""
    out = []
    for k, v in columns.items():
        v = np.asarray(v)
        if v.ndim == 1:
            out.append([k, v.dtype.str, None])
        else:
            names = axes if len(axes) == v.shape[1] else tuple(str(j) for j in range(v.shape[1]))
            out.append([k, v.dtype.str, [f"{k}_{a}" for a in names]])
    return out



# --- provenance ----------------------------------------------------------------------------------------


def _scenario_text(scenario: Scenario) -> str:
    """The scenario as TOML in the provenance record (what a resumed run must match, and what
    :func:`read_campaign_store` rebuilds the scenario from)."""
    return scenario.to_toml()


def _scenario_from_text(text: str) -> Optional[Scenario]:
    """The scenario back from its TOML text, or None when the text is not a scenario file."""
    try:
        return files.scenario_from_dict(files.read_toml(text, "<the store's provenance.json>"),
                                        "<the store's provenance.json>")
    except LandingError:
        return None


def _now() -> str:
    return datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds")


def _cpu_name() -> str:
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def machine() -> dict[str, Any]:
    """The machine a session ran on: platform, CPU name, cores."""
    return {
        "platform": platform.platform(),
        "python": platform.python_version(),
        "cpu": _cpu_name(),
        "cores": os.cpu_count(),
    }


@dataclass(frozen=True)
class CampaignKey:
    """What a store's chunks depend on: a resumed run must match every field. Made by
    :meth:`CampaignKey.of`.

    Parameters
    ----------
    version : str
        The package version that wrote the store.
    scenario : str
        The scenario as text (its TOML).
    seed : int
        The campaign's seed.
    n : int
        The number of cases.
    chunk_size : int
        Cases per chunk.
    record_every : int
        The recorded signals' decimation (0: none recorded).
    keep : tuple of str
        The recorded signals kept.
    x0_sha256 : str
        The SHA-256 of the initial states (m, m/s, kg as float64 bytes).

    Examples
    --------
    >>> import landing
    >>> from landing.campaign.store import CampaignKey
    >>> scenario = landing.scenarios.preset("mars_monte_carlo").replace(t_final=5.0)
    >>> x0 = scenario.initial_states(8, seed=1)
    >>> key = CampaignKey.of(scenario, seed=1, n=8, chunk_size=4, record_every=50, keep=("states",), x0=x0)
    >>> key.n, key.chunk_size, key.keep
    (8, 4, ('states',))
    >>> CampaignKey.of(scenario, seed=2, n=8, chunk_size=4, record_every=50, keep=("states",),
    ...                x0=x0).differences(key)
    ['seed: 1 in the store, 2 here']
    """

    version: str
    scenario: str
    seed: int
    n: int
    chunk_size: int
    record_every: int
    keep: tuple[str, ...]
    x0_sha256: str

    @staticmethod
    def of(scenario: Scenario, *, seed: int, n: int, chunk_size: int, record_every: int,
           keep: Sequence[str], x0: np.ndarray) -> CampaignKey:
        """The key of a campaign.

        Parameters
        ----------
        scenario : landing.scenarios.Scenario
            The campaign's scenario.
        seed, n, chunk_size, record_every : int
            The campaign's seed, cases, cases per chunk and decimation.
        keep : sequence of str
            The recorded signals kept.
        x0 : numpy.ndarray
            The campaign's initial states, (n, state_dim).

        Returns
        -------
        CampaignKey
            The key, with this package's version.
        """
        return CampaignKey(
            version=__version__, scenario=_scenario_text(scenario), seed=int(seed), n=int(n),
            chunk_size=int(chunk_size), record_every=int(record_every), keep=tuple(keep),
            x0_sha256=hashlib.sha256(np.ascontiguousarray(x0, dtype=np.float64).tobytes()).hexdigest(),
        )

    def to_json(self) -> dict[str, Any]:
        """The key as the provenance record stores it.

        Returns
        -------
        dict
            Its fields, ``keep`` as a list.
        """
        d = dataclasses.asdict(self)
        d["keep"] = list(self.keep)
        return d

    @staticmethod
    def from_json(d: Mapping[str, Any]) -> CampaignKey:
        """A key read back from the provenance record (the inverse of :meth:`to_json`).

        Parameters
        ----------
        d : mapping
            The record's fields.

        Returns
        -------
        CampaignKey
            The key.
        """
        return CampaignKey(**{**d, "keep": tuple(d["keep"])})

    def differences(self, stored: CampaignKey) -> list[str]:
        """What differs, as "field: stored value there, this value here".

        Parameters
        ----------
        stored : CampaignKey
            The store's key.

        Returns
        -------
        list of str
            One line per field that differs (empty when the keys agree).
        """
        out = []
        for f in dataclasses.fields(self):
            mine, theirs = getattr(self, f.name), getattr(stored, f.name)
            if mine == theirs:
                continue
            if f.name == "scenario":
                out.append("scenario: " + _scenario_differences(theirs, mine))
            elif f.name == "x0_sha256":
                out.append("initial states: they differ from the store's")
            else:
                out.append(f"{f.name}: {theirs!r} in the store, {mine!r} here")
        return out


def _flat(d: Any, prefix: str = "") -> dict[str, Any]:
    """A parsed TOML document as {dotted key: value}."""
    if isinstance(d, dict):
        out: dict[str, Any] = {}
        for k, v in d.items():
            out.update(_flat(v, f"{prefix}.{k}" if prefix else str(k)))
        return out
    if isinstance(d, list) and d and all(isinstance(v, dict) for v in d):
        out = {}
        for i, v in enumerate(d):
            out.update(_flat(v, f"{prefix}[{i}]"))
        return out
    return {prefix: d}


def _scenario_differences(theirs: str, mine: str) -> str:
    """Where two scenarios' TOML texts differ, key by key, on one line (the texts whole when
    one does not parse)."""
    try:
        a, b = _flat(files.read_toml(theirs, "<the store's>")), _flat(files.read_toml(mine, "<this one>"))
    except LandingError:
        return "the store's is\n" + _indent(theirs) + "\n  this one is\n" + _indent(mine)
    keys = [k for k in dict.fromkeys([*a, *b]) if a.get(k, _MISSING) != b.get(k, _MISSING)]
    return "; ".join(f"{k} = {short(a.get(k, _MISSING))} in the store's, {short(b.get(k, _MISSING))} in this one's"
                     for k in keys)


class _Missing:
    def __repr__(self) -> str:
        return "(none)"


_MISSING = _Missing()


def _indent(text: str) -> str:
    return "\n".join("    " + line for line in text.splitlines())


# --- files ------------------------------------------------------------------------------------------


def _fsync_file(path: Path) -> None:
    fd = os.open(path, os.O_RDONLY)
    try:
        os.fsync(fd)
    finally:
        os.close(fd)


def _fsync_dir(path: Path) -> None:
    try:
        _fsync_file(path)
    except OSError:  # directories cannot be opened for fsync on some systems
        pass


def _write_json_atomic(path: Path, data: Any) -> None:
    """Write to a temporary name, make it durable, then rename over ``path``."""
    tmp = path.with_name(f".{path.name}.tmp")
    with open(tmp, "w") as f:
        json.dump(data, f, indent=1, sort_keys=False)
        f.write("\n")
        f.flush()
        os.fsync(f.fileno())
    os.replace(tmp, path)
    _fsync_dir(path.parent)


#: What to do about a store whose record cannot be read.
_REMEDY_RECORD = ("restore the file from a copy, or delete the directory and run the campaign again "
                  "(the Parquet parts and the Zarr tree stay readable without this package)")


def _read_record(store: Path, name: str) -> dict[str, Any]:
    """``provenance.json`` or ``manifest.json`` of the store at ``store`` as a dict: a file that
    is missing, unreadable, not JSON or not a JSON object is a StoreError naming it."""
    path = store / name
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise StoreError(f"store = '{store}': its {name} is missing ({path}); {_REMEDY_RECORD}") from None
    except (OSError, UnicodeDecodeError, ValueError, RecursionError) as exc:
        why = exc.strerror if isinstance(exc, OSError) and exc.strerror else f"{type(exc).__name__}: {exc}"
        raise StoreError(f"store = '{store}': its {name} ({path}) cannot be read ({why}); {_REMEDY_RECORD}") from None
    if not isinstance(data, dict):
        raise StoreError(f"store = '{store}': its {name} ({path}) is not a JSON object; {_REMEDY_RECORD}")
    return data


def _is_int(v: Any) -> bool:
    return isinstance(v, int) and not isinstance(v, bool)


def _key_of(store: Path, prov: Mapping[str, Any]) -> CampaignKey:
    """The campaign key a store's provenance records, each field of the type it must have."""
    key = prov.get("key")
    rules: dict[str, tuple[str, Callable[[Any], bool]]] = {
        "version": ("a string", lambda v: isinstance(v, str)),
        "scenario": ("a string", lambda v: isinstance(v, str)),
        "seed": ("an integer >= 0", lambda v: _is_int(v) and v >= 0),
        "n": ("an integer >= 1", lambda v: _is_int(v) and v >= 1),
        "chunk_size": ("an integer >= 1", lambda v: _is_int(v) and v >= 1),
        "record_every": ("an integer >= 0", lambda v: _is_int(v) and v >= 0),
        "keep": ("a list of signal names", lambda v: isinstance(v, list) and all(isinstance(x, str) for x in v)),
        "x0_sha256": ("a string", lambda v: isinstance(v, str)),
    }
    file = store / PROVENANCE
    if not isinstance(key, dict) or set(key) != set(rules):
        raise StoreError(f"store = '{store}': its {PROVENANCE} ({file}) does not record the campaign (its 'key' "
                         f"must hold {sorted(rules)}); {_REMEDY_RECORD}")
    for name, (rule, ok) in rules.items():
        if not ok(key[name]):
            raise StoreError(f"store = '{store}': its {PROVENANCE} ({file}) records key.{name} = "
                             f"{short(key[name])}, which must be {rule}; {_REMEDY_RECORD}")
    return CampaignKey.from_json(key)


def _chunks_of(store: Path, manifest: Mapping[str, Any], key: CampaignKey) -> dict[int, dict[str, Any]]:
    """The completed chunks a store's manifest records, each where the campaign's chunking puts
    it (chunk i holds cases i * chunk_size up to the next chunk's or n)."""
    file = store / MANIFEST
    chunks = manifest.get("chunks")
    layout = manifest.get("layout", {})
    if not isinstance(chunks, list) or not isinstance(layout, dict):
        raise StoreError(f"store = '{store}': its {MANIFEST} ({file}) does not list the chunks; {_REMEDY_RECORD}")
    n_chunks = -(-key.n // key.chunk_size)
    out: dict[int, dict[str, Any]] = {}
    for c in chunks:
        index: Any = c.get("index") if isinstance(c, dict) else None
        if (not isinstance(c, dict) or not _is_int(index) or not 0 <= index < n_chunks or index in out
                or c.get("start") != index * key.chunk_size
                or c.get("stop") != min(key.n, (index + 1) * key.chunk_size)
                or not isinstance(c.get("sha256", {}), dict)):
            raise StoreError(f"store = '{store}': its {MANIFEST} ({file}) records a chunk that is not one of the "
                             f"campaign's {n_chunks} ({short(c)}); {_REMEDY_RECORD}")
        out[int(index)] = c
    return out


def _part(index: int) -> str:
    return f"part-{index:06d}.parquet"


def _zarr_create(group: Any, name: str, shape: tuple[int, ...], chunks: tuple[int, ...], dtype: Any,
                 dims: Sequence[str], attrs: Mapping[str, Any]) -> Any:
    """An array with named dims, under zarr 2 or 3."""
    if hasattr(group, "create_array"):  # zarr 3
        fmt = getattr(getattr(group, "metadata", None), "zarr_format", 3)
        kw: dict[str, Any] = {"dimension_names": list(dims)} if fmt == 3 else {}
        arr = group.create_array(name, shape=shape, chunks=chunks, dtype=dtype, fill_value=np.nan, **kw)
        if fmt != 3:
            arr.attrs["_ARRAY_DIMENSIONS"] = list(dims)
    else:  # zarr 2
        arr = group.create_dataset(name, shape=shape, chunks=chunks, dtype=dtype, fill_value=np.nan)
        arr.attrs["_ARRAY_DIMENSIONS"] = list(dims)
    arr.attrs.update(dict(attrs))
    return arr


@dataclass
class CampaignStore:
    """A campaign's directory, open for writing and resuming (see the module's docstring). Opened by
    :func:`open_campaign_store` (to write) and :func:`read_campaign_store` (to read).

    Parameters
    ----------
    path : pathlib.Path
        The store's directory.
    key : CampaignKey
        The campaign it holds.
    completed : dict of int to dict
        The completed chunks by index, as the manifest records them (start, stop, checksums).
    layout : dict
        The layout of the metric columns and of the Zarr tree.
    lock : WriterLock, optional
        Held from :meth:`open` to :meth:`close` (by the process writing the store).
    checked : set of tuple
        The (folder, chunk) Parquet parts already checked in this session (each is read once).

    Examples
    --------
    >>> import tempfile, landing
    >>> from landing.campaign.store import read_campaign_store
    >>> path = tempfile.mkdtemp() + "/campaign"
    >>> scenario = landing.scenarios.preset("mars_monte_carlo").replace(t_final=5.0)
    >>> mc = landing.monte_carlo(scenario, n=8, seed=1, store=path, chunk_size=4)
    >>> store, scenario, x0, check_bounds = read_campaign_store(path)
    >>> store.n_chunks, store.completed_cases, x0.shape
    (2, 8, (8, 7))
    >>> store.read_chunk(1).metrics["fuel_used"].shape
    (4,)
    """

    path: Path
    key: CampaignKey
    completed: dict[int, dict[str, Any]] = field(default_factory=dict)
    layout: dict[str, Any] = field(default_factory=dict)
    #: Held from :meth:`open` to :meth:`close` (by the process writing the store).
    lock: Optional[WriterLock] = None
    #: The (folder, chunk) Parquet parts already checked in this session (each is read once).
    checked: set[tuple[str, int]] = field(default_factory=set, repr=False)

    # -- opening --

    @staticmethod
    def open(path: Union[str, os.PathLike], key: CampaignKey, *, threads: Optional[int], check_bounds: bool,
             record_every: int, one_case: Callable[[], SimulationResult]) -> CampaignStore:
        """Open (resume) the campaign at ``path`` or create it; a store written by another campaign is
        refused with what differs. A new store's Zarr tree is created here, once, with the shapes of
        ``one_case()`` (one case of the campaign run: the time grid, the names, the diagnostics and
        the metric columns as the core gives them).

        Parameters
        ----------
        path : str or os.PathLike
            The store's directory (new, empty, or this campaign's store).
        key : CampaignKey
            The campaign.
        threads : int or None
            The threads the run uses (recorded in the provenance).
        check_bounds : bool
            Whether the run checks the theory's bounds (recorded).
        record_every : int
            The decimation (recorded).
        one_case : callable
            Runs case 0 as the campaign does.

        Returns
        -------
        CampaignStore
            The store, its writer lock held until :meth:`close`.
        """
        require_io("pyarrow", "pyarrow.parquet", "zarr", "xarray", "pandas", what="monte_carlo(store=...)")
        path = Path(path)
        prov_path = path / PROVENANCE
        own = {LOCK, HOLDER}
        if not prov_path.exists() and path.exists() and (
                not path.is_dir() or any(p.name not in own for p in path.iterdir())):
            raise ParameterError(
                f"store = '{path}' exists and is not a campaign store (no {PROVENANCE}); "
                "give a new or empty directory"
            )
        path.mkdir(parents=True, exist_ok=True)
        lock = WriterLock(path)
        lock.acquire()
        try:
            store = CampaignStore._open_locked(path, key, threads=threads, check_bounds=check_bounds,
                                               record_every=record_every, one_case=one_case)
        except BaseException:
            lock.release()
            raise
        store.lock = lock
        return store

    def close(self) -> None:
        """Releases the store's writer lock (the campaign's end, or its interruption)."""
        if self.lock is not None:
            self.lock.release()
            self.lock = None

    @staticmethod
    def _open_locked(path: Path, key: CampaignKey, *, threads: Optional[int], check_bounds: bool,
                     record_every: int, one_case: Callable[[], SimulationResult]) -> CampaignStore:
        prov_path = path / PROVENANCE
        if prov_path.exists():
            prov = _read_record(path, PROVENANCE)
            stored = _key_of(path, prov)
            if not isinstance(prov.get("sessions"), list):
                raise StoreError(f"store = '{path}': its {PROVENANCE} ({prov_path}) does not list its sessions; "
                                 f"{_REMEDY_RECORD}")
            diffs = key.differences(stored)
            if diffs:
                raise ParameterError(
                    f"store = '{path}' holds another campaign, so it cannot be resumed by this one "
                    "(a store resumes only the same scenario, seed, n, chunk_size, record settings and "
                    "package version):\n  " + "\n  ".join(diffs)
                    + "\nuse another directory, or delete this one to start again"
                )
            # no manifest yet: created, then stopped before anything completed
            manifest = _read_record(path, MANIFEST) if (path / MANIFEST).exists() else {"chunks": []}
            store = CampaignStore(path, key, _chunks_of(path, manifest, key), manifest.get("layout", {}))
            store.check_tree()
        else:
            (path / METRICS_DIR).mkdir(parents=True, exist_ok=True)
            (path / INITIAL_DIR).mkdir(parents=True, exist_ok=True)
            prov = {
                "format": STORE_FORMAT,
                "package": "landing",
                "version": key.version,
                "scenario": key.scenario,
                "seed": key.seed,
                "n": key.n,
                "chunk_size": key.chunk_size,
                "record_every": record_every,
                "keep": list(key.keep),
                "check_bounds": bool(check_bounds),
                "created": _now(),
                "sessions": [],
                "key": key.to_json(),
            }
            _write_json_atomic(prov_path, prov)
            store = CampaignStore(path, key)
        if not store.layout:
            # a new store (or one whose creation was interrupted before its manifest): its Zarr
            # tree for the whole campaign, then the manifest that records its layout
            store._create_trajectories(one_case())
            store._write_manifest()
        prov["sessions"].append({"started": _now(), "machine": machine(), "threads": threads,
                                 "threads_used": threads or os.cpu_count(), "kernel": None,
                                 "resumed_chunks": len(store.completed)})
        _write_json_atomic(prov_path, prov)
        return store

    @property
    def n_chunks(self) -> int:
        """The number of chunks the campaign is cut into."""
        return -(-self.key.n // self.key.chunk_size)

    @property
    def completed_cases(self) -> int:
        """How many cases the completed chunks hold."""
        return int(sum(c["stop"] - c["start"] for c in self.completed.values()))

    def is_complete(self, index: int) -> bool:
        """Whether chunk ``index`` is complete.

        Parameters
        ----------
        index : int
            The chunk.

        Returns
        -------
        bool
            True when the manifest names it complete.
        """
        return index in self.completed

    def forget(self, index: int) -> None:
        """Chunk ``index`` no longer complete (found damaged): the manifest stops naming it, so that it
        is run and written again.

        Parameters
        ----------
        index : int
            The chunk.
        """
        self.completed.pop(index, None)
        self.checked = {k for k in self.checked if k[1] != index}
        self._write_manifest()

    def resume_chunk(self, index: int) -> Optional[SimulationResult]:
        """What a resumed campaign takes from the store for chunk ``index``: the chunk, or None when it
        must run (not complete, or damaged: then forgotten, with a StoreWarning naming the damage, and
        run and written again).

        Parameters
        ----------
        index : int
            The chunk.

        Returns
        -------
        landing.SimulationResult or None
            The chunk's cases, or None.
        """
        if not self.is_complete(index):
            return None
        try:
            return self.read_chunk(index)
        except StoreError as exc:
            warnings.warn(f"{exc}: running it again", StoreWarning, stacklevel=4)
            self.forget(index)
            return None

    def _write_manifest(self) -> None:
        chunks = [self.completed[i] for i in sorted(self.completed)]
        _write_json_atomic(self.path / MANIFEST, {
            "format": STORE_FORMAT,
            "n": self.key.n,
            "chunk_size": self.key.chunk_size,
            "n_chunks": self.n_chunks,
            "completed_cases": self.completed_cases,
            "complete": len(chunks) == self.n_chunks,
            "updated": _now(),
            "layout": self.layout,
            "chunks": chunks,
        })

    def _note_kernel(self, kernel: str) -> None:
        prov_path = self.path / PROVENANCE
        prov = json.loads(prov_path.read_text())
        session = prov["sessions"][-1]
        if session.get("kernel") is None:
            session["kernel"] = kernel
            _write_json_atomic(prov_path, prov)

    # -- trajectories --

    def _zarr_group(self, mode: str) -> Any:
        zarr = require_io("zarr", what="the campaign store")
        root = self.path / TRAJECTORIES
        try:
            return zarr.open_group(str(root), mode=mode)
        except Exception as exc:  # noqa: BLE001 - any failure to open it is damage, named
            raise StoreError(
                f"store = '{self.path}': its Zarr tree ({root}) cannot be opened ({type(exc).__name__}: {exc}); "
                "delete the directory and run the campaign again") from None

    def check_tree(self) -> None:
        """The Zarr tree as created: each of its files (metadata, coordinates) the checksum the
        manifest records, every array of the layout and the coordinates readable (what
        ``xarray.open_zarr`` needs), the ``case`` coordinate the campaign's cases."""
        if not self.layout:
            return
        root = self.path / TRAJECTORIES
        for rel, expected in self.layout.get("tree_sha256", {}).items():
            file = root / rel
            try:
                ok = hashlib.sha256(file.read_bytes()).hexdigest() == expected
                why = "does not match its checksum in the manifest"
            except OSError as exc:
                ok, why = False, f"cannot be read ({exc.strerror})"
            if not ok:
                raise StoreError(f"store = '{self.path}': its Zarr tree is damaged: {file} {why}; delete the "
                                 "directory and run the campaign again")
        group = self._zarr_group("r")
        names = list(self.layout["arrays"]) + ["case", "time", "state", "state_units"]
        if self.layout["control_names"]:
            names += ["control", "control_units"]
        try:
            present = set(group.array_keys())
            arrays = {name: group[name] for name in names if name in present}
            for name in present - set(arrays):
                group[name]  # noqa: B018 - its metadata read: a damaged one fails here
            case = arrays["case"][:] if "case" in arrays else None
        except Exception as exc:  # noqa: BLE001 - any failure to read it is damage, named
            raise StoreError(f"store = '{self.path}': its Zarr tree ({root}) is damaged ({type(exc).__name__}: "
                             f"{exc}); delete the directory and run the campaign again") from None
        missing = [name for name in names if name not in arrays]
        if missing or case is None or not np.array_equal(case, np.arange(self.key.n)):
            what = f"lacks {missing}" if missing else "has not the campaign's cases as its case coordinate"
            raise StoreError(f"store = '{self.path}': its Zarr tree ({root}) {what}; delete the directory and run "
                             "the campaign again")

    def _create_trajectories(self, part: SimulationResult) -> None:
        """The Zarr store's arrays, for the whole campaign, from one case's shapes (at the
        store's creation; chunks then write regions of them, never the tree); the
        chunking along ``case`` is the campaign's (a divisor of it for large chunks), so each
        campaign chunk writes whole Zarr chunks."""
        zarr, xr = require_io("zarr", "xarray", what="the campaign store")
        n, T = self.key.n, part.t.size
        root = self.path / TRAJECTORIES
        axes = part.axis_names
        coords = {"case": ("case", np.arange(n, dtype=np.int64)),
                  **dataset_coords(part.t, part.state_names, part.control_names, axes)}
        # Zarr format 2: its fixed-width strings and consolidated metadata are part of the
        # format (zarr-python 3 still writes it; xarray reads either)
        fmt = {"zarr_format": 2} if int(zarr.__version__.split(".")[0]) >= 3 else {}
        xr.Dataset(coords=coords, attrs={"campaign": "landing Monte Carlo", "seed": self.key.seed,
                                         "n": n}).to_zarr(str(root), mode="w", consolidated=False, **fmt)
        group = zarr.open_group(str(root), mode="r+")
        arrays: dict[str, tuple[tuple[int, ...], tuple[str, ...], dict[str, Any]]] = {
            "final_state": ((len(part.state_names),), ("case", "state"),
                            {"long_name": "state at t_final", "units_by": "state_units"}),
        }
        if "states" in self.key.keep:
            arrays["states"] = ((T, len(part.state_names)), ("case", "time", "state"),
                                {"long_name": "state at the recorded instants", "units_by": "state_units"})
        if "controls" in self.key.keep:
            arrays["controls"] = ((T, len(part.control_names)), ("case", "time", "control"),
                                  {"long_name": "command applied after saturation", "units_by": "control_units"})
        if "diagnostics" in self.key.keep:
            for name, v in part.diagnostics.items():
                arrays[name] = ((T,) + v.shape[2:], ("case", "time") + (("axis",) if v.ndim == 3 else ()),
                                {"long_name": f"law diagnostic {name}"})
        for name, (tail, dims, attrs) in arrays.items():
            row_bytes = 8 * int(np.prod(tail, dtype=np.int64))
            zc = self.key.chunk_size
            while zc > 1 and zc * row_bytes > 64 * 2**20:  # keep Zarr chunks under 64 MiB
                zc = next(d for d in range(zc - 1, 0, -1) if self.key.chunk_size % d == 0)
            _zarr_create(group, name, (n,) + tail, (zc,) + tail, np.float64, dims, attrs)
        zarr.consolidate_metadata(str(root))
        # the tree as created (metadata and coordinates; chunks only ever add their own files)
        tree = {p.relative_to(root).as_posix(): hashlib.sha256(p.read_bytes()).hexdigest()
                for p in sorted(root.rglob("*")) if p.is_file()}
        self.layout = {
            "tree_sha256": tree,
            "arrays": list(arrays),
            "diagnostics": [name for name in part.diagnostics if name in arrays],
            "state_names": list(part.state_names),
            "control_names": list(part.control_names),
            "axis_names": list(axes),
            "metrics": metrics_layout(part.metrics, axes),
        }

    # -- writing and reading chunks --

    def write_chunk(self, index: int, start: int, stop: int, part: SimulationResult, x0: np.ndarray,
                    draws: Optional[np.ndarray]) -> None:
        """Write chunk ``index`` (cases start..stop): Parquet files and the Zarr region, made durable,
        then the manifest naming it complete. A failure of the file system (a full disk, a
        permission) is a StoreError naming the file and the remedy; the chunk is then not complete,
        and a resume writes it again.

        Parameters
        ----------
        index : int
            The chunk.
        start, stop : int
            Its cases, ``start`` to ``stop - 1``.
        part : landing.SimulationResult
            The chunk's runs.
        x0 : numpy.ndarray
            Its initial states, (stop - start, state_dim).
        draws : numpy.ndarray or None
            Its dispersion draws, if any.
        """
        try:
            self._write_chunk(index, start, stop, part, x0, draws)
        except OSError as exc:
            where = f" {exc.filename}" if getattr(exc, "filename", None) else ""
            full = getattr(exc, "errno", None) == errno.ENOSPC or "No space left" in str(exc)
            remedy = ("free space and run the same monte_carlo(..., store=...) call again to resume" if full
                      else "fix it and run the same monte_carlo(..., store=...) call again to resume")
            raise StoreError(f"store = '{self.path}': writing chunk {index} (cases {start}..{stop - 1}) failed"
                             f"{where}: {exc.strerror or exc}; {remedy}") from exc

    def _write_chunk(self, index: int, start: int, stop: int, part: SimulationResult, x0: np.ndarray,
                     draws: Optional[np.ndarray]) -> None:
        pa, pq = require_io("pyarrow", "pyarrow.parquet", what="the campaign store")
        case = np.arange(start, stop, dtype=np.int64)
        axes = tuple(self.layout["axis_names"])
        files = []
        metrics = {"case": case, **flat_columns(part.metrics, axes)}
        initial: dict[str, np.ndarray] = {"case": case}
        for j, name in enumerate(self.layout["state_names"]):
            initial[f"x0_{name}"] = x0[:, j]
        if draws is not None:
            for j in range(draws.shape[1]):
                initial[f"draw_{j}"] = draws[:, j]
        units = flat_metric_units(self.layout["state_names"], self.layout["control_names"], axes)
        for folder, columns in ((METRICS_DIR, metrics), (INITIAL_DIR, initial)):
            target = self.path / folder / _part(index)
            tmp = target.with_name(f".{target.name}.tmp")  # hidden from Parquet dataset readers
            table = pa.table(columns)
            # each metric column carries its unit (the core's declaration) in its field metadata
            table = table.cast(pa.schema([f.with_metadata({"units": units[f.name]}) if f.name in units else f
                                          for f in table.schema]))
            pq.write_table(table, str(tmp))
            _fsync_file(tmp)
            os.replace(tmp, target)
            files.append(target)
        group = self._zarr_group("r+")
        signals = {"final_state": part.final_state, "states": part.states, "controls": part.controls,
                   **part.diagnostics}
        for name in self.layout["arrays"]:
            arr = group[name]
            arr[start:stop] = signals[name]  # a region write of whole Zarr chunks
            zc = arr.chunks[0]
            for i in range(start // zc, (stop - 1) // zc + 1):  # format 2 keys: "i.0.0"
                chunk_file = self.path / TRAJECTORIES / name / ".".join([str(i)] + ["0"] * (arr.ndim - 1))
                if chunk_file.exists():  # an all-NaN chunk is not written
                    _fsync_file(chunk_file)
        for folder in (METRICS_DIR, INITIAL_DIR):
            _fsync_dir(self.path / folder)
        self._note_kernel(part.kernel)
        digests = {"metrics": _digest(metrics), "initial": _digest(initial),
                   "trajectories": _digest({name: signals[name] for name in self.layout["arrays"]})}
        self.completed[index] = {"index": index, "start": start, "stop": stop, "kernel": part.kernel,
                                 "written": _now(), "sha256": digests}
        try:
            self._write_manifest()
        except BaseException:
            # not in the manifest, so not kept: what an interruption reports is what a resume finds
            del self.completed[index]
            raise

    def check_layout(self, scenario: Scenario) -> None:
        """The trajectories' layout against the provenance: the kept signals are the arrays present, and
        the time grid is the scenario's instants at ``record_every``.

        Parameters
        ----------
        scenario : landing.scenarios.Scenario
            The campaign's scenario.
        """
        if not self.layout or not self.completed:
            return
        present = set(self.layout["arrays"]) - {"final_state"} - set(self.layout["diagnostics"])
        kept = {k for k in self.key.keep if k != "diagnostics"}
        if present != kept or (bool(self.layout["diagnostics"]) and "diagnostics" not in self.key.keep):
            raise StoreError(f"store = '{self.path}': it keeps {sorted(self.layout['arrays'])} but its provenance "
                             f"says keep = {list(self.key.keep)}: the record or the data was changed")
        t = self._zarr_group("r")["time"][:]
        steps = round(scenario.t_final / scenario.dt)
        every = self.key.record_every
        k = np.arange(0, steps + 1, every) if every else np.zeros(0, dtype=np.int64)
        if k.size and k[-1] != steps:
            k = np.append(k, steps)  # the last instant is recorded too
        expected = k * scenario.dt
        if t.shape != expected.shape or not np.allclose(t, expected, rtol=1e-12, atol=1e-12 * scenario.t_final):
            raise StoreError(f"store = '{self.path}': its time grid ({t.size} instants) is not the scenario's at "
                             f"record_every = {every} ({expected.size} instants of t_final = {scenario.t_final:g} s, "
                             f"dt = {scenario.dt:g} s): the record or the data was changed")

    def check_a_case(self, scenario: Scenario, x0: np.ndarray) -> None:
        """The first completed case run again from the provenance's scenario and seed: its final state
        must be the stored one (a scenario text edited after the run, in a way the initial states do
        not show, is found here). One case: milliseconds.

        Parameters
        ----------
        scenario : landing.scenarios.Scenario
            The campaign's scenario.
        x0 : numpy.ndarray
            The campaign's initial states, (n, state_dim).
        """
        if not self.completed:
            return
        c = self.completed[min(self.completed)]
        i = int(c["start"])
        stored = self._zarr_group("r")["final_state"][i]
        again = scenario.simulate_cases(x0[i:i + 1], i, self.key.n, seed=self.key.seed, record_every=0)
        # every value the same (a NaN of a diverged case may read back as the fill's NaN)
        if not np.array_equal(np.asarray(again.final_state[0]), np.asarray(stored), equal_nan=True):
            raise StoreError(f"store = '{self.path}': case {i} run again from the scenario and seed its provenance "
                             "records does not end where the stored one does: the record or the data was changed")

    def _damaged(self, index: int, what: str, file: Path, why: str) -> StoreError:
        c = self.completed[index]
        return StoreError(
            f"store = '{self.path}': chunk {index} (cases {c['start']}..{c['stop'] - 1}) is damaged: its {what} "
            f"({file}) {why}; monte_carlo(..., store='{self.path}') re-runs the damaged chunks")

    def _table(self, index: int, folder: Path, what: str) -> Any:
        """Chunk ``index``'s Parquet table in ``folder``, checked against the manifest: readable,
        its ``case`` column the chunk's cases, its content's checksum the one written."""
        pq = require_io("pyarrow.parquet", what="the campaign store")
        file = self.path / folder / _part(index)
        c = self.completed[index]
        try:
            table = pq.read_table(str(file))
            columns = {name: table.column(name).to_numpy() for name in table.schema.names}
        except Exception as exc:  # noqa: BLE001 - any failure to read it is damage, named
            raise self._damaged(index, what, file, f"cannot be read ({type(exc).__name__}: {exc})") from None
        case = columns.get("case")
        if case is None or not np.array_equal(case, np.arange(c["start"], c["stop"])):
            raise self._damaged(index, what, file, "does not hold the chunk's cases (its 'case' column)")
        expected = c.get("sha256", {}).get(what)
        if expected is not None and _digest(columns) != expected:
            raise self._damaged(index, what, file, "does not match its checksum in the manifest")
        self.checked.add((str(folder), index))
        return table

    def read_metrics(self, index: int) -> dict[str, np.ndarray]:
        """Chunk ``index``'s metric columns, put back together (dtypes as written), checked.

        Parameters
        ----------
        index : int
            A completed chunk.

        Returns
        -------
        dict of str to numpy.ndarray
            The metric columns, in their units.
        """
        table = self._table(index, METRICS_DIR, "metrics")
        out = {}
        for name, dtype, parts in self.layout["metrics"]:
            if parts is None:
                out[name] = _column(table, name, dtype)
            else:
                out[name] = np.stack([_column(table, p, dtype) for p in parts], axis=1)
        return out

    def read_chunk(self, index: int) -> SimulationResult:
        """A completed chunk as the batch result it was (what was not kept is None/empty).

        Parameters
        ----------
        index : int
            A completed chunk.

        Returns
        -------
        landing.SimulationResult
            The chunk's cases.
        """
        c = self.completed[index]
        start, stop = c["start"], c["stop"]
        if (str(INITIAL_DIR), index) not in self.checked:  # its initial states too: damage anywhere is named
            self._table(index, INITIAL_DIR, "initial")
        root = self.path / TRAJECTORIES
        try:
            group = self._zarr_group("r")
            arrays = {name: group[name][start:stop] for name in self.layout["arrays"]}
            t = group["time"][:]
        except Exception as exc:  # noqa: BLE001 - any failure to read them is damage, named
            raise self._damaged(index, "trajectories", root, f"cannot be read ({type(exc).__name__}: {exc})") from None
        if any(a.shape[0] != stop - start for a in arrays.values()):
            raise self._damaged(index, "trajectories", root, "do not extend over the chunk's cases")
        expected = c.get("sha256", {}).get("trajectories")
        if expected is not None and _digest(arrays) != expected:
            # a chunk file deleted reads as its fill value: damage, never fill
            raise self._damaged(index, "trajectories", root, "do not match their checksum in the manifest")
        return SimulationResult(
            t=t,
            states=arrays.get("states"),
            controls=arrays.get("controls"),
            final_state=arrays["final_state"],
            diagnostics={k: arrays[k] for k in self.layout["diagnostics"]},
            metrics=Metrics(self.read_metrics(index)),
            state_names=tuple(self.layout["state_names"]),
            control_names=tuple(self.layout["control_names"]),
            kernel=c["kernel"],
        )

    def signals(self, result: SimulationResult, rows: Optional[np.ndarray] = None) -> StoredResult:
        """``result`` (the campaign's final states and metrics, its cases ``rows`` of the campaign,
        default all) with the recorded signals this store keeps as :class:`StoredArray` views of its
        Zarr tree: read on demand (:mod:`landing.campaign.lazy`), never held here.

        Parameters
        ----------
        result : landing.SimulationResult
            The campaign's final states and metrics.
        rows : numpy.ndarray, optional
            The campaign's cases it holds (default all).

        Returns
        -------
        landing.campaign.lazy.StoredResult
            The result with lazy signals.
        """
        group = self._zarr_group("r")
        root = self.path / TRAJECTORIES
        arrays: dict[str, np.ndarray] = {}
        for name in self.layout["arrays"]:
            if name == "final_state":
                continue
            stored = group[name]
            lazy = StoredArray.open(root, name, tuple(stored.shape), int(stored.chunks[0]), stored.dtype)
            # the field is typed as an array: a StoredArray stands for one (shape, dtype, indexing,
            # np.asarray), read only
            arrays[name] = cast(np.ndarray, lazy if rows is None else lazy[rows])
        return StoredResult(
            t=result.t,
            states=arrays.get("states"),
            controls=arrays.get("controls"),
            final_state=result.final_state,
            diagnostics={k: arrays[k] for k in self.layout["diagnostics"]},
            metrics=result.metrics,
            state_names=result.state_names,
            control_names=result.control_names,
            kernel=result.kernel,
        )

    def read_initial(self) -> np.ndarray:
        """The initial states of every completed chunk, in case order.

        Returns
        -------
        numpy.ndarray
            (n, n_state) (m, m/s, kg); NaN rows for the chunks not completed.
        """
        names = [f"x0_{s}" for s in self.layout["state_names"]]
        x0 = np.full((self.key.n, len(names)), np.nan)
        for index, c in self.completed.items():
            table = self._table(index, INITIAL_DIR, "initial")
            for j, name in enumerate(names):
                x0[c["start"]:c["stop"], j] = _column(table, name, "<f8")
        return x0


def default_chunk_size(n: int) -> int:
    """Cases per chunk of a stored, cluster or progress-bar campaign when none is given: max(1000, n / 50) (at
    most n); at a few ms of scheduling per chunk that keeps the overhead small for any scenario
    longer than a few steps (BENCHMARKS.md measures it).

    Parameters
    ----------
    n : int
        The campaign's cases.

    Returns
    -------
    int
        Cases per chunk.

    Examples
    --------
    >>> from landing.campaign.store import default_chunk_size
    >>> default_chunk_size(500), default_chunk_size(10_000), default_chunk_size(200_000)
    (500, 1000, 4000)
    """
    return min(n, max(1000, -(-n // 50)))


def store_path(path: Any) -> Path:
    """``monte_carlo``'s ``store`` argument as a path (a ParameterTypeError for anything else).

    Parameters
    ----------
    path : str or os.PathLike
        The store's directory.

    Returns
    -------
    pathlib.Path
        The path.

    Examples
    --------
    >>> from landing.campaign.store import store_path
    >>> store_path("runs/mars").name
    'mars'
    """
    if not isinstance(path, (str, os.PathLike)):
        raise ParameterTypeError(f"store must be a directory path (str or os.PathLike), got {path!r}")
    return Path(path)


def store_chunk_size(path: Union[str, os.PathLike], n: int, chunk_size: Optional[int]) -> int:
    """The cases per chunk of the campaign stored at ``path``: ``chunk_size`` when given, else the
    store's own when it exists (a resumed campaign keeps its chunking), else
    :func:`default_chunk_size`.

    Parameters
    ----------
    path : str or os.PathLike
        The store's directory (it need not exist).
    n : int
        The campaign's cases.
    chunk_size : int or None
        The chunk size asked for.

    Returns
    -------
    int
        Cases per chunk.

    Examples
    --------
    >>> import tempfile, landing
    >>> from landing.campaign.store import read_campaign_store
    >>> path = tempfile.mkdtemp() + "/campaign"
    >>> scenario = landing.scenarios.preset("mars_monte_carlo").replace(t_final=5.0)
    >>> mc = landing.monte_carlo(scenario, n=8, seed=1, store=path, chunk_size=4)
    >>> store, scenario, x0, check_bounds = read_campaign_store(path)
    >>> from landing.campaign.store import store_chunk_size
    >>> store_chunk_size(path, 8, None), store_chunk_size(path + "-new", 100_000, None)
    (4, 2000)
    """
    if chunk_size is not None:
        return chunk_size
    path = store_path(path)
    if (path / PROVENANCE).exists():
        return _key_of(path, _read_record(path, PROVENANCE)).chunk_size
    return default_chunk_size(n)


def open_campaign_store(
    path: Union[str, os.PathLike],
    scenario: Scenario,
    *,
    seed: int,
    n: int,
    x0: np.ndarray,
    keep: Sequence[str],
    record_every: int,
    chunk_size: Optional[int],
    threads: Optional[int],
    check_bounds: bool,
) -> CampaignStore:
    """The store of ``monte_carlo(..., store=path)``: created, or resumed when it holds this
    campaign. Without a chunk size a resumed store keeps its own and a new one takes
    ``max(1000, n / 50)`` cases per chunk (at most n). Needs ``pip install "landing[io]"``.

    Parameters
    ----------
    path : str or os.PathLike
        The store's directory.
    scenario : landing.scenarios.Scenario
        The campaign's scenario.
    seed, n : int
        The campaign's seed and cases.
    x0 : numpy.ndarray
        The campaign's initial states, (n, state_dim).
    keep : sequence of str
        The recorded signals kept.
    record_every : int
        The decimation.
    chunk_size : int or None
        Cases per chunk.
    threads : int or None
        The run's threads (recorded).
    check_bounds : bool
        Whether the run checks the theory's bounds (recorded).

    Returns
    -------
    CampaignStore
        The store, its writer lock held: :meth:`CampaignStore.close` releases it.

    Examples
    --------
    >>> import tempfile, landing
    >>> from landing.campaign.store import open_campaign_store
    >>> scenario = landing.scenarios.preset("mars_monte_carlo").replace(t_final=5.0)
    >>> x0 = scenario.initial_states(8, seed=1)
    >>> store = open_campaign_store(tempfile.mkdtemp() + "/c", scenario, seed=1, n=8, x0=x0, keep=("states",),
    ...                             record_every=50, chunk_size=4, threads=None, check_bounds=True)
    >>> store.n_chunks, store.completed_cases
    (2, 0)
    >>> store.close()
    """
    require_io("pyarrow", "pyarrow.parquet", "zarr", "xarray", "pandas", what="monte_carlo(store=...)")
    path = store_path(path)
    chunk_size = store_chunk_size(path, n, chunk_size)
    key = CampaignKey.of(scenario, seed=seed, n=n, chunk_size=chunk_size, record_every=record_every,
                         keep=keep, x0=x0)

    def one_case() -> SimulationResult:
        # case 0 as the campaign runs it: what the new store's Zarr tree is shaped after
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", DivergenceWarning)
            return scenario.simulate_cases(x0[:1], 0, n, seed=seed, threads=1, record_every=record_every)

    return CampaignStore.open(path, key, threads=threads, check_bounds=check_bounds, record_every=record_every,
                              one_case=one_case)


def _digest(columns: Mapping[str, Any]) -> str:
    """SHA-256 of named arrays' content: each name, dtype, shape and C-order bytes, in order.
    Of what a chunk holds, not of its files' bytes: the same whatever the compression."""
    h = hashlib.sha256()
    for name, v in columns.items():
        a = np.ascontiguousarray(v)
        if a.dtype.kind == "f":
            # one NaN: a Zarr chunk that was all NaN is not written and reads back as the fill value
            a = np.where(np.isnan(a), np.nan, a)
        h.update(f"{name}|{a.dtype.str}|{a.shape}|".encode())
        h.update(a.tobytes())
    return h.hexdigest()


def _column(table: Any, name: str, dtype: str) -> np.ndarray:
    return np.asarray(table.column(name).to_numpy(), dtype=np.dtype(dtype))


# --- reading ------------------------------------------------------------------------------------------


def read_campaign_store(
    path: Union[str, os.PathLike], *, scenario: Optional[Scenario] = None, partial: bool = False
) -> tuple[CampaignStore, Scenario, np.ndarray, bool]:
    """The campaign stored at ``path``, open for reading: its store, its scenario (the one given,
    checked against the stored text, or rebuilt from that text), its initial states (checked
    against the provenance record; with ``partial``, the completed chunks' rows against the
    scenario's draws, the others NaN) and whether its run checked the bounds. An interrupted
    campaign is refused unless ``partial``. What :func:`landing.load` assembles the result from.
    Needs ``pip install "landing[io]"``.

    Parameters
    ----------
    path : str or os.PathLike
        The store's directory.
    scenario : landing.scenarios.Scenario, optional
        The campaign's scenario, checked against the stored one.
    partial : bool, default False
        Whether an interrupted campaign is read.

    Returns
    -------
    tuple
        ``(store, scenario, x0, check_bounds)``: the :class:`CampaignStore`, the scenario, the
        initial states (n, state_dim) and whether the run checked the bounds.

    Examples
    --------
    >>> import tempfile, landing
    >>> from landing.campaign.store import read_campaign_store
    >>> path = tempfile.mkdtemp() + "/campaign"
    >>> scenario = landing.scenarios.preset("mars_monte_carlo").replace(t_final=5.0)
    >>> mc = landing.monte_carlo(scenario, n=8, seed=1, store=path, chunk_size=4)
    >>> store, scenario, x0, check_bounds = read_campaign_store(path)
    >>> store.n_chunks, scenario.name, x0.shape, check_bounds
    (2, 'mars_monte_carlo', (8, 7), True)
    """
    require_io("pyarrow", "pyarrow.parquet", "zarr", "xarray", "pandas", what="landing.load")
    path = Path(path)
    prov_path = path / PROVENANCE
    if not prov_path.is_file():
        raise ParameterError(f"path = '{path}' is not a campaign store: it has no {PROVENANCE}")
    prov = _read_record(path, PROVENANCE)
    key = _key_of(path, prov)
    text = key.scenario
    if scenario is None:
        scenario = _scenario_from_text(text)
        if scenario is None:
            raise ParameterError(
                f"the scenario of the store at '{path}' cannot be rebuilt from its text (not a scenario "
                f"file); pass it: landing.load(path, scenario=...). The stored scenario:\n{text}"
            )
    elif _scenario_text(scenario) != text:
        raise ParameterError(
            f"scenario = {scenario.name!r} is not the scenario of the store at '{path}': "
            + _scenario_differences(text, _scenario_text(scenario))
        )
    manifest = _read_record(path, MANIFEST)
    if manifest.get("format") != STORE_FORMAT or prov.get("format", STORE_FORMAT) != STORE_FORMAT:
        raise StoreError(f"store = '{path}': format {short(manifest.get('format'))} is not this version's "
                         f"({STORE_FORMAT}); read it with the landing version that wrote it ({short(key.version)})")
    store = CampaignStore(path, key, _chunks_of(path, manifest, key), manifest.get("layout", {}))
    store.check_tree()
    complete = len(store.completed) == store.n_chunks
    if not complete and not partial:
        raise ParameterError(
            f"the campaign at '{path}' is incomplete ({manifest['completed_cases']} of {key.n} cases in "
            f"{len(store.completed)} of {store.n_chunks} chunks); re-run landing.monte_carlo with "
            "store= this path to complete it, or load the completed cases: landing.load(path, partial=True)"
        )
    x0 = store.read_initial()
    # the provenance against the data: its labels are believed only where the data agree
    done = np.isfinite(x0).all(axis=1)
    drawn = scenario.initial_states(key.n, seed=key.seed)
    if not np.array_equal(x0[done], drawn[done]):
        raise StoreError(f"store = '{path}': its initial states are not the draws of the scenario and seed "
                         f"({key.seed}) its provenance records: the record or the data was changed")
    if complete:
        expected = CampaignKey.of(scenario, seed=key.seed, n=key.n, chunk_size=key.chunk_size,
                                  record_every=key.record_every, keep=key.keep, x0=x0)
        if expected.x0_sha256 != key.x0_sha256:
            raise StoreError(f"store = '{path}': its initial states do not match its provenance record")
    store.check_layout(scenario)
    store.check_a_case(scenario, x0)
    return store, scenario, x0, bool(prov.get("check_bounds", True))
