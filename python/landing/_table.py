"""Configuration objects to parameter tables for the core.

Plants, controllers, references and disturbances are dataclasses. Each turns itself into a
table (a dict of float64 arrays, flags and names) that the Rust core reads, validates and
broadcasts over the cases of a batch. Validation happens in the core only, both at
construction (so a bad gain fails where it is written) and again at simulation time.
"""

from __future__ import annotations

import dataclasses
from typing import Any, ClassVar, Sequence, Union

import numpy as np

from landing.errors import ParameterTypeError

ArrayLike = Union[float, Sequence[float], Sequence[Sequence[float]], np.ndarray]


def as_float_array(owner: str, name: str, value: Any) -> np.ndarray:
    """`value` as a float64 array, or a ParameterTypeError naming the parameter."""
    if isinstance(value, (str, bytes)):
        raise ParameterTypeError(f"{owner}: {name} must be a real number or an array of them, got {value!r}")
    try:
        arr = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise ParameterTypeError(
            f"{owner}: {name} must be a real number or an array of them, got {value!r}"
        ) from exc
    return np.ascontiguousarray(arr)


class Table:
    """Base of the configuration dataclasses: ``kind`` names the core type."""

    kind: ClassVar[str]

    def _table(self) -> dict[str, Any]:
        owner = type(self).__name__
        out: dict[str, Any] = {"kind": self.kind}
        for field in dataclasses.fields(self):  # type: ignore[arg-type]
            value = getattr(self, field.name)
            if value is None or isinstance(value, (bool, str)):
                out[field.name] = value
            elif isinstance(value, Table):
                out[field.name] = value._table()
            else:
                out[field.name] = as_float_array(owner, field.name, value)
        return out
