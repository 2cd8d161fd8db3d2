//! Measured data a scene compares with: a small CSV.
//!
//! Format: lines starting with `#` and blank lines are ignored; the first other line is the
//! header. Its first column is the scene's swept quantity (`angle_deg`, `v_x0` in m/s or
//! `omega0` in rad/s, as the scene's `cases.kind`), followed by any of `e_t` (tangential
//! restitution of the centres) and `omega` (sphere 1's spin after the impact, rad/s, signed as in
//! the rest of the project: sphere 1's contact point moves at `v_x + R ω`). Cells may be empty
//! where a quantity was not measured.

use std::path::Path;

use super::spec::CaseKind;
use super::SceneError;

/// One measured point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeasuredPoint {
    /// Swept quantity (degrees, m/s or rad/s).
    pub x: f64,
    /// Measured `e_t`, if any.
    pub e_t: Option<f64>,
    /// Measured spin after the impact (rad/s), if any.
    pub omega: Option<f64>,
}

/// Parse measured-data CSV text; `path` names it in messages.
pub fn parse(text: &str, path: &Path, kind: CaseKind) -> Result<Vec<MeasuredPoint>, SceneError> {
    let err = |line: usize, message: String| SceneError::Measured {
        path: path.display().to_string(),
        line,
        message,
    };
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim()))
        .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
    let Some((hline, header)) = lines.next() else {
        return Err(err(1, "no header line (and no data)".into()));
    };
    let cols: Vec<&str> = header.split(',').map(str::trim).collect();
    if cols.first() != Some(&kind.x_column()) {
        return Err(err(
            hline,
            format!(
                "the first column must be `{}` (the swept quantity of cases.kind = \"{}\"), \
                 found `{}`",
                kind.x_column(),
                kind.name(),
                cols.first().unwrap_or(&"")
            ),
        ));
    }
    let mut e_t_col = None;
    let mut omega_col = None;
    for (i, c) in cols.iter().enumerate().skip(1) {
        let slot = match *c {
            "e_t" => &mut e_t_col,
            "omega" => &mut omega_col,
            other => {
                return Err(err(
                    hline,
                    format!("unknown column `{other}`: allowed are e_t and omega"),
                ))
            }
        };
        if slot.replace(i).is_some() {
            return Err(err(hline, format!("column `{c}` appears twice")));
        }
    }
    if e_t_col.is_none() && omega_col.is_none() {
        return Err(err(hline, "no data column: give e_t and/or omega".into()));
    }
    let mut points = Vec::new();
    for (n, line) in lines {
        let cells: Vec<&str> = line.split(',').map(str::trim).collect();
        if cells.len() != cols.len() {
            return Err(err(
                n,
                format!("{} cells, the header has {}", cells.len(), cols.len()),
            ));
        }
        let cell = |i: usize, name: &str| -> Result<Option<f64>, SceneError> {
            if cells[i].is_empty() {
                return Ok(None);
            }
            match cells[i].parse::<f64>() {
                Ok(v) if v.is_finite() => Ok(Some(v)),
                _ => Err(err(
                    n,
                    format!("`{}` in column {name} is not a finite number", cells[i]),
                )),
            }
        };
        let Some(x) = cell(0, kind.x_column())? else {
            return Err(err(n, format!("empty {} cell", kind.x_column())));
        };
        if kind == CaseKind::Angles && (x <= -90.0 || x >= 90.0) {
            return Err(err(
                n,
                format!("angle_deg = {x}: must be in (-90, 90) degrees from the normal"),
            ));
        }
        points.push(MeasuredPoint {
            x,
            e_t: e_t_col.map(|i| cell(i, "e_t")).transpose()?.flatten(),
            omega: omega_col.map(|i| cell(i, "omega")).transpose()?.flatten(),
        });
    }
    if points.is_empty() {
        return Err(err(hline, "no data rows".into()));
    }
    Ok(points)
}

/// Read and parse a measured-data CSV.
pub fn load(path: &Path, kind: CaseKind) -> Result<Vec<MeasuredPoint>, SceneError> {
    let text = std::fs::read_to_string(path).map_err(|e| SceneError::Io {
        path: path.display().to_string(),
        message: format!("cannot read measured data: {e}"),
    })?;
    parse(&text, path, kind)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_comments_gaps_and_rejects_bad_columns() {
        let p = Path::new("m.csv");
        let text = "# synthetic\nangle_deg, e_t, omega\n10, 0.8, \n20,,-5\n";
        let pts = parse(text, p, CaseKind::Angles).unwrap();
        assert_eq!(pts.len(), 2);
        assert_eq!(pts[0].e_t, Some(0.8));
        assert_eq!(pts[0].omega, None);
        assert_eq!(pts[1].omega, Some(-5.0));
        let e = parse("angle_deg,foo\n1,2\n", p, CaseKind::Angles).unwrap_err();
        assert!(e.to_string().contains("foo"), "{e}");
        let e = parse("omega0,e_t\n1,2\n", p, CaseKind::Angles).unwrap_err();
        assert!(e.to_string().contains("angle_deg"), "{e}");
        let e = parse("angle_deg,e_t\n1,x\n", p, CaseKind::Angles).unwrap_err();
        assert!(e.to_string().contains("line 2"), "{e}");
    }
}
