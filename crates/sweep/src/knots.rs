//! The knots of the partial-slip coordinate of a table of Thornton's law (`nodes.knots`):
//! its kinks inside the slip regions (`docs/solver.md`, "Kinks inside the slip regions")
//! traced on a grid of `(γ, e_n)` and sent to fixed cell edges (`docs/table-format.md`, "The
//! knots"), so that no leaf straddles them; and the knot of its stick patch, the loading fold
//! `α_L` ([`loading_fold_knots`]).
//!
//! | knot | kink | `c'` | grading |
//! |---|---|---|---|
//! | `α_c1(γ, e_n)` | the Kelvin–Voigt end of the full-slip line, where the coordinate changes its map (`c = 1/2`); the law's own edge `α₁` lies within a few per cent of it | 1/2 | none |
//! | `α_R(γ, e_n)` | the re-slip fold: `P` departs like `(α/α_R − 1)^{3/2}` above it | 5/8 | above |
//! | `2/7` | the end of the first gross-slip episode at the switch: a jump of curvature | 3/4 | none |
//! | `α_S(γ, e_n)` | the switch fold: `P` departs like `(1 − α/α_S)^{3/2}` below it | 7/8 | below |
//! | `α₊lo(γ, e_n)`, `α₊hi(γ, e_n)` | the edges of the `+` strip (γ ≳ 1.95, small `e_n`), where the table's range meets it | 15/16, 61/64 | none |
//!
//! As `e_n → 1` the folds merge towards `α = 2/7` (`α_S` − 2/7 falls like `√(1 − e_n)`), so
//! the knots apply up to [`E_N_MAX`] only. The strip exists over part of the knots' region
//! only ([`strip_shares`]): elsewhere its two knots continue its edges as ghosts, cell edges
//! where `P` has no kink.

use rayon::prelude::*;

use super::SweepError;
use crate::kink::KinkSurface;
use oblique_solver::history::{loading_fold_thornton, reslip_fold_thornton, switch_fold_thornton};
use oblique_table::surface::{Axis, AxisMap, Knots, PartialMap, PatchKind};

/// Highest `e_n` the knots apply at (rounded down to a sixteenth of a root cell).
pub const E_N_MAX: f64 = 0.98;
/// Lowest γ the knots apply from (rounded up to a sixteenth of a root cell): next to γ = 1 the
/// re-slip fold `α_R` does not exist (none at γ 1.15, `e_n` 0.3), and at γ 1.02–1.1 the switch
/// fold `α_S` lies above `α_c2`; from γ 1.2 all four lie in order over `e_n` 0.3–0.98.
pub const GAMMA_MIN: f64 = 1.2;
/// Largest grid spacing along γ of the traced kinks.
pub const GAMMA_STEP: f64 = 0.025;
/// Largest grid spacing along `e_n` of the traced kinks.
pub const E_N_STEP: f64 = 0.01;
/// Steps per contact time of the tracing (the folds within about 1e-6 of their converged
/// values, `docs/solver.md`).
pub const STEPS: usize = 2048;
/// Where the knots are sent: `α_c1`, `α_R`, `2/7`, `α_S`.
pub const C_STAR: [f64; 4] = [0.5, 0.625, 0.75, 0.875];
/// Their grading ([`oblique_table::surface::Grade`] values): none, above, none, below.
pub const GRADE: [u8; 4] = [0, 2, 0, 1];
/// Names of the knots in messages.
const NAMES: [&str; 4] = ["alpha_c1", "alpha_R", "2/7", "alpha_S"];
/// Where the edges of the `+` strip are sent, between `α_S` (7/8) and `α_c2` (1), near their
/// usual share of that span (the lower edge at 0.3–0.7 of it, the strip 0.01–0.05 wide): not
/// root-cell edges, so the tree splits every cell across them without evaluating it.
pub const STRIP_C_STAR: [f64; 2] = [0.9375, 0.953125];
/// Largest degree in each of γ and `e_n` of the strip knots' fitted surfaces
/// ([`strip_shares`]; lower where fewer than twice the coefficients' points hold the strip,
/// or where the knots of this degree cross between grid points).
/// Over γ 2–2.2, `e_n` 0.3–0.4 the fitted edges lie within 1e-3 of the traced ones (shares of
/// `(c_S, 1)`) at nine in ten points with degree 5 (2e-3 and 3e-3 with degree 4 and 3), up to
/// 2.1e-3 (`cargo run --release -p oblique-tools --bin stripknots -- 2 2.2 0.3 0.4`).
pub const STRIP_FIT_DEGREE: usize = 5;
/// Smallest share of `(c_S, 1)` between two strip knots, and between them and its ends: the
/// strip is born with zero width, and its ghosts keep this gap.
pub const STRIP_GAP: f64 = 0.005;

/// `n ≥ 4` points over `[first, last]` at equal steps of at most the step asked for.
#[derive(Debug, Clone, Copy)]
struct Grid {
    first: f64,
    step: f64,
    n: usize,
    last: f64,
}

impl Grid {
    fn new(lo: f64, hi: f64, step: f64) -> Self {
        let n = (((hi - lo) / step).ceil() as usize + 1).max(4);
        Grid {
            first: lo,
            step: (hi - lo) / (n - 1) as f64,
            n,
            last: hi,
        }
    }

    /// Point `i`: `last` itself for the last one.
    fn at(self, i: usize) -> f64 {
        if i + 1 == self.n {
            self.last
        } else {
            self.first + self.step * i as f64
        }
    }
}

/// Root-cell positions along `e_n` of a patch over `e_range` with `blocks` root cells and the
/// map `map` of the axis ([`Axis::x`], [`Axis::at`]), and back; for a linear axis the linear
/// expressions themselves, `(e − lo)/(hi − lo)·blocks` and `lo + (hi − lo)·v/blocks`.
#[derive(Debug, Clone, Copy)]
struct ECells {
    lo: f64,
    hi: f64,
    blocks: f64,
    map: AxisMap,
}

impl ECells {
    fn new((lo, hi): (f64, f64), blocks: usize, map: AxisMap) -> ECells {
        ECells {
            lo,
            hi,
            blocks: blocks as f64,
            map,
        }
    }

    /// The root-cell position of `e`.
    fn cells(&self, e: f64) -> f64 {
        match self.map {
            AxisMap::Linear => (e - self.lo) / (self.hi - self.lo) * self.blocks,
            _ => self.axis().x(e) * self.blocks,
        }
    }

    /// The `e_n` at root-cell position `v`.
    fn at(&self, v: f64) -> f64 {
        match self.map {
            AxisMap::Linear => self.lo + (self.hi - self.lo) * v / self.blocks,
            _ => self.axis().at(v / self.blocks),
        }
    }

    fn axis(&self) -> Axis {
        Axis {
            name: oblique_table::surface::AxisName::RESTITUTION_N,
            map: self.map,
            lo: self.lo,
            hi: self.hi,
            blocks: 1,
        }
    }
}

/// The knots of the partial-slip patch over `γ ∈ gammas` (`bg` root cells) and `e_n ∈ e_range`
/// (`be` root cells), with the partial-slip coordinate of Thornton's law
/// ([`PartialMap::Slip`]); `None` when the `e_n` range starts above [`E_N_MAX`] or the γ range
/// ends below [`GAMMA_MIN`]. `Err` names the kink and the point where it is missing or out of
/// order.
///
/// With `strip` (the traced edges of the `+` strip, `kink::thornton_plus_strip_surfaces`)
/// two more knots follow its edges ([`STRIP_C_STAR`], [`strip_shares`]) where some grid
/// point of the region holds it inside the patch, and the knots' line stays strictly increasing
/// between the grid points (checked on a grid four times finer): the fit of the highest degree
/// up to [`STRIP_FIT_DEGREE`] that does, else the four knots alone.
pub fn thornton_knots(
    gammas: (f64, f64),
    bg: usize,
    e_range: (f64, f64),
    be: usize,
    e_map: AxisMap,
    strip: Option<&[Option<KinkSurface>; 2]>,
) -> Result<Option<Knots>, SweepError> {
    let (e_lo, e_hi) = e_range;
    let ec = ECells::new(e_range, be, e_map);
    // The region along e_n: root-cell units, down to a multiple of 1/16.
    let top = if e_hi <= E_N_MAX {
        be as f64
    } else {
        (ec.cells(E_N_MAX) * 16.0).floor() / 16.0
    };
    if top <= 0.0 {
        return Ok(None);
    }
    let e_top = ec.at(top);
    // The region along γ: from GAMMA_MIN, up to a multiple of 1/16 of a root cell.
    let (g_lo, g_hi) = gammas;
    let from = if g_lo >= GAMMA_MIN {
        0.0
    } else {
        ((GAMMA_MIN - g_lo) / (g_hi - g_lo) * bg as f64 * 16.0).ceil() / 16.0
    };
    if from >= bg as f64 {
        return Ok(None);
    }
    let g_from = g_lo + (g_hi - g_lo) * from / bg as f64;
    let gg = Grid::new(g_from, g_hi, GAMMA_STEP);
    let eg = Grid::new(e_lo, e_top, E_N_STEP);
    let (ng, ne) = (gg.n, eg.n);
    let points: Vec<(f64, f64)> = (0..ng)
        .flat_map(|i| (0..ne).map(move |l| (gg.at(i), eg.at(l))))
        .collect();
    let traced: Vec<[f64; 4]> = points
        .par_iter()
        .map(|&(g, e)| knots_at(g, e))
        .collect::<Result<_, _>>()?;
    let region = [from, bg as f64, 0.0, top];
    // The four knots, and the strip's two where `extra` holds them at every point.
    let make = |extra: &[[f64; 2]]| {
        let k = if extra.is_empty() { 4 } else { 6 };
        // `knot[j, i, l]`, j the knot.
        let mut knot = vec![0.0; k * ng * ne];
        for (p, t) in traced.iter().enumerate() {
            let all = t.iter().chain(extra.get(p).into_iter().flatten());
            for (j, &v) in all.enumerate() {
                knot[j * ng * ne + p] = v;
            }
        }
        let (c_star, grade) = if k == 4 {
            (C_STAR.to_vec(), GRADE.to_vec())
        } else {
            (
                C_STAR.iter().chain(&STRIP_C_STAR).copied().collect(),
                GRADE.iter().chain(&[0, 0]).copied().collect(),
            )
        };
        Knots::new(
            gg.first,
            gg.step,
            eg.first,
            eg.step,
            region,
            c_star,
            grade,
            [k, ng, ne],
            knot,
        )
        .map_err(|what| SweepError::Knots {
            knot: "all",
            gamma: gammas.0,
            e_n: e_lo,
            what,
        })
    };
    if let Some(strip) = strip {
        // `c` of `α_S`, the knot below the strip's.
        let s_of = |p: usize| traced[p][3];
        let raw: Vec<Option<[f64; 2]>> = points
            .iter()
            .enumerate()
            .map(|(p, &(g, e))| {
                let c = |a: Option<f64>| {
                    a.map(|a| {
                        PatchKind::PartialSlip.coord_at(PartialMap::Slip, g, a, e, f64::INFINITY)
                    })
                };
                let edge = |k: usize| c(strip[k].as_ref().and_then(|s| s.alpha_at(g, e)));
                let (lo, hi) = (edge(0), edge(1));
                let cs = s_of(p);
                let share = |c: f64| (c - cs) / (1.0 - cs);
                match (lo, hi) {
                    (Some(lo), Some(hi)) if share(lo) > 0.0 && share(hi) < 1.0 && hi > lo => {
                        Some([share(lo), share(hi)])
                    }
                    _ => None,
                }
            })
            .collect();
        // From the highest degree the points allow down to a plane: the first fit whose
        // knots stay in order between the grid points.
        for degree in (1..=STRIP_FIT_DEGREE).rev() {
            let Some(shares) = strip_shares(&points, &raw, degree) else {
                continue;
            };
            let extra: Vec<[f64; 2]> = shares
                .iter()
                .enumerate()
                .map(|(p, f)| {
                    let cs = s_of(p);
                    [cs + f[0] * (1.0 - cs), cs + f[1] * (1.0 - cs)]
                })
                .collect();
            let knots = make(&extra)?;
            if increasing_between(&knots, (gg, eg)) {
                return Ok(Some(knots));
            }
        }
    }
    let knots = make(&[])?;
    Ok(Some(knots))
}

/// The shares `f = (c − c_S)/(1 − c_S)` of the strip's two knots at the grid's `points` from
/// the edges found there (`raw`, both inside `(c_S, 1)`): a smooth surface fitted to them
/// and continued smoothly where the strip is not (a kink of a knot along `e_n` or γ would
/// put a kink into `P` over the whole coordinate between its neighbours). The lower edge as
/// `f_lo = g + (1 − 3g) σ(u)` and the width as `f_hi = f_lo + g + (1 − 2g − f_lo) σ(v)`
/// ([`STRIP_GAP`] `g`, `σ` the logistic function), `u` and `v` polynomials of degree up to
/// [`STRIP_FIT_DEGREE`] in each of γ and `e_n` (least squares over the points that hold the
/// strip), so that the knots keep their order and gaps everywhere. `None` with fewer than
/// eight such points or a singular fit.
fn strip_shares(
    points: &[(f64, f64)],
    raw: &[Option<[f64; 2]>],
    degree: usize,
) -> Option<Vec<[f64; 2]>> {
    let g = STRIP_GAP;
    let held: Vec<((f64, f64), [f64; 2])> = points
        .iter()
        .zip(raw)
        .filter_map(|(&p, r)| r.map(|r| (p, r)))
        .filter(|(_, [lo, hi])| *lo > g && *hi < 1.0 - g && hi - lo > g)
        .collect();
    let n = (2..=degree + 1).rev().find(|n| held.len() >= 2 * n * n)?;
    let tensor = Tensor::over(held.iter().map(|&(p, _)| p), n);
    let basis = |gm: f64, e: f64| tensor.basis(gm, e);
    let logit = |t: f64| (t / (1.0 - t)).ln();
    let sigma = |x: f64| 1.0 / (1.0 + (-x).exp());
    let u = least_squares(
        &held
            .iter()
            .map(|&((gm, e), [lo, _])| (basis(gm, e), logit((lo - g) / (1.0 - 3.0 * g))))
            .collect::<Vec<_>>(),
    )?;
    let v = least_squares(
        &held
            .iter()
            .map(|&((gm, e), [lo, hi])| (basis(gm, e), logit((hi - lo - g) / (1.0 - 2.0 * g - lo))))
            .collect::<Vec<_>>(),
    )?;
    let eval = |c: &[f64], gm: f64, e: f64| -> f64 {
        basis(gm, e).iter().zip(c).map(|(b, c)| b * c).sum()
    };
    Some(
        points
            .iter()
            .map(|&(gm, e)| {
                let lo = g + (1.0 - 3.0 * g) * sigma(eval(&u, gm, e));
                let hi = lo + g + (1.0 - 2.0 * g - lo) * sigma(eval(&v, gm, e));
                [lo, hi]
            })
            .collect(),
    )
}

/// Whether the knots' line is strictly increasing (and inside `(0, 1)`) on a grid four times
/// finer than theirs along both axes: the line between grid points is interpolated.
fn increasing_between(knots: &Knots, (gg, eg): (Grid, Grid)) -> bool {
    let (ng, ne) = (4 * (gg.n - 1), 4 * (eg.n - 1));
    (0..=ng).all(|i| {
        let g = gg.first + (gg.last - gg.first) * i as f64 / ng as f64;
        (0..=ne).all(|l| {
            let e = eg.first + (eg.last - eg.first) * l as f64 / ne as f64;
            let k = knots.line(g, e);
            let k = k.knots();
            k.first().is_some_and(|&f| f > 0.0)
                && k.last().is_some_and(|&f| f < 1.0)
                && k.windows(2).all(|w| w[1] > w[0])
        })
    })
}

/// The coordinates `c` of the four kinks at `(γ, e_n)`, checked to lie in order inside `(0, 1)`.
fn knots_at(gamma: f64, e_n: f64) -> Result<[f64; 4], SweepError> {
    let fail = |j: usize, what: String| SweepError::Knots {
        knot: NAMES[j],
        gamma,
        e_n,
        what,
    };
    let missing = |j: usize| fail(j, "no such kink here".into());
    // `α_c1` is `c = 1/2` of the coordinate, where its map changes (linear in α below,
    // graded above): a knot that stays there keeps that change on a cell edge.
    let a1 = oblique_physics::regimes::alpha_c1_dissipative(gamma, e_n);
    let ar = reslip_fold_thornton(gamma, e_n, STEPS)
        .map_err(|e| fail(1, e.to_string()))?
        .ok_or_else(|| missing(1))?;
    let as_ = switch_fold_thornton(gamma, e_n, STEPS)
        .map_err(|e| fail(3, e.to_string()))?
        .ok_or_else(|| missing(3))?;
    let alphas = [a1, ar, 2.0 / 7.0, as_];
    let mut out = [0.0; 4];
    let mut below = 0.0;
    for (j, &a) in alphas.iter().enumerate() {
        let c = PatchKind::PartialSlip.coord_at(PartialMap::Slip, gamma, a, e_n, f64::INFINITY);
        if !(c > below && c < 1.0) {
            return Err(fail(
                j,
                format!(
                    "at alpha = {a} (c = {c}): the kinks must lie in the order alpha_c1 < alpha_R \
                     < 2/7 < alpha_S < alpha_c2"
                ),
            ));
        }
        below = c;
        out[j] = if j == 0 { 0.5 } else { c };
    }
    Ok(out)
}

/// Where the loading fold `α_L` is sent in the stick patch ([`loading_fold_knots`]).
pub const LOADING_C_STAR: f64 = 0.5;
/// Smallest stick coordinate of `α_L` inside its knots' region: along `e_n` the fold falls to
/// `α_c2` (the patch's lower edge, `c = 0`; at γ 1.6 between `e_n` 0.85 and 0.9, at γ 2.6
/// between 0.7 and 0.8), and the region ends at the last row of its grid where it still lies
/// this far above that edge at every γ.
pub const LOADING_C_MIN: f64 = 0.05;

/// The knot of the loading fold `α_L(γ, e_n)` in the stick patch `stick_high` of a table of
/// Thornton's law (`nodes.knots`): below `α_L` a zone of the contact reaches the `+μq` limit
/// while it loads, above it none does, and `P` departs from its smooth continuation like
/// `(1 − α/α_L)^{3/2}` below it ([`loading_fold_thornton`]). Traced on a grid of at most
/// [`GAMMA_STEP`] by [`E_N_STEP`] from [`GAMMA_MIN`] (up to a root-cell edge) and from the
/// lowest `e_n` upwards, each γ column up to the first row where the fold is gone or lies below
/// [`LOADING_C_MIN`]; the region holds the rows where it lies above that at every γ (its top
/// the last such row, down to a root-cell edge) and on one branch of it (from the first row
/// above the highest jump of any column, [`branch_start`], up to a root-cell edge), sent to
/// [`LOADING_C_STAR`] and graded below. `None` where fewer than four rows qualify, the region would hold no whole root
/// cell, or the γ range ends below [`GAMMA_MIN`]. `alpha_max` is the table's `α_max`.
pub fn loading_fold_knots(
    gammas: (f64, f64),
    bg: usize,
    e_range: (f64, f64),
    be: usize,
    e_map: AxisMap,
    alpha_max: f64,
) -> Result<Option<Knots>, SweepError> {
    let (g_lo, g_hi) = gammas;
    let (e_lo, e_hi) = e_range;
    let ec = ECells::new(e_range, be, e_map);
    // From GAMMA_MIN up to a root-cell edge (as the top along e_n below).
    let from = if g_lo >= GAMMA_MIN {
        0.0
    } else {
        ((GAMMA_MIN - g_lo) / (g_hi - g_lo) * bg as f64).ceil()
    };
    if from >= bg as f64 {
        return Ok(None);
    }
    let g_from = g_lo + (g_hi - g_lo) * from / bg as f64;
    let gg = Grid::new(g_from, g_hi, GAMMA_STEP);
    let eg = Grid::new(e_lo, e_hi, E_N_STEP);
    let (ng, ne_all) = (gg.n, eg.n);
    // Each column's coordinates of α_L, from the lowest e_n up to the first row that fails.
    let columns: Vec<Vec<f64>> = (0..ng)
        .into_par_iter()
        .map(|i| {
            let g = gg.at(i);
            let mut cs = Vec::new();
            for l in 0..ne_all {
                let e = eg.at(l);
                let fold = loading_fold_thornton(g, e, STEPS).map_err(|err| SweepError::Knots {
                    knot: "alpha_L",
                    gamma: g,
                    e_n: e,
                    what: err.to_string(),
                })?;
                let c =
                    fold.map(|a| PatchKind::Stick.coord_at(PartialMap::Slip, g, a, e, alpha_max));
                match c {
                    Some(c) if (LOADING_C_MIN..1.0).contains(&c) => cs.push(c),
                    _ => break,
                }
            }
            Ok(cs)
        })
        .collect::<Result<_, SweepError>>()?;
    let ne = columns.iter().map(Vec::len).min().unwrap_or(0);
    // From γ ≈ 1.75 the located fold jumps between two branches at small e_n (0.32 at γ 1.75,
    // 0.46 at 2.6): the knot follows the branch above the highest jump of any column, from
    // its first row, so that it is continuous where it is interpolated.
    let start = columns
        .iter()
        .map(|c| branch_start(&c[..ne]))
        .max()
        .unwrap_or(0);
    if ne < start + 4 {
        return Ok(None);
    }
    // The region along e_n: from that row up to the last common row, both rounded into the
    // grid to root-cell edges. An edge inside a root cell splits every cell across it down to
    // its depth without evaluating them, and there the knot lies next to α_c2, where the map
    // stretches the patch most: at a sixteenth, over γ 1.6–2.0 and e_n 0.65–0.9 (target 5e-5),
    // the stick patch needed 66 458 nodes with the knot against 51 895 without.
    let cells = |e: f64| ec.cells(e);
    let e_first = eg.at(start);
    let bottom = if start == 0 {
        0.0
    } else {
        (cells(e_first) - 1e-9).ceil()
    };
    let top = if ne == ne_all {
        be as f64
    } else {
        cells(eg.at(ne - 1)).floor()
    };
    if top <= bottom {
        return Ok(None);
    }
    let mut knot = Vec::with_capacity(ng * (ne - start));
    for column in &columns {
        knot.extend_from_slice(&column[start..ne]);
    }
    // The grid is the tracing's, over the rows of the branch.
    Knots::new(
        gg.first,
        gg.step,
        e_first,
        eg.step,
        [from, bg as f64, bottom, top],
        vec![LOADING_C_STAR],
        vec![1],
        [1, ng, ne - start],
        knot,
    )
    .map(Some)
    .map_err(|what| SweepError::Knots {
        knot: "alpha_L",
        gamma: g_lo,
        e_n: e_lo,
        what,
    })
}

/// Largest second difference along `e_n` of the loading fold's coordinate (rows
/// [`E_N_STEP`] apart) on one branch: over γ 1.6–2.6 it is at most 2e-4 on a branch, and
/// 0.055–0.15 where the located fold jumps to another (`thornfold` on that grid).
pub const LOADING_JUMP: f64 = 0.01;

/// The first row of the branch of the loading fold's column `c` (coordinates by rows of
/// `e_n`) that holds its top row: the row after the highest jump, where a second difference
/// exceeds [`LOADING_JUMP`] (a jump between rows `j − 1` and `j` shows at rows `j` and `j + 1`);
/// 0 where there is none.
fn branch_start(c: &[f64]) -> usize {
    (2..c.len())
        .rev()
        .find(|&k| (c[k] - 2.0 * c[k - 1] + c[k - 2]).abs() > LOADING_JUMP)
        .map_or(0, |k| k - 1)
}

/// Degree of the fitted fold surface F₋ in each of γ and `e_n` ([`fold_minus_knots`]).
pub const FIT_DEGREE: usize = 4;
/// Largest relative difference between the fitted F₋ and its traced nodes that
/// [`fold_minus_knots`] accepts: a fold `(α − α_F)^{3/2}` that far from a cell edge moves a
/// leaf's cubic by about 1e-7.
pub const FIT_TOL: f64 = 1e-4;

/// The knot of the fold F₋ of a Kelvin–Voigt table's partial-slip patch (`nodes.knots`):
/// F₋ traced as for the probes ([`kink::fold_minus_surface`]), `ln α_F(γ, e_n)` fitted by a
/// polynomial of degree [`FIT_DEGREE`] in each variable (least squares over the traced nodes,
/// within [`FIT_TOL`] of each), which continues it smoothly where F₋ does not exist (beyond
/// its end along `e_n` and below its birth along γ, where `P` is smooth and any smooth knot
/// does), tabulated over the box of root cells that holds every traced node and reaches
/// [`BOX_MARGIN`] below them in γ and `e_n` (edges rounded outwards to a sixteenth of a root
/// cell), sent to the root-cell edge `c*` nearest to its
/// middle and graded above (`P` departs from its smooth continuation like `(α − α_F)^{3/2}`
/// above F₋). `None` when the domain holds no F₋. `map` is the table's partial-slip map,
/// `alpha_max` its `α_max`.
pub fn fold_minus_knots(
    gammas: (f64, f64),
    bg: usize,
    e_range: (f64, f64),
    be: usize,
    bc: usize,
    map: PartialMap,
) -> Result<Option<Knots>, SweepError> {
    let Some(surface) = crate::kink::fold_minus_surface(gammas, e_range)? else {
        return Ok(None);
    };
    let nodes: Vec<(f64, f64, f64)> = surface
        .nodes()
        .into_iter()
        .filter(|&(g, e, _)| g >= gammas.0 - 0.02 && e >= e_range.0 - 0.01)
        .collect();
    if nodes.len() < (FIT_DEGREE + 1) * (FIT_DEGREE + 1) {
        return Ok(None);
    }
    let fail = |gamma: f64, e_n: f64, what: String| SweepError::Knots {
        knot: "F-",
        gamma,
        e_n,
        what,
    };
    let tensor = Tensor::over(nodes.iter().map(|&(g, e, _)| (g, e)), FIT_DEGREE + 1);
    let [g0, _, e0, _] = tensor.bounds;
    let basis = |g: f64, e: f64| tensor.basis(g, e);
    let coef = least_squares(
        &nodes
            .iter()
            .map(|&(g, e, l)| (basis(g, e), l))
            .collect::<Vec<_>>(),
    )
    .ok_or_else(|| fail(g0, e0, "the fit of F- is singular".into()))?;
    let fit = |g: f64, e: f64| -> f64 { basis(g, e).iter().zip(&coef).map(|(b, c)| b * c).sum() };
    for &(g, e, l) in &nodes {
        let d = (fit(g, e) - l).exp() - 1.0;
        if d.abs() > FIT_TOL {
            return Err(fail(
                g,
                e,
                format!(
                    "the fitted F- is {d:.2e} (relative) from the traced one, more than {FIT_TOL:e}"
                ),
            ));
        }
    }
    // The region: root-cell units, outwards to a sixteenth.
    let (gl, gh) = gammas;
    let (el, eh) = e_range;
    let pos = |v: f64, lo: f64, hi: f64, blocks: usize| {
        ((v - lo) / (hi - lo) * blocks as f64).clamp(0.0, blocks as f64)
    };
    let from_g = (pos(g0 - BOX_MARGIN, gl, gh, bg) * 16.0).floor() / 16.0;
    let from_e = (pos(e0 - BOX_MARGIN, el, eh, be) * 16.0).floor() / 16.0;
    let region = [from_g, bg as f64, from_e, be as f64];
    let g_from = gl + (gh - gl) * from_g / bg as f64;
    let e_from = el + (eh - el) * from_e / be as f64;
    let gg = Grid::new(g_from, gh, STEP_F_MINUS_GAMMA);
    let eg = Grid::new(e_from, eh, STEP_F_MINUS_E_N);
    let (ng, ne) = (gg.n, eg.n);
    let mut knot = Vec::with_capacity(ng * ne);
    for i in 0..ng {
        let g = gg.at(i);
        for l in 0..ne {
            let e = eg.at(l);
            let a = fit(g, e).exp();
            let c = PatchKind::PartialSlip.coord_at(map, g, a, e, f64::INFINITY);
            if !(c > 0.0 && c < 1.0) {
                return Err(fail(
                    g,
                    e,
                    format!("the fitted F- at alpha = {a} lies outside the patch (c = {c})"),
                ));
            }
            knot.push(c);
        }
    }
    let mut sorted = knot.clone();
    sorted.sort_by(f64::total_cmp);
    let middle = sorted[sorted.len() / 2];
    let c_star =
        ((middle * bc as f64).round() / bc as f64).clamp(1.0 / bc as f64, 1.0 - 1.0 / bc as f64);
    if !(c_star > 0.0 && c_star < 1.0) {
        return Err(fail(
            gl,
            el,
            format!("blocks_coord = {bc}: the knot needs a root-cell edge inside the patch (>= 2)"),
        ));
    }
    Knots::new(
        gg.first,
        gg.step,
        eg.first,
        eg.step,
        region,
        vec![c_star],
        vec![2],
        [1, ng, ne],
        knot,
    )
    .map(Some)
    .map_err(|what| fail(gl, el, what))
}

/// How far below the lowest traced γ and `e_n` of F₋ its knot's box reaches (before rounding
/// outwards to a sixteenth of a root cell): where F₋ is born and where it ends along `e_n`, `P`
/// bends sharply over a short range without a fold yet, and a knot there (the fit's smooth
/// continuation) keeps those leaves away from a cell that straddles the box's edge.
pub const BOX_MARGIN: f64 = 0.02;

/// Grid spacings of the F₋ knot (those of the traced surface).
const STEP_F_MINUS_GAMMA: f64 = 0.01;
const STEP_F_MINUS_E_N: f64 = 0.005;

/// The tensor basis `x^i y^j` (`i, j < n`) of a polynomial fit in `(γ, e_n)`, each scaled to
/// `[−1, 1]` over the box of the fitted points.
struct Tensor {
    /// `[γ lo, γ hi, e_n lo, e_n hi]` of the points.
    bounds: [f64; 4],
    n: usize,
}

impl Tensor {
    fn over(points: impl Iterator<Item = (f64, f64)>, n: usize) -> Self {
        let mut b = [f64::MAX, f64::MIN, f64::MAX, f64::MIN];
        for (g, e) in points {
            b = [b[0].min(g), b[1].max(g), b[2].min(e), b[3].max(e)];
        }
        Tensor { bounds: b, n }
    }

    fn basis(&self, g: f64, e: f64) -> Vec<f64> {
        let scale = |v: f64, lo: f64, hi: f64| {
            if hi > lo {
                2.0 * (v - lo) / (hi - lo) - 1.0
            } else {
                0.0
            }
        };
        let [g0, g1, e0, e1] = self.bounds;
        let (x, y) = (scale(g, g0, g1), scale(e, e0, e1));
        let mut b = Vec::with_capacity(self.n * self.n);
        let mut xi = 1.0;
        for _ in 0..self.n {
            let mut yj = 1.0;
            for _ in 0..self.n {
                b.push(xi * yj);
                yj *= y;
            }
            xi *= x;
        }
        b
    }
}

/// The least-squares coefficients of `rows` (`(basis values, value)`), by the normal equations
/// and Gaussian elimination with partial pivoting; `None` when they are singular.
fn least_squares(rows: &[(Vec<f64>, f64)]) -> Option<Vec<f64>> {
    let n = rows.first()?.0.len();
    let mut a = vec![vec![0.0; n + 1]; n];
    for (b, v) in rows {
        for i in 0..n {
            for j in 0..n {
                a[i][j] += b[i] * b[j];
            }
            a[i][n] += b[i] * v;
        }
    }
    for col in 0..n {
        let piv = (col..n).max_by(|&x, &y| a[x][col].abs().total_cmp(&a[y][col].abs()))?;
        if a[piv][col].abs() < 1e-300 {
            return None;
        }
        a.swap(col, piv);
        let pivot = a[col].clone();
        for (r, row) in a.iter_mut().enumerate() {
            if r != col {
                let f = row[col] / pivot[col];
                for (x, p) in row.iter_mut().zip(&pivot).skip(col) {
                    *x -= f * p;
                }
            }
        }
    }
    Some((0..n).map(|i| a[i][n] / a[i][i]).collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use oblique_solver::history::fold_minus_at_e;

    /// Next to γ = 1 the re-slip fold does not exist: the knots start at [`GAMMA_MIN`] (up to a
    /// sixteenth of a root cell), their grid from there, and a range below it has none.
    #[test]
    fn thornton_knots_start_at_gamma_min() {
        let k = thornton_knots((1.1, 1.3), 1, (0.8, 0.9), 1, AxisMap::Linear, None)
            .expect("traced")
            .expect("knots from 1.2");
        assert_eq!(k.region(), [0.5, 1.0, 0.0, 1.0]);
        assert!((k.gamma_0() - 1.2).abs() < 1e-12, "{}", k.gamma_0());
        // 1.2 is 0.4 of the way through 1.1–1.35: up to 7/16.
        let k = thornton_knots((1.1, 1.35), 1, (0.8, 0.85), 1, AxisMap::Linear, None)
            .expect("traced")
            .expect("knots");
        assert_eq!(k.region()[0], 7.0 / 16.0);
        assert!(
            thornton_knots((1.0, 1.15), 1, (0.8, 0.9), 1, AxisMap::Linear, None)
                .expect("nothing traced")
                .is_none()
        );
        // Without the start, the tracing fails where α_R is missing.
        assert!(knots_at(1.1, 0.8).is_err());
    }

    /// Where the table's range meets the `+` strip (γ 2.1–2.15, `e_n` 0.3–0.35: born below
    /// γ 2 at `e_n` 0.3, gone above about 0.4 at γ 2.1), its edges are the fifth and sixth knots:
    /// at the grid's corners within 2e-3 of the traced edges (shares of `(c_S, 1)`, the strip
    /// 0.017–0.022 wide there), and in order in between.
    #[test]
    fn the_strip_edges_are_knots_where_the_range_meets_it() {
        let (gammas, e_range) = ((2.1, 2.15), (0.3, 0.35));
        let strip = crate::kink::thornton_plus_strip_surfaces(gammas, e_range).expect("traced");
        let k = thornton_knots(gammas, 1, e_range, 1, AxisMap::Linear, Some(&strip))
            .expect("traced")
            .expect("knots");
        assert_eq!(k.c_star().len(), 6);
        assert_eq!(&k.c_star()[4..], &STRIP_C_STAR);
        let coord = |g: f64, a: f64, e: f64| {
            PatchKind::PartialSlip.coord_at(PartialMap::Slip, g, a, e, f64::INFINITY)
        };
        for (g, e) in [
            (2.1, 0.3),
            (2.15, 0.3),
            (2.1, 0.35),
            (2.15, 0.35),
            (2.125, 0.325),
        ] {
            let line = k.line(g, e);
            let knots = line.knots();
            assert!(knots.windows(2).all(|w| w[1] > w[0]), "{knots:?}");
            let share = |c: f64| (c - knots[3]) / (1.0 - knots[3]);
            for j in 0..2 {
                let a = strip[j]
                    .as_ref()
                    .and_then(|s| s.alpha_at(g, e))
                    .expect("edge");
                let (traced, knot) = (share(coord(g, a, e)), share(knots[4 + j]));
                assert!(
                    (traced - knot).abs() < 2e-3,
                    "{g} {e}: {knot} against {traced}"
                );
            }
        }
    }

    /// The loading fold's knot ends along `e_n` at the last root-cell edge below the last row of
    /// its grid where `α_L` lies at least [`LOADING_C_MIN`] into the stick patch at every γ (at
    /// γ 1.6 `α_L` reaches `α_c2` between `e_n` 0.85 and 0.9); with a root cell that ends
    /// beyond that row, or a range where the fold is gone, there is none.
    #[test]
    fn the_loading_fold_knot_ends_where_the_fold_nears_alpha_c2() {
        // Four root cells along e_n (0.05 each): the knot's region ends at 0.8.
        let k = loading_fold_knots((1.6, 1.7), 1, (0.7, 0.9), 4, AxisMap::Linear, f64::INFINITY)
            .expect("traced")
            .expect("alpha_L above alpha_c2 from 0.7");
        assert_eq!(k.region(), [0.0, 1.0, 0.0, 2.0]);
        assert_eq!((k.c_star(), k.grade_values()), (&[0.5][..], vec![1]));
        // At the region's top the knot lies above LOADING_C_MIN; at the next root-cell edge
        // the fold lies below it at γ 1.7 (or is gone).
        for g in [1.6, 1.65, 1.7] {
            let c = k.line(g, 0.8).knots()[0];
            assert!((LOADING_C_MIN..0.2).contains(&c), "γ {g}: c {c}");
        }
        let beyond = loading_fold_thornton(1.7, 0.85, STEPS)
            .expect("solve")
            .map(|a| PatchKind::Stick.coord_at(PartialMap::Slip, 1.7, a, 0.85, f64::INFINITY));
        assert!(beyond.is_none_or(|c| c < LOADING_C_MIN), "{beyond:?}");
        // One root cell along e_n: the fold leaves inside it, no knot.
        assert!(
            loading_fold_knots((1.6, 1.7), 1, (0.7, 0.9), 1, AxisMap::Linear, f64::INFINITY)
                .expect("traced")
                .is_none()
        );
        assert!(loading_fold_knots(
            (1.6, 1.7),
            1,
            (0.9, 0.95),
            1,
            AxisMap::Linear,
            f64::INFINITY
        )
        .expect("traced")
        .is_none());
        // Below GAMMA_MIN the region starts at the next root-cell edge along γ.
        let k = loading_fold_knots((1.1, 1.3), 2, (0.6, 0.7), 1, AxisMap::Linear, f64::INFINITY)
            .expect("traced")
            .expect("alpha_L from 1.2");
        assert_eq!(k.region()[..2], [1.0, 2.0]);
    }

    /// From γ ≈ 1.75 the located loading fold jumps to another branch at small `e_n` (γ 2.3:
    /// from about 4.05 to 2.80 `α_c2` between `e_n` 0.40 and 0.41): the knot's region and grid
    /// start above the jump, at a root-cell edge, and the knot is continuous there (with one
    /// root cell along `e_n` the region would start inside it, and there is no knot: the
    /// table of `docs/table-format.md`, γ 2.25–2.35, `e_n` 0.3–0.45).
    #[test]
    fn the_loading_fold_knot_starts_above_the_jump_of_its_branch() {
        // Two root cells along e_n (0.1 each): the region from 0.45.
        let k = loading_fold_knots(
            (2.25, 2.35),
            1,
            (0.35, 0.55),
            2,
            AxisMap::Linear,
            f64::INFINITY,
        )
        .expect("traced")
        .expect("alpha_L above the jump");
        assert_eq!(k.region(), [0.0, 1.0, 1.0, 2.0]);
        let e0 = k.e_n_0();
        assert!(e0 > 0.41 && e0 <= 0.45, "grid from {e0}");
        // The located fold jumps below the grid and lies on the knot's branch above it.
        let c = |g: f64, e: f64| {
            loading_fold_thornton(g, e, STEPS)
                .expect("solve")
                .map(|a| PatchKind::Stick.coord_at(PartialMap::Slip, g, a, e, f64::INFINITY))
                .expect("a fold")
        };
        assert!(c(2.3, 0.39) - c(2.3, 0.42) > 0.05, "the jump");
        for (g, e) in [(2.25, 0.46), (2.3, 0.5), (2.35, 0.55)] {
            let knot = k.line(g, e).knots()[0];
            assert!((knot - c(g, e)).abs() < 1e-4, "γ {g}, e_n {e}: {knot}");
        }
    }

    /// The fitted F₋ against F₋ located directly where it exists: within 1e-4 (relative),
    /// sent to a root-cell edge, its region inside the patch and holding those points.
    #[test]
    fn the_fitted_fold_minus_lies_on_the_located_fold() {
        let (gammas, e_range) = ((2.45, 2.6), (0.95, 1.0));
        let map = PartialMap::SqrtBoth;
        let k = fold_minus_knots(gammas, 1, e_range, 1, 4, map)
            .expect("traced")
            .expect("F- exists there");
        let c_star = k.c_star()[0];
        assert_eq!(
            (c_star * 4.0).fract(),
            0.0,
            "c* {c_star} on a root-cell edge"
        );
        assert_eq!(k.grade_values(), vec![2]);
        let r = k.region();
        assert!(
            r[0] < 1.0 && r[1] == 1.0 && r[2] < 1.0 && r[3] == 1.0,
            "{r:?}"
        );
        for &(g, e, guess) in &[(2.5, 0.99, 0.476), (2.55, 0.97, 0.449), (2.6, 0.96, 0.428)] {
            let a_f = fold_minus_at_e(g, e, guess, 2048)
                .expect("solve")
                .expect("F- here");
            let line = k.line(g, e);
            let c_f = PatchKind::PartialSlip.coord_at(map, g, a_f, e, f64::INFINITY);
            let a_k = PatchKind::PartialSlip.alpha_at(map, g, line.knots()[0], e, f64::INFINITY);
            assert!(
                (a_k / a_f - 1.0).abs() < 1e-4,
                "γ {g}, e_n {e}: knot at α {a_k}, F- at {a_f} (c {c_f})"
            );
        }
    }
}
