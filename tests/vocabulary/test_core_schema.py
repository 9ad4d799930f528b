"""The core's declarations as the extension module exposes them: the parameter schemas, the
metric columns and the handles' ``parameter`` (only ``landing._core`` and numpy)."""

import numpy as np
import pytest

from landing import _core

SHAPES = {"scalar", "per_axis", "per_component", "choice", "flag", "count", "nested", "list", "fuzzy_system"}
KEYS = {"name", "shape", "unit", "rule", "required", "doc"}


def _check_param(where, p):
    assert KEYS <= set(p), where
    assert p["shape"] in SHAPES, where
    assert isinstance(p["name"], str) and p["name"], where
    assert isinstance(p["required"], bool), where
    if p["shape"] in ("choice", "count"):
        assert p["choices"], where
    if p["shape"] in ("nested", "list"):
        assert "family" in p, where
        if p["family"] is None:
            for q in p["layout"]:
                _check_param(f"{where}.{p['name']}", q)
        else:
            assert p["family"] in _core.SCHEMAS, where


def test_every_registered_kind_has_a_schema():
    s = _core.SCHEMAS
    assert list(s) == ["plant", "law", "gravity", "disturbance", "reference", "dispersion", "sensor", "filter",
                       "fuzzy"]
    assert list(s["plant"]) == _core.PLANT_KINDS
    assert list(s["law"]) == _core.CONTROLLER_KINDS
    assert list(s["gravity"]) == _core.GRAVITY_KINDS
    assert set(s["fuzzy"]) == {"mamdani", "triangle", "trapezoid"}
    for family, kinds in s.items():
        for kind, schema in kinds.items():
            names = [p["name"] for p in schema["parameters"]]
            assert len(names) == len(set(names)), (family, kind)
            for p in schema["parameters"]:
                _check_param(f"{family}:{kind}", p)
            assert ("random" in schema) == (family == "disturbance"), (family, kind)
    random = {k: v["random"] for k, v in s["disturbance"].items()}
    assert random == {"constant": False, "sinusoid": False, "uniform_noise": True, "command_noise": True}


def test_the_schemas_name_each_kinds_keys():
    def names(family, kind):
        return [p["name"] for p in _core.SCHEMAS[family][kind]["parameters"]]

    assert names("law", "pd_sliding_mode") == ["lambda_", "k", "switch", "boundary_layer"]
    assert names("reference", "cubic") == ["t_end", "c0", "c1", "c2", "c3", "after"]
    assert names("plant", "small_body") == [
        "gravity", "omega", "acceleration_limit", "acceleration_magnitude_limit", "control_delay",
        "engine_time_constant", "sensor", "filter",
    ]
    assert names("sensor", "noise") == ["std", "bias", "random_walk"]
    assert names("filter", "kalman") == ["process_noise"]
    tether = names("plant", "tethered_satellite")
    assert tether[0] == "fidelity" and {"nodes", "tether_density", "axial_damping"} <= set(tether)
    nodes = next(p for p in _core.SCHEMAS["plant"]["tethered_satellite"]["parameters"] if p["name"] == "nodes")
    assert nodes["shape"] == "count" and nodes["choices"] == [2, 4, 8, 16] and nodes["rule"] == "nodes in {2, 4, 8, 16}"
    gravity = _core.SCHEMAS["plant"]["small_body"]["parameters"][0]
    assert gravity["shape"] == "nested" and gravity["family"] == "gravity"
    q1 = next(p for p in _core.SCHEMAS["law"]["fixed_time_mss"]["parameters"] if p["name"] == "q1")
    assert (q1["shape"], q1["unit"], q1["rule"], q1["required"]) == ("per_axis", "1", "0 < q1 < 1", True)
    limit = next(p for p in _core.SCHEMAS["plant"]["mars_lander"]["parameters"] if p["name"] == "thrust_limit")
    assert limit["required"] is False and limit["unit"] == "N"
    variant = next(p for p in _core.SCHEMAS["law"]["super_twisting"]["parameters"] if p["name"] == "variant")
    assert variant["choices"] == ["printed", "standard"]


def _batch():
    plant = _core.Plant("DoubleIntegrator", {"kind": "double_integrator", "acceleration_limit": None})
    law = _core.Law("OpenLoop", {"kind": "open_loop", "acceleration": np.array([1.0, -2.0, 0.5])})
    x0 = np.array([[0.0, 1.0, 2.0, 0.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0, 0.0, 0.0]])
    return _core.simulate_batch(
        plant, law, x0, t_final=1.0, dt=0.1, integrator="rk4", substeps=1, reference=None,
        disturbance=None, record_every=1, seed=0, first_case=0, settle_tolerance=0.02,
        settle_relative=True, chatter_cutoff=None, threads=1,
    )


def test_the_metric_columns_are_the_declared_ones_in_order():
    out = _batch()
    m = out["metrics"]
    assert [c["name"] for c in _core.METRICS] == list(m)
    for c in _core.METRICS:
        assert set(c) == {"name", "unit", "per_axis", "doc"}
        v = m[c["name"]]
        assert v.shape == ((2, 3) if c["per_axis"] else (2,)), c["name"]
    assert m["diverged"].dtype == np.bool_ and m["diverged_reason"].dtype == np.uint8
    assert m["final_error"].dtype == np.float64
    units = {c["name"]: c["unit"] for c in _core.METRICS}
    assert units["settle_time"] == "s" and units["fuel_used"] == "kg"
    # the open-loop double integrator: q(1) = q0 + a / 2
    np.testing.assert_allclose(m["final_error"][0], [0.5, 0.0, 2.25], atol=1e-12)


def test_a_handle_gives_its_parameters_as_the_core_reads_them():
    law = _core.Law("PDSlidingMode", {
        "kind": "pd_sliding_mode", "lambda_": np.array([1.0, 2.0, 3.0]), "k": np.array([[1.0], [2.0]]),
        "switch": "sat", "boundary_layer": np.array(0.5),
    })
    np.testing.assert_array_equal(law.parameter("lambda_", 3), [[1.0, 2.0, 3.0]])
    np.testing.assert_array_equal(law.parameter("k", 3), [[1.0, 1.0, 1.0], [2.0, 2.0, 2.0]])
    np.testing.assert_array_equal(law.parameter("k", 2), [[1.0, 1.0], [2.0, 2.0]])
    np.testing.assert_array_equal(law.parameter("boundary_layer", 3), [0.5])
    with pytest.raises(ValueError, match='unknown parameter "lambda"'):
        law.parameter("lambda", 3)
    with pytest.raises(ValueError, match='unknown parameter "switch"'):
        law.parameter("switch", 3)
    plant = _core.Plant("MarsLander", {
        "kind": "mars_lander", "isp": np.array([200.0, 225.0]), "area": np.array([6.0, 7.5, 8.7]),
        "gravity": np.array(3.7114), "drag": True, "thrust_limit": None, "drag_coefficient": np.array(0.699),
        "density_decay": np.array(0.0009), "g0": np.array(9.807),
    })
    np.testing.assert_array_equal(plant.parameter("isp", 3), [200.0, 225.0])
    np.testing.assert_array_equal(plant.parameter("area", 3), [[6.0, 7.5, 8.7]])
    with pytest.raises(ValueError, match="thrust_limit is not given"):
        plant.parameter("thrust_limit", 3)
    gravity = _core.Gravity("PointMass", {"kind": "point_mass", "mu": np.array(4.46e5)})
    np.testing.assert_array_equal(gravity.parameter("mu", 3), [4.46e5])
    reference = _core.Reference("Constant", {"kind": "constant", "position": np.array([1.0, 2.0]),
                                             "velocity": np.array(0.0)})
    np.testing.assert_array_equal(reference.parameter("position", 2), [[1.0, 2.0]])
    disturbance = _core.Disturbance("Sinusoid", {"components": [
        {"kind": "sinusoid", "amplitude": np.array(20.0), "omega": np.array([1.0, 2.0, 3.0]), "phase": np.array(0.0)},
        {"kind": "uniform_noise", "bound": np.array([0.1, 0.2])},
    ]})
    np.testing.assert_array_equal(disturbance.parameter("omega", 3), [[1.0, 2.0, 3.0]])
    # a 1-D array whose length is not the axis count is one value per case
    np.testing.assert_array_equal(disturbance.parameter("bound", 3), [[0.1, 0.1, 0.1], [0.2, 0.2, 0.2]])
    np.testing.assert_array_equal(disturbance.parameter("bound", 2), [[0.1, 0.2]])
    with pytest.raises(ValueError, match="unknown parameter"):
        disturbance.parameter("value", 3)


def test_the_dispersion_handle_keeps_its_former_name():
    assert _core.DispersionHandle is _core.Dispersion
    d = _core.Dispersion({"kind": "normal", "mean": np.array([1.0, 2.0]), "std": np.array(0.0)})
    np.testing.assert_array_equal(d.sample(0, 0, 2), [[1.0, 2.0], [1.0, 2.0]])
    with pytest.raises(ValueError, match=r"std\[1\] = -1 violates std >= 0"):
        _core.Dispersion({"kind": "normal", "mean": np.array([1.0, 2.0]), "std": np.array([1.0, -1.0])})


def test_a_fuzzy_system_reads_its_table_through_the_core():
    table = _core.variable_rate_system_table(101)
    system = _core.FuzzySystem(table)
    assert system.evaluate(np.zeros((1, 2)))[0] == pytest.approx(0.0, abs=1e-12)
    bad = dict(table, inputs=[dict(table["inputs"][0], sets=[("triangle", [1.0, 0.0, 2.0])]), table["inputs"][1]])
    unordered = r"fuzzy system: input 0: sets\[0\] triangle = 0 violates corners in non-decreasing order"
    with pytest.raises(ValueError, match=unordered):
        _core.FuzzySystem(bad)
