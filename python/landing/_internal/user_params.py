"""The parameters of a law or a plant written in Python: named numbers the user's functions
receive, checked and frozen once, and changed by name with ``replace``."""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from types import MappingProxyType
from typing import Any, Callable, Optional, Protocol, TypeVar

import numpy as np

from landing._internal.table import as_float_array
from landing.errors import ParameterError, ParameterTypeError

__all__ = ["frozen_params", "replace_with_params", "params_taking_cases"]


class _HasParams(Protocol):
    @property
    def params(self) -> Mapping[str, Any]: ...


T = TypeVar("T", bound=_HasParams)


def frozen_params(owner: str, params: Any, shapes: str) -> Mapping[str, Any]:
    """``params`` as a read-only mapping of read-only float64 copies, each at most 2-d; the
    errors name ``owner`` and say the accepted ``shapes``."""
    if not isinstance(params, Mapping):
        raise ParameterTypeError(f"{owner}: params must be a dict of numbers, got {type(params).__name__}")
    out = {}
    for key, value in params.items():
        if not isinstance(key, str) or not key.isidentifier():
            raise ParameterError(f"{owner}: params key {key!r} must be a name (an identifier)")
        arr = as_float_array(owner, f"params[{key!r}]", value).copy()
        if arr.ndim > 2:
            raise ParameterError(f"{owner}: params[{key!r}] has shape {arr.shape}; it takes {shapes}")
        arr.setflags(write=False)
        out[key] = arr
    return MappingProxyType(out)


def replace_with_params(obj: T, owner: str, changes: dict[str, Any]) -> T:
    """A copy of the dataclass ``obj`` (which has a ``params`` mapping) with some fields or
    parameters changed: a keyword that is not a field names a parameter; ``params=`` replaces
    them all."""
    fields = {f.name for f in dataclasses.fields(obj)}  # type: ignore[arg-type]
    current = obj.params
    unknown = [k for k in changes if k not in fields and k not in current]
    if unknown:
        raise ParameterError(f"{owner}: {unknown[0]!r} is neither a field ({sorted(fields)}) nor one of "
                             f"its params ({sorted(current)})")
    params = dict(changes.pop("params", current))
    for k in [k for k in changes if k not in fields]:
        params[k] = changes.pop(k)
    return dataclasses.replace(obj, params=params, **changes)  # type: ignore[type-var]


def params_taking_cases(obj: T, rows_of: Callable[[np.ndarray], Optional[int]], start: int, stop: int) -> T:
    """``obj`` with each parameter given per case (``rows_of(value)`` rows; None when shared)
    cut to its rows ``start .. stop`` (``obj`` itself if none is)."""
    params = dict(obj.params)
    cut = {k: v[start:stop] for k, v in params.items() if rows_of(v) is not None}
    if not cut:
        return obj
    return dataclasses.replace(obj, params={**params, **cut})  # type: ignore[type-var]
