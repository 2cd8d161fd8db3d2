//! Helpers shared by the tests of the dependency-free evaluator (`tests/c_evaluator.rs`,
//! `tests/fortran.rs`): running a compiled program on an input, and the random bodies and
//! impacts both compare with the Rust library.

// Each test file uses a part of this module.
#![allow(dead_code)]

use std::io::Write;
use std::path::Path;
use std::process::{Command, Output, Stdio};

use oblique_lookup::rebound::{Body, Incident3, Motion3, Rebound3};
use oblique_lookup::Answer;
use oblique_physics::sample::SplitMix;

/// Run `exe` with `args`, `input` on its standard input. A program that exits early may leave
/// the input unread; that is an error only when it succeeds.
pub fn run(exe: &Path, args: &[&str], input: &str) -> Output {
    let mut child = Command::new(exe)
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap_or_else(|e| panic!("spawn {}: {e}", exe.display()));
    let mut stdin = child.stdin.take().expect("stdin");
    let input = input.to_owned();
    let writer = std::thread::spawn(move || stdin.write_all(input.as_bytes()));
    let out = child.wait_with_output().expect("wait");
    let written = writer.join().expect("writer");
    if out.status.success() {
        written.expect("write stdin");
    }
    out
}

/// [`run`], requiring success; the standard output.
pub fn run_ok(exe: &Path, args: &[&str], input: &str) -> String {
    let out = run(exe, args, input);
    assert!(
        out.status.success(),
        "{} {args:?}: {}\n{}",
        exe.display(),
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).expect("utf-8")
}

/// A sphere of random mass (0.1–10 g), radius (1–11 mm) and inertia factor (0.2–0.8).
pub fn random_body(r: &mut SplitMix) -> Body {
    Body {
        mass: 1e-4 + 1e-2 * r.uniform(),
        radius: 1e-3 + 1e-2 * r.uniform(),
        kappa: 0.2 + 0.6 * r.uniform(),
    }
}

/// A vector with components uniform in `[−scale, scale]`.
pub fn random_vec3(r: &mut SplitMix, scale: f64) -> [f64; 3] {
    [
        scale * (2.0 * r.uniform() - 1.0),
        scale * (2.0 * r.uniform() - 1.0),
        scale * (2.0 * r.uniform() - 1.0),
    ]
}

/// A random 3-D impact on a wall (the other body at rest) or of two spheres: a normal in the
/// unit cube, velocities up to 3 m/s, spins up to 500 rad/s; `None` unless the bodies approach
/// along the normal faster than 1e-3 (so that a caller drawing until it has enough keeps the
/// same stream of draws).
pub fn random_impact(r: &mut SplitMix, wall: bool) -> Option<Incident3> {
    let n = random_vec3(r, 1.0);
    let s = Incident3 {
        sphere: Motion3 {
            velocity: random_vec3(r, 3.0),
            spin: random_vec3(r, 500.0),
        },
        other: if wall {
            Motion3::default()
        } else {
            Motion3 {
                velocity: random_vec3(r, 3.0),
                spin: random_vec3(r, 500.0),
            }
        },
        normal: n,
    };
    let d: Vec<f64> = (0..3)
        .map(|k| s.sphere.velocity[k] - s.other.velocity[k])
        .collect();
    (d[0] * n[0] + d[1] * n[1] + d[2] * n[2] > 1e-3).then_some(s)
}

/// The fields of a 3-D rebound the C and Fortran programs print, in their order: sphere 1's
/// velocity and spin, sphere 2's (zero for a wall), P, e_t, the energy lost, α, `|u0|`.
pub fn rebound_fields(a: &Answer<Rebound3>) -> Vec<f64> {
    let b = &a.rebound;
    let o = b.other.unwrap_or_default();
    [b.sphere.velocity, b.sphere.spin, o.velocity, o.spin]
        .iter()
        .flatten()
        .copied()
        .chain([b.p, b.e_t, b.energy_lost, a.alpha, b.slip_before])
        .collect()
}
