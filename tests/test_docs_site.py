"""The documentation site's generated scenario-file reference: every key of every preset's file
is a row of its kind's table (the presets' files are written by a second path, the TOML
writer, so a kind or key the page misses is caught)."""

from __future__ import annotations

import re
import sys
from pathlib import Path

import pytest

from landing.scenarios import PRESETS, preset
from landing.scenarios.files import tomllib

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "docs" / "_ext"))
toml_reference = pytest.importorskip("toml_reference")


def _sections(page: str) -> dict[str, set[str]]:
    """Keys by kind, as the page lists them."""
    out: dict[str, set[str]] = {}
    kind = None
    for line in page.splitlines():
        if m := re.match(r'### `kind = "(\w+)"`', line):
            kind = m.group(1)
            out.setdefault(kind, set())
        elif kind and (m := re.match(r"\| `(\w+)` \|", line)):
            out[kind].add(m.group(1))
    return out


def _tables(d: dict, path: str = ""):
    """Every table with a kind in a scenario file, with where it is."""
    if "kind" in d and isinstance(d["kind"], str):
        yield path, d
    for k, v in d.items():
        if isinstance(v, dict):
            yield from _tables(v, f"{path}.{k}")
        elif isinstance(v, list) and v and all(isinstance(x, dict) for x in v):
            for i, x in enumerate(v):
                yield from _tables(x, f"{path}.{k}[{i}]")


@pytest.mark.parametrize("name", sorted(PRESETS))
def test_every_key_of_every_preset_file_is_on_the_reference_page(name):
    listed = _sections(toml_reference.page())
    settings = set(re.findall(r"^\| `(\w+)` \| [^|]* \|$", toml_reference.page(), flags=re.M))
    data = tomllib.loads(preset(name).to_toml())
    for key, value in data.items():
        if not isinstance(value, dict) and not (isinstance(value, list) and value and isinstance(value[0], dict)):
            assert key in settings, f"{name}: setting {key!r} is not on the page"
    for where, table in _tables({k: v for k, v in data.items() if k != "dispersions"}):
        kind = table["kind"]
        if kind in ("Mamdani", "Sum"):
            continue
        assert kind in listed, f"{name}{where}: kind {kind!r} is not on the page"
        missing = set(table) - {"kind"} - listed[kind]
        assert not missing, f"{name}{where}: {sorted(missing)} of {kind} are not on the page"
