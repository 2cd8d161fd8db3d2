//! `sweep kinks`: the fold curve F₊ of `P(γ, α)`, where a `+μF_N` gross-slip episode of the
//! restitution phase vanishes as α grows and `P(α)` has a kink.

use crate::failure::outln;
use std::time::Instant;

use crate::failure::Result;
use clap::Args;
use serde_json::json;

use oblique_physics::regimes;
use oblique_solver::history::{fold_plus_curve, FOLD_MIN_STEPS};

use crate::args::{fmt_num, parse_f64, parse_range};

#[derive(Args)]
pub struct KinksArgs {
    /// Largest gamma of the curve, in (0, 3.6]; the curve starts at its birth point gamma_b ~ 2.90.
    #[arg(long, default_value_t = 3.5, value_parser = parse_gamma_max, allow_hyphen_values = true)]
    gamma_max: f64,
    /// Number of points from gamma_b to --gamma-max (both included), 2 to 1000.
    #[arg(long, default_value_t = 16, value_parser = parse_points, allow_hyphen_values = true)]
    points: usize,
    /// Time steps per contact time of every run (continuum row), 256 to 65536.
    #[arg(long, default_value_t = 2048, value_parser = parse_kink_steps, allow_hyphen_values = true)]
    steps: usize,
    /// Print one JSON object instead of CSV.
    #[arg(long)]
    json: bool,
}

/// Largest `--gamma-max` of `sweep kinks`: the continuation is tested up to 3.5.
const KINKS_GAMMA_MAX: f64 = 3.6;

fn parse_gamma_max(s: &str) -> Result<f64, String> {
    match parse_f64(s) {
        Ok(v) if v > 0.0 && v <= KINKS_GAMMA_MAX => Ok(v),
        _ => Err(format!(
            "gamma-max must be a number in (0, {KINKS_GAMMA_MAX}]"
        )),
    }
}

fn parse_points(s: &str) -> Result<usize, String> {
    parse_range(s, "points", 2, 1000)
}

fn parse_kink_steps(s: &str) -> Result<usize, String> {
    parse_range(s, "steps", FOLD_MIN_STEPS, 65536)
}

/// Run `sweep kinks`.
pub fn run(args: KinksArgs) -> Result<()> {
    let start = Instant::now();
    let curve = fold_plus_curve(args.gamma_max, args.points, args.steps)?;
    let elapsed = start.elapsed().as_secs_f64();
    let (gb, ab) = curve.birth;
    let below = format!(
        "no fold curve F+ below its birth point gamma_b = {gb:.6} (--gamma-max {})",
        fmt_num(args.gamma_max)
    );
    if args.json {
        let points: Vec<serde_json::Value> = curve
            .points
            .iter()
            .map(|p| {
                json!({
                    "gamma": p.gamma,
                    "alpha_F": p.alpha,
                    "alpha_F_over_alpha_c2": p.alpha / regimes::alpha_c2(p.gamma),
                    "slope_jump": p.slope_jump,
                    "episode": p.episode.map(|e| json!({"start": e.start, "end": e.end})),
                })
            })
            .collect();
        let mut out = json!({
            "curve": "F+",
            "steps": curve.steps,
            "birth": {"gamma": gb, "alpha": ab, "alpha_over_alpha_c2": ab / regimes::alpha_c2(gb)},
            "gamma_max": args.gamma_max,
            "points": points,
            "elapsed_s": elapsed,
        });
        if curve.points.is_empty() {
            out["note"] = json!(below);
        }
        outln!("{out}")?;
        return Ok(());
    }
    if curve.points.is_empty() {
        outln!("{below}")?;
        return Ok(());
    }
    outln!(
        "# fold curve F+ ({} steps, continuum row): birth at gamma_b = {gb:.6}, alpha_b = {ab:.6} \
         ({:.4} alpha_c2); {elapsed:.2} s",
        curve.steps,
        ab / regimes::alpha_c2(gb)
    )?;
    outln!("# gamma,alpha_F,alpha_F/alpha_c2,slope_jump")?;
    for p in &curve.points {
        outln!(
            "{:.6},{:.9},{:.6},{:.4}",
            p.gamma,
            p.alpha,
            p.alpha / regimes::alpha_c2(p.gamma),
            p.slope_jump
        )?;
    }
    Ok(())
}
