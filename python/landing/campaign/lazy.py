"""A stored campaign's recorded signals, read from its Zarr tree on demand.

A campaign run or loaded with a store (``monte_carlo(..., store=DIR)``, ``landing.load(DIR)``)
holds its per-case metrics, initial states and final states in memory (a few hundred bytes a
case) and leaves its recorded signals (states, controls, diagnostics: most of its size) in the
store: ``mc.result.states`` is a :class:`StoredArray`, a read-only array that reads what is
asked of it, when it is asked:

- selecting cases (a slice, an integer index array or a boolean mask on the first axis, the
  other axes whole: ``states[a:b]``, ``result.cases(a, b)``) gives a lazy view of them, which
  reads nothing yet;
- any other index (a case number, an instant, a component: ``states[17]``,
  ``states[:, -1, 2]``) reads what it selects into a numpy array, and ``np.asarray(states)``
  reads the whole (view);
- the Zarr chunks are read whole, one at a time, the last one cached per array: reading cases
  slice by slice in order decompresses each chunk once.

The campaign's own uses read slice by slice (the theory's checks, ``mc.bands`` over blocks of
instants, the figures' first cases); ``mc.to_xarray()`` gives a Dataset whose signals are
xarray's lazily indexed Zarr variables.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Iterator
from pathlib import Path
from typing import TYPE_CHECKING, Any, Optional, Union

import numpy as np

from landing.results import SimulationResult, require_io, result_dataset

if TYPE_CHECKING:  # pragma: no cover
    import xarray

__all__ = ["StoredArray", "StoredResult", "in_memory", "stored_dataset"]

#: A selection along one axis of the stored array: an index (the axis dropped) or indices.
_Selector = Union[int, np.ndarray]


class _ZarrSource:
    """One array of a store's Zarr tree, opened read-only on first use; its Zarr chunks (along
    the case axis) are read whole, the last one kept."""

    def __init__(self, root: Path, name: str, shape: tuple[int, ...], dtype: np.dtype, rows_per_chunk: int):
        self.root = root
        self.name = name
        self.shape = shape
        self.dtype = dtype
        self.rows_per_chunk = rows_per_chunk
        self._array: Any = None
        self._cached: tuple[int, Optional[np.ndarray]] = (-1, None)

    def __getstate__(self) -> dict[str, Any]:  # pickled without the open array and the cache
        return {**self.__dict__, "_array": None, "_cached": (-1, None)}

    def chunk(self, index: int) -> np.ndarray:
        """Rows ``index * rows_per_chunk`` up to the next chunk's: one Zarr chunk, decoded."""
        if self._cached[0] == index:
            block = self._cached[1]
            assert block is not None
            return block
        if self._array is None:
            zarr = require_io("zarr", what="reading a stored campaign's signals")
            self._array = zarr.open_group(str(self.root), mode="r")[self.name]
        start = index * self.rows_per_chunk
        block = np.asarray(self._array[start:min(self.shape[0], start + self.rows_per_chunk)])
        self._cached = (index, None)  # the old block freed before the new one is kept
        self._cached = (index, block)
        return block


class StoredArray:
    """A read-only array of a campaign store's Zarr tree (case first), read on demand: see
    :mod:`landing.campaign.lazy`. ``shape``, ``dtype``, ``ndim``, ``len()``, iteration over the
    cases, numpy indexing and ``np.asarray`` work as on the array it stands for, and give the same
    bits. Made by the store (:meth:`StoredArray.open`); the values are in the signal's units (m,
    m/s, kg for the states, N for the commands).

    Parameters
    ----------
    source : _ZarrSource
        The Zarr array it reads.
    select : tuple, optional
        The view's selection per axis (default: the whole array).

    Examples
    --------
    >>> import tempfile, numpy as np, landing
    >>> scenario = landing.scenarios.preset("mars_monte_carlo").replace(t_final=5.0)
    >>> mc = landing.monte_carlo(scenario, n=8, seed=1, store=tempfile.mkdtemp() + "/campaign", chunk_size=4)
    >>> states = mc.states
    >>> type(states).__name__, states.shape
    ('StoredArray', (8, 101, 7))
    >>> type(states[2:4]).__name__, type(states[2]).__name__  # cases: a lazy view; a case: read
    ('StoredArray', 'ndarray')
    >>> bool(np.array_equal(np.asarray(states)[2], states[2]))
    True
    """

    __slots__ = ("_source", "_select")

    def __init__(self, source: _ZarrSource, select: Optional[tuple[_Selector, ...]] = None):
        self._source = source
        self._select: tuple[_Selector, ...] = (
            select if select is not None else tuple(np.arange(n, dtype=np.intp) for n in source.shape))

    @staticmethod
    def open(root: Union[str, Path], name: str, shape: tuple[int, ...], rows_per_chunk: int,
             dtype: Any = np.float64) -> StoredArray:
        """The array ``name`` of the Zarr tree at ``root``, of ``shape``, chunked along its first axis by
        ``rows_per_chunk``.

        Parameters
        ----------
        root : str or pathlib.Path
            The Zarr tree's directory.
        name : str
            The array's name in it.
        shape : tuple of int
            Its shape.
        rows_per_chunk : int
            Cases per Zarr chunk.
        dtype : numpy.dtype, default float64
            Its dtype.

        Returns
        -------
        StoredArray
            The whole array, nothing read yet.
        """
        return StoredArray(_ZarrSource(Path(root), name, tuple(shape), np.dtype(dtype), rows_per_chunk))

    # -- what it stands for --

    @property
    def shape(self) -> tuple[int, ...]:
        """The view's shape."""
        return tuple(s.size for s in self._select if isinstance(s, np.ndarray))

    @property
    def ndim(self) -> int:
        """The view's number of axes."""
        return len(self.shape)

    @property
    def dtype(self) -> np.dtype:
        """The array's dtype."""
        return self._source.dtype

    @property
    def size(self) -> int:
        """The view's number of elements."""
        return int(np.prod(self.shape, dtype=np.int64))

    @property
    def nbytes(self) -> int:
        """Bytes it takes once read."""
        return self.size * self.dtype.itemsize

    def __len__(self) -> int:
        if not self.shape:
            raise TypeError("len() of a 0-d array")
        return self.shape[0]

    def __iter__(self) -> Iterator[np.ndarray]:
        for i in range(len(self)):
            row = self[i]  # a case: read
            assert isinstance(row, np.ndarray)
            yield row

    def __repr__(self) -> str:
        return (f"StoredArray(shape={self.shape}, dtype={self.dtype}, read on demand from "
                f"'{self._source.root / self._source.name}')")

    def __setitem__(self, key: Any, value: Any) -> None:
        raise TypeError("a stored campaign's signals are read-only: np.array(...) makes a copy to write into")

    # -- indexing and reading --

    def __getitem__(self, key: Any) -> Union[StoredArray, np.ndarray]:
        """Cases alone (a slice, an index array or a mask on the first axis) give a lazy view;
        any other index reads what it selects."""
        view = self._view(key)
        if view is None:  # numpy's pointwise indexing of several index arrays, or new axes
            return self.read()[key]
        keys = key if isinstance(key, tuple) else (key,)
        cases_only = (keys and self._select and isinstance(self._select[0], np.ndarray)
                      and not _is_integer(keys[0]) and keys[0] is not Ellipsis
                      and all(isinstance(k, slice) and k == slice(None) for k in keys[1:]))
        return view if cases_only else view.read()

    def _view(self, key: Any) -> Optional[StoredArray]:
        """The lazy view ``self[key]`` (orthogonal indexing, which is numpy's for basic indices
        and at most one index array), or None for what it cannot express."""
        keys = key if isinstance(key, tuple) else (key,)
        if sum(1 for k in keys if k is Ellipsis) > 1:
            raise IndexError("an index can only have a single ellipsis ('...')")
        if any(k is None for k in keys) or sum(1 for k in keys if _is_index_array(k)) > 1:
            return None
        ndim = self.ndim
        at = next((i for i, k in enumerate(keys) if k is Ellipsis), None)
        if at is not None:
            keys = keys[:at] + (slice(None),) * (ndim - len(keys) + 1) + keys[at + 1:]
        if len(keys) > ndim:
            raise IndexError(f"too many indices for array: array is {ndim}-dimensional, but {len(keys)} were indexed")
        keys = keys + (slice(None),) * (ndim - len(keys))
        out: list[_Selector] = []
        axis = 0
        for s in self._select:
            if not isinstance(s, np.ndarray):
                out.append(s)
                continue
            k = keys[axis]
            axis += 1
            if _is_integer(k):
                out.append(int(s[k]))  # numpy's bounds check and negative indices
            elif isinstance(k, slice):
                out.append(s[k])
            else:
                k = np.asarray(k)
                if k.dtype == bool:
                    if k.shape != (s.size,):
                        raise IndexError(f"boolean index of shape {k.shape} for an axis of {s.size}")
                    out.append(s[k])
                elif k.ndim == 1 and k.dtype.kind in "iu" or k.size == 0:
                    out.append(s[k.astype(np.intp)])
                else:
                    raise IndexError(f"a stored array takes 1-d integer or boolean index arrays, got {k.dtype} "
                                     f"of shape {k.shape}")
        return StoredArray(self._source, tuple(out))

    def read(self) -> np.ndarray:
        """What this (view) selects, read into a numpy array.

        Returns
        -------
        numpy.ndarray
            The values, of :attr:`shape`.
        """
        cases, rest = self._select[0], self._select[1:]
        rows = np.atleast_1d(np.asarray(cases, dtype=np.intp))
        tail = tuple(s.size for s in rest if isinstance(s, np.ndarray))
        out = np.empty((rows.size,) + tail, dtype=self.dtype)
        per = self._source.rows_per_chunk
        chunk = rows // per
        # runs of rows in one Zarr chunk, in the view's order
        cuts = np.flatnonzero(np.diff(chunk)) + 1
        for a, b in zip(np.r_[0, cuts], np.r_[cuts, rows.size]):
            if a == b:
                continue
            block = self._source.chunk(int(chunk[a]))
            out[a:b] = _outer(block[rows[a:b] - chunk[a] * per], rest)
        return out if isinstance(cases, np.ndarray) else out[0]

    def __array__(self, dtype: Any = None, copy: Optional[bool] = None) -> np.ndarray:
        a = self.read()
        return a if dtype is None else a.astype(dtype, copy=False)


def _is_integer(k: Any) -> bool:
    return isinstance(k, (int, np.integer)) and not isinstance(k, (bool, np.bool_))


def _is_index_array(k: Any) -> bool:
    return isinstance(k, (list, np.ndarray)) or (hasattr(k, "__array__") and not np.isscalar(k))


def _outer(block: np.ndarray, select: tuple[_Selector, ...]) -> np.ndarray:
    """``block`` (rows, ...) with ``select`` applied to its other axes, one axis at a time."""
    for axis, s in enumerate(select, start=1):
        if isinstance(s, np.ndarray) and not (s.size == block.shape[axis] and np.array_equal(s, np.arange(s.size))):
            block = np.take(block, s, axis=axis)
    ints = tuple(s if not isinstance(s, np.ndarray) else slice(None) for s in select)
    return block[(slice(None),) + ints] if any(not isinstance(s, np.ndarray) for s in select) else block


@dataclasses.dataclass(frozen=True, eq=False)
class StoredResult(SimulationResult):
    """A :class:`~landing.results.SimulationResult` whose recorded signals are :class:`StoredArray`
    views of a campaign store (``landing.load``, ``monte_carlo(..., store=...)``); its slices and
    cases are results of the same kind, and ``result[i]`` reads case i. Its metrics know the
    initial states (for ``to_pandas``) as a lazy view of the states' first instant, read when
    asked.

    Parameters
    ----------
    *args, **kwargs
        The fields of :class:`~landing.results.SimulationResult`, its signals StoredArrays.

    Examples
    --------
    >>> import tempfile, numpy as np, landing
    >>> scenario = landing.scenarios.preset("mars_monte_carlo").replace(t_final=5.0)
    >>> mc = landing.monte_carlo(scenario, n=8, seed=1, store=tempfile.mkdtemp() + "/campaign", chunk_size=4)
    >>> type(mc.result).__name__, type(mc.result.states).__name__
    ('StoredResult', 'StoredArray')
    >>> mc.result[0].states.shape  # case 0, read
    (101, 7)
    """

    def __post_init__(self) -> None:
        states = self.states
        if not isinstance(states, StoredArray):
            super().__post_init__()
            return
        # the base's context (axis and state names) without reading the states' first instant
        plain = dataclasses.replace(self, states=None)
        context = {"x0": states._view((Ellipsis, 0, slice(None)))} if self.t.size and self.t[0] == 0.0 else {}
        object.__setattr__(self, "metrics", plain.metrics._with_context(**context))

    def to_xarray(self) -> xarray.Dataset:
        """As :meth:`SimulationResult.to_xarray`, the recorded signals lazily indexed Zarr variables
        (read when their values are asked for).

        Returns
        -------
        xarray.Dataset
            The result's data, time in s and each variable's units in its attributes.
        """
        return stored_dataset(self)


def in_memory(result: SimulationResult) -> SimulationResult:
    """``result`` with its recorded signals read into numpy arrays (a result already in memory is
    returned as it is).

    Parameters
    ----------
    result : landing.SimulationResult
        A result, stored or not.

    Returns
    -------
    landing.SimulationResult
        The result, its signals numpy arrays.

    Examples
    --------
    >>> import tempfile, numpy as np, landing
    >>> scenario = landing.scenarios.preset("mars_monte_carlo").replace(t_final=5.0)
    >>> mc = landing.monte_carlo(scenario, n=8, seed=1, store=tempfile.mkdtemp() + "/campaign", chunk_size=4)
    >>> from landing.campaign.lazy import in_memory
    >>> type(in_memory(mc.result).states).__name__
    'ndarray'
    """
    lazy = [result.states, result.controls, *result.diagnostics.values()]
    if not any(isinstance(a, StoredArray) for a in lazy):
        return result
    return dataclasses.replace(
        result,
        states=None if result.states is None else np.asarray(result.states),
        controls=None if result.controls is None else np.asarray(result.controls),
        diagnostics={k: np.asarray(v) for k, v in result.diagnostics.items()},
    )


def stored_dataset(result: SimulationResult, *, x0: Optional[np.ndarray] = None, seed: Optional[int] = None,
                   attrs: Optional[dict[str, Any]] = None) -> xarray.Dataset:
    """:func:`landing.results.result_dataset` of a result whose signals may be stored: those are the
    Zarr tree's variables (``xarray.open_zarr``, lazily indexed, no dask), selected to the
    result's cases; the rest as ``result_dataset`` makes it, in the same order. Needs
    ``pip install "landing[io]"``.

    Parameters
    ----------
    result : landing.SimulationResult
        The result, stored or not.
    x0 : numpy.ndarray, optional
        The initial states, (N, state_dim) (m, m/s, kg).
    seed : int, optional
        The campaign's seed, kept in the attributes.
    attrs : dict, optional
        More attributes of the Dataset.

    Returns
    -------
    xarray.Dataset
        The result's data, time in s and each variable's units in its attributes.

    Examples
    --------
    >>> import tempfile, numpy as np, landing
    >>> scenario = landing.scenarios.preset("mars_monte_carlo").replace(t_final=5.0)
    >>> mc = landing.monte_carlo(scenario, n=8, seed=1, store=tempfile.mkdtemp() + "/campaign", chunk_size=4)
    >>> from landing.campaign.lazy import stored_dataset
    >>> ds = stored_dataset(mc.result)
    >>> ds.sizes["case"], ds.sizes["time"], list(ds.data_vars)[:2]
    (8, 101, ['states', 'controls'])
    """
    signals: dict[str, Any] = {"states": result.states, "controls": result.controls, **result.diagnostics}
    stored = {k: v for k, v in signals.items() if isinstance(v, StoredArray)}
    if not stored:
        return result_dataset(result, x0=x0, seed=seed, attrs=attrs)
    xr = require_io("xarray", what="to_xarray")
    rest = dataclasses.replace(
        result,
        states=None if "states" in stored else result.states,
        controls=None if "controls" in stored else result.controls,
        diagnostics={k: v for k, v in result.diagnostics.items() if k not in stored},
    )
    base = result_dataset(rest, x0=x0, seed=seed, attrs=attrs)
    roots = {v._source.root for v in stored.values()}
    assert len(roots) == 1, roots  # one store's signals
    tree = xr.open_zarr(str(roots.pop()), chunks=None, consolidated=True, mask_and_scale=False)
    variables = {}
    for name, v in stored.items():
        cases, rest_select = v._select[0], v._select[1:]
        if not (isinstance(cases, np.ndarray) and all(
                isinstance(s, np.ndarray) and np.array_equal(s, np.arange(n))
                for s, n in zip(rest_select, v._source.shape[1:]))):
            raise ValueError(f"{name}: only a selection of cases of a stored signal has a Dataset")
        var = tree[name].variable[cases]  # lazily indexed: nothing read yet
        var.attrs.pop("_FillValue", None)
        variables[name] = var
    # the order of result_dataset's: the signals first, then the rest
    data = {name: variables[name] if name in variables else base[name].variable
            for name in signals if name in variables or name in base.data_vars}
    data.update({str(k): v.variable for k, v in base.data_vars.items() if k not in data})
    return xr.Dataset(data, coords=base.coords, attrs=base.attrs)
