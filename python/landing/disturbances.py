"""Lumped unknown disturbances: generalized accelerations the laws do not see.

Components add up: pass a list (``disturbance=[Constant(...), Sinusoid(...)]``) or write
``Constant(...) + Sinusoid(...)``. Deterministic parts are evaluated at every integrator stage;
random parts are drawn once per control period from the case's own counter-based stream, so a
case's noise does not depend on the thread count or the batch it runs in.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import Any, ClassVar, Union

from landing import _core
from landing._internal.table import ArrayLike, Table
from landing.errors import ParameterTypeError

__all__ = ["Disturbance", "Constant", "Sinusoid", "UniformNoise", "CommandNoise", "Sum", "compiled"]


class Disturbance(Table):
    """Base class of the disturbance components: generalized accelerations, in q/s^2 (m/s^2
    for a lander), added to the plant's dynamics. Components add up with ``+``.

    Parameters
    ----------
    **fields : ArrayLike
        The subclass's fields (see each one); the base class takes none of its own.

    Examples
    --------
    >>> from landing.disturbances import Constant, UniformNoise
    >>> d = Constant([0.0, 0.0, -1e-3]) + UniformNoise(bound=1e-4)
    >>> [type(p).__name__ for p in d.components()], UniformNoise.random
    (['Constant', 'UniformNoise'], True)
    """

    family: ClassVar[str] = "disturbance"
    #: Whether the component draws random numbers (declared by the core; the draws are held
    #: over each control period and keyed by seed and case).
    random: ClassVar[bool] = False

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        kind = cls.__dict__.get("kind")
        if isinstance(kind, str):
            cls.random = bool(_core.SCHEMAS["disturbance"][kind]["random"])

    @staticmethod
    def _compiler(owner: str, table: dict) -> _core.Disturbance:
        return _core.Disturbance(owner, {"components": [table]})

    def __add__(self, other: Disturbance) -> Sum:
        return Sum([self]) + other

    def components(self) -> list[Disturbance]:
        return [self]


@dataclass(frozen=True, eq=False)
class Constant(Disturbance):
    """A constant acceleration per axis.

    Parameters
    ----------
    value : ArrayLike
        The acceleration, q/s^2, per axis (a scalar for every axis).

    Examples
    --------
    >>> Constant([0.0, 0.0, -1e-3])
    Constant(value=array([ 0.   ,  0.   , -0.001]))
    """

    value: ArrayLike

    kind: ClassVar[str] = "constant"


@dataclass(frozen=True, eq=False)
class Sinusoid(Disturbance):
    """``amplitude sin(omega t + phase)`` per axis (the Mars fixed-time guidance paper,
    eq. 47: 20 sin t on every axis).

    Parameters
    ----------
    amplitude : ArrayLike
        Amplitude A, q/s^2, per axis.
    omega : ArrayLike
        Angular frequency, rad/s, per axis.
    phase : ArrayLike
        Phase at t = 0, rad, per axis (default 0).

    Examples
    --------
    >>> Sinusoid(amplitude=20.0, omega=1.0)
    Sinusoid(amplitude=20.0, omega=1.0, phase=0.0)
    """

    amplitude: ArrayLike
    omega: ArrayLike
    phase: ArrayLike = 0.0

    kind: ClassVar[str] = "sinusoid"


@dataclass(frozen=True, eq=False)
class UniformNoise(Disturbance):
    """Uniform on ``[-bound, bound]`` per axis, drawn once per control period and held.

    Parameters
    ----------
    bound : ArrayLike
        Half-width of the range, q/s^2, per axis; bound >= 0.

    Examples
    --------
    >>> UniformNoise(bound=1e-4).random
    True
    """

    bound: ArrayLike

    kind: ClassVar[str] = "uniform_noise"


@dataclass(frozen=True, eq=False)
class CommandNoise(Disturbance):
    """Uniform on ``[-fraction, fraction]`` times the commanded acceleration, per axis, drawn
    once per control period (the fuzzy variable-rate asteroid paper: a model uncertainty of up to 1 % of the command,
    ``CommandNoise(0.01)``). The commanded acceleration is the applied command over the
    plant's inertia.

    Parameters
    ----------
    fraction : ArrayLike
        Relative half-width of the range, dimensionless, per axis; fraction >= 0.

    Examples
    --------
    >>> CommandNoise(0.01)
    CommandNoise(fraction=0.01)
    """

    fraction: ArrayLike

    kind: ClassVar[str] = "command_noise"


class Sum(Disturbance):
    """Several components acting together (what ``a + b`` builds); nested sums are flattened.

    Parameters
    ----------
    parts : Iterable[Disturbance]
        The components (a ``Sum`` among them contributes its own components).

    Raises
    ------
    ParameterTypeError
        If a part is not a disturbance component.

    Examples
    --------
    >>> Sum([Constant(1e-3), Sinusoid(amplitude=2e-3, omega=0.5)])
    Constant(value=0.001) + Sinusoid(amplitude=0.002, omega=0.5, phase=0.0)
    """

    def __init__(self, parts: Iterable[Disturbance]):
        self.parts: list[Disturbance] = []
        for p in parts:
            if not isinstance(p, Disturbance):
                raise ParameterTypeError(
                    f"disturbance must be a landing.disturbances component or a list of them, got {p!r}"
                )
            self.parts.extend(p.components())
        self._compile()

    def _compile(self) -> None:
        self._core = _core.Disturbance.combine([p._core for p in self.parts])

    def components(self) -> list[Disturbance]:
        return list(self.parts)

    def case_rows(self, n: int, axes: int) -> dict[str, int]:
        return {f"parts[{i}].{k}": r for i, p in enumerate(self.parts) for k, r in p.case_rows(n, axes).items()}

    def take_cases(self, start: int, stop: int, n: int, axes: int) -> Sum:
        taken = [p.take_cases(start, stop, n, axes) for p in self.parts]
        return self if all(a is b for a, b in zip(taken, self.parts)) else Sum(taken)

    def __add__(self, other: Disturbance) -> Sum:
        if not isinstance(other, Disturbance):
            raise ParameterTypeError(
                f"disturbance must be a landing.disturbances component or a list of them, got {other!r}"
            )
        return Sum(self.parts + other.components())

    def __repr__(self) -> str:
        return " + ".join(repr(p) for p in self.parts) or "Sum([])"


DisturbanceLike = Union[Disturbance, Sequence[Disturbance], None]


def compiled(disturbance: DisturbanceLike) -> Union[_core.Disturbance, None]:
    """The core's compiled disturbance for a component, a sum, a list of them, or None.

    Parameters
    ----------
    disturbance : Disturbance, sequence of Disturbance, or None
        What a scenario's ``disturbance`` holds.

    Returns
    -------
    landing._core.Disturbance or None
        The compiled sum of the components, or None for None.

    Raises
    ------
    ParameterTypeError
        If ``disturbance`` is neither a component, an iterable of components nor None.

    Examples
    --------
    >>> compiled(None) is None
    True
    >>> type(compiled([UniformNoise(0.1)])).__name__
    'Disturbance'
    """
    if disturbance is None:
        return None
    if isinstance(disturbance, Disturbance):
        return disturbance._core
    refused = ParameterTypeError(
        f"disturbance must be a landing.disturbances component or a list of them, got {disturbance!r}"
    )
    if isinstance(disturbance, (str, bytes, dict)) or not hasattr(disturbance, "__iter__"):
        raise refused
    try:
        parts = list(disturbance)
    except TypeError:  # e.g. a 0-d array, iterable in type only
        raise refused from None
    return Sum(parts)._core
