//! The MDR row of tangential springs (Cattaneo–Mindlin partial slip in one dimension).
//!
//! By symmetry only the half-row `x ≥ 0` is stored; integrals are over `[0, a]` and the caller
//! doubles them. Spring `i` sits at `x_i`, is pressed by `ũ_z,i = d − x_i²/R*` and carries the
//! tangential displacement `ũ_x,i` bounded by the local Coulomb limit
//! `|ũ_x,i| ≤ c (d − x_i²/R*)`, `c = μ E*/G*`.

/// Motion over one time step, as the accurate update needs it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepMotion {
    /// Step length `h` (s).
    pub h: f64,
    /// Indentation at the start of the step `d_n` (m).
    pub d0: f64,
    /// Indentation rate `ḋ_n` (m/s).
    pub rate0: f64,
    /// Indentation acceleration `d̈_n` (m/s²).
    pub accel0: f64,
    /// Slip velocity `u_n = ẇ_n` (m/s).
    pub slip_velocity: f64,
    /// Slip acceleration `ẅ_n` (m/s²); `w` is quadratic over the step.
    pub slip_accel: f64,
    /// Indentation rate at the end of the step `ḋ_{n+1}` (m/s).
    pub rate1: f64,
    /// Indentation acceleration at the end of the step `d̈_{n+1}` (m/s²).
    pub accel1: f64,
}

impl StepMotion {
    /// Release of the springs at the `+` and `−` Coulomb limits during the step: the instant `τ`
    /// where `ẇ = ±L̇` (with `L̇ = c ḋ` the same for every spring), if it falls inside the step.
    /// `A` is the rate difference at the start and `B` its slope, both linear over the step.
    pub fn release_times(&self, c: f64) -> (Option<f64>, Option<f64>) {
        let time = |a0: f64, b0: f64| (a0 < 0.0 && b0 > 0.0 && -a0 < b0 * self.h).then(|| -a0 / b0);
        let (v, a) = (self.slip_velocity, self.slip_accel);
        (
            time(c * self.rate0 - v, c * self.accel0 - a),
            time(c * self.rate0 + v, c * self.accel0 + a),
        )
    }

    /// The displacement a released spring misses in the end-of-step clip, `∫₀^τ (L̇ ∓ ẇ) dt`
    /// `= −A²/(2B)`, for the `+` and `−` limits (0 when there is no release in the step).
    pub(crate) fn release_corrections(&self, c: f64) -> (f64, f64) {
        let (v, a) = (self.slip_velocity, self.slip_accel);
        let (tp, tm) = self.release_times(c);
        let corr = |a0: f64, b0: f64, t: Option<f64>| t.map_or(0.0, |_| -a0 * a0 / (2.0 * b0));
        (
            corr(c * self.rate0 - v, c * self.accel0 - a, tp),
            -corr(c * self.rate0 + v, c * self.accel0 + a, tm),
        )
    }
}

/// What one accurate step returns.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepResult {
    /// `∫₀^a ũ_x dx` over the half-row (m²).
    pub integral: f64,
    /// Mean displacement `∫₀^a ũ_x dx / a` (m); at `a = 0` its limit, the displacement of the
    /// last point in contact.
    pub mean: f64,
}

/// Half-row of tangential springs.
#[derive(Debug, Clone)]
pub struct SpringRow {
    /// Mean spring spacing `Δx` (m).
    dx: f64,
    /// Trapezoid weights `(x_{i+1} − x_{i−1})/2` (m) (`(x_1 − x_0)/2` for the centre node).
    w: Vec<f64>,
    /// Spring positions `x_i` (m).
    x: Vec<f64>,
    /// Profile heights `g(x_i) = x_i² / R*` (m).
    g: Vec<f64>,
    /// Tangential displacements `ũ_x,i` (m).
    u: Vec<f64>,
    /// Effective radius `R*` (m).
    radius: f64,
    /// Number of springs in contact after the last step.
    in_contact: usize,
    /// Whether some spring ended the last step at the `+` / `−` Coulomb limit.
    at_limit: (bool, bool),
}

impl SpringRow {
    /// Springs for the accurate scheme: trapezoid nodes `x_i = a_max (1 − (1 − σ_i)²)`, `σ_i = i/N`,
    /// plus a few nodes of the last spacing beyond `a_max`.
    ///
    /// The nodes are uniform in `σ`, in which the entry time of a spring is smooth at both ends of
    /// the row: near the centre (`a ∝ √t`) and near `a_max` (where `a_max − a ∝ (t − t_m)²`). On a
    /// uniform grid in `x` the stick displacement has a `√(a_max − x)` singularity there and the
    /// scheme drops to order 1.5.
    pub fn nodes(a_max: f64, springs: usize, radius: f64) -> Self {
        let n = springs.max(1);
        let map = |i: usize| {
            let s = 1.0 - i as f64 / n as f64;
            a_max * (1.0 - s * s)
        };
        let last = map(n) - map(n - 1);
        let x = (0..=n)
            .map(map)
            .chain((1..4).map(|j| a_max + j as f64 * last));
        Self::build(a_max / n as f64, x, radius)
    }

    /// Springs at cell midpoints `x_i = (i + ½) Δx`, as in the seed paper's scheme.
    pub fn midpoints(a_max: f64, springs: usize, radius: f64) -> Self {
        let springs = springs.max(1);
        let dx = a_max / springs as f64;
        Self::build(dx, (0..springs + 3).map(|i| (i as f64 + 0.5) * dx), radius)
    }

    fn build(dx: f64, x: impl Iterator<Item = f64>, radius: f64) -> Self {
        let x: Vec<f64> = x.collect();
        let g = x.iter().map(|&xi| xi * xi / radius).collect();
        let u = vec![0.0; x.len()];
        let m = x.len();
        let w = (0..m)
            .map(|i| {
                let lo = x[i.saturating_sub(1)];
                let hi = x[(i + 1).min(m - 1)];
                0.5 * (hi - lo)
            })
            .collect();
        Self {
            dx,
            w,
            x,
            g,
            u,
            radius,
            in_contact: 0,
            at_limit: (false, false),
        }
    }

    /// Whether some spring sits at the `+` / `−` Coulomb limit (after the last step).
    pub fn at_limit(&self) -> (bool, bool) {
        self.at_limit
    }

    /// Number of springs whose position satisfies `g(x_i) < d`.
    fn count_in_contact(&self, d: f64) -> usize {
        // g is increasing; partition_point gives the first index with g >= d.
        self.g.partition_point(|&gi| gi < d)
    }

    /// Second-order update over one time step (the default scheme).
    ///
    /// `dw` is the increment of the contact-point displacement `w` over the step (m), `d0`, `d1`
    /// the indentation at the start and end of the step (m), `c = μ E*/G*` the slip-limit factor
    /// (`f64::INFINITY` for no slip). A spring that enters contact during the step receives only
    /// the part of `dw` after its entry (entry time by linear interpolation of `d`); springs
    /// leaving contact drop to zero. Returns `∫₀^a ũ_x dx` (m²) at the end of the step by the
    /// trapezoid rule, the last partial interval `[x_k, a]` included, so the force is continuous
    /// in time as the contact edge crosses nodes; and the mean displacement over the contact.
    pub fn step_accurate(&mut self, m: &StepMotion, d1: f64, c: f64) -> StepResult {
        let (d0, h, v, a) = (m.d0, m.h, m.slip_velocity, m.slip_accel);
        let dw = h * v + 0.5 * h * h * a;
        let center = self.u[0];
        let n0 = self.in_contact;
        let n1 = self.count_in_contact(d1);
        let old = n0.min(n1);
        {
            let u = &mut self.u[..old];
            let g = &self.g[..old];
            if c.is_finite() {
                // Springs at the Coulomb limit at the start of the step that stick again inside
                // it: all share L̇ = c ḋ, so they release at one instant τ where ẇ = ±L̇, and
                // miss ∫₀^τ (L̇ ∓ ẇ) dt in the end-of-step clip. With ẇ and ḋ linear over the
                // step that integral is −A²/(2B) (A, B: the rate difference and its slope).
                let (plus, minus) = m.release_corrections(c);
                let (mut any_plus, mut any_minus) = (false, false);
                for (ui, &gi) in u.iter_mut().zip(g) {
                    let lim0 = c * (d0 - gi);
                    let lim = c * (d1 - gi);
                    let mut next = *ui + dw;
                    if *ui == lim0 && next < lim {
                        next += plus;
                    } else if *ui == -lim0 && next > -lim {
                        next += minus;
                    }
                    *ui = next.clamp(-lim, lim);
                    any_plus |= *ui == lim && lim > 0.0;
                    any_minus |= *ui == -lim && lim > 0.0;
                }
                self.at_limit = (any_plus, any_minus);
            } else {
                for ui in u.iter_mut() {
                    *ui += dw;
                }
            }
        }
        if n1 > n0 {
            let span = d1 - d0;
            for i in n0..n1 {
                let theta = if span > 0.0 {
                    ((self.g[i] - d0) / span).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                // w(h) − w(θh) for w quadratic over the step.
                let rest = 1.0 - theta;
                let inc = h * v * rest + 0.5 * a * h * h * (1.0 - theta * theta);
                let lim = c * (d1 - self.g[i]);
                self.u[i] = if c.is_finite() {
                    inc.clamp(-lim, lim)
                } else {
                    inc
                };
            }
        } else {
            self.u[n1..n0].fill(0.0);
        }
        self.in_contact = n1;
        let integral = self.integral(d1, c, d1 >= d0);
        let a1 = (self.radius * d1).sqrt();
        let mean = if a1 > 0.0 && n1 > 0 {
            integral / a1
        } else if c.is_finite() {
            // Contact vanished: the Coulomb limit at the last point in contact is zero.
            0.0
        } else {
            // No slip: the last spring carries its displacement to the end.
            center + dw
        };
        StepResult { integral, mean }
    }

    /// `∫₀^a ũ_x dx`: trapezoid rule on the nodes in contact plus the partial interval
    /// `[x_k, a]`, where `ũ_x` is a straight line clamped by the Coulomb limit
    /// `±c (d − x²/R*)` and integrated exactly. While the contact grows (`growing`) the line runs
    /// from `(x_k, ũ_k)` to `(a, 0)` (springs enter with zero displacement); while it shrinks
    /// it is extrapolated from the last two nodes (springs leave with whatever they carry).
    fn integral(&self, d: f64, c: f64, growing: bool) -> f64 {
        let n = self.in_contact;
        if n == 0 {
            return 0.0;
        }
        let a = (self.radius * d).sqrt();
        let k = n - 1;
        let u = &self.u[..n];
        let weighted: f64 = u.iter().zip(&self.w[..n]).map(|(ui, wi)| ui * wi).sum();
        let xk = self.x[k];
        // Node k's trapezoid weight counts half of [x_k, x_{k+1}], which is not (fully) inside.
        let inner = weighted - 0.5 * u[k] * (self.x[k + 1] - xk);
        let slope = if growing || k == 0 {
            if a > xk {
                -u[k] / (a - xk)
            } else {
                0.0
            }
        } else {
            (u[k] - u[k - 1]) / (xk - self.x[k - 1])
        };
        inner + clamped_line_integral(xk, a, u[k], slope, c, d, self.radius)
    }

    /// The seed's update: every spring in contact at the end of the step receives the full
    /// increment `dw`, then the Coulomb limit is applied; springs out of contact drop to zero.
    /// Returns `(Σ ũ_z Δx, Σ ũ_x Δx)` over the half-row (m², m²).
    pub fn step_euler(&mut self, dw: f64, d1: f64, c: f64) -> (f64, f64) {
        let n1 = self.count_in_contact(d1);
        let n0 = self.in_contact;
        if n1 < n0 {
            self.u[n1..n0].fill(0.0);
        }
        let mut sz = 0.0;
        let mut sx = 0.0;
        for (ui, &gi) in self.u[..n1].iter_mut().zip(&self.g[..n1]) {
            let uz = d1 - gi;
            let lim = c * uz;
            let v = *ui + dw;
            *ui = if v.abs() > lim { lim.copysign(v) } else { v };
            sz += uz;
            sx += *ui;
        }
        self.in_contact = n1;
        (sz * self.dx, sx * self.dx)
    }
}

/// `∫_{x0}^{a} clamp(u0 + s (x − x0), −λ(x), λ(x)) dx` with `λ(x) = c (d − x²/R)`, exactly.
///
/// `λ` is concave and the line is straight, so the clamp switches at the roots of the two
/// quadratics `line ∓ λ = 0`; between switch points the integrand is a polynomial.
fn clamped_line_integral(x0: f64, a: f64, u0: f64, s: f64, c: f64, d: f64, r: f64) -> f64 {
    if a <= x0 {
        return 0.0;
    }
    let line = |x: f64| u0 + s * (x - x0);
    // Antiderivatives of the line and of λ.
    let line_int = |x: f64| u0 * (x - x0) + 0.5 * s * (x - x0) * (x - x0);
    if !c.is_finite() {
        return line_int(a);
    }
    let lam_int = |x: f64| c * (d * x - x * x * x / (3.0 * r));
    let mut cuts = [x0, a, a, a, a, a];
    let mut m = 2;
    // line(x) = ±λ(x)  ⇔  (c/r) x² ± (s x + u0 − s x0) − c d = 0 … written as A x² + B x + C = 0.
    for sign in [1.0, -1.0] {
        let qa = sign * c / r;
        let qb = s;
        let qc = u0 - s * x0 - sign * c * d;
        let disc = qb * qb - 4.0 * qa * qc;
        if qa != 0.0 && disc >= 0.0 {
            let sq = disc.sqrt();
            for root in [(-qb + sq) / (2.0 * qa), (-qb - sq) / (2.0 * qa)] {
                if root > x0 && root < a {
                    cuts[m] = root;
                    m += 1;
                }
            }
        }
    }
    let cuts = &mut cuts[..m];
    cuts.sort_by(|p, q| p.total_cmp(q));
    let mut total = 0.0;
    for w in cuts.windows(2) {
        let (lo, hi) = (w[0], w[1]);
        if hi <= lo {
            continue;
        }
        let mid = 0.5 * (lo + hi);
        let lam = c * (d - mid * mid / r);
        let v = line(mid);
        total += if v > lam {
            lam_int(hi) - lam_int(lo)
        } else if v < -lam {
            lam_int(lo) - lam_int(hi)
        } else {
            line_int(hi) - line_int(lo)
        };
    }
    total
}

/// A unit step with increment `dw` (constant slip velocity) from indentation `d0`; for the
/// unit tests of this module and of [`super::continuum`].
#[cfg(test)]
pub(crate) fn motion(dw: f64, d0: f64) -> StepMotion {
    StepMotion {
        h: 1.0,
        d0,
        rate0: 0.0,
        accel0: 0.0,
        slip_velocity: dw,
        slip_accel: 0.0,
        rate1: 0.0,
        accel1: 0.0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn trapezoid_integrates_linear_edge_profile_exactly() {
        // Slip everywhere: ũ = c (d − x²), whose integral over [0, √d] is (2/3) c d^{3/2}.
        let mut row = SpringRow::nodes(1.0, 400, 1.0);
        let d = 0.49;
        let got = row.step_accurate(&motion(10.0, 0.0), d, 1.0).integral;
        let exact = 2.0 / 3.0 * d.powf(1.5);
        assert!((got - exact).abs() < 1e-5, "{got} vs {exact}");
    }

    #[test]
    fn clamped_line_integral_matches_quadrature() {
        let (x0, a, u0, s, c, d, r) = (0.3, 0.7, 0.05, -0.4, 0.8, 0.49, 1.0);
        let exact = clamped_line_integral(x0, a, u0, s, c, d, r);
        let n = 200_000;
        let h = (a - x0) / n as f64;
        let num: f64 = (0..n)
            .map(|i| {
                let x = x0 + (i as f64 + 0.5) * h;
                let lam = c * (d - x * x / r);
                (u0 + s * (x - x0)).clamp(-lam, lam) * h
            })
            .sum();
        assert!((exact - num).abs() < 1e-10, "{exact} vs {num}");
    }

    #[test]
    fn springs_leaving_contact_are_reset() {
        let mut row = SpringRow::nodes(1.0, 10, 1.0);
        row.step_accurate(&motion(1.0, 0.0), 0.81, f64::INFINITY);
        row.step_accurate(&motion(0.0, 0.81), 0.04, f64::INFINITY);
        assert!(row.u[3..].iter().all(|&u| u == 0.0));
        assert!(row.u[..2].iter().all(|&u| u > 0.0));
    }
}
