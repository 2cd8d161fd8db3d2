#!/usr/bin/env python3
"""Reference reader of the P(gamma, alpha) table (HDF5, schema v5, v4, v3 or v2), h5py + numpy
only.

Implements the interpolation rule of docs/table-format.md (steps 1-10, the rule of a table with
a normal-restitution axis, schema v4, that of the table of one pair, axes 'alpha,e_n', and that
of a table of Thornton's law, which has no full-slip line: "Tables of Thornton's law", with the
knots of its partial-slip and stick coordinates where the table has them: "The knots", and its
e_n axis over (1 - e_n)^(1/4) where the table maps it: "Schema v5") exactly,
independently of the Rust code, so that it can cross-check both the `oblique-lookup` crate and
the simulator.

    python3 scripts/read_table.py TABLE --gamma G --alpha A        # prints P (alpha may be inf)
    python3 scripts/read_table.py TABLE --gamma G --alpha A --e-n E   # P(gamma, alpha, e_n)
    python3 scripts/read_table.py PAIR_TABLE --alpha A --e-n E       # at the pair's gamma
    python3 scripts/read_table.py TABLE --check-stored             # vs /checks/P_interpolated
    python3 scripts/read_table.py TABLE --error-bound              # the stated error bound
    python3 scripts/read_table.py TABLE --check-against-sweep 12 --max-error 1e-5

Exit status: 0 success, 1 a check failed, 2 usage error / unreadable table / query outside
the domain.

As a library:

    from read_table import Table
    t = Table("tables/full.h5")
    t.p(1.754, 1.0), t.p(0.8, float("inf"))
    t = Table("kv.h5")                 # a table with an e_n axis (schema 4)
    t.e_n_range, t.p_e(1.45, 0.3, 0.8)
    t.axes, t.p_at([1.45, 0.3, 0.8])   # ('gamma', 'alpha', 'e_n'): a point of any table
    t = Table("tables/dissipative-pair.h5")   # the table of one pair: P(alpha, e_n) at one gamma
    t.pair_gamma, t.p_e(t.pair_gamma, 0.3, 0.8)
"""

import argparse
import json
import math
import os
import struct
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor

try:
    import h5py
    import numpy as np
except ImportError as e:  # pragma: no cover - depends on the machine
    sys.stderr.write(f"error: {e}; install the dependencies with `pip install h5py numpy`\n")
    sys.exit(2)

FORMAT_NAME = "oblique-P-table"
SCHEMA_VERSION = 5
# v2: v3 without the optional warp; v4: v3 with an optional e_n axis; v5: v4 whose root attribute
# 'e_n_coordinate' names the map of the e_n axis
SCHEMA_VERSIONS = (2, 3, 4, 5)
# The maps of the e_n axis a schema-5 table may name (root attribute 'e_n_coordinate'): the
# linear axis of schema 4, and the axis over t = (1 - e_n)^(1/4).
E_N_LINEAR = "e_n"
E_N_QUARTER_ROOT = "(1-e_n)^(1/4)"
E_N_COORDINATES = (E_N_LINEAR, E_N_QUARTER_ROOT)
AXES_PAIR = "alpha,e_n"  # the axes of the table of one pair (schema 4): P(alpha, e_n) at one gamma
# The contact laws whose tables (with an e_n axis) this reader answers (root attribute 'law'),
# each with the partial-slip coordinate its tables have (attribute 'coordinate' of
# /patches/partial_high). Thornton's law has no closed-form full-slip line: its partial-slip
# patch covers 0 <= alpha <= alpha_c2 (docs/table-format.md, "Tables of Thornton's law").
LAWS_E_N = {"kelvin-voigt": "1-sqrt(1-sqrt(l))", "thornton": "slip,1-sqrt(1-sqrt(l))"}
LAWS_NO_LINE = ("thornton",)
# The axes a table may have beyond gamma and alpha (schema 4), each with the bounds of its range,
# bound_lo < NAME_min < NAME_max <= bound_hi; the file names its range NAME_min, NAME_max (root)
# and its root cells blocks_NAME (patch).
EXTRA_AXES = {"e_n": (0.0, 1.0)}
# A stored node coordinate may differ from where the tree puts the node by this share of its
# axis's span (rounding is a few ulps; any edit that matters is far larger).
POSITION_TOL = 1e-9
PAIR_GAMMA_TOL = 1e-9  # a gamma within this (relative) of the pair's is the pair's
PATCH_NAMES = ("stick_low", "partial_high", "stick_high")
PATCH_KINDS = {"stick_low": "stick", "partial_high": "partial-slip", "stick_high": "stick"}


class TableError(Exception):
    """The file is not a readable P table of schema v2, v3, v4 or v5."""


class DomainError(ValueError):
    """A query (gamma, alpha[, e_n]) outside what the table (or the rule) answers; `name` is
    the refused argument: 'gamma', 'alpha' or 'e_n'."""

    def __init__(self, message, name=None):
        super().__init__(message)
        self.name = name


def alpha_c1(gamma):
    """alpha_c1 = 2 gamma^2 / (7 (2 gamma^2 - 1)); where the denominator overflows, the same
    value as 1 / (7 (1 - 1/(2 gamma^2))) (1/7), as the Rust library computes it."""
    g2 = gamma * gamma
    d = 7.0 * (2.0 * g2 - 1.0)
    if d == math.inf:
        return 1.0 / (7.0 * (1.0 - 1.0 / (2.0 * g2)))
    return 2.0 * g2 / d


def alpha_c2(gamma):
    """alpha_c2 = 2 gamma^2 / 7."""
    return 2.0 * gamma * gamma / 7.0


def alpha_lin(gamma):
    """Upper end of the exact full-slip line P = 1 - 7 alpha (step 1)."""
    return alpha_c1(gamma) if gamma > 1.0 else alpha_c2(gamma)


def stick_rho(gamma):
    """rho = 2 (1 - gamma^2) for gamma < 1, 1 for gamma >= 1."""
    return 2.0 * (1.0 - gamma * gamma) if gamma < 1.0 else 1.0


def stick_s(gamma, alpha):
    """S(alpha) = r / (r + rho), r = alpha/alpha_c2 - 1, S(inf) = 1."""
    r = alpha / alpha_c2(gamma) - 1.0
    if math.isinf(r):  # alpha = inf, or so large that r overflows
        return 1.0
    return r / (r + stick_rho(gamma))


def coordinate(kind, gamma, alpha, alpha_max):
    """Patch coordinate c of (gamma, alpha) (before clamping)."""
    if kind == "partial-slip":
        c1 = alpha_c1(gamma)
        ell = math.log(alpha / c1) / math.log(alpha_c2(gamma) / c1)
        return 1.0 - math.sqrt(max(1.0 - ell, 0.0))
    return stick_s(gamma, alpha) / stick_s(gamma, alpha_max)


def alpha_at(kind, gamma, c, alpha_max):
    """Inverse of `coordinate`: alpha at patch coordinate c in [0, 1] (alpha_max at c = 1)."""
    if kind == "partial-slip":
        c1 = alpha_c1(gamma)
        return c1 * (alpha_c2(gamma) / c1) ** (1.0 - (1.0 - c) ** 2)
    if c >= 1.0:
        return alpha_max
    rho = stick_rho(gamma)
    q = c * stick_s(gamma, alpha_max)
    return alpha_c2(gamma) * (1.0 + rho * q / (1.0 - q))


def lagrange(u, n, k):
    """Step 8: start index and the k Lagrange weights at grid position u on nodes 0..n."""
    cell = min(int(math.floor(u)), n - 1)
    start = min(max(cell + 1 - k // 2, 0), n + 1 - k)
    w = []
    for j in range(k):
        prod = 1.0
        for m in range(k):
            if m != j:
                prod *= (u - (start + m)) / (j - m)
        w.append(prod)
    return start, w


def lebesgue(k, per=4096):
    """Lebesgue constant of the k-point Lagrange basis on the equispaced nodes 0..k-1: the
    maximum over u in [0, k-1] (sampled on `per` points per interval) of sum_j |l_j(u)|."""
    worst = 1.0
    for s in range(per * (k - 1) + 1):
        u = s / per
        total = 0.0
        for j in range(k):
            prod = 1.0
            for n in range(k):
                if n != j:
                    prod *= (u - n) / (j - n)
            total += abs(prod)
        worst = max(worst, total)
    return worst


def _clamp01(v):
    return min(max(v, 0.0), 1.0)


# ---------------------------------------------------------------------------------------------
# The rule of a table with an e_n axis (schema v4), written with the operations, in the order,
# that docs/table-format.md ("Schema v4", "The same bits") states, so that P has the bits of
# every other reader: closed-form cubic weights, sums from left to right, libm's log (Python's
# math module calls the C library's, as Rust does on Linux; sqrt is exact everywhere).


def alpha_c1_e(gamma, e_n):
    """alpha_c1(gamma, e_n) = 2 gamma^2 / (7 (gamma^2 (1 + e_n) - e_n))."""
    g2 = gamma * gamma
    d = 7.0 * (g2 * (1.0 + e_n) - e_n)
    if d == math.inf:  # overflow: the same value, as the Rust library computes it
        return 2.0 / (7.0 * ((1.0 + e_n) - e_n / g2))
    return 2.0 * g2 / d


def alpha_lin_e(gamma, e_n):
    """End of the full-slip line P = 1 - (7/2)(1 + e_n) alpha: alpha_c1(gamma, e_n) for
    gamma > 1, else alpha_c2(gamma) (which does not move with e_n)."""
    return alpha_c1_e(gamma, e_n) if gamma > 1.0 else alpha_c2(gamma)


def full_slip_e(alpha, e_n):
    """P = 1 - (7/2)(1 + e_n) alpha."""
    return 1.0 - 3.5 * (1.0 + e_n) * alpha


def partial_coord_e(gamma, alpha, e_n):
    """c = 1 - sqrt(1 - sqrt(l)), l = ln(alpha/alpha_c1)/ln(alpha_c2/alpha_c1) clamped to [0, 1],
    with alpha/alpha_c1 = 7 alpha h/(2 gamma^2) and alpha_c2/alpha_c1 = h = gamma^2(1+e_n) - e_n."""
    g2 = gamma * gamma
    ratio = g2 * (1.0 + e_n) - e_n
    ell = math.log(7.0 * alpha * ratio / (2.0 * g2)) / math.log(ratio)
    return 1.0 - math.sqrt(1.0 - math.sqrt(_clamp01(ell)))


def partial_coord_slip(gamma, alpha, e_n):
    """The partial-slip coordinate of a table without a full-slip line (Thornton's law), over
    0 <= alpha <= alpha_c2: q = alpha/alpha_c1 = 7 alpha h/(2 gamma^2); c = q/2 for q <= 1 (no
    logarithm), else c = 1/2 + (1 - sqrt(1 - sqrt(l)))/2, l = ln(q)/ln(h) clamped to [0, 1]."""
    g2 = gamma * gamma
    ratio = g2 * (1.0 + e_n) - e_n
    q = 7.0 * alpha * ratio / (2.0 * g2)
    if q <= 1.0:
        return 0.5 * q
    ell = math.log(q) / math.log(ratio)
    return 0.5 + 0.5 * (1.0 - math.sqrt(1.0 - math.sqrt(_clamp01(ell))))


def stick_coord(gamma, alpha, alpha_max):
    """S(alpha)/S(alpha_max), S = d/(d + rho c2), d = alpha - c2, c2 = gamma^2 (2/7)."""
    if math.isinf(alpha):
        return 1.0
    c2 = gamma * gamma * (2.0 / 7.0)
    rho = stick_rho(gamma)
    d = alpha - c2
    s = d / (d + rho * c2)
    if math.isinf(alpha_max):
        return s
    dm = alpha_max - c2
    return s / (dm / (dm + rho * c2))


def cubic_stencil(u, n):
    """Step 8 for k = 4 on n nodes: start and the cubic Lagrange weights at u, in closed form."""
    cell = min(max(int(u), 0), n - 2)  # u >= 0: int() is floor
    start = min(max(cell - 1, 0), n - 4)
    a = u - start
    b, c, d = a - 1.0, a - 2.0, a - 3.0
    ab, cd = a * b, c * d
    return start, (-(b * cd) * (1.0 / 6.0), a * cd * 0.5, -(ab * d) * 0.5, ab * c * (1.0 / 6.0))


def locate(x, blocks):
    """Step 6 on one axis: root cell and position in it of x in [0, 1] (clamped)."""
    u = min(max(x * blocks, 0.0), float(blocks))
    a = min(max(int(u), 0), blocks - 1)
    return a, u - a


def _str_attr(attrs, name):
    v = attrs[name]
    if isinstance(v, bytes):
        v = v.decode("utf-8")
    if isinstance(v, np.ndarray) and v.shape == ():
        v = v[()]
        if isinstance(v, bytes):
            v = v.decode("utf-8")
    if not isinstance(v, str):
        raise TypeError(f"attribute '{name}' is not a string")
    return v


def _float_attr(attrs, name):
    v = np.asarray(attrs[name])
    if v.shape not in ((), (1,)) or v.dtype.kind not in "fiu":
        raise TypeError(f"attribute '{name}' is not a number")
    return float(v.reshape(()))


def quarter_root(e):
    """The mapped value m(e) = -(1 - e)^(1/4) of an e_n axis over (1 - e_n)^(1/4), as
    -sqrt(sqrt(1 - e)): two correctly rounded square roots (Python floats are binary64)."""
    return -math.sqrt(math.sqrt(1.0 - e))


class EAxis:
    """The e_n axis of a table, [lo, hi], and how e_n maps to its coordinate: linearly,
    x_e = (e_n - lo)/(hi - lo), or over t = (1 - e_n)^(1/4) (schema 5, 'e_n_coordinate' =
    '(1-e_n)^(1/4)'), x_e = (m(e_n) - m(lo))/(m(hi) - m(lo)) with m = quarter_root, i.e.
    (t_min - t)/(t_min - t_max) (docs/table-format.md, "Schema v5")."""

    def __init__(self, lo, hi, quarter):
        self.lo, self.hi, self.quarter = lo, hi, quarter
        # The mapped ends: x_e = (m(e_n) - m_lo)/m_width (lo, hi - lo on a linear axis).
        if quarter:
            self.m_lo = quarter_root(lo)
            self.m_width = quarter_root(hi) - self.m_lo
        else:
            self.m_lo, self.m_width = lo, hi - lo

    def x(self, e_n):
        """The coordinate x_e of e_n (steps 6 and 7, and the knots' region)."""
        if self.quarter:
            return (quarter_root(e_n) - self.m_lo) / self.m_width
        return (e_n - self.lo) / (self.hi - self.lo)

    def at_cells(self, v, blocks):
        """The e_n at root-cell position v of the axis's `blocks` root cells (the knots' check):
        lo + (hi - lo) v/blocks on a linear axis; over t at x = v/blocks, lo at x <= 0, hi at
        x >= 1, else 1 - w^4 of w = m_lo + m_width x, clamped to [lo, hi]."""
        if not self.quarter:
            return self.lo + (self.hi - self.lo) * v / blocks
        x = v / blocks
        if x >= 1.0:
            return self.hi
        if x <= 0.0:
            return self.lo
        w = self.m_lo + self.m_width * x
        w = w * w
        return min(max(1.0 - w * w, self.lo), self.hi)


class Warp:
    """The optional warp of the partial-slip coordinate (group /patches/partial_high/warp)."""

    def __init__(self, start, gamma_0, gamma_step, c_star, knot):
        self.start = start  # lattice position along gamma (root rows) where the warp starts
        self.gamma_0 = gamma_0
        self.gamma_step = gamma_step
        self.c_star = c_star
        self.knot = [float(k) for k in knot]

    def knot_at(self, gamma):
        """K(gamma): 4-point Lagrange rule (step 8) on the knot values at
        u = (gamma - gamma_0)/gamma_step clamped to [0, n - 1]."""
        n = len(self.knot)
        u = min(max((gamma - self.gamma_0) / self.gamma_step, 0.0), float(n - 1))
        start, w = lagrange(u, n - 1, 4)
        total = 0.0
        for j in range(4):
            total += w[j] * self.knot[start + j]
        return total

    def apply(self, gamma, c):
        """Step 5: c -> c' (for a point at or beyond `start`): graded below the knot K,
        linear above it."""
        k = self.knot_at(gamma)
        if c <= k:
            return self.c_star * (1.0 - math.sqrt(max(1.0 - c / k, 0.0)))
        return self.c_star + (1.0 - self.c_star) * (c - k) / (1.0 - k)


MAX_KNOTS = 8  # most knots the group 'knots' may hold


class Knots:
    """The optional knots of the partial-slip coordinate of a table over gamma, alpha, e_n
    (group /patches/partial_high/knots): kink surfaces K_j(gamma, e_n) sent to fixed c*_j
    (docs/table-format.md, "The knots"; step 5 with the operations, in the order, it states)."""

    def __init__(self, gamma_0, gamma_step, e_n_0, e_n_step, region, c_star, grade, knot):
        self.gamma_0 = gamma_0
        self.gamma_step = gamma_step
        self.e_n_0 = e_n_0
        self.e_n_step = e_n_step
        self.region = region  # [gamma from, gamma to, e_n from, e_n to], root-cell units
        self.c_star = c_star  # [k] floats
        self.grade = grade  # [k] ints: 0 none, 1 the segment below graded, 2 the one above
        self.n_gamma, self.n_e_n = knot.shape[1], knot.shape[2]
        # knot[j][i] is the row of K_j at gamma_0 + i gamma_step along e_n, as Python floats.
        self.knot = [[[float(v) for v in row] for row in plane] for plane in knot]

    def applies(self, vg, ve, blocks_gamma, blocks_e_n):
        """Whether the knots apply at the clamped root-cell positions vg (gamma) and ve (e_n):
        from <= v < to on both axes, v = to included where to is the last root edge."""
        r = self.region

        def inside(v, lo, hi, blocks):
            return v >= lo and (v < hi or hi >= blocks)
        return inside(vg, r[0], r[1], blocks_gamma) and inside(ve, r[2], r[3], blocks_e_n)

    def line(self, gamma, e_n):
        """The knot values K_j at (gamma, e_n): the cubic stencils of step 8 on the grid at
        u = (gamma - gamma_0)/gamma_step and w = (e_n - e_n_0)/e_n_step, each clamped to the
        grid; r_a = we_0 knot[j, s_g+a, s_e] + ... + we_3 knot[j, s_g+a, s_e+3], then
        K_j = wg_0 r_0 + ... + wg_3 r_3, both from left to right (from 0)."""
        u = min(max((gamma - self.gamma_0) / self.gamma_step, 0.0), float(self.n_gamma - 1))
        w = min(max((e_n - self.e_n_0) / self.e_n_step, 0.0), float(self.n_e_n - 1))
        sg, wg = cubic_stencil(u, self.n_gamma)
        se, we = cubic_stencil(w, self.n_e_n)
        out = []
        for plane in self.knot:
            total = 0.0
            for a in range(4):
                v = plane[sg + a]
                inner = we[0] * v[se] + we[1] * v[se + 1] + we[2] * v[se + 2] + we[3] * v[se + 3]
                total += wg[a] * inner
            out.append(total)
        return out

    def apply(self, ks, c):
        """c -> c' on the line whose knot values are ks (step 5 with knots)."""
        n = len(ks)
        s = sum(1 for k in ks if k < c)
        k0, c0 = (0.0, 0.0) if s == 0 else (ks[s - 1], self.c_star[s - 1])
        k1, c1 = (1.0, 1.0) if s == n else (ks[s], self.c_star[s])
        w = k1 - k0
        if not w > 0.0:  # also a NaN width: the segment is empty
            return c0
        if s < n and self.grade[s] == 1:
            t = (c - k0) / w
            return c0 + (c1 - c0) * (1.0 - math.sqrt(max(1.0 - t, 0.0)))
        if s > 0 and self.grade[s - 1] == 2:
            t = (c - k0) / w
            return c0 + (c1 - c0) * math.sqrt(max(t, 0.0))
        return c0 + (c1 - c0) * (c - k0) / w


class Patch:
    """One patch held in memory: root cells, quadtree (octree with an e_n axis) and node
    values."""

    def __init__(self, name, kind, gamma_lo, gamma_hi, blocks_gamma, blocks_coord,
                 leaf_intervals, tree, p, warp=None, blocks_e_n=None, e_n_range=None,
                 split=None, pair=False, knots=None, e_axis=None):
        self.name = name
        self.kind = kind
        self.gamma_lo = gamma_lo
        self.gamma_hi = gamma_hi
        self.blocks_gamma = blocks_gamma
        self.blocks_coord = blocks_coord
        self.leaf_intervals = leaf_intervals
        self.tree = tree  # int list [cells]
        self.p = p  # float64 [leaves, m+1, m+1] ([leaves, m+1, m+1, m+1] with an e_n axis)
        self.warp = warp  # Warp or None
        self.blocks_e_n = blocks_e_n  # root cells along e_n, or None (no e_n axis)
        self.e_n_range = e_n_range  # (e_n_min, e_n_max) or None
        # The e_n axis and its map (EAxis; linear over e_n_range when not given), or None.
        if e_axis is None and e_n_range is not None:
            e_axis = EAxis(e_n_range[0], e_n_range[1], False)
        self.e_axis = e_axis
        # Per cell, the axes a split cell halves (bit 4: gamma, 2: c, 1: e_n), or None: all.
        self.split = split
        # The patch of one pair: gamma_lo = gamma_hi, its tree over (c, e_n) only.
        self.pair = pair
        # Knots or None (only partial_high and stick_high of a table over gamma, alpha, e_n)
        self.knots = knots
        # Node values as Python floats, flat (leaf, i_gamma, i_c, i_e), for the e_n rule.
        self.flat = [float(v) for v in p.reshape(-1)] if blocks_e_n is not None else None

    def find_leaf(self, x, c):
        """Steps 6 and 7: leaf number and position (fx, fc) inside it, for x, c in [0, 1].
        The children of a split cell i are tree[i] + 2 q_gamma + q_c, or, with the dataset
        'split', the 2^k cells from tree[i] numbered over the k axes the cell halves."""
        bg, bc = self.blocks_gamma, self.blocks_coord
        a = min(int(math.floor(x * bg)), bg - 1)
        fx = x * bg - a
        b = min(int(math.floor(c * bc)), bc - 1)
        fc = c * bc - b
        # The descent halves the axes of each split cell's mask (bit 2: gamma, 1: c; both
        # without the dataset 'split').
        leaf, (fx, fc) = self.descend(a * bc + b, [fx, fc])
        return leaf, fx, fc

    def interpolate(self, gamma, c, k):
        """Steps 4 (x, with c given) to 10."""
        x = _clamp01((gamma - self.gamma_lo) / (self.gamma_hi - self.gamma_lo))
        c = _clamp01(c)
        if self.warp is not None and x * self.blocks_gamma >= self.warp.start:
            c = self.warp.apply(gamma, c)
        leaf, fx, fc = self.find_leaf(x, c)
        m = self.leaf_intervals
        sg, wg = lagrange(fx * m, m, k)
        sc, wc = lagrange(fc * m, m, k)
        vals = self.p[leaf]
        total = 0.0
        for i in range(k):
            inner = 0.0
            for j in range(k):
                inner += float(vals[sg + i, sc + j]) * wc[j]
            total += wg[i] * inner
        # 10. The bound: |P| <= 1.
        return min(max(total, -1.0), 1.0)

    def knotted(self, gamma, c, xe, e_n):
        """Step 5 with knots: c' of the clamped c where the knots apply (v_gamma =
        x blocks_gamma and v_e = x_e blocks_e_n clamped as in step 6, inside the region), else
        c."""
        k = self.knots
        if k is None:
            return c
        bg, be = float(self.blocks_gamma), float(self.blocks_e_n)
        x = (gamma - self.gamma_lo) / (self.gamma_hi - self.gamma_lo)
        vg = min(max(x * bg, 0.0), bg)
        ve = min(max(xe * be, 0.0), be)
        if not k.applies(vg, ve, bg, be):
            return c
        return k.apply(k.line(gamma, e_n), c)

    def find_leaf3(self, gamma, c, xe):
        """Steps 6 and 7 in the octree of a patch with an e_n axis: leaf number and position
        (fg, fc, fe) inside it. Roots row-major (gamma outer, e_n inner); the children of a
        split cell i are tree[i] + 4 q_gamma + 2 q_c + q_e, or, with the dataset 'split', the
        2^k cells from tree[i] numbered over the k axes the cell halves (gamma, c, e_n order)."""
        bg, bc, be = self.blocks_gamma, self.blocks_coord, self.blocks_e_n
        a, fg = locate((gamma - self.gamma_lo) / (self.gamma_hi - self.gamma_lo), bg)
        b, fc = locate(c, bc)
        e, fe = locate(xe, be)
        leaf, (fg, fc, fe) = self.descend((a * bc + b) * be + e, [fg, fc, fe])
        return leaf, fg, fc, fe

    def descend(self, i, f):
        """Step 7 from root cell i in a tree whose cells halve the axes of their mask (bit
        n - 1 - k for axis k of the n positions f; every axis without the dataset 'split'):
        each halved position doubled, q_k = 1 where it reaches 1 (then 1 subtracted), the child
        tree[i] + q with q the q_k of the halved axes as binary digits in axis order. Returns
        the leaf number and the positions inside it."""
        tree, split, n = self.tree, self.split, len(f)
        while tree[i] >= 0:
            mask = (1 << n) - 1 if split is None else split[i]
            q = 0
            for k in range(n):
                if mask >> (n - 1 - k) & 1:
                    f[k] = 2.0 * f[k]
                    b = int(f[k] >= 1.0)
                    f[k], q = f[k] - b, 2 * q + b
            i = tree[i] + q
        return -tree[i] - 1, f

    def find_leaf_pair(self, c, xe):
        """Steps 6 and 7 in the quadtree of the patch of one pair, over (c, x_e): leaf number
        and position (fc, fe) inside it. Roots row-major (c outer); the children of a split
        cell i are tree[i] + 2 q_c + q_e, or, with the dataset 'split', the 2^k cells from
        tree[i] numbered over the k axes the cell halves (mask bit 2: c, bit 1: e_n)."""
        b, fc = locate(c, self.blocks_coord)
        e, fe = locate(xe, self.blocks_e_n)
        leaf, (fc, fe) = self.descend(b * self.blocks_e_n + e, [fc, fe])
        return leaf, fc, fe

    def interpolate_pair(self, c, e_n):
        """Steps 6 to 10 of the patch of one pair (the cubic stencil over (c, x_e)), c clamped:
        the rows along e_n first, r_j = P[s_c + j, s_e] w_e0 + ... + P[s_c + j, s_e + 3] w_e3,
        then w_c0 r_0 + ... + w_c3 r_3, each sum from left to right."""
        leaf, fc, fe = self.find_leaf_pair(c, self.e_axis.x(e_n))
        m = self.leaf_intervals
        n1 = m + 1
        sc, wc = cubic_stencil(fc * m, n1)
        se, we = cubic_stencil(fe * m, n1)
        v = self.flat
        base = leaf * n1 * n1
        rows = []
        for j in range(4):
            at = base + (sc + j) * n1 + se
            rows.append(v[at] * we[0] + v[at + 1] * we[1] + v[at + 2] * we[2] + v[at + 3] * we[3])
        total = wc[0] * rows[0] + wc[1] * rows[1] + wc[2] * rows[2] + wc[3] * rows[3]
        return min(max(total, -1.0), 1.0)

    def interpolate_e(self, gamma, c, e_n):
        """Steps 6 to 10 of a patch with an e_n axis (the cubic stencil), c clamped, at
        x_e = (e_n - e_n_min)/(e_n_max - e_n_min) (through the axis's map, EAxis.x): the tensor
        product summed e_n innermost, gamma outermost, each sum from left to right. The patch of
        one pair: over (c, x_e)."""
        if self.pair:
            return self.interpolate_pair(c, e_n)
        xe = self.e_axis.x(e_n)
        c = self.knotted(gamma, c, xe, e_n)
        leaf, fg, fc, fe = self.find_leaf3(gamma, c, xe)
        m = self.leaf_intervals
        n1 = m + 1
        sg, wg = cubic_stencil(fg * m, n1)
        sc, wc = cubic_stencil(fc * m, n1)
        se, we = cubic_stencil(fe * m, n1)
        v = self.flat
        base = leaf * n1 * n1 * n1
        planes = []
        for i in range(4):
            rows = []
            for j in range(4):
                at = base + ((sg + i) * n1 + sc + j) * n1 + se
                rows.append(v[at] * we[0] + v[at + 1] * we[1] + v[at + 2] * we[2]
                            + v[at + 3] * we[3])
            planes.append(wc[0] * rows[0] + wc[1] * rows[1] + wc[2] * rows[2] + wc[3] * rows[3])
        total = wg[0] * planes[0] + wg[1] * planes[1] + wg[2] * planes[2] + wg[3] * planes[3]
        return min(max(total, -1.0), 1.0)


def check_tree(tree, roots, fanout=4, split=None):
    """Problem with a quadtree (fanout 4) or octree (8) array (docs/table-format.md, 'The
    tree'), or None; and the leaf count. With `split` (one mask per cell), a split cell i has
    2^popcount(split[i]) children."""
    n = len(tree)
    if n < roots:
        return f"has {n} cells: expected at least {roots} roots", 0
    fan = [fanout if split is None else 1 << bin(split[i]).count("1") for i in range(n)]
    children = sum(fan[i] for i in range(n) if tree[i] >= 0)
    if n - roots != children:
        return (f"has {n} cells: expected {roots} roots plus {children} children of its split "
                "cells"), 0
    referenced = [False] * n
    leaves = []
    for i, t in enumerate(tree):
        if t < 0:
            leaves.append(-t - 1)
            continue
        if t <= i or t < roots or t + fan[i] > n:
            return f"cell {i} points to children at {t}: out of range", 0
        for q in range(t, t + fan[i]):
            if referenced[q]:
                return f"cell {i}: children at {t} shared with another cell", 0
            referenced[q] = True
    for i in range(roots, n):
        if not referenced[i]:
            return f"cell {i} is not reachable from a root", 0
    if sorted(leaves) != list(range(len(leaves))):
        return "does not number its leaves 0, 1, 2, ... exactly once", 0
    return None, len(leaves)


def check_seal(path):
    """Refuse a sealed table whose bytes changed after it was written (docs/table-format.md,
    "Integrity"): OBLQSEAL, file length, FNV-1a 64 of the bytes after the 512-byte user block."""
    with open(path, "rb") as fh:
        data = fh.read()
    if len(data) < 512 or data[:8] != b"OBLQSEAL":
        return  # not sealed (written by other software): left to HDF5
    length, digest = struct.unpack("<QQ", data[8:24])
    h = 0xCBF29CE484222325
    if length == len(data):
        for b in data[512:]:
            h = ((h ^ b) * 0x100000001B3) & 0xFFFFFFFFFFFFFFFF
    if length != len(data) or h != digest:
        raise TableError(
            f"{path}: damaged: its checksum does not match its contents (truncated, corrupted "
            "or modified after it was written)")


class Table:
    """A P(gamma, alpha) table of schema v2, v3 or v4 (P(gamma, alpha, e_n) with a normal-
    restitution axis), loaded into memory (no HDF5 call per query)."""

    def __init__(self, path):
        self.path = str(path)
        if not os.path.isfile(self.path):
            raise TableError(f"{self.path}: no such file")
        check_seal(self.path)
        try:
            f = h5py.File(self.path, "r")
        except OSError as e:
            raise TableError(
                f"{self.path}: not an HDF5 file, or truncated/corrupted ({e})") from None
        with f:
            self._load(f)

    def _invalid(self, msg):
        return TableError(f"{self.path}: {msg}")

    def _load(self, f):
        try:
            fmt = _str_attr(f.attrs, "format")
        except (KeyError, TypeError):
            raise self._invalid(
                f"not a P table (root attribute 'format' = '{FORMAT_NAME}' missing)") from None
        if fmt != FORMAT_NAME:
            raise self._invalid(f"not a P table (format '{fmt}', expected '{FORMAT_NAME}')")
        try:
            version = _float_attr(f.attrs, "schema_version")
        except (KeyError, TypeError):
            raise self._invalid("missing or non-numeric attribute 'schema_version'") from None
        if version not in SCHEMA_VERSIONS:
            raise self._invalid(
                f"schema version {version:g}, this reader understands "
                f"{SCHEMA_VERSIONS[0]} to {SCHEMA_VERSIONS[-1]}")
        self.schema_version = int(version)

        def num(attrs, name, where="root"):
            try:
                return _float_attr(attrs, name)
            except (KeyError, TypeError):
                raise self._invalid(
                    f"missing or non-numeric {where} attribute '{name}'") from None

        k = num(f.attrs, "stencil_points")
        if k != int(k) or not 2 <= k <= 8 or int(k) % 2:
            raise self._invalid(f"stencil_points = {k:g}: must be an even integer in [2, 8]")
        self.stencil = int(k)
        self.gamma_min = num(f.attrs, "gamma_min")
        self.gamma_max = num(f.attrs, "gamma_max")
        self.alpha_max = num(f.attrs, "alpha_max")
        if not (0 < self.gamma_min <= self.gamma_max < math.inf):
            raise self._invalid(
                f"gamma domain [{self.gamma_min}, {self.gamma_max}] must satisfy "
                "0 < gamma_min < gamma_max < inf (gamma_min = gamma_max in the table of one "
                "pair)")
        if math.isnan(self.alpha_max) or self.alpha_max <= 0:
            raise self._invalid(f"alpha_max = {self.alpha_max} must be > 0 or inf")
        # Schema 4 names its axes; an e_n axis brings its range (None: an elastic table). The
        # table of one pair ('alpha,e_n') holds the single gamma gamma_min = gamma_max.
        self.e_n_range = None
        # The contact law of a table with an e_n axis (None: an elastic table), and whether the
        # table has no closed-form full-slip line (Thornton's law: no step 1 of the rule).
        self.law = None
        self.no_line = False
        axes = "gamma,alpha"
        if self.schema_version >= 4:
            try:
                axes = _str_attr(f.attrs, "axes")
            except (KeyError, TypeError):
                raise self._invalid("missing or non-string root attribute 'axes'") from None
            if axes in ("gamma,alpha,e_n", AXES_PAIR):
                # The extra axis's range: root attributes NAME_min, NAME_max.
                name = axes.split(",")[-1]
                b0, b1 = EXTRA_AXES[name]
                lo, hi = num(f.attrs, f"{name}_min"), num(f.attrs, f"{name}_max")
                if not b0 < lo < hi <= b1:
                    raise self._invalid(
                        f"{name} range [{lo}, {hi}]: must satisfy {b0:g} < {name}_min < "
                        f"{name}_max <= {b1:g}")
                self.e_n_range = (lo, hi)
                try:
                    law = _str_attr(f.attrs, "law")
                except (KeyError, TypeError):
                    raise self._invalid("missing or non-string root attribute 'law'") from None
                if law not in LAWS_E_N:
                    raise self._invalid(
                        f"root attribute 'law' = '{law}': this reader knows the law "
                        + ", ".join(f"'{x}'" for x in LAWS_E_N)
                        + "; a table of another law cannot answer this reader's questions")
                self.law = law
                self.no_line = law in LAWS_NO_LINE
                if self.no_line and (axes != "gamma,alpha,e_n" or not self.gamma_min >= 1.0):
                    raise self._invalid(
                        f"root attribute 'law' = '{law}' with 'axes' = '{axes}' and "
                        f"'gamma_min' = {self.gamma_min!r}: a table of this law has the axes "
                        "'gamma,alpha,e_n' and gamma_min >= 1")
            elif axes != "gamma,alpha":
                raise self._invalid(
                    f"root attribute 'axes' = '{axes}': this reader understands 'gamma,alpha', "
                    f"'gamma,alpha,e_n' and '{AXES_PAIR}'")
        # Schema 5 names the map of the e_n axis (root attribute 'e_n_coordinate', required
        # there); before it the axis is linear.
        self.e_n_coordinate = E_N_LINEAR
        if self.schema_version >= 5:
            try:
                coord = _str_attr(f.attrs, "e_n_coordinate")
            except (KeyError, TypeError):
                raise self._invalid(
                    "missing or non-string root attribute 'e_n_coordinate' (schema 5)") from None
            if coord not in E_N_COORDINATES:
                raise self._invalid(
                    f"root attribute 'e_n_coordinate' = '{coord}': this reader understands "
                    + " and ".join(f"'{c}'" for c in E_N_COORDINATES))
            if self.e_n_range is None:
                raise self._invalid(
                    f"root attribute 'e_n_coordinate' = '{coord}' in a table without an e_n "
                    "axis")
            self.e_n_coordinate = coord
        self.e_axis = None
        if self.e_n_range is not None:
            self.e_axis = EAxis(*self.e_n_range, self.e_n_coordinate == E_N_QUARTER_ROOT)
            if not self.e_axis.m_width > 0.0:
                raise self._invalid(
                    f"e_n range [{self.e_n_range[0]}, {self.e_n_range[1]}] over "
                    f"'{self.e_n_coordinate}': its ends map to the same coordinate")
        pair = axes == AXES_PAIR
        if pair != (self.gamma_min == self.gamma_max):
            raise self._invalid(
                f"root attributes 'gamma_min' = {self.gamma_min!r}, 'gamma_max' = "
                f"{self.gamma_max!r} with 'axes' = '{axes}': the table of one pair "
                f"('{AXES_PAIR}') has gamma_min = gamma_max, any other table "
                "gamma_min < gamma_max")
        # The single gamma of the table of one pair, None for a table over a range of gamma.
        self.pair_gamma = self.gamma_min if pair else None
        # The axes of a query's point (p_at), from the file's 'axes': gamma, alpha, then the
        # extra axes (the table of one pair takes its gamma too).
        self.axes = ("gamma", "alpha") + tuple(
            a for a in axes.split(",") if a not in ("gamma", "alpha"))
        if "patches" not in f or not isinstance(f["patches"], h5py.Group):
            raise self._invalid("missing group '/patches'")
        self.patches = {}
        self.bounds = {}
        for name in PATCH_NAMES:
            if name in f["patches"]:
                self.patches[name] = self._patch(f["patches"][name], name, num)
        if self.gamma_min < 1.0 and "stick_low" not in self.patches:
            raise self._invalid("missing patch 'stick_low' (gamma_min < 1)")
        if self.gamma_max > 1.0 and not {"partial_high", "stick_high"} <= set(self.patches):
            raise self._invalid("missing patch 'partial_high' or 'stick_high' (gamma_max > 1)")
        # The stated error bound: the largest over the patches (NaN: the file states none).
        self.error_bound = max(self.bounds.values(), default=0.0)
        if any(math.isnan(b) for b in self.bounds.values()):
            self.error_bound = math.nan
        self.checks = None
        if "checks" in f:
            g = f["checks"]
            self.checks = {n: g[n][()] for n in
                           ("gamma", "alpha", "e_n", "P_simulated", "P_interpolated",
                            "interpolation_error", "patch") if n in g}

    def _patch(self, g, name, num):
        where = f"patch '{name}'"
        try:
            kind = _str_attr(g.attrs, "kind")
        except (KeyError, TypeError):
            raise self._invalid(f"{where}: missing or non-string attribute 'kind'") from None
        if kind != PATCH_KINDS[name]:
            raise self._invalid(f"{where}: kind '{kind}', expected '{PATCH_KINDS[name]}'")
        lo = num(g.attrs, "gamma_lo", where)
        hi = num(g.attrs, "gamma_hi", where)
        pair = self.pair_gamma is not None
        if pair:
            if not lo == hi == self.pair_gamma:
                raise self._invalid(
                    f"{where}: attributes 'gamma_lo' = {lo!r}, 'gamma_hi' = {hi!r}: the patch of "
                    f"one pair has both equal to the table's gamma_min = gamma_max = "
                    f"{self.pair_gamma!r}")
        elif not (0 < lo < hi < math.inf):
            raise self._invalid(f"{where}: gamma edges [{lo}, {hi}] must be finite, > 0, increasing")
        counts = []
        for a in ("blocks_gamma", "blocks_coord", "leaf_intervals"):
            v = num(g.attrs, a, where)
            if v != int(v) or v < 1:
                raise self._invalid(f"{where}: attribute '{a}' = {v}: must be an integer >= 1")
            counts.append(int(v))
        bg, bc, m = counts
        if pair and bg != 1:
            raise self._invalid(
                f"{where}: attribute 'blocks_gamma' = {bg}: must be 1 in the patch of one pair")
        if m + 1 < self.stencil:
            raise self._invalid(
                f"{where}: leaf_intervals = {m} gives fewer nodes than stencil_points")
        be = None
        if "knots" in g and (name not in ("partial_high", "stick_high")
                             or self.e_n_range is None or pair):
            raise self._invalid(
                f"patch '{name}' has a group 'knots': only 'partial_high' and 'stick_high' of "
                "a table over gamma, alpha and e_n may have one")
        if self.e_n_range is not None:
            # Root cells along the extra axis: patch attribute blocks_NAME.
            key = f"blocks_{self.axes[2]}"
            be = num(g.attrs, key, where)
            if be != int(be) or not 1 <= be <= 65536:
                raise self._invalid(
                    f"{where}: attribute '{key}' = {be}: must be an integer in [1, 65536]")
            be = int(be)
            if self.stencil != 4:
                raise self._invalid(
                    f"{where}: stencil_points = {self.stencil}: this reader evaluates tables "
                    "with an e_n axis with the cubic stencil (4) only")
            if "warp" in g:
                raise self._invalid(f"{where}: a patch with an e_n axis cannot have a warp")

            if kind == "partial-slip":
                coord = g.attrs.get("coordinate")
                coord = coord.decode() if isinstance(coord, bytes) else coord
                want = LAWS_E_N[self.law]
                if coord != want:
                    raise self._invalid(
                        f"{where}: attribute 'coordinate' = {coord!r} in a table of the "
                        f"'{self.law}' law, whose coordinate is '{want}' (this reader "
                        "understands " + ", ".join(
                            f"'{c}' ({law})" for law, c in LAWS_E_N.items()) + ")")
                if self.no_line and bc % 2:
                    raise self._invalid(
                        f"{where}: attribute 'blocks_coord' = {bc}: must be even in a table "
                        "without a full-slip line (alpha_c1 is the root-cell edge c = 1/2)")
        # The tree's axes: (gamma, c), (gamma, c, e_n), or (c, e_n) in the patch of one pair.
        dims = 2 if be is None or pair else 3
        if "tree" not in g:
            raise self._invalid(f"{where}: missing dataset 'tree'")
        d = g["tree"]
        if d.ndim != 1 or d.dtype.kind != "i":
            raise self._invalid(
                f"{where}: dataset 'tree' is {d.dtype}{list(d.shape)}, expected 1-D integer")
        tree = [int(t) for t in d[()]]
        split = None
        if "split" in g:
            d = g["split"]
            if d.ndim != 1 or d.dtype.kind not in "iu" or len(d) != len(tree):
                raise self._invalid(
                    f"{where}: dataset 'split' is {d.dtype}{list(d.shape)}, expected 1-D integer "
                    f"[{len(tree)}] (one mask per cell)")
            split = [int(s) for s in d[()]]
            top = (1 << dims) - 1
            for i, (t, s) in enumerate(zip(tree, split)):
                if (t >= 0) != (s != 0) or not 0 <= s <= top:
                    raise self._invalid(
                        f"{where}: dataset 'split'[{i}] = {s}: must be 1 to {top} for a split "
                        "cell, 0 for a leaf"
                        + (" (the patch of one pair halves c and e_n only: no gamma bit 4)"
                           if pair else "")
                        + (" (a table without an e_n axis: bit 2 gamma, bit 1 c)"
                           if dims == 2 and not pair else ""))
        problem, leaves = check_tree(tree, bg * bc * (be or 1), 1 << dims, split)
        if problem:
            raise self._invalid(f"{where}: dataset 'tree' {problem}")
        if "P" not in g:
            raise self._invalid(f"{where}: missing dataset 'P'")
        d = g["P"]
        shape = (leaves,) + (m + 1,) * dims
        if d.shape != shape or d.dtype.kind != "f":
            raise self._invalid(
                f"{where}: dataset 'P' is {d.dtype}{list(d.shape)}, expected float {list(shape)}")
        p = d[()].astype(np.float64)
        if not np.all(np.isfinite(p)):
            raise self._invalid(f"{where}: non-finite value in 'P'")
        warp = self._warp(g, name, lo, hi, bg, bc, tree, split, num) if "warp" in g else None
        knots = self._knots(g, name, lo, hi, bg, bc, be, tree, split, num) \
            if "knots" in g else None
        self._check_nodes(g, where, lo, hi, bg, bc, be, m, tree, split, dims, pair, leaves,
                          shape)
        # The stated error bound of the patch (docs/table-format.md, "The stated error bound"):
        # max over leaves of leaf_predicted_error + Lambda_k^dims * max node error_estimate.
        bound = math.nan
        if "leaf_predicted_error" in g and "error_estimate" in g:
            pred = g["leaf_predicted_error"][()].astype(np.float64)
            est = g["error_estimate"][()].astype(np.float64)
            if pred.shape == (leaves,) and est.shape == shape:
                factor = lebesgue(self.stencil) ** dims
                per_leaf = pred + factor * est.reshape(leaves, -1).max(axis=1, initial=0.0)
                bound = float(per_leaf.max(initial=0.0))
        self.bounds[name] = bound
        return Patch(name, kind, lo, hi, bg, bc, m, tree, p, warp, be, self.e_n_range, split,
                     pair, knots, self.e_axis)

    def _check_nodes(self, g, where, lo, hi, bg, bc, be, m, tree, split, dims, pair, leaves,
                     shape):
        """The stored node coordinates (gamma, coord, e_n, alpha) where the tree and the axis
        attributes put the nodes: within POSITION_TOL of each axis's span (alpha: a number
        >= 0, inf allowed). A file whose attributes were edited after its build is refused."""
        names = ["gamma", "coord", "alpha"] + (["e_n"] if be is not None else [])
        stored = {}
        for n in names:
            if n not in g:
                raise self._invalid(f"{where}: missing dataset '{n}'")
            d = g[n]
            if d.shape != shape or d.dtype.kind != "f":
                raise self._invalid(
                    f"{where}: dataset '{n}' is {d.dtype}{list(d.shape)}, expected float "
                    f"{list(shape)}")
            stored[n] = d[()].astype(np.float64).reshape(leaves, -1)
        if not np.all(stored["alpha"] >= 0):
            raise self._invalid(f"{where}: node alphas must be >= 0 (inf allowed)")
        # The tree's axes: (values, lo, span, root cells) in tree order; the e_n axis in its
        # mapped values (EAxis: m_lo, m_width), its stored values compared through the map.
        e_axis = [("e_n", self.e_axis.m_lo, self.e_axis.m_width, be)] if be is not None else []
        if pair:
            axes = [("coord", 0.0, 1.0, bc)] + e_axis
        else:
            axes = [("gamma", lo, hi - lo, bg), ("coord", 0.0, 1.0, bc)] + e_axis
        blocks = [a[3] for a in axes]
        pos = np.zeros((leaves, dims))
        depth = np.zeros((leaves, dims))
        stack = []
        for r in range(int(np.prod(blocks))):
            p, rest = [0.0] * dims, r
            for k in reversed(range(dims)):
                p[k], rest = float(rest % blocks[k]), rest // blocks[k]
            stack.append((r, p, [0] * dims))
        while stack:
            cell, p, d = stack.pop()
            t = tree[cell]
            if t < 0:
                pos[-t - 1], depth[-t - 1] = p, d
                continue
            mask = (1 << dims) - 1 if split is None else split[cell]
            halved = [k for k in range(dims) if mask >> (dims - 1 - k) & 1]
            for q in range(1 << len(halved)):
                pq, dq = list(p), list(d)
                for j, k in enumerate(halved):
                    pq[k] = 2.0 * pq[k] + ((q >> (len(halved) - 1 - j)) & 1)
                    dq[k] += 1
                stack.append((t + q, pq, dq))
        idx = np.indices((m + 1,) * dims).reshape(dims, -1)
        for k, (n, a_lo, span, b) in enumerate(axes):
            scale = b * np.exp2(depth[:, k])[:, None]
            want = a_lo + span * (pos[:, k][:, None] + idx[k][None, :] / m) / scale
            got = stored[n]
            if n == "e_n" and self.e_axis.quarter:
                # m(e) = -sqrt(sqrt(1 - e)); a stored e_n above 1 gives NaN: refused.
                with np.errstate(invalid="ignore"):
                    got = -np.sqrt(np.sqrt(1.0 - got))
                want_value = 1.0 - (want * want) ** 2
            else:
                want_value = want
            bad = ~(np.abs(got - want) <= POSITION_TOL * abs(span))
            if bad.any():
                leaf, node = np.argwhere(bad)[0]
                raise self._invalid(
                    f"{where}: {n}[{leaf * idx.shape[1] + node}] = "
                    f"{stored[n][leaf, node]!r} where the tree and the axis attributes put the "
                    f"node at {want_value[leaf, node]!r} (leaf {leaf}): the attributes do not "
                    "describe the stored nodes")
        if pair and not np.all(stored["gamma"] == lo):
            raise self._invalid(f"{where}: node gammas differ from the pair's gamma {lo!r}")

    def _warp(self, g, name, gamma_lo, gamma_hi, bg, bc, tree, split, num):
        """The optional warp group of a patch, validated as docs/table-format.md states."""
        where = f"'{name}/warp'"
        if name != "partial_high":
            raise self._invalid(
                f"patch '{name}' has a group 'warp': only 'partial_high' may have one")
        if self.schema_version < 3:
            raise self._invalid(
                f"group {where} in a schema-{self.schema_version} file: a warp needs schema "
                "version 3")
        w = g["warp"]
        if not isinstance(w, h5py.Group):
            raise self._invalid(f"{where} is not a group")

        def attr(a, allowed, ok):
            v = num(w.attrs, a, where)
            if not (math.isfinite(v) and ok(v)):
                raise self._invalid(f"{where}: attribute '{a}' = {v}: must be {allowed}")
            return v

        start = attr("start", f"in (0, {bg}) (root rows of the patch) and a multiple of 2^-20",
                     lambda v: 0 < v < bg and (v * 1048576.0).is_integer())
        gamma_0 = attr("gamma_0", "finite", lambda v: True)
        gamma_step = attr("gamma_step", "finite and > 0", lambda v: v > 0)
        c_star = attr("c_star", "in (0, 1)", lambda v: 0 < v < 1)
        if "knot" not in w or not isinstance(w["knot"], h5py.Dataset) \
                or w["knot"].ndim != 1 or w["knot"].dtype.kind != "f":
            raise self._invalid(f"{where}: dataset 'knot' missing or not a 1-D float64 array")
        knot = w["knot"][()].astype(np.float64)
        if len(knot) < 4:
            raise self._invalid(
                f"{where}: dataset 'knot' has {len(knot)} values: must have at least 4")
        for i, k in enumerate(knot):
            if not 0 < k < 1:
                raise self._invalid(f"{where}: dataset 'knot'[{i}] = {k}: must be in (0, 1)")
        first = gamma_lo + (gamma_hi - gamma_lo) * start / bg
        end = gamma_0 + (len(knot) - 1) * gamma_step
        slack = 1e-12 * abs(gamma_hi)
        if not (gamma_0 <= first + slack and end >= gamma_hi - slack):
            raise self._invalid(
                f"{where}: the knot grid 'gamma_0' + i*'gamma_step' spans [{gamma_0}, {end}] "
                f"({len(knot)} values of 'knot'): must cover the warped gamma range "
                f"[{first}, {gamma_hi}]")
        # No leaf may straddle `start`: every leaf's rows [a/2^d, (a+1)/2^d] lie on one side
        # (d: the splits above it that halve gamma, mask bit 2; all without 'split').
        stack = [(i, 0, i // bc) for i in range(bg * bc)]
        while stack:
            cell, d, a = stack.pop()
            t = tree[cell]
            if t < 0:
                lo_row, hi_row = a / 2.0 ** d, (a + 1) / 2.0 ** d
                if lo_row < start < hi_row:
                    raise self._invalid(
                        f"{where}: leaf {-t - 1} spans root rows [{lo_row}, {hi_row}] across "
                        f"attribute 'start' = {start}: no leaf may straddle it")
                continue
            mask = 3 if split is None else split[cell]
            if mask & 2:
                # q_gamma is the first bit of q: q // 2 of four children, q of two.
                fan = 1 << bin(mask).count("1")
                stack.extend((t + q, d + 1, 2 * a + q // (fan // 2)) for q in range(fan))
            else:
                stack.extend((t + q, d, a) for q in range(2))
        return Warp(start, gamma_0, gamma_step, c_star, knot)

    def _knots(self, g, name, gamma_lo, gamma_hi, bg, bc, be, tree, split, num):
        """The optional knots group of partial_high or stick_high (a table over gamma, alpha,
        e_n), validated as docs/table-format.md ("The knots") states; each refusal names the
        field."""
        where = f"'{name}/knots'"
        k = g["knots"]
        if not isinstance(k, h5py.Group):
            raise self._invalid(f"{where} is not a group")

        def attr(a, allowed, ok):
            v = num(k.attrs, a, where)
            if not (math.isfinite(v) and ok(v)):
                raise self._invalid(f"{where}: attribute '{a}' = {v}: must be {allowed}")
            return v

        gamma_0 = attr("gamma_0", "finite", lambda v: True)
        gamma_step = attr("gamma_step", "finite and > 0", lambda v: v > 0)
        e_n_0 = attr("e_n_0", "finite", lambda v: True)
        e_n_step = attr("e_n_step", "finite and > 0", lambda v: v > 0)

        def dataset(n, ndim, kinds, what):
            d = k.get(n)
            if not isinstance(d, h5py.Dataset) or d.ndim != ndim or d.dtype.kind not in kinds:
                raise self._invalid(f"{where}: dataset '{n}' missing or not a {what} array")
            return d[()]

        region = [float(v) for v in dataset("region", 1, "f", "1-D float64")]
        if len(region) != 4:
            raise self._invalid(
                f"{where}: dataset 'region' has {len(region)} values: expected 4 ([gamma from, "
                "gamma to, e_n from, e_n to])")
        c_star = [float(v) for v in dataset("c_star", 1, "f", "1-D float64")]
        grade = [int(v) for v in dataset("grade", 1, "u", "1-D uint8")]
        knot = np.asarray(dataset("knot", 3, "f", "3-D float64"), dtype=np.float64)
        nk, ng, ne = knot.shape
        if not 1 <= nk <= MAX_KNOTS:
            raise self._invalid(
                f"{where}: dataset 'knot' holds {nk} knots: must hold 1 to {MAX_KNOTS}")
        if ng < 4 or ne < 4:
            raise self._invalid(
                f"{where}: dataset 'knot' has {ng} x {ne} grid points: must have at least 4 "
                "along each of gamma and e_n")
        if len(c_star) != nk or len(grade) != nk:
            raise self._invalid(
                f"{where}: datasets 'c_star' and 'grade' have {len(c_star)} and {len(grade)} "
                f"values: expected {nk}, one per knot")
        for j, cs in enumerate(c_star):
            below = c_star[j - 1] if j else 0.0
            if not below < cs < 1.0:
                raise self._invalid(
                    f"{where}: dataset 'c_star'[{j}] = {cs}: must be in ({below}, 1) (strictly "
                    "increasing in (0, 1))")
        for j, v in enumerate(grade):
            if v not in (0, 1, 2):
                raise self._invalid(
                    f"{where}: dataset 'grade'[{j}] = {v}: must be 0 (none), 1 (below) or 2 "
                    "(above)")
            if j and grade[j - 1] == 2 and v == 1:
                raise self._invalid(
                    f"{where}: dataset 'grade': knot {j - 1} is graded 2 (above) and knot {j} "
                    "1 (below): a segment may be graded at one end only")
        for i in range(ng):
            for l in range(ne):
                below = 0.0
                for j in range(nk):
                    v = float(knot[j, i, l])
                    if not below < v < 1.0:
                        raise self._invalid(
                            f"{where}: dataset 'knot'[{j}, {i}, {l}] = {v}: must be in "
                            f"({below}, 1) (strictly increasing in the knot index, inside "
                            "(0, 1))")
                    below = v
        # The region: finite multiples of 2^-20 in [0, blocks], from < to, per axis.
        blocks = (bg, be)
        for axis, axis_name in enumerate(("gamma", "e_n")):
            lo_r, hi_r = region[2 * axis], region[2 * axis + 1]
            if not (math.isfinite(lo_r) and math.isfinite(hi_r) and 0.0 <= lo_r < hi_r
                    <= blocks[axis] and (lo_r * 1048576.0).is_integer()
                    and (hi_r * 1048576.0).is_integer()):
                raise self._invalid(
                    f"{where}: dataset 'region' = {region}: the {axis_name} edges must be "
                    f"multiples of 2^-20 with 0 <= from < to <= {blocks[axis]} (root cells of "
                    "the patch)")
        # The grid covers the region (within 1e-12 of the value; along e_n through the axis's
        # map).
        def at(axis, v):
            if axis == 1:
                return self.e_axis.at_cells(v, blocks[1])
            return gamma_lo + (gamma_hi - gamma_lo) * v / blocks[0]
        for axis, (axis_name, first, step, n) in enumerate(
                (("gamma", gamma_0, gamma_step, ng), ("e_n", e_n_0, e_n_step, ne))):
            at_from = at(axis, region[2 * axis])
            at_to = at(axis, region[2 * axis + 1])
            end = first + (n - 1) * step
            slack = 1e-12 * max(abs(at_to), 1.0)
            if not (first <= at_from + slack and end >= at_to - slack):
                raise self._invalid(
                    f"{where}: the knot grid along {axis_name} ('{axis_name}_0' + "
                    f"i*'{axis_name}_step', {n} points of 'knot') spans [{first}, {end}]: "
                    f"must cover the region's [{at_from}, {at_to}]")
        # No leaf straddles an edge of the region along gamma or e_n: walk the octree with the
        # split masks, each leaf's extent [a/2^d, (a+1)/2^d] in root cells along both axes.
        stack = []
        for r in range(bg * bc * be):
            stack.append((r, 0, r // (bc * be), 0, r % be))
        while stack:
            cell, dg, ag, de, ae = stack.pop()
            t = tree[cell]
            if t < 0:
                for axis_name, d, a, lo_r, hi_r in (("gamma", dg, ag, region[0], region[1]),
                                                    ("e_n", de, ae, region[2], region[3])):
                    lo_c, hi_c = a / 2.0 ** d, (a + 1) / 2.0 ** d
                    if lo_c < lo_r < hi_c or lo_c < hi_r < hi_c:
                        raise self._invalid(
                            f"{where}: leaf {-t - 1} spans root cells [{lo_c}, {hi_c}] along "
                            f"{axis_name} across an edge of dataset 'region' = {region}: no "
                            "leaf may straddle one")
                continue
            mask = 7 if split is None else split[cell]
            halved = [a for a in range(3) if mask >> (2 - a) & 1]
            for q in range(1 << len(halved)):
                bits = {a: (q >> (len(halved) - 1 - j)) & 1 for j, a in enumerate(halved)}
                ndg, nag = (dg + 1, 2 * ag + bits[0]) if 0 in bits else (dg, ag)
                nde, nae = (de + 1, 2 * ae + bits[2]) if 2 in bits else (de, ae)
                stack.append((t + q, ndg, nag, nde, nae))
        return Knots(gamma_0, gamma_step, e_n_0, e_n_step, region, c_star, grade, knot)

    def region(self, gamma, alpha, e_n=1.0):
        """Patch name of a query (steps 1 and 3), or 'line' for the exact full-slip line (at
        normal restitution e_n). A table without a full-slip line (Thornton's law) answers every
        alpha from its patches: 'partial_high' for gamma >= 1 and alpha < alpha_c2."""
        if self.no_line:
            if gamma < 1.0:
                return "stick_low"
            return "partial_high" if alpha < alpha_c2(gamma) else "stick_high"
        if alpha <= (alpha_lin(gamma) if e_n == 1.0 else alpha_lin_e(gamma, e_n)):
            return "line"
        if gamma <= 1.0:
            return "stick_low"
        return "partial_high" if alpha < alpha_c2(gamma) else "stick_high"

    def _check_point(self, gamma, alpha):
        if not (math.isfinite(gamma) and gamma > 0):
            raise DomainError(f"gamma = {gamma}: must be a finite number > 0", "gamma")
        if math.isnan(alpha) or alpha < 0:
            raise DomainError(f"alpha = {alpha}: must be >= 0 (or inf)", "alpha")

    def rule_gamma(self, gamma):
        """gamma as the rule takes it: in the table of one pair, a gamma within PAIR_GAMMA_TOL
        (relative) of the pair's is the pair's; any other gamma as it is."""
        g = self.pair_gamma
        if g is not None and abs(gamma - g) <= PAIR_GAMMA_TOL * g:
            return g
        return gamma

    def _check_domain(self, gamma, alpha, lin):
        """Step 2; `lin` is alpha_lin(gamma), None in a table without a full-slip line."""
        outside = ("nothing is answered outside it: this table has no closed-form full-slip "
                   "line" if lin is None else
                   f"only alpha <= alpha_lin(gamma) = {lin} is answered outside it")
        if self.pair_gamma is not None and gamma != self.pair_gamma:
            raise DomainError(
                f"gamma = {gamma}: this table holds one pair of materials, gamma = "
                f"{self.pair_gamma!r} (within a relative {PAIR_GAMMA_TOL:g}; only alpha <= "
                f"alpha_lin(gamma) = {lin} is answered at another gamma)", "gamma")
        if not self.gamma_min <= gamma <= self.gamma_max:
            raise DomainError(
                f"gamma = {gamma} outside the table's domain [{self.gamma_min}, "
                f"{self.gamma_max}] ({outside})", "gamma")
        if alpha > self.alpha_max:
            raise DomainError(
                f"alpha = {alpha} above the table's alpha_max = {self.alpha_max}", "alpha")

    def p_at(self, point):
        """P at `point`, one value per axis of self.axes in that order: p(gamma, alpha) of an
        elastic table, p_e(gamma, alpha, e_n) of a table with an e_n axis. A point of another
        length raises ValueError naming the axes."""
        point = [float(x) for x in point]
        if len(point) != len(self.axes):
            raise ValueError(
                f"a point of this table has {len(self.axes)} values ({', '.join(self.axes)}), "
                f"not {len(point)}")
        return self.p(*point) if len(point) == 2 else self.p_e(*point)

    def p_e(self, gamma, alpha, e_n):
        """P(gamma, alpha, e_n) at normal restitution e_n (schema v4). e_n must lie in the
        table's e_n range, never clamped; an elastic table answers e_n = 1 only (as p). The table
        of one pair answers its gamma (within PAIR_GAMMA_TOL, relative: taken as the pair's) and
        the full-slip line at any gamma. Raises DomainError outside the answered domain."""
        gamma, alpha, e_n = float(gamma), float(alpha), float(e_n)
        gamma = self.rule_gamma(gamma)
        self._check_point(gamma, alpha)
        if self.e_n_range is None:
            if e_n != 1.0:
                raise DomainError(
                    f"e_n = {e_n}: this table is elastic (no e_n axis), it answers e_n = 1 only",
                    "e_n")
            return self.p(gamma, alpha)
        lo, hi = self.e_n_range
        if not lo <= e_n <= hi:
            raise DomainError(f"e_n = {e_n} outside the table's e_n range [{lo}, {hi}]", "e_n")
        if self.no_line:
            # No step 1 (Thornton's law): 2. domain (gamma_min >= 1), 3. patch, the partial-slip
            # patch from alpha = 0 to alpha_c2.
            self._check_domain(gamma, alpha, None)
            name = self.region(gamma, alpha, e_n)
        else:
            # 1. Full slip, exact (any gamma): P = 1 - (7/2)(1 + e_n) alpha.
            lin = alpha_lin_e(gamma, e_n)
            if alpha <= lin:
                return full_slip_e(alpha, e_n)
            # 2. Domain.
            self._check_domain(gamma, alpha, lin)
            # 3. Patch (alpha_c2 does not move with e_n).
            name = "stick_low" if gamma <= 1.0 else (
                "partial_high" if alpha < alpha_c2(gamma) else "stick_high")
        patch = self.patches.get(name)
        if patch is None:
            return -e_n  # at gamma = 1 exactly the contact sticks at once
        # 4. Coordinates (no warp with an e_n axis); 6-10 in Patch.interpolate_e (over (c, x_e)
        # in the table of one pair, at its gamma).
        if patch.kind == "partial-slip":
            c = (partial_coord_slip if self.no_line else partial_coord_e)(gamma, alpha, e_n)
        else:
            c = stick_coord(gamma, alpha, self.alpha_max)
        return patch.interpolate_e(gamma, _clamp01(c), e_n)

    def p(self, gamma, alpha):
        """P(gamma, alpha) by steps 1-10 (a table with an e_n axis: p_e at e_n = 1). Raises
        DomainError outside the answered domain."""
        gamma = float(gamma)
        alpha = float(alpha)
        if self.e_n_range is not None:
            return self.p_e(gamma, alpha, 1.0)
        self._check_point(gamma, alpha)
        # 1. Full slip, exact (any gamma).
        name = self.region(gamma, alpha)
        if name == "line":
            return 1.0 - 7.0 * alpha
        # 2. Domain.
        self._check_domain(gamma, alpha, alpha_lin(gamma))
        # 3. Patch.
        patch = self.patches.get(name)
        if patch is None:
            return -1.0
        # 4-10 (the warp of step 5 in Patch.interpolate).
        c = coordinate(patch.kind, gamma, alpha, self.alpha_max)
        return patch.interpolate(gamma, c, self.stencil)


# ---------------------------------------------------------------------------------------------
# Command line


def parse_number(s):
    t = s.strip().lower()
    if t in ("inf", "+inf", "infinity", "\u221e"):
        return math.inf
    try:
        return float(t)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{s}' is not a number") from None


class SplitMix64:
    """Small deterministic generator (independent of numpy's streams)."""

    def __init__(self, seed):
        self.state = seed & 0xFFFFFFFFFFFFFFFF

    def uniform(self):
        mask = 0xFFFFFFFFFFFFFFFF
        self.state = (self.state + 0x9E3779B97F4A7C15) & mask
        z = self.state
        z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & mask
        z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & mask
        z ^= z >> 31
        return (z >> 11) / float(1 << 53)


def sample_points(table, count, seed=20240611):
    """`count` deterministic points cycling over the table's patches; in each patch gamma and the
    coordinate c are uniform, and every fourth point of a stick patch sits at c = 1
    (alpha = alpha_max, i.e. inf for a table with no slip)."""
    rng = SplitMix64(seed)
    names = [n for n in PATCH_NAMES if n in table.patches]
    pts = []
    for i in range(count):
        patch = table.patches[names[i % len(names)]]
        per = i // len(names)
        gamma = patch.gamma_lo + (patch.gamma_hi - patch.gamma_lo) * rng.uniform()
        u = rng.uniform()
        if patch.kind == "stick" and per % 4 == 3:
            c = 1.0
        else:
            c = 0.02 + 0.96 * u  # strictly inside: away from the patch's curved edges
        alpha = alpha_at(patch.kind, gamma, c, table.alpha_max)
        pts.append((patch.name, gamma, alpha))
    return pts


def fmt_alpha(a):
    return "inf" if math.isinf(a) else repr(float(a))


def run_sweep(sweep, gamma, alpha, tol):
    cmd = [sweep, "impact", "--gamma", repr(float(gamma)), "--alpha", fmt_alpha(alpha),
           "--tol", repr(float(tol)), "--json"]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"`{' '.join(cmd)}` exited {r.returncode}: {r.stderr.strip()}")
    out = json.loads(r.stdout)
    return float(out["P"]), float(out["error_estimate"])


def check_against_sweep(table, count, sweep, max_error, tol, jobs):
    if not (os.path.isfile(sweep) and os.access(sweep, os.X_OK)):
        print(f"error: sweep binary {sweep} not found or not executable "
              "(build it with `cargo build --release` or pass --sweep PATH)", file=sys.stderr)
        return 2
    pts = sample_points(table, count)
    with ThreadPoolExecutor(max_workers=max(1, jobs)) as ex:
        futs = [ex.submit(run_sweep, sweep, g, a, tol) for _, g, a in pts]
        results = []
        for fut in futs:
            try:
                results.append(fut.result())
            except Exception as e:  # noqa: BLE001 - reported per point
                results.append(e)
    print(f"{'#':>3} {'patch':<13} {'gamma':>10} {'alpha':>12} {'P_table':>20} "
          f"{'P_sweep':>20} {'sweep_err':>9} {'|diff|':>9}")
    worst = 0.0
    failed = 0
    for i, ((name, g, a), res) in enumerate(zip(pts, results)):
        try:
            pt = table.p(g, a)
        except DomainError as e:
            pt = float("nan")
            print(f"    point {i}: table refused it: {e}", file=sys.stderr)
        if isinstance(res, Exception):
            print(f"{i:>3} {name:<13} {g:>10.6f} {fmt_alpha(a)[:12]:>12} {pt:>20.15f} "
                  f"{'FAILED':>20}", flush=True)
            print(f"    {res}", file=sys.stderr)
            failed += 1
            continue
        ps, pe = res
        d = abs(pt - ps)
        bad = not d <= max_error
        failed += bad
        if not math.isnan(d):
            worst = max(worst, d)
        print(f"{i:>3} {name:<13} {g:>10.6f} {fmt_alpha(a)[:12]:>12} {pt:>20.15f} "
              f"{ps:>20.15f} {pe:>9.1e} {d:>9.2e}{'  > max-error' if bad else ''}")
    print(f"max |P_table - P_sweep| = {worst:.3e} over {count} points "
          f"(bound {max_error:g}, sweep tol {tol:g})")
    if failed:
        print(f"FAIL: {failed} of {count} points exceed the bound or failed", file=sys.stderr)
        return 1
    return 0


def check_stored(table, tolerance=1e-12):
    ch = table.checks
    need = ("gamma", "alpha", "P_interpolated", "patch")
    if ch is None or any(n not in ch for n in need):
        print(f"error: {table.path} has no complete /checks group", file=sys.stderr)
        return 1
    n = len(ch["gamma"])
    if n == 0:
        print(f"error: {table.path} has no held-out checks", file=sys.stderr)
        return 1
    index = {"stick_low": 0, "partial_high": 1, "stick_high": 2, "line": -1}
    worst = 0.0
    bad = 0
    with_e_n = table.e_n_range is not None and "e_n" in ch
    for i in range(n):
        g, a = float(ch["gamma"][i]), float(ch["alpha"][i])
        e = float(ch["e_n"][i]) if with_e_n else 1.0
        stored = float(ch["P_interpolated"][i])
        try:
            mine = table.p_e(g, a, e)
        except DomainError as e:
            print(f"check {i}: (gamma {g!r}, alpha {a!r}) refused: {e}", file=sys.stderr)
            bad += 1
            continue
        d = abs(mine - stored)
        if not d <= tolerance:
            bad += 1
            print(f"check {i}: gamma {g!r} alpha {a!r}: reader {mine!r}, stored {stored!r}, "
                  f"|diff| {d:.3e}", file=sys.stderr)
        else:
            worst = max(worst, d)
        want = index[table.region(g, a, e)]
        if int(ch["patch"][i]) != want:
            bad += 1
            print(f"check {i}: gamma {g!r} alpha {a!r}: stored patch {int(ch['patch'][i])}, "
                  f"the rule selects {want}", file=sys.stderr)
    print(f"{n} held-out checks: max |reader - P_interpolated| = {worst:.3e} "
          f"(tolerance {tolerance:g}), {bad} mismatches")
    return 1 if bad else 0


def main(argv=None):
    ap = argparse.ArgumentParser(
        description="Reference reader of a P(gamma, alpha) table (docs/table-format.md).")
    ap.add_argument("table", help="HDF5 table written by `sweep run`")
    ap.add_argument("--gamma", type=parse_number,
                    help="gamma > 0 (default for the table of one pair: the pair's gamma)")
    ap.add_argument("--alpha", type=parse_number, help="alpha >= 0, or inf")
    ap.add_argument("--e-n", type=parse_number, default=None,
                    help="normal restitution e_n in the table's e_n range (default 1; an "
                    "elastic table answers 1 only)")
    ap.add_argument("--error-bound", action="store_true",
                    help="print the table's stated error bound (docs/table-format.md)")
    ap.add_argument("--check-stored", action="store_true",
                    help="compare with /checks/P_interpolated (1e-12)")
    ap.add_argument("--check-against-sweep", type=int, metavar="N",
                    help="compare N deterministic points with `sweep impact`")
    ap.add_argument("--sweep", default=None,
                    help="sweep binary (default: target/release/sweep of this repository)")
    ap.add_argument("--max-error", type=float, default=1e-5,
                    help="bound of |P_table - P_sweep| (default 1e-5)")
    ap.add_argument("--tol", type=float, default=1e-8,
                    help="`sweep impact --tol` (default 1e-8)")
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 1,
                    help="parallel `sweep impact` processes (default: cores)")
    args = ap.parse_args(argv)

    query = args.gamma is not None or args.alpha is not None
    if args.gamma is not None and args.alpha is None:
        ap.error("--gamma needs --alpha")
    if args.e_n is not None and not query:
        ap.error("--e-n needs --alpha (and --gamma, except for the table of one pair)")
    if not (query or args.error_bound or args.check_stored
            or args.check_against_sweep is not None):
        ap.error("nothing to do: give --gamma/--alpha (--alpha alone for the table of one "
                 "pair), --error-bound, --check-stored or --check-against-sweep N")
    if args.check_against_sweep is not None and args.check_against_sweep < 1:
        ap.error("--check-against-sweep N needs N >= 1")
    try:
        table = Table(args.table)
    except TableError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    status = 0
    if query:
        gamma = table.pair_gamma if args.gamma is None else args.gamma
        if gamma is None:
            print(f"error: --gamma is needed: {table.path} spans gamma in [{table.gamma_min}, "
                  f"{table.gamma_max}] (only the table of one pair has a default)",
                  file=sys.stderr)
            return 2
        try:
            e_n = 1.0 if args.e_n is None else args.e_n
            print(repr(table.p_e(gamma, args.alpha, e_n)))
        except DomainError as e:
            print(f"error: {e}", file=sys.stderr)
            return 2
    if args.error_bound:
        print(repr(table.error_bound))
    if args.check_stored:
        status = max(status, check_stored(table))
    if args.check_against_sweep is not None and table.e_n_range is not None:
        print("error: --check-against-sweep samples elastic tables; for a table with an e_n "
              "axis run `sweep verify TABLE`", file=sys.stderr)
        return 2
    if args.check_against_sweep is not None:
        sweep = args.sweep or os.path.join(
            os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "target", "release",
            "sweep")
        status = max(status, check_against_sweep(table, args.check_against_sweep, sweep,
                                                 args.max_error, args.tol, args.jobs))
    return status


if __name__ == "__main__":
    sys.exit(main())
