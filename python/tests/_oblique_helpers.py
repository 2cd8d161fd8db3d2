"""Helpers of the `oblique` tests: paths, closed forms of physics.md written out independently
of the package, the Rust CLI as a reference, and point sets."""

from __future__ import annotations

import subprocess
from pathlib import Path
from typing import Tuple

import numpy as np

import oblique

ROOT = Path(__file__).resolve().parents[2]
TABLES = ROOT / "tables"
SWEEP = ROOT / "target" / "release" / "sweep"
READER = ROOT / "scripts" / "read_table.py"
SHIPPED = ("full", "quick", "isotropic")
#: The shipped table with a normal-restitution axis (e_n in [0.5, 1], Kelvin–Voigt law).
DISSIPATIVE = TABLES / "dissipative-demo.h5"
#: The shipped table of one pair (alumina-96 on soda-lime glass): P(α, e_n) at one γ.
PAIR = TABLES / "dissipative-pair.h5"


# ---------------------------------------------------------------------------------------------
# Closed forms of physics.md, written out independently of the package


def alpha_c1(gamma):
    """α_c1 = 2γ²/(7(2γ² − 1))."""
    g2 = np.asarray(gamma, dtype=float) ** 2
    with np.errstate(divide="ignore"):
        return 2.0 * g2 / (7.0 * (2.0 * g2 - 1.0))


def alpha_c2(gamma):
    """α_c2 = 2γ²/7."""
    return 2.0 * np.asarray(gamma, dtype=float) ** 2 / 7.0


def alpha_lin(gamma):
    """Upper end of the exact full-slip line P = 1 − 7α (α_c1 for γ > 1, α_c2 for γ ≤ 1)."""
    g = np.asarray(gamma, dtype=float)
    return np.where(g > 1.0, alpha_c1(g), alpha_c2(g))


def effective_moduli(e1, nu1, e2, nu2):
    """(E*, G*): 1/E* = Σ (1 − ν²)/E, 1/G* = Σ (2 − ν)/(4G), G = E/(2(1 + ν)); E = ∞ adds
    nothing."""

    def compliance(e, nu):
        e = np.asarray(e, dtype=float)
        nu = np.asarray(nu, dtype=float)
        g = e / (2.0 * (1.0 + nu))
        ce = np.where(np.isinf(e), 0.0, (1.0 - nu**2) / e)
        cg = np.where(np.isinf(e), 0.0, (2.0 - nu) / (4.0 * g))
        return ce, cg

    a, b = compliance(e1, nu1), compliance(e2, nu2)
    return 1.0 / (a[0] + b[0]), 1.0 / (a[1] + b[1])


def masses(m1, r1, k1, m2=None, r2=None, k2=None):
    """(m*, m_t, R*) of sphere 1 on a wall (m2 None) or on sphere 2."""
    inv_t = 1.0 / m1 + r1**2 / (k1 * m1 * r1**2)
    if m2 is None:
        return m1, 1.0 / inv_t, r1
    inv_t = inv_t + 1.0 / m2 + r2**2 / (k2 * m2 * r2**2)
    return 1.0 / (1.0 / m1 + 1.0 / m2), 1.0 / inv_t, r1 * r2 / (r1 + r2)


# ---------------------------------------------------------------------------------------------
# The Rust CLI


def sweep_query(table: Path, gamma, alpha, clamp: bool = False) -> Tuple[np.ndarray, np.ndarray]:
    """P and e_t of `sweep query TABLE --batch -` for the points (gamma[i], alpha[i]), parsed
    exactly (the CLI prints Rust's shortest round-trip formatting). Fails the test when the CLI
    is missing, exits non-zero or does not echo the points it was given."""
    assert SWEEP.is_file(), f"{SWEEP} is missing: build it with `cargo build --release`"
    g = np.asarray(gamma, dtype=float).ravel()
    a = np.asarray(alpha, dtype=float).ravel()
    assert g.shape == a.shape
    text = "".join(f"{x!r},{y!r}\n" for x, y in zip(g.tolist(), a.tolist()))
    cmd = [str(SWEEP), "query", str(table), "--batch", "-"] + (["--clamp"] if clamp else [])
    r = subprocess.run(cmd, input=text, capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, f"{' '.join(cmd)} exited {r.returncode}: {r.stderr[-2000:]}"
    lines = r.stdout.splitlines()
    assert len(lines) == len(g), f"{len(lines)} output lines for {len(g)} points"
    cols = [ln.split(",") for ln in lines]
    assert all(len(c) == 4 for c in cols), "expected lines gamma,alpha,P,e_t"
    echo_g = np.array([float(c[0]) for c in cols])
    echo_a = np.array([float(c[1]) for c in cols])
    assert np.array_equal(echo_g, g) and np.array_equal(echo_a, a), "points not echoed in order"
    p = np.array([float(c[2]) for c in cols])
    e_t = np.array([float(c[3]) for c in cols])
    return p, e_t


def domain_points(t: oblique.Table, n: int, seed: int) -> Tuple[np.ndarray, np.ndarray]:
    """`n` points (γ, α) over a table's domain: γ uniform in [gamma_min, gamma_max] (both ends
    included), α a mix of uniform [0, min(3, alpha_max)], exactly 0, alpha_max (inf for a table
    with no slip), and points exactly on the critical curves that oblique.critical gives."""
    info = t.info
    gmin, gmax, amax = info["gamma_min"], info["gamma_max"], info["alpha_max"]
    rng = np.random.default_rng(seed)
    g = rng.uniform(gmin, gmax, n)
    g[:5] = gmin
    g[5:10] = gmax
    g[10:12] = 1.0 if gmin <= 1.0 <= gmax else gmin
    a = rng.uniform(0.0, min(3.0, amax), n)
    kind = rng.integers(0, 10, n)
    c1, c2 = oblique.critical(g)
    a = np.where(kind == 0, 0.0, a)
    a = np.where(kind == 1, amax, a)
    a = np.where((kind == 2) & (c1 >= 0) & (c1 <= amax), c1, a)
    a = np.where((kind == 3) & (c2 <= amax), c2, a)
    # Neighbours of the curves (one ulp either side).
    a = np.where((kind == 4) & (c1 > 0) & (c1 < amax), np.nextafter(np.abs(c1), np.inf), a)
    a = np.where((kind == 5) & (c2 < amax), np.nextafter(c2, 0.0), a)
    assert np.all((a >= 0) & (a <= amax))
    return g, a
