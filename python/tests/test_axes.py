"""The axes of a table as data: ``Table.axes`` lists a point's axes, ``Table.p`` takes every axis
beyond γ and α as a keyword of its name (``e_n``), and the answers are those of the reference
reader's ``p_at`` (``scripts/read_table.py``, itself ``p``/``p_e``): its bits on
``tables/default.h5`` (axes γ, α, e_n), within its 1e-12 on ``tables/full.h5`` (γ, α)."""

from __future__ import annotations

import numpy as np
import pytest

import oblique
from _oblique_helpers import TABLES


def _bits(x):
    return np.asarray(x, dtype=np.float64).view(np.uint64)


@pytest.fixture(scope="module", params=["default", "full"])
def pair(request, reader):
    path = TABLES / f"{request.param}.h5"
    return oblique.Table(path), reader.Table(str(path))


def _points(t, n, seed):
    rng = np.random.default_rng(seed)
    i = t.info
    g = rng.uniform(i["gamma_min"], i["gamma_max"], n)
    a = 10.0 ** rng.uniform(-3, 1, n)
    a[::17] = np.inf
    e = rng.uniform(i["e_n_min"], i["e_n_max"], n)
    return g, a, e


def test_axes_are_the_files_and_the_readers(pair):
    t, ref = pair
    assert t.axes == tuple(ref.axes)
    assert t.axes[:2] == ("gamma", "alpha")
    assert list(t.info["axes"]) == list(t.axes)


def test_p_by_axis_keywords_gives_the_reference_readers_bits(pair):
    t, ref = pair
    g, a, e = _points(t, 1500, 52)
    extra = t.axes[2:]
    kw = {"e_n": e} if extra else {}
    p = t.p(g, a, **kw)
    for i in range(len(g)):
        point = [g[i], a[i]] + ([e[i]] if extra else [])
        want = ref.p_at(point)
        if extra:
            assert _bits(p[i]) == _bits(want), point
        else:
            # The reader's rule of an elastic table agrees to 1e-12 (test_table.READER_TOL).
            assert abs(p[i] - want) <= 1e-12, point
        scalar = t.p(float(g[i]), float(a[i]), **({"e_n": float(e[i])} if extra else {}))
        assert _bits(scalar) == _bits(p[i]), point
        if extra:
            assert _bits(ref.p_e(*point)) == _bits(want)
        else:
            assert _bits(ref.p(*point)) == _bits(want)


def test_a_keyword_of_no_axis_is_a_type_error_naming_the_axes(pair):
    t, _ = pair
    with pytest.raises(TypeError, match=r"'e_t'.*e_n"):
        t.p(1.5, 0.3, e_t=0.8)
    with pytest.raises(TypeError, match=r"'e_t'"):
        t.p(np.array([1.5, 1.6]), 0.3, e_t=0.8)
    if "e_n" not in t.axes:
        # An elastic table answers e_n = 1 only.
        assert _bits(t.p(1.5, 0.3, e_n=1.0)) == _bits(t.p(1.5, 0.3))
        with pytest.raises(ValueError, match="e_n"):
            t.p(1.5, 0.3, e_n=0.8)
    with pytest.raises(ValueError, match="e_n"):
        t.p(1.5, 0.3, e_n=float("nan"))


def test_the_reference_reader_refuses_a_point_of_another_length(pair):
    _, ref = pair
    n = len(ref.axes)
    with pytest.raises(ValueError, match=", ".join(ref.axes)):
        ref.p_at([1.5, 0.3, 0.9, 1.0][: n + 1])
