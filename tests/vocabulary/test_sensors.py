"""A sensor and a Kalman filter between the plant and the law, against their specification:
the noise's mean, variance and autocorrelation over 10^5 draws, the filter's steady-state
covariance against the discrete Riccati equation's solution (scipy), and the same bits
whatever the threads, the levels and the batch a case runs in."""

import numpy as np
import pytest
from scipy import linalg

import landing
from _cases import LEVELS, RECONSTRUCTED_GAINS, assert_same_bits
from landing.sensors import KalmanFilter, Noise

C, P = landing.controllers, landing.plants

DT = 0.1
SPACING = 1e4  # between the cases' x positions: a row of what the law saw names its case


class Seen:
    """A zero-command law that keeps what it reads: (t, e, de) per call."""

    def __init__(self) -> None:
        self.calls: list[tuple[float, np.ndarray, np.ndarray]] = []

    def __call__(self, t, e, de, ref, drift, inertia, params, memory):
        self.calls.append((t, e.copy(), de.copy()))
        return np.zeros_like(e)

    def errors(self, x0: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The measurement errors (instants, cases, 6), rows put in case order: with zero
        command and no disturbance case i is at x0_i + v0_i t."""
        n = x0.shape[0]
        times = sorted({c[0] for c in self.calls})
        out = np.full((len(times), n, 6), np.nan)
        for t, e, de in self.calls:
            k = times.index(t)
            q = x0[:, :3] + x0[:, 3:] * t
            case = np.rint(e[:, 0] / SPACING).astype(int)
            out[k, case, :3] = e - q[case]
            out[k, case, 3:] = de - x0[case, 3:]
        assert not np.isnan(out).any()
        return np.asarray(times), out


def starts(n: int) -> np.ndarray:
    x0 = np.zeros((n, 6))
    x0[:, 0] = SPACING * np.arange(n)
    x0[:, 3:] = [0.5, -0.25, 0.125]  # exact in binary: q(t) = x0 + v0 t has no rounding to speak of
    return x0


def measured(sensor: Noise, n: int, t_final: float, seed: int = 7) -> np.ndarray:
    law = Seen()
    x0 = starts(n)
    landing.simulate_batch(P.DoubleIntegrator(sensor=sensor), C.PythonLaw(law), x0, t_final=t_final, dt=DT,
                           seed=seed, threads=1)
    return law.errors(x0)[1]


def lag1(e: np.ndarray) -> np.ndarray:
    """Lag-1 autocorrelation per component of (instants, cases, components), pooled."""
    a, b = e[:-1] - e.mean(axis=(0, 1)), e[1:] - e.mean(axis=(0, 1))
    return (a * b).mean(axis=(0, 1)) / e.var(axis=(0, 1))


STD = np.array([1.0, 2.0, 3.0, 0.1, 0.2, 0.3])
BIAS = np.array([0.5, -0.5, 0.0, 0.05, 0.0, -0.02])


def test_white_noise_and_bias_have_their_mean_variance_and_no_autocorrelation():
    # 1000 cases x 100 instants = 10^5 draws per component
    e = measured(Noise(std=STD, bias=BIAS), n=1000, t_final=99 * DT)
    assert e.shape == (100, 1000, 6)
    draws = e.reshape(-1, 6)
    n = draws.shape[0]
    np.testing.assert_array_less(np.abs(draws.mean(axis=0) - BIAS), 4.5 * STD / np.sqrt(n))
    # the sample variance's relative standard deviation is sqrt(2 / n) = 0.45 %
    np.testing.assert_allclose(draws.var(axis=0), STD**2, rtol=5 * np.sqrt(2 / n))
    np.testing.assert_array_less(np.abs(lag1(e)), 4.5 / np.sqrt(n))
    # and the components are independent of each other
    corr = np.corrcoef(draws.T)
    np.testing.assert_array_less(np.abs(corr - np.eye(6)), 4.5 / np.sqrt(n))


def test_the_random_walk_grows_as_its_density_squared_times_t():
    walk = np.array([0.3, 0.6, 0.9, 0.03, 0.06, 0.09])
    # 10^4 cases x 11 instants: 10^5 increments per component
    e = measured(Noise(random_walk=walk), n=10_000, t_final=10 * DT)
    np.testing.assert_array_equal(e[0], 0.0)  # w_0 = 0
    steps = np.diff(e, axis=0)
    n = steps.shape[0] * steps.shape[1]
    np.testing.assert_allclose(steps.reshape(-1, 6).var(axis=0), walk**2 * DT, rtol=5 * np.sqrt(2 / n))
    np.testing.assert_array_less(np.abs(lag1(steps)), 4.5 / np.sqrt(n))
    # at the last instant (t = 1 s), over 10^4 cases: variance walk^2 t
    np.testing.assert_allclose(e[-1].var(axis=0), walk**2 * 1.0, rtol=5 * np.sqrt(2 / 10_000))


def riccati(dt: float, s: float, r_q: float, r_v: float) -> np.ndarray:
    """The steady-state (updated) covariance of the Kalman filter of [q, q'] under an
    acceleration of standard deviation s held over each period, measuring both."""
    F = np.array([[1.0, dt], [0.0, 1.0]])
    G = np.array([[dt * dt / 2], [dt]])
    Q = s * s * (G @ G.T)
    R = np.diag([r_q, r_v])
    predicted = linalg.solve_discrete_are(F.T, np.eye(2), Q, R)
    return predicted - predicted @ np.linalg.solve(predicted + R, predicted)


def pd(t, e, de, ref, drift, inertia, params, memory):
    """A PD law on what it reads (the estimate)."""
    return -0.5 * e - 1.2 * de


def test_the_filter_error_covariance_is_the_riccati_solution():
    bound = 2.0  # the unknown acceleration: uniform on [-2, 2] m/s^2, held over each period
    s = bound / np.sqrt(3.0)
    std = np.array([3.0, 3.0, 3.0, 0.4, 0.4, 0.4])
    plant = P.DoubleIntegrator(sensor=Noise(std=std), filter=KalmanFilter(process_noise=s))
    n = 4000
    rng = np.random.default_rng(1)
    x0 = np.concatenate([rng.normal(0, 50, (n, 3)), rng.normal(0, 5, (n, 3))], axis=1)
    res = landing.simulate_batch(plant, C.PythonLaw(pd), x0, t_final=30.0, dt=DT, seed=3,
                                 disturbance=landing.disturbances.UniformNoise(bound))
    m = res.metrics
    err = np.stack([m["navigation_position_error"], m["navigation_velocity_error"]], axis=-1)  # (n, 3, 2)
    samples = err.reshape(-1, 2)  # the three axes have the same model: 12,000 samples
    expected = riccati(DT, s, std[0] ** 2, std[3] ** 2)
    empirical = np.cov(samples.T)
    # relative standard deviation of a sample variance: sqrt(2 / 12000) = 1.3 %
    np.testing.assert_allclose(np.diag(empirical), np.diag(expected), rtol=0.06)
    rho = expected[0, 1] / np.sqrt(expected[0, 0] * expected[1, 1])
    assert empirical[0, 1] / np.sqrt(empirical[0, 0] * empirical[1, 1]) == pytest.approx(rho, abs=0.05)
    # the filter beats the raw measurement
    raw = landing.simulate_batch(P.DoubleIntegrator(sensor=Noise(std=std)), C.PythonLaw(pd), x0[:200],
                                 t_final=30.0, dt=DT, seed=3, disturbance=landing.disturbances.UniformNoise(bound))
    assert np.all(m["navigation_position_rms"][:200] < raw.metrics["navigation_position_rms"])
    assert np.all(m["navigation_velocity_rms"][:200] < raw.metrics["navigation_velocity_rms"])


def test_a_built_in_law_steers_the_measured_state_so_a_bias_offsets_the_truth():
    bias = np.array([2.0, -1.0, 0.5, 0.0, 0.0, 0.0])
    law = C.FixedTimeMSS(**RECONSTRUCTED_GAINS)
    x0 = np.array([30.0, -20.0, 10.0, 0.0, 0.0, 0.0])
    res = landing.simulate(P.DoubleIntegrator(sensor=Noise(bias=bias)), law, x0, t_final=120.0, dt=0.01)
    # the law drives what it reads to 0: the true position ends at -bias
    np.testing.assert_allclose(res.metrics["final_error"], -bias[:3], atol=1e-3)
    np.testing.assert_allclose(res.metrics["navigation_position_error"], bias[:3], atol=1e-12)
    assert res.metrics["navigation_position_rms"] == pytest.approx(np.linalg.norm(bias[:3]), rel=1e-12)
    truth = landing.simulate(P.DoubleIntegrator(), law, x0, t_final=120.0, dt=0.01)
    assert np.isnan(truth.metrics["navigation_position_rms"])


def test_sensed_runs_give_the_same_bits_whatever_the_threads_levels_and_batch():
    plant = P.MarsLander(sensor=Noise(std=[5.0, 5.0, 2.0, 0.5, 0.5, 0.2], bias=0.1, random_walk=0.05),
                         filter=KalmanFilter(process_noise=[0.2, 0.2, 0.3]))
    law = C.FixedTimeMSS(**RECONSTRUCTED_GAINS)
    rng = np.random.default_rng(4)
    x0 = np.array([-2000.0, 1000.0, 1500.0, 100.0, -15.0, -75.0, 1905.0]) + np.c_[rng.normal(0, 50, (13, 6)),
                                                                                  np.zeros(13)]
    kw = dict(t_final=20.0, dt=0.05, seed=9, record_every=10)
    ref = landing.simulate_batch(plant, law, x0, threads=1, **kw)
    assert np.isfinite(ref.metrics["navigation_position_rms"]).all()
    assert_same_bits(ref.states, landing.simulate_batch(plant, law, x0, threads=2, **kw).states, "threads")
    for level in LEVELS:
        other = landing.simulate_batch(plant, law, x0, kernel=level, **kw)
        assert_same_bits(ref.states, other.states, f"level {level}")
        assert_same_bits(ref.metrics["navigation_velocity_error"], other.metrics["navigation_velocity_error"],
                         f"level {level}")
    alone = landing.simulate_batch(plant, law, x0[5:6], first_case=5, **kw)
    assert_same_bits(ref.states[5:6], alone.states, "case 5 alone")
    # a Python law runs through the same navigation as a built-in one: the same command from
    # both gives the same measurements, estimates and states, bit for bit
    a = (0.0, 0.0, 3.7114)
    built_in = landing.simulate_batch(plant, C.OpenLoop(acceleration=a), x0, **kw)
    python = landing.simulate_batch(plant, C.PythonLaw(lambda t, e, de, ref, drift, inertia, params, memory:
                                                       np.tile(a, (e.shape[0], 1))), x0, **kw)
    assert_same_bits(python.states, built_in.states, "Python law, states")
    for name in ("navigation_position_error", "navigation_velocity_rms"):
        assert_same_bits(python.metrics[name], built_in.metrics[name], f"Python law, {name}")
    assert_same_bits(python.diagnostics["estimated_position"], built_in.diagnostics["estimated_position"],
                     "Python law, recorded estimate")


def test_the_noise_changes_with_the_seed():
    a = measured(Noise(std=1.0), n=3, t_final=1.0, seed=1)
    b = measured(Noise(std=1.0), n=3, t_final=1.0, seed=2)
    assert not np.array_equal(a, b)


@pytest.mark.parametrize(
    "make, match",
    [
        (lambda: Noise(std=-1.0), "std"),
        (lambda: Noise(std=[1.0, 2.0]), "std has 2 values"),
        (lambda: Noise(random_walk=[0.1, 0.1, 0.1, 0.1, 0.1, -0.1]), "random_walk"),
        (lambda: Noise(bias=np.inf), "bias"),
        (lambda: KalmanFilter(process_noise=-0.1), "process_noise"),
        (lambda: P.DoubleIntegrator(filter=KalmanFilter(process_noise=0.1)), "filter needs a sensor"),
        (lambda: P.MarsLander(sensor=Noise(std=[1.0, 1.0, 1.0, 0.1, 0.1, 0.0]), filter=KalmanFilter(0.1)),
         "std > 0 on every component"),
    ],
)
def test_bad_sensors_are_refused_naming_the_parameter(make, match):
    with pytest.raises(landing.ParameterError, match=match):
        make()


def test_the_estimate_the_law_read_is_recorded_with_the_diagnostics():
    std = np.array([1.0, 1.0, 1.0, 0.1, 0.1, 0.1])
    law = Seen()
    x0 = starts(5)
    plant = P.DoubleIntegrator(sensor=Noise(std=std), filter=KalmanFilter(process_noise=0.01))
    res = landing.simulate_batch(plant, C.PythonLaw(law), x0, t_final=2.0, dt=DT, record_every=1, threads=1)
    est_q, est_v = res.diagnostics["estimated_position"], res.diagnostics["estimated_velocity"]
    assert est_q.shape == est_v.shape == (5, 21, 3)
    # what the law read at each instant (the reference is 0: e is the estimate), bit for bit
    for t, e, de in law.calls:
        k = int(round(t / DT))
        rows = np.rint(e[:, 0] / SPACING).astype(int)
        np.testing.assert_array_equal(est_q[rows, k], e)
        np.testing.assert_array_equal(est_v[rows, k], de)
    # a built-in law records its own signals first, then the estimate
    mss = landing.simulate_batch(plant, C.FixedTimeMSS(**RECONSTRUCTED_GAINS), x0, t_final=2.0, dt=DT,
                                 record_every=1)
    assert list(mss.diagnostics)[-2:] == ["estimated_position", "estimated_velocity"]
    assert "s1" in mss.diagnostics
    # and without a sensor there is none
    assert "estimated_position" not in landing.simulate_batch(P.DoubleIntegrator(), C.PythonLaw(law), x0,
                                                              t_final=1.0, dt=DT, record_every=1).diagnostics


def test_sensor_numbers_given_per_case_are_each_case_s_own():
    # a bias alone (no white noise, no walk) is what the law reads on top of the truth, exactly:
    # each case's navigation error is its own row, as a run of that case alone with the row
    # shared would have it
    bias = np.array([[2.0, -1.0, 0.5, 0.0, 0.25, 0.0],
                     [-3.0, 0.0, 1.0, 0.5, 0.0, -0.125],
                     [0.0, 4.0, -2.0, 0.0, 0.0, 0.0]])
    std = np.array([[0.0], [0.5], [1.5]])  # (N, 1): one number on every component
    law = C.FixedTimeMSS(**RECONSTRUCTED_GAINS)
    x0 = starts(3)
    kw = dict(t_final=3.0, dt=DT, seed=5, record_every=5)
    per_case = landing.simulate_batch(P.DoubleIntegrator(sensor=Noise(bias=bias, std=std)), law, x0, **kw)
    for i in range(3):
        alone = landing.simulate_batch(P.DoubleIntegrator(sensor=Noise(bias=bias[i], std=std[i, 0])), law,
                                       x0[i:i + 1], first_case=i, **kw)
        assert_same_bits(per_case.states[i:i + 1], alone.states, f"case {i}")
        assert_same_bits(per_case.metrics["navigation_velocity_rms"][i:i + 1],
                         alone.metrics["navigation_velocity_rms"], f"case {i}")
    noiseless = landing.simulate_batch(P.DoubleIntegrator(sensor=Noise(bias=bias)), law, x0, **kw)
    # (q + b) - q: b to the rounding of q
    np.testing.assert_allclose(noiseless.metrics["navigation_position_error"], bias[:, :3], rtol=0, atol=1e-12)
    np.testing.assert_allclose(noiseless.metrics["navigation_velocity_error"], bias[:, 3:], rtol=0, atol=1e-12)


def test_a_filter_and_its_sensor_take_per_case_rows_of_their_own_width():
    rows = np.array([[0.1, 0.1, 0.2], [0.3, 0.3, 0.3]])
    plant = P.MarsLander(sensor=Noise(std=1.0), filter=KalmanFilter(process_noise=rows))
    law = C.FixedTimeMSS(**RECONSTRUCTED_GAINS)
    x0 = np.array([[-2000.0, 1000.0, 1500.0, 100.0, -15.0, -75.0, 1905.0]] * 2)
    kw = dict(t_final=5.0, dt=0.05, seed=3, record_every=0)
    both = landing.simulate_batch(plant, law, x0, **kw)
    second = landing.simulate_batch(P.MarsLander(sensor=Noise(std=1.0), filter=KalmanFilter(process_noise=rows[1])),
                                    law, x0[1:], first_case=1, **kw)
    assert_same_bits(both.final_state[1:], second.final_state, "case 1's own process noise")
    assert not np.array_equal(both.final_state[0], both.final_state[1])
    with pytest.raises(landing.ParameterError, match="bias has 5 values"):
        Noise(bias=np.zeros((4, 5)))
    with pytest.raises(landing.ParameterError, match=r"bias has shape \(2, 3, 6\)"):
        Noise(bias=np.zeros((2, 3, 6)))
    with pytest.raises(landing.ParameterError, match="4 values per case but the batch has 2 cases"):
        landing.simulate_batch(P.MarsLander(sensor=Noise(bias=np.zeros((4, 6)))), law, x0, **kw)
