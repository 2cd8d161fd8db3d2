"""The table of one pair of materials: P(α, e_n) at the pair's single γ.

    python3 python/examples/pair_table.py [TABLE]

TABLE defaults to the repository's tables/dissipative-pair.h5 (alumina-96 on soda-lime glass,
e_n from 0.5 to 1, Kelvin–Voigt law; configs/dissipative-pair.toml), found from this file's
place, so that it runs from any directory of a checkout.
"""

import sys
from pathlib import Path

import numpy as np

import oblique

DEFAULT = Path(__file__).resolve().parents[2] / "tables" / "dissipative-pair.h5"
table = oblique.Table(sys.argv[1] if len(sys.argv) > 1 else DEFAULT)
print(table)
gamma = table.pair_gamma  # the one gamma it answers (None for a table over a range of gamma)
if gamma is None:
    sys.exit(f"{table.info['path']}: not the table of one pair")

# P(gamma, alpha, e_n) at the pair's gamma: alpha and e_n broadcast, here (4,) against (3, 1).
e_n = np.array([0.5, 0.75, 1.0])
alpha = np.array([0.1, 0.3, 1.0, np.inf])
print("alpha            :", alpha)
for e, row in zip(e_n, table.p(gamma, alpha, e_n=e_n[:, None])):
    print(f"P(gamma, e_n={e:<4}):", np.round(row, 6))

# Rebounds of the pair from the catalogue's materials (their gamma is the table's).
m = oblique.materials
ball = oblique.Sphere(mass=2.4347e-4, radius=2.5e-3, kappa=0.4)
theta = np.radians(30.0)
r = table.rebound(
    ball,
    velocity=[3.9 * np.sin(theta), 0.0, 3.9 * np.cos(theta)],  # m/s
    friction=0.092,
    materials=(m["alumina-96"], m["soda-lime-glass"]),
    e_n=e_n,
)
print("e_n   P          e_t       spin_y")
for k in range(len(e_n)):
    print(f"{r.e_n[k]:<4}  {r.p[k]:+.6f}  {r.e_t[k]:.6f}  {r.spin[k, 1]:+9.3f}")

# Another gamma (another pair of materials) is refused, naming both.
try:
    table.p([gamma, 1.75], 0.3, e_n=0.8)
except ValueError as err:
    print("refused:", err)
