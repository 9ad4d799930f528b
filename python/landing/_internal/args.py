"""Argument checks shared by the public entry points.

Real numbers only where numbers are meant (no bool, complex, strings or objects, as Python
values or numpy dtypes), integers where counts are meant (Python or numpy integers, through
``operator.index``: ``1.5`` and ``True`` are refused), finite values where the model needs
them, and the caps of :mod:`landing._internal.limits`. Every refusal is a
:class:`~landing.errors.ParameterError` (a ValueError) or
:class:`~landing.errors.ParameterTypeError` (a TypeError) whose message names the argument,
the value and the rule.
"""

from __future__ import annotations

import math
import numbers
import operator
from collections.abc import Sequence
from typing import Any, Optional

import numpy as np

from landing._internal.limits import LIMITS
from landing.errors import ParameterError, ParameterTypeError

__all__ = ["integer", "real", "real_array", "boolean", "choice", "finite_array", "pair", "short", "number_text"]

#: numpy dtype kinds that hold real numbers (bool, complex, strings, dates and objects do not).
_REAL_KINDS = frozenset("iuf")


def short(value: Any, limit: int = 80) -> str:
    """``repr(value)``, cut to ``limit`` characters for the messages (a huge integer as its
    order of magnitude)."""
    if isinstance(value, int) and not isinstance(value, bool):
        return number_text(value)
    try:
        text = repr(value)
    except ValueError:  # a container of integers of more than 4300 digits
        return f"a {type(value).__name__} too large to print"
    return text if len(text) <= limit else text[: limit - 3] + "..."


def number_text(v: int) -> str:
    """An integer for a message: as written up to 20 digits, beyond that its order of
    magnitude (``about 10^300``: a 300-digit number helps no one, and Python refuses to print
    one of more than 4300 digits)."""
    if abs(v) < 10**20:
        return str(v)
    return f"about {'-' if v < 0 else ''}10^{int(math.log10(abs(v)))}"


def _prefix(owner: Optional[str]) -> str:
    return f"{owner}: " if owner else ""


def integer(
    name: str,
    value: Any,
    *,
    minimum: Optional[int] = None,
    maximum: Optional[int] = None,
    cap: Optional[str] = None,
    owner: Optional[str] = None,
) -> int:
    """``value`` as a Python int: a Python or numpy integer (not a bool, not a float even if
    whole), within ``[minimum, maximum]`` and the cap named ``cap`` (a key of LIMITS)."""
    p = _prefix(owner)
    if isinstance(value, (bool, np.bool_)):
        raise ParameterTypeError(f"{p}{name} must be an integer, got {value!r} (a bool)")
    try:
        v = operator.index(value)
    except TypeError:
        raise ParameterTypeError(f"{p}{name} must be an integer, got {short(value)}") from None
    if minimum is not None and v < minimum:
        raise ParameterError(f"{p}{name} = {number_text(v)} violates {name} >= {minimum}")
    if maximum is not None and v > maximum:
        raise ParameterError(f"{p}{name} = {number_text(v)} violates {name} <= {maximum}")
    if cap is not None and v > LIMITS[cap]:
        raise ParameterError(
            f"{p}{name} = {number_text(v)} violates {name} <= {cap} ({LIMITS[cap]}); see landing._core.LIMITS"
        )
    return int(v)


def real(
    name: str,
    value: Any,
    *,
    finite: bool = True,
    positive: bool = False,
    nonnegative: bool = False,
    owner: Optional[str] = None,
) -> float:
    """``value`` as a float: a Python or numpy real number (or a 0-d real array), not a bool,
    complex or string; finite unless ``finite=False``; > 0 or >= 0 when asked."""
    p = _prefix(owner)
    if isinstance(value, np.ndarray) and value.ndim == 0:
        value = value[()]
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real):
        raise ParameterTypeError(f"{p}{name} must be a real number, got {short(value)}")
    try:
        v = float(value)
    except OverflowError:  # an integer beyond the largest double
        raise ParameterError(f"{p}{name} = {short(value)} violates finite values "
                             "(a real number within the doubles, |x| < 1.8e308)") from None
    if finite and not np.isfinite(v):
        raise ParameterError(f"{p}{name} = {v} violates finite values")
    if positive and not v > 0:
        raise ParameterError(f"{p}{name} = {v:g} violates {name} > 0")
    if nonnegative and not v >= 0:
        raise ParameterError(f"{p}{name} = {v:g} violates {name} >= 0")
    return v


_EXPECTED = "a real number or an array of real numbers"


def _check_dtype(name: str, raw: np.ndarray, value: Any, owner: Optional[str], expected: str) -> None:
    p = _prefix(owner)
    kind = raw.dtype.kind
    if kind in _REAL_KINDS:
        return
    if kind == "O":
        for item in raw.flat:
            if isinstance(item, (bool, np.bool_)) or not isinstance(item, numbers.Real):
                break
        else:
            return
    what = {"b": "bool", "c": "complex", "U": "str", "S": "bytes", "O": "object"}.get(kind, str(raw.dtype))
    raise ParameterTypeError(
        f"{p}{name} must be {expected}, got {what} values ({short(value)})"
    )


def real_array(
    name: str,
    value: Any,
    *,
    finite: bool = False,
    owner: Optional[str] = None,
    expected: str = _EXPECTED,
) -> np.ndarray:
    """``value`` as a C-contiguous float64 array, refusing bool, complex, string and object
    values (which ``np.asarray(..., dtype=float)`` would truncate or cast); NaN and Inf are
    refused too with ``finite=True``."""
    p = _prefix(owner)
    if isinstance(value, (str, bytes)):
        raise ParameterTypeError(
            f"{p}{name} must be {expected}, got {short(value)}"
        )
    try:
        raw = value if isinstance(value, np.ndarray) else np.asarray(value)
    except (TypeError, ValueError) as exc:
        raise ParameterTypeError(
            f"{p}{name} must be {expected}, got {short(value)}"
        ) from exc
    _check_dtype(name, raw, value, owner, expected)
    try:
        # np.asarray keeps a scalar 0-d (np.ascontiguousarray would make it (1,))
        arr = np.asarray(raw, dtype=np.float64, order="C")
    except OverflowError:  # integers beyond the largest double
        raise ParameterError(f"{p}{name} = {short(value)} violates finite values (real numbers within the doubles, "
                             "|x| < 1.8e308)") from None
    except (TypeError, ValueError) as exc:
        raise ParameterTypeError(
            f"{p}{name} must be {expected}, got {short(value)}"
        ) from exc
    if finite:
        finite_array(name, arr, owner=owner)
    return arr


def finite_array(name: str, arr: np.ndarray, *, owner: Optional[str] = None) -> np.ndarray:
    """Refuses NaN and Inf in ``arr``, naming the first offending entry."""
    ok = np.isfinite(arr)
    if not ok.all():
        idx = tuple(int(i) for i in np.argwhere(~ok)[0])
        at = f"[{', '.join(map(str, idx))}]" if idx else ""
        raise ParameterError(f"{_prefix(owner)}{name}{at} = {arr[idx]} violates finite values")
    return arr


def boolean(name: str, value: Any, *, owner: Optional[str] = None) -> bool:
    """``value`` as a bool: True or False (Python or numpy), nothing else."""
    if not isinstance(value, (bool, np.bool_)):
        raise ParameterTypeError(f"{_prefix(owner)}{name} must be True or False, got {short(value)}")
    return bool(value)


def choice(name: str, value: Any, options: Sequence[str], *, owner: Optional[str] = None) -> str:
    """``value`` as one of the names ``options``."""
    p = _prefix(owner)
    if not isinstance(value, str):
        raise ParameterTypeError(f"{p}{name} must be a string, one of {tuple(options)}, got {short(value)}")
    if value not in options:
        raise ParameterError(f"{p}{name} = {value!r} is not one of {tuple(options)}")
    return value


def pair(name: str, value: Any, *, owner: Optional[str] = None) -> tuple[Any, Any]:
    """``value`` as a pair of items (a tuple, list or 1-d array of length 2)."""
    if not isinstance(value, (str, bytes)):
        try:
            items = tuple(value)
        except TypeError:  # not iterable, or a 0-d array
            items = None
        if items is not None and len(items) == 2:
            return items[0], items[1]
    raise ParameterTypeError(f"{_prefix(owner)}{name} must be a pair of real numbers, got {short(value)}")
