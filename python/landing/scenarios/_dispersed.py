"""Dispersed parameters: a parameter of a scenario's plant, law, reference or disturbance named by
its path (``"plant.isp"``, ``"controller.alpha1"``, ``"disturbance.parts[1].bound"``), its
declaration read from the core's schema, and a case's draws put in its place.

The paths are the ones :meth:`Scenario.case_rows <landing.scenarios.Scenario.case_rows>` prints
for parameters given per case: the scenario's field, then a nested configuration's field (with
``[i]`` for an item of a list), then the parameter's name.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from typing import Any

import numpy as np

from landing._internal.table import Table
from landing.dispersions import Dispersion
from landing.disturbances import Sum
from landing.errors import ParameterError, ParameterTypeError

__all__ = ["apply_draws", "checked_dispersions", "target"]

#: The scenario's fields whose parameters may be dispersed.
PARTS = ("plant", "controller", "reference", "disturbance")

_SEGMENT = re.compile(r"([A-Za-z_]\w*)((?:\[\d+\])*)")


#: How a case's draws are given to a dispersed parameter: ``"rows"``, one value per case
#: ``(N,)``; ``"columns"``, ``(N, k)`` (a per-axis parameter, or a Python law's or plant's).
Form = str


def _segments(name: str) -> list[tuple[str, list[int]]]:
    parts = name.split(".")
    out = []
    for part in parts:
        m = _SEGMENT.fullmatch(part)
        if m is None:
            raise ParameterError(f"dispersions: {name!r} is not a parameter's path ('plant.isp', "
                                 "'controller.alpha1', 'disturbance.parts[0].bound')")
        out.append((m.group(1), [int(i) for i in re.findall(r"\d+", m.group(2))]))
    if len(out) < 2 or out[0][0] not in PARTS or out[-1][1]:
        raise ParameterError(f"dispersions: {name!r} must start with one of {PARTS} and end with a parameter's "
                             "name ('plant.isp')")
    return out


def _child(obj: Any, attr: str, index: list[int], name: str) -> Any:
    value = getattr(obj, attr, None)
    if value is None:
        raise ParameterError(f"dispersions: {name!r}: {type(obj).__name__} has no {attr!r} to disperse in")
    for i in index:
        if not isinstance(value, (list, tuple)) or i >= len(value):
            raise ParameterError(f"dispersions: {name!r}: {attr} has no item [{i}]")
        value = value[i]
    return value


def _leaf(owner: Any, attr: str, name: str, axes: int, dim: int) -> Form:
    """The per-case form in which parameter ``attr`` of ``owner`` takes the draws of a
    ``dim``-component dispersion, checked against the parameter's declaration."""
    if isinstance(owner, Sum):
        raise ParameterError(f"dispersions: {name!r}: a sum of disturbances holds its components in "
                             "'parts[i]' ('disturbance.parts[0].bound')")
    params = getattr(owner, "params", None)
    if not getattr(owner, "_in_core", True) and isinstance(params, Mapping):
        # a law or plant written in Python: its own named parameters, given per case as (N, k)
        # (a law) or (N,) and (N, k) (a plant: a scalar stays one number per case)
        if attr not in params:
            raise ParameterError(f"dispersions: {name!r}: {type(owner).__name__} has no parameter {attr!r} "
                                 f"(its params: {sorted(params)})")
        plant = isinstance(owner, Table) and owner.family == "plant"
        return "rows" if plant and dim == 1 else "columns"
    declared = getattr(owner, "parameters", {})
    p = declared.get(attr)
    if p is None:
        raise ParameterError(f"dispersions: {name!r}: {type(owner).__name__} has no parameter {attr!r} "
                             f"(its parameters: {sorted(declared)})")
    if not p.per_case:
        raise ParameterError(f"dispersions: {name!r} is a {p.shape} parameter; only the numbers a case reads "
                             "(scalar, per-axis or a sensor's per-component parameters) can be dispersed")
    if p.shape == "per_component":
        # one draw for every component, or one per component (the core checks their number)
        return "columns"
    if p.shape == "scalar":
        if dim != 1:
            raise ParameterError(f"dispersions: {name!r} is a scalar; its dispersion has {dim} components, not 1")
        return "rows"
    if dim not in (1, axes):
        raise ParameterError(f"dispersions: {name!r} is per axis ({axes} axes); its dispersion has {dim} "
                             f"components: give 1 (one draw for every axis) or {axes} (one per axis)")
    return "columns"


def target(scenario: Any, name: str, dispersion: Any) -> Form:
    """How the parameter ``name`` of ``scenario``, which ``dispersion`` disperses, takes a
    case's draws (checked: it exists, is numeric, and the components fit it)."""
    if not isinstance(name, str):
        raise ParameterTypeError(f"dispersions: a key must be a parameter's path (a string), got {name!r}")
    if not isinstance(dispersion, Dispersion):
        raise ParameterTypeError(f"dispersions: {name!r} must be given a landing.dispersions dispersion "
                                 f"(Normal, Uniform, TruncatedNormal, LogNormal), got {dispersion!r}")
    segments = _segments(name)
    obj: Any = scenario
    for attr, index in segments[:-1]:
        obj = _child(obj, attr, index, name)
    return _leaf(obj, segments[-1][0], name, scenario.plant.axes, dispersion.dim)


def checked_dispersions(scenario: Any, dispersions: Any) -> Mapping[str, Dispersion]:
    """``dispersions`` (name -> dispersion) as a dict of its own (picklable, for the Dask
    workers), each name checked against
    the scenario's parts."""
    if not isinstance(dispersions, Mapping):
        raise ParameterTypeError("dispersions must be a dict of parameter paths to landing.dispersions "
                                 f"dispersions, got {type(dispersions).__name__}")
    for name, d in dispersions.items():
        target(scenario, name, d)
    return dict(dispersions)


def _with(obj: Any, segments: list[tuple[str, list[int]]], value: np.ndarray) -> Any:
    """``obj`` with the parameter at ``segments`` set to ``value`` (each configuration on the
    way made anew, so validated)."""
    attr, index = segments[0]
    if len(segments) == 1:
        return obj.replace(**{attr: value})
    child = getattr(obj, attr)
    new = _within(child, index, segments[1:], value)
    if isinstance(obj, Sum) and attr == "parts":
        return Sum(new)
    return obj.replace(**{attr: new})


def _within(value: Any, index: list[int], rest: list[tuple[str, list[int]]], v: np.ndarray) -> Any:
    if not index:
        return _with(value, rest, v)
    items = list(value)
    items[index[0]] = _within(items[index[0]], index[1:], rest, v)
    return type(value)(items) if isinstance(value, tuple) else items


def apply_draws(scenario: Any, draws: Mapping[str, np.ndarray]) -> Any:
    """``scenario`` with each dispersed parameter given its cases' draws (``(m, k)`` each, in
    the per-case form its declaration takes)."""
    for name, d in draws.items():
        form = target(scenario, name, scenario.dispersions[name])
        value = d[:, 0] if form == "rows" else d
        scenario = _with(scenario, _segments(name), np.ascontiguousarray(value))
    return scenario
