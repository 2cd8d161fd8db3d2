"""Tables with a normal-restitution axis (schema 4, ``tables/dissipative-demo.h5``):
``Table.p(..., e_n=)`` and ``Table.rebound``/``rebound_2d(..., e_n=)``. The rebounds are checked
against the mechanics written out here: the relative normal velocity reverses to ``e_n`` times
its value, the kinetic energy lost (rotation included) is ``energy_lost``, and ``P`` is the
table's ``P(γ, α, e_n)`` bit for bit; e_n that a table does not answer is refused."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

import oblique
from oblique import RIGID, Material, Sphere
from _oblique_helpers import DISSIPATIVE

NAN = math.nan
S = Sphere(0.1, 0.01)
STEEL = Material(2.1e11, 0.29)


def _dot(a, b):
    return np.einsum("...i,...i->...", a, b)


def _gammas(t, rng, n):
    """`n` values of γ uniform over the table's γ domain."""
    return rng.uniform(t.info["gamma_min"], t.info["gamma_max"], n)


def _raises(exc, fn, *needles):
    with pytest.raises(exc) as info:
        fn()
    msg = str(info.value)
    for n in needles:
        assert re.search(n, msg), f"{n!r} not in message {msg!r}"
    return msg


# ---------------------------------------------------------------------------------------------
# Table.p


def test_info_states_the_e_n_range_and_the_law(dissipative, full):
    i = dissipative.info
    assert i["schema_version"] == 4
    assert (i["e_n_min"], i["e_n_max"]) == (0.5, 1.0)
    assert i["law"] == "kelvin-voigt"
    assert i["e_n_coordinate"] == "e_n"
    f = full.info
    assert (f["e_n_min"], f["e_n_max"]) == (1.0, 1.0)
    assert f["law"] == "elastic"
    assert f["e_n_coordinate"] is None


def test_p_broadcasts_over_e_n(dissipative):
    e = np.array([[0.5], [0.75], [1.0]])
    alpha = np.array([0.05, 0.3, 1.0, np.inf])
    p = dissipative.p(1.7, alpha, e_n=e)
    assert p.shape == (3, 4)
    for i, ei in enumerate(e[:, 0]):
        for j, aj in enumerate(alpha):
            assert p[i, j] == dissipative.p(1.7, float(aj), e_n=float(ei))
    # out=, and e_n as an array of the full shape.
    out = np.empty((3, 4))
    assert dissipative.p(1.7, alpha, out, e_n=np.broadcast_to(e, (3, 4))) is out
    np.testing.assert_array_equal(out, p)
    # e_n moves P: at α = ∞ (no slip) the contact-point restitution depends on e_n.
    assert np.all(np.abs(p[0] - p[2]) > 1e-3)
    assert np.all(np.abs(p) <= 1.0)


def test_p_at_e_n_one_is_close_to_the_elastic_table(dissipative, full):
    rng = np.random.default_rng(61)
    g = _gammas(dissipative, rng, 500)
    a = np.concatenate([rng.uniform(0.0, 3.0, 499), [np.inf]])
    bound = dissipative.error_bound + full.error_bound
    d = dissipative.p(g, a)  # e_n = 1, the default, is inside [0.5, 1]
    np.testing.assert_allclose(d, full.p(g, a), rtol=0, atol=bound)
    np.testing.assert_array_equal(d, dissipative.p(g, a, e_n=1.0))


def test_p_refuses_e_n_outside_the_table(dissipative, full):
    _raises(ValueError, lambda: full.p(1.5, 0.3, e_n=0.8), r"\be_n\b", r"elastic")
    _raises(ValueError, lambda: full.p([1.5, 1.5], 0.3, e_n=[1.0, 0.8]), r"\be_n\b",
            re.escape("(at index (1,))"))
    for bad in (0.4, 1.01, NAN, -np.inf):
        _raises(ValueError, lambda: dissipative.p(1.5, 0.3, e_n=bad), r"\be_n\b",
                re.escape("[0.5, 1]"))
    _raises(ValueError, lambda: dissipative.p(1.5, [0.1, 0.2, 0.3], e_n=[0.9, 0.6, 0.4]),
            r"\be_n\b", re.escape("[0.5, 1]"), re.escape("(at index (2,))"))


# ---------------------------------------------------------------------------------------------
# Rebounds


def _unit(rng, n):
    v = rng.normal(size=(n, 3))
    return v / np.linalg.norm(v, axis=1)[:, None]


def wall_impacts(t, n, seed):
    """Random 3-D sphere–wall impacts with γ inside the domain of table ``t``, e_n over the demo
    table's range (both ends included), μ finite, 0 and ∞, spins, and a few pure normal
    impacts."""
    rng = np.random.default_rng(seed)
    d = {
        "m": 10 ** rng.uniform(-3, 1, n),
        "r": 10 ** rng.uniform(-3, -1, n),
        "k": rng.uniform(0.2, 1.0, n),
        "gamma": _gammas(t, rng, n),
        "e_n": rng.uniform(0.5, 1.0, n),
        "mu": rng.uniform(0.0, 1.5, n),
    }
    d["e_n"][:20] = 0.5
    d["e_n"][20:40] = 1.0
    d["mu"][40:140] = np.inf
    d["mu"][140:240] = 0.0
    nh = _unit(rng, n)
    d["nh"] = nh
    d["n"] = nh * rng.uniform(0.3, 3.0, n)[:, None]
    v = rng.normal(size=(n, 3))
    vn = _dot(v, nh)
    d["v"] = v + (np.where(vn <= 0, -vn, 0.0) + rng.uniform(0.05, 2.0, n))[:, None] * nh
    d["w"] = rng.normal(size=(n, 3)) / d["r"][:, None]
    # Pure normal impacts (no slip): along an axis, without spin.
    k = slice(n - 30, n)
    axes = np.eye(3)[rng.integers(0, 3, 30)]
    d["nh"][k] = axes
    d["n"][k] = axes
    d["v"][k] = axes * rng.uniform(0.5, 2.0, 30)[:, None]
    d["w"][k] = 0.0
    return d


def run_wall(t, d, e_n=None):
    return t.rebound(
        Sphere(d["m"], d["r"], d["k"]),
        d["v"],
        d["w"],
        friction=d["mu"],
        normal=d["n"],
        gamma=d["gamma"],
        e_n=d["e_n"] if e_n is None else e_n,
    )


def _balance(lost_measured, lost, e0):
    """|ΔE − energy_lost| within 1e-9 of energy_lost plus 1e-13 of the energy before."""
    err = np.abs(lost_measured - lost)
    worst = np.argmax(err - (1e-9 * np.abs(lost) + 1e-13 * e0))
    assert np.all(err <= 1e-9 * np.abs(lost) + 1e-13 * e0), (
        f"energy balance at {worst}: {lost_measured[worst]!r} vs {lost[worst]!r}"
    )


def _kinetic(m, r, k, v, w):
    """Translation and rotation: m v²/2 + κ m R² ω²/2."""
    return 0.5 * m * _dot(v, v) + 0.5 * k * m * r**2 * _dot(w, w)


@pytest.fixture(scope="module")
def wall(dissipative):
    d = wall_impacts(dissipative, 4000, seed=67)
    return d, run_wall(dissipative, d)


def test_wall_normal_velocity_reverses_with_e_n(wall):
    d, r = wall
    np.testing.assert_array_equal(r.e_n, d["e_n"])
    before = _dot(d["v"], d["nh"])
    after = _dot(r.velocity, d["nh"])
    np.testing.assert_allclose(after, -d["e_n"] * before, rtol=1e-12, atol=0)
    np.testing.assert_allclose(r.approach_speed, before, rtol=1e-14)
    # Normal impulse (1 + e_n) m v_z0 on the wall.
    np.testing.assert_allclose(r.normal_impulse, (1 + d["e_n"]) * d["m"] * before, rtol=1e-14)


def test_wall_energy_balance(wall):
    d, r = wall
    m, rad, k = d["m"], d["r"], d["k"]
    e0 = _kinetic(m, rad, k, d["v"], d["w"])
    e1 = _kinetic(m, rad, k, r.velocity, r.spin)
    assert np.all(r.energy_lost >= 0)
    _balance(e0 - e1, r.energy_lost, e0)
    # The normal part, (m*/2) v_z0² (1 − e_n²), is lost even without friction.
    frictionless = d["mu"] == 0.0
    vz = r.approach_speed[frictionless]
    np.testing.assert_allclose(
        r.energy_lost[frictionless],
        0.5 * m[frictionless] * vz**2 * (1 - d["e_n"][frictionless] ** 2),
        rtol=1e-12,
        atol=1e-300,
    )


def test_p_is_the_table_answer_bit_for_bit(dissipative, wall):
    d, r = wall
    slips = ~np.isnan(r.p)
    assert slips.sum() == len(slips) - 30  # the pure normal impacts do not consult the table
    np.testing.assert_array_equal(
        r.p[slips], dissipative.p(r.gamma[slips], r.alpha[slips], e_n=d["e_n"][slips])
    )
    np.testing.assert_array_equal(r.gamma, d["gamma"])


def test_rebound_broadcasts_over_e_n(dissipative):
    v = np.array([[1.0, 0.0, 1.0], [0.3, 0.4, 2.0], [2.0, -1.0, 0.5], [0.0, 0.5, 1.5]])
    e = np.array([[0.5], [0.8], [1.0]])
    r = dissipative.rebound(S, v, friction=0.3, gamma=1.8, e_n=e)
    assert r.velocity.shape == (3, 4, 3) and r.p.shape == (3, 4) and r.e_n.shape == (3, 4)
    np.testing.assert_array_equal(r.e_n, np.broadcast_to(e, (3, 4)))
    np.testing.assert_allclose(r.velocity[..., 2], -e * v[:, 2], rtol=1e-15)
    for i, ei in enumerate(e[:, 0]):
        one = dissipative.rebound(S, v, friction=0.3, gamma=1.8, e_n=float(ei))
        for f in ("velocity", "spin", "p", "alpha", "energy_lost", "e_t", "normal_impulse"):
            np.testing.assert_array_equal(getattr(r, f)[i], getattr(one, f), err_msg=f)
        assert dissipative.rebound(S, v[1], friction=0.3, gamma=1.8, e_n=float(ei)).p == one.p[1]
    # Scalars give floats, e_n included.
    s = dissipative.rebound(S, v[0], friction=0.3, gamma=1.8, e_n=0.7)
    assert isinstance(s.e_n, float) and s.e_n == 0.7 and isinstance(s.p, float)
    # 2-D: the same broadcast.
    r2 = dissipative.rebound_2d(S, v[:, 0], v[:, 2], friction=0.3, gamma=1.8, e_n=e)
    assert r2.v_z.shape == (3, 4)
    np.testing.assert_array_equal(r2.e_n, np.broadcast_to(e, (3, 4)))
    np.testing.assert_allclose(r2.v_z, -e * v[:, 2], rtol=1e-15)


def test_shared_e_n_agrees_with_e_n_per_row(dissipative):
    """A scalar e_n with shared bodies and μ (checked once: the faster path; from 1024 rows the
    pair is also prepared for the table) against the same e_n repeated per impact (the general
    path), and against a few rows of the shared path (prepared without the table)."""
    d = wall_impacts(dissipative, 3000, seed=71)
    fields = ("velocity", "spin", "p", "alpha", "energy_lost", "e_n", "tangent")
    for e in (0.5, 0.73, 1.0):
        body = Sphere(0.02, 0.008, 0.4)
        kw = dict(normal=d["n"], friction=0.4, gamma=1.9)
        shared = dissipative.rebound(body, d["v"], d["w"], e_n=e, **kw)
        rows = dissipative.rebound(body, d["v"], d["w"], e_n=np.full(len(d["m"]), e), **kw)
        for f in fields:
            np.testing.assert_array_equal(
                getattr(shared, f), getattr(rows, f), err_msg=f"{f} at e_n = {e}"
            )
        k = slice(0, 10)
        few = dissipative.rebound(
            body, d["v"][k], d["w"][k], e_n=e, normal=d["n"][k], friction=0.4, gamma=1.9
        )
        for f in fields:
            np.testing.assert_array_equal(
                getattr(few, f), getattr(shared, f)[k], err_msg=f"{f} at e_n = {e}, 10 rows"
            )


def test_sphere_on_sphere_relative_normal_velocity(dissipative):
    rng = np.random.default_rng(73)
    n = 2000
    nh = _unit(rng, n)
    v1 = rng.normal(size=(n, 3))
    v2 = rng.normal(size=(n, 3))
    vn = _dot(v1 - v2, nh)
    v1 = v1 + (np.where(vn <= 0, -vn, 0.0) + rng.uniform(0.05, 2.0, n))[:, None] * nh
    e = rng.uniform(0.5, 1.0, n)
    m1, m2 = 10 ** rng.uniform(-3, 1, n), 10 ** rng.uniform(-3, 1, n)
    r = dissipative.rebound(
        Sphere(m1, 0.01), v1, rng.normal(size=(n, 3)) * 50,
        friction=0.3, normal=nh, gamma=_gammas(dissipative, rng, n), e_n=e,
        other=Sphere(m2, 0.02, 0.5), other_velocity=v2, other_spin=rng.normal(size=(n, 3)) * 20,
    )
    before = _dot(v1 - v2, nh)
    after = _dot(r.velocity - r.other_velocity, nh)
    np.testing.assert_allclose(after, -e * before, rtol=1e-11)
    # Momentum is conserved.
    p0 = m1[:, None] * v1 + m2[:, None] * v2
    p1 = m1[:, None] * r.velocity + m2[:, None] * r.other_velocity
    np.testing.assert_allclose(p1, p0, rtol=0, atol=1e-12 * np.abs(p0).max())


def test_rebound_2d_wall(dissipative):
    rng = np.random.default_rng(79)
    n = 3000
    m, rad, k = 10 ** rng.uniform(-3, 1, n), 10 ** rng.uniform(-3, -1, n), rng.uniform(0.2, 1, n)
    vx, vz = rng.normal(size=n), rng.uniform(0.05, 3.0, n)
    om = rng.normal(size=n) / rad
    e = rng.uniform(0.5, 1.0, n)
    g = _gammas(dissipative, rng, n)
    r = dissipative.rebound_2d(Sphere(m, rad, k), vx, vz, om, friction=0.25, gamma=g, e_n=e)
    np.testing.assert_array_equal(r.e_n, e)
    np.testing.assert_allclose(r.v_z, -e * vz, rtol=1e-12)
    e0 = 0.5 * m * (vx**2 + vz**2) + 0.5 * k * m * rad**2 * om**2
    e1 = 0.5 * m * (r.v_x**2 + r.v_z**2) + 0.5 * k * m * rad**2 * r.omega**2
    _balance(e0 - e1, r.energy_lost, e0)
    np.testing.assert_array_equal(r.p, dissipative.p(r.gamma, r.alpha, e_n=e))
    # The 3-D rebound in the x-z plane gives the same answer.
    r3 = dissipative.rebound(
        Sphere(m, rad, k),
        np.stack([vx, np.zeros(n), vz], axis=-1),
        np.stack([np.zeros(n), om, np.zeros(n)], axis=-1),
        friction=0.25,
        gamma=g,
        e_n=e,
    )
    np.testing.assert_array_equal(r3.e_n, r.e_n)
    np.testing.assert_allclose(r3.velocity[:, 2], r.v_z, rtol=1e-14)
    _balance(r3.energy_lost, r.energy_lost, e0)


def test_elastic_default_is_unchanged(full):
    """e_n = 1 (the default) on an elastic table: the elastic rebound, e_n reported as 1."""
    v = np.array([[1.0, 0.2, 1.0], [0.3, 0.4, 2.0]])
    a = full.rebound(S, v, friction=0.3, materials=(STEEL, RIGID))
    b = full.rebound(S, v, friction=0.3, materials=(STEEL, RIGID), e_n=1.0)
    c = full.rebound(S, v, friction=0.3, materials=(STEEL, RIGID), e_n=[1.0, 1.0])
    for f in ("velocity", "spin", "p", "energy_lost"):
        np.testing.assert_array_equal(getattr(a, f), getattr(b, f))
        np.testing.assert_array_equal(getattr(a, f), getattr(c, f))
    np.testing.assert_array_equal(a.e_n, [1.0, 1.0])
    np.testing.assert_allclose(a.velocity[:, 2], -v[:, 2], rtol=1e-15)
    np.testing.assert_allclose(a.normal_impulse, 2 * S.mass * v[:, 2], rtol=1e-15)


# ---------------------------------------------------------------------------------------------
# Refusals


def _wall3(t, **kw):
    args = dict(friction=0.3, gamma=1.5)
    args.update(kw)
    return lambda: t.rebound(S, args.pop("velocity", (1.0, 0.0, 1.0)), **args)


def _wall2(t, **kw):
    args = dict(friction=0.3, gamma=1.5)
    args.update(kw)
    return lambda: t.rebound_2d(S, 1.0, 1.0, **args)


@pytest.mark.parametrize("call", [_wall3, _wall2])
def test_elastic_table_refuses_e_n_below_one(full, call):
    msg = _raises(ValueError, call(full, e_n=0.8), r"\be_n = 0\.8\b", r"elastic")
    assert "index" not in msg
    _raises(ValueError, call(full, e_n=[1.0, 1.0, 0.8]), r"\be_n = 0\.8\b",
            re.escape("(at index (2,))"))
    _raises(ValueError, call(full, e_n=NAN), r"\be_n = NaN\b")


@pytest.mark.parametrize("call", [_wall3, _wall2])
def test_table_refuses_e_n_outside_its_range(dissipative, call):
    for bad in (0.4, 1.5, -0.1, NAN, np.inf):
        _raises(ValueError, call(dissipative, e_n=bad), r"\be_n\b", re.escape("[0.5, 1]"))
    _raises(ValueError, call(dissipative, e_n=[[0.9, 0.6], [0.7, 0.4]]), r"\be_n = 0\.4\b",
            re.escape("[0.5, 1]"), re.escape("(at index (1, 1))"))
    _raises(ValueError, call(dissipative, e_n=[0.9, NAN]), r"\be_n = NaN\b",
            re.escape("(at index (1,))"))


def test_e_n_is_refused_also_without_slip(dissipative):
    """A pure normal impact does not consult the table for P, but its e_n is checked all the
    same."""
    _raises(ValueError, _wall3(dissipative, velocity=(0.0, 0.0, 1.0), e_n=0.4), r"\be_n\b",
            re.escape("[0.5, 1]"))
    _raises(ValueError, lambda: dissipative.rebound_2d(S, 0.0, 1.0, friction=0.3, gamma=1.5,
                                                       e_n=[0.5, 0.45]),
            r"\be_n\b", re.escape("(at index (1,))"))
    r = dissipative.rebound(S, (0.0, 0.0, 1.0), friction=0.3, gamma=1.5, e_n=0.5)
    assert math.isnan(r.p) and math.isclose(r.velocity[2], -0.5, rel_tol=1e-15)


def test_e_n_type_and_shape_errors(dissipative):
    _raises(TypeError, _wall3(dissipative, e_n="0.8"), r"\be_n\b")
    _raises(TypeError, _wall2(dissipative, e_n=0.8 + 0j), r"\be_n\b")
    _raises(ValueError, _wall3(dissipative, velocity=np.ones((4, 3)), e_n=np.full(3, 0.8)),
            re.escape("e_n (3,)"))
    _raises(ValueError, lambda: dissipative.rebound_2d(S, np.ones(4), 1.0, friction=0.3,
                                                       gamma=1.5, e_n=np.full(3, 0.8)),
            re.escape("e_n (3,)"))
    _raises(TypeError, lambda: dissipative.p(1.5, 0.3, e_n=[True]), r"\be_n\b")


def test_regimes_and_critical_curves_know_e_n(sweep_bin):
    """regime, Table.regime and critical take e_n: full slip ends at
    α_c1(γ, e_n) = 2γ²/(7(γ²(1 + e_n) − e_n)) for γ > 1 (α_c2 = 2γ²/7 does not move), as the
    CLI's query says; at (1.6, 0.2, e_n = 0.5) both say full slip (Python said partial slip)."""
    import subprocess

    rng = np.random.default_rng(5)
    n = 20_000
    g = rng.uniform(0.2, 4.0, n)
    a = rng.uniform(0.0, 3.0, n)
    e = rng.uniform(0.3, 1.0, n)
    c1 = 2 * g * g / (7 * (g * g * (1 + e) - e))
    c2 = 2 * g * g / 7
    full_slip = np.where(g > 1.0, a <= c1, a <= c2)
    want = np.where(full_slip, "full-slip", np.where(a >= c2, "stick", "partial-slip"))
    assert np.array_equal(oblique.regime(g, a, e_n=e), want)
    got1, got2 = oblique.critical(g, e_n=e)
    assert np.allclose(got1, c1, rtol=1e-14, atol=0) and np.array_equal(got2, c2)
    # e_n = 1 (the default) is the elastic regime.
    assert np.array_equal(oblique.regime(g, a), oblique.regime(g, a, e_n=1.0))
    t = oblique.Table(DISSIPATIVE)
    assert oblique.regime(1.6, 0.2, e_n=0.5) == "full-slip"
    assert t.regime(1.6, 0.2, 0.5) == "full-slip"
    assert t.regime(1.6, 0.2) == "partial-slip"
    out = subprocess.run(
        [str(sweep_bin), "query", str(DISSIPATIVE), "--gamma", "1.6", "--alpha", "0.2",
         "--e-n", "0.5"],
        capture_output=True, text=True, check=True,
    ).stdout
    assert "full-slip" in out, out
    for bad in (0.2, 1.5, NAN):
        with pytest.raises(ValueError, match="e_n"):
            oblique.regime(1.5, 0.3, e_n=bad)
        with pytest.raises(ValueError, match="e_n"):
            oblique.critical(1.5, e_n=bad)
