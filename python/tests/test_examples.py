"""The examples the docs show run and do what they say (the docs' check compares their output;
here: the figure is drawn)."""

from __future__ import annotations

import os
import subprocess
import sys

from _oblique_helpers import DISSIPATIVE, PAIR, ROOT


def test_seed000_example_draws_the_figure(tmp_path):
    figure = tmp_path / "seed000.png"
    env = dict(os.environ, MPLBACKEND="Agg")
    r = subprocess.run(
        [sys.executable, str(ROOT / "python/examples/seed000.py"), str(ROOT / "tables/full.h5"), str(figure)],
        capture_output=True,
        text=True,
        cwd=tmp_path,
        env=env,
        timeout=120,
    )
    assert r.returncode == 0, r.stderr
    data = figure.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n" and len(data) > 20_000
    # 89 angles, each in one regime.
    regimes = next(line for line in r.stdout.splitlines() if line.startswith("regimes:"))
    counts = [int(part.split()[-1]) for part in regimes.split(":", 1)[1].split(",")]
    assert sum(counts) == 89


def test_quickstart_example_runs_from_any_directory(tmp_path):
    # No table given: the one built into the package, from a folder without tables/.
    r = subprocess.run(
        [sys.executable, str(ROOT / "python/examples/quickstart.py")],
        capture_output=True,
        text=True,
        cwd=tmp_path,
        timeout=120,
    )
    assert r.returncode == 0, r.stderr
    assert "simulated P(1.754, 0.3)" in r.stdout
    assert "built-in tables/default.h5" in r.stdout


def test_first_example_runs_from_any_directory(tmp_path):
    r = subprocess.run(
        [sys.executable, str(ROOT / "python/examples/first.py")],
        capture_output=True,
        text=True,
        cwd=tmp_path,
        timeout=120,
    )
    assert r.returncode == 0, r.stderr
    assert abs(float(r.stdout.splitlines()[0]) - 0.098791819) < 1e-5


def test_dissipative_rebound_example_runs_from_any_directory(tmp_path):
    # Its default table is found from the example's place in the checkout, not the cwd.
    assert DISSIPATIVE == ROOT / "tables/dissipative-demo.h5"
    r = subprocess.run(
        [sys.executable, str(ROOT / "python/examples/dissipative_rebound.py")],
        capture_output=True,
        text=True,
        cwd=tmp_path,
        timeout=120,
    )
    assert r.returncode == 0, r.stderr
    assert r.stdout.startswith("law kelvin-voigt, e_n in [0.5, 1.0]")
    # The rows of the rebound table: v_z after = −e_n v_z0, with v_z0 = 3.9 cos 30°.
    rows = [ln.split() for ln in r.stdout.splitlines()[-3:]]
    for row in rows:
        e_n, v_z = float(row[0]), float(row[4])
        assert abs(v_z + e_n * 3.9 * 3**0.5 / 2) < 1e-5


def test_pair_table_example_runs_from_any_directory(tmp_path):
    assert PAIR == ROOT / "tables/dissipative-pair.h5"
    r = subprocess.run(
        [sys.executable, str(ROOT / "python/examples/pair_table.py")],
        capture_output=True,
        text=True,
        cwd=tmp_path,
        timeout=120,
    )
    assert r.returncode == 0, r.stderr
    lines = r.stdout.splitlines()
    assert "gamma = 1.7497858600774299 (one pair)" in lines[0]
    assert lines[-1].startswith("refused: invalid gamma = 1.75:")
    assert "1.7497858600774299" in lines[-1] and lines[-1].endswith("(at index (1,))")
