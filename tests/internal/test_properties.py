"""Property tests of the public API's input handling: every entry point, driven with generated
shapes, dtypes (float, int, bool, complex, object, str), NaN and Inf, zero, negative and huge
sizes and unknown names, gives a valid result or refuses the input with a ParameterError,
ParameterTypeError or MemoryError whose message names the argument. Anything else (an
IndexError, an OverflowError, a PanicException, a hang) fails the test. Then one regression
test per finding of the probe that motivated this (docs/parameters.md, "Limits").

Horizons are a few control periods and example counts are bounded, so the file runs in
seconds.
"""

from __future__ import annotations

import dataclasses
import math
import numbers
import os
import subprocess
import sys
import textwrap
import tracemalloc
from typing import Any, Callable

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

import landing
from _cases import RECONSTRUCTED_GAINS, ROOT
from landing import (
    controllers,
    dispersions,
    disturbances,
    fuzzy,
    gravity,
    plants,
    reference,
    scenarios,
    theory,
)
from landing._internal.limits import LIMITS, available_memory, require_memory
from landing.errors import LandingError, ParameterError, ParameterTypeError, SimulationError

#: Examples per property (LANDING_PROPERTY_EXAMPLES=2000 for a long search).
EXAMPLES = int(os.environ.get("LANDING_PROPERTY_EXAMPLES", "100"))
FAST = settings(
    max_examples=EXAMPLES,
    deadline=2000,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much],
    database=None,
)

REFUSALS = (ParameterError, ParameterTypeError, MemoryError)

# --------------------------------------------------------------------------- strategies

FLOAT = st.floats(allow_nan=True, allow_infinity=True, width=64)
INTS = st.one_of(st.integers(-10, 10), st.integers(-(2**70), 2**70))
SCALARS = st.one_of(
    FLOAT,
    INTS,
    st.booleans(),
    st.complex_numbers(max_magnitude=1e3, allow_nan=False),
    st.text(max_size=3),
    st.none(),
    st.just(np.float64(np.nan)),
    st.just(np.int64(3)),
    st.just(np.bool_(True)),
    st.just(np.complex128(1 + 1j)),
)
DTYPES = st.sampled_from([np.float64, np.float32, np.int64, np.bool_, np.complex128, object, "U3"])


@st.composite
def arrays(draw: Any, max_dims: int = 3, max_side: int = 5) -> np.ndarray:
    """Arrays of every dtype, with zero-length axes, NaN and Inf among the floats."""
    dtype = draw(DTYPES)
    shape = draw(hnp.array_shapes(min_dims=0, max_dims=max_dims, min_side=0, max_side=max_side))
    if dtype is object:
        return np.array(draw(st.lists(st.one_of(FLOAT, st.text(max_size=2), st.none()),
                                      min_size=int(np.prod(shape)), max_size=int(np.prod(shape)))),
                        dtype=object).reshape(shape)
    if dtype == "U3":
        return draw(hnp.arrays(np.dtype("U3"), shape, elements=st.text(alphabet="ab1.e-", max_size=3)))
    if dtype in (np.float64, np.float32):
        elements = st.floats(allow_nan=True, allow_infinity=True, width=32 if dtype is np.float32 else 64)
    elif dtype is np.int64:
        elements = st.integers(-1000, 1000)
    elif dtype is np.complex128:
        elements = st.complex_numbers(max_magnitude=1e3, allow_nan=False)
    else:
        elements = st.booleans()
    return draw(hnp.arrays(dtype, shape, elements=elements))


ANY = st.one_of(SCALARS, arrays(), st.lists(FLOAT, max_size=4))


def not_huge_but_valid(n: Any, limit: int) -> bool:
    """False for a count between ``limit`` and the cap: valid, but slow to run (and, within
    memory, large to allocate); the tests keep to small valid counts and to refused ones."""
    if isinstance(n, (bool, np.bool_)) or not isinstance(n, (int, np.integer)):
        return True
    return not limit < n <= LIMITS["max_cases"]


def valid_or_refused(call: Callable[[], Any], *names: str) -> Any:
    """The result of ``call()``, or None if it refused its input with one of the library's
    errors naming one of ``names``; any other exception propagates and fails the test."""
    try:
        return call()
    except REFUSALS as exc:
        message = str(exc)
        assert any(n in message for n in names), f"{type(exc).__name__} does not name {names}: {message}"
        assert isinstance(exc, (LandingError, MemoryError))
        return None


# --------------------------------------------------------------------------- simulate_batch

PLANT = plants.DoubleIntegrator()
LAW = controllers.PDSlidingMode(lambda_=1.0, k=1.0)
X0 = np.array([[1.0, -2.0, 0.5, 0.0, 0.0, 0.0]])
TINY = dict(t_final=0.03, dt=0.01)


def small_int(big: list[int]) -> st.SearchStrategy:
    return st.one_of(st.integers(-3, 6), st.sampled_from(big), SCALARS)


RUN_ARGUMENTS = {
    "t_final": st.one_of(FLOAT, SCALARS),
    "dt": st.one_of(FLOAT, SCALARS),
    "substeps": small_int([LIMITS["max_substeps"], LIMITS["max_substeps"] + 1, 10**9, 2**63, 2**70]),
    "record_every": small_int([2**40, 2**63, 2**64, 2**70]),
    "seed": small_int([2**64 - 1, 2**64, 2**70, -1, -(2**63)]),
    "first_case": small_int([2**63 - 1, 2**63, 2**70, -1]),
    "threads": small_int([LIMITS["max_threads"] + 1, 10**9, 2**63, 2**70]),
    "integrator": st.one_of(st.sampled_from(["rk4", "euler", "rk45", "", "RK4"]), SCALARS),
    "kernel": st.one_of(st.sampled_from(["baseline", "avx3", ""]), SCALARS),
    "settle_tolerance": st.one_of(FLOAT, SCALARS),
    "chatter_cutoff": st.one_of(FLOAT, SCALARS),
    "disturbance": st.one_of(SCALARS, st.lists(SCALARS, max_size=2), arrays()),
    "reference": st.one_of(SCALARS, st.dictionaries(st.text(max_size=3), FLOAT, max_size=2)),
}


@FAST
@given(data=st.data(), name=st.sampled_from(sorted(RUN_ARGUMENTS)))
def test_simulate_batch_keyword_arguments(data: Any, name: str) -> None:
    value = data.draw(RUN_ARGUMENTS[name], label=name)
    kw: dict[str, Any] = dict(TINY)
    kw[name] = value
    if name in ("t_final", "dt") and isinstance(value, (int, float)) and not isinstance(value, bool):
        # keep valid horizons tiny: at most a few hundred control periods
        other = kw["dt"] if name == "t_final" else kw["t_final"]
        if math.isfinite(value) and value > 0:
            ratio = value / other if name == "t_final" else other / value
            assume(ratio < 300)
    res = valid_or_refused(lambda: landing.simulate_batch(PLANT, LAW, X0, **kw), name)
    if res is not None:
        assert res.final_state.shape == (1, 6)


@FAST
@given(x0=st.one_of(arrays(max_dims=3, max_side=7), SCALARS, st.lists(FLOAT, max_size=7)))
def test_simulate_batch_initial_states(x0: Any) -> None:
    res = valid_or_refused(lambda: landing.simulate_batch(PLANT, LAW, x0, **TINY), "x0")
    if res is not None:
        x = np.asarray(x0)
        assert x.dtype.kind in "iuf" and x.ndim == 2 and x.shape[1] == 6 and x.shape[0] >= 1
        assert np.isfinite(x).all()
        assert res.final_state.shape == x.shape


@FAST
@given(x0=st.one_of(arrays(max_dims=2, max_side=7), SCALARS))
def test_simulate_one_state(x0: Any) -> None:
    res = valid_or_refused(lambda: landing.simulate(PLANT, LAW, x0, **TINY), "x0")
    if res is not None:
        assert res.final_state.shape == (6,)


@FAST
@given(plant=SCALARS, controller=SCALARS)
def test_simulate_batch_needs_configuration_objects(plant: Any, controller: Any) -> None:
    with pytest.raises(ParameterTypeError, match="plant|controller"):
        landing.simulate_batch(plant, controller, X0, **TINY)


# --------------------------------------------------------------------------- configuration classes

def _required(cls: type) -> dict[str, Any]:
    """Valid values for the fields a class has no default for."""
    if cls is controllers.FixedTimeMSS:
        return dict(RECONSTRUCTED_GAINS)
    if cls is controllers.PDSlidingMode:
        return dict(lambda_=1.0, k=1.0)
    if cls in (controllers.FastTerminalSMC, controllers.FuzzyFastTerminalSMC):
        extra = dict(n=1.0, m=1.0) if cls is controllers.FuzzyFastTerminalSMC else {}
        return dict(alpha=1.0, beta=1.0, p=3.0, q=5.0, k=1.0, **extra)
    if cls is controllers.IntegralExponentialReaching:
        return dict(c1=1.0, c2=1.0, k=1.0, epsilon=0.1)
    if cls is controllers.FuzzyVariableRate:
        return dict(c1=1.0, c2=1.0, k=1.0, ke=1.0, kec=1.0, ku=1.0)
    if cls is disturbances.Constant:
        return dict(value=1.0)
    if cls is disturbances.Sinusoid:
        return dict(amplitude=1.0, omega=1.0)
    if cls is disturbances.UniformNoise:
        return dict(bound=1.0)
    if cls is disturbances.CommandNoise:
        return dict(fraction=0.01)
    if cls is dispersions.Normal:
        return dict(mean=[0.0, 1.0], std=[1.0, 2.0])
    if cls is dispersions.Uniform:
        return dict(low=[0.0, 1.0], high=[1.0, 2.0])
    if cls is reference.Cubic:
        return dict(coefficients=np.zeros((3, 4)), t_end=1.0)
    return {}


CONFIGURATIONS = [
    plants.MarsLander, plants.DoubleIntegrator, plants.SmallBody, plants.TetheredSatellite,
    controllers.FixedTimeMSS, controllers.SuperTwisting, controllers.OpenLoop, controllers.PDSlidingMode,
    controllers.FastTerminalSMC, controllers.FuzzyFastTerminalSMC, controllers.IntegralExponentialReaching,
    controllers.FuzzyVariableRate, controllers.NTSMC, controllers.FixedTimeNTSMC,
    gravity.PointMass, gravity.TwoPointMass, gravity.Harmonic2,
    reference.Constant, reference.Cubic,
    disturbances.Constant, disturbances.Sinusoid, disturbances.UniformNoise, disturbances.CommandNoise,
    dispersions.Normal, dispersions.Uniform,
]
FIELDS = [(cls, f.name) for cls in CONFIGURATIONS for f in dataclasses.fields(cls) if f.init]


def test_every_configuration_class_builds_with_the_test_values() -> None:
    # the property below perturbs one field of these; each must be valid as it stands
    for cls in CONFIGURATIONS:
        if cls is gravity.PointMass:
            cls(mu=1.0)
        else:
            cls(**_required(cls))


@settings(FAST, max_examples=2 * EXAMPLES)
@given(data=st.data(), which=st.sampled_from(FIELDS))
def test_configuration_fields(data: Any, which: tuple[type, str]) -> None:
    cls, name = which
    value = data.draw(st.one_of(ANY, st.sampled_from(["unknown", "exact", "flexible"])), label=name)
    kw = dict(_required(cls), **({"mu": 1.0} if cls is gravity.PointMass else {}))
    kw[name] = value
    # `lambda_` is the core's `lambda` (a Python keyword)
    valid_or_refused(lambda: cls(**kw), name.rstrip("_"))


@FAST
@given(cls=st.sampled_from(CONFIGURATIONS), key=st.text(min_size=1, max_size=6))
def test_unknown_parameters_are_refused(cls: type, key: str) -> None:
    assume(key not in {f.name for f in dataclasses.fields(cls)})
    kw = dict(_required(cls), **({"mu": 1.0} if cls is gravity.PointMass else {}))
    with pytest.raises(TypeError):  # the dataclass refuses an unknown keyword
        cls(**kw, **{key: 1.0})


# --------------------------------------------------------------------------- evaluators

FIELDS_TO_EVALUATE = [gravity.PointMass(1.0), gravity.TwoPointMass(), gravity.Harmonic2()]


@FAST
@given(field=st.sampled_from(FIELDS_TO_EVALUATE), r=st.one_of(arrays(max_side=4), SCALARS),
       potential=st.booleans())
def test_gravity_evaluation(field: gravity.Gravity, r: Any, potential: bool) -> None:
    call = field.potential if potential else field.acceleration
    out = valid_or_refused(lambda: call(r), "r")
    if out is not None:
        x = np.asarray(r, dtype=float)
        assert np.isfinite(x).all() and x.shape[-1] == 3
        assert out.shape == (x.shape[:-1] if potential else x.shape)


@FAST
@given(t=st.one_of(arrays(max_dims=2), SCALARS), axes=st.one_of(st.integers(-2, 5), SCALARS))
def test_reference_evaluation(t: Any, axes: Any) -> None:
    ref = reference.Cubic.from_boundary([0, 0, 0], [0, 0, 0], [1, 2, 3], [0, 0, 0], 5.0)
    out = valid_or_refused(lambda: ref.evaluate(t, axes), "t", "axes")
    if out is not None:
        assert all(np.isfinite(a).all() for a in out)


@FAST
@given(args=st.lists(st.one_of(ANY, st.lists(FLOAT, min_size=3, max_size=3)), min_size=5, max_size=5))
def test_cubic_from_boundary(args: list[Any]) -> None:
    valid_or_refused(lambda: reference.Cubic.from_boundary(*args), "p0", "v0", "pT", "vT", "T")


SYSTEM = fuzzy.variable_rate_system(resolution=51)


@FAST
@given(inputs=st.one_of(arrays(max_dims=3, max_side=4), SCALARS))
def test_mamdani_evaluation(inputs: Any) -> None:
    out = valid_or_refused(lambda: SYSTEM.evaluate(inputs), "inputs")
    if out is not None:
        assert np.isfinite(out).all() and out.ndim == 1


@FAST
@given(resolution=st.one_of(st.integers(-5, 5), st.sampled_from(
    [LIMITS["max_fuzzy_resolution"] + 1, 10**12, 2**63, 2**70]), SCALARS))
def test_fuzzy_resolution(resolution: Any) -> None:
    out = valid_or_refused(lambda: fuzzy.variable_rate_system(resolution), "resolution")
    if out is not None:
        assert out.resolution == resolution


@FAST
@given(universe=st.one_of(st.tuples(ANY, ANY), SCALARS), set_=st.one_of(
    st.tuples(st.sampled_from(["triangle", "trapezoid", "gauss"]), FLOAT, FLOAT, FLOAT), SCALARS))
def test_fuzzy_variables(universe: Any, set_: Any) -> None:
    def build() -> Any:
        v = fuzzy.Variable(universe, {"A": set_, "B": ("triangle", 0.0, 0.5, 1.0)})
        return fuzzy.Mamdani([v], v, [(("A",), "B"), (("B",), "A")])
    valid_or_refused(build, "universe", "sets", "input", "output")


@FAST
@given(n=st.one_of(st.integers(-3, 5), st.sampled_from([2**40, 2**62, 2**64, 2**70]), SCALARS),
       seed=st.one_of(st.integers(-2, 3), st.sampled_from([2**64 - 1, 2**64, -1]), SCALARS),
       first_case=st.one_of(st.integers(-2, 3), st.sampled_from([2**64 - 1, 2**64]), SCALARS))
def test_dispersion_sample(n: Any, seed: Any, first_case: Any) -> None:
    assume(not_huge_but_valid(n, 10**5))
    d = dispersions.Normal(mean=[0.0, 1.0, 2.0], std=1.0)
    out = valid_or_refused(lambda: d.sample(n, seed=seed, first_case=first_case), "n", "seed", "first_case")
    if out is not None:
        assert out.shape == (n, 3)


@FAST
@given(states=st.one_of(arrays(max_dims=3, max_side=5), SCALARS),
       angles=st.lists(st.one_of(FLOAT, arrays(max_dims=1, max_side=3)), min_size=4, max_size=4))
def test_tether_coordinate_helpers(states: Any, angles: list[Any]) -> None:
    plant = plants.TetheredSatellite(nodes=2)
    valid_or_refused(lambda: plant.coordinates(states), "states")
    x = valid_or_refused(lambda: plant.initial_state(*angles), "phi", "theta", "phi_dot", "theta_dot", "coordinates")
    if x is not None:
        assert np.isfinite(x).all() and x.shape[-1] == plant.state_dim


# --------------------------------------------------------------------------- theory

SCALAR_THEORY = {
    theory.fixed_time_bound: ("c1", "e1", "c2", "e2"),
    theory.practical_time_bound: ("c1", "e1", "c2", "e2", "theta"),
    theory.practical_radius: ("c1", "e1", "c2", "e2", "d_max", "theta"),
    theory.min_final_time: ("r0", "v0", "a_max", "g"),
    theory.min_time_to_rest: ("r0", "v0", "a_max", "g"),
    theory.fntsmc_ts_printed: ("c_v", "alpha_s", "beta_s"),
    theory.fntsmc_td_printed: ("k1", "p1", "k2", "p2", "d"),
    theory.chattering_band: ("c1", "e1", "dt"),
}


@pytest.mark.filterwarnings("ignore:overflow encountered:RuntimeWarning")  # huge valid inputs give inf
@settings(FAST, max_examples=2 * EXAMPLES)
@given(data=st.data(), fn=st.sampled_from(sorted(SCALAR_THEORY, key=lambda f: f.__name__)))
def test_theory_formulas(data: Any, fn: Callable[..., Any]) -> None:
    names = SCALAR_THEORY[fn]
    args = [data.draw(st.one_of(st.floats(-3, 3), ANY), label=n) for n in names]
    valid_or_refused(lambda: fn(*args), *names)


@FAST
@given(t=st.one_of(arrays(max_dims=2), SCALARS), signal=st.one_of(arrays(max_dims=4), SCALARS),
       tol=st.one_of(arrays(max_dims=1), SCALARS))
def test_theory_time_helpers(t: Any, signal: Any, tol: Any) -> None:
    for fn in (theory.entry_time, theory.settle_time):
        valid_or_refused(lambda fn=fn: fn(t, signal, tol), "t", "signal", "tol")


@FAST
@given(ap_max=ANY, theta1=SCALARS, tol=ANY, d_max=ANY, axes=st.one_of(st.integers(-1, 4), SCALARS))
def test_theory_bounds_of_laws(ap_max: Any, theta1: Any, tol: Any, d_max: Any, axes: Any) -> None:
    law = controllers.FixedTimeMSS(**RECONSTRUCTED_GAINS)
    valid_or_refused(lambda: theory.mss_bounds(law, ap_max, theta1), "ap_max", "theta1")
    valid_or_refused(lambda: theory.fntsmc_bounds(controllers.FixedTimeNTSMC(), tol, d_max=d_max, axes=axes),
                     "tol", "d_max", "axes")
    valid_or_refused(lambda: theory.disturbance_bound(None, axes), "axes")


@settings(FAST, max_examples=max(1, EXAMPLES // 2))
@given(s0=st.one_of(arrays(max_dims=2, max_side=3), SCALARS), dt=st.one_of(st.none(), SCALARS),
       tol=SCALARS, axis=st.one_of(st.integers(-2, 3), SCALARS))
def test_theory_checks_refuse_bad_input(s0: Any, dt: Any, tol: Any, axis: Any) -> None:
    # only refusals are exercised here (a valid check simulates for seconds): values that
    # would be valid are replaced by an invalid tolerance
    if isinstance(tol, numbers.Real) and not isinstance(tol, (bool, np.bool_)) and math.isfinite(tol) and tol > 0:
        tol = -1.0
    with pytest.raises(REFUSALS) as info:
        theory.check_fixed_time_bound(0.9, 0.9, 0.5, 1.1, s0, dt=dt, tol=tol)
    assert any(n in str(info.value) for n in ("s0", "dt", "tol"))
    with pytest.raises(REFUSALS) as info:
        theory.check_fntsmc_bound(controllers.FixedTimeNTSMC(), s0, axis=axis, tol=tol, dt=dt)
    assert any(n in str(info.value) for n in ("pairs", "axis", "tol", "dt"))


# --------------------------------------------------------------------------- scenarios and campaigns

def tiny_campaign() -> scenarios.Scenario:
    return scenarios.mars_monte_carlo().replace(t_final=0.003, record_every=1)


CAMPAIGN = tiny_campaign()


@FAST
@given(n=st.one_of(st.integers(-2, 4), st.sampled_from([2**33, 2**40, 2**64]), SCALARS),
       seed=st.one_of(st.integers(-1, 3), st.sampled_from([2**64, -(2**63)]), SCALARS),
       chunk_size=st.one_of(st.none(), st.integers(-1, 3), SCALARS),
       threads=st.one_of(st.none(), st.integers(-1, 2), st.just(10**6), SCALARS))
def test_monte_carlo_arguments(n: Any, seed: Any, chunk_size: Any, threads: Any) -> None:
    assume(not_huge_but_valid(n, 100))
    mc = valid_or_refused(
        lambda: landing.monte_carlo(CAMPAIGN, n, seed=seed, chunk_size=chunk_size, threads=threads,
                                    check_bounds=False, progress=False),
        "n", "seed", "chunk_size", "threads",
    )
    if mc is not None:
        assert mc.x0.shape == (n, 7)


SCENARIO_FIELDS = ["t_final", "dt", "x0", "substeps", "record_every", "integrator", "theta",
                   "settle_tolerance", "chatter_cutoff", "plant", "controller", "dispersion", "disturbance"]


@FAST
@given(field=st.sampled_from(SCENARIO_FIELDS), value=ANY)
def test_scenario_fields(field: str, value: Any) -> None:
    valid_or_refused(lambda: CAMPAIGN.replace(**{field: value}), field)


@FAST
@given(law=st.one_of(st.sampled_from(["pd", "ftsmc", "fntsmc", "exponential", "nope"]), SCALARS),
       spread=st.one_of(FLOAT, SCALARS))
def test_scenario_presets(law: Any, spread: Any) -> None:
    valid_or_refused(lambda: scenarios.seed000_tracking(law, t_final=0.03), "law")
    valid_or_refused(lambda: scenarios.seed002_landing(law, t_final=0.3), "law")
    valid_or_refused(lambda: scenarios.tether_law(law), "law")
    valid_or_refused(lambda: scenarios.tether_monte_carlo(spread, fidelity="simplified"), "spread_deg")


# --------------------------------------------------------------------------- the probe's findings


def run(**kw: Any) -> landing.SimulationResult:
    return landing.simulate_batch(kw.pop("plant", PLANT), kw.pop("controller", LAW), kw.pop("x0", X0),
                                  **{**TINY, **kw})


@pytest.mark.parametrize("kw, error, message", [
    (dict(seed=-1), ParameterError, "seed = -1 violates seed >= 0"),
    (dict(seed=True), ParameterTypeError, "seed must be an integer, got True"),
    (dict(seed=np.bool_(True)), ParameterTypeError, "seed must be an integer"),
    (dict(threads=True), ParameterTypeError, "threads must be an integer, got True"),
    (dict(threads=10**6), ParameterError, r"threads = 1000000 violates threads <= max_threads \(1024\)"),
    (dict(threads=2**70), ParameterError, "threads = .* violates threads <= max_threads"),
    (dict(substeps=10**9), ParameterError, r"substeps = 1000000000 violates substeps <= max_substeps \(10000\)"),
    (dict(substeps=2**70), ParameterError, "substeps = .* violates substeps <= max_substeps"),
    (dict(substeps=True), ParameterTypeError, "substeps must be an integer"),
    (dict(record_every=2**70), ParameterError, "record_every"),
    (dict(disturbance=1.0), ParameterTypeError, "disturbance must be a landing.disturbances component"),
    (dict(x0=X0 + 1j), ParameterTypeError, "x0 must be an array of real numbers, got complex values"),
    (dict(x0=X0.astype(bool)), ParameterTypeError, "x0 must be an array of real numbers, got bool values"),
    (dict(x0=X0.astype(object)), None, None),
    (dict(x0=X0.astype(str)), ParameterTypeError, "x0 must be an array of real numbers, got str values"),
    (dict(t_final=1 + 0j), ParameterTypeError, "t_final must be a real number"),
    (dict(dt=True), ParameterTypeError, "dt must be a real number"),
    (dict(kernel=3), ParameterTypeError, "kernel must be a string"),
])
def test_probe_findings_in_simulate_batch(kw: dict, error: Any, message: Any) -> None:
    if error is None:
        assert run(**kw).final_state.shape == (1, 6)  # an object array of floats is real
        return
    with pytest.raises(error, match=message):
        run(**kw)


def test_n_must_be_a_whole_number_of_cases() -> None:
    for n in (1.9, 2.0, True, "3", None, 1 + 0j):
        with pytest.raises(ParameterTypeError, match="n must be an integer"):
            landing.monte_carlo(CAMPAIGN, n, check_bounds=False)
    with pytest.raises(ParameterTypeError, match="n must be an integer"):
        dispersions.Normal(mean=0.0, std=1.0).sample(1.9)
    with pytest.raises(ParameterError, match="seed = -1 violates seed >= 0"):
        landing.monte_carlo(CAMPAIGN, 2, seed=-1)
    with pytest.raises(ParameterError, match="seed = -1 violates seed >= 0"):
        dispersions.Normal(mean=0.0, std=1.0).sample(2, seed=-1)
    assert landing.monte_carlo(CAMPAIGN, np.int64(2), check_bounds=False).x0.shape == (2, 7)


def test_huge_counts_are_refused_without_allocating(monkeypatch: pytest.MonkeyPatch) -> None:
    d = dispersions.Normal(mean=np.zeros(7), std=1.0)
    with pytest.raises(ParameterError, match=r"n = 1000000000000 violates n <= max_cases \(4294967296\)"):
        d.sample(10**12)
    with pytest.raises(ParameterError, match="n = .* violates n <= max_cases"):
        landing.monte_carlo(CAMPAIGN, 2**70)
    # within the cap but beyond memory (here made 1 GiB): a MemoryError stating the size and
    # what is available, raised before anything of that size is allocated
    monkeypatch.setattr(landing._internal.limits, "available_memory", lambda: 2**30)
    tracemalloc.start()
    try:
        with pytest.raises(MemoryError, match=r"needs 224 GiB \(240518168576 bytes\) but only 1 GiB"):
            d.sample(2**32)
        with pytest.raises(MemoryError, match=r"the recorded runs needs .* bytes\) but only 1 GiB"):
            landing.monte_carlo(CAMPAIGN, 2**31, check_bounds=False)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert peak < 2**20
    assert d.sample(1000).shape == (1000, 7)  # 56 kB fit
    # broadcasting makes sizes too: 10^5 x 10^5 values from two vectors
    column, row = np.zeros((10**5, 1)), np.zeros((1, 10**5))
    with pytest.raises(MemoryError, match=r"fixed_time_bound over arrays of shape \(100000, 100000\) needs"):
        theory.fixed_time_bound(column + 0.9, 0.9, row + 0.5, 1.1)
    with pytest.raises(MemoryError, match=r"initial_state: states of shape \(100000, 100000, 4\) needs"):
        plants.TetheredSatellite(fidelity="simplified").initial_state(column, row)
    with pytest.raises(MemoryError, match=r"initial_state: states of shape \(100000, 100000, 7\) needs"):
        plants.MarsLander.initial_state(np.zeros((10**5, 1, 3)), np.zeros((1, 10**5, 3)), 1000.0)


def test_the_memory_check_states_size_and_availability() -> None:
    with pytest.raises(MemoryError, match=r"a test buffer needs 2 GiB \(2147483648 bytes\) but only 1 GiB"):
        require_memory("a test buffer", 2 * 2**30, available=2**30)
    require_memory("a test buffer", 2**30, available=2**30)  # fits exactly
    free = available_memory()
    assert free is None or free > 0


def test_huge_requests_do_not_abort_or_hang_in_a_fresh_interpreter() -> None:
    # the probe's aborts and hangs, each in a subprocess: it must end promptly with the error
    code = textwrap.dedent("""
        import landing, numpy as np
        from landing import dispersions, fuzzy, plants, controllers
        for call in (
            lambda: dispersions.Normal(mean=np.zeros(7), std=1.0).sample(2**62),
            lambda: dispersions.Normal(mean=np.zeros(7), std=1.0).sample(2.0**62),
            lambda: fuzzy.variable_rate_system(10**12),
            lambda: landing.simulate_batch(plants.DoubleIntegrator(), controllers.OpenLoop(),
                                           np.zeros((1, 6)), t_final=1.0, dt=0.5, substeps=2**40),
        ):
            try:
                call()
            except (landing.LandingError, MemoryError) as e:
                print(type(e).__name__)
    """)
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert out.returncode == 0, out.stderr
    assert out.stdout.split() == ["ParameterError", "ParameterTypeError", "ParameterError", "ParameterError"]


def test_empty_and_bad_plant_parameters_are_validation_errors() -> None:
    with pytest.raises(ParameterError, match=r"nodes has shape \(0,\); it takes at least one value"):
        plants.TetheredSatellite(nodes=[])
    with pytest.raises(ParameterError, match=r"main_mass has shape \(0,\)"):
        plants.TetheredSatellite(main_mass=[])
    with pytest.raises(ParameterError, match=r"isp has shape \(2, 0\)"):
        plants.MarsLander(isp=np.zeros((2, 0)))
    with pytest.raises(ParameterTypeError, match="area must be a real number or an array of real numbers, got complex"):
        plants.MarsLander(area=(6.0 + 1j, 7.5, 8.7))
    with pytest.raises(ParameterTypeError, match="isp must be a real number or an array of real numbers, got bool"):
        plants.MarsLander(isp=np.array([True]))


def test_nan_into_the_evaluators_is_refused() -> None:
    with pytest.raises(ParameterError, match=r"PointMass: r\[1\] = nan violates finite values"):
        gravity.PointMass(1.0).acceleration([1.0, np.nan, 0.0])
    with pytest.raises(ParameterError, match=r"r\[0, 2\] = inf violates finite values"):
        gravity.Harmonic2().potential([[1e4, 0.0, np.inf]])
    with pytest.raises(ParameterTypeError, match="r must be a real number or an array of real numbers, got complex"):
        gravity.PointMass(1.0).acceleration([1.0 + 1j, 0.0, 0.0])
    with pytest.raises(ParameterError, match=r"Mamdani: inputs\[0, 1\] = nan violates finite values"):
        SYSTEM.evaluate([[0.0, np.nan]])
    with pytest.raises(ParameterError, match=r"t\[1\] = nan violates finite values"):
        reference.Constant(position=(1.0, 2.0, 3.0)).evaluate([0.0, np.nan])


def test_fuzzy_resolution_beyond_its_cap() -> None:
    with pytest.raises(ParameterError, match=r"resolution = 100001 violates resolution <= max_fuzzy_resolution"):
        fuzzy.variable_rate_system(LIMITS["max_fuzzy_resolution"] + 1)
    with pytest.raises(ParameterTypeError, match="resolution must be an integer, got 401.5"):
        fuzzy.variable_rate_system(401.5)
    v = fuzzy.Variable((-1, 1), {"N": ("triangle", -1, -1, 0), "P": ("triangle", 0, 1, 1)})
    with pytest.raises(ParameterError, match="resolution = 1000000000 violates"):
        fuzzy.Mamdani([v], v, [(("N",), "P")], resolution=10**9)
    assert fuzzy.variable_rate_system(LIMITS["max_fuzzy_resolution"]).resolution == 100_000


@pytest.mark.parametrize("call, error, message", [
    (lambda: theory.chattering_band(1.0, 1.0, 0.01), ParameterError, "e1 = 1 violates 0 < e1 < 1"),
    (lambda: theory.chattering_band(1.0, 0.5, 0.0), ParameterError, "dt = 0 violates dt > 0"),
    (lambda: theory.entry_time([], np.zeros((0, 3)), 0.1), ParameterError, r"t has shape \(0,\)"),
    (lambda: theory.settle_time([0.0, 1.0], np.zeros((3, 3)), 0.1), ParameterError, "signal has shape"),
    (lambda: theory.check_fixed_time_bound(0.9, 0.9, 0.5, 1.1, []), ParameterError, r"s0 has shape \(0, 1\)"),
    (lambda: theory.check_fntsmc_bound(controllers.FixedTimeNTSMC(), [[0.1, 0.0]], axis=5), ParameterError,
     "axis = 5 violates axis <= 1"),
    (lambda: theory.check_fntsmc_bound(controllers.FixedTimeNTSMC(), []), ParameterError, r"pairs has shape \(0,\)"),
    (lambda: theory.fixed_time_bound(0.9, 0.9, 0.5, [1.1, 1.2 + 1j]), ParameterTypeError, "e2 must be a real"),
    (lambda: theory.fixed_time_bound(0.9, np.nan, 0.5, 1.1), ParameterError, "e1 = nan violates finite values"),
    (lambda: theory.fixed_time_bound([0.9, 0.8], [0.9, 0.8, 0.7], 0.5, 1.1), ParameterError, "broadcast"),
    (lambda: theory.min_final_time("a", 0.0, 1.0), ParameterTypeError, "r0 must be a real"),
    (lambda: theory.mss_bounds(controllers.FixedTimeMSS(**RECONSTRUCTED_GAINS), ap_max=[1.0, 2.0]), ParameterError,
     r"ap_max has shape \(2,\)"),
    (lambda: theory.disturbance_bound(None, axes=4), ParameterError, r"axes = 4 violates axes in \(2, 3\)"),
    (lambda: scenarios.tether_monte_carlo(True), ParameterTypeError, "spread_deg must be a real number"),
    (lambda: scenarios.tether_monte_carlo(math.inf), ParameterError, "spread_deg = inf violates finite values"),
    (lambda: scenarios.mars_nominal(substeps=2**40), ParameterError, "substeps = .* violates substeps <= max_substeps"),
    (lambda: scenarios.mars_nominal(t_finall=1.0), ParameterTypeError, "unknown field 't_finall'"),
])
def test_probe_findings_in_theory_and_scenarios(call: Callable[[], Any], error: type, message: str) -> None:
    with pytest.raises(error, match=message):
        call()


def test_a_panic_in_the_core_arrives_as_a_landing_error() -> None:
    with pytest.raises(LandingError, match="internal error in the simulation core") as info:
        landing._core._panic_for_test()
    assert isinstance(info.value, SimulationError) and isinstance(info.value, Exception)
    try:  # an ordinary `except Exception` catches it (pyo3's PanicException would escape)
        landing._core._panic_for_test()
    except Exception as exc:  # noqa: BLE001
        assert type(exc) is SimulationError
    # the interpreter is fine afterwards
    assert run().final_state.shape == (1, 6)


def test_the_limits_come_from_the_core() -> None:
    assert dict(LIMITS) == dict(landing._core.LIMITS)
    assert set(LIMITS) == {"max_cases", "max_steps", "max_substeps", "max_threads", "max_fuzzy_resolution"}
    assert LIMITS["max_steps"] == 2**40  # the horizon rule t_final / dt <= 2^40 documented with it
    # the presets stay within the caps with room to spare
    assert plants.TetheredSatellite(nodes=16).substeps_for(0.01) < LIMITS["max_substeps"] // 100


def test_every_binding_entry_point_runs_under_the_panic_guard() -> None:
    """Each #[pyfunction] and #[pymethods] item of the binding starts its body with
    ``guard(...)``, so that the test above holds for all of them, including ones added later;
    the theory's formulas are written by one macro (analysis.rs's ``formulas!``), whose body is
    checked once."""
    import re

    src = ROOT / "crates" / "landing_py" / "src"
    if not src.is_dir():
        pytest.skip("the binding's sources are not here")
    unguarded, seen = [], 0
    assert "guard(|| theory::$name(" in (src / "analysis.rs").read_text()
    for path in sorted(src.glob("*.rs")):
        text = path.read_text()
        bodies = [m.group(1) for m in re.finditer(r"\n#\[pyfunction\]\n[\s\S]*?\{\n(.*)\n", text)]
        names = [m.group(1) for m in re.finditer(r"\n#\[pyfunction\]\n[\s\S]*?fn (\w+)", text)]
        for block in re.finditer(r"#\[pymethods\]\nimpl \w+ \{([\s\S]*?)\n\}\n", text):
            for m in re.finditer(r"\n    (?:pub )?fn (\w+)[\s\S]*?\{\n(.*)\n", block.group(1)):
                names.append(m.group(1))
                bodies.append(m.group(2))
        for name, first in zip(names, bodies):
            seen += 1
            if "guard(" not in first:
                unguarded.append(f"{path.name}: {name}")
    assert seen >= 30, seen
    assert not unguarded, unguarded
