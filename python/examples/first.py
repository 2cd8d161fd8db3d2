import numpy as np
import oblique

table = oblique.Table()  # the table built into the package; or Table("tables/full.h5")
print(table.p(1.754, 1.0))                       # P(gamma, alpha): a float
print(table.p(1.754, np.array([0.1, 0.3, np.inf])))  # arrays broadcast

# A 5 mm alumina sphere (kg, m; kappa = 0.4) hits glass at 3.9 m/s, 30 deg from the normal.
ball = oblique.Sphere(mass=2.4347e-4, radius=2.5e-3)
r = table.rebound(ball, velocity=[1.95, 0.0, 3.3775], normal=[0, 0, 1], friction=0.092,
                  materials=(oblique.Material(370e9, 0.25), oblique.Material(73e9, 0.217)))
print(f"e_t = {r.e_t:.6f}, spin = {r.spin.round(2)} rad/s, energy lost = {r.energy_lost:.4e} J")
