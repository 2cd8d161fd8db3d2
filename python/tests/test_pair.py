"""The table of one pair of materials (schema 4, axes ``alpha,e_n``;
``tables/dissipative-pair.h5``, alumina-96 on soda-lime glass): ``P(α, e_n)`` at its single γ.
Its answers are those of the independent reference reader (``scripts/read_table.py``) and of
the Rust CLI (``sweep query --batch``) bit for bit, broadcast like every other table's; a γ
other than the pair's is refused naming γ and the pair's value (with the index in an array),
and ``Table.pair_gamma``, ``info`` and ``repr`` say which γ the table holds."""

from __future__ import annotations

import math
import re
import subprocess

import numpy as np
import pytest

import oblique
from _oblique_helpers import PAIR, SWEEP

#: γ of an alumina-96 sphere on a soda-lime-glass wall (``sweep gamma``).
GAMMA = 1.7497858600774299
PAIR_TEXT = re.escape(repr(GAMMA))


@pytest.fixture(scope="module")
def pair() -> oblique.Table:
    assert PAIR.is_file(), f"shipped table {PAIR} is missing"
    return oblique.Table(PAIR)


@pytest.fixture(scope="module")
def pair_reference(reader):
    return reader.Table(str(PAIR))


def _raises(exc, fn, *needles):
    with pytest.raises(exc) as info:
        fn()
    msg = str(info.value)
    for n in needles:
        assert re.search(n, msg), f"{n!r} not in message {msg!r}"
    return msg


def _bits(x):
    return np.asarray(x, dtype=np.float64).view(np.int64)


def _points(t, n, seed):
    """`n` points (α, e_n) at the pair's γ: α uniform in [0, 3] and log-uniform up to 1e3,
    with exactly 0, ∞, α_c1(γ, e_n), α_c2 and their neighbours among them; e_n uniform over
    the table's range with both ends."""
    rng = np.random.default_rng(seed)
    lo, hi = t.info["e_n_min"], t.info["e_n_max"]
    e = rng.uniform(lo, hi, n)
    e[::17] = lo
    e[1::17] = hi
    a = np.where(rng.random(n) < 0.5, rng.uniform(0.0, 3.0, n), 10 ** rng.uniform(-2, 3, n))
    g2 = GAMMA * GAMMA
    c1 = 2 * g2 / (7 * (g2 * (1 + e) - e))
    c2 = 2 * g2 / 7
    kind = np.arange(n) % 13
    a = np.where(kind == 0, 0.0, a)
    a = np.where(kind == 1, np.inf, a)
    a = np.where(kind == 2, c1, a)
    a = np.where(kind == 3, np.nextafter(c1, np.inf), a)
    a = np.where(kind == 4, c2, a)
    a = np.where(kind == 5, np.nextafter(c2, 0.0), a)
    return a, e


# ---------------------------------------------------------------------------------------------
# What the table holds


def test_pair_gamma_info_and_repr(pair, dissipative, full):
    assert pair.pair_gamma == GAMMA
    i = pair.info
    assert i["gamma_min"] == i["gamma_max"] == i["pair_gamma"] == GAMMA
    assert i["axes"] == ["alpha", "e_n"]
    assert (i["e_n_min"], i["e_n_max"]) == (0.5, 1.0)
    assert i["law"] == "kelvin-voigt" and i["schema_version"] == 4
    text = repr(pair)
    assert f"gamma = {GAMMA!r} (one pair)" in text and "gamma in" not in text, text
    assert "e_n in [0.5, 1.0]" in text
    # Every other table spans a range of γ.
    for t, axes in ((dissipative, ["gamma", "alpha", "e_n"]), (full, ["gamma", "alpha"])):
        assert t.pair_gamma is None and t.info["pair_gamma"] is None
        assert t.info["axes"] == axes
        assert "gamma in [" in repr(t) and "one pair" not in repr(t)
    assert oblique.Table().pair_gamma is None


# ---------------------------------------------------------------------------------------------
# Answers


def test_p_is_the_reference_readers_bits(pair, pair_reference):
    a, e = _points(pair, 20_000, seed=71)
    p = pair.p(pair.pair_gamma, a, e_n=e)
    ref = np.array([pair_reference.p_e(GAMMA, x, y) for x, y in zip(a.tolist(), e.tolist())])
    np.testing.assert_array_equal(_bits(p), _bits(ref))
    assert np.all(np.abs(p) <= 1.0)
    # Scalar calls, and e_n = 1 (the default), the same bits.
    for x, y in list(zip(a.tolist(), e.tolist()))[:500]:
        assert _bits(pair.p(GAMMA, x, e_n=y)) == _bits(pair_reference.p_e(GAMMA, x, y))
    ones = pair.p(GAMMA, a[:2000])
    np.testing.assert_array_equal(_bits(ones), _bits(pair.p(GAMMA, a[:2000], e_n=1.0)))
    np.testing.assert_array_equal(
        _bits(ones), _bits([pair_reference.p_e(GAMMA, x, 1.0) for x in a[:2000].tolist()])
    )


def test_p_is_the_cli_bits(pair):
    assert SWEEP.is_file(), f"{SWEEP} is missing: build it with `cargo build --release`"
    a, e = _points(pair, 3000, seed=73)
    text = "".join(f"{GAMMA!r},{x!r},{y!r}\n" for x, y in zip(a.tolist(), e.tolist()))
    r = subprocess.run([str(SWEEP), "query", str(PAIR), "--batch", "-"], input=text,
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr[-2000:]
    cols = [ln.split(",") for ln in r.stdout.splitlines()]
    assert len(cols) == len(a) and all(len(c) == 5 for c in cols), "lines gamma,alpha,e_n,P,e_t"
    cli = np.array([float(c[3]) for c in cols])
    np.testing.assert_array_equal(_bits(pair.p(GAMMA, a, e_n=e)), _bits(cli))


def test_a_gamma_within_1e_9_of_the_pairs_is_the_pairs(pair):
    a, e = _points(pair, 2000, seed=79)
    at = pair.p(GAMMA, a, e_n=e)
    rng = np.random.default_rng(83)
    near = GAMMA * (1 + rng.uniform(-9e-10, 9e-10, a.shape))
    np.testing.assert_array_equal(_bits(pair.p(near, a, e_n=e)), _bits(at))


def test_p_broadcasts(pair):
    e = np.array([[0.5], [0.75], [1.0]])
    alpha = np.array([0.05, 0.3, 1.0, np.inf])
    p = pair.p(GAMMA, alpha, e_n=e)
    assert p.shape == (3, 4)
    for i, ei in enumerate(e[:, 0].tolist()):
        for j, aj in enumerate(alpha.tolist()):
            assert p[i, j] == pair.p(GAMMA, aj, e_n=ei)
    g = np.full((2, 1, 1), GAMMA)
    q = pair.p(g, alpha, e_n=e)
    assert q.shape == (2, 3, 4)
    np.testing.assert_array_equal(q, np.broadcast_to(p, (2, 3, 4)))
    out = np.empty((3, 4))
    assert pair.p(pair.pair_gamma, alpha, out, e_n=e) is out
    np.testing.assert_array_equal(out, p)
    # e_t of a solid sphere at e_n = 1 follows P.
    np.testing.assert_array_equal(pair.e_t(GAMMA, alpha, 0.4), 1 - (0.4 / 1.4) * (1 - p[2]))


def test_the_line_is_exact_at_any_gamma(pair):
    a = np.array([0.0, 0.005, 0.01])
    for g in (0.3, 1.0, 3.0, GAMMA * 1.1):
        np.testing.assert_array_equal(pair.p(g, a, e_n=0.8), 1 - 3.5 * 1.8 * a)


def test_the_curve_of_the_pair(pair):
    """``Table.curve`` at the pair's γ: P(α) at e_n = 1, the values of ``Table.p`` to 1e-14;
    another γ refused as in ``Table.p``."""
    a = np.concatenate([np.linspace(0.0, 3.0, 3001), 10 ** np.linspace(0.5, 4, 50), [np.inf]])
    c = pair.curve(pair.pair_gamma)
    assert c.gamma == GAMMA
    np.testing.assert_allclose(c.p(a), pair.p(GAMMA, a), rtol=0, atol=1e-14)
    _raises(ValueError, lambda: pair.curve(1.75), r"\bgamma = 1\.75\b", PAIR_TEXT)


# ---------------------------------------------------------------------------------------------
# Refusals


def test_another_gamma_is_refused_naming_the_pairs(pair):
    for bad in (1.75, GAMMA * (1 + 2e-9), 0.9, 3.0):
        _raises(ValueError, lambda: pair.p(bad, 0.5, e_n=0.8), r"\bgamma = ", PAIR_TEXT,
                "one pair")
    msg = _raises(ValueError, lambda: pair.p(1.75, 0.5), r"\bgamma = 1\.75\b", PAIR_TEXT)
    assert "index" not in msg
    _raises(ValueError, lambda: pair.p([GAMMA, GAMMA, 1.75], 0.5, e_n=0.8),
            r"\bgamma = 1\.75\b", PAIR_TEXT, re.escape("(at index (2,))"))
    _raises(ValueError, lambda: pair.p([[GAMMA], [1.8]], [0.5, 1.0]), r"\bgamma = 1\.8\b",
            PAIR_TEXT, re.escape("(at index (1, 0))"))
    big = np.full(20_000, GAMMA)
    big[12_345] = 1.7
    _raises(ValueError, lambda: pair.p(big, 0.5, e_n=0.9), r"\bgamma = 1\.7\b", PAIR_TEXT,
            re.escape("(at index (12345,))"))
    # e_n outside the range: refused naming e_n (never clamped).
    _raises(ValueError, lambda: pair.p(GAMMA, [0.5, 0.6], e_n=[0.7, 0.4]), r"\be_n = 0\.4\b",
            re.escape("[0.5, 1]"), re.escape("(at index (1,))"))


def test_clamping_answers_at_the_pairs_gamma(pair):
    clamped = oblique.Table(PAIR, clamp=True)
    a = np.array([0.3, 1.0, np.inf])
    at = pair.p(GAMMA, a, e_n=0.7)
    for g in (0.5, 1.75, 3.0):
        np.testing.assert_array_equal(clamped.p(g, a, e_n=0.7), at)


# ---------------------------------------------------------------------------------------------
# Rebounds


def _alumina_on_glass(pair, e_n, **kw):
    ball = oblique.Sphere(mass=2.4347e-4, radius=2.5e-3, kappa=0.4)
    theta = np.radians([15.0, 30.0, 60.0])[:, None]  # rows: angle; columns: e_n
    v = 3.9 * np.stack([np.sin(theta), 0 * theta, np.cos(theta)], axis=-1)  # (3, 1, 3)
    return pair.rebound(ball, v, friction=0.092, e_n=e_n, **kw)


def test_rebounds_from_the_pairs_materials(pair):
    e = np.array([0.5, 0.8, 1.0])
    m = oblique.materials
    r = _alumina_on_glass(pair, e, materials=(m["alumina-96"], m["soda-lime-glass"]))
    assert r.p.shape == (3, 3)
    assert np.all(np.abs(r.gamma - GAMMA) <= 1e-9 * GAMMA)
    np.testing.assert_array_equal(_bits(r.p), _bits(pair.p(GAMMA, r.alpha, e_n=r.e_n)))
    np.testing.assert_array_equal(r.e_n, np.broadcast_to(e, (3, 3)))
    g = _alumina_on_glass(pair, e, gamma=pair.pair_gamma)
    np.testing.assert_array_equal(_bits(g.p), _bits(r.p))
    two = pair.rebound_2d(oblique.Sphere(2.4347e-4, 2.5e-3), 1.0, 2.0, friction=0.092,
                          gamma=GAMMA, e_n=e)
    np.testing.assert_array_equal(_bits(two.p), _bits(pair.p(GAMMA, two.alpha, e_n=e)))
    np.testing.assert_allclose(two.v_z, -e * 2.0, rtol=1e-15)


def test_rebounds_at_another_gamma_are_refused(pair):
    e = np.array([0.5, 0.8, 1.0])
    steel = oblique.Material(2.1e11, 0.29)
    _raises(ValueError, lambda: _alumina_on_glass(pair, e, materials=(steel, oblique.RIGID)),
            r"\bgamma = ", PAIR_TEXT, re.escape("(at index (0, 0))"))
    # Steep impacts (15 degrees from the normal) are in partial slip or stick; the 60-degree
    # ones slip throughout, on the full-slip line, answered at any gamma.
    _raises(ValueError, lambda: _alumina_on_glass(pair, e, gamma=[[GAMMA, GAMMA, 1.8]]),
            r"\bgamma = 1\.8\b", PAIR_TEXT, re.escape("(at index (0, 2))"))
    r = _alumina_on_glass(pair, e, gamma=[[GAMMA], [GAMMA], [1.8]])
    assert np.all(oblique.regime(1.8, r.alpha[2]) == "full-slip")
    np.testing.assert_array_equal(r.p[2], 1 - 3.5 * (1 + e) * r.alpha[2])
    msg = _raises(ValueError, lambda: pair.rebound_2d(oblique.Sphere(1.0, 0.01), 1.0, 1.0,
                                                      friction=0.3, gamma=1.5, e_n=0.8),
                  r"\bgamma = 1\.5\b", PAIR_TEXT)
    assert "index" not in msg
    assert math.isfinite(pair.rebound_2d(oblique.Sphere(1.0, 0.01), 1.0, 1.0, friction=0.3,
                                         gamma=GAMMA, e_n=0.8).p)
