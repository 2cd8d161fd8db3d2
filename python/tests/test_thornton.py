"""Thornton's elastic–perfectly plastic law from Python (physics.md, "Elastic–plastic impacts"):
impact(law="thornton") against `sweep impact --law thornton --json`, simulate(yield_pressure=…)
of steel shot below and above its yield speed against the elastic answer and Thornton's closed
form of e_n written out here, and the refusals of bad limiting pressures."""

from __future__ import annotations

import json
import math
import subprocess

import numpy as np
import pytest

import oblique
from oblique import RIGID, Material, Sphere

STEEL = Material(2.1e11, 0.29)
SIM_TOL = 1e-7

#: The elastic impact's peak pressure at v_z0 = 1, p_0 = (2/π)(15/16)^(1/5) (units of E*).
P0 = 2.0 / math.pi * (15.0 / 16.0) ** 0.2


def thornton_e_n(r: float) -> float:
    """Thornton's closed form of e_n for r = V_y/V (physics.md), 1 for r ≥ 1."""
    if r >= 1.0:
        return 1.0
    lead = math.sqrt(6.0 * math.sqrt(3.0) / 5.0) * math.sqrt(1.0 - r * r / 6.0)
    return lead * (r / (r + 2.0 * math.sqrt(6.0 / 5.0 - r * r / 5.0))) ** 0.25


def yield_speed(p_y: float, e_star: float, radius: float, mass: float) -> float:
    """V_y (m/s) at which the Hertz peak pressure reaches p_y (Pa): ½ m* V_y² = (2/5) k d_y^(5/2),
    k = (4/3) E* √R*, d_y = R* (π p_y/(2 E*))²."""
    d_y = radius * (math.pi * p_y / (2.0 * e_star)) ** 2
    k = 4.0 / 3.0 * e_star * math.sqrt(radius)
    return math.sqrt(2.0 * 0.4 * k * d_y**2.5 / mass)


# ---------------------------------------------------------------------------------------------
# impact(law="thornton")


@pytest.mark.parametrize("gamma,alpha,e_n", [(1.754, 1.0, 0.8), (1.3, 0.4, 0.6)])
def test_impact_equals_sweep_impact(sweep_bin, gamma, alpha, e_n):
    r = oblique.impact(gamma, alpha, 1e-6, e_n=e_n, law="thornton")
    cmd = [str(sweep_bin), "impact", "--law", "thornton", "--gamma", repr(gamma),
           "--alpha", repr(alpha), "--e-n", repr(e_n), "--tol", "1e-6", "--json"]
    out = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    j = json.loads(out.stdout)
    assert j["law"] == "thornton"
    # The same solver, the same request: the same bits.
    assert r.p == j["P"] and r.error_estimate == j["error_estimate"]
    assert r.yield_pressure == j["yield_pressure"] > 0 and r.tau == j["tau"] == 0.0
    assert r.e_n == e_n and not r.closed_form and 0 < r.error_estimate <= 1e-6


def test_impact_broadcasts_and_reports_the_limiting_pressure():
    e = np.array([0.6, 0.8, 0.95])
    r = oblique.impact(np.array([[1.3], [1.754]]), 1.0, 1e-6, e_n=e, law="thornton")
    assert r.p.shape == r.yield_pressure.shape == r.tau.shape == (2, 3)
    # physics.md: p_y giving e_n = 0.6 / 0.8 / 0.95 is 0.214225241 / 0.350980351 / 0.501431593.
    np.testing.assert_allclose(r.yield_pressure[0], [0.214225241, 0.350980351, 0.501431593],
                               atol=1e-9)
    np.testing.assert_array_equal(r.yield_pressure[0], r.yield_pressure[1])
    assert np.all(r.tau == 0.0) and np.all(r.yield_pressure < P0)
    for i, g in enumerate((1.3, 1.754)):
        for k, en in enumerate(e):
            assert r.p[i, k] == oblique.impact(g, 1.0, 1e-6, e_n=float(en), law="thornton").p
    # At the same e_n the law changes P (physics.md: by 0.1–0.5 at γ = 1.75, e_n = 0.8–0.6).
    kv = oblique.impact(1.754, 1.0, 1e-6, e_n=e)
    assert np.all(kv.yield_pressure == 0.0) and np.all(kv.tau > 0)
    assert abs(r.p[1, 0] - kv.p[0]) > 0.05
    # At e_n = 1 every law is the elastic one: the same answer, with Thornton's p̂_y = p_0 (every
    # p_y ≥ p_0 leaves the impact elastic).
    one = oblique.impact(1.754, 1.0, 1e-6, e_n=1.0, law="thornton")
    assert one.p == oblique.impact(1.754, 1.0, 1e-6).p
    assert math.isclose(one.yield_pressure, P0, rel_tol=1e-12) and one.tau == 0.0


# ---------------------------------------------------------------------------------------------
# simulate(yield_pressure=…)

#: Steel shot (R = 1 mm, 7800 kg/m³) on a steel wall, limiting pressure 2 GPa: V_y ≈ 0.24 m/s.
SHOT = Sphere(7800.0 * 4.0 / 3.0 * math.pi * 1e-3**3, 1e-3)
P_Y = 2.0e9


def shot(v_z, **kw):
    return oblique.simulate(SHOT, 0.3 * v_z, v_z, friction=0.3, materials=(STEEL, STEEL),
                            tol=SIM_TOL, **kw)


def test_steel_shot_below_its_yield_speed_is_elastic():
    sim = shot(0.1, yield_pressure=P_Y)
    g = sim.groups
    assert yield_speed(P_Y, g.e_star, g.radius, g.normal_mass) > 0.2
    elastic = shot(0.1)
    assert (sim.law, sim.e_n, sim.tau) == ("thornton", 1.0, 0.0)
    assert math.isclose(sim.yield_pressure, P0, rel_tol=1e-12)
    # The elastic run, bit for bit.
    assert (sim.p, sim.v_x, sim.v_z, sim.omega) == (elastic.p, elastic.v_x, elastic.v_z,
                                                    elastic.omega)
    assert (elastic.law, elastic.yield_pressure, elastic.tau) == ("elastic", 0.0, 0.0)


@pytest.mark.parametrize("v_z", [2.0, 5.0])
def test_steel_shot_above_its_yield_speed_rebounds_with_thorntons_e_n(v_z):
    sim = shot(v_z, yield_pressure=P_Y)
    g = sim.groups
    r = yield_speed(P_Y, g.e_star, g.radius, g.normal_mass) / v_z
    assert r < 0.15
    assert sim.law == "thornton" and sim.tau == 0.0
    assert math.isclose(sim.e_n, thornton_e_n(r), rel_tol=1e-12)
    assert 0.3 < sim.e_n < 0.75
    # p̂_y = p_0 (V_y/V)^(2/5), and the wall reverses the normal velocity with e_n.
    assert math.isclose(sim.yield_pressure, P0 * r**0.4, rel_tol=1e-12)
    assert math.isclose(sim.v_z, -sim.e_n * v_z, rel_tol=1e-9)
    # The plastic contact lasts longer and goes deeper than the elastic one.
    elastic = shot(v_z)
    assert sim.max_indentation > elastic.max_indentation
    assert sim.peak_force < elastic.peak_force
    # P depends on (γ, α, e_n) only: the dimensionless impact of the same groups.
    imp = oblique.impact(g.gamma, g.alpha, SIM_TOL, e_n=sim.e_n, law="thornton")
    assert math.isclose(imp.yield_pressure, sim.yield_pressure, rel_tol=1e-9)
    assert abs(sim.p - imp.p) <= sim.error_estimate + imp.error_estimate + 1e-9
    assert abs(sim.p - elastic.p) > 0.01


@pytest.mark.parametrize("bad", [0.0, -1.0e9, math.nan, math.inf, -math.inf])
def test_a_bad_yield_pressure_is_refused_by_name(bad):
    with pytest.raises(ValueError, match="yield_pressure"):
        shot(1.0, yield_pressure=bad)


def test_a_yield_pressure_too_low_for_the_speed_and_both_laws_are_refused():
    # e_n would fall below 0.3.
    with pytest.raises(ValueError, match=r"yield_pressure.*0\.3"):
        shot(20.0, yield_pressure=1e8)
    with pytest.raises(ValueError, match="relaxation_time and yield_pressure"):
        shot(1.0, yield_pressure=P_Y, relaxation_time=1e-7)
    with pytest.raises(ValueError, match="relaxation_time and yield_pressure"):
        shot(1.0, yield_pressure=P_Y, relaxation_time=0.0)
    # A rigid wall: E* is the sphere's alone, and the law still applies.
    sim = oblique.simulate(SHOT, 0.0, 2.0, friction=0.3, materials=(STEEL, RIGID),
                           yield_pressure=P_Y)
    g = sim.groups
    r = yield_speed(P_Y, g.e_star, g.radius, g.normal_mass) / 2.0
    assert math.isclose(sim.e_n, thornton_e_n(r), rel_tol=1e-12) and math.isnan(sim.p)
