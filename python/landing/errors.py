"""The exceptions and warnings `landing` raises on purpose.

Every error about an input is a :class:`ParameterError` (a ``ValueError``) or a
:class:`ParameterTypeError` (a ``TypeError``); both are :class:`LandingError`, so one ``except``
catches everything the library raises deliberately. The message names the argument, the value
and the rule it breaks.
"""

from __future__ import annotations

__all__ = [
    "LandingError",
    "ParameterError",
    "ParameterTypeError",
    "SimulationError",
    "UserFunctionError",
    "StoreError",
    "StoreWarning",
    "DivergenceWarning",
]


class LandingError(Exception):
    """Base class of the library's errors: one ``except LandingError`` catches every error
    the library raises on purpose.

    Parameters
    ----------
    *args : object
        The message (a str), as for any exception.

    Examples
    --------
    >>> from landing.gravity import PointMass
    >>> try:
    ...     PointMass(mu=-1.0)
    ... except LandingError as e:
    ...     print(type(e).__name__, e)
    ParameterError PointMass: mu = -1 violates mu > 0
    """


class ParameterError(LandingError, ValueError):
    """An argument has a valid type but a value or shape the model does not accept.

    Also a ``ValueError``. The message names the argument, the value and the rule it breaks.

    Parameters
    ----------
    *args : object
        The message (a str), as for any exception.

    Examples
    --------
    >>> from landing.gravity import PointMass
    >>> try:
    ...     PointMass(mu=4.842e5).acceleration([1.0, 2.0])
    ... except ValueError as e:
    ...     print(isinstance(e, ParameterError), e)
    True PointMass: r has shape (2,); it takes (3,) or (N, 3)
    """


class ParameterTypeError(LandingError, TypeError):
    """An argument has the wrong type. Also a ``TypeError``.

    Parameters
    ----------
    *args : object
        The message (a str), as for any exception.

    Examples
    --------
    >>> from landing.reference import Constant
    >>> try:
    ...     Constant(position="a")
    ... except ParameterTypeError as e:
    ...     print(e)
    Constant: position must be a real number or an array of real numbers
    """


class SimulationError(LandingError, RuntimeError):
    """The simulation could not run (thread pool, internal error). Also a ``RuntimeError``.

    Parameters
    ----------
    *args : object
        The message (a str), as for any exception.

    Examples
    --------
    >>> issubclass(SimulationError, (LandingError, RuntimeError))
    True
    """


class UserFunctionError(LandingError, RuntimeError):
    """A function the user gave the engine (a :class:`~landing.controllers.PythonLaw`'s) raised,
    or returned something other than what it must: the message names the function, the control
    instant and the cases, and what was expected; a raised exception is chained
    (``__cause__``). Also a ``RuntimeError``.

    Parameters
    ----------
    *args : object
        The message (a str), as for any exception.

    Examples
    --------
    >>> issubclass(UserFunctionError, (LandingError, RuntimeError))
    True
    """


class StoreError(LandingError, RuntimeError):
    """A campaign store cannot be used as asked (another process is writing it): the message
    names the store, the reason and the remedy. Also a ``RuntimeError``.

    Parameters
    ----------
    *args : object
        The message (a str), as for any exception.

    Examples
    --------
    >>> issubclass(StoreError, (LandingError, RuntimeError))
    True
    """


class StoreWarning(RuntimeWarning):
    """A campaign store needed repair while it was resumed (a damaged chunk run again).

    A ``RuntimeWarning``, issued through :mod:`warnings` (not a :class:`LandingError`).

    Parameters
    ----------
    *args : object
        The message (a str), as for any exception.

    Examples
    --------
    >>> import warnings
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     warnings.warn("chunk 3 was damaged; it ran again", StoreWarning)
    >>> caught[0].category.__name__
    'StoreWarning'
    """


class DivergenceWarning(RuntimeWarning):
    """Some cases of a batch left the model's domain (non-finite state, no mass left).

    They are stopped and flagged in ``metrics["diverged"]``; their recorded states are NaN
    from the divergence on. The other cases are unaffected. A ``RuntimeWarning``, issued
    through :mod:`warnings`; ``warnings.simplefilter("error", DivergenceWarning)`` turns it
    into an error.

    Parameters
    ----------
    *args : object
        The message (a str), as for any exception.

    Examples
    --------
    >>> issubclass(DivergenceWarning, RuntimeWarning), issubclass(DivergenceWarning, LandingError)
    (True, False)
    """
