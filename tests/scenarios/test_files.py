"""Scenario files: every preset ships as a TOML file that reads back to the same scenario (the
same bits when run), bad files are refused with the file, the key, the value and the rule, and
a scenario's parts are changed through replace()."""

from __future__ import annotations

import numpy as np
import pytest

import landing
from _cases import write_file
from landing.scenarios import PRESETS, FileError, Scenario, load_scenario, preset, preset_path


def _short(s: Scenario, steps: int = 40) -> dict:
    return dict(t_final=steps * s.dt, record_every=7)


@pytest.mark.parametrize("name", sorted(PRESETS))
def test_every_preset_ships_as_an_up_to_date_toml_file(name):
    path = preset_path(name)
    assert path.exists(), f"{path} missing: run landing.scenarios.write_preset_files()"
    assert path.read_text(encoding="utf-8") == preset(name).to_toml(), (
        f"{path} is out of date: run landing.scenarios.write_preset_files()")


@pytest.mark.parametrize("name", ["mars_monte_carlo", "mars_super_twisting_standard", "seed000_fuzzy_ftsmc_sign",
                                  "seed002_fuzzy_variable_rate", "tether_fntsmc_flexible"])
def test_a_preset_file_runs_with_the_bits_of_the_python_preset(name):
    py, toml = preset(name), Scenario.load(name)
    assert toml.name == name
    opts = _short(py)
    x0 = py.initial_states(5, seed=3)
    assert np.array_equal(toml.initial_states(5, seed=3), x0)
    a = py.simulate_batch(x0, seed=3, **opts)
    b = toml.simulate_batch(x0, seed=3, **opts)
    for field in ("states", "controls", "final_state"):
        assert np.array_equal(getattr(a, field), getattr(b, field), equal_nan=True), field
    for k in a.metrics:
        assert np.array_equal(a.metrics[k], b.metrics[k], equal_nan=True), k


def _nominal_text() -> str:
    return preset("mars_nominal").to_toml()


@pytest.mark.parametrize("edit, pattern", [
    (("alpha1 = 4.89", "alpah1 = 4.89"), r"mine\.toml: controller\.alpah1: unknown key \(FixedTimeMSS takes"),
    (("alpha1 = 4.89", "alpha1 = -4.89"), r"mine\.toml: controller: FixedTimeMSS: alpha1 = -4\.89 violates alpha1 > 0"),
    (("alpha1 = 4.89", 'alpha1 = "fast"'), r"mine\.toml: controller: .*alpha1.*real number"),
    (("dt = 0.001", "dt = -0.001"), r"mine\.toml: dt = -0\.001 violates dt > 0"),
    (("substeps = 1", "substeps = 1.5"), r"mine\.toml: substeps = 1\.5 violates substeps an integer >= 1"),
    (('kind = "FixedTimeMSS"', 'kind = "FixedTime"'), r"mine\.toml: controller\.kind = 'FixedTime' is not one of"),
    (('integrator = "rk4"', 'integrator = "rk5"'), r"mine\.toml: integrator = 'rk5' is not one of"),
    (("t_final = 60.0", "t_final = 60.0\nhorizon = 3"), r"mine\.toml: horizon: unknown key"),
    (("x0 = [", "x0 = [1.0, "), r"mine\.toml: x0 = .* violates x0 a list of 7 finite numbers"),
    (("dt = 0.001", "dt = 0.001 ="), r"mine\.toml: not valid TOML"),
    # the probe's files (issue 24): nesting beyond the parser's recursion, integers beyond a
    # double or beyond Python's printing, a horizon beyond the step cap (not a memory refusal)
    (("t_final = 60.0", "t_final = 60.0\nx = " + "[" * 100_000 + "]" * 100_000),
     r"mine\.toml: not a scenario file: its arrays or tables are nested too deeply"),
    (("t_final = 60.0", "t_final = 60.0\nx = " + "{a = " * 20_000 + "1" + "}" * 20_000),
     r"mine\.toml: not a scenario file: its arrays or tables are nested too deeply"),
    (("alpha1 = 4.89", "alpha1 = " + "9" * 5000), r"mine\.toml: not valid TOML \(Exceeds the limit"),
    (("t_final = 60.0", f"t_final = {10**400}"), r"mine\.toml: t_final = about 10\^400 violates finite values"),
    (("alpha1 = 4.89", f"alpha1 = {10**400}"), r"mine\.toml: controller: .*alpha1 = about 10\^400 violates finite"),
    (("x0 = [", f"x0 = [{10**400}, "), r"mine\.toml: x0 = .* must be a list of numbers"),
    (("t_final = 60.0", f"t_final = {10**300}"), r"mine\.toml: t_final = 1e\+300 violates t_final / dt <= 2\^40"),
])
def test_a_bad_file_is_refused_naming_the_file_the_key_the_value_and_the_rule(tmp_path, edit, pattern):
    old, new = edit
    text = _nominal_text()
    assert old in text
    path = write_file(tmp_path, text.replace(old, new, 1))
    with pytest.raises(FileError, match=pattern):
        load_scenario(path)
    assert issubclass(FileError, landing.ParameterError)


def test_replace_changes_one_gain_in_one_call():
    s = preset("mars_nominal")
    a = s.replace(controller={"alpha1": 6.0}, plant={"thrust_limit": 4e4})
    assert float(a.controller.alpha1) == 6.0 and float(a.controller.beta1) == float(s.controller.beta1)
    assert float(a.plant.thrust_limit) == 4e4
    b = s.replace(controller=s.controller.replace(alpha1=6.0), plant=s.plant.replace(thrust_limit=4e4))
    assert a.to_toml() == b.to_toml()
    with pytest.raises(landing.ParameterTypeError, match="unknown field 'controler'"):
        s.replace(controler={"alpha1": 6.0})
    with pytest.raises(landing.ParameterError, match="alpha1"):
        s.replace(controller={"alpha1": -1.0})


def test_every_preset_pickles_and_compiles_again_on_arrival():
    # how a scenario a file cannot describe travels to Dask workers (cloudpickle reads as pickle)
    import pickle

    for name in PRESETS:
        s = preset(name)
        back = pickle.loads(pickle.dumps(s))
        assert back.to_toml() == s.to_toml(), name
        a = s.replace(t_final=s.dt * 3).simulate()
        b = back.replace(t_final=s.dt * 3).simulate()
        np.testing.assert_array_equal(b.states, a.states, err_msg=name)
