"""A plant written in Python, integrated by the core with one call per integrator stage.

:class:`PlantStep` is what the core calls for one batch: its hooks take the states (and the
commands) of every case at one instant as numpy arrays, call the user's functions with them and
the plant's parameters, check what they return and hand the core float64 arrays. Everything the
user can get wrong is caught here, with the function's name, the instant and the cases in the
message; the core checks only that the shapes it is given are the ones it asked for.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any, Optional

import numpy as np

from landing._internal.user_law import checked_floats
from landing.errors import UserFunctionError

__all__ = ["PlantStep", "per_case"]


def per_case(owner: str, name: str, given: Any, n: int) -> np.ndarray:
    """A plant parameter as the functions see it, one row per case: a scalar as ``(n,)``, a
    value per case ``(N,)`` or ``(N, k)`` as it is, a vector ``(k,)`` shared by every case (k
    not N) as ``(n, k)``. Read-only, a copy of the value: a scalar broadcast without another
    copy (stride 0), anything else a C-contiguous array."""
    value = np.array(given, dtype=np.float64)
    if value.ndim == 0:
        # stride 0: numpy reads it as it reads a Python float (BENCHMARKS.md, "A Python law's
        # shared parameters handed as views")
        return np.broadcast_to(value, (n,))
    if value.shape[0] == n and value.ndim <= 2:
        out = value
    elif value.ndim == 1:
        # a full (n, k) array, not a view with a zero stride along the cases: numpy could not
        # merge that view's axes and would loop over rows of k values (BENCHMARKS.md,
        # "per-axis parameters")
        out = np.ascontiguousarray(np.broadcast_to(value, (n, value.shape[0])))
    else:
        raise UserFunctionError(
            f"{owner}: params[{name!r}] has shape {value.shape}; with {n} cases it takes a scalar, a vector "
            f"(k,) shared by every case, or a value per case ({n},) or ({n}, k)")
    out.setflags(write=False)
    return out


class PlantStep:
    """The hooks of a plant written in Python for one batch of ``n`` cases numbered from
    ``first_case``, as the core calls them (``landing._core.simulate_batch`` reads ``_hooks``
    and ``_layout``)."""

    def __init__(self, *, name: str, derivative: Callable[..., Any], model: Optional[Callable[..., Any]],
                 actuate: Optional[Callable[..., Any]], in_domain: Optional[Callable[..., Any]],
                 params: Mapping[str, np.ndarray], n_state: int, axes: int,
                 layout: tuple[int, list[int], list[int], Optional[int], Optional[int]],
                 n: int, first_case: int) -> None:
        self.name = name
        self.functions = {"derivative": derivative, "model": model, "actuate": actuate, "in_domain": in_domain}
        self.params = dict(params)
        self.n_state, self.axes, self.n, self.first_case = n_state, axes, n, first_case
        hooks: tuple[Callable[..., np.ndarray], ...] = (self._derivative, self._model, self._actuate,
                                                         self._in_domain)
        self._hooks: tuple[Optional[Callable[..., np.ndarray]], ...] = tuple(
            h if self.functions[k] is not None else None for k, h in zip(self.functions, hooks))
        self._layout: tuple[int, list[int], list[int], Optional[int], Optional[int]] = layout

    def _call(self, which: str, t: float, *arrays: np.ndarray) -> tuple[Any, str]:
        # the arrays come read-only from the core (made so once, not at every call)
        last = self.first_case + self.n - 1
        where = f"PythonPlant {self.name}: {which} at t = {t:.9g} s on cases {self.first_case}..{last}"
        function = self.functions[which]
        assert function is not None
        try:
            return function(t, *arrays, self.params), where
        except Exception as exc:
            raise UserFunctionError(f"{where} raised {type(exc).__name__}: {exc}") from exc

    def _derivative(self, t: float, x: np.ndarray, u: np.ndarray) -> np.ndarray:
        out, where = self._call("derivative", t, x, u)
        return checked_floats("a derivative", out, (self.n, self.n_state), where)

    def _model(self, t: float, x: np.ndarray) -> np.ndarray:
        out, where = self._call("model", t, x)
        if not isinstance(out, tuple) or len(out) != 2:
            raise UserFunctionError(f"{where} returned {type(out).__name__}; expected (drift, inertia), "
                                    f"two arrays of shape ({self.n}, {self.axes})")
        shape = (self.n, self.axes)
        drift = checked_floats("a drift", out[0], shape, where)
        inertia = checked_floats("an inertia", out[1], shape, where)
        return np.ascontiguousarray(np.concatenate([drift, inertia], axis=1))

    def _actuate(self, t: float, x: np.ndarray, a: np.ndarray) -> np.ndarray:
        out, where = self._call("actuate", t, x, a)
        return checked_floats("an applied command", out, (self.n, self.axes), where)

    def _in_domain(self, t: float, x: np.ndarray) -> np.ndarray:
        out, where = self._call("in_domain", t, x)
        arr = np.asarray(out)
        if arr.shape != (self.n,) or arr.dtype != np.bool_:
            raise UserFunctionError(f"{where} returned an array of shape {arr.shape} and dtype {arr.dtype}; "
                                    f"expected booleans of shape ({self.n},)")
        return arr.astype(np.float64).reshape(self.n, 1)
