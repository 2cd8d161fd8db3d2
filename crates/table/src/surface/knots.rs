//! The knots of the partial-slip coordinate of a table with an `e_n` axis (schema 4, optional):
//! kink surfaces `α_j(γ, e_n)` of `P` sent to fixed cell edges.
//!
//! Where `P(γ, α, e_n)` has a kink inside the partial-slip patch (a fold, where it departs from
//! its smooth continuation like a `3/2` power, or a jump of curvature), a cell that straddles
//! the kink needs many nodes. The knots move the kinks onto cell edges: the tree of the patch is
//! over `(x, c', x_e)` with `c'` a piecewise map of `c` that sends the knot values
//! `K_j(γ, e_n)` (the kinks' coordinates `c`) to fixed `c*_j`, linear between them or graded
//! (a square root) next to a fold, so that the `3/2` power becomes a cubic in `c'`. The rule is
//! step 5 of `docs/table-format.md` ("The knots").

use super::*;

/// Most knots one patch may have.
pub const MAX_KNOTS: usize = 8;

/// How the segments next to a knot are graded (the dataset `grade`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(u8)]
pub enum Grade {
    /// Linear on both sides (a jump of curvature, or no kink at all).
    None = 0,
    /// Graded on the segment below the knot (`P ≈ smooth + C·(K − c)^{3/2}` below it): a fold
    /// approached from below.
    Below = 1,
    /// Graded on the segment above the knot (`P ≈ smooth + C·(c − K)^{3/2}` above it).
    Above = 2,
}

impl Grade {
    /// The grade of a stored value, `None` for a value the format does not know.
    pub fn from_u8(v: u8) -> Option<Grade> {
        match v {
            0 => Some(Grade::None),
            1 => Some(Grade::Below),
            2 => Some(Grade::Above),
            _ => None,
        }
    }
}

/// The knots of a patch: `k` kink surfaces tabulated on a regular `(γ, e_n)` grid, each sent to
/// a fixed coordinate, applied inside a box of root cells.
///
/// Stored as the group `knots` of `partial_high` (schema 4, a table over `γ, α, e_n`):
/// attributes `gamma_0`, `gamma_step`, `e_n_0`, `e_n_step`, `region`; datasets `c_star`
/// (`[k]`), `grade` (`uint8 [k]`) and `knot` (`[k, n_γ, n_e]`).
#[derive(Debug, Clone, PartialEq)]
pub struct Knots {
    /// γ of the first grid row.
    pub(super) gamma_0: f64,
    /// γ spacing of the grid (`> 0`).
    pub(super) gamma_step: f64,
    /// `e_n` of the first grid column.
    pub(super) e_n_0: f64,
    /// `e_n` spacing of the grid (`> 0`).
    pub(super) e_n_step: f64,
    /// The box of root cells where the knots apply, root-cell units: `[γ from, γ to, e_n from,
    /// e_n to]`.
    pub(super) region: [f64; 4],
    /// Where each knot is sent, strictly increasing in `(0, 1)`.
    pub(super) c_star: Vec<f64>,
    /// The grading next to each knot.
    pub(super) grade: Vec<Grade>,
    /// Grid points along γ and along `e_n`.
    pub(super) n_gamma: usize,
    pub(super) n_e_n: usize,
    /// `K_j` at `(gamma_0 + i·gamma_step, e_n_0 + l·e_n_step)`, index `(j·n_gamma + i)·n_e_n + l`.
    pub(super) knot: Vec<f64>,
}

/// The knots at one `(γ, e_n)`: the map `c → c'` of step 5 on that line.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KnotLine {
    n: usize,
    k: [f64; MAX_KNOTS],
    c_star: [f64; MAX_KNOTS],
    grade: [Grade; MAX_KNOTS],
}

impl KnotLine {
    /// The segment of `c`: the number of knots `K_j < c`.
    #[inline(always)]
    fn segment(&self, c: f64) -> usize {
        self.k[..self.n].iter().filter(|&&k| k < c).count()
    }

    /// The ends `(K, c*)` of segment `s` (`(0, 0)` below the first knot, `(1, 1)` above the last).
    #[inline(always)]
    fn ends(&self, s: usize) -> ((f64, f64), (f64, f64)) {
        let lo = if s == 0 {
            (0.0, 0.0)
        } else {
            (self.k[s - 1], self.c_star[s - 1])
        };
        let hi = if s == self.n {
            (1.0, 1.0)
        } else {
            (self.k[s], self.c_star[s])
        };
        (lo, hi)
    }

    /// `c → c'` (step 5): on the segment `K_lo < c ≤ K_hi` (`K = 0` and `1` at the ends, sent
    /// to `0` and `1`), with `t = (c − K_lo)/(K_hi − K_lo)`:
    /// `c' = c*_lo + (c*_hi − c*_lo)·(1 − √max(1 − t, 0))` when the upper knot is graded below,
    /// `c*_lo + (c*_hi − c*_lo)·√max(t, 0)` when the lower one is graded above, and
    /// `c*_lo + (c*_hi − c*_lo)·(c − K_lo)/(K_hi − K_lo)` (in that order) otherwise; `c*_lo`
    /// where `K_hi ≤ K_lo`.
    #[inline(always)]
    pub fn apply(&self, c: f64) -> f64 {
        let s = self.segment(c);
        let ((k0, c0), (k1, c1)) = self.ends(s);
        let w = k1 - k0;
        // Also a NaN width: the segment is empty.
        if w.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
            return c0;
        }
        if s < self.n && self.grade[s] == Grade::Below {
            let t = (c - k0) / w;
            c0 + (c1 - c0) * (1.0 - (1.0 - t).max(0.0).sqrt())
        } else if s > 0 && self.grade[s - 1] == Grade::Above {
            let t = (c - k0) / w;
            c0 + (c1 - c0) * t.max(0.0).sqrt()
        } else {
            c0 + (c1 - c0) * (c - k0) / w
        }
    }

    /// `c' → c`, the inverse of [`KnotLine::apply`] (for laying out nodes at given `c'`).
    pub fn invert(&self, c_prime: f64) -> f64 {
        let s = self.c_star[..self.n]
            .iter()
            .filter(|&&cs| cs < c_prime)
            .count();
        let ((k0, c0), (k1, c1)) = self.ends(s);
        let t = if c1 > c0 {
            ((c_prime - c0) / (c1 - c0)).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let t = if s < self.n && self.grade[s] == Grade::Below {
            let u = 1.0 - t;
            1.0 - u * u
        } else if s > 0 && self.grade[s - 1] == Grade::Above {
            t * t
        } else {
            t
        };
        k0 + (k1 - k0) * t
    }

    /// The knot values `K_j` on this line.
    pub fn knots(&self) -> &[f64] {
        &self.k[..self.n]
    }
}

impl Knots {
    /// Knots from their stored values, checked: finite grid origins, steps `> 0`, at least 4
    /// grid points per axis, `1 ≤ k ≤` [`MAX_KNOTS`] knots, `c_star` strictly increasing in
    /// `(0, 1)`, no segment graded at both ends, every knot value in `(0, 1)` and strictly
    /// increasing in `j` at every grid point, a finite region with `from < to` per axis. The
    /// rules against the patch (the region inside its root cells, the grid covering it, no
    /// leaf across the region's edges) are [`Patch::new`]'s. `Err` names the attribute or
    /// dataset and the allowed range.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        gamma_0: f64,
        gamma_step: f64,
        e_n_0: f64,
        e_n_step: f64,
        region: [f64; 4],
        c_star: Vec<f64>,
        grade: Vec<u8>,
        shape: [usize; 3],
        knot: Vec<f64>,
    ) -> Result<Knots, String> {
        for (name, v, ok) in [
            ("gamma_0", gamma_0, gamma_0.is_finite()),
            (
                "gamma_step",
                gamma_step,
                gamma_step.is_finite() && gamma_step > 0.0,
            ),
            ("e_n_0", e_n_0, e_n_0.is_finite()),
            ("e_n_step", e_n_step, e_n_step.is_finite() && e_n_step > 0.0),
        ] {
            if !ok {
                let allowed = if name.ends_with("step") {
                    "finite and > 0"
                } else {
                    "finite"
                };
                return Err(format!("attribute '{name}' = {v}: must be {allowed}"));
            }
        }
        if !(region.iter().all(|r| r.is_finite())
            && region[0] >= 0.0
            && region[0] < region[1]
            && region[2] >= 0.0
            && region[2] < region[3])
        {
            return Err(format!(
                "attribute 'region' = {region:?}: must be finite root-cell positions [gamma from, \
                 gamma to, e_n from, e_n to] with 0 <= from < to on each axis"
            ));
        }
        let [k, n_gamma, n_e_n] = shape;
        if !(1..=MAX_KNOTS).contains(&k) {
            return Err(format!(
                "dataset 'knot' holds {k} knots: must hold 1 to {MAX_KNOTS}"
            ));
        }
        if n_gamma < 4 || n_e_n < 4 {
            return Err(format!(
                "dataset 'knot' has {n_gamma} x {n_e_n} grid points: must have at least 4 along \
                 each of gamma and e_n"
            ));
        }
        if knot.len() != k * n_gamma * n_e_n {
            return Err(format!(
                "dataset 'knot' has {} values: expected {k} x {n_gamma} x {n_e_n}",
                knot.len()
            ));
        }
        if c_star.len() != k || grade.len() != k {
            return Err(format!(
                "datasets 'c_star' and 'grade' have {} and {} values: expected {k}, one per knot",
                c_star.len(),
                grade.len()
            ));
        }
        for (j, &cs) in c_star.iter().enumerate() {
            let above = if j == 0 { 0.0 } else { c_star[j - 1] };
            if !(cs > above && cs < 1.0) {
                return Err(format!(
                    "dataset 'c_star'[{j}] = {cs}: must be in ({above}, 1) (strictly increasing \
                     in (0, 1))"
                ));
            }
        }
        let grade = grade
            .iter()
            .enumerate()
            .map(|(j, &g)| {
                Grade::from_u8(g).ok_or_else(|| {
                    format!("dataset 'grade'[{j}] = {g}: must be 0 (none), 1 (below) or 2 (above)")
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        for j in 1..k {
            if grade[j - 1] == Grade::Above && grade[j] == Grade::Below {
                return Err(format!(
                    "dataset 'grade': knot {} is graded above and knot {j} below: a segment may \
                     be graded at one end only",
                    j - 1
                ));
            }
        }
        for i in 0..n_gamma {
            for l in 0..n_e_n {
                let mut below = 0.0;
                for j in 0..k {
                    let v = knot[(j * n_gamma + i) * n_e_n + l];
                    if !(v > below && v < 1.0) {
                        return Err(format!(
                            "dataset 'knot'[{j}, {i}, {l}] = {v}: must be in ({below}, 1) \
                             (strictly increasing in the knot index, inside (0, 1))"
                        ));
                    }
                    below = v;
                }
            }
        }
        Ok(Knots {
            gamma_0,
            gamma_step,
            e_n_0,
            e_n_step,
            region,
            c_star,
            grade,
            n_gamma,
            n_e_n,
            knot,
        })
    }

    /// γ of the first grid row.
    pub fn gamma_0(&self) -> f64 {
        self.gamma_0
    }

    /// γ spacing of the grid.
    pub fn gamma_step(&self) -> f64 {
        self.gamma_step
    }

    /// `e_n` of the first grid column.
    pub fn e_n_0(&self) -> f64 {
        self.e_n_0
    }

    /// `e_n` spacing of the grid.
    pub fn e_n_step(&self) -> f64 {
        self.e_n_step
    }

    /// The box of root cells where the knots apply: `[γ from, γ to, e_n from, e_n to]`.
    pub fn region(&self) -> [f64; 4] {
        self.region
    }

    /// Where each knot is sent.
    pub fn c_star(&self) -> &[f64] {
        &self.c_star
    }

    /// The grading of each knot, as stored.
    pub fn grade_values(&self) -> Vec<u8> {
        self.grade.iter().map(|&g| g as u8).collect()
    }

    /// `[k, n_γ, n_e]`: knots, grid points along γ and along `e_n`.
    pub fn shape(&self) -> [usize; 3] {
        [self.c_star.len(), self.n_gamma, self.n_e_n]
    }

    /// The stored knot values, `[k, n_γ, n_e]` row-major.
    pub fn values(&self) -> &[f64] {
        &self.knot
    }

    /// Whether the knots apply at the root-cell positions `vg` (γ) and `ve` (`e_n`) of a point
    /// (as step 6 computes them, clamped): `from ≤ v < to` on both axes, or `v` up to `to`
    /// inclusive where `to` is the patch's last root edge (`blocks`), as the descent puts a
    /// point on an edge into the upper cell except at the end.
    #[inline(always)]
    pub fn applies(&self, vg: f64, ve: f64, blocks_gamma: f64, blocks_e_n: f64) -> bool {
        let inside =
            |v: f64, from: f64, to: f64, blocks: f64| v >= from && (v < to || to >= blocks);
        inside(vg, self.region[0], self.region[1], blocks_gamma)
            && inside(ve, self.region[2], self.region[3], blocks_e_n)
    }

    /// The knots at `(γ, e_n)`: each `K_j` the tensor product of 4-point Lagrange rules on
    /// the grid at `u = (γ − gamma_0)/gamma_step` and `w = (e_n − e_n_0)/e_n_step`, each
    /// clamped to the grid ([`stencil4`]): `K_j = Σ_a wγ_a · (Σ_b we_b · knot[j, sγ + a,
    /// se + b])`, both sums in index order.
    #[inline]
    pub fn line(&self, gamma: f64, e_n: f64) -> KnotLine {
        let u = ((gamma - self.gamma_0) / self.gamma_step).clamp(0.0, (self.n_gamma - 1) as f64);
        let w = ((e_n - self.e_n_0) / self.e_n_step).clamp(0.0, (self.n_e_n - 1) as f64);
        let (sg, wg) = stencil4(u, self.n_gamma);
        let (se, we) = stencil4(w, self.n_e_n);
        let n = self.c_star.len();
        let mut line = KnotLine {
            n,
            k: [0.0; MAX_KNOTS],
            c_star: [0.0; MAX_KNOTS],
            grade: [Grade::None; MAX_KNOTS],
        };
        for j in 0..n {
            let mut sum = 0.0;
            for (a, &wa) in wg.iter().enumerate() {
                let row = (j * self.n_gamma + sg + a) * self.n_e_n + se;
                let v = &self.knot[row..row + 4];
                let inner = we[0] * v[0] + we[1] * v[1] + we[2] * v[2] + we[3] * v[3];
                sum += wa * inner;
            }
            line.k[j] = sum;
            line.c_star[j] = self.c_star[j];
            line.grade[j] = self.grade[j];
        }
        line
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Three knots on a 5 × 4 grid, tilted in γ and `e_n`: graded above, none, below.
    fn knots() -> Knots {
        let (ng, ne) = (5, 4);
        let mut knot = Vec::new();
        for base in [0.3, 0.5, 0.7] {
            for i in 0..ng {
                for l in 0..ne {
                    knot.push(base + 0.01 * i as f64 - 0.02 * l as f64);
                }
            }
        }
        Knots::new(
            1.0,
            0.5,
            0.5,
            0.2,
            [0.0, 4.0, 0.0, 2.0],
            vec![0.25, 0.5, 0.75],
            vec![2, 0, 1],
            [3, ng, ne],
            knot,
        )
        .expect("valid knots")
    }

    #[test]
    fn the_knots_go_to_their_coordinates_and_the_map_inverts() {
        let k = knots();
        for &(g, e) in &[(1.0, 0.5), (1.37, 0.77), (3.0, 1.1), (2.2, 0.93)] {
            let line = k.line(g, e);
            for (j, &kj) in line.knots().iter().enumerate() {
                assert!((line.apply(kj) - k.c_star()[j]).abs() < 1e-15);
            }
            let mut last = -1.0;
            for i in 0..=1000 {
                let c = i as f64 / 1000.0;
                let cp = line.apply(c);
                assert!(
                    cp >= last && (0.0..=1.0).contains(&cp),
                    "monotone at c = {c}"
                );
                assert!((line.invert(cp) - c).abs() < 1e-12, "inverse at c = {c}");
                last = cp;
            }
        }
    }

    #[test]
    fn the_map_is_graded_on_the_side_of_each_fold() {
        let line = knots().line(1.5, 0.6);
        let [k0, _, k2] = [line.knots()[0], line.knots()[1], line.knots()[2]];
        // Above knot 0 (graded 2): c' − c*₀ ∝ √(c − K₀); below knot 2 (graded 1): c*₂ − c' ∝
        // √(K₂ − c). A quarter of the distance halves the step in c'.
        for (at, side, star) in [(k0, 1.0, 0.25), (k2, -1.0, 0.75)] {
            let step = |d: f64| (line.apply(at + side * d) - star).abs();
            let ratio = step(1e-6) / step(0.25e-6);
            assert!((ratio - 2.0).abs() < 1e-6, "ratio {ratio}");
            // The other side is linear: a quarter of the distance, a quarter of the step.
            let other = |d: f64| (line.apply(at - side * d) - star).abs();
            let ratio = other(1e-6) / other(0.25e-6);
            assert!((ratio - 4.0).abs() < 1e-6, "ratio {ratio}");
        }
    }

    #[test]
    fn one_knot_graded_below_is_the_warp() {
        let knot = vec![0.4, 0.42, 0.45, 0.43, 0.41];
        let grid: Vec<f64> = knot.iter().flat_map(|&v| [v; 4]).collect();
        let k = Knots::new(
            2.0,
            0.25,
            0.5,
            0.25,
            [0.0, 1.0, 0.0, 1.0],
            vec![0.5],
            vec![1],
            [1, 5, 4],
            grid,
        )
        .expect("valid");
        let w = Warp::new(0.5, 2.0, 0.25, 0.5, knot).expect("valid warp");
        for i in 0..200 {
            let g = 2.0 + i as f64 * 0.005;
            let line = k.line(g, 0.8);
            let kw = w.knot_at(g);
            assert!((line.knots()[0] - kw).abs() < 1e-15);
            for j in 0..=100 {
                let c = j as f64 / 100.0;
                assert_eq!(
                    line.apply(c).to_bits(),
                    w.apply_with(line.knots()[0], c).to_bits(),
                    "γ {g}, c {c}"
                );
            }
        }
    }

    #[test]
    fn invalid_knots_are_refused_naming_the_field() {
        let ok = knots();
        let remake = |f: &dyn Fn(&mut Knots)| {
            let mut k = ok.clone();
            f(&mut k);
            Knots::new(
                k.gamma_0,
                k.gamma_step,
                k.e_n_0,
                k.e_n_step,
                k.region,
                k.c_star.clone(),
                k.grade_values(),
                [k.c_star.len(), k.n_gamma, k.n_e_n],
                k.knot.clone(),
            )
            .expect_err("refused")
        };
        type Edit<'a> = &'a dyn Fn(&mut Knots);
        let cases: [(Edit, &str); 8] = [
            (&|k| k.n_e_n = 1, "at least 4 along"),
            (&|k| k.gamma_step = 0.0, "'gamma_step'"),
            (&|k| k.e_n_0 = f64::NAN, "'e_n_0'"),
            (&|k| k.region[1] = k.region[0], "'region'"),
            (&|k| k.c_star[1] = 0.2, "'c_star'[1]"),
            (&|k| k.grade[1] = Grade::Below, "graded above"),
            (&|k| k.knot[0] = 0.0, "'knot'[0, 0, 0]"),
            (&|k| k.knot[20] = 0.2, "'knot'[1, 0, 0]"),
        ];
        for (f, want) in cases {
            let e = remake(f);
            assert!(e.contains(want), "{e}");
        }
    }
}
