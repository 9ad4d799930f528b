"""The counter-based generator against numpy's independent Philox implementation."""

import numpy as np

import landing
from _cases import numpy_block
from landing import _core


def test_philox_blocks_match_numpy():
    rng = np.random.default_rng(0)
    cases = [([0, 0, 0, 0], [0, 0]), ([2**64 - 1] * 4, [2**64 - 1] * 2)]
    for _ in range(20):
        cases.append(
            ([int(v) for v in rng.integers(0, 2**63, 4)], [int(v) for v in rng.integers(0, 2**63, 2)])
        )
    for counter, key in cases:
        assert list(_core.philox4x64(counter, key)) == numpy_block(counter, key)


def test_disturbance_noise_is_the_philox_draw_held_per_period():
    """Recover the noise from the velocity increments of a coasting lander and compare with
    uniforms computed from numpy's Philox for key (seed, stream 1), counter (k, case, 0, 0)."""
    seed, bound, dt, substeps = 1234, np.array([0.5, 1.0, 2.0]), 0.1, 4
    plant = landing.plants.MarsLander(drag=False, gravity=0.0)
    x0 = np.tile([0, 0, 100.0, 0, 0, 0, 1000.0], (3, 1))
    res = landing.simulate_batch(
        plant, landing.controllers.OpenLoop(), x0, t_final=2.0, dt=dt, integrator="euler",
        substeps=substeps, disturbance=landing.disturbances.UniformNoise(bound), seed=seed,
        first_case=5,
    )
    v = res.states[:, :, 3:6]
    noise = np.diff(v, axis=1) / dt  # Euler with a held draw: exact per period
    for i in range(3):
        for k in range(noise.shape[1]):
            raw = numpy_block([k, 5 + i, 0, 0], [seed, 1])[:3]
            u = np.array([(r >> 11) * 2.0**-53 for r in raw])
            np.testing.assert_allclose(noise[i, k], bound * (2 * u - 1), rtol=0, atol=1e-9)
