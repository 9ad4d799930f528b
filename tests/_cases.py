"""Cases and checks the test modules share (importable through pytest's ``pythonpath``): the
seed-001 state and gains, dispersed states, the laws every plant is run under, numpy's Philox
and the bit-for-bit comparisons. No test module imports another."""

from pathlib import Path

import numpy as np

import landing
from landing import controllers as C

#: The repository's root (the examples, the README, the crates).
ROOT = Path(__file__).resolve().parents[1]

# Seed 001 Table I and the gains reconstructed from seed 001's printed bounds (docs/parameters.md).
NOMINAL = np.array([-2000.0, 1000.0, 1500.0, 100.0, -15.0, -75.0, 1905.0])
RECONSTRUCTED_GAINS = dict(beta1=0.8, beta2=0.4, q1=0.95, q2=1.05, alpha1=0.9, alpha2=0.5, gamma1=0.9, gamma2=1.1)
G_MARS = 3.7114


#: The instruction-set levels this CPU runs (every one gives the same bits).
LEVELS = landing.kernel_levels()


def write_file(folder: Path, text: str, name: str = "mine.toml") -> Path:
    """``text`` written to ``folder/name`` (a user's edited scenario file)."""
    p = folder / name
    p.write_text(text, encoding="utf-8")
    return p


def small_campaign(**kw: object) -> landing.scenarios.Scenario:
    """Seed 001's Monte Carlo set-up over 5 s at dt = 2 ms (a campaign in a second)."""
    return landing.scenarios.mars_monte_carlo(t_final=5.0, dt=2e-3, record_every=25, **kw)


def tether_comparison_runs() -> dict[str, landing.SimulationResult]:
    """Seed 003's comparison run under each law (the seed's figures 3 to 7)."""
    return {law: landing.scenarios.tether_comparison(law).simulate() for law in ("fntsmc", "ntsmc")}


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


def assert_same_result_bits(a: landing.SimulationResult, b: landing.SimulationResult, what: str) -> None:
    """Two results agree bit for bit: states, controls, final states, diagnostics, metrics."""
    np.testing.assert_array_equal(a.states.view(np.uint64), b.states.view(np.uint64), err_msg=what)
    np.testing.assert_array_equal(a.controls.view(np.uint64), b.controls.view(np.uint64), err_msg=what)
    np.testing.assert_array_equal(a.final_state.view(np.uint64), b.final_state.view(np.uint64),
                                  err_msg=what)
    for k in a.diagnostics:
        np.testing.assert_array_equal(a.diagnostics[k].view(np.uint64), b.diagnostics[k].view(np.uint64),
                                      err_msg=f"{what}: diagnostic {k}")
    for k in a.metrics:
        x, y = np.asarray(a.metrics[k]), np.asarray(b.metrics[k])
        np.testing.assert_array_equal(x.astype(np.float64).view(np.uint64), y.astype(np.float64).view(np.uint64),
                                      err_msg=f"{what}: metric {k}")


def numpy_block(counter, key):
    """numpy's Philox increments its counter before generating: start one below."""
    c = list(counter)
    for i in range(4):
        if c[i] > 0:
            c[i] -= 1
            break
        c[i] = 2**64 - 1
    bg = np.random.Philox(counter=np.array(c, dtype=np.uint64), key=np.array(key, dtype=np.uint64))
    return [int(x) for x in bg.random_raw(4)]


def laws(inertia, blend_k):
    return {
        "fixed_time_mss": C.FixedTimeMSS(**landing.scenarios.MARS_FIXED_TIME_GAINS),
        "super_twisting": C.SuperTwisting(b1=2.0 * inertia, b2=0.2 * inertia, c=0.5, variant="standard"),
        "pd_sliding_mode": C.PDSlidingMode(lambda_=0.5, k=0.5, switch="tanh", boundary_layer=1.0),
        "fast_terminal_smc": C.FastTerminalSMC(alpha=0.5, beta=0.3, p=3, q=5, k=0.5, switch="tanh", boundary_layer=1.0),
        "fuzzy_fast_terminal_smc": C.FuzzyFastTerminalSMC(alpha=0.5, beta=0.3, p=3, q=5, k=blend_k, n=1.0, m=10.0,
                                                          switch="tanh", boundary_layer=1.0),
        "integral_exponential_reaching": C.IntegralExponentialReaching(c1=0.25, c2=1.0, k=0.5, epsilon=0.01,
                                                                       switch="sat", boundary_layer=0.1),
        "fuzzy_variable_rate": C.FuzzyVariableRate(c1=0.25, c2=1.0, k=0.5, ke=10.0, kec=1.0, ku=0.003),
        "ntsmc": C.NTSMC(alpha=1.0, beta=[0.5] * 3, gamma=[1.5] * 3, k=[0.5] * 3),
        "fixed_time_ntsmc": C.FixedTimeNTSMC(k1=0.5, k2=0.5, k3=0.5, eps_max=0.0, p1=1.1, p2=0.6, alpha_s=0.7,
                                             beta_s=1.5, sigma_phi=0.01, gamma=0.0, rbf_scale_e1=10.0,
                                             rbf_scale_e2=1.0, rbf_width=1.0),
    }


def tether_laws(inertia):
    layer = dict(switch="sat", boundary_layer=1e-3)
    terminal = dict(alpha=[0.1, 0.5], beta=[1e-3, 0.05], p=1, q=5, k=[2e-5, 1e-3], e_floor=1e-4, **layer)
    surface = dict(c1=[0.0025, 0.0625], c2=[0.1, 0.5], k=0.1)
    return {
        "fixed_time_mss": C.FixedTimeMSS(beta1=[0.05, 0.5], q1=0.6, beta2=[0.01, 0.1], q2=1.2, alpha1=[0.1, 1.0],
                                         gamma1=0.6, alpha2=[0.01, 0.1], gamma2=1.2, s1_floor=1e-6),
        "super_twisting": C.SuperTwisting(b1=list(2e-3 * inertia), b2=list(2e-5 * inertia), c=[0.05, 0.5],
                                          variant="standard"),
        "pd_sliding_mode": C.PDSlidingMode(lambda_=[0.1, 0.5], k=[2e-5, 1e-3], **layer),
        "fast_terminal_smc": C.FastTerminalSMC(**terminal),
        "fuzzy_fast_terminal_smc": C.FuzzyFastTerminalSMC(**terminal, n=1.0, m=1e4),
        "integral_exponential_reaching": C.IntegralExponentialReaching(**surface, epsilon=[2e-5, 1e-3], **layer),
        "fuzzy_variable_rate": C.FuzzyVariableRate(**surface, ke=[1e4, 1e3], kec=[1e5, 1e4], ku=[4e-6, 2e-4]),
        "ntsmc": C.NTSMC(),
        "fixed_time_ntsmc": C.FixedTimeNTSMC(),
    }


def assert_within_engine_limits(u, t_max, throttle, pointing, *, cone_binds=True) -> np.ndarray:
    """Every finite applied force ``u`` (n, instants, 3) within its case's magnitude limit, throttle
    range and pointing cone, the magnitude bound (and the cone, unless told) binding somewhere: the
    constraints exercised, not idle. Returns the mask of finite instants."""
    live = np.isfinite(u).all(axis=2)
    mag = np.linalg.norm(u, axis=2)
    angle = np.arccos(np.clip(u[..., 2] / mag, -1, 1))
    per = lambda v: np.broadcast_to(np.asarray(v)[:, None], mag.shape)[live]  # noqa: E731
    assert (mag[live] <= per(t_max) * (1 + 1e-15)).all()
    assert (mag[live] >= per(throttle * t_max) * (1 - 1e-15)).all()
    assert (angle[live] <= per(pointing) + 1e-12).all()
    assert np.isclose(mag[live], per(t_max), rtol=1e-12).any()
    if cone_binds:
        assert np.isclose(angle[live], per(pointing), atol=1e-9).any()
    return live


def crash_after_chunks(monkeypatch, chunks: int) -> None:
    """Makes the campaigns run under ``monkeypatch`` raise KeyboardInterrupt when a store's
    manifest is about to record chunk ``chunks`` as complete (its files written, the manifest
    not): the first ``chunks`` chunks are kept, as after a Ctrl-C or a kill at that moment."""
    from landing.campaign.store import CampaignStore

    original, calls = CampaignStore._write_manifest, []

    def write(self):
        calls.append(1)
        if len(calls) == chunks + 2:  # the empty manifest, then one per completed chunk
            raise KeyboardInterrupt
        original(self)

    monkeypatch.setattr(CampaignStore, "_write_manifest", write)
