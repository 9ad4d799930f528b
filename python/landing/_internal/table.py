"""Configuration objects, compiled once by the core.

Plants, controllers, references, disturbances, gravity fields and dispersions are frozen
dataclasses. At construction each turns itself into a parameter table (a dict of float64
arrays, flags, names and nested tables) that the Rust core reads, validates and broadcasts over
the cases of a batch, once: the object keeps the compiled result (``_core``) and every batch and
query uses it. A configuration is changed by making a new one, ``law.replace(alpha1=6.0)``,
which is validated in turn.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from typing import Any, Callable, ClassVar, Union

import numpy as np

from landing._internal.args import real_array

ArrayLike = Union[float, Sequence[float], Sequence[Sequence[float]], np.ndarray]


def as_float_array(owner: str, name: str, value: Any) -> np.ndarray:
    """`value` as a float64 array, or a ParameterTypeError naming the parameter (bool, complex,
    string and object values are refused rather than cast)."""
    return real_array(name, value, owner=owner)


class Table:
    """Base of the configuration dataclasses: ``kind`` names the core type; ``_compiler`` is the
    core's handle type that compiles the table."""

    kind: ClassVar[str]
    _compiler: ClassVar[Callable[..., Any]]
    #: The compiled handle (a ``landing._core`` type), made once by :meth:`_compile`.
    _core: Any
    #: What ``@dataclass`` gives every configuration class (declared for the type checker).
    __dataclass_fields__: ClassVar[dict[str, dataclasses.Field[Any]]]

    def _table(self) -> dict[str, Any]:
        owner = type(self).__name__
        out: dict[str, Any] = {"kind": self.kind}
        for field in dataclasses.fields(self):
            if not field.init:
                continue
            value = getattr(self, field.name)
            if value is None or isinstance(value, (bool, str)):
                out[field.name] = value
            elif isinstance(value, Table):
                out[field.name] = value._nested()
            else:
                out[field.name] = as_float_array(owner, field.name, value)
        return out

    def _nested(self) -> Any:
        """What this object is inside another's table (its own table, by default)."""
        return self._table()

    def _freeze_arrays(self) -> None:
        """Keeps read-only copies of array and list parameters, so that changing the caller's
        array afterwards cannot make the object disagree with what the core compiled."""
        for field in dataclasses.fields(self):
            value = getattr(self, field.name)
            if isinstance(value, (list, np.ndarray)):
                arr = as_float_array(type(self).__name__, field.name, value).copy()
                arr.setflags(write=False)
                object.__setattr__(self, field.name, arr)

    def _compile(self) -> None:
        """Compiles the table once; the handle is what batches and queries use."""
        self._freeze_arrays()
        object.__setattr__(self, "_core", type(self)._compiler(type(self).__name__, self._table()))

    def __post_init__(self) -> None:
        self._compile()

    def replace(self, **changes: Any) -> Any:
        """A copy with some parameters changed, validated like a new object:
        ``law.replace(alpha1=6.0)``."""
        return dataclasses.replace(self, **changes)
