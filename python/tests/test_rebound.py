"""Table.rebound (3-D) and Table.rebound_2d against the mechanics written out in the tests:
conservation laws, the closed forms of physics.md and of the module doc of
crates/physics/src/rebound.rs, and the consistency of the two paths (bodies shared by every
impact, or given per impact)."""

from __future__ import annotations

import numpy as np
import pytest

from oblique import RIGID, Material, Sphere
from _oblique_helpers import effective_moduli, masses

N = 10_000


def _dot(a, b):
    return np.einsum("...i,...i->...", a, b)


def _unit(rng, n):
    v = rng.normal(size=(n, 3))
    return v / np.linalg.norm(v, axis=1)[:, None]


def random_impacts(n, seed, wall=False):
    """Random 3-D impacts: masses, radii, κ, materials, μ (with some 0 and inf), a normal of
    random length, velocities that approach along it, spins; a few pure normal impacts (no
    slip of the contact point)."""
    rng = np.random.default_rng(seed)
    d = {
        "m1": 10 ** rng.uniform(-3, 1, n),
        "r1": 10 ** rng.uniform(-3, -1, n),
        "k1": rng.uniform(0.2, 1.0, n),
        "e1": 10 ** rng.uniform(9, 11.5, n),
        "nu1": rng.uniform(-0.5, 0.5, n),
        "e2": 10 ** rng.uniform(9, 11.5, n),
        "nu2": rng.uniform(-0.5, 0.5, n),
    }
    nh = _unit(rng, n)
    d["n"] = nh * rng.uniform(0.3, 3.0, n)[:, None]  # any non-zero length
    d["nh"] = nh
    v1 = rng.normal(size=(n, 3))
    w1 = rng.normal(size=(n, 3)) / d["r1"][:, None]
    if wall:
        v2 = np.zeros((n, 3))
        w2 = np.zeros((n, 3))
    else:
        d["m2"] = 10 ** rng.uniform(-3, 1, n)
        d["r2"] = 10 ** rng.uniform(-3, -1, n)
        d["k2"] = rng.uniform(0.2, 1.0, n)
        v2 = rng.normal(size=(n, 3))
        w2 = rng.normal(size=(n, 3)) / d["r2"][:, None]
    vn = _dot(v1 - v2, nh)
    v1 = v1 + (np.where(vn <= 0, -vn, 0.0) + rng.uniform(0.05, 2.0, n))[:, None] * nh
    # Pure normal impacts: both bodies move along n without spin (n along an axis with a
    # power-of-two length, so that the slip is exactly zero in floating point too).
    k = slice(0, 50)
    axes = np.eye(3)[rng.integers(0, 3, 50)] * rng.choice([-1.0, 1.0], (50, 1))
    nh[k] = axes
    d["n"][k] = axes * rng.choice([0.5, 1.0, 2.0, 4.0], 50)[:, None]
    v1[k] = nh[k] * rng.uniform(0.5, 2.0, 50)[:, None]
    w1[k] = 0.0
    if not wall:
        v2[k] = -nh[k] * rng.uniform(0.0, 1.0, 50)[:, None]
        w2[k] = 0.0
    mu = rng.uniform(0.0, 1.5, n)
    mu[50:250] = np.inf
    mu[250:450] = 0.0
    d.update(v1=v1, w1=w1, v2=v2, w2=w2, mu=mu)
    return d


def run(t, d, wall=False, gamma=None):
    kw = dict(
        friction=d["mu"],
        normal=d["n"],
    )
    if gamma is None:
        kw["materials"] = (Material(d["e1"], d["nu1"]), Material(d["e2"], d["nu2"]))
    else:
        kw["gamma"] = gamma
    if not wall:
        kw.update(
            other=Sphere(d["m2"], d["r2"], d["k2"]),
            other_velocity=d["v2"],
            other_spin=d["w2"],
        )
    return t.rebound(Sphere(d["m1"], d["r1"], d["k1"]), d["v1"], d["w1"], **kw)


@pytest.fixture(scope="module")
def pair(full):
    d = random_impacts(N, seed=41)
    return d, run(full, d)


@pytest.fixture(scope="module")
def wall(full):
    d = random_impacts(N, seed=43, wall=True)
    return d, run(full, d, wall=True)


def _inertia(d, i):
    return d[f"k{i}"] * d[f"m{i}"] * d[f"r{i}"] ** 2


def _after(d, r, wall):
    v2 = np.zeros_like(d["v1"]) if wall else r.other_velocity
    w2 = np.zeros_like(d["v1"]) if wall else r.other_spin
    return r.velocity, r.spin, v2, w2


def _contact_slip(d, v1, w1, v2, w2, wall):
    """u = (v1 + ω1 × R1 n) − (v2 − ω2 × R2 n), tangential part."""
    nh = d["nh"]
    c1 = v1 + np.cross(w1, d["r1"][:, None] * nh)
    c2 = np.zeros_like(c1) if wall else v2 - np.cross(w2, d["r2"][:, None] * nh)
    u = c1 - c2
    return u - _dot(u, nh)[:, None] * nh


@pytest.mark.parametrize("kind", ["pair", "wall"])
def test_conservation_laws(kind, request):
    d, r = request.getfixturevalue(kind)
    wall = kind == "wall"
    nh = d["nh"]
    v1, w1, v2, w2 = _after(d, r, wall)
    m1, i1 = d["m1"][:, None], _inertia(d, 1)[:, None]
    if wall:
        m2 = i2 = np.zeros_like(m1)
        assert r.other_velocity is None and r.other_spin is None
    else:
        m2, i2 = d["m2"][:, None], _inertia(d, 2)[:, None]
        # Linear momentum m1 v1 + m2 v2.
        p0 = m1 * d["v1"] + m2 * d["v2"]
        p1 = m1 * v1 + m2 * v2
        scale = np.linalg.norm(m1 * d["v1"], axis=1) + np.linalg.norm(m2 * d["v2"], axis=1)
        assert np.max(np.linalg.norm(p1 - p0, axis=1) / scale) < 1e-13
    # Angular momentum about the contact point: r1 = −R1 n, r2 = +R2 n from it.
    r1 = -d["r1"][:, None] * nh
    r2 = (np.zeros_like(nh) if wall else d["r2"][:, None] * nh)

    def ang(v1, w1, v2, w2):
        return m1 * np.cross(r1, v1) + i1 * w1 + m2 * np.cross(r2, v2) + i2 * w2

    def size(v, w, m, i, r):
        return m * np.linalg.norm(r, axis=1) * np.linalg.norm(v, axis=1) + i * np.linalg.norm(
            w, axis=1)

    l0 = ang(d["v1"], d["w1"], d["v2"], d["w2"])
    l1 = ang(v1, w1, v2, w2)
    scale = size(d["v1"], d["w1"], m1[:, 0], i1[:, 0], r1) + size(
        d["v2"], d["w2"], m2[:, 0], i2[:, 0], r2)
    assert np.max(np.linalg.norm(l1 - l0, axis=1) / scale) < 1e-13

    # Kinetic energy: before − after = energy_lost ≥ 0.
    def ke(v1, w1, v2, w2):
        return 0.5 * (
            m1[:, 0] * _dot(v1, v1) + i1[:, 0] * _dot(w1, w1)
            + m2[:, 0] * _dot(v2, v2) + i2[:, 0] * _dot(w2, w2)
        )

    k0 = ke(d["v1"], d["w1"], d["v2"], d["w2"])
    k1 = ke(v1, w1, v2, w2)
    assert np.all(r.energy_lost >= 0)
    assert np.max(np.abs((k0 - k1) - r.energy_lost) / k0) < 1e-12
    # The energy lost by the closed form (m_t/2) u0² (1 − P²) (0 when u0 = 0).
    _, m_t, _ = masses(d["m1"], d["r1"], d["k1"], d.get("m2"), d.get("r2"), d.get("k2"))
    u0 = np.linalg.norm(_contact_slip(d, d["v1"], d["w1"], d["v2"], d["w2"], wall), axis=1)
    slip = r.slip_before > 0
    lost = 0.5 * m_t * u0**2 * (1 - r.p**2)
    np.testing.assert_allclose(r.energy_lost[slip], lost[slip], rtol=1e-12, atol=0)
    assert np.all(r.energy_lost[~slip] == 0.0)
    # |P| <= 1; NaN exactly where nothing slips.
    assert np.all(np.abs(r.p[slip]) <= 1.0)
    assert np.all(np.isnan(r.p[~slip]))
    assert (~slip).sum() >= 50
    # No torsional friction: the spin about the normal of each body is unchanged.
    for w_before, w_after, rad in [(d["w1"], w1, d["r1"])] + (
        [] if wall else [(d["w2"], w2, d["r2"])]
    ):
        ws = np.linalg.norm(w_before, axis=1) + 1.0 / rad
        assert np.max(np.abs(_dot(w_after, nh) - _dot(w_before, nh)) / ws) < 1e-13
    # Normal relative velocity reversed (elastic).
    vn0 = _dot(d["v1"] - d["v2"], nh)
    vn1 = _dot(v1 - v2, nh)
    speed = np.linalg.norm(d["v1"], axis=1) + np.linalg.norm(d["v2"], axis=1)
    assert np.all(vn0 > 0)
    assert np.max(np.abs(vn1 + vn0) / speed) < 1e-13
    np.testing.assert_allclose(r.approach_speed, vn0, rtol=1e-13)


@pytest.mark.parametrize("kind", ["pair", "wall"])
def test_groups_and_p(kind, request, full):
    d, r = request.getfixturevalue(kind)
    wall = kind == "wall"
    e_s, g_s = effective_moduli(d["e1"], d["nu1"], d["e2"], d["nu2"])
    m_s, m_t, _ = masses(d["m1"], d["r1"], d["k1"], d.get("m2"), d.get("r2"), d.get("k2"))
    gamma = np.sqrt(m_s / m_t * g_s / e_s)
    np.testing.assert_allclose(r.gamma, gamma, rtol=1e-13)
    u_t = _contact_slip(d, d["v1"], d["w1"], d["v2"], d["w2"], wall)
    u0 = np.linalg.norm(u_t, axis=1)
    vz0 = _dot(d["v1"] - d["v2"], d["nh"])
    slip = r.slip_before > 0
    with np.errstate(divide="ignore", invalid="ignore"):
        alpha = 2.0 / 7.0 * (m_s / m_t) * d["mu"] * vz0 / u0
    alpha = np.where(np.isnan(alpha), np.inf, alpha)
    np.testing.assert_allclose(r.alpha, alpha, rtol=1e-12)
    assert np.all(np.isinf(r.alpha[~slip]))
    np.testing.assert_allclose(r.slip_before, u0, rtol=1e-12, atol=1e-14 * np.max(u0))
    # P is the table's answer at (γ, α), to the bit.
    assert np.array_equal(r.p[slip], full.p(r.gamma[slip], r.alpha[slip]))
    assert np.all(r.p[slip & (d["mu"] == 0)] == 1.0)
    # The contact point's tangential slip after is P times the slip before (as a vector).
    v1, w1, v2, w2 = _after(d, r, wall)
    u_after = _contact_slip(d, v1, w1, v2, w2, wall)
    err = np.linalg.norm(u_after - np.where(slip, r.p, 0.0)[:, None] * u_t, axis=1)
    scale = np.linalg.norm(d["v1"], axis=1) + np.linalg.norm(d["v2"], axis=1) + u0
    assert np.max(err / scale) < 1e-12
    # Tangent: the unit direction of the incident slip, in the plane.
    np.testing.assert_allclose(np.linalg.norm(r.tangent, axis=1), 1.0, rtol=1e-14)
    assert np.max(np.abs(_dot(r.tangent, d["nh"]))) < 1e-13
    np.testing.assert_allclose(r.tangent[slip], u_t[slip] / u0[slip, None], atol=1e-12)
    np.testing.assert_allclose(r.slip_after[slip], r.p[slip] * u0[slip], rtol=1e-12, atol=0)
    # Impulses: normal 2 m* v_z0; friction m_t (1 − P)|u0|, on body 2 along +t.
    np.testing.assert_allclose(r.normal_impulse, 2 * m_s * vz0, rtol=1e-13)
    np.testing.assert_allclose(
        r.tangential_impulse[slip], m_t[slip] * (1 - r.p[slip]) * u0[slip], rtol=1e-12, atol=0
    )
    dv1 = d["m1"][:, None] * (v1 - d["v1"])
    jt = np.where(slip, r.tangential_impulse, 0.0)[:, None] * r.tangent
    want = -jt - r.normal_impulse[:, None] * d["nh"]
    np.testing.assert_allclose(dv1, want, rtol=0, atol=1e-12 * np.max(np.abs(dv1)))
    # The centres: e_t = (w_after · w_before)/|w_before|² of the tangential relative velocity.
    rel0 = d["v1"] - d["v2"]
    rel1 = v1 - v2
    w0 = rel0 - _dot(rel0, d["nh"])[:, None] * d["nh"]
    w1_ = rel1 - _dot(rel1, d["nh"])[:, None] * d["nh"]
    np.testing.assert_allclose(r.centre_speed_before, np.linalg.norm(w0, axis=1), rtol=1e-12)
    np.testing.assert_allclose(r.centre_speed_after, np.linalg.norm(w1_, axis=1), rtol=1e-10,
                               atol=1e-13 * np.max(np.linalg.norm(w0, axis=1)))
    moving = np.linalg.norm(w0, axis=1) > 1e-6 * np.linalg.norm(rel0, axis=1)
    assert moving.sum() > 0.9 * len(moving)
    e_t = _dot(w1_[moving], w0[moving]) / _dot(w0[moving], w0[moving])
    np.testing.assert_allclose(r.e_t[moving], e_t, rtol=1e-12, atol=1e-12)
    assert np.all(np.isnan(r.e_t[np.linalg.norm(w0, axis=1) == 0]))
    np.testing.assert_allclose(
        r.incidence_angle, np.arctan2(np.linalg.norm(w0, axis=1), vz0), rtol=1e-12, atol=1e-15
    )
    assert np.all((r.rebound_angle_centre >= 0) & (r.rebound_angle_centre < np.pi / 2))
    np.testing.assert_allclose(
        r.rebound_angle_contact[slip], np.arctan2(r.p * u0, vz0)[slip], rtol=1e-12, atol=1e-15
    )
    assert r.e_t_contact is r.p


def _compare(a, b, rtol=1e-13):
    for f in ("velocity", "spin", "other_velocity", "other_spin", "gamma", "alpha", "p", "e_t",
              "slip_before", "slip_after", "tangential_impulse", "normal_impulse",
              "approach_speed", "centre_speed_before", "centre_speed_after", "energy_lost",
              "tangent", "incidence_angle", "rebound_angle_centre", "rebound_angle_contact"):
        x, y = getattr(a, f), getattr(b, f)
        if x is None or y is None:
            assert x is None and y is None, f
            continue
        x, y = np.asarray(x), np.asarray(y)
        assert x.shape == y.shape, f
        assert np.array_equal(np.isnan(x), np.isnan(y)), f
        assert np.array_equal(np.isinf(x), np.isinf(y)), f
        assert np.array_equal(x[np.isinf(x)], y[np.isinf(y)]), f
        ok = np.isfinite(x)
        scale = np.max(np.abs(y[ok]), initial=0.0)
        np.testing.assert_allclose(x[ok], y[ok], rtol=rtol, atol=rtol * scale, err_msg=f)


@pytest.mark.parametrize("wall", [False, True])
@pytest.mark.parametrize("by", ["materials", "gamma"])
def test_shared_path_agrees_with_per_row_path(full, wall, by):
    """Bodies, materials and μ shared by every impact (scalars: checked once, the faster path)
    against the same values repeated per impact (the general path)."""
    d = random_impacts(N, seed=47, wall=wall)
    for i, gamma in ((3, 0.6), (100, 1.4), (300, 2.9)):  # μ finite, inf, 0
        s = {k: float(d[k][i]) for k in ("m1", "r1", "k1", "e1", "nu1", "e2", "nu2", "mu")}
        if not wall:
            s.update({k: float(d[k][i]) for k in ("m2", "r2", "k2")})
        if by == "gamma":
            stiff = dict(gamma=gamma)
            stiff_rows = dict(gamma=np.full(N, stiff["gamma"]))
        else:
            stiff = dict(materials=(Material(s["e1"], s["nu1"]), Material(s["e2"], s["nu2"])))
            stiff_rows = dict(
                materials=(Material(np.full(N, s["e1"]), s["nu1"]), Material(s["e2"], s["nu2"]))
            )
        other = {} if wall else dict(
            other=Sphere(s["m2"], s["r2"], s["k2"]), other_velocity=d["v2"], other_spin=d["w2"]
        )
        shared = full.rebound(Sphere(s["m1"], s["r1"], s["k1"]), d["v1"], d["w1"],
                              friction=s["mu"], normal=d["n"], **stiff, **other)
        rows = full.rebound(Sphere(np.full(N, s["m1"]), s["r1"], s["k1"]), d["v1"], d["w1"],
                            friction=np.full(N, s["mu"]), normal=d["n"], **stiff_rows, **other)
        assert shared.p.shape == (N,)
        _compare(shared, rows)


def test_gamma_given_equals_materials(full, pair):
    d, r = pair
    g = run(full, d, gamma=r.gamma)
    assert np.array_equal(g.p, r.p, equal_nan=True)
    assert np.array_equal(g.alpha, r.alpha)
    assert np.array_equal(g.gamma, r.gamma)
    _compare(g, r, rtol=1e-15)
    # One solid steel sphere on a rigid wall, by materials and by the closed-form γ.
    e, nu = 2.1e11, 0.29
    g_shear = e / (2 * (1 + nu))
    gamma = np.sqrt(3.5 * ((2 - nu) / (4 * g_shear)) ** -1 / ((1 - nu**2) / e) ** -1)
    s = Sphere(0.05, 0.012)
    v = np.array([[0.7, -0.2, 1.3], [2.0, 0.1, 0.4]])
    a = full.rebound(s, v, friction=0.25, materials=(Material(e, nu), RIGID))
    b = full.rebound(s, v, friction=0.25, gamma=float(a.gamma[0]))
    np.testing.assert_allclose(a.gamma, gamma, rtol=1e-14)
    assert np.array_equal(a.p, b.p)
    assert np.array_equal(a.velocity, b.velocity) and np.array_equal(a.spin, b.spin)


def test_wall_centre_restitution_closed_forms(full):
    """Sphere on a wall without spin: e_t = (2P + 5)/7 (κ = 0.4), 1 − κ/(1 + κ)(1 − P)."""
    rng = np.random.default_rng(53)
    n = 5000
    vx = rng.uniform(0.01, 3.0, n) * rng.choice([-1.0, 1.0], n)
    vz = rng.uniform(0.01, 3.0, n)
    gamma = rng.uniform(0.1, 3.5, n)
    mu = rng.uniform(0.0, 2.0, n)
    v = np.stack([vx, np.zeros(n), vz], axis=-1)
    solid = full.rebound(Sphere(0.2, 0.03), v, friction=mu, gamma=gamma)
    np.testing.assert_allclose(solid.e_t, (2.0 * solid.p + 5.0) / 7.0, rtol=0, atol=1e-15)
    np.testing.assert_allclose(solid.velocity[:, 0] / vx, (2 * solid.p + 5) / 7, atol=1e-14)
    np.testing.assert_allclose(solid.alpha, mu * vz / np.abs(vx), rtol=1e-13)
    np.testing.assert_allclose(solid.e_t, full.e_t(gamma, solid.alpha), rtol=0, atol=1e-15)
    # ω = 5 v_x0 (P − 1)/(7R) about the axis y = z × x (physics.md, solid sphere, ω0 = 0).
    np.testing.assert_allclose(
        solid.spin[:, 1], 5 * vx * (solid.p - 1) / (7 * 0.03), rtol=1e-12, atol=1e-12
    )
    kappa = rng.uniform(0.1, 1.5, n)
    # γ fixed by the caller here: the same (γ, α) give the same P for any κ when α is scaled.
    other = full.rebound(Sphere(0.2, 0.03, kappa), v, friction=mu, gamma=gamma)
    want = 1.0 - kappa / (1.0 + kappa) * (1.0 - other.p)
    np.testing.assert_allclose(other.e_t, want, rtol=0, atol=1e-15)
    np.testing.assert_allclose(other.e_t, full.e_t(gamma, other.alpha, kappa=kappa), atol=1e-15)
    # α = (2/7)(m*/m_t) μ v_z0/|u0| with m*/m_t = (1 + κ)/κ.
    np.testing.assert_allclose(
        other.alpha, 2 / 7 * (1 + kappa) / kappa * mu * vz / np.abs(vx), rtol=1e-13
    )


@pytest.mark.parametrize("wall", [False, True])
def test_rebound_2d_agrees_with_3d_in_the_xz_plane(full, wall):
    """2-D: z the normal, x the tangent, ω signed so that sphere 1's contact point moves at
    v_x + R ω, i.e. ω is the component along y = z × x of the angular velocity vector."""
    rng = np.random.default_rng(59 + wall)
    n = 4000
    m1, r1, k1 = 10 ** rng.uniform(-2, 0, n), 10 ** rng.uniform(-3, -1, n), rng.uniform(0.2, 1, n)
    vx, vz, om = rng.normal(size=n), rng.uniform(0.05, 2, n), rng.normal(size=n) / r1
    mu = rng.uniform(0, 1.5, n)
    mats = (Material(10 ** rng.uniform(9, 11, n), rng.uniform(-0.4, 0.5, n)),
            Material(10 ** rng.uniform(9, 11, n), rng.uniform(-0.4, 0.5, n)))
    z = np.zeros(n)
    kw3, kw2 = {}, {}
    if not wall:
        m2, r2, k2 = 10 ** rng.uniform(-2, 0, n), 10 ** rng.uniform(-3, -1, n), rng.uniform(
            0.2, 1, n)
        ovx, ovz, oom = rng.normal(size=n), rng.uniform(-2, 0, n), rng.normal(size=n) / r2
        kw3 = dict(other=Sphere(m2, r2, k2), other_velocity=np.stack([ovx, z, ovz], -1),
                   other_spin=np.stack([z, oom, z], -1))
        kw2 = dict(other=Sphere(m2, r2, k2), other_v_x=ovx, other_v_z=ovz, other_omega=oom)
    r3 = full.rebound(Sphere(m1, r1, k1), np.stack([vx, z, vz], -1), np.stack([z, om, z], -1),
                      friction=mu, materials=mats, normal=(0.0, 0.0, 1.0), **kw3)
    r2d = full.rebound_2d(Sphere(m1, r1, k1), vx, vz, om, friction=mu, materials=mats, **kw2)

    def close(a, b, what):
        np.testing.assert_allclose(a, b, rtol=1e-13, atol=1e-13 * np.max(np.abs(b)),
                                   err_msg=what)

    close(r3.velocity[:, 0], r2d.v_x, "v_x")
    close(r3.velocity[:, 2], r2d.v_z, "v_z")
    close(r3.spin[:, 1], r2d.omega, "omega")
    assert np.all(r3.velocity[:, 1] == 0) and np.all(r3.spin[:, [0, 2]] == 0)
    if wall:
        assert r2d.other_v_x is None and r2d.other_v_z is None and r2d.other_omega is None
    else:
        close(r3.other_velocity[:, 0], r2d.other_v_x, "other_v_x")
        close(r3.other_velocity[:, 2], r2d.other_v_z, "other_v_z")
        close(r3.other_spin[:, 1], r2d.other_omega, "other_omega")
    for f in ("gamma", "alpha", "p", "energy_lost", "normal_impulse", "e_t"):
        close(getattr(r3, f), getattr(r2d, f), f)
    # The slip: signed in 2-D, a magnitude along the tangent t = ±x in 3-D.
    u0 = vx + r1 * om - ((kw2["other_v_x"] - kw2["other"].radius * kw2["other_omega"])
                         if not wall else 0.0)
    close(r2d.slip_before, u0, "slip_before")
    close(r3.slip_before, np.abs(u0), "|slip_before|")
    assert np.max(np.abs(np.abs(r3.tangent[:, 0]) - 1.0)) < 1e-15
    assert np.all(r3.tangent[:, 1:] == 0.0)
    sign = np.sign(r3.tangent[:, 0])
    assert np.all(np.sign(u0) == sign)
    close(r3.tangential_impulse * sign, r2d.tangential_impulse, "tangential_impulse")
    close(r3.slip_after * sign, r2d.slip_after, "slip_after")
    close(r3.rebound_angle_contact * sign, r2d.rebound_angle_contact, "rebound_angle_contact")
    close(r2d.slip_after, r2d.p * u0, "slip_after = P u0")
    close(np.abs(r2d.incidence_angle), r3.incidence_angle, "incidence_angle")
    # The 2-D spin convention, checked on the contact point directly.
    close(r2d.v_x + r1 * r2d.omega - (0.0 if wall else r2d.other_v_x - kw2["other"].radius
                                      * r2d.other_omega), r2d.p * u0, "P u0")


def test_rebound_broadcasting_and_scalars(full):
    s = Sphere(0.1, 0.01)
    # Scalars: floats, and (3,) vectors.
    r = full.rebound(s, (0.5, 0.0, 1.0), friction=0.3, gamma=1.6)
    assert type(r.p) is float and type(r.alpha) is float
    assert r.velocity.shape == (3,) and r.spin.shape == (3,) and r.tangent.shape == (3,)
    assert r.p == full.p(1.6, r.alpha)
    r2 = full.rebound_2d(s, 0.5, 1.0, friction=0.3, gamma=1.6)
    assert type(r2.v_x) is float and r2.p == r.p
    # Batch shape from every argument: velocity (4, 1, 3), friction (5,) → (4, 5).
    v = np.random.default_rng(61).uniform(0.1, 1.0, (4, 1, 3))
    mu = np.linspace(0.0, 1.0, 5)
    b = full.rebound(s, v, friction=mu, gamma=1.6)
    assert b.p.shape == (4, 5) and b.velocity.shape == (4, 5, 3) and b.tangent.shape == (4, 5, 3)
    for i in range(4):
        for j in range(5):
            one = full.rebound(s, v[i, 0], friction=float(mu[j]), gamma=1.6)
            np.testing.assert_allclose(b.velocity[i, j], one.velocity, rtol=1e-15)
            assert b.p[i, j] == one.p
    # A Sphere field may carry the shape too.
    c = full.rebound(Sphere([0.1, 0.2, 0.3], 0.01), (0.5, 0.0, 1.0), friction=0.3, gamma=1.6)
    assert c.p.shape == (3,) and c.velocity.shape == (3, 3)
    # Empty batches.
    e = full.rebound(s, np.empty((0, 3)), friction=0.3, gamma=1.6)
    assert e.p.shape == (0,) and e.velocity.shape == (0, 3)
    # 2-D broadcasting.
    d2 = full.rebound_2d(s, [[0.1], [0.5]], [1.0, 2.0, 3.0], friction=0.3, gamma=1.6)
    assert d2.v_x.shape == (2, 3) and d2.p.shape == (2, 3)
    # Non-contiguous vector input (a transposed (3, n) array).
    vt = np.ascontiguousarray(np.random.default_rng(62).uniform(0.1, 1.0, (3, 7))).T
    assert not vt.flags.c_contiguous
    nc = full.rebound(s, vt, friction=0.3, gamma=1.6)
    cc = full.rebound(s, np.ascontiguousarray(vt), friction=0.3, gamma=1.6)
    assert np.array_equal(nc.velocity, cc.velocity) and np.array_equal(nc.p, cc.p)


def test_rotation_invariance(full, pair):
    """Rotating every vector of the impacts rotates every vector of the outcome."""
    d, r = pair
    rng = np.random.default_rng(67)
    q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    if np.linalg.det(q) < 0:
        q[:, 0] = -q[:, 0]
    rot = {k: d[k] @ q.T for k in ("v1", "w1", "v2", "w2", "n", "nh")}
    rr = run(full, {**d, **rot})
    for f in ("velocity", "spin", "other_velocity", "other_spin"):
        a, b = getattr(rr, f), getattr(r, f) @ q.T
        np.testing.assert_allclose(a, b, rtol=0, atol=1e-11 * np.max(np.abs(b)), err_msg=f)
    for f in ("gamma", "normal_impulse"):
        np.testing.assert_allclose(getattr(rr, f), getattr(r, f), rtol=1e-13, err_msg=f)
    # Away from the pure normal impacts (the first 50: there the rotated slip is a rounding
    # residue instead of exactly 0).
    for f in ("alpha", "p", "energy_lost"):
        np.testing.assert_allclose(getattr(rr, f)[50:], getattr(r, f)[50:], rtol=1e-9,
                                   atol=1e-12, err_msg=f)


def test_rolling_contact_changes_only_the_normal_motion(full):
    """u0 = 0 (the contact point does not slip, the centre moves): nothing tangential happens;
    P is NaN, e_t = 1, the tangent follows the centre's tangential motion."""
    rng = np.random.default_rng(71)
    n = 200
    vx, vy, vz = rng.uniform(-2, 2, n), rng.uniform(-2, 2, n), rng.uniform(0.1, 2, n)
    # Contact point at +R z: u = v + ω × (R z) = (v_x + R ω_y, v_y − R ω_x, ·) = 0; R a
    # power of two, so that R (v/R) = v exactly.
    R = 0.0625
    v = np.stack([vx, vy, vz], -1)
    w = np.stack([vy / R, -vx / R, rng.uniform(-5, 5, n)], -1)
    r = full.rebound(Sphere(0.3, R), v, w, friction=0.5, gamma=1.7)
    rolling = r.slip_before == 0.0
    assert rolling.sum() > n // 2
    assert np.all(np.isnan(r.p[rolling])) and np.all(np.isinf(r.alpha[rolling]))
    assert np.all(r.e_t[rolling] == 1.0)
    assert np.all(r.energy_lost[rolling] == 0.0)
    assert np.array_equal(r.velocity[rolling][:, :2], v[rolling][:, :2])
    np.testing.assert_allclose(r.velocity[rolling][:, 2], -v[rolling][:, 2], rtol=1e-15)
    assert np.array_equal(r.spin[rolling], w[rolling])
    w_t = v[:, :2] / np.linalg.norm(v[:, :2], axis=1)[:, None]
    np.testing.assert_allclose(r.tangent[rolling][:, :2], w_t[rolling], atol=1e-15)
    # 2-D: ω = −v_x/R rolls.
    r2 = full.rebound_2d(Sphere(0.3, R), vx, vz, -vx / R, friction=0.5, gamma=1.7)
    rolling2 = r2.slip_before == 0.0
    assert rolling2.sum() > n // 2
    assert np.all(np.isnan(r2.p[rolling2])) and np.all(r2.e_t[rolling2] == 1.0)
    assert np.array_equal(r2.v_x[rolling2], vx[rolling2])
    assert np.array_equal(r2.omega[rolling2], (-vx / R)[rolling2])
