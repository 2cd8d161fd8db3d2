#!/usr/bin/env python3
"""The README figure: P(gamma, alpha) against alpha for several gamma, read from a table with the
reference reader (scripts/read_table.py). The alpha axis is compactified, alpha/(1 + alpha), so
that alpha = inf (no slip) is on the plot.

    python3 scripts/plot_readme.py tables/isotropic.h5 docs/img/p_curves.png

Needs matplotlib, h5py, numpy (pip install matplotlib h5py numpy).
"""
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from read_table import Table, alpha_c1, alpha_c2  # noqa: E402


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: plot_readme.py TABLE OUT.png")
    path, out = sys.argv[1], sys.argv[2]
    table = Table(path)
    gmin, gmax = table.gamma_min, table.gamma_max
    gammas = np.linspace(gmin, gmax, 5)
    fig, ax = plt.subplots(figsize=(7.5, 4.6), dpi=110)
    s = np.linspace(0.0, 1.0, 1201)
    for g in gammas:
        alphas = np.where(s < 1.0, s / np.maximum(1.0 - s, 1e-300), np.inf)
        p = [table.p(g, a) for a in alphas]
        (line,) = ax.plot(s, p, lw=1.6, label=f"γ = {g:.2f}")
        for crit in ((alpha_c1(g), alpha_c2(g)) if g > 1 else (alpha_c2(g),)):
            ax.plot(crit / (1 + crit), table.p(g, crit), "o", ms=3.5, color=line.get_color())
    ax.plot(s, 1 - 7 * np.where(s < 1, s / np.maximum(1 - s, 1e-300), np.inf), "k--", lw=0.8,
            label="full slip P = 1 − 7α")
    ax.set_xlim(0, 1)
    ax.set_ylim(-1.02, 1.02)
    ticks = [0, 0.1, 0.2, 0.5, 1, 2, 5, np.inf]
    ax.set_xticks([t / (1 + t) if np.isfinite(t) else 1.0 for t in ticks])
    ax.set_xticklabels(["0", "0.1", "0.2", "0.5", "1", "2", "5", "∞"])
    ax.set_xlabel("α = μ v_z0 / |v_x0 + R ω0|   (axis: α/(1+α))")
    ax.set_ylabel("P = u_after / u_before")
    ax.set_title("Tangential restitution of the contact point (dots: α_c1, α_c2)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="upper right")
    fig.text(0.01, 0.005,
             f"table {os.path.basename(path)} (schema v1); "
             f"figure: python3 scripts/plot_readme.py {path} {out}",
             fontsize=6.5, color="0.35")
    fig.tight_layout(rect=(0, 0.03, 1, 1))
    fig.savefig(out)


if __name__ == "__main__":
    main()
