"""A campaign's cases one at a time: ``mc[i]``, the worst cases, a case re-run alone with full
recording (bit for bit the campaign's), a partial store loaded as such, and what an interrupted
or resumed campaign says."""

from __future__ import annotations

import numpy as np
import pytest

import landing
from _cases import crash_after_chunks, small_campaign
from landing.dispersions import Normal
from landing.errors import ParameterError, ParameterTypeError
from landing.scenarios import mars_realistic

N = 24


@pytest.fixture(scope="module")
def realistic() -> landing.MonteCarloResult:
    # random disturbances, sensor noise, dispersed states and parameters, each case ending at its
    # touchdown: everything a re-run must reproduce
    s = mars_realistic(record_every=50, t_final=60.0).disperse({"plant.isp": Normal(225.0, 3.0)})
    return landing.monte_carlo(s, N, seed=5, chunk_size=7, progress=False)


def same_bits(a, b) -> bool:
    a, b = np.asarray(a), np.asarray(b)
    return a.shape == b.shape and a.tobytes() == b.tobytes()


def test_a_campaign_is_indexed_by_case(realistic):
    mc = realistic
    assert len(mc) == N
    one = mc[5]
    assert same_bits(one.final_state, mc.result.final_state[5]) and same_bits(one.states, mc.states[5])
    assert same_bits(mc[-1].final_state, mc.result.final_state[N - 1])
    for bad in ("5", 2.0, True):
        with pytest.raises(ParameterTypeError, match="indexed by a case number"):
            mc[bad]
    with pytest.raises(ParameterError):
        mc[N]


def test_the_worst_cases_are_the_largest_values_nan_first(realistic):
    mc = realistic
    v = mc.metrics["touchdown_speed"]
    assert list(mc.worst("touchdown_speed", 4)) == list(np.argsort(-v)[:4])
    assert list(mc.worst("touchdown_speed", 3, largest=False)) == list(np.argsort(v)[:3])
    fake = np.array([1.0, np.nan, 3.0, 2.0])
    m = landing.monte_carlo(small_campaign(), 4, seed=1, progress=False, check_bounds=False)
    m = m.__class__(**{**m.__dict__, "result": m.result.with_metrics({"fuel_used": fake})})
    assert list(m.worst("fuel_used", 4)) == [1, 2, 3, 0]
    with pytest.raises(ParameterError, match="per axis"):
        mc.worst("final_error")


@pytest.mark.parametrize("case", [0, 9, N - 1])
def test_a_rerun_is_the_campaigns_case_bit_for_bit_with_every_instant_recorded(realistic, case):
    mc = realistic
    r = mc.rerun(case, record_every=1)
    assert same_bits(r.final_state[0], mc.result.final_state[case])
    for k in mc.metrics:
        assert same_bits(r.metrics[k][0], mc.metrics[k][case]), k
    # every instant now, the campaign's every 50th among them
    every = mc.scenario.record_every
    assert same_bits(r.t[::every][:mc.t.size], mc.t)
    assert same_bits(r.states[0, ::every][:mc.t.size], mc.states[case])


@pytest.mark.io
def test_a_partial_store_loads_its_completed_cases_and_says_so(tmp_path, monkeypatch):
    pytest.importorskip("pyarrow")
    s = small_campaign().disperse({"plant.isp": Normal(225.0, 5.0)})
    whole = landing.monte_carlo(s, N, seed=4, progress=False, check_bounds=False)
    path = tmp_path / "c"
    with monkeypatch.context() as m:
        crash_after_chunks(m, 2)
        with pytest.raises(KeyboardInterrupt, match=r"10 of 24 cases \(2 of 5 chunks\) are kept in .* resumes it"):
            landing.monte_carlo(s, N, seed=4, chunk_size=5, store=path, progress=False, check_bounds=False)
    with pytest.raises(ParameterError, match=r"incomplete .* partial=True"):
        landing.load(path)
    part = landing.load(path, partial=True)
    assert part.partial and part.planned == N and list(part.cases) == list(range(10))
    assert same_bits(part.result.final_state, whole.result.final_state[:10])
    for k in whole.metrics:
        assert same_bits(part.metrics[k], whole.metrics[k][:10]), k
    assert "partial: 10 of the campaign's 24 cases" in part.report()
    assert same_bits(part.rerun(7).final_state[0], whole.result.final_state[7])

    # the resumed run's progress counts the 14 cases it computes, and says the store holds 10
    bars = []

    class Recorder:
        def __init__(self, n, label):
            bars.append([n, label, 0])

        def update(self, k):
            bars[-1][2] += k

        def close(self):
            pass

    monkeypatch.setattr(landing.campaign.api, "ProgressBar", Recorder)
    resumed = landing.monte_carlo(s, N, seed=4, store=path, progress=True, check_bounds=False)
    assert bars == [[14, f"{s.name} (resumed: 10 of 24 cases in the store)", 14]]
    assert same_bits(resumed.result.final_state, whole.result.final_state)


def test_an_interrupted_campaign_without_a_store_says_nothing_is_kept(monkeypatch):
    s = small_campaign()

    def interrupt(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(landing.scenarios.Scenario, "simulate_cases", interrupt)
    with pytest.raises(KeyboardInterrupt, match="nothing is kept .* store=DIR"):
        landing.monte_carlo(s, N, seed=4, progress=False, check_bounds=False)
