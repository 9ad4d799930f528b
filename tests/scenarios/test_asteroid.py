"""The asteroid papers' claims, on the presets of landing.scenarios."""

import numpy as np
import pytest

import landing
from landing.scenarios import SEED000_LAWS, seed000_tracking, seed002_landing


@pytest.fixture(scope="module")
def seed000():
    return {(law, sw): seed000_tracking(law, sw).simulate().metrics for law in SEED000_LAWS for sw in ("sign", "tanh")}


def test_seed000_tracking_time_ordering(seed000):
    for sw in ("sign", "tanh"):
        t = [seed000[(law, sw)]["settle_time"] for law in SEED000_LAWS]
        assert np.all(np.isfinite(t))
        assert t[0] > t[1] > t[2], (sw, t)  # PD-SMC > FTSMC > fuzzy FTSMC (seed: 8, 5, 4 s)
    assert seed000[("pd", "sign")]["settle_time"] == pytest.approx(8.0, abs=0.1)  # the calibration


def test_seed000_error_ordering(seed000):
    for sw in ("sign", "tanh"):
        e = [seed000[(law, sw)]["iae"] for law in SEED000_LAWS]
        assert e[0] > e[1] > e[2], (sw, e)  # seed: 244 > 139 > 113


def test_seed000_smoother_switches_chatter_less(seed000):
    for law in SEED000_LAWS:
        for key in ("chattering_variation", "chattering_hf_share"):
            assert seed000[(law, "tanh")][key] < seed000[(law, "sign")][key], (law, key)
    for sw in ("sign", "tanh"):
        # the fuzzy blend chatters less than the FTSMC it blends (and, with sign, than PD-SMC)
        tv = [seed000[(law, sw)]["chattering_variation"] for law in SEED000_LAWS]
        assert tv[2] < tv[1], (sw, tv)
    assert seed000[("fuzzy_ftsmc", "sign")]["chattering_variation"] < seed000[("pd", "sign")]["chattering_variation"]
    # with tanh, PD-SMC is the smoothest (docs/reproduction-asteroid.md: not reproduced with tanh)
    assert seed000[("pd", "tanh")]["chattering_variation"] < seed000[("fuzzy_ftsmc", "tanh")]["chattering_variation"]


def test_seed000_full_landing_reaches_the_target():
    m = landing.scenarios.seed000_landing("pd").simulate().metrics
    assert m["final_position_error"] < 1e-3 and m["final_velocity_error"] < 1e-3


@pytest.fixture(scope="module")
def seed002():
    return {law: seed002_landing(law).simulate() for law in ("exponential", "fuzzy_variable_rate")}


def test_seed002_on_the_nominal_trajectory_by_400_s(seed002):
    for res in seed002.values():
        assert res.metrics["settle_time"] <= 400.0
        # and before that it was not: the offset was real
        assert res.metrics["settle_time"] > 100.0


def test_seed002_fuzzy_chatters_less_at_equal_accuracy(seed002):
    exp, fuzzy = (seed002[k].metrics for k in ("exponential", "fuzzy_variable_rate"))
    assert fuzzy["iae"] == pytest.approx(exp["iae"], rel=0.01)
    assert max(exp["final_position_error"], fuzzy["final_position_error"]) < 1e-3
    assert fuzzy["chattering_variation"] < exp["chattering_variation"] / 10
    assert fuzzy["chattering_hf_share"] < exp["chattering_hf_share"] / 10


def test_seed002_fuzzy_term_is_active_and_bounded(seed002):
    """The fuzzy term does the switching term's job (it is not switched off) within the same
    authority, ku times the rule base's largest output = epsilon."""
    eps = np.abs(seed002["fuzzy_variable_rate"].diagnostics["epsilon"])
    epsilon = landing.scenarios.SEED002_GAINS["epsilon"]
    assert eps.max() <= epsilon * 1.0001
    assert eps.max() > 0.5 * epsilon
