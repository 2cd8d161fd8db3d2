"""Shared fixtures of the `oblique` test suite.

The suite compares the package against references that do not go through it: the Rust CLI
(`target/release/sweep query --batch -`), the independent reference reader
(`scripts/read_table.py`, h5py + numpy only) and closed forms of `physics.md` written out in
the tests. Nothing here skips: a missing binary, table or module is a failure.
"""

from __future__ import annotations

import importlib.util
import json
import subprocess
from pathlib import Path
from typing import Dict

import pytest

import oblique
from _oblique_helpers import DISSIPATIVE, READER, ROOT, SHIPPED, SWEEP, TABLES

# ---------------------------------------------------------------------------------------------
# Fixtures


@pytest.fixture(scope="session")
def sweep_bin() -> Path:
    assert SWEEP.is_file(), f"{SWEEP} is missing: build it with `cargo build --release`"
    return SWEEP


@pytest.fixture(scope="session")
def table_paths() -> Dict[str, Path]:
    paths = {n: TABLES / f"{n}.h5" for n in SHIPPED}
    for n, p in paths.items():
        assert p.is_file(), f"shipped table {p} is missing"
    return paths


@pytest.fixture(scope="session")
def tables(table_paths) -> Dict[str, oblique.Table]:
    return {n: oblique.Table(p) for n, p in table_paths.items()}


@pytest.fixture(scope="session")
def full(tables) -> oblique.Table:
    return tables["full"]


@pytest.fixture(scope="session")
def dissipative() -> oblique.Table:
    """tables/dissipative-demo.h5: P(γ, α, e_n) for 0.5 <= e_n <= 1 (schema 4)."""
    assert DISSIPATIVE.is_file(), f"shipped table {DISSIPATIVE} is missing"
    return oblique.Table(DISSIPATIVE)


@pytest.fixture(scope="session")
def full_clamped(table_paths) -> oblique.Table:
    return oblique.Table(table_paths["full"], clamp=True)


@pytest.fixture(scope="session")
def finite_table_path(tmp_path_factory, sweep_bin) -> Path:
    """A small table with a finite alpha_max (every shipped table has alpha_max = inf), built
    by `sweep run` from configs/quick.toml with alpha_max = 5 (about a second)."""
    d = tmp_path_factory.mktemp("finite")
    out = d / "finite.h5"
    text = (ROOT / "configs" / "quick.toml").read_text()
    assert 'alpha_max = "inf"' in text and "output =" in text
    lines = []
    for ln in text.splitlines():
        if ln.startswith("output ="):
            ln = "output = " + json.dumps(str(out))
        elif ln.startswith("alpha_max ="):
            ln = "alpha_max = 5.0"
        lines.append(ln)
    cfg = d / "finite.toml"
    cfg.write_text("\n".join(lines) + "\n")
    r = subprocess.run(
        [str(sweep_bin), "run", str(cfg), "--quiet", "--threads", "2"],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert r.returncode == 0, f"sweep run failed: {r.stderr[-2000:]}"
    assert out.is_file()
    return out


@pytest.fixture(scope="session")
def finite_table(finite_table_path) -> oblique.Table:
    t = oblique.Table(finite_table_path)
    assert t.info["alpha_max"] == 5.0
    return t


@pytest.fixture(scope="session")
def reader():
    """The independent reference reader scripts/read_table.py, imported as a module."""
    assert READER.is_file(), f"{READER} is missing"
    spec = importlib.util.spec_from_file_location("read_table_reference", READER)
    mod = importlib.util.module_from_spec(spec)
    assert spec.loader is not None
    spec.loader.exec_module(mod)
    return mod


@pytest.fixture(scope="session")
def reference_tables(reader, table_paths):
    """The shipped tables loaded by the reference reader (loading full.h5 takes ~1.5 s: once)."""
    cache = {}

    def get(name):
        if name not in cache:
            cache[name] = reader.Table(str(table_paths[name]))
        return cache[name]

    return get
