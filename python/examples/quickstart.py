"""A first session with the Python package: P, e_t and regimes from the table, a 3-D rebound,
and the solver for a point checked against the table.

    python3 python/examples/quickstart.py [TABLE]

TABLE defaults to the table built into the package (tables/default.h5); runs from any
directory.
"""

import sys

import numpy as np

import oblique

table = oblique.Table(sys.argv[1] if len(sys.argv) > 1 else None)
print(table)

# P(gamma, alpha), e_t of a solid sphere without spin, the regime: scalars or arrays.
print(f"P(1.754, 1) = {table.p(1.754, 1.0):.9f}  +/- {table.error_bound:.1e}")
alpha = np.array([0.1, 0.3, 1.0, np.inf])
print("alpha :", alpha)
print("P     :", np.round(table.p(1.754, alpha), 6))
print("e_t   :", np.round(table.e_t(1.754, alpha), 6))
print("regime:", table.regime(1.754, alpha))
# Normal restitution e_n = 0.8 (Kelvin-Voigt law), where the table has an e_n axis (the
# built-in one has: 0.3 <= e_n <= 1).
if "e_n" in table.info["axes"]:
    print("P at e_n = 0.8:", np.round(table.p(1.754, alpha, e_n=0.8), 6))

# A 5 mm alumina sphere hits a glass plate at 3.9 m/s, 30 degrees from the normal.
alumina = oblique.Material(youngs_modulus=370e9, poisson_ratio=0.25)
glass = oblique.Material(youngs_modulus=73e9, poisson_ratio=0.217)
ball = oblique.Sphere(mass=2.4347e-4, radius=2.5e-3, kappa=0.4)
theta = np.radians(30.0)
r = table.rebound(
    ball,
    velocity=[3.9 * np.sin(theta), 0.0, 3.9 * np.cos(theta)],  # m/s
    normal=[0.0, 0.0, 1.0],  # from the sphere into the wall
    friction=0.092,
    materials=(alumina, glass),
)
print(f"gamma = {r.gamma:.6f}, alpha = {r.alpha:.6f}, P = {r.p:.6f}, e_t = {r.e_t:.6f}")
print("velocity after:", np.round(r.velocity, 6), "m/s")
print("spin after    :", np.round(r.spin, 3), "rad/s")
print(f"rebound angle {np.degrees(r.rebound_angle_centre):.3f} deg, "
      f"energy lost {r.energy_lost:.4e} J")

# The solver itself, at a point in partial slip: agrees within the table's bound.
sim = oblique.impact(1.754, 0.3, tol=1e-6)
print(f"simulated P(1.754, 0.3) = {sim.p:.7f} +/- {sim.error_estimate:.1e}, "
      f"table: {table.p(1.754, 0.3):.7f}")
