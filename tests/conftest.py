import numpy as np
import pytest

import landing

# Seed 001 Table I and the gains reconstructed from seed 001's printed bounds (docs/parameters.md).
NOMINAL = np.array([-2000.0, 1000.0, 1500.0, 100.0, -15.0, -75.0, 1905.0])
RECONSTRUCTED_GAINS = dict(beta1=0.8, beta2=0.4, q1=0.95, q2=1.05, alpha1=0.9, alpha2=0.5, gamma1=0.9, gamma2=1.1)
G_MARS = 3.7114


@pytest.fixture
def nominal() -> np.ndarray:
    return NOMINAL.copy()


@pytest.fixture
def ftmss() -> landing.controllers.FixedTimeMSS:
    return landing.controllers.FixedTimeMSS(**RECONSTRUCTED_GAINS)


def dispersed(n: int, seed: int = 1) -> np.ndarray:
    """Table II-like dispersed initial states, drawn with numpy (independent of the core)."""
    rng = np.random.default_rng(seed)
    sd = np.array([100, 100, 100, 10, 10, 10, 20.0])
    return NOMINAL + sd * rng.standard_normal((n, 7))


def assert_same_bits(a: np.ndarray, b: np.ndarray, what: str) -> None:
    """Equal dtype, shape and bits (signed zeros and NaN payloads included)."""
    a, b = np.asarray(a), np.asarray(b)
    assert a.dtype == b.dtype, f"{what}: dtype {a.dtype} != {b.dtype}"
    assert a.shape == b.shape, f"{what}: shape {a.shape} != {b.shape}"
    if a.dtype.kind in "fc":
        assert np.array_equal(a, b, equal_nan=True), f"{what}: values differ"
    # and the bits, signed zeros and NaN payloads included
    assert a.tobytes() == b.tobytes(), f"{what}: the bits differ"


def assert_same_campaign(a: landing.MonteCarloResult, b: landing.MonteCarloResult) -> None:
    """Two campaigns agree bit for bit: every array, metric, check and the report."""
    assert a.seed == b.seed and a.keep == b.keep and a.n_cases == b.n_cases
    assert_same_bits(a.x0, b.x0, "x0")
    assert_same_bits(a.t, b.t, "t")
    assert_same_bits(a.result.final_state, b.result.final_state, "final_state")
    for name in ("states", "controls"):
        x, y = getattr(a, name), getattr(b, name)
        assert (x is None) == (y is None), name
        if x is not None:
            assert_same_bits(x, y, name)
    assert list(a.diagnostics) == list(b.diagnostics)
    for k in a.diagnostics:
        assert_same_bits(a.diagnostics[k], b.diagnostics[k], k)
    assert list(a.metrics) == list(b.metrics)
    for k in a.metrics:
        assert_same_bits(a.metrics[k], b.metrics[k], f"metrics[{k!r}]")
    assert a.result.state_names == b.result.state_names and a.result.control_names == b.result.control_names
    wa, wb = a.within_bounds(), b.within_bounds()
    assert (wa is None) == (wb is None)
    if wa is not None:
        assert_same_bits(wa, wb, "within_bounds")
    assert a.report() == b.report()
