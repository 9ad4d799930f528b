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
