"""Metrics computed in the rollout against the same quantities computed from the recording."""

import numpy as np
import pytest

import landing
from _cases import dispersed


@pytest.fixture(scope="module")
def run():
    law = landing.controllers.FixedTimeMSS(**landing.scenarios.MARS_FIXED_TIME_GAINS)
    return landing.simulate_batch(landing.plants.MarsLander(thrust_limit=5e4), law, dispersed(3), t_final=40.0,
                                  dt=0.01, settle_tolerance=50.0, record_every=1)


def test_iae_is_the_integral_of_the_error(run):
    applied = run.states[:, :-1, :3]  # the error at the start of each control period
    iae = np.abs(applied).sum(axis=1) * 0.01  # the reference is the origin
    np.testing.assert_allclose(run.metrics["iae_axis"], iae, rtol=1e-12)
    np.testing.assert_allclose(run.metrics["iae"], iae.sum(axis=1), rtol=1e-12)


def test_variation_is_the_total_variation_per_second(run):
    u = run.controls[:, :-1]  # the last record is the command at t_final, not applied
    tv = np.abs(np.diff(u, axis=1)).sum(axis=1) / 40.0
    np.testing.assert_allclose(run.metrics["chattering_variation_axis"], tv, rtol=1e-12)
    np.testing.assert_allclose(run.metrics["chattering_variation"], tv.sum(axis=1), rtol=1e-12)


def butterworth_highpass(x, hz, dt):
    """An independent writing of the 2nd-order Butterworth high-pass (bilinear, prewarped),
    started at rest on the first sample."""
    k = np.tan(np.pi * hz * dt)
    norm = 1 / (1 + np.sqrt(2) * k + k * k)
    b = np.array([1, -2, 1]) * norm
    a = np.array([2 * (k * k - 1), 1 - np.sqrt(2) * k + k * k]) * norm
    y = np.zeros_like(x)
    xp = np.r_[x[0], x[0], x]
    yp = np.zeros(len(x) + 2)
    for n in range(len(x)):
        yp[n + 2] = b[0] * xp[n + 2] + b[1] * xp[n + 1] + b[2] * xp[n] - a[0] * yp[n + 1] - a[1] * yp[n]
    y[:] = yp[2:]
    return y


@pytest.mark.parametrize("cutoff", [None, 2.0])
def test_high_frequency_share(cutoff):
    law = landing.controllers.SuperTwisting(variant="standard", c=0.3)
    res = landing.simulate(landing.plants.MarsLander(thrust_limit=5e4), law, dispersed(1)[0], t_final=20.0,
                           dt=0.01, chatter_cutoff=cutoff)
    hz = 0.05 / 0.01 if cutoff is None else cutoff
    u = res.controls[:-1]
    hp = np.stack([butterworth_highpass(u[:, j], hz, 0.01) for j in range(3)], axis=1)
    share = (hp**2).sum(axis=0) / (u**2).sum(axis=0)
    np.testing.assert_allclose(res.metrics["chattering_hf_share_axis"], share, rtol=1e-9)
    np.testing.assert_allclose(res.metrics["chattering_hf_share"], (hp**2).sum() / (u**2).sum(), rtol=1e-9)


def test_settle_time_from_the_recording(run):
    err = np.linalg.norm(run.states[:, :, :3], axis=2)
    for i in range(3):
        outside = np.flatnonzero(err[i] > 50.0)
        expect = 0.0 if outside.size == 0 else (np.nan if outside[-1] == err.shape[1] - 1 else run.t[outside[-1] + 1])
        np.testing.assert_equal(run.metrics["settle_time"][i], expect)
    assert np.isfinite(run.metrics["settle_time"]).any() and (run.metrics["settle_time"] > 0).any()


def test_chatter_cutoff_is_validated():
    with pytest.raises(ValueError, match=r"chatter_cutoff = 60 violates 0 < chatter_cutoff < 1 / \(2 dt\)"):
        landing.simulate(landing.plants.DoubleIntegrator(), landing.controllers.OpenLoop(), np.zeros(6),
                         t_final=1.0, dt=0.01, chatter_cutoff=60.0)
