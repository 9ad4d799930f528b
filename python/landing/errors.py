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
    """Base class of the library's errors."""


class ParameterError(LandingError, ValueError):
    """An argument has a valid type but a value or shape the model does not accept."""


class ParameterTypeError(LandingError, TypeError):
    """An argument has the wrong type."""


class SimulationError(LandingError, RuntimeError):
    """The simulation could not run (thread pool, internal error)."""


class UserFunctionError(LandingError, RuntimeError):
    """A function the user gave the engine (a :class:`~landing.controllers.PythonLaw`'s) raised,
    or returned something other than what it must: the message names the function, the control
    instant and the cases, and what was expected; a raised exception is chained
    (``__cause__``)."""


class StoreError(LandingError, RuntimeError):
    """A campaign store cannot be used as asked (another process is writing it): the message
    names the store, the reason and the remedy."""


class StoreWarning(RuntimeWarning):
    """A campaign store needed repair while it was resumed (a damaged chunk run again)."""


class DivergenceWarning(RuntimeWarning):
    """Some cases of a batch left the model's domain (non-finite state, no mass left).

    They are stopped and flagged in ``metrics["diverged"]``; their recorded states are NaN
    from the divergence on. The other cases are unaffected.
    """
