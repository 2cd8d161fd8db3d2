"""Invalid input: the exception type, and a message that names the argument, its allowed range
and, for arrays, the index of the first bad element; damaged table files; nothing crashes the
interpreter."""

from __future__ import annotations

import math
import os
import re
import subprocess
import sys
import textwrap

import numpy as np
import pytest

import oblique
from oblique import RIGID, Material, Sphere

NAN, INF = math.nan, math.inf
S = Sphere(0.1, 0.01)
STEEL = Material(2.1e11, 0.29)


def raises(exc, fn, *needles):
    """Call fn, expect `exc`, and that every needle (a regex) occurs in the message."""
    with pytest.raises(exc) as info:
        fn()
    msg = str(info.value)
    for n in needles:
        assert re.search(n, msg), f"{n!r} not in message {msg!r}"
    return msg


# ---------------------------------------------------------------------------------------------
# γ and α


@pytest.mark.parametrize("gamma", [NAN, -1.0, 0.0, INF, -INF])
def test_bad_gamma(full, gamma):
    gamma_range = r"gamma.*finite number > 0"
    raises(ValueError, lambda: full.p(gamma, 0.3), gamma_range)
    raises(ValueError, lambda: full.curve(gamma), gamma_range)
    raises(ValueError, lambda: oblique.regime(gamma, 0.3), gamma_range)
    raises(ValueError, lambda: oblique.critical(gamma), gamma_range)
    raises(ValueError, lambda: oblique.impact(gamma, 0.3), gamma_range)
    raises(ValueError, lambda: full.rebound(S, (1.0, 0, 1.0), friction=0.3, gamma=gamma),
           gamma_range)
    g = np.array([1.5, 1.5, 1.5, gamma, 1.5, gamma])
    raises(ValueError, lambda: full.p(g, 0.3), gamma_range, re.escape("(at index (3,))"))
    raises(ValueError, lambda: oblique.regime(g, 0.3), gamma_range, re.escape("(at index (3,))"))
    raises(ValueError, lambda: full.e_t(g, 0.3), gamma_range, re.escape("(at index (3,))"))
    raises(ValueError, lambda: oblique.critical(g), re.escape("(at index (3,))"))
    raises(ValueError, lambda: full.p(g.reshape(2, 3), 0.3), re.escape("(at index (1, 0))"))
    raises(ValueError, lambda: full.rebound(S, (1.0, 0, 1.0), friction=0.3, gamma=g),
           gamma_range, re.escape("(at index (3,))"))
    raises(ValueError, lambda: full.rebound_2d(S, 1.0, 1.0, friction=0.3, gamma=g),
           gamma_range, re.escape("(at index (3,))"))


@pytest.mark.parametrize("alpha", [NAN, -1e-300, -0.3, -INF])
def test_bad_alpha(full, alpha):
    alpha_range = r"alpha.*>= 0"
    raises(ValueError, lambda: full.p(1.5, alpha), alpha_range)
    raises(ValueError, lambda: full.curve(1.5).p(alpha), alpha_range)
    raises(ValueError, lambda: oblique.regime(1.5, alpha), alpha_range)
    raises(ValueError, lambda: oblique.impact(1.5, alpha), alpha_range)
    raises(ValueError, lambda: full.e_t(1.5, alpha), alpha_range)
    a = np.zeros((3, 4))
    a[2, 1] = alpha
    a[2, 3] = alpha
    idx = re.escape("(at index (2, 1))")
    raises(ValueError, lambda: full.p(1.5, a), alpha_range, idx)
    raises(ValueError, lambda: full.curve(1.5).p(a), alpha_range, idx)
    raises(ValueError, lambda: oblique.regime(1.5, a), alpha_range, idx)


def test_impact_error_message_is_not_prefixed(full):
    """The array error of impact() reads like every other one: the problem, not the Python
    exception's repr ("ValueError: invalid alpha ...")."""
    msg = raises(ValueError, lambda: oblique.impact(1.5, [0.2, 0.3, -1.0]), r"alpha.*>= 0",
                 re.escape("(at index (2,))"))
    assert msg.startswith("invalid alpha"), msg
    scalar = raises(ValueError, lambda: oblique.impact(1.5, -1.0))
    assert msg == scalar + " (at index (2,))"


def test_outside_the_domain(full, finite_table):
    info = full.info
    dom = re.escape(f"[{info['gamma_min']}, {info['gamma_max']}]")
    for g in (0.5 * info["gamma_min"], 2.0 * info["gamma_max"]):
        raises(ValueError, lambda: full.p(g, 10.0), r"gamma", dom, "clamp")
        raises(ValueError, lambda: full.curve(g), r"gamma", dom)
        raises(ValueError, lambda: full.p([1.5, 1.5, g], 10.0), dom,
               re.escape("(at index (2,))"))
        raises(ValueError, lambda: full.rebound(S, (1.0, 0, 1.0), friction=INF, gamma=g), dom)
    raises(ValueError, lambda: finite_table.p(1.5, 6.0), r"alpha", r"alpha_max", r"\b5\b",
           "clamp")
    raises(ValueError, lambda: finite_table.p(1.5, INF), r"alpha", r"alpha_max")
    raises(ValueError, lambda: finite_table.p(1.5, [1.0, 2.0, 3.0, 7.0]), r"alpha_max",
           re.escape("(at index (3,))"))
    raises(ValueError, lambda: finite_table.curve(1.5).p(6.0), r"alpha_max")
    raises(ValueError, lambda: finite_table.rebound(S, (1e-3, 0, 1.0), friction=INF, gamma=1.5),
           r"alpha_max")


def test_index_of_the_first_bad_element_in_large_batches(full):
    """Large batches run in parallel chunks; the error still names the lowest bad index."""
    g = np.full(40_000, 1.5)
    g[[31_000, 9_001, 20_000]] = -1.0
    raises(ValueError, lambda: full.p(g, 0.3), re.escape("(at index (9001,))"))
    raises(ValueError, lambda: full.p(g.reshape(200, 200), 0.3), re.escape("(at index (45, 1))"))
    raises(ValueError, lambda: oblique.regime(g, 0.3), re.escape("(at index (9001,))"))
    raises(ValueError, lambda: full.curve(1.5).p(-1.0 - g), re.escape("(at index (0,))"))
    v = np.tile([1.0, 0.0, 1.0], (40_000, 1))
    v[[30_000, 12_345], 2] = -1.0
    raises(ValueError, lambda: full.rebound(S, v, friction=0.3, gamma=1.5),
           r"v_z", r"approach", re.escape("(at index (12345,))"))
    m = np.full(40_000, 0.1)
    m[[39_999, 8_200]] = -1.0
    raises(ValueError, lambda: full.rebound(Sphere(m, 0.01), v[:1], friction=0.3, gamma=1.5),
           r"mass", re.escape("(at index (8200,))"))


# ---------------------------------------------------------------------------------------------
# Bodies, materials, friction, motion


def _wall(full, **kw):
    args = dict(sphere=S, velocity=(1.0, 0.0, 2.0), friction=0.3, materials=(STEEL, RIGID))
    args.update(kw)
    return lambda: full.rebound(args.pop("sphere"), args.pop("velocity"), **args)


def _pair(full, **kw):
    args = dict(sphere=S, velocity=(1.0, 0.0, 2.0), friction=0.3, materials=(STEEL, STEEL),
                other=Sphere(0.2, 0.02))
    args.update(kw)
    return lambda: full.rebound(args.pop("sphere"), args.pop("velocity"), **args)


POSITIVE = r"finite number > 0"


@pytest.mark.parametrize("bad", [-0.1, 0.0, NAN, INF])
def test_bad_body(full, bad):
    # A Sphere is refused where it is made, naming the field (and the index in an array).
    raises(ValueError, lambda: Sphere(bad, 0.01), r"^Sphere: invalid mass\b", POSITIVE)
    raises(ValueError, lambda: Sphere(0.1, bad), r"^Sphere: invalid radius\b", POSITIVE)
    raises(ValueError, lambda: Sphere(0.1, 0.01, bad), r"^Sphere: invalid kappa\b", POSITIVE)
    raises(ValueError, lambda: Sphere(0.1, 0.01, kappa=bad), r"^Sphere: invalid kappa\b")
    arr = np.array([0.1, 0.1, bad])
    raises(ValueError, lambda: Sphere(0.1, 0.01, arr), r"^Sphere: invalid kappa\b", POSITIVE,
           re.escape("(at index (2,))"))
    # A plain tuple in its place is refused where it is used, naming the argument.
    raises(ValueError, _wall(full, sphere=(bad, 0.01)), r"\bmass", POSITIVE)
    raises(ValueError, _wall(full, sphere=(0.1, bad)), r"\bradius", POSITIVE)
    raises(ValueError, _wall(full, sphere=(0.1, 0.01, bad)), r"\bkappa", POSITIVE)
    raises(ValueError, _pair(full, other=(bad, 0.01)), r"other[._ ]mass", POSITIVE)
    raises(ValueError, _pair(full, other=(0.1, bad)), r"other[._ ]radius", POSITIVE)
    raises(ValueError, _pair(full, other=(0.1, 0.01, bad)), r"other[._ ]kappa", POSITIVE)
    raises(ValueError, _wall(full, sphere=(arr, 0.01)), r"\bmass", POSITIVE,
           re.escape("(at index (2,))"))
    raises(ValueError, _pair(full, other=(0.1, 0.01, arr)), r"other[._ ]kappa",
           re.escape("(at index (2,))"))
    raises(ValueError, lambda: full.rebound_2d((bad, 0.01), 1.0, 1.0, friction=0.3,
                                               gamma=1.5), r"\bmass", POSITIVE)
    raises(ValueError, lambda: full.e_t(1.5, 0.3, kappa=bad), r"kappa", POSITIVE)
    raises(ValueError, lambda: full.e_t(1.5, 0.3, kappa=[0.4, bad]), r"kappa",
           re.escape("(at index (1,))"))


def test_bad_materials(full):
    nu_range = re.escape("(-1, 0.5]")
    for nu in (0.5000001, 0.7, -1.0, -2.0, NAN, INF):
        raises(ValueError, _wall(full, materials=(Material(1e9, nu), RIGID)), r"poisson_ratio",
               nu_range)
        raises(ValueError, _pair(full, materials=(STEEL, Material(1e9, nu))), r"poisson_ratio",
               nu_range)
    for e in (0.0, -1e9, NAN, -INF):
        raises(ValueError, _wall(full, materials=(Material(e, 0.3), RIGID)), r"youngs_modulus",
               r"> 0")
        raises(ValueError, _pair(full, materials=(STEEL, Material(e, 0.3))), r"youngs_modulus",
               r"> 0")
    raises(ValueError, _wall(full, materials=(RIGID, RIGID)), r"youngs_modulus", r"rigid")
    raises(ValueError, _pair(full, materials=(RIGID, Material(INF, 0.2))), r"youngs_modulus")
    raises(ValueError, _wall(full, materials=(Material([1e9, 1e9, -1.0], 0.3), RIGID)),
           r"youngs_modulus", re.escape("(at index (2,))"))
    # Either limit of ν is fine: 0.5 (incompressible) and just above −1.
    _wall(full, materials=(Material(1e9, 0.5), RIGID))()
    _wall(full, materials=(Material(1e9, -0.999), RIGID))()
    # groups and simulate check the same.
    raises(ValueError, lambda: oblique.groups(S, 1.0, 1.0, friction=0.3,
                                              materials=(Material(1e9, 0.7), RIGID)),
           r"poisson_ratio")
    raises(ValueError, lambda: oblique.simulate(S, 1.0, 1.0, friction=0.3,
                                                materials=(RIGID, RIGID)), r"youngs_modulus")


@pytest.mark.parametrize("mu", [-0.1, -INF, NAN])
def test_bad_friction(full, mu):
    raises(ValueError, _wall(full, friction=mu), r"friction", r">= 0")
    raises(ValueError, _wall(full, friction=[0.3, 0.3, mu]), r"friction",
           re.escape("(at index (2,))"))
    raises(ValueError, lambda: full.rebound_2d(S, 1.0, 1.0, friction=mu, gamma=1.5),
           r"friction", r">= 0")
    raises(ValueError, lambda: oblique.groups(S, 1.0, 1.0, friction=mu,
                                              materials=(STEEL, RIGID)), r"friction")


def test_not_approaching(full):
    approach = r"v_z.*approach"
    for vz in (0.0, -1.0, -1e-300):
        raises(ValueError, _wall(full, velocity=(1.0, 0.0, vz)), approach)
        raises(ValueError, lambda: full.rebound_2d(S, 1.0, vz, friction=0.3, gamma=1.5),
               approach)
    # Sphere on sphere: the relative velocity along n counts.
    raises(ValueError, _pair(full, velocity=(0.0, 0.0, 1.0), other_velocity=(0.0, 0.0, 1.0)),
           approach)
    raises(ValueError, _pair(full, velocity=(0.0, 0.0, 1.0), other_velocity=(5.0, 0.0, 2.0)),
           approach)
    # The normal sets the direction.
    raises(ValueError, _wall(full, velocity=(1.0, 0.0, 2.0), normal=(0.0, 0.0, -1.0)), approach)
    raises(ValueError, _wall(full, velocity=[(1.0, 0.0, 2.0)] * 3 + [(1.0, 0.0, -2.0)]),
           approach, re.escape("(at index (3,))"))
    raises(ValueError, lambda: oblique.simulate(S, 1.0, -1.0, friction=0.3,
                                                materials=(STEEL, RIGID)), approach)


def test_bad_normal_and_non_finite_motion(full):
    raises(ValueError, _wall(full, normal=(0.0, 0.0, 0.0)), r"normal", r"non-zero")
    raises(ValueError, _wall(full, normal=[(0.0, 0.0, 1.0), (0.0, 0.0, 0.0)]), r"normal",
           re.escape("(at index (1,))"))
    for bad in (NAN, INF, -INF):
        raises(ValueError, _wall(full, velocity=(bad, 0.0, 2.0)), r"velocity", r"finite")
        raises(ValueError, _wall(full, velocity=(1.0, 0.0, bad)), r"velocity", r"finite")
        raises(ValueError, _wall(full, spin=(0.0, bad, 0.0)), r"spin", r"finite")
        raises(ValueError, _wall(full, normal=(0.0, bad, 1.0)), r"normal", r"finite")
        raises(ValueError, _pair(full, other_velocity=(bad, 0.0, 0.0)), r"other[._ ]velocity",
               r"finite")
        raises(ValueError, _pair(full, other_spin=(bad, 0.0, 0.0)), r"other[._ ]spin", r"finite")
        raises(ValueError, lambda: full.rebound_2d(S, bad, 1.0, friction=0.3, gamma=1.5),
               r"v_x", r"finite")
        raises(ValueError, lambda: full.rebound_2d(S, 1.0, 1.0, bad, friction=0.3, gamma=1.5),
               r"omega", r"finite")


def test_wall_with_moving_other(full):
    """A wall does not move: other_velocity / other_spin must be zero."""
    raises(ValueError, _wall(full, other_velocity=(0.0, 0.0, 1.0)), r"other[._ ]velocity",
           r"zero")
    raises(ValueError, _wall(full, other_velocity=(0.5, 0.0, 0.0)), r"other[._ ]velocity",
           r"zero")
    raises(ValueError, lambda: full.rebound_2d(S, 1.0, 1.0, friction=0.3, gamma=1.5,
                                               other_v_x=0.5), r"other[._ ]v_x", r"zero")
    for kw in (dict(other_spin=(0.0, 2.0, 0.0)), dict(other_velocity=[(0, 0, 0), (0, 0, 1.0)])):
        with pytest.raises(ValueError):
            _wall(full, **kw)()
    for kw in (dict(other_omega=2.0), dict(other_v_z=-2.0)):
        with pytest.raises(ValueError):
            full.rebound_2d(S, 1.0, 1.0, friction=0.3, gamma=1.5, **kw)


def test_wall_with_moving_other_names_the_offending_value(full):
    """The message names the value given ("its value"): for other_velocity = (0, 0, 1) that is
    the 1 (or the vector), not one of the zero components."""
    msg = raises(ValueError, _wall(full, other_velocity=(0.0, 0.0, 1.0)))
    assert re.search(r"=\s*\(?[^:]*\b1(\.0)?\b", msg.split("must")[0]), msg


def test_wall_with_moving_other_names_the_offending_argument(full):
    """The message names the argument that is not zero: other_spin / other_omega / other_v_z,
    not other_velocity / other_v_x."""
    raises(ValueError, _wall(full, other_spin=(0.0, 2.0, 0.0)), r"other[._ ]spin", r"zero")
    raises(ValueError, lambda: full.rebound_2d(S, 1.0, 1.0, friction=0.3, gamma=1.5,
                                               other_omega=2.0), r"other[._ ]omega", r"zero")
    raises(ValueError, lambda: full.rebound_2d(S, 1.0, 1.0, friction=0.3, gamma=1.5,
                                               other_v_z=-2.0), r"other[._ ]v_z", r"zero")


# ---------------------------------------------------------------------------------------------
# Shapes and types


def test_vector_shapes(full):
    for bad in [(1.0, 2.0), (1.0, 2.0, 3.0, 4.0), 1.0, np.ones((2, 4)), np.ones((3, 2))]:
        raises(ValueError, _wall(full, velocity=bad), r"velocity", re.escape("(..., 3)"))
        raises(ValueError, _wall(full, spin=bad), r"spin", re.escape("(..., 3)"))
        raises(ValueError, _wall(full, normal=bad), r"normal", re.escape("(..., 3)"))
        raises(ValueError, _pair(full, other_velocity=bad), r"other_velocity")
        raises(ValueError, _pair(full, other_spin=bad), r"other_spin")


def test_shapes_that_do_not_broadcast(full):
    raises(ValueError, lambda: full.p(np.ones(3), np.ones(4)), r"broadcast",
           re.escape("gamma (3,)"), re.escape("alpha (4,)"))
    raises(ValueError, lambda: full.e_t(1.5, np.ones(4), kappa=np.ones(3)),
           re.escape("alpha (4,)"), re.escape("kappa (3,)"))
    raises(ValueError, lambda: oblique.regime(np.ones((2, 3)), np.ones(2)),
           re.escape("gamma (2, 3)"), re.escape("alpha (2,)"))
    raises(ValueError, lambda: oblique.impact(np.ones(3), np.ones(2)), re.escape("gamma (3,)"))
    raises(ValueError, _wall(full, velocity=np.ones((4, 3)), spin=np.ones((5, 3))),
           r"broadcast", re.escape("velocity (4,)"), re.escape("spin (5,)"))
    raises(ValueError, _wall(full, velocity=np.ones((4, 3)), friction=np.ones(3)),
           re.escape("velocity (4,)"), re.escape("friction (3,)"))
    raises(ValueError, _wall(full, velocity=np.ones((4, 3)), sphere=Sphere(np.ones(2), 0.01)),
           re.escape("velocity (4,)"), re.escape("mass (2,)"))
    raises(ValueError, lambda: full.rebound_2d(S, np.ones(2), np.ones(3), friction=0.3,
                                               gamma=1.5),
           re.escape("v_x (2,)"), re.escape("v_z (3,)"))
    raises(ValueError, lambda: oblique.simulate(S, [1.0, 2.0], 1.0, friction=0.3,
                                                materials=(STEEL, RIGID)), r"scalar")


BAD_DTYPES = {
    "complex": np.array([1.5 + 0.5j]),
    "str": np.array(["1.5"]),
    "object": np.array([1.5], dtype=object),
    "bool": np.array([True]),
    "python complex": 1.5 + 0j,
    "python bool": True,
    "python str": "1.5",
    # A mask would be dropped by np.asarray: the masked entries computed as numbers.
    "masked": np.ma.masked_array([1.5], mask=[True]),
    "masked, none masked": np.ma.masked_array([1.5], mask=[False]),
}


@pytest.mark.parametrize("kind", list(BAD_DTYPES))
def test_bad_dtypes(full, kind):
    x = BAD_DTYPES[kind]
    v = x if np.ndim(x) == 0 else np.repeat(x, 3)
    raises(TypeError, lambda: full.p(x, 0.3), r"\bgamma\b")
    raises(TypeError, lambda: full.p(1.5, x), r"\balpha\b")
    raises(TypeError, lambda: full.e_t(1.5, 0.3, kappa=x), r"\bkappa\b")
    raises(TypeError, lambda: full.curve(1.5).p(x), r"\balpha\b")
    raises(TypeError, lambda: oblique.regime(x, 0.3), r"\bgamma\b")
    raises(TypeError, lambda: oblique.critical(x), r"\bgamma\b")
    raises(TypeError, lambda: oblique.impact(1.5, x), r"\balpha\b")
    raises(TypeError, _wall(full, friction=x), r"\bfriction\b")
    raises(TypeError, lambda: Sphere(x, 0.01), r"\bmass\b")
    raises(TypeError, lambda: Sphere(0.1, x), r"\bradius\b")
    raises(TypeError, _wall(full, sphere=(x, 0.01)), r"\bmass\b")
    raises(TypeError, _wall(full, sphere=(0.1, x)), r"\bradius\b")
    raises(TypeError, _wall(full, materials=(Material(x, 0.3), RIGID)), r"youngs_modulus")
    raises(TypeError, _wall(full, materials=(Material(1e9, x), RIGID)), r"poisson_ratio")
    raises(TypeError, _wall(full, materials=None, gamma=x), r"\bgamma\b")
    raises(TypeError, _wall(full, velocity=v), r"\bvelocity\b")
    raises(TypeError, lambda: full.rebound_2d(S, x, 1.0, friction=0.3, gamma=1.5), r"\bv_x\b")
    raises(TypeError, lambda: oblique.groups(S, 1.0, x, friction=0.3, materials=(STEEL, RIGID)),
           r"\bv_z\b")


def test_materials_and_gamma_both_or_neither(full):
    msg = r"materials.*gamma"
    raises(TypeError, _wall(full, materials=(STEEL, RIGID), gamma=1.5), msg)
    raises(TypeError, _wall(full, materials=None), msg)
    raises(TypeError, lambda: full.rebound_2d(S, 1.0, 1.0, friction=0.3), msg)
    raises(TypeError, lambda: full.rebound_2d(S, 1.0, 1.0, friction=0.3, gamma=1.5,
                                              materials=(STEEL, RIGID)), msg)
    raises(TypeError, _wall(full, materials=STEEL), r"materials")
    raises(TypeError, _wall(full, sphere="a sphere"), r"sphere")


# ---------------------------------------------------------------------------------------------
# Table files


def _damaged(tmp_path, table_paths):
    data = table_paths["full"].read_bytes()
    files = {}
    files["truncated"] = tmp_path / "truncated.h5"
    files["truncated"].write_bytes(data[: len(data) // 2])
    # Truncated, with the integrity seal removed: HDF5 itself must refuse it.
    unsealed = bytearray(data[: len(data) // 2])
    unsealed[:8] = bytes(8)
    files["truncated-unsealed"] = tmp_path / "truncated_unsealed.h5"
    files["truncated-unsealed"].write_bytes(bytes(unsealed))
    flipped = bytearray(data)
    flipped[len(flipped) // 2] ^= 0xFF
    files["one byte changed"] = tmp_path / "flipped.h5"
    files["one byte changed"].write_bytes(bytes(flipped))
    files["random"] = tmp_path / "random.h5"
    files["random"].write_bytes(np.random.default_rng(71).bytes(100_000))
    files["empty"] = tmp_path / "empty.h5"
    files["empty"].write_bytes(b"")
    files["text"] = tmp_path / "text.h5"
    files["text"].write_text("gamma,alpha\n1.5,0.3\n" * 100)
    return files


def test_damaged_tables(tmp_path, table_paths):
    assert issubclass(oblique.TableError, OSError)
    for kind, path in _damaged(tmp_path, table_paths).items():
        with pytest.raises(oblique.TableError) as info:
            oblique.Table(path)
        assert isinstance(info.value, OSError)
        assert path.name in str(info.value), (kind, str(info.value))
    with pytest.raises(FileNotFoundError):
        oblique.Table(tmp_path / "no-such-table.h5")
    with pytest.raises(IsADirectoryError):
        oblique.Table(tmp_path)
    # str and os.PathLike both work, and the package still answers afterwards.
    t = oblique.Table(str(table_paths["full"]))
    assert t.p(1.5, 0.0) == 1.0


def test_damaged_tables_do_not_crash_the_interpreter(tmp_path, table_paths):
    files = _damaged(tmp_path, table_paths)
    files["missing"] = tmp_path / "missing.h5"
    files["directory"] = tmp_path
    script = textwrap.dedent(
        """
        import sys, oblique
        for path in sys.argv[1:]:
            try:
                oblique.Table(path)
            except oblique.TableError:
                print("TableError")
            except FileNotFoundError:
                print("FileNotFoundError")
            except IsADirectoryError:
                print("IsADirectoryError")
            else:
                print("loaded")
        t = oblique.Table(%r)
        print("still answers", t.p(1.5, 0.0))
        """
        % str(table_paths["full"])
    )
    names = list(files)
    r = subprocess.run(
        [sys.executable, "-c", script, *[os.fspath(files[n]) for n in names]],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert r.returncode == 0, f"exit {r.returncode}: {r.stderr[-2000:]}"
    lines = r.stdout.splitlines()
    want = ["TableError"] * (len(names) - 2) + ["FileNotFoundError", "IsADirectoryError"]
    assert lines[:-1] == want, r.stdout
    assert lines[-1] == "still answers 1.0"


def test_a_fifo_or_device_is_refused_without_blocking(tmp_path):
    # Opening a FIFO for reading blocks until a writer comes: run in a child with a timeout.
    fifo = tmp_path / "fifo"
    os.mkfifo(fifo)
    for target in (str(fifo), "/dev/zero"):
        r = subprocess.run(
            [sys.executable, "-c",
             "import sys, oblique\n"
             "try:\n    oblique.Table(sys.argv[1])\n"
             "except oblique.TableError as e:\n    print('refused:', e)\n",
             target],
            capture_output=True, text=True, timeout=60,
        )
        assert r.returncode == 0, r.stderr
        assert "refused:" in r.stdout and target in r.stdout, r.stdout


def test_masked_arrays_are_refused_naming_the_argument(full):
    m = np.ma.masked_array([1.5, 2.0], mask=[False, True])
    raises(TypeError, lambda: full.p(m, 0.3), r"\bgamma\b", "masked")
    raises(TypeError, lambda: full.p([1.5, 2.0], np.ma.masked_array([0.3, 0.4])), r"\balpha\b",
           "masked")
    raises(TypeError, lambda: oblique.critical(np.ma.masked), r"\bgamma\b", "masked")
    out = np.ma.masked_array(np.zeros(2), mask=[False, True])
    raises(TypeError, lambda: full.p([1.5, 2.0], 0.3, out=out), r"\bout\b", "masked")
    assert np.all(out.data == 0.0)
    # The unmasked values, as the message says, are answered.
    assert full.p(m.compressed(), 0.3) == full.p(1.5, 0.3)
