//! Reference engine for oblique elastic impacts with friction.
//!
//! Layers: [`physics`] (one impact, no I/O), [`sweep`] (schedules many impacts and places the
//! table's nodes), [`storage`] (owns writing the HDF5 table format), [`scene`] (a user's bodies
//! and impact conditions to rebound curves), [`plot`] (drawing), [`figures`] (the pictures of a
//! table) and [`accuracy`] (the accuracy-against-cost study); [`nodestore`] owns the checkpoint
//! and shard-part files. The `sweep` binary is a thin CLI over them; the `oblique-lookup` crate
//! reads the tables.

pub mod accuracy;
pub mod figures;
pub mod nodestore;
pub mod physics;
pub mod plot;
pub mod scene;
pub mod storage;
pub mod sweep;

/// Engine version.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");
/// Git commit the engine was built from (`-dirty` when the work tree had changes).
pub const GIT_COMMIT: &str = env!("OBLIQUE_GIT_COMMIT");

/// Current UTC time as RFC 3339 (`YYYY-MM-DDTHH:MM:SSZ`).
pub fn utc_now() -> String {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_secs() as i64)
        .unwrap_or(0);
    let (days, rem) = (secs.div_euclid(86_400), secs.rem_euclid(86_400));
    // Civil date from days since 1970-01-01 (Howard Hinnant's algorithm).
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    format!(
        "{y:04}-{m:02}-{d:02}T{:02}:{:02}:{:02}Z",
        rem / 3600,
        rem / 60 % 60,
        rem % 60
    )
}
