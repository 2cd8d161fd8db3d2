"""e_t and spin against incidence angle: an alumina sphere on soda-lime glass (seed 000, Fig. 5).

    python3 python/examples/seed000.py [TABLE] [FIGURE]

TABLE defaults to the table built into the package (tables/default.h5), FIGURE to
seed000_alumina_on_glass.png in the current directory. Needs matplotlib.
"""

import os
import sys

import matplotlib

matplotlib.use("Agg")  # draw to a file; no display needed
import matplotlib.pyplot as plt
import numpy as np

import oblique

table_path = sys.argv[1] if len(sys.argv) > 1 else None
figure_path = sys.argv[2] if len(sys.argv) > 2 else "seed000_alumina_on_glass.png"
table = oblique.Table(table_path)

# The catalogue's alumina-96 and soda-lime-glass hold the values the seed assumes (E = 370 GPa,
# nu = 0.25; E = 73 GPa, nu = 0.217), with densities and sources (docs/materials.md).
# A 5 mm solid sphere (mass from the density) at 3.9 m/s, mu = 0.092.
alumina = oblique.materials["alumina-96"]
glass = oblique.materials["soda-lime-glass"]
ball = alumina.solid_sphere(radius=2.5e-3)  # m; kappa = 0.4
speed, mu = 3.9, 0.092  # m/s, friction coefficient

theta = np.radians(np.linspace(1.0, 89.0, 89))  # incidence angle from the normal
r = table.rebound_2d(
    ball,
    v_x=speed * np.sin(theta),  # tangential, no spin before
    v_z=speed * np.cos(theta),  # towards the wall
    friction=mu,
    materials=(alumina, glass),
)

# The full-slip approximation (seed 000, eq. 35): P = 1 - 7 alpha at every angle, so that
# e_t = 1 - (kappa/(1 + kappa))(1 - P) = 1 - 2 alpha, with alpha = mu v_z0/v_x0 here.
full_slip = 1.0 - 2.0 * r.alpha

alpha_c1, alpha_c2 = oblique.critical(r.gamma[0])
i = int(np.argmin(r.e_t))
onset = np.degrees(np.arctan(mu / alpha_c1))  # alpha = mu cot(theta) reaches alpha_c1
print(f"gamma = {r.gamma[0]:.6f}, alpha_c1 = {alpha_c1:.6f}, alpha_c2 = {alpha_c2:.6f}")
print(f"minimum e_t = {r.e_t[i]:.4f} at {np.degrees(theta[i]):.1f} deg")
print(f"full slip (alpha <= alpha_c1) from {onset:.1f} deg on")
names, counts = np.unique(table.regime(r.gamma, r.alpha), return_counts=True)
print("regimes:", ", ".join(f"{n} {c}" for n, c in zip(names, counts)))

fig, (left, right) = plt.subplots(1, 2, figsize=(9, 3.6), constrained_layout=True)
deg = np.degrees(theta)
left.plot(deg, r.e_t, label="MDR (table)")
left.plot(deg, full_slip, ls="--", label="full slip everywhere")
left.set_ylim(0.4, 1.02)
left.set(xlabel="incidence angle from the normal (deg)", ylabel="$e_t = v_x/v_{x0}$")
left.axvline(onset, color="0.6", lw=0.8, ls="--")
left.legend()
right.plot(deg, r.omega)
right.set(xlabel="incidence angle from the normal (deg)", ylabel="spin after $\\omega$ (rad/s)")
fig.suptitle("alumina sphere (R = 2.5 mm, 3.9 m/s) on soda-lime glass, $\\mu$ = 0.092")
os.makedirs(os.path.dirname(figure_path) or ".", exist_ok=True)
fig.savefig(figure_path, dpi=120)
print(f"wrote {figure_path}")
