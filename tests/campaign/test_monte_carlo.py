"""Dispersions, Monte Carlo campaigns and scenarios."""

import numpy as np
import pytest

import landing
from _cases import numpy_block, small_campaign
from landing import dispersions, scenarios
from landing.scenarios import preset
from landing.simulation import simulate_batch_into


def test_uniform_dispersion_is_the_philox_draw():
    """Case i, component j: low + (high - low) u with u from word j of the dispersion stream
    (stream 0) of (seed, i), computed here with numpy's Philox."""
    low = np.array([-1000.0, 0.0, 1000.0, -15.0, -100.0])
    high = np.array([200.0, 2000.0, 1500.0, 45.0, 0.0])
    d = dispersions.Uniform(low=low, high=high)
    x = d.sample(6, seed=99, first_case=10)
    for i in range(6):
        raw = numpy_block([0, 10 + i, 0, 0], [99, 0]) + numpy_block([1, 10 + i, 0, 0], [99, 0])
        u = np.array([(r >> 11) * 2.0**-53 for r in raw[:5]])
        np.testing.assert_allclose(x[i], low + (high - low) * u, rtol=0, atol=1e-9)


def test_dispersion_statistics_match_the_request():
    sd = np.array([100, 100, 100, 10, 10, 10, 20.0])
    d = dispersions.Normal(mean=scenarios.MARS_NOMINAL_STATE, std=sd)
    x = d.sample(20000, seed=2)
    assert np.all(np.abs(x.mean(axis=0) - scenarios.MARS_NOMINAL_STATE) <= 4 * sd / np.sqrt(20000))
    np.testing.assert_allclose(x.std(axis=0), sd, rtol=0.03)
    assert abs(np.corrcoef(x[:, 0], x[:, 1])[0, 1]) < 0.03  # independent components
    u = dispersions.Uniform(low=[0.0, -1.0], high=[2.0, -1.0]).sample(20000, seed=2)
    assert u[:, 0].min() >= 0 and u[:, 0].max() <= 2 and np.all(u[:, 1] == -1.0)
    assert u[:, 0].std() == pytest.approx(2 / np.sqrt(12), rel=0.03)


def test_dispersions_are_validated():
    with pytest.raises(ValueError, match=r"std\[2\] = -1 violates std >= 0"):
        dispersions.Normal(mean=[0, 0, 0], std=[1, 1, -1])
    with pytest.raises(ValueError, match="high"):
        dispersions.Uniform(low=[0, 1], high=[1, 0])


def test_the_sampled_states_are_the_simulated_ones():
    s = small_campaign()
    mc = landing.monte_carlo(s, 16, seed=5)
    np.testing.assert_array_equal(mc.x0, s.initial_states(16, seed=5))
    np.testing.assert_array_equal(mc.states[:, 0], mc.x0)
    assert mc.x0.shape == (16, 7) and len(set(mc.x0[:, 0])) == 16


def test_same_seed_same_bits_across_threads_and_chunks():
    s = small_campaign()
    runs = [
        landing.monte_carlo(s, 20, seed=8, threads=1),
        landing.monte_carlo(s, 20, seed=8, threads=2, chunk_size=3),
        landing.monte_carlo(s, 20, seed=8, threads=2, chunk_size=7),
    ]
    for other in runs[1:]:
        assert other.states.tobytes() == runs[0].states.tobytes()
        for k in runs[0].metrics:
            np.testing.assert_array_equal(other.metrics[k], runs[0].metrics[k])
    # the first cases of a larger campaign are these cases
    bigger = landing.monte_carlo(s, 30, seed=8, chunk_size=11)
    assert bigger.states[:20].tobytes() == runs[0].states.tobytes()
    assert landing.monte_carlo(s, 20, seed=9).states.tobytes() != runs[0].states.tobytes()


def test_summary_agrees_with_the_table():
    mc = landing.monte_carlo(small_campaign(), 25, seed=1)
    summary = mc.summary()
    for k, stats in summary.items():
        v = mc.metrics[k]
        v = v[np.isfinite(v)]
        assert stats["n"] == v.size
        if v.size:
            assert stats["mean"] == pytest.approx(v.mean())
            assert stats["max"] == v.max() and stats["min"] == v.min()
            assert stats["std"] == pytest.approx(v.std(ddof=1))
            assert stats["p95"] == pytest.approx(np.percentile(v, 95))
    text = mc.report()
    assert "25 cases" in text and "final_position_error" in text


def test_campaign_bounds_and_checks():
    mc = landing.monte_carlo(small_campaign(), 10, seed=1)
    assert mc.bounds is not None and set(mc.checks) == {"s1", "s2"}
    np.testing.assert_allclose(mc.bounds.ap_max, 20.0)
    assert mc.within_radius_at_end().all()


def test_scenarios_print_and_override():
    s = scenarios.mars_monte_carlo()
    text = str(s)
    for field in ("plant", "controller", "dispersion", "disturbance", "t_final", "theta"):
        assert field in text
    t = s.replace(dt=0.01, controller=landing.controllers.SuperTwisting())
    assert t.dt == 0.01 and isinstance(t.controller, landing.controllers.SuperTwisting)
    assert s.dt == 1e-3 and isinstance(s.controller, landing.controllers.FixedTimeMSS)
    assert t.bounds() is None  # no fixed-time bounds for super-twisting
    assert scenarios.mars_thrust_limited().initial_states(3, seed=0)[:, 6].tolist() == [1905.0] * 3


def test_monte_carlo_refuses_bad_input():
    with pytest.raises(ValueError, match="n = 0 violates"):
        landing.monte_carlo(small_campaign(), 0)
    with pytest.raises(ValueError, match="scenario must be"):
        landing.monte_carlo("mars", 10)
    with pytest.raises(ValueError, match="chunk_size"):
        landing.monte_carlo(small_campaign(), 10, chunk_size=0)


@pytest.mark.parametrize("per_case", ["(N,)", "(N, 3)"])
def test_per_case_gains_go_through_monte_carlo_and_its_bounds(per_case):
    n = 8
    alpha = np.linspace(1.0, 5.0, n)
    gains = alpha if per_case == "(N,)" else np.repeat(alpha[:, None], 3, axis=1)
    s = preset("mars_monte_carlo").replace(t_final=2.0, controller={"alpha1": gains})
    mc = landing.monte_carlo(s, n, seed=4)
    assert mc.bounds.t2.shape == (n, 3)
    # case i's bounds are those of the law with its own gain (computed case by case)
    for i in (0, n - 1):
        single = landing.theory.mss_bounds(s.controller.replace(alpha1=float(alpha[i])),
                                           landing.theory.disturbance_bound(s.disturbance), *s.theta)
        assert np.array_equal(mc.bounds.t2[i], single.t2)
    report = mc.report()
    assert f"over {n} cases" in report and len(report.splitlines()) < 40


def test_progress_reaches_logs_as_lines(capsys):
    s = preset("mars_monte_carlo").replace(t_final=0.5)
    landing.monte_carlo(s, 40, seed=1, progress=True, chunk_size=10)
    err = capsys.readouterr().err
    lines = [line for line in err.splitlines() if "mars_monte_carlo" in line]
    assert lines and "40/40" in lines[-1] and "\r" not in err


def test_an_address_space_limit_is_honoured_up_front_and_the_refusal_names_what_fits(tmp_path):
    # a child process under ulimit -v: the core's measure of what it can take is bounded by the
    # limit less its virtual size, and a campaign too large for it is refused before it starts,
    # saying which record_every or keep would fit
    import subprocess
    import sys
    import textwrap

    code = textwrap.dedent('''
        import resource
        import landing
        from landing import _core
        with open("/proc/self/status") as f:
            size = next(int(l.split()[1]) * 1024 for l in f if l.startswith("VmSize:"))
        limit = size + 400 * 2**20
        resource.setrlimit(resource.RLIMIT_AS, (limit, resource.RLIM_INFINITY))
        room = _core.available_memory()
        assert room is not None and room <= 400 * 2**20, room
        s = landing.scenarios.mars_monte_carlo(record_every=1)
        try:
            landing.monte_carlo(s, 2000, seed=1, progress=False)
        except MemoryError as exc:
            print("REFUSED", exc)
    ''')
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    assert "REFUSED" in out.stdout and "what fits: record_every=" in out.stdout, out.stdout


def test_a_check_that_cannot_fail_is_reported_as_not_informative():
    # seed 001 part 2 over its 60 s: every final error is far inside the s1 radius (about 1954 m
    # for errors of metres), so "300 of 300 within" says nothing; over 5 s the errors are of the
    # radius's size and the check informs
    long = landing.monte_carlo(scenarios.mars_monte_carlo(record_every=0, dt=2e-3), 20, seed=1, progress=False)
    line = next(x for x in long.report().splitlines() if "within the s1 radius" in x)
    assert "not informative: the radius is" in line
    radius = float(np.min(long.bounds.s1_radius))
    largest = float(np.max(np.abs(long.metrics["final_error"])))
    assert radius / largest >= 10
    short = landing.monte_carlo(scenarios.mars_monte_carlo(record_every=0, t_final=5.0, dt=2e-3), 20, seed=1,
                                progress=False)
    assert "not informative" not in next(x for x in short.report().splitlines() if "within the s1 radius" in x)


def test_a_neighbourhood_whose_bound_time_is_beyond_the_run_gives_no_count():
    # Theorem 4's s2 and s1 bound times (about 800 and 2978 s for part 2) are beyond the 60 s
    # run: "300 of 300 stay from the bound time on" would read as a pass over nothing
    mc = landing.monte_carlo(scenarios.mars_monte_carlo(dt=2e-3, record_every=25), 8, seed=1, progress=False)
    assert mc.checks and all(not np.any(c.extra["checkable"]) for c in mc.checks.values())
    lines = [x for x in mc.report().splitlines() if "stays in its neighbourhood" in x]
    assert len(lines) == 2
    for line in lines:
        assert "not informative (the bound time" in line and " of 8" not in line
        bound = float(line.split("the bound time, ")[1].split(" s")[0])
        assert bound > 60.0


def test_a_campaign_of_a_law_with_a_fuzzy_system_runs_in_chunks():
    # the Mamdani system is a configuration but not a dataclass: looking for per-case
    # parameters inside it raised a TypeError from dataclasses.fields (found by the figures' work)
    s = landing.scenarios.seed002_landing(t_final=20.0)
    whole = landing.monte_carlo(s, 6, seed=1, progress=False)
    chunked = landing.monte_carlo(s, 6, seed=1, chunk_size=2, progress=False)
    assert np.array_equal(whole.result.final_state, chunked.result.final_state)


@pytest.mark.parametrize("n, chunk, calls", [(20, 7, [(7, False), (7, True), (6, True)]),
                                              (150, 100, [(64, False), (36, True), (50, True)])])
def test_a_chunked_campaign_records_into_its_output_the_bits_of_one_batch(monkeypatch, n, chunk, calls):
    # each chunk's recording is written by the core into the chunk's rows of the campaign's
    # output (Assembly.destination); the first chunk runs its first 64 cases alone when it has
    # more, to allocate the output from their shapes; a diverging case records NaN there
    s = small_campaign()
    x0 = s.initial_states(n, seed=8)
    x0[5, 3] = 1e200
    seen = []
    real = landing.simulation._core.simulate_batch

    def spy(plant, law, x, **kwargs):
        out = real(plant, law, x, **kwargs)
        into = kwargs.get("into")
        seen.append((x.shape[0], into is not None and all(
            out[k] is a for k, a in zip(("states", "controls", "diagnostics"), into))))
        return out

    monkeypatch.setattr(landing.simulation._core, "simulate_batch", spy)
    monkeypatch.setattr(type(s), "initial_states", lambda self, n, seed=0, first_case=0: x0[first_case:first_case + n])
    with pytest.warns(landing.errors.DivergenceWarning):
        mc = landing.monte_carlo(s, n, seed=8, threads=2, chunk_size=chunk, progress=False)
    assert seen == calls
    with pytest.warns(landing.errors.DivergenceWarning):
        one = s.simulate_batch(x0, seed=8, threads=1)
    res = mc.result
    assert np.isnan(one.states[5]).any()
    for name in ("states", "controls", "final_state"):
        assert getattr(res, name).tobytes() == getattr(one, name).tobytes(), name
    assert list(res.diagnostics) == list(one.diagnostics)
    for k, v in one.diagnostics.items():
        assert res.diagnostics[k].shape == v.shape and res.diagnostics[k].tobytes() == v.tobytes(), k
    for k in one.metrics:
        np.testing.assert_array_equal(res.metrics[k], one.metrics[k])


def test_a_lent_recording_of_the_wrong_shape_or_layout_is_refused():
    s = small_campaign()
    x0 = s.initial_states(4, seed=1)
    one = s.simulate_batch(x0, seed=1)
    states, controls = np.empty_like(one.states), np.empty_like(one.controls)
    width = sum(v.shape[2] if v.ndim == 3 else 1 for v in one.diagnostics.values())
    block = np.full((4, one.t.size, width), 7.25)
    wrong = np.empty((4, one.t.size, width + 1))
    with pytest.raises(landing.errors.ParameterError, match=r"the diagnostics lent .* shape \[4, \d+, \d+\]"):
        simulate_batch_into((states, controls, wrong), s.plant, s.controller, x0, **s.run_options(seed=1))
    assert (block == 7.25).all()
    strided = np.empty((4, one.t.size, 2 * width))[:, :, ::2]
    with pytest.raises(landing.errors.ParameterError, match="C-contiguous"):
        simulate_batch_into((states, controls, strided), s.plant, s.controller, x0, **s.run_options(seed=1))
    res = simulate_batch_into((states, controls, block), s.plant, s.controller, x0, **s.run_options(seed=1))
    assert res.states is states and res.states.tobytes() == one.states.tobytes()
    assert res.controls.tobytes() == one.controls.tobytes()
    for k, v in one.diagnostics.items():
        assert res.diagnostics[k].tobytes() == v.tobytes()
