//! Deterministic pseudo-random numbers and query points for the tests, benchmarks and examples
//! of this workspace (not part of the API: hidden from the documentation, may change).

use crate::rebound::{Body, Elastic, Incident3, Motion3, Pair};
use crate::{Contact, Table};
use oblique_table::Surface;

/// Held while a test starts a child process and while the test itself has an HDF5 file open
/// for writing with the `hdf5` crate (an edit of a table on purpose): a child inherits the
/// parent's open descriptors, and with them HDF5's lock on a file being written (`flock`, kept
/// until the child exits), so a later edit of that file in the test process fails with "unable
/// to lock file". The workspace's own reader and writer take no lock and need no guard.
pub fn fork_guard() -> std::sync::MutexGuard<'static, ()> {
    static GUARD: std::sync::Mutex<()> = std::sync::Mutex::new(());
    GUARD.lock().unwrap_or_else(|e| e.into_inner())
}

/// `t` with every node value replaced by one next to ±1: `−(1 − off(i))` in leaves of even
/// number, `1 − off(i)` in odd ones, exactly ±1 at every third node (`off` is not called
/// there). Its tensor product overshoots ±1 at most points: the test table for step 10 of the
/// rule (`|P| ≤ 1`).
pub fn overshooting(t: Table, mut off: impl FnMut(usize) -> f64) -> Table {
    let surface = t
        .surface()
        .map_patches(|_, p| {
            let size = p.leaf_size();
            p.map_values(|i, _| {
                let sign = if (i / size) % 2 == 0 { -1.0 } else { 1.0 };
                sign * (1.0 - if i % 3 == 0 { 0.0 } else { off(i) })
            })
        })
        .expect("values within [-1, 1] keep the patches valid");
    Table::from_parts(
        surface,
        t.provenance().clone(),
        t.checks().to_vec(),
        t.error_bound(),
    )
}

/// Uniform numbers in `[0, 1)` from a xorshift64 generator seeded with `seed` (nonzero): the
/// 53 high bits of each state. No external RNG, the same stream on every platform.
pub fn uniform(seed: u64) -> impl FnMut() -> f64 {
    let mut state = seed;
    move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// `n` points over a table's domain drawn from `next`: γ uniform in `[gamma_min, gamma_max]`,
/// α log-uniform in `[1e-3, 1e3]`, with 10 % α = ∞ (about a third of them on the full-slip
/// line).
pub fn domain_points_from(
    surface: &Surface,
    n: usize,
    next: &mut impl FnMut() -> f64,
) -> Vec<(f64, f64)> {
    (0..n)
        .map(|_| {
            let g = surface.gamma_min() + (surface.gamma_max() - surface.gamma_min()) * next();
            let a = if next() < 0.1 {
                f64::INFINITY
            } else {
                10f64.powf(-3.0 + 6.0 * next())
            };
            (g, a)
        })
        .collect()
}

/// [`domain_points_from`] with a fresh [`uniform`] stream.
pub fn domain_points(surface: &Surface, n: usize, seed: u64) -> Vec<(f64, f64)> {
    domain_points_from(surface, n, &mut uniform(seed))
}

/// The sphere–sphere impact of the benchmarks: an alumina sphere (R 2.5 mm, 0.24 g) on a steel
/// sphere (R 6 mm, 2.4 g), both solid (κ = 0.4), μ = 0.15, γ from the materials, with spins and
/// a tilted normal (`crates/lookup-capi/examples/query.c` has the same with the normal along z).
pub fn reference_spheres() -> (Pair, Contact, Incident3) {
    let pair = Pair {
        sphere: Body {
            mass: 2.4e-4,
            radius: 2.5e-3,
            kappa: 0.4,
        },
        other: Some(Body {
            mass: 2.4e-3,
            radius: 6e-3,
            kappa: 0.4,
        }),
    };
    let alumina = Elastic {
        youngs_modulus: 3.7e11,
        poisson_ratio: 0.25,
    };
    let steel = Elastic {
        youngs_modulus: 2.1e11,
        poisson_ratio: 0.3,
    };
    let incident = Incident3 {
        sphere: Motion3 {
            velocity: [0.8, 0.3, 1.5],
            spin: [20.0, 120.0, -40.0],
        },
        other: Motion3 {
            velocity: [-0.2, 0.1, -0.4],
            spin: [0.0, -50.0, 10.0],
        },
        normal: [0.1, -0.2, 0.97],
    };
    (
        pair,
        Contact::with_materials(alumina, steel, 0.15),
        incident,
    )
}
