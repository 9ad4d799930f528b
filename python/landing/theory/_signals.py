"""When a recorded signal enters, and when it settles in, a band: the measurements the checks
compare with the bounds."""

from __future__ import annotations

from typing import Any

import numpy as np

from landing._internal.args import real_array
from landing.errors import ParameterError

__all__ = ["entry_time", "settle_time"]


def _time_signal(owner: str, t: Any, signal: Any, tol: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Recorded times (T,), a signal (..., T, D) and a tolerance (scalar or (..., D)), checked."""
    tt = real_array("t", t, owner=owner)
    sig = real_array("signal", signal, owner=owner)
    tl = real_array("tol", tol, owner=owner)
    if tt.ndim != 1 or tt.size == 0:
        raise ParameterError(f"{owner}: t has shape {tt.shape}; it takes (T,) with T >= 1")
    if sig.ndim < 2 or sig.shape[-2] != tt.size:
        raise ParameterError(
            f"{owner}: signal has shape {sig.shape}; it takes (..., T, D) with T = len(t) = {tt.size}"
        )
    if tl.ndim:
        try:
            np.broadcast_shapes(tl[..., None, :].shape, sig.shape)
        except (ValueError, IndexError):
            raise ParameterError(
                f"{owner}: tol has shape {tl.shape}; it takes a scalar or (..., D) matching signal {sig.shape}"
            ) from None
    return tt, sig, tl


def entry_time(t: np.ndarray, signal: np.ndarray, tol: Any) -> np.ndarray:
    """First recorded time at which ``|signal| <= tol``; ``signal`` has time on axis -2
    (``(..., T, D)``), the result drops it. NaN where never.

    Parameters
    ----------
    t : array_like
        The recorded times (s), (T,).
    signal : array_like
        The signal, (..., T, D), in its own unit (m, m/s, rad...).
    tol : float or array_like
        The band's half-width in the signal's unit: a scalar or (..., D).

    Returns
    -------
    numpy.ndarray
        The entry times (s), (..., D).

    Examples
    --------
    >>> import numpy as np
    >>> from landing.theory import entry_time
    >>> entry_time(np.arange(4.0), np.array([[3.0], [1.0], [0.5], [2.0]]), 1.0)
    array([1.])
    """
    t, signal, tol = _time_signal("entry_time", t, signal, tol)
    inside = np.abs(signal) <= np.asarray(tol)[..., None, :] if np.ndim(tol) else np.abs(signal) <= tol
    first = np.argmax(inside, axis=-2)
    out = np.asarray(t)[first].astype(float)
    out[~inside.any(axis=-2)] = np.nan
    return out


def settle_time(t: np.ndarray, signal: np.ndarray, tol: Any) -> np.ndarray:
    """First recorded time from which ``|signal| <= tol`` holds to the end (NaN if it does not hold
    at the end); layout as :func:`entry_time`.

    Parameters
    ----------
    t : array_like
        The recorded times (s), (T,).
    signal : array_like
        The signal, (..., T, D), in its own unit.
    tol : float or array_like
        The band's half-width in the signal's unit: a scalar or (..., D).

    Returns
    -------
    numpy.ndarray
        The settling times (s), (..., D).

    Examples
    --------
    >>> import numpy as np
    >>> from landing.theory import settle_time
    >>> settle_time(np.arange(4.0), np.array([[3.0], [1.0], [2.0], [0.5]]), 1.0)
    array([3.])
    """
    t, signal, tol = _time_signal("settle_time", t, signal, tol)
    inside = np.abs(signal) <= np.asarray(tol)[..., None, :] if np.ndim(tol) else np.abs(signal) <= tol
    tail = np.flip(np.logical_and.accumulate(np.flip(inside, axis=-2), axis=-2), axis=-2)
    first = np.argmax(tail, axis=-2)
    out = np.asarray(t)[first].astype(float)
    out[~tail.any(axis=-2)] = np.nan
    return out
