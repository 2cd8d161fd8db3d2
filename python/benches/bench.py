"""Speed of the Python package against the Rust library, on the same inputs in one run.

    python3 python/benches/bench.py [TABLE] [--points N] [--reps R]

Draws N random (γ, α) points (γ uniform over the table's γ domain, α uniform in [0, 2]) and N
random 3-D sphere–sphere impacts (two steel spheres, R = 5 mm and 3 mm, μ = 0.3; velocities and
spins uniform in boxes, random normals, every pair approaching), writes them to a scratch folder,
runs the Rust side (`target/release/examples/batch_timing`, built by
`cargo build --release --workspace --examples`) on them, then times the same work through
`oblique`. Prints medians over R runs: wall time, CPU time of the process (all threads), queries
per second, and the Python/Rust ratio of wall times. Checks that both sides give the same P.
"""

import argparse
import math
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

import oblique

ROOT = Path(__file__).resolve().parents[2]


def median_time(reps, f):
    walls, cpus = [], []
    for _ in range(reps):
        w0, c0 = time.perf_counter(), time.process_time()
        f()
        walls.append(time.perf_counter() - w0)
        cpus.append(time.process_time() - c0)
    return float(np.median(walls)), float(np.median(cpus))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("table", nargs="?", default=str(ROOT / "tables" / "full.h5"))
    ap.add_argument("--points", type=int, default=1_000_000, help="queries per batch (10^6)")
    ap.add_argument("--reps", type=int, default=7, help="runs per measurement (7)")
    args = ap.parse_args()
    exe = ROOT / "target" / "release" / "examples" / "batch_timing"
    if not exe.exists():
        sys.exit(f"bench: {exe} missing: cargo build --release --workspace --examples")

    table = oblique.Table(args.table)
    info = table.info
    rng = np.random.default_rng(2026)
    n = args.points
    gamma = rng.uniform(info["gamma_min"], info["gamma_max"], n)
    alpha = rng.uniform(0.0, 2.0, n)
    steel = oblique.Material(210e9, 0.29)
    mass = lambda r: 7850.0 * 4.0 / 3.0 * math.pi * r**3  # noqa: E731
    s1, s2 = oblique.Sphere(mass(5e-3), 5e-3, 0.4), oblique.Sphere(mass(3e-3), 3e-3, 0.4)
    v1 = rng.uniform(-2.0, 2.0, (n, 3))
    w1 = rng.uniform(-300.0, 300.0, (n, 3))
    v2 = rng.uniform(-2.0, 2.0, (n, 3))
    w2 = rng.uniform(-300.0, 300.0, (n, 3))
    normal = rng.normal(size=(n, 3))
    normal /= np.linalg.norm(normal, axis=1, keepdims=True)
    # Every pair approaches: the normal points along the relative velocity's side.
    normal *= np.sign(np.einsum("ij,ij->i", v1 - v2, normal))[:, None]

    with tempfile.TemporaryDirectory(prefix="oblique-bench-") as tmp:
        points, impacts = Path(tmp) / "points.bin", Path(tmp) / "impacts.bin"
        np.stack([gamma, alpha], axis=1).astype("<f8").tofile(points)
        np.concatenate([v1, w1, v2, w2, normal], axis=1).astype("<f8").tofile(impacts)
        rust = subprocess.run(
            [str(exe), args.table, str(points), str(impacts), str(args.reps)],
            check=True,
            capture_output=True,
            text=True,
        )
    measured = {}
    for line in rust.stdout.splitlines():
        name, count, wall, cpu = line.split()
        measured[name] = (int(count), float(wall), float(cpu))
    if rust.stderr:
        sys.exit(f"bench: the Rust side reported: {rust.stderr}")

    # Python, the same work.
    single = measured["p_single"][0]
    gl, al = gamma[:single].tolist(), alpha[:single].tolist()
    p_scalar = table.p

    def scalar_loop():
        for g, a in zip(gl, al):
            p_scalar(g, a)

    py = {
        "p_single": median_time(args.reps, scalar_loop),
        "p_batch_par": median_time(args.reps, lambda: table.p(gamma, alpha)),
        "rebound_3d_batch_par": median_time(
            args.reps,
            lambda: table.rebound(
                s1, v1, w1, friction=0.3, normal=normal, materials=(steel, steel),
                other=s2, other_velocity=v2, other_spin=w2,
            ),
        ),
    }
    out = np.empty(n)
    py["p_batch_par (out=)"] = median_time(args.reps, lambda: table.p(gamma, alpha, out=out))
    # Both sides answer the same P (the Rust batch wrote its last answers; check ours).
    if not np.array_equal(table.p(gamma[:1000], alpha[:1000]), [p_scalar(g, a) for g, a in zip(gl[:1000], al[:1000])]):
        sys.exit("bench: the scalar and the batch paths differ")

    print(f"table {args.table}, {n} points, {args.reps} runs each; medians")
    print(f"{'what':<42} {'wall':>10} {'CPU':>10} {'per item':>10} {'items/s':>10} {'py/rust':>8}")

    def row(label, count, wall, cpu, ref=None):
        ratio = f"{wall / ref:8.2f}" if ref else " " * 8
        print(
            f"{label:<42} {wall * 1e3:8.2f}ms {cpu * 1e3:8.2f}ms {wall / count * 1e9:8.1f}ns"
            f" {count / wall / 1e6:8.1f}M {ratio}"
        )

    c, w, cp = measured["p_single"]
    row("Rust   Table::p, one call per point", c, w, cp)
    row("Python Table.p(float, float), one call", c, *py["p_single"], w)
    c, w, cp = measured["p_batch"]
    row("Rust   Table::p_batch (1 thread)", c, w, cp)
    c, w, cp = measured["p_batch_par"]
    row("Rust   Table::p_batch_par", c, w, cp)
    row("Python Table.p(array, array)", n, *py["p_batch_par"], w)
    row("Python Table.p(array, array, out=)", n, *py["p_batch_par (out=)"], w)
    c, w, cp = measured["rebound_3d_batch"]
    row("Rust   rebound_3d_batch (1 thread)", c, w, cp)
    c, w, cp = measured["rebound_3d_batch_par"]
    row("Rust   rebound_3d_batch_par", c, w, cp)
    row("Python Table.rebound, sphere-sphere 3-D", n, *py["rebound_3d_batch_par"], w)


if __name__ == "__main__":
    main()
