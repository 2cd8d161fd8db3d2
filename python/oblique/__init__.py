"""Oblique impacts of spheres with friction, elastic and viscoelastic: the tangential
restitution P(γ, α, e_n), rebounds, tables and the MDR impact solver, from NumPy.

A sphere hits a wall or another sphere, elastically (normal restitution e_n = 1) or, with a
table built with an e_n range, dissipatively (e_n < 1), with Coulomb friction μ. What happens
tangentially depends on two numbers besides e_n (see ``physics.md``):

- ``γ = √((m*/m_t) G*/E*)``, the elastic group (``√((7/2) G*/E*)`` for a solid sphere on a wall);
- ``α = (2/7)(m*/m_t) μ v_z0/|u0|``, the friction group (``μ v_z0/|u0|`` for a solid sphere on a
  wall), with ``v_z0`` the approach speed and ``u0`` the incident slip of the contact point;

and the answer is ``P = u_after/u_before``, the tangential restitution of the contact point.

- :class:`Table` answers ``P`` from a table written by ``sweep run`` (``tables/full.h5``, elastic,
  ``tables/dissipative-demo.h5``, with an e_n axis, and ``tables/dissipative-pair.h5``, the
  table of one pair at its :attr:`Table.pair_gamma`, ship with the project), with the error
  bound the table states, in nanoseconds per point; and rebounds (:meth:`Table.rebound`,
  :meth:`Table.rebound_2d`) in SI units.
- :data:`materials` is the material catalogue (E, ν, density, the source of the values):
  ``materials=(oblique.materials["alumina-96"], oblique.materials["soda-lime-glass"])``.
- :func:`impact` simulates ``P(γ, α)`` directly to a tolerance; :func:`simulate` simulates one
  impact in physical units; :func:`groups` gives ``γ`` and ``α`` of an impact;
  :func:`critical` the critical friction groups ``α_c1``, ``α_c2``; :func:`regime` the regime.
- :func:`build_table` builds a table from a config (a TOML file or a dict), as ``sweep run``
  does: a table of your own pair of materials in seconds.

Every function takes NumPy arrays or scalars and broadcasts them by NumPy's rules; arrays are
converted to float64 (integers are accepted; complex, strings, objects, booleans and masked
arrays, whose mask would be lost, are not).
Invalid values raise ``ValueError`` naming the argument, its value, the allowed range and, for
arrays, the index; a file that is not a valid table raises :class:`TableError`.
"""

from __future__ import annotations

import errno
import math
import numbers
import os
import re
import stat
import sys
import time
from collections.abc import Iterator, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable, List, NamedTuple, Optional, Sequence, Tuple, Union, overload

import numpy as np
from numpy.typing import ArrayLike, NDArray

from . import _native
from ._native import TableError

__all__ = [
    "Table",
    "Curve",
    "TableError",
    "Material",
    "CatalogueMaterial",
    "Sphere",
    "RIGID",
    "materials",
    "Rebound",
    "Rebound2D",
    "Groups",
    "Impact",
    "Simulation",
    "impact",
    "simulate",
    "groups",
    "critical",
    "regime",
    "build_table",
    "BuildProgress",
    "REGIMES",
    "EMBEDDED_TABLE",
]

__version__: str = _native.VERSION

#: The table built into the package, opened by ``Table()`` without a path (as the repository
#: names it: the Kelvin–Voigt law, 1.3 ≤ γ ≤ 2.2, 0.3 ≤ e_n ≤ 1).
EMBEDDED_TABLE: str = _native.EMBEDDED_TABLE

#: Names of the friction regimes, indexed by the codes the native layer returns.
REGIMES: Tuple[str, str, str] = ("full-slip", "partial-slip", "stick")
_REGIME_NAMES = np.array(REGIMES)

#: A result that is a ``float`` for scalar arguments and an ``NDArray[np.float64]`` of the
#: broadcast shape otherwise (typed ``Any`` so that both uses check without narrowing).
Float = Any


class Material(NamedTuple):
    """Elastic constants of an isotropic material (either may be an array)."""

    youngs_modulus: ArrayLike
    """Young's modulus E (Pa), > 0; ``math.inf`` for a rigid body."""
    poisson_ratio: ArrayLike
    """Poisson's ratio ν, in (−1, 0.5]."""


#: A rigid body: E = ∞ (it adds no compliance; at most one of the two bodies).
RIGID = Material(math.inf, 0.0)


class CatalogueMaterial(Material):
    """An entry of :data:`materials`: a :class:`Material` (it unpacks, compares and is passed
    as one: ``(E, ν)``) that also carries its name, density and the source of its values.
    Read-only."""

    name: str = ""
    """The catalogue's name, e.g. ``"soda-lime-glass"``."""
    density: Optional[float] = None
    """Density ρ (kg/m³); ``None`` for the rigid body. Only :meth:`solid_sphere` uses it:
    impacts take masses (:class:`Sphere`)."""
    source: str = ""
    """Where the values come from (a citation)."""
    yield_stress: Optional[float] = None
    """Uniaxial yield stress Y (Pa) where a source gives one (the metals); ``None`` for brittle
    materials and polymers, which Thornton's elastic–perfectly plastic law does not describe."""
    limiting_pressure: Optional[float] = None
    """The limiting contact pressure ``p_y = 1.60 Y`` (Pa) of Thornton's law, the peak Hertz
    pressure at first yield (Johnson 1985, chapter 6): pass it as
    ``simulate(..., yield_pressure=)``; ``None`` without a yield stress."""
    yield_source: str = ""
    """Where the yield stress comes from, or why there is none."""

    def __setattr__(self, key: str, value: Any) -> None:
        raise AttributeError(f"catalogue entries are read-only (cannot set {key})")

    def solid_sphere(self, radius: float) -> "Sphere":
        """A solid sphere of this material: ``Sphere(mass=ρ (4/3)π R³, radius, kappa=0.4)``,
        ``radius`` R in m. ``ValueError`` when the density is not known (rigid)."""
        if self.density is None:
            raise ValueError(f"solid_sphere: {self.name} has no density (give Sphere(mass, ...))")
        r = float(radius)
        if not (math.isfinite(r) and r > 0.0):
            raise ValueError(f"invalid radius = {radius!r}: must be a finite number > 0 (m)")
        return Sphere(self.density * 4.0 / 3.0 * math.pi * r**3, r, 0.4)

    def __repr__(self) -> str:
        return (
            f"CatalogueMaterial({self.name!r}, youngs_modulus={self.youngs_modulus!r}, "
            f"poisson_ratio={self.poisson_ratio!r}, density={self.density!r})"
        )


def _entry(
    name: str,
    e: float,
    nu: float,
    density: Optional[float],
    source: str,
    yield_stress: Optional[float],
    limiting_pressure: Optional[float],
    yield_source: str,
) -> CatalogueMaterial:
    m = CatalogueMaterial(e, nu)
    for key, value in (
        ("name", name),
        ("density", density),
        ("source", source),
        ("yield_stress", yield_stress),
        ("limiting_pressure", limiting_pressure),
        ("yield_source", yield_source),
    ):
        object.__setattr__(m, key, value)
    return m


class _Catalogue(Mapping[str, CatalogueMaterial]):
    """The material catalogue: a read-only mapping from a name to its entry."""

    def __init__(
        self,
        rows: Sequence[
            Tuple[str, float, float, Optional[float], str, Optional[float], Optional[float], str]
        ],
    ) -> None:
        self._by_name = {row[0]: _entry(*row) for row in rows}

    def __getitem__(self, name: str) -> CatalogueMaterial:
        try:
            return self._by_name[name]
        except (KeyError, TypeError):
            raise KeyError(
                f"unknown material {name!r}: the catalogue has {', '.join(self._by_name)} "
                "(your own values: oblique.Material(youngs_modulus, poisson_ratio))"
            ) from None

    def __iter__(self) -> Iterator[str]:
        return iter(self._by_name)

    def __len__(self) -> int:
        return len(self._by_name)

    def __repr__(self) -> str:
        return f"<oblique.materials: {', '.join(self._by_name)}>"


#: The built-in material catalogue, a read-only mapping name → :class:`CatalogueMaterial` (a
#: :class:`Material` with ``name``, ``density`` in kg/m³, ``None`` for ``"rigid"``,
#: ``source``, the citation of the values, and for the metals ``yield_stress`` and Thornton's
#: ``limiting_pressure`` in Pa with ``yield_source``): the materials of scene files and ``sweep gamma``
#: (``docs/materials.md``). Nominal room-temperature, quasi-static values; the polymers' are a
#: first estimate.
materials: Mapping[str, CatalogueMaterial] = _Catalogue(_native.MATERIALS)


class _SphereFields(NamedTuple):
    mass: ArrayLike
    """Mass m (kg), > 0."""
    radius: ArrayLike
    """Radius R (m), > 0."""
    kappa: ArrayLike = 0.4
    """Inertia factor κ in I = κ m R² (0.4 a solid sphere, 2/3 a thin shell), > 0."""


class Sphere(_SphereFields):
    """Mass (kg), radius (m) and inertia factor κ (I = κ m R²; 0.4 a solid sphere, 2/3 a thin
    shell) of a sphere; each may be an array. Each must be a finite number > 0: anything else is
    refused here, with a ``ValueError`` naming the field (and the index in an array)."""

    __slots__ = ()

    def __new__(cls, mass: ArrayLike, radius: ArrayLike, kappa: ArrayLike = 0.4) -> "Sphere":
        for name, value in (("mass", mass), ("radius", radius), ("kappa", kappa)):
            a = _f64(value, f"Sphere {name}")
            bad = ~(np.isfinite(a) & (a > 0.0))
            if bad.any():
                at = tuple(int(i) for i in np.argwhere(bad)[0])
                where = f" (at index {at})" if a.ndim else ""
                raise ValueError(
                    f"Sphere: invalid {name} = {float(a[at])!r}: must be a finite number > 0"
                    f"{where}"
                )
        return super().__new__(cls, mass, radius, kappa)


# ---------------------------------------------------------------------------------------------
# Conversion and broadcasting


def _f64(x: Any, name: str) -> NDArray[np.float64]:
    """``x`` as a float64 array, refusing what is not a real number."""
    if isinstance(x, np.ma.MaskedArray):
        # np.asarray would drop the mask: the masked entries would be computed as numbers.
        raise TypeError(
            f"{name}: masked arrays are not accepted (their mask would be ignored); pass "
            "x.compressed() or x.filled(value)"
        )
    try:
        a = np.asarray(x)
    except Exception as e:  # ragged lists and the like
        raise TypeError(f"{name}: expected real numbers, got {type(x).__name__} ({e})") from None
    if a.dtype.kind not in "fiu":
        raise TypeError(
            f"{name}: expected real numbers (float or int), got dtype {a.dtype}"
            + (" (complex numbers are not accepted)" if a.dtype.kind == "c" else "")
        )
    return a.astype(np.float64, copy=False)


def _vector(x: Any, name: str) -> NDArray[np.float64]:
    a = _f64(x, name)
    if a.ndim == 0 or a.shape[-1] != 3:
        raise ValueError(f"{name}: expected shape (..., 3) (x, y, z components), got {a.shape}")
    return a


def _shape(args: Sequence[Tuple[str, Tuple[int, ...]]]) -> Tuple[int, ...]:
    """The broadcast shape of named shapes, or a ValueError naming them."""
    try:
        return tuple(np.broadcast_shapes(*(s for _, s in args)))
    except ValueError:
        listed = ", ".join(f"{n} {s}" for n, s in args)
        raise ValueError(f"shapes do not broadcast together: {listed}") from None


def _extra_axes(function: str, axes: dict) -> List[Tuple[str, Any]]:
    """The keyword arguments ``axes`` of ``function`` as ``(name, value)`` in the order of
    ``_native.EXTRA_AXES`` (the axes a table may have beyond γ and α), leaving out a scalar at
    the axis's fixed value (e_n = 1); a keyword of no axis is a ``TypeError`` naming them."""
    known = dict(_native.EXTRA_AXES)
    for name in axes:
        if name not in known:
            names = ", ".join(known)
            raise TypeError(
                f"{function}() got an unexpected keyword argument '{name}': the axes beyond "
                f"gamma and alpha are {names}"
            )
    return [
        (n, axes[n])
        for n in known
        if n in axes and not (type(axes[n]) in _NUMBER and axes[n] == known[n])
    ]


def _column(a: NDArray[np.float64], shape: Tuple[int, ...], width: int = 1) -> NDArray[np.float64]:
    """A contiguous 1-D column: the value(s) once when shared by every row, else one per row."""
    if a.size == width:
        return np.ascontiguousarray(a).reshape(-1)
    full = shape + ((width,) if width > 1 else ())
    return np.ascontiguousarray(np.broadcast_to(a, full)).reshape(-1)


def _full(a: NDArray[np.float64], shape: Tuple[int, ...]) -> NDArray[np.float64]:
    """A contiguous 1-D array of one value per element of ``shape``."""
    if a.shape == shape and a.flags.c_contiguous:
        return a.reshape(-1)
    return np.ascontiguousarray(np.broadcast_to(a, shape)).reshape(-1)


def _output(out: Optional[np.ndarray], shape: Tuple[int, ...]) -> np.ndarray:
    if out is None:
        return np.empty(shape, dtype=np.float64)
    if not isinstance(out, np.ndarray) or isinstance(out, np.ma.MaskedArray):
        raise TypeError(f"out: expected a numpy.ndarray (not masked), got {type(out).__name__}")
    if out.dtype != np.float64:
        raise TypeError(f"out: expected dtype float64, got {out.dtype}")
    if out.shape != shape:
        raise ValueError(f"out: expected shape {shape} (the broadcast shape), got {out.shape}")
    if not out.flags.writeable:
        raise ValueError("out: the array is read-only")
    return out


def _into(out: np.ndarray, fill: Any, *inputs: np.ndarray) -> None:
    """Call ``fill(flat)`` with a contiguous 1-D view of ``out``, or with a scratch array that
    is then copied into ``out`` when ``out`` is not contiguous or shares memory with one of the
    ``inputs`` (``out=`` may be an input, as in NumPy)."""
    if out.flags.c_contiguous and not any(np.may_share_memory(out, x) for x in inputs):
        fill(out.reshape(-1))
    else:
        scratch = np.empty(out.shape, dtype=np.float64)
        fill(scratch.reshape(-1))
        out[...] = scratch


def _result(out: np.ndarray, given: Optional[np.ndarray]) -> Float:
    if given is not None:
        return given
    return float(out) if out.ndim == 0 else out


#: Types answered by the scalar fast path (a plain Python number, no array made).
_NUMBER = (float, int)


def _stiffness(
    materials: Optional[Tuple[Material, Material]], gamma: Optional[ArrayLike], need: bool = False
) -> Tuple[Optional[NDArray[np.float64]], list]:
    if (materials is None) == (gamma is None):
        if need and gamma is not None:
            raise TypeError("materials: required here (gamma alone does not fix E* and G*)")
        raise TypeError("give exactly one of materials=(Material, Material) and gamma=")
    if gamma is not None:
        return _f64(gamma, "gamma"), []
    assert materials is not None
    try:
        (e1, n1), (e2, n2) = materials
    except (TypeError, ValueError):
        raise TypeError(
            "materials: expected a pair (sphere's Material, wall's or other sphere's Material)"
        ) from None
    names = ["youngs_modulus", "poisson_ratio", "other youngs_modulus", "other poisson_ratio"]
    return None, [_f64(x, n) for x, n in zip((e1, n1, e2, n2), names)]


def _body(s: Any, name: str) -> list:
    if not isinstance(s, Sphere):
        try:
            # Checked below with the argument's name (a tuple is not refused as a Sphere).
            s = _SphereFields(*s)
        except TypeError:
            raise TypeError(f"{name}: expected oblique.Sphere(mass, radius, kappa)") from None
    prefix = "" if name == "sphere" else "other "
    return [_f64(x, prefix + n) for x, n in zip(s, ("mass", "radius", "kappa"))]


# ---------------------------------------------------------------------------------------------
# Results


@dataclass(frozen=True)
class Rebound:
    """Outcome of 3-D impacts (:meth:`Table.rebound`), one entry per impact of the broadcast
    shape ``S``; vectors have shape ``S + (3,)``. SI units. The model has no torsional friction:
    spin about the normal, and velocity and spin across the plane of impact, pass unchanged."""

    velocity: NDArray[np.float64]
    """Velocity of sphere 1's centre after the impact (m/s)."""
    spin: NDArray[np.float64]
    """Angular velocity of sphere 1 after the impact (rad/s)."""
    other_velocity: Optional[NDArray[np.float64]]
    """Velocity of sphere 2 after (m/s); ``None`` for a wall."""
    other_spin: Optional[NDArray[np.float64]]
    """Angular velocity of sphere 2 after (rad/s); ``None`` for a wall."""
    gamma: Float
    """Elastic group γ used."""
    alpha: Float
    """Friction group α = (2/7)(m*/m_t) μ v_z0/|u0| (∞ when u0 = 0)."""
    p: Float
    """P = u_after/u_before from the table: the contact-point restitution (β of event-driven
    codes). NaN when u0 = 0 (nothing tangential happens)."""
    e_t: Float
    """Tangential restitution of the centres, (w_after · w_before)/|w_before|² with w the
    tangential part of v_1 − v_2 (v_x/v_x0 for a wall); NaN when w_before = 0."""
    slip_before: Float
    """|u0|, the incident slip speed of the contact point (m/s), along ``tangent``."""
    slip_after: Float
    """P |u0|, the slip after along ``tangent`` (m/s; negative when it reversed)."""
    tangential_impulse: Float
    """Friction impulse J on body 2 along +tangent (N s); body 1 receives −J."""
    normal_impulse: Float
    """Normal impulse (1 + e_n) m* v_z0 on body 2 along +normal (N s)."""
    e_n: Float
    """Normal restitution used (dimensionless; 1: elastic): the bodies separate at e_n v_z0."""
    approach_speed: Float
    """v_z0 = (v_1 − v_2)·n > 0 (m/s); the bodies separate at e_n v_z0."""
    centre_speed_before: Float
    """|w_before|, tangential speed of the relative centre velocity before (m/s)."""
    centre_speed_after: Float
    """|w_after| (m/s)."""
    energy_lost: Float
    """Kinetic energy lost, (m_t/2) u0² (1 − P²) + (m*/2) v_z0² (1 − e_n²) (J), ≥ 0: to friction
    (and tangential damping), and to normal damping (0 for e_n = 1)."""
    tangent: NDArray[np.float64]
    """Unit tangent t of the plane of impact: the direction of the incident slip u0."""
    incidence_angle: Float
    """Angle of the incident relative centre velocity from the normal (rad)."""
    rebound_angle_centre: Float
    """Angle of the relative centre velocity after, from the normal (rad), in [0, π/2]:
    atan2(|w_after|, e_n v_z0)."""
    rebound_angle_contact: Float
    """Angle of the contact-point velocity after, from the normal, in the plane of impact (rad),
    atan2(P |u0|, e_n v_z0): negative when the slip reversed."""

    @property
    def e_t_contact(self) -> Float:
        """Contact-point tangential restitution u_after/u_before: P itself."""
        return self.p


@dataclass(frozen=True)
class Rebound2D:
    """Outcome of impacts in the plane of impact (:meth:`Table.rebound_2d`). ``z`` is the normal
    from sphere 1 into the other body, ``x`` the tangent; a spin ω is signed so that sphere 1's
    contact point moves at v_x + R ω (sphere 2's at v_x − R ω). SI units."""

    v_x: Float
    """Tangential velocity of sphere 1 after (m/s)."""
    v_z: Float
    """Normal velocity of sphere 1 after (m/s)."""
    omega: Float
    """Spin of sphere 1 after (rad/s)."""
    other_v_x: Optional[Float]
    """Tangential velocity of sphere 2 after (m/s); ``None`` for a wall."""
    other_v_z: Optional[Float]
    """Normal velocity of sphere 2 after (m/s); ``None`` for a wall."""
    other_omega: Optional[Float]
    """Spin of sphere 2 after (rad/s); ``None`` for a wall."""
    gamma: Float
    """Elastic group γ used."""
    alpha: Float
    """Friction group α (∞ when u0 = 0)."""
    p: Float
    """P = u_after/u_before, the contact-point restitution (NaN when u0 = 0)."""
    e_t: Float
    """Tangential restitution of the centres, (v_1x − v_2x)_after/(v_1x − v_2x)_before
    (v_x/v_x0 for a wall); NaN when the incident relative v_x is 0."""
    slip_before: Float
    """Incident slip velocity u0 = (v_1x + R_1 ω_1) − (v_2x − R_2 ω_2) (m/s)."""
    slip_after: Float
    """P u0 (m/s)."""
    tangential_impulse: Float
    """Friction impulse J on body 2 along +x (N s); body 1 receives −J."""
    normal_impulse: Float
    """Normal impulse (1 + e_n) m* v_z0 on body 2 along +z (N s)."""
    e_n: Float
    """Normal restitution used (dimensionless; 1: elastic): the relative v_z after is
    −e_n v_z0."""
    incidence_angle: Float
    """atan2(v_x0,rel, v_z0) (rad)."""
    rebound_angle_centre: Float
    """atan2(v_x,rel after, e_n v_z0) (rad), positive on the side of +x."""
    rebound_angle_contact: Float
    """atan2(P u0, e_n v_z0) (rad): negative when the contact point's motion reversed."""
    energy_lost: Float
    """Kinetic energy lost, (m_t/2) u0² (1 − P²) + (m*/2) v_z0² (1 − e_n²) (J): to friction
    (and tangential damping), and to normal damping (0 for e_n = 1)."""

    @property
    def e_t_contact(self) -> Float:
        """Contact-point tangential restitution u_after/u_before: P itself."""
        return self.p


class Groups(NamedTuple):
    """Dimensionless groups of impacts and the effective quantities behind them (SI)."""

    gamma: Float
    """γ = √((m*/m_t) G*/E*)."""
    alpha: Float
    """α = (2/7)(m*/m_t) μ v_z0/|u0| (∞ when u0 = 0 or μ = ∞)."""
    e_star: Float
    """E* (Pa), 1/E* = Σ (1 − ν²)/E."""
    g_star: Float
    """G* (Pa), 1/G* = Σ (2 − ν)/(4G)."""
    normal_mass: Float
    """m* = m_1 m_2/(m_1 + m_2) (kg; m_1 for a wall)."""
    tangential_mass: Float
    """m_t, 1/m_t = Σ (1/m + R²/I) (kg)."""
    radius: Float
    """R* = R_1 R_2/(R_1 + R_2) (m; R_1 for a wall)."""
    approach_speed: Float
    """v_z0 (m/s)."""
    slip_velocity: Float
    """u0 (m/s)."""


class Impact(NamedTuple):
    """``P(γ, α, e_n)`` simulated (:func:`impact`)."""

    p: Float
    """P = u_after/u_before."""
    error_estimate: Float
    """Estimated absolute error of P (0 for the closed forms), ≤ tol."""
    closed_form: Union[bool, NDArray[np.bool_]]
    """Whether P came from an exact closed form (nothing simulated)."""
    springs: Union[int, NDArray[np.int64]]
    """Springs on the half-row of the finest run (0: closed form or the continuum row)."""
    steps: Union[int, NDArray[np.int64]]
    """Time steps per contact of the finest run (0 for closed forms)."""
    e_n: Float
    """Normal restitution of the impact (1: elastic)."""
    tau: Float
    """Dimensionless relaxation time τ̂ of the Kelvin–Voigt law that gives ``e_n`` (0 for the
    other laws), in units of (m*/k)^(2/5) v_z0^(-1/5) (4/3)^(2/5), k = (4/3) E* √R*."""
    yield_pressure: Float
    """Dimensionless limiting pressure p̂_y of Thornton's law that gives ``e_n`` (0 for the
    other laws): p_y in units of E* (m* v_z0²/(E* R*³))^(1/5), the unit in which the elastic
    impact's peak pressure is p_0 = (2/π)(15/16)^(1/5) ≈ 0.6285 (p̂_y = p_0 at e_n = 1)."""


@dataclass(frozen=True)
class Simulation:
    """One impact simulated in physical units (:func:`simulate`). SI units; 2-D conventions as
    in :class:`Rebound2D`."""

    v_x: float
    """Tangential velocity of sphere 1 after (m/s)."""
    v_z: float
    """Normal velocity of sphere 1 after (m/s): the relative normal velocity reverses with
    ``e_n``."""
    omega: float
    """Spin of sphere 1 after (rad/s)."""
    other_v_x: Optional[float]
    """Tangential velocity of sphere 2 after (m/s); ``None`` for a wall."""
    other_v_z: Optional[float]
    """Normal velocity of sphere 2 after (m/s); ``None`` for a wall."""
    other_omega: Optional[float]
    """Spin of sphere 2 after (rad/s); ``None`` for a wall."""
    p: float
    """P = u_after/u0 (NaN when u0 = 0)."""
    error_estimate: float
    """Estimated absolute error of P, ≤ tol (0 when u0 = 0)."""
    contact_time: float
    """Measured contact time (s)."""
    peak_force: float
    """Measured peak normal force (N)."""
    max_indentation: float
    """Measured maximum indentation (m)."""
    e_n: float
    """Normal restitution of the impact (1 for elastic bodies, and for Thornton's bodies at
    or below their yield speed)."""
    law: str
    """The bodies' contact law: ``"elastic"``, ``"kelvin-voigt"`` or ``"thornton"``."""
    tau: float
    """Dimensionless relaxation time τ̂ of the impact (0 for the other laws): that of
    :func:`impact` at the same ``e_n``."""
    yield_pressure: float
    """Dimensionless limiting pressure p̂_y of the impact (0 for the other laws): the
    argument ``yield_pressure`` p_y (Pa) in units of E* (m* v_z0²/(E* R*³))^(1/5), that of
    :func:`impact` with ``law="thornton"`` at the same ``e_n``; p_0 = (2/π)(15/16)^(1/5) at
    or below the yield speed, where the impact is elastic."""
    springs: int
    """Springs on the half-row of the finest run (0: the continuum row)."""
    steps: int
    """Time steps per contact of the finest run."""
    groups: Groups
    """γ, α and the effective quantities of the impact."""


def _views(raw: np.ndarray, shape: Tuple[int, ...], names: Sequence[str]) -> dict:
    cols = raw.reshape(shape + (len(names),))
    return {n: cols[..., k] if shape else float(cols[k]) for k, n in enumerate(names)}


def _vec(raw: np.ndarray, shape: Tuple[int, ...], names: Sequence[str], prefix: str) -> Any:
    """The vector ``prefix`` (columns ``prefix_x``, ``_y``, ``_z``, adjacent): a view."""
    k = list(names).index(prefix + "_x")
    return raw.reshape(shape + (len(names),))[..., k : k + 3]


# ---------------------------------------------------------------------------------------------
# The table


class Curve:
    """``P(α)`` at one fixed γ (:meth:`Table.curve`): the same values as :meth:`Table.p` to about
    2e-15, with fewer operations per query. For codes that meet one pair of materials many
    times."""

    __slots__ = ("_c",)

    def __init__(self, native: Any) -> None:
        self._c = native

    @property
    def gamma(self) -> float:
        """γ the curve answers (the requested γ, clamped into the domain if asked)."""
        return self._c.gamma

    @property
    def requested_gamma(self) -> float:
        """γ asked for."""
        return self._c.requested_gamma

    @property
    def nbytes(self) -> int:
        """Memory the curve holds (bytes)."""
        return self._c.nbytes

    @overload
    def p(self, alpha: float, out: None = None) -> float: ...
    @overload
    def p(self, alpha: ArrayLike, out: Optional[np.ndarray] = None) -> NDArray[np.float64]: ...
    def p(self, alpha: ArrayLike, out: Optional[np.ndarray] = None) -> Float:
        """P(γ, α) for α ≥ 0 (``inf``: no slip), any shape."""
        if out is None and type(alpha) in _NUMBER:
            return self._c.p(alpha)  # type: ignore[arg-type]  # checked above
        a = _f64(alpha, "alpha")
        shape = a.shape
        o = _output(out, shape)
        flat = _full(a, shape)
        _into(o, lambda f: self._c.p_into(flat, f, list(shape)), flat)
        return _result(o, out)

    def __repr__(self) -> str:
        return f"<oblique.Curve gamma={self.gamma!r}, {self.nbytes} bytes>"


class Table:
    """A table of P(γ, α) written by ``sweep run`` (HDF5), loaded into memory and checked; of
    P(γ, α, e_n) for a table built with an e_n range (schema 4, ``e_n_min`` of :attr:`info` < 1); of
    P(α, e_n) at a single γ for the table of one pair of materials (:attr:`pair_gamma`; such a
    table answers that γ only, within a relative 1e-9, and the full-slip line at any γ).

    ``clamp=False`` (the default) refuses a γ or α outside the table's domain (:attr:`info`)
    with ``ValueError``; ``clamp=True`` answers there at the nearest point of the domain (an
    extrapolation by a constant; the error it makes is yours). The full-slip line
    ``P = 1 − 7α`` (α up to α_c1 for γ > 1, α_c2 for γ ≤ 1) is exact and answered for any γ > 0.

    ``path``: a ``str``, ``bytes`` or ``os.PathLike`` (``pathlib.Path``); ``None`` (the
    default, ``oblique.Table()``) opens the table built into the package,
    :data:`EMBEDDED_TABLE` (``tables/default.h5``: the Kelvin–Voigt law, 1.3 ≤ γ ≤ 2.2, α
    from 0 to ∞, 0.3 ≤ e_n ≤ 1, stated error bound 8.1e-6; every body of the material
    catalogue, solid spheres, thin shells and pairs of them); give ``tables/full.h5`` of the
    repository for 0.1 ≤ γ ≤ 3.5 at e_n = 1.

    Immutable; one table may be used by many threads. Raises ``FileNotFoundError`` (and the other
    ``OSError`` subclasses) when the file cannot be opened, :class:`TableError` when it is not a
    valid table.
    """

    __slots__ = ("_t", "_clamp", "_info")

    def __init__(
        self, path: Optional[Union[str, bytes, os.PathLike]] = None, clamp: bool = False
    ) -> None:
        self._clamp = bool(clamp)
        self._info: Optional[dict] = None
        if path is None:
            self._t = _native.Table.embedded()
            return
        path = os.fspath(path)
        if isinstance(path, bytes):
            path = os.fsdecode(path)
        # The operating system's own error for a path that cannot be read (FileNotFoundError,
        # IsADirectoryError, PermissionError), before the format is looked at; a FIFO, device
        # or socket is refused without opening it (opening a FIFO blocks until a writer comes).
        mode = os.stat(path).st_mode
        if stat.S_ISDIR(mode):
            raise IsADirectoryError(errno.EISDIR, os.strerror(errno.EISDIR), path)
        if not stat.S_ISREG(mode):
            kind = (
                "a FIFO (named pipe)"
                if stat.S_ISFIFO(mode)
                else "a device"
                if stat.S_ISCHR(mode) or stat.S_ISBLK(mode)
                else "not a regular file"
            )
            raise TableError(f"{path}: {kind}, not a table file; give the path of a table")
        with open(path, "rb"):
            pass
        self._t = _native.Table(path)

    @property
    def clamp(self) -> bool:
        """Whether points outside the domain are answered at its nearest point."""
        return self._clamp

    @property
    def info(self) -> dict:
        """Domain (``gamma_min``, ``gamma_max``, ``alpha_max``, and ``e_n_min``, ``e_n_max``:
        both 1 for an elastic table; ``pair_gamma``, the γ of the table of one pair, else
        ``None``; ``axes``, the names of the table's axes; ``e_n_coordinate``, how its ``e_n``
        axis maps to the coordinate, ``"e_n"`` or ``"(1-e_n)^(1/4)"``, ``None`` for an elastic
        table), the contact ``law``, the stated
        ``error_bound`` (the
        largest absolute error of any P the table answers), the held-out checks (``checks``,
        ``checks_max_error``) and the provenance (``schema_version``, ``engine_version``,
        ``git_commit``, ``created``, ``config``, ``solver``, ``node_tol``, ``check_tol``,
        ``target_error``, ``wall_time_s``, ``path``)."""
        if self._info is None:
            self._info = self._t.info()
        return dict(self._info)

    @property
    def error_bound(self) -> float:
        """The absolute error bound the table states for every P it answers."""
        return self.info["error_bound"]

    @property
    def pair_gamma(self) -> Optional[float]:
        """The single γ of the table of one pair of materials (axes α, e_n; built with
        ``domain.gamma``), ``None`` for a table over a range of γ. Such a table answers this γ
        (a γ within a relative 1e-9 of it is taken as it) and refuses any other with
        ``ValueError`` naming both (except on the full-slip line, exact at any γ)."""
        g = self.info["pair_gamma"]
        return None if g is None else float(g)

    @property
    def axes(self) -> Tuple[str, ...]:
        """The names of the axes of a point of this table, in order: ``("gamma", "alpha")``,
        then its extra axes (``"e_n"`` for a table built with an e_n range). :meth:`p` takes
        every extra axis as a keyword argument of that name."""
        return tuple(self._t.axes())

    @overload
    def p(
        self, gamma: float, alpha: float, out: None = None, *, e_n: float = 1.0, **axes: float
    ) -> float: ...
    @overload
    def p(
        self,
        gamma: ArrayLike,
        alpha: ArrayLike,
        out: Optional[np.ndarray] = None,
        *,
        e_n: ArrayLike = 1.0,
        **axes: ArrayLike,
    ) -> NDArray[np.float64]: ...
    def p(
        self,
        gamma: ArrayLike,
        alpha: ArrayLike,
        out: Optional[np.ndarray] = None,
        **axes: ArrayLike,
    ) -> Float:
        """P(γ, α, e_n), the tangential restitution of the contact point, by the table's
        interpolation rule. γ finite > 0, α ≥ 0 (``inf``: no slip), e_n the normal restitution:
        1 (the default) for an elastic table, inside ``e_n_min`` … ``e_n_max`` of :attr:`info` for
        a table built with an e_n range (never clamped: ``ValueError`` outside). Every axis
        beyond γ and α (:attr:`axes`) is a keyword argument of its name, at its fixed value
        (e_n = 1) when not given; another keyword is a ``TypeError`` naming the axes. The table of
        one pair answers γ = :attr:`pair_gamma` only (``ValueError`` naming γ and the pair's
        γ elsewhere, except on the full-slip line). Broadcasts over all arguments; returns a
        float for scalar arguments. |P| ≤ 1 everywhere."""
        extra = _extra_axes("p", axes)
        if not extra:
            if out is None and type(gamma) in _NUMBER and type(alpha) in _NUMBER:
                return self._t.p(gamma, alpha, self._clamp)  # type: ignore[arg-type]  # checked above
            g, a = _f64(gamma, "gamma"), _f64(alpha, "alpha")
            shape = _shape([("gamma", g.shape), ("alpha", a.shape)])
            o = _output(out, shape)
            gf, af = _full(g, shape), _full(a, shape)
            _into(o, lambda f: self._t.p_into(gf, af, f, self._clamp, list(shape)), gf, af)
            return _result(o, out)
        names = [n for n, _ in extra]
        if (
            out is None
            and all(type(v) in _NUMBER for _, v in extra)
            and type(gamma) in _NUMBER
            and type(alpha) in _NUMBER
        ):
            values = [v for _, v in extra]
            return self._t.p_axes(gamma, alpha, names, values, self._clamp)  # type: ignore[arg-type]  # checked above
        g, a = _f64(gamma, "gamma"), _f64(alpha, "alpha")
        xs = [_f64(v, n) for n, v in extra]
        shape = _shape([("gamma", g.shape), ("alpha", a.shape)] + [(n, x.shape) for n, x in zip(names, xs)])
        o = _output(out, shape)
        gf, af = _full(g, shape), _full(a, shape)
        xf = [_full(x, shape) for x in xs]
        _into(
            o,
            lambda f: self._t.p_axes_into(gf, af, names, xf, f, self._clamp, list(shape)),
            gf,
            af,
            *xf,
        )
        return _result(o, out)

    @overload
    def e_t(
        self, gamma: float, alpha: float, kappa: float = 0.4, out: None = None
    ) -> float: ...
    @overload
    def e_t(
        self,
        gamma: ArrayLike,
        alpha: ArrayLike,
        kappa: ArrayLike = 0.4,
        out: Optional[np.ndarray] = None,
    ) -> NDArray[np.float64]: ...
    def e_t(
        self,
        gamma: ArrayLike,
        alpha: ArrayLike,
        kappa: ArrayLike = 0.4,
        out: Optional[np.ndarray] = None,
    ) -> Float:
        """Tangential restitution of the centre, e_t = v_x/v_x0 = 1 − (κ/(1 + κ))(1 − P), of a
        sphere (inertia factor κ) hitting a wall without spin; (2P + 5)/7 for a solid sphere.
        Broadcasts over γ, α and κ."""
        g, a, k = _f64(gamma, "gamma"), _f64(alpha, "alpha"), _f64(kappa, "kappa")
        shape = _shape([("gamma", g.shape), ("alpha", a.shape), ("kappa", k.shape)])
        p = np.asarray(self.p(np.broadcast_to(g, shape), np.broadcast_to(a, shape)))
        o = _output(out, shape)
        pf, kf = _full(p, shape), _column(k, shape)
        _into(o, lambda f: _native.e_t_into(pf, kf, f, list(shape)), pf, kf)
        return _result(o, out)

    def regime(
        self, gamma: ArrayLike, alpha: ArrayLike, e_n: ArrayLike = 1.0
    ) -> Union[str, NDArray[np.str_]]:
        """The friction regime of (γ, α) at normal restitution ``e_n`` (1: elastic):
        ``'full-slip'``, ``'partial-slip'`` or ``'stick'`` (:func:`regime`; exact, from the
        critical curves α_c1(γ, e_n) and α_c2(γ), for any γ > 0)."""
        return regime(gamma, alpha, e_n=e_n)

    def curve(self, gamma: float) -> Curve:
        """P(α) at one γ, precomputed (≤ 1.4 ms, ≤ 68 KB for ``tables/full.h5``)."""
        return Curve(self._t.curve(float(_f64(gamma, "gamma")), self._clamp))

    def rebound(
        self,
        sphere: Sphere,
        velocity: ArrayLike,
        spin: ArrayLike = (0.0, 0.0, 0.0),
        *,
        friction: ArrayLike,
        normal: ArrayLike = (0.0, 0.0, 1.0),
        materials: Optional[Tuple[Material, Material]] = None,
        gamma: Optional[ArrayLike] = None,
        other: Optional[Sphere] = None,
        other_velocity: ArrayLike = (0.0, 0.0, 0.0),
        other_spin: ArrayLike = (0.0, 0.0, 0.0),
        e_n: ArrayLike = 1.0,
    ) -> Rebound:
        """3-D impacts of sphere 1 on a fixed wall (``other=None``) or on sphere 2.

        ``velocity``, ``spin`` (m/s, rad/s; shape ``(..., 3)``) are sphere 1's before the
        impact; ``normal`` (``(..., 3)``, any non-zero length) points from sphere 1's centre
        into the wall or towards sphere 2's centre, and the bodies must approach along it.
        ``friction`` is μ ≥ 0 (``inf``: no slip). γ comes from ``materials=(sphere's Material,
        wall's or sphere 2's Material)`` with the pair's masses and κ, or is given as
        ``gamma=``. ``e_n`` is the normal restitution (dimensionless): the relative normal
        velocity reverses to ``e_n`` times its value, and P is the table's P(γ, α, e_n); 1 (the
        default, elastic) for an elastic table, inside ``e_n_min`` … ``e_n_max`` of :attr:`info`
        for a table built with an e_n range (never clamped: ``ValueError`` outside, also for
        impacts without slip). With the table of one pair the γ of every impact (from
        ``materials`` or ``gamma``) must be its :attr:`pair_gamma`. Every argument (the fields of :class:`Sphere` and
        :class:`Material` included) broadcasts against the others; the leading shape of the
        vectors is the batch shape. When the bodies, materials, μ and e_n are the same for
        every impact they are checked once (the faster path)."""
        g, mats = _stiffness(materials, gamma)
        vecs = [
            ("velocity", _vector(velocity, "velocity")),
            ("spin", _vector(spin, "spin")),
            ("other_velocity", _vector(other_velocity, "other_velocity")),
            ("other_spin", _vector(other_spin, "other_spin")),
            ("normal", _vector(normal, "normal")),
        ]
        s1 = _body(sphere, "sphere")
        s2 = [] if other is None else _body(other, "other")
        mu = _f64(friction, "friction")
        e = _f64(e_n, "e_n")
        scal = [("friction", mu), ("e_n", e)] + list(zip(("mass", "radius", "kappa"), s1))
        scal += list(zip(("other mass", "other radius", "other kappa"), s2))
        scal += [("gamma", g)] if g is not None else list(zip(("materials",) * 4, mats))
        shape = _shape([(n, v.shape[:-1]) for n, v in vecs] + [(n, x.shape) for n, x in scal])
        rows = math.prod(shape)
        c = [_column(v, shape, 3) for _, v in vecs]
        raw = _native.rebound_3d(
            self._t,
            rows,
            list(shape),
            c[0],
            c[1],
            c[2],
            c[3],
            c[4],
            [_column(x, shape) for x in s1],
            [_column(x, shape) for x in s2],
            None if g is None else _column(g, shape),
            [_column(x, shape) for x in mats],
            _column(mu, shape),
            _column(e, shape),
            self._clamp,
        )
        names = _native.REBOUND3
        v = _views(raw, shape, names)
        wall = other is None
        return Rebound(
            velocity=_vec(raw, shape, names, "velocity"),
            spin=_vec(raw, shape, names, "spin"),
            other_velocity=None if wall else _vec(raw, shape, names, "other_velocity"),
            other_spin=None if wall else _vec(raw, shape, names, "other_spin"),
            tangent=_vec(raw, shape, names, "tangent"),
            **{
                k: v[k]
                for k in _native.REBOUND3
                if not k.startswith(("velocity_", "spin_", "other_", "tangent_"))
            },
        )

    def rebound_2d(
        self,
        sphere: Sphere,
        v_x: ArrayLike,
        v_z: ArrayLike,
        omega: ArrayLike = 0.0,
        *,
        friction: ArrayLike,
        materials: Optional[Tuple[Material, Material]] = None,
        gamma: Optional[ArrayLike] = None,
        other: Optional[Sphere] = None,
        other_v_x: ArrayLike = 0.0,
        other_v_z: ArrayLike = 0.0,
        other_omega: ArrayLike = 0.0,
        e_n: ArrayLike = 1.0,
    ) -> Rebound2D:
        """Impacts in the plane of impact: ``z`` the normal from sphere 1 into the wall or sphere
        2 (``v_z > 0`` approaches), ``x`` the tangent, ω signed so that sphere 1's contact point
        moves at v_x + R ω (sphere 2's at v_x − R ω). Arguments, ``e_n`` (the normal
        restitution: the relative v_z reverses to ``e_n`` times its value) included, as in
        :meth:`rebound`; all broadcast."""
        g, mats = _stiffness(materials, gamma)
        e = _f64(e_n, "e_n")
        motion, s1, s2, mu, shape = _planar(
            sphere,
            v_x,
            v_z,
            omega,
            friction,
            other,
            other_v_x,
            other_v_z,
            other_omega,
            g,
            mats,
            [("e_n", e)],
        )
        raw = _native.rebound_2d(
            self._t,
            math.prod(shape),
            list(shape),
            motion,
            s1,
            s2,
            None if g is None else _column(g, shape),
            [_column(x, shape) for x in mats],
            mu,
            _column(e, shape),
            self._clamp,
        )
        v = _views(raw, shape, _native.REBOUND2)
        if other is None:
            v.update(other_v_x=None, other_v_z=None, other_omega=None)
        return Rebound2D(**v)

    def __repr__(self) -> str:
        i = self.info
        gamma = (
            f"gamma in [{i['gamma_min']}, {i['gamma_max']}]"
            if i["pair_gamma"] is None
            else f"gamma = {i['pair_gamma']} (one pair)"
        )
        return (
            f"<oblique.Table {i['path']!r}: {gamma}, "
            f"alpha <= {i['alpha_max']}, "
            + "".join(f"{n} in [{i[n + '_min']}, {i[n + '_max']}], " for n in self.axes[2:])
            + f"error bound {i['error_bound']:.2g}"
            + (", clamped" if self._clamp else "")
            + ">"
        )


def _planar(sphere, v_x, v_z, omega, friction, other, ov_x, ov_z, oomega, g, mats, extra=()):
    """Columns of a 2-D batch: motion (six), bodies, μ, and the broadcast shape (of these and
    of the named arrays ``extra``)."""
    names = ("v_x", "v_z", "omega", "other_v_x", "other_v_z", "other_omega")
    motion = [_f64(x, n) for x, n in zip((v_x, v_z, omega, ov_x, ov_z, oomega), names)]
    s1 = _body(sphere, "sphere")
    s2 = [] if other is None else _body(other, "other")
    mu = _f64(friction, "friction")
    named = list(zip(names, motion)) + [("friction", mu)]
    named += list(zip(("mass", "radius", "kappa"), s1))
    named += list(zip(("other mass", "other radius", "other kappa"), s2))
    named += [("gamma", g)] if g is not None else list(zip(("materials",) * 4, mats))
    named += list(extra)
    shape = _shape([(n, x.shape) for n, x in named])
    col = lambda xs: [_column(x, shape) for x in xs]  # noqa: E731
    return col(motion), col(s1), col(s2), _column(mu, shape), shape


# ---------------------------------------------------------------------------------------------
# Without a table


def regime(
    gamma: ArrayLike, alpha: ArrayLike, *, e_n: ArrayLike = 1.0
) -> Union[str, NDArray[np.str_]]:
    """The friction regime of (γ, α) at normal restitution ``e_n`` (0.3 to 1; 1, the default:
    elastic), exact for any γ > 0, α ≥ 0: ``'full-slip'`` for α ≤ α_c1(γ, e_n) (γ > 1) or
    α ≤ α_c2 (γ ≤ 1), ``'stick'`` for α ≥ α_c2, ``'partial-slip'`` between (:func:`critical`).
    Broadcasts; a str for scalar arguments, else an array of str."""
    g, a, e = _f64(gamma, "gamma"), _f64(alpha, "alpha"), _f64(e_n, "e_n")
    shape = _shape([("gamma", g.shape), ("alpha", a.shape), ("e_n", e.shape)])
    codes = np.empty(shape, dtype=np.float64)
    gc, ac, ec = _column(g, shape), _column(a, shape), _column(e, shape)
    _native.regime_into(gc, ac, ec, codes.reshape(-1), list(shape))
    names = _REGIME_NAMES[codes.astype(np.intp)]
    return str(names) if names.ndim == 0 else names


def critical(gamma: ArrayLike, *, e_n: ArrayLike = 1.0) -> Tuple[Float, Float]:
    """The critical friction groups ``(α_c1, α_c2)`` at γ > 0 and normal restitution ``e_n``
    (0.3 to 1; 1, the default: elastic; physics.md): α_c1 = 2γ²/(7(γ²(1 + e_n) − e_n)), the end
    of full slip for γ > 1 (2γ²/(7(2γ² − 1)) at e_n = 1; negative for γ < 1/√2, where it marks
    nothing), α_c2 = 2γ²/7, the start of stick, which does not move with e_n. Broadcasts."""
    g, e = _f64(gamma, "gamma"), _f64(e_n, "e_n")
    shape = _shape([("gamma", g.shape), ("e_n", e.shape)])
    out = np.empty(shape + (2,), dtype=np.float64)
    _native.critical_into(_column(g, shape), _column(e, shape), out.reshape(-1), list(shape))
    if not shape:
        return float(out[0]), float(out[1])
    return out[..., 0], out[..., 1]


def impact(
    gamma: ArrayLike,
    alpha: ArrayLike,
    tol: float = 1e-6,
    simulate: bool = False,
    *,
    e_n: ArrayLike = 1.0,
    law: Optional[str] = None,
) -> Impact:
    """P(γ, α, e_n) by simulating the impact (MDR, error-controlled) until the error estimate
    is ≤ ``tol`` (absolute); where P is known in closed form (the full-slip line, γ = 1 with
    α ≥ 2/7, α = 0) that is returned unless ``simulate=True``. For points a table does not
    cover. One point takes 0.05–5 ms at tol 1e-6; arrays run in parallel. Broadcasts over
    ``gamma``, ``alpha`` and ``e_n``.

    ``e_n`` is the normal restitution, from 0.3 to 1 (1, the default: elastic). Below 1 the
    springs follow a dissipative ``law``: ``"kelvin-voigt"`` (one relaxation time in the normal
    and tangential direction, non-adhesive; physics.md, "Dissipative impacts"), the one
    ``law=None`` picks below 1 (``"elastic"`` at 1), or ``"thornton"`` (elastic–perfectly
    plastic, Thornton 1997; physics.md, "Elastic–plastic impacts"). Each row reports the
    law's parameter that gives its ``e_n``: ``tau`` for Kelvin–Voigt, ``yield_pressure`` for
    Thornton (0 for the other laws)."""
    g, a, e = _f64(gamma, "gamma"), _f64(alpha, "alpha"), _f64(e_n, "e_n")
    shape = _shape([("gamma", g.shape), ("alpha", a.shape), ("e_n", e.shape)])
    raw = _native.impact(
        _column(g, shape),
        _column(a, shape),
        _column(e, shape),
        math.prod(shape),
        list(shape),
        float(tol),
        bool(simulate),
        law,
    )
    v = _views(raw, shape, _native.IMPACT)
    v["closed_form"] = v["closed_form"] != 0
    for k in ("springs", "steps"):
        v[k] = v[k].astype(np.int64) if shape else int(v[k])
    return Impact(**v)


def groups(
    sphere: Sphere,
    v_x: ArrayLike,
    v_z: ArrayLike,
    omega: ArrayLike = 0.0,
    *,
    friction: ArrayLike,
    materials: Tuple[Material, Material],
    other: Optional[Sphere] = None,
    other_v_x: ArrayLike = 0.0,
    other_v_z: ArrayLike = 0.0,
    other_omega: ArrayLike = 0.0,
) -> Groups:
    """γ and α of impacts given in physical units (arguments and conventions as in
    :meth:`Table.rebound_2d`), with E*, G*, m*, m_t, R*, v_z0 and u0. Broadcasts."""
    _, mats = _stiffness(materials, None, need=True)
    motion, s1, s2, mu, shape = _planar(
        sphere, v_x, v_z, omega, friction, other, other_v_x, other_v_z, other_omega, None, mats
    )
    raw = _native.groups(
        math.prod(shape), list(shape), motion, s1, s2, [_column(x, shape) for x in mats], mu
    )
    return Groups(**_views(raw, shape, _native.GROUPS))


def simulate(
    sphere: Sphere,
    v_x: float,
    v_z: float,
    omega: float = 0.0,
    *,
    friction: float,
    materials: Tuple[Material, Material],
    other: Optional[Sphere] = None,
    other_v_x: float = 0.0,
    other_v_z: float = 0.0,
    other_omega: float = 0.0,
    tol: float = 1e-6,
    relaxation_time: Optional[float] = None,
    yield_pressure: Optional[float] = None,
) -> Simulation:
    """One impact in physical units, simulated directly (the two bodies' equations of motion,
    Hertz normal contact, MDR tangential springs) until the error estimate of P is ≤ ``tol``:
    the reference a table answer can be checked against. Arguments and conventions as in
    :meth:`Table.rebound_2d`, scalars only.

    ``relaxation_time`` τ (s, ≥ 0) makes the bodies Kelvin–Voigt (for this law τ equals
    Brilliantov's dissipative constant A); the normal restitution it gives at this impact
    speed is returned as ``e_n`` (it falls as the speed grows, 1 − e_n ∝ τ v_z0^(1/5) at
    first order) and must be ≥ 0.3.

    ``yield_pressure`` p_y (Pa, finite, > 0) makes the bodies Thornton's elastic–perfectly
    plastic ones (physics.md, "Elastic–plastic impacts"; about 1.6 times the yield stress of
    the softer body): the impact is elastic (``e_n`` = 1) up to the yield speed V_y at which
    the Hertz peak pressure reaches p_y, and above it ``e_n`` is Thornton's closed form of
    V_y/v_z0 (it must be ≥ 0.3). Give ``relaxation_time`` or ``yield_pressure``, not both;
    neither: elastic bodies."""
    _, mats = _stiffness(materials, None, need=True)
    motion, s1, s2, mu, shape = _planar(
        sphere, v_x, v_z, omega, friction, other, other_v_x, other_v_z, other_omega, None, mats
    )
    if shape:
        raise ValueError(f"simulate: scalar arguments only, got the broadcast shape {shape}")
    d = _native.simulate(
        motion,
        s1,
        s2,
        [_column(x, ()) for x in mats],
        mu,
        float(tol),
        None if relaxation_time is None else float(relaxation_time),
        None if yield_pressure is None else float(yield_pressure),
    )
    v_x, v_z, omega = d["sphere"]
    o_x, o_z, o_omega = d["other"] or (None, None, None)
    return Simulation(
        v_x=v_x,
        v_z=v_z,
        omega=omega,
        other_v_x=o_x,
        other_v_z=o_z,
        other_omega=o_omega,
        p=d["p"],
        error_estimate=d["error_estimate"],
        contact_time=d["contact_time"],
        peak_force=d["peak_force"],
        max_indentation=d["max_indentation"],
        e_n=d["e_n"],
        law=d["law"],
        tau=d["tau"],
        yield_pressure=d["yield_pressure"],
        springs=d["springs"],
        steps=d["steps"],
        groups=Groups(*d["groups"]),
    )


# ---------------------------------------------------------------------------------------------
# Building a table


class BuildProgress(NamedTuple):
    """One report of :func:`build_table` to a ``progress`` callable."""

    kind: str
    """``"stage"``: a stage (or a refinement round of one) begins; ``"count"``: impacts finished
    in it (at most every 0.1 s); ``"note"``: a line of information, in ``message``."""
    step: int
    """Number of the stage, 1 to ``steps``."""
    steps: int
    """Number of stages: the pre-flight, each patch's refinement (preceded by the fold tracing
    with ``nodes.fold_warp``), the held-out checks, writing."""
    stage: str
    """Name of the stage: ``"preflight"``, ``"stick_low refinement"``, ``"held-out checks"``,
    ``"writing"``, …"""
    detail: str
    """What the stage goes on with, e.g. ``"round 2"``, ``"60 points"``, the output path."""
    done: int
    """Impacts finished in this stage (or round)."""
    total: Optional[int]
    """Impacts this stage (or round) simulates, once known (nodes found in a checkpoint are not
    counted); ``None`` before."""
    message: str
    """The note when ``kind == "note"``, else ``""``."""


class _ProgressLines:
    """The default progress of :func:`build_table`: on ``sys.stderr``, one line per stage or
    round, the notes, and at most every 2 s the percent done of the stage (or round) with its
    ETA."""

    EVERY = 2.0

    def __init__(self) -> None:
        self._start = self._last = time.monotonic()

    def __call__(self, p: BuildProgress) -> None:
        label = f"[oblique] step {p.step}/{p.steps} {p.stage}"
        if p.detail:
            label += f": {p.detail}"
        now = time.monotonic()
        if p.kind == "note":
            line = p.message
        elif p.kind == "stage":
            line, self._start, self._last = label, now, now
        elif p.total and p.done and now - self._last >= self.EVERY:
            eta = (now - self._start) / p.done * (p.total - p.done)
            line = f"{label}: {100 * p.done // p.total}% of {p.total} impacts, ETA {eta:.0f} s"
            self._last = now
        else:
            return
        print(line, file=sys.stderr, flush=True)


_BARE_KEY = re.compile(r"[A-Za-z0-9_-]+\Z")


def _toml_string(s: str) -> str:
    """``s`` as a TOML basic string."""
    out = ['"']
    for ch in s:
        if ch in '"\\':
            out.append("\\" + ch)
        elif ch == "\n":
            out.append("\\n")
        elif ch == "\t":
            out.append("\\t")
        elif ord(ch) < 0x20 or ord(ch) == 0x7F:
            out.append(f"\\u{ord(ch):04X}")
        else:
            out.append(ch)
    out.append('"')
    return "".join(out)


def _toml_key(key: object, where: str) -> str:
    if not isinstance(key, str):
        raise ValueError(f"config: key {key!r}{where}: keys must be strings")
    return key if _BARE_KEY.match(key) else _toml_string(key)


def _toml_value(v: object, key: str) -> str:
    """A config value as TOML: strings (and paths), booleans, integers, floats (``inf`` and
    ``nan`` as TOML writes them), lists of those."""
    if isinstance(v, (bool, np.bool_)):
        return "true" if v else "false"
    if isinstance(v, numbers.Integral):
        return str(int(v))
    if isinstance(v, numbers.Real):
        x = float(v)
        if math.isnan(x):
            return "nan"
        if math.isinf(x):
            return "inf" if x > 0 else "-inf"
        return repr(x)
    if isinstance(v, str):
        return _toml_string(v)
    if isinstance(v, os.PathLike):
        return _toml_string(os.fsdecode(os.fspath(v)))
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_toml_value(x, key) for x in v) + "]"
    raise ValueError(
        f"config: `{key}` = {v!r}: must be a string, number, boolean or table (dict)"
    )


def _toml(config: Mapping[str, Any]) -> str:
    """A config given as nested dicts (``{"output": ..., "domain": {...}, ...}``) as TOML
    text: each dict value a table ``[name]``, every other value a key of its table."""
    lines: List[str] = []

    def table(t: Mapping[Any, Any], path: List[str]) -> None:
        where = f" in [{'.'.join(path)}]" if path else ""
        subtables = []
        for key, value in t.items():
            name = _toml_key(key, where)
            if isinstance(value, Mapping):
                subtables.append((path + [name], value))
            else:
                dotted = ".".join(path + [str(key)])
                lines.append(f"{name} = {_toml_value(value, dotted)}")
        for sub, value in subtables:
            lines.append("")
            lines.append(f"[{'.'.join(sub)}]")
            table(value, sub)

    table(config, [])
    return "\n".join(lines) + "\n"


def build_table(
    config: Union[str, "os.PathLike[str]", Mapping[str, Any]],
    output: Optional[Union[str, "os.PathLike[str]"]] = None,
    *,
    resume: bool = False,
    restart: bool = False,
    threads: Optional[int] = None,
    progress: Union[bool, Callable[[BuildProgress], object]] = True,
) -> Path:
    """Build a table from a config, as ``sweep run CONFIG`` does, and return the path of the
    table it wrote (open it with :class:`Table`).

    ``config`` is the path of a TOML config (``configs/*.toml``; keys in ``docs/config.md``)
    or the same as a dict of dicts: ``{"output": "pair.h5", "domain": {"gamma": 1.75, ...},
    "nodes": {...}, "solver": {...}}`` (``alpha_max`` may be ``"inf"`` or ``math.inf``).
    ``output`` (a path) replaces the config's ``output``; ``threads`` its ``run.threads``
    (0 = one per core).

    Finished nodes go to the checkpoint ``OUTPUT.ckpt`` as the build goes; it is removed once
    the table is written. Ctrl-C (``KeyboardInterrupt``) stops the build after its current
    batch of impacts, with the checkpoint kept, and raises ``KeyboardInterrupt``;
    ``resume=True`` continues from the checkpoint (a table the same, bit for bit, as that of an
    uninterrupted build), ``restart=True`` discards it and starts afresh. Without either an
    existing checkpoint is refused (``FileExistsError``).

    ``progress=True`` prints a line per stage and refinement round, with the percent done and
    an ETA at most every 2 s, the notes of ``sweep run`` (the pre-flight's, the nodes resumed,
    what was written) on ``sys.stderr``; ``False`` prints nothing; a callable is called with a :class:`BuildProgress` instead (an exception it
    raises stops the build as Ctrl-C does, and is raised).

    A bad key or value raises ``ValueError`` naming the key and the allowed range (also a
    tolerance the pre-flight finds out of reach, and a refinement past ``nodes.max_nodes``);
    a config file or output that cannot be read or written raises ``OSError``; another build
    writing the same output, ``RuntimeError``.
    """
    path: Optional[str] = None
    if isinstance(config, Mapping):
        text, name = _toml(config), "<dict>"
    else:
        given = os.fspath(config)
        path = os.fsdecode(given) if isinstance(given, bytes) else given
        # The text as it is (newline=""): it goes into the table's provenance.
        with open(path, encoding="utf-8", newline="") as f:
            text = f.read()
        name = path
    if threads is not None and (
        isinstance(threads, bool) or not isinstance(threads, numbers.Integral) or threads < 0
    ):
        raise ValueError(f"threads = {threads!r}: must be in [0, 1024] (0 = one per core)")
    out: Optional[str] = None
    if output is not None:
        o = os.fspath(output)
        out = os.fsdecode(o) if isinstance(o, bytes) else o
    if progress is True:
        callback: Optional[Callable[[BuildProgress], object]] = _ProgressLines()
    elif progress is False or progress is None:
        callback = None
    elif callable(progress):
        callback = progress
    else:
        raise TypeError(f"progress: expected True, False or a callable, got {progress!r}")

    def report(
        kind: str,
        step: int,
        steps: int,
        stage: str,
        detail: str,
        done: int,
        total: Optional[int],
        message: str,
    ) -> None:
        if callback is not None:
            callback(BuildProgress(kind, step, steps, stage, detail, done, total, message))

    built = _native.build_table(
        text,
        name,
        path,
        out,
        bool(resume),
        bool(restart),
        None if threads is None else int(threads),
        None if callback is None else report,
    )
    return Path(built)
