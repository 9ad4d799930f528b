"""The API reference's rule (issue 26): every public function and class of the modules below
has, in its numpy-style docstring, ``Parameters`` (when it takes any), ``Returns`` (functions
that return something) and ``Examples``; and every example runs and prints what it says."""

from __future__ import annotations

import doctest
import importlib
import inspect
import re
from collections.abc import Iterator
from types import ModuleType
from typing import Any

import numpy as np
import pytest

MODULES = [
    "landing",
    "landing.plants",
    "landing.controllers",
    "landing.reference",
    "landing.disturbances",
    "landing.gravity",
    "landing.dispersions",
    "landing.sensors",
    "landing.fuzzy",
    "landing.simulation",
    "landing.results",
    "landing.errors",
    "landing.optimal",
    "landing.tuning",
    "landing.tuning.pareto",
    "landing.tuning.result",
    "landing.tuning.search",
    "landing.scenarios._scenario",
    "landing.scenarios.files",
    "landing.campaign",
    "landing.campaign.api",
    "landing.campaign.result",
    "landing.campaign.store",
    "landing.campaign.lazy",
    "landing.campaign.dask",
    "landing.campaign.sensitivity",
    "landing.campaign.verify",
    "landing.theory",
    "landing.theory.bounds",
    "landing.theory.checks",
    "landing.theory._signals",
    "landing.plots",
    "landing.plots._common",
    "landing.plots.comparison",
    "landing.plots.mars",
    "landing.plots.sensitivity",
    "landing.plots.standard",
    "landing.plots.tether",
    "landing.plots.tuning",
]

#: What the examples of a module need beyond the package: its optional extras' modules.
EXTRAS = {
    "landing.results": ("pandas", "xarray"),  # to_pandas, to_xarray (io)
    "landing.campaign.api": ("zarr", "pyarrow"),  # load: a campaign store (io)
    "landing.campaign.result": ("xarray",),  # to_xarray (io)
    "landing.campaign.store": ("zarr", "pyarrow"),
    "landing.campaign.lazy": ("zarr", "pyarrow", "xarray"),
    "landing.campaign.dask": ("distributed",),
    "landing.campaign.sensitivity": ("SALib",),  # sobol
    **{f"landing.plots.{m}": ("matplotlib",) for m in ("_common", "comparison", "mars", "sensitivity", "standard",
                                                       "tether")},
    "landing.plots.tuning": ("matplotlib", "cma"),
}


def _public(module: ModuleType) -> Iterator[tuple[str, Any]]:
    for name in getattr(module, "__all__", []):
        obj = getattr(module, name)
        if not (inspect.isclass(obj) or inspect.isfunction(obj)):
            continue
        if obj.__module__ != module.__name__:
            continue  # re-exported: checked in the module that defines it
        yield f"{module.__name__}.{name}", obj


def _has_section(doc: str, *titles: str) -> bool:
    return any(re.search(rf"^{t}\n-{{3,}}$", doc, re.M) for t in titles)


def _takes_parameters(obj: Any) -> bool:
    try:
        sig = inspect.signature(obj)
    except (TypeError, ValueError):
        return False
    named = (inspect.Parameter.POSITIONAL_ONLY, inspect.Parameter.POSITIONAL_OR_KEYWORD,
             inspect.Parameter.KEYWORD_ONLY)
    return any(p.kind in named and p.name != "self" for p in sig.parameters.values())


def _returns_something(obj: Any) -> bool:
    ann = inspect.signature(obj).return_annotation
    return ann not in (None, "None", inspect.Signature.empty)


def _missing(obj: Any) -> list[str]:
    doc = inspect.getdoc(obj) or ""
    missing = []
    if _takes_parameters(obj) and not _has_section(doc, "Parameters"):
        missing.append("Parameters")
    if inspect.isfunction(obj) and _returns_something(obj) and not _has_section(doc, "Returns", "Yields"):
        missing.append("Returns")
    if not _has_section(doc, "Examples?"):
        missing.append("Examples")
    return missing


PUBLIC = [item for name in MODULES for item in _public(importlib.import_module(name))]


@pytest.mark.parametrize("qualname, obj", PUBLIC, ids=[q for q, _ in PUBLIC])
def test_sections(qualname: str, obj: Any) -> None:
    missing = _missing(obj)
    assert not missing, f"{qualname}: the docstring has no {', '.join(missing)} section"


@pytest.mark.parametrize("name", MODULES)
def test_examples_run(name: str) -> None:
    if name == "landing.optimal":
        pytest.importorskip("casadi")  # the optimal extra
    if name.startswith("landing.tuning."):
        pytest.importorskip("cma")  # the tune extra
    for extra in EXTRAS.get(name, ()):
        pytest.importorskip(extra)
    module = importlib.import_module(name)
    with np.printoptions(precision=4, suppress=True, legacy=False):
        result = doctest.testmod(module, optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    assert result.failed == 0, f"{result.failed} of the examples of {name} failed (output above)"
