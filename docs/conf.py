"""Sphinx configuration of landing's documentation: ``python -m sphinx -W -b html docs docs/_build``
(README.md, "Documentation"). The pages are the Markdown files of this folder (MyST); the API
reference is read from the docstrings of the installed package."""

from __future__ import annotations

import re
import sys
from pathlib import Path

import landing

# the generated pages (docs/_ext: the scenario-file reference)
sys.path.insert(0, str(Path(__file__).parent / "_ext"))

project = "landing"
author = "the landing developers"
release = landing.__version__
version = release

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.napoleon",
    "sphinx.ext.mathjax",
    "sphinx.ext.viewcode",
    "toml_reference",
    "guide_examples",
]

source_suffix = {".md": "markdown"}
master_doc = "index"
exclude_patterns = ["_build", "_ext"]

# numpy-style docstrings ("Parameters", "Returns" sections)
napoleon_google_docstring = False
napoleon_numpy_docstring = True
napoleon_use_rtype = False
autodoc_member_order = "bysource"
autodoc_typehints = "description"
autodoc_default_options = {"members": True, "show-inheritance": True}

myst_heading_anchors = 3
# a link to a page or a heading that does not exist is a warning (so an error in CI)
suppress_warnings: list[str] = []
# a bare attribute name in a type or a docstring (``metrics``, ``axes``) that several classes
# hold: Sphinx links it to one of them and warns; the link is right for the class documented
suppress_warnings += ["ref.python"]

html_theme = "alabaster"
html_title = "landing"


def _escape_bars(text: str) -> str:
    """``|F|`` in our docstrings is an absolute value, not reStructuredText's substitution:
    the bars outside inline literals (which may span lines) are escaped."""
    parts = text.split("``")
    for i in range(0, len(parts), 2):  # the even parts lie outside ``literals``
        parts[i] = re.sub(r"(?<!\\)\|", r"\\|", parts[i])
    return "``".join(parts)


def _plain_text_math(app, what, name, obj, options, lines) -> None:  # noqa: ANN001 - Sphinx's hook
    lines[:] = _escape_bars("\n".join(lines)).split("\n")


def setup(app) -> None:  # noqa: ANN001 - Sphinx's entry point
    app.connect("autodoc-process-docstring", _plain_text_math)
