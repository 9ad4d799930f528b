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
from collections.abc import Mapping, Sequence
from types import MappingProxyType
from typing import Any, Callable, ClassVar, Optional, Union

import numpy as np

from landing import _core
from landing._internal.args import real_array

ArrayLike = Union[float, Sequence[float], Sequence[Sequence[float]], np.ndarray]


def as_float_array(owner: str, name: str, value: Any) -> np.ndarray:
    """`value` as a float64 array, or a ParameterTypeError naming the parameter (bool, complex,
    string and object values are refused rather than cast)."""
    return real_array(name, value, owner=owner)


@dataclasses.dataclass(frozen=True)
class Parameter:
    """One parameter of a plant, law, gravity field, disturbance, reference, dispersion or fuzzy
    system, as the core declares it (and reads and checks it): ``Law.parameters["b1"]``.

    ``shape`` is how its table gives it: ``"scalar"`` (a number, shared or one per case),
    ``"per_axis"`` (a number per axis: a scalar, ``(D,)``, or per case ``(N,)``, ``(N, 1)``,
    ``(N, D)``), ``"per_component"`` (a scalar or ``(K,)``; per case ``(N, 1)`` or ``(N, K)``
    where ``per_case``: a sensor's), ``"choice"`` (one of ``choices``), ``"flag"``,
    ``"count"`` (a whole number among ``choices``), ``"nested"`` or ``"list"`` (tables of the
    kinds of ``family``), ``"fuzzy_system"``. ``unit`` is SI ("1" dimensionless; "q" stands for
    the plant's generalized coordinate, m for the landers and rad for the tethered satellite);
    ``rule`` is the inequality the core enforces ("" when only finiteness).
    """

    name: str
    shape: str
    unit: str
    rule: str
    required: bool
    doc: str
    choices: tuple[Any, ...] = ()
    family: Optional[str] = None
    #: Whether the parameter may be given one row per case (scalars, per-axis parameters and a
    #: sensor's per-component ones).
    per_case: bool = False

    @property
    def numeric(self) -> bool:
        """Whether the parameter is numbers a case reads (so it can be swept or tuned)."""
        return self.shape in ("scalar", "per_axis")


def schema(family: str, kind: str) -> Mapping[str, Parameter]:
    """The parameters the core declares for ``kind`` of ``family`` (``"law"``, ``"plant"``, ...),
    by name in declaration order."""
    declared = _core.SCHEMAS[family][kind]["parameters"]
    return MappingProxyType({
        p["name"]: Parameter(
            name=p["name"], shape=p["shape"], unit=p["unit"], rule=p["rule"], required=p["required"],
            doc=p["doc"], choices=tuple(p.get("choices", ())), family=p.get("family"), per_case=p["per_case"],
        )
        for p in declared
    })


def case_rows(shape: str, value_shape: tuple[int, ...], axes: int) -> Optional[int]:
    """How many cases a numeric parameter's value gives one row each, by the core's rule (None:
    the value is shared by every case): a scalar parameter per case is ``(N,)``; a per-axis one
    ``(N, D)``, ``(N, 1)`` or ``(N,)``, where a 1-d value of length D is read per axis; a
    per-component one that may vary by case (:attr:`Parameter.per_case`) ``(N, K)`` or
    ``(N, 1)``."""
    if shape == "per_component" and len(value_shape) == 2:
        return value_shape[0]
    if shape == "scalar" and len(value_shape) == 1:
        return value_shape[0]
    if shape == "per_axis" and (len(value_shape) == 2 or (len(value_shape) == 1 and value_shape[0] != axes)):
        return value_shape[0]
    return None


def nested_tables(value: Any) -> list[tuple[str, Table]]:
    """The configurations inside a field's value (a nested one, or a list of them), each with
    the suffix that names it (``""``, ``"[1]"``). A fuzzy system (a Table that is not a
    dataclass) is shared by every case and holds no parameter per case: not among them."""
    if isinstance(value, Table) and dataclasses.is_dataclass(value):
        return [("", value)]
    if (isinstance(value, (list, tuple)) and value
            and all(isinstance(v, Table) and dataclasses.is_dataclass(v) for v in value)):
        return [(f"[{i}]", v) for i, v in enumerate(value)]
    return []


def nested_taking_cases(value: Any, start: int, stop: int, n: int, axes: int) -> Any:
    """A field's nested configurations (see :func:`nested_tables`) for cases ``start .. stop``
    (:meth:`Table.take_cases`), or ``value`` itself when none has a parameter per case."""
    inner = [t for _, t in nested_tables(value)]
    taken = [t.take_cases(start, stop, n, axes) for t in inner]
    if all(a is b for a, b in zip(inner, taken)):
        return value
    return taken[0] if isinstance(value, Table) else type(value)(taken)


class Table:
    """Base of the configuration dataclasses: ``kind`` names the core type; ``_compiler`` is the
    core's handle type that compiles the table; ``family`` names the core's registry the kind is
    in, and ``parameters`` is what the core declares for it (:class:`Parameter`)."""

    kind: ClassVar[str]
    family: ClassVar[str]
    parameters: ClassVar[Mapping[str, Parameter]]
    _compiler: ClassVar[Callable[..., Any]]
    #: Whether the kind is one the core declares (a law written in Python is not).
    _in_core: ClassVar[bool] = True
    #: The compiled handle (a ``landing._core`` type), made once by :meth:`_compile`.
    _core: Any
    #: What ``@dataclass`` gives every configuration class (declared for the type checker).
    __dataclass_fields__: ClassVar[dict[str, dataclasses.Field[Any]]]

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        kind = cls.__dict__.get("kind")
        if isinstance(kind, str) and hasattr(cls, "family") and cls.__dict__.get("_in_core", True):
            # a kind the core does not declare fails here, at import
            cls.parameters = schema(cls.family, kind)

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

    # Pickling (a campaign's scenario sent to Dask workers) carries the parameters and compiles
    # them again on arrival: the core's handles are not picklable, and need not be.
    def __getstate__(self) -> dict[str, Any]:
        state = dict(self.__dict__)
        state.pop("_core", None)
        return state

    def __setstate__(self, state: dict[str, Any]) -> None:
        for key, value in state.items():
            object.__setattr__(self, key, value)
        self._compile()

    def replace(self, **changes: Any) -> Any:
        """A copy with some parameters changed, validated like a new object:
        ``law.replace(alpha1=6.0)``."""
        return dataclasses.replace(self, **changes)

    # Parameters given per case, and the configuration for some of the cases (a campaign's
    # chunk): one rule for every kind, read from the core's schema.

    def _numbers(self) -> dict[str, tuple[Parameter, np.ndarray]]:
        """The numeric parameters given as arrays, by field name, with their declarations."""
        out = {}
        declared = getattr(self, "parameters", {})
        for f in dataclasses.fields(self):
            value = getattr(self, f.name)
            p = declared.get(f.name)
            numbers = isinstance(value, (np.ndarray, list, tuple)) and not nested_tables(value)
            if p is not None and p.per_case and numbers:
                out[f.name] = (p, np.asarray(value, dtype=np.float64))
        return out

    def case_rows(self, n: int, axes: int) -> dict[str, int]:
        """The parameters given one row per case, by name (a nested one's dotted), and their
        rows; ``axes`` is the plant's, ``n`` the cases of the batch or campaign (which tells
        a vector per case from a shared one where the shape alone cannot)."""
        out = {name: rows for name, (p, v) in self._numbers().items()
               if (rows := case_rows(p.shape, v.shape, axes)) is not None}
        for f in dataclasses.fields(self):
            for suffix, inner in nested_tables(getattr(self, f.name)):
                out.update({f"{f.name}{suffix}.{k}": r for k, r in inner.case_rows(n, axes).items()})
        return out

    def take_cases(self, start: int, stop: int, n: int, axes: int) -> Any:
        """This configuration for cases ``start .. stop`` of ``n``: each parameter given per case
        keeps its rows ``start .. stop`` (itself if none is)."""
        changes: dict[str, Any] = {
            name: v[start:stop] for name, (p, v) in self._numbers().items()
            if case_rows(p.shape, v.shape, axes) is not None
        }
        for f in dataclasses.fields(self):
            value = getattr(self, f.name)
            taken = nested_taking_cases(value, start, stop, n, axes)
            if taken is not value:
                changes[f.name] = taken
        return dataclasses.replace(self, **changes) if changes else self
