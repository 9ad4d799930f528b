"""Every entry point refuses bad input with an error naming the argument and the rule."""

import dataclasses
import warnings

import numpy as np
import pytest

import landing
from _cases import NOMINAL, RECONSTRUCTED_GAINS
from landing import controllers, disturbances, plants, reference


def gains(**kw):
    return dict(RECONSTRUCTED_GAINS, **kw)


CONSTRUCTION = [
    (lambda: plants.MarsLander(isp=0.0), "isp = 0 violates isp > 0"),
    (lambda: plants.MarsLander(isp=[225.0, -1.0]), r"isp = -1 violates isp > 0 \(case 1\)"),
    (lambda: plants.MarsLander(area=(6.0, -7.5, 8.7)), r"area = -7.5 violates area > 0 \(axis 1\)"),
    (lambda: plants.MarsLander(gravity=-1.0), "gravity"),
    (lambda: plants.MarsLander(g0=0.0), "g0"),
    (lambda: plants.MarsLander(drag_coefficient=-0.1), "drag_coefficient"),
    (lambda: plants.MarsLander(density_decay=-1.0), "density_decay"),
    (lambda: plants.MarsLander(thrust_limit=0.0), "thrust_limit = 0 violates thrust_limit > 0"),
    (lambda: plants.MarsLander(isp=np.nan), "isp = NaN violates finite values"),
    (lambda: plants.MarsLander(area=np.ones((2, 2, 3))), "area has shape"),
    (lambda: controllers.FixedTimeMSS(**gains(q1=1.2)), "q1 = 1.2 violates 0 < q1 < 1"),
    (lambda: controllers.FixedTimeMSS(**gains(q1=0.0)), "0 < q1 < 1"),
    (lambda: controllers.FixedTimeMSS(**gains(q2=0.9)), "q2 = 0.9 violates q2 > 1"),
    (lambda: controllers.FixedTimeMSS(**gains(gamma1=(0.9, 1.0, 0.9))),
     r"gamma1 = 1 violates 0 < gamma1 < 1 \(axis 1\)"),
    (lambda: controllers.FixedTimeMSS(**gains(gamma2=1.0)), "gamma2 > 1"),
    (lambda: controllers.FixedTimeMSS(**gains(beta1=-0.8)), "beta1 > 0"),
    (lambda: controllers.FixedTimeMSS(**gains(beta2=0.0)), "beta2 > 0"),
    (lambda: controllers.FixedTimeMSS(**gains(alpha1=0.0)), "alpha1 > 0"),
    (lambda: controllers.FixedTimeMSS(**gains(alpha2=-1.0)), "alpha2 > 0"),
    (lambda: controllers.FixedTimeMSS(**gains(), s1_floor=0.0), "s1_floor > 0"),
    (lambda: controllers.FixedTimeMSS(**gains(), variant="exactly"), "variant = \"exactly\" is not one of"),
    (lambda: controllers.FixedTimeMSS(**gains(alpha1=[0.9, 0.8, 0.7, 0.6, 0.5], alpha2=[0.5, 0.4, 0.3, 0.2])),
     r"alpha2 has 4 values: one per axis takes 3 \(the plant's axes\), one per case 5 \(the batch's cases\); "
     r"alpha1 gave 5 per case"),
    # the two-axis law's per-axis default meets rows of three: the message names the parameter
    # that made them cases too
    (lambda: controllers.NTSMC(alpha=np.ones((3, 3))), r"beta has 2 values: .*; alpha gave 3 per case"),
    (lambda: controllers.SuperTwisting(b1=0.0), "b1 > 0"),
    (lambda: controllers.SuperTwisting(b2=-1.0), "b2 > 0"),
    (lambda: controllers.SuperTwisting(c=0.0), "c > 0"),
    (lambda: controllers.SuperTwisting(s_floor=-1.0), "s_floor > 0"),
    (lambda: controllers.SuperTwisting(variant="classic"), "variant"),
    (lambda: controllers.OpenLoop(acceleration=np.inf), "acceleration = inf violates finite values"),
    (lambda: reference.Cubic.from_boundary([0, 0, 0], [0, 0, 0], [1, 1, 1], [0, 0, 0], -5.0), "T = -5 violates T > 0"),
    (lambda: reference.Cubic(coefficients=np.zeros((3, 3)), t_end=1.0), "coefficients has shape"),
    (lambda: reference.Cubic(coefficients=[[0.0, 1.0, np.nan, 0.0]], t_end=1.0).evaluate(0.0, axes=1),
     r"coefficients = NaN violates finite values \(entry \[0, 2\]\)"),
    (lambda: reference.Constant(position=(0.0, np.nan, 0.0)), "position"),
    (lambda: disturbances.UniformNoise(bound=-1.0), "bound >= 0"),
    (lambda: disturbances.Sinusoid(amplitude=1.0, omega=np.inf), "omega"),
]


@pytest.mark.parametrize("make, message", CONSTRUCTION)
def test_constructors_refuse_bad_parameters(make, message):
    with pytest.raises(ValueError, match=message) as info:
        make()
    assert isinstance(info.value, landing.ParameterError)


def test_type_errors_name_the_argument():
    with pytest.raises(TypeError, match="isp must be a real number"):
        plants.MarsLander(isp="fast")
    with pytest.raises(TypeError, match="drag must be True or False"):
        plants.MarsLander(drag="yes")
    with pytest.raises(TypeError, match="acceleration must be a real number"):
        controllers.OpenLoop(acceleration=[1.0, "x", 2.0])


def run(**kw):
    args = dict(plant=plants.MarsLander(), controller=controllers.OpenLoop(), x0=NOMINAL[None, :],
                t_final=1.0, dt=0.1)
    args.update(kw)
    return landing.simulate_batch(args.pop("plant"), args.pop("controller"), args.pop("x0"), **args)


SIMULATION = [
    (dict(dt=0.0), ValueError, "dt = 0 violates dt > 0"),
    (dict(dt=-0.1), ValueError, "dt"),
    (dict(dt=np.nan), ValueError, "dt"),
    (dict(t_final=0.0), ValueError, "t_final = 0 violates"),
    (dict(t_final=np.inf), ValueError, "t_final"),
    (dict(t_final=1.05), ValueError, "t_final an integer multiple of dt"),
    (dict(t_final=0.05), ValueError, "t_final >= dt"),
    (dict(integrator="rk45"), ValueError, r"integrator = 'rk45' is not one of \('rk4', 'euler'\)"),
    (dict(integrator=4), TypeError, "integrator must be a string"),
    (dict(substeps=0), ValueError, "substeps = 0 violates substeps >= 1"),
    (dict(substeps=2.5), TypeError, "substeps must be an integer"),
    (dict(record_every=-1), ValueError, "record_every = -1 violates"),
    (dict(seed=-1), ValueError, "seed = -1 violates"),
    (dict(seed=2**64), ValueError, "seed"),
    (dict(seed=1.5), TypeError, "seed must be an integer"),
    (dict(threads=0), ValueError, "threads = 0 violates threads >= 1"),
    (dict(first_case=-2), ValueError, "first_case"),
    (dict(x0=NOMINAL), ValueError, r"x0 has shape \(7,\)"),
    (dict(x0=NOMINAL[None, :6]), ValueError, r"x0 has shape \(1, 6\); this plant takes \(N, 7\)"),
    (dict(x0=np.zeros((0, 7))), ValueError, "N >= 1"),
    (dict(x0=np.array([NOMINAL, NOMINAL * np.r_[1, 1, 1, 1, 1, 1, -1]])), ValueError,
     r"x0\[1, 6\] = -1905 violates mass x0\[6\] > 0"),
    (dict(x0=np.array([np.r_[NOMINAL[:6], np.nan]])), ValueError, r"x0\[0, 6\] = NaN violates finite values"),
    (dict(x0=[["a"] * 7]), TypeError, "x0 must be an array of real numbers"),
    (dict(plant="mars"), TypeError, "plant must be a landing.plants plant"),
    (dict(controller=None), TypeError, "controller must be a landing.controllers law"),
    (dict(reference={"kind": "constant"}), TypeError, "reference must be"),
    (dict(disturbance=[1.0]), TypeError, "disturbance must be a landing.disturbances component"),
    (dict(disturbance=[disturbances.Sinusoid(1.0, 1.0)] * 5), ValueError, "at most 4"),
    (dict(t_final=5.0, dt=1e-12), ValueError, r"t_final / dt <= 2\^40"),
    (dict(controller=controllers.FixedTimeMSS(**gains(alpha1=[0.9, 0.8]))), ValueError,
     r"alpha1 has 2 values: one per axis of a 2-axis plant, but this plant has 3 axes; one per case would be 1"),
]


@pytest.mark.parametrize("kw, error, message", SIMULATION)
def test_simulate_batch_refuses_bad_input(kw, error, message):
    with pytest.raises(error, match=message) as info:
        run(**kw)
    assert isinstance(info.value, landing.LandingError)


def test_simulate_takes_one_state():
    with pytest.raises(ValueError, match=r"simulate takes one state"):
        landing.simulate(plants.MarsLander(), controllers.OpenLoop(), NOMINAL[None, :], t_final=1.0, dt=0.1)


def test_configurations_are_compiled_once_and_frozen():
    law = controllers.FixedTimeMSS(**RECONSTRUCTED_GAINS)
    with pytest.raises(dataclasses.FrozenInstanceError):
        law.q2 = 0.5
    # a change is a new object, validated like one
    with pytest.raises(ValueError, match=r"FixedTimeMSS: q2 = 0.5 violates q2 > 1"):
        law.replace(q2=0.5)
    assert law.replace(alpha1=0.7).alpha1 == 0.7
    # an array handed in is copied and read-only: changing the caller's array afterwards cannot
    # make the object disagree with what the core compiled
    alpha1 = np.array([0.9, 0.8, 0.7])
    law = controllers.FixedTimeMSS(**{**RECONSTRUCTED_GAINS, "alpha1": alpha1})
    alpha1[0] = -1.0
    assert law.alpha1[0] == 0.9 and not law.alpha1.flags.writeable
    assert not run(controller=law).metrics["diverged"].any()


def test_recording_too_large_is_a_memory_error_not_a_crash():
    x0 = np.tile(NOMINAL, (10_000, 1))
    with pytest.raises(MemoryError, match="record fewer instants"):
        run(x0=x0, t_final=1e6, dt=1e-3)


def test_overflowing_or_missing_inputs_are_parameter_errors_naming_them():
    # reproducers of the reliability probe: an OverflowError and an AttributeError before
    with pytest.raises(landing.ParameterError, match="chattering_band: .* exceeds the largest double"):
        landing.theory.chattering_band(1e300, 0.5, 0.001)
    with pytest.raises(landing.ParameterError, match="law = None is not one of"):
        landing.scenarios.tether_comparison(law=None)
    # and an ordinary band is the closed form (c1 dt)^(1/(1 - e1))
    assert landing.theory.chattering_band(4.0, 0.5, 0.01) == pytest.approx(0.04**2, rel=1e-15)


@pytest.mark.parametrize("call, error, pattern", [
    # the second probe (issue 24): a TypeError from deep inside, a message naming the Cubic's T
    # instead of the argument, an integer beyond a double taken for a wrong type
    (lambda: landing.monte_carlo(landing.scenarios.preset("mars_nominal"), 2, keep=3), landing.ParameterTypeError,
     r"keep must be a signal's name or a sequence of them, among \('states', 'controls', 'diagnostics'\), got 3"),
    (lambda: landing.monte_carlo(landing.scenarios.preset("mars_nominal"), 2, keep=None), landing.ParameterTypeError,
     r"keep must be .* got None"),
    (lambda: landing.scenarios.seed000_reference(t_end=0), landing.ParameterError,
     r"seed000_reference: t_end = 0 violates t_end > 0"),
    (lambda: landing.scenarios.seed002_reference(t_end=float("nan")), landing.ParameterError,
     r"seed002_reference: t_end = nan violates finite values"),
    (lambda: landing.scenarios.seed000_reference(t_end=10**400), landing.ParameterError,
     r"seed000_reference: t_end = about 10\^400 violates finite values"),
    (lambda: landing.controllers.PDSlidingMode(lambda_=1.0, k=10**400), landing.ParameterError,
     r"k = about 10\^400 violates finite values"),
    (lambda: landing.simulate(landing.scenarios.preset("mars_nominal").plant,
                              landing.scenarios.preset("mars_nominal").controller, NOMINAL, t_final=1e300, dt=0.01),
     landing.ParameterError, r"t_final = 1e\+300 violates t_final / dt <= 2\^40"),
])
def test_extreme_inputs_are_the_library_s_errors_naming_the_argument(call, error, pattern):
    with pytest.raises(error, match=pattern):
        call()


def _every_number_finite_or_flagged(r):
    m = r.metrics
    for i in range(r.n_cases):
        if m["diverged"][i]:
            continue
        for name in m:
            v = np.asarray(m[name], dtype=float)[i]
            assert np.isfinite(v).all() or name in NAN_BY_DEFINITION, (i, name, v)
        for name, d in r.diagnostics.items():
            assert np.isfinite(d[i]).all(), (i, name)


# metrics NaN by definition on a case that ran: no mass, no touchdown, no sensor, no settling
NAN_BY_DEFINITION = {"fuel_used", "fuel_to_settle", "settle_time", "diverged_time", "touchdown_time",
                     "touchdown_position", "touchdown_velocity", "touchdown_speed", "navigation_position_rms",
                     "navigation_velocity_rms", "navigation_position_error", "navigation_velocity_error",
                     "high_frequency_share", "high_frequency_share_total"}


@pytest.mark.parametrize("preset, component", [
    ("seed000_pd_sign", 2), ("seed000_ftsmc_tanh", 2), ("tether_fntsmc_simplified", 0), ("mars_nominal", 2),
])
@pytest.mark.parametrize("value", [1e200, -1e200, 1e99])
def test_a_finite_but_huge_initial_state_is_flagged_or_its_metrics_finite(preset, component, value):
    # the probe's three reproducers (issue 24) and the Mars lander: beyond 1e100 (every plant's
    # state limit) the case is flagged out of its domain; below it every metric is finite
    s = landing.scenarios.preset(preset)
    x0 = np.asarray(s.x0, dtype=float).copy()
    x0[component] = value
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", landing.DivergenceWarning)
        r = s.replace(t_final=50 * s.dt).simulate_batch(x0[None, :], record_every=10)
    _every_number_finite_or_flagged(r)
    if abs(value) > 1e100:
        assert r.metrics["diverged"][0]


@pytest.mark.parametrize("position", [1e200, 1e150, -1e101])
def test_a_reference_far_beyond_the_state_limit_is_flagged_or_its_metrics_finite(position):
    s = landing.scenarios.preset("mars_nominal")
    far = landing.reference.Constant(position=[position, 0.0, 0.0])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", landing.DivergenceWarning)
        r = s.replace(reference=far, t_final=50 * s.dt).simulate_batch(np.asarray(s.x0)[None, :], record_every=10)
    _every_number_finite_or_flagged(r)
