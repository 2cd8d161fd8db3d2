//! `sweep impact`: simulate one impact in dimensionless form and print `P(γ, α, e_n)` with its
//! error estimate, the regime, and optionally the gross-slip history.

use crate::failure::outln;
use std::time::Instant;

use crate::failure::Result;
use clap::{Args, ValueEnum};
use serde_json::json;

use oblique_physics::regimes;
use oblique_solver::history::{slip_history, Episode, SlipSign};
use oblique_solver::impact::{Limits, ALPHA_NO_SLIP};
use oblique_solver::{Accuracy, Law, Method, Preset, Request, Resolution, Scheme, PARAMETER_KEYS};

use crate::args::{
    fmt_num, json_number, parse_alpha, parse_e_n, parse_gamma, parse_law, parse_preset,
    parse_springs, parse_steps, parse_tol,
};
use crate::impact_progress;

#[derive(Clone, Copy, ValueEnum)]
pub enum SchemeArg {
    /// Second order, with an error estimate (default).
    Accurate,
    /// The seed paper's explicit Euler scheme (first order; baseline for comparisons).
    Euler,
}

#[derive(Args)]
pub struct ImpactArgs {
    /// Material group gamma = sqrt((m*/m_t) G*/E*) (`sweep gamma`), from 0.01 to 5 (the tested
    /// range).
    #[arg(long, value_parser = parse_gamma, allow_hyphen_values = true)]
    gamma: f64,
    /// Friction group alpha = (2/7)(m*/m_t) mu v_z0/|u0|; >= 0, or `inf` for no slip.
    #[arg(long, value_parser = parse_alpha, allow_hyphen_values = true)]
    alpha: f64,
    /// Normal restitution e_n of the impact, from 0.3 to 1 (1: elastic, the default). Below 1
    /// the law's parameter that gives this e_n is found first: with the kelvin-voigt law (the
    /// default) the springs are Kelvin-Voigt elements (one relaxation time in the normal and
    /// tangential direction, non-adhesive), and the JSON output reports their relaxation time as
    /// `tau` (in units of (m*/k)^(2/5) v_z0^(-1/5) (4/3)^(2/5)); with the thornton law the
    /// pressure is capped at a limiting pressure (elastic-perfectly plastic), reported as
    /// `yield_pressure` (in units of E* (m* v_z0^2/(E* R*^3))^(1/5)).
    #[arg(long = "e-n", value_parser = parse_e_n, default_value = "1", allow_hyphen_values = true)]
    e_n: f64,
    /// Dissipation law: elastic (e_n = 1 only), kelvin-voigt (viscoelastic springs), thornton
    /// (elastic-perfectly plastic, Thornton 1997: metals, ceramics) or thornton-mdr (its loading
    /// with the MDR's own unloading, for comparison). Default: elastic at e_n = 1, kelvin-voigt
    /// below. P at e_n < 1 depends on the law; answers name theirs.
    #[arg(long, value_parser = parse_law)]
    law: Option<Law>,
    /// Target absolute error of P, > 0 and <= 1e-2; the resolution is doubled until the error
    /// estimate is below it.
    #[arg(long, value_parser = parse_tol, allow_hyphen_values = true, conflicts_with_all = ["springs", "steps"])]
    tol: Option<f64>,
    /// Accuracy preset: fast (tol 1e-4), standard (1e-6, the default) or reference (1e-8).
    #[arg(long, value_parser = parse_preset, conflicts_with_all = ["tol", "springs", "steps"])]
    preset: Option<Preset>,
    /// Springs on the half-row [0, a_max] (>= 2; an error estimate needs >= 16), or 0 for the
    /// continuum row (exact in space, what --tol refines; the only row for e_n < 1); use with
    /// --steps instead of --tol.
    #[arg(long, requires = "steps", value_parser = parse_springs)]
    springs: Option<usize>,
    /// Time steps per contact time (>= 8; an error estimate needs >= 64); use with --springs
    /// instead of --tol.
    #[arg(long, requires = "springs", value_parser = parse_steps)]
    steps: Option<usize>,
    /// Numerical scheme.
    #[arg(long, value_enum, default_value = "accurate")]
    scheme: SchemeArg,
    /// Simulate even where P is known in closed form (full-slip line, gamma = 1 plateau).
    #[arg(long)]
    simulate: bool,
    /// Print one JSON object instead of a summary (alpha = inf is written as the string "inf").
    #[arg(long)]
    json: bool,
    /// Also list the gross-slip episodes (the whole contact at the Coulomb limit, F_t = +/-mu F_N)
    /// of one continuum-row run at the solver's number of steps (at least 1024), with start and
    /// end as fractions of the contact time. Where such an episode vanishes inside the contact,
    /// P(alpha) has a kink (docs/solver.md). Elastic impacts only (e_n = 1).
    #[arg(long)]
    history: bool,
    /// Report every level of the automatic refinement on stderr (level, resolution, error
    /// estimate against the tolerance); shown on a terminal anyway once a solve takes 1 s.
    #[arg(long)]
    progress: bool,
}

/// Default tolerance of `sweep impact` when neither `--tol`, `--preset` nor `--springs/--steps`
/// is given: the `standard` preset.
const DEFAULT_TOL: f64 = 1e-6;

/// Steps of the run behind `sweep impact --history` when the solver answered in closed form.
const HISTORY_MIN_STEPS: usize = 1024;

/// The gross-slip episodes for `--history`, or why there are none to compute.
fn slip_episodes(
    gamma: f64,
    alpha: f64,
    steps: usize,
) -> Result<std::result::Result<Vec<Episode>, &'static str>> {
    if alpha == 0.0 {
        return Ok(Err("frictionless (alpha = 0): nothing resists the slip"));
    }
    if alpha > ALPHA_NO_SLIP {
        return Ok(Err("no slip: the contact never reaches the Coulomb limit"));
    }
    let h = slip_history(gamma, alpha, steps.max(HISTORY_MIN_STEPS))?;
    Ok(Ok(h.episodes))
}

fn sign_str(e: &Episode) -> &'static str {
    match e.sign {
        SlipSign::Plus => "+",
        SlipSign::Minus => "-",
    }
}

/// Run `sweep impact`.
pub fn run(args: ImpactArgs) -> Result<()> {
    let scheme = match args.scheme {
        SchemeArg::Accurate => Scheme::Accurate,
        SchemeArg::Euler => Scheme::Euler,
    };
    let accuracy = match (args.springs, args.steps) {
        (Some(springs), Some(steps)) => Accuracy::Fixed(Resolution { springs, steps }),
        _ => Accuracy::Tolerance(
            args.tol
                .or(args.preset.map(Preset::tolerance))
                .unwrap_or(DEFAULT_TOL),
        ),
    };
    let law = args.law.unwrap_or(Law::for_restitution(args.e_n));
    if args.history && args.e_n < 1.0 {
        return Err(crate::failure::Failure::usage(
            "--history lists the gross-slip episodes of elastic impacts only (e_n = 1)".into(),
        ));
    }
    let request = Request::new(args.gamma, args.alpha)
        .e_n(args.e_n)
        .law(law)
        .accuracy(accuracy)
        .scheme(scheme)
        .forced(args.simulate)
        .limits(Limits::default());
    let start = Instant::now();
    let mut progress = impact_progress::ImpactProgress::new(args.progress);
    let sol = request.solve_observed(&mut |event| progress.report(event));
    progress.finish();
    let sol = sol?;
    let elapsed = start.elapsed().as_secs_f64();
    let e_n = sol.e_n;
    // α_c1(e_n) marks the end of the full-slip line only for γ > 1; below, the line ends at
    // α_c2 and the formula for α_c1 means nothing (negative for γ < 1/√2; physics.md).
    // Thornton's law (below e_n = 1) leaves the full-slip line at every α > 0 (its limits jump
    // at the switch to unloading), and its MDR-unloading variant's critical α has no closed
    // form: no closed-form regime is named for either.
    let classified = !matches!(sol.law.law(), Law::Thornton | Law::ThorntonMdr) || e_n == 1.0;
    let alpha_c1 =
        (classified && args.gamma >= 1.0).then(|| regimes::alpha_c1_dissipative(args.gamma, e_n));
    let alpha_c2 = regimes::alpha_c2(args.gamma);
    // The continuum row has no spring count; a closed form has no resolution at all.
    let (springs, steps, row) = match sol.method {
        Method::ClosedForm => (None, None, None),
        Method::Simulated if sol.resolution.springs == 0 => {
            (None, Some(sol.resolution.steps), Some("continuum"))
        }
        Method::Simulated => (
            Some(sol.resolution.springs),
            Some(sol.resolution.steps),
            Some("springs"),
        ),
    };
    let e_t = regimes::tangential_restitution(sol.p);
    let regime = classified.then(|| regimes::Regime::of_dissipative(args.gamma, args.alpha, e_n));
    let method = match sol.method {
        Method::ClosedForm => "closed-form",
        Method::Simulated => "simulated",
    };
    let episodes = if args.history {
        Some(slip_episodes(args.gamma, args.alpha, sol.resolution.steps)?)
    } else {
        None
    };
    if args.json {
        let out = json!({
            "gamma": args.gamma,
            "alpha": json_number(args.alpha),
            "e_n": e_n,
            "law": sol.law.name(),
            "P": sol.p,
            "e_t": e_t,
            "error_estimate": sol.estimate(),
            "springs": springs,
            "steps": steps,
            "row": row,
            "scheme": sol.scheme.name(),
            "method": method,
            "regime": regime.map(|r| r.name()),
            "alpha_c1": alpha_c1,
            "alpha_c2": alpha_c2,
            "elapsed_s": elapsed,
        });
        let mut out = out;
        // The law's parameters under their keys (`tau`), through the law.
        for (key, value) in PARAMETER_KEYS.into_iter().zip(sol.law.values()) {
            out[key] = json!(value);
        }
        if let Some(why) = sol.no_estimate {
            out["no_estimate_reason"] = json!(why.to_string());
        }
        if let Some(ep) = &episodes {
            out["gross_slip"] = match ep {
                Ok(list) => json!(list
                    .iter()
                    .map(|e| json!({"sign": sign_str(e), "start": e.start, "end": e.end}))
                    .collect::<Vec<_>>()),
                Err(why) => json!(why),
            };
        }
        outln!("{out}")?;
    } else {
        let head = if e_n == 1.0 && sol.law.law() == Law::Elastic {
            format!(
                "P(gamma = {}, alpha = {}) = {:.9}",
                fmt_num(args.gamma),
                fmt_num(args.alpha),
                sol.p
            )
        } else {
            format!(
                "P(gamma = {}, alpha = {}, e_n = {}) = {:.9}",
                fmt_num(args.gamma),
                fmt_num(args.alpha),
                fmt_num(e_n),
                sol.p
            )
        };
        match (sol.estimate(), sol.no_estimate) {
            (Some(est), _) => outln!("{head}  +/- {est:.1e}")?,
            (None, Some(why)) => outln!("{head}  (no error estimate: {why})")?,
            (None, None) => outln!("{head}  (no error estimate)")?,
        }
        outln!("e_t = (2P + 5)/7 = {e_t:.9}   (solid sphere, no initial spin)")?;
        if let Some(parameters) = sol.law.describe() {
            outln!("law {} ({parameters})", sol.law.name())?;
        }
        match (regime, alpha_c1) {
            (Some(r), Some(c1)) => outln!(
                "regime {} (alpha_c1 = {c1:.6}, alpha_c2 = {alpha_c2:.6})",
                r.name()
            )?,
            (Some(r), None) => outln!(
                "regime {} (alpha_c2 = {alpha_c2:.6}; for gamma < 1 the full-slip line ends at \
                 alpha_c2, alpha_c1 does not apply)",
                r.name()
            )?,
            (None, _) => outln!(
                "regime not classified (the {} law has no closed-form slip regimes; alpha_c2 = \
                 {alpha_c2:.6})",
                sol.law.name()
            )?,
        }
        match sol.method {
            Method::ClosedForm => outln!("closed form (exact; --simulate to simulate anyway)")?,
            Method::Simulated => outln!(
                "{} scheme, {}, {:.3} ms",
                sol.scheme.name(),
                sol.resolution,
                elapsed * 1e3
            )?,
        }
        match &episodes {
            None => {}
            Some(Err(why)) => outln!("gross slip: {why}")?,
            Some(Ok(list)) if list.is_empty() => {
                outln!("gross slip: none (the contact never slips as a whole)")?
            }
            Some(Ok(list)) => {
                let parts: Vec<String> = list
                    .iter()
                    .map(|e| format!("{} {:.4}..{:.4}", sign_str(e), e.start, e.end))
                    .collect();
                outln!(
                    "gross slip (F_t = +/-mu F_N; start..end in units of t_c): {}",
                    parts.join(", ")
                )?;
            }
        }
    }
    Ok(())
}
