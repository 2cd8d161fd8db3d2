"""Table.p, Curve.p, Table.e_t and regime against independent references (the Rust CLI, the
reference reader scripts/read_table.py, closed forms), and the NumPy conventions of the API
(broadcasting, return types, out=, strides, dtypes)."""

from __future__ import annotations

import math
import os

import numpy as np
import pytest

import oblique
from _oblique_helpers import (
    DISSIPATIVE,
    SHIPPED,
    TABLES,
    alpha_c1,
    alpha_c2,
    alpha_lin,
    domain_points,
    sweep_query,
)

N_CLI = 100_000
N_READER = 20_000
# scripts/check_table.sh runs `read_table.py --check-stored`, whose tolerance is 1e-12.
READER_TOL = 1e-12


# ---------------------------------------------------------------------------------------------
# 1. Agreement with the Rust rule, to the last bit


@pytest.mark.parametrize("name", SHIPPED)
def test_p_bit_identical_to_cli(name, tables, table_paths):
    t = tables[name]
    g, a = domain_points(t, N_CLI, seed=11 + SHIPPED.index(name))
    assert np.isinf(a).sum() > 1000 and (a == 0).sum() > 1000
    c1, c2 = oblique.critical(g)
    assert (a == c1).sum() > 500 and (a == c2).sum() > 1000  # on the critical curves
    cli_p, cli_e_t = sweep_query(table_paths[name], g, a)
    p = t.p(g, a)
    assert p.dtype == np.float64 and p.shape == g.shape
    mismatch = np.flatnonzero(p != cli_p)
    assert mismatch.size == 0, (
        f"{mismatch.size} of {g.size} points differ from `sweep query`; first: gamma "
        f"{g[mismatch[0]]!r} alpha {a[mismatch[0]]!r}: {p[mismatch[0]]!r} vs {cli_p[mismatch[0]]!r}"
    )
    assert np.array_equal(p, cli_p)
    # |P| <= 1 everywhere, and the exact line where it applies.
    assert np.all(np.abs(p) <= 1.0)
    line = a <= alpha_lin(g)
    assert np.array_equal(p[line], 1.0 - 7.0 * a[line])
    # The CLI's e_t is (2P + 5)/7; so is Table.e_t for a solid sphere.
    e_t = t.e_t(g, a)
    np.testing.assert_allclose(cli_e_t, (2.0 * cli_p + 5.0) / 7.0, rtol=0, atol=4e-16)
    np.testing.assert_allclose(e_t, (2.0 * cli_p + 5.0) / 7.0, rtol=0, atol=4e-16)


@pytest.mark.parametrize("name", SHIPPED)
def test_scalar_path_equals_array_path(name, tables):
    t = tables[name]
    g, a = domain_points(t, 3000, seed=3)
    p = t.p(g, a)
    scalar = np.array([t.p(float(x), float(y)) for x, y in zip(g, a)])
    assert np.array_equal(p, scalar)


def test_finite_alpha_max_table_bit_identical_to_cli(finite_table, finite_table_path):
    t = finite_table
    g, a = domain_points(t, 20_000, seed=5)
    assert (a == 5.0).sum() > 1000
    cli_p, _ = sweep_query(finite_table_path, g, a)
    assert np.array_equal(t.p(g, a), cli_p)


def _outside_points(info, n, seed):
    rng = np.random.default_rng(seed)
    gmin, gmax, amax = info["gamma_min"], info["gamma_max"], info["alpha_max"]
    g = np.concatenate(
        [
            rng.uniform(gmin * 0.05, gmin, n // 4),
            rng.uniform(gmax, 3.0 * gmax, n // 4),
            rng.uniform(gmin, gmax, n - 2 * (n // 4)),
        ]
    )
    a = rng.uniform(0.0, 3.0, n)
    a[::7] = np.inf
    a[1::11] = 0.0
    if math.isfinite(amax):
        # Above alpha_max, inside the γ range too.
        a[2::3] = rng.uniform(amax, 4 * amax, a[2::3].size)
    return g, a


@pytest.mark.parametrize("which", ["full", "finite"])
def test_clamp_bit_identical_to_cli(which, table_paths, finite_table_path):
    path = finite_table_path if which == "finite" else table_paths["full"]
    tc = oblique.Table(path, clamp=True)
    t = oblique.Table(path)
    assert tc.clamp is True and t.clamp is False
    info = tc.info
    g, a = _outside_points(info, 20_000, seed=17)
    outside = (g < info["gamma_min"]) | (g > info["gamma_max"]) | (a > info["alpha_max"])
    off_line = a > alpha_lin(g)
    assert (outside & off_line).sum() > 5000
    cli_p, _ = sweep_query(path, g, a, clamp=True)
    p = tc.p(g, a)
    assert np.array_equal(p, cli_p)
    # The documented meaning: the nearest point of the domain, except on the exact line.
    gn = np.clip(g, info["gamma_min"], info["gamma_max"])
    an = np.minimum(a, info["alpha_max"])
    assert np.array_equal(p[off_line], t.p(gn[off_line], an[off_line]))
    assert np.array_equal(p[~off_line], 1.0 - 7.0 * a[~off_line])
    # Inside the domain clamping changes nothing; outside, the unclamped table refuses.
    inside = ~outside
    assert np.array_equal(p[inside], t.p(g[inside], a[inside]))
    k = np.flatnonzero(outside & off_line)[0]
    with pytest.raises(ValueError):
        t.p(g[k], a[k])


def test_curve_matches_table(tables):
    rng = np.random.default_rng(23)
    for name, t in tables.items():
        info = t.info
        gammas = [info["gamma_min"], info["gamma_max"]] + list(
            rng.uniform(info["gamma_min"], info["gamma_max"], 6)
        )
        if info["gamma_min"] <= 1.0 <= info["gamma_max"]:
            gammas.append(1.0)
        for gamma in gammas:
            c = t.curve(gamma)
            assert c.gamma == gamma and c.requested_gamma == gamma
            assert c.nbytes > 0
            a = np.concatenate(
                [rng.uniform(0.0, 3.0, 4000), [0.0, np.inf, *oblique.critical(gamma)]]
            )
            a = a[a >= 0]
            want = t.p(gamma, a)
            got = c.p(a)
            assert got.shape == a.shape
            np.testing.assert_allclose(got, want, rtol=0, atol=1e-13, err_msg=f"{name} {gamma}")
            # Scalar queries answer the same as the array path.
            for x in a[:50]:
                v = c.p(float(x))
                assert isinstance(v, float)
                assert abs(v - t.p(gamma, float(x))) <= 1e-13


def test_curve_clamped(full, full_clamped):
    gmax = full.info["gamma_max"]
    c = full_clamped.curve(2 * gmax)
    assert c.requested_gamma == 2 * gmax and c.gamma == gmax
    a = np.linspace(alpha_lin(2 * gmax) * 1.01, 3.0, 500)
    np.testing.assert_allclose(c.p(a), full.p(gmax, a), rtol=0, atol=1e-13)
    with pytest.raises(ValueError):
        full.curve(2 * gmax)


@pytest.mark.parametrize("name", SHIPPED)
def test_agrees_with_reference_reader(name, tables, reference_tables):
    t = tables[name]
    ref = reference_tables(name)
    n = N_READER if name == "full" else 5000
    g, a = domain_points(t, n, seed=29 + SHIPPED.index(name))
    want = np.array([ref.p(x, y) for x, y in zip(g.tolist(), a.tolist())])
    got = t.p(g, a)
    err = np.abs(got - want)
    # Just below α_c2 in the partial-slip patch (γ > 1) the patch coordinate
    # c = 1 − √(1 − ℓ) amplifies the rounding of ℓ ≈ 1 to ~√ε ≈ 1e-8 in c: two correct
    # implementations differ there by a few 1e-12 (checked against a 50-digit evaluation of
    # the coordinate). Those points get the tolerance that conditioning allows.
    c2 = alpha_c2(g)
    ill = (g > 1.0) & (a < c2) & (a > c2 * (1.0 - 1e-9))
    assert name == "quick" or ill.sum() > 100
    for mask, tol in ((~ill, READER_TOL), (ill, 1e-10)):
        if not mask.any():
            continue
        k = np.flatnonzero(mask)[int(np.argmax(err[mask]))]
        assert err[k] <= tol, f"gamma {g[k]!r} alpha {a[k]!r}: {got[k]!r} vs {want[k]!r}"
    # The reference reader refuses what the package refuses.
    assert np.all(np.isfinite(want))


@pytest.mark.parametrize("name", SHIPPED)
def test_info_matches_reference_reader(name, tables, table_paths, reference_tables):
    t = tables[name]
    ref = reference_tables(name)
    info = t.info
    assert info["gamma_min"] == ref.gamma_min
    assert info["gamma_max"] == ref.gamma_max
    assert info["alpha_max"] == ref.alpha_max
    assert info["schema_version"] == ref.schema_version
    assert info["schema_version"] == (3 if name == "full" else 2)
    assert math.isclose(info["error_bound"], ref.error_bound, rel_tol=1e-12)
    assert t.error_bound == info["error_bound"]
    assert info["path"] == str(table_paths[name])
    # The held-out checks: count, worst error, and the table reproduces every stored value.
    ch = ref.checks
    assert info["checks"] == len(ch["gamma"])
    assert math.isclose(
        info["checks_max_error"], float(np.max(ch["interpolation_error"])), rel_tol=1e-12
    )
    p = t.p(ch["gamma"], ch["alpha"])
    # Stored values of older tables may lie a hair outside [-1, 1]; the rule's last step
    # bounds |P| <= 1 (docs/table-format.md step 10, as the reader does).
    np.testing.assert_allclose(p, np.clip(ch["P_interpolated"], -1, 1), rtol=0, atol=READER_TOL)
    assert repr(t).startswith("<oblique.Table ")
    # info is a copy: changing it does not change the table.
    info["gamma_min"] = -1.0
    assert t.info["gamma_min"] == ref.gamma_min


# ---------------------------------------------------------------------------------------------
# 2. Broadcasting and the NumPy conventions


def test_scalar_arguments_return_float(full):
    for g, a in [(1.5, 0.3), (2, 1), (np.float64(1.5), 0.3), (np.array(1.5), np.array(0.3))]:
        v = full.p(g, a)
        assert type(v) is float, type(v)
    assert full.p(2, 1) == full.p(2.0, 1.0)
    assert full.p(np.array(1.5), np.array(0.3)) == full.p(1.5, 0.3)
    assert type(full.e_t(1.5, 0.3)) is float
    assert type(full.e_t(1.5, 0.3, kappa=np.array(0.5))) is float
    assert type(full.curve(1.5).p(0.3)) is float
    assert type(full.curve(1.5).p(np.array(0.3))) is float
    c1, c2 = oblique.critical(1.5)
    assert type(c1) is float and type(c2) is float
    assert c1 == pytest.approx(float(alpha_c1(1.5)), rel=1e-15)
    assert c2 == pytest.approx(float(alpha_c2(1.5)), rel=1e-15)


def test_shapes_broadcast(full):
    g = np.array([0.7, 1.5, 2.5])
    a = np.array([[0.05], [0.8]])
    p = full.p(g, a)
    assert isinstance(p, np.ndarray) and p.shape == (2, 3) and p.dtype == np.float64
    for i in range(2):
        for j in range(3):
            assert p[i, j] == full.p(float(g[j]), float(a[i, 0]))
    p3 = full.p(g, 0.8)
    assert p3.shape == (3,)
    assert np.array_equal(p3, p[1])
    assert full.p(1.5, np.array([0.3])).shape == (1,)
    # Lists and tuples are arrays.
    assert np.array_equal(full.p([0.7, 1.5, 2.5], [[0.05], [0.8]]), p)
    assert np.array_equal(full.p((0.7, 1.5, 2.5), 0.8), p3)
    # Critical and regime broadcast too.
    c1, c2 = oblique.critical(np.ones((2, 3)) * 1.5)
    assert c1.shape == c2.shape == (2, 3)
    assert oblique.regime(g, a).shape == (2, 3)


def test_zero_d_and_empty(full):
    assert full.p(np.array(1.5), 0.3) == full.p(1.5, 0.3)
    empty = full.p(np.empty(0), 0.3)
    assert isinstance(empty, np.ndarray) and empty.shape == (0,) and empty.dtype == np.float64
    assert full.p(np.empty((2, 0)), np.empty((1, 0))).shape == (2, 0)
    assert full.p(1.5, np.empty((0, 4))).shape == (0, 4)
    assert full.e_t(np.empty(0), 0.3).shape == (0,)
    assert full.curve(1.5).p(np.empty(0)).shape == (0,)
    assert oblique.regime(np.empty(0), 0.3).shape == (0,)
    c1, c2 = oblique.critical(np.empty(0))
    assert c1.shape == c2.shape == (0,)
    out = np.empty(0)
    assert full.p(np.empty(0), 0.3, out=out) is out


def test_out_argument(full):
    g = np.linspace(0.2, 3.4, 12).reshape(3, 4)
    a = np.linspace(0.0, 2.0, 4)
    want = full.p(g, a)
    out = np.full((3, 4), np.nan)
    r = full.p(g, a, out=out)
    assert r is out
    assert np.array_equal(out, want)
    # A 0-d out for scalar arguments.
    o0 = np.empty(())
    assert full.p(1.5, 0.3, out=o0) is o0 and o0[()] == full.p(1.5, 0.3)
    # Wrong shape, dtype, read-only.
    with pytest.raises(ValueError, match="shape"):
        full.p(g, a, out=np.empty((4, 3)))
    with pytest.raises(ValueError, match="shape"):
        full.p(g, a, out=np.empty(12))
    with pytest.raises(TypeError, match="dtype"):
        full.p(g, a, out=np.empty((3, 4), dtype=np.float32))
    with pytest.raises(TypeError):
        full.p(g, a, out=[[0.0] * 4] * 3)
    ro = np.empty((3, 4))
    ro.flags.writeable = False
    with pytest.raises(ValueError, match="read-only"):
        full.p(g, a, out=ro)
    # Non-contiguous out: a transposed array and a strided view are filled correctly.
    big = np.full((4, 3), np.nan)
    tr = big.T
    assert not tr.flags.c_contiguous
    assert full.p(g, a, out=tr) is tr
    assert np.array_equal(tr, want) and np.array_equal(big, want.T)
    base = np.full((6, 8), 7.0)
    view = base[::2, ::2]
    assert full.p(g, a, out=view) is view
    assert np.array_equal(view, want)
    assert np.all(base[1::2] == 7.0) and np.all(base[:, 1::2] == 7.0)  # nothing else touched
    # out= of e_t and Curve.p.
    oe = np.empty((3, 4))
    assert full.e_t(g, a, out=oe) is oe
    np.testing.assert_allclose(oe, (2 * want + 5) / 7, rtol=0, atol=4e-16)
    c = full.curve(1.5)
    oc = np.empty((8, 2))[:, 0]
    assert c.p(a.repeat(2), out=oc) is oc
    assert np.array_equal(oc, c.p(a.repeat(2)))


def test_out_may_alias_an_input(full):
    """NumPy's convention (ufuncs): out= may be one of the inputs; the answer is as if the
    inputs had been copied first."""
    g = np.linspace(0.5, 3.0, 10)
    a = np.full(10, 0.8)
    want = full.p(g.copy(), a.copy())
    gg = g.copy()
    assert full.p(gg, a, out=gg) is gg
    assert np.array_equal(gg, want)
    aa = a.copy()
    assert full.p(g, aa, out=aa) is aa
    assert np.array_equal(aa, want)


def test_non_contiguous_inputs(full):
    rng = np.random.default_rng(31)
    g = rng.uniform(0.1, 3.5, (40, 30))
    a = rng.uniform(0.0, 3.0, (40, 30))
    cases = [
        (g[::3, ::2], a[::3, ::2]),  # slices with a step
        (g.T, a.T),  # transposed
        (np.asfortranarray(g), np.asfortranarray(a)),  # Fortran order
        (g[::-1], a[:, ::-1][::-1, ::-1]),  # negative strides
        (g[:, 5], a[:, 5]),  # a column
    ]
    for gi, ai in cases:
        want = full.p(np.ascontiguousarray(gi), np.ascontiguousarray(ai))
        got = full.p(gi, ai)
        assert got.shape == gi.shape
        assert np.array_equal(got, want)
        assert np.array_equal(full.e_t(gi, ai), full.e_t(gi.copy(), ai.copy()))
        assert np.array_equal(full.curve(1.7).p(ai), full.curve(1.7).p(ai.copy()))
    # Broadcast (stride-0) views.
    gb = np.broadcast_to(np.array([[1.2], [2.2]]), (2, 5))
    ab = np.broadcast_to(np.linspace(0, 2, 5), (2, 5))
    assert np.array_equal(full.p(gb, ab), full.p(gb.copy(), ab.copy()))


def test_integer_float32_and_list_inputs(full):
    assert full.p(2, 1) == full.p(2.0, 1.0)
    assert np.array_equal(full.p(np.array([1, 2, 3]), 1), full.p([1.0, 2.0, 3.0], 1.0))
    for dt in (np.int8, np.int32, np.int64, np.uint16, np.uint64):
        assert np.array_equal(full.p(np.array([1, 2, 3], dtype=dt), np.array(1, dtype=dt)),
                              full.p([1.0, 2.0, 3.0], 1.0))
    g32 = np.array([1.3, 1.7, 2.9], dtype=np.float32)
    a32 = np.float32(0.45)
    want = full.p(g32.astype(np.float64), float(a32))
    assert np.array_equal(full.p(g32, a32), want)
    assert full.p(np.float32(1.3), np.float32(0.45)) == full.p(float(np.float32(1.3)),
                                                               float(np.float32(0.45)))
    assert np.array_equal(full.p([1.3, 1.7], [0.1, 0.9]),
                          np.array([full.p(1.3, 0.1), full.p(1.7, 0.9)]))


def test_e_t_broadcasts_over_kappa(full):
    g = np.array([0.6, 1.5, 2.5])
    a = np.array([0.1, 0.7, np.inf])
    kappa = np.array([[0.4], [2.0 / 3.0], [1.0], [0.25]])
    e = full.e_t(g, a, kappa=kappa)
    assert e.shape == (4, 3)
    p = full.p(g, a)
    want = 1.0 - kappa / (1.0 + kappa) * (1.0 - p)
    np.testing.assert_allclose(e, want, rtol=0, atol=1e-15)
    np.testing.assert_allclose(e[0], (2.0 * p + 5.0) / 7.0, rtol=0, atol=4e-16)
    # Default kappa is the solid sphere.
    assert np.array_equal(full.e_t(g, a), e[0])
    # kappa alone may carry the shape.
    assert full.e_t(1.5, 0.7, kappa=[0.4, 0.5]).shape == (2,)


def _regime_by_definition(g, a):
    g = np.asarray(g, dtype=float)
    a = np.asarray(a, dtype=float)
    c1 = np.where(g > 1.0, alpha_c1(g), np.nan)
    c2 = alpha_c2(g)
    full_slip = np.where(g > 1.0, a <= c1, a <= c2)
    stick = ~full_slip & (a >= c2)
    return np.where(full_slip, "full-slip", np.where(stick, "stick", "partial-slip"))


def test_regime_agrees_with_definitions(full):
    assert oblique.REGIMES == ("full-slip", "partial-slip", "stick")
    rng = np.random.default_rng(37)
    g = rng.uniform(0.05, 4.0, 20_000)
    a = np.concatenate([rng.uniform(0.0, 3.0, 19_000), np.zeros(500), np.full(500, np.inf)])
    rng.shuffle(a)
    got = oblique.regime(g, a)
    assert isinstance(got, np.ndarray) and got.shape == g.shape and got.dtype.kind == "U"
    want = _regime_by_definition(g, a)
    assert np.array_equal(got, want)
    assert set(np.unique(got)) == {"full-slip", "partial-slip", "stick"}
    # Exactly on the curves (as oblique.critical gives them): the definitions' inequalities.
    c1, c2 = oblique.critical(g)
    on_c1 = np.where(g > 1.0, c1, c2)
    assert np.all(oblique.regime(g, on_c1) == "full-slip")
    assert np.all(oblique.regime(g[g > 1], c2[g > 1]) == "stick")
    assert np.all(oblique.regime(g[g <= 1], np.nextafter(c2[g <= 1], np.inf)) == "stick")
    # γ = 1: both curves at 2/7.
    assert oblique.regime(1.0, 2.0 / 7.0) == "full-slip"
    assert oblique.regime(1.0, 0.3) == "stick"
    # Scalars give str; Table.regime is the same function; 2-D broadcasting.
    r = oblique.regime(1.5, 0.3)
    assert type(r) is str and r == "partial-slip"
    assert full.regime(1.5, 0.3) == r
    assert type(oblique.regime(np.array(1.5), np.array(3.0))) is str
    r2 = full.regime([0.8, 1.5, 2.5], [[0.01], [0.3], [10.0]])
    assert r2.shape == (3, 3)
    assert np.array_equal(r2, _regime_by_definition([0.8, 1.5, 2.5], [[0.01], [0.3], [10.0]]))
    # Critical values agree with the closed forms.
    np.testing.assert_allclose(c1, alpha_c1(g), rtol=1e-15)
    np.testing.assert_allclose(c2, alpha_c2(g), rtol=1e-15)


def test_full_slip_line_exact_for_any_gamma(full):
    """The line P = 1 − 7α is answered for any γ > 0, inside the domain or not."""
    g = np.array([1e-3, 0.05, 0.5, 1.0, 2.0, 5.0, 50.0])
    a = 0.9 * alpha_lin(g)
    assert np.array_equal(full.p(g, a), 1.0 - 7.0 * a)
    assert np.array_equal(full.p(g, 0.0), np.ones_like(g))


def test_full_slip_line_where_gamma_squared_overflows(full, dissipative):
    """γ ≳ 1.3e154: 2γ² overflows; α_c1 is 1/7 there (its limit), not NaN, and the line is
    answered as for every γ > 0 (it was refused, and the regime said partial slip)."""
    for g in (3.6e153, 1e154, 1.4e154, 1e200, 1.7e308):
        c1, c2 = oblique.critical(g)
        assert c1 == 1.0 / 7.0 and c2 >= 3e306, (g, c1, c2)
        assert oblique.regime(g, 0.1) == "full-slip"
        assert oblique.regime(g, 0.15) == "partial-slip"
        assert oblique.regime(g, math.inf) == "stick"
        assert full.p(g, 0.1) == 1.0 - 7.0 * 0.1
        with pytest.raises(ValueError, match=r"\bgamma\b"):
            full.p(g, 0.15)
        assert dissipative.p(g, 0.17, e_n=0.6) == 1.0 - 3.5 * 1.6 * 0.17
    g = np.array([1e154, 1e200])
    assert np.array_equal(oblique.critical(g)[0], [1.0 / 7.0] * 2)
    assert np.array_equal(full.p(g, 0.1), [1.0 - 7.0 * 0.1] * 2)


def test_a_table_path_as_str_bytes_or_path(table_paths):
    path = table_paths["quick"]
    want = oblique.Table(str(path)).p(1.5, 0.3)
    for given in (path, bytes(path), os.fsencode(str(path))):
        assert oblique.Table(given).p(1.5, 0.3) == want, repr(given)
    with pytest.raises(FileNotFoundError):
        oblique.Table(b"/nonexistent/table.h5")


def test_no_path_opens_the_built_in_table(tables):
    # The table built into the package is tables/default.h5, answered to the same bits, at
    # e_n = 1 (no e_n given) and below.
    built_in = oblique.Table()
    assert oblique.EMBEDDED_TABLE == "tables/default.h5"
    default = oblique.Table(TABLES / "default.h5")
    demo = oblique.Table(DISSIPATIVE)
    info, shipped = built_in.info, default.info
    assert info["path"] == "built-in tables/default.h5"
    for key in ("gamma_min", "gamma_max", "alpha_max", "e_n_min", "e_n_max", "law",
                "error_bound", "git_commit", "created"):
        assert info[key] == shipped[key], key
    assert (info["e_n_min"], info["e_n_max"], info["law"]) == (0.3, 1.0, "kelvin-voigt")
    assert info["error_bound"] <= 1e-5
    gamma, alpha = domain_points(built_in, 2000, 5)
    e_n = np.random.default_rng(6).uniform(0.3, 1.0, gamma.shape)
    assert np.array_equal(built_in.p(gamma, alpha), default.p(gamma, alpha))
    assert np.array_equal(built_in.p(gamma, alpha, e_n=e_n),
                          default.p(gamma, alpha, e_n=e_n))
    assert np.array_equal(built_in.p(gamma, alpha), built_in.p(gamma, alpha, e_n=1.0))
    # Both within their stated bounds of the same truth.
    bound = info["error_bound"] + tables["full"].info["error_bound"]
    assert abs(built_in.p(1.754, 1.0) - tables["full"].p(1.754, 1.0)) < bound
    bound = info["error_bound"] + demo.info["error_bound"]
    want = demo.p(1.754, 1.0, e_n=0.8)
    assert abs(built_in.p(1.754, 1.0, e_n=0.8) - want) < bound
    with pytest.raises(ValueError, match="gamma"):
        built_in.p(3.0, 1.0)
    with pytest.raises(ValueError, match="e_n"):
        built_in.p(1.754, 1.0, e_n=0.2)
    assert oblique.Table(clamp=True).clamp
    assert "built-in tables/default.h5" in repr(built_in)


def test_curve_on_a_finite_alpha_max_table(finite_table, finite_table_path):
    amax = finite_table.info["alpha_max"]
    clamped = oblique.Table(finite_table_path, clamp=True)
    a = np.array([0.0, 0.01, 1.0, amax, np.nextafter(amax, np.inf), 2 * amax, 1e300, np.inf])
    for gamma in (0.7, 1.0, 1.5, 2.4):
        c = clamped.curve(gamma)
        np.testing.assert_allclose(c.p(a), clamped.p(gamma, a), rtol=0, atol=1e-13)
        # Above alpha_max the clamped answer is the one at alpha_max.
        assert np.all(clamped.p(gamma, a[a >= amax]) == finite_table.p(gamma, amax))
        with pytest.raises(ValueError, match="alpha_max"):
            finite_table.curve(gamma).p(2 * amax)
        assert finite_table.curve(gamma).p(amax) == pytest.approx(
            finite_table.p(gamma, amax), abs=1e-13)


def test_parallel_and_serial_paths_agree(full):
    """Large batches are split over threads; the answers do not depend on the batch size."""
    g, a = domain_points(full, 60_000, seed=41)
    big = full.p(g, a)
    small = np.concatenate([full.p(g[i:i + 1000], a[i:i + 1000]) for i in range(0, g.size, 1000)])
    assert np.array_equal(big, small)
    c = full.curve(2.0)
    big = c.p(a)
    small = np.concatenate([c.p(a[i:i + 1000]) for i in range(0, a.size, 1000)])
    assert np.array_equal(big, small)


def test_threads_share_a_table(full):
    from concurrent.futures import ThreadPoolExecutor

    g, a = domain_points(full, 50_000, seed=43)
    want = full.p(g, a)
    c = full.curve(1.7)
    want_c = c.p(a)
    with ThreadPoolExecutor(max_workers=4) as ex:
        got = list(ex.map(lambda k: full.p(g, a) if k % 2 else c.p(a), range(8)))
    for k, r in enumerate(got):
        assert np.array_equal(r, want if k % 2 else want_c)
