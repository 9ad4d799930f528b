"""Gravity fields and the small-body plant against independent computations."""

import numpy as np
import pytest

import landing
from landing import gravity

FIELDS = [
    gravity.PointMass(mu=4.46e5),
    gravity.TwoPointMass(),
    gravity.Harmonic2(),
    gravity.Harmonic2(mu=1e6, r0=5000.0, c20=0.3, c22=-0.2),
]
POINTS = np.array([[3200.0, 1300.0, 9000.0], [550.0, 500.0, 8200.0], [-2e4, 7e3, -3e3], [1.5e4, -1.4e4, 500.0]])


@pytest.mark.parametrize("field", FIELDS, ids=lambda f: type(f).__name__)
def test_field_is_the_gradient_of_the_potential(field):
    h = 0.5
    g = field.acceleration(POINTS)
    for j in range(3):
        e = np.zeros(3)
        e[j] = h
        fd = (field.potential(POINTS + e) - field.potential(POINTS - e)) / (2 * h)
        np.testing.assert_allclose(g[:, j], fd, rtol=1e-6, atol=1e-12)


@pytest.mark.parametrize("field", FIELDS, ids=lambda f: type(f).__name__)
def test_field_attracts(field):
    far = POINTS * 10
    g = field.acceleration(far)
    assert np.all(np.einsum("ij,ij->i", g, far) < 0)
    assert np.all(field.potential(far) > 0)


def test_point_mass_closed_form():
    r = np.array([3.0, 4.0, 12.0])
    np.testing.assert_allclose(gravity.PointMass(mu=2.0).acceleration(r), -2.0 * r / 13.0**3)
    assert gravity.PointMass(mu=2.0).potential(r) == pytest.approx(2.0 / 13.0)


def test_two_point_mass_is_the_sum_of_two_point_masses():
    tp = gravity.TwoPointMass(m1=1e15, m2=3e15, position1=[1000, 0, 0], position2=[-500, 200, 0])
    r = POINTS
    g1 = gravity.PointMass(mu=gravity.G * 1e15).acceleration(r - [1000, 0, 0])
    g2 = gravity.PointMass(mu=gravity.G * 3e15).acceleration(r - [-500, 200, 0])
    np.testing.assert_allclose(tp.acceleration(r), g1 + g2, rtol=1e-13)


def test_harmonic_field_tends_to_the_point_mass():
    h = gravity.Harmonic2()
    pm = gravity.PointMass(mu=h.mu)
    direction = np.array([0.3, -0.5, 0.8]) / np.linalg.norm([0.3, -0.5, 0.8])
    rel = []
    for dist in (1e4, 1e5, 1e6):
        r = direction * dist
        rel.append(np.linalg.norm(h.acceleration(r) - pm.acceleration(r)) / np.linalg.norm(pm.acceleration(r)))
    # the quadrupole falls off as (R0 / r)^2 relative to the monopole
    assert rel[1] / rel[0] == pytest.approx(1e-2, rel=0.05)
    assert rel[2] / rel[1] == pytest.approx(1e-2, rel=0.05)


def test_inertially_fixed_point_seen_from_the_rotating_frame():
    """No gravity to speak of, no control: a point at rest in inertial space turns backwards at
    omega in the body frame; only the Coriolis and centrifugal terms can reproduce it."""
    w = 3.3118e-4
    plant = landing.plants.SmallBody(gravity=gravity.PointMass(mu=1e-30), omega=w)
    big = np.array([3200.0, 1300.0, 9000.0])
    x0 = np.r_[big, w * big[1], -w * big[0], 0.0]
    res = landing.simulate(plant, landing.controllers.OpenLoop(), x0, t_final=4000.0, dt=1.0, record_every=100)
    th = w * res.t
    expect = np.stack([big[0] * np.cos(th) + big[1] * np.sin(th), -big[0] * np.sin(th) + big[1] * np.cos(th),
                       np.full_like(th, big[2])], axis=1)
    np.testing.assert_allclose(res.states[:, :3], expect, atol=1e-6)


def test_the_seed_000_reference_coefficients():
    """Seed 000 eq. 9-10 print c2, c3 per axis for the Table 1 boundary states (T = 8000 s)."""
    ref = landing.reference.Cubic.from_boundary([3200, 1300, 9000], [-1.2, 0.2, -1], [2837, 928.1, 5708], [0, 0, 0],
                                                8000)
    c = ref.coefficients
    printed = {0: (2.83e-4, -1.73e-8), 1: (-6.74e-5, 4.58e-9), 2: (9.57e-5, -2.76e-9)}
    # three printed digits, some rounded and some truncated: within one unit of the last digit
    for axis, (c2, c3) in printed.items():
        assert abs(c[axis, 2] - c2) <= 0.01 * abs(c2)
        assert abs(c[axis, 3] - c3) <= 0.01 * abs(c3)
        assert abs(c[axis, 2] - c2) <= 1e-2 * 10 ** np.floor(np.log10(abs(c2)))
        assert abs(c[axis, 3] - c3) <= 1e-2 * 10 ** np.floor(np.log10(abs(c3)))
    np.testing.assert_array_equal(c[:, 0], [3200, 1300, 9000])
    np.testing.assert_array_equal(c[:, 1], [-1.2, 0.2, -1])


def test_gravity_rejects_bad_input():
    with pytest.raises(ValueError, match="mu = -1 violates mu > 0"):
        gravity.PointMass(mu=-1.0)
    with pytest.raises(ValueError, match="r0"):
        gravity.Harmonic2(r0=0.0)
    with pytest.raises(ValueError, match=r"r has shape \(2,\)"):
        gravity.PointMass(mu=1.0).acceleration([1.0, 2.0])
    with pytest.raises(TypeError, match="gravity must be a landing.gravity field"):
        landing.plants.SmallBody(gravity=3.0)
