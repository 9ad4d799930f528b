"""Importing an optional extra (cma, matplotlib, SALib...) so that an interrupt cannot break it.

Python leaves a module whose import was interrupted (Ctrl-C during ``import cma``, which takes
a second) half-initialised in ``sys.modules``: every later import returns the broken module,
and the process can no longer tune or plot. :func:`import_extra` takes the module and its
submodules out again when its import does not complete, so that the next call imports it
afresh.
"""

from __future__ import annotations

import importlib
import sys
from types import ModuleType

__all__ = ["import_extra"]


def import_extra(name: str, install: str) -> ModuleType:
    """The module ``name`` (``"matplotlib.pyplot"``), imported; ``install`` is what to install
    when it is missing (``'pip install "landing[tune]"'``), in the ImportError."""
    before = set(sys.modules)
    try:
        return importlib.import_module(name)
    except ImportError as exc:
        raise ImportError(f"{name} is needed here: {install} ({exc})") from None
    except BaseException:
        # an interrupt (or any failure) half-way: forget what this import added
        for key in set(sys.modules) - before:
            del sys.modules[key]
        raise
