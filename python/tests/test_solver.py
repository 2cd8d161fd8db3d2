"""The solver from Python: impact() (P(γ, α) simulated), simulate() (one impact in physical
units), groups() (γ, α and the effective quantities), against the table, the closed forms of
physics.md and Hertz theory."""

from __future__ import annotations

import math

import numpy as np
import pytest

import oblique
from oblique import RIGID, Material, Sphere
from _oblique_helpers import alpha_c1, alpha_c2, alpha_lin, effective_moduli, masses

TOL = 1e-7

# Partial slip (γ > 1, α_c1 < α < α_c2) and stick (α ≥ α_c2; γ < 1 past the line), and the
# no-slip limit.
POINTS = [
    (1.2, 0.5 * (float(alpha_c1(1.2)) + float(alpha_c2(1.2)))),
    (1.6, 0.5),
    (2.0, 0.9),
    (2.9, 1.5),
    (3.3, 2.0),
    (1.5, 1.2),
    (2.4, 4.0),
    (0.8, 0.6),
    (0.4, 0.3),
    (0.9, math.inf),
    (1.8, math.inf),
]


def test_points_are_where_they_should_be():
    for g, a in POINTS:
        assert a > alpha_lin(g)
        assert oblique.regime(g, a) in ("partial-slip", "stick")
    assert {oblique.regime(g, a) for g, a in POINTS} == {"partial-slip", "stick"}


@pytest.mark.parametrize("gamma,alpha", POINTS)
def test_impact_agrees_with_table(full, gamma, alpha):
    r = oblique.impact(gamma, alpha, TOL)
    assert type(r.p) is float and isinstance(r.closed_form, (bool, np.bool_))
    assert not r.closed_form
    assert 0 < r.error_estimate <= TOL
    assert r.steps > 0
    assert abs(r.p - full.p(gamma, alpha)) <= full.error_bound + TOL
    assert abs(r.p) <= 1.0


def test_impact_closed_forms():
    gammas = np.array([0.3, 0.8, 1.0, 1.3, 2.0, 3.4, 10.0])
    for g in gammas:
        for frac in (0.0, 0.3, 0.999, 1.0):
            a = frac * float(alpha_lin(g))
            r = oblique.impact(g, a, TOL)
            assert r.closed_form, (g, a)
            assert r.p == 1.0 - 7.0 * a, (g, a, r.p)
            assert r.error_estimate == 0.0 and r.steps == 0
    # γ = 1: P = −1 for α ≥ 2/7 (physics.md).
    for a in (2.0 / 7.0, 0.5, 3.0, math.inf):
        r = oblique.impact(1.0, a, TOL)
        assert r.closed_form and r.p == -1.0
    # simulate=True simulates on the line too, and finds the line.
    r = oblique.impact(1.6, 0.05, TOL, simulate=True)
    assert not r.closed_form and r.steps > 0
    assert abs(r.p - (1.0 - 7.0 * 0.05)) <= TOL + r.error_estimate


def test_impact_broadcasts():
    g = np.array([0.7, 1.5, 2.2])
    a = np.array([[0.02], [0.8]])
    r = oblique.impact(g, a, 1e-6)
    assert r.p.shape == r.error_estimate.shape == (2, 3)
    assert r.closed_form.shape == r.springs.shape == r.steps.shape == (2, 3)
    assert r.closed_form.dtype == np.bool_
    assert r.springs.dtype == np.int64 and r.steps.dtype == np.int64
    assert np.all(r.closed_form[0]) and not np.any(r.closed_form[1])
    for i in range(2):
        for j in range(3):
            one = oblique.impact(float(g[j]), float(a[i, 0]), 1e-6)
            assert one.p == r.p[i, j]
            assert one.error_estimate == r.error_estimate[i, j]
            assert one.closed_form == r.closed_form[i, j] and one.steps == r.steps[i, j]
    s = oblique.impact(1.5, 0.8, 1e-6)
    assert type(s.p) is float and type(s.error_estimate) is float
    assert type(s.springs) is int and type(s.steps) is int
    e = oblique.impact(np.empty(0), 0.5)
    assert e.p.shape == (0,)


STEEL = Material(2.1e11, 0.29)
GLASS = Material(6.3e10, 0.22)
ALUMINIUM = Material(7.0e10, 0.33)
SIM_TOL = 1e-7

CASES = {
    "solid sphere on a rigid wall": dict(
        sphere=Sphere(0.033, 0.01), v_x=1.3, v_z=2.0, omega=-40.0, friction=0.25,
        materials=(STEEL, RIGID)),
    "glass sphere on a steel wall": dict(
        sphere=Sphere(0.011, 0.01), v_x=-0.4, v_z=1.1, omega=0.0, friction=0.9,
        materials=(GLASS, STEEL)),
    "thin shell on a solid sphere": dict(
        sphere=Sphere(0.02, 0.015, 2.0 / 3.0), v_x=0.8, v_z=1.5, omega=30.0, friction=0.3,
        materials=(ALUMINIUM, GLASS), other=Sphere(0.05, 0.01, 0.4),
        other_v_x=-0.3, other_v_z=-0.7, other_omega=-25.0),
    "steel on hollow aluminium, sticking": dict(
        sphere=Sphere(0.1, 0.0145), v_x=0.2, v_z=3.0, omega=5.0, friction=2.0,
        materials=(STEEL, ALUMINIUM), other=Sphere(0.03, 0.02, 0.55),
        other_v_x=0.1, other_v_z=0.5, other_omega=-3.0),
}


@pytest.mark.parametrize("case", list(CASES))
def test_simulate_agrees_with_rebound_2d(full, case):
    kw = dict(CASES[case])
    sphere = kw.pop("sphere")
    sim = oblique.simulate(sphere, **kw, tol=SIM_TOL)
    reb = full.rebound_2d(sphere, **kw)
    wall = "other" not in kw
    assert 0 < sim.error_estimate <= SIM_TOL
    dp = abs(sim.p - reb.p)
    allowed = full.error_bound + sim.error_estimate
    assert dp <= allowed, (sim.p, reb.p)
    # The physical-units simulation and the dimensionless one at the mapped (γ, α) agree to
    # their error estimates (physics.md: to ~1e-9), whatever the table's error.
    imp = oblique.impact(sim.groups.gamma, sim.groups.alpha, SIM_TOL)
    assert abs(sim.p - imp.p) <= sim.error_estimate + imp.error_estimate
    # Same groups.
    assert math.isclose(sim.groups.gamma, reb.gamma, rel_tol=1e-14)
    assert math.isclose(sim.groups.alpha, reb.alpha, rel_tol=1e-14)
    # The velocities follow from P: Δv_x = J/m, Δω = J R/I with J = m_t (1 − P) u0.
    u0 = reb.slip_before
    m_t = sim.groups.tangential_mass
    dj = allowed * abs(u0) * m_t
    m1, r1, k1 = (float(x) for x in sphere)
    assert abs(sim.v_x - reb.v_x) <= dj / m1 * (1 + 1e-6) + 1e-12
    assert abs(sim.omega - reb.omega) <= dj * r1 / (k1 * m1 * r1**2) * (1 + 1e-6) + 1e-9
    # Elastic normal motion: the approach velocity reverses.
    assert math.isclose(sim.v_z, reb.v_z, rel_tol=1e-9)
    if wall:
        assert sim.other_v_x is None and reb.other_v_x is None
        assert math.isclose(sim.v_z, -kw["v_z"], rel_tol=1e-9)
    else:
        m2, r2, k2 = (float(x) for x in kw["other"])
        assert abs(sim.other_v_x - reb.other_v_x) <= dj / m2 * (1 + 1e-6) + 1e-12
        assert abs(sim.other_omega - reb.other_omega) <= dj * r2 / (k2 * m2 * r2**2) * (
            1 + 1e-6) + 1e-9
        assert math.isclose(sim.other_v_z, reb.other_v_z, rel_tol=1e-9)
        assert math.isclose(sim.v_z - sim.other_v_z, -(kw["v_z"] - kw["other_v_z"]),
                            rel_tol=1e-9)
    # Hertz (normal contact, elastic): maximum indentation δ = (15 m* v²/(16 E* √R*))^(2/5),
    # peak force (4/3) E* √R* δ^(3/2), contact time 2.9432 (15 m*/(16 E* √R*))^(2/5) v^(-1/5).
    g = sim.groups
    m_s, e_s, r_s, v = g.normal_mass, g.e_star, g.radius, g.approach_speed
    delta = (15 * m_s * v**2 / (16 * e_s * math.sqrt(r_s))) ** 0.4
    assert math.isclose(sim.max_indentation, delta, rel_tol=1e-3)
    assert math.isclose(sim.peak_force, 4 / 3 * e_s * math.sqrt(r_s) * delta**1.5, rel_tol=2e-3)
    t_c = 2.943275 * (15 * m_s / (16 * e_s * math.sqrt(r_s))) ** 0.4 * v**-0.2
    assert math.isclose(sim.contact_time, t_c, rel_tol=1e-3)


@pytest.mark.parametrize("case", list(CASES))
def test_groups_closed_forms(full, case):
    kw = dict(CASES[case])
    sphere = kw.pop("sphere")
    g = oblique.groups(sphere, **kw)
    (e1, nu1), (e2, nu2) = kw["materials"]
    e_s, g_s = effective_moduli(e1, nu1, e2, nu2)
    m1, r1, k1 = (float(x) for x in sphere)
    other = kw.get("other")
    if other is None:
        m_s, m_t, r_s = masses(m1, r1, k1)
        vz0 = kw["v_z"]
        u0 = kw["v_x"] + r1 * kw["omega"]
    else:
        m2, r2, k2 = (float(x) for x in other)
        m_s, m_t, r_s = masses(m1, r1, k1, m2, r2, k2)
        vz0 = kw["v_z"] - kw["other_v_z"]
        u0 = (kw["v_x"] + r1 * kw["omega"]) - (kw["other_v_x"] - r2 * kw["other_omega"])
    for got, want in [
        (g.e_star, e_s), (g.g_star, g_s), (g.normal_mass, m_s), (g.tangential_mass, m_t),
        (g.radius, r_s), (g.approach_speed, vz0), (g.slip_velocity, u0),
        (g.gamma, math.sqrt(m_s / m_t * g_s / e_s)),
        (g.alpha, 2 / 7 * m_s / m_t * kw["friction"] * vz0 / abs(u0)),
    ]:
        assert math.isclose(got, float(want), rel_tol=1e-13), (got, want)
    # The same γ and α as the rebound of that impact.
    reb = full.rebound_2d(sphere, **kw)
    assert math.isclose(g.gamma, reb.gamma, rel_tol=1e-15)
    assert math.isclose(g.alpha, reb.alpha, rel_tol=1e-15)
    assert reb.p == full.p(g.gamma, g.alpha)


def test_groups_solid_sphere_on_wall():
    """Solid sphere on a wall: γ² = (7/2) G*/E*, α = μ v_z0/|v_x0 + R ω0|; broadcasts."""
    rng = np.random.default_rng(73)
    n = 500
    e1, nu1 = 10 ** rng.uniform(8, 12, n), rng.uniform(-0.9, 0.5, n)
    e2, nu2 = 10 ** rng.uniform(8, 12, n), rng.uniform(-0.9, 0.5, n)
    e2[:100] = np.inf  # a rigid wall
    m, r = 10 ** rng.uniform(-4, 1, n), 10 ** rng.uniform(-4, -1, n)
    vx, vz, om = rng.normal(size=n), rng.uniform(0.01, 5, n), rng.normal(size=n) / r
    mu = rng.uniform(0, 2, n)
    g = oblique.groups(Sphere(m, r), vx, vz, om, friction=mu,
                       materials=(Material(e1, nu1), Material(e2, nu2)))
    assert g.gamma.shape == (n,)
    e_s, g_s = effective_moduli(e1, nu1, e2, nu2)
    # Written out once more for the rigid wall: E* = E/(1 − ν²), G* = 4G/(2 − ν).
    g1 = e1 / (2 * (1 + nu1))
    np.testing.assert_allclose(e_s[:100], e1[:100] / (1 - nu1[:100] ** 2), rtol=1e-14)
    np.testing.assert_allclose(g_s[:100], 4 * g1[:100] / (2 - nu1[:100]), rtol=1e-14)
    np.testing.assert_allclose(g.e_star, e_s, rtol=1e-13)
    np.testing.assert_allclose(g.g_star, g_s, rtol=1e-13)
    np.testing.assert_allclose(g.gamma**2, 3.5 * g_s / e_s, rtol=1e-13)
    np.testing.assert_allclose(g.alpha, mu * vz / np.abs(vx + r * om), rtol=1e-12)
    np.testing.assert_allclose(g.tangential_mass, 2 * m / 7, rtol=1e-14)
    np.testing.assert_allclose(g.normal_mass, m, rtol=0)
    np.testing.assert_allclose(g.radius, r, rtol=0)
    # One material, both bodies: G*/E* = 2(1 − ν)/(2 − ν).
    same = oblique.groups(Sphere(m, r), vx, vz, friction=mu,
                          materials=(Material(e1, nu1), Material(e1, nu1)))
    np.testing.assert_allclose(same.gamma**2, 3.5 * 2 * (1 - nu1) / (2 - nu1), rtol=1e-13)
    # Broadcasting: (2, 1) × (3,).
    b = oblique.groups(Sphere(0.1, 0.01), [[0.5], [1.0]], [1.0, 2.0, 3.0], friction=0.4,
                       materials=(STEEL, RIGID))
    assert b.alpha.shape == (2, 3) and b.gamma.shape == (2, 3)
    np.testing.assert_allclose(b.alpha, 0.4 * np.array([1.0, 2.0, 3.0]) / [[0.5], [1.0]],
                               rtol=1e-14)
    s = oblique.groups(Sphere(0.1, 0.01), 0.5, 1.0, friction=0.4, materials=(STEEL, RIGID))
    assert type(s.gamma) is float and type(s.alpha) is float
    # u0 = 0: α = ∞.
    assert oblique.groups(Sphere(0.1, 0.01), 0.0, 1.0, friction=0.4,
                          materials=(STEEL, RIGID)).alpha == math.inf


# Dissipative impacts (Kelvin–Voigt law, physics.md "Dissipative impacts").


def test_impact_broadcasts_over_e_n_and_keeps_the_elastic_answer_at_one():
    e = np.array([0.5, 0.8, 1.0])
    r = oblique.impact(1.754, np.array([[0.5], [2.0]]), 1e-6, e_n=e)
    assert r.p.shape == (2, 3) and r.e_n.shape == (2, 3)
    np.testing.assert_array_equal(r.e_n, np.broadcast_to(e, (2, 3)))
    # τ̂ grows as e_n falls; 0 at e_n = 1, where the answer is the elastic solver's, bit for bit.
    assert np.all(r.tau[:, 0] > r.tau[:, 1]) and np.all(r.tau[:, 2] == 0.0)
    for i, a in enumerate((0.5, 2.0)):
        assert r.p[i, 2] == oblique.impact(1.754, a, 1e-6).p
        assert r.p[i, 0] == oblique.impact(1.754, a, 1e-6, e_n=0.5).p
    # At e_n = 0.5 the answer moves far from the elastic one (physics.md: up to 0.3–0.5).
    assert np.all(np.abs(r.p[:, 0] - r.p[:, 2]) > 0.1)
    assert np.all(np.abs(r.p) <= 1.0)


def test_the_dissipative_full_slip_line():
    # P = 1 − (7/2)(1 + e_n) α up to α_c1(e_n) = 2γ²/(7(γ²(1 + e_n) − e_n)).
    for g, e in ((1.2, 0.75), (2.5, 0.6)):
        c1 = 2 * g * g / (7 * (g * g * (1 + e) - e))
        for frac in (0.3, 0.999):
            a = frac * c1
            r = oblique.impact(g, a, 1e-7, e_n=e)
            assert r.closed_form and abs(r.p - (1 - 3.5 * (1 + e) * a)) < 1e-12
            s = oblique.impact(g, a, 1e-7, simulate=True, e_n=e)
            assert abs(s.p - (1 - 3.5 * (1 + e) * a)) <= s.error_estimate + 1e-9
        above = oblique.impact(g, 1.01 * c1, 1e-7, e_n=e)
        assert not above.closed_form and above.p - (1 - 3.5 * (1 + e) * 1.01 * c1) > 1e-5


def test_bad_restitution_and_law_are_refused_by_name():
    for bad in (0.2, 1.1, math.nan):
        with pytest.raises(ValueError, match=r"e_n.*0\.3"):
            oblique.impact(1.5, 0.3, e_n=bad)
    with pytest.raises(ValueError, match=r"e_n.*elastic"):
        oblique.impact(1.5, 0.3, e_n=0.9, law="elastic")
    with pytest.raises(ValueError, match=r"law.*kelvin-voigt"):
        oblique.impact(1.5, 0.3, e_n=0.9, law="plastic")
    with pytest.raises(ValueError, match="relaxation_time"):
        oblique.simulate(Sphere(0.01, 0.005), 1.0, 1.0, friction=0.3,
                         materials=(GLASS, GLASS), relaxation_time=-1.0)


def test_simulate_with_a_relaxation_time_matches_impact_at_its_e_n():
    # A glass bead on a glass wall with τ = 1e-7 s, then the same on a steel sphere.
    for kw in (dict(), dict(other=Sphere(0.05, 0.012), other_v_z=-0.5)):
        sim = oblique.simulate(Sphere(0.004, 0.007), 0.6, 2.0, 30.0, friction=0.3,
                               materials=(GLASS, GLASS if not kw else STEEL),
                               relaxation_time=1e-7, tol=SIM_TOL, **kw)
        assert 0.3 < sim.e_n < 1.0 and sim.tau > 0
        imp = oblique.impact(sim.groups.gamma, sim.groups.alpha, SIM_TOL, e_n=sim.e_n)
        assert abs(sim.p - imp.p) <= sim.error_estimate + imp.error_estimate
        assert math.isclose(imp.tau, sim.tau, rel_tol=1e-9)
        # The relative normal velocity reverses with e_n.
        before = 2.0 - kw.get("other_v_z", 0.0)
        after = sim.v_z - (sim.other_v_z if kw else 0.0)
        assert math.isclose(after, -sim.e_n * before, rel_tol=1e-9)


def test_impact_over_an_array_stops_at_ctrl_c():
    # 20 000 impacts at tol 1e-8 and γ = 3.3 take minutes; SIGINT after 0.5 s must raise
    # KeyboardInterrupt between two waves of rows, not after the whole array.
    import os
    import signal
    import threading
    import time

    g = np.full(20_000, 3.3)
    a = np.linspace(1.0, 3.0, 20_000)
    # Python's own Ctrl-C handler, even where the test runner was started with SIGINT ignored
    # (a background job of a shell without job control inherits SIG_IGN, and Python then
    # installs no handler: the signal would be dropped and the whole array computed).
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    timer = threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT))
    start = time.monotonic()
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            oblique.impact(g, a, 1e-8)
    finally:
        timer.cancel()
        signal.signal(signal.SIGINT, previous)
    assert time.monotonic() - start < 15.0
