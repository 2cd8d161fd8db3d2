//! The result table of a scene as CSV (one header line, one row per case). A value that is
//! undefined for a case is an empty field, never `NaN`:
//!
//! - `e_t`, `e_t_closed_form`, `e_t_rolling` where the incident relative tangential velocity of
//!   the centres `v_x0` is 0 (a ratio to it; every case of a spin sweep without tangential
//!   speed, and normal incidence);
//! - `P` for a pure normal impact (`u0 = 0`, `method` = `normal-impact`): nothing tangential
//!   happens, and the other columns hold the unchanged tangential state;
//! - `e_t_closed_form`, `omega_closed_form` where `α = ∞` (`friction = inf` or `u0 = 0`): the
//!   full-slip approximation has no value there;
//! - `e_t_measured`, `omega_measured` where the measured file has no value.
//!
//! Every other field is a finite number, except `alpha`, which is `inf` for no slip
//! (`friction = inf`) and for a pure normal impact.
//!
//! Columns (SI units; angles in degrees from the normal; sphere 1 unless suffixed `_2`):
//!
//! | column | meaning |
//! |---|---|
//! | `angle_deg` | incidence angle (the swept angle, or that of the relative centre velocity) |
//! | `v_x`, `v_z`, `omega` | sphere 1 after the impact (m/s, m/s, rad/s) |
//! | `e_t` | tangential restitution of the centres (`v_x/v_x0` on a wall) |
//! | `rebound_angle_centre_deg` | rebound angle of the relative centre velocity |
//! | `rebound_angle_contact_deg` | rebound angle of the contact-point velocity (< 0: reversed) |
//! | `P` | `u_after/u_before` |
//! | `regime` | `full-slip`, `partial-slip`, `stick` or `normal-impact` |
//! | `energy_lost_J` | kinetic energy lost to friction (J) |
//! | `e_t_closed_form` | `e_t` of the full-slip approximation `P = 1 − 7α` |
//! | `e_t_rolling` | `e_t` of the rolling solution `P = 0` |
//! | `alpha`, `P_error`, `method` | `α`, error bound of `P`, how `P` was obtained |
//! | `v_x0`, `v_z0`, `omega0` | sphere 1 before the impact |
//! | `omega_closed_form`, `omega_rolling` | `ω` of the two approximations |
//! | `e_n`, `law` | normal restitution of the case and the law (`kelvin-voigt`, or `elastic` where `e_n = 1`; `thornton` for every case of a scene with `yield_pressure`; scenes that give `e_n`, `relaxation_time` or `yield_pressure` only) |
//! | `v_x_2`, `v_z_2`, `omega_2` | sphere 2 after the impact (sphere–sphere scenes only) |
//! | `e_t_measured`, `omega_measured` | measured values (scenes with measured data only) |

use std::io::Write;

use super::eval::{Evaluation, Row, RowMethod};

/// Numbers as the scene files spell them ([`super::format::num`]).
pub use super::format::num;

fn opt(v: Option<f64>) -> String {
    v.map(num).unwrap_or_default()
}

/// `v` where `is_defined`, else an empty field.
fn defined(is_defined: bool, v: f64) -> String {
    if is_defined {
        num(v)
    } else {
        String::new()
    }
}

/// The header and rows as CSV text lines (without line ends).
pub fn lines(ev: &Evaluation, sphere_sphere: bool) -> Vec<String> {
    let has_measured = ev.rows.iter().any(|r| r.measured.is_some());
    let mut header = vec![
        "angle_deg",
        "v_x",
        "v_z",
        "omega",
        "e_t",
        "rebound_angle_centre_deg",
        "rebound_angle_contact_deg",
        "P",
        "regime",
        "energy_lost_J",
        "e_t_closed_form",
        "e_t_rolling",
        "alpha",
        "P_error",
        "method",
        "v_x0",
        "v_z0",
        "omega0",
        "omega_closed_form",
        "omega_rolling",
    ];
    if ev.dissipative {
        header.extend(["e_n", "law"]);
    }
    if sphere_sphere {
        header.extend(["v_x_2", "v_z_2", "omega_2"]);
    }
    if has_measured {
        header.extend(["e_t_measured", "omega_measured"]);
    }
    let mut out = vec![header.join(",")];
    for r in &ev.rows {
        out.push(row(r, ev.dissipative, sphere_sphere, has_measured).join(","));
    }
    out
}

fn row(r: &Row, dissipative: bool, sphere_sphere: bool, has_measured: bool) -> Vec<String> {
    let m = &r.model;
    let cf = r.closed_form.as_ref();
    // e_t is a ratio to the incident relative tangential velocity of the centres.
    let has_e_t = r.incident.sphere.v_x - r.incident.other.v_x != 0.0;
    let has_p = r.method != RowMethod::NormalImpact;
    let mut cells = vec![
        num(r.angle_deg),
        num(m.sphere.v_x),
        num(m.sphere.v_z),
        num(m.sphere.omega),
        defined(has_e_t, m.e_t),
        num(m.rebound_angle_centre.to_degrees()),
        num(m.rebound_angle_contact.to_degrees()),
        defined(has_p, r.p),
        r.regime.map_or("normal-impact", |g| g.name()).to_string(),
        num(m.energy_lost),
        cf.map(|c| defined(has_e_t, c.e_t)).unwrap_or_default(),
        defined(has_e_t, r.rolling.e_t),
        num(r.alpha),
        num(r.p_error),
        r.method.name().to_string(),
        num(r.incident.sphere.v_x),
        num(r.incident.sphere.v_z),
        num(r.incident.sphere.omega),
        cf.map(|c| num(c.sphere.omega)).unwrap_or_default(),
        num(r.rolling.sphere.omega),
    ];
    if dissipative {
        cells.push(num(r.e_n));
        cells.push(r.law.name().to_string());
    }
    if sphere_sphere {
        let o = m.other.unwrap_or_default();
        cells.extend([num(o.v_x), num(o.v_z), num(o.omega)]);
    }
    if has_measured {
        cells.push(opt(r.measured.and_then(|p| p.e_t)));
        cells.push(opt(r.measured.and_then(|p| p.omega)));
    }
    cells
}

/// Write the CSV.
pub fn write(ev: &Evaluation, sphere_sphere: bool, w: &mut impl Write) -> std::io::Result<()> {
    for line in lines(ev, sphere_sphere) {
        writeln!(w, "{line}")?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::num;

    #[test]
    fn numbers_read_back_exactly() {
        for v in [
            0.0,
            1.0,
            -0.1,
            1e-9,
            123456789.0,
            3.9e-5,
            0.7425119420000001,
        ] {
            assert_eq!(num(v).parse::<f64>().unwrap(), v, "{}", num(v));
        }
        assert_eq!(num(f64::NAN), "NaN");
        assert_eq!(num(f64::INFINITY), "inf");
    }
}
