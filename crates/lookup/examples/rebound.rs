//! The lookup from Rust, as a DEM code would use it: open a table once, then answer `P(γ, α)`
//! and whole rebounds without simulating.
//!
//! ```sh
//! cargo run --release -p oblique-lookup --example rebound -- tables/full.h5
//! ```
//!
//! 1. `P` at one point of the surface, with the table's stated error bound.
//! 2. An alumina sphere (R = 2.5 mm, 3.9 m/s, 30° from the normal, no spin) on a glass wall,
//!    μ = 0.092: the case of seed 000's Fig. 5, materials as in `configs/scenes/`.
//! 3. Two steel spheres of one material pair, the pair prepared once and `P(α)` taken from a
//!    curve at the pair's γ: the per-impact path of a DEM code's collision operator.

use std::process::ExitCode;

use oblique_lookup::rebound::{Body, Elastic, Incident3, Motion3, Pair};
use oblique_lookup::{Contact, LookupError, Table};

const ALUMINA: Elastic = Elastic {
    youngs_modulus: 370e9,
    poisson_ratio: 0.25,
};
const GLASS: Elastic = Elastic {
    youngs_modulus: 73e9,
    poisson_ratio: 0.217,
};
const STEEL: Elastic = Elastic {
    youngs_modulus: 210e9,
    poisson_ratio: 0.3,
};

/// `v = [..] m/s, spin = [..] rad/s` of one body after the impact.
fn motion(m: &Motion3) -> String {
    let [vx, vy, vz] = m.velocity;
    let [wx, wy, wz] = m.spin;
    format!("v = [{vx:.6}, {vy:.6}, {vz:.6}] m/s, spin = [{wx:.3}, {wy:.3}, {wz:.3}] rad/s")
}

/// A solid sphere (κ = 2/5) of radius `r` (m) and density `rho` (kg/m³).
fn solid(r: f64, rho: f64) -> Body {
    Body {
        mass: rho * 4.0 / 3.0 * std::f64::consts::PI * r.powi(3),
        radius: r,
        kappa: 0.4,
    }
}

fn run(path: &str) -> Result<(), LookupError> {
    let table = Table::open(path)?;

    // 1. One point of the surface.
    let p = table.p(1.754, 1.0)?;
    println!(
        "P(gamma = 1.754, alpha = 1) = {p:.9}  +/- {:.1e}",
        table.error_bound()
    );

    // 2. Sphere on a wall: z is the normal into the wall, the sphere moves along +x and +z.
    let pair = Pair {
        sphere: solid(2.5e-3, 3720.0),
        other: None,
    };
    let contact = Contact::with_materials(ALUMINA, GLASS, 0.092);
    let (v, theta) = (3.9, 30f64.to_radians());
    let incident = Incident3 {
        sphere: Motion3 {
            velocity: [v * theta.sin(), 0.0, v * theta.cos()],
            spin: [0.0; 3],
        },
        other: Motion3::default(),
        normal: [0.0, 0.0, 1.0],
    };
    let answer = table.rebound_3d(&pair, &contact, &incident)?;
    let r = &answer.rebound;
    println!(
        "alumina on glass, 30 deg: gamma = {:.6}, alpha = {:.6}, P = {:.6}",
        answer.gamma, answer.alpha, r.p
    );
    println!("  {}", motion(&r.sphere));
    println!(
        "  e_t = {:.6}, rebound angle {:.3} deg, energy lost {:.4e} J",
        r.e_t,
        r.rebound_angle_centre().to_degrees(),
        r.energy_lost
    );

    // 3. Two steel spheres (radii 1 mm and 2 mm), the pair prepared once.
    let pair = Pair {
        sphere: solid(1e-3, 7850.0),
        other: Some(solid(2e-3, 7850.0)),
    };
    let contact = Contact::with_materials(STEEL, STEEL, 0.3);
    let prepared = table.prepare(&pair, &contact)?;
    let curve = table.curve(prepared.gamma(), contact.outside)?;
    let incident = Incident3 {
        sphere: Motion3 {
            velocity: [0.5, 0.1, 1.0],
            spin: [0.0, 200.0, 0.0],
        },
        other: Motion3 {
            velocity: [0.0, 0.0, -0.5],
            spin: [0.0, 0.0, 50.0],
        },
        normal: [0.0, 0.0, 1.0],
    };
    let answer = table.rebound_3d_curve(&prepared, &curve, &incident)?;
    let r = &answer.rebound;
    let other = r.other.unwrap_or_default();
    println!(
        "steel on steel: gamma = {:.6}, alpha = {:.6}, P = {:.6}",
        answer.gamma, answer.alpha, r.p
    );
    println!("  sphere 1: {}", motion(&r.sphere));
    println!("  sphere 2: {}", motion(&other));
    println!("  energy lost {:.4e} J", r.energy_lost);
    Ok(())
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().collect();
    let [_, path] = args.as_slice() else {
        eprintln!("usage: rebound TABLE (e.g. tables/full.h5)");
        return ExitCode::from(2);
    };
    match run(path) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(if e.user_can_fix() { 2 } else { 1 })
        }
    }
}
