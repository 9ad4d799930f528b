"""Fixtures; the shared cases and checks are in ``_cases.py``."""

import numpy as np
import pytest

# the shared checks' asserts are rewritten like the tests' own, for readable failures
pytest.register_assert_rewrite("_cases")

import landing  # noqa: E402
from _cases import NOMINAL, RECONSTRUCTED_GAINS  # noqa: E402


@pytest.fixture
def nominal() -> np.ndarray:
    return NOMINAL.copy()


@pytest.fixture
def ftmss() -> landing.controllers.FixedTimeMSS:
    return landing.controllers.FixedTimeMSS(**RECONSTRUCTED_GAINS)
