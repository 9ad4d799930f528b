"""Laws written in Python (``landing.controllers.PythonLaw``) against the same laws built in.

The built-in laws are re-written here from their equations in numpy (a second implementation,
not the core's code): where they use only IEEE arithmetic and square roots the runs agree bit
for bit, where the core's own powers are involved to 1e-12.
"""

from __future__ import annotations

import os
import platform
import signal
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

import landing
from _cases import NOMINAL, RECONSTRUCTED_GAINS
from landing import controllers as C
from landing import plants as P
from landing.errors import DivergenceWarning, UserFunctionError


def mars_x0(n: int, seed: int = 1) -> np.ndarray:
    rng = np.random.default_rng(seed)
    x = np.tile(NOMINAL, (n, 1))
    x[:, :3] += rng.normal(0.0, 20.0, (n, 3))
    x[:, 3:6] += rng.normal(0.0, 1.0, (n, 3))
    return x


def sig(x: np.ndarray, p: np.ndarray) -> np.ndarray:
    return np.sign(x) * np.abs(x) ** p


def mss_printed(t, e, de, ref, drift, inertia, params, memory):
    """FixedTimeMSS, printed variant (seed 001 eq. 21-25): s1 = e, s2 = de + beta1 sig^q1 + beta2
    sig^q2, the cancellation of the printed eq. 25 and the two-power reaching law on s2."""
    b1, b2, q1, q2 = params["beta1"], params["beta2"], params["q1"], params["q2"]
    a1, a2, g1, g2 = params["alpha1"], params["alpha2"], params["gamma1"], params["gamma2"]
    floor = params["s1_floor"]
    abs1 = np.abs(e)
    p1, p2 = abs1**q1, abs1**q2
    s2 = de + np.sign(e) * (b1 * p1 + b2 * p2)
    with np.errstate(divide="ignore", invalid="ignore"):
        e1 = 2 * q1 - 1
        t1 = np.where((e1 >= 0) | (abs1 >= floor), p1 * p1 / abs1, floor**e1)
        rest = (p2 / abs1) * (b2 * b2 * q2 * p2 + b1 * b2 * (q1 + q2) * p1)
        cancel = np.where(abs1 > 0, np.sign(e) * (b1 * b1 * q1 * t1 + rest), 0.0)
    reach = -np.sign(s2) * (a1 * np.abs(s2) ** g1 + a2 * np.abs(s2) ** g2)
    return ref.acceleration - drift + (cancel + reach), memory, {"s1": e, "s2": s2}


def super_twisting_standard(t, e, de, ref, drift, inertia, params, memory):
    """Super-twisting, standard variant: sigma = de + c e, a = -c de + (-b1 sig^(1/2)(sigma) + w)/m,
    w' = -b2 sgn(sigma), advanced by forward Euler over the period after the command."""
    b1, b2, c, dt = params["b1"], params["b2"], params["c"], params["dt"]
    sigma = de + c * e
    w = memory["w"]
    a = ref.acceleration - drift + (-c * de + (-b1 * np.sign(sigma) * np.sqrt(np.abs(sigma)) + w) / inertia)
    return a, {"w": w - dt * b2 * np.sign(sigma)}, {"sigma": sigma, "w": w}


def pd_sat(t, e, de, ref, drift, inertia, params, memory):
    """PD sliding mode with the saturation switch: s = de + lambda e, a = q_ref'' - drift -
    lambda de - k sat(s / phi)."""
    lam, k, phi = params["lambda"], params["k"], params["phi"]
    s = de + lam * e
    return ref.acceleration - drift - lam * de - k * np.clip(s / phi, -1.0, 1.0), None, {"s": s}


def run_both(plant, builtin, python, x0, **kw):
    a = landing.simulate_batch(plant, builtin, x0, **kw)
    b = landing.simulate_batch(plant, python, x0, **kw)
    return a, b


def assert_same_run(a: landing.SimulationResult, b: landing.SimulationResult, rtol: float) -> None:
    if rtol == 0:
        np.testing.assert_array_equal(b.states, a.states)
        np.testing.assert_array_equal(b.controls, a.controls)
    else:
        # relative to each signal's scale: a command crossing zero has no relative accuracy
        def close(x: np.ndarray, y: np.ndarray) -> None:
            np.testing.assert_allclose(x, y, rtol=0, atol=rtol * np.nanmax(np.abs(y)))

        close(b.states, a.states)
        close(b.controls, a.controls)
    for name in a.diagnostics:
        if rtol == 0:
            np.testing.assert_array_equal(b.diagnostics[name], a.diagnostics[name])
        else:
            close(b.diagnostics[name], a.diagnostics[name])
    for name in ("final_position_error", "fuel_used", "control_effort", "iae", "settle_time"):
        np.testing.assert_allclose(b.metrics[name], a.metrics[name], rtol=max(rtol, 1e-15), atol=0)


def test_the_fixed_time_mss_law_in_numpy_agrees_with_the_built_in_one():
    gains = dict(RECONSTRUCTED_GAINS, s1_floor=1e-3)
    builtin = C.FixedTimeMSS(**RECONSTRUCTED_GAINS)
    python = C.PythonLaw(mss_printed, params=gains, diagnostics=("s1", "s2"))
    a, b = run_both(P.MarsLander(), builtin, python, mars_x0(20), t_final=20.0, dt=1e-3, record_every=100)
    assert_same_run(a, b, rtol=1e-12)
    assert a.metrics["final_position_error"].max() < 50.0  # the law does its work


def test_the_super_twisting_law_with_memory_agrees_bit_for_bit():
    builtin = C.SuperTwisting(b1=(1200.0, 1000.0, 1000.0), b2=(5500.0, 5000.0, 5000.0), variant="standard", c=0.5)
    dt = 1e-3
    python = C.PythonLaw(super_twisting_standard,
                         params={"b1": (1200.0, 1000.0, 1000.0), "b2": (5500.0, 5000.0, 5000.0), "c": 0.5, "dt": dt},
                         memory={"w": np.zeros(3)}, diagnostics=("sigma", "w"))
    a, b = run_both(P.MarsLander(), builtin, python, mars_x0(13), t_final=10.0, dt=dt, record_every=10)
    assert_same_run(a, b, rtol=0)
    assert np.abs(a.diagnostics["w"]).max() > 0  # the memory moved


@pytest.mark.parametrize("plant", [P.DoubleIntegrator(), P.SmallBody()], ids=["double_integrator", "small_body"])
def test_the_pd_sliding_law_agrees_bit_for_bit_on_other_plants(plant):
    builtin = C.PDSlidingMode(lambda_=0.3, k=0.02, switch="sat", boundary_layer=0.5)
    python = C.PythonLaw(pd_sat, params={"lambda": 0.3, "k": 0.02, "phi": 0.5}, diagnostics=("s",))
    n_state = len(landing.simulate(plant, builtin, np.zeros(6) + 0.0 if plant.kind == "double_integrator"
                                   else np.r_[500.0, 300.0, 200.0, 0, 0, 0], t_final=0.1, dt=0.1).state_names)
    rng = np.random.default_rng(4)
    x0 = np.zeros((11, n_state))
    x0[:, :3] = rng.normal(0, 1, (11, 3)) * (1.0 if plant.kind == "double_integrator" else 50.0) + (
        0.0 if plant.kind == "double_integrator" else np.array([500.0, 300.0, 200.0]))
    a, b = run_both(plant, builtin, python, x0, t_final=30.0, dt=0.05, record_every=1)
    assert_same_run(a, b, rtol=0)


def test_per_case_parameters_reach_the_function_and_match_a_per_case_built_in_law():
    k = np.linspace(0.01, 0.05, 9)
    builtin = C.PDSlidingMode(lambda_=0.3, k=k, switch="sat", boundary_layer=0.5)
    python = C.PythonLaw(pd_sat, params={"lambda": 0.3, "k": k, "phi": 0.5}, diagnostics=("s",))
    x0 = np.tile([1.0, -2.0, 0.5, 0.0, 0.0, 0.0], (9, 1))
    a, b = run_both(P.DoubleIntegrator(), builtin, python, x0, t_final=5.0, dt=0.05)
    assert_same_run(a, b, rtol=0)
    assert len({tuple(r) for r in a.final_state.round(12)}) == 9  # the gains differ per case


def test_the_parameters_are_read_only_copies_a_scalar_a_view_with_zero_strides():
    # a scalar is handed as a broadcast view, not an (n, D) copy: numpy reads it from the cache;
    # any other value as a contiguous array, since numpy loops over rows of D values for a view
    # with one zero stride (BENCHMARKS.md); what the caller gave is copied first
    seen = []

    def law(t, e, de, ref, drift, inertia, params, memory):
        if not seen:
            seen.append({k: (v.shape, v.strides, v.flags.writeable, v.copy()) for k, v in params.items()})
        return -params["k"] * e

    n = 6
    per_case = np.linspace(1.0, 2.0, n)
    per_axis = np.array([1.0, 2.0, 3.0])
    full = np.arange(3.0 * n).reshape(n, 3)
    given = {"shared": 0.5, "axes": per_axis, "cases": per_case, "cases_1": per_case[:, None], "full": full,
             "k": 0.1}
    law_ = C.PythonLaw(law, params=given)
    per_axis[:] = -1.0  # changed after the law was made: the run sees the values given
    landing.simulate_batch(P.DoubleIntegrator(), law_, np.ones((n, 6)), t_final=0.02, dt=0.01, record_every=0,
                           threads=1)
    (p,) = seen
    expect = {"shared": np.full((n, 3), 0.5), "axes": np.tile([1.0, 2.0, 3.0], (n, 1)),
              "cases": np.repeat(per_case[:, None], 3, axis=1), "cases_1": np.repeat(per_case[:, None], 3, axis=1),
              "full": full}
    for k, v in expect.items():
        shape, strides, writeable, values = p[k]
        assert shape == (n, 3) and not writeable, (k, shape, writeable)
        np.testing.assert_array_equal(values, v, err_msg=k)
    assert p["shared"][1] == (0, 0)
    assert {p[k][1] for k in ("axes", "cases", "cases_1", "full")} == {(24, 8)}


def test_the_python_law_is_bit_identical_across_threads_and_levels():
    gains = dict(RECONSTRUCTED_GAINS, s1_floor=1e-3)
    law = C.PythonLaw(mss_printed, params=gains, diagnostics=("s1", "s2"))
    x0 = mars_x0(37)
    storm = landing.disturbances.UniformNoise(bound=0.3) + landing.disturbances.Sinusoid(amplitude=0.1, omega=1.0)
    runs = [landing.simulate_batch(P.MarsLander(), law, x0, t_final=2.0, dt=1e-3, threads=t, kernel=lv,
                                   disturbance=storm, seed=5)
            for t in (1, 2) for lv in landing.kernel_levels()]
    for r in runs[1:]:
        np.testing.assert_array_equal(r.states, runs[0].states)
        np.testing.assert_array_equal(r.final_state, runs[0].final_state)


def test_one_call_per_control_instant_with_all_cases():
    calls = []

    def law(t, e, de, ref, drift, inertia, params, memory):
        calls.append((t, e.shape))
        return -e - de

    landing.simulate_batch(P.DoubleIntegrator(), C.PythonLaw(law), np.ones((21, 6)), t_final=1.0, dt=0.1)
    assert [c[1] for c in calls] == [(21, 3)] * 11
    np.testing.assert_allclose([c[0] for c in calls], np.arange(11) * 0.1, rtol=0, atol=1e-15)


def test_a_batch_larger_than_cases_per_call_runs_a_slice_at_a_time_with_the_same_bits():
    # the super-twisting law keeps memory and the fixed-time MSS law records diagnostics: each
    # slice has its own memory, and the results are those of the whole batch in every call
    dt = 1e-3
    twisting = C.PythonLaw(super_twisting_standard,
                           params={"b1": np.linspace(1000.0, 1400.0, 37), "b2": 5000.0, "c": 0.5, "dt": dt},
                           memory={"w": np.zeros(3)}, diagnostics=("sigma", "w"))
    mss = C.PythonLaw(mss_printed, params=dict(RECONSTRUCTED_GAINS, s1_floor=1e-3), diagnostics=("s1", "s2"))
    storm = landing.disturbances.UniformNoise(bound=0.3)
    for law in (twisting, mss):
        calls = []

        def seen(t, e, de, ref, drift, inertia, params, memory, law=law, calls=calls):
            # a slice's parameters are its own dict: its identity tells the slices apart
            calls.append((t, e.shape[0], id(params)))
            return law.function(t, e, de, ref, drift, inertia, params, memory)

        whole = landing.simulate_batch(P.MarsLander(), law.replace(cases_per_call=None), mars_x0(37), t_final=0.5,
                                       dt=dt, record_every=10, disturbance=storm, seed=3)
        for per_call, threads in ((8, 1), (9, 2), (16, 2), (36, 1)):
            sliced = landing.simulate_batch(P.MarsLander(), law.replace(function=seen, cases_per_call=per_call),
                                            mars_x0(37), t_final=0.5, dt=dt, record_every=10, disturbance=storm,
                                            seed=3, threads=threads, kernel="baseline")
            assert_same_run(whole, sliced, rtol=0)
            np.testing.assert_array_equal(sliced.final_state, whole.final_state)
            # slices of whole blocks, each through all 501 instants in time order: on one thread one
            # after another, the same size but the last; on two, two at a time, their calls alternating
            slices, current = [], {}
            for i, (t, m, slice_id) in enumerate(calls):
                if t == 0.0:
                    current[slice_id] = []
                    slices.append(current[slice_id])
                current[slice_id].append((i, t, m))
            sizes = [s[0][2] for s in slices]
            for s in slices:
                assert len({m for _, _, m in s}) == 1
                np.testing.assert_allclose([t for _, t, _ in s], np.arange(501) * dt, rtol=0, atol=1e-12)
            assert sum(sizes) == 37 and len(calls) == 501 * len(sizes)
            assert all(n <= per_call for n in sizes)
            contiguous = [s[-1][0] - s[0][0] == 500 for s in slices]
            if threads == 1:
                assert all(contiguous) and len(set(sizes[:-1])) <= 1
            else:
                first, second = slices[0], slices[1]
                assert [i for i, _, _ in first[:3]] == [0, 2, 4] and [i for i, _, _ in second[:3]] == [1, 3, 5]
            calls.clear()


def test_a_batch_that_fits_one_call_runs_as_two_alternating_slices_on_two_threads():
    # on two threads, one slice's call overlaps the other's plant periods: the same bits as one
    # thread's single slice, half the cases per call
    seen = []

    def law(t, e, de, ref, drift, inertia, params, memory):
        seen.append(e.shape[0])
        return pd_sat(t, e, de, ref, drift, inertia, params, memory)

    rng = np.random.default_rng(9)
    x0 = np.zeros((1200, 6))
    x0[:, :3] = rng.normal(0.0, 1.0, (1200, 3))
    python = C.PythonLaw(law, params={"lambda": 0.3, "k": 0.02, "phi": 0.5}, diagnostics=("s",))
    runs = {}
    for threads in (1, 2):
        seen.clear()
        runs[threads] = landing.simulate_batch(P.DoubleIntegrator(), python, x0, t_final=1.0, dt=0.05,
                                               threads=threads, record_every=1)
        assert sum(seen) == 1200 * 21
        if threads == 1:
            assert set(seen) == {1200}
        else:
            # two slices of whole blocks, within a block of each other, called in turn
            assert seen[0] + seen[1] == 1200 and abs(seen[0] - seen[1]) <= 16 and seen[2:4] == seen[:2]
    for name in ("states", "controls", "final_state"):
        np.testing.assert_array_equal(getattr(runs[2], name), getattr(runs[1], name))
    np.testing.assert_array_equal(runs[2].diagnostics["s"], runs[1].diagnostics["s"])
    builtin = landing.simulate_batch(P.DoubleIntegrator(), C.PDSlidingMode(lambda_=0.3, k=0.02, switch="sat",
                                                                           boundary_layer=0.5),
                                     x0, t_final=1.0, dt=0.05, threads=2, record_every=1)
    np.testing.assert_array_equal(runs[2].states, builtin.states)


def test_an_exception_in_a_slice_names_the_slice_s_cases():
    def bad(t, e, de, ref, drift, inertia, params, memory):
        if e.shape[0] < 8:  # the last slice: cases 16 to 20
            raise ValueError("boom")
        return -e

    with pytest.raises(UserFunctionError, match=r"at t = 0 s on cases 116\.\.120 raised ValueError: boom"):
        landing.simulate_batch(P.DoubleIntegrator(), C.PythonLaw(bad, cases_per_call=8), np.ones((21, 6)),
                               t_final=1.0, dt=0.1, first_case=100)


def test_cases_per_call_is_a_positive_count():
    with pytest.raises(landing.errors.ParameterError, match="cases_per_call = 0 violates"):
        C.PythonLaw(pd_sat, cases_per_call=0)
    with pytest.raises(landing.errors.ParameterTypeError, match="cases_per_call must be an integer"):
        C.PythonLaw(pd_sat, cases_per_call=1.5)
    assert C.PythonLaw(pd_sat).cases_per_call == C.DEFAULT_CASES_PER_CALL


def test_inputs_a_law_keeps_are_never_overwritten():
    # the engine reuses its input arrays from one instant to the next, unless the function kept
    # one: then the kept array must still hold its own instant's values
    kept = []

    def law(t, e, de, ref, drift, inertia, params, memory):
        kept.append(e)  # the array itself, not a copy
        return -e - de

    x0 = np.array([[1.0, -2.0, 0.5, 0.0, 0.0, 0.0], [0.0, 1.0, 2.0, 0.5, 0.0, 0.0]])
    res = landing.simulate_batch(P.DoubleIntegrator(), C.PythonLaw(law), x0, t_final=1.0, dt=0.1)
    # e = q - q_ref, q_ref = 0: each kept array is its instant's positions, as recorded
    np.testing.assert_array_equal(np.stack(kept), res.states[:, :, :3].transpose(1, 0, 2))


def test_the_inputs_are_read_only():
    # made read-only once by the engine, on both tracks of two threads, whether kept or reused
    flags = []

    def law(t, e, de, ref, drift, inertia, params, memory):
        flags.append([a.flags.writeable for a in (e, de, ref.position, ref.velocity, ref.acceleration, drift,
                                                  inertia)])
        if len(flags) % 3 == 0:
            law.kept = e  # a kept array makes the engine hand a fresh one next time
        return np.zeros_like(e)

    landing.simulate_batch(P.MarsLander(), C.PythonLaw(law, cases_per_call=16), mars_x0(40), t_final=0.01,
                           dt=1e-3, record_every=0, threads=2)
    assert len(flags) > 20 and not any(any(f) for f in flags), flags


@pytest.mark.parametrize("keep", [False, True], ids=["arrays-reused", "arrays-kept"])
def test_cases_that_have_stopped_keep_their_last_inputs(keep):
    # the engine writes each instant's inputs of the cases still running into the arrays it
    # handed over at the instant before; the cases that have stopped must keep their last
    # inputs there, also when the function kept those arrays and the engine had to make new ones
    n, stop = 64, 0.3
    seen, kept = [], []

    def law(t, e, de, ref, drift, inertia, params, memory):
        seen.append((t, e.copy()))
        if keep:
            kept.append(e)
        u = -e - 2.0 * de
        if t >= stop:
            u[:32] = np.nan  # whole blocks of lanes stop at every level
        return u

    x0 = np.zeros((n, 6))
    x0[:, :3] = np.linspace(1.0, 2.0, n)[:, None] * np.array([1.0, -2.0, 0.5])
    with pytest.warns(DivergenceWarning):
        res = landing.simulate_batch(P.DoubleIntegrator(), C.PythonLaw(law), x0, t_final=1.0, dt=0.01,
                                     threads=1)
    assert res.metrics["diverged"].tolist() == [True] * 32 + [False] * 32
    times = np.array([t for t, _ in seen])
    e = np.stack([v for _, v in seen])
    assert len(times) == 101 and np.array_equal(times, np.arange(101) * 0.01)
    first = int(np.argmax(times >= stop))
    # before the stop every case moves; the period of the instant that commanded NaN is the
    # stopped cases' last (it writes no inputs), so from then on they see that instant's inputs,
    # while the others go on moving
    assert (np.diff(e[: first + 1, :32], axis=0) != 0).any(axis=(1, 2)).all()
    np.testing.assert_array_equal(e[first:, :32], np.broadcast_to(e[first, :32], e[first:, :32].shape))
    assert (np.diff(e[first:, 32:], axis=0) != 0).any(axis=(1, 2)).all()
    # and those are the positions at that instant (q_ref = 0) of a run in which nothing stops
    # (the stopped run records NaN from its stop on)
    clean = landing.simulate_batch(P.DoubleIntegrator(), C.PythonLaw(lambda t, e, de, *rest: -e - 2.0 * de), x0,
                                   t_final=1.0, dt=0.01)
    np.testing.assert_array_equal(e[first, :32], clean.states[:32, first, :3])


def test_a_time_dependent_disturbance_sees_the_true_time():
    # OpenLoop stepped one period at a time restarts every call at t = 0; a PythonLaw does not
    dist = landing.disturbances.Sinusoid(amplitude=(1.0, 0.0, 0.0), omega=3.0)
    zero = C.PythonLaw(lambda t, e, de, ref, drift, inertia, params, memory: np.zeros_like(e))
    a = landing.simulate_batch(P.DoubleIntegrator(), C.OpenLoop(), np.zeros((2, 6)), t_final=3.0, dt=0.01,
                               disturbance=dist)
    b = landing.simulate_batch(P.DoubleIntegrator(), zero, np.zeros((2, 6)), t_final=3.0, dt=0.01,
                               disturbance=dist)
    np.testing.assert_array_equal(b.states, a.states)


def test_a_numba_jitted_law_runs():
    numba = pytest.importorskip("numba")

    @numba.njit(cache=False)
    def pd(t, e, de, ref, drift, inertia, params, memory):
        return -drift - 2.0 * e - 3.0 * de

    def law(t, e, de, ref, drift, inertia, params, memory):
        return pd(t, e, de, ref.acceleration, drift, inertia, None, None)

    plain = C.PythonLaw(lambda t, e, de, ref, drift, inertia, params, memory: -drift - 2.0 * e - 3.0 * de)
    x0 = np.tile([1.0, 2.0, -1.0, 0.0, 0.0, 0.0], (5, 1))
    a = landing.simulate_batch(P.DoubleIntegrator(), plain, x0, t_final=2.0, dt=0.01)
    b = landing.simulate_batch(P.DoubleIntegrator(), C.PythonLaw(law), x0, t_final=2.0, dt=0.01)
    np.testing.assert_array_equal(b.states, a.states)


def test_a_jax_jitted_law_runs():
    """A JAX-jitted PD law gives the numpy law's trajectory (XLA may fuse the sum's products,
    so to rounding, not bit for bit), and that trajectory decays as the closed form of
    e'' = -2 e - 3 e' does, e(t) = e0 (2 exp(-t) - exp(-2 t)), to the zero-order hold's error
    at dt = 0.01 (under 1 %)."""
    jax = pytest.importorskip("jax")
    jax.config.update("jax_enable_x64", True)

    @jax.jit
    def pd(e, de, drift):
        return -drift - 2.0 * e - 3.0 * de

    law = C.PythonLaw(lambda t, e, de, ref, drift, inertia, params, memory: pd(e, de, drift))
    plain = C.PythonLaw(lambda t, e, de, ref, drift, inertia, params, memory: -drift - 2.0 * e - 3.0 * de)
    x0 = np.tile([1.0, 2.0, -1.0, 0.0, 0.0, 0.0], (5, 1))
    res = landing.simulate_batch(P.DoubleIntegrator(), law, x0, t_final=2.0, dt=0.01)
    ref = landing.simulate_batch(P.DoubleIntegrator(), plain, x0, t_final=2.0, dt=0.01)
    np.testing.assert_allclose(res.states, ref.states, rtol=0, atol=1e-13)
    closed = x0[:, :3] * (2.0 * np.exp(-2.0) - np.exp(-4.0))
    np.testing.assert_allclose(res.final_state[:, :3], closed, rtol=0.01)


# --- bad input and faults ---------------------------------------------------------------------

def run_law(function, **kw):
    return landing.simulate_batch(P.DoubleIntegrator(), C.PythonLaw(function, **kw), np.ones((4, 6)),
                                  t_final=1.0, dt=0.1, first_case=10)


def test_an_exception_in_the_function_arrives_chained_with_the_instant_and_the_cases():
    def bad(t, e, de, ref, drift, inertia, params, memory):
        if t > 0.25:
            raise ZeroDivisionError("boom")
        return -e

    with pytest.raises(UserFunctionError) as info:
        run_law(bad)
    msg = str(info.value)
    assert "bad" in msg and "t = 0.3 s" in msg and "cases 10..13" in msg and "ZeroDivisionError: boom" in msg
    assert isinstance(info.value.__cause__, ZeroDivisionError)


@pytest.mark.parametrize(("returned", "expected"), [
    (lambda e: e[:, :2], "shape (4, 2); expected (4, 3)"),
    (lambda e: e.astype(int), "dtype int64"),
    (lambda e: e.tolist(), "of type list"),
    (lambda e: 3.0, "of type float"),
    (lambda e: (e, None, None, None), "a tuple of 4 values"),
])
def test_a_wrong_return_is_refused_naming_the_function_and_what_was_expected(returned, expected):
    def wrong(t, e, de, ref, drift, inertia, params, memory):
        return returned(e)

    with pytest.raises(UserFunctionError, match="wrong") as info:
        run_law(wrong)
    assert expected in str(info.value)


def test_declared_diagnostics_must_be_returned():
    with pytest.raises(UserFunctionError, match="declares"):
        run_law(lambda t, e, de, ref, drift, inertia, params, memory: -e, diagnostics=("s",))


def test_a_memory_that_changes_shape_is_refused():
    def grows(t, e, de, ref, drift, inertia, params, memory):
        return -e, {"w": np.zeros((4, 4))}

    with pytest.raises(UserFunctionError, match=r"memory\['w'\] of shape \(4, 4\); expected \(4, 3\)"):
        run_law(grows, memory={"w": np.zeros(3)})


def test_a_non_finite_command_flags_the_case_and_spares_the_others():
    def nan_for_case_2(t, e, de, ref, drift, inertia, params, memory):
        u = -e - de
        if t >= 0.5:
            u[2] = np.nan
        return u

    with pytest.warns(DivergenceWarning):
        res = run_law(nan_for_case_2)
    assert res.metrics["diverged"].tolist() == [False, False, True, False]
    assert landing.DIVERGENCE_REASONS[res.metrics["diverged_reason"][2]] == "non_finite_command"
    assert res.metrics["diverged_time"][2] == pytest.approx(0.5)
    assert np.isfinite(res.metrics["final_position_error"][[0, 1, 3]]).all()


def test_bad_configuration_is_refused_at_construction():
    with pytest.raises(landing.errors.ParameterTypeError, match="callable"):
        C.PythonLaw(3.0)
    with pytest.raises(landing.errors.ParameterTypeError, match=r"params\['k'\]"):
        C.PythonLaw(lambda *a: a[1], params={"k": "fast"})
    with pytest.raises(landing.errors.ParameterError, match="'axes' or 'scalar'"):
        C.PythonLaw(lambda *a: a[1], diagnostics={"s": "vector"})
    with pytest.raises(UserFunctionError, match=r"params\['k'\] has shape \(5,\)"):
        run_law(lambda t, e, *a: -e, params={"k": np.ones(5)})


def test_replace_changes_a_parameter():
    law = C.PythonLaw(pd_sat, params={"lambda": 0.3, "k": 0.02, "phi": 0.5})
    assert float(law.replace(k=0.04).params["k"]) == 0.04 and float(law.params["k"]) == 0.02
    with pytest.raises(landing.errors.ParameterError, match="neither a field"):
        law.replace(kd=1.0)


def test_ctrl_c_stops_a_python_law_run_within_a_second():
    def slow(t, e, de, ref, drift, inertia, params, memory):
        time.sleep(0.01)
        return -e

    timer = threading.Timer(0.5, lambda: signal.raise_signal(signal.SIGINT))
    start = time.monotonic()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        landing.simulate_batch(P.DoubleIntegrator(), C.PythonLaw(slow), np.ones((2, 6)), t_final=100.0, dt=0.1)
    assert time.monotonic() - start < 1.5


def test_the_readme_block_runs_as_a_file():
    import re

    from _cases import ROOT

    readme = (ROOT / "README.md").read_text()
    section = readme[readme.index("## Your own law, in Python"):]
    code = re.search(r"```python\n(.*?)```", section, re.S).group(1)
    ns: dict = {}
    exec(compile(code, "README.md", "exec"), ns)
    # e'' = -e - 2 e' from e = e' = 1: critically damped, e(t) = (1 + 2 t) e^-t
    np.testing.assert_allclose(ns["res"].final_state[:, 0], 21 * np.exp(-10.0), rtol=0.05)


@pytest.mark.parametrize("fidelity", ["simplified", "flexible"])
def test_the_pd_sliding_law_agrees_bit_for_bit_on_the_tethered_satellite(fidelity):
    plant = P.TetheredSatellite(fidelity=fidelity, nodes=4) if fidelity == "flexible" else \
        P.TetheredSatellite(fidelity=fidelity)
    builtin = C.PDSlidingMode(lambda_=0.05, k=1e-4, switch="sat", boundary_layer=0.01)
    python = C.PythonLaw(pd_sat, params={"lambda": 0.05, "k": 1e-4, "phi": 0.01}, diagnostics=("s",))
    x0 = np.stack([plant.initial_state(phi=np.radians(a), theta=np.radians(-a)) for a in (0.5, 1.0, 2.0)])
    dt = 0.05
    kw = dict(t_final=5.0, dt=dt, substeps=plant.substeps_for(dt) if fidelity == "flexible" else 1)
    a, b = run_both(plant, builtin, python, x0, **kw)
    assert not a.metrics["diverged"].any()
    assert_same_run(a, b, rtol=0)


_MALLOC_PROBE = """
import ctypes, sys
import numpy as np
import landing
from landing import controllers as C, plants as P


class MallInfo2(ctypes.Structure):
    _fields_ = [(name, ctypes.c_size_t) for name in
                ("arena", "ordblks", "smblks", "hblks", "hblkhd", "usmblks", "fsmblks", "uordblks",
                 "fordblks", "keepcost")]


libc = ctypes.CDLL(None)
libc.malloc.restype = ctypes.c_void_p
libc.free.argtypes = [ctypes.c_void_p]
libc.mallinfo2.restype = MallInfo2


def mapped(size):
    # whether malloc serves a block of `size` bytes with a mapping of its own
    before = libc.mallinfo2().hblks
    block = libc.malloc(size)
    after = libc.mallinfo2().hblks
    libc.free(block)
    return after > before


# freeing a mapped block raises the threshold to its size: the probe before the run is smaller
first = mapped(1 << 20)
law = C.PythonLaw(lambda t, e, de, ref, drift, inertia, params, memory: np.zeros_like(e))
landing.simulate_batch(P.DoubleIntegrator(), law, np.ones((4, 6)), t_final=0.01, dt=1e-3, record_every=0)
print(first, mapped(4 << 20))
"""


@pytest.mark.skipif(platform.libc_ver()[0] != "glibc", reason="glibc's dynamic mmap threshold")
def test_a_python_law_run_raises_the_c_heap_s_thresholds():
    """Before a Python callee's first run the binding frees one 8 MB block, so that glibc's
    dynamic mmap and trim thresholds are raised at once instead of after the process first
    frees a large array: until then numpy's temporaries had their pages returned and faulted
    in again at every call (BENCHMARKS.md). Seen through ``mallinfo2``, in a fresh process: a
    1 MB block is mapped of its own before the run (which raises the threshold to 1 MB), and a
    4 MB block comes from the heap after it."""
    # glibc fixes its thresholds when one is set in the environment (Dask's client sets
    # MALLOC_TRIM_THRESHOLD_ in this process's): the probe runs with glibc's defaults
    env = {k: v for k, v in os.environ.items() if not k.startswith("MALLOC_")}
    out = subprocess.run([sys.executable, "-c", _MALLOC_PROBE], capture_output=True, text=True, check=True, env=env)
    before, after = out.stdout.split()
    if before != "True":
        pytest.skip("the C heap's thresholds were already raised when the probe began")
    assert after == "False", "a 4 MB block is still mapped of its own after a Python law's run"

