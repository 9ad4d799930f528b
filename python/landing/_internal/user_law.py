"""A control law written in Python, run by the core once per control instant.

The core calls :class:`LawStep` with the law inputs of every case of the batch at one instant
(numpy arrays); it calls the user's function with them, its parameters and its memory, checks
what the function returns and hands the core the commands and diagnostics as float64 arrays.
Everything the user can get wrong is caught here, with the function's name, the instant and the
cases in the message; the core checks only that the shapes it is given are the ones it asked
for.
"""

from __future__ import annotations

import hashlib
import importlib
import inspect
import sys
from collections.abc import Callable, Mapping, Sequence
from typing import Any, NamedTuple, Optional

import numpy as np

from landing.errors import UserFunctionError

__all__ = ["ReferencePoint", "LawStep", "qualified_name", "source_hash", "per_axis", "load_function",
           "checked_floats"]


class ReferencePoint(NamedTuple):
    """The reference at a control instant, each (n, D): what a law tracks."""

    position: np.ndarray
    velocity: np.ndarray
    acceleration: np.ndarray


def qualified_name(function: Callable[..., Any]) -> str:
    """``module:qualname`` of a function (of the function a jitted wrapper holds), the way
    scenario files name one."""
    inner = getattr(function, "py_func", None) or getattr(function, "__wrapped__", None) or function
    module = getattr(inner, "__module__", None) or type(inner).__module__
    name = getattr(inner, "__qualname__", None) or type(inner).__qualname__
    return f"{module}:{name}"


def source_hash(function: Callable[..., Any]) -> str:
    """SHA-256 of the function's source (of its byte code when the source cannot be read): a
    changed function gives another hash."""
    inner = getattr(function, "py_func", None) or getattr(function, "__wrapped__", None) or function
    try:
        text = inspect.getsource(inner).encode()
    except (OSError, TypeError):
        code = getattr(inner, "__code__", None)
        text = code.co_code + repr(code.co_consts).encode() if code is not None else repr(inner).encode()
    return hashlib.sha256(text).hexdigest()


def load_function(spec: str, search: Sequence[str] = ()) -> Callable[..., Any]:
    """The function ``"package.module:name"`` names (``name`` may be dotted: a class's method).
    The module is imported as usual, else from the folders ``search`` (a scenario file's own
    folder, the working directory). ValueError, ImportError or AttributeError say why not."""
    module_name, sep, name = spec.partition(":")
    if not sep or not module_name or not name or "<" in name:
        raise ValueError(f"{spec!r} does not name an importable function; write 'package.module:name' "
                         "(a function at module level, not a lambda or a nested function)")
    try:
        module = importlib.import_module(module_name)
    except ModuleNotFoundError:
        extra = [p for p in search if p not in sys.path]
        sys.path[:0] = extra
        try:
            module = importlib.import_module(module_name)
        finally:
            for p in extra:
                sys.path.remove(p)
    out: Any = module
    for part in name.split("."):
        out = getattr(out, part)
    if not callable(out):
        raise ValueError(f"{spec!r} names a {type(out).__name__}, not a function")
    return out


def per_axis(owner: str, name: str, given: Any, n: int, axes: int) -> np.ndarray:
    """A parameter given as a scalar, ``(D,)``, or per case ``(N,)``, ``(N, 1)``, ``(N, D)``, as
    the read-only (n, D) array the function sees (a 1-d value of length D is per axis; give
    (N, 1) for a value per case when N equals D): a scalar as a broadcast view of one copy, any
    other value as a C-contiguous array of its own."""
    # a copy of what was given, so that a run does not see later changes to the caller's array
    value = np.array(given, dtype=np.float64)
    shape = value.shape
    if value.ndim == 0:
        # zero strides on both axes: numpy reads it as it reads a Python float, from the cache,
        # where an (n, D) array would be read at every operation (BENCHMARKS.md, "A Python
        # law's shared parameters handed as views")
        return np.broadcast_to(value, (n, axes))
    if shape == (axes,):
        out = np.broadcast_to(value, (n, axes))
    elif value.ndim == 1 and shape[0] == n:
        out = np.broadcast_to(value[:, None], (n, axes))
    elif value.ndim == 2 and shape[0] == n and shape[1] in (1, axes):
        out = np.broadcast_to(value, (n, axes))
    else:
        raise UserFunctionError(
            f"{owner}: params[{name!r}] has shape {shape}; with {n} cases and {axes} axes it takes a scalar, "
            f"({axes},), ({n},), ({n}, 1) or ({n}, {axes})"
        )
    # copied whole, not a view with a zero stride along one axis only: numpy cannot merge such
    # a view's two axes into one, so every operation with it loops over rows of D values, 3 to
    # 4.4 times slower than over an array (BENCHMARKS.md, "per-axis parameters")
    out = np.ascontiguousarray(out)
    out.setflags(write=False)
    return out


def checked_floats(what: str, value: Any, shape: tuple[int, ...], where: str) -> np.ndarray:
    """``value`` as a float64 array of ``shape``, or an error saying what was expected."""
    if not hasattr(value, "__array__") and not isinstance(value, np.ndarray):
        raise UserFunctionError(
            f"{where} returned {what} of type {type(value).__name__}; expected an array of shape {shape}")
    arr = np.asarray(value)
    if arr.dtype.kind != "f":
        raise UserFunctionError(
            f"{where} returned {what} of dtype {arr.dtype}; expected floating-point values of shape {shape}")
    if arr.shape != shape:
        raise UserFunctionError(f"{where} returned {what} of shape {arr.shape}; expected {shape}")
    return np.ascontiguousarray(arr, dtype=np.float64)


class _Slice:
    """The slice of cases a track of the core runs: its rows of the batch, its parameters and
    its memory."""

    __slots__ = ("first", "m", "params", "memory", "no_diagnostics")

    def __init__(self, first: int, m: int, params: dict[str, np.ndarray]) -> None:
        self.first, self.m, self.params = first, m, params
        self.memory: Optional[dict[str, np.ndarray]] = None
        # the diagnostics of a law that declares none, made once per slice
        self.no_diagnostics = np.empty((m, 0))


class LawStep:
    """What the core calls at each control instant of one batch (``n`` cases of a plant with
    ``axes`` axes, numbered from ``first_case``): calls ``function(t, e, de, ref, drift,
    inertia, params, memory)`` and returns ``(command, diagnostics)``, float64 (m, D) and
    (m, width).

    The core calls it on a slice of at most ``cases_per_call`` cases at a time (all the batch's
    when it is smaller): ``first`` is the slice's first row in the batch. With more than one
    thread two slices run at once on two tracks, their calls alternating (``track``, 0 or 1),
    each slice's in time order; a track's next slice starts at ``k = 0``. Each slice's memory
    is its own.
    """

    def __init__(self, function: Callable[..., Any], *, name: str, params: Mapping[str, np.ndarray],
                 memory: Any, layout: Sequence[tuple[str, int]], n: int, axes: int, first_case: int,
                 cases_per_call: int) -> None:
        self.function = function
        self.name = name
        self.params = dict(params)
        self.initial = memory
        self.layout = list(layout)
        self.n, self.axes, self.first_case = n, axes, first_case
        self.cases_per_call = cases_per_call
        self.width = sum(w for _, w in self.layout)
        # the slice each track runs
        self._tracks: list[_Slice] = [_Slice(0, n, self.params), _Slice(0, n, self.params)]

    def _where(self, t: float, s: _Slice) -> str:
        start = self.first_case + s.first
        return f"PythonLaw {self.name} at t = {t:.9g} s on cases {start}..{start + s.m - 1}"

    def _memory(self, value: Any, s: _Slice, where: str, what: str) -> Optional[dict[str, np.ndarray]]:
        """A memory the function returned (or the initial one): a mapping of arrays, one row per
        case, with the names and shapes of the one before."""
        if value is None:
            return None
        if not isinstance(value, Mapping):
            raise UserFunctionError(
                f"{where} returned {what} of type {type(value).__name__}; expected a dict of arrays")
        before = s.memory
        if before is not None and set(value) != set(before):
            raise UserFunctionError(f"{where} returned {what} with keys {sorted(value)}; expected {sorted(before)}")
        out = {}
        for key, v in value.items():
            arr = np.asarray(v)
            shape = before[key].shape if before is not None else arr.shape
            if before is None and (arr.ndim == 0 or arr.shape[0] != s.m):
                raise UserFunctionError(f"{where} returned {what}[{key!r}] of shape {arr.shape}; "
                                        f"expected one row per case, ({s.m}, ...)")
            out[key] = checked_floats(f"{what}[{key!r}]", v, shape, where)
        return out

    def _start(self, t: float, first: int, track: int, args: tuple[Any, ...]) -> _Slice:
        """A slice's first instant: its rows, parameters and initial memory, on its track."""
        m = args[1].shape[0]
        whole = first == 0 and m == self.n
        s = _Slice(first, m, self.params if whole else {k: v[first:first + m] for k, v in self.params.items()})
        self._tracks[track] = s
        init = self.initial
        if init is None:
            return s
        if callable(init):
            try:
                value = init(*args, s.params)
            except Exception as exc:
                raise UserFunctionError(
                    f"the memory initialiser of {self._where(t, s)} raised {type(exc).__name__}: {exc}") from exc
            s.memory = self._memory(value, s, self._where(t, s), "memory (initial)")
        else:
            # values shared by every case, broadcast to one row per case
            s.memory = {k: np.array(np.broadcast_to(np.asarray(v, dtype=np.float64), (m, *np.shape(v))))
                        for k, v in init.items()}
        return s

    def __call__(self, t: float, k: int, first: int, track: int, e: np.ndarray, de: np.ndarray,
                 position: np.ndarray, velocity: np.ndarray, acceleration: np.ndarray, drift: np.ndarray,
                 inertia: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        # the arrays come read-only from the core (made so once, not at every call)
        args = (t, e, de, ReferencePoint(position, velocity, acceleration), drift, inertia)
        s = self._start(t, first, track, args) if k == 0 else self._tracks[track]
        try:
            out = self.function(*args, s.params, s.memory)
        except Exception as exc:
            raise UserFunctionError(f"{self._where(t, s)} raised {type(exc).__name__}: {exc}") from exc
        diagnostics: Any = None
        if isinstance(out, tuple):
            if len(out) not in (2, 3):
                raise UserFunctionError(f"{self._where(t, s)} returned a tuple of {len(out)} values; expected the "
                                        "command, (command, memory) or (command, memory, diagnostics)")
            command, memory = out[0], out[1]
            diagnostics = out[2] if len(out) == 3 else None
            s.memory = self._memory(memory, s, self._where(t, s), "memory")
        else:
            command = out
        m = s.m
        if (isinstance(command, np.ndarray) and command.dtype == np.float64 and command.shape == (m, self.axes)
                and command.flags.c_contiguous):
            u = command  # the common case, checked without formatting a message
        else:
            u = checked_floats("a command", command, (m, self.axes), self._where(t, s))
        return u, self._diagnostics(diagnostics, t, s)

    def _diagnostics(self, value: Any, t: float, s: _Slice) -> np.ndarray:
        m = s.m
        if not self.layout:
            return s.no_diagnostics
        out = np.empty((m, self.width))
        where = self._where(t, s)
        if not isinstance(value, Mapping):
            names = [name for name, _ in self.layout]
            raise UserFunctionError(f"{where} returned no diagnostics dict; it declares {names}")
        col = 0
        for name, width in self.layout:
            if name not in value:
                raise UserFunctionError(f"{where} returned diagnostics without {name!r}")
            shape = (m, width) if width == self.axes else (m,)
            arr = checked_floats(f"diagnostics[{name!r}]", value[name], shape, where)
            out[:, col:col + width] = arr.reshape(m, width)
            col += width
        return out
