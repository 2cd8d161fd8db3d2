//! Argument parsers and number formatting shared by the commands: each parser names the flag
//! and its allowed range in its message (clap prints it with exit status 2).

use oblique_solver::Preset;
use serde_json::json;

/// A number; `inf` (or `infinity`, `∞`) spelled out for infinity. A number beyond the largest
/// double (`1e400`) is refused, not read as `inf`.
pub(crate) fn parse_f64(s: &str) -> Result<f64, String> {
    let t = s.trim().to_ascii_lowercase();
    match t.as_str() {
        "inf" | "infinity" | "+inf" | "∞" => Ok(f64::INFINITY),
        _ => {
            let v = t
                .parse::<f64>()
                .map_err(|_| format!("`{s}` is not a number"))?;
            let spelled = t.trim_start_matches(['+', '-']).starts_with("inf");
            if v.is_infinite() && !spelled {
                return Err(format!(
                    "`{s}` overflows: its magnitude exceeds the largest number, {:e} (write inf for \
                     infinity where it is allowed)",
                    f64::MAX
                ));
            }
            Ok(v)
        }
    }
}

/// Range of `sweep impact --gamma`: the γ range of the extremes suite (`tests/extremes.rs`,
/// docs/accuracy.md), in which the solver is tested for boundedness and convergence.
pub(crate) const IMPACT_GAMMA_RANGE: (f64, f64) = (0.01, 5.0);

pub(crate) fn parse_gamma(s: &str) -> Result<f64, String> {
    let v = parse_f64(s)?;
    let (lo, hi) = IMPACT_GAMMA_RANGE;
    if (lo..=hi).contains(&v) {
        Ok(v)
    } else {
        Err(format!(
            "gamma must be a number from {lo} to {hi}, the range the solver is tested in \
             (docs/accuracy.md)"
        ))
    }
}

/// γ of a table query: any finite number > 0 (the table's domain is checked by the lookup; the
/// full-slip closed form holds for every γ).
pub(crate) fn parse_table_gamma(s: &str) -> Result<f64, String> {
    let v = parse_f64(s)?;
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err("gamma must be a finite number > 0".into())
    }
}

/// A number as written by a person: plain decimals from 1e-4 to 1e9, exponent notation
/// outside (Rust's `{}` would print 1e308 with 309 digits).
pub(crate) fn fmt_num(v: f64) -> String {
    if v == 0.0 || !v.is_finite() || (1e-4..1e9).contains(&v.abs()) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

pub(crate) fn parse_alpha(s: &str) -> Result<f64, String> {
    let v = parse_f64(s)?;
    if v >= 0.0 {
        Ok(v)
    } else {
        Err("alpha must be >= 0 (or inf for no slip)".into())
    }
}

/// Largest `--tol`: a tolerance on P (in [−1, 1]) is meaningful well below its range.
pub(crate) const MAX_TOL: f64 = 1e-2;

pub(crate) fn parse_tol(s: &str) -> Result<f64, String> {
    let v = parse_f64(s)?;
    if v > 0.0 && v <= MAX_TOL {
        Ok(v)
    } else {
        Err(format!(
            "tol must be a number > 0 and <= {MAX_TOL} (an absolute error of P; e.g. 1e-6)"
        ))
    }
}

/// Normal restitution `e_n`: a number in [0.3, 1] (1: elastic).
pub(crate) fn parse_e_n(s: &str) -> Result<f64, String> {
    let v = parse_f64(s)?;
    oblique_solver::law::check_restitution(v).map_err(|_| {
        "e-n (the normal restitution) must be a number from 0.3 to 1 (1: elastic)".into()
    })
}

/// A dissipation law by name.
pub(crate) fn parse_law(s: &str) -> Result<oblique_solver::Law, String> {
    oblique_solver::Law::from_name(s).map_err(|e| e.to_string())
}

pub(crate) fn parse_preset(s: &str) -> Result<Preset, String> {
    Preset::from_name(s).map_err(|e| e.to_string())
}

pub(crate) fn parse_count(s: &str, name: &str, min: usize) -> Result<usize, String> {
    parse_integer(s, min, None).ok_or_else(|| format!("{name} must be an integer >= {min}"))
}

/// Springs on the half-row: 0 (the continuum row) or an integer >= 2.
pub(crate) fn parse_springs(s: &str) -> Result<usize, String> {
    match parse_integer(s, 0, None) {
        Some(n) if n != 1 => Ok(n),
        _ => Err("springs must be 0 (the continuum row) or an integer >= 2".into()),
    }
}

pub(crate) fn parse_steps(s: &str) -> Result<usize, String> {
    parse_count(s, "steps", 8)
}

pub(crate) fn json_number(v: f64) -> serde_json::Value {
    if v.is_finite() {
        json!(v)
    } else {
        json!("inf")
    }
}

pub(crate) fn parse_range(s: &str, name: &str, min: usize, max: usize) -> Result<usize, String> {
    parse_integer(s, min, Some(max))
        .ok_or_else(|| format!("{name} must be an integer from {min} to {max}"))
}

/// An integer `>= min` (and `<= max` if given), or `None`.
pub(crate) fn parse_integer(s: &str, min: usize, max: Option<usize>) -> Option<usize> {
    s.trim()
        .parse::<usize>()
        .ok()
        .filter(|&v| v >= min && max.is_none_or(|m| v <= m))
}
