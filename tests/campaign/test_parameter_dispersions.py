"""Dispersions of parameters (``Scenario.disperse``): the distributions against scipy.stats,
draws keyed by (seed, case, path), the draws reaching the cases they were drawn for (checked by
running each case with its value given per case), and chunked, threaded, stored, resumed,
clustered and tuned campaigns agreeing bit for bit with the whole batch."""

from __future__ import annotations

import numpy as np
import pytest

import landing
from _cases import assert_same_bits, assert_same_campaign, crash_after_chunks, small_campaign
from _user_laws import pd
from landing import controllers as C
from landing import disturbances as W
from landing import plants as P
from landing.dispersions import LogNormal, Normal, TruncatedNormal, Uniform
from landing.errors import ParameterError, ParameterTypeError
from landing.scenarios import Scenario, files

stats = pytest.importorskip("scipy.stats")

N = 12


def draws(d, n=100_000, key="plant.isp", seed=7):
    return d.sample(n, seed=seed, key=key)[:, 0]


@pytest.mark.parametrize("d, frozen", [
    (Normal(225.0, 5.0), stats.norm(225.0, 5.0)),
    (Uniform(4.0, 6.0), stats.uniform(4.0, 2.0)),
    (LogNormal(0.1, 0.2), stats.lognorm(s=0.2, scale=np.exp(0.1))),
    (TruncatedNormal(225.0, 5.0, 215.0, 228.0), stats.truncnorm(-2.0, 0.6, loc=225.0, scale=5.0)),
    # one-sided, and a window far in the upper tail, where rejection sampling would never end
    (TruncatedNormal(0.0, 1.0, 0.0, 1e300), stats.truncnorm(0.0, np.inf)),
    (TruncatedNormal(10.0, 2.0, 30.0, 31.0), stats.truncnorm(10.0, 10.5, loc=10.0, scale=2.0)),
], ids=["normal", "uniform", "lognormal", "truncated", "half-normal", "far tail"])
def test_each_distribution_is_what_scipy_stats_says(d, frozen):
    x = draws(d)
    # Kolmogorov-Smirnov against scipy's distribution function, and the moments against its own
    assert stats.kstest(x, frozen.cdf).pvalue > 1e-3
    n = x.size
    assert abs(x.mean() - frozen.mean()) < 5 * frozen.std() / np.sqrt(n)
    assert abs(x.std() / frozen.std() - 1) < 0.02
    support = frozen.support()
    assert np.all(x >= support[0]) and np.all(x <= support[1])


def test_truncated_normal_inverts_scipys_distribution_function():
    # the draw is the truncated quantile of the case's uniform: compare it with scipy's ppf of the
    # same uniform (the normal's quantile in the core is Wichura's AS 241, scipy's is Cephes')
    d = TruncatedNormal(1.0, 2.0, -3.0, 4.0)
    u = Uniform(0.0, 1.0).sample(1000, seed=5, key="k")[:, 0]
    x = d.sample(1000, seed=5, key="k")[:, 0]
    expected = stats.truncnorm(-2.0, 1.5, loc=1.0, scale=2.0).ppf(u)
    np.testing.assert_allclose(x, expected, rtol=1e-13, atol=1e-13)


def test_a_draw_depends_on_the_seed_the_case_and_the_path_only():
    d = Normal([1.0, 2.0, 3.0], 0.5)
    whole = d.sample(100, seed=3, key="controller.alpha1")
    assert np.array_equal(whole[40:60], d.sample(20, seed=3, first_case=40, key="controller.alpha1"))
    assert not np.array_equal(whole, d.sample(100, seed=3, key="controller.alpha2"))
    assert not np.array_equal(whole, d.sample(100, seed=4, key="controller.alpha1"))
    # the initial states' stream is another one
    assert not np.array_equal(whole, d.sample(100, seed=3))


def dispersed_mars() -> Scenario:
    return small_campaign().disperse({
        "plant.isp": TruncatedNormal(225.0, 10.0, 200.0, 250.0),
        "controller.alpha1": Uniform(4.0, 6.0),                 # one draw for the three axes
        "controller.alpha2": Normal([0.0129] * 3, [0.001] * 3),  # one per axis
    })


def test_each_case_runs_its_own_draws():
    s = dispersed_mars()
    mc = landing.monte_carlo(s, N, seed=4, progress=False, check_bounds=False)
    m = mc.metrics
    assert m["param.plant.isp"].shape == (N,) and m["param.controller.alpha1"].shape == (N,)
    assert m["param.controller.alpha2"].shape == (N, 3)
    assert np.all((m["param.plant.isp"] >= 200) & (m["param.plant.isp"] <= 250))
    # a second path: the recorded values given per case, no dispersion
    plain = small_campaign().replace(
        plant=s.plant.replace(isp=m["param.plant.isp"]),
        controller=s.controller.replace(alpha1=m["param.controller.alpha1"][:, None],
                                        alpha2=m["param.controller.alpha2"]))
    again = landing.monte_carlo(plain, N, seed=4, progress=False, check_bounds=False)
    assert np.array_equal(mc.result.final_state, again.result.final_state)
    assert np.array_equal(mc.metrics["fuel_used"], again.metrics["fuel_used"])
    # and a dispersion the cases read: the fuel differs from the undispersed campaign's
    nominal = landing.monte_carlo(small_campaign(), N, seed=4, progress=False, check_bounds=False)
    assert not np.array_equal(mc.metrics["fuel_used"], nominal.metrics["fuel_used"])
    assert "plant.isp ~ TruncatedNormal" in mc.report()


def test_draws_do_not_depend_on_the_other_parameters_dispersed():
    one = landing.monte_carlo(small_campaign().disperse({"plant.isp": Normal(225.0, 5.0)}), N, seed=4,
                              progress=False, check_bounds=False)
    three = landing.monte_carlo(dispersed_mars().disperse({"plant.isp": Normal(225.0, 5.0)}), N, seed=4,
                                progress=False, check_bounds=False)
    assert np.array_equal(one.metrics["param.plant.isp"], three.metrics["param.plant.isp"])


def test_chunks_and_threads_give_the_whole_batch_bit_for_bit():
    s = dispersed_mars()
    whole = landing.monte_carlo(s, N, seed=4, progress=False, check_bounds=False)
    for chunk, threads in ((5, 1), (1, 2), (7, None)):
        assert_same_campaign(landing.monte_carlo(s, N, seed=4, chunk_size=chunk, threads=threads, progress=False,
                                                 check_bounds=False), whole)
    assert_same_campaign(landing.monte_carlo(s, N, seed=4, chunk_size=4, progress=True, check_bounds=False), whole)


@pytest.mark.io
def test_a_stored_campaign_resumes_and_loads_with_its_draws(tmp_path, monkeypatch):
    pytest.importorskip("pyarrow")
    s = dispersed_mars()
    whole = landing.monte_carlo(s, N, seed=4, progress=False, check_bounds=False)
    path = tmp_path / "c"
    with monkeypatch.context() as m:
        crash_after_chunks(m, 1)
        with pytest.raises(KeyboardInterrupt):
            landing.monte_carlo(s, N, seed=4, chunk_size=5, store=path, progress=False, check_bounds=False)
    resumed = landing.monte_carlo(s, N, seed=4, store=path, progress=False, check_bounds=False)
    assert_same_campaign(resumed, whole)
    assert_same_campaign(landing.load(path), whole)
    # the dispersions are part of the campaign's identity: another one is refused
    other = s.disperse({"plant.isp": Normal(225.0, 1.0)})
    with pytest.raises(ParameterError):
        landing.monte_carlo(other, N, seed=4, store=path, progress=False, check_bounds=False)


@pytest.mark.dask
def test_a_dask_cluster_draws_as_the_local_run():
    distributed = pytest.importorskip("distributed")
    s = dispersed_mars()
    whole = landing.monte_carlo(s, N, seed=4, progress=False, check_bounds=False)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1",
                                  dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        mc = landing.monte_carlo(s, N, seed=4, client=client, chunk_size=5, threads=1, check_bounds=False)
    assert_same_campaign(mc, whole)


def test_python_laws_python_plants_and_disturbances_are_dispersed_by_path():
    x0 = np.array([1.0, -1.0, 2.0, 0.0, 0.5, 0.0])

    def damped(t, x, u, params):
        return np.concatenate([x[:, 3:], u - params["c"][:, None] * x[:, 3:]], axis=1)

    plant = P.PythonPlant(damped, 6, positions=(0, 1, 2), velocities=(3, 4, 5), params={"c": 0.5})
    law = C.PythonLaw(pd, params={"kp": 4.0, "kd": 3.0})
    s = Scenario(name="damped", plant=plant, controller=law, x0=x0, t_final=1.0, dt=0.01, record_every=10,
                 disturbance=W.Sum([W.Sinusoid(amplitude=0.1, omega=1.0), W.Constant(0.0)]))
    d = s.disperse({"plant.c": Uniform(0.1, 0.9), "controller.kp": Normal(4.0, [0.1, 0.2, 0.3]),
                    "disturbance.parts[0].amplitude": Uniform(0.0, 0.2)})
    mc = landing.monte_carlo(d, N, seed=2, chunk_size=5, progress=False, check_bounds=False)
    m = mc.metrics
    plain = s.replace(plant=plant.replace(c=m["param.plant.c"]), controller=law.replace(kp=m["param.controller.kp"]),
                      disturbance=W.Sum([W.Sinusoid(amplitude=m["param.disturbance.parts[0].amplitude"][:, None],
                                                    omega=1.0), W.Constant(0.0)]))
    again = landing.monte_carlo(plain, N, seed=2, progress=False, check_bounds=False)
    assert np.array_equal(mc.result.final_state, again.result.final_state)


@pytest.mark.parametrize("name, d, rule", [
    ("plant.ispx", Normal(1.0, 1.0), "has no parameter 'ispx'"),
    ("plant.sensor.std", Normal(1.0, 1.0), "has no 'sensor'"),
    ("plant.drag", Normal(1.0, 1.0), "only the numbers a case reads"),
    ("plant.isp", Normal([1.0, 2.0], 1.0), "is a scalar; its dispersion has 2 components"),
    ("controller.alpha1", Normal([1.0, 2.0], 1.0), "give 1 .* or 3"),
    ("isp", Normal(1.0, 1.0), "must start with one of"),
    ("plant.isp[0]", Normal(1.0, 1.0), "end with a parameter's name"),
])
def test_bad_dispersions_are_refused_naming_the_path(name, d, rule):
    with pytest.raises(ParameterError, match=rule):
        small_campaign().disperse({name: d})


def test_a_dispersion_must_be_a_dispersion():
    with pytest.raises(ParameterTypeError, match="must be given a landing.dispersions dispersion"):
        small_campaign().disperse({"plant.isp": 225.0})


def test_a_truncation_window_without_probability_is_refused():
    with pytest.raises(ParameterError, match="window"):
        TruncatedNormal(0.0, 1.0, 40.0, 41.0)
    with pytest.raises(ParameterError, match="window"):
        TruncatedNormal(0.0, 0.0, 1.0, 2.0)  # a fixed value outside its window


def test_scenario_files_hold_dispersions_in_both_forms(tmp_path):
    s = dispersed_mars()
    back = files.scenario_from_dict(files.tomllib.loads(s.to_toml()))
    assert back.to_toml() == s.to_toml()
    assert_same_campaign(landing.monte_carlo(back, N, seed=4, progress=False, check_bounds=False),
                         landing.monte_carlo(s, N, seed=4, progress=False, check_bounds=False))
    head = small_campaign().to_toml()
    short = files.scenario_from_dict(files.tomllib.loads(
        head + '\n[dispersions]\n"plant.isp" = { truncated_normal = [225.0, 10.0, 200.0, 250.0] }\n'))
    assert repr(short.dispersions["plant.isp"]) == repr(TruncatedNormal(225.0, 10.0, 200.0, 250.0))
    path = tmp_path / "bad.toml"
    path.write_text(head + '\n[dispersions]\n"plant.isp" = { normal = [225.0] }\n')
    with pytest.raises(files.FileError, match=r"bad.toml: dispersions.\"plant.isp\".normal"):
        Scenario.load(str(path))


@pytest.mark.tune
def test_the_tuner_evaluates_each_candidate_on_the_campaigns_draws():
    pytest.importorskip("cma")
    s = small_campaign().disperse({"plant.isp": Normal(225.0, 10.0)})
    r = landing.tune(s, gains={"alpha1": (3.0, 6.0)}, objective="mean(fuel_used)", cases=4, budget=6, seed=1)
    for e in (0, len(r.x) - 1):
        mc = landing.monte_carlo(s.replace(controller={"alpha1": float(r.x[e, 0])}), 4, seed=1, progress=False,
                                 check_bounds=False)
        assert r.objective_values[e, 0] == np.mean(mc.metrics["fuel_used"])
    with pytest.raises(ParameterError, match="is tuned and the scenario disperses it"):
        landing.tune(s.disperse({"controller.alpha1": Uniform(4.0, 6.0)}), gains={"alpha1": (3.0, 6.0)},
                     objective="mean(fuel_used)", cases=4, budget=6)


def test_a_sensor_s_numbers_are_dispersed_per_case_and_per_component(tmp_path):
    # a bias alone (no white noise, no walk) is what the law reads on top of the truth: each
    # case's navigation error at the end is its own draw (to the rounding of (q + b) - q, q of
    # 1e3 m), one for every component or one per
    # component; the campaign chunked, stored and resumed equals the whole batch
    from landing.sensors import KalmanFilter, Noise

    s = small_campaign()
    sensed = s.replace(plant=s.plant.replace(sensor=Noise(bias=0.0)))
    d = sensed.disperse({"plant.sensor.bias": Normal(0.0, [0.5, 0.5, 0.5, 0.05, 0.05, 0.05])})
    whole = landing.monte_carlo(d, N, seed=4, progress=False, check_bounds=False)
    bias = whole.metrics["param.plant.sensor.bias"]
    assert bias.shape == (N, 6) and np.unique(bias).size == 6 * N
    np.testing.assert_allclose(whole.metrics["navigation_position_error"], bias[:, :3], rtol=0, atol=1e-9)
    np.testing.assert_allclose(whole.metrics["navigation_velocity_error"], bias[:, 3:], rtol=0, atol=1e-9)
    chunked = landing.monte_carlo(d, N, seed=4, chunk_size=5, threads=2, progress=False, check_bounds=False)
    assert_same_campaign(whole, chunked)
    store = tmp_path / "sensed"
    landing.monte_carlo(d, N, seed=4, chunk_size=5, store=store, progress=False, check_bounds=False)
    assert_same_campaign(whole, landing.load(store))
    # one draw for every component; a filter's process noise per case
    one = sensed.disperse({"plant.sensor.bias": Uniform(-1.0, 1.0)})
    m = landing.monte_carlo(one, N, seed=4, progress=False, check_bounds=False).metrics
    assert m["param.plant.sensor.bias"].shape == (N,)
    np.testing.assert_allclose(m["navigation_position_error"], np.repeat(m["param.plant.sensor.bias"][:, None], 3, 1),
                               rtol=0, atol=1e-9)
    filtered = s.replace(plant=s.plant.replace(sensor=Noise(std=1.0), filter=KalmanFilter(0.1)))
    f = filtered.disperse({"plant.filter.process_noise": LogNormal(np.log(0.1), 0.5)})
    mc = landing.monte_carlo(f, N, seed=4, chunk_size=5, progress=False, check_bounds=False)
    rows = mc.metrics["param.plant.filter.process_noise"]
    given = filtered.replace(plant=filtered.plant.replace(filter=KalmanFilter(rows[:, None])))  # (N, 1) rows
    assert_same_bits(mc.result.final_state,
                     landing.monte_carlo(given, N, seed=4, progress=False, check_bounds=False).result.final_state,
                     "the draws given per case")
