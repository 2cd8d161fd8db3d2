#!/usr/bin/env python3
"""Dense check of a table along lines in α: every (γ, e_n) of the lists, α on a uniform grid,
each point simulated (the oblique package, `impact(..., simulate=True)`) and compared with the
table's answer. Prints the largest error over all lines and per e_n, and the table's stated
bound; exit status 1 when a point is above the bound. For narrow features that a random sample
misses (a kink band, a region edge).

    python3 scripts/dense_lines.py tables/default.h5 \\
        --gamma 1.7939308,1.79,1.785,1.78,1.795,1.8 \\
        --e-n 0.9587945,0.999,1,0.94,0.8,0.5,0.3 --alpha 2.9:3.5:61 --tol 1e-9

Points outside the table's γ or e_n range are left out.
"""

import argparse
import sys
import time

import numpy as np

import oblique


def floats(text):
    return [float(x) for x in text.split(",")]


def grid(text):
    lo, hi, n = text.split(":")
    return np.linspace(float(lo), float(hi), int(n))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("table")
    ap.add_argument("--gamma", type=floats, required=True, help="γ of the lines, comma-separated")
    ap.add_argument("--e-n", type=floats, default=[1.0], help="e_n of the lines (default 1)")
    ap.add_argument("--alpha", type=grid, required=True, help="LO:HI:N, N points from LO to HI")
    ap.add_argument("--tol", type=float, default=1e-9, help="tolerance of the simulations")
    args = ap.parse_args()
    t = oblique.Table(args.table)
    info = t.info
    e_lo = info["e_n_min"] if info["e_n_min"] is not None else 1.0
    pts = [(g, a, e) for g in args.gamma for e in args.e_n for a in args.alpha
           if info["gamma_min"] <= g <= info["gamma_max"] and e_lo <= e <= 1.0]
    if not pts:
        sys.exit("dense_lines: no line inside the table's domain")
    g, a, e = (np.array(c) for c in zip(*pts))
    start = time.time()
    truth = oblique.impact(g, a, tol=args.tol, simulate=True, e_n=e).p
    err = np.abs(t.p(g, a, e_n=e) - truth)
    i = int(np.argmax(err))
    bound = info["error_bound"]
    print(f"{len(g)} points simulated at tol {args.tol:g} in {time.time() - start:.0f} s")
    print(f"max |error| {err[i]:.3e} at gamma = {float(g[i])!r}, alpha = {float(a[i])!r}, "
          f"e_n = {float(e[i])!r}")
    for en in sorted(set(e.tolist())):
        print(f"  e_n = {en}: max {err[e == en].max():.3e}")
    above = int(np.sum(err > bound))
    print(f"stated bound {bound:.3e}; points above it: {above}")
    sys.exit(1 if above else 0)


if __name__ == "__main__":
    main()
