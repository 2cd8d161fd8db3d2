"""A table with a normal-restitution axis: P(γ, α, e_n) and rebounds at e_n < 1.

    python3 python/examples/dissipative_rebound.py [TABLE]

TABLE defaults to the repository's tables/dissipative-demo.h5 (e_n from 0.5 to 1, Kelvin–Voigt
law), found from this file's place, so that it runs from any directory of a checkout.
"""

import sys
from pathlib import Path

import numpy as np

import oblique

DEFAULT = Path(__file__).resolve().parents[2] / "tables" / "dissipative-demo.h5"
table = oblique.Table(sys.argv[1] if len(sys.argv) > 1 else DEFAULT)
info = table.info
print(f"law {info['law']}, e_n in [{info['e_n_min']}, {info['e_n_max']}], "
      f"gamma in [{info['gamma_min']}, {info['gamma_max']}], error bound {table.error_bound:.1e}")

# P(gamma, alpha, e_n): e_n broadcasts like gamma and alpha, here (3, 1) against (4,).
e_n = np.array([0.5, 0.75, 1.0])
alpha = np.array([0.1, 0.3, 1.0, np.inf])
print("alpha          :", alpha)
p = table.p(1.754, alpha, e_n=e_n[:, None])
for e, row in zip(e_n, p):
    print(f"P(1.754, e_n={e:<4}):", np.round(row, 6))

# The alumina sphere on glass of the first session (3.9 m/s, 30 degrees from the normal) at the
# three e_n: one call, e_n an array.
alumina = oblique.Material(youngs_modulus=370e9, poisson_ratio=0.25)
glass = oblique.Material(youngs_modulus=73e9, poisson_ratio=0.217)
ball = oblique.Sphere(mass=2.4347e-4, radius=2.5e-3, kappa=0.4)
theta = np.radians(30.0)
r = table.rebound(
    ball,
    velocity=[3.9 * np.sin(theta), 0.0, 3.9 * np.cos(theta)],  # m/s
    friction=0.092,
    materials=(alumina, glass),
    e_n=e_n,
)
print(f"gamma = {r.gamma[0]:.6f}")
print("e_n   alpha     P          e_t       v_z after  spin_y      energy lost")
for k in range(len(e_n)):
    print(f"{r.e_n[k]:<4}  {r.alpha[k]:.6f}  {r.p[k]:+.6f}  {r.e_t[k]:.6f}  "
          f"{r.velocity[k, 2]:+.5f}   {r.spin[k, 1]:+9.3f}  {r.energy_lost[k]:.4e} J")
