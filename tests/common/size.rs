//! The size of the slowest tests: smaller in `scripts/test`, full in the release check
//! (`scripts/test --full`, which sets `OBLIQUE_FULL_TESTS=1`). A smaller run checks the same
//! properties on fewer points or cases. Shared by the test crates that size a test
//! (`common::size` here; `#[path]` from the crates' own tests).
#![allow(dead_code)]

/// Whether the tests run at their full size: `OBLIQUE_FULL_TESTS` set to `1`.
pub fn full_size() -> bool {
    std::env::var_os("OBLIQUE_FULL_TESTS").is_some_and(|v| v == "1")
}

/// `full` in the release check, `small` otherwise: the number of points, cases or mutations
/// of a sized test.
pub fn sized(small: usize, full: usize) -> usize {
    if full_size() {
        full
    } else {
        small
    }
}
