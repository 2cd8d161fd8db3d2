"""Dissipative impacts: how far the normal restitution e_n moves P from the elastic answer.

    python3 python/examples/dissipation.py

For three materials groups γ, the largest |P(γ, α, e_n) − P(γ, α, 1)| over 240 α from 0.05 to
30 and α = ∞ (Kelvin–Voigt law, simulated to 1e-6; about 5 s on 2 cores), and where it is.
"""

from __future__ import annotations

import numpy as np

import oblique

ALPHAS = np.concatenate([np.logspace(-1.3, 1.5, 240), [np.inf]])
E_N = (0.99, 0.95, 0.9, 0.8, 0.6)

print("gamma  " + "  ".join(f"e_n={e:<4}" for e in E_N) + "  at alpha")
for gamma in (1.2, 1.75, 2.5):
    elastic = oblique.impact(gamma, ALPHAS, 1e-6).p
    # One call for all e_n: the arrays broadcast, (5, 1) against (241,).
    damped = oblique.impact(gamma, ALPHAS, 1e-6, e_n=np.array(E_N)[:, None]).p
    diff = np.abs(damped - elastic)
    worst = diff.argmax(axis=1)
    maxima = "  ".join(f"{diff[k, i]:8.4f}" for k, i in enumerate(worst))
    print(f"{gamma:<5}  {maxima}  {ALPHAS[worst[-1]]:.3g}")
