//! Tabulates the universal dimensionless Hertz normal motion (`m* = R* = E* = v_z0 = 1`,
//! `k = 4/3`) at build time, with the code the solver runs (`src/hertz.rs`): its measured
//! contact time and its trajectory on every power-of-two grid of the refinement from
//! [`FIRST`] to [`LAST`] steps. `impact::dimensionless_normal` reads them instead of
//! integrating them again in every process (`crates/solver/src/impact.rs` checks that they are
//! the bits the process would compute).

#[allow(dead_code)]
#[path = "src/hertz.rs"]
mod hertz;

/// Smallest tabulated grid (the refinement starts at 16 steps for `γ ≤ 1`).
const FIRST: u32 = 4;
/// Largest tabulated grid, `2^13 = 8192` steps (262 KB for all of them).
const LAST: u32 = 13;

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-changed=src/hertz.rs");
    let bodies = hertz::NormalBodies {
        inv_mass1: 1.0,
        inv_mass2: 0.0,
        stiffness: 4.0 / 3.0,
        approach_speed: 1.0,
    };
    let tc = bodies.measure_contact_time();
    let mut values = vec![f64::from(FIRST), f64::from(LAST), tc];
    for k in FIRST..=LAST {
        let t = bodies.trajectory_over(1 << k, tc);
        values.extend([t.max_indentation, t.peak_force, t.delta_v1, t.delta_v2]);
        values.extend(&t.indentation);
        values.extend(&t.rate);
    }
    let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
    let out = std::env::var_os("OUT_DIR").expect("cargo sets OUT_DIR for build scripts");
    let path = std::path::Path::new(&out).join("universal_hertz.bin");
    std::fs::write(&path, bytes).expect("write the tabulated Hertz motion to OUT_DIR");
}
