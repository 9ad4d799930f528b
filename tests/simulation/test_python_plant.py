"""Plants written in Python (``landing.plants.PythonPlant``) against the same plants built in.

The double integrator and the Mars lander are re-written here from their equations in numpy (a
second implementation, not the core's code). The double integrator's dynamics are additions
only, so the runs agree bit for bit; the Mars lander's drag and rocket equation agree to 1e-12.
"""

from __future__ import annotations

import signal
import threading
import time

import numpy as np
import pytest

import landing
from _cases import NOMINAL
from _user_laws import integral_pd, pd, start_at_error
from landing import controllers as C
from landing import disturbances as W
from landing import plants as P
from landing.errors import DivergenceWarning, ParameterError, UserFunctionError


def double_integrator(t, x, u, params):
    return np.concatenate([x[:, 3:], u], axis=1)


DOUBLE_INTEGRATOR = P.PythonPlant(double_integrator, 6, positions=(0, 1, 2), velocities=(3, 4, 5))


def mars_derivative(t, x, u, params):
    """Seed 001 eq. 12: r' = v, v' = F/m + g + a_drag, m' = -|F| / (isp g0)."""
    m = x[:, 6:7]
    drift, _ = mars_model(t, x, params)
    a = u * (1.0 / m) + drift
    mdot = -np.sqrt((u * u).sum(axis=1, keepdims=True)) * (1.0 / (params["isp"][:, None] * 9.807))
    return np.concatenate([x[:, 3:6], a, mdot], axis=1)


def mars_model(t, x, params):
    v, m = x[:, 3:6], x[:, 6:7]
    density = 0.699 * np.exp(-0.0009 * x[:, 2:3])
    drag = -(density * (v * np.abs(v))) * (1.0 / m) / np.array([6.0, 7.5, 8.7])
    gravity = np.array([0.0, 0.0, -3.7114])
    return gravity + drag, np.repeat(m, 3, axis=1)


def mars_actuate(t, x, a, params):
    limit = params["thrust_limit"][:, None]
    return np.clip(a * x[:, 6:7], -limit, limit)


def mars_domain(t, x, params):
    return (x[:, 6] > 0.0) & ((x[:, :3] ** 2).sum(axis=1) <= 1e16)


MARS = P.PythonPlant(mars_derivative, 7, positions=(0, 1, 2), velocities=(3, 4, 5), model=mars_model,
                     actuate=mars_actuate, in_domain=mars_domain, params={"isp": 225.0, "thrust_limit": 50_000.0},
                     mass=6, altitude=2, state_names=("rx", "ry", "rz", "vx", "vy", "vz", "m"),
                     control_names=("Fx", "Fy", "Fz"))

MSS = C.FixedTimeMSS(beta1=1.3, q1=0.589, beta2=0.0242, q2=1.18, alpha1=4.89, gamma1=0.319, alpha2=0.0129,
                     gamma2=1.42)


def mars_x0(n: int, seed: int = 3) -> np.ndarray:
    rng = np.random.default_rng(seed)
    return NOMINAL + np.array([100.0, 100.0, 100.0, 10.0, 10.0, 10.0, 20.0]) * rng.standard_normal((n, 7))


def same_bits(a, b) -> None:
    for name in ("t", "states", "controls", "final_state"):
        np.testing.assert_array_equal(getattr(a, name), getattr(b, name), err_msg=name)
    for key in a.metrics:
        np.testing.assert_array_equal(np.asarray(a.metrics[key]), np.asarray(b.metrics[key]), err_msg=key)


@pytest.mark.parametrize("integrator", ["rk4", "euler"])
def test_the_double_integrator_in_python_gives_the_built_in_bits(integrator):
    x0 = np.random.default_rng(0).normal(size=(40, 6))
    noise = W.Sum([W.Sinusoid(amplitude=0.3, omega=1.0), W.UniformNoise(bound=0.2), W.CommandNoise(0.01)])
    laws = [C.PDSlidingMode(lambda_=1.0, k=2.0), C.PythonLaw(pd, params={"kp": 1.0, "kd": 2.0}),
            C.PythonLaw(integral_pd, params={"kp": 1.0, "kd": 2.0, "ki": 0.1, "dt": 0.01},
                        memory=start_at_error, diagnostics=["z"])]
    for law in laws:
        kw = dict(t_final=2.0, dt=0.01, substeps=2, integrator=integrator, disturbance=noise, record_every=7,
                  seed=5)
        built_in = landing.simulate_batch(P.DoubleIntegrator(), law, x0, **kw)
        python = landing.simulate_batch(DOUBLE_INTEGRATOR, law, x0, **kw)
        same_bits(built_in, python)
        for name in built_in.diagnostics:
            np.testing.assert_array_equal(built_in.diagnostics[name], python.diagnostics[name])
        assert python.kernel == "baseline"
        assert python.state_names == ("x0", "x1", "x2", "x3", "x4", "x5")


def test_states_a_plant_keeps_are_never_overwritten():
    # the engine reuses the arrays it hands the functions, unless one was kept: a kept state
    # must still hold its own stage's values (forward Euler: one stage, the period's start)
    kept = []

    def derivative(t, x, u, params):
        kept.append(x)  # the array itself, not a copy
        return np.concatenate([x[:, 3:], u], axis=1)

    plant = P.PythonPlant(derivative, 6, positions=(0, 1, 2), velocities=(3, 4, 5))
    x0 = np.array([[1.0, -2.0, 0.5, 0.0, 0.0, 0.0], [0.0, 1.0, 2.0, 0.5, 0.0, 0.0]])
    res = landing.simulate_batch(plant, C.PDSlidingMode(lambda_=1.0, k=2.0), x0, t_final=1.0, dt=0.1,
                                 integrator="euler")
    np.testing.assert_array_equal(np.stack(kept), res.states[:, :-1].transpose(1, 0, 2))


def test_the_arrays_a_plant_is_handed_are_read_only():
    # made read-only once by the engine, at every call and stage, whether kept or reused
    flags = []

    def derivative(t, x, u, params):
        flags.append((x.flags.writeable, u.flags.writeable))
        if len(flags) % 3 == 0:
            derivative.kept = x  # a kept array makes the engine hand a fresh one next time
        return np.concatenate([x[:, 3:], u], axis=1)

    plant = P.PythonPlant(derivative, 6, positions=(0, 1, 2), velocities=(3, 4, 5))
    x0 = np.array([[1.0, -2.0, 0.5, 0.0, 0.0, 0.0], [0.0, 1.0, 2.0, 0.5, 0.0, 0.0]])
    landing.simulate_batch(plant, C.PDSlidingMode(lambda_=1.0, k=2.0), x0, t_final=0.5, dt=0.1)
    assert len(flags) == 20 and not any(w for pair in flags for w in pair), flags


def test_a_plant_s_parameters_are_read_only_a_scalar_a_view_with_zero_strides():
    # a scalar is a broadcast view with stride 0, not a copy per case; a shared vector is a
    # contiguous (n, k) array, since numpy loops over rows of k values for a view with a zero
    # stride along the cases (BENCHMARKS.md)
    seen = []

    def derivative(t, x, u, params):
        if not seen:
            seen.append({k: (v.shape, v.strides, v.flags.writeable) for k, v in params.items()})
        return np.concatenate([x[:, 3:], u * params["gain"][:, None]], axis=1)

    n = 4
    params = {"gain": 1.0, "vector": np.array([1.0, 2.0]), "cases": np.linspace(1.0, 2.0, n)}
    plant = P.PythonPlant(derivative, 6, positions=(0, 1, 2), velocities=(3, 4, 5), params=params)
    landing.simulate_batch(plant, C.OpenLoop(), np.zeros((n, 6)), t_final=0.02, dt=0.01, record_every=0)
    (p,) = seen
    assert p == {"gain": ((n,), (0,), False), "vector": ((n, 2), (16, 8), False), "cases": ((n,), (8,), False)}


def test_the_mars_lander_in_python_agrees_with_the_built_in_one():
    x0 = mars_x0(30)
    x0[4] = [10.0, 0.0, 3.0, 0.0, 0.0, -40.0, 1900.0]  # touches down in the first tenth of a second
    kw = dict(t_final=3.0, dt=0.01, disturbance=W.Sinusoid(amplitude=20.0, omega=1.0), record_every=10)
    built_in = landing.simulate_batch(P.MarsLander(thrust_limit=50_000.0), MSS, x0, **kw)
    python = landing.simulate_batch(MARS, MSS, x0, **kw)
    np.testing.assert_allclose(python.final_state, built_in.final_state, rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(python.states, built_in.states, rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(python.controls, built_in.controls, rtol=1e-12, atol=1e-6)
    for key in ("fuel_used", "control_effort", "iae", "touchdown_time", "touchdown_speed"):
        np.testing.assert_allclose(np.asarray(python.metrics[key], float), np.asarray(built_in.metrics[key], float),
                                   rtol=1e-10, err_msg=key)
    assert np.isfinite(python.metrics["touchdown_time"][4])
    assert python.metrics["fuel_used"].min() > 0
    assert python.control_names == ("Fx", "Fy", "Fz")


def test_chunks_and_threads_give_the_same_bits():
    x0 = mars_x0(12)
    kw = dict(t_final=0.5, dt=0.01, disturbance=W.UniformNoise(bound=1.0), record_every=0, seed=9)
    whole = landing.simulate_batch(MARS, MSS, x0, threads=2, **kw)
    first = landing.simulate_batch(MARS, MSS, x0[:5], threads=1, **kw)
    rest = landing.simulate_batch(MARS, MSS, x0[5:], first_case=5, **kw)
    np.testing.assert_array_equal(whole.final_state, np.concatenate([first.final_state, rest.final_state]))


def test_per_case_parameters_reach_the_functions():
    isp = np.linspace(200.0, 300.0, 6)
    x0 = mars_x0(6)
    python = landing.simulate_batch(MARS.replace(isp=isp), MSS, x0, t_final=1.0, dt=0.01)
    for i in (0, 5):
        one = landing.simulate_batch(P.MarsLander(thrust_limit=50_000.0, isp=isp[i]), MSS, x0[i:i + 1],
                                     t_final=1.0, dt=0.01)
        np.testing.assert_allclose(python.final_state[i], one.final_state[0], rtol=1e-12)


def test_a_state_out_of_the_domain_or_not_finite_is_flagged():
    def blows_up(t, x, u, params):
        xdot = double_integrator(t, x, u, params)
        xdot[1] = np.nan  # case 1's derivative is not finite
        return xdot

    def inside(t, x, params):
        return np.abs(x[:, 0]) < 1.505

    x0 = np.zeros((3, 6))
    x0[2, 3] = 1.0  # case 2 moves out of |x| < 1.505 in the step ending at 1.51 s
    plant = P.PythonPlant(blows_up, 6, positions=(0, 1, 2), velocities=(3, 4, 5), in_domain=inside)
    with pytest.warns(DivergenceWarning):
        res = landing.simulate_batch(plant, C.OpenLoop(), x0, t_final=3.0, dt=0.01)
    reasons = [landing.DIVERGENCE_REASONS[c] for c in res.metrics["diverged_reason"]]
    assert reasons == ["none", "non_finite_state", "out_of_domain"]
    assert res.metrics["diverged_time"][2] == pytest.approx(1.51)


def test_what_a_function_gets_wrong_is_named():
    def raises(t, x, u, params):
        if t > 0.05:
            raise ZeroDivisionError("boom")
        return double_integrator(t, x, u, params)

    plant = P.PythonPlant(raises, 6, positions=(0, 1, 2), velocities=(3, 4, 5), name="mine")
    with pytest.raises(UserFunctionError, match=r"PythonPlant mine: derivative at t = 0.05\d* s on cases 3..4 "
                                                r"raised ZeroDivisionError: boom") as info:
        landing.simulate_batch(plant, C.OpenLoop(), np.zeros((2, 6)), t_final=1.0, dt=0.01, first_case=3)
    assert isinstance(info.value.__cause__, ZeroDivisionError)
    bad = [
        (P.PythonPlant(lambda t, x, u, p: x[:, :3], 6, (0, 1, 2), (3, 4, 5)), r"a derivative of shape \(2, 3\); "
         r"expected \(2, 6\)"),
        (P.PythonPlant(lambda t, x, u, p: x.astype(np.int64), 6, (0, 1, 2), (3, 4, 5)), "dtype int64"),
        (P.PythonPlant(double_integrator, 6, (0, 1, 2), (3, 4, 5), model=lambda t, x, p: x[:, :3]),
         r"expected \(drift, inertia\)"),
        (P.PythonPlant(double_integrator, 6, (0, 1, 2), (3, 4, 5), in_domain=lambda t, x, p: x[:, 0]),
         "expected booleans"),
    ]
    for plant, message in bad:
        with pytest.raises(UserFunctionError, match=message):
            landing.simulate_batch(plant, C.OpenLoop(), np.zeros((2, 6)), t_final=0.1, dt=0.01)


@pytest.mark.parametrize("kwargs, message", [
    (dict(n_state=0), "n_state = 0 violates"),
    (dict(n_state=33), "n_state = 33 violates"),
    (dict(positions=(0, 1)), "one index per axis"),
    (dict(velocities=(3, 4, 2)), "distinct components"),
    (dict(velocities=(3, 4, 6)), "distinct components of 0..5"),
    (dict(mass=6), "mass = 6 violates"),
    (dict(params={"a b": 1.0}), "must be a name"),
    (dict(state_names=("a",)), "state_names has 1 names"),
])
def test_a_bad_plant_is_refused_naming_the_argument(kwargs, message):
    args = dict(derivative=double_integrator, n_state=6, positions=(0, 1, 2), velocities=(3, 4, 5))
    with pytest.raises(ParameterError, match=message):
        P.PythonPlant(**{**args, **kwargs})


def test_x0_must_fit_the_plant():
    with pytest.raises(ParameterError, match=r"x0 has shape \(2, 7\); this plant takes \(N, 6\)"):
        landing.simulate_batch(DOUBLE_INTEGRATOR, C.OpenLoop(), np.zeros((2, 7)), t_final=0.1, dt=0.01)


def test_one_case_and_a_scenario_run_on_a_python_plant():
    res = landing.simulate(MARS, MSS, NOMINAL, t_final=0.5, dt=0.01)
    ref = landing.simulate(P.MarsLander(thrust_limit=50_000.0), MSS, NOMINAL, t_final=0.5, dt=0.01)
    np.testing.assert_allclose(res.final_state, ref.final_state, rtol=1e-12)
    scenario = landing.scenarios.mars_monte_carlo(plant=MARS, t_final=0.5, dt=0.01, record_every=0)
    mc = landing.monte_carlo(scenario, 8, seed=2, chunk_size=3)
    built = landing.monte_carlo(scenario.replace(plant=P.MarsLander(thrust_limit=50_000.0)), 8, seed=2)
    np.testing.assert_allclose(mc.result.final_state, built.result.final_state, rtol=1e-12)
    np.testing.assert_array_equal(mc.x0, built.x0)


def test_a_python_plant_is_refused_by_scenario_files_naming_why(tmp_path):
    scenario = landing.scenarios.mars_monte_carlo(plant=MARS, t_final=0.1, dt=0.01, record_every=0)
    with pytest.raises(ParameterError, match="a PythonPlant cannot be written to a scenario file yet"):
        scenario.to_toml()
    with pytest.raises(ParameterError, match="a PythonPlant cannot be written"):
        landing.monte_carlo(scenario, 2, seed=0, store=tmp_path / "s", progress=False, check_bounds=False)


def test_ctrl_c_stops_a_python_plant_run_within_a_second():
    def slow(t, x, u, params):
        time.sleep(0.01)
        return double_integrator(t, x, u, params)

    plant = P.PythonPlant(slow, 6, positions=(0, 1, 2), velocities=(3, 4, 5))
    timer = threading.Timer(0.5, lambda: signal.raise_signal(signal.SIGINT))
    start = time.monotonic()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        landing.simulate_batch(plant, C.OpenLoop(), np.ones((2, 6)), t_final=100.0, dt=0.1)
    assert time.monotonic() - start < 1.5


@pytest.mark.dask
def test_a_dask_cluster_runs_a_plant_defined_in_a_script():
    distributed = pytest.importorskip("distributed")

    # closures: not importable by name, they travel by cloudpickle
    def local_derivative(t, x, u, params):
        return np.concatenate([x[:, 3:], u], axis=1)

    plant = P.PythonPlant(local_derivative, 6, positions=(0, 1, 2), velocities=(3, 4, 5))
    x0 = np.array([1.0, -1.0, 2.0, 0.0, 0.5, 0.0])
    s = landing.scenarios.Scenario(name="di", description="", plant=plant,
                                   controller=C.PDSlidingMode(lambda_=1.0, k=2.0), x0=x0,
                                   dispersion=landing.dispersions.Normal(mean=x0, std=np.full(6, 0.1)),
                                   t_final=1.0, dt=0.01, record_every=0)
    expected = landing.monte_carlo(s, 12, seed=2, progress=False, check_bounds=False)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1",
                                  dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        mc = landing.monte_carlo(s, 12, seed=2, client=client, chunk_size=5, threads=1, check_bounds=False)
    np.testing.assert_array_equal(mc.result.final_state, expected.result.final_state)
