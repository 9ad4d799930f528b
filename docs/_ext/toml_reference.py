"""The scenario-file reference page, generated from the classes the files name (their kinds,
fields, defaults) and the core's declarations of their parameters (shape, unit, rule, doc):
the page cannot drift from what a file may hold. Written to ``_generated/toml.md`` when the
build starts."""

from __future__ import annotations

import dataclasses
import inspect
from collections.abc import Mapping
from pathlib import Path
from types import ModuleType
from typing import Any

import numpy as np

from landing.scenarios import Scenario
from landing.scenarios.files import _SETTINGS, NESTED, SECTIONS

HEAD = """# Scenario files (TOML): reference

A scenario file holds the scenario's own settings at the top level and one table per part, each
with a `kind` naming its class; the other keys are the class's parameters, as in Python
(`landing run FILE`, `landing mc FILE --cases N`, `landing.scenarios.read_toml(path)`;
`landing show PRESET` prints any preset as a file to start from). This page is generated from
the classes and the core's declarations of their parameters.

Shapes: *scalar* (a number, or one per case as a list), *per_axis* (a number, a list of one per
axis, or per case a list of lists), *per_component* (a number or a list; a sensor's may also be
per case), *choice* (a string among those listed), *flag* (`true`/`false`), *count* (a whole
number among those listed), *nested* (a table of the family named), *list* (an array of tables).
A parameter whose default is shown may be left out.
"""

FAMILY_OF_NESTED = {"gravity": "gravity fields", "system": "fuzzy systems", "sensor": "sensors", "filter": "filters"}


def _default(field: dataclasses.Field) -> str:
    if field.default is not dataclasses.MISSING:
        value = field.default
    elif field.default_factory is not dataclasses.MISSING:
        value = field.default_factory()
    else:
        return "required"
    if value is None:
        return "none"
    if isinstance(value, (bool, str)):
        return f"`{str(value).lower() if isinstance(value, bool) else value}`"
    if isinstance(value, (int, float, np.floating)):
        return f"`{value:g}`"
    if isinstance(value, (tuple, list, np.ndarray)) and len(value) <= 7:
        return "`" + str(np.asarray(value).tolist()) + "`"
    return f"`{type(value).__name__}`"


def _cell(text: str) -> str:
    return text.replace("|", "\\|").replace("\n", " ")


def _kinds(module: ModuleType) -> list[type]:
    out = []
    for name in module.__all__:
        cls = getattr(module, name)
        if inspect.isclass(cls) and dataclasses.is_dataclass(cls) and "kind" in vars(cls):
            out.append(cls)
    return out


def _table(cls: type) -> list[str]:
    declared = getattr(cls, "parameters", {})
    if not isinstance(declared, Mapping):  # a law or plant written in Python: its own params
        declared = {}
    doc = (inspect.getdoc(cls) or "").split("\n\n")[0].replace("\n", " ")
    lines = [f"### `kind = \"{cls.__name__}\"`", "", doc, ""]
    rows = []
    for f in dataclasses.fields(cls):
        if f.name.startswith("_"):
            continue
        key = f.name  # a file's key is the Python field's name, the core's name too
        p = declared.get(f.name)
        if p is None:
            rows.append(f"| `{key}` | | | | {_default(f)} | |")
            continue
        shape = p.shape + (f" ({', '.join(map(str, p.choices))})" if p.choices else "")
        shape += f" of {p.family}" if p.family else ""
        cells = [f"`{key}`", _cell(shape), _cell(p.unit), _cell(p.rule), _default(f), _cell(p.doc)]
        rows.append("| " + " | ".join(cells) + " |")
    if rows:
        lines += ["| key | shape | unit | rule | default | meaning |", "|---|---|---|---|---|---|", *rows, ""]
    return lines


def page() -> str:
    lines = [HEAD, "## Settings (top level)", "", "| key | default |", "|---|---|"]
    fields = {f.name: f for f in dataclasses.fields(Scenario)}
    for key in _SETTINGS:
        lines.append(f"| `{key}` | {_default(fields[key]) if key in fields else ''} |")
    lines += ["", "What each setting means: `landing.simulate_batch` and `landing.scenarios.Scenario` in the API "
              "reference (the keywords of the same names). `[dispersions]` maps a parameter's path "
              "(`\"plant.isp\"`, `\"plant.sensor.bias\"`) to a dispersion table (below) or "
              "`{ normal = [mean, std] }`. A disturbance of several components is an array of tables, "
              "`[[disturbance]]`, one per component.", ""]
    for section, module in SECTIONS.items():
        lines += [f"## `[{section}]`", ""]
        for cls in _kinds(module):
            lines += _table(cls)
    for key, module in NESTED.items():
        lines += [f"## `{key}` tables ({FAMILY_OF_NESTED[key]})", ""]
        kinds = [c for c in _kinds(module) if getattr(c, "family", key) in (key, "sensor", "filter")]
        if key in ("sensor", "filter"):
            kinds = [c for c in kinds if getattr(c, "family", None) == key]
        for cls in kinds:
            lines += _table(cls)
        if key == "system":
            lines += ["A `landing.fuzzy.Mamdani` system: `kind = \"Mamdani\"`, `resolution`, `inputs` and "
                      "`output` (each a `universe` and its named `sets`, a set a shape's name and its corners) "
                      "and `rules` (`[[antecedents...], consequent]`); `landing show seed002_fuzzy_variable_rate` "
                      "prints one.", ""]
    return "\n".join(lines) + "\n"


def _write(app: Any) -> None:
    out = Path(app.srcdir) / "_generated" / "toml.md"
    out.parent.mkdir(exist_ok=True)
    text = page()
    if not out.exists() or out.read_text(encoding="utf-8") != text:
        out.write_text(text, encoding="utf-8")


def setup(app: Any) -> dict[str, Any]:
    app.connect("builder-inited", _write)
    return {"parallel_read_safe": True}
