"""Every configuration class against the core's declaration of its parameters.

The core declares each kind's parameters once (name, shape, unit, rule); the Python classes are
written by hand. These tests hold the two against each other from the Python side: the keys a
class's table carries, the fields that become them, the names a ``Literal`` hint allows, which
parameters may be None, and whether the core reads a parameter per axis (it accepts a per-case
column ``(N, 1)``) or as a scalar (it refuses one).
"""

from __future__ import annotations

import dataclasses
import inspect
import typing

import numpy as np
import pytest

import landing
from _cases import laws
from landing import _core, controllers, dispersions, disturbances, fuzzy, gravity, plants, reference, sensors
from landing._internal.table import Parameter, Table
from landing.errors import LandingError

MODULES = (controllers, plants, gravity, reference, disturbances, dispersions, fuzzy, sensors)

# One instance of each kind, built the way a user would.
EXAMPLES: dict[type, Table] = {type(law): law for law in laws(inertia=1.0, blend_k=0.5).values()}
EXAMPLES.update({type(obj): obj for obj in (
    controllers.OpenLoop(acceleration=[0.1, 0.2, 0.3]),
    controllers.Tabulated(force=[[1.0, 2.0, 3.0], [-1.0, 0.0, 1.0]], hold=2),
    plants.MarsLander(thrust_limit=50e3),
    plants.DoubleIntegrator(acceleration_limit=1.0),
    plants.SmallBody(gravity=gravity.Harmonic2(), omega=1.65e-4, acceleration_limit=0.5),
    plants.TetheredSatellite(fidelity="flexible", nodes=4),
    gravity.PointMass(mu=4.46e5),
    gravity.TwoPointMass(),
    gravity.Harmonic2(),
    reference.Constant(position=[1.0, 2.0, 3.0], velocity=0.5),
    reference.Cubic.from_boundary([0.0, 0.0, 10.0], [1.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0], 5.0),
    disturbances.Constant(value=[0.1, 0.2, 0.3]),
    disturbances.Sinusoid(amplitude=20.0, omega=1.0, phase=0.5),
    disturbances.UniformNoise(bound=0.1),
    disturbances.CommandNoise(fraction=0.01),
    dispersions.Normal(mean=[0.0, 1.0], std=[1.0, 2.0]),
    dispersions.Uniform(low=[0.0, 1.0], high=[1.0, 2.0]),
    dispersions.TruncatedNormal(mean=[0.0, 1.0], std=[1.0, 2.0], low=[-1.0, 0.0], high=[1.0, 3.0]),
    dispersions.LogNormal(mu=[0.0, 1.0], sigma=[0.1, 0.2]),
    fuzzy.variable_rate_system(),
    sensors.Noise(std=[1.0, 1.0, 1.0, 0.1, 0.1, 0.1], bias=0.5, random_walk=0.01),
    sensors.KalmanFilter(process_noise=[0.1, 0.1, 0.2]),
)})

# Fields whose table is laid out otherwise than one key per field (documented on each class).
LAID_OUT = {reference.Cubic: ({"coefficients"}, {"c0", "c1", "c2", "c3"}),
            controllers.Tabulated: ({"force"}, {"rows"})}


def kinds() -> list[type]:
    found = []
    for module in MODULES:
        for name in module.__all__:
            cls = getattr(module, name)
            # the kinds the core declares (a law written in Python is not one)
            if inspect.isclass(cls) and issubclass(cls, Table) and "kind" in vars(cls) and cls._in_core:
                found.append(cls)
    return found


CLASSES = kinds()
IDS = [c.__name__ + "/" + c.family for c in CLASSES]


def test_every_declared_kind_has_a_class_and_an_example() -> None:
    declared = {(family, kind) for family, kinds_ in _core.SCHEMAS.items() for kind in kinds_}
    # the fuzzy family's membership shapes are tables inside a Mamdani system, not classes
    declared -= {("fuzzy", "triangle"), ("fuzzy", "trapezoid")}
    assert {(c.family, c.kind) for c in CLASSES} == declared
    assert set(EXAMPLES) == set(CLASSES)


@pytest.mark.parametrize("cls", CLASSES, ids=IDS)
def test_the_table_carries_exactly_the_declared_keys(cls: type) -> None:
    table = EXAMPLES[cls]._table()
    assert set(table) - {"kind"} == set(cls.parameters)
    for p in cls.parameters.values():
        assert isinstance(p, Parameter) and p.doc, (cls.__name__, p.name)
        if p.numeric:
            assert p.unit, f"{cls.__name__}.{p.name} declares no unit"


@pytest.mark.parametrize("cls", [c for c in CLASSES if dataclasses.is_dataclass(c)], ids=lambda c: c.__name__)
def test_each_field_is_one_declared_parameter(cls: type) -> None:
    fields = {f.name for f in dataclasses.fields(cls) if f.init}
    own, keys = LAID_OUT.get(cls, (set(), set()))
    assert (fields - own) | keys == set(cls.parameters)


@pytest.mark.parametrize("cls", [c for c in CLASSES if dataclasses.is_dataclass(c)], ids=lambda c: c.__name__)
def test_literal_hints_and_defaults_agree_with_the_declaration(cls: type) -> None:
    hints = typing.get_type_hints(cls)
    for f in dataclasses.fields(cls):
        declared = cls.parameters.get(f.name)
        if declared is None:
            continue
        literal = [a for a in _literals(hints.get(f.name))]
        if literal:
            assert set(literal) == set(declared.choices), (cls.__name__, f.name)
        if f.default is None and getattr(EXAMPLES[cls].replace(**{f.name: None}), f.name) is None:
            # left None (not filled in by the class), so the table goes without it
            assert not declared.required, f"{cls.__name__}.{f.name} may be None but the core requires it"


def _literals(hint: object) -> list[object]:
    if typing.get_origin(hint) is typing.Literal:
        return list(typing.get_args(hint))
    return [a for arg in typing.get_args(hint) for a in _literals(arg)]


SHAPE_ERROR = "it takes a scalar or one value per case"


@pytest.mark.parametrize("cls", [c for c in CLASSES if dataclasses.is_dataclass(c) and c not in LAID_OUT],
                         ids=lambda c: c.__name__)
def test_the_core_reads_each_numeric_parameter_in_its_declared_shape(cls: type) -> None:
    obj = EXAMPLES[cls]
    for f in dataclasses.fields(cls):
        declared = cls.parameters.get(f.name)
        value = getattr(obj, f.name)
        if declared is None or not declared.numeric or value is None:
            continue
        column = np.full((2, 1), np.asarray(value, dtype=float).flat[0])  # two cases, one column
        try:
            obj.replace(**{f.name: column})
        except LandingError as exc:
            refused = SHAPE_ERROR in str(exc)
        else:
            refused = False
        assert refused == (declared.shape == "scalar"), (cls.__name__, f.name, declared.shape)


def test_the_random_disturbances_are_the_ones_that_draw() -> None:
    # the core's declaration against the draws themselves: a random component gives different
    # commands for two seeds, a deterministic one the same
    plant = plants.DoubleIntegrator()
    law = controllers.OpenLoop(acceleration=[0.1, 0.2, 0.3])
    for cls in (c for c in CLASSES if c.family == "disturbance"):
        runs = [_final_state(plant, law, EXAMPLES[cls], seed) for seed in (1, 2)]
        assert cls.random == (not np.array_equal(runs[0], runs[1])), cls.__name__


def _final_state(plant: plants.Plant, law: controllers.Controller, disturbance: disturbances.Disturbance,
                 seed: int) -> np.ndarray:
    res = landing.simulate(plant, law, np.zeros(6), t_final=0.5, dt=0.01, disturbance=disturbance, seed=seed)
    return res.final_state
