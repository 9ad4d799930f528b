"""A law written in Python everywhere a built-in law goes: campaigns in chunks with a progress
bar, stores and resume (refused when the function changed), scenario files and the command
line, a Dask cluster (the function by cloudpickle), the tuner over its parameters."""

from __future__ import annotations

import importlib
import sys
import textwrap

import numpy as np
import pytest

import landing
from _cases import assert_same_campaign, small_campaign, write_file
from _user_laws import integral_pd, pd
from landing import cli
from landing import controllers as C
from landing.errors import ParameterError
from landing.scenarios.files import FileError, scenario_from_dict, tomllib


def mars_pd(**kw) -> landing.scenarios.Scenario:
    # gains on the lander's 5 s horizon: a slow PD, so that nothing saturates
    law = C.PythonLaw(pd, params={"kp": 0.02, "kd": 0.3}, **kw)
    return small_campaign().replace(controller=law)


def mars_integral() -> landing.scenarios.Scenario:
    law = C.PythonLaw(integral_pd, params={"kp": 0.02, "kd": 0.3, "ki": 0.001, "dt": 2e-3},
                      memory={"z": np.zeros(3)}, diagnostics=("z",))
    return small_campaign().replace(controller=law)


@pytest.fixture(scope="module")
def whole():
    return landing.monte_carlo(mars_integral(), 20, seed=3, chunk_size=20, progress=False)


def test_a_campaign_in_chunks_with_a_progress_bar_equals_the_whole_batch(whole):
    chunked = landing.monte_carlo(mars_integral(), 20, seed=3, chunk_size=6, progress=True)
    assert_same_campaign(chunked, whole)
    assert np.abs(whole.diagnostics["z"]).max() > 0


def test_the_law_behaves_as_written():
    # the PD law on the double integrator from rest at e0: e'' = -kp e - kd e', a closed form
    kp, kd = 4.0, 5.0  # roots -1 and -4: e = e0 (4 e^-t - e^-4t) / 3
    law = C.PythonLaw(pd, params={"kp": kp, "kd": kd})
    res = landing.simulate(landing.plants.DoubleIntegrator(), law, [1.0, 0, 0, 0, 0, 0], t_final=2.0, dt=1e-3)
    t = res.t
    exact = (4 * np.exp(-t) - np.exp(-4 * t)) / 3
    # the zero-order hold over 1 ms costs O(dt)
    np.testing.assert_allclose(res.states[:, 0], exact, atol=3e-3)


@pytest.mark.io
def test_a_store_resumes_and_refuses_a_changed_function(tmp_path, monkeypatch, whole):
    path = tmp_path / "c"
    landing.monte_carlo(mars_integral(), 20, seed=3, chunk_size=5, store=path, progress=False)
    assert_same_campaign(landing.load(path, scenario=mars_integral()), whole)
    prov = (path / "provenance.json").read_text()
    assert "_user_laws:integral_pd" in prov and mars_integral().controller.source_hash in prov

    # the same law, edited: its source (and hash) differ, the store is refused
    module = tmp_path / "mylaw_edit.py"
    module.write_text(textwrap.dedent('''
        def integral_pd(t, e, de, ref, drift, inertia, params, memory):
            z = memory["z"]
            u = ref.acceleration - drift - params["kp"] * e - params["kd"] * de - params["ki"] * z
            return u, {"z": z + params["dt"] * e}, {"z": z}
    '''))
    monkeypatch.syspath_prepend(str(tmp_path))
    edited = importlib.import_module("mylaw_edit")
    other = mars_integral().replace(controller=mars_integral().controller.replace(function=edited.integral_pd))
    with pytest.raises(ParameterError, match="another campaign[\\s\\S]*source_sha256"):
        landing.monte_carlo(other, 20, seed=3, chunk_size=5, store=path, progress=False)


def test_scenario_files_name_the_function(tmp_path):
    s = mars_integral()
    text = s.to_toml()
    assert 'function = "_user_laws:integral_pd"' in text and "source_sha256" in text
    back = scenario_from_dict(tomllib.loads(text))
    assert back.to_toml() == text
    # kind = "python", a memory initialiser by name, scalar diagnostics
    table = tomllib.loads(text)
    table["controller"] = {"kind": "python", "function": "_user_laws:integral_pd",
                           "params": {"kp": 0.02, "kd": 0.3, "ki": 0.001, "dt": 2e-3},
                           "memory": "_user_laws:start_at_error", "diagnostics": {"z": "axes"}}
    law = scenario_from_dict(table).controller
    assert isinstance(law, C.PythonLaw) and law.memory is not None and law.function is integral_pd
    assert law.cases_per_call == C.DEFAULT_CASES_PER_CALL
    # cases_per_call: written when not the default, "all" for the whole batch at every call
    for per_call, written in ((64, "cases_per_call = 64"), (None, 'cases_per_call = "all"')):
        changed = s.replace(controller=s.controller.replace(cases_per_call=per_call))
        assert written in changed.to_toml()
        assert scenario_from_dict(tomllib.loads(changed.to_toml())).controller.cases_per_call == per_call
    table["controller"]["source_sha256"] = "0" * 64
    with pytest.raises(FileError, match="has changed since the file was written"):
        scenario_from_dict(table)
    table["controller"] = {"kind": "python", "function": "_user_laws:no_such_law"}
    with pytest.raises(FileError, match="no_such_law"):
        scenario_from_dict(table)
    table["controller"] = {"kind": "python", "function": "not a spec"}
    with pytest.raises(FileError, match="package.module:name"):
        scenario_from_dict(table)


def test_the_command_line_runs_a_file_whose_law_sits_beside_it(tmp_path, capsys):
    (tmp_path / "beside_law.py").write_text(textwrap.dedent('''
        def pd(t, e, de, ref, drift, inertia, params, memory):
            return ref.acceleration - drift - params["kp"] * e - params["kd"] * de
    '''))
    text = mars_pd().to_toml()
    table = tomllib.loads(text)
    table["controller"] = {"kind": "python", "function": "beside_law:pd", "params": {"kp": 0.02, "kd": 0.3}}
    from landing.scenarios.files import dumps

    path = write_file(tmp_path, dumps(table))
    try:
        assert cli.main(["run", str(path), "--out", ""]) == 0
        assert "final_position_error" in capsys.readouterr().out
        assert cli.main(["mc", str(path), "--cases", "4", "--out", "", "--no-progress"]) == 0
        assert "4 cases" in capsys.readouterr().out
    finally:
        sys.modules.pop("beside_law", None)


@pytest.mark.tune
def test_the_tuner_searches_the_parameters_of_a_python_law():
    pytest.importorskip("cma")
    s = landing.scenarios.Scenario(
        name="pd", plant=landing.plants.DoubleIntegrator(), controller=C.PythonLaw(pd, params={"kp": 1.0, "kd": 1.0}),
        x0=[1.0, 0.0, 0.0, 0.0, 0.0, 0.0], t_final=4.0, dt=0.01)
    result = landing.tune(s, {"kd": (0.5, 8.0)}, "mean(iae)", budget=40, seed=1, progress=False)
    # IAE of e'' = -e - kd e' is smallest near critical damping (kd = 2) and grows either side
    best = result.best_gains["kd"]
    assert 1.2 < best < 3.5
    law = result.scenario().controller
    assert isinstance(law, C.PythonLaw) and float(law.params["kd"]) == best


@pytest.mark.dask
def test_a_dask_cluster_runs_a_law_defined_in_a_script():
    distributed = pytest.importorskip("distributed")

    # a closure: not importable by name, it travels by cloudpickle
    gain = 0.02

    def local_pd(t, e, de, ref, drift, inertia, params, memory):
        return ref.acceleration - drift - gain * e - 0.3 * de

    s = small_campaign().replace(controller=C.PythonLaw(local_pd))
    expected = landing.monte_carlo(s, 12, seed=2, progress=False)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1",
                                  dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        mc = landing.monte_carlo(s, 12, seed=2, client=client, chunk_size=5, threads=1)
    assert_same_campaign(mc, expected)


def test_the_guide_pages_scenario_file_reads(tmp_path, monkeypatch):
    import re

    from _cases import ROOT

    page = (ROOT / "docs" / "own-law.md").read_text()
    block = re.search(r"```toml\n(.*?)```", page, re.S).group(1)
    block = "\n".join(line[2:] if line.startswith("  ") else line for line in block.splitlines())
    # the page's law is the example script's
    (tmp_path / "mylaws.py").write_text((ROOT / "examples" / "own_law.py").read_text())
    monkeypatch.chdir(tmp_path)
    table = tomllib.loads(mars_pd().to_toml())
    table["controller"] = tomllib.loads(block)["controller"]
    try:
        s = scenario_from_dict(table)
        law = s.controller
        assert isinstance(law, C.PythonLaw) and law.name == "mylaws:integral_smc"
        assert float(law.params["lam"]) == 0.15 and law.diagnostic_kinds == {"s": "axes"}
        res = s.replace(t_final=0.1).simulate()
        assert res.diagnostics["s"].shape == (len(res.t), 3)
    finally:
        sys.modules.pop("mylaws", None)
