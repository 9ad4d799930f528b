"""RunOptions: the one set of run settings simulate_batch, Scenario, scenario files and the
tuner share, checked once when made."""

import dataclasses

import numpy as np
import pytest

import landing
from landing import RunOptions
from landing.errors import ParameterError, ParameterTypeError
from landing.scenarios import FileError, load_scenario, preset


@pytest.mark.parametrize("kw, error, message", [
    (dict(t_final=0.0), ParameterError, "t_final = 0 violates t_final > 0"),
    (dict(dt=np.nan), ParameterError, "dt = nan violates finite values"),
    (dict(integrator="rk5"), ParameterError, r"integrator = 'rk5' is not one of \('rk4', 'euler'\)"),
    (dict(substeps=np.int64(0)), ParameterError, "substeps = 0 violates substeps >= 1"),
    (dict(record_every=1.0), ParameterTypeError, "record_every must be an integer"),
    (dict(settle_tolerance=-1.0), ParameterError, "settle_tolerance = -1 violates settle_tolerance >= 0"),
    (dict(chatter_cutoff=0.0), ParameterError, "chatter_cutoff = 0 violates chatter_cutoff > 0"),
    (dict(threads=0), ParameterError, "threads = 0 violates threads >= 1"),
    (dict(kernel=3), ParameterTypeError, "kernel must be a string or None, got 3"),
    (dict(kernel="sse9"), ParameterError, "kernel = 'sse9' is not one of"),
])
def test_each_option_is_checked_when_made(kw, error, message):
    with pytest.raises(error, match=message):
        RunOptions(**{"t_final": 1.0, "dt": 0.1, **kw})
    # and the same through simulate_batch, and with the scenario's name through a scenario
    plant, law = landing.plants.DoubleIntegrator(), landing.controllers.PDSlidingMode(lambda_=1.0, k=1.0)
    with pytest.raises(error, match=message):
        landing.simulate_batch(plant, law, np.zeros((1, 6)), **{"t_final": 1.0, "dt": 0.1, **kw})
    if "threads" not in kw and "kernel" not in kw:
        with pytest.raises(error, match="Scenario 'mars_nominal': " + message):
            preset("mars_nominal").replace(**kw)


def test_the_options_are_frozen_and_hold_the_checked_values():
    o = RunOptions(t_final=np.float64(2), dt=1, substeps=np.int64(3))
    assert type(o.t_final) is float and type(o.dt) is float and type(o.substeps) is int
    assert o.settle_relative and not o.replace(settle_tolerance=0.0).settle_relative
    with pytest.raises(dataclasses.FrozenInstanceError):
        o.dt = 0.5  # type: ignore[misc]
    assert RunOptions(**o.keywords()) == o


def test_a_scenario_holds_its_options():
    s = preset("mars_nominal")
    assert s.options == RunOptions(t_final=60.0, dt=1e-3, record_every=10, settle_tolerance=1.0)
    assert s.replace(dt=2e-3).options.dt == 2e-3 and s.options.dt == 1e-3
    with pytest.raises(dataclasses.FrozenInstanceError):
        s.dt = 0.5  # type: ignore[misc]
    with pytest.raises(ParameterTypeError, match="unknown field 'options'"):
        s.replace(options=s.options)
    assert "options" not in str(s)


def test_a_file_is_checked_by_the_same_rules(tmp_path):
    path = tmp_path / "mine.toml"
    text = preset("mars_nominal").to_toml()
    path.write_text(text.replace("settle_tolerance = 1.0", "settle_tolerance = -2.0"))
    with pytest.raises(FileError, match=r"mine\.toml: settle_tolerance = -2 violates settle_tolerance >= 0"):
        load_scenario(path)
    path.write_text(text.replace("dt = 0.001", 'dt = "fast"'))
    with pytest.raises(FileError, match=r"mine\.toml: dt must be a real number, got 'fast'"):
        load_scenario(path)


@pytest.mark.tune
def test_the_tuner_checks_its_counts_and_the_threads_before_it_runs():
    pytest.importorskip("cma")
    s = preset("mars_nominal").replace(t_final=0.01)
    gains = {"alpha1": (1.0, 6.0)}
    with pytest.raises(ParameterError, match="budget = 0 violates budget >= 1"):
        landing.tune(s, gains, "mean(iae)", budget=0)
    with pytest.raises(ParameterTypeError, match="cases must be an integer, got 1.5"):
        landing.tune(s, gains, "mean(iae)", cases=1.5)
    with pytest.raises(ParameterError, match=r"seed = 4294967296 violates seed <= 4294967295"):
        landing.tune(s, gains, "mean(iae)", seed=2**32)
    with pytest.raises(ParameterError, match="threads = 0 violates threads >= 1"):
        landing.tune(s, gains, "mean(iae)", threads=0)
