//! How the scene's files and messages spell a number.

/// Format a number so that it reads back exactly (`NaN`, `inf` spelled out; the CSV itself
/// writes undefined values as empty fields).
pub fn num(v: f64) -> String {
    if v.is_nan() {
        "NaN".into()
    } else if v.is_infinite() {
        if v > 0.0 { "inf" } else { "-inf" }.into()
    } else if v == 0.0 || (1e-4..1e7).contains(&v.abs()) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}
