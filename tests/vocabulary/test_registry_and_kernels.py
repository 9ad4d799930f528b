"""The registries and the instruction-set levels.

Each plant kind, law kind and gravity field is listed once in the core; its Python class is the
only other place it is named (CONTRIBUTING.md). These tests check the two lists agree and that
every kind compiles from Python and refuses what it does not know. Then every law on every plant
runs at every kernel level this CPU has, and a case's bits must not depend on the level, on the
lane it occupies, or on the batch around it.
"""

from __future__ import annotations

import inspect
from types import ModuleType

import numpy as np
import pytest

import landing
from _cases import LEVELS, assert_same_result_bits, laws, tether_laws
from landing import _core
from landing import controllers as C
from landing import gravity as G
from landing import plants as P
from landing._internal.table import Table
from landing.errors import LandingError


def classes(module: ModuleType) -> dict[str, type]:
    """The module's public configuration classes of the core's kinds, by kind (a law written in
    Python is not one)."""
    found: dict[str, type] = {}
    for name, cls in vars(module).items():
        if (inspect.isclass(cls) and issubclass(cls, Table) and not name.startswith("_")
                and cls.__module__ == module.__name__ and "kind" in vars(cls) and cls._in_core):
            assert cls.kind not in found, f"{cls.kind} has two classes: {found[cls.kind]} and {cls}"
            found[cls.kind] = cls
    return found


# One instance of each kind, built the way a user would.
EXAMPLES = {
    **laws(inertia=1.0, blend_k=0.5),
    "open_loop": C.OpenLoop(),
    "tabulated": C.Tabulated(force=[[1.0, 2.0, 3.0], [-1.0, 0.0, 1.0]], hold=2),
    "mars_lander": P.MarsLander(),
    "double_integrator": P.DoubleIntegrator(),
    "small_body": P.SmallBody(gravity=G.Harmonic2(), omega=1.65e-4),
    "tethered_satellite": P.TetheredSatellite(),
    "point_mass": G.PointMass(mu=4.46e5),
    "two_point_mass": G.TwoPointMass(),
    "harmonic2": G.Harmonic2(),
}


@pytest.mark.parametrize("module, kinds", [(C, _core.CONTROLLER_KINDS), (P, _core.PLANT_KINDS),
                                           (G, _core.GRAVITY_KINDS)], ids=["laws", "plants", "gravity"])
def test_every_registered_kind_has_one_python_class(module: ModuleType, kinds: list[str]) -> None:
    assert sorted(classes(module)) == sorted(kinds)


@pytest.mark.parametrize("kind", _core.CONTROLLER_KINDS + _core.PLANT_KINDS + _core.GRAVITY_KINDS)
def test_every_kind_round_trips_from_python(kind: str) -> None:
    obj = EXAMPLES[kind]
    assert obj.kind == kind
    assert obj._core.kind == kind  # compiled by the core's registry entry of that name
    # The core reads back exactly the table Python sent: a copy compiles to the same kind, and
    # a table with one parameter more, or one less, is refused naming it.
    table = obj._table()
    handle = type(obj._core)
    assert handle(type(obj).__name__, table).kind == kind
    with pytest.raises(LandingError, match='unknown parameter "not_a_parameter"'):
        handle("probe", {**table, "not_a_parameter": np.array(1.0)})
    required = [k for k, v in table.items() if k != "kind" and isinstance(v, np.ndarray)]
    if required:
        name = required[0]
        reduced = {k: v for k, v in table.items() if k != name}
        try:
            handle("probe", reduced)  # a parameter with a default may be left out ...
        except LandingError as exc:  # ... one without must be named
            assert name in str(exc)


def test_an_unknown_kind_is_refused_with_the_known_ones() -> None:
    with pytest.raises(LandingError, match="unknown kind") as exc:
        _core.Law("probe", {"kind": "no_such_law"})
    for kind in _core.CONTROLLER_KINDS:
        assert kind in str(exc.value)


# --- every law on every plant, at every level --------------------------------------------------

RNG = np.random.default_rng(5)


def three_axis_cases(plant_name: str, n: int) -> tuple[P.Plant, np.ndarray, landing.reference.Constant]:
    target = {"small_body": np.array([2000.0, 500.0, 8000.0])}.get(plant_name, np.zeros(3))
    plant = EXAMPLES[plant_name]
    extra = np.full((n, 1), 1905.0) if plant_name == "mars_lander" else np.zeros((n, 0))
    x0 = np.hstack([target + RNG.uniform(-20.0, 20.0, (n, 3)), RNG.uniform(-1.0, 1.0, (n, 3)), extra])
    return plant, x0, landing.reference.Constant(position=target)


def run_levels(plant, law, x0, **kw) -> dict[str, landing.SimulationResult]:
    return {level: landing.simulate_batch(plant, law, x0, kernel=level, **kw) for level in LEVELS}


def test_the_levels_are_the_cpus() -> None:
    assert LEVELS[0] == "baseline" and set(LEVELS) <= set(_core.KERNEL_LEVELS)


@pytest.mark.parametrize("plant_name", ["double_integrator", "small_body", "mars_lander"])
def test_every_law_gives_the_same_bits_at_every_level(plant_name: str) -> None:
    # 37 cases: several blocks at every level, the last one partly padding.
    plant, x0, ref = three_axis_cases(plant_name, 37)
    noise = [landing.disturbances.Sinusoid(amplitude=0.01, omega=1.0),
             landing.disturbances.UniformNoise(bound=0.01)]
    for name, law in laws(1905.0 if plant_name == "mars_lander" else 1.0,
                          5.0 if plant_name == "mars_lander" else 0.5).items():
        runs = run_levels(plant, law, x0, t_final=2.0, dt=0.01, record_every=7, reference=ref,
                          disturbance=noise, seed=11, settle_tolerance=1.0)
        for level, res in runs.items():
            assert res.kernel == level
            assert_same_result_bits(runs["baseline"], res, f"{plant_name} / {name} at {level}")


@pytest.mark.parametrize("fidelity", ["simplified", "flexible"])
def test_every_law_gives_the_same_bits_at_every_level_on_the_tether(fidelity: str) -> None:
    plant = P.TetheredSatellite(fidelity=fidelity)
    angles = np.radians(RNG.uniform(-1.0, 1.0, (11, 2)))
    x0 = np.stack([plant.initial_state(a, b) for a, b in angles])
    for name, law in tether_laws(P.TetheredSatellite(fidelity="simplified").inertia).items():
        runs = run_levels(plant, law, x0, t_final=1.0, dt=0.01, substeps=plant.substeps_for(0.01),
                          record_every=10, disturbance=landing.disturbances.UniformNoise(bound=1e-6), seed=3)
        for level, res in runs.items():
            assert not res.metrics["diverged"].any(), f"tether ({fidelity}) / {name} diverged"
            assert_same_result_bits(runs["baseline"], res, f"tether ({fidelity}) / {name} at {level}")


def test_a_case_does_not_depend_on_its_lane_or_its_batch() -> None:
    plant, x0, ref = three_axis_cases("mars_lander", 41)
    law = EXAMPLES["fixed_time_mss"]
    kw = dict(t_final=2.0, dt=0.01, record_every=20, reference=ref, seed=4,
              disturbance=landing.disturbances.UniformNoise(bound=0.1))
    for level in LEVELS:
        whole = landing.simulate_batch(plant, law, x0, kernel=level, **kw)
        for i in (0, 5, 17, 40):  # alone, as its own case index: the lane is 0, not i % lanes
            alone = landing.simulate_batch(plant, law, x0[i:i + 1], first_case=i, kernel=level, **kw)
            assert_same_result_bits(whole[i:i + 1], alone, f"case {i} alone at {level}")
        shifted = landing.simulate_batch(plant, law, x0[3:], first_case=3, kernel=level, threads=1, **kw)
        assert_same_result_bits(whole[3:], shifted, f"cases 3.. shifted by three lanes at {level}")


def test_an_unsupported_or_unknown_level_is_refused() -> None:
    plant, x0, _ = three_axis_cases("double_integrator", 2)
    with pytest.raises(LandingError, match="not one of"):
        landing.simulate_batch(plant, EXAMPLES["ntsmc"], x0, t_final=0.1, dt=0.01, kernel="avx1024")
