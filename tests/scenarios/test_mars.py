"""Seed 001's Mars claims that our runs reproduce, asserted with their tolerances (the gaps are
asserted as gaps where docs/reproduction-mars.md states them).

Numbers the seed prints: a fuel of 238.2907 kg to land (Fig. 4), a peak thrust below 40 kN
(Fig. 2(c)), the super-twisting baseline landing in 30 s against the fixed-time law's 10 to 15 s
(its central comparison), the fuel ordering optimum < fixed-time < super-twisting (Fig. 3, 4).
The fuel of the presets is a tuning target (docs/parameters.md): the first test checks that the
shipped gains still meet it; the orderings and the landing times are not tuned for.
"""

from __future__ import annotations

import numpy as np
import pytest

from landing import scenarios

SEED_FUEL = 238.2907  # kg, seed Fig. 4
SEED_SUPER_TWISTING_LANDING = 30.0  # s, the seed's baseline
THRUST = 40e3  # N, the seed's Fig. 2(c)


@pytest.fixture(scope="module")
def runs():
    names = ("mars_nominal", "mars_fast", "mars_super_twisting_printed", "mars_super_twisting_standard")
    return {name: scenarios.preset(name).simulate() for name in names}


def test_the_fixed_time_presets_land_on_the_seed_s_fuel_within_its_tolerance(runs):
    # a tuning target of both gain sets (R3: within 2 % of 238.2907 kg), checked, not reproduced
    for name in ("mars_nominal", "mars_fast"):
        m = runs[name].metrics
        assert abs(float(m["fuel_to_settle"]) - SEED_FUEL) <= 0.02 * SEED_FUEL, name
        assert float(m["final_position_error"]) < 0.1 and float(m["final_velocity_error"]) < 0.1, name


def test_the_fixed_time_law_lands_sooner_than_the_seed_s_super_twisting_under_40_kN(runs):
    """The paper's central comparison against its own 30 s: mars_fast lands in 23.6 s with the
    thrust's magnitude under 40 kN at every recorded instant."""
    fast = runs["mars_fast"]
    assert float(fast.metrics["settle_time"]) < SEED_SUPER_TWISTING_LANDING - 5.0
    assert float(fast.metrics["peak_command"]) < THRUST
    assert np.linalg.norm(fast.controls, axis=-1).max() < THRUST
    # the hand-tuned preset keeps a margin on the thrust and lands later (31.2 s)
    nominal = runs["mars_nominal"]
    assert float(nominal.metrics["peak_command"]) < THRUST
    assert float(nominal.metrics["settle_time"]) > float(fast.metrics["settle_time"])


def test_fuel_and_landing_time_order_fixed_time_before_super_twisting(runs):
    """Fixed-time < super-twisting in fuel and in landing time, for both fixed-time gain sets and
    both super-twisting variants (the optimum's place below them is tests/test_optimal.py's)."""
    for fixed in ("mars_nominal", "mars_fast"):
        for twisting in ("mars_super_twisting_printed", "mars_super_twisting_standard"):
            f, t = runs[fixed].metrics, runs[twisting].metrics
            assert float(f["fuel_to_settle"]) < float(t["fuel_to_settle"]), (fixed, twisting)
            assert float(f["settle_time"]) < float(t["settle_time"]), (fixed, twisting)


def test_the_seed_s_super_twisting_does_not_land_in_30_s_here(runs):
    """A gap stated in docs/reproduction-mars.md ("Super-twisting baseline"): with B1, B2 as
    printed neither variant lands within the seed's 30 s, and the printed one needs far more
    than 40 kN."""
    for name in ("mars_super_twisting_printed", "mars_super_twisting_standard"):
        assert float(runs[name].metrics["settle_time"]) > 2 * SEED_SUPER_TWISTING_LANDING, name
    assert float(runs["mars_super_twisting_printed"].metrics["peak_command"]) > 10 * THRUST
