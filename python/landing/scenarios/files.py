"""Scenarios as TOML files: every preset ships as one, and a user's copy runs the same way.

A file holds the scenario's own settings at the top level and one table per part::

    name = "mars_nominal"
    t_final = 60.0
    dt = 0.001
    x0 = [-2000.0, 1000.0, 1500.0, 100.0, -15.0, -75.0, 1905.0]

    [plant]
    kind = "MarsLander"
    isp = 225.0

    [controller]
    kind = "FixedTimeMSS"
    alpha1 = 4.89
    ...

``kind`` names the class in the part's module (``landing.plants``, ``landing.controllers``,
``landing.reference``, ``landing.dispersions``, ``landing.disturbances``; a plant's ``gravity``
table is a ``landing.gravity`` field, its ``sensor`` and ``filter`` tables ``landing.sensors``
classes, a law's ``system`` a ``landing.fuzzy.Mamdani``); the other
keys are the class's parameters, as in Python. A disturbance of several components is an array
of tables (``[[disturbance]]``). Numbers, per-axis lists and per-case lists of lists are
written as in Python.

A bad file is refused with a :class:`FileError` (a ``ParameterError``) naming the file, the key,
the value and the rule. The presets' files are generated from the Python presets
(:data:`landing.scenarios.PRESETS`) and a test checks that they agree.
"""

from __future__ import annotations

import dataclasses
import json
import math
import os
import re
import sys
from collections.abc import Mapping
from types import ModuleType
from typing import Any

import numpy as np

from landing import controllers, dispersions, disturbances, fuzzy, gravity, plants, reference, sensors
from landing._internal.table import Table
from landing._internal.user_law import load_function, qualified_name
from landing.errors import LandingError, ParameterError
from landing.scenarios._scenario import Scenario
from landing.simulation import RunOptions

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - exercised on Python < 3.11 only
    import tomli as tomllib

__all__ = ["FileError", "dumps", "read_toml", "scenario_to_dict", "scenario_to_toml", "scenario_from_dict", "tomllib"]

#: The part tables of a file and the module their ``kind`` is looked up in.
SECTIONS: dict[str, ModuleType] = {
    "plant": plants,
    "controller": controllers,
    "reference": reference,
    "dispersion": dispersions,
    "disturbance": disturbances,
}

#: Parameters that hold a nested configuration object, and its module.
NESTED: dict[str, ModuleType] = {"gravity": gravity, "system": fuzzy, "sensor": sensors, "filter": sensors}

#: The scenario's own settings: key -> (rule, check). The parts are checked by their classes.
_SETTINGS = ("name", "description", "x0", "t_final", "dt", "integrator", "substeps", "record_every",
             "settle_tolerance", "chatter_cutoff", "stop_at", "theta")


class FileError(ParameterError):
    """A scenario file that cannot be read: the message names the file, the key, the value and
    the rule. A :class:`~landing.errors.ParameterError`.

    Parameters
    ----------
    *args : object
        The message (a str), as for any exception.

    Examples
    --------
    >>> try:
    ...     read_toml("a = ", "broken.toml")
    ... except FileError as e:
    ...     print(e)  # doctest: +ELLIPSIS
    broken.toml: not valid TOML (...)
    """


# ---------------------------------------------------------------------------------------------
# writing


def _plain(value: Any) -> Any:
    """A parameter value as TOML can hold it (lists of floats, ints, strings, booleans)."""
    if isinstance(value, (bool, str, int)) and not isinstance(value, np.generic):
        return value
    if isinstance(value, (np.bool_,)):
        return bool(value)
    if isinstance(value, np.integer):
        return int(value)
    if isinstance(value, fuzzy.Mamdani):  # a Table, but not a dataclass
        return _encode_mamdani(value)
    if isinstance(value, Table):
        return _encode_table(value)
    if isinstance(value, (tuple, list)) and any(isinstance(v, str) for v in value):
        return [_plain(v) for v in value]
    arr = np.asarray(value, dtype=float)
    return float(arr) if arr.ndim == 0 else arr.tolist()


def _encode_mamdani(m: fuzzy.Mamdani) -> dict[str, Any]:
    def variable(v: fuzzy.Variable) -> dict[str, Any]:
        return {
            "universe": [float(v.universe[0]), float(v.universe[1])],
            "sets": {name: [str(s[0])] + [float(x) for x in s[1:]] for name, s in v.sets.items()},
        }

    return {
        "kind": "Mamdani",
        "resolution": int(m.resolution),
        "inputs": [variable(v) for v in m.inputs],
        "output": variable(m.output),
        "rules": [[list(a), c] for a, c in m.rules],
    }


def _encode_python_law(law: controllers.PythonLaw) -> dict[str, Any]:
    """A law written in Python: its function by ``module:name`` and the hash of its source (so
    that a store's provenance tells a changed function), and its settings."""
    out: dict[str, Any] = {"kind": "PythonLaw", "function": qualified_name(law.function),
                           "source_sha256": law.source_hash}
    if law.name != qualified_name(law.function):
        out["name"] = law.name
    if law.params:
        out["params"] = {k: _plain(v) for k, v in law.params.items()}
    if callable(law.memory):
        out["memory"] = qualified_name(law.memory)
    elif law.memory is not None:
        out["memory"] = {k: _plain(v) for k, v in law.memory.items()}
    if law.diagnostics:
        out["diagnostics"] = dict(law.diagnostic_kinds)
    if law.cases_per_call != controllers.DEFAULT_CASES_PER_CALL:
        # TOML has no None: "all" is the whole batch in every call
        out["cases_per_call"] = "all" if law.cases_per_call is None else law.cases_per_call
    return out


def _encode_table(obj: Table) -> dict[str, Any]:
    if isinstance(obj, controllers.PythonLaw):
        return _encode_python_law(obj)
    out: dict[str, Any] = {"kind": type(obj).__name__}
    for f in dataclasses.fields(obj):
        if not f.init:
            continue
        value = getattr(obj, f.name)
        if value is None:
            if f.default is not None:
                raise ParameterError(
                    f"{type(obj).__name__}: {f.name} = None cannot be written to a file (its default is "
                    f"{f.default!r})"
                )
            continue  # None is the default: leaving the key out restores it
        out[f.name] = _plain(value)
    return out


def scenario_to_dict(scenario: Scenario) -> dict[str, Any]:
    """The scenario as the nested dict a TOML file holds.

    Parameters
    ----------
    scenario : Scenario
        The scenario; its parts are written by class name (``kind``) and fields.

    Returns
    -------
    dict
        Plain values (numbers, strings, lists) and nested dicts, as :func:`dumps` writes them
        and :func:`scenario_from_dict` reads them.

    Examples
    --------
    >>> import landing
    >>> from landing.controllers import PDSlidingMode
    >>> from landing.scenarios import Scenario
    >>> s = Scenario("pd", landing.plants.DoubleIntegrator(),
    ...              PDSlidingMode(lambda_=1.0, k=0.5, switch="sat", boundary_layer=0.1),
    ...              x0=[10.0, 0, 5, 0, 0, 0], t_final=10.0, dt=0.05)
    >>> d = scenario_to_dict(s)
    >>> d["dt"], d["plant"], d["controller"]["kind"]
    (0.05, {'kind': 'DoubleIntegrator'}, 'PDSlidingMode')
    """
    out: dict[str, Any] = {}
    for key in _SETTINGS:
        value = getattr(scenario, key)
        if value is None:
            continue
        if key in ("name", "description", "integrator", "stop_at"):
            out[key] = str(value)
        elif key in ("substeps", "record_every"):
            out[key] = int(value)
        else:
            out[key] = _plain(value)
    if isinstance(scenario.plant, plants.PythonPlant):
        raise ParameterError(
            f"{scenario.name}: a PythonPlant cannot be written to a scenario file yet (nor, so, kept in a "
            "campaign store); run the campaign without store=, or use a built-in plant"
        )
    out["plant"] = _encode_table(scenario.plant)
    out["controller"] = _encode_table(scenario.controller)
    if scenario.reference is not None:
        out["reference"] = _encode_table(scenario.reference)
    if scenario.dispersion is not None:
        out["dispersion"] = _encode_table(scenario.dispersion)
    if scenario.dispersions:
        out["dispersions"] = {name: _encode_table(d) for name, d in scenario.dispersions.items()}
    d = scenario.disturbance
    if d is not None:
        parts = d.components() if isinstance(d, disturbances.Disturbance) else list(d)
        out["disturbance"] = [_encode_table(p) for p in parts]
    return out


def scenario_to_toml(scenario: Scenario) -> str:
    """The scenario as TOML text (what ``landing show`` prints and a store keeps).

    Parameters
    ----------
    scenario : Scenario
        The scenario.

    Returns
    -------
    str
        The TOML text; :func:`landing.scenarios.load_scenario` reads it back.

    Examples
    --------
    >>> import landing
    >>> from landing.controllers import PDSlidingMode
    >>> from landing.scenarios import Scenario
    >>> s = Scenario("pd", landing.plants.DoubleIntegrator(),
    ...              PDSlidingMode(lambda_=1.0, k=0.5, switch="sat", boundary_layer=0.1),
    ...              x0=[10.0, 0, 5, 0, 0, 0], t_final=10.0, dt=0.05)
    >>> print(scenario_to_toml(s).split("[controller]")[1].strip())
    kind = "PDSlidingMode"
    lambda_ = 1.0
    k = 0.5
    switch = "sat"
    boundary_layer = 0.1
    """
    header = f"# landing scenario{': ' + scenario.description if scenario.description else ''}\n"
    return header + dumps(scenario_to_dict(scenario))


def _key(k: str) -> str:
    return k if re.fullmatch(r"[A-Za-z0-9_-]+", k) else json.dumps(k)


def _value(v: Any) -> str:
    """One TOML value: the restricted set this module writes (no dates)."""
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)  # the shortest text that reads back as the same double
    if isinstance(v, str):
        return json.dumps(v)  # JSON's escapes are TOML basic-string escapes
    if isinstance(v, list):
        return "[" + ", ".join(_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{_key(k)} = {_value(x)}" for k, x in v.items()) + " }"
    raise TypeError(f"cannot write {v!r} to TOML")


def _is_table_list(v: Any) -> bool:
    return isinstance(v, list) and len(v) > 0 and all(isinstance(x, dict) for x in v)


def _emit(table: Mapping[str, Any], path: list[str], lines: list[str]) -> None:
    for k, v in table.items():
        if not isinstance(v, dict) and not _is_table_list(v):
            lines.append(f"{_key(k)} = {_value(v)}")
    for k, v in table.items():
        sub = path + [_key(k)]
        if isinstance(v, dict):
            lines.extend(["", f"[{'.'.join(sub)}]"])
            _emit(v, sub, lines)
        elif _is_table_list(v):
            for item in v:
                lines.extend(["", f"[[{'.'.join(sub)}]]"])
                _emit(item, sub, lines)


def dumps(d: Mapping[str, Any]) -> str:
    """TOML text of a nested dict of the kinds :func:`scenario_to_dict` makes: plain values
    first, then each table as a ``[section]`` and each list of tables as ``[[sections]]``, every
    number written so that it reads back bit for bit.

    Parameters
    ----------
    d : Mapping[str, Any]
        Plain values (numbers, strings, booleans, lists of them), tables and lists of tables.

    Returns
    -------
    str
        The TOML text.

    Examples
    --------
    >>> print(dumps({"a": 1, "b": {"c": 0.1, "d": "x"}}).strip())
    a = 1
    <BLANKLINE>
    [b]
    c = 0.1
    d = "x"
    """
    lines: list[str] = []
    _emit(d, [], lines)
    return "\n".join(lines) + "\n"


# ---------------------------------------------------------------------------------------------
# reading


def read_toml(text: str, source: str) -> dict[str, Any]:
    """The TOML ``text`` of the file ``source`` as a dict; what is not TOML, or nested more
    deeply than the parser can follow (its recursion), is a :class:`FileError` naming the file.

    Parameters
    ----------
    text : str
        The file's text.
    source : str
        The file's name, for the messages.

    Returns
    -------
    dict
        The parsed tables.

    Raises
    ------
    FileError
        If the text is not TOML or is nested too deeply.

    Examples
    --------
    >>> read_toml("a = 1", "x.toml")
    {'a': 1}
    >>> read_toml(dumps({"b": {"c": 0.1}}), "x.toml")
    {'b': {'c': 0.1}}
    """
    try:
        return tomllib.loads(text)
    except ValueError as exc:  # a TOMLDecodeError, or a value Python cannot hold (an integer of 5000 digits)
        raise FileError(f"{source}: not valid TOML ({exc})") from None
    except RecursionError:
        raise FileError(f"{source}: not a scenario file: its arrays or tables are nested too deeply to read "
                        "(a scenario nests a few levels)") from None


def _where(source: str, path: str) -> str:
    return f"{source}: {path}" if path else source


def _classes(module: ModuleType) -> dict[str, type]:
    out = {}
    for name in getattr(module, "__all__", dir(module)):
        cls = getattr(module, name, None)
        if isinstance(cls, type) and dataclasses.is_dataclass(cls) and issubclass(cls, Table):
            out[name] = cls
    return out


def _kind(table: Mapping[str, Any], module: ModuleType, source: str, path: str) -> type:
    known = _classes(module)
    if "kind" not in table:
        raise FileError(f"{_where(source, path)}: missing key 'kind' (one of {sorted(known)})")
    kind = table["kind"]
    if kind not in known:
        raise FileError(f"{_where(source, path + '.kind')} = {kind!r} is not one of {sorted(known)}")
    return known[kind]


def _decode_mamdani(table: Mapping[str, Any], source: str, path: str) -> fuzzy.Mamdani:
    allowed = {"kind", "resolution", "inputs", "output", "rules"}
    for key in table:
        if key not in allowed:
            raise FileError(f"{_where(source, path + '.' + key)}: unknown key (Mamdani takes {sorted(allowed)})")
    if table.get("kind") != "Mamdani":
        raise FileError(f"{_where(source, path + '.kind')} = {table.get('kind')!r} is not 'Mamdani'")

    def variable(t: Any, p: str) -> fuzzy.Variable:
        if not isinstance(t, Mapping) or set(t) != {"universe", "sets"}:
            raise FileError(f"{_where(source, p)}: a fuzzy variable is a table with 'universe' and 'sets'")
        return fuzzy.Variable(tuple(t["universe"]), {k: tuple(v) for k, v in t["sets"].items()})

    try:
        inputs = [variable(t, f"{path}.inputs[{i}]") for i, t in enumerate(table.get("inputs", []))]
        output = variable(table.get("output"), f"{path}.output")
        rules = [(tuple(r[0]), r[1]) for r in table.get("rules", [])]
        return fuzzy.Mamdani(inputs, output, rules, table.get("resolution", 401))
    except FileError:
        raise
    except (LandingError, TypeError, ValueError, IndexError, KeyError) as exc:
        raise FileError(f"{_where(source, path)}: {exc}") from None


def _decode_value(value: Any, source: str, path: str) -> Any:
    if isinstance(value, Mapping):
        name = path.rsplit(".", 1)[-1]
        if name in NESTED:
            if NESTED[name] is fuzzy:
                return _decode_mamdani(value, source, path)
            return _decode_table(value, NESTED[name], source, path)
        raise FileError(f"{_where(source, path)}: a table is not a valid value here")
    return value


#: Other spellings of a kind: ``kind = "python"`` is :class:`~landing.controllers.PythonLaw`.
ALIASES = {"python": "PythonLaw"}


def _function(spec: Any, source: str, path: str) -> Any:
    if not isinstance(spec, str):
        raise FileError(f"{_where(source, path)} = {spec!r} must be a string 'package.module:name'")
    folders = [os.getcwd()]
    if os.path.isfile(source):
        folders.insert(0, os.path.dirname(os.path.abspath(source)))
    try:
        return load_function(spec, folders)
    except (ValueError, ImportError, AttributeError) as exc:
        raise FileError(f"{_where(source, path)} = {spec!r}: {type(exc).__name__}: {exc}") from None


def _decode_python_law(table: Mapping[str, Any], source: str, path: str) -> Table:
    allowed = {"kind", "function", "source_sha256", "name", "params", "memory", "diagnostics", "cases_per_call"}
    for key in table:
        if key not in allowed:
            raise FileError(f"{_where(source, path + '.' + key)}: unknown key (PythonLaw takes {sorted(allowed)})")
    if "function" not in table:
        raise FileError(f"{_where(source, path)}: missing key 'function' ('package.module:name')")
    function = _function(table["function"], source, f"{path}.function")
    memory = table.get("memory")
    if isinstance(memory, str):
        memory = _function(memory, source, f"{path}.memory")
    per_call = table.get("cases_per_call", controllers.DEFAULT_CASES_PER_CALL)
    try:
        law = controllers.PythonLaw(function, params=dict(table.get("params", {})), memory=memory,
                                    diagnostics=table.get("diagnostics", ()), name=table.get("name"),
                                    cases_per_call=None if per_call == "all" else per_call)
    except LandingError as exc:
        raise FileError(f"{_where(source, path)}: {exc}") from None
    expected = table.get("source_sha256")
    if expected is not None and expected != law.source_hash:
        raise FileError(f"{_where(source, path + '.source_sha256')}: the source of {table['function']} has changed "
                        f"since the file was written (sha256 {law.source_hash}, the file records {expected})")
    return law


def _decode_table(table: Any, module: ModuleType, source: str, path: str) -> Table:
    if not isinstance(table, Mapping):
        raise FileError(f"{_where(source, path)} = {table!r} must be a table with a 'kind'")
    kind = table.get("kind")
    if module is controllers and isinstance(kind, str) and ALIASES.get(kind, kind) == "PythonLaw":
        return _decode_python_law(table, source, path)
    cls = _kind(table, module, source, path)
    fields = {f.name for f in dataclasses.fields(cls) if f.init}
    kwargs = {}
    for key, value in table.items():
        if key == "kind":
            continue
        if key not in fields:
            raise FileError(
                f"{_where(source, path + '.' + key)}: unknown key ({cls.__name__} takes {sorted(fields)})"
            )
        kwargs[key] = _decode_value(value, source, f"{path}.{key}")
    try:
        return cls(**kwargs)
    except TypeError as exc:  # a required parameter missing
        raise FileError(f"{_where(source, path)}: {exc}") from None
    except LandingError as exc:
        raise FileError(f"{_where(source, path)}: {exc}") from None


#: The short form of a parameter's dispersion: ``{ normal = [mean, std] }`` and the like.
SHORT_DISPERSIONS: dict[str, type] = {
    "normal": dispersions.Normal, "uniform": dispersions.Uniform,
    "truncated_normal": dispersions.TruncatedNormal, "lognormal": dispersions.LogNormal,
}


def _decode_dispersions(table: Any, source: str) -> dict[str, Any]:
    """The ``[dispersions]`` table: parameter path -> a dispersion's table (``kind = "Normal"``,
    its fields), or its short form ``{ normal = [225.0, 5.0] }`` (the fields in order)."""
    if not isinstance(table, Mapping):
        raise FileError(f"{source}: dispersions must be a table of parameter paths ('plant.isp') to dispersions")
    out = {}
    for name, spec in table.items():
        path = f"dispersions.{_key(name)}"
        short = [k for k in SHORT_DISPERSIONS if isinstance(spec, Mapping) and k in spec]
        if isinstance(spec, Mapping) and "kind" not in spec and len(spec) == 1 and short:
            cls = SHORT_DISPERSIONS[short[0]]
            values = spec[short[0]]
            fields = [f.name for f in dataclasses.fields(cls) if f.init]
            if not isinstance(values, list) or len(values) != len(fields):
                raise FileError(f"{_where(source, path + '.' + short[0])} = {values!r} must list {fields}")
            try:
                out[name] = cls(*values)
            except LandingError as exc:
                raise FileError(f"{_where(source, path)}: {exc}") from None
        elif isinstance(spec, Mapping) and "kind" not in spec:
            raise FileError(f"{_where(source, path)} = {spec!r} must be a dispersion's table (kind = \"Normal\", "
                            f"...) or one of {sorted(SHORT_DISPERSIONS)} with its fields in order")
        else:
            out[name] = _decode_table(spec, dispersions, source, path)
    return out


def _check_settings(d: Mapping[str, Any], source: str) -> None:
    """The scenario's own settings: what a TOML value must be (a string, an integer), then the
    run options' rules (:class:`~landing.simulation.RunOptions`), each refusal naming the file."""
    for key in ("name", "description", "integrator", "stop_at"):
        if key in d and not isinstance(d[key], str):
            raise FileError(f"{source}: {key} = {d[key]!r} must be a string")
    for key, low in RunOptions.MINIMUM.items():
        # a TOML float where a count is meant (substeps = 1.5) is refused as written
        if key in d and (isinstance(d[key], bool) or not isinstance(d[key], int)):
            raise FileError(f"{source}: {key} = {d[key]!r} violates {key} an integer >= {low}")
    try:
        RunOptions(**{key: d[key] for key in Scenario.RUN_OPTIONS if key in d})
    except LandingError as exc:
        raise FileError(f"{source}: {exc}") from None
    if "theta" in d:
        t = d["theta"]
        if (not isinstance(t, list) or len(t) != 2
                or not all(isinstance(v, (int, float)) and not isinstance(v, bool) and 0 < v < 1 for v in t)):
            raise FileError(f"{source}: theta = {t!r} violates theta a pair of numbers in (0, 1)")


def scenario_from_dict(d: Mapping[str, Any], source: str = "<scenario>") -> Scenario:
    """A :class:`~landing.scenarios.Scenario` from the nested dict of a file; ``source`` names
    the file in error messages.

    Parameters
    ----------
    d : Mapping[str, Any]
        The dict (as :func:`read_toml` or :func:`scenario_to_dict` makes it).
    source : str
        The file's name, for the messages (default ``"<scenario>"``).

    Returns
    -------
    Scenario
        The scenario, checked.

    Raises
    ------
    FileError
        If a key, a kind or a value is refused: the message names the file, the key and the
        rule.

    Examples
    --------
    >>> import landing
    >>> from landing.controllers import PDSlidingMode
    >>> from landing.scenarios import Scenario
    >>> s = Scenario("pd", landing.plants.DoubleIntegrator(),
    ...              PDSlidingMode(lambda_=1.0, k=0.5, switch="sat", boundary_layer=0.1),
    ...              x0=[10.0, 0, 5, 0, 0, 0], t_final=10.0, dt=0.05)
    >>> scenario_from_dict(scenario_to_dict(s)).controller
    PDSlidingMode(lambda_=1.0, k=0.5, switch='sat', boundary_layer=0.1)
    >>> scenario_from_dict({**scenario_to_dict(s), "dt": -1.0}, "my.toml")
    Traceback (most recent call last):
        ...
    landing.scenarios.files.FileError: my.toml: dt = -1 violates dt > 0
    """
    allowed = set(_SETTINGS) | set(SECTIONS) | {"dispersions"}
    for key in d:
        if key not in allowed:
            raise FileError(f"{source}: {key}: unknown key (a scenario takes {sorted(allowed)})")
    for key in ("name", "plant", "controller", "x0", "t_final", "dt"):
        if key not in d:
            raise FileError(f"{source}: missing key {key!r}")
    _check_settings(d, source)
    parts: dict[str, Any] = {}
    for key, module in SECTIONS.items():
        if key not in d:
            continue
        if key == "disturbance" and isinstance(d[key], list):
            comps: list[Any] = [_decode_table(t, module, source, f"disturbance[{i}]") for i, t in enumerate(d[key])]
            parts[key] = comps[0] if len(comps) == 1 else disturbances.Sum(comps)
        else:
            parts[key] = _decode_table(d[key], module, source, key)
    plant = parts["plant"]
    try:
        x0 = np.asarray(d["x0"], dtype=float)
    except (TypeError, ValueError, OverflowError):
        raise FileError(f"{source}: x0 = {d['x0']!r} must be a list of numbers") from None
    if x0.shape != (plant.state_dim,) or not np.all(np.isfinite(x0)):
        raise FileError(
            f"{source}: x0 = {d['x0']!r} violates x0 a list of {plant.state_dim} finite numbers "
            f"({', '.join(plant.state_names)})"
        )
    if "dispersions" in d:
        parts["dispersions"] = _decode_dispersions(d["dispersions"], source)
    settings = {k: d[k] for k in _SETTINGS if k in d and k not in ("x0", "theta")}
    if "theta" in d:
        settings["theta"] = tuple(float(v) for v in d["theta"])
    for key in ("t_final", "dt", "settle_tolerance", "chatter_cutoff"):
        if key in settings:  # checked by _check_settings: real numbers within the doubles
            settings[key] = float(settings[key])
    try:
        return Scenario(x0=x0, **settings, **parts)
    except LandingError as exc:  # what only the whole scenario can check (a dispersed parameter's path)
        raise FileError(f"{source}: {exc}") from None
