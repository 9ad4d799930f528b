"""Faults and interrupts: Ctrl-C stops a batch within a second and leaves the process
consistent, a batch that cannot fit in memory is refused before anything is allocated, and a
case that leaves its model is stopped and flagged with the time and the reason."""

from __future__ import annotations

import os
import resource
import signal
import subprocess
import sys
import textwrap
import threading
import time

import numpy as np
import pytest

import landing
from landing.campaign.result import summarize

# A digest of a small batch's bits, computed in a fresh interpreter and after an interrupted
# batch: the interruption must leave nothing behind.
_DIGEST = """
import hashlib
import landing
s = landing.scenarios.mars_monte_carlo()
r = s.simulate_batch(s.initial_states(40, seed=3), seed=3, t_final=1.0, record_every=0)
print("digest", hashlib.sha256(r.final_state.tobytes() + r.metrics["fuel_used"].tobytes()).hexdigest(), flush=True)
"""


def _python(code: str) -> subprocess.Popen:
    return subprocess.Popen(
        [sys.executable, "-c", code], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
        env={**os.environ, "PYTHONUNBUFFERED": "1"},
    )


@pytest.mark.skipif(sys.platform == "win32", reason="SIGINT to a child process is POSIX")
def test_ctrl_c_stops_a_long_batch_within_a_second_and_leaves_the_process_consistent():
    # 200,000 cases of 60 s at 1 ms (1.2e10 case-steps: hours on two cores), final states only
    code = textwrap.dedent("""
        import time
        import landing
        s = landing.scenarios.mars_monte_carlo()
        x0 = s.initial_states(200_000, seed=1)
        print("go", flush=True)
        try:
            s.simulate_batch(x0, seed=1, record_every=0)
            print("finished", flush=True)
        except KeyboardInterrupt:
            print(f"interrupted {time.monotonic():.6f}", flush=True)
    """) + _DIGEST
    child = _python(code)
    # a child that ignores the signal is killed, so that the test fails instead of hanging
    guard = threading.Timer(30.0, child.kill)
    guard.start()
    try:
        assert child.stdout.readline().strip() == "go"
        time.sleep(1.5)  # well inside the batch
        sent = time.monotonic()
        child.send_signal(signal.SIGINT)
        line = child.stdout.readline().split()
        assert line and line[0] == "interrupted", (line, child.stderr.read())
        latency = float(line[1]) - sent
        print(f"KeyboardInterrupt {latency:.3f} s after SIGINT")
        assert latency < 1.0, f"KeyboardInterrupt {latency:.3f} s after SIGINT"
        after = child.stdout.readline().split()
        child.wait(timeout=60)
    finally:
        guard.cancel()
        child.kill()
    fresh = _python(_DIGEST)
    out, err = fresh.communicate(timeout=60)
    assert after[0] == "digest" and out.split() == after, (out, err)


def test_a_batch_too_large_for_memory_is_refused_before_anything_is_allocated():
    s = landing.scenarios.mars_nominal()
    x0 = s.initial_states(10_000)
    before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss  # KiB on Linux
    t0 = time.perf_counter()
    # 1e8 recorded instants x 10,000 cases x 17 values: about 1.2e14 bytes
    with pytest.raises(MemoryError, match=r"needs [0-9.]+ GiB .*GiB of memory are available.*record_every"):
        s.simulate_batch(x0, t_final=1e5, dt=1e-3, record_every=1)
    assert time.perf_counter() - t0 < 5.0
    grown = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - before
    assert grown < 100_000, f"peak memory grew by {grown} KiB before the refusal"


def test_a_diverging_case_is_flagged_with_time_and_reason_and_named_in_summaries():
    s = landing.scenarios.mars_nominal()
    x0 = np.tile(s.x0, (3, 1))
    x0[1, 0] = 1e200  # absurdly far: the law's powers overflow in its first command
    with pytest.warns(landing.DivergenceWarning, match=r"1 of 3 cases diverged \(non_finite_command: 1 \(cases 1\)\)"):
        r = s.simulate_batch(x0, t_final=1.0, record_every=0)
    m = r.metrics
    assert m["diverged"].tolist() == [False, True, False]
    assert landing.DIVERGENCE_REASONS[m["diverged_reason"][1]] == "non_finite_command"
    assert m["diverged_reason"][0] == m["diverged_reason"][2] == 0
    assert m["diverged_time"][1] == 0.0 and np.isnan(m["diverged_time"][[0, 2]]).all()
    assert {k: v.tolist() for k, v in m.diverged_cases().items()} == {"non_finite_command": [1]}
    summary = summarize(m)
    assert summary["fuel_used"]["n"] == 2
    assert "left out of the statistics: 1 diverged case (non_finite_command: 1)" in str(summary)
    assert "non_finite_command: 1 (cases 1)" in repr(m)


def test_leaving_the_mars_model_range_is_out_of_domain():
    # 1e5 m/s^2 straight up: the lander passes 1e8 m from the target at t = 44.7 s (with an
    # absurd specific impulse, so that the mass lasts that long)
    plant = landing.plants.MarsLander(drag=False, isp=1e9)
    law = landing.controllers.OpenLoop(acceleration=[0.0, 0.0, 1e5])
    x0 = plant.initial_state([0, 0, 1500], [0, 0, 0], 1905)[None, :]
    with pytest.warns(landing.DivergenceWarning, match="out_of_domain"):
        r = landing.simulate_batch(plant, law, x0, t_final=60.0, dt=0.1, record_every=0)
    t_cross = np.sqrt((1e8 - 1500.0) / 5e4)
    assert landing.DIVERGENCE_REASONS[r.metrics["diverged_reason"][0]] == "out_of_domain"
    assert t_cross - 0.1 < r.metrics["diverged_time"][0] <= t_cross + 0.1


def test_no_metric_is_infinite_without_the_flag():
    # Initial states from the nominal to 1e300 m and m/s away, with and without a thrust limit:
    # every case either ends with finite statistics or is flagged.
    rng = np.random.default_rng(7)
    base = landing.scenarios.mars_nominal().x0
    scale = 10.0 ** rng.uniform(0, 300, size=(64, 6))
    x0 = np.tile(base, (64, 1))
    x0[:, :6] *= scale * rng.choice([-1.0, 1.0], size=(64, 6))
    for limit in (None, 5e4):
        s = landing.scenarios.mars_nominal(plant=landing.plants.MarsLander(thrust_limit=limit))
        with pytest.warns(landing.DivergenceWarning):
            m = s.simulate_batch(x0, t_final=2.0, dt=0.01, record_every=0).metrics
        for name, col in m.items():
            col = np.asarray(col, dtype=float)
            infinite = np.isinf(col).reshape(len(x0), -1).any(axis=1)
            assert not np.any(infinite & ~m["diverged"]), f"{name} infinite on an unflagged case"
