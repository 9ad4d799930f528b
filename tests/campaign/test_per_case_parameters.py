"""Parameters given per case (one row for each case of the campaign) in campaigns cut into
chunks: each chunk runs its own cases' rows, for built-in and Python laws and plants and the
disturbances, so that a chunked, stored, resumed or clustered campaign is the whole batch's
bit for bit, and case i runs the value of row i."""

from __future__ import annotations

import numpy as np
import pytest

import landing
from _cases import assert_same_campaign, crash_after_chunks, small_campaign
from _user_laws import pd
from landing import controllers as C
from landing import disturbances as W
from landing import plants as P
from landing.errors import ParameterError

N = 12
ROWS = np.linspace(0.0, 1.0, N)


def damped(t, x, u, params):
    """A double integrator with a drag per case: q'' = u - c q'."""
    return np.concatenate([x[:, 3:], u - params["c"][:, None] * x[:, 3:]], axis=1)


def damped_plant(c) -> P.PythonPlant:
    return P.PythonPlant(damped, 6, positions=(0, 1, 2), velocities=(3, 4, 5), params={"c": c})


def on_damped(plant: P.Plant, law: C.Controller) -> landing.scenarios.Scenario:
    x0 = np.array([1.0, -1.0, 2.0, 0.0, 0.5, 0.0])
    return landing.scenarios.Scenario(
        name="damped", plant=plant, controller=law, x0=x0, t_final=1.0, dt=0.01, record_every=10,
        dispersion=landing.dispersions.Normal(mean=x0, std=np.full(6, 0.1)))


# each: the scenario with one parameter per case, and the same scenario with case i's value shared
mars = small_campaign()
CASES = {
    "PythonLaw gain per case": lambda v: mars.replace(
        controller=C.PythonLaw(pd, params={"kp": 0.02 + 0.01 * v, "kd": 0.3})),
    "PythonLaw gain per case and axis": lambda v: mars.replace(
        controller=C.PythonLaw(pd, params={"kp": 0.02 + 0.01 * np.outer(v, [1.0, 2.0, 3.0]), "kd": 0.3})),
    "built-in law gain per case": lambda v: mars.replace(controller=mars.controller.replace(beta1=1.0 + 0.5 * v)),
    "built-in law gain per case and axis": lambda v: mars.replace(
        controller=mars.controller.replace(alpha1=4.0 + np.outer(v, [1.0, 0.5, 2.0]))),
    "built-in plant parameter per case": lambda v: mars.replace(plant=mars.plant.replace(isp=200.0 + 50.0 * v)),
    "disturbances per case": lambda v: mars.replace(
        disturbance=[W.Constant(np.outer(v, [0.01, -0.02, 0.03])), W.Sinusoid(0.02, 1.0 + v)]),
    "PythonPlant parameter per case": lambda v: on_damped(damped_plant(0.5 + v), C.PDSlidingMode(lambda_=1.0, k=2.0)),
}


@pytest.mark.parametrize("name", list(CASES))
def test_a_chunked_campaign_runs_each_case_with_its_own_row(name):
    scenario = CASES[name](ROWS)
    rows = scenario.case_rows(N)
    assert rows and set(rows.values()) == {N}, rows
    whole = landing.monte_carlo(scenario, N, seed=4, chunk_size=N, progress=False, check_bounds=False)
    for chunk_size in (1, 5):
        chunked = landing.monte_carlo(scenario, N, seed=4, chunk_size=chunk_size, progress=False,
                                      check_bounds=False)
        assert_same_campaign(chunked, whole)
    # and case i ran row i: the same case alone, under the value of its row shared
    x0 = scenario.initial_states(N, seed=4)
    for i in (0, 7, N - 1):
        alone = CASES[name](np.array([ROWS[i]]))
        one = alone.simulate_batch(x0[i:i + 1], seed=4, first_case=i)
        np.testing.assert_array_equal(one.final_state[0], whole.result.final_state[i], err_msg=f"case {i}")
    # the parameter matters: the first and last cases differ (else the test could not fail)
    assert not np.array_equal(whole.result.final_state[0], whole.result.final_state[-1])


def test_a_scenario_cut_to_some_cases_keeps_their_rows():
    s = CASES["PythonLaw gain per case"](ROWS)
    cut = s.cases(3, 7, N)
    np.testing.assert_array_equal(cut.controller.params["kp"], s.controller.params["kp"][3:7])
    assert cut.controller.params["kd"] == s.controller.params["kd"]
    assert s.cases(0, N, N) is s
    plain = small_campaign()
    assert plain.case_rows(N) == {} and plain.cases(2, 5, N) is plain


@pytest.mark.parametrize("name", ["built-in plant parameter per case", "PythonLaw gain per case",
                                  "disturbances per case"])
def test_a_campaign_of_another_size_than_the_rows_is_refused_naming_the_parameter(name):
    scenario = CASES[name](ROWS)
    with pytest.raises(ParameterError, match=f"has {N} values per case but the campaign has {N - 2} cases"):
        landing.monte_carlo(scenario, N - 2, seed=4, progress=False, check_bounds=False)


@pytest.mark.io
def test_a_stored_campaign_resumes_with_its_rows(tmp_path, monkeypatch):
    pytest.importorskip("pyarrow")
    scenario = CASES["built-in law gain per case"](ROWS)
    whole = landing.monte_carlo(scenario, N, seed=4, progress=False, check_bounds=False)
    path = tmp_path / "c"
    with monkeypatch.context() as m:
        crash_after_chunks(m, 1)
        with pytest.raises(KeyboardInterrupt):
            landing.monte_carlo(scenario, N, seed=4, chunk_size=5, store=path, progress=False, check_bounds=False)
    # the chunks left are run on resume, each with its own rows
    resumed = landing.monte_carlo(scenario, N, seed=4, store=path, progress=False, check_bounds=False)
    assert_same_campaign(resumed, whole)
    assert_same_campaign(landing.load(path, scenario=scenario), whole)


@pytest.mark.dask
def test_a_dask_cluster_runs_each_chunk_with_its_rows():
    distributed = pytest.importorskip("distributed")
    scenario = CASES["PythonLaw gain per case"](ROWS)
    whole = landing.monte_carlo(scenario, N, seed=4, progress=False, check_bounds=False)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1",
                                  dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        mc = landing.monte_carlo(scenario, N, seed=4, client=client, chunk_size=5, threads=1, check_bounds=False)
    assert_same_campaign(mc, whole)
