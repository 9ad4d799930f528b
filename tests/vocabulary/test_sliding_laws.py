"""Laws 1-5 (docs/parameters.md) against hand recursions on a double integrator.

On q'' = u with the command held over each period (and a fixed target), one period maps
(e, e') to (e + dt e' + dt^2 u / 2, e' + dt u) exactly, so a law's sequence of sliding
variables can be computed independently in numpy from its printed formula."""

import numpy as np
import pytest

import landing
from _cases import numpy_block
from landing import controllers
from landing.plants import DoubleIntegrator

DT = 0.01
X0 = np.array([4.0, -2.0, 0.5, 0.3, 1.0, -0.8])


def run(law, steps=300, x0=X0, **kw):
    return landing.simulate(DoubleIntegrator(), law, x0, t_final=steps * DT, dt=DT, **kw)


def propagate(command, steps, x0=X0):
    """Exact held-command propagation of the double integrator; command(k, e, de) -> u."""
    e, de = x0[:3].copy(), x0[3:].copy()
    out = [(e.copy(), de.copy(), None)]
    for k in range(steps):
        u = command(k, e, de)
        e, de = e + DT * de + 0.5 * DT**2 * u, de + DT * u
        out.append((e.copy(), de.copy(), u))
    return out


def switch(kind, s, phi):
    return {"sign": np.sign(s), "sat": np.clip(s / phi, -1, 1), "tanh": np.tanh(s / phi)}[kind]


@pytest.mark.parametrize("kind", ["sign", "sat", "tanh"])
def test_pd_sliding_mode(kind):
    lam, k, phi = np.array([1.0, 2.0, 0.5]), np.array([0.8, 0.5, 1.2]), 0.3
    law = controllers.PDSlidingMode(lambda_=lam, k=k, switch=kind, boundary_layer=phi)
    ref = propagate(lambda i, e, de: -lam * de - k * switch(kind, de + lam * e, phi), 300)
    res = run(law)
    np.testing.assert_allclose(res.states[:, :3], [r[0] for r in ref], rtol=1e-10, atol=1e-12)
    np.testing.assert_allclose(res.diagnostics["s"], [r[1] + lam * r[0] for r in ref], rtol=1e-10, atol=1e-12)


def terminal_command(alpha, beta, r, k, kind, phi, floor):
    def command(i, e, de):
        s = de + alpha * e + beta * np.sign(e) * np.abs(e) ** r
        slope = np.where(np.abs(e) >= floor, np.abs(e) ** (r - 1), floor ** (r - 1))
        return -(alpha + beta * r * slope) * de, -k * switch(kind, s, phi), s
    return command


def test_fast_terminal_smc():
    alpha, beta, p, q, k = np.array([1.0, 0.5, 2.0]), np.array([0.6, 1.0, 0.3]), 3.0, 5.0, np.array([0.7, 0.4, 0.9])
    law = controllers.FastTerminalSMC(alpha=alpha, beta=beta, p=p, q=q, k=k, switch="tanh", boundary_layer=0.2)
    parts = terminal_command(alpha, beta, p / q, k, "tanh", 0.2, 1e-3)
    ref = propagate(lambda i, e, de: sum(parts(i, e, de)[:2]), 400)
    res = run(law, steps=400)
    np.testing.assert_allclose(res.states[:, :3], [r[0] for r in ref], rtol=1e-9, atol=1e-12)
    # it reaches the target and stays finite through e = 0 (the floor guards |e|^(p/q - 1))
    assert np.all(np.isfinite(res.controls))


def test_fuzzy_fast_terminal_smc_blends_as_printed():
    alpha, beta, k, n, m = np.array([1.0, 0.5, 2.0]), np.array([0.6, 1.0, 0.3]), np.array([0.7, 0.4, 0.9]), 2.0, 3.0
    law = controllers.FuzzyFastTerminalSMC(alpha=alpha, beta=beta, p=3, q=5, k=k, n=n, m=m)
    parts = terminal_command(alpha, beta, 0.6, k, "sign", 1.0, 1e-3)

    def command(i, e, de):
        eq, sw, s = parts(i, e, de)
        dist = np.linalg.norm(s / np.sqrt(1 + alpha**2))
        return np.exp(-n * dist) * eq + (1 - np.exp(-m * dist)) * sw

    ref = propagate(command, 300)
    res = run(law)
    np.testing.assert_allclose(res.states[:, :3], [r[0] for r in ref], rtol=1e-9, atol=1e-12)
    a, b, dist = (res.diagnostics[x] for x in ("a", "b", "distance"))
    assert a.shape == (301,)
    np.testing.assert_allclose(a, np.exp(-n * dist))
    np.testing.assert_allclose(b, 1 - np.exp(-m * dist))
    assert a[0] < a[-1] and b[0] > b[-1]  # far: switching part; near: equivalent control


@pytest.mark.parametrize("epsilon", [0.0, 0.05])
def test_integral_exponential_reaching_law(epsilon):
    """With the integral advanced once per period, a fixed target and q'' = u, one
    period gives exactly s(k+1) = s(k) - dt (k s(k) + epsilon sgn(s(k)))."""
    c1, c2, gain = np.array([0.5, 1.0, 2.0]), np.array([1.0, 1.5, 3.0]), np.array([0.8, 0.3, 1.1])
    law = controllers.IntegralExponentialReaching(c1=c1, c2=c2, k=gain, epsilon=epsilon)
    res = run(law, steps=200)
    s = res.diagnostics["s"]
    np.testing.assert_allclose(s[0], -X0[3:])  # s(0) = -sigma'(0) with I(0) = 0
    np.testing.assert_allclose(s[1:], s[:-1] - DT * (gain * s[:-1] + epsilon * np.sign(s[:-1])), atol=1e-12)
    # and the integral is the rectangle-rule integral of c1 sigma + c2 sigma'
    e, de = res.states[:, :3], res.states[:, 3:]
    np.testing.assert_allclose(res.diagnostics["integral"][1:], np.cumsum(c1 * e[:-1] + c2 * de[:-1], axis=0) * DT,
                               atol=1e-12)


def test_fuzzy_variable_rate_law():
    c1, c2, gain = 0.5, 1.0, 0.4
    ke, kec, ku = 1.0, 2.0, 0.05
    law = controllers.FuzzyVariableRate(c1=c1, c2=c2, k=gain, ke=ke, kec=kec, ku=ku)
    res = run(law, steps=150)
    s, ds, eps = res.diagnostics["s"], res.diagnostics["s_dot"], res.diagnostics["epsilon"]
    np.testing.assert_allclose(ds[1:], (s[1:] - s[:-1]) / DT, rtol=1e-9, atol=1e-12)
    assert np.all(ds[0] == 0)
    system = landing.fuzzy.variable_rate_system()
    fuzzy = ku * system.evaluate(np.column_stack([ke * s.ravel(), kec * ds.ravel()])).reshape(s.shape)
    np.testing.assert_allclose(eps, fuzzy, atol=1e-12)
    # the fuzzy output replaces epsilon sgn(s) in the reaching law
    np.testing.assert_allclose(s[1:], s[:-1] - DT * (gain * s[:-1] + eps[:-1]), atol=1e-12)


def test_command_noise_is_a_fraction_of_the_command():
    """OpenLoop a on a double integrator: dv / dt = a (1 + n_k), n_k from stream 2 of the case."""
    a = np.array([0.5, -2.0, 1.0])
    res = landing.simulate(DoubleIntegrator(), controllers.OpenLoop(acceleration=a), np.zeros(6), t_final=1.0, dt=0.1,
                           integrator="euler", disturbance=landing.disturbances.CommandNoise(0.01), seed=21,
                           first_case=3)
    n = np.diff(res.states[:, 3:], axis=0) / (0.1 * a) - 1.0
    for k in range(n.shape[0]):
        raw = numpy_block([k, 3, 0, 0], [21, 2])[:3]
        u = np.array([(r >> 11) * 2.0**-53 for r in raw])
        np.testing.assert_allclose(n[k], 0.01 * (2 * u - 1), atol=1e-12)


def test_laws_refuse_bad_gains():
    with pytest.raises(ValueError, match="q = 3 violates q > p"):
        controllers.FastTerminalSMC(alpha=1, beta=1, p=5, q=3, k=1)
    with pytest.raises(ValueError, match="lambda_ = 0 violates lambda_ > 0"):
        controllers.PDSlidingMode(lambda_=0.0, k=1.0)
    with pytest.raises(ValueError, match="boundary_layer = 0 violates boundary_layer > 0"):
        controllers.PDSlidingMode(lambda_=1.0, k=1.0, switch="tanh", boundary_layer=0.0)
    with pytest.raises(ValueError, match="switch"):
        controllers.PDSlidingMode(lambda_=1.0, k=1.0, switch="smooth")
    with pytest.raises(ValueError, match="n = -1 violates n > 0"):
        controllers.FuzzyFastTerminalSMC(alpha=1, beta=1, p=3, q=5, k=1, n=-1.0, m=1.0)
    with pytest.raises(ValueError, match="c1"):
        controllers.IntegralExponentialReaching(c1=-1.0, c2=1.0, k=1.0, epsilon=0.1)
    with pytest.raises(ValueError, match="ku"):
        controllers.FuzzyVariableRate(c1=1.0, c2=1.0, k=1.0, ke=1.0, kec=1.0, ku=0.0)
    with pytest.raises(ValueError, match="fraction"):
        landing.disturbances.CommandNoise(-0.1)
