"""The material catalogue from Python: ``oblique.materials`` is the catalogue of scene files and
``sweep gamma`` (the same names, values and sources, checked against the CLI's JSON), read-only,
with entries that are ``oblique.Material`` (they unpack into (E, ν) as before) and work wherever
a Material does."""

from __future__ import annotations

import json
import math
import subprocess

import numpy as np
import pytest

import oblique
from oblique import RIGID, Material, Sphere
from _oblique_helpers import SWEEP


@pytest.fixture(scope="module")
def cli_catalogue():
    out = subprocess.run(
        [str(SWEEP), "gamma", "--catalogue", "--json"], check=True, capture_output=True, text=True
    ).stdout
    return json.loads(out)["materials"]


def test_the_catalogue_is_the_clis(cli_catalogue):
    assert list(oblique.materials) == [m["name"] for m in cli_catalogue]
    assert len(oblique.materials) == len(cli_catalogue) >= 7
    for m in cli_catalogue:
        mat = oblique.materials[m["name"]]
        assert isinstance(mat, Material)
        e = math.inf if m["youngs_modulus"] == "inf" else m["youngs_modulus"]
        assert (mat.youngs_modulus, mat.poisson_ratio) == (e, m["poisson_ratio"])
        assert mat.density == m["density"]
        assert mat.source == m["source"] and len(mat.source) > 20
        assert (mat.yield_stress, mat.limiting_pressure) == (
            m.get("yield_stress"),
            m.get("limiting_pressure"),
        )
        assert mat.yield_source == m["yield_source"] and len(mat.yield_source) > 10
    glass = oblique.materials["soda-lime-glass"]
    assert (glass.youngs_modulus, glass.poisson_ratio, glass.density) == (73e9, 0.217, 2500.0)
    assert "Gorham & Kharaz" in glass.source
    assert oblique.materials["rigid"].density is None
    assert oblique.materials["rigid"].youngs_modulus == math.inf
    # The metals' limiting pressure is 1.60 times their yield stress (Pa); glass has none.
    steel = oblique.materials["steel"]
    assert steel.yield_stress == 235e6 and steel.limiting_pressure == pytest.approx(376e6)
    assert oblique.materials["soda-lime-glass"].limiting_pressure is None
    assert "brittle" in oblique.materials["alumina-96"].yield_source


def test_read_only_and_unknown_names_list_the_catalogue():
    with pytest.raises(TypeError):
        oblique.materials["steel"] = Material(1e9, 0.3)  # type: ignore[index]
    with pytest.raises(KeyError, match=r"unknown material 'glass'.*soda-lime-glass.*rigid"):
        oblique.materials["glass"]
    assert "steel" in oblique.materials and "glass" not in oblique.materials
    assert oblique.materials.get("glass") is None
    with pytest.raises(AttributeError, match="read-only"):
        oblique.materials["steel"].density = 1.0
    # An entry is a Material of two fields: it unpacks and compares as one.
    e, nu = oblique.materials["steel"]
    assert (e, nu) == (210e9, 0.3)
    assert oblique.materials["rigid"] == RIGID
    assert isinstance(oblique.materials["steel"], oblique.CatalogueMaterial)
    assert "'steel'" in repr(oblique.materials["steel"]) and "7850" in repr(oblique.materials["steel"])
    assert "steel" in repr(oblique.materials)


def test_entries_work_as_materials(cli_catalogue):
    """γ from catalogue entries is the CLI's, for every pair; plain Materials still work."""
    names = [m["name"] for m in cli_catalogue]
    ball = Sphere(1e-3, 2e-3)
    for i, a in enumerate(cli_catalogue):
        for j, b in enumerate(cli_catalogue):
            pair = (oblique.materials[a["name"]], oblique.materials[b["name"]])
            want = a["gamma"][j]
            if want is None:  # two rigid bodies
                with pytest.raises(ValueError, match="youngs_modulus"):
                    oblique.groups(ball, 1.0, 1.0, friction=0.3, materials=pair)
                continue
            g = oblique.groups(ball, 1.0, 1.0, friction=0.3, materials=pair).gamma
            assert g == pytest.approx(want, rel=1e-14), (names[i], names[j])
    # The same γ as a Material of the same E and ν, and as a plain (E, ν) pair.
    alumina = oblique.materials["alumina-96"]
    g1 = oblique.groups(ball, 1.0, 1.0, friction=0.3, materials=(alumina, RIGID)).gamma
    g2 = oblique.groups(ball, 1.0, 1.0, friction=0.3, materials=(Material(370e9, 0.25), RIGID)).gamma
    g3 = oblique.groups(ball, 1.0, 1.0, friction=0.3, materials=((370e9, 0.25), (math.inf, 0.0))).gamma
    assert g1 == g2 == g3
    # Arrays of E in a Material, as before.
    g = oblique.groups(
        ball, 1.0, 1.0, friction=0.3, materials=(Material(np.array([370e9, 73e9]), 0.25), RIGID)
    ).gamma
    assert g.shape == (2,) and g[0] == g1


def test_solid_sphere_from_the_density():
    steel = oblique.materials["steel"]
    s = steel.solid_sphere(5e-3)
    assert s == Sphere(7850.0 * 4.0 / 3.0 * math.pi * 5e-3**3, 5e-3, 0.4)
    with pytest.raises(ValueError, match="no density"):
        oblique.materials["rigid"].solid_sphere(1e-3)
    with pytest.raises(ValueError, match="radius"):
        steel.solid_sphere(-1.0)
    # A seed-000 rebound from the catalogue: the scene's γ (sweep scene, README).
    r = oblique.groups(
        oblique.materials["alumina-96"].solid_sphere(2.5e-3),
        3.9 * math.sin(math.radians(30)),
        3.9 * math.cos(math.radians(30)),
        friction=0.092,
        materials=(oblique.materials["alumina-96"], oblique.materials["soda-lime-glass"]),
    )
    assert r.gamma == pytest.approx(1.7497858600774299, rel=1e-15)
    assert r.normal_mass == pytest.approx(2.4347e-4, rel=1e-4)
